//===- FrontendFuzzer.cpp - bytes into the lexer, parser and Sema ---------===//
//
// libFuzzer target (`./dev.sh fuzz frontend`), and the same function run on
// a corpus by the replay driver in the test suite (fuzz/README.md). Any
// input must end in diagnostics or a checked behavior: never a crash, an
// assertion or a hang. The input is one module; the diagnostics are
// formatted too, since printing them (carets, ranges) is part of the path.
//
//===----------------------------------------------------------------------===//
#include "bsc/Parse/Parser.h"
#include "bsc/Sema/Sema.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"
#include <cstddef>
#include <cstdint>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size) {
  using namespace bsc;
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(
          llvm::StringRef(reinterpret_cast<const char *>(Data), Size),
          "fuzz.bs"),
      llvm::SMLoc());
  ASTContext Ctx;
  DiagnosticEngine Diags;
  ModuleAST *M = parseModule(SM, ID, "fuzz", Ctx, Diags);
  Behavior Out;
  if (!Diags.hasErrors())
    checkBehavior({M}, Ctx, Diags, Out);
  std::string Text;
  llvm::raw_string_ostream OS(Text);
  printDiagnostics(SM, Diags.getDiagnostics(), OS);
  return 0;
}

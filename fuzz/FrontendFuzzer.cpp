//===- FrontendFuzzer.cpp - bytes into the lexer, parser and Sema ---------===//
//
// libFuzzer target (`./dev.sh fuzz frontend`), and the same function run on
// a corpus by the replay driver in the test suite (fuzz/README.md). Any
// input must end in diagnostics or a checked behavior: never a crash, an
// assertion or a hang. The input is one module; the diagnostics are
// formatted too, since printing them (carets, ranges) is part of the path.
// The editor's paths over the same input: `bsc format` formats it or
// refuses it, and what it writes is the same program and formats to
// itself (else a trap); the language server's index of the checked module
// answers at every line's start.
//
//===----------------------------------------------------------------------===//
#include "bsc/Format/Format.h"
#include "bsc/LSP/Index.h"
#include "bsc/Parse/Parser.h"
#include "bsc/Sema/Sema.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/SourceMgr.h"
#include "llvm/Support/raw_ostream.h"
#include <cstddef>
#include <cstdint>

/// Formats the input, then the result: the second must change nothing.
static void formatTwice(const llvm::SourceMgr &SM, unsigned ID) {
  bsc::DiagnosticEngine Diags;
  auto First = bsc::format::formatBuffer(SM, ID, Diags);
  if (!First) // Output that is another program: the formatter's bug.
    __builtin_trap();
  if (!*First)
    return;
  llvm::SourceMgr SM2;
  unsigned ID2 = SM2.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy((*First)->Text, "formatted.bs"),
      llvm::SMLoc());
  auto Second = bsc::format::formatBuffer(SM2, ID2, Diags);
  if (!Second || !*Second || (*Second)->Text != (*First)->Text)
    __builtin_trap();
}

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

  M->BufferID = ID;
  lsp::Index Idx = lsp::buildIndex({M});
  llvm::StringRef Source = SM.getMemoryBuffer(ID)->getBuffer();
  for (size_t At = 0; At < Source.size(); At = Source.find('\n', At + 1)) {
    llvm::SMLoc Loc = llvm::SMLoc::getFromPointer(Source.data() + At);
    (void)Idx.findAt(Loc);
    (void)Idx.findExpressionAt(Loc);
  }
  formatTwice(SM, ID);
  return 0;
}

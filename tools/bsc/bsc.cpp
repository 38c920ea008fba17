//===- bsc.cpp - the b-script compiler driver -----------------------------===//
//
// Wires the phases together; the phases themselves never print. Each
// `--emit=` value names a place where the pipeline can stop and dump what it
// has (MLIR Toy's -emit), which is what the tests look at.
//
//===----------------------------------------------------------------------===//
#include "bsc/Frontend/Frontend.h"
#include "bsc/Parse/Lexer.h"
#include "bsc/Parse/Parser.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;
namespace cl = llvm::cl;

namespace {
enum class EmitKind { Default, Tokens, AST, TypedAST };

cl::OptionCategory BscCategory("bsc options");

cl::list<std::string> InputFiles(cl::Positional, cl::desc("<file.bs>..."),
                                 cl::cat(BscCategory));
cl::opt<bool> SyntaxOnly("fsyntax-only",
                         cl::desc("Check the program; produce no output"),
                         cl::cat(BscCategory));
cl::opt<bool> Verify("verify",
                     cl::desc("Check diagnostics against the source's "
                              "'# expected-error {{...}}' comments"),
                     cl::cat(BscCategory));
cl::opt<EmitKind> Emit(
    "emit", cl::desc("Stop at a stage and print it"), cl::init(EmitKind::Default),
    cl::values(clEnumValN(EmitKind::Tokens, "tokens", "the tokens of each file"),
               clEnumValN(EmitKind::AST, "ast", "the syntax tree (parse only)"),
               clEnumValN(EmitKind::TypedAST, "typed-ast",
                          "the syntax tree after semantic checks")),
    cl::cat(BscCategory));
cl::list<std::string> IncludeDirs("I", cl::Prefix,
                                  cl::desc("Search folder for required modules"),
                                  cl::value_desc("dir"), cl::cat(BscCategory));

/// Prints the diagnostics (or verifies them) and returns the exit status.
int finish(Compilation &C) {
  if (Verify)
    return verifyDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs()) ? 0
                                                                           : 1;
  printDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs(),
                   llvm::WithColor(llvm::errs()).colorsEnabled());
  return C.Diags.hasErrors() ? 1 : 0;
}

int emitTokens(Compilation &C) {
  if (InputFiles.empty())
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
  for (const std::string &Path : InputFiles)
    if (unsigned ID = addSourceFile(C, Path))
      dumpTokens(C.SM, ID, C.Diags, llvm::outs());
  return finish(C);
}

int emitAST(Compilation &C, const FrontendOptions &Opts) {
  if (Emit == EmitKind::AST)
    loadModules(C, Opts);
  else
    runFrontend(C, Opts);
  for (ModuleAST *M : C.Modules)
    dumpAST(*M, llvm::outs());
  return finish(C);
}
} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM X(argc, argv);
  cl::HideUnrelatedOptions(BscCategory);
  cl::ParseCommandLineOptions(argc, argv,
                              "bsc: the b-script compiler for robot behaviors\n");

  Compilation C;
  FrontendOptions Opts;
  Opts.Inputs.assign(InputFiles.begin(), InputFiles.end());
  Opts.IncludeDirs.assign(IncludeDirs.begin(), IncludeDirs.end());

  switch (Emit) {
  case EmitKind::Tokens:
    return emitTokens(C);
  case EmitKind::AST:
  case EmitKind::TypedAST:
    return emitAST(C, Opts);
  case EmitKind::Default:
    break;
  }
  runFrontend(C, Opts);
  return finish(C);
}

//===- LanguageServer.cpp - `bsc lsp`: the server on stdin and stdout -----===//
//
// The server checks each behavior for the target its bscript.json names,
// with that target's standard modules, found as the compiler finds them
// (ToolChain.h); everything else is lib/LSP's.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Driver/ToolChain.h"
#include "bsc/LSP/Server.h"
#include <unistd.h>

using namespace bsc;

int bsc::lspCommand(llvm::StringRef RuntimeDir, const char *Argv0) {
  lsp::ServerOptions Opts;
  std::string Dir = RuntimeDir.str();
  Opts.BaseOptions = [Dir, Argv0](llvm::StringRef Target) {
    ToolChain TC = getToolChain(Target, Dir, Argv0);
    FrontendOptions F;
    F.Target = TC.getTriple();
    addStandardModules(TC, F);
    return F;
  };
  return lsp::runServer(Opts, STDIN_FILENO, STDOUT_FILENO);
}

//===- LanguageServer.cpp - `bsc lsp` and `bsc dap` on stdin and stdout ---===//
//
// The language server checks each behavior for the target its bscript.json
// names, and the debug adapter runs behaviors on the host, each with the
// target's standard modules found as the compiler finds them (ToolChain.h);
// everything else is lib/LSP's and lib/DAP's.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/DAP/Adapter.h"
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

int bsc::dapCommand(llvm::StringRef RuntimeDir, const char *Argv0) {
  dap::AdapterOptions Opts;
  std::string Dir = RuntimeDir.str();
  Opts.BaseOptions = [Dir, Argv0] {
    ToolChain TC = getToolChain("", Dir, Argv0);
    FrontendOptions F;
    F.Target = TC.getTriple();
    addStandardModules(TC, F);
    return F;
  };
  return dap::runAdapter(Opts, STDIN_FILENO, STDOUT_FILENO);
}

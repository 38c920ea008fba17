//===- Adapter.h - `bsc dap`: the Debug Adapter Protocol --------*- C++ -*-===//
//
// A debug adapter (microsoft.github.io/debug-adapter-protocol) over the
// REPL's session (bsc/REPL/DebugSession.h), so that VS Code, Neovim's
// nvim-dap, Emacs' dap-mode and Helix debug a behavior: breakpoints on
// lines and tasks, the active task hierarchy as the stack (a thread per
// robot), values, stepping by cycles and back in time, and the REPL's
// commands in the debug console. docs/editors.md, "Debugging".
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DAP_ADAPTER_H
#define BSC_DAP_ADAPTER_H

#include "bsc/Frontend/Frontend.h"
#include <functional>

namespace bsc {
namespace dap {

struct AdapterOptions {
  /// The front end's options every launch starts from: the host target and
  /// its standard modules.
  std::function<FrontendOptions()> BaseOptions;
};

/// Serves one client on the descriptors until it disconnects or its input
/// ends. What the behavior and its C++ print to standard output is caught
/// and sent as output events (the protocol has standard output otherwise).
/// Returns the exit status.
int runAdapter(const AdapterOptions &Opts, int InFd, int OutFd);

} // namespace dap
} // namespace bsc

#endif

//===- Server.h - `bsc lsp`: the language server ---------------*- C++ -*-===//
//
// A Language Server Protocol 3.17 server on a pair of file descriptors
// (JSON-RPC with Content-Length headers, llvm::json), built on the same
// front end as the compiler, so the editor shows exactly bsc's diagnostics
// (docs/editors.md). One thread: a request is answered before the next is
// read, and an edit is analysed once no other message has come for a
// moment (the debounce), so typing never queues analyses.
//
// lib/LSP: Transport.cpp (the wire), Workspace.cpp (documents, the
// behavior a file belongs to and its analysis), Index.cpp (what each name
// stands for), Features.cpp (hover, definition, completion, ...),
// Server.cpp (the entry: lifecycle and dispatch).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LSP_SERVER_H
#define BSC_LSP_SERVER_H

#include "bsc/Frontend/Frontend.h"
#include <functional>

namespace bsc {
namespace lsp {

struct ServerOptions {
  /// The front end's options for a target (empty: the host), as the driver
  /// sets them: the triple and the standard modules of its runtime.
  std::function<FrontendOptions(llvm::StringRef Target)> BaseOptions;
  /// How long an edit waits for the next message before it is analysed.
  unsigned DebounceMs = 50;
};

/// Serves one client reading `InFd` and writing `OutFd` until `exit` or
/// the end of the input. Returns the process's exit status: 0 after
/// `shutdown` then `exit`, 1 otherwise (as the protocol asks).
int runServer(const ServerOptions &Opts, int InFd, int OutFd);

} // namespace lsp
} // namespace bsc

#endif

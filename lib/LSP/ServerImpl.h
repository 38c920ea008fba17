//===- ServerImpl.h - the language server, shared by its files --*- C++ -*-===//
//
// The Server of lsp::runServer: Server.cpp reads messages, keeps the
// documents and answers the requests about a document's place;
// ServerWorkspace.cpp answers those about the whole workspace and checks a
// rename before it is given.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_LSP_SERVERIMPL_H
#define BSC_LIB_LSP_SERVERIMPL_H

#include "Features.h"
#include "bsc/Basic/Transport.h"
#include "bsc/LSP/Server.h"
#include <set>

namespace bsc {
namespace lsp {

/// JSON-RPC and LSP error codes.
enum ErrorCode {
  ParseError = -32700,
  InvalidRequest = -32600,
  MethodNotFound = -32601,
  InvalidParams = -32602,
  ServerNotInitialized = -32002,
  RequestFailed = -32803,
};

/// The byte offset of an LSP position in `Text` (clamped to the text).
size_t offsetOf(llvm::StringRef Text, const llvm::json::Object *Position);
/// The LSP position just past the end of `Text`.
llvm::json::Object endOf(llvm::StringRef Text);
/// The file a request's textDocument names ("" if none).
std::string pathOf(const llvm::json::Object *Params);

class Server {
public:
  Server(const ServerOptions &Opts, int InFd, int OutFd)
      : Opts(Opts), T(InFd, OutFd), W(Opts) {}
  int run();

private:
  void handle(const llvm::json::Object &Message);
  void reply(const llvm::json::Value &Id, llvm::json::Value Result) {
    T.write(llvm::json::Object{
        {"jsonrpc", "2.0"}, {"id", Id}, {"result", std::move(Result)}});
  }
  void replyError(const llvm::json::Value &Id, int Code, llvm::StringRef Msg) {
    T.write(llvm::json::Object{
        {"jsonrpc", "2.0"},
        {"id", Id},
        {"error", llvm::json::Object{{"code", Code}, {"message", Msg.str()}}}});
  }
  void notify(llvm::StringRef Method, llvm::json::Value Params) {
    T.write(llvm::json::Object{
        {"jsonrpc", "2.0"}, {"method", Method.str()}, {"params", std::move(Params)}});
  }

  void didChange(const std::string &Path, const llvm::json::Array &Changes);
  /// Analyses the dirty documents and publishes their diagnostics.
  void analyzeDirty();
  /// `Path`'s text changed (an edit, an open or a close that is not its
  /// file's text): every other open document whose last analysis read it,
  /// as a module it requires directly or not, is checked again.
  void markDependents(const std::string &Path);
  /// The analysis of a document, up to date (analysed now if dirty).
  const Analysis *analysisOf(const std::string &Path);
  void publish(const Analysis &A);
  /// Analyses of every file of the behaviors around `A`: its folder's and
  /// include folders' .bs files and the open documents.
  std::vector<std::unique_ptr<Analysis>> relatedAnalyses(const Analysis &A);
  /// A request on a document at a position: the analysis, its buffer and
  /// the place; false after replying with an error.
  bool locate(const llvm::json::Value &Id, const llvm::json::Object *Params,
              const Analysis *&A, unsigned &Buffer, llvm::SMLoc &Loc);
  llvm::json::Value format(const std::string &Path,
                           const llvm::json::Object *Range);
  /// Why renaming the occurrences (the cursor's at `Loc` among them) to
  /// `NewName` would change the behavior beyond the name, or empty: each
  /// edited file, checked again with the edited texts, reports an error
  /// it did not before (`All`: the name is declared there already), or
  /// the name reaches other places than before (it shadows, or is
  /// shadowed by, another declaration).
  std::string checkRename(llvm::ArrayRef<const Analysis *> All,
                          const Analysis &A, llvm::SMLoc Loc,
                          llvm::ArrayRef<Location> Occurrences,
                          llvm::StringRef NewName);
  void request(const llvm::json::Value &Id, llvm::StringRef Method,
               const llvm::json::Object *Params);
  /// The requests about the workspace rather than a document's place
  /// (ServerWorkspace.cpp): workspace/symbol, willRenameFiles, the call
  /// hierarchy's calls. False if `Method` is none of them.
  bool workspaceRequest(const llvm::json::Value &Id, llvm::StringRef Method,
                        const llvm::json::Object *Params);
  /// `workspace/willRenameFiles`: the edits that follow renamed module
  /// files (renameModuleFile), or null.
  llvm::json::Value willRenameFiles(const llvm::json::Object *Params);

  const ServerOptions &Opts;
  Transport T;
  Workspace W;
  bool Initialized = false, ShutDown = false, Exited = false;
  /// initializationOptions' parameterNameHints: inlay hints are given.
  bool ParameterNameHints = false;
  std::set<std::string> Dirty;
  std::map<std::string, std::unique_ptr<Analysis>> Analyses;
};

} // namespace lsp
} // namespace bsc

#endif

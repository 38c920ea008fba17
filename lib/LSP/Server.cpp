//===- Server.cpp - the language server's loop and dispatch ---------------===//
//
// One message at a time: a request is answered before the next message is
// read. Edits mark their document dirty; it is analysed when no message
// has come for ServerOptions::DebounceMs, or at once when a request needs
// it, and its diagnostics are published then. Every request gets an
// answer: a result, null, or a JSON-RPC error (malformed JSON, unknown
// method, bad parameters, a request before `initialize` or after
// `shutdown`).
//
//===----------------------------------------------------------------------===//
#include "ServerImpl.h"
#include "bsc/Format/Format.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include <set>

using namespace bsc;
using namespace bsc::lsp;

size_t lsp::offsetOf(llvm::StringRef Text,
                     const llvm::json::Object *Position) {
  int64_t Line = Position ? Position->getInteger("line").value_or(0) : 0;
  int64_t Char = Position ? Position->getInteger("character").value_or(0) : 0;
  size_t Start = 0;
  for (int64_t L = 0; L < Line; ++L) {
    size_t NL = Text.find('\n', Start);
    if (NL == llvm::StringRef::npos)
      return Text.size();
    Start = NL + 1;
  }
  size_t Byte = Start;
  for (int64_t Units = 0; Byte < Text.size() && Text[Byte] != '\n' &&
                          Units < Char;) {
    unsigned char B = Text[Byte];
    unsigned Len = B < 0x80 ? 1 : B >= 0xF0 ? 4 : B >= 0xE0 ? 3 : B >= 0xC0 ? 2 : 1;
    Units += Len == 4 ? 2 : 1;
    Byte = std::min(Text.size(), Byte + Len);
  }
  return Byte;
}

llvm::json::Object lsp::endOf(llvm::StringRef Text) {
  int64_t Lines = Text.count('\n');
  llvm::StringRef Last = Text.substr(Text.rfind('\n') + 1);
  return llvm::json::Object{{"line", Lines},
                            {"character", int64_t(Last.size())}};
}


std::string lsp::pathOf(const llvm::json::Object *Params) {
  const llvm::json::Object *Doc =
      Params ? Params->getObject("textDocument") : nullptr;
  std::optional<llvm::StringRef> URI = Doc ? Doc->getString("uri") : std::nullopt;
  return URI ? uriToPath(*URI) : "";
}

int Server::run() {
  while (!Exited) {
    llvm::json::Value Message = nullptr;
    std::string Error;
    int Timeout = Dirty.empty() ? -1 : int(Opts.DebounceMs);
    switch (T.read(Message, Error, Timeout)) {
    case Transport::Read::Timeout:
      analyzeDirty();
      continue;
    case Transport::Read::End:
      return 1; // The client went away without `exit`.
    case Transport::Read::Malformed:
      replyError(nullptr, ParseError, Error);
      continue;
    case Transport::Read::Message:
      break;
    }
    if (const llvm::json::Object *O = Message.getAsObject())
      handle(*O);
    else
      replyError(nullptr, InvalidRequest, "a message must be a JSON object");
  }
  return ShutDown ? 0 : 1;
}

void Server::handle(const llvm::json::Object &Message) {
  std::optional<llvm::StringRef> Method = Message.getString("method");
  const llvm::json::Value *Id = Message.get("id");
  const llvm::json::Object *Params = Message.getObject("params");
  if (!Method) {
    if (Id && !Message.get("result") && !Message.get("error"))
      replyError(*Id, InvalidRequest, "a request needs a method");
    return; // A response to a request of ours: nothing to do.
  }
  if (Id) {
    request(*Id, *Method, Params);
    return;
  }
  // Notifications.
  if (*Method == "exit") {
    Exited = true;
    return;
  }
  if (!Initialized || ShutDown)
    return;
  std::string Path = pathOf(Params);
  if (*Method == "textDocument/didOpen" && !Path.empty()) {
    const llvm::json::Object *Doc = Params->getObject("textDocument");
    std::string Text = Doc->getString("text").value_or("").str();
    // An editor's text that is not the file's (a buffer restored unsaved)
    // changes what the documents requiring it read.
    auto OnDisk = llvm::MemoryBuffer::getFile(Path);
    bool Differs = !OnDisk || (*OnDisk)->getBuffer() != Text;
    W.open(Path, std::move(Text), Doc->getInteger("version").value_or(0));
    Dirty.insert(Path);
    if (Differs)
      markDependents(Path);
  } else if (*Method == "textDocument/didChange" && !Path.empty()) {
    if (const llvm::json::Array *Changes = Params->getArray("contentChanges"))
      didChange(Path, *Changes);
    if (std::optional<int64_t> V =
            Params->getObject("textDocument")->getInteger("version"))
      W.setVersion(Path, *V);
  } else if (*Method == "textDocument/didClose" && !Path.empty()) {
    W.close(Path);
    Dirty.erase(Path);
    Analyses.erase(Path);
    markDependents(Path); // They read the file on disk from now on.
    // Its diagnostics go with it: the file is no longer being edited.
    notify("textDocument/publishDiagnostics",
           llvm::json::Object{{"uri", pathToURI(Path)},
                              {"diagnostics", llvm::json::Array()}});
  } else if (*Method == "workspace/didChangeWatchedFiles") {
    // A module, a binding object or bscript.json changed on disk: every
    // open document may read it.
    for (const auto &[Open, Text] : W.getOpen())
      Dirty.insert(Open);
  }
  // Others ($/cancelRequest, initialized, didSave, ...) need nothing:
  // requests are answered before the next message is read.
}

void Server::didChange(const std::string &Path,
                       const llvm::json::Array &Changes) {
  std::string *Text = W.getText(Path);
  if (!Text)
    return;
  for (const llvm::json::Value &C : Changes) {
    const llvm::json::Object *Change = C.getAsObject();
    if (!Change)
      continue;
    std::string New = Change->getString("text").value_or("").str();
    const llvm::json::Object *Range = Change->getObject("range");
    if (!Range) {
      *Text = std::move(New);
      continue;
    }
    size_t From = offsetOf(*Text, Range->getObject("start"));
    size_t To = offsetOf(*Text, Range->getObject("end"));
    if (To < From)
      std::swap(From, To);
    Text->replace(From, To - From, New);
  }
  Dirty.insert(Path);
  markDependents(Path);
}

void Server::markDependents(const std::string &Path) {
  for (const auto &[Doc, A] : Analyses)
    if (Doc != Path && A && W.getText(Doc) && A->getBuffer(Path))
      Dirty.insert(Doc);
}

void Server::publish(const Analysis &A) {
  for (auto &[URI, List] : diagnostics(A)) {
    llvm::json::Object Params{{"uri", URI}, {"diagnostics", std::move(List)}};
    // The version of the text they are about, for an open document.
    if (std::optional<int64_t> V = W.getVersion(uriToPath(URI)))
      Params["version"] = *V;
    notify("textDocument/publishDiagnostics", std::move(Params));
  }
}

void Server::analyzeDirty() {
  std::set<std::string> Paths;
  std::swap(Paths, Dirty);
  for (const std::string &Path : Paths) {
    Analyses[Path] = W.analyze(Path);
    publish(*Analyses[Path]);
  }
}

const Analysis *Server::analysisOf(const std::string &Path) {
  auto It = Analyses.find(Path);
  if (It == Analyses.end() || Dirty.count(Path)) {
    Dirty.erase(Path);
    Analyses[Path] = W.analyze(Path);
    publish(*Analyses[Path]);
    return Analyses[Path].get();
  }
  return It->second.get();
}

std::vector<std::unique_ptr<Analysis>>
Server::relatedAnalyses(const Analysis &A) {
  std::set<std::string> Files;
  std::vector<std::string> Dirs = A.Config.Include;
  Dirs.push_back(llvm::sys::path::parent_path(A.Path).str());
  for (const std::string &Dir : Dirs) {
    std::error_code EC;
    for (llvm::sys::fs::directory_iterator It(Dir, EC), End; It != End && !EC;
         It.increment(EC))
      if (llvm::sys::path::extension(It->path()) == ".bs")
        Files.insert(uriToPath(pathToURI(It->path())));
  }
  for (const auto &[Path, Text] : W.getOpen())
    Files.insert(Path);
  std::vector<std::unique_ptr<Analysis>> All;
  for (const std::string &Path : Files)
    if (Path != A.Path)
      All.push_back(W.analyze(Path));
  return All;
}

bool Server::locate(const llvm::json::Value &Id,
                    const llvm::json::Object *Params, const Analysis *&A,
                    unsigned &Buffer, llvm::SMLoc &Loc) {
  std::string Path = pathOf(Params);
  if (Path.empty()) {
    replyError(Id, InvalidParams, "the request names no file document");
    return false;
  }
  A = analysisOf(Path);
  Buffer = A->getBuffer(Path);
  if (!Buffer) {
    replyError(Id, RequestFailed,
               "'" + Path + "' could not be read as a b-script module");
    return false;
  }
  Loc = A->getLoc(Buffer, Params->get("position"));
  return true;
}

llvm::json::Value Server::format(const std::string &Path,
                                 const llvm::json::Object *Range) {
  std::string Text;
  if (const std::string *Open = W.getText(Path))
    Text = *Open;
  else if (auto Buf = llvm::MemoryBuffer::getFile(Path))
    Text = (*Buf)->getBuffer().str();
  else
    return nullptr;
  llvm::SourceMgr SM;
  unsigned ID = SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(Text, Path), llvm::SMLoc());
  DiagnosticEngine Diags;
  auto F = format::formatBuffer(SM, ID, Diags);
  if (!F) {
    llvm::consumeError(F.takeError());
    return nullptr;
  }
  if (!*F)
    return nullptr; // Syntax errors: the diagnostics say where.
  llvm::json::Array Edits;
  if (!Range) {
    if ((*F)->Text != Text)
      Edits.push_back(llvm::json::Object{
          {"range",
           llvm::json::Object{
               {"start", llvm::json::Object{{"line", 0}, {"character", 0}}},
               {"end", endOf(Text)}}},
          {"newText", (*F)->Text}});
    return Edits;
  }
  auto LineOf = [&](const char *Key) {
    const llvm::json::Object *P = Range->getObject(Key);
    return unsigned(P ? P->getInteger("line").value_or(0) : 0) + 1;
  };
  std::optional<format::RangeEdit> E =
      format::formatLines(**F, LineOf("start"), LineOf("end"));
  if (!E)
    return Edits;
  llvm::json::Object Start{{"line", int64_t(E->FromLine) - 1}, {"character", 0}};
  llvm::json::Object End{{"line", int64_t(E->ToLine)}, {"character", 0}};
  // The last line of a file without a final newline ends the text.
  if (int64_t(E->ToLine) > int64_t(llvm::StringRef(Text).count('\n')))
    End = endOf(Text);
  Edits.push_back(llvm::json::Object{
      {"range", llvm::json::Object{{"start", std::move(Start)},
                                   {"end", std::move(End)}}},
      {"newText", E->Text}});
  return Edits;
}

static llvm::json::Object capabilities() {
  llvm::json::Array Types, Modifiers;
  for (const char *T : TokenTypes)
    Types.push_back(T);
  for (const char *M : TokenModifiers)
    Modifiers.push_back(M);
  return llvm::json::Object{
      {"textDocumentSync",
       llvm::json::Object{{"openClose", true}, {"change", 2}}},
      {"hoverProvider", true},
      {"definitionProvider", true},
      {"referencesProvider", true},
      {"documentHighlightProvider", true},
      {"callHierarchyProvider", true},
      {"workspace",
       llvm::json::Object{
           {"fileOperations",
            llvm::json::Object{
                {"willRename",
                 llvm::json::Object{
                     {"filters",
                      llvm::json::Array{llvm::json::Object{
                          {"scheme", "file"},
                          {"pattern",
                           llvm::json::Object{{"glob", "**/*.bs"}}}}}}}}}}}},
      {"documentSymbolProvider", true},
      {"workspaceSymbolProvider", true},
      {"completionProvider",
       llvm::json::Object{
           {"triggerCharacters", llvm::json::Array{".", ":"}}}},
      {"signatureHelpProvider",
       llvm::json::Object{
           {"triggerCharacters", llvm::json::Array{"(", ","}}}},
      {"renameProvider", llvm::json::Object{{"prepareProvider", true}}},
      {"documentFormattingProvider", true},
      {"documentRangeFormattingProvider", true},
      {"codeActionProvider",
       llvm::json::Object{
           {"codeActionKinds", llvm::json::Array{"quickfix"}}}},
      {"foldingRangeProvider", true},
      {"semanticTokensProvider",
       llvm::json::Object{
           {"legend", llvm::json::Object{{"tokenTypes", std::move(Types)},
                                         {"tokenModifiers",
                                          std::move(Modifiers)}}},
           {"full", true}}}};
}

void Server::request(const llvm::json::Value &Id, llvm::StringRef Method,
                     const llvm::json::Object *Params) {
  if (Method == "initialize") {
    if (Initialized)
      return replyError(Id, InvalidRequest, "initialize was already sent");
    Initialized = true;
    // Inlay hints are off unless the client asks for them.
    const llvm::json::Object *Init =
        Params ? Params->getObject("initializationOptions") : nullptr;
    ParameterNameHints =
        Init && Init->getBoolean("parameterNameHints").value_or(false);
    llvm::json::Object Capabilities = capabilities();
    if (ParameterNameHints)
      Capabilities["inlayHintProvider"] = true;
    return reply(Id, llvm::json::Object{
                         {"capabilities", std::move(Capabilities)},
                         {"serverInfo", llvm::json::Object{{"name", "bsc"}}}});
  }
  if (!Initialized)
    return replyError(Id, ServerNotInitialized,
                      "the first request must be initialize");
  if (ShutDown)
    return replyError(Id, InvalidRequest, "the server is shutting down");
  if (Method == "shutdown") {
    ShutDown = true;
    return reply(Id, nullptr);
  }
  if (workspaceRequest(Id, Method, Params))
    return;
  if (!Method.starts_with("textDocument/"))
    return replyError(Id, MethodNotFound, "no method '" + Method.str() + "'");
  llvm::StringRef What = Method.drop_front(strlen("textDocument/"));
  if (What == "formatting" || What == "rangeFormatting") {
    std::string Path = pathOf(Params);
    if (Path.empty())
      return replyError(Id, InvalidParams, "the request names no file document");
    return reply(Id, format(Path, What == "rangeFormatting"
                                      ? Params->getObject("range")
                                      : nullptr));
  }
  static const std::set<std::string> Known = {
      "hover",          "definition",   "references",     "documentSymbol",
      "completion",     "signatureHelp", "rename",        "prepareRename",
      "codeAction",     "foldingRange", "semanticTokens/full",
      "documentHighlight", "prepareCallHierarchy", "inlayHint"};
  if (!Known.count(What.str()))
    return replyError(Id, MethodNotFound, "no method '" + Method.str() + "'");
  const Analysis *A;
  unsigned Buffer;
  llvm::SMLoc Loc;
  if (!locate(Id, Params, A, Buffer, Loc))
    return;
  if (What == "hover")
    return reply(Id, hover(*A, Loc));
  if (What == "definition")
    return reply(Id, definition(*A, Loc));
  if (What == "documentHighlight")
    return reply(Id, documentHighlights(*A, Buffer, Loc));
  if (What == "prepareCallHierarchy")
    return reply(Id, prepareCallHierarchy(*A, Loc));
  if (What == "inlayHint") {
    if (!ParameterNameHints)
      return reply(Id, llvm::json::Array());
    const llvm::json::Object *R = Params->getObject("range");
    llvm::SMLoc From = A->getLoc(Buffer, R ? R->get("start") : nullptr);
    llvm::SMLoc To = R ? A->getLoc(Buffer, R->get("end"))
                       : llvm::SMLoc::getFromPointer(
                             A->C->SM.getMemoryBuffer(Buffer)->getBufferEnd());
    return reply(Id, inlayHints(*A, Buffer, {From, To}));
  }
  if (What == "documentSymbol")
    return reply(Id, documentSymbols(*A, Buffer));
  if (What == "completion")
    return reply(Id, completion(*A, Buffer, Loc));
  if (What == "signatureHelp")
    return reply(Id, signatureHelp(*A, Buffer, Loc));
  if (What == "foldingRange")
    return reply(Id, foldingRanges(*A, Buffer));
  if (What == "semanticTokens/full")
    return reply(Id, semanticTokens(*A, Buffer));
  if (What == "prepareRename")
    return reply(Id, prepareRename(*A, Loc));
  if (What == "codeAction") {
    const llvm::json::Object *R = Params->getObject("range");
    llvm::SMLoc From = A->getLoc(Buffer, R ? R->get("start") : nullptr);
    llvm::SMLoc To = A->getLoc(Buffer, R ? R->get("end") : nullptr);
    return reply(Id, codeActions(*A, Buffer, {From, To}));
  }
  // references and rename look at the whole behavior.
  std::vector<std::unique_ptr<Analysis>> Others = relatedAnalyses(*A);
  std::vector<const Analysis *> All{A};
  for (const auto &O : Others)
    All.push_back(O.get());
  if (What == "references") {
    const llvm::json::Object *Context = Params->getObject("context");
    bool WithDecl =
        Context && Context->getBoolean("includeDeclaration").value_or(false);
    return reply(Id, references(All, *A, Loc, WithDecl));
  }
  std::optional<llvm::StringRef> NewName = Params->getString("newName");
  if (!NewName)
    return replyError(Id, InvalidParams, "rename needs a newName");
  llvm::Expected<llvm::json::Value> Edit = rename(All, *A, Loc, *NewName);
  if (!Edit)
    return replyError(Id, RequestFailed, llvm::toString(Edit.takeError()));
  std::string Why =
      checkRename(All, *A, Loc, findOccurrences(All, *A, Loc, true), *NewName);
  if (!Why.empty())
    return replyError(Id, RequestFailed, Why);
  reply(Id, std::move(*Edit));
}

int lsp::runServer(const ServerOptions &Opts, int InFd, int OutFd) {
  return Server(Opts, InFd, OutFd).run();
}

//===- Workspace.cpp - documents, behaviors and their analyses ------------===//
//
// A document is checked as the input of its behavior, as `bsc` would
// check it with the behavior's `--bind`, `-I` and `-target` (from
// bscript.json), reading the open documents' texts instead of their files.
// Positions are converted here: LSP counts UTF-16 code units, the
// SourceMgr bytes.
//
//===----------------------------------------------------------------------===//
#include "Workspace.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/ConvertUTF.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

using namespace bsc;
using namespace bsc::lsp;

/// An `untitled:` document (a buffer the editor has not saved yet) is
/// checked under a path no file has: the folder below, which cannot exist
/// (a name with a colon at the root), so that nothing is read beside it.
static constexpr llvm::StringLiteral UntitledFolder = "/untitled:/";

/// The file name each untitled document got -> its URI as the editor
/// wrote it (one server, one thread: the table lives as long as it).
static std::map<std::string, std::string> &untitledNames() {
  static std::map<std::string, std::string> Names;
  return Names;
}

std::string lsp::uriToPath(llvm::StringRef URI) {
  if (URI.consume_front("untitled:")) {
    // A module is named by its file: the name as a b-script name.
    std::string Name;
    for (char C : URI)
      Name += llvm::isAlnum(C) || C == '_' ? C : '_';
    if (Name.empty() || llvm::isDigit(Name[0]))
      Name = "Untitled" + Name;
    std::string Full = ("untitled:" + URI).str();
    std::string File = Name + ".bs";
    // Two documents whose names differ only in punctuation get two files.
    for (unsigned N = 2; untitledNames().count(File) &&
                         untitledNames()[File] != Full;
         ++N)
      File = Name + "_" + std::to_string(N) + ".bs";
    untitledNames()[File] = Full;
    return (UntitledFolder + File).str();
  }
  if (!URI.consume_front("file://"))
    return "";
  std::string Path;
  for (size_t I = 0; I < URI.size(); ++I) {
    unsigned Byte;
    if (URI[I] == '%' && I + 2 < URI.size() &&
        !URI.substr(I + 1, 2).getAsInteger(16, Byte)) {
      Path += char(Byte);
      I += 2;
    } else {
      Path += URI[I];
    }
  }
  llvm::SmallString<256> Clean(Path);
  llvm::sys::path::remove_dots(Clean, /*remove_dot_dot=*/true);
  return std::string(Clean);
}

std::string lsp::pathToURI(llvm::StringRef Path) {
  if (Path.consume_front(UntitledFolder)) {
    // Back to the editor's name (uriToPath kept it but for punctuation).
    auto It = untitledNames().find(Path.str());
    return It != untitledNames().end() ? It->second
                                       : "untitled:" + Path.drop_back(3).str();
  }
  std::string URI = "file://";
  for (char C : Path) {
    if (llvm::isAlnum(C) || llvm::StringRef("/-._~").contains(C))
      URI += C;
    else
      URI += "%" + llvm::utohexstr((unsigned char)C, false, 2);
  }
  return URI;
}

//===----------------------------------------------------------------------===//
// bscript.json
//===----------------------------------------------------------------------===//

/// The entry of a build folder's "behaviors" (what bscript_add_behavior
/// writes) that `Script` belongs to: one that lists it among its
/// "sources", else one with a source in its folder or an "include" folder
/// holding it (a module the sources require).
static const llvm::json::Object *
findBehavior(const llvm::json::Array &Behaviors, llvm::StringRef Script) {
  llvm::StringRef Dir = llvm::sys::path::parent_path(Script);
  const llvm::json::Object *Near = nullptr;
  for (const llvm::json::Value &B : Behaviors) {
    const llvm::json::Object *O = B.getAsObject();
    if (!O)
      continue;
    auto Strings = [&](llvm::StringRef Key) {
      std::vector<llvm::StringRef> Out;
      if (const llvm::json::Array *A = O->getArray(Key))
        for (const llvm::json::Value &S : *A)
          if (std::optional<llvm::StringRef> Str = S.getAsString())
            Out.push_back(*Str);
      return Out;
    };
    for (llvm::StringRef Source : Strings("sources")) {
      if (Source == Script)
        return O;
      if (!Near && llvm::sys::path::parent_path(Source) == Dir)
        Near = O;
    }
    for (llvm::StringRef Include : Strings("include"))
      if (!Near && Dir == Include)
        Near = O;
  }
  return Near;
}

/// Reads `File`'s settings for the script at `Script`: the top level's, or
/// those of the entry of "behaviors" whose "sources" hold it.
static BehaviorConfig readConfig(llvm::StringRef File, llvm::StringRef Script) {
  BehaviorConfig Config;
  Config.File = File.str();
  auto Buf = llvm::MemoryBuffer::getFile(File);
  if (!Buf) {
    Config.Error = "cannot read '" + File.str() + "': " +
                   Buf.getError().message();
    return Config;
  }
  llvm::Expected<llvm::json::Value> V = llvm::json::parse((*Buf)->getBuffer());
  if (!V) {
    Config.Error = "'" + File.str() + "' is not JSON: " +
                   llvm::toString(V.takeError());
    return Config;
  }
  const llvm::json::Object *Settings = V->getAsObject();
  if (Settings)
    if (const llvm::json::Array *Behaviors = Settings->getArray("behaviors")) {
      Settings = findBehavior(*Behaviors, Script);
      if (!Settings)
        return Config; // Not one of its behaviors': the defaults.
    }
  if (!Settings) {
    Config.Error = "'" + File.str() + "' is not a JSON object";
    return Config;
  }
  llvm::StringRef Dir = llvm::sys::path::parent_path(File);
  auto Paths = [&](llvm::StringRef Key, std::vector<std::string> &Out) {
    const llvm::json::Value *List = Settings->get(Key);
    if (!List)
      return;
    const llvm::json::Array *A = List->getAsArray();
    for (size_t I = 0; A && I < A->size(); ++I) {
      std::optional<llvm::StringRef> S = (*A)[I].getAsString();
      if (!S) {
        A = nullptr;
        break;
      }
      llvm::SmallString<256> P(*S);
      llvm::sys::fs::make_absolute(Dir, P);
      Out.push_back(std::string(P));
    }
    if (!A)
      Config.Error = "'" + File.str() + "': \"" + Key.str() +
                     "\" must be a list of paths";
  };
  Paths("bind", Config.Bind);
  Paths("include", Config.Include);
  if (const llvm::json::Value *T = Settings->get("target")) {
    if (std::optional<llvm::StringRef> S = T->getAsString())
      Config.Target = S->str();
    else
      Config.Error = "'" + File.str() + "': \"target\" must be a string";
  }
  return Config;
}

BehaviorConfig lsp::findConfig(llvm::StringRef Path) {
  llvm::SmallString<256> Dir = llvm::sys::path::parent_path(Path);
  while (!Dir.empty()) {
    for (const char *Sub : {"", "build"}) {
      llvm::SmallString<256> File(Dir);
      llvm::sys::path::append(File, Sub, "bscript.json");
      if (llvm::sys::fs::is_regular_file(File))
        return readConfig(File, Path);
    }
    llvm::StringRef Parent = llvm::sys::path::parent_path(Dir);
    if (Parent == Dir)
      break;
    Dir = Parent;
  }
  return {};
}

//===----------------------------------------------------------------------===//
// Analysis
//===----------------------------------------------------------------------===//

std::unique_ptr<Analysis> Workspace::analyze(llvm::StringRef Path) {
  auto A = std::make_unique<Analysis>();
  A->Path = Path.str();
  // An untitled document belongs to no folder: it is checked as a file of
  // the server's (the editor's workspace), its settings and modules.
  bool Untitled = Path.starts_with(UntitledFolder);
  llvm::SmallString<256> Here;
  llvm::sys::fs::current_path(Here);
  A->Config = findConfig(Untitled ? (Here + "/Untitled.bs").str() : Path);
  A->C = std::make_unique<Compilation>();
  FrontendOptions FOpts = Opts.BaseOptions(A->Config.Target);
  FOpts.Inputs = {Path.str()};
  FOpts.IncludeDirs = A->Config.Include;
  if (Untitled)
    FOpts.IncludeDirs.insert(FOpts.IncludeDirs.begin(), std::string(Here));
  FOpts.BindObjects = A->Config.Bind;
  FOpts.Unsaved = &Unsaved;
  runFrontend(*A->C, FOpts);
  if (A->C->Modules.empty() && !FOpts.BindObjects.empty()) {
    // Binding objects that cannot be read stop the front end before the
    // scripts: check them without, and say why at the top of the file.
    for (const Diagnostic &D : A->C->Diags.getDiagnostics())
      if (D.Sev == Severity::Error)
        A->SetupErrors.push_back(D.Message);
    A->C = std::make_unique<Compilation>();
    FOpts.BindObjects.clear();
    runFrontend(*A->C, FOpts);
  }
  A->C->Diags.sortBySource(A->C->SM);
  A->Idx = buildIndex(A->C->Modules);
  return A;
}

unsigned Analysis::getBuffer(llvm::StringRef File) const {
  for (const ModuleAST *M : C->Modules)
    if (getPath(M->BufferID) == File)
      return M->BufferID;
  return 0;
}

std::string Analysis::getPath(unsigned BufferID) const {
  llvm::SmallString<256> P(
      C->SM.getMemoryBuffer(BufferID)->getBufferIdentifier());
  llvm::sys::fs::make_absolute(P);
  llvm::sys::path::remove_dots(P, /*remove_dot_dot=*/true);
  return std::string(P);
}

/// The UTF-16 length of UTF-8 text (each byte of a bad sequence counts 1).
static unsigned utf16Length(llvm::StringRef Text) {
  unsigned N = 0;
  for (size_t I = 0; I < Text.size();) {
    unsigned char B = Text[I];
    unsigned Len = B < 0x80 ? 1 : B >= 0xF0 ? 4 : B >= 0xE0 ? 3 : B >= 0xC0 ? 2 : 1;
    if (I + Len > Text.size())
      Len = 1;
    N += Len == 4 ? 2 : 1;
    I += Len;
  }
  return N;
}

llvm::SMLoc Analysis::getLoc(unsigned BufferID,
                             const llvm::json::Value *Position) const {
  // No position (a request that needs none, or a client's mistake): the
  // start of the document, so that every feature has a place to start from.
  const llvm::json::Object *P = Position ? Position->getAsObject() : nullptr;
  int64_t Line = P ? P->getInteger("line").value_or(0) : 0;
  int64_t Char = P ? P->getInteger("character").value_or(0) : 0;
  llvm::StringRef Text = C->SM.getMemoryBuffer(BufferID)->getBuffer();
  // The line's start; past the last line, the end of the text.
  size_t Start = 0;
  for (int64_t L = 0; L < Line; ++L) {
    size_t NL = Text.find('\n', Start);
    if (NL == llvm::StringRef::npos)
      return llvm::SMLoc::getFromPointer(Text.end());
    Start = NL + 1;
  }
  llvm::StringRef Rest = Text.substr(Start);
  Rest = Rest.take_until([](char C) { return C == '\n'; });
  size_t Byte = 0;
  for (int64_t Units = 0; Byte < Rest.size() && Units < Char;) {
    unsigned char B = Rest[Byte];
    unsigned Len = B < 0x80 ? 1 : B >= 0xF0 ? 4 : B >= 0xE0 ? 3 : B >= 0xC0 ? 2 : 1;
    Units += Len == 4 ? 2 : 1;
    Byte = std::min(Rest.size(), Byte + Len);
  }
  return llvm::SMLoc::getFromPointer(Rest.data() + Byte);
}

llvm::json::Object Analysis::getPosition(llvm::SMLoc Loc) const {
  unsigned ID = C->SM.FindBufferContainingLoc(Loc);
  if (!ID)
    return llvm::json::Object{{"line", 0}, {"character", 0}};
  auto [Line, Col] = C->SM.getLineAndColumn(Loc, ID);
  llvm::StringRef LineText(Loc.getPointer() - (Col - 1), Col - 1);
  return llvm::json::Object{{"line", int64_t(Line) - 1},
                            {"character", int64_t(utf16Length(LineText))}};
}

llvm::json::Object Analysis::getRange(llvm::SMRange R) const {
  llvm::SMLoc End = R.End.isValid() ? R.End : R.Start;
  return llvm::json::Object{{"start", getPosition(R.Start)},
                            {"end", getPosition(End)}};
}

llvm::json::Object Analysis::getLocation(llvm::SMRange R) const {
  unsigned ID = C->SM.FindBufferContainingLoc(R.Start);
  return llvm::json::Object{{"uri", ID ? pathToURI(getPath(ID)) : ""},
                            {"range", getRange(R)}};
}

//===- Workspace.h - documents, behaviors and their analyses ---*- C++ -*-===//
#ifndef BSC_LIB_LSP_WORKSPACE_H
#define BSC_LIB_LSP_WORKSPACE_H

#include "bsc/LSP/Index.h"
#include "bsc/LSP/Server.h"
#include "llvm/Support/JSON.h"
#include <map>
#include <memory>
#include <string>

namespace bsc {
namespace lsp {

/// A behavior's settings, from `bscript.json` (docs/editors.md).
struct BehaviorConfig {
  std::vector<std::string> Bind, Include;
  std::string Target;
  /// The file they came from (empty: none found, the defaults).
  std::string File;
  /// What is wrong with that file, if anything (shown as a diagnostic).
  std::string Error;
};

/// Finds and reads the configuration of the script at `Path`: the nearest
/// `bscript.json` in its folder or above, or in a `build` folder there.
BehaviorConfig findConfig(llvm::StringRef Path);

/// One check of a behavior, with the edited file as its input.
struct Analysis {
  std::unique_ptr<Compilation> C;
  Index Idx;
  std::string Path;
  BehaviorConfig Config;
  /// Errors of the binding objects when they could not be read (the
  /// behavior was then checked without them).
  std::vector<std::string> SetupErrors;

  /// The buffer of the module read from `Path`, or 0.
  unsigned getBuffer(llvm::StringRef Path) const;
  /// The absolute path of a buffer's file.
  std::string getPath(unsigned BufferID) const;
  /// LSP positions (0-based line, UTF-16 character) and locations; a
  /// missing or damaged position is the document's start, and one past a
  /// line or the text is clamped to it.
  llvm::SMLoc getLoc(unsigned BufferID, const llvm::json::Value *Position) const;
  llvm::json::Object getPosition(llvm::SMLoc Loc) const;
  llvm::json::Object getRange(llvm::SMRange R) const;
  /// {uri, range}.
  llvm::json::Object getLocation(llvm::SMRange R) const;
};

/// The open documents and what the server knows of them.
class Workspace {
public:
  explicit Workspace(const ServerOptions &Opts) : Opts(Opts) {}

  void open(llvm::StringRef Path, std::string Text, int64_t Version) {
    Unsaved[Path.str()] = std::move(Text);
    Versions[Path.str()] = Version;
  }
  void close(llvm::StringRef Path) {
    Unsaved.erase(Path.str());
    Versions.erase(Path.str());
  }
  void setVersion(llvm::StringRef Path, int64_t Version) {
    Versions[Path.str()] = Version;
  }
  /// The editor's version of an open document (diagnostics name it).
  std::optional<int64_t> getVersion(llvm::StringRef Path) const {
    auto It = Versions.find(Path.str());
    return It == Versions.end() ? std::nullopt : std::optional(It->second);
  }
  /// The editor's text of an open document.
  std::string *getText(llvm::StringRef Path) {
    auto It = Unsaved.find(Path.str());
    return It == Unsaved.end() ? nullptr : &It->second;
  }
  const std::map<std::string, std::string> &getOpen() const { return Unsaved; }

  /// Checks the behavior with `Path` as its input, with the open
  /// documents' texts.
  std::unique_ptr<Analysis> analyze(llvm::StringRef Path);

private:
  const ServerOptions &Opts;
  std::map<std::string, std::string> Unsaved;
  std::map<std::string, int64_t> Versions;
};

/// `file:///a/b.bs` -> `/a/b.bs` (percent escapes decoded); empty if the
/// URI is not a file's.
std::string uriToPath(llvm::StringRef URI);
std::string pathToURI(llvm::StringRef Path);

} // namespace lsp
} // namespace bsc

#endif

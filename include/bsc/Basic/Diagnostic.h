//===- Diagnostic.h - diagnostics collected by every phase -----*- C++ -*-===//
//
// Phases never print (style.md): they report into a DiagnosticEngine, which
// formats the message from the one table in DiagnosticKinds.def and keeps
// it. The driver prints the collected diagnostics with llvm::SourceMgr (file,
// line, column, source line and caret) or, in --verify mode, checks them
// against the `# expected-error {{...}}` comments of the sources.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_DIAGNOSTIC_H
#define BSC_BASIC_DIAGNOSTIC_H

#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/SMLoc.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/SourceMgr.h"
#include <string>
#include <vector>

namespace llvm {
class raw_ostream;
}

namespace bsc {

namespace diag {
/// Every diagnostic kind, from DiagnosticKinds.def.
enum Kind : unsigned {
#define DIAG(Id, Severity, Format) Id,
#include "bsc/Basic/DiagnosticKinds.def"
  NumKinds
};
} // namespace diag

enum class Severity { Error, Warning, Note };

/// One reported diagnostic, already formatted.
struct Diagnostic {
  diag::Kind Kind;
  Severity Sev;
  llvm::SMLoc Loc;
  std::string Message;
  llvm::SmallVector<llvm::SMRange, 1> Ranges;
  /// Replacements printed under the caret line, as clang's fix-its.
  llvm::SmallVector<llvm::SMFixIt, 1> FixIts;
  /// Whether the source line and the caret follow the message.
  bool ShowSourceLine = true;
};

/// Streamed into a diagnostic whose location is a line of data (a replayed
/// JSON line, hundreds of characters long): `file:line:col:` names the
/// line, and echoing it would bury what the message says.
struct NoSourceLine {};

/// The severity and format string of a kind.
Severity getSeverity(diag::Kind K);
llvm::StringRef getFormat(diag::Kind K);
llvm::StringRef getIdName(diag::Kind K);

class DiagnosticEngine;

/// Collects the arguments of one diagnostic; the diagnostic is recorded when
/// the builder goes out of scope: `Diags.report(Loc, diag::err_x) << Name;`.
class DiagnosticBuilder {
public:
  DiagnosticBuilder(DiagnosticEngine *Engine, diag::Kind K, llvm::SMLoc Loc)
      : Engine(Engine), Kind(K), Loc(Loc) {}
  DiagnosticBuilder(DiagnosticBuilder &&Other)
      : Engine(Other.Engine), Kind(Other.Kind), Loc(Other.Loc),
        Args(std::move(Other.Args)), Ranges(std::move(Other.Ranges)),
        FixIts(std::move(Other.FixIts)), ShowSourceLine(Other.ShowSourceLine) {
    Other.Engine = nullptr;
  }
  DiagnosticBuilder(const DiagnosticBuilder &) = delete;
  ~DiagnosticBuilder();

  DiagnosticBuilder &operator<<(llvm::StringRef S) {
    Args.push_back(S.str());
    return *this;
  }
  DiagnosticBuilder &operator<<(const char *S) {
    return *this << llvm::StringRef(S);
  }
  DiagnosticBuilder &operator<<(const std::string &S) {
    return *this << llvm::StringRef(S);
  }
  DiagnosticBuilder &operator<<(long long N) {
    Args.push_back(std::to_string(N));
    return *this;
  }
  DiagnosticBuilder &operator<<(int N) { return *this << (long long)N; }
  DiagnosticBuilder &operator<<(unsigned N) { return *this << (long long)N; }
  DiagnosticBuilder &operator<<(size_t N) { return *this << (long long)N; }
  /// Underlines a range of the source line in addition to the caret.
  DiagnosticBuilder &operator<<(llvm::SMRange R) {
    Ranges.push_back(R);
    return *this;
  }
  /// Suggests replacing a range with a text (printed under the caret).
  DiagnosticBuilder &operator<<(llvm::SMFixIt F) {
    FixIts.push_back(std::move(F));
    return *this;
  }
  DiagnosticBuilder &operator<<(NoSourceLine) {
    ShowSourceLine = false;
    return *this;
  }

private:
  DiagnosticEngine *Engine;
  diag::Kind Kind;
  llvm::SMLoc Loc;
  llvm::SmallVector<std::string, 3> Args;
  llvm::SmallVector<llvm::SMRange, 1> Ranges;
  llvm::SmallVector<llvm::SMFixIt, 1> FixIts;
  bool ShowSourceLine = true;
};

/// Keeps the diagnostics of a compilation in the order they were reported.
class DiagnosticEngine {
public:
  /// After this many errors further errors (and their notes) are dropped, so
  /// that garbage input (random bytes, a 10 MB file) cannot produce an
  /// unbounded flood; phases poll tooManyErrors() to stop early.
  static constexpr unsigned MaxErrors = 50;

  DiagnosticBuilder report(llvm::SMLoc Loc, diag::Kind K) {
    return DiagnosticBuilder(this, K, Loc);
  }

  /// `-Wno-<group>`: drops the warnings of a group (and their notes).
  /// Returns false if there is no such group.
  bool ignoreWarningGroup(llvm::StringRef Group);
  /// `-Werror=<group>`: the warnings of a group are errors. Returns false
  /// if there is no such group.
  bool promoteWarningGroup(llvm::StringRef Group);
  /// `-Werror`: every warning is an error.
  void promoteAllWarnings() { AllWarningsAreErrors = true; }
  /// The names `-Wno-` takes, for messages.
  static std::string getWarningGroupList();

  /// Orders the diagnostics so far by file (in the order the files were
  /// loaded) and position, each with its notes; locationless ones first.
  /// Phases report in the order they work, which is not the reader's.
  void sortBySource(const llvm::SourceMgr &SM);

  bool hasErrors() const { return NumErrors != 0; }
  unsigned getNumErrors() const { return NumErrors; }
  unsigned getNumWarnings() const { return NumWarnings; }
  bool tooManyErrors() const { return NumErrors >= MaxErrors; }
  llvm::ArrayRef<Diagnostic> getDiagnostics() const { return Diags; }
  void clear();

  /// Formats `Format` with the %N arguments (also used by tests).
  static std::string format(llvm::StringRef Format,
                            llvm::ArrayRef<std::string> Args);

private:
  friend class DiagnosticBuilder;
  void record(diag::Kind K, llvm::SMLoc Loc, std::string Message,
              llvm::ArrayRef<llvm::SMRange> Ranges,
              llvm::ArrayRef<llvm::SMFixIt> FixIts, bool ShowSourceLine);

  std::vector<Diagnostic> Diags;
  unsigned NumErrors = 0;
  unsigned NumWarnings = 0;
  bool DroppingNotes = false;
  bool Ignored[diag::NumKinds] = {};
  bool Promoted[diag::NumKinds] = {};
  bool AllWarningsAreErrors = false;
};

/// Prints diagnostics the way clang does: `file:line:col: error: message`,
/// the source line and a caret (unless NoSourceLine).
void printDiagnostics(const llvm::SourceMgr &SM,
                      llvm::ArrayRef<Diagnostic> Diags, llvm::raw_ostream &OS,
                      bool ShowColors = false);

/// An error in bsc itself, not in what it was given (an llvm::Error from
/// LLVM or the JIT where bsc's own code should have made none): `bsc:
/// error: internal error: ...` on stderr, the one place that words it.
void reportInternalError(llvm::Error E);

} // namespace bsc

#endif

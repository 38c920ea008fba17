//===- Diagnostic.cpp - the diagnostics table and its engine --------------===//
#include "bsc/Basic/Diagnostic.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"
#include <algorithm>

using namespace bsc;

namespace {
struct KindInfo {
  Severity Sev;
  const char *Format;
  const char *Id;
};
const KindInfo KindTable[] = {
#define DIAG(Id, Sev, Format) {Severity::Sev, Format, #Id},
#include "bsc/Basic/DiagnosticKinds.def"
};
/// The warnings `-Wno-<Name>` silences.
const struct {
  const char *Name;
  diag::Kind Kind;
} WarningGroups[] = {
    {"yield-loop", diag::warn_yield_loop},
    {"yield-loop", diag::warn_endless_loop_in_func},
    {"unreachable-code", diag::warn_unreachable_code},
    {"double-yield", diag::warn_double_yield},
    {"skipped-yield", diag::warn_loop_skips_yield},
    {"duplicate-require", diag::warn_duplicate_require},
};
} // namespace

/// Sets the flag of every warning kind of `Group`; false if there is none.
static bool markWarningGroup(llvm::StringRef Group,
                             bool (&Flags)[diag::NumKinds]) {
  bool Found = false;
  for (const auto &G : WarningGroups)
    if (Group == G.Name) {
      Flags[G.Kind] = true;
      Found = true;
    }
  return Found;
}

bool DiagnosticEngine::ignoreWarningGroup(llvm::StringRef Group) {
  return markWarningGroup(Group, Ignored);
}

bool DiagnosticEngine::promoteWarningGroup(llvm::StringRef Group) {
  return markWarningGroup(Group, Promoted);
}

std::string DiagnosticEngine::getWarningGroupList() {
  std::string List;
  for (const auto &G : WarningGroups) {
    std::string Quoted = "'" + std::string(G.Name) + "'";
    if (List.find(Quoted) != std::string::npos)
      continue;
    List += List.empty() ? Quoted : ", " + Quoted;
  }
  return List;
}

Severity bsc::getSeverity(diag::Kind K) { return KindTable[K].Sev; }
llvm::StringRef bsc::getFormat(diag::Kind K) { return KindTable[K].Format; }
llvm::StringRef bsc::getIdName(diag::Kind K) { return KindTable[K].Id; }

DiagnosticBuilder::~DiagnosticBuilder() {
  if (!Engine)
    return;
  Engine->record(Kind, Loc, DiagnosticEngine::format(getFormat(Kind), Args),
                 Ranges, FixIts, ShowSourceLine);
}

std::string DiagnosticEngine::format(llvm::StringRef Format,
                                     llvm::ArrayRef<std::string> Args) {
  std::string Out;
  for (size_t I = 0, E = Format.size(); I != E; ++I) {
    char C = Format[I];
    if (C == '%' && I + 1 != E && Format[I + 1] >= '0' && Format[I + 1] <= '9') {
      unsigned N = Format[++I] - '0';
      if (N < Args.size())
        Out += Args[N];
      continue;
    }
    Out += C;
  }
  return Out;
}

void DiagnosticEngine::record(diag::Kind K, llvm::SMLoc Loc,
                              std::string Message,
                              llvm::ArrayRef<llvm::SMRange> Ranges,
                              llvm::ArrayRef<llvm::SMFixIt> FixIts,
                              bool ShowSourceLine) {
  Severity Sev = getSeverity(K);
  // -Werror: an error like any other, which says why (as clang does).
  if (Sev == Severity::Warning && !Ignored[K] &&
      (AllWarningsAreErrors || Promoted[K])) {
    Sev = Severity::Error;
    Message += " [-Werror]";
  }
  switch (Sev) {
  case Severity::Error:
    if (NumErrors >= MaxErrors) {
      DroppingNotes = true;
      return;
    }
    ++NumErrors;
    break;
  case Severity::Warning:
    if (tooManyErrors() || Ignored[K]) {
      DroppingNotes = true;
      return;
    }
    ++NumWarnings;
    break;
  case Severity::Note:
    // A note belongs to the diagnostic before it.
    if (DroppingNotes)
      return;
    break;
  }
  if (Sev != Severity::Note)
    DroppingNotes = false;
  Diags.push_back(Diagnostic{K, Sev, Loc, std::move(Message),
                             llvm::SmallVector<llvm::SMRange, 1>(Ranges),
                             llvm::SmallVector<llvm::SMFixIt, 1>(FixIts),
                             ShowSourceLine});
}

void DiagnosticEngine::sortBySource(const llvm::SourceMgr &SM) {
  struct Group {
    std::pair<unsigned, const char *> Key;
    size_t Begin, End; ///< Into Diags: the diagnostic and its notes.
  };
  std::vector<Group> Groups;
  for (size_t I = 0; I < Diags.size(); ++I) {
    if (Diags[I].Sev == Severity::Note && !Groups.empty()) {
      Groups.back().End = I + 1;
      continue;
    }
    llvm::SMLoc Loc = Diags[I].Loc;
    unsigned Buffer = Loc.isValid() ? SM.FindBufferContainingLoc(Loc) : 0;
    Groups.push_back({{Buffer, Buffer ? Loc.getPointer() : nullptr}, I, I + 1});
  }
  std::stable_sort(Groups.begin(), Groups.end(),
                   [](const Group &A, const Group &B) { return A.Key < B.Key; });
  std::vector<Diagnostic> Sorted;
  Sorted.reserve(Diags.size());
  for (const Group &G : Groups)
    for (size_t I = G.Begin; I < G.End; ++I)
      Sorted.push_back(std::move(Diags[I]));
  Diags = std::move(Sorted);
}

void DiagnosticEngine::clear() {
  Diags.clear();
  NumErrors = NumWarnings = 0;
  DroppingNotes = false;
}

static llvm::SourceMgr::DiagKind toLLVM(Severity S) {
  switch (S) {
  case Severity::Error:
    return llvm::SourceMgr::DK_Error;
  case Severity::Warning:
    return llvm::SourceMgr::DK_Warning;
  case Severity::Note:
    return llvm::SourceMgr::DK_Note;
  }
  llvm_unreachable("unknown severity");
}

/// `file:line:col: error: message` and nothing more: SMDiagnostic prints
/// no source line when it has no line and column of its own, so the place
/// goes into its file name.
static void printWithoutSourceLine(const llvm::SourceMgr &SM,
                                   const Diagnostic &D, llvm::raw_ostream &OS,
                                   bool ShowColors) {
  std::string Where;
  if (unsigned Buffer = SM.FindBufferContainingLoc(D.Loc)) {
    auto [Line, Col] = SM.getLineAndColumn(D.Loc, Buffer);
    Where = (SM.getMemoryBuffer(Buffer)->getBufferIdentifier() + ":" +
             llvm::Twine(Line) + ":" + llvm::Twine(Col))
                .str();
  }
  llvm::SMDiagnostic(Where, toLLVM(D.Sev), D.Message)
      .print(Where.empty() ? "bsc" : nullptr, OS, ShowColors);
}

void bsc::printDiagnostics(const llvm::SourceMgr &SM,
                           llvm::ArrayRef<Diagnostic> Diags,
                           llvm::raw_ostream &OS, bool ShowColors) {
  unsigned Errors = 0;
  for (const Diagnostic &D : Diags) {
    if (D.Sev == Severity::Error)
      ++Errors;
    // Locationless diagnostics (options, missing files) print as
    // `bsc: error: ...`; SourceMgr does that for an invalid SMLoc.
    if (D.Loc.isValid() && !D.ShowSourceLine)
      printWithoutSourceLine(SM, D, OS, ShowColors);
    else if (D.Loc.isValid())
      SM.PrintMessage(OS, D.Loc, toLLVM(D.Sev), D.Message, D.Ranges,
                      D.FixIts, ShowColors);
    else
      llvm::SMDiagnostic("", toLLVM(D.Sev), D.Message)
          .print("bsc", OS, ShowColors);
  }
  if (Errors >= DiagnosticEngine::MaxErrors)
    OS << "bsc: fatal: too many errors emitted, stopping now\n";
}

void bsc::reportInternalError(llvm::Error E) {
  llvm::WithColor::error(llvm::errs(), "bsc")
      << "internal error: " << llvm::toString(std::move(E)) << "\n";
}

//===- Shrink.cpp - `bsc replay --shrink`: the shortest log that still fails -===//
//
// A failing recording of thousands of cycles becomes one of a few that
// fails the same way, for a bug report or a regression test: its cycles
// cut after the failure, then a window of the cycles before it started
// afresh (the shortest that still fails so; a behavior starts from its
// first cycle, since a recording holds no task state to start from), then
// input changes undone, delta-debugging style: chunks of the cycles whose
// input changed get the input of the cycle before, halving the chunks,
// while the log still fails the same way. "The same way": the replay's
// first failure is at the log's last cycle with the same output members
// differing. Every candidate is replayed as `bsc replay` would.
//
// A log that replays exactly (it is of this behavior, with its calls into
// C++) is shrunk exactly: each candidate keeps the header and its cycles'
// calls, so a random number or a sensor read by C++ is what the robot
// got, and a window whose calls part from the log's (the tasks started
// afresh call otherwise) is no candidate. A log replayed in regression
// mode is shrunk so, without header and calls. A binary log is shrunk as
// the JSON-lines recording it converts to, header and calls and all.
//
//===----------------------------------------------------------------------===//
#include "ReplayLog.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Basic/Output.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"

using namespace bsc;

namespace {
/// The members a failure names (`output.motion`), without the values.
std::vector<std::string> failedMembers(const ReplayFailure &F) {
  std::vector<std::string> Members;
  for (const std::string &D : F.Differences)
    Members.push_back(llvm::StringRef(D).split(": recorded").first.str());
  return Members;
}

class Shrinker {
public:
  Shrinker(Compilation &C, LoadedBehavior &L, const ReplayLogsOptions &Opts,
           std::string Temp)
      : C(C), L(L), Opts(Opts), Temp(std::move(Temp)) {}

  /// Reads the log at `Path` (named `Name` in messages: a binary log's
  /// conversion is read) and replays it; false after reporting (also if
  /// it does not fail on an output).
  llvm::Expected<bool> start(llvm::StringRef Path, llvm::StringRef Name);
  /// Shrinks it; Start, End and Keep say what is left.
  llvm::Expected<bool> shrink();
  /// Writes the shrunk log; false after reporting.
  bool write(llvm::StringRef Path);

  ReplayFailure Original;
  size_t Start = 0, End = 0; ///< The window of cycles, [Start, End).

private:
  /// Replays the window with the input changes `Keep` says; true if it
  /// fails as the log did.
  llvm::Expected<bool> failsAlike(size_t From, const std::vector<bool> &Keep);
  std::string render(size_t From, const std::vector<bool> &Keep) const;

  Compilation &C;
  LoadedBehavior &L;
  const ReplayLogsOptions &Opts;
  std::string Temp;
  std::vector<llvm::json::Value> Cycles; ///< Each cycle's line.
  std::vector<bool> Keep; ///< Per cycle: its input change stays.
  /// The log replays exactly: candidates keep its header and calls.
  bool Exact = false;
  std::optional<llvm::json::Value> Header;
};
} // namespace

llvm::Expected<bool> Shrinker::start(llvm::StringRef Path,
                                     llvm::StringRef Name) {
  RunOptions Run;
  Run.Failed = &Original;
  Run.ReplayedExactly = &Exact;
  uint32_t Count = 0;
  llvm::Expected<bool> Passed = replayLog(C, L, Opts, Path.str(), Run, Count);
  if (!Passed)
    return Passed.takeError();
  if (*Passed || !Original.Cycle) {
    // Its own diagnostics say what else went wrong; a log that could not
    // be read at all needs no more.
    if (!*Passed && Count == 0)
      return false;
    printDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs());
    C.Diags.clear();
    C.Diags.report(llvm::SMLoc(), diag::err_shrink_passes)
        << Name << (*Passed ? "replays as recorded" : "fails otherwise");
    return false;
  }
  C.Diags.clear();
  auto Buffer = llvm::MemoryBuffer::getFile(Path);
  if (!Buffer) { // It was read a moment ago.
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Path << Buffer.getError().message();
    return false;
  }
  for (llvm::StringRef Rest = (*Buffer)->getBuffer(); !Rest.empty();) {
    auto [Line, After] = Rest.split('\n');
    Rest = After;
    if (Line.trim().empty())
      continue;
    llvm::Expected<llvm::json::Value> V = llvm::json::parse(Line);
    if (!V)
      return V.takeError(); // The replay took it.
    const llvm::json::Object *O = V->getAsObject();
    if (O && O->get("recording")) {
      Header = std::move(*V);
      continue;
    }
    if (O && O->get("robot")) {
      C.Diags.report(llvm::SMLoc(), diag::err_shrink_team) << Name;
      return false;
    }
    Cycles.push_back(std::move(*V));
    if (Cycles.size() == Original.Cycle)
      break; // What comes after the failure is cut.
  }
  End = Cycles.size();
  Keep.assign(Cycles.size(), true);
  return true;
}

std::string Shrinker::render(size_t From, const std::vector<bool> &Keep) const {
  // Replayed exactly, the log's header and calls stay: the candidate
  // replays exactly too, and parts from its calls where the tasks started
  // afresh call otherwise. Else neither: it replays in regression mode.
  std::string Text;
  if (Exact && Header)
    Text += debug::toJSONString(*Header) + "\n";
  // Each cycle's input: its own if its change stays, else the one before's.
  const llvm::json::Value *Input = nullptr;
  for (size_t I = From; I < End; ++I) {
    llvm::json::Object Line = *Cycles[I].getAsObject();
    const llvm::json::Value *Own = Cycles[I].getAsObject()->get("input");
    if (I == From || Keep[I] || !Input)
      Input = Own;
    if (Input)
      Line["input"] = *Input;
    Line["cycle"] = int64_t(I - From + 1);
    if (!Exact)
      Line.erase("calls");
    Text += debug::toJSONString(llvm::json::Value(std::move(Line))) + "\n";
  }
  return Text;
}

llvm::Expected<bool> Shrinker::failsAlike(size_t From,
                                          const std::vector<bool> &Keep) {
  {
    std::error_code EC;
    llvm::raw_fd_ostream OS(Temp, EC);
    if (EC) // It was written before (shrinkLog).
      return llvm::errorCodeToError(EC);
    OS << render(From, Keep);
  }
  ReplayFailure Failure;
  RunOptions Run;
  Run.Failed = &Failure;
  uint32_t Count = 0;
  LogSources Sources(C.SM);
  llvm::Expected<bool> Passed = replayLog(C, L, Opts, Temp, Run, Count);
  C.Diags.clear();
  if (!Passed)
    return Passed.takeError();
  return !*Passed && Failure.Cycle == End - From &&
         failedMembers(Failure) == failedMembers(Original);
}

llvm::Expected<bool> Shrinker::shrink() {
  // The shortest window before the failure that fails alike: doubled until
  // one does, then halved back between the last that did not and it.
  size_t Fails = End - Start, Short = 0;
  for (size_t Len = 1; Len < End - Start; Len *= 2) {
    llvm::Expected<bool> F = failsAlike(End - Len, Keep);
    if (!F)
      return F.takeError();
    if (*F) {
      Fails = Len;
      break;
    }
    Short = Len;
  }
  while (Fails - Short > 1) {
    size_t Mid = Short + (Fails - Short) / 2;
    llvm::Expected<bool> F = failsAlike(End - Mid, Keep);
    if (!F)
      return F.takeError();
    (*F ? Fails : Short) = Mid;
  }
  Start = End - Fails;
  // The input changes, in chunks of halving size.
  std::vector<size_t> Changes; // Cycles whose input differs from the one before.
  for (size_t I = Start + 1; I < End; ++I) {
    const llvm::json::Value *A = Cycles[I - 1].getAsObject()->get("input");
    const llvm::json::Value *B = Cycles[I].getAsObject()->get("input");
    if (A && B && !(*A == *B))
      Changes.push_back(I);
  }
  for (size_t Chunk = std::max<size_t>(Changes.size() / 2, 1); Chunk >= 1;
       Chunk /= 2) {
    for (size_t At = 0; At < Changes.size(); At += Chunk) {
      std::vector<bool> Try = Keep;
      bool Any = false;
      for (size_t K = At; K < std::min(At + Chunk, Changes.size()); ++K) {
        Any |= Try[Changes[K]];
        Try[Changes[K]] = false;
      }
      if (!Any)
        continue;
      llvm::Expected<bool> F = failsAlike(Start, Try);
      if (!F)
        return F.takeError();
      if (*F)
        Keep = std::move(Try);
    }
    if (Chunk == 1)
      break;
  }
  return true;
}

bool Shrinker::write(llvm::StringRef Path) {
  std::unique_ptr<llvm::ToolOutputFile> Out =
      openOutput(C.Diags, Path, /*Text=*/true);
  if (!Out)
    return false;
  Out->os() << render(Start, Keep);
  return keepOutput(C.Diags, *Out, Path);
}

llvm::Expected<int> bsc::shrinkLog(Compilation &C, LoadedBehavior &L,
                                   const ReplayLogsOptions &Opts,
                                   llvm::StringRef Log, llvm::StringRef Out,
                                   llvm::raw_ostream &OS) {
  llvm::SmallString<128> Temp = llvm::sys::path::parent_path(Out);
  llvm::sys::path::append(Temp, "." + llvm::sys::path::filename(Out) +
                                    ".candidate.jsonl");
  {
    // Candidates are written there: a folder that takes no file is the
    // user's to fix.
    std::error_code EC;
    llvm::raw_fd_ostream Probe(Temp, EC);
    if (EC) {
      C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
          << Temp << EC.message();
      return 1;
    }
  }
  // A binary log is read as the recording it converts to, beside the
  // candidates.
  std::string Source = Log.str();
  if (isBinaryLogPath(Log)) {
    Source = (Temp + ".source.jsonl").str();
    auto Session = startSession(C, L);
    if (!Session)
      return Session.takeError();
    if (!*Session || !convertRecording(C, L, **Session, Log, Source)) {
      llvm::sys::fs::remove(Temp);
      llvm::sys::fs::remove(Source);
      return 1;
    }
  }
  auto RemoveTemporaries = [&] {
    llvm::sys::fs::remove(Temp);
    if (Source != Log)
      llvm::sys::fs::remove(Source);
  };
  Shrinker S(C, L, Opts, Temp.str().str());
  llvm::Expected<bool> Started = S.start(Source, Log);
  if (!Started || !*Started)
    RemoveTemporaries();
  if (!Started || !*Started)
    return Started ? llvm::Expected<int>(1) : Started.takeError();
  size_t Before = S.End;
  llvm::Expected<bool> Shrunk = S.shrink();
  RemoveTemporaries();
  if (!Shrunk)
    return Shrunk.takeError();
  if (!S.write(Out))
    return 1;
  uint64_t From = 0, To = 0;
  llvm::sys::fs::file_size(Log, From);
  llvm::sys::fs::file_size(Out, To);
  OS << "shrunk " << Log << " (" << Before << " cycles to its failure, "
     << From << " bytes) to " << Out << " (" << S.End - S.Start
     << (S.End - S.Start == 1 ? " cycle, " : " cycles, ") << To
     << " bytes): it fails at its last cycle as the log did at cycle "
     << S.Original.Cycle << ":\n";
  for (const std::string &D : S.Original.Differences)
    OS << "  " << D << "\n";
  return 0;
}

//===- ReadRun.cpp - recordings and robot logs as runs --------------------===//
//
// A recording is read as `--replay` reads one: in the SourceMgr, so that
// every error is at its line with a caret; a line is checked, handed to the
// RunBuilder and dropped. A robot's trace log is decoded with the object's
// tables as `bsc trace-decode` decodes it.
//
//===----------------------------------------------------------------------===//
#include "TimelineImpl.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Debug/TraceDecode.h"
#include "bsc/Frontend/Frontend.h"
#include "llvm/ADT/StringMap.h"
#include "llvm/Support/FileSystem.h"

using namespace bsc;
using namespace bsc::timeline;

/// A robot's log starts with a little-endian cycle number, so it has a NUL
/// byte within its first bytes (cycle numbers below 2^24); a recording is
/// text that starts with `{`. Text of blank lines is a recording without
/// cycles, which is what it is reported as: not a damaged log.
static bool looksLikeRecording(llvm::StringRef Text) {
  llvm::StringRef Head = Text.take_front(4096);
  llvm::StringRef Start = Head.ltrim();
  return (Start.empty() || Start.starts_with("{")) && !Head.contains('\0');
}

/// A key of `O` that is none of `Known`. Looked up rather than iterated
/// when all are known: walking a json::Object visits all its buckets (64
/// at least), which is most of the time of reading a line's tasks.
static std::optional<llvm::StringRef>
findUnknownKey(const llvm::json::Object &O,
               std::initializer_list<llvm::StringRef> Known) {
  size_t Present = llvm::count_if(
      Known, [&](llvm::StringRef K) { return O.find(K) != O.end(); });
  if (Present == O.size())
    return std::nullopt;
  for (const auto &KV : O)
    if (!llvm::is_contained(Known, llvm::StringRef(KV.first)))
      return llvm::StringRef(KV.first);
  return std::nullopt;
}

namespace {
/// Checks one parsed line and turns it into a cycle for the builder.
class LineReader {
public:
  LineReader(Compilation &C, llvm::SMLoc Loc) : C(C), Loc(Loc) {}

  /// Reports what is wrong with the line and returns false. `Robot`: the
  /// line's `robot` (`--robots N --record FILE` writes every robot's lines
  /// into one file).
  bool read(const llvm::json::Value &Line, uint32_t &Cycle,
            std::optional<unsigned> &Robot, std::vector<CycleTask> &Tasks) {
    const llvm::json::Object *O = Line.getAsObject();
    if (!O) {
      C.Diags.report(Loc, diag::err_record_not_object);
      return false;
    }
    if (std::optional<llvm::StringRef> Key = findUnknownKey(
            *O, {"cycle", "input", "output", "tasks", "calls", "robot"})) {
      C.Diags.report(Loc, diag::err_record_unknown_key) << *Key;
      return false;
    }
    const llvm::json::Value *CycleValue = O->get("cycle");
    if (!CycleValue) {
      C.Diags.report(Loc, diag::err_record_no_cycle);
      return false;
    }
    std::optional<int64_t> N = CycleValue->getAsInteger();
    if (!N || *N < 1 || *N > int64_t(UINT32_MAX)) {
      C.Diags.report(Loc, diag::err_record_bad_cycle);
      return false;
    }
    Cycle = *N;
    if (const llvm::json::Value *R = O->get("robot")) {
      std::optional<int64_t> K = R->getAsInteger();
      if (!K || *K < 0 || *K >= MaxRobots)
        return bad("robot", "a robot's number, from 0 to " +
                                std::to_string(MaxRobots - 1));
      Robot = unsigned(*K);
    }
    for (llvm::StringRef Key : {"input", "output"})
      if (const llvm::json::Value *V = O->get(Key); V && !V->getAsObject())
        return bad(Key, "an object");
    const llvm::json::Value *TaskList = O->get("tasks");
    if (!TaskList) {
      C.Diags.report(Loc, diag::err_record_no_tasks);
      return false;
    }
    const llvm::json::Array *A = TaskList->getAsArray();
    if (!A)
      return bad("tasks", "an array");
    for (size_t I = 0; I < A->size(); ++I)
      if (!readTask((*A)[I], I, Tasks))
        return false;
    return true;
  }

private:
  bool bad(llvm::StringRef What, llvm::StringRef Must) {
    C.Diags.report(Loc, diag::err_record_bad_member) << What << Must;
    return false;
  }

  bool readTask(const llvm::json::Value &V, size_t I,
                std::vector<CycleTask> &Tasks) {
    std::string Name = "tasks[" + std::to_string(I) + "]";
    const llvm::json::Object *O = V.getAsObject();
    if (!O)
      return bad(Name, "an object with 'task', 'state' and 'parent'");
    if (std::optional<llvm::StringRef> Key = findUnknownKey(
            *O, {"task", "state", "at", "parent", "params", "locals"})) {
      C.Diags.report(Loc, diag::err_record_task_unknown_key) << *Key << Name;
      return false;
    }
    CycleTask T;
    std::optional<llvm::StringRef> Task = O->getString("task");
    if (!Task || Task->empty())
      return bad(Name + ".task", "the task's name");
    T.Name = *Task;
    std::optional<llvm::StringRef> State = O->getString("state");
    if (!State || State->empty())
      return bad(Name + ".state", "the task's state, as 'running'");
    T.State = *State;
    if (const llvm::json::Value *At = O->get("at")) {
      if (!At->getAsString())
        return bad(Name + ".at", "the yield it waits at, as \"Kick.bs:10\"");
      T.Place = *At->getAsString();
    }
    std::optional<int64_t> Parent = O->getInteger("parent");
    if (!Parent || *Parent < -1 || *Parent >= int64_t(I))
      return bad(Name + ".parent",
                 "-1 (a root) or the position of an earlier task");
    T.Parent = *Parent;
    for (const auto &[Key, Into] :
         {std::pair{"params", &T.Params}, std::pair{"locals", &T.Locals}})
      if (const llvm::json::Value *F = O->get(Key)) {
        if (!F->getAsObject())
          return bad(Name + "." + Key, "an object");
        *Into = F->getAsObject();
      }
    // A set, not a search of the earlier tasks: a line of a megabyte can
    // list tens of thousands.
    auto [Earlier, New] = Positions.try_emplace(T.Name, I);
    if (!New) {
      C.Diags.report(Loc, diag::err_record_task_twice)
          << "tasks[" + std::to_string(Earlier->second) + "]" << Name
          << T.Name;
      return false;
    }
    Tasks.push_back(T);
    return true;
  }

  Compilation &C;
  llvm::SMLoc Loc;
  /// The line's tasks so far, by name: their positions.
  llvm::StringMap<size_t> Positions;
};
} // namespace

namespace {
/// The runs of one file as its cycles come: one, or one per robot of a
/// team's file.
class FileRuns {
public:
  FileRuns(llvm::StringRef Name, bool Team) : Name(Name), Team(Team) {}
  bool isTeam() const { return Team; }
  /// Robot K's builder (0 for one robot's file), added with the robots
  /// before it if new.
  RunBuilder &robot(unsigned K) {
    while (Runs.size() <= K) {
      Runs.push_back(std::make_unique<Run>());
      Runs.back()->Name = Name;
      Runs.back()->Robot = Team ? int(Runs.size() - 1) : -1;
      Builders.push_back(std::make_unique<RunBuilder>(*Runs.back()));
    }
    return *Builders[K];
  }
  /// Finishes the runs into `Out`; false after reporting a file without
  /// cycles, or a robot without any below one with some.
  bool finish(Compilation &C, std::vector<Run> &Out) {
    if (Runs.empty() || (!Team && Runs[0]->Cycles.empty())) {
      C.Diags.report(llvm::SMLoc(), diag::err_record_empty) << Name;
      return false;
    }
    for (size_t K = 0; K < Runs.size(); ++K)
      if (Runs[K]->Cycles.empty()) {
        C.Diags.report(llvm::SMLoc(), diag::err_record_team_gap)
            << Name << Runs.size() - 1 << K;
        return false;
      }
    for (size_t K = 0; K < Runs.size(); ++K) {
      Builders[K]->finish();
      Out.push_back(std::move(*Runs[K]));
    }
    return true;
  }

private:
  std::string Name;
  bool Team;
  std::vector<std::unique_ptr<Run>> Runs;
  std::vector<std::unique_ptr<RunBuilder>> Builders;
};
} // namespace

bool timeline::isRecording(llvm::StringRef Path) {
  // Only the bytes that are there: a slice past the end of the file is
  // filled with NULs, which made every recording shorter than the slice a
  // log.
  uint64_t Size = 0;
  if (llvm::sys::fs::file_size(Path, Size))
    return false;
  auto Head = llvm::MemoryBuffer::getFileSlice(
      Path, std::min<uint64_t>(Size, 4096), 0);
  return Head && looksLikeRecording((*Head)->getBuffer());
}

bool timeline::readRecording(Compilation &C, llvm::StringRef Path,
                             std::vector<Run> &Runs) {
  // addSourceFile's message for a directory speaks of b-script files.
  if (llvm::sys::fs::is_directory(Path)) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << Path << std::make_error_code(std::errc::is_a_directory).message();
    return false;
  }
  unsigned ID = addSourceFile(C, Path, MaxRecordingMiB);
  return ID && readRecordingBuffer(C, ID, Path, Runs);
}

bool timeline::readRecordingBuffer(Compilation &C, unsigned BufferID,
                                   llvm::StringRef Name,
                                   std::vector<Run> &Runs) {
  llvm::StringRef Text = C.SM.getMemoryBuffer(BufferID)->getBuffer();
  if (!looksLikeRecording(Text)) {
    C.Diags.report(llvm::SMLoc(), diag::err_timeline_not_recording) << Name;
    return false;
  }
  std::optional<FileRuns> File;
  std::vector<std::optional<uint32_t>> Previous; // Per robot.
  while (!Text.empty()) {
    auto [Raw, Rest] = Text.split('\n');
    Text = Rest;
    if (Raw.trim().empty())
      continue;
    llvm::SMLoc Loc = llvm::SMLoc::getFromPointer(Raw.data());
    std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, Raw);
    if (!V)
      return false;
    // The header names the behavior (docs/repl.md "Recordings"); the page
    // draws what the cycles recorded, calls into C++ included.
    if (const llvm::json::Object *O = V->getAsObject();
        O && !File && O->size() == 1 && O->get("recording"))
      continue;
    uint32_t Cycle = 0;
    std::optional<unsigned> Robot;
    std::vector<CycleTask> Tasks;
    if (!LineReader(C, Loc).read(*V, Cycle, Robot, Tasks))
      return false;
    // The first line says whether the file is a team's: then every line
    // names its robot.
    if (!File)
      File.emplace(Name, Robot.has_value());
    if (Robot.has_value() != File->isTeam()) {
      C.Diags.report(Loc, diag::err_record_team_mixed)
          << (Robot ? "this line names its robot, but the first line does "
                      "not"
                    : "this line does not name its robot, but the first "
                      "line does");
      return false;
    }
    unsigned K = Robot.value_or(0);
    if (Previous.size() <= K)
      Previous.resize(K + 1);
    if (Previous[K] && Cycle <= *Previous[K]) {
      C.Diags.report(Loc, diag::err_record_cycle_order) << Cycle << *Previous[K];
      return false;
    }
    Previous[K] = Cycle;
    const llvm::json::Object *O = V->getAsObject();
    File->robot(K).addCycle(Cycle, O->get("input"), O->get("output"), Tasks);
  }
  if (!File) {
    C.Diags.report(llvm::SMLoc(), diag::err_record_empty) << Name;
    return false;
  }
  return File->finish(C, Runs);
}

bool timeline::readReplayedLog(Compilation &C, const TimelineOptions &Opts,
                               llvm::StringRef Path, std::vector<Run> &Runs) {
  if (!Opts.ReplayLog) {
    C.Diags.report(llvm::SMLoc(), diag::err_timeline_log_needs_behavior)
        << Path;
    return false;
  }
  // A log's header says how many robots it has: the replay hands robot
  // K's cycles to the K-th sink, and names the count first.
  std::optional<FileRuns> File;
  auto SinkFor = [&](unsigned Robot, unsigned Robots) -> CycleSink & {
    if (!File)
      File.emplace(Path, Robots > 1);
    return File->robot(Robot);
  };
  if (!Opts.ReplayLog(Path, SinkFor))
    return false;
  if (!File) {
    C.Diags.report(llvm::SMLoc(), diag::err_record_empty) << Path;
    return false;
  }
  return File->finish(C, Runs);
}

bool timeline::readRobotLog(Compilation &C, const debug::DebugTables &Tables,
                            llvm::StringRef LogPath, std::vector<Run> &Runs) {
  std::optional<std::vector<debug::LoggedCycle>> Cycles =
      debug::readTraceLog(LogPath, Tables, C.Diags);
  if (!Cycles)
    return false;
  if (Cycles->empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_record_empty) << LogPath;
    return false;
  }
  Run R;
  R.Name = LogPath.str();
  R.FromRobotLog = true;
  RunBuilder Builder(R);
  std::optional<uint32_t> Previous;
  for (const debug::LoggedCycle &Logged : *Cycles) {
    if (Previous && Logged.Cycle <= *Previous) {
      C.Diags.report(llvm::SMLoc(), diag::err_trace_decode)
          << LogPath
          << ("cycle " + std::to_string(Logged.Cycle) + " after cycle " +
              std::to_string(*Previous) +
              ": a log's cycles increase (were two runs written to one "
              "file?)");
      return false;
    }
    std::vector<debug::RecordedTask> Listed =
        debug::listActiveTasks(Tables, Logged.Records);
    std::vector<CycleTask> Tasks;
    for (const debug::RecordedTask &F : Listed)
      Tasks.push_back(
          {Tables.Tasks[F.Record.Task].Name, F.State, F.Place, F.Parent});
    Builder.addCycle(Logged.Cycle, nullptr, nullptr, Tasks);
    Previous = Logged.Cycle;
  }
  Builder.finish();
  Runs.push_back(std::move(R));
  return true;
}

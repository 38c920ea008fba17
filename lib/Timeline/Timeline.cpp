//===- Timeline.cpp - bsc timeline: read the runs, compare, write ---------===//
#include "bsc/Timeline/Timeline.h"
#include "TimelineImpl.h"
#include "bsc/Basic/ByteCoding.h"
#include "bsc/Basic/Output.h"
#include "bsc/Debug/TraceDecode.h"
#include "bsc/Frontend/Frontend.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/ToolOutputFile.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;
using namespace bsc::timeline;

/// `run.jsonl` -> `run.html`, beside it.
static std::string defaultOutput(llvm::StringRef Record) {
  llvm::SmallString<128> Path(Record);
  llvm::sys::path::replace_extension(Path, "html");
  return std::string(Path);
}

bool timeline::writeTimeline(Compilation &C, const TimelineOptions &Opts,
                             llvm::raw_ostream &OS) {
  if (Opts.Records.empty() || Opts.Records.size() > 2) {
    C.Diags.report(llvm::SMLoc(), diag::err_timeline_records)
        << static_cast<long long>(Opts.Records.size());
    return false;
  }
  // With --object, each record is a robot's log or a recording, so that
  // the robot's run compares with the JIT's.
  std::optional<debug::DebugTables> Tables;
  if (!Opts.ObjectPath.empty()) {
    Tables = debug::readObjectTables(Opts.ObjectPath, C.Diags);
    if (!Tables)
      return false;
  }
  // Each file's runs: one, or one per robot of a team's.
  std::vector<std::vector<Run>> Files(Opts.Records.size());
  for (size_t I = 0; I < Files.size(); ++I) {
    llvm::StringRef Path = Opts.Records[I];
    bool Read = isBinaryLogFile(Path) ? readReplayedLog(C, Opts, Path, Files[I])
                : Tables && !isRecording(Path)
                    ? readRobotLog(C, *Tables, Path, Files[I])
                    : readRecording(C, Path, Files[I]);
    if (!Read)
      return false;
    for (Run &R : Files[I])
      R.Record = I;
  }
  std::optional<Difference> Diff;
  if (Files.size() == 2 && !compareFiles(C, Files[0], Files[1], Diff))
    return false;

  std::string Output = Opts.OutputPath.empty()
                           ? defaultOutput(Opts.Records.front())
                           : Opts.OutputPath;
  // `-o run.jsonl`, or a record named `run.html`, would lose the run.
  for (const std::string &Record : Opts.Records)
    if (llvm::sys::fs::equivalent(Output, Record)) {
      C.Diags.report(llvm::SMLoc(), diag::err_timeline_output_is_record)
          << Record;
      return false;
    }
  std::unique_ptr<llvm::ToolOutputFile> Page =
      openOutput(C.Diags, Output, /*Text=*/false);
  if (!Page)
    return false;
  std::vector<const Run *> Drawn;
  for (const std::vector<Run> &File : Files)
    for (const Run &R : File)
      Drawn.push_back(&R);
  writePage(Page->os(), Drawn, Diff);
  if (!keepOutput(C.Diags, *Page, Output))
    return false;

  if (Files.size() == 2) {
    if (!Diff) {
      OS << "the runs do not differ\n";
    } else {
      OS << "first difference at cycle " << Diff->Cycle << ":\n";
      for (const std::string &Note : Diff->Notes)
        OS << "  " << Note << "\n";
    }
  }
  return true;
}

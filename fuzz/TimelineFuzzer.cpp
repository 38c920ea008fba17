//===- TimelineFuzzer.cpp - bytes into bsc timeline's reader and page -----===//
//
// libFuzzer target (`./dev.sh fuzz timeline`), and the same function run on
// a corpus by the replay driver in the test suite (fuzz/README.md). The
// input is a recording as `bsc timeline` reads one: in a Compilation's
// SourceMgr, through timeline::readRecordingBuffer (lib/Timeline's own
// header: the reader has no public one), into a run.
//
// What must hold, beyond not crashing or hanging: a refused recording is
// exactly one error (the first stops the reader), printed with its line; a
// read one never differs from itself, and the page drawn from it carries
// data that JSON reads (a bare `inf` once made the page's script fail).
// A violation aborts, which both drivers report.
//
//===----------------------------------------------------------------------===//
#include "TimelineImpl.h"
#include "bsc/Basic/Diagnostic.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Frontend/Frontend.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include <cstddef>
#include <cstdint>
#include <cstdlib>

using namespace bsc;

namespace {
/// The page's data: the text of its data element, which the page's script
/// reads with JSON.parse.
llvm::StringRef pageData(llvm::StringRef Page) {
  constexpr llvm::StringLiteral Open =
      "<script id=\"bsc-timeline-data\" type=\"application/json\">";
  size_t Start = Page.find(Open);
  if (Start == llvm::StringRef::npos)
    std::abort();
  llvm::StringRef Data = Page.drop_front(Start + Open.size());
  size_t End = Data.find("</script>");
  if (End == llvm::StringRef::npos)
    std::abort();
  return Data.take_front(End);
}

/// Draws `Runs` and checks that the data reads back.
void checkPage(llvm::ArrayRef<const timeline::Run *> Runs,
               const std::optional<timeline::Difference> &Diff) {
  std::string Page;
  llvm::raw_string_ostream OS(Page);
  timeline::writePage(OS, Runs, Diff);
  OS.flush();
  llvm::Expected<llvm::json::Value> Data = parseJSON(pageData(Page));
  if (!Data) {
    llvm::consumeError(Data.takeError());
    std::abort();
  }
  const llvm::json::Object *O = Data->getAsObject();
  if (!O || O->getInteger("format") != 1)
    std::abort();
}
} // namespace

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size) {
  Compilation C;
  unsigned ID = C.SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(
          llvm::StringRef(reinterpret_cast<const char *>(Data), Size),
          "fuzz.jsonl"),
      llvm::SMLoc());
  std::vector<timeline::Run> Runs;
  if (!timeline::readRecordingBuffer(C, ID, "fuzz.jsonl", Runs)) {
    if (C.Diags.getDiagnostics().size() != 1 || !C.Diags.hasErrors())
      std::abort();
    // Printing it (the line, the caret) is part of the path.
    std::string Text;
    llvm::raw_string_ostream OS(Text);
    printDiagnostics(C.SM, C.Diags.getDiagnostics(), OS);
    return 0;
  }
  if (!C.Diags.getDiagnostics().empty() || Runs.empty())
    std::abort();
  // One run, or a team's: a run per robot, numbered in order.
  std::vector<const timeline::Run *> Drawn;
  for (size_t K = 0; K < Runs.size(); ++K) {
    const timeline::Run &R = Runs[K];
    if (R.Cycles.empty() ||
        R.Robot != (Runs.front().Robot < 0 ? -1 : int(K)))
      std::abort();
    Drawn.push_back(&R);
  }
  // A file never differs from itself.
  std::optional<timeline::Difference> Diff;
  if (!timeline::compareFiles(C, Runs, Runs, Diff) || Diff)
    std::abort();
  checkPage(Drawn, std::nullopt);
  std::vector<timeline::Run> Second = Runs;
  for (timeline::Run &R : Second)
    R.Record = 1;
  for (const timeline::Run &R : Second)
    Drawn.push_back(&R);
  checkPage(Drawn, std::nullopt);
  return 0;
}

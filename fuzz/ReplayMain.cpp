//===- ReplayMain.cpp - run a fuzz target over files, without libFuzzer ---===//
//
// The test suite's half of fuzzing: every file named on the command line
// (or found below a folder named there) is given to the target's
// LLVMFuzzerTestOneInput once. A crash fails the test; so does a run that
// takes longer than the per-input limit of --timeout seconds. Built with
// the project's own compiler, so the suite needs no libFuzzer.
//
//===----------------------------------------------------------------------===//
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/raw_ostream.h"
#include <chrono>
#include <csignal>
#include <cstdint>
#include <cstdlib>
#include <string>
#include <unistd.h>
#include <vector>

extern "C" int LLVMFuzzerTestOneInput(const uint8_t *Data, size_t Size);

namespace {
/// Inputs larger than this are cut, as libFuzzer's -max_len would.
constexpr size_t MaxInputBytes = 1 << 20;
const char *Current = "";

void onAlarm(int) {
  llvm::errs() << "timeout on " << Current << "\n";
  std::_Exit(1);
}
} // namespace

int main(int argc, char **argv) {
  unsigned Timeout = 10;
  std::vector<std::string> Files;
  for (int I = 1; I < argc; ++I) {
    llvm::StringRef Arg = argv[I];
    if (Arg.consume_front("--timeout=")) {
      if (Arg.getAsInteger(10, Timeout)) {
        llvm::errs() << "usage: " << argv[0] << " [--timeout=S] FILE|DIR...\n";
        return 2;
      }
      continue;
    }
    if (!llvm::sys::fs::is_directory(Arg)) {
      Files.push_back(Arg.str());
      continue;
    }
    std::error_code EC;
    for (llvm::sys::fs::recursive_directory_iterator It(Arg, EC), End;
         It != End && !EC; It.increment(EC))
      if (llvm::sys::fs::is_regular_file(It->path()))
        Files.push_back(It->path());
  }
  if (Files.empty()) {
    llvm::errs() << "usage: " << argv[0] << " [--timeout=S] FILE|DIR...\n";
    return 2;
  }
  std::signal(SIGALRM, onAlarm);
  for (const std::string &F : Files) {
    auto Buf = llvm::MemoryBuffer::getFile(F, /*IsText=*/false,
                                           /*RequiresNullTerminator=*/false);
    if (!Buf) {
      llvm::errs() << "cannot read " << F << "\n";
      return 1;
    }
    Current = F.c_str();
    alarm(Timeout);
    llvm::StringRef Bytes = (*Buf)->getBuffer();
    LLVMFuzzerTestOneInput(reinterpret_cast<const uint8_t *>(Bytes.data()),
                           std::min(Bytes.size(), MaxInputBytes));
    alarm(0);
  }
  llvm::outs() << Files.size() << " inputs ran\n";
  return 0;
}

//===- ReplayWorkers.cpp - `bsc replay --jobs N`: one process per core ----===//
//
// Processes rather than threads: the cycle guard (JIT.cpp) catches a
// crash with a signal handler and a process-wide timer, one session at a
// time, and registered C++ may keep globals; a forked worker has all of
// that to itself, and a worker that dies takes only its own log with it.
// The parent compiles before forking and starts no session, and the JIT
// runs no threads of its own (LLJIT without compile threads), so a worker
// starts with a consistent copy of it.
//
//===----------------------------------------------------------------------===//
#include "ReplayWorkers.h"
#include "llvm/Support/Signals.h"
#include "llvm/Support/raw_ostream.h"
#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <optional>
#include <poll.h>
#include <sys/mman.h>
#include <sys/wait.h>
#include <unistd.h>

using namespace bsc;

//===----------------------------------------------------------------------===//
// Records
//===----------------------------------------------------------------------===//
//
// A result is a sequence of fields, each a tag byte, a 32-bit length and
// that many bytes (this machine's byte order: both ends are this process).
// A new member is one more tag (the coverage counters were added so).

namespace {
enum ResultTag : uint8_t {
  TagPassed = 1,
  TagCycles,
  TagSeconds,
  TagReport,
  TagCoverage,
  TagExact,
  TagGroup,
  TagChanged, ///< --update: "1" or "0", then "member\tcycles\n" lines.
  TagFound,
  TagStretches
};
/// What a worker writes into its pipe: a frame kind, the log's index and
/// the payload's length, then the payload (a result, or nothing).
enum FrameKind : uint8_t { FrameStart = 1, FrameResult };
struct FrameHeader {
  uint8_t Kind;
  uint32_t Log;
  uint32_t Length;
};
constexpr size_t FrameHeaderSize = 9;
} // namespace

static void appendField(std::string &Out, ResultTag Tag, const void *Data,
                        uint32_t Size) {
  Out += char(Tag);
  Out.append(reinterpret_cast<const char *>(&Size), 4);
  Out.append(static_cast<const char *>(Data), Size);
}

std::string bsc::encodeResult(const LogResult &R) {
  std::string Out;
  uint8_t Passed = R.Passed;
  appendField(Out, TagPassed, &Passed, 1);
  appendField(Out, TagCycles, &R.Cycles, 4);
  uint8_t Exact = R.Exact;
  appendField(Out, TagExact, &Exact, 1);
  appendField(Out, TagSeconds, &R.Seconds, 8);
  appendField(Out, TagReport, R.Report.data(), R.Report.size());
  appendField(Out, TagGroup, R.Group.data(), R.Group.size());
  std::string Changed = R.Updated ? "1" : "0";
  for (const auto &[Member, Cycles] : R.Changed)
    Changed += Member + "\t" + std::to_string(Cycles) + "\n";
  appendField(Out, TagChanged, Changed.data(), Changed.size());
  appendField(Out, TagFound, R.Found.data(), R.Found.size());
  appendField(Out, TagStretches, &R.Stretches, 4);
  if (!R.Coverage.empty())
    appendField(Out, TagCoverage, R.Coverage.data(), 8 * R.Coverage.size());
  return Out;
}

bool bsc::decodeResult(llvm::StringRef Payload, LogResult &R) {
  R = LogResult();
  while (!Payload.empty()) {
    uint32_t Size;
    if (Payload.size() < 5)
      return false;
    uint8_t Tag = Payload[0];
    std::memcpy(&Size, Payload.data() + 1, 4);
    Payload = Payload.drop_front(5);
    if (Payload.size() < Size)
      return false;
    llvm::StringRef Data = Payload.take_front(Size);
    Payload = Payload.drop_front(Size);
    auto Fixed = [&](void *To, size_t N) {
      if (Size != N)
        return false;
      std::memcpy(To, Data.data(), N);
      return true;
    };
    bool OK = true;
    switch (Tag) {
    case TagPassed: {
      uint8_t P = 0;
      OK = Fixed(&P, 1);
      R.Passed = P;
      break;
    }
    case TagCycles:
      OK = Fixed(&R.Cycles, 4);
      break;
    case TagExact: {
      uint8_t E = 0;
      OK = Fixed(&E, 1);
      R.Exact = E;
      break;
    }
    case TagSeconds:
      OK = Fixed(&R.Seconds, 8);
      break;
    case TagReport:
      R.Report = Data.str();
      break;
    case TagGroup:
      R.Group = Data.str();
      break;
    case TagFound:
      R.Found = Data.str();
      break;
    case TagStretches:
      OK = Fixed(&R.Stretches, 4);
      break;
    case TagChanged: {
      R.Updated = Data.starts_with("1");
      for (llvm::StringRef Rest = Data.drop_front(std::min<size_t>(1, Size));
           !Rest.empty();) {
        auto [Line, After] = Rest.split('\n');
        auto [Member, Count] = Line.split('\t');
        unsigned N = 0;
        OK &= !Count.getAsInteger(10, N);
        R.Changed[Member.str()] = N;
        Rest = After;
      }
      break;
    }
    case TagCoverage:
      OK = Size % 8 == 0;
      R.Coverage.resize(Size / 8);
      if (OK && Size)
        std::memcpy(R.Coverage.data(), Data.data(), Size);
      break;
    default: // A field a newer worker sends: skipped.
      break;
    }
    if (!OK)
      return false;
  }
  return true;
}

//===----------------------------------------------------------------------===//
// Workers
//===----------------------------------------------------------------------===//

static bool writeAll(int Fd, llvm::StringRef Data) {
  while (!Data.empty()) {
    ssize_t N = ::write(Fd, Data.data(), Data.size());
    if (N < 0 && errno == EINTR)
      continue;
    if (N <= 0)
      return false;
    Data = Data.drop_front(N);
  }
  return true;
}

static bool writeFrame(int Fd, FrameKind Kind, size_t Log,
                       llvm::StringRef Payload) {
  char Header[FrameHeaderSize];
  uint32_t Index = Log, Length = Payload.size();
  Header[0] = char(Kind);
  std::memcpy(Header + 1, &Index, 4);
  std::memcpy(Header + 5, &Length, 4);
  return writeAll(Fd, llvm::StringRef(Header, FrameHeaderSize)) &&
         writeAll(Fd, Payload);
}

/// A worker: takes the next log from the shared counter until none is
/// left, announcing each before replaying it (so that the parent knows
/// which log a worker that dies was on). Never returns.
[[noreturn]] static void runWorker(int Fd, std::atomic<uint64_t> &Next,
                                   size_t NumLogs, ReplayOneFn ReplayOne) {
  // A worker that dies is reported by the parent; LLVM's crash handlers
  // (a stack dump asking for a bug report) are for bsc's own bugs.
  llvm::sys::unregisterHandlers();
  int Status = 0;
  for (;;) {
    size_t Log = Next.fetch_add(1);
    if (Log >= NumLogs)
      break;
    if (!writeFrame(Fd, FrameStart, Log, "")) {
      Status = 3; // The parent is gone.
      break;
    }
    llvm::Expected<LogResult> R = ReplayOne(Log);
    if (!R) {
      reportInternalError(R.takeError());
      Status = 70;
      break;
    }
    if (!writeFrame(Fd, FrameResult, Log, encodeResult(*R))) {
      Status = 3;
      break;
    }
  }
  llvm::errs().flush();
  std::fflush(nullptr);
  // No destructors or atexit handlers: they belong to the parent (its JIT,
  // its output files).
  _exit(Status);
}

namespace {
/// The parent's view of one worker.
struct Worker {
  pid_t Pid = -1;
  int Fd = -1;
  std::string Buffer;
  /// The log it announced and has not sent the result of.
  std::optional<size_t> Current;
};

/// Collects the workers' results and hands them on in log order.
class Collector {
public:
  Collector(size_t NumLogs, LogDoneFn Done) : Results(NumLogs), Done(Done) {}

  void add(size_t Log, LogResult R) {
    if (Log >= Results.size() || Results[Log])
      return;
    Results[Log] = std::move(R);
    while (NextToHandOn < Results.size() && Results[NextToHandOn]) {
      Done(NextToHandOn, *Results[NextToHandOn]);
      ++NextToHandOn;
    }
  }
  bool has(size_t Log) const { return Results[Log].has_value(); }
  std::vector<LogResult> take() {
    std::vector<LogResult> Out;
    for (std::optional<LogResult> &R : Results)
      Out.push_back(std::move(*R));
    return Out;
  }

private:
  std::vector<std::optional<LogResult>> Results;
  size_t NextToHandOn = 0;
  LogDoneFn Done;
};
} // namespace

/// Takes the complete frames out of `W`'s buffer. False if one is damaged
/// (the worker is then treated as dead).
static bool takeFrames(Worker &W, Collector &Results) {
  llvm::StringRef Rest = W.Buffer;
  bool OK = true;
  while (Rest.size() >= FrameHeaderSize) {
    FrameHeader H;
    H.Kind = Rest[0];
    std::memcpy(&H.Log, Rest.data() + 1, 4);
    std::memcpy(&H.Length, Rest.data() + 5, 4);
    if (Rest.size() < FrameHeaderSize + H.Length)
      break;
    llvm::StringRef Payload = Rest.substr(FrameHeaderSize, H.Length);
    Rest = Rest.drop_front(FrameHeaderSize + H.Length);
    LogResult R;
    if (H.Kind == FrameStart) {
      W.Current = H.Log;
    } else if (H.Kind == FrameResult && decodeResult(Payload, R)) {
      Results.add(H.Log, std::move(R));
      W.Current.reset();
    } else {
      OK = false;
      break;
    }
  }
  W.Buffer.erase(0, W.Buffer.size() - Rest.size());
  return OK;
}

/// How a worker ended, for a message; empty if it exited normally.
static std::string describeFate(int Status) {
  if (WIFSIGNALED(Status))
    return "was killed by signal " + std::to_string(WTERMSIG(Status)) + " (" +
           strsignal(WTERMSIG(Status)) + ")";
  if (WIFEXITED(Status) && WEXITSTATUS(Status) != 0)
    return "exited with status " + std::to_string(WEXITSTATUS(Status));
  return "";
}

namespace {
/// The workers of one `bsc replay`: started, read from, and replaced when
/// one dies on a log, so that a crashing log costs only itself.
class WorkerPool {
public:
  WorkerPool(size_t NumLogs, std::atomic<uint64_t> &Next, ReplayOneFn ReplayOne,
             llvm::function_ref<LogResult(llvm::StringRef)> Died,
             Collector &Results)
      : NumLogs(NumLogs), Next(Next), ReplayOne(ReplayOne), Died(Died),
        Results(Results) {}

  /// Forks one more worker; false (with Failure set) if it cannot.
  bool start();
  /// Reads from every worker until all have closed their pipes.
  void collect();
  /// How the last worker that ended early ended (empty if none did).
  const std::string &getLastFate() const { return LastFate; }
  std::string Failure;

private:
  /// Reads what `W` sent; at the end of its pipe, reaps it.
  void readFrom(Worker &W);
  void reap(Worker &W);

  size_t NumLogs;
  std::atomic<uint64_t> &Next;
  ReplayOneFn ReplayOne;
  llvm::function_ref<LogResult(llvm::StringRef)> Died;
  Collector &Results;
  std::vector<Worker> Workers;
  std::string LastFate;
};
} // namespace

bool WorkerPool::start() {
  int Pipe[2];
  if (::pipe(Pipe) < 0) {
    Failure = std::strerror(errno);
    return false;
  }
  // What is buffered would be written once by each process.
  llvm::outs().flush();
  llvm::errs().flush();
  std::fflush(nullptr);
  pid_t Pid = ::fork();
  if (Pid < 0) {
    Failure = std::strerror(errno);
    ::close(Pipe[0]);
    ::close(Pipe[1]);
    return false;
  }
  if (Pid == 0) {
    ::close(Pipe[0]);
    for (Worker &W : Workers)
      if (W.Fd >= 0)
        ::close(W.Fd);
    runWorker(Pipe[1], Next, NumLogs, ReplayOne);
  }
  ::close(Pipe[1]);
  Worker W;
  W.Pid = Pid;
  W.Fd = Pipe[0];
  Workers.push_back(std::move(W));
  return true;
}

void WorkerPool::collect() {
  for (;;) {
    std::vector<pollfd> Fds;
    std::vector<size_t> Polled;
    for (size_t I = 0; I < Workers.size(); ++I)
      if (Workers[I].Fd >= 0) {
        Fds.push_back({Workers[I].Fd, POLLIN, 0});
        Polled.push_back(I);
      }
    if (Fds.empty())
      return;
    if (::poll(Fds.data(), Fds.size(), -1) < 0 && errno != EINTR)
      return;
    // By index: reap() may start a worker, which moves the vector.
    for (size_t I = 0; I < Fds.size(); ++I)
      if (Fds[I].revents)
        readFrom(Workers[Polled[I]]);
  }
}

void WorkerPool::readFrom(Worker &W) {
  char Chunk[65536];
  ssize_t N = ::read(W.Fd, Chunk, sizeof Chunk);
  if (N < 0 && errno == EINTR)
    return;
  if (N > 0) {
    W.Buffer.append(Chunk, N);
    if (takeFrames(W, Results))
      return;
    ::kill(W.Pid, SIGKILL); // It sent garbage: no longer trusted.
  }
  reap(W);
}

void WorkerPool::reap(Worker &W) {
  ::close(W.Fd);
  W.Fd = -1;
  int Status = 0;
  while (::waitpid(W.Pid, &Status, 0) < 0 && errno == EINTR)
    ;
  std::string Fate = describeFate(Status);
  std::optional<size_t> Lost = W.Current;
  if (Fate.empty() && Lost)
    Fate = "ended without a result";
  if (!Fate.empty())
    LastFate = Fate;
  if (!Lost)
    return;
  Results.add(*Lost, Died(Fate));
  // A worker that died on a log is replaced: the logs after it still get
  // all the cores. (One that died before taking a log is not, so a worker
  // that cannot start does not make the parent fork for ever.)
  if (Next.load() < NumLogs)
    start();
}

llvm::Expected<std::vector<LogResult>>
bsc::replayInWorkers(size_t NumLogs, unsigned Jobs, ReplayOneFn ReplayOne,
                     llvm::function_ref<LogResult(llvm::StringRef Fate)> Died,
                     LogDoneFn Done) {
  // The counter the workers take logs from, shared across fork().
  void *Shared = ::mmap(nullptr, sizeof(std::atomic<uint64_t>),
                        PROT_READ | PROT_WRITE, MAP_SHARED | MAP_ANONYMOUS,
                        -1, 0);
  if (Shared == MAP_FAILED)
    return llvm::createStringError("cannot map memory for the workers: " +
                                   std::string(std::strerror(errno)));
  auto *Next = new (Shared) std::atomic<uint64_t>(0);
  Collector Results(NumLogs, Done);
  WorkerPool Pool(NumLogs, *Next, ReplayOne, Died, Results);
  unsigned Started = 0;
  while (Started < Jobs && Started < NumLogs && Pool.start())
    ++Started;
  if (!Started && NumLogs) {
    ::munmap(Shared, sizeof(std::atomic<uint64_t>));
    return llvm::createStringError("cannot start a worker: " + Pool.Failure);
  }
  Pool.collect();
  // Workers that ended before taking a log leave logs that ran nowhere.
  std::string Fate = Pool.getLastFate();
  for (size_t Log = 0; Log < NumLogs; ++Log)
    if (!Results.has(Log))
      Results.add(Log, Died(Fate.empty() ? "ended early" : Fate));
  ::munmap(Shared, sizeof(std::atomic<uint64_t>));
  return Results.take();
}

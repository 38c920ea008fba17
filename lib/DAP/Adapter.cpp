//===- Adapter.cpp - `bsc dap`: requests, responses and events -----------===//
//
// One client, one launched behavior. The adapter reads a request, answers
// it, and for the run requests (continue, next, stepIn, stepOut, stepBack,
// reverseContinue) answers first, runs, and then sends `stopped`; while
// cycles run it looks at its input between them for `pause` and keeps any
// other request for after the stop. Frames and variables are numbered
// afresh at each stop (the protocol's handles live until the next resume).
//
// What the session prints goes to the debug console as output events:
// the REPL's answers ("console"), diagnostics ("stderr"), and whatever the
// behavior, its C++ and the world print to standard output ("stdout"),
// which the adapter catches in a file: its own standard output is the
// protocol's channel.
//
//===----------------------------------------------------------------------===//
#include "bsc/DAP/Adapter.h"
#include "bsc/Basic/Transport.h"
#include "bsc/REPL/DebugSession.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include <deque>
#include <fcntl.h>
#include <unistd.h>

using namespace bsc;
using namespace bsc::dap;
namespace json = llvm::json;

namespace {

/// A request's answer: its body, or why it cannot be answered as asked
/// (the error response's message).
using Reply = llvm::Expected<json::Value>;

llvm::Error refuse(const llvm::Twine &Message) {
  return llvm::createStringError(llvm::inconvertibleErrorCode(), Message);
}

/// Standard output redirected into an unlinked file, read back after each
/// request: a pipe would fill (and block the behavior) during a long run.
class CaughtStdout {
public:
  CaughtStdout() {
    char Name[] = "/tmp/bsc-dap-stdout-XXXXXX";
    Fd = mkstemp(Name);
    if (Fd < 0)
      return;
    unlink(Name);
    fflush(stdout);
    dup2(Fd, STDOUT_FILENO);
  }
  ~CaughtStdout() {
    if (Fd >= 0)
      close(Fd);
  }
  /// What was printed since the last call.
  std::string take() {
    fflush(stdout);
    std::string Text;
    char Buf[65536];
    ssize_t N;
    while (Fd >= 0 && (N = pread(Fd, Buf, sizeof Buf, Offset)) > 0) {
      Text.append(Buf, N);
      Offset += N;
    }
    return Text;
  }

private:
  int Fd = -1;
  off_t Offset = 0;
};

/// A variablesReference: a scope of task fields, or a value whose members
/// are its children.
struct VariableNode {
  unsigned Robot = 0;
  std::optional<unsigned> Frame; ///< Fields of Frames[*Frame].
  json::Value Value = nullptr;
  std::string Path; ///< The expression of Value (`input.ball`).
};

class Adapter {
public:
  Adapter(const AdapterOptions &Opts, int InFd, int OutFd)
      : Opts(Opts), T(InFd, OutFd) {}
  int run();

private:
  // Messages.
  void send(json::Object Message);
  void respond(const json::Object &Request, json::Value Body = nullptr);
  void fail(const json::Object &Request, llvm::StringRef Message);
  void event(llvm::StringRef Name, json::Value Body = json::Object{});
  /// The output events of what the session and the behavior printed.
  void flushOutput();
  void stopped(const DebugStop &Stop);
  /// Reads the next message, from those kept during a run first.
  Transport::Read next(json::Value &Message, std::string &Error);

  /// Dispatch: a reply's error becomes an error response.
  void handle(const json::Object &Request);
  llvm::Error dispatch(const json::Object &Request);
  /// Responds with the reply's body, or passes its error on.
  llvm::Error answer(const json::Object &Request, Reply R);
  Reply initialize(const json::Object &Args);
  Reply launch(const json::Object &Args);
  void configurationDone();
  Reply setBreakpoints(const json::Object &Args);
  Reply setFunctionBreakpoints(const json::Object &Args);
  Reply setExceptionBreakpoints(const json::Object &Args);
  Reply threads();
  Reply stackTrace(const json::Object &Args);
  Reply scopes(const json::Object &Args);
  Reply variables(const json::Object &Args);
  Reply setVariable(const json::Object &Args);
  /// Answers itself: a console command that moved in time is followed by
  /// a `stopped` event, one that may have changed values by `invalidated`.
  llvm::Error evaluate(const json::Object &Request, const json::Object &Args);
  Reply exceptionInfo(const json::Object &Args);
  Reply completions(const json::Object &Args);
  void resume(const json::Object &Request, DebugRun How);
  /// Runs, answering `pause` between cycles, then sends `stopped`.
  void runUntilStop(DebugRun How);
  llvm::Error gotoCycle(const json::Object &Request, const json::Object &Args);

  llvm::Expected<unsigned> robotOf(const json::Object &Args);
  /// The index in Frames of the frame a request names; a RequestError if
  /// none.
  llvm::Expected<size_t> frameOf(const json::Object &Args);
  /// A variable of `V` (children numbered if it has some).
  json::Object variable(unsigned Robot, const DebugValue &V);
  int64_t childrenOf(unsigned Robot, const json::Value &V,
                     const std::string &Path);
  void forgetHandles();

  const AdapterOptions &Opts;
  Transport T;
  int64_t Seq = 1;
  CaughtStdout Stdout;
  std::deque<json::Value> Kept; ///< Requests that came during a run.
  std::unique_ptr<DebugSession> Session;
  bool StopOnEntry = true, Configured = false, Done = false;
  /// The last stop, for exceptionInfo.
  DebugStop LastStop;
  std::string LastDetails;
  std::vector<std::pair<unsigned, DebugFrame>> Frames;
  std::vector<VariableNode> Nodes;
};

} // namespace

//===----------------------------------------------------------------------===//
// Messages
//===----------------------------------------------------------------------===//

void Adapter::send(json::Object Message) {
  Message["seq"] = Seq++;
  T.write(json::Value(std::move(Message)));
}

void Adapter::respond(const json::Object &Request, json::Value Body) {
  json::Object R{{"type", "response"},
                 {"request_seq", Request.getInteger("seq").value_or(0)},
                 {"command", Request.getString("command").value_or("")},
                 {"success", true}};
  if (Body.kind() != json::Value::Null)
    R["body"] = std::move(Body);
  send(std::move(R));
}

void Adapter::fail(const json::Object &Request, llvm::StringRef Message) {
  send(json::Object{{"type", "response"},
                    {"request_seq", Request.getInteger("seq").value_or(0)},
                    {"command", Request.getString("command").value_or("")},
                    {"success", false},
                    {"message", Message}});
}

void Adapter::event(llvm::StringRef Name, json::Value Body) {
  send(json::Object{
      {"type", "event"}, {"event", Name}, {"body", std::move(Body)}});
}

void Adapter::flushOutput() {
  auto Output = [&](llvm::StringRef Category, const std::string &Text) {
    if (!Text.empty())
      event("output", json::Object{{"category", Category}, {"output", Text}});
  };
  Output("stdout", Stdout.take());
  if (Session) {
    Output("console", Session->takeOutput());
    Output("stderr", Session->takeErrors());
  }
}

void Adapter::forgetHandles() {
  Frames.clear();
  Nodes.clear();
}

void Adapter::stopped(const DebugStop &Stop) {
  std::string Details = Session->takeErrors();
  flushOutput();
  if (!Details.empty())
    event("output", json::Object{{"category", "stderr"}, {"output", Details}});
  forgetHandles();
  LastStop = Stop;
  LastDetails = Details;
  static const char *Reasons[] = {
      "step", "breakpoint", "function breakpoint", "exception", "pause",
      "goto", "entry"};
  json::Object Body{{"reason", Reasons[Stop.Why]},
                    {"description", Stop.Description},
                    {"threadId", int64_t(Stop.Robot) + 1},
                    {"allThreadsStopped", true}};
  if (!Stop.Breakpoints.empty()) {
    json::Array Ids;
    for (unsigned N : Stop.Breakpoints)
      Ids.push_back(int64_t(N));
    Body["hitBreakpointIds"] = std::move(Ids);
  }
  if (Stop.Why == DebugStop::Exception)
    Body["text"] = Stop.ExceptionId;
  event("stopped", std::move(Body));
}

Transport::Read Adapter::next(json::Value &Message, std::string &Error) {
  if (!Kept.empty()) {
    Message = std::move(Kept.front());
    Kept.pop_front();
    return Transport::Read::Message;
  }
  return T.read(Message, Error, -1);
}

int Adapter::run() {
  while (!Done) {
    json::Value Message = nullptr;
    std::string Error;
    switch (next(Message, Error)) {
    case Transport::Read::End:
      return 0;
    case Transport::Read::Timeout:
      continue;
    case Transport::Read::Malformed:
      // The protocol has no error for a message that is not one; say it in
      // the console.
      event("output", json::Object{{"category", "stderr"},
                                   {"output", "bsc dap: a message that is not "
                                              "JSON was skipped: " +
                                                  Error + "\n"}});
      continue;
    case Transport::Read::Message:
      break;
    }
    const json::Object *Request = Message.getAsObject();
    if (!Request || Request->getString("type") != "request" ||
        !Request->getString("command")) {
      event("output",
            json::Object{{"category", "stderr"},
                         {"output", "bsc dap: skipped a message that is no "
                                    "request (it needs \"type\": "
                                    "\"request\" and a \"command\")\n"}});
      continue;
    }
    handle(*Request);
  }
  return 0;
}

//===----------------------------------------------------------------------===//
// Dispatch
//===----------------------------------------------------------------------===//

static const json::Object &argumentsOf(const json::Object &Request) {
  static const json::Object None;
  const json::Object *Args = Request.getObject("arguments");
  return Args ? *Args : None;
}

void Adapter::handle(const json::Object &Request) {
  if (llvm::Error E = dispatch(Request)) {
    fail(Request, llvm::toString(std::move(E)));
    flushOutput();
  }
}

llvm::Error Adapter::answer(const json::Object &Request, Reply R) {
  if (!R)
    return R.takeError();
  respond(Request, std::move(*R));
  return llvm::Error::success();
}

llvm::Error Adapter::dispatch(const json::Object &Request) {
  llvm::StringRef Command = *Request.getString("command");
  const json::Object &Args = argumentsOf(Request);
  if (Command == "initialize")
    return answer(Request, initialize(Args));
  if (Command == "launch") {
    if (llvm::Error E = answer(Request, launch(Args)))
      return E;
    flushOutput();
    event("initialized");
    return llvm::Error::success();
  }
  if (Command == "attach")
    return refuse("bsc dap launches behaviors; it cannot attach to a "
                  "running one (replay its log with \"replay\")");
  if (Command == "disconnect" || Command == "terminate") {
    respond(Request);
    if (Command == "terminate")
      event("terminated");
    Done = true;
    return llvm::Error::success();
  }
  if (!Session)
    return refuse("no behavior is launched: 'launch' comes first");
  if (Command == "configurationDone") {
    respond(Request);
    configurationDone();
    return llvm::Error::success();
  }
  using Handler = Reply (Adapter::*)(const json::Object &);
  static const std::pair<const char *, Handler> Handlers[] = {
      {"setBreakpoints", &Adapter::setBreakpoints},
      {"setFunctionBreakpoints", &Adapter::setFunctionBreakpoints},
      {"setExceptionBreakpoints", &Adapter::setExceptionBreakpoints},
      {"stackTrace", &Adapter::stackTrace},
      {"scopes", &Adapter::scopes},
      {"variables", &Adapter::variables},
      {"setVariable", &Adapter::setVariable},
      {"exceptionInfo", &Adapter::exceptionInfo},
      {"completions", &Adapter::completions},
  };
  for (auto [Name, Run] : Handlers)
    if (Command == Name)
      return answer(Request, (this->*Run)(Args));
  if (Command == "threads")
    return answer(Request, threads());
  if (Command == "evaluate")
    return evaluate(Request, Args);
  if (Command == "bscript/gotoCycle")
    return gotoCycle(Request, Args);
  if (Command == "pause") {
    // Not running (a run answers pause between its cycles).
    respond(Request);
    DebugStop Stop;
    Stop.Why = DebugStop::Pause;
    Stop.Robot = LastStop.Robot;
    Stop.Description = "paused at cycle " + std::to_string(Session->getCycle());
    stopped(Stop);
    return llvm::Error::success();
  }
  static const std::pair<const char *, DebugRun> Runs[] = {
      {"continue", DebugRun::Continue},
      {"next", DebugRun::Next},
      {"stepIn", DebugRun::StepIn},
      {"stepOut", DebugRun::StepOut},
      {"stepBack", DebugRun::StepBack},
      {"reverseContinue", DebugRun::ReverseContinue}};
  for (auto [Name, How] : Runs)
    if (Command == Name) {
      resume(Request, How);
      return llvm::Error::success();
    }
  return refuse("bsc dap does not support the request '" + Command + "'");
}

//===----------------------------------------------------------------------===//
// Starting
//===----------------------------------------------------------------------===//

Reply Adapter::initialize(const json::Object &) {
  json::Array Filters;
  for (const ExceptionFilter &F : getExceptionFilters())
    Filters.push_back(json::Object{{"filter", F.Id},
                                   {"label", F.Label},
                                   {"description", F.Description},
                                   {"default", F.Default}});
  return json::Object{
      {"supportsConfigurationDoneRequest", true},
      {"supportsFunctionBreakpoints", true},
      {"supportsConditionalBreakpoints", true},
      {"supportsHitConditionalBreakpoints", true},
      {"supportsLogPoints", true},
      {"supportsEvaluateForHovers", true},
      {"supportsStepBack", true},
      {"supportsSetVariable", true},
      {"supportsExceptionInfoRequest", true},
      {"supportsCompletionsRequest", true},
      {"supportsTerminateRequest", true},
      {"supportsDelayedStackTraceLoading", false},
      {"exceptionBreakpointFilters", std::move(Filters)},
  };
}

namespace {
/// Reads launch's arguments; the first that is of the wrong type is kept
/// in Error, and every later read returns its default.
struct LaunchArguments {
  const json::Object &Args;
  std::string Error;

  /// A string or an array of strings.
  std::vector<std::string> strings(llvm::StringRef Name) {
    const json::Value *V = Args.get(Name);
    if (!V || V->kind() == json::Value::Null || !Error.empty())
      return {};
    if (std::optional<llvm::StringRef> S = V->getAsString())
      return {S->str()};
    std::vector<std::string> Strings;
    const json::Array *A = V->getAsArray();
    for (size_t I = 0; A && I < A->size(); ++I)
      if (std::optional<llvm::StringRef> S = (*A)[I].getAsString())
        Strings.push_back(S->str());
    if (!A || Strings.size() != A->size())
      Error = "launch: \"" + Name.str() +
              "\" must be a string or an array of strings";
    return Strings;
  }
  std::string string(llvm::StringRef Name) {
    const json::Value *V = Args.get(Name);
    if (!V || V->kind() == json::Value::Null || !Error.empty())
      return "";
    if (std::optional<llvm::StringRef> S = V->getAsString())
      return S->str();
    Error = "launch: \"" + Name.str() + "\" must be a string";
    return "";
  }
  int64_t number(llvm::StringRef Name, int64_t Min, int64_t Max,
                 int64_t Default) {
    const json::Value *V = Args.get(Name);
    if (!V || V->kind() == json::Value::Null || !Error.empty())
      return Default;
    std::optional<int64_t> N = V->getAsInteger();
    if (N && *N >= Min && *N <= Max)
      return *N;
    Error = "launch: \"" + Name.str() + "\" must be a whole number from " +
            std::to_string(Min) + " to " + std::to_string(Max);
    return Default;
  }
  bool boolean(llvm::StringRef Name, bool Default) {
    const json::Value *V = Args.get(Name);
    if (!V || V->kind() == json::Value::Null || !Error.empty())
      return Default;
    if (std::optional<bool> B = V->getAsBoolean())
      return *B;
    Error = "launch: \"" + Name.str() + "\" must be true or false";
    return Default;
  }
};
} // namespace

Reply Adapter::launch(const json::Object &Args) {
  if (Session)
    return refuse("a behavior is launched already");
  LaunchArguments A{Args, ""};
  ReplOptions R;
  R.Frontend = Opts.BaseOptions();
  std::string Cwd = A.string("cwd");
  R.Frontend.Inputs = A.strings("program");
  R.Frontend.BindObjects = A.strings("bind");
  R.Frontend.IncludeDirs = A.strings("includeDirs");
  R.WorldLibrary = A.string("world");
  R.WorldOutput = A.string("worldOutput");
  R.EntryName = A.string("entry");
  if (R.EntryName.empty())
    R.EntryName = "main";
  R.Robots = A.number("robots", 1, MaxRobots, 1);
  R.Load.OptLevel = A.number("optimize", 0, 3, 0);
  R.Load.CycleBudget = A.number("cycleBudget", 0, UINT32_MAX, 0);
  R.CycleLimitMs = A.number("cycleLimitMs", 0, 3600000, DefaultCycleLimitMs);
  std::string Replay = A.string("replay");
  StopOnEntry = A.boolean("stopOnEntry", true);
  if (!A.Error.empty())
    return refuse(A.Error);
  if (!Cwd.empty() && llvm::sys::fs::set_current_path(Cwd))
    return refuse("launch: cannot change to the folder \"" + Cwd + "\"");
  if (R.Frontend.Inputs.empty())
    return refuse("launch: \"program\" names the behavior's .bs files");
  for (const std::string &File : R.Frontend.Inputs)
    if (!llvm::sys::fs::exists(File))
      return refuse("launch: no file \"" + File + "\"");
  if (!Replay.empty() && !llvm::sys::fs::exists(Replay))
    return refuse("launch: no file \"" + Replay + "\" to replay");
  if (!R.WorldOutput.empty() && R.WorldLibrary.empty() &&
      R.Frontend.BindObjects.empty())
    return refuse("launch: \"worldOutput\" needs \"world\" or \"bind\"");
  R.Load.StandardModules = R.Frontend.StandardModules;
  R.Load.BindObjects = R.Frontend.BindObjects;
  std::string Errors;
  Session = DebugSession::start(R, Replay, Errors);
  if (!Session) {
    event("output", json::Object{{"category", "stderr"}, {"output", Errors}});
    // The first line names the problem in the editor's message.
    llvm::StringRef First = llvm::StringRef(Errors).split('\n').first;
    return refuse(
        "the behavior cannot be debugged: " +
        (First.empty() ? llvm::StringRef("see the debug console") : First));
  }
  return nullptr;
}

void Adapter::configurationDone() {
  Configured = true;
  if (StopOnEntry) {
    DebugStop Stop;
    Stop.Why = DebugStop::Entry;
    Stop.Description = Session->getCycle()
                           ? "at cycle " + std::to_string(Session->getCycle())
                           : "before the first cycle";
    return stopped(Stop);
  }
  runUntilStop(DebugRun::Continue);
}

//===----------------------------------------------------------------------===//
// Breakpoints
//===----------------------------------------------------------------------===//

static json::Object breakpointOf(const BreakpointState &B) {
  json::Object O{{"verified", B.Verified}};
  if (B.Id)
    O["id"] = int64_t(B.Id);
  if (B.Line)
    O["line"] = int64_t(B.Line);
  if (!B.Message.empty())
    O["message"] = B.Message;
  return O;
}

Reply Adapter::setBreakpoints(const json::Object &Args) {
  const json::Object *Source = Args.getObject("source");
  std::optional<llvm::StringRef> Path =
      Source ? Source->getString("path") : std::nullopt;
  if (!Path)
    return refuse("setBreakpoints needs a source with a path");
  std::vector<SourceBreakpoint> Wanted;
  if (const json::Array *A = Args.getArray("breakpoints"))
    for (const json::Value &V : *A) {
      const json::Object *B = V.getAsObject();
      std::optional<int64_t> Line = B ? B->getInteger("line") : std::nullopt;
      if (!Line || *Line < 1)
        return refuse("a breakpoint needs a line from 1");
      SourceBreakpoint SB;
      SB.Line = *Line;
      SB.Condition = B->getString("condition").value_or("").str();
      SB.HitCondition = B->getString("hitCondition").value_or("").str();
      SB.LogMessage = B->getString("logMessage").value_or("").str();
      Wanted.push_back(SB);
    }
  json::Array Result;
  for (const BreakpointState &B : Session->setSourceBreakpoints(*Path, Wanted))
    Result.push_back(breakpointOf(B));
  return json::Object{{"breakpoints", std::move(Result)}};
}

Reply Adapter::setFunctionBreakpoints(const json::Object &Args) {
  std::vector<TaskBreakpoint> Wanted;
  if (const json::Array *A = Args.getArray("breakpoints"))
    for (const json::Value &V : *A) {
      const json::Object *B = V.getAsObject();
      std::optional<llvm::StringRef> Name =
          B ? B->getString("name") : std::nullopt;
      if (!Name)
        return refuse("a function breakpoint needs the task's name");
      TaskBreakpoint TB;
      TB.Name = Name->trim().str();
      TB.Condition = B->getString("condition").value_or("").str();
      TB.HitCondition = B->getString("hitCondition").value_or("").str();
      Wanted.push_back(TB);
    }
  json::Array Result;
  for (const BreakpointState &B : Session->setTaskBreakpoints(Wanted))
    Result.push_back(breakpointOf(B));
  return json::Object{{"breakpoints", std::move(Result)}};
}

Reply Adapter::setExceptionBreakpoints(const json::Object &Args) {
  std::vector<std::string> Filters;
  if (const json::Array *A = Args.getArray("filters"))
    for (const json::Value &V : *A)
      if (std::optional<llvm::StringRef> F = V.getAsString())
        Filters.push_back(F->str());
  if (std::string Error = Session->setExceptionFilters(Filters); !Error.empty())
    return refuse(Error);
  return nullptr;
}

//===----------------------------------------------------------------------===//
// Running
//===----------------------------------------------------------------------===//

void Adapter::resume(const json::Object &Request, DebugRun How) {
  respond(Request,
          How == DebugRun::Continue
              ? json::Value(json::Object{{"allThreadsContinued", true}})
              : json::Value(nullptr));
  runUntilStop(How);
}

void Adapter::runUntilStop(DebugRun How) {
  // Between cycles: a pause stops the run; other requests wait for the
  // stop (every 16 cycles, so that looking costs nothing to speak of).
  unsigned Cycles = 0;
  auto ShouldPause = [&] {
    if (++Cycles % 16)
      return false;
    json::Value Message = nullptr;
    std::string Error;
    bool Pause = false;
    while (T.read(Message, Error, 0) == Transport::Read::Message) {
      const json::Object *R = Message.getAsObject();
      if (R && R->getString("command") == "pause") {
        respond(*R);
        Pause = true;
        continue;
      }
      Kept.push_back(std::move(Message));
    }
    return Pause;
  };
  stopped(Session->run(How, ShouldPause));
}

llvm::Error Adapter::gotoCycle(const json::Object &Request,
                               const json::Object &Args) {
  std::optional<int64_t> Cycle = Args.getInteger("cycle");
  if (!Cycle || *Cycle < 0 || *Cycle > UINT32_MAX)
    return refuse("bscript/gotoCycle needs a \"cycle\" from 0");
  std::optional<DebugStop> Stop = Session->gotoCycle(*Cycle);
  if (!Stop)
    return refuse("cannot go to cycle " + std::to_string(*Cycle) + ": " +
                  llvm::StringRef(Session->takeErrors()).trim().str());
  respond(Request);
  stopped(*Stop);
  return llvm::Error::success();
}

//===----------------------------------------------------------------------===//
// The stack and values
//===----------------------------------------------------------------------===//

Reply Adapter::threads() {
  json::Array Threads;
  unsigned Robots = Session->getRobots();
  for (unsigned K = 0; K < Robots; ++K)
    Threads.push_back(
        json::Object{{"id", int64_t(K) + 1},
                     {"name", Robots == 1 ? std::string("behavior")
                                          : "robot " + std::to_string(K)}});
  return json::Object{{"threads", std::move(Threads)}};
}

/// Args[Key], a number from 1 to Count (threads, frames, variables); else
/// "no WHAT N" and `Why`.
static llvm::Expected<size_t> getHandle(const json::Object &Args,
                                        llvm::StringRef Key, size_t Count,
                                        llvm::StringRef What,
                                        llvm::StringRef Why) {
  std::optional<int64_t> N = Args.getInteger(Key);
  if (!N || *N < 1 || uint64_t(*N) > Count)
    return refuse("no " + What + " " +
                  (N ? std::to_string(*N) : std::string("given")) + Why);
  return *N;
}

llvm::Expected<unsigned> Adapter::robotOf(const json::Object &Args) {
  llvm::Expected<size_t> Thread =
      getHandle(Args, "threadId", Session->getRobots(), "thread",
                ": a thread is a robot, from 1");
  if (!Thread)
    return Thread.takeError();
  return *Thread - 1;
}

Reply Adapter::stackTrace(const json::Object &Args) {
  llvm::Expected<unsigned> Thread = robotOf(Args);
  if (!Thread)
    return Thread.takeError();
  unsigned Robot = *Thread;
  std::vector<DebugFrame> Stack = Session->getFrames(Robot);
  int64_t Start = Args.getInteger("startFrame").value_or(0);
  int64_t Levels = Args.getInteger("levels").value_or(0);
  json::Array Result;
  for (int64_t I = std::max<int64_t>(Start, 0);
       I < int64_t(Stack.size()) && (Levels <= 0 || I < Start + Levels); ++I) {
    const DebugFrame &F = Stack[I];
    Frames.push_back({Robot, F});
    Result.push_back(json::Object{
        {"id", int64_t(Frames.size())},
        {"name", F.Name},
        {"source",
         json::Object{{"name", llvm::sys::path::filename(F.Path).str()},
                      {"path", F.Path}}},
        {"line", int64_t(F.Line)},
        {"column", 1}});
  }
  return json::Object{{"stackFrames", std::move(Result)},
                      {"totalFrames", int64_t(Stack.size())}};
}

llvm::Expected<size_t> Adapter::frameOf(const json::Object &Args) {
  llvm::Expected<size_t> Frame =
      getHandle(Args, "frameId", Frames.size(), "frame",
                " (frames are numbered afresh at each stop)");
  if (!Frame)
    return Frame.takeError();
  return *Frame - 1;
}

Reply Adapter::scopes(const json::Object &Args) {
  llvm::Expected<size_t> Found = frameOf(Args);
  if (!Found)
    return Found.takeError();
  size_t Index = *Found;
  unsigned Robot = Frames[Index].first;
  const DebugFrame &Frame = Frames[Index].second;
  json::Array Scopes;
  if (Frame.Task) {
    VariableNode N;
    N.Robot = Robot;
    N.Frame = Index;
    Nodes.push_back(std::move(N));
    Scopes.push_back(json::Object{
        {"name", Frame.Waiting ? "Parameters and locals" : "Parameters"},
        {"presentationHint", "locals"},
        {"variablesReference", int64_t(Nodes.size())},
        {"expensive", false}});
  }
  for (std::optional<DebugValue> V :
       {Session->getInput(Robot), Session->getOutput(Robot)}) {
    if (!V)
      continue;
    Scopes.push_back(json::Object{
        {"name", V->Name},
        {"variablesReference", childrenOf(Robot, V->Value, V->Path)},
        {"expensive", false}});
  }
  return json::Object{{"scopes", std::move(Scopes)}};
}

/// A value in a line: `{x: 1, y: 2}`, `[1, 2]`, `"kick"`, `3.5`.
static std::string preview(const json::Value &V) {
  if (const json::Object *O = V.getAsObject()) {
    std::vector<std::string> Keys;
    for (const auto &KV : *O)
      Keys.push_back(KV.first.str());
    llvm::sort(Keys);
    std::string Text = "{";
    for (const std::string &K : Keys) {
      if (Text.size() > 60) {
        Text += ", ...";
        break;
      }
      Text += (Text.size() > 1 ? ", " : "") + K + ": " + preview(*O->get(K));
    }
    return Text + "}";
  }
  if (const json::Array *A = V.getAsArray()) {
    std::string Text = "[";
    for (const json::Value &E : *A) {
      if (Text.size() > 60) {
        Text += ", ...";
        break;
      }
      Text += (Text.size() > 1 ? ", " : "") + preview(E);
    }
    return Text + "]";
  }
  std::string Text;
  llvm::raw_string_ostream(Text) << V;
  return Text;
}

int64_t Adapter::childrenOf(unsigned Robot, const json::Value &V,
                            const std::string &Path) {
  if (!V.getAsObject() && !V.getAsArray())
    return 0;
  VariableNode N;
  N.Robot = Robot;
  N.Value = V;
  N.Path = Path;
  Nodes.push_back(std::move(N));
  return Nodes.size();
}

json::Object Adapter::variable(unsigned Robot, const DebugValue &V) {
  json::Object O{{"name", V.Name},
                 {"value", V.Display.empty() ? preview(V.Value) : V.Display},
                 {"evaluateName", V.Path},
                 {"variablesReference", childrenOf(Robot, V.Value, V.Path)}};
  if (!V.Type.empty())
    O["type"] = V.Type;
  return O;
}

Reply Adapter::variables(const json::Object &Args) {
  llvm::Expected<size_t> Ref =
      getHandle(Args, "variablesReference", Nodes.size(), "variables",
                " (they are numbered afresh at each stop)");
  if (!Ref)
    return Ref.takeError();
  // Copied: variable() grows Nodes.
  VariableNode N = Nodes[*Ref - 1];
  json::Array Result;
  if (N.Frame) {
    for (const DebugValue &V :
         Session->getFields(N.Robot, Frames[*N.Frame].second))
      Result.push_back(variable(N.Robot, V));
  } else if (const json::Object *O = N.Value.getAsObject()) {
    std::vector<std::string> Keys;
    for (const auto &KV : *O)
      Keys.push_back(KV.first.str());
    llvm::sort(Keys);
    for (const std::string &K : Keys) {
      DebugValue V;
      V.Name = K;
      V.Value = *O->get(K);
      V.Path = N.Path + "." + K;
      Result.push_back(variable(N.Robot, V));
    }
  } else if (const json::Array *A = N.Value.getAsArray()) {
    for (size_t I = 0; I < A->size(); ++I) {
      DebugValue V;
      V.Name = "[" + std::to_string(I) + "]";
      V.Value = (*A)[I];
      V.Path = N.Path + V.Name;
      Result.push_back(variable(N.Robot, V));
    }
  }
  return json::Object{{"variables", std::move(Result)}};
}

Reply Adapter::setVariable(const json::Object &Args) {
  std::optional<int64_t> Ref = Args.getInteger("variablesReference");
  std::optional<llvm::StringRef> Name = Args.getString("name");
  std::optional<llvm::StringRef> Value = Args.getString("value");
  if (!Ref || *Ref < 1 || *Ref > int64_t(Nodes.size()) || !Name || !Value)
    return refuse("setVariable needs a variablesReference of this stop, "
                  "a name and a value");
  const VariableNode &N = Nodes[*Ref - 1];
  std::string Path = N.Path + (Name->starts_with("[") ? "" : ".") + Name->str();
  if (N.Frame)
    Path = Name->str();
  std::optional<DebugValue> V = Session->setInput(Path, *Value, N.Robot);
  if (!V)
    return refuse(llvm::StringRef(Session->takeErrors()).trim().str());
  flushOutput();
  json::Object Body{{"value", V->Display}};
  if (!V->Type.empty())
    Body["type"] = V->Type;
  return Body;
}

llvm::Error Adapter::evaluate(const json::Object &Request,
                              const json::Object &Args) {
  std::optional<llvm::StringRef> Expr = Args.getString("expression");
  if (!Expr)
    return refuse("evaluate needs an expression");
  llvm::StringRef Context = Args.getString("context").value_or("repl");
  unsigned Robot = LastStop.Robot;
  std::optional<unsigned> Task;
  if (Args.get("frameId")) {
    llvm::Expected<size_t> Found = frameOf(Args);
    if (!Found)
      return Found.takeError();
    size_t Frame = *Found;
    Robot = Frames[Frame].first;
    Task = Frames[Frame].second.Task;
  }
  llvm::StringRef Text = Expr->trim();
  uint32_t Before = Session->getCycle();
  // The console takes the REPL's commands: `:why`, `:goto 12`, `:tasks`.
  if (Context == "repl" &&
      (Text.starts_with(":") || Text.starts_with("requires"))) {
    Session->runConsoleLine(Text, Robot);
    std::string Answer = Session->takeOutput();
    flushOutput();
    respond(Request,
            json::Object{{"result", llvm::StringRef(Answer).rtrim("\n").str()},
                         {"variablesReference", 0}});
  } else {
    std::optional<DebugValue> V = Session->evaluate(Text, Robot, Task);
    if (!V)
      return refuse(llvm::StringRef(Session->takeErrors()).trim().str());
    json::Object Body{
        {"result", V->Type.empty() ? "" : V->Display},
        {"variablesReference", childrenOf(Robot, V->Value, V->Path)}};
    if (!V->Type.empty())
      Body["type"] = V->Type;
    respond(Request, std::move(Body));
    flushOutput();
    if (Context != "repl")
      return llvm::Error::success(); // A hover or a watch.
  }
  if (Session->getCycle() != Before) {
    DebugStop Stop;
    Stop.Why = DebugStop::Goto;
    Stop.Robot = Robot;
    Stop.Description = "cycle " + std::to_string(Session->getCycle());
    stopped(Stop);
  } else {
    event("invalidated", json::Object{{"areas", json::Array{"variables"}}});
  }
  return llvm::Error::success();
}

Reply Adapter::exceptionInfo(const json::Object &Args) {
  if (llvm::Expected<unsigned> Thread = robotOf(Args); !Thread)
    return Thread.takeError();
  if (LastStop.Why != DebugStop::Exception)
    return refuse("the last stop was no exception");
  return json::Object{
      {"exceptionId", LastStop.ExceptionId},
      {"description", LastStop.Description},
      {"breakMode", "always"},
      {"details", json::Object{{"message", LastStop.Description},
                               {"stackTrace", LastDetails}}}};
}

Reply Adapter::completions(const json::Object &Args) {
  std::string Text = Args.getString("text").value_or("").str();
  int64_t Column = Args.getInteger("column").value_or(Text.size() + 1);
  size_t Pos = std::min<size_t>(std::max<int64_t>(Column - 1, 0), Text.size());
  json::Array Targets;
  for (const std::string &Name : Session->complete(Text, Pos))
    Targets.push_back(json::Object{{"label", Name}});
  return json::Object{{"targets", std::move(Targets)}};
}

int dap::runAdapter(const AdapterOptions &Opts, int InFd, int OutFd) {
  // The protocol keeps the descriptor; standard output becomes the file
  // the adapter reads back.
  if (OutFd == STDOUT_FILENO)
    OutFd = dup(STDOUT_FILENO);
  return Adapter(Opts, InFd, OutFd).run();
}

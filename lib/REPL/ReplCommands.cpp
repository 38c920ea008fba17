//===- ReplCommands.cpp - the REPL's `:` commands and its stepping --------===//
//
// Every command is a row of getCommands() (dispatch, `:help`, completion and
// the "did you mean" of a typo come from it) and a cmd* method taking the
// text after its name. step() runs cycles and stops them at breakpoints.
//
//===----------------------------------------------------------------------===//
#include "ReplImpl.h"
#include "bsc/Sema/CallGraph.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Format.h"
#include <csignal>
#include <fcntl.h>

using namespace bsc;
using namespace bsc::repl;

namespace {
/// Set by Ctrl-C during `:run`; checked between cycles.
volatile sig_atomic_t Interrupted = 0;
void onInterrupt(int) { Interrupted = 1; }
} // namespace

std::optional<unsigned> Repl::findTask(llvm::StringRef Name) const {
  for (size_t I = 0; I < L->Tables.Tasks.size(); ++I) {
    const debug::DebugTables::Task &T = L->Tables.Tasks[I];
    if (T.Name == Name || T.ShortName == Name)
      return I;
  }
  return std::nullopt;
}

unsigned Repl::parseCount(llvm::StringRef Cmd, llvm::StringRef Arg,
                          unsigned Default, llvm::SMLoc Loc) {
  if (Arg.empty())
    return Default;
  unsigned N;
  if (Arg.getAsInteger(10, N) || N == 0 || N > MaxCycles) {
    C->Diags.report(Loc, diag::err_repl_bad_count) << Cmd << MaxCycles << Arg;
    return 0;
  }
  return N;
}

/// The leaves of `New` that differ from `Old`: `output.motion = "kick"`,
/// `output.wide[3] = 9`.
static void collectChanges(const llvm::json::Value &Old,
                           const llvm::json::Value &New, std::string Path,
                           std::vector<std::string> &Out) {
  const llvm::json::Array *NA = New.getAsArray();
  const llvm::json::Array *OA = Old.getAsArray();
  if (NA && OA && NA->size() == OA->size()) {
    for (size_t I = 0; I < NA->size(); ++I)
      collectChanges((*OA)[I], (*NA)[I], Path + "[" + std::to_string(I) + "]",
                     Out);
    return;
  }
  const llvm::json::Object *NO = New.getAsObject();
  const llvm::json::Object *OO = Old.getAsObject();
  if (NO && OO) {
    std::vector<llvm::StringRef> Keys;
    for (const auto &KV : *NO)
      Keys.push_back(KV.first);
    llvm::sort(Keys);
    for (llvm::StringRef K : Keys) {
      const llvm::json::Value *OV = OO->get(K);
      collectChanges(OV ? *OV : llvm::json::Value(nullptr), *NO->get(K),
                     Path + "." + K.str(), Out);
    }
    return;
  }
  if (debug::findDifference(Old, New, Path))
    Out.push_back(Path + " = " + debug::toJSONString(New));
}

std::string Repl::cycleName(uint32_t Cycle, unsigned Robot) const {
  std::string Name = "cycle " + std::to_string(Cycle);
  if (Robots->size() > 1)
    Name += ", robot " + std::to_string(Robot);
  return Name;
}

bool Repl::oneRobot(llvm::StringRef Name, llvm::SMLoc Loc) {
  if (Robots->size() == 1)
    return true;
  C->Diags.report(Loc, diag::err_repl_team_command) << Name << Robots->size();
  return false;
}

void Repl::reportStop(llvm::StringRef Why) {
  flushDiagnostics();
  uint32_t Cycle = S->getCycle();
  OS << "stopped after " << cycleName(Cycle, Selected) << ": " << Why << "\n"
     << cycleName(Cycle, Selected) << ": "
     << debug::formatTraceLine(
            L->Tables, debug::takeSnapshot(S->getState(), &S->getInfo()))
     << "\n";
}

StepEnd Repl::step(unsigned N, bool Report, Probe *Until,
                   const std::function<std::string()> &StopWhen) {
  LastStop = StopInfo();
  rebaseWatches();
  Interrupted = 0;
  auto OldHandler = std::signal(SIGINT, onInterrupt);
  StepEnd End = StepEnd::Ran;
  unsigned RobotCount = Robots->size();
  for (unsigned I = 0; I < N; ++I) {
    std::vector<llvm::json::Value> Before;
    for (unsigned K = 0; K < RobotCount; ++K)
      Before.push_back(L->OutputClass && Report
                           ? Values->readClass(*L->OutputClass,
                                               (*Robots)[K].getOutput())
                           : llvm::json::Value(nullptr));
    uint32_t Cycle = S->getCycle() + 1;
    bool FromHistory = false;
    unsigned Broke = 0;
    BehaviorSession::Outcome O = runNextCycle(FromHistory, Broke);
    if (!reportOutcome(*C, *L, O, Cycle, Opts.CycleLimitMs)) {
      noteRobot(*C, Broke, RobotCount);
      bool Diverged = O.K == BehaviorSession::Outcome::Diverged;
      if (Diverged)
        C->Diags.report(llvm::SMLoc(), diag::note_history_ends) << Cycle - 1;
      LastStop.Broke =
          Diverged ? StopInfo::Diverged
          : O.K == BehaviorSession::Outcome::TimedOut ? StopInfo::TimedOut
          : llvm::any_of(C->Diags.getDiagnostics(),
                         [](const Diagnostic &D) {
                           return D.Kind == diag::err_assertion_failed ||
                                  D.Kind == diag::err_assumption_failed;
                         })
              ? StopInfo::Assertion
              : StopInfo::Crash;
      LastStop.Assumption = llvm::any_of(
          C->Diags.getDiagnostics(), [](const Diagnostic &D) {
            return D.Kind == diag::err_assumption_failed;
          });
      flushDiagnostics();
      OS << "stopped in cycle " << Cycle
         << (Diverged ? "; the state is as the live run left cycle " +
                            std::to_string(Cycle - 1)
                      : std::string("; the state is as it left it"))
         << "\n";
      End = StepEnd::Broken;
      break;
    }
    for (unsigned K = 0; K < RobotCount && RecordingLog && !FromHistory; ++K)
      logCycle(*RecordingLog, K, *L, (*Robots)[K]);
    for (unsigned K = 0; K < RobotCount && Recording && !RecordingLog &&
                         !FromHistory;
         ++K) {
      llvm::json::Value Rec = recordCycle(*Values, *L, (*Robots)[K]);
      if (RobotCount > 1) // One file with every robot, as `bsc run --record`.
        (*Rec.getAsObject())["robot"] = int64_t(K);
      debug::printJSON(*Recording, Rec);
      *Recording << "\n";
      Recording->flush();
    }
    for (unsigned K = 0; K < RobotCount && Report; ++K) {
      OS << cycleName(Cycle, K);
      if (L->OutputClass) {
        std::vector<std::string> Changes;
        collectChanges(
            Before[K],
            Values->readClass(*L->OutputClass, (*Robots)[K].getOutput()),
            "output", Changes);
        OS << (Changes.empty() ? ": output unchanged"
                               : ": " + llvm::join(Changes, ", "));
      }
      OS << "\n";
    }
    std::string Why = checkBreakpoints();
    if (Why.empty() && Until && isTrue(*Until))
      Why = Until->Text + " is true";
    if (Why.empty() && StopWhen && !(Why = StopWhen()).empty())
      LastStop.Predicate = true;
    if (Why.empty() && EntryIndex) {
      int32_t State =
          bs_task_state_at(S->getState(), &S->getInfo().tasks[*EntryIndex]);
      if (State < 0) {
        Why = "the entry " + L->Entry->getQualifiedName() + " failed";
        LastStop.EntryFailed = true;
      }
    }
    if (Why.empty() && (Interrupted || (ShouldPause && ShouldPause()))) {
      Why = "interrupted";
      LastStop.Interrupted = true;
    }
    if (!Why.empty()) {
      reportStop(Why);
      LastStop.Why = Why;
      End = StepEnd::Stopped;
      break;
    }
  }
  std::signal(SIGINT, OldHandler);
  LastStop.End = End;
  return End;
}

void Repl::cmdTasks(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("tasks", Args, Loc))
    return;
  if (S->getCycle() == 0) {
    OS << "no cycle has run yet\n";
    return;
  }
  std::vector<debug::Activation> Records =
      debug::takeSnapshot(S->getState(), &S->getInfo());
  debug::ActiveTree Tree = debug::buildActiveTree(L->Tables, Records);
  if (Tree.Nodes.empty()) {
    OS << "no task ran in cycle " << S->getCycle() << "\n";
    return;
  }
  const auto *State = static_cast<const char *>(S->getState());
  std::function<void(unsigned, unsigned)> Print = [&](unsigned N,
                                                      unsigned Depth) {
    const debug::ActiveTask &Node = Tree.Nodes[N];
    const BehaviorLayout::Task &T = L->Layout.Tasks[Node.Record.Task];
    std::string Indent(2 * Depth, ' ');
    std::vector<std::string> Params, Locals;
    for (const BehaviorLayout::FrameField &F : T.Fields) {
      std::string Text = F.D->getName().Name.str() + " = " +
                         formatValue(F.Ty, Values->read(F.Ty, State + F.Offset));
      (llvm::isa<ParamDecl>(F.D) ? Params : Locals).push_back(Text);
    }
    OS << Indent << L->Tables.Tasks[Node.Record.Task].ShortName;
    if (!T.Decl->Params.empty())
      OS << "(" << llvm::join(Params, ", ") << ")";
    OS << " [" << debug::describeActivation(L->Tables, Node.Record) << "]";
    // A finished task's locals are gone (the next call starts afresh).
    if (Node.Record.Resume > 0 && !Locals.empty())
      OS << "  " << llvm::join(Locals, ", ");
    OS << "\n";
    for (unsigned Child : Node.Children)
      Print(Child, Depth + 1);
  };
  OS << "cycle " << S->getCycle() << ":\n";
  for (unsigned R : Tree.Roots)
    Print(R, 1);
}

void Repl::cmdRecord(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "record" << "a file name or 'off'";
    return;
  }
  stopRecording();
  if (Args == "off") {
    OS << "recording stopped\n";
    return;
  }
  // A new file starts with the header that names the behavior; cycles
  // appended to an old one follow its header. A binary log is written
  // whole (its cycles are changes against those before).
  bool Binary = isBinaryLogPath(Args);
  uint64_t Size = 0;
  bool New = llvm::sys::fs::file_size(Args, Size) || Size == 0;
  if (Binary && !New) {
    C->Diags.report(Loc, diag::err_repl_log_exists) << Args;
    return;
  }
  if (Binary && !checkWorldAsBytes(C->Diags, Loc, *L, Args))
    return;
  std::error_code EC;
  auto F = std::make_unique<llvm::raw_fd_ostream>(
      Args, EC, Binary ? llvm::sys::fs::OF_None : llvm::sys::fs::OF_Append);
  if (EC) {
    C->Diags.report(Loc, diag::err_cannot_write_output) << Args << EC.message();
    return;
  }
  if (Binary) {
    RecordingLog = std::make_unique<BinaryLogWriter>(
        *F, logHeader(*C, *L, (*Robots)[0], Robots->size()),
        /*Compress=*/true);
  } else if (New) {
    debug::printJSON(*F, recordHeader(*L));
    *F << "\n";
  }
  Recording = std::move(F);
  // The calls into C++ go into the recording too.
  for (unsigned K = 0; K < Robots->size(); ++K)
    (*Robots)[K].keepCalls(true);
  OS << "recording cycles to " << Args << "\n";
}

void Repl::cmdReplay(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "replay" << "a file name";
    return;
  }
  RunOptions R;
  R.ReplayPath = Args.str();
  R.CycleLimitMs = Opts.CycleLimitMs;
  std::string Why;
  // After each cycle of the whole team (a team's recording has a line
  // per robot and cycle, and as many robots as the session).
  R.StopAfterCycle = [&] {
    recordLiveCycle();
    Why = checkBreakpoints();
    return !Why.empty();
  };
  // Each robot's conditions, for `:why`, before the next robot's cycle.
  R.TakeCycle = [&](unsigned K, BehaviorSession &) {
    keepExplainLog(K);
    noteLinesRan(K);
    return true;
  };
  forgetFuture(); // The recording's inputs replace the history's.
  uint32_t Before = S->getCycle();
  rebaseWatches();
  markCounters();
  bool OK = runTeam(*C, *L, *Robots, R, OS);
  flushDiagnostics();
  if (S->getCycle() == Before) // The file was refused before a cycle ran.
    OS << "replayed no cycle\n";
  else
    OS << "replayed cycles " << Before + 1 << " to " << S->getCycle()
       << (OK ? "; no recorded output differs" : "") << "\n";
  if (!Why.empty())
    reportStop(Why);
}

void Repl::cmdFrame(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    Checker->setFrame(nullptr);
    OS << "lines are checked in module " << L->Entry->Module->Name << "\n";
    return;
  }
  std::optional<unsigned> T = findTask(Args);
  if (!T) {
    C->Diags.report(Loc, diag::err_repl_unknown_task) << Args;
    return;
  }
  const BehaviorLayout::Task &Task = L->Layout.Tasks[*T];
  Checker->setFrame(llvm::cast<TaskDecl>(Task.Decl));
  std::vector<std::string> Names;
  for (const BehaviorLayout::FrameField &F : Task.Fields)
    if (!llvm::is_contained(Names, F.D->getName().Name))
      Names.push_back(F.D->getName().Name.str());
  OS << "frame of " << Task.Decl->getQualifiedName() << ": "
     << (Names.empty() ? std::string("it keeps no parameter or local")
                       : llvm::join(Names, ", "))
     << "\n";
}

void Repl::cmdQuiet(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty() || Args == "on") {
    if (QuietFd < 0)
      QuietFd = ::open("/dev/null", O_WRONLY | O_CLOEXEC);
    Robots->setWorldOutput(QuietFd);
    OS << "the world's output is discarded\n";
  } else if (Args == "off") {
    Robots->setWorldOutput(WorldOutputFd);
    OS << "the world's output goes to "
       << (WorldOutputFd < 0 ? "standard output" : Opts.WorldOutput) << "\n";
  } else {
    C->Diags.report(Loc, diag::err_repl_extra_argument) << "quiet" << Args;
  }
}

void Repl::selectRobot(unsigned K) {
  Selected = K;
  S = &(*Robots)[K];
  if (!Histories.empty())
    History = Histories[K].get();
}

void Repl::cmdRobot(llvm::StringRef Args, llvm::SMLoc Loc) {
  unsigned K;
  if (!Args.empty()) {
    if (Args.getAsInteger(10, K) || K >= Robots->size()) {
      C->Diags.report(Loc, diag::err_repl_bad_robot)
          << Robots->size() - 1 << Args;
      return;
    }
    selectRobot(K);
  }
  OS << "robot " << Selected << " of " << Robots->size()
     << ": lines, :tasks, :why, :history, breakpoints and watches follow "
        "it\n";
}

void Repl::cmdGraph(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("graph", Args, Loc))
    return;
  llvm::DenseSet<const CallableDecl *> Active;
  for (const debug::Activation &A :
       debug::takeSnapshot(S->getState(), &S->getInfo()))
    Active.insert(L->Layout.Tasks[A.Task].Decl);
  writeCallGraphDOT(C->Checked, C->SM, OS, &Active);
}

void Repl::cmdCoverage(llvm::StringRef Args, llvm::SMLoc Loc) {
  std::vector<uint64_t> Counts = readCoverage(*L);
  printCoverageSummary(OS, summarizeCoverage(*C, *L, Counts));
  if (!Args.empty() &&
      writeLcov(*C, *L, Counts, Args, L->Entry->getQualifiedName()))
    OS << "wrote " << Args << "\n";
}

void Repl::cmdHelp(llvm::StringRef, llvm::SMLoc) {
  auto Head = [](const CommandInfo &Cmd) {
    return (":" + llvm::Twine(Cmd.Name) +
            (*Cmd.Args ? " " + llvm::Twine(Cmd.Args) : ""))
        .str();
  };
  size_t Width = 0;
  for (const CommandInfo &Cmd : getCommands())
    Width = std::max(Width, Head(Cmd).size());
  for (const CommandInfo &Cmd : getCommands())
    OS << "  " << llvm::left_justify(Head(Cmd), Width + 2) << Cmd.Help
       << "\n";
  OS << "  Any other line is b-script: an expression shows its value "
        "(`input.ball.x`),\n  a statement runs (`input.time = 3000`, "
        "`float k = 2.5`), between cycles.\n";
}

bool Repl::noArgs(llvm::StringRef Name, llvm::StringRef Args,
                  llvm::SMLoc Loc) {
  if (Args.empty())
    return true;
  C->Diags.report(Loc, diag::err_repl_extra_argument) << Name << Args;
  return false;
}

void Repl::cmdStep(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (unsigned N = parseCount("step", Args, 1, Loc))
    step(N, /*Report=*/true);
}

void Repl::cmdRun(llvm::StringRef Args, llvm::SMLoc Loc) {
  unsigned N = parseCount("run", Args, MaxCycles, Loc);
  if (!N)
    return;
  if (step(N, /*Report=*/false) != StepEnd::Ran)
    return;
  OS << "ran " << N << " cycles to cycle " << S->getCycle();
  if (!Breakpoints.empty())
    OS << "; no breakpoint was hit";
  OS << "\n";
}

llvm::ArrayRef<Repl::CommandInfo> Repl::getCommands() {
  static const CommandInfo Commands[] = {
      {"step", "[N]", "run N cycles (1), printing what changed in output",
       &Repl::cmdStep},
      {"run", "[N]",
       "run until a breakpoint, a failure of the entry, Ctrl-C or N cycles "
       "(1000000)",
       &Repl::cmdRun},
      {"tasks", "",
       "the tasks of the last cycle: states, waiting lines, parameters and "
       "locals",
       &Repl::cmdTasks},
      {"frame", "[TASK]",
       "check later lines in TASK's frame: its parameters, kept locals and "
       "nested funcs unqualified (no TASK: the entry's module)",
       &Repl::cmdFrame},
      {"break", "TASK|FILE:LINE|failure|budget [if EXPR]",
       "stop after a cycle in which TASK ran, a task waits at a yield on "
       "FILE:LINE (another line: the cycle ran it), a task failed, or the "
       "cycle budget ran out (and EXPR is true)",
       &Repl::cmdBreak},
      {"until", "EXPR [N]",
       "run until EXPR is true after a cycle, a breakpoint, or N cycles "
       "(1000000)",
       &Repl::cmdUntil},
      {"watch", "EXPR", "stop after a cycle that changed the value of EXPR",
       &Repl::cmdWatch},
      {"breaks", "", "list the breakpoints and watches", &Repl::cmdBreaks},
      {"delete", "[N]", "delete breakpoint N, or all", &Repl::cmdDelete},
      {"goto", "CYCLE",
       "go to CYCLE of this session, back or forth (the cycles in between "
       "run again on their inputs)",
       &Repl::cmdGoto},
      {"back", "[N]", "go back N cycles (1)", &Repl::cmdBack},
      {"history", "EXPR [FROM TO]",
       "the cycles of this session at which EXPR's value changed",
       &Repl::cmdHistory},
      {"reload", "",
       "recompile the edited files, keeping the state of every task whose "
       "frame did not change",
       &Repl::cmdReload},
      {"record", "FILE|off", "append each cycle's input and output to FILE",
       &Repl::cmdRecord},
      {"replay", "FILE",
       "run a recording: feed its inputs, compare outputs",
       &Repl::cmdReplay},
      {"quiet", "[on|off]",
       "discard what the --world library prints (off: to --world-output "
       "or standard output again)",
       &Repl::cmdQuiet},
      {"graph", "",
       "the call graph as DOT, the tasks of the last cycle filled",
       &Repl::cmdGraph},
      {"coverage", "[FILE]",
       "what the cycles since the behavior was loaded exercised (re-runs "
       "of :goto included): lines, branches, tasks never active, yields "
       "never reached; FILE: also as an lcov tracefile",
       &Repl::cmdCoverage},
      {"why", "[TASK]",
       "the conditions TASK (or every task) evaluated in the last cycle, "
       "with their values, and the yield it stopped at",
       &Repl::cmdWhy},
      {"robot", "[K]",
       "show robot K of a team (--robots N, from 0): lines, :tasks, "
       ":why, :history, breakpoints and watches follow it",
       &Repl::cmdRobot},
      {"help", "", "this list", &Repl::cmdHelp},
      {"quit", "", "leave (so does the end of input)", nullptr},
  };
  return Commands;
}

void Repl::command(llvm::StringRef Name, llvm::StringRef Args,
                   llvm::SMLoc Loc) {
  for (const CommandInfo &Cmd : getCommands())
    if (Name == Cmd.Name && Cmd.Run) {
      (this->*Cmd.Run)(Args, Loc);
      flushDiagnostics();
      return;
    }
  // The closest command by edit distance, as clang suggests names.
  const char *Best = nullptr;
  unsigned BestDistance = 3;
  for (const CommandInfo &Cmd : getCommands()) {
    unsigned D = Name.edit_distance(Cmd.Name, true, BestDistance);
    if (D < BestDistance) {
      BestDistance = D;
      Best = Cmd.Name;
    }
  }
  if (Best)
    C->Diags.report(Loc, diag::err_repl_unknown_command_suggest) << Name << Best;
  else
    C->Diags.report(Loc, diag::err_repl_unknown_command) << Name;
  flushDiagnostics();
}

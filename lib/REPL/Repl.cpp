//===- Repl.cpp - `bsc repl`: stepping a behavior and asking it questions -===//
//
// The REPL holds one compilation, the behavior loaded from it into a JIT,
// and a session (the state and the input and output objects). A line is a
// command (`:step`, `:tasks`, ...) or b-script: ReplChecker checks it as
// the body of a new func in the entry's module, emitReplLine compiles it
// into the same JIT, and it runs under the session's guard between cycles.
// Its variables live here, at fixed addresses the generated code is given,
// so they outlive the line.
//
// Breakpoints are checked after each cycle (a cycle is the unit the robot
// runs; the state between cycles is all there is to see), against the
// cycle's activations (bsc/Debug/Trace.h): a task that ran, a task waiting
// at a yield on a line, a task that failed, a watched value that changed.
//
// `:reload` compiles the edited files into a new JIT and a new state, then
// carries over what still fits: each task frame whose fields are the same
// (names and types, in order), the input and output values, the cycle
// number. Other tasks start afresh, as after a missed cycle.
//
// Everything printed is deterministic, so that lit tests drive the REPL
// with `--batch` (or a standard input that is not a terminal).
//
//===----------------------------------------------------------------------===//
#include "bsc/REPL/Repl.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Parse/Parser.h"
#include "bsc/Sema/CallGraph.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSwitch.h"
#include "llvm/LineEditor/LineEditor.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Process.h"
#include "llvm/Support/WithColor.h"
#include <csignal>
#include <cstring>
#include <unistd.h>

using namespace bsc;

namespace {

/// Set by Ctrl-C during `:run`; checked between cycles.
volatile sig_atomic_t Interrupted = 0;
void onInterrupt(int) { Interrupted = 1; }

/// The most cycles one `:step` or `:run` runs: about a day of a robot's
/// 30 Hz cycles would be 2.6 million; a million ends runs that no
/// breakpoint stops, also in batch mode.
constexpr unsigned MaxCycles = 1000000;

/// Storage of a REPL variable or a line's result: aligned, zeroed.
struct Slot {
  void *Ptr = nullptr;
  size_t Size = 0, Align = 1;
  const Type *Ty = nullptr;
};

struct Breakpoint {
  enum Kind { Task, Line, Failure, Watch } K;
  unsigned Number;
  std::string Text; ///< As the user wrote it.
  unsigned TaskIndex = 0;
  std::string File;
  unsigned LineNo = 0;
  /// Watch: the compiled expression and its last value.
  void (*Eval)(void *) = nullptr;
  Slot Result;
  llvm::json::Value Last = nullptr;
};

class Repl {
public:
  Repl(const ReplOptions &Opts, llvm::raw_ostream &OS)
      : Opts(Opts), OS(OS) {}
  ~Repl();

  /// Compiles and starts the behavior; false after reporting.
  bool start();
  /// Handles one input line; false once the user quits.
  bool handleLine(llvm::StringRef Line);
  std::vector<llvm::LineEditor::Completion> complete(llvm::StringRef Buffer,
                                                     size_t Pos) const;

private:
  // Loading.
  std::unique_ptr<Compilation> compileFiles();
  bool load(std::unique_ptr<Compilation> NewC);

  // Lines of b-script.
  void evaluate(llvm::StringRef Line);
  /// Compiles `Text` as REPL line number ++LineNo; its result and new
  /// variables get slots. Null after reporting.
  struct Compiled {
    void (*Fn)(void *) = nullptr;
    std::optional<ReplChecker::Line> Checked;
    Slot Result;
  };
  std::optional<Compiled> compileLine(llvm::StringRef Text);
  Slot allocateSlot(const Type *T);
  void destroySlot(Slot &S);
  /// The value as the REPL prints it: `(int) 3`.
  std::string describe(const Type *T, const void *Addr);
  std::string formatValue(const Type *T, const llvm::json::Value &V);

  // Commands: each takes the text after its name and the place of the line
  // (for carets).
  using Handler = void (Repl::*)(llvm::StringRef Args, llvm::SMLoc Loc);
  struct CommandInfo {
    const char *Name, *Args, *Help;
    Handler Run;
  };
  /// Every command, for dispatch, `:help`, completion and suggestions.
  static llvm::ArrayRef<CommandInfo> getCommands();
  void command(llvm::StringRef Name, llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdStep(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdRun(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdTasks(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdWatch(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdBreaks(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdDelete(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdReload(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdRecord(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdReplay(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdGraph(llvm::StringRef Args, llvm::SMLoc Loc);
  void cmdHelp(llvm::StringRef Args, llvm::SMLoc Loc);
  /// Reports arguments given to a command that takes none; true if none.
  bool noArgs(llvm::StringRef Name, llvm::StringRef Args, llvm::SMLoc Loc);
  void step(unsigned N, bool Report);
  /// Parses `:step N`'s N (empty: `Default`); reports and returns 0 if bad.
  unsigned parseCount(llvm::StringRef Cmd, llvm::StringRef Arg,
                      unsigned Default, llvm::SMLoc Loc);

  /// Why the last cycle should stop `:run`, or empty.
  std::string checkBreakpoints();
  /// Takes the watches' values as the ones to compare against.
  void rebaseWatches();
  /// "stopped after cycle N: why" and the cycle's trace.
  void reportStop(llvm::StringRef Why);
  /// Prints and forgets the diagnostics so far.
  void flushDiagnostics();
  /// A buffer holding `Text`, named `<repl>`, for carets under a line.
  llvm::SMLoc addBuffer(llvm::StringRef Text);
  std::optional<unsigned> findTask(llvm::StringRef Name) const;

  const ReplOptions &Opts;
  llvm::raw_ostream &OS;

  // Declared in the order they must be destroyed in reverse: the session
  // before the JIT that holds its code, both before the compilation whose
  // types and natives they refer to.
  std::unique_ptr<Compilation> C;
  std::unique_ptr<LoadedBehavior> L;
  std::unique_ptr<BehaviorSession> S;
  std::unique_ptr<ReplChecker> Checker;
  std::unique_ptr<debug::ValueIO> Values;
  std::vector<Slot> Variables;
  std::vector<Breakpoint> Breakpoints;
  unsigned NextBreakpoint = 1;
  unsigned LineNo = 0;
  std::unique_ptr<llvm::raw_fd_ostream> Recording;
  /// The entry's index in the task table, if the entry is a task (its
  /// failure stops `:run`).
  std::optional<unsigned> EntryIndex;
};

} // namespace

//===----------------------------------------------------------------------===//
// Loading
//===----------------------------------------------------------------------===//

Repl::~Repl() {
  for (Slot &V : Variables)
    destroySlot(V);
  for (Breakpoint &B : Breakpoints)
    destroySlot(B.Result);
}

void Repl::flushDiagnostics() {
  OS.flush();
  if (!C)
    return;
  printDiagnostics(C->SM, C->Diags.getDiagnostics(), llvm::errs(),
                   llvm::WithColor(llvm::errs()).colorsEnabled());
  llvm::errs().flush();
  C->Diags.clear();
}

std::unique_ptr<Compilation> Repl::compileFiles() {
  auto NewC = std::make_unique<Compilation>();
  if (!runFrontend(*NewC, Opts.Frontend) ||
      !findProgramEntry(*NewC, Opts.EntryName)) {
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), llvm::errs(),
                     llvm::WithColor(llvm::errs()).colorsEnabled());
    return nullptr;
  }
  return NewC;
}

/// Whether a task's frame has the same fields, in order, in both layouts,
/// the task as many yields and its resume point and state the same widths:
/// then its bytes mean the same in the new state.
static bool sameFrame(const BehaviorLayout::Task &A,
                      const BehaviorLayout::Task &B) {
  // The resume point numbers the yields: a task with more or fewer yields
  // would resume somewhere else.
  if (A.FrameSize != B.FrameSize || A.Fields.size() != B.Fields.size() ||
      A.Decl->Yields.size() != B.Decl->Yields.size() ||
      A.OnlyRunningStates != B.OnlyRunningStates ||
      A.Resume.Bytes != B.Resume.Bytes || A.State.Bytes != B.State.Bytes)
    return false;
  for (size_t I = 0; I < A.Fields.size(); ++I) {
    const BehaviorLayout::FrameField &FA = A.Fields[I], &FB = B.Fields[I];
    if (FA.D->getName().Name != FB.D->getName().Name ||
        FA.Ty->getName() != FB.Ty->getName() ||
        FA.Offset - A.FrameOffset != FB.Offset - B.FrameOffset)
      return false;
  }
  return true;
}

bool Repl::load(std::unique_ptr<Compilation> NewC) {
  const CallableDecl *Entry = findProgramEntry(*NewC, Opts.EntryName);
  LoadOptions LOpts = Opts.Load;
  LOpts.ExternalFunctions = true;
  auto Loaded = loadBehavior(*NewC, *Entry, LOpts);
  if (!Loaded) {
    llvm::WithColor::error(llvm::errs(), "bsc")
        << "internal error: " << llvm::toString(Loaded.takeError()) << "\n";
    return false;
  }
  if (!*Loaded) {
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), llvm::errs());
    return false;
  }
  auto Session = startSession(*NewC, **Loaded);
  if (!Session || !*Session) {
    if (!Session)
      llvm::WithColor::error(llvm::errs(), "bsc")
          << "internal error: " << llvm::toString(Session.takeError()) << "\n";
    printDiagnostics(NewC->SM, NewC->Diags.getDiagnostics(), llvm::errs());
    return false;
  }
  std::unique_ptr<LoadedBehavior> NewL = std::move(*Loaded);
  std::unique_ptr<BehaviorSession> NewS = std::move(*Session);
  auto NewValues = std::make_unique<debug::ValueIO>(
      [J = NewL->JIT.get()](llvm::StringRef Sym) { return J->lookup(Sym); });
  bool FirstLoad = !S;

  if (S) {
    // :reload. The world, the frames that still fit, the cycle, input and
    // output.
    NewS->takeWorldFrom(*S);
    OS.flush();
    auto *OldBytes = static_cast<unsigned char *>(S->getState());
    auto *NewBytes = static_cast<unsigned char *>(NewS->getState());
    std::vector<std::string> Reset;
    for (size_t I = 0; I < NewL->Layout.Tasks.size(); ++I) {
      const BehaviorLayout::Task &NT = NewL->Layout.Tasks[I];
      std::string Name = NT.Decl->getQualifiedName();
      bool Kept = false;
      for (size_t J = 0; J < L->Layout.Tasks.size(); ++J) {
        const BehaviorLayout::Task &OT = L->Layout.Tasks[J];
        if (OT.Decl->getQualifiedName() != Name)
          continue;
        uint64_t Size = OT.FrameSize;
        if (sameFrame(OT, NT)) {
          std::memcpy(NewBytes + NT.FrameOffset, OldBytes + OT.FrameOffset,
                      Size);
          // Narrow resume points and states sit outside the frame.
          std::memcpy(NewBytes + NT.Resume.Offset,
                      OldBytes + OT.Resume.Offset, NT.Resume.Bytes);
          std::memcpy(NewBytes + NT.State.Offset, OldBytes + OT.State.Offset,
                      NT.State.Bytes);
          // The values moved: the old state must not destroy them.
          std::memset(OldBytes + OT.FrameOffset, 0, Size);
          Kept = true;
        }
      }
      if (!Kept)
        Reset.push_back(Name);
    }
    auto *OldHeader = static_cast<bs_state_header *>(S->getState());
    static_cast<bs_state_header *>(NewS->getState())->cycle = OldHeader->cycle;
    if (L->InputClass && NewL->InputClass)
      llvm::consumeError(NewValues->writeClass(
          *NewL->InputClass, NewS->getInput(),
          Values->readClass(*L->InputClass, S->getInput()), "input"));
    if (L->OutputClass && NewL->OutputClass)
      llvm::consumeError(NewValues->writeClass(
          *NewL->OutputClass, NewS->getOutput(),
          Values->readClass(*L->OutputClass, S->getOutput()), "output"));
    OS << "reloaded; "
       << (Reset.empty() ? std::string("every task keeps its state")
                         : "reset: " + llvm::join(Reset, ", "))
       << "\n";
    if (!Variables.empty() || !Breakpoints.empty())
      OS << "REPL variables and breakpoints were cleared\n";
    for (Slot &V : Variables)
      destroySlot(V);
    Variables.clear();
    for (Breakpoint &B : Breakpoints)
      destroySlot(B.Result);
    Breakpoints.clear();
  }
  // The old session ends before its JIT, the JIT before its compilation.
  S = std::move(NewS);
  Checker.reset();
  Values = std::move(NewValues);
  L = std::move(NewL);
  C = std::move(NewC);
  Checker = std::make_unique<ReplChecker>(C->Ctx, C->Diags, C->Checked,
                                          &C->Natives, L->Entry->Module);
  EntryIndex.reset();
  for (unsigned T = 0; T < L->Layout.Tasks.size(); ++T)
    if (L->Layout.Tasks[T].Decl == L->Entry)
      EntryIndex = T;
  if (FirstLoad && !Opts.WorldLibrary.empty() &&
      !attachWorldLibrary(*C, *L, *S, Opts.WorldLibrary, Opts.CycleLimitMs)) {
    printDiagnostics(C->SM, C->Diags.getDiagnostics(), llvm::errs());
    return false;
  }
  return true;
}

bool Repl::start() {
  std::unique_ptr<Compilation> NewC = compileFiles();
  return NewC && load(std::move(NewC));
}

void Repl::cmdReload(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("reload", Args, Loc))
    return;
  std::unique_ptr<Compilation> NewC = compileFiles();
  if (!NewC || !load(std::move(NewC))) {
    C->Diags.report(llvm::SMLoc(), diag::err_repl_reload_failed);
    flushDiagnostics();
  }
}

//===----------------------------------------------------------------------===//
// Lines of b-script
//===----------------------------------------------------------------------===//

llvm::SMLoc Repl::addBuffer(llvm::StringRef Text) {
  unsigned ID = C->SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(Text, "<repl>"), llvm::SMLoc());
  return llvm::SMLoc::getFromPointer(
      C->SM.getMemoryBuffer(ID)->getBufferStart());
}

Slot Repl::allocateSlot(const Type *T) {
  Slot S;
  S.Ty = T;
  if (const NativeClass *NC = T->getClass()) {
    S.Size = NC->Size ? NC->Size : 1;
    S.Align = NC->Align ? NC->Align : 1;
  } else {
    S.Size = S.Align = T->isBool() ? 1 : T->isString() ? sizeof(void *) : 4;
  }
  S.Ptr = llvm::allocate_buffer(S.Size, S.Align);
  std::memset(S.Ptr, 0, S.Size);
  return S;
}

void Repl::destroySlot(Slot &Sl) {
  if (!Sl.Ptr)
    return;
  // A class value the line constructed there (the REPL's variables and
  // results are never destroyed by generated code).
  if (const NativeClass *NC = Sl.Ty->getClass())
    if (!NC->TriviallyDestructible && L)
      if (void *Destroy = L->JIT->lookup(NC->Destroy))
        reinterpret_cast<void (*)(void *)>(Destroy)(Sl.Ptr);
  llvm::deallocate_buffer(Sl.Ptr, Sl.Size, Sl.Align);
  Sl.Ptr = nullptr;
}

std::optional<Repl::Compiled> Repl::compileLine(llvm::StringRef Text) {
  llvm::SMLoc Start = addBuffer(Text);
  unsigned ID = C->SM.FindBufferContainingLoc(Start);
  BlockStmt *Body = parseReplLine(C->SM, ID, C->Ctx, C->Diags);
  if (C->Diags.hasErrors())
    return std::nullopt;
  Compiled R;
  R.Checked = Checker->check(Body, ++LineNo);
  if (!R.Checked)
    return std::nullopt;
  llvm::DenseMap<const Decl *, uint64_t> Addresses;
  for (size_t I = 0; I < Checker->getVariables().size(); ++I) {
    const VarDecl *V = Checker->getVariables()[I];
    if (I >= Variables.size())
      Variables.push_back(allocateSlot(V->Ty));
    Addresses[V] = reinterpret_cast<uintptr_t>(Variables[I].Ptr);
  }
  if (const VarDecl *Res = R.Checked->Result) {
    R.Result = allocateSlot(Res->Ty);
    Addresses[Res] = reinterpret_cast<uintptr_t>(R.Result.Ptr);
  }
  std::string Symbol = "bs.repl." + std::to_string(LineNo);
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> M =
      emitReplLine(C->Checked, *R.Checked->Func, Symbol, *Ctx,
                   L->JIT->getTriple(), L->JIT->getDataLayout(), Addresses,
                   L->Layout.Sites);
  if (llvm::Error E = verifyGeneratedModule(*M)) {
    llvm::WithColor::error(llvm::errs(), "bsc")
        << "internal error: " << llvm::toString(std::move(E)) << "\n";
    destroySlot(R.Result);
    return std::nullopt;
  }
  if (llvm::Error E = L->JIT->addModule(std::move(M), std::move(Ctx), 0)) {
    llvm::WithColor::error(llvm::errs(), "bsc")
        << "internal error: " << llvm::toString(std::move(E)) << "\n";
    destroySlot(R.Result);
    return std::nullopt;
  }
  R.Fn = reinterpret_cast<void (*)(void *)>(L->JIT->lookup(Symbol));
  return R;
}

std::string Repl::formatValue(const Type *T, const llvm::json::Value &V) {
  // An enum's value by name, unquoted, as the script writes it.
  if (T->isEnum())
    if (std::optional<llvm::StringRef> Name = V.getAsString())
      return Name->str();
  return debug::toJSONString(V);
}

std::string Repl::describe(const Type *T, const void *Addr) {
  return "(" + T->getName().str() + ") " +
         formatValue(T, Values->read(T, Addr));
}

void Repl::evaluate(llvm::StringRef Line) {
  std::optional<Compiled> R = compileLine(Line);
  if (!R) {
    flushDiagnostics();
    return;
  }
  BehaviorSession::Outcome O = S->runGuarded(R->Fn, Opts.CycleLimitMs);
  if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs)) {
    flushDiagnostics();
    OS << "the line was stopped; the state is as it left it\n";
    destroySlot(R->Result);
    return;
  }
  if (R->Result.Ptr)
    OS << describe(R->Result.Ty, R->Result.Ptr) << "\n";
  destroySlot(R->Result);
}

//===----------------------------------------------------------------------===//
// Commands
//===----------------------------------------------------------------------===//

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

std::string Repl::checkBreakpoints() {
  std::vector<debug::Activation> Records =
      debug::takeSnapshot(S->getState(), &S->getInfo());
  for (Breakpoint &B : Breakpoints) {
    switch (B.K) {
    case Breakpoint::Task:
      for (const debug::Activation &A : Records)
        if (A.Task == B.TaskIndex)
          return "breakpoint " + std::to_string(B.Number) + ", " + B.Text +
                 " ran";
      break;
    case Breakpoint::Line:
      for (const debug::Activation &A : Records) {
        const debug::DebugTables::Task &T = L->Tables.Tasks[A.Task];
        if (A.Resume > 0 && T.File == B.File &&
            T.YieldLines[A.Resume - 1] == B.LineNo)
          return "breakpoint " + std::to_string(B.Number) + ", " + T.Name +
                 " waits at " + B.Text;
      }
      break;
    case Breakpoint::Failure:
      for (const debug::Activation &A : Records)
        if (A.State < 0)
          return "breakpoint " + std::to_string(B.Number) + ", " +
                 L->Tables.Tasks[A.Task].Name + " failed";
      break;
    case Breakpoint::Watch: {
      BehaviorSession::Outcome O = S->runGuarded(B.Eval, Opts.CycleLimitMs);
      if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs))
        return "watch " + std::to_string(B.Number) + " was stopped";
      llvm::json::Value Now = Values->read(B.Result.Ty, B.Result.Ptr);
      if (debug::findDifference(B.Last, Now, B.Text)) {
        std::string Why = "watch " + std::to_string(B.Number) + ", " + B.Text +
                          ": " + formatValue(B.Result.Ty, B.Last) + " -> " +
                          formatValue(B.Result.Ty, Now);
        B.Last = std::move(Now);
        return Why;
      }
      break;
    }
    }
  }
  return "";
}

void Repl::rebaseWatches() {
  // A watch stops on what the cycles change, not on what was changed at
  // the prompt since it was last looked at.
  for (Breakpoint &B : Breakpoints)
    if (B.K == Breakpoint::Watch &&
        S->runGuarded(B.Eval, Opts.CycleLimitMs).K ==
            BehaviorSession::Outcome::Completed)
      B.Last = Values->read(B.Result.Ty, B.Result.Ptr);
}

void Repl::reportStop(llvm::StringRef Why) {
  flushDiagnostics();
  uint32_t Cycle = S->getCycle();
  OS << "stopped after cycle " << Cycle << ": " << Why << "\n"
     << "cycle " << Cycle << ": "
     << debug::formatTraceLine(
            L->Tables, debug::takeSnapshot(S->getState(), &S->getInfo()))
     << "\n";
}

void Repl::step(unsigned N, bool Report) {
  rebaseWatches();
  Interrupted = 0;
  auto OldHandler = std::signal(SIGINT, onInterrupt);
  for (unsigned I = 0; I < N; ++I) {
    llvm::json::Value Before =
        L->OutputClass && Report
            ? Values->readClass(*L->OutputClass, S->getOutput())
            : llvm::json::Value(nullptr);
    uint32_t Cycle = S->getCycle() + 1;
    BehaviorSession::Outcome O = S->runCycle(Opts.CycleLimitMs);
    if (!reportOutcome(*C, *L, O, Cycle, Opts.CycleLimitMs)) {
      flushDiagnostics();
      OS << "stopped in cycle " << Cycle << "; the state is as it left it\n";
      break;
    }
    if (Recording) {
      debug::printJSON(*Recording, recordCycle(*Values, *L, *S));
      *Recording << "\n";
      Recording->flush();
    }
    if (Report) {
      OS << "cycle " << Cycle;
      if (L->OutputClass) {
        std::vector<std::string> Changes;
        collectChanges(Before,
                       Values->readClass(*L->OutputClass, S->getOutput()),
                       "output", Changes);
        OS << (Changes.empty() ? ": output unchanged"
                               : ": " + llvm::join(Changes, ", "));
      }
      OS << "\n";
    }
    std::string Why = checkBreakpoints();
    if (Why.empty() && EntryIndex) {
      int32_t State =
          bs_task_state_at(S->getState(), &S->getInfo().tasks[*EntryIndex]);
      if (State < 0)
        Why = "the entry " + L->Entry->getQualifiedName() + " failed";
    }
    if (Why.empty() && Interrupted)
      Why = "interrupted";
    if (!Why.empty()) {
      reportStop(Why);
      break;
    }
  }
  std::signal(SIGINT, OldHandler);
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

void Repl::cmdBreak(llvm::StringRef Args, llvm::SMLoc Loc) {
  Breakpoint B;
  B.Number = NextBreakpoint;
  B.Text = Args.str();
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "break" << "a task, FILE:LINE or 'failure'";
    return;
  }
  if (Args == "failure") {
    B.K = Breakpoint::Failure;
  } else if (auto [File, LineText] = Args.rsplit(':');
             !LineText.empty() && llvm::all_of(LineText, llvm::isDigit)) {
    B.K = Breakpoint::Line;
    B.File = File.str();
    LineText.getAsInteger(10, B.LineNo);
    bool Found = false;
    for (const debug::DebugTables::Task &T : L->Tables.Tasks)
      Found |= T.File == File && llvm::is_contained(T.YieldLines, B.LineNo);
    if (!Found) {
      C->Diags.report(Loc, diag::err_repl_no_yield_at) << File << LineText;
      return;
    }
  } else if (std::optional<unsigned> T = findTask(Args)) {
    B.K = Breakpoint::Task;
    B.TaskIndex = *T;
  } else {
    C->Diags.report(Loc, diag::err_repl_unknown_task) << Args;
    return;
  }
  ++NextBreakpoint;
  OS << "breakpoint " << B.Number << ": " << B.Text << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdWatch(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "watch" << "an expression";
    return;
  }
  std::optional<Compiled> R = compileLine(Args);
  if (!R)
    return;
  if (!R->Result.Ptr) {
    C->Diags.report(Loc, diag::err_repl_watch_void);
    return;
  }
  Breakpoint B;
  B.K = Breakpoint::Watch;
  B.Number = NextBreakpoint++;
  B.Text = Args.str();
  B.Eval = R->Fn;
  B.Result = R->Result;
  BehaviorSession::Outcome O = S->runGuarded(B.Eval, Opts.CycleLimitMs);
  if (!reportOutcome(*C, *L, O, S->getCycle(), Opts.CycleLimitMs)) {
    destroySlot(B.Result);
    return;
  }
  B.Last = Values->read(B.Result.Ty, B.Result.Ptr);
  OS << "watch " << B.Number << ": " << B.Text << " = "
     << formatValue(B.Result.Ty, B.Last) << "\n";
  Breakpoints.push_back(std::move(B));
}

void Repl::cmdBreaks(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (!noArgs("breaks", Args, Loc))
    return;
  if (Breakpoints.empty())
    OS << "no breakpoints\n";
  for (const Breakpoint &B : Breakpoints)
    OS << (B.K == Breakpoint::Watch ? "watch " : "breakpoint ") << B.Number
       << ": " << B.Text << "\n";
}

void Repl::cmdDelete(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    for (Breakpoint &B : Breakpoints)
      destroySlot(B.Result);
    Breakpoints.clear();
    OS << "deleted every breakpoint\n";
    return;
  }
  unsigned N;
  auto It = Breakpoints.end();
  if (!Args.getAsInteger(10, N))
    It = llvm::find_if(Breakpoints,
                       [&](const Breakpoint &B) { return B.Number == N; });
  if (It == Breakpoints.end()) {
    C->Diags.report(Loc, diag::err_repl_no_breakpoint) << Args;
    return;
  }
  destroySlot(It->Result);
  Breakpoints.erase(It);
  OS << "deleted " << Args << "\n";
}

void Repl::cmdRecord(llvm::StringRef Args, llvm::SMLoc Loc) {
  if (Args.empty()) {
    C->Diags.report(Loc, diag::err_repl_missing_argument)
        << "record" << "a file name or 'off'";
    return;
  }
  Recording.reset();
  if (Args == "off") {
    OS << "recording stopped\n";
    return;
  }
  std::error_code EC;
  auto F = std::make_unique<llvm::raw_fd_ostream>(Args, EC,
                                                  llvm::sys::fs::OF_Append);
  if (EC) {
    C->Diags.report(Loc, diag::err_cannot_write_output) << Args << EC.message();
    return;
  }
  Recording = std::move(F);
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
  R.StopAfterCycle = [&] {
    Why = checkBreakpoints();
    return !Why.empty();
  };
  uint32_t Before = S->getCycle();
  rebaseWatches();
  bool OK = runBehavior(*C, *L, *S, R, OS);
  flushDiagnostics();
  if (S->getCycle() == Before) // The file was refused before a cycle ran.
    OS << "replayed no cycle\n";
  else
    OS << "replayed cycles " << Before + 1 << " to " << S->getCycle()
       << (OK ? "; no recorded output differs" : "") << "\n";
  if (!Why.empty())
    reportStop(Why);
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

void Repl::cmdHelp(llvm::StringRef, llvm::SMLoc) {
  for (const CommandInfo &Cmd : getCommands()) {
    std::string Head = (":" + llvm::Twine(Cmd.Name) +
                        (*Cmd.Args ? " " + llvm::Twine(Cmd.Args) : ""))
                           .str();
    OS << "  " << llvm::left_justify(Head, 30) << Cmd.Help << "\n";
  }
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
  uint32_t Before = S->getCycle();
  step(N, /*Report=*/false);
  if (S->getCycle() - Before == N)
    OS << "ran " << N << " cycles to cycle " << S->getCycle() << "\n";
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
      {"break", "TASK|FILE:LINE|failure",
       "stop after a cycle in which TASK ran, a task waits at a yield on "
       "FILE:LINE, or a task failed",
       &Repl::cmdBreak},
      {"watch", "EXPR", "stop after a cycle that changed the value of EXPR",
       &Repl::cmdWatch},
      {"breaks", "", "list the breakpoints and watches", &Repl::cmdBreaks},
      {"delete", "[N]", "delete breakpoint N, or all", &Repl::cmdDelete},
      {"reload", "",
       "recompile the edited files, keeping the state of every task whose "
       "frame did not change",
       &Repl::cmdReload},
      {"record", "FILE|off", "append each cycle's input and output to FILE",
       &Repl::cmdRecord},
      {"replay", "FILE",
       "run a recording: feed its inputs, compare outputs",
       &Repl::cmdReplay},
      {"graph", "",
       "the call graph as DOT, the tasks of the last cycle filled",
       &Repl::cmdGraph},
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

bool Repl::handleLine(llvm::StringRef Line) {
  llvm::StringRef Text = Line.trim();
  if (Text.empty() || Text.starts_with("#"))
    return true;
  if (!Text.consume_front(":")) {
    evaluate(Text);
    OS.flush();
    return true;
  }
  llvm::SMLoc Loc = addBuffer(":" + Text.str());
  auto [Name, Args] = Text.split(' ');
  if (Name == "quit" || Name == "q")
    return false;
  command(Name, Args.trim(), Loc);
  OS.flush();
  return true;
}

std::vector<llvm::LineEditor::Completion>
Repl::complete(llvm::StringRef Buffer, size_t Pos) const {
  std::vector<llvm::LineEditor::Completion> Result;
  llvm::StringRef Before = Buffer.substr(0, Pos);
  size_t WordStart = Before.find_last_of(" (,=+-*/<>!&|");
  llvm::StringRef Word =
      WordStart == llvm::StringRef::npos ? Before : Before.substr(WordStart + 1);
  std::vector<std::string> Candidates;
  if (Word.starts_with(":")) {
    for (const CommandInfo &Cmd : getCommands())
      Candidates.push_back(":" + std::string(Cmd.Name));
  } else if (Word.contains('.')) {
    // Members of `input.` / `output.` chains, by the world's classes.
    auto [Base, Partial] = Word.rsplit('.');
    const NativeClass *Class = nullptr;
    llvm::SmallVector<llvm::StringRef, 4> Parts;
    Base.split(Parts, '.');
    if (Parts[0] == "input")
      Class = L->InputClass;
    else if (Parts[0] == "output")
      Class = L->OutputClass;
    for (size_t I = 1; Class && I < Parts.size(); ++I) {
      const NativeFunction *M = Class->findMember(Parts[I]);
      Class = M ? M->Result.TheClass : nullptr;
    }
    if (Class)
      for (const NativeFunction &M : Class->Members)
        Candidates.push_back((Base + "." + M.Name).str());
  } else {
    for (const debug::DebugTables::Task &T : L->Tables.Tasks)
      Candidates.push_back(T.ShortName);
    for (const ModuleAST *M : C->Checked.Modules)
      Candidates.push_back(M->Name + "::");
    for (const NativeModule *M : C->Checked.NativeModules)
      Candidates.push_back(M->Name + "::");
    Candidates.insert(Candidates.end(), {"input", "output"});
  }
  for (const std::string &Cand : Candidates)
    if (llvm::StringRef(Cand).starts_with(Word))
      Result.emplace_back(Cand.substr(Word.size()), Cand);
  return Result;
}

//===----------------------------------------------------------------------===//
// Entry
//===----------------------------------------------------------------------===//

int bsc::runRepl(const ReplOptions &Opts, llvm::raw_ostream &OS) {
  Repl R(Opts, OS);
  if (!R.start())
    return 1;
  // A terminal gets a prompt with history and completion; anything else
  // (a pipe, a file, --batch) runs as a batch with no prompt.
  std::unique_ptr<llvm::MemoryBuffer> Batch;
  if (!Opts.BatchFile.empty()) {
    auto Buf = llvm::MemoryBuffer::getFile(Opts.BatchFile);
    if (!Buf) {
      llvm::WithColor::error(llvm::errs(), "bsc")
          << "cannot open '" << Opts.BatchFile
          << "': " << Buf.getError().message() << "\n";
      return 1;
    }
    Batch = std::move(*Buf);
  } else if (!llvm::sys::Process::StandardInIsUserInput()) {
    // Line by line, answering each before reading the next, so that a
    // program can hold a conversation through a pipe.
    std::string Line;
    char Buf[4096];
    while (std::fgets(Buf, sizeof Buf, stdin)) {
      Line += Buf;
      if (Line.back() != '\n' && !std::feof(stdin))
        continue;
      if (!R.handleLine(llvm::StringRef(Line).rtrim("\r\n")))
        break;
      Line.clear();
    }
    return 0;
  }
  if (Batch) {
    llvm::SmallVector<llvm::StringRef, 0> Lines;
    Batch->getBuffer().split(Lines, '\n');
    for (llvm::StringRef Line : Lines)
      if (!R.handleLine(Line.rtrim('\r')))
        break;
    return 0;
  }
  llvm::SmallString<256> History;
  if (llvm::sys::path::home_directory(History))
    llvm::sys::path::append(History, ".bsc_history");
  llvm::LineEditor LE("bsc", History);
  LE.setPrompt("bsc> ");
  LE.setListCompleter([&R](llvm::StringRef Buffer, size_t Pos) {
    return R.complete(Buffer, Pos);
  });
  OS << "bsc repl: ':help' lists the commands, ':quit' leaves\n";
  while (std::optional<std::string> Line = LE.readLine())
    if (!R.handleLine(*Line))
      break;
  return 0;
}

//===- Runner.cpp - loading a behavior into the JIT; `bsc run` ------------===//
//
// The same path serves `bsc run` and the REPL: generate the behavior for
// the host with probes (CodeGenOptions::Probes), link the standard modules
// and bindings as a program links them, start a session, and then run
// cycles under the session's guard. Everything the runner prints about the
// behavior (traces, outputs, recordings) goes through bsc/Debug.
//
//===----------------------------------------------------------------------===//
#include "bsc/REPL/Debugger.h"
#include "bsc/Basic/JSON.h"
#include "bsc/Bind/Bind.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Debug/Values.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/Support/DynamicLibrary.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/ToolOutputFile.h"
#include <csignal>

using namespace bsc;

/// The thunks and descriptors `M` imports from the binding modules.
static std::vector<std::string> getBindingImports(Compilation &C,
                                                  const llvm::Module &M) {
  llvm::StringSet<> BindingSymbols;
  for (const std::string &S : bind::getBindingSymbols(C.Checked.BindingModules))
    BindingSymbols.insert(S);
  std::vector<std::string> Imports;
  for (const llvm::GlobalValue &GV : M.global_values())
    if (GV.isDeclaration() && BindingSymbols.contains(GV.getName()))
      Imports.push_back(GV.getName().str());
  return Imports;
}

bool bsc::checkBindingImports(Compilation &C, const llvm::Module &M,
                                llvm::ArrayRef<std::string> BindObjects) {
  std::vector<std::string> Missing =
      bind::findUndefinedSymbols(BindObjects, getBindingImports(C, M));
  for (const std::string &S : Missing)
    C.Diags.report(llvm::SMLoc(), diag::err_stale_binding_symbol)
        << llvm::demangle(S);
  return Missing.empty();
}

/// Reports the link errors that are the user's to fix (a library the loader
/// refuses, a function no --bind file defines) and returns the rest.
static llvm::Error reportBindingLinkErrors(Compilation &C, llvm::Error E) {
  return llvm::handleErrors(
      std::move(E),
      [&](const BindingLoadError &BL) {
        C.Diags.report(llvm::SMLoc(), diag::err_bind_load)
            << BL.Path << BL.Message;
      },
      [&](const MissingSymbolsError &MS) {
        for (const std::string &S : MS.Symbols)
          C.Diags.report(llvm::SMLoc(), diag::err_jit_undefined_symbol)
              << llvm::demangle(S);
      });
}

llvm::Expected<std::unique_ptr<LoadedBehavior>>
bsc::loadBehavior(Compilation &C, const CallableDecl &Entry,
                  const LoadOptions &Opts) {
  auto L = std::make_unique<LoadedBehavior>();
  auto JITOrErr = BehaviorJIT::create(Opts.OptLevel, Opts.DebugInfo);
  if (!JITOrErr)
    return JITOrErr.takeError();
  L->JIT = std::move(*JITOrErr);
  BehaviorJIT &JIT = *L->JIT;

  CodeGenOptions CGOpts;
  CGOpts.BehaviorName = C.Modules.front()->Name;
  CGOpts.Probes = true;
  CGOpts.ExternalFunctions = Opts.ExternalFunctions;
  CGOpts.DebugInfo = Opts.DebugInfo;
  CGOpts.Sources = &C.SM;
  CGOpts.OptLevel = Opts.OptLevel;
  CGOpts.CycleBudget = Opts.CycleBudget;
  CGOpts.Explain = Opts.Explain;
  // The JIT calls the entry only.
  CGOpts.Exports.emplace();
  if (isCallableFromC(Entry))
    CGOpts.Exports->push_back(&Entry);
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> M = emitLLVM(
      C.Checked, *Ctx, JIT.getTriple(), JIT.getDataLayout(), CGOpts, L->Layout);
  if (llvm::Error E = verifyGeneratedModule(*M))
    return E;
  L->Entry = &Entry;
  L->EntrySymbol = getEntrySymbol(CGOpts.BehaviorName, Entry);
  L->Tables = debug::buildDebugTables(C.Checked, L->Layout, C.SM);
  if (!checkBindingImports(C, *M, Opts.BindObjects))
    return nullptr;
  // The standard modules' thunks from the host runtime archive, then the
  // --bind objects, as a program links them.
  for (const std::string &Path : Opts.StandardModules)
    if (llvm::Error E = JIT.addArchive(Path))
      return E;
  for (const std::string &Path : Opts.BindObjects)
    if (llvm::Error E = JIT.addObjectFile(Path)) {
      if (llvm::Error Internal = reportBindingLinkErrors(C, std::move(E)))
        return Internal;
      return nullptr;
    }
  // Link the bindings the behavior calls before its own code: a function
  // that a binding object calls and no --bind file defines (it is in
  // another object of the robot build) is the user's to fix, and the
  // behavior must never run with it unresolved.
  if (llvm::Error E = JIT.link(getBindingImports(C, *M))) {
    if (llvm::Error Internal = reportBindingLinkErrors(C, std::move(E)))
      return Internal;
    return nullptr;
  }
  if (llvm::Error E = JIT.addModule(std::move(M), std::move(Ctx), Opts.OptLevel))
    return E;
  if (const NativeModule *World = C.Checked.World) {
    L->InputClass = World->Input;
    L->OutputClass = World->Output;
    for (auto [Class, Obj] : {std::pair(World->Input, &L->Input),
                              std::pair(World->Output, &L->Output)})
      if (Class)
        *Obj = {size_t(Class->Size), size_t(Class->Align), Class->Construct,
                Class->TriviallyDestructible ? "" : Class->Destroy};
  }
  return L;
}

llvm::Expected<std::unique_ptr<BehaviorSession>>
bsc::startSession(Compilation &C, LoadedBehavior &L) {
  auto S = BehaviorSession::start(*L.JIT, L.Layout.InfoSymbol, L.EntrySymbol,
                                  L.Input, L.Output);
  if (S)
    return S;
  // A stale binding module is the user's to fix, not an internal error.
  llvm::Error E = llvm::handleErrors(S.takeError(), [&](const StaleBindingError &SB) {
    C.Diags.report(llvm::SMLoc(), diag::err_stale_binding_module) << SB.Module;
  });
  if (E)
    return E;
  return nullptr;
}

bool bsc::attachWorldLibrary(Compilation &C, const LoadedBehavior &L,
                             BehaviorSession &S, llvm::StringRef Path,
                             unsigned LimitMs) {
  // By absolute path, as --bind loads a library: dlopen looks for a bare
  // name in the library path, not in the current folder.
  llvm::SmallString<256> Abs(Path);
  llvm::sys::fs::make_absolute(Abs);
  std::string Err;
  llvm::sys::DynamicLibrary Lib =
      llvm::sys::DynamicLibrary::getPermanentLibrary(Abs.c_str(), &Err);
  if (!Lib.isValid()) {
    C.Diags.report(llvm::SMLoc(), diag::err_world_load) << Path << Err;
    return false;
  }
  WorldHooks H;
  auto Find = [&](const char *Name, auto &Slot, bool Required) {
    Slot = reinterpret_cast<std::remove_reference_t<decltype(Slot)>>(
        Lib.getAddressOfSymbol(Name));
    if (!Slot && Required)
      C.Diags.report(llvm::SMLoc(), diag::err_world_missing_hook)
          << Path << Name;
    return Slot || !Required;
  };
  bool OK = Find("bs_world_init", H.Init, true);
  OK &= Find("bs_world_begin", H.Begin, true);
  Find("bs_world_end", H.End, false);
  Find("bs_world_exit", H.Exit, false);
  if (!OK)
    return false;
  return reportOutcome(C, L, S.attachWorld(H, LimitMs), 0, LimitMs);
}

int bsc::openWorldOutput(Compilation &C, llvm::StringRef Path) {
  int Fd;
  if (std::error_code EC = llvm::sys::fs::openFileForWrite(Path, Fd)) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    return -1;
  }
  return Fd;
}

/// "SIGSEGV (segmentation fault)".
static std::string describeSignal(int Sig) {
  const char *Name = Sig == SIGSEGV   ? "SIGSEGV"
                     : Sig == SIGBUS  ? "SIGBUS"
                     : Sig == SIGFPE  ? "SIGFPE"
                     : Sig == SIGILL  ? "SIGILL"
                                      : "signal";
  return std::string(Name) + " (" + strsignal(Sig) + ")";
}

bool bsc::reportOutcome(Compilation &C, const LoadedBehavior &L,
                        const BehaviorSession::Outcome &O, uint32_t Cycle,
                        unsigned LimitMs) {
  auto Site = [&](uint32_t N) -> const DebugSite * {
    return N && N <= L.Layout.Sites.size() ? &L.Layout.Sites[N - 1] : nullptr;
  };
  if (O.K != BehaviorSession::Outcome::Completed && O.WorldHook) {
    std::string When = Cycle ? "cycle " + std::to_string(Cycle)
                             : std::string("before the first cycle");
    if (O.K == BehaviorSession::Outcome::TimedOut)
      C.Diags.report(llvm::SMLoc(), diag::err_world_runaway)
          << When << LimitMs << O.WorldHook;
    else
      C.Diags.report(llvm::SMLoc(), diag::err_world_crash)
          << When << describeSignal(O.Signal) << O.WorldHook;
    return false;
  }
  switch (O.K) {
  case BehaviorSession::Outcome::Completed:
    return true;
  case BehaviorSession::Outcome::TimedOut:
    if (const DebugSite *N = Site(O.NativeSite))
      C.Diags.report(N->Loc, diag::err_cycle_runaway_native)
          << Cycle << LimitMs << N->Native;
    else if (const DebugSite *Loop = Site(O.LoopSite))
      C.Diags.report(Loop->Loc, diag::err_cycle_runaway)
          << Cycle << LimitMs << Loop->In->getQualifiedName();
    else // Only C++ the probes do not mark (life-cycle thunks) is left.
      C.Diags.report(llvm::SMLoc(), diag::err_cycle_runaway_native)
          << Cycle << LimitMs << "a constructor or destructor";
    return false;
  case BehaviorSession::Outcome::Crashed:
    if (const DebugSite *N = Site(O.NativeSite)) {
      C.Diags.report(N->Loc, diag::err_cycle_crash_native)
          << Cycle << describeSignal(O.Signal) << N->Native;
      // The likeliest cause when C++ that reads bs::Context::user() runs
      // without a world: nothing attached a user pointer.
      if (N->TakesContext && O.NullUser)
        C.Diags.report(N->Loc, diag::note_null_user_pointer) << N->Native;
    } else
      C.Diags.report(llvm::SMLoc(), diag::err_cycle_crash_native)
          << Cycle << describeSignal(O.Signal) << "a constructor or destructor";
    return false;
  }
  return true;
}

namespace {
/// One line of a replay file, checked.
struct ReplayLine {
  llvm::SMLoc Loc; ///< Its first character.
  llvm::json::Value Parsed = nullptr;
  const llvm::json::Value *get(llvm::StringRef Key) const {
    return Parsed.getAsObject()->get(Key);
  }
};

/// Reads a JSONL replay file into the SourceMgr (so that its errors have
/// carets) and checks the shape of each line. Returns false after reporting.
bool readReplay(Compilation &C, const LoadedBehavior &L, llvm::StringRef Path,
                std::vector<ReplayLine> &Lines) {
  unsigned ID = addSourceFile(C, Path, MaxRecordingMiB);
  if (!ID)
    return false;
  llvm::StringRef Text = C.SM.getMemoryBuffer(ID)->getBuffer();
  bool OK = true;
  llvm::SmallVector<llvm::StringRef, 0> Raw;
  Text.split(Raw, '\n');
  for (llvm::StringRef R : Raw) {
    llvm::SMLoc Loc = llvm::SMLoc::getFromPointer(R.data());
    if (R.trim().empty())
      continue;
    std::optional<llvm::json::Value> V = parseJSONLine(C.Diags, R);
    if (!V) {
      OK = false;
      continue;
    }
    ReplayLine Line{Loc, std::move(*V)};
    const llvm::json::Object *O = Line.Parsed.getAsObject();
    if (!O) {
      C.Diags.report(Loc, diag::err_replay_not_object);
      OK = false;
      continue;
    }
    for (const auto &KV : *O) {
      llvm::StringRef K = KV.first;
      if (K == "input" || K == "output") {
        const NativeClass *Class = K == "input" ? L.InputClass : L.OutputClass;
        if (!Class) {
          C.Diags.report(Loc, diag::err_replay_no_world) << K;
          OK = false;
        }
      } else if (K != "cycle" && K != "tasks") {
        C.Diags.report(Loc, diag::err_replay_unknown_key) << K;
        OK = false;
      }
    }
    Lines.push_back(std::move(Line));
  }
  if (OK && Lines.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_replay_empty) << Path;
    OK = false;
  }
  return OK;
}
} // namespace

/// The cycle's hierarchy as a recording keeps it: depth first, each task
/// with its state, the yield it waits at, its parent's position and its
/// parameters and (unless it finished) locals.
static llvm::json::Array recordTasks(debug::ValueIO &Values,
                                     const LoadedBehavior &L,
                                     const BehaviorSession &S) {
  const auto *State = static_cast<const char *>(S.getState());
  llvm::json::Array Tasks;
  for (const debug::RecordedTask &F : debug::listActiveTasks(
           L.Tables, debug::takeSnapshot(State, &S.getInfo()))) {
    llvm::json::Object Task{{"task", L.Tables.Tasks[F.Record.Task].Name},
                            {"state", F.State},
                            {"parent", F.Parent}};
    if (!F.Place.empty())
      Task["at"] = F.Place;
    llvm::json::Object Params, Locals;
    for (const BehaviorLayout::FrameField &Field :
         L.Layout.Tasks[F.Record.Task].Fields) {
      bool IsParam = llvm::isa<ParamDecl>(Field.D);
      // A finished task's locals are gone (the next call starts afresh).
      if (!IsParam && F.Record.Resume == 0)
        continue;
      llvm::json::Object &Into = IsParam ? Params : Locals;
      // Locals of one name in different blocks: `x`, `x#2`, ... in the
      // frame's order.
      std::string Name = Field.D->getName().Name.str();
      for (unsigned N = 2; Into.find(Name) != Into.end(); ++N)
        Name = Field.D->getName().Name.str() + "#" + std::to_string(N);
      Into[Name] = Values.read(Field.Ty, State + Field.Offset);
    }
    if (!Params.empty())
      Task["params"] = std::move(Params);
    if (!Locals.empty())
      Task["locals"] = std::move(Locals);
    Tasks.push_back(std::move(Task));
  }
  return Tasks;
}

llvm::json::Value bsc::recordCycle(debug::ValueIO &Values,
                                   const LoadedBehavior &L,
                                   const BehaviorSession &S) {
  llvm::json::Object Rec{{"cycle", int64_t(S.getCycle())}};
  if (L.InputClass)
    Rec["input"] = Values.readClass(*L.InputClass, S.getInput());
  if (L.OutputClass)
    Rec["output"] = Values.readClass(*L.OutputClass, S.getOutput());
  Rec["tasks"] = recordTasks(Values, L, S);
  return Rec;
}

/// `--cycle-budget`: a warning at the loop that ran out first (the
/// behavior went on: its task failed), with how many cycles ran out.
static void reportBudgetRanOut(Compilation &C, const LoadedBehavior &L,
                               const BehaviorSession &S, uint32_t Cycle,
                               const bs_loop_info &Loop, unsigned RanOut) {
  const bs_budget_layout &Budget = S.getInfo().budget;
  size_t Index = &Loop - Budget.loops;
  const BehaviorLayout::BudgetLayout::Loop &Where = L.Layout.Budget.Loops[Index];
  C.Diags.report(Where.Loc, llvm::isa<TaskDecl>(Where.Owner)
                                ? diag::warn_budget_ran_out_task
                                : diag::warn_budget_ran_out_func)
      << Cycle << Budget.budget << Where.Owner->getQualifiedName();
  if (RanOut > 1)
    C.Diags.report(Where.Loc, diag::note_budget_ran_out_count) << RanOut;
}

/// A replayed cycle whose output differs from the line's: one error, then
/// a note per field that differs, at the line. Neither echoes it: a
/// recording fills it with every output member. Returns whether it
/// reported.
static bool reportMismatch(Compilation &C, const ReplayLine &Line,
                           uint32_t Cycle, const llvm::json::Value &Recorded,
                           const llvm::json::Value &Got) {
  std::vector<debug::Difference> Ds =
      debug::findDifferences(Recorded, Got, "output");
  if (Ds.empty())
    return false;
  C.Diags.report(Line.Loc, diag::err_replay_mismatch) << Cycle << NoSourceLine();
  for (const debug::Difference &D : Ds)
    C.Diags.report(Line.Loc, diag::note_replay_difference)
        << D.Path << D.Recorded << D.Got << NoSourceLine();
  return true;
}

bool bsc::runBehavior(Compilation &C, LoadedBehavior &L, BehaviorSession &S,
                      const RunOptions &Opts, llvm::raw_ostream &OS) {
  std::vector<ReplayLine> Replay;
  if (!Opts.ReplayPath.empty()) {
    if (Opts.CyclesGiven) {
      C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
          << "--cycles" << "--replay";
      return false;
    }
    if (!readReplay(C, L, Opts.ReplayPath, Replay))
      return false;
  }
  std::unique_ptr<llvm::ToolOutputFile> Record;
  if (!Opts.RecordPath.empty()) {
    std::error_code EC;
    Record = std::make_unique<llvm::ToolOutputFile>(Opts.RecordPath, EC,
                                                    llvm::sys::fs::OF_Text);
    if (EC) {
      C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
          << Opts.RecordPath << EC.message();
      return false;
    }
  }

  debug::ValueIO Values([&](llvm::StringRef Sym) { return L.JIT->lookup(Sym); });
  const TaskDecl *EntryTask = llvm::dyn_cast<TaskDecl>(L.Entry);
  // The entry task's place in the task table, whose state tells a failure.
  std::optional<unsigned> EntryIndex;
  for (unsigned T = 0; T < L.Layout.Tasks.size(); ++T)
    if (L.Layout.Tasks[T].Decl == EntryTask)
      EntryIndex = T;
  bool ReportedFailure = false;
  // `--cycle-budget`: the first cycle that ran out, and how many did.
  std::optional<std::pair<uint32_t, const bs_loop_info *>> FirstRanOut;
  unsigned RanOut = 0;
  debug::TraceFilter Traces(Opts.Trace);

  unsigned Cycles = Replay.empty() ? Opts.Cycles : Replay.size();
  for (unsigned I = 0; I < Cycles; ++I) {
    uint32_t Cycle = S.getCycle() + 1;
    const ReplayLine *Line = Replay.empty() ? nullptr : &Replay[I];
    if (const llvm::json::Value *In = Line ? Line->get("input") : nullptr)
      if (llvm::Error E =
              Values.writeClass(*L.InputClass, S.getInput(), *In, "input")) {
        C.Diags.report(Line->Loc, diag::err_replay_value)
            << llvm::toString(std::move(E));
        return false;
      }
    BehaviorSession::Outcome O = S.runCycle(Opts.CycleLimitMs);
    if (!reportOutcome(C, L, O, Cycle, Opts.CycleLimitMs))
      return false;
    if (const bs_loop_info *Loop = bs_budget_ran_out(S.getState(), &S.getInfo())) {
      ++RanOut;
      if (!FirstRanOut)
        FirstRanOut = {Cycle, Loop};
    }

    // The objects are read as JSON only for what asks for them: a plain
    // run of many cycles does no more than the robot would.
    const llvm::json::Value *Recorded = Line ? Line->get("output") : nullptr;
    llvm::json::Value Rec = Record ? recordCycle(Values, L, S) : nullptr;
    llvm::json::Value Out = nullptr;
    if (Record && L.OutputClass)
      Out = *Rec.getAsObject()->get("output");
    else if (L.OutputClass && (Opts.PrintOutput || Recorded))
      Out = Values.readClass(*L.OutputClass, S.getOutput());
    if (Opts.Trace != debug::TraceMode::Off) {
      std::string Trace = debug::formatTraceLine(
          L.Tables, debug::takeSnapshot(S.getState(), &S.getInfo()));
      if (Traces.shouldPrint(Trace))
        OS << "cycle " << Cycle << ": " << Trace << "\n";
    }
    if (Opts.PrintOutput && L.OutputClass) {
      debug::printJSON(OS, llvm::json::Object{{"cycle", int64_t(Cycle)},
                                              {"output", Out}});
      OS << "\n";
    }
    OS.flush();
    if (Record) {
      debug::printJSON(Record->os(), Rec);
      Record->os() << "\n";
    }
    if (EntryIndex && !ReportedFailure) {
      int32_t State =
          bs_task_state_at(S.getState(), &S.getInfo().tasks[*EntryIndex]);
      if (State < 0) {
        C.Diags.report(L.Entry->getLoc(), diag::warn_entry_failed)
            << L.Entry->getQualifiedName() << State << Cycle;
        ReportedFailure = true;
      }
    }
    if (Recorded && reportMismatch(C, *Line, Cycle, *Recorded, Out)) {
      if (Record)
        Record->keep();
      return false;
    }
    if (Opts.StopAfterCycle && Opts.StopAfterCycle())
      break;
  }
  if (FirstRanOut)
    reportBudgetRanOut(C, L, S, FirstRanOut->first, *FirstRanOut->second,
                       RanOut);
  if (Record)
    Record->keep();
  return true;
}

//===- JIT.h - running a behavior on the host with ORC LLJIT ---*- C++ -*-===//
//
// `bsc run`: the development machine runs a behavior in a JIT, cycle by
// cycle, with the same runtime shim and the same generated code as a
// compiled program, so it prints exactly what the robot program would.
// The runtime shim is linked into bsc and handed to the JIT by address;
// the standard modules' thunks (`io`) come from the host runtime archive,
// loaded like a --bind archive. Without --bind objects the generated code
// cannot reach anything else in the bsc process.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_JIT_JIT_H
#define BSC_JIT_JIT_H

#include "llvm/IR/DataLayout.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/ADT/STLFunctionalExtras.h"
#include "llvm/Support/Error.h"
#include "llvm/TargetParser/Triple.h"
#include "bsc/JIT/Boundary.h"
#include "bscript/bscript.h"
#include <memory>
#include <string>

namespace llvm::orc {
class LLJIT;
} // namespace llvm::orc

namespace bsc {

/// bs_state_init refused the behavior because the binding module `Module`
/// linked into the JIT is not the one the behavior was compiled against
/// (its descriptor hash differs). A user-facing error, not an internal one.
class StaleBindingError : public llvm::ErrorInfo<StaleBindingError> {
public:
  static char ID;
  std::string Module;
  explicit StaleBindingError(std::string Module) : Module(std::move(Module)) {}
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

/// A --bind shared library that the JIT cannot load (dlopen failed: a
/// missing dependency, an unresolvable symbol); `Message` is the loader's.
class BindingLoadError : public llvm::ErrorInfo<BindingLoadError> {
public:
  static char ID;
  std::string Path, Message;
  BindingLoadError(std::string Path, std::string Message)
      : Path(std::move(Path)), Message(std::move(Message)) {}
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

/// Symbols that linking the binding objects into the JIT needed and nothing
/// defined (an object given with --bind calls a function another object
/// defines). A user-facing error, not an internal one.
class MissingSymbolsError : public llvm::ErrorInfo<MissingSymbolsError> {
public:
  static char ID;
  std::vector<std::string> Symbols; ///< Mangled, in the order found.
  explicit MissingSymbolsError(std::vector<std::string> Symbols)
      : Symbols(std::move(Symbols)) {}
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

/// One JIT session on the host: a DataLayout to generate code for, then one
/// module to run.
class BehaviorJIT {
public:
  /// Creates the JIT for the host CPU. Failures here and below are not the
  /// user's mistakes (the program was checked), so they are llvm::Errors
  /// that the driver prints as internal errors.
  /// `OptLevel` 0 also selects LLVM's fastest code generation.
  /// `Debuggable`: every object linked is registered with gdb's JIT
  /// interface (__jit_debug_register_code), so gdb attached to bsc sees
  /// the behavior's DWARF.
  static llvm::Expected<std::unique_ptr<BehaviorJIT>>
  create(unsigned OptLevel, bool Debuggable = false);
  ~BehaviorJIT();

  const llvm::Triple &getTriple() const { return Triple; }
  const llvm::DataLayout &getDataLayout() const { return DL; }

  /// Optimises `M` at `OptLevel` and adds it.
  llvm::Error addModule(std::unique_ptr<llvm::Module> M,
                        std::unique_ptr<llvm::LLVMContext> Ctx,
                        unsigned OptLevel);

  /// Adds a binding object (.o), archive (.a) or shared library built for
  /// the host: the thunks generated code calls. Their own references
  /// (libstdc++, libm) resolve against this process. A shared library that
  /// cannot be loaded gives a BindingLoadError.
  llvm::Error addObjectFile(llvm::StringRef Path);

  /// Loads shared library `Path` into this process and resolves generated
  /// code's references from what it exports. All its symbols are bound as
  /// it loads: one that nothing defines is a MissingSymbolsError.
  llvm::Error addSharedLibrary(llvm::StringRef Path);

  /// Adds the members of archive `Path` on demand, as a static linker does,
  /// without this process's libraries: for the runtime archive, whose
  /// standard modules' thunks need nothing but the runtime shim.
  llvm::Error addArchive(llvm::StringRef Path);

  /// The storage `bsc run` provides for `input` or `output`: the world
  /// module's registered class (size 0: the behavior declares none).
  struct GlobalObject {
    size_t Size = 0;
    size_t Align = 1;
    std::string Construct; ///< Construct thunk symbol, or empty.
    std::string Destroy;   ///< Destroy thunk symbol; empty if trivial.
  };

  /// The address of `Symbol` in the JIT, or null if nothing defines it.
  void *lookup(llvm::StringRef Symbol);

  /// Links what defines `Symbols` (the binding objects' thunks and
  /// descriptors a behavior imports) and everything that needs in turn.
  /// A symbol nothing defines on the way gives a MissingSymbolsError.
  llvm::Error link(llvm::ArrayRef<std::string> Symbols);

  /// The errors linking reported beside a lookup's result (ORC reports a
  /// failed link to the session, not always to the lookup that caused it),
  /// taken: a MissingSymbolsError for symbols nothing defines, else the
  /// first error, else success.
  llvm::Error takeLinkErrors();

private:
  friend class BehaviorSession;
  BehaviorJIT() = default;
  /// The session's error reporter: keeps the errors for takeLinkErrors.
  void recordLinkError(llvm::Error E);
  std::vector<std::string> MissingSymbols;
  std::vector<std::string> OtherLinkErrors;

  std::unique_ptr<llvm::orc::LLJIT> J;
  llvm::Triple Triple;
  llvm::DataLayout DL{""};
  std::string CPU;
  bool ProcessSymbols = false; ///< The process-symbol generator is added.
};

/// The hooks of a world library (`bsc run --world LIB.so`, docs/repl.md
/// "A closed loop"): C functions the library exports. Init's result
/// becomes the state's user pointer (bs_state_set_user); Begin runs before
/// each cycle's entry, End after it (Cycle: the behavior's cycle number,
/// the first is 1); Exit, if any, when the session ends.
struct WorldHooks {
  void *(*Init)(void *Input, void *Output) = nullptr;
  void (*Begin)(void *User, void *Input, void *Output, uint32_t Cycle) = nullptr;
  void (*End)(void *User, const void *Input, void *Output,
              uint32_t Cycle) = nullptr;
  void (*Exit)(void *User) = nullptr;
  /// Optional: right after Init, which robot of how many this world is
  /// (`--robots N`; robot 0 of 1 without), so that N robot worlds differ.
  void (*Robot)(void *User, unsigned Robot, unsigned Robots) = nullptr;
  /// A team world (bscript/world.h, `--robots N`): one library simulates
  /// every robot. TeamInit's result is the team's pointer, which the other
  /// team hooks get with the robot's index (0 to N-1); TeamRobot, if any,
  /// gives each robot's user pointer (else the team's).
  void *(*TeamInit)(unsigned Robots) = nullptr;
  void *(*TeamRobot)(void *Team, unsigned Robot, void *Input,
                     void *Output) = nullptr;
  void (*TeamBegin)(void *Team, unsigned Robot, void *Input, void *Output,
                    uint32_t Cycle) = nullptr;
  void (*TeamEnd)(void *Team, unsigned Robot, const void *Input, void *Output,
                  uint32_t Cycle) = nullptr;
  void (*TeamExit)(void *Team) = nullptr;
  bool isTeam() const { return TeamInit != nullptr; }
};

/// A behavior running in the JIT: its state and its `input` and `output`
/// objects, advanced one cycle at a time by `bsc run` or the REPL. Each cycle
/// runs under a guard: a watchdog stops a cycle that runs longer than its
/// limit (a loop without `yield`), and a signal raised in registered C++
/// (SIGSEGV, ...) ends the cycle instead of the process.
/// Either leaves the state as it was at that moment; the driver reports it
/// and stops. The guard uses SIGALRM and the fault signals while the session
/// lives, and puts the previous handlers back at its end.
class BehaviorSession {
public:
  /// Initialises a state for the behavior whose info struct is `InfoSymbol`
  /// and the `Input`/`Output` objects (zeroed, then constructed). A stale
  /// binding module gives a StaleBindingError.
  static llvm::Expected<std::unique_ptr<BehaviorSession>>
  start(BehaviorJIT &JIT, llvm::StringRef InfoSymbol,
        llvm::StringRef EntrySymbol, const BehaviorJIT::GlobalObject &Input,
        const BehaviorJIT::GlobalObject &Output);
  /// Destroys the state (bs_state_destroy), then the objects.
  ~BehaviorSession();

  /// How a cycle ended.
  struct Outcome {
    /// Diverged: a cycle run from a record parted from it (Divergence
    /// says how); it completed, with whatever its calls returned after.
    enum Kind { Completed, TimedOut, Crashed, Diverged } K = Completed;
    std::string Divergence;
    int Signal = 0;          ///< Crashed: the signal.
    uint32_t LoopSite = 0;   ///< The last loop probe (BehaviorLayout::Sites).
    uint32_t NativeSite = 0; ///< The binding being called, if any.
    /// The world library's hook that was running (`bs_world_begin`...),
    /// or null if the behavior was.
    const char *WorldHook = nullptr;
    /// The state's user pointer (bs::Context::user()) was null: a crash in
    /// C++ that takes the context may have read through it.
    bool NullUser = false;
  };
  /// Begins the next cycle and calls the entry; a cycle still running after
  /// `LimitMs` milliseconds (0: no limit) is stopped. Without `WithWorld`
  /// the world's hooks are not called (a replay sets `input` itself).
  /// With keepCalls on, what the cycle observed of its calls into
  /// registered C++ (bsc/JIT/Boundary.h), the world's end hook's among
  /// them, is kept with the input the entry saw (getLastCalls).
  Outcome runCycle(unsigned LimitMs, bool WithWorld = true);
  /// Whether runCycle keeps each cycle's calls (the REPL's history and
  /// recordings do).
  void keepCalls(bool On) { KeepCalls = On; }
  /// replayCycle makes the calls of assertions' conditions for real: the
  /// record is of a robot's object that left its assertions out.
  void replayMakesAssertionCalls(bool On);
  bool keepsCalls() const { return KeepCalls; }
  /// The calls of the last cycle runCycle ran with keepCalls on.
  const CycleRecord &getLastCalls() const { return LastCalls; }
  /// Begins the next cycle and calls the entry on the input the caller
  /// set, taking every call into registered C++ (and the world's end
  /// hook) from `From` instead of calling it: the REPL's time travel and
  /// exact replays. A cycle that parts from its record is Diverged.
  /// `PrintAgain`: the standard `io` module's calls are made for real (a
  /// replay of a recording prints what the behavior printed; the REPL's
  /// re-runs do not).
  Outcome replayCycle(unsigned LimitMs, const CycleRecord &From,
                      bool PrintAgain = false);
  /// Calls `Fn(state)` under the same guard, between cycles (a REPL line).
  Outcome runGuarded(void (*Fn)(void *), unsigned LimitMs) {
    return runGuardedBody([&] { Fn(State); }, LimitMs);
  }
  /// Runs `Body` under the guard.
  Outcome runGuardedBody(llvm::function_ref<void()> Body, unsigned LimitMs);
  /// Drives the session's input and output from a world library from now
  /// on: calls its Init (under the guard) and attaches the result to the
  /// state as its user pointer.
  /// `Robot` of `Robots` is told to the world's bs_world_robot, if any.
  Outcome attachWorld(const WorldHooks &Hooks, unsigned LimitMs,
                      unsigned Robot = 0, unsigned Robots = 1);
  /// Makes the session robot `Robot` of a team world whose bs_team_init
  /// returned `Team`: its cycles call the team's begin and end hooks with
  /// the index; bs_team_robot (if any, under the guard) gives the state's
  /// user pointer, else `Team` is. The team's exit is its owner's.
  Outcome attachTeamWorld(const WorldHooks &Hooks, void *Team, unsigned Robot,
                          unsigned LimitMs);
  /// Runs `Call` under the guard as the world hook `Name` (the team's own
  /// hooks, bs_team_init and bs_team_exit, which no one robot runs).
  Outcome runWorldHook(const char *Name, llvm::function_ref<void()> Call,
                       unsigned LimitMs) {
    return runGuardedBody([&] { inHook(Name, Call); }, LimitMs);
  }
  /// :reload: the new session goes on with the old one's world (its user
  /// pointer included), which the old one then no longer ends.
  void takeWorldFrom(BehaviorSession &Old) {
    World = Old.World;
    WorldUser = Old.WorldUser;
    WorldOutput = Old.WorldOutput;
    TeamUser = Old.TeamUser;
    Robot = Old.Robot;
    Calls->setCaptureFd(WorldOutput);
    bs_state_set_user(State, WorldUser);
    Old.World = WorldHooks();
  }

  /// What the world's hooks print to standard output goes to file
  /// descriptor `Fd` (the session does not own it); -1: standard output.
  void setWorldOutput(int Fd);
  /// Whether the session has a world library attached.
  bool hasWorld() const { return World.Init || World.TeamBegin || World.TeamEnd; }
  /// The sizes of the view's blocks: state, input, output.
  void getViewSizes(size_t Sizes[3]) const {
    Sizes[0] = Info->state_size;
    Sizes[1] = InputSpec.Size;
    Sizes[2] = OutputSpec.Size;
  }

  void *getState() const { return State; }
  void *getInput() const { return Input; }
  void *getOutput() const { return Output; }
  const bs_behavior_info &getInfo() const { return *Info; }
  uint32_t getCycle() const;

private:
  BehaviorSession(BehaviorJIT &JIT) : JIT(JIT) {}
  llvm::Error callThunk(const std::string &Symbol, void *Obj);

  BehaviorJIT &JIT;
  const bs_behavior_info *Info = nullptr;
  void (*Entry)(void *) = nullptr;
  void *State = nullptr;
  void *Input = nullptr, *Output = nullptr;
  BehaviorJIT::GlobalObject InputSpec, OutputSpec;
  volatile uint32_t *LoopProbe = nullptr, *NativeProbe = nullptr;
  bool Started = false; ///< bs_state_init succeeded.
  /// The recorder of the calls into registered C++ (Boundary.h).
  std::unique_ptr<Boundary> Calls;
  bool KeepCalls = false;
  CycleRecord LastCalls;
  /// The entry and the world's end hooks, under Calls: the one cycle body
  /// of runCycle and replayCycle.
  void runEntry(bool WithWorld);
  WorldHooks World;
  void *WorldUser = nullptr;
  /// A team world's pointer and this robot's index in the team.
  void *TeamUser = nullptr;
  unsigned Robot = 0;
  /// The hook running now (read after a signal or the watchdog).
  const char *volatile CurrentHook = nullptr;
  /// setWorldOutput's descriptor, and standard output's own while a hook
  /// runs with it (-1: none).
  int WorldOutput = -1, SavedStdout = -1;
  /// Points standard output at WorldOutput (To) or back.
  void redirectStdout(bool To);
  /// Calls a world hook, naming it while it runs.
  template <class Fn> void inHook(const char *Name, Fn &&Call) {
    CurrentHook = Name;
    redirectStdout(true);
    Call();
    redirectStdout(false);
    CurrentHook = nullptr;
  }
};

} // namespace bsc

#endif

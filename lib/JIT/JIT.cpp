//===- JIT.cpp - running a behavior on the host with ORC LLJIT ------------===//
//
// The runtime shim's C functions are defined in the JIT as absolute symbols
// with their addresses in this process (bsc links bscript_rt), and the
// thunks of the standard modules (`io`) are linked on demand from the host
// runtime archive, as a program links them. That is exactly the set of
// symbols a compiled object may import (CodeGen.h), so a behavior that
// would not link on the robot does not link here either, rather than
// silently picking up something else bsc happens to contain.
//
//===----------------------------------------------------------------------===//
#include "bsc/JIT/JIT.h"
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/CodeGen/Target.h"
#include "bscript/bscript.h"
#include "llvm/ExecutionEngine/Orc/Core.h"
#include "llvm/ExecutionEngine/Orc/DebugObjectManagerPlugin.h"
#include "llvm/ExecutionEngine/Orc/EPCDebugObjectRegistrar.h"
#include "llvm/ExecutionEngine/Orc/TargetProcess/JITLoaderGDB.h"
#include "llvm/ExecutionEngine/Orc/ExecutionUtils.h"
#include "llvm/ExecutionEngine/Orc/ObjectLinkingLayer.h"
#include "llvm/BinaryFormat/Magic.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"
#include "llvm/ExecutionEngine/Orc/ThreadSafeModule.h"
#include "llvm/ADT/ScopeExit.h"
#include "llvm/MC/TargetRegistry.h"
#include "llvm/Support/MemAlloc.h"
#include <csetjmp>
#include <dlfcn.h>
#include <csignal>
#include <cstdio>
#include <cstring>
#include <iterator>
#include <ctime>
#include <stdio_ext.h>
#include <sys/time.h>
#include <unistd.h>

using namespace bsc;

char StaleBindingError::ID;
char BindingLoadError::ID;
char MissingSymbolsError::ID;

void MissingSymbolsError::log(llvm::raw_ostream &OS) const {
  OS << "symbols not found:";
  for (const std::string &S : Symbols)
    OS << " " << S;
}

void BindingLoadError::log(llvm::raw_ostream &OS) const {
  OS << "cannot load '" << Path << "': " << Message;
}

void StaleBindingError::log(llvm::raw_ostream &OS) const {
  OS << "the behavior was compiled against binding module '" << Module
     << "' whose descriptor has changed";
}

BehaviorJIT::~BehaviorJIT() = default;

/// gdb's JIT interface: each linked object (its debug sections included)
/// is announced through __jit_debug_register_code, which gdb breaks on. The
/// registration function lives in this process (LLVM's OrcTargetProcess,
/// linked into bsc), so it is passed by address rather than looked up.
static llvm::Error registerWithDebugger(llvm::orc::LLJIT &J) {
  auto *Linker =
      llvm::dyn_cast<llvm::orc::ObjectLinkingLayer>(&J.getObjLinkingLayer());
  if (!Linker)
    return llvm::createStringError(
        "the JIT's linker cannot register code with a debugger");
  auto Registrar = std::make_unique<llvm::orc::EPCDebugObjectRegistrar>(
      J.getExecutionSession(),
      llvm::orc::ExecutorAddr::fromPtr(&llvm_orc_registerJITLoaderGDBWrapper));
  Linker->addPlugin(std::make_unique<llvm::orc::DebugObjectManagerPlugin>(
      J.getExecutionSession(), std::move(Registrar),
      /*RequireDebugSections=*/false, /*AutoRegisterCode=*/true));
  return llvm::Error::success();
}

llvm::Expected<std::unique_ptr<BehaviorJIT>>
BehaviorJIT::create(unsigned OptLevel, bool Debuggable) {
  initializeTargets();
  auto JTMB = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!JTMB)
    return JTMB.takeError();
  JTMB->setRelocationModel(llvm::Reloc::PIC_);
  // -O0 is for quick turnaround (the REPL's :reload): the fast instruction
  // selector and no machine-level optimisation, as llc -O0 does.
  if (OptLevel == 0)
    JTMB->setCodeGenOptLevel(llvm::CodeGenOptLevel::None);
  auto DL = JTMB->getDefaultDataLayoutForTarget();
  if (!DL)
    return DL.takeError();
  std::unique_ptr<BehaviorJIT> Result(new BehaviorJIT());
  Result->Triple = JTMB->getTargetTriple();
  Result->DL = *DL;
  Result->CPU = JTMB->getCPU();
  auto J = llvm::orc::LLJITBuilder().setJITTargetMachineBuilder(*JTMB).create();
  if (!J)
    return J.takeError();
  Result->J = std::move(*J);
  // Link failures become errors of ours rather than LLJIT's "JIT session
  // error" on stderr followed by a lookup that may still succeed.
  Result->J->getExecutionSession().setErrorReporter(
      [R = Result.get()](llvm::Error E) { R->recordLinkError(std::move(E)); });
  if (Debuggable)
    if (llvm::Error E = registerWithDebugger(*Result->J))
      return E;

  // The runtime shim, by address (see the file comment).
  llvm::orc::MangleAndInterner Mangle(Result->J->getExecutionSession(),
                                      Result->J->getDataLayout());
  llvm::orc::SymbolMap Runtime;
  auto Add = [&](llvm::StringRef Name, auto *Fn) {
    Runtime[Mangle(Name)] = {llvm::orc::ExecutorAddr::fromPtr(Fn),
                             llvm::JITSymbolFlags::Exported |
                                 llvm::JITSymbolFlags::Callable};
  };
  Add("bs_state_init", &bs_state_init);
  Add("bs_begin_cycle", &bs_begin_cycle);
  Add("bs_task_state", &bs_task_state);
  Add("bs_state_destroy", &bs_state_destroy);
  // The boundary's recorder (Boundary.h, CodeGenOptions::Boundary).
  Add("bs_boundary_enter", &bs_boundary_enter);
  Add("bs_boundary_leave", &bs_boundary_leave);
  Add("bs_boundary_assertion", &bs_boundary_assertion);
  // What the io thunks call.
  Add("bs_io_printi", &bs_io_printi);
  Add("bs_io_printf", &bs_io_printf);
  Add("bs_io_printb", &bs_io_printb);
  Add("bs_io_prints", &bs_io_prints);
  if (llvm::Error E = Result->J->getMainJITDylib().define(
          llvm::orc::absoluteSymbols(std::move(Runtime))))
    return E;
  return Result;
}

llvm::Error BehaviorJIT::addModule(std::unique_ptr<llvm::Module> M,
                                   std::unique_ptr<llvm::LLVMContext> Ctx,
                                   unsigned OptLevel) {
  initializeTargets();
  std::string Error;
  const llvm::Target *T =
      llvm::TargetRegistry::lookupTarget(Triple.str(), Error);
  if (!T)
    return llvm::createStringError(Error);
  // The same pipeline as compiled programs, tuned for this CPU.
  std::unique_ptr<llvm::TargetMachine> TM(T->createTargetMachine(
      Triple.str(), CPU, "", llvm::TargetOptions(), llvm::Reloc::PIC_));
  M->setDataLayout(DL);
  M->setTargetTriple(Triple.str());
  optimizeModule(*M, TM.get(), OptLevel);
  return J->addIRModule(
      llvm::orc::ThreadSafeModule(std::move(M), std::move(Ctx)));
}

llvm::Error BehaviorJIT::addObjectFile(llvm::StringRef Path) {
  llvm::orc::JITDylib &JD = J->getMainJITDylib();
  if (!ProcessSymbols) {
    // What the binding objects need beyond themselves: libstdc++, libm and
    // libc, which this process has loaded.
    auto G = llvm::orc::DynamicLibrarySearchGenerator::GetForCurrentProcess(
        J->getDataLayout().getGlobalPrefix());
    if (!G)
      return G.takeError();
    JD.addGenerator(std::move(*G));
    ProcessSymbols = true;
  }
  if (llvm::sys::path::extension(Path) == ".a")
    return addArchive(Path);
  llvm::file_magic Magic;
  if (!llvm::identify_magic(Path, Magic) &&
      Magic == llvm::file_magic::elf_shared_object)
    return addSharedLibrary(Path);
  auto Buf = llvm::MemoryBuffer::getFile(Path);
  if (!Buf)
    return llvm::createStringError(Buf.getError(),
                                   "cannot read '" + Path + "'");
  return J->addObjectFile(std::move(*Buf));
}

llvm::Error BehaviorJIT::addSharedLibrary(llvm::StringRef Path) {
  // dlopen: the library's own dependencies (libstdc++, ...) come with it,
  // and generated code finds the thunks it exports by name, as the dynamic
  // linker would for a program linked against it.
  // By absolute path: dlopen looks for a bare name in the library path,
  // not in the current directory.
  llvm::SmallString<256> Abs(Path);
  llvm::sys::fs::make_absolute(Abs);
  // Every symbol bound now (RTLD_NOW; the handle stays open, as the
  // generator's does): with lazy binding, a function the library needs and
  // nothing defines would make the dynamic loader end bsc at its first call
  // ("symbol lookup error", status 127).
  if (!dlopen(Abs.c_str(), RTLD_NOW | RTLD_GLOBAL)) {
    std::string Message = dlerror();
    llvm::StringRef Undefined = "undefined symbol: ";
    size_t At = Message.find(Undefined.str());
    if (At != std::string::npos)
      return llvm::make_error<MissingSymbolsError>(std::vector<std::string>{
          Message.substr(At + Undefined.size())});
    return llvm::make_error<BindingLoadError>(Path.str(), Message);
  }
  auto G = llvm::orc::DynamicLibrarySearchGenerator::Load(
      Abs.c_str(), J->getDataLayout().getGlobalPrefix());
  if (!G)
    return llvm::make_error<BindingLoadError>(
        Path.str(), llvm::toString(G.takeError()));
  J->getMainJITDylib().addGenerator(std::move(*G));
  return llvm::Error::success();
}

llvm::Error BehaviorJIT::addArchive(llvm::StringRef Path) {
  auto G = llvm::orc::StaticLibraryDefinitionGenerator::Load(
      J->getObjLinkingLayer(), Path.str().c_str());
  if (!G)
    return G.takeError();
  J->getMainJITDylib().addGenerator(std::move(*G));
  return llvm::Error::success();
}

void BehaviorJIT::recordLinkError(llvm::Error E) {
  llvm::handleAllErrors(
      std::move(E),
      [&](const llvm::orc::SymbolsNotFound &NF) {
        for (const llvm::orc::SymbolStringPtr &S : NF.getSymbols())
          MissingSymbols.push_back((*S).str());
      },
      [&](const llvm::ErrorInfoBase &Other) {
        OtherLinkErrors.push_back(Other.message());
      });
}

llvm::Error BehaviorJIT::takeLinkErrors() {
  auto Clear = llvm::make_scope_exit([&] {
    MissingSymbols.clear();
    OtherLinkErrors.clear();
  });
  if (!MissingSymbols.empty())
    return llvm::make_error<MissingSymbolsError>(MissingSymbols);
  if (!OtherLinkErrors.empty())
    return llvm::createStringError(OtherLinkErrors.front());
  return llvm::Error::success();
}

llvm::Error BehaviorJIT::link(llvm::ArrayRef<std::string> Symbols) {
  for (const std::string &S : Symbols) {
    auto Addr = J->lookup(S);
    llvm::Error Reported = takeLinkErrors();
    if (Reported) {
      llvm::consumeError(Addr.takeError());
      return Reported;
    }
    if (!Addr)
      return Addr.takeError();
  }
  return llvm::Error::success();
}

void *BehaviorJIT::lookup(llvm::StringRef Symbol) {
  auto Addr = J->lookup(Symbol);
  if (!Addr) {
    llvm::consumeError(Addr.takeError());
    return nullptr;
  }
  return Addr->toPtr<void *>();
}

//===----------------------------------------------------------------------===//
// BehaviorSession
//===----------------------------------------------------------------------===//

namespace {
/// The cycle guard (BehaviorSession): where a signal during a cycle jumps
/// to. One session runs cycles at a time, on one thread.
sigjmp_buf CycleJump;
volatile sig_atomic_t InCycle = 0;
volatile sig_atomic_t CaughtSignal = 0;
constexpr int GuardedSignals[] = {SIGSEGV, SIGBUS, SIGFPE, SIGILL, SIGALRM};
struct sigaction PreviousActions[std::size(GuardedSignals)];
unsigned Sessions = 0;
/// The handler runs on its own stack, so a stack overflow in registered C++
/// still reaches it.
alignas(16) char AltStack[64 * 1024];

/// The cycle limit costs a clock read per cycle, not two system calls: one
/// ITIMER_REAL stays armed across cycles. A cycle notes when it started and
/// its limit; when the timer fires, it stops a cycle past its limit,
/// re-arms for the rest of one that is not, and stays off when no cycle
/// runs (a REPL waiting at its prompt gets one signal, whose reads restart).
volatile sig_atomic_t TimerArmed = 0;
/// When the armed timer fires, and the running cycle's start and limit
/// (CLOCK_MONOTONIC nanoseconds; a limit of 0: none).
volatile uint64_t TimerDueNs = 0, CycleStartNs = 0, CycleLimitNs = 0;

uint64_t nowNs() {
  struct timespec T;
  clock_gettime(CLOCK_MONOTONIC, &T);
  return uint64_t(T.tv_sec) * 1000000000u + uint64_t(T.tv_nsec);
}

/// Arms the timer to fire in `Ns` (0: disarms it). Async-signal-safe.
void armTimer(uint64_t Ns) {
  struct itimerval T = {};
  T.it_value.tv_sec = time_t(Ns / 1000000000u);
  T.it_value.tv_usec = suseconds_t(Ns % 1000000000u / 1000u);
  if (Ns && !T.it_value.tv_sec && !T.it_value.tv_usec)
    T.it_value.tv_usec = 1;
  setitimer(ITIMER_REAL, &T, nullptr);
  TimerArmed = Ns != 0;
  TimerDueNs = Ns ? nowNs() + Ns : 0;
}

/// Starts the clock of a cycle limited to `LimitMs` (0: none).
void startCycleClock(unsigned LimitMs) {
  uint64_t Now = nowNs();
  CycleStartNs = Now;
  CycleLimitNs = uint64_t(LimitMs) * 1000000u;
  // Armed already, to fire no later than this cycle's limit: nothing to do.
  if (LimitMs && (!TimerArmed || TimerDueNs > Now + CycleLimitNs))
    armTimer(CycleLimitNs);
}

/// Whether SIGALRM stopped a cycle's clock rather than ended its limit:
/// then the timer is re-armed or left off, and the signal is done with.
bool timerOnly(int Sig) {
  if (Sig != SIGALRM || !TimerArmed)
    return false;
  if (!InCycle || !CycleLimitNs) {
    TimerArmed = 0;
    return true;
  }
  uint64_t Now = nowNs(), Deadline = CycleStartNs + CycleLimitNs;
  if (Now >= Deadline) {
    TimerArmed = 0; // It fired: the next cycle arms it again.
    return false;
  }
  armTimer(Deadline - Now);
  return true;
}

void onGuardedSignal(int Sig) {
  if (timerOnly(Sig))
    return;
  if (!InCycle) {
    // Not ours: what would have happened without the guard.
    for (size_t I = 0; I < std::size(GuardedSignals); ++I)
      if (GuardedSignals[I] == Sig)
        sigaction(Sig, &PreviousActions[I], nullptr);
    raise(Sig);
    return;
  }
  InCycle = 0;
  CaughtSignal = Sig;
  siglongjmp(CycleJump, 1);
}

void installGuard() {
  if (Sessions++)
    return;
  stack_t SS = {};
  SS.ss_sp = AltStack;
  SS.ss_size = sizeof AltStack;
  sigaltstack(&SS, nullptr);
  struct sigaction SA = {};
  SA.sa_handler = onGuardedSignal;
  // No signal is blocked in the handler (SA_NODEFER, an empty mask), so
  // jumping out of it leaves the mask as it was: sigsetjmp need not save
  // it (a system call per cycle).
  SA.sa_flags = SA_ONSTACK | SA_NODEFER | SA_RESTART;
  sigemptyset(&SA.sa_mask);
  for (size_t I = 0; I < std::size(GuardedSignals); ++I)
    sigaction(GuardedSignals[I], &SA, &PreviousActions[I]);
}

void removeGuard() {
  if (--Sessions)
    return;
  armTimer(0); // No SIGALRM of ours after the guard is gone.
  for (size_t I = 0; I < std::size(GuardedSignals); ++I)
    sigaction(GuardedSignals[I], &PreviousActions[I], nullptr);
}

/// An aligned, zeroed heap block.
void *allocateZeroed(size_t Size, size_t Align) {
  void *P = llvm::allocate_buffer(Size ? Size : 1, Align ? Align : 1);
  std::memset(P, 0, Size ? Size : 1);
  return P;
}
void deallocate(void *P, size_t Size, size_t Align) {
  if (P)
    llvm::deallocate_buffer(P, Size ? Size : 1, Align ? Align : 1);
}
} // namespace

llvm::Error BehaviorSession::callThunk(const std::string &Symbol, void *Obj) {
  if (Symbol.empty() || !Obj)
    return llvm::Error::success();
  auto Fn = JIT.J->lookup(Symbol);
  if (!Fn)
    return Fn.takeError();
  Fn->toPtr<void (*)(void *)>()(Obj);
  return llvm::Error::success();
}

llvm::Expected<std::unique_ptr<BehaviorSession>>
BehaviorSession::start(BehaviorJIT &JIT, llvm::StringRef InfoSymbol,
                       llvm::StringRef EntrySymbol,
                       const BehaviorJIT::GlobalObject &InputSpec,
                       const BehaviorJIT::GlobalObject &OutputSpec) {
  auto InfoAddr = JIT.J->lookup(InfoSymbol);
  if (!InfoAddr)
    return InfoAddr.takeError();
  auto EntryAddr = JIT.J->lookup(EntrySymbol);
  if (!EntryAddr)
    return EntryAddr.takeError();
  // Never run code whose linking failed somewhere (its addresses may be
  // dangling): loadBehavior's link() reports what it can first.
  if (llvm::Error E = JIT.takeLinkErrors())
    return E;
  std::unique_ptr<BehaviorSession> S(new BehaviorSession(JIT));
  S->Info = InfoAddr->toPtr<const bs_behavior_info *>();
  // Entries without parameters: a func's result (if any) is returned in a
  // register and ignored, as the program's main does.
  S->Entry = EntryAddr->toPtr<void (*)(void *)>();
  S->LoopProbe = static_cast<uint32_t *>(JIT.lookup(LoopProbeSymbol));
  S->NativeProbe = static_cast<uint32_t *>(JIT.lookup(NativeProbeSymbol));

  // The embedding provides the state; here it is one aligned heap block.
  S->State = allocateZeroed(S->Info->state_size, S->Info->state_align);
  int Init = bs_state_init(S->State, S->Info);
  if (Init == BS_INIT_STALE_BINDINGS)
    if (const char *Module = bs_check_bindings(S->Info))
      return llvm::make_error<StaleBindingError>(Module);
  if (Init != BS_INIT_OK)
    return llvm::createStringError(
        "bs_state_init refused the state of ABI version " +
        std::to_string(S->Info->abi_version));
  S->Started = true;
  // Generated code reads input and writes output through the state header,
  // so a behavior that declares them must get real objects, never null.
  S->InputSpec = InputSpec;
  S->OutputSpec = OutputSpec;
  if (InputSpec.Size)
    S->Input = allocateZeroed(InputSpec.Size, InputSpec.Align);
  if (OutputSpec.Size)
    S->Output = allocateZeroed(OutputSpec.Size, OutputSpec.Align);
  if (llvm::Error E = S->callThunk(InputSpec.Construct, S->Input))
    return E;
  if (llvm::Error E = S->callThunk(OutputSpec.Construct, S->Output))
    return E;
  // What bs_begin_cycle stores each cycle, already before the first one:
  // the REPL may read and write them between cycles.
  auto *Header = static_cast<bs_state_header *>(S->State);
  Header->input = S->Input;
  Header->output = S->Output;
  S->Calls = std::make_unique<Boundary>(S->State, S->Info->state_size,
                                        S->Input, InputSpec.Size, S->Output,
                                        OutputSpec.Size);
  installGuard();
  return S;
}

BehaviorSession::~BehaviorSession() {
  if (Started) {
    // As a robot program ends: the world, the class values running tasks
    // hold, then the input and output objects.
    if (World.Exit)
      runGuardedBody(
          [&] { inHook("bs_world_exit", [&] { World.Exit(WorldUser); }); }, 0);
    bs_state_destroy(State, Info);
    llvm::consumeError(callThunk(InputSpec.Destroy, Input));
    llvm::consumeError(callThunk(OutputSpec.Destroy, Output));
    removeGuard();
  }
  deallocate(Input, InputSpec.Size, InputSpec.Align);
  deallocate(Output, OutputSpec.Size, OutputSpec.Align);
  if (Info)
    deallocate(State, Info->state_size, Info->state_align);
  std::fflush(stdout);
}

uint32_t BehaviorSession::getCycle() const {
  return static_cast<const bs_state_header *>(State)->cycle;
}

/// The world's end hooks as calls of the boundary: a re-run takes what
/// they wrote to `output` from the record.
static const bs_boundary_site WorldEndSite = {"bs_world_end", SitePseudo, 0,
                                              0, nullptr, 0};
static const bs_boundary_site TeamEndSite = {"bs_team_end", SitePseudo, 0, 0,
                                             nullptr, 0};

void BehaviorSession::runEntry(bool WithWorld) {
  Entry(State);
  uint32_t Cycle = getCycle();
  // Each end hook as a call: live, it runs and its writes are recorded;
  // replayed, its writes come from the record, whether or not this session
  // has the world that made them.
  auto EndHook = [&](const bs_boundary_site &Site, bool Has, auto &&Call) {
    if (Calls->isReplaying() ? !Calls->nextCallIs(Site.name)
                             : !(WithWorld && Has))
      return;
    if (!Calls->enterPseudo(Site))
      inHook(Site.name, Call);
    Calls->leavePseudo(Site);
  };
  EndHook(WorldEndSite, World.End != nullptr,
          [&] { World.End(WorldUser, Input, Output, Cycle); });
  EndHook(TeamEndSite, World.TeamEnd != nullptr, [&] {
    World.TeamEnd(TeamUser, Robot, Input, Output, Cycle);
  });
}

BehaviorSession::Outcome BehaviorSession::runCycle(unsigned LimitMs,
                                                   bool WithWorld) {
  bs_begin_cycle(State, Input, Output);
  // A world's hooks run in the cycle: under its guard and time limit.
  uint32_t Cycle = getCycle();
  Boundary::Current = Calls.get();
  Outcome O = runGuardedBody(
      [&] {
        if (WithWorld && World.Begin)
          inHook("bs_world_begin",
                 [&] { World.Begin(WorldUser, Input, Output, Cycle); });
        if (WithWorld && World.TeamBegin)
          inHook("bs_team_begin", [&] {
            World.TeamBegin(TeamUser, Robot, Input, Output, Cycle);
          });
        if (KeepCalls)
          Calls->startRecording(LastCalls);
        runEntry(WithWorld);
      },
      LimitMs);
  Calls->finish();
  Boundary::Current = nullptr;
  return O;
}

BehaviorSession::Outcome
BehaviorSession::replayCycle(unsigned LimitMs, const CycleRecord &From,
                             bool PrintAgain) {
  bs_begin_cycle(State, Input, Output);
  std::vector<unsigned char> EntryInput, EntryOutput;
  if (KeepCalls && InputSpec.Size)
    EntryInput.assign(static_cast<unsigned char *>(Input),
                      static_cast<unsigned char *>(Input) + InputSpec.Size);
  if (KeepCalls && OutputSpec.Size)
    EntryOutput.assign(static_cast<unsigned char *>(Output),
                       static_cast<unsigned char *>(Output) + OutputSpec.Size);
  Boundary::Current = Calls.get();
  Calls->setReplayCallsStandard(PrintAgain);
  Calls->startReplay(From);
  Outcome O = runGuardedBody([&] { runEntry(/*WithWorld=*/false); }, LimitMs);
  std::string Why = Calls->finish();
  Boundary::Current = nullptr;
  if (KeepCalls) { // A recording of a replay keeps the replayed calls.
    LastCalls = From;
    LastCalls.EntryInput = std::move(EntryInput);
    LastCalls.EntryOutput = std::move(EntryOutput);
  }
  if (O.K == Outcome::Completed && !Why.empty()) {
    O.K = Outcome::Diverged;
    O.Divergence = std::move(Why);
  }
  return O;
}

BehaviorSession::Outcome BehaviorSession::attachWorld(const WorldHooks &Hooks,
                                                      unsigned LimitMs,
                                                      unsigned Index,
                                                      unsigned Robots) {
  World = Hooks;
  return runGuardedBody(
      [&] {
        inHook("bs_world_init", [&] { WorldUser = World.Init(Input, Output); });
        bs_state_set_user(State, WorldUser);
        if (World.Robot)
          inHook("bs_world_robot",
                 [&] { World.Robot(WorldUser, Index, Robots); });
      },
      LimitMs);
}

BehaviorSession::Outcome
BehaviorSession::attachTeamWorld(const WorldHooks &Hooks, void *Team,
                                 unsigned Index, unsigned LimitMs) {
  World = Hooks;
  TeamUser = Team;
  Robot = Index;
  WorldUser = Team;
  return runGuardedBody(
      [&] {
        if (World.TeamRobot)
          inHook("bs_team_robot", [&] {
            WorldUser = World.TeamRobot(Team, Index, Input, Output);
          });
        bs_state_set_user(State, WorldUser);
      },
      LimitMs);
}

BehaviorSession::Outcome
BehaviorSession::runGuardedBody(llvm::function_ref<void()> Body,
                                unsigned LimitMs) {
  Outcome Result;
  if (LoopProbe)
    *LoopProbe = 0;
  if (NativeProbe)
    *NativeProbe = 0;
  if (sigsetjmp(CycleJump, 0) == 0) {
    startCycleClock(LimitMs);
    InCycle = 1;
    Body();
    InCycle = 0;
  } else {
    Result.K = CaughtSignal == SIGALRM ? Outcome::TimedOut : Outcome::Crashed;
    Result.Signal = CaughtSignal;
  }
  Result.LoopSite = LoopProbe ? *LoopProbe : 0;
  Result.NativeSite = NativeProbe ? *NativeProbe : 0;
  Result.WorldHook = CurrentHook;
  Result.NullUser = !bs_state_user(State);
  CurrentHook = nullptr;
  redirectStdout(false); // A hook that crashed did not put it back.
  if (__fpending(stdout)) // What the behavior printed, before bsc's lines.
    std::fflush(stdout);
  return Result;
}

void BehaviorSession::replayMakesAssertionCalls(bool On) {
  Calls->setReplayMakesAssertionCalls(On);
}

void BehaviorSession::setWorldOutput(int Fd) {
  redirectStdout(false);
  WorldOutput = Fd;
  // What registered C++ prints in a cycle goes there too.
  Calls->setCaptureFd(Fd);
}

void BehaviorSession::redirectStdout(bool To) {
  if (WorldOutput < 0 || (SavedStdout >= 0) == To)
    return;
  std::fflush(stdout);
  if (To) {
    SavedStdout = dup(STDOUT_FILENO);
    dup2(WorldOutput, STDOUT_FILENO);
  } else {
    dup2(SavedStdout, STDOUT_FILENO);
    close(SavedStdout);
    SavedStdout = -1;
  }
}

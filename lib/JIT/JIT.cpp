//===- JIT.cpp - running a behavior on the host with ORC LLJIT ------------===//
//
// The runtime shim's functions are defined in the JIT as absolute symbols
// with their addresses in this process (bsc links bscript_rt). That is
// exactly the set of symbols a compiled object may import (CodeGen.h), so a
// behavior that would not link on the robot does not link here either,
// rather than silently picking up something else bsc happens to contain.
//
//===----------------------------------------------------------------------===//
#include "bsc/JIT/JIT.h"
#include "bsc/CodeGen/Target.h"
#include "bscript/bscript.h"
#include "llvm/ExecutionEngine/Orc/Core.h"
#include "llvm/ExecutionEngine/Orc/JITTargetMachineBuilder.h"
#include "llvm/ExecutionEngine/Orc/LLJIT.h"
#include "llvm/ExecutionEngine/Orc/ThreadSafeModule.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/raw_ostream.h"
#include <cstdio>

using namespace bsc;

BehaviorJIT::~BehaviorJIT() = default;

std::unique_ptr<BehaviorJIT> BehaviorJIT::create(DiagnosticEngine &Diags) {
  initializeTargets();
  auto JTMB = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!JTMB) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed)
        << llvm::toString(JTMB.takeError());
    return nullptr;
  }
  JTMB->setRelocationModel(llvm::Reloc::PIC_);
  auto DL = JTMB->getDefaultDataLayoutForTarget();
  if (!DL) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed)
        << llvm::toString(DL.takeError());
    return nullptr;
  }
  std::unique_ptr<BehaviorJIT> Result(new BehaviorJIT());
  Result->Triple = JTMB->getTargetTriple();
  Result->DL = *DL;
  Result->CPU = JTMB->getCPU();
  auto J = llvm::orc::LLJITBuilder().setJITTargetMachineBuilder(*JTMB).create();
  if (!J) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed) << llvm::toString(J.takeError());
    return nullptr;
  }
  Result->J = std::move(*J);

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
  Add("bs_io_printi", &bs_io_printi);
  Add("bs_io_printf", &bs_io_printf);
  Add("bs_io_printb", &bs_io_printb);
  Add("bs_io_prints", &bs_io_prints);
  if (llvm::Error E = Result->J->getMainJITDylib().define(
          llvm::orc::absoluteSymbols(std::move(Runtime)))) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed) << llvm::toString(std::move(E));
    return nullptr;
  }
  return Result;
}

bool BehaviorJIT::addModule(std::unique_ptr<llvm::Module> M,
                            std::unique_ptr<llvm::LLVMContext> Ctx,
                            unsigned OptLevel, DiagnosticEngine &Diags) {
  TargetOptions TO;
  TO.Target = Triple.str();
  TO.CPU = CPU;
  TO.OptLevel = OptLevel;
  std::unique_ptr<llvm::TargetMachine> TM = createTargetMachine(TO, Diags);
  if (!TM)
    return false;
  M->setDataLayout(DL);
  M->setTargetTriple(Triple.str());
  optimizeModule(*M, TM.get(), OptLevel);
  if (llvm::Error E = J->addIRModule(
          llvm::orc::ThreadSafeModule(std::move(M), std::move(Ctx)))) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed) << llvm::toString(std::move(E));
    return false;
  }
  return true;
}

void *BehaviorJIT::lookup(llvm::StringRef Symbol, DiagnosticEngine &Diags) {
  auto Addr = J->lookup(Symbol);
  if (!Addr) {
    Diags.report(llvm::SMLoc(), diag::err_jit_failed)
        << llvm::toString(Addr.takeError());
    return nullptr;
  }
  return Addr->toPtr<void *>();
}

bool BehaviorJIT::runCycles(llvm::StringRef InfoSymbol,
                            llvm::StringRef EntrySymbol, unsigned Cycles,
                            DiagnosticEngine &Diags) {
  auto *Info =
      static_cast<const bs_behavior_info *>(lookup(InfoSymbol, Diags));
  if (!Info)
    return false;
  // Entries without parameters: a func's result (if any) is returned in a
  // register and ignored, as the program's main does.
  auto *Entry = reinterpret_cast<void (*)(void *)>(lookup(EntrySymbol, Diags));
  if (!Entry)
    return false;

  // The embedding provides the state; here it is one aligned heap block.
  size_t Align = Info->state_align ? Info->state_align : 1;
  size_t Size = Info->state_size ? Info->state_size : 1;
  void *State = llvm::allocate_buffer(Size, Align);
  bool OK = bs_state_init(State, Info) == 0;
  if (!OK)
    Diags.report(llvm::SMLoc(), diag::err_jit_failed)
        << "bs_state_init refused the behavior's state (ABI version " +
               std::to_string(Info->abi_version) + ")";
  for (unsigned I = 0; OK && I < Cycles; ++I) {
    bs_begin_cycle(State, nullptr, nullptr);
    Entry(State);
  }
  std::fflush(stdout);
  llvm::deallocate_buffer(State, Size, Align);
  return OK;
}

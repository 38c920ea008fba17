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
#include "bsc/CodeGen/Target.h"
#include "bscript/bscript.h"
#include "llvm/ExecutionEngine/Orc/Core.h"
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
#include <cstdio>
#include <cstring>

using namespace bsc;

char StaleBindingError::ID;
char BindingLoadError::ID;

void BindingLoadError::log(llvm::raw_ostream &OS) const {
  OS << "cannot load '" << Path << "': " << Message;
}

void StaleBindingError::log(llvm::raw_ostream &OS) const {
  OS << "the behavior was compiled against binding module '" << Module
     << "' whose descriptor has changed";
}

BehaviorJIT::~BehaviorJIT() = default;

llvm::Expected<std::unique_ptr<BehaviorJIT>> BehaviorJIT::create() {
  initializeTargets();
  auto JTMB = llvm::orc::JITTargetMachineBuilder::detectHost();
  if (!JTMB)
    return JTMB.takeError();
  JTMB->setRelocationModel(llvm::Reloc::PIC_);
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

namespace {
/// An aligned, zeroed heap object, constructed through its thunk.
class JITObject {
public:
  JITObject(size_t Size, size_t Align)
      : Size(Size ? Size : 1), Align(Align ? Align : 1),
        Ptr(llvm::allocate_buffer(this->Size, this->Align)) {
    std::memset(Ptr, 0, this->Size);
  }
  ~JITObject() { llvm::deallocate_buffer(Ptr, Size, Align); }
  void *get() const { return Ptr; }

private:
  size_t Size, Align;
  void *Ptr;
};
} // namespace

llvm::Error BehaviorJIT::runCycles(llvm::StringRef InfoSymbol,
                                   llvm::StringRef EntrySymbol,
                                   unsigned Cycles, const GlobalObject &Input,
                                   const GlobalObject &Output) {
  auto InfoAddr = J->lookup(InfoSymbol);
  if (!InfoAddr)
    return InfoAddr.takeError();
  auto EntryAddr = J->lookup(EntrySymbol);
  if (!EntryAddr)
    return EntryAddr.takeError();
  const auto *Info = InfoAddr->toPtr<const bs_behavior_info *>();
  // Entries without parameters: a func's result (if any) is returned in a
  // register and ignored, as the program's main does.
  auto *Entry = EntryAddr->toPtr<void (*)(void *)>();

  // The embedding provides the state; here it is one aligned heap block.
  size_t Align = Info->state_align ? Info->state_align : 1;
  size_t Size = Info->state_size ? Info->state_size : 1;
  void *State = llvm::allocate_buffer(Size, Align);
  auto Free =
      llvm::make_scope_exit([&] { llvm::deallocate_buffer(State, Size, Align); });
  int Init = bs_state_init(State, Info);
  if (Init == BS_INIT_STALE_BINDINGS)
    if (const char *Module = bs_check_bindings(Info))
      return llvm::make_error<StaleBindingError>(Module);
  if (Init != BS_INIT_OK)
    return llvm::createStringError(
        "bs_state_init refused the state of ABI version " +
        std::to_string(Info->abi_version));
  // Generated code reads input and writes output through the state header,
  // so a behavior that declares them must get real objects, never null.
  JITObject InputObj(Input.Size, Input.Align), OutputObj(Output.Size,
                                                         Output.Align);
  // Runs one life-cycle thunk (construct or destroy) on both objects.
  auto CallOnObjects = [&](std::string GlobalObject::*Thunk) -> llvm::Error {
    for (auto [Spec, Obj] : {std::pair(&Input, &InputObj),
                             std::pair(&Output, &OutputObj)}) {
      if ((Spec->*Thunk).empty())
        continue;
      auto Fn = J->lookup(Spec->*Thunk);
      if (!Fn)
        return Fn.takeError();
      Fn->toPtr<void (*)(void *)>()(Obj->get());
    }
    return llvm::Error::success();
  };
  if (llvm::Error E = CallOnObjects(&GlobalObject::Construct))
    return E;
  void *In = Input.Size ? InputObj.get() : nullptr;
  void *Out = Output.Size ? OutputObj.get() : nullptr;
  for (unsigned I = 0; I < Cycles; ++I) {
    bs_begin_cycle(State, In, Out);
    Entry(State);
  }
  // As a robot program ends: the class values running tasks hold, then
  // the input and output objects.
  bs_state_destroy(State, Info);
  if (llvm::Error E = CallOnObjects(&GlobalObject::Destroy))
    return E;
  std::fflush(stdout);
  return llvm::Error::success();
}

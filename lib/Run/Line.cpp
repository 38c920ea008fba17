//===- Line.cpp - lines of b-script compiled into a loaded behavior -------===//
#include "bsc/Run/Line.h"
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Parse/Parser.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/MemAlloc.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/WithColor.h"
#include <cstring>

using namespace bsc;

Slot bsc::allocateSlot(const Type *T) {
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

void bsc::destroySlot(const LoadedBehavior *L, Slot &Sl) {
  if (!Sl.Ptr)
    return;
  // A class value the line constructed there (REPL variables and results
  // are never destroyed by generated code).
  if (const NativeClass *NC = Sl.Ty->getClass())
    if (!NC->TriviallyDestructible && L)
      if (void *Destroy = L->JIT->lookup(NC->Destroy))
        reinterpret_cast<void (*)(void *)>(Destroy)(Sl.Ptr);
  llvm::deallocate_buffer(Sl.Ptr, Sl.Size, Sl.Align);
  Sl.Ptr = nullptr;
}

std::unique_ptr<ReplChecker> bsc::makeLineChecker(Compilation &C,
                                                  const LoadedBehavior &L,
                                                  llvm::StringRef FrameTask) {
  auto Checker = std::make_unique<ReplChecker>(C.Ctx, C.Diags, C.Checked,
                                               &C.Natives, L.Entry->Module);
  llvm::DenseSet<const Decl *> Kept;
  for (const BehaviorLayout::Task &T : L.Layout.Tasks)
    for (const BehaviorLayout::FrameField &F : T.Fields)
      Kept.insert(F.D);
  Checker->setFrameFields(std::move(Kept));
  for (const BehaviorLayout::Task &T : L.Layout.Tasks)
    if (T.Decl->getQualifiedName() == FrameTask)
      Checker->setFrame(llvm::cast<TaskDecl>(T.Decl));
  return Checker;
}

std::optional<CompiledLine>
bsc::compileLine(Compilation &C, LoadedBehavior &L, ReplChecker &Checker,
                 llvm::StringRef Text, llvm::StringRef BufferName,
                 unsigned Number, std::vector<Slot> &Variables) {
  unsigned ID = C.SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy(Text, BufferName), llvm::SMLoc());
  BlockStmt *Body = parseReplLine(C.SM, ID, C.Ctx, C.Diags);
  if (C.Diags.hasErrors())
    return std::nullopt;
  CompiledLine R;
  R.Checked = Checker.check(Body, Number);
  if (!R.Checked)
    return std::nullopt;
  llvm::DenseMap<const Decl *, uint64_t> Addresses;
  for (size_t I = 0; I < Checker.getVariables().size(); ++I) {
    const VarDecl *V = Checker.getVariables()[I];
    if (I >= Variables.size())
      Variables.push_back(allocateSlot(V->Ty));
    Addresses[V] = reinterpret_cast<uintptr_t>(Variables[I].Ptr);
  }
  if (const VarDecl *Res = R.Checked->Result) {
    R.Result = allocateSlot(Res->Ty);
    Addresses[Res] = reinterpret_cast<uintptr_t>(R.Result.Ptr);
  }
  std::string Symbol = "bs.repl." + std::to_string(Number);
  auto Ctx = std::make_unique<llvm::LLVMContext>();
  std::unique_ptr<llvm::Module> M =
      emitReplLine(C.Checked, *R.Checked->Func, Symbol, *Ctx,
                   L.JIT->getTriple(), L.JIT->getDataLayout(), Addresses,
                   L.Layout.Sites);
  llvm::Error E = verifyGeneratedModule(*M);
  if (!E)
    E = L.JIT->addModule(std::move(M), std::move(Ctx), 0);
  if (E) {
    reportInternalError(std::move(E));
    destroySlot(&L, R.Result);
    return std::nullopt;
  }
  R.Fn = reinterpret_cast<void (*)(void *)>(L.JIT->lookup(Symbol));
  return R;
}

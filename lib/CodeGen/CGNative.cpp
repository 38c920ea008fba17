//===- CGNative.cpp - thunks of registered C++ and strings ----------------===//
//
// What generated code calls or points to outside its own functions: the
// C-ABI declarations of registered C++ (functions, setters, the life-cycle
// thunks of classes), string constants, and `bs.string.eq`, defined in the
// module so that an object needs no strcmp from a libc.
//
//===----------------------------------------------------------------------===//
#include "CodeGenImpl.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/IR/Function.h"
#include "llvm/IR/GlobalVariable.h"

using namespace bsc;
using namespace bsc::codegen;

llvm::FunctionCallee ModuleEmitter::getNative(const NativeFunction &NF) {
  llvm::FunctionCallee &Slot = Natives[&NF];
  if (Slot)
    return Slot;
  // wire(R) f([T *self,] [bs::Context *,] wire(A)...) or void f(R *out,
  // [T *self,] ...).
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::SmallVector<llvm::Type *, 4> Params;
  if (NF.ResultViaOut)
    Params.push_back(Ptr);
  if (NF.hasSelf())
    Params.push_back(Ptr);
  if (NF.TakesContext)
    Params.push_back(Ptr);
  for (const NativeType &P : NF.Params)
    Params.push_back(getNativeType(P));
  llvm::Type *Result = NF.ResultViaOut ? llvm::Type::getVoidTy(Ctx)
                                       : getNativeType(NF.Result);
  auto *FTy = llvm::FunctionType::get(Result, Params, false);
  Slot = M.getOrInsertFunction(NF.Symbol, FTy);
  if (auto *F = llvm::dyn_cast<llvm::Function>(Slot.getCallee()))
    F->addFnAttr(llvm::Attribute::NoUnwind);
  return Slot;
}

llvm::FunctionCallee
ModuleEmitter::getNativeSetter(const NativeFunction &NF) {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  auto *FTy = llvm::FunctionType::get(
      llvm::Type::getVoidTy(Ctx), {Ptr, getNativeType(NF.Result)}, false);
  llvm::FunctionCallee F = M.getOrInsertFunction(NF.Setter, FTy);
  if (auto *Fn = llvm::dyn_cast<llvm::Function>(F.getCallee()))
    Fn->addFnAttr(llvm::Attribute::NoUnwind);
  return F;
}

llvm::FunctionCallee ModuleEmitter::getLifeThunk(llvm::StringRef Symbol,
                                                 unsigned NumPtrs) {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::SmallVector<llvm::Type *, 2> Params(NumPtrs, Ptr);
  auto *FTy =
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), Params, false);
  llvm::FunctionCallee F = M.getOrInsertFunction(Symbol, FTy);
  if (auto *Fn = llvm::dyn_cast<llvm::Function>(F.getCallee()))
    Fn->addFnAttr(llvm::Attribute::NoUnwind);
  return F;
}

llvm::Constant *ModuleEmitter::getString(llvm::StringRef S) {
  llvm::Constant *&Slot = Strings[S];
  if (Slot)
    return Slot;
  llvm::Constant *Init = llvm::ConstantDataArray::getString(Ctx, S, true);
  auto *GV = new llvm::GlobalVariable(M, Init->getType(), /*isConstant=*/true,
                                      llvm::GlobalValue::PrivateLinkage, Init,
                                      ".str");
  GV->setUnnamedAddr(llvm::GlobalValue::UnnamedAddr::Global);
  GV->setAlignment(llvm::Align(1));
  Slot = GV;
  return GV;
}

llvm::Function *ModuleEmitter::getStringEquals() {
  if (StringEquals)
    return StringEquals;
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::Type *I8 = llvm::Type::getInt8Ty(Ctx);
  StringEquals = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getInt1Ty(Ctx), {Ptr, Ptr}, false),
      llvm::GlobalValue::InternalLinkage, "bs.string.eq", M);
  addCommonAttributes(StringEquals);
  StringEquals->setOnlyReadsMemory();
  llvm::Argument *A = StringEquals->getArg(0), *B = StringEquals->getArg(1);
  A->setName("a");
  B->setName("b");
  auto *Entry = llvm::BasicBlock::Create(Ctx, "entry", StringEquals);
  auto *Loop = llvm::BasicBlock::Create(Ctx, "loop", StringEquals);
  auto *Next = llvm::BasicBlock::Create(Ctx, "next", StringEquals);
  auto *Same = llvm::BasicBlock::Create(Ctx, "same", StringEquals);
  auto *Differ = llvm::BasicBlock::Create(Ctx, "differ", StringEquals);
  llvm::IRBuilder<> IRB(Entry);
  // A null string (a binding may return one) reads as "".
  llvm::Constant *Empty = getString("");
  llvm::Value *SA = IRB.CreateSelect(IRB.CreateIsNull(A), Empty, A, "a.str");
  llvm::Value *SB = IRB.CreateSelect(IRB.CreateIsNull(B), Empty, B, "b.str");
  IRB.CreateCondBr(IRB.CreateICmpEQ(SA, SB, "same.ptr"), Same, Loop);
  IRB.SetInsertPoint(Loop);
  llvm::PHINode *I = IRB.CreatePHI(IRB.getInt32Ty(), 2, "i");
  I->addIncoming(IRB.getInt32(0), Entry);
  llvm::Value *CA = IRB.CreateLoad(I8, IRB.CreateGEP(I8, SA, I), "ca");
  llvm::Value *CB = IRB.CreateLoad(I8, IRB.CreateGEP(I8, SB, I), "cb");
  IRB.CreateCondBr(IRB.CreateICmpEQ(CA, CB), Next, Differ);
  IRB.SetInsertPoint(Next);
  I->addIncoming(IRB.CreateAdd(I, IRB.getInt32(1), "i.next"), Next);
  IRB.CreateCondBr(IRB.CreateIsNull(CA, "end"), Same, Loop);
  IRB.SetInsertPoint(Same);
  IRB.CreateRet(IRB.getTrue());
  IRB.SetInsertPoint(Differ);
  IRB.CreateRet(IRB.getFalse());
  return StringEquals;
}

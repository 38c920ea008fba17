//===- CGNative.cpp - thunks of registered C++ and strings ----------------===//
//
// What generated code calls or points to outside its own functions: the
// C-ABI declarations of registered C++ (functions, setters, the life-cycle
// thunks of classes), string constants, and `bs.string.eq`, defined in the
// module so that an object needs no strcmp from a libc.
//
//===----------------------------------------------------------------------===//
#include "ModuleEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/IR/Function.h"
#include "llvm/IR/GlobalVariable.h"
#include "llvm/TargetParser/Triple.h"

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
  llvm::FunctionCallee Thunk = M.getOrInsertFunction(NF.Symbol, FTy);
  if (auto *F = llvm::dyn_cast<llvm::Function>(Thunk.getCallee()))
    F->addFnAttr(llvm::Attribute::NoUnwind);
  // What the thunk may write besides the view: a class result's storage,
  // the object of a non-const method, `T&` arguments; what it reads.
  BehaviorLayout::NativeCall Shape;
  unsigned Arg = 0;
  if (NF.ResultViaOut)
    Shape.Writes.push_back({Arg++, NF.Result.TheClass->Size});
  if (NF.hasSelf()) {
    if (NF.Owner) {
      Shape.Reads.push_back({Arg, NF.Owner->Size});
      if (!NF.ConstSelf)
        Shape.Writes.push_back({Arg, NF.Owner->Size});
    }
    ++Arg;
  }
  if (NF.TakesContext)
    ++Arg; // The state: in the view.
  for (const NativeType &P : NF.Params) {
    if (P.TheClass) {
      Shape.Reads.push_back({Arg, P.TheClass->Size});
      if (P.MutableRef)
        Shape.Writes.push_back({Arg, P.TheClass->Size});
    }
    ++Arg;
  }
  bool Standard = false;
  Shape.Name = getNativeName(NF, Standard);
  Shape.Flags = (Standard ? SiteStandard : SiteNoFlags) |
                (!NF.ResultViaOut && NF.Result.TheCode == NativeType::String
                     ? SiteResultIsString
                     : SiteNoFlags);
  Shape.Pure = NF.Pure;
  Shape.Getter = NF.isData();
  Layout.NativeCalls[NF.Symbol] = Shape;
  if (NF.Pure)
    return Slot = Thunk;
  return Slot = wrapForBoundary(Thunk, Shape.Name, Shape.Flags, Shape.Writes);
}

std::string ModuleEmitter::getNativeName(const NativeFunction &NF,
                                         bool &Standard) const {
  Standard = false;
  if (NF.Owner) {
    Standard = NF.Owner->Module && NF.Owner->Module->Standard;
    return NF.Owner->QualifiedName + "::" + NF.Name;
  }
  for (const NativeModule *NM : B.NativeModules)
    if (NM->findFunction(NF.Name) == &NF) {
      Standard = NM->Standard;
      return NM->Name + "::" + NF.Name;
    }
  if (B.World && B.World->findFunction(NF.Name) == &NF)
    return B.World->Name + "::" + NF.Name;
  return NF.Name;
}

llvm::FunctionCallee ModuleEmitter::wrapForBoundary(
    llvm::FunctionCallee Thunk, llvm::StringRef Name, uint32_t Flags,
    llvm::ArrayRef<std::pair<unsigned, uint64_t>> Writable) {
  if (!Opts.Boundary && !Opts.FlightRecorder)
    return Thunk;
  // The JIT's recorder may take the call from its record instead of
  // making it; the robot's recorder only logs it.
  bool Flight = !Opts.Boundary;
  auto *ThunkFn = llvm::cast<llvm::Function>(Thunk.getCallee());
  std::string WrapperName =
      ((Flight ? "bs.flight." : "bs.boundary.") + ThunkFn->getName()).str();
  if (llvm::Function *F = M.getFunction(WrapperName))
    return F;
  llvm::FunctionType *FTy = Thunk.getFunctionType();
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Void = llvm::Type::getVoidTy(Ctx);
  const llvm::DataLayout &DL = M.getDataLayout();
  llvm::Type *RetTy = FTy->getReturnType();
  uint64_t ResultSize = RetTy->isVoidTy() ? 0 : DL.getTypeStoreSize(RetTy);

  // The site: struct bs_boundary_site (bsc/JIT/Boundary.h), the same as
  // bs_flight_site (bscript/flight.h).
  llvm::SmallVector<llvm::Constant *, 4> Sizes;
  for (auto [Index, Size] : Writable)
    Sizes.push_back(llvm::ConstantInt::get(I32, Size));
  llvm::Constant *SizesPtr = llvm::ConstantPointerNull::get(
      llvm::PointerType::getUnqual(Ctx));
  if (!Sizes.empty()) {
    auto *ArrTy = llvm::ArrayType::get(I32, Sizes.size());
    auto *GV = new llvm::GlobalVariable(
        M, ArrTy, true, llvm::GlobalValue::PrivateLinkage,
        llvm::ConstantArray::get(ArrTy, Sizes), WrapperName + ".sizes");
    SizesPtr = GV;
  }
  auto *SiteTy = llvm::StructType::get(Ctx, {Ptr, I32, I32, I32, Ptr, I32});
  auto *Site = new llvm::GlobalVariable(
      M, SiteTy, true, llvm::GlobalValue::PrivateLinkage,
      llvm::ConstantStruct::get(
          SiteTy, {getString(Name), llvm::ConstantInt::get(I32, Flags),
                   llvm::ConstantInt::get(I32, ResultSize),
                   llvm::ConstantInt::get(I32, Writable.size()), SizesPtr,
                   llvm::ConstantInt::get(I32, BoundarySites.size())}),
      WrapperName + ".site");
  BoundarySites.push_back(Site);

  auto *F = llvm::Function::Create(FTy, llvm::GlobalValue::InternalLinkage,
                                   WrapperName, M);
  F->addFnAttr(llvm::Attribute::NoUnwind);
  auto *Entry = llvm::BasicBlock::Create(Ctx, "entry", F);
  auto *Live = llvm::BasicBlock::Create(Ctx, "live", F);
  auto *Leave = llvm::BasicBlock::Create(Ctx, "leave", F);
  llvm::IRBuilder<> IRB(Entry);
  llvm::AllocaInst *Result =
      ResultSize ? IRB.CreateAlloca(RetTy, nullptr, "result") : nullptr;
  llvm::AllocaInst *Ptrs =
      Writable.empty()
          ? nullptr
          : IRB.CreateAlloca(llvm::ArrayType::get(Ptr, Writable.size()),
                             nullptr, "ptrs");
  llvm::FunctionCallee Enter = M.getOrInsertFunction(
      Flight ? "bs_flight_enter" : "bs_boundary_enter",
      llvm::FunctionType::get(Flight ? Void : I32, {Ptr}, false));
  llvm::FunctionCallee LeaveFn = M.getOrInsertFunction(
      Flight ? "bs_flight_leave" : "bs_boundary_leave",
      llvm::FunctionType::get(Void, {Ptr, Ptr, Ptr}, false));
  llvm::Value *Take = IRB.CreateCall(Enter, {Site});
  if (Flight)
    IRB.CreateBr(Live);
  else
    IRB.CreateCondBr(IRB.CreateICmpNE(Take, IRB.getInt32(0), "take"), Leave,
                     Live);

  IRB.SetInsertPoint(Live);
  llvm::SmallVector<llvm::Value *, 6> Args;
  for (llvm::Argument &A : F->args())
    Args.push_back(&A);
  llvm::CallInst *Call = IRB.CreateCall(Thunk, Args);
  if (Result)
    IRB.CreateStore(Call, Result);
  IRB.CreateBr(Leave);

  IRB.SetInsertPoint(Leave);
  for (size_t I = 0; I < Writable.size(); ++I)
    IRB.CreateStore(F->getArg(Writable[I].first),
                    IRB.CreateConstInBoundsGEP2_32(Ptrs->getAllocatedType(),
                                                   Ptrs, 0, I));
  llvm::Value *Null = llvm::ConstantPointerNull::get(
      llvm::PointerType::getUnqual(Ctx));
  IRB.CreateCall(LeaveFn, {Site, Result ? (llvm::Value *)Result : Null,
                           Ptrs ? (llvm::Value *)Ptrs : Null});
  if (Result)
    IRB.CreateRet(IRB.CreateLoad(RetTy, Result));
  else
    IRB.CreateRetVoid();
  return F;
}

llvm::StructType *ModuleEmitter::getFlightTableType() {
  // struct bs_flight_table (bscript/flight.h).
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  return llvm::StructType::get(Ctx,
                               {I32, I32, Ptr, I32, I32, Ptr, Ptr, I32, Ptr, I32});
}

llvm::GlobalVariable *ModuleEmitter::getFlightTable() {
  // Declared when `main` refers to it; defined last, when every call
  // site is known (emitFlightTable).
  Layout.FlightTableSymbol = "bs_" + Opts.BehaviorName + "_flight";
  if (llvm::GlobalVariable *GV = M.getNamedGlobal(Layout.FlightTableSymbol))
    return GV;
  return new llvm::GlobalVariable(M, getFlightTableType(), true,
                                  llvm::GlobalValue::ExternalLinkage, nullptr,
                                  Layout.FlightTableSymbol);
}

void ModuleEmitter::emitFlightTable() {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  auto Private = [&](llvm::Constant *Init, const char *Name) {
    auto *GV = new llvm::GlobalVariable(M, Init->getType(), true,
                                        llvm::GlobalValue::PrivateLinkage,
                                        Init, Name);
    return GV;
  };
  auto *SitesTy = llvm::ArrayType::get(Ptr, BoundarySites.size());
  llvm::SmallVector<llvm::Constant *, 16> SitePtrs(BoundarySites.begin(),
                                                   BoundarySites.end());
  auto *EntryTy = llvm::StructType::get(Ctx, {Ptr, Ptr});
  llvm::SmallVector<llvm::Constant *, 8> Entries;
  for (const auto &[Name, Hash] : Opts.FlightEntries)
    Entries.push_back(llvm::ConstantStruct::get(
        EntryTy, {getString(Name), getString(Hash)}));
  auto *EntriesTy = llvm::ArrayType::get(EntryTy, Entries.size());
  const NativeModule *World = B.World;
  auto SizeOf = [&](const NativeClass *C) {
    return llvm::ConstantInt::get(I32, C ? C->Size : 0);
  };
  llvm::StructType *TableTy = getFlightTableType();
  llvm::Constant *Fields[] = {
      llvm::ConstantInt::get(I32, 1), // BS_FLIGHT_VERSION
      llvm::ConstantInt::get(I32, BoundarySites.size()),
      Private(llvm::ConstantArray::get(SitesTy, SitePtrs), "bs.flight.sites"),
      SizeOf(World ? World->Input : nullptr),
      SizeOf(World ? World->Output : nullptr),
      getString(llvm::Triple(M.getTargetTriple()).getArchName()),
      getString(getIOLayoutHash(B)),
      llvm::ConstantInt::get(I32, Entries.size()),
      Private(llvm::ConstantArray::get(EntriesTy, Entries),
              "bs.flight.entries"),
      llvm::ConstantInt::get(I32, Opts.Assertions != AssertionMode::None)};
  getFlightTable()->setInitializer(llvm::ConstantStruct::get(TableTy, Fields));
}

llvm::FunctionCallee
ModuleEmitter::getNativeSetter(const NativeFunction &NF) {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  auto *FTy = llvm::FunctionType::get(
      llvm::Type::getVoidTy(Ctx), {Ptr, getNativeType(NF.Result)}, false);
  llvm::FunctionCallee F = M.getOrInsertFunction(NF.Setter, FTy);
  if (auto *Fn = llvm::dyn_cast<llvm::Function>(F.getCallee()))
    Fn->addFnAttr(llvm::Attribute::NoUnwind);
  bool Standard;
  BehaviorLayout::NativeCall &Shape = Layout.NativeCalls[NF.Setter];
  Shape.Name = getNativeName(NF, Standard) + " (set)";
  Shape.Flags = Standard ? SiteStandard : SiteNoFlags;
  Shape.Writes = {{0, NF.Owner ? NF.Owner->Size : 0}};
  return wrapForBoundary(F, Shape.Name, Shape.Flags, Shape.Writes);
}

llvm::FunctionCallee ModuleEmitter::getLifeThunk(const NativeClass *C,
                                                 llvm::StringRef Symbol,
                                                 unsigned NumPtrs) {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::SmallVector<llvm::Type *, 2> Params(NumPtrs, Ptr);
  auto *FTy =
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), Params, false);
  llvm::FunctionCallee F = M.getOrInsertFunction(Symbol, FTy);
  if (auto *Fn = llvm::dyn_cast<llvm::Function>(F.getCallee()))
    Fn->addFnAttr(llvm::Attribute::NoUnwind);
  // The object (the copy's destination) is written.
  const char *What = Symbol == C->Construct ? "construct"
                     : Symbol == C->Copy    ? "copy"
                     : Symbol == C->Assign  ? "assign"
                                            : "destroy";
  BehaviorLayout::NativeCall &Shape = Layout.NativeCalls[Symbol.str()];
  Shape.Name = C->QualifiedName + " (" + What + ")";
  Shape.Flags = C->Module && C->Module->Standard ? SiteStandard : SiteNoFlags;
  Shape.Writes = {{0, C->Size}};
  if (NumPtrs == 2) // The copy's source.
    Shape.Reads = {{1, C->Size}};
  return wrapForBoundary(F, Shape.Name, Shape.Flags, Shape.Writes);
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

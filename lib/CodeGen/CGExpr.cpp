//===- CGExpr.cpp - lowering expressions ----------------------------------===//
//
// Expressions become SSA values: int/TaskState/enums are i32, float is
// float, bool i1, string a pointer to a constant. Sema has made every
// conversion explicit (an implicit int-to-float promotion is a
// ConversionExpr), so operands of one operator have one type.
//
// The runtime-safety rules of language.md are enforced here, in the
// instructions chosen, rather than by checks that trap:
// - + - * on int wrap: no nsw/nuw flags, so no poison and no UB.
// - int / and % never divide by zero or overflow: a divisor of 1 is
//   substituted and the result selected (emitSafeIntDivRem).
// - float -> int saturates with llvm.fptosi.sat (NaN -> 0).
// - float % is computed inline, never by fmodf (no libm in the object).
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/Intrinsics.h"
#include "llvm/Support/ErrorHandling.h"

using namespace bsc;
using namespace bsc::codegen;

llvm::LoadInst *FunctionEmitter::createLoad(ModuleEmitter::Access A,
                                            llvm::Type *Ty, llvm::Value *Addr,
                                            const llvm::Twine &Name) {
  llvm::LoadInst *L = Builder.CreateLoad(Ty, Addr, Name);
  L->setMetadata(llvm::LLVMContext::MD_tbaa, CGM.getAccessTag(A));
  return L;
}

llvm::StoreInst *FunctionEmitter::createStore(ModuleEmitter::Access A,
                                              llvm::Value *V,
                                              llvm::Value *Addr) {
  llvm::StoreInst *S = Builder.CreateStore(V, Addr);
  S->setMetadata(llvm::LLVMContext::MD_tbaa, CGM.getAccessTag(A));
  return S;
}

// Variables (frame fields, allocas, REPL slots) are state memory.
llvm::Value *FunctionEmitter::emitLoad(const Type *T, llvm::Value *Addr,
                                       const llvm::Twine &Name) {
  using Access = ModuleEmitter::Access;
  if (T->isClass()) // The value is its storage.
    return Addr;
  if (!T->isBool())
    return createLoad(Access::State, CGM.getMemoryType(T), Addr, Name);
  llvm::Value *V = createLoad(Access::State, CGM.getMemoryType(T), Addr);
  return Builder.CreateTrunc(V, Builder.getInt1Ty(), Name);
}

void FunctionEmitter::emitStore(const Type *T, llvm::Value *V,
                                llvm::Value *Addr) {
  if (T->isClass()) // Variables of class type are always constructed.
    return emitClassCopy(T->getClass(), Addr, V, /*DstConstructed=*/true);
  if (T->isBool())
    V = Builder.CreateZExt(V, Builder.getInt8Ty());
  createStore(ModuleEmitter::Access::State, V, Addr);
}

llvm::Value *FunctionEmitter::getDeclAddress(const Decl *Dcl) {
  if (const auto *V = llvm::dyn_cast<VarDecl>(Dcl)) {
    // A task's locals are in its frame, also when a nested func uses them,
    // unless their values never outlive a call (keepsInFrame): allocas.
    if (const auto *T = llvm::dyn_cast_or_null<TaskDecl>(V->Owner))
      if (CGM.keepsInFrame(V))
        return getFrameFieldPtr(T, CGM.getFrame(T).Fields.lookup(V));
    if (llvm::Value *Fixed = CGM.getReplSlot(V))
      return Fixed;
    assert(Slots.count(V) && "local of another func");
    return Slots.lookup(V);
  }
  const auto *P = llvm::cast<ParamDecl>(Dcl);
  if (const auto *T = llvm::dyn_cast_or_null<TaskDecl>(P->Owner)) {
    if (T == Task)
      return nullptr;
    return getFrameFieldPtr(T, CGM.getFrame(T).Fields.lookup(P));
  }
  assert(Slots.count(P) && "parameter of another func");
  return Slots.lookup(P);
}

llvm::Value *FunctionEmitter::getLValueAddress(const NameExpr &N) {
  const Decl *Target = N.Kind == NameKind::Local
                           ? static_cast<const Decl *>(N.Local)
                           : static_cast<const Decl *>(N.Param);
  assert((N.Kind == NameKind::Local || N.Kind == NameKind::Param) &&
         "Sema allows assignment only to variables");
  llvm::Value *Addr = getDeclAddress(Target);
  assert(Addr && "Sema rejects assignment to a task parameter");
  return Addr;
}

llvm::Value *FunctionEmitter::emitFieldAddress(const MemberExpr &E) {
  assert(E.Resolved && E.Resolved->FieldOffset && "not a field");
  llvm::Value *Base = emitExpr(E.Base); // A class value: its storage.
  return Builder.CreateConstInBoundsGEP1_64(Builder.getInt8Ty(), Base,
                                            *E.Resolved->FieldOffset,
                                            E.Member.Name + ".addr");
}

llvm::Value *FunctionEmitter::emitElementAddress(const IndexExpr &E) {
  const Expr *Base = E.Base;
  llvm::Value *Array =
      llvm::isa<IndexExpr>(Base)
          ? emitElementAddress(*llvm::cast<IndexExpr>(Base))
          : emitFieldAddress(*llvm::cast<MemberExpr>(Base));
  llvm::Value *Index;
  if (E.ConstIndex) {
    Index = Builder.getInt32(*E.ConstIndex); // Checked by Sema.
  } else {
    // Clamped into [0, Extent - 1] (docs/language.md, "Array fields"): an
    // index never leaves the array, so compiled code stays memory safe.
    Index = emitExpr(E.Index);
    Index = Builder.CreateBinaryIntrinsic(llvm::Intrinsic::smax, Index,
                                          Builder.getInt32(0));
    Index = Builder.CreateBinaryIntrinsic(llvm::Intrinsic::smin, Index,
                                          Builder.getInt32(E.Extent - 1),
                                          nullptr, "index.clamped");
  }
  llvm::Type *Element = llvm::ArrayType::get(Builder.getInt8Ty(), E.Stride);
  return Builder.CreateInBoundsGEP(Element, Array, Index, "element.addr");
}

llvm::Value *FunctionEmitter::emitFieldLoad(const Type *T, const NativeType &NT,
                                            llvm::Value *Addr) {
  const auto Native = ModuleEmitter::Access::Native;
  unsigned Size = NT.StorageSize;
  if (T->isClass())
    return Addr;
  if (T->isFloat()) {
    if (Size == 8)
      return Builder.CreateFPTrunc(
          createLoad(Native, Builder.getDoubleTy(), Addr),
          Builder.getFloatTy());
    return createLoad(Native, Builder.getFloatTy(), Addr);
  }
  if (T->isString())
    return createLoad(Native, Builder.getPtrTy(), Addr);
  if (Size == 0 || Size > 4)
    Size = T->isBool() ? 1 : 4;
  llvm::Value *V = createLoad(Native, Builder.getIntNTy(Size * 8), Addr);
  if (T->isBool())
    return Builder.CreateICmpNE(V, llvm::ConstantInt::get(V->getType(), 0));
  // Narrow storage extends as its C++ type does: int8_t -1 is -1, uint8_t
  // 255 is 255 (a sign extension would make it -1).
  if (Size < 4)
    V = NT.Unsigned ? Builder.CreateZExt(V, Builder.getInt32Ty())
                    : Builder.CreateSExt(V, Builder.getInt32Ty());
  return V;
}

void FunctionEmitter::emitFieldStore(const Type *T, const NativeType &NT,
                                     llvm::Value *V, llvm::Value *Addr) {
  const auto Native = ModuleEmitter::Access::Native;
  unsigned Size = NT.StorageSize;
  if (T->isClass())
    return emitClassCopy(T->getClass(), Addr, V, /*DstConstructed=*/true);
  if (T->isFloat()) {
    if (Size == 8)
      V = Builder.CreateFPExt(V, Builder.getDoubleTy());
    createStore(Native, V, Addr);
    return;
  }
  if (T->isString()) {
    createStore(Native, V, Addr);
    return;
  }
  if (Size == 0 || Size > 4)
    Size = T->isBool() ? 1 : 4;
  createStore(Native, Builder.CreateZExtOrTrunc(V, Builder.getIntNTy(Size * 8)),
              Addr);
}

llvm::AllocaInst *FunctionEmitter::createClassTemp(const NativeClass *C,
                                                   const llvm::Twine &Name) {
  llvm::Type *Ty = CGM.getClassMemoryType(C);
  auto *A = new llvm::AllocaInst(Ty, 0, Name, EntryPoint);
  A->setAlignment(CGM.getModule().getDataLayout().getABITypeAlign(Ty));
  return A;
}

/// The widest unit (1, 2 or 4 bytes) that the class's size and alignment
/// allow for copies and zeroing by explicit loads and stores.
static unsigned getCopyUnit(const NativeClass *C) {
  for (unsigned U : {4u, 2u})
    if (C->Align >= U && C->Size % U == 0)
      return U;
  return 1;
}

void ModuleEmitter::emitClassInit(llvm::IRBuilderBase &IRB,
                                  const NativeClass *C, llvm::Value *Addr) {
  // Explicit stores, never memset (no libc in the object).
  unsigned U = getCopyUnit(C);
  llvm::Type *UnitTy = IRB.getIntNTy(U * 8);
  for (uint64_t Off = 0; Off < C->Size; Off += U)
    IRB.CreateAlignedStore(
        llvm::ConstantInt::get(UnitTy, 0),
        IRB.CreateConstInBoundsGEP1_64(IRB.getInt8Ty(), Addr, Off),
        llvm::Align(U));
  if (!C->Construct.empty())
    IRB.CreateCall(getLifeThunk(C, C->Construct, 1), {Addr});
}

void FunctionEmitter::emitClassInit(const NativeClass *C, llvm::Value *Addr) {
  CGM.emitClassInit(Builder, C, Addr);
}

void FunctionEmitter::emitClassCopy(const NativeClass *C, llvm::Value *Dst,
                                    llvm::Value *Src, bool DstConstructed) {
  if (Dst == Src)
    return;
  if (!C->CopiesAsBytes) {
    if (DstConstructed && !C->Assign.empty()) {
      Builder.CreateCall(CGM.getLifeThunk(C, C->Assign, 2), {Dst, Src});
      return;
    }
    if (!C->Copy.empty()) {
      // Without an assign thunk, assignment is destroy + copy-construct.
      if (DstConstructed && ModuleEmitter::needsDestroy(C))
        emitDestroy(C, Dst);
      Builder.CreateCall(CGM.getLifeThunk(C, C->Copy, 2), {Dst, Src});
      return;
    }
    // Not copyable: Sema reports every copy (err_class_not_copyable).
  }
  // Loads first, then stores: the source may overlap the destination.
  unsigned U = getCopyUnit(C);
  llvm::Type *UnitTy = Builder.getIntNTy(U * 8);
  llvm::SmallVector<llvm::Value *, 8> Units;
  for (uint64_t Off = 0; Off < C->Size; Off += U)
    Units.push_back(Builder.CreateAlignedLoad(
        UnitTy,
        Builder.CreateConstInBoundsGEP1_64(Builder.getInt8Ty(), Src, Off),
        llvm::Align(U)));
  uint64_t Off = 0;
  for (llvm::Value *V : Units) {
    Builder.CreateAlignedStore(
        V, Builder.CreateConstInBoundsGEP1_64(Builder.getInt8Ty(), Dst, Off),
        llvm::Align(U));
    Off += U;
  }
}

llvm::Value *
FunctionEmitter::emitNativeCall(const NativeFunction &NF, llvm::Value *Self,
                                llvm::ArrayRef<const Expr *> Args) {
  llvm::SmallVector<llvm::Value *, 4> Values;
  for (const Expr *A : Args)
    Values.push_back(emitExpr(A));
  return emitNativeCallWithValues(NF, Self, Values);
}

llvm::Value *FunctionEmitter::emitNativeCallWithValues(
    const NativeFunction &NF, llvm::Value *Self,
    llvm::ArrayRef<llvm::Value *> Values) {
  // `bsc verify --model`: the model stands for the C++, but in itself
  // (where a call of the C++ is what it constrains).
  if (const FuncDecl *Model = CGM.getModel(NF); Model && Model != &D) {
    llvm::SmallVector<llvm::Value *, 4> Args;
    if (Self)
      Args.push_back(Self);
    Args.append(Values.begin(), Values.end());
    return emitCallWithValues(*Model, NF.ResultViaOut ? NF.Result.TheClass
                                                      : nullptr,
                              Args);
  }
  llvm::FunctionCallee Callee = CGM.getNative(NF);
  llvm::FunctionType *FTy = Callee.getFunctionType();
  llvm::SmallVector<llvm::Value *, 6> Args;
  llvm::AllocaInst *Out = nullptr;
  if (NF.ResultViaOut) {
    assert(NF.Result.TheClass && "a class result names its class");
    Out = createClassTemp(NF.Result.TheClass, NF.Name);
    Args.push_back(Out);
  }
  if (NF.hasSelf()) {
    assert(Self && "a member call needs its object");
    Args.push_back(Self);
  }
  // bs::Context & is the state, whose header bs::Context is.
  if (NF.TakesContext)
    Args.push_back(StatePtr);
  for (llvm::Value *V : Values) {
    llvm::Type *PTy = FTy->getParamType(Args.size());
    // The C ABI: bool is an int32 0/1; ints promote to float parameters;
    // class values are already pointers to their storage.
    if (V->getType()->isIntegerTy(1))
      V = Builder.CreateZExt(V, PTy);
    else if (PTy->isFloatTy() && V->getType()->isIntegerTy(32))
      V = Builder.CreateSIToFP(V, PTy);
    Args.push_back(V);
  }
  // The probe names the binding should it crash (CodeGenOptions::Probes).
  bool Probe = CGM.getOptions().Probes;
  if (Probe) {
    bool Standard;
    std::string Name = CGM.getNativeName(NF, Standard);
    emitProbe(NativeProbeSymbol,
              CGM.addSite({DebugSite::NativeCall, &D, CurStmtLoc, Name,
                           NF.TakesContext}));
  }
  llvm::CallInst *Call = Builder.CreateCall(
      Callee, Args, FTy->getReturnType()->isVoidTy() || Out ? "" : NF.Name);
  if (Probe)
    emitProbe(NativeProbeSymbol, 0);
  if (Out) {
    pushTemp(NF.Result.TheClass, Out);
    return Out;
  }
  if (NF.Result.TheCode == NativeType::Void)
    return Call;
  if (NF.Result.TheCode == NativeType::Bool)
    return Builder.CreateICmpNE(Call, Builder.getInt32(0), "tobool");
  return Call;
}

llvm::Value *FunctionEmitter::emitGlobalIOPointer(NameKind K) {
  assert((K == NameKind::Input || K == NameKind::Output) && "not a global");
  // The embedding passes this cycle's input and output to bs_begin_cycle,
  // which keeps them in the state header.
  unsigned Field = K == NameKind::Input ? StateInput : StateOutput;
  llvm::Value *Addr = Builder.CreateConstInBoundsGEP2_32(
      CGM.getStateType(), StatePtr, 0, Field,
      K == NameKind::Input ? "input.addr" : "output.addr");
  return createLoad(ModuleEmitter::Access::State, Builder.getPtrTy(), Addr,
                    K == NameKind::Input ? "input" : "output");
}

llvm::Value *FunctionEmitter::emitCond(const Expr *E) {
  llvm::Value *V = emitExpr(E);
  assert(V->getType()->isIntegerTy(1) && "Sema makes conditions bool");
  return V;
}

llvm::Value *FunctionEmitter::emitExpr(const Expr *E) {
  // CodeGenOptions::Explain: an operand of the condition being lowered
  // also goes into the condition's record (CGExplain.cpp).
  if (Explaining)
    if (llvm::Value *V = emitExplainedOperand(E))
      return V;
  switch (E->getKind()) {
  case NodeKind::IntLiteralExpr:
    return Builder.getInt32(llvm::cast<IntLiteralExpr>(E)->Value);
  case NodeKind::FloatLiteralExpr:
    return llvm::ConstantFP::get(Builder.getFloatTy(),
                                 llvm::cast<FloatLiteralExpr>(E)->Value);
  case NodeKind::BoolLiteralExpr:
    return Builder.getInt1(llvm::cast<BoolLiteralExpr>(E)->Value);
  case NodeKind::StringLiteralExpr:
    return CGM.getString(llvm::cast<StringLiteralExpr>(E)->Value);
  case NodeKind::NameExpr:
    return emitName(*llvm::cast<NameExpr>(E));
  case NodeKind::MemberExpr:
    return emitMember(*llvm::cast<MemberExpr>(E));
  case NodeKind::IndexExpr: {
    // An element (arrays are never values: Sema): loaded as the field
    // stores it, or for a class element its storage.
    const auto &IE = *llvm::cast<IndexExpr>(E);
    return emitFieldLoad(IE.Ty, *IE.Field, emitElementAddress(IE));
  }
  case NodeKind::CallExpr:
    return emitCall(*llvm::cast<CallExpr>(E));
  case NodeKind::UnaryExpr:
    return emitUnary(*llvm::cast<UnaryExpr>(E));
  case NodeKind::BinaryExpr:
    return emitBinary(*llvm::cast<BinaryExpr>(E));
  case NodeKind::TaskStateExpr:
    return emitTaskState(llvm::cast<TaskStateExpr>(E)->Task);
  case NodeKind::ConversionExpr:
    return emitConversion(*llvm::cast<ConversionExpr>(E));
  case NodeKind::ErrorExpr:
    llvm_unreachable("a behavior with a parse error never reaches CodeGen");
#define DECL(Class) case NodeKind::Class:
#define STMT(Class) case NodeKind::Class:
#include "bsc/AST/ASTNodes.def"
    break;
  }
  llvm_unreachable("not an expression");
}

llvm::Value *FunctionEmitter::emitName(const NameExpr &E) {
  switch (E.Kind) {
  case NameKind::Local:
    return emitLoad(E.Local->Ty, getDeclAddress(E.Local),
                    E.Local->getName().Name);
  case NameKind::Param:
    if (llvm::Value *Addr = getDeclAddress(E.Param))
      return emitLoad(E.Param->Ty, Addr, E.Param->getName().Name);
    return Fn->getArg(E.Param->Index + getFirstParamArg());
  case NameKind::EnumValue:
    return Builder.getInt32(E.EnumValue);
  case NameKind::Constant: {
    // Sema computed the value.
    const ConstDecl &C = *E.Const;
    if (C.Ty->isFloat())
      return llvm::ConstantFP::get(Builder.getFloatTy(), C.Value.Float);
    if (C.Ty->isBool())
      return Builder.getInt1(C.Value.Bool);
    if (C.Ty->isString())
      return CGM.getString(C.Value.String);
    return Builder.getInt32(C.Value.Int);
  }
  case NameKind::Input:
  case NameKind::Output:
    return emitGlobalIOPointer(E.Kind);
  case NameKind::Callable:
  case NameKind::NativeFunction:
  case NameKind::Unresolved:
    break;
  }
  llvm_unreachable("Sema allows callables only as callees");
}

llvm::Value *FunctionEmitter::emitMember(const MemberExpr &E) {
  // `input.ball.position.x`: offsets from the input pointer for fields,
  // the getter thunk for properties (and fields without an offset).
  if (E.TaskField) {
    // `Striker.state` at the prompt: the field where the state keeps it.
    const auto *V = llvm::dyn_cast<VarDecl>(E.TaskField);
    const Type *T = V ? V->Ty : llvm::cast<ParamDecl>(E.TaskField)->Ty;
    return emitLoad(T, getDeclAddress(E.TaskField),
                    E.TaskField->getName().Name);
  }
  const NativeFunction &NF = *E.Resolved;
  assert(NF.isData() && "a method is only a callee (emitCall)");
  if (NF.Kind == NativeFunction::Field && NF.FieldOffset)
    return emitFieldLoad(E.Ty, NF.Result, emitFieldAddress(E));
  return emitNativeCallWithValues(NF, emitExpr(E.Base), {});
}

llvm::Value *FunctionEmitter::emitCall(const CallExpr &E) {
  switch (E.Kind) {
  case CallKind::Func:
  case CallKind::Task: {
    // Tasks and funcs alike: (state, args...). A task call runs one step.
    llvm::SmallVector<llvm::Value *, 4> Values;
    for (const Expr *A : E.Args)
      Values.push_back(emitExpr(A));
    llvm::Value *Call = emitCallWithValues(
        *E.Target, E.Ty->isClass() ? E.Ty->getClass() : nullptr, Values);
    if (E.Kind == CallKind::Task)
      LastTaskCall = llvm::cast<llvm::CallInst>(Call);
    return Call;
  }
  case CallKind::NativeFunction:
    return emitNativeCall(*E.NativeFn, nullptr, E.Args);
  case CallKind::Method: {
    // `a.abs()`: the thunk gets the object's storage after the out pointer.
    const auto *ME = llvm::cast<MemberExpr>(E.Callee);
    return emitNativeCall(*E.NativeFn, emitExpr(ME->Base), E.Args);
  }
  case CallKind::Unresolved:
    break;
  }
  llvm_unreachable("Sema resolves every call");
}

llvm::Value *
FunctionEmitter::emitCallWithValues(const CallableDecl &Target,
                                    const NativeClass *ResultClass,
                                    llvm::ArrayRef<llvm::Value *> Values) {
  llvm::Function *Callee = CGM.getFunction(&Target);
  llvm::SmallVector<llvm::Value *, 4> Args = {StatePtr};
  llvm::AllocaInst *Out = nullptr;
  if (ModuleEmitter::returnsClass(Target)) {
    Out = createClassTemp(ResultClass, Target.getName().Name);
    Args.push_back(Out);
  }
  for (llvm::Value *V : Values) {
    llvm::Type *PTy = Callee->getArg(Args.size())->getType();
    if (PTy->isFloatTy() && V->getType()->isIntegerTy(32))
      V = Builder.CreateSIToFP(V, PTy);
    Args.push_back(V);
  }
  if (Out) {
    Builder.CreateCall(Callee, Args);
    pushTemp(ResultClass, Out);
    return Out;
  }
  if (Callee->getReturnType()->isVoidTy())
    return Builder.CreateCall(Callee, Args);
  return Builder.CreateCall(Callee, Args, Target.getName().Name);
}

llvm::Value *FunctionEmitter::emitUnary(const UnaryExpr &E) {
  if (E.Operator) // `-v` on a class value: its `_neg_`.
    return emitNativeCall(*E.Operator, emitExpr(E.Operand), {});
  llvm::Value *V = emitExpr(E.Operand);
  switch (E.Op) {
  case UnaryOp::Neg:
    if (V->getType()->isFloatTy())
      return Builder.CreateFNeg(V);
    // 0 - x without nsw: -INT_MIN wraps to INT_MIN.
    return Builder.CreateSub(Builder.getInt32(0), V, "neg");
  case UnaryOp::Not:
    return Builder.CreateNot(V, "not");
  }
  llvm_unreachable("unknown unary operator");
}

llvm::Value *FunctionEmitter::emitBinary(const BinaryExpr &E) {
  if (E.Op == BinaryOp::And || E.Op == BinaryOp::Or)
    return emitLogical(E);
  if (E.Operator) {
    // A class-typed LHS: the operator's method with RHS as its argument.
    llvm::Value *Self = emitExpr(E.LHS);
    llvm::Value *R = emitNativeCall(*E.Operator, Self, {E.RHS});
    if (E.NegateOperator)
      return Builder.CreateNot(R, "not");
    return R;
  }
  llvm::Value *L = emitExpr(E.LHS);
  llvm::Value *R = emitExpr(E.RHS);
  if (E.LHS->Ty->isString()) {
    // Contents, not pointers: equal literals need not share one global.
    llvm::Value *Eq = Builder.CreateCall(CGM.getStringEquals(), {L, R}, "str.eq");
    return E.Op == BinaryOp::Eq ? Eq : Builder.CreateNot(Eq, "str.ne");
  }
  if (E.StateTest != BinaryExpr::StateKindTest::None) {
    // The kind of a state (docs/language.md, Tasks): the other side's.
    llvm::Value *State = E.NamedStateOnLeft ? R : L;
    llvm::Value *Is =
        E.StateTest == BinaryExpr::StateKindTest::Running
            ? Builder.CreateICmpSGT(State, Builder.getInt32(0), "is.running")
            : Builder.CreateICmpSLT(State, Builder.getInt32(0), "is.failure");
    return E.Op == BinaryOp::Eq ? Is : Builder.CreateNot(Is, "not");
  }
  // Sema promotes mixed int/float operands; this only guards the IR.
  if (L->getType()->isFloatTy() && R->getType()->isIntegerTy(32))
    R = Builder.CreateSIToFP(R, L->getType());
  if (R->getType()->isFloatTy() && L->getType()->isIntegerTy(32))
    L = Builder.CreateSIToFP(L, R->getType());
  return emitArith(E.Op, L, R);
}

llvm::Value *FunctionEmitter::emitLogical(const BinaryExpr &E) {
  llvm::LLVMContext &Ctx = CGM.getContext();
  bool IsAnd = E.Op == BinaryOp::And;
  llvm::Value *L = emitCond(E.LHS);
  llvm::BasicBlock *LHSEnd = Builder.GetInsertBlock();
  llvm::BasicBlock *RHSBB =
      llvm::BasicBlock::Create(Ctx, IsAnd ? "and.rhs" : "or.rhs", Fn);
  llvm::BasicBlock *EndBB =
      llvm::BasicBlock::Create(Ctx, IsAnd ? "and.end" : "or.end");
  // The right operand runs only when the left one does not decide: it may
  // call a task, which must then not advance.
  if (IsAnd)
    Builder.CreateCondBr(L, RHSBB, EndBB);
  else
    Builder.CreateCondBr(L, EndBB, RHSBB);
  // The right operand's temporaries die at its end, so that only those of
  // the operand that ran are destroyed (no flags).
  Builder.SetInsertPoint(RHSBB);
  llvm::Value *R = emitFullCond(E.RHS);
  llvm::BasicBlock *RHSEnd = Builder.GetInsertBlock();
  Builder.CreateBr(EndBB);

  EndBB->insertInto(Fn);
  Builder.SetInsertPoint(EndBB);
  llvm::PHINode *Phi =
      Builder.CreatePHI(Builder.getInt1Ty(), 2, IsAnd ? "and" : "or");
  Phi->addIncoming(Builder.getInt1(!IsAnd), LHSEnd);
  Phi->addIncoming(R, RHSEnd);
  return Phi;
}

llvm::Value *FunctionEmitter::emitSafeIntDivRem(bool IsRem, llvm::Value *L,
                                                llvm::Value *R) {
  llvm::Value *Zero = Builder.getInt32(0);
  llvm::Value *One = Builder.getInt32(1);
  llvm::Value *IsZero = Builder.CreateICmpEQ(R, Zero, "div.zero");
  llvm::Value *IsIntMin =
      Builder.CreateICmpEQ(L, Builder.getInt32(INT32_MIN), "div.intmin");
  llvm::Value *IsMinus1 =
      Builder.CreateICmpEQ(R, Builder.getInt32(-1), "div.minus1");
  llvm::Value *Overflow = Builder.CreateAnd(IsIntMin, IsMinus1, "div.ovf");
  // Dividing by 1 instead is always defined and, for INT_MIN / -1, already
  // gives the wrapped quotient INT_MIN and the remainder 0.
  llvm::Value *Divisor = Builder.CreateSelect(
      Builder.CreateOr(IsZero, Overflow, "div.unsafe"), One, R, "div.safe");
  if (IsRem) {
    llvm::Value *Rem = Builder.CreateSRem(L, Divisor, "rem");
    // x % 0 == x keeps a == (a / b) * b + a % b true for b == 0.
    return Builder.CreateSelect(IsZero, L, Rem, "rem.res");
  }
  llvm::Value *Quot = Builder.CreateSDiv(L, Divisor, "div");
  return Builder.CreateSelect(IsZero, Zero, Quot, "div.res");
}

llvm::Value *FunctionEmitter::emitFloatRem(llvm::Value *L, llvm::Value *R) {
  // a - b * trunc(a / b). trunc is done by an int round trip where the
  // quotient fits (|q| < 2^23 is exact in i32) and is q itself beyond that
  // (such floats are integral already): llvm.trunc would become a truncf
  // call on an x87 target, and frem a call of fmodf. IEEE semantics carry
  // NaN and infinities through (b == 0 gives NaN, as fmod does).
  llvm::Type *FloatTy = L->getType();
  llvm::Value *Q = Builder.CreateFDiv(L, R, "frem.q");
  llvm::Value *AbsQ = Builder.CreateUnaryIntrinsic(llvm::Intrinsic::fabs, Q);
  llvm::Value *Small = Builder.CreateFCmpOLT(
      AbsQ, llvm::ConstantFP::get(FloatTy, 8388608.0), "frem.small");
  // Saturating, so the arm not selected is not poison for huge or NaN q.
  llvm::Value *QI = Builder.CreateIntrinsic(
      llvm::Intrinsic::fptosi_sat, {Builder.getInt32Ty(), FloatTy}, {Q});
  llvm::Value *Trunc = Builder.CreateSelect(
      Small, Builder.CreateSIToFP(QI, FloatTy), Q, "frem.t");
  return Builder.CreateFSub(L, Builder.CreateFMul(R, Trunc), "frem");
}

llvm::Value *FunctionEmitter::emitArith(BinaryOp Op, llvm::Value *L,
                                        llvm::Value *R) {
  bool IsFloat = L->getType()->isFloatTy();
  switch (Op) {
  case BinaryOp::Add:
    return IsFloat ? Builder.CreateFAdd(L, R, "add")
                   : Builder.CreateAdd(L, R, "add");
  case BinaryOp::Sub:
    return IsFloat ? Builder.CreateFSub(L, R, "sub")
                   : Builder.CreateSub(L, R, "sub");
  case BinaryOp::Mul:
    return IsFloat ? Builder.CreateFMul(L, R, "mul")
                   : Builder.CreateMul(L, R, "mul");
  case BinaryOp::Div:
    return IsFloat ? Builder.CreateFDiv(L, R, "div")
                   : emitSafeIntDivRem(/*IsRem=*/false, L, R);
  case BinaryOp::Rem:
    return IsFloat ? emitFloatRem(L, R)
                   : emitSafeIntDivRem(/*IsRem=*/true, L, R);
  // Float comparisons are ordered except !=, as in C: NaN compares unequal
  // to everything and nothing else is true of it.
  case BinaryOp::Lt:
    return IsFloat ? Builder.CreateFCmpOLT(L, R, "lt")
                   : Builder.CreateICmpSLT(L, R, "lt");
  case BinaryOp::Le:
    return IsFloat ? Builder.CreateFCmpOLE(L, R, "le")
                   : Builder.CreateICmpSLE(L, R, "le");
  case BinaryOp::Gt:
    return IsFloat ? Builder.CreateFCmpOGT(L, R, "gt")
                   : Builder.CreateICmpSGT(L, R, "gt");
  case BinaryOp::Ge:
    return IsFloat ? Builder.CreateFCmpOGE(L, R, "ge")
                   : Builder.CreateICmpSGE(L, R, "ge");
  case BinaryOp::Eq:
    return IsFloat ? Builder.CreateFCmpOEQ(L, R, "eq")
                   : Builder.CreateICmpEQ(L, R, "eq");
  case BinaryOp::Ne:
    return IsFloat ? Builder.CreateFCmpUNE(L, R, "ne")
                   : Builder.CreateICmpNE(L, R, "ne");
  case BinaryOp::And:
  case BinaryOp::Or:
    break;
  }
  llvm_unreachable("logical operators short-circuit (emitLogical)");
}

llvm::Value *FunctionEmitter::emitConversion(const ConversionExpr &E) {
  llvm::Value *V = emitExpr(E.Operand);
  llvm::Type *From = V->getType();
  llvm::Type *To = CGM.getValueType(E.Ty);
  if (From == To) // int(TaskState), int(enum), float(float), ...
    return V;
  if (To->isFloatTy()) {
    // bool -> 0.0/1.0; int -> nearest float.
    if (From->isIntegerTy(1))
      return Builder.CreateUIToFP(V, To, "conv");
    return Builder.CreateSIToFP(V, To, "conv");
  }
  if (To->isIntegerTy(1)) {
    // bool(x) is x != 0, as in C (NaN is true).
    if (From->isFloatTy())
      return Builder.CreateFCmpUNE(V, llvm::ConstantFP::get(From, 0.0),
                                   "tobool");
    return Builder.CreateICmpNE(V, llvm::ConstantInt::get(From, 0), "tobool");
  }
  assert(To->isIntegerTy(32) && "conversions produce int, float or bool");
  if (From->isIntegerTy(1))
    return Builder.CreateZExt(V, To, "conv");
  // Saturating: out-of-range floats clamp to INT_MIN/INT_MAX, NaN is 0.
  return Builder.CreateIntrinsic(llvm::Intrinsic::fptosi_sat, {To, From}, {V},
                                 nullptr, "conv");
}

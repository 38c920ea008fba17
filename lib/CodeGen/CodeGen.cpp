//===- CodeGen.cpp - a checked behavior to one LLVM module ----------------===//
//
// The entry point `emitLLVM` and everything that concerns the module as a
// whole: the behavior-state and frame struct types, the functions of funcs
// and tasks, the exported entries, the `bs_<B>_info` table and the optional
// program `main`. The ABI these implement is include/bscript/bscript.h and
// docs/design/backend.md; the numbers that robot code sees (state size,
// alignment, frame offsets) are computed only here, from the target's
// DataLayout, and no optimisation level can change them because every
// frame is an explicit struct type rather than something a pass computes
// (which is why tasks are lowered by hand and not with llvm.coro.*).
//
//===----------------------------------------------------------------------===//
#include "CodeGenImpl.h"
#include "bscript/bscript.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/IR/Function.h"
#include "llvm/IR/GlobalVariable.h"
#include "llvm/IR/InstIterator.h"
#include "llvm/IR/MDBuilder.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Transforms/Utils/BasicBlockUtils.h"

using namespace bsc;
using namespace bsc::codegen;

/// The ABI version written into bs_behavior_info: the runtime's.
static constexpr uint32_t ABIVersion = BS_ABI_VERSION;

std::string bsc::getEntrySymbol(llvm::StringRef BehaviorName,
                                const CallableDecl &D) {
  std::string S = "bs_" + BehaviorName.str() + "__";
  if (D.Module)
    S += D.Module->Name;
  return S + "__" + D.getName().Name.str();
}

/// The name of the internal function of a func or task: `bs.M.f`, and
/// `bs.M.task.f` for a func nested in a task. Dots cannot occur in
/// b-script names, so these never clash with each other or with exports.
static std::string getInternalName(const CallableDecl &D) {
  std::string S = "bs.";
  if (D.Module)
    S += D.Module->Name + ".";
  if (const auto *F = llvm::dyn_cast<FuncDecl>(&D))
    if (F->EnclosingTask)
      S += F->EnclosingTask->getName().Name.str() + ".";
  return S + D.getName().Name.str();
}

//===----------------------------------------------------------------------===//
// ModuleEmitter
//===----------------------------------------------------------------------===//

ModuleEmitter::ModuleEmitter(const Behavior &B, llvm::Module &M,
                             const CodeGenOptions &Opts, BehaviorLayout &Layout)
    : B(B), M(M), Ctx(M.getContext()), Opts(Opts), Layout(Layout) {
  llvm::MDBuilder MDB(Ctx);
  llvm::MDNode *Root = MDB.createTBAARoot("bsc memory");
  auto Tag = [&](llvm::StringRef Name) {
    llvm::MDNode *Ty = MDB.createTBAAScalarTypeNode(Name, Root);
    return MDB.createTBAAStructTagNode(Ty, Ty, 0);
  };
  AccessTags[unsigned(Access::State)] = Tag("behavior state");
  AccessTags[unsigned(Access::Native)] = Tag("registered C++ field");
  AccessTags[unsigned(Access::TraceRecord)] = Tag("trace record");
  AccessTags[unsigned(Access::Budget)] = Tag("budget record");
}

llvm::Type *ModuleEmitter::getValueType(const Type *T) {
  switch (T->getKind()) {
  case TypeKind::Void:
    return llvm::Type::getVoidTy(Ctx);
  case TypeKind::Int:
  case TypeKind::TaskState:
  case TypeKind::Enum:
    return llvm::Type::getInt32Ty(Ctx);
  case TypeKind::Float:
    return llvm::Type::getFloatTy(Ctx);
  case TypeKind::Bool:
    return llvm::Type::getInt1Ty(Ctx);
  case TypeKind::String:
    return llvm::PointerType::getUnqual(Ctx);
  case TypeKind::Class:
    // A pointer to the value's storage (CodeGenImpl.h).
    return llvm::PointerType::getUnqual(Ctx);
  case TypeKind::Error:
  case TypeKind::Array: // Only indexed (IndexExpr), never a value.
    break;
  }
  llvm_unreachable("the error type never reaches code generation");
}

llvm::Type *ModuleEmitter::getMemoryType(const Type *T) {
  if (T->isBool())
    return llvm::Type::getInt8Ty(Ctx);
  if (T->isClass())
    return getClassMemoryType(T->getClass());
  return getValueType(T);
}

llvm::Type *ModuleEmitter::getClassMemoryType(const NativeClass *C) {
  uint64_t Align = C->Align ? C->Align : 1;
  if (Align == 1 || C->Size % Align != 0)
    return llvm::ArrayType::get(llvm::Type::getInt8Ty(Ctx), C->Size);
  // A unit of Align bytes whose ABI alignment on this target is Align, so
  // that frames, the state and allocas get the class's alignment from the
  // DataLayout (i64 is only 4-aligned on i586; vectors are size-aligned).
  const llvm::DataLayout &DL = M.getDataLayout();
  llvm::Type *Unit = nullptr;
  for (unsigned Bits : {16u, 32u, 64u, 128u}) {
    llvm::Type *I = llvm::Type::getIntNTy(Ctx, Bits);
    if (Bits / 8 == Align && DL.getABITypeAlign(I).value() == Align &&
        DL.getTypeAllocSize(I) == Align) {
      Unit = I;
      break;
    }
  }
  if (!Unit)
    Unit = llvm::FixedVectorType::get(llvm::Type::getInt8Ty(Ctx), Align);
  return llvm::ArrayType::get(Unit, C->Size / Align);
}

bool ModuleEmitter::returnsClass(const CallableDecl &D) {
  const auto *F = llvm::dyn_cast<FuncDecl>(&D);
  return F && F->ResultTy && F->ResultTy->isClass();
}

bool ModuleEmitter::needsDestroy(const NativeClass *C) {
  return C && !C->TriviallyDestructible && !C->Destroy.empty();
}

bool ModuleEmitter::needsDestroy(const Type *T) {
  return T && T->isClass() && needsDestroy(T->getClass());
}

llvm::Constant *ModuleEmitter::getZeroValue(const Type *T) {
  // A string local without initialiser is "" rather than null: it may be
  // passed to C code that expects a valid `const char *`.
  if (T->isString())
    return getString("");
  return llvm::Constant::getNullValue(getMemoryType(T));
}

const FrameInfo &ModuleEmitter::getFrame(const TaskDecl *T) const {
  auto It = Frames.find(T);
  assert(It != Frames.end() && "task is not part of the behavior");
  return It->second;
}

llvm::Function *ModuleEmitter::getFunction(const CallableDecl *D) const {
  auto It = Functions.find(D);
  assert(It != Functions.end() && "callable is not part of the behavior");
  return It->second;
}

llvm::Type *ModuleEmitter::getNativeType(const NativeType &NT) {
  switch (NT.TheCode) {
  case NativeType::Void:
    return llvm::Type::getVoidTy(Ctx);
  case NativeType::Bool: // C ABI: bool travels as a 0/1 int32 (bscript.h).
  case NativeType::Int:
  case NativeType::Enum:
    return llvm::Type::getInt32Ty(Ctx);
  case NativeType::Float:
    return llvm::Type::getFloatTy(Ctx);
  case NativeType::String:
    return llvm::PointerType::getUnqual(Ctx);
  case NativeType::Class: // const T * / T *.
    return llvm::PointerType::getUnqual(Ctx);
  }
  llvm_unreachable("unknown native type");
}

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

void ModuleEmitter::addCommonAttributes(llvm::Function *F) {
  F->addFnAttr(llvm::Attribute::NoUnwind);
  F->addFnAttr("no-builtins");
  // Unwind tables (.eh_frame), as C++ compilers emit them on x86: a
  // debugger or crash handler stopped in registered C++ walks back through
  // the tasks that called it. They take space in the object, not time.
  F->setUWTableKind(llvm::UWTableKind::Async);
}

uint64_t ModuleEmitter::getFrameFieldOffset(const TaskDecl *T,
                                            unsigned Field) const {
  const llvm::DataLayout &DL = M.getDataLayout();
  const FrameInfo &FI = getFrame(T);
  return DL.getStructLayout(StateTy)->getElementOffset(FI.StateFieldNo) +
         DL.getStructLayout(FI.Ty)->getElementOffset(Field);
}

uint64_t ModuleEmitter::getTaskWordOffset(const TaskDecl *T,
                                          TaskWord W) const {
  const FrameInfo &FI = getFrame(T);
  const TaskWordInfo &Word = FI.getWord(W);
  if (Word.InFrame)
    return getFrameFieldOffset(T, Word.Field);
  const llvm::DataLayout &DL = M.getDataLayout();
  auto *Headers = llvm::cast<llvm::StructType>(
      StateTy->getElementType(HeadersField));
  return DL.getStructLayout(StateTy)->getElementOffset(HeadersField) +
         DL.getStructLayout(Headers)->getElementOffset(FI.HeaderFieldNo) +
         DL.getStructLayout(FI.HeaderTy)->getElementOffset(Word.Field);
}

void ModuleEmitter::chooseTaskWords(const TaskDecl &T, FrameInfo &FI) {
  // The resume point counts the yields (0: the top).
  size_t Yields = T.Yields.size();
  unsigned ResumeBits = Yields <= 0xff ? 8 : Yields <= 0xffff ? 16 : 32;
  // The state: running at the reset, done at the end, and each yield's.
  bool SmallStates = !planYields(T).ComputedStates;
  for (const YieldStmt *Y : T.Yields)
    if (std::optional<int64_t> V = getConstantState(Y->Value))
      SmallStates &= *V >= INT8_MIN && *V <= INT8_MAX;
  unsigned StateBits = SmallStates ? 8 : 32;

  llvm::SmallVector<llvm::Type *, 2> Narrow;
  std::string Name = "bs.header.";
  if (T.Module)
    Name += T.Module->Name + ".";
  Name += T.getName().Name.str();
  for (auto [W, Bits] : {std::pair(&FI.Resume, ResumeBits),
                         std::pair(&FI.State, StateBits)}) {
    W->Ty = llvm::Type::getIntNTy(Ctx, Bits);
    W->InFrame = Bits == 32;
    if (!W->InFrame) {
      W->Field = Narrow.size();
      Narrow.push_back(W->Ty);
    }
  }
  FI.HeaderTy =
      Narrow.empty() ? nullptr : llvm::StructType::create(Ctx, Narrow, Name);
}

void ModuleEmitter::addTaskHeaders(
    llvm::SmallVectorImpl<llvm::Type *> &StateFields) {
  // Widest first, so that none needs padding.
  llvm::SmallVector<const TaskDecl *, 16> Narrow;
  for (const TaskDecl *T : B.Tasks)
    if (Frames[T].HeaderTy)
      Narrow.push_back(T);
  const llvm::DataLayout &DL = M.getDataLayout();
  llvm::stable_sort(Narrow, [&](const TaskDecl *A, const TaskDecl *B) {
    return DL.getABITypeAlign(Frames[A].HeaderTy) >
           DL.getABITypeAlign(Frames[B].HeaderTy);
  });
  HeadersField = 0;
  if (Narrow.empty())
    return;
  llvm::SmallVector<llvm::Type *, 16> Headers;
  for (const TaskDecl *T : Narrow) {
    Frames[T].HeaderFieldNo = Headers.size();
    Headers.push_back(Frames[T].HeaderTy);
  }
  HeadersField = StateFields.size();
  StateFields.push_back(llvm::StructType::create(Ctx, Headers, "bs.headers"));
}

bool ModuleEmitter::keepsInFrame(const Decl *D) const {
  if (Opts.Probes)
    return true;
  if (const auto *P = llvm::dyn_cast<ParamDecl>(D))
    return P->Ty->isClass() || P->ReadByNestedFunc;
  const auto *V = llvm::cast<VarDecl>(D);
  return V->Ty->isClass() || V->LivesAcrossYield || V->UsedByNestedFunc;
}

void ModuleEmitter::layoutState() {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  // bs_state_header: cycle, input, output, user.
  llvm::SmallVector<llvm::Type *, 8> StateFields = {I32, Ptr, Ptr, Ptr};
  for (const TaskDecl *T : B.Tasks) {
    FrameInfo &FI = Frames[T];
    FI.TaskIndex = StateFields.size() - FirstFrameField;
    // The last call; the resume point and state if they take 4 bytes; then
    // params, then locals.
    llvm::SmallVector<llvm::Type *, 8> Fields = {I32};
    std::string Prefix = T->getName().Name.str() + ".";
    FI.FieldNames = {Prefix + "last_call"};
    chooseTaskWords(*T, FI);
    for (TaskWordInfo *W : {&FI.Resume, &FI.State})
      if (W->InFrame) {
        W->Field = Fields.size();
        Fields.push_back(I32);
        FI.FieldNames.push_back(Prefix +
                                (W == &FI.Resume ? "resume" : "state"));
      }
    auto Add = [&](const Decl *D, const Type *Ty) {
      FI.Fields[D] = Fields.size();
      Fields.push_back(getMemoryType(Ty));
      FI.FieldNames.push_back(Prefix + D->getName().Name.str());
    };
    for (const ParamDecl *P : T->Params)
      if (keepsInFrame(P))
        Add(P, P->Ty);
    // Scalar locals whose scopes do not overlap (`for(int j...)` after
    // `for(int i...)`) share a field; the debugger's exact frames do not,
    // nor a local that a nested func may read before its declaration (it
    // must read the zero of the reset, not an earlier local's value).
    struct SharedField {
      unsigned Field;
      llvm::Type *Ty;
      unsigned FreeFrom; ///< ScopeEnd of its newest local.
    };
    llvm::SmallVector<SharedField, 8> Shared;
    for (const VarDecl *V : T->Locals) {
      if (!keepsInFrame(V))
        continue;
      llvm::Type *Ty = getMemoryType(V->Ty);
      unsigned End = V->ScopeEnd ? V->ScopeEnd : ~0u;
      if (!Opts.Probes && !V->Ty->isClass() && !V->ReadBeforeDeclared) {
        auto It = llvm::find_if(Shared, [&](const SharedField &S) {
          return S.Ty == Ty && S.FreeFrom <= V->ScopeBegin;
        });
        if (It != Shared.end()) {
          FI.Fields[V] = It->Field;
          It->FreeFrom = End;
          continue;
        }
        Shared.push_back({unsigned(Fields.size()), Ty, End});
      }
      Add(V, V->Ty);
    }
    // Whether the class values are constructed: the frame must stay
    // zero-initialisable (bs_state_init only zeroes), and a state can be
    // destroyed at any time, also before a task ever ran.
    bool Destructible =
        llvm::any_of(T->Params, [](const ParamDecl *P) {
          return needsDestroy(P->Ty);
        }) ||
        llvm::any_of(T->Locals,
                     [](const VarDecl *V) { return needsDestroy(V->Ty); });
    if (Destructible) {
      FI.LiveField = Fields.size();
      Fields.push_back(llvm::Type::getInt8Ty(Ctx));
      FI.FieldNames.push_back(Prefix + "live");
    }
    std::string Name = "bs.frame.";
    if (T->Module)
      Name += T->Module->Name + ".";
    Name += T->getName().Name.str();
    FI.Ty = llvm::StructType::create(Ctx, Fields, Name);
    FI.StateFieldNo = StateFields.size();
    StateFields.push_back(FI.Ty);
  }
  addTaskHeaders(StateFields);
  // `--instrument`: the trace record, after the frames so that the frames
  // sit where they do without it.
  BehaviorLayout::TraceLayout &Trace = Layout.Trace;
  Trace = {};
  if (Opts.Instrument) {
    // Wide enough for every resume point and the finished value (and with
    // a budget the value below it).
    size_t MostYields = 0;
    for (const TaskDecl *T : B.Tasks)
      MostYields = std::max(MostYields, T->Yields.size());
    Trace.SlotBytes = 1;
    while (MostYields >= (Opts.CycleBudget ? Trace.budgetFailedSlot()
                                           : Trace.finishedSlot()))
      Trace.SlotBytes *= 2;
    Trace.ClearSize = llvm::alignTo(B.Tasks.size() * Trace.SlotBytes, 4);
    if (Opts.CycleBudget) {
      Trace.BudgetWord = Trace.ClearSize;
      Trace.ClearSize += 4;
    }
    Trace.RecordSize = Trace.ClearSize;
    for (const TaskDecl *T : B.Tasks) {
      std::optional<uint64_t> Word;
      if (planYields(*T).ComputedStates) {
        Word = Trace.RecordSize;
        Trace.RecordSize += 4;
      }
      Trace.StateWords.push_back(Word);
    }
    // Never 0, which reads "not instrumented".
    Trace.RecordSize = std::max<uint64_t>(Trace.RecordSize, 4);
    TraceRecordField = StateFields.size();
    StateFields.push_back(llvm::ArrayType::get(I32, Trace.RecordSize / 4));
  }
  // `--cycle-budget`: its record last (bscript.h bs_budget_record).
  Layout.Budget = {};
  if (Opts.CycleBudget) {
    Layout.Budget.Budget = Opts.CycleBudget;
    BudgetRecordField = StateFields.size();
    StateFields.push_back(llvm::ArrayType::get(I32, BudgetRecordWords));
  }
  StateTy = llvm::StructType::create(Ctx, StateFields, "bs.state");

  const llvm::DataLayout &DL = M.getDataLayout();
  const llvm::StructLayout *SL = DL.getStructLayout(StateTy);
  Layout.StateSize = DL.getTypeAllocSize(StateTy);
  Layout.StateAlign = DL.getABITypeAlign(StateTy).value();
  if (Opts.Instrument)
    Trace.Offset = SL->getElementOffset(TraceRecordField);
  if (Opts.CycleBudget)
    Layout.Budget.Offset = SL->getElementOffset(BudgetRecordField);
  Layout.Tasks.clear();
  for (const TaskDecl *T : B.Tasks) {
    const FrameInfo &FI = Frames[T];
    uint64_t FrameOffset = SL->getElementOffset(FI.StateFieldNo);
    auto Word = [&](TaskWord W) {
      return BehaviorLayout::TaskWord{
          getTaskWordOffset(T, W),
          unsigned(FI.getWord(W).Ty->getBitWidth() / 8)};
    };
    BehaviorLayout::Task Entry{T,
                               FrameOffset,
                               DL.getTypeStoreSize(FI.Ty),
                               Word(TaskWord::Resume),
                               Word(TaskWord::State),
                               {},
                               false,
                               {}};
    auto Add = [&](const Decl *D, const Type *Ty) {
      Entry.Fields.push_back(
          {D, Ty, getFrameFieldOffset(T, FI.Fields.lookup(D))});
    };
    for (const ParamDecl *P : T->Params)
      if (FI.Fields.count(P))
        Add(P, P->Ty);
    for (const VarDecl *V : T->Locals)
      if (FI.Fields.count(V))
        Add(V, V->Ty);
    Entry.OnlyRunningStates = planYields(*T).OnlyRunning;
    for (const YieldStmt *Y : T->Yields) {
      std::optional<int64_t> V = getConstantState(Y->Value);
      Entry.YieldValues.push_back(V ? std::optional<int32_t>(*V)
                                    : std::nullopt);
    }
    Layout.Tasks.push_back(std::move(Entry));
  }
}

void ModuleEmitter::useRegisterCalls() {
  // LLVM's i386 PIC lowering loads the GOT address into EBX before every
  // call that is not a tail call, whatever the callee, so that a call
  // through the PLT finds it: three instructions and a saved register in
  // every function that calls another, though calls between internal
  // functions never go through the PLT. It leaves calls of the regcall
  // convention alone. Only functions whose every use is a direct call can
  // change their convention (bs.destroy is called through
  // bs_behavior_info; the entries are C functions).
  for (llvm::Function &F : M) {
    if (F.isDeclaration() || !F.hasLocalLinkage() ||
        llvm::any_of(F.uses(), [](const llvm::Use &U) {
          const auto *Call = llvm::dyn_cast<llvm::CallBase>(U.getUser());
          return !Call || !Call->isCallee(&U);
        }))
      continue;
    F.setCallingConv(llvm::CallingConv::X86_RegCall);
    for (llvm::Use &U : F.uses())
      llvm::cast<llvm::CallBase>(U.getUser())
          ->setCallingConv(llvm::CallingConv::X86_RegCall);
  }
}

unsigned ModuleEmitter::addSite(DebugSite Site) {
  Layout.Sites.push_back(std::move(Site));
  return Layout.Sites.size();
}

llvm::GlobalVariable *ModuleEmitter::getProbe(const char *Symbol) {
  if (llvm::GlobalVariable *G = M.getGlobalVariable(Symbol))
    return G;
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  // A REPL line's module uses the behavior module's probes.
  return new llvm::GlobalVariable(
      M, I32, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
      ReplSlots ? nullptr : llvm::ConstantInt::get(I32, 0), Symbol);
}

void ModuleEmitter::declareFunctions() {
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  auto Declare = [&](const CallableDecl *D, llvm::Type *Result) {
    llvm::SmallVector<llvm::Type *, 4> Params = {Ptr};
    bool ClassResult = returnsClass(*D);
    if (ClassResult) {
      // A class result goes to the caller's storage: (state, out, params).
      Params.push_back(Ptr);
      Result = llvm::Type::getVoidTy(Ctx);
    }
    for (const ParamDecl *P : D->Params)
      Params.push_back(getValueType(P->Ty));
    auto *FTy = llvm::FunctionType::get(Result, Params, false);
    auto *F = llvm::Function::Create(FTy, getFunctionLinkage(),
                                     getInternalName(*D), M);
    addCommonAttributes(F);
    F->getArg(0)->setName(StateParamName);
    if (ClassResult)
      F->getArg(1)->setName("result");
    unsigned First = ClassResult ? 2 : 1;
    for (const ParamDecl *P : D->Params)
      F->getArg(P->Index + First)->setName(P->getName().Name);
    Functions[D] = F;
  };
  for (const CallableDecl *D : getSourceOrder()) {
    if (const auto *F = llvm::dyn_cast<FuncDecl>(D))
      Declare(F, F->ResultTy->isClass() ? llvm::Type::getVoidTy(Ctx)
                                        : getValueType(F->ResultTy));
    else // The state it left (CGTask.cpp, "The result"), or nothing.
      Declare(D, tasksReturnStates() ? llvm::Type::getInt32Ty(Ctx)
                                     : llvm::Type::getVoidTy(Ctx));
  }
  // After the funcs and tasks, so that they keep their names should a
  // nested func be called `destroy` (LLVM then renames this one).
  for (const TaskDecl *T : B.Tasks) {
    FrameInfo &FI = Frames[T];
    if (!FI.LiveField)
      continue;
    FI.Destroy = llvm::Function::Create(
        llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), {Ptr}, false),
        getFunctionLinkage(), getInternalName(*T) + ".destroy",
        M);
    addCommonAttributes(FI.Destroy);
    FI.Destroy->getArg(0)->setName(StateParamName);
  }
}

void ModuleEmitter::emitDestroyFunctions() {
  llvm::Type *I8 = llvm::Type::getInt8Ty(Ctx);
  llvm::SmallVector<llvm::Function *, 4> TaskDestroys;
  for (const TaskDecl *T : B.Tasks) {
    const FrameInfo &FI = Frames[T];
    if (!FI.Destroy)
      continue;
    TaskDestroys.push_back(FI.Destroy);
    // if (frame.live) { destroy locals and params, newest first; live = 0 }
    llvm::Function *F = FI.Destroy;
    llvm::BasicBlock *Entry = llvm::BasicBlock::Create(Ctx, "entry", F);
    llvm::BasicBlock *Live = llvm::BasicBlock::Create(Ctx, "live", F);
    llvm::BasicBlock *Done = llvm::BasicBlock::Create(Ctx, "done", F);
    llvm::IRBuilder<> IRB(Entry);
    llvm::Value *Frame = IRB.CreateConstInBoundsGEP2_32(
        StateTy, F->getArg(0), 0, FI.StateFieldNo, "frame");
    auto Field = [&](unsigned No) {
      return IRB.CreateConstInBoundsGEP2_32(FI.Ty, Frame, 0, No,
                                            FI.FieldNames[No]);
    };
    llvm::Value *LiveAddr = Field(FI.LiveField);
    IRB.CreateCondBr(
        IRB.CreateICmpNE(IRB.CreateLoad(I8, LiveAddr, "is.live"),
                         llvm::ConstantInt::get(I8, 0)),
        Live, Done);
    IRB.SetInsertPoint(Live);
    // The reset constructs the parameters, then the locals.
    llvm::SmallVector<std::pair<const Decl *, const Type *>, 8> Values;
    for (const ParamDecl *P : T->Params)
      Values.push_back({P, P->Ty});
    for (const VarDecl *V : T->Locals)
      Values.push_back({V, V->Ty});
    for (auto It = Values.rbegin(); It != Values.rend(); ++It)
      if (needsDestroy(It->second))
        IRB.CreateCall(getLifeThunk(It->second->getClass()->Destroy, 1),
                       {Field(FI.Fields.lookup(It->first))});
    IRB.CreateStore(llvm::ConstantInt::get(I8, 0), LiveAddr);
    IRB.CreateBr(Done);
    IRB.SetInsertPoint(Done);
    IRB.CreateRetVoid();
  }
  if (TaskDestroys.empty())
    return;
  // The behavior's: every frame, the last task's first.
  BehaviorDestroy = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx),
                              {llvm::PointerType::getUnqual(Ctx)}, false),
      llvm::GlobalValue::InternalLinkage, "bs.destroy", M);
  addCommonAttributes(BehaviorDestroy);
  BehaviorDestroy->getArg(0)->setName(StateParamName);
  llvm::IRBuilder<> IRB(
      llvm::BasicBlock::Create(Ctx, "entry", BehaviorDestroy));
  for (auto It = TaskDestroys.rbegin(); It != TaskDestroys.rend(); ++It)
    IRB.CreateCall(*It, {BehaviorDestroy->getArg(0)});
  IRB.CreateRetVoid();
}

std::vector<const CallableDecl *> ModuleEmitter::getSourceOrder() const {
  // Module by module, each task followed by its nested funcs, so the IR
  // reads like the source (and FileCheck tests can follow it).
  std::vector<const CallableDecl *> Order;
  llvm::DenseSet<const CallableDecl *> Seen;
  auto Add = [&](const CallableDecl *D) {
    if (Seen.insert(D).second)
      Order.push_back(D);
  };
  for (const ModuleAST *Mod : B.Modules)
    for (const CallableDecl *D : Mod->Decls) {
      Add(D);
      if (const auto *T = llvm::dyn_cast<TaskDecl>(D))
        for (const FuncDecl *F : T->NestedFuncs)
          Add(F);
    }
  // Behavior::Tasks/Funcs are the definitive lists; anything the walk did
  // not meet still gets its function.
  for (const TaskDecl *T : B.Tasks)
    Add(T);
  for (const FuncDecl *F : B.Funcs)
    Add(F);
  return Order;
}

void ModuleEmitter::emitEntries() {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  Layout.Entries.clear();
  std::vector<const CallableDecl *> Exports =
      Opts.Exports ? *Opts.Exports : findBehaviorRoots(B);
  for (const CallableDecl *D : Exports) {
    assert(isCallableFromC(*D) && "the driver checks --export");
    llvm::Function *Impl = getFunction(D);
    // The C face: bool travels as int32 0/1 both ways.
    auto CType = [&](llvm::Type *T) { return T->isIntegerTy(1) ? I32 : T; };
    llvm::SmallVector<llvm::Type *, 4> Params = {Ptr};
    for (const ParamDecl *P : D->Params)
      Params.push_back(CType(getValueType(P->Ty)));
    // A task's entry returns nothing: its state is bs_B_state_of__M__t's.
    llvm::Type *Result = llvm::isa<TaskDecl>(D)
                             ? llvm::Type::getVoidTy(Ctx)
                             : CType(Impl->getReturnType());
    std::string Symbol = getEntrySymbol(Opts.BehaviorName, *D);
    auto *F = llvm::Function::Create(
        llvm::FunctionType::get(Result, Params, false),
        llvm::GlobalValue::ExternalLinkage, Symbol, M);
    addCommonAttributes(F);
    F->getArg(0)->setName(StateParamName);

    llvm::IRBuilder<> IRB(llvm::BasicBlock::Create(Ctx, "entry", F));
    emitBudgetStart(IRB, F->getArg(0));
    emitExplainEntryStart(IRB, F->getArg(0));
    llvm::SmallVector<llvm::Value *, 4> Args = {F->getArg(0)};
    for (const ParamDecl *P : D->Params) {
      llvm::Value *A = F->getArg(P->Index + 1);
      A->setName(P->getName().Name);
      if (P->Ty->isBool())
        A = IRB.CreateICmpNE(A, llvm::ConstantInt::get(I32, 0),
                             P->getName().Name + ".bool");
      Args.push_back(A);
    }
    if (Result->isVoidTy()) {
      IRB.CreateCall(Impl, Args);
      emitExplainEntryEnd(IRB);
      IRB.CreateRetVoid();
    } else {
      llvm::Value *R = IRB.CreateCall(Impl, Args, "result");
      emitExplainEntryEnd(IRB);
      if (R->getType()->isIntegerTy(1))
        R = IRB.CreateZExt(R, I32, "result.int");
      IRB.CreateRet(R);
    }
    Layout.Entries.push_back({D, Symbol});
  }
}

void ModuleEmitter::emitInfo() {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *I64 = llvm::Type::getInt64Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::Type *I8 = llvm::Type::getInt8Ty(Ctx);
  auto *TaskInfoTy = llvm::StructType::create(Ctx, {Ptr, I32, I32, I32, I8, I8},
                                              "bs_task_info");
  auto *ModuleInfoTy =
      llvm::StructType::create(Ctx, {Ptr, Ptr, I64}, "bs_binding_module");
  auto *TraceTy =
      llvm::StructType::create(Ctx, {I32, I32, I32, I32}, "bs_trace_layout");
  auto *LoopTy =
      llvm::StructType::create(Ctx, {Ptr, I32, I32, I32}, "bs_loop_info");
  auto *BudgetTy = llvm::StructType::create(Ctx, {I32, I32, I32, Ptr},
                                            "bs_budget_layout");
  auto *InfoTy = llvm::StructType::create(
      Ctx, {I32, I32, I32, I32, Ptr, I32, Ptr, Ptr, Ptr, TraceTy, BudgetTy},
      "bs_behavior_info");

  // A private constant array, or null when there is nothing to list.
  auto EmitTable = [&](llvm::StructType *Ty,
                       llvm::ArrayRef<llvm::Constant *> Elts,
                       llvm::StringRef Name) -> llvm::Constant * {
    if (Elts.empty())
      return llvm::ConstantPointerNull::get(llvm::PointerType::getUnqual(Ctx));
    auto *ArrTy = llvm::ArrayType::get(Ty, Elts.size());
    return new llvm::GlobalVariable(
        M, ArrTy, /*isConstant=*/true, llvm::GlobalValue::PrivateLinkage,
        llvm::ConstantArray::get(ArrTy, Elts),
        "bs_" + Opts.BehaviorName + Name);
  };

  llvm::SmallVector<llvm::Constant *, 8> Tasks;
  for (const BehaviorLayout::Task &T : Layout.Tasks)
    Tasks.push_back(llvm::ConstantStruct::get(
        TaskInfoTy, {getString(T.Decl->getQualifiedName()),
                     llvm::ConstantInt::get(I32, T.FrameOffset),
                     llvm::ConstantInt::get(I32, T.Resume.Offset),
                     llvm::ConstantInt::get(I32, T.State.Offset),
                     llvm::ConstantInt::get(I8, T.Resume.Bytes),
                     llvm::ConstantInt::get(I8, T.State.Bytes)}));

  // The binding modules it was compiled against: each descriptor by its
  // symbol (so the link fails if the module is missing) with the hash bsc
  // read, for bs_state_init to compare (docs/bindings.md, staleness).
  llvm::SmallVector<llvm::Constant *, 4> Modules;
  for (const NativeModule *NM : B.BindingModules) {
    auto *Descriptor = M.getOrInsertGlobal("bs_module_" + NM->Name,
                                           llvm::Type::getInt8Ty(Ctx));
    Modules.push_back(llvm::ConstantStruct::get(
        ModuleInfoTy, {getString(NM->Name), Descriptor,
                       llvm::ConstantInt::get(I64, NM->Hash)}));
  }

  const BehaviorLayout::TraceLayout &Trace = Layout.Trace;
  llvm::Constant *TraceInit = llvm::ConstantStruct::get(
      TraceTy, {llvm::ConstantInt::get(I32, Trace.RecordSize),
                llvm::ConstantInt::get(I32, Trace.ClearSize),
                llvm::ConstantInt::get(I32, Trace.RecordSize ? Trace.SlotBytes
                                                              : 0),
                llvm::ConstantInt::get(I32, Trace.Offset)});

  Layout.InfoSymbol = "bs_" + Opts.BehaviorName + "_info";
  llvm::Constant *Init = llvm::ConstantStruct::get(
      InfoTy, {llvm::ConstantInt::get(I32, ABIVersion),
               llvm::ConstantInt::get(I32, Layout.StateSize),
               llvm::ConstantInt::get(I32, Layout.StateAlign),
               llvm::ConstantInt::get(I32, Layout.Tasks.size()),
               EmitTable(TaskInfoTy, Tasks, "_tasks"),
               llvm::ConstantInt::get(I32, Modules.size()),
               EmitTable(ModuleInfoTy, Modules, "_modules"),
               BehaviorDestroy ? static_cast<llvm::Constant *>(BehaviorDestroy)
                               : llvm::ConstantPointerNull::get(
                                     llvm::PointerType::getUnqual(Ctx)),
               getDebugTables(), TraceInit,
               getBudgetInfo(BudgetTy, LoopTy)});
  Info = new llvm::GlobalVariable(M, InfoTy, /*isConstant=*/true,
                                  llvm::GlobalValue::ExternalLinkage, Init,
                                  Layout.InfoSymbol);
}

llvm::Constant *ModuleEmitter::getDebugTables() {
  if (!Opts.Instrument)
    return llvm::ConstantPointerNull::get(llvm::PointerType::getUnqual(Ctx));
  // Declared here and defined by defineDebugTables: lib/Debug builds the
  // tables from the layout this module produces, and CodeGen cannot depend
  // on it.
  Layout.DebugTablesSymbol = "bs_" + Opts.BehaviorName + "_debug_tables";
  return M.getOrInsertGlobal(Layout.DebugTablesSymbol,
                             llvm::Type::getInt8Ty(Ctx));
}

void bsc::defineDebugTables(llvm::Module &M, const BehaviorLayout &Layout,
                            llvm::StringRef JSON) {
  llvm::GlobalVariable *Decl =
      M.getGlobalVariable(Layout.DebugTablesSymbol, /*AllowInternal=*/true);
  assert(Decl && Decl->isDeclaration() && "emitLLVM ran with Instrument");
  llvm::Constant *Text =
      llvm::ConstantDataArray::getString(M.getContext(), JSON);
  auto *G = new llvm::GlobalVariable(M, Text->getType(), /*isConstant=*/true,
                                     llvm::GlobalValue::ExternalLinkage, Text);
  // A section of its own, so that `bsc trace-decode` finds the text in an
  // object without following relocations.
  G->setSection(DebugTablesSection);
  G->setAlignment(llvm::Align(1));
  G->takeName(Decl);
  Decl->replaceAllUsesWith(G);
  Decl->eraseFromParent();
}

void ModuleEmitter::emitProgramMain() {
  const CallableDecl *Entry = Opts.ProgramEntry;
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  llvm::FunctionCallee Init = M.getOrInsertFunction(
      "bs_state_init", llvm::FunctionType::get(I32, {Ptr, Ptr}, false));
  llvm::FunctionCallee Report = M.getOrInsertFunction(
      "bs_report_init_failure", llvm::FunctionType::get(I32, {Ptr, I32}, false));
  llvm::FunctionCallee Begin = M.getOrInsertFunction(
      "bs_begin_cycle",
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), {Ptr, Ptr, Ptr},
                              false));
  llvm::FunctionCallee Destroy = M.getOrInsertFunction(
      "bs_state_destroy",
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), {Ptr, Ptr}, false));

  auto *Main = llvm::Function::Create(llvm::FunctionType::get(I32, false),
                                      llvm::GlobalValue::ExternalLinkage,
                                      "main", M);
  addCommonAttributes(Main);
  llvm::BasicBlock *EntryBB = llvm::BasicBlock::Create(Ctx, "entry", Main);
  llvm::BasicBlock *Refused = llvm::BasicBlock::Create(Ctx, "init.failed", Main);
  llvm::BasicBlock *Start = llvm::BasicBlock::Create(Ctx, "start", Main);
  llvm::BasicBlock *Cond = llvm::BasicBlock::Create(Ctx, "cycle.cond", Main);
  llvm::BasicBlock *Body = llvm::BasicBlock::Create(Ctx, "cycle", Main);
  llvm::BasicBlock *Done = llvm::BasicBlock::Create(Ctx, "done", Main);
  llvm::IRBuilder<> IRB(EntryBB);
  llvm::AllocaInst *State = IRB.CreateAlloca(StateTy, nullptr, "state");
  State->setAlignment(llvm::Align(Layout.StateAlign));
  // A refused state (stale bindings, bscript.h) ends the program with the
  // runtime's message and status 1 before anything runs.
  llvm::Value *InitResult = IRB.CreateCall(Init, {State, Info}, "init");
  IRB.CreateCondBr(
      IRB.CreateICmpEQ(InitResult, llvm::ConstantInt::get(I32, 0), "init.ok"),
      Start, Refused);
  IRB.SetInsertPoint(Refused);
  IRB.CreateRet(IRB.CreateCall(Report, {Info, InitResult}, "status"));

  // `input` and `output` of the world module are objects on main's stack,
  // constructed as `bsc run` constructs them (zeroed, then the construct
  // thunk) once the state is accepted; generated code reaches them through
  // the pointers bs_begin_cycle stores in the state header, so a behavior
  // that reads input must never get null. The driver refuses a class that
  // can be neither constructed nor start as zero bytes.
  IRB.SetInsertPoint(Start);
  llvm::Constant *Null = llvm::ConstantPointerNull::get(
      llvm::PointerType::getUnqual(Ctx));
  llvm::Value *WorldObjects[2] = {Null, Null};
  const NativeClass *WorldClasses[2] = {
      B.World ? B.World->Input : nullptr, B.World ? B.World->Output : nullptr};
  for (unsigned K = 0; K < 2; ++K) {
    const NativeClass *C = WorldClasses[K];
    if (!C)
      continue;
    llvm::Type *Ty = getClassMemoryType(C);
    auto *A = new llvm::AllocaInst(Ty, 0, K == 0 ? "input" : "output",
                                   llvm::cast<llvm::Instruction>(InitResult));
    A->setAlignment(M.getDataLayout().getABITypeAlign(Ty));
    emitClassInit(IRB, C, A);
    WorldObjects[K] = A;
  }
  IRB.CreateBr(Cond);

  // for (i = 0; i < cycles; ++i) { bs_begin_cycle(...); entry(state); }
  // (zero cycles run nothing).
  IRB.SetInsertPoint(Cond);
  llvm::PHINode *I = IRB.CreatePHI(I32, 2, "i");
  I->addIncoming(llvm::ConstantInt::get(I32, 0), Start);
  IRB.CreateCondBr(
      IRB.CreateICmpULT(I, llvm::ConstantInt::get(I32, Opts.ProgramCycles)),
      Body, Done);

  IRB.SetInsertPoint(Body);
  IRB.CreateCall(Begin, {State, WorldObjects[0], WorldObjects[1]});
  emitBudgetStart(IRB, State);
  llvm::Function *Callee = getFunction(Entry);
  llvm::SmallVector<llvm::Value *, 4> Args = {State};
  // The driver refuses entries with parameters; zeros keep the IR valid.
  for (unsigned A = 1; A < Callee->arg_size(); ++A)
    Args.push_back(llvm::Constant::getNullValue(Callee->getArg(A)->getType()));
  IRB.CreateCall(Callee, Args);
  // `--cycle-budget`: a cycle that ran out says where, on stderr.
  if (Opts.CycleBudget)
    IRB.CreateCall(M.getOrInsertFunction(
                       "bs_report_budget",
                       llvm::FunctionType::get(I32, {Ptr, Ptr}, false)),
                   {State, Info});
  // The budget's start split the cycle's block: the edge back is from here.
  I->addIncoming(IRB.CreateAdd(I, llvm::ConstantInt::get(I32, 1), "i.next"),
                 IRB.GetInsertBlock());
  IRB.CreateBr(Cond);

  // The end of the behavior: the class values running tasks still hold,
  // then the input and output objects (in `bsc run`'s order).
  IRB.SetInsertPoint(Done);
  IRB.CreateCall(Destroy, {State, Info});
  for (unsigned K = 0; K < 2; ++K)
    if (needsDestroy(WorldClasses[K]))
      IRB.CreateCall(getLifeThunk(WorldClasses[K]->Destroy, 1),
                     {WorldObjects[K]});
  IRB.CreateRet(llvm::ConstantInt::get(I32, 0));
}

/// Rounds every float `F` computes to a float in memory (a volatile store
/// and load, which no optimisation removes) before anything uses it. The
/// x87 unit computes with 64 mantissa bits and a 15-bit exponent; a value
/// stored as a float is rounded once more to 24 bits and the float's range.
/// Rounding twice gives the same result as rounding once for + - * / when
/// the first precision has at least 2 * 24 + 2 bits (64 does), so the
/// result is the IEEE float result the host computes with SSE.
static void narrowX87Floats(llvm::Function &F) {
  llvm::SmallVector<llvm::Instruction *, 16> Computed;
  for (llvm::Instruction &I : llvm::instructions(F)) {
    if (!I.getType()->isFloatTy())
      continue;
    // Loads, constants, arguments and phis carry floats that were already
    // rounded; negation and selection are exact.
    if (llvm::isa<llvm::BinaryOperator>(I) || llvm::isa<llvm::SIToFPInst>(I) ||
        llvm::isa<llvm::UIToFPInst>(I) || llvm::isa<llvm::CallInst>(I))
      Computed.push_back(&I);
  }
  if (Computed.empty())
    return;
  llvm::IRBuilder<> B(&*F.getEntryBlock().getFirstInsertionPt());
  llvm::AllocaInst *Slot = B.CreateAlloca(B.getFloatTy(), nullptr, "x87.round");
  for (llvm::Instruction *I : Computed) {
    B.SetInsertPoint(I->getNextNode());
    B.SetCurrentDebugLocation(I->getDebugLoc());
    llvm::StoreInst *Store = B.CreateStore(I, Slot, /*isVolatile=*/true);
    llvm::Value *Rounded =
        B.CreateLoad(B.getFloatTy(), Slot, /*isVolatile=*/true,
                     I->getName() + ".rounded");
    I->replaceUsesWithIf(Rounded,
                         [&](llvm::Use &U) { return U.getUser() != Store; });
  }
}

void ModuleEmitter::run() {
  layoutState();
  if (Opts.DebugInfo) {
    assert(Opts.Sources && "debug information needs the sources' lines");
    DebugInfo = std::make_unique<DebugInfoEmitter>(*this, *Opts.Sources);
  }
  declareFunctions();
  for (const CallableDecl *D : getSourceOrder()) {
    FunctionEmitter(*this, *D).run();
    if (Opts.NarrowX87Floats)
      narrowX87Floats(*getFunction(D));
  }
  emitEntries();
  emitDestroyFunctions();
  emitInfo();
  if (Opts.ProgramEntry)
    emitProgramMain();
  if (llvm::Triple(M.getTargetTriple()).getArch() == llvm::Triple::x86)
    useRegisterCalls();
  // Both probes exist whenever probes are on: the REPL's lines use them too.
  if (Opts.Probes) {
    getProbe(LoopProbeSymbol);
    getProbe(NativeProbeSymbol);
  }
  if (DebugInfo) {
    // The glue: an entry (and `main`) is attributed to its func's or
    // task's line, the rest to line 0.
    llvm::DenseMap<const llvm::Function *, llvm::SMLoc> GlueLocs;
    for (const BehaviorLayout::Entry &E : Layout.Entries)
      GlueLocs[M.getFunction(E.Symbol)] = E.Decl->getLoc();
    if (Opts.ProgramEntry)
      GlueLocs[M.getFunction("main")] = Opts.ProgramEntry->getLoc();
    for (llvm::Function &F : M)
      if (!F.isDeclaration() && !F.getSubprogram())
        DebugInfo->createGlueFunction(F, GlueLocs.lookup(&F));
    DebugInfo->finalize();
  }
}

//===----------------------------------------------------------------------===//
// FunctionEmitter: what funcs and tasks share
//===----------------------------------------------------------------------===//

FunctionEmitter::FunctionEmitter(ModuleEmitter &CGM, const CallableDecl &D)
    : CGM(CGM), D(D), Task(llvm::dyn_cast<TaskDecl>(&D)),
      Fn(CGM.getFunction(&D)), Builder(CGM.getContext()),
      StatePtr(Fn->getArg(0)) {}

const TaskDecl *FunctionEmitter::getFrameTask() const {
  if (Task)
    return Task;
  return llvm::cast<FuncDecl>(D).EnclosingTask;
}

void FunctionEmitter::run() {
  Builder.SetInsertPoint(llvm::BasicBlock::Create(CGM.getContext(), "entry", Fn));
  // Allocas and frame-field addresses go before this marker, so they all
  // sit at the top of the entry block whatever control flow the body adds:
  // mem2reg promotes only entry-block allocas, and an address computed in
  // the entry block dominates every use, including the resume blocks.
  EntryPoint =
      Builder.CreateAlloca(Builder.getInt8Ty(), nullptr, "entry.point");
  if (CGM.getDebugInfo())
    emitDebugPrologue();
  // A task's prologue is attributed to the task's line. A func's copies its
  // arguments to their slots first, unattributed, as Clang's do: a
  // debugger's breakpoint on the func goes after them.
  if (Task) {
    setDebugLocation(D.getLoc());
    emitTaskPrologue();
  } else {
    emitFuncPrologue();
    setDebugLocation(D.getLoc());
  }
  if (D.Body)
    emitBlock(D.Body);
  if (Task)
    emitTaskEpilogue();
  else
    emitFuncEpilogue();
  // Statements after `return`, `break` or `continue` were emitted into
  // blocks nothing branches to; drop them so -O0 code has no dead blocks.
  llvm::EliminateUnreachableBlocks(*Fn);
  if (CGM.getOptions().Probes)
    restoreLoopProbeOnReturn();
  if (CGM.getOptions().Explain && Task)
    emitExplainTaskMarks();
  EntryPoint->eraseFromParent();
  EntryPoint = nullptr;
}

void FunctionEmitter::restoreLoopProbeOnReturn() {
  // A call leaves the loop probe as it found it: the caller's loop, not a
  // loop of this function that a `return` or `yield` left.
  llvm::GlobalVariable *Probe = CGM.getProbe(LoopProbeSymbol);
  llvm::IRBuilder<> B(EntryPoint);
  llvm::Value *Saved = B.CreateLoad(B.getInt32Ty(), Probe, /*isVolatile=*/true,
                                    "probe.saved");
  for (llvm::BasicBlock &BB : *Fn)
    if (auto *Ret = llvm::dyn_cast<llvm::ReturnInst>(BB.getTerminator())) {
      B.SetInsertPoint(Ret);
      B.CreateStore(Saved, Probe, /*isVolatile=*/true);
    }
}

unsigned FunctionEmitter::getFirstParamArg() const {
  return ModuleEmitter::returnsClass(D) ? 2 : 1;
}

llvm::AllocaInst *FunctionEmitter::createSlot(const Type *T,
                                              const llvm::Twine &Name) {
  llvm::Type *MemTy = CGM.getMemoryType(T);
  auto *Slot = new llvm::AllocaInst(MemTy, 0, Name, EntryPoint);
  Slot->setAlignment(CGM.getModule().getDataLayout().getABITypeAlign(MemTy));
  return Slot;
}

void FunctionEmitter::emitFuncPrologue() {
  // A class parameter is the func's own copy: copy-constructed from the
  // caller's value, destroyed at every return. Locals are constructed by
  // their declarations (emitDecl).
  for (const ParamDecl *P : D.Params) {
    llvm::AllocaInst *Slot = createSlot(P->Ty, P->getName().Name + ".addr");
    Slots[P] = Slot;
    llvm::Value *Arg = Fn->getArg(P->Index + getFirstParamArg());
    if (P->Ty->isClass()) {
      emitClassCopy(P->Ty->getClass(), Slot, Arg, /*DstConstructed=*/false);
      if (ModuleEmitter::needsDestroy(P->Ty))
        Live.push_back({P->Ty->getClass(), Slot});
      continue;
    }
    emitStore(P->Ty, Arg, Slot);
  }
  for (const ParamDecl *P : D.Params)
    declareForDebugger(*P, P->Ty, P->Index + 2);
  for (const VarDecl *V : D.Locals)
    if (!CGM.getReplSlot(V))
      Slots[V] = createSlot(V->Ty, V->getName().Name);
}

void FunctionEmitter::emitFuncEpilogue() {
  // Sema makes every path of a func with a result return; should a path
  // still end here, it returns the zero value rather than anything
  // undefined (runtime safety).
  if (!Builder.GetInsertBlock()->getTerminator())
    emitFuncZeroReturn();
}

void FunctionEmitter::emitFuncZeroReturn() {
  const Type *ResultTy = llvm::cast<FuncDecl>(D).ResultTy;
  emitLiveCleanups(0, /*Forget=*/false);
  if (ResultTy->isClass()) {
    emitClassInit(ResultTy->getClass(), Fn->getArg(1));
    Builder.CreateRetVoid();
  } else if (ResultTy->isVoid())
    Builder.CreateRetVoid();
  else if (ResultTy->isString())
    Builder.CreateRet(CGM.getString(""));
  else
    Builder.CreateRet(llvm::Constant::getNullValue(Fn->getReturnType()));
}

//===----------------------------------------------------------------------===//
// Entry point
//===----------------------------------------------------------------------===//

std::unique_ptr<llvm::Module> bsc::emitLLVM(const Behavior &B,
                                            llvm::LLVMContext &Ctx,
                                            const llvm::Triple &Triple,
                                            const llvm::DataLayout &DL,
                                            const CodeGenOptions &Opts,
                                            BehaviorLayout &Layout) {
  // The driver names the behavior; without a name, the first module's name
  // is the default bscript.h promises.
  CodeGenOptions Named = Opts;
  if (Named.BehaviorName.empty() && !B.Modules.empty())
    Named.BehaviorName = B.Modules.front()->Name;
  auto M = std::make_unique<llvm::Module>(Named.BehaviorName, Ctx);
  M->setTargetTriple(Triple.str());
  M->setDataLayout(DL);
  if (!B.Modules.empty())
    M->setSourceFileName(B.Modules.front()->Path);
  Layout = BehaviorLayout();
  ModuleEmitter(B, *M, Named, Layout).run();
  return M;
}

//===----------------------------------------------------------------------===//
// REPL lines
//===----------------------------------------------------------------------===//

llvm::Value *ModuleEmitter::getReplSlot(const Decl *D) {
  if (!ReplSlots)
    return nullptr;
  auto It = ReplSlots->find(D);
  if (It == ReplSlots->end())
    return nullptr;
  llvm::Type *I64 = llvm::Type::getInt64Ty(Ctx);
  return llvm::ConstantExpr::getIntToPtr(llvm::ConstantInt::get(I64, It->second),
                                         llvm::PointerType::getUnqual(Ctx));
}

void ModuleEmitter::runReplLine(
    const FuncDecl &Line, llvm::StringRef Symbol,
    const llvm::DenseMap<const Decl *, uint64_t> &Slots) {
  ReplSlots = &Slots;
  // The same types and declarations as the behavior's module, no bodies.
  layoutState();
  declareFunctions();
  auto *F = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx),
                              {llvm::PointerType::getUnqual(Ctx)}, false),
      llvm::GlobalValue::ExternalLinkage, Symbol, M);
  addCommonAttributes(F);
  F->getArg(0)->setName(StateParamName);
  Functions[&Line] = F;
  FunctionEmitter(*this, Line).run();
}

std::unique_ptr<llvm::Module>
bsc::emitReplLine(const Behavior &B, const FuncDecl &Line,
                  llvm::StringRef Symbol, llvm::LLVMContext &Ctx,
                  const llvm::Triple &Triple, const llvm::DataLayout &DL,
                  const llvm::DenseMap<const Decl *, uint64_t> &Slots,
                  std::vector<DebugSite> &Sites) {
  auto M = std::make_unique<llvm::Module>(Symbol, Ctx);
  M->setTargetTriple(Triple.str());
  M->setDataLayout(DL);
  CodeGenOptions Opts;
  Opts.ExternalFunctions = true;
  Opts.Probes = true;
  BehaviorLayout Layout;
  // The line's sites are numbered after those of the behavior and of the
  // lines before it: they share the probes.
  Layout.Sites = std::move(Sites);
  ModuleEmitter(B, *M, Opts, Layout).runReplLine(Line, Symbol, Slots);
  Sites = std::move(Layout.Sites);
  return M;
}

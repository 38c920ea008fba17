//===- CGLayout.cpp - the behavior state and task frames ------------------===//
//
// `%bs.state`: the header of bs_state_header, then a frame per task (its
// last call, resume point and state when they take 4 bytes, the parameters
// and locals it keeps), the tasks' narrow headers, and with `--instrument`
// and `--cycle-budget` their records. layoutState builds the types in that
// order and records in BehaviorLayout the offsets robot code and the
// debugger see, all computed from the target's DataLayout.
//
//===----------------------------------------------------------------------===//
#include "ModuleEmitter.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/Support/xxhash.h"

using namespace bsc;
using namespace bsc::codegen;

const FrameInfo &ModuleEmitter::getFrame(const TaskDecl *T) const {
  auto It = Frames.find(T);
  assert(It != Frames.end() && "task is not part of the behavior");
  return It->second;
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
    layoutFrame(*T, FI);
    FI.StateFieldNo = StateFields.size();
    StateFields.push_back(FI.Ty);
  }
  addTaskHeaders(StateFields);
  addTraceRecord(StateFields);
  // `--cycle-budget`: its record last (bscript.h bs_budget_record).
  Layout.Budget = {};
  if (Opts.CycleBudget) {
    Layout.Budget.Budget = Opts.CycleBudget;
    BudgetRecordField = StateFields.size();
    StateFields.push_back(llvm::ArrayType::get(I32, BudgetRecordWords));
  }
  // `--assertions=count`: a counter per assertion.
  Layout.Assertions = {Opts.Assertions, 0};
  if (Opts.Assertions == AssertionMode::Count && !B.Assertions.empty()) {
    AssertionCountersField = StateFields.size();
    StateFields.push_back(llvm::ArrayType::get(I32, B.Assertions.size()));
  }
  StateTy = llvm::StructType::create(Ctx, StateFields, "bs.state");
  recordStateLayout();
}

void ModuleEmitter::layoutFrame(const TaskDecl &T, FrameInfo &FI) {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  // The last call; the resume point and state if they take 4 bytes; then
  // params, then locals.
  llvm::SmallVector<llvm::Type *, 8> Fields = {I32};
  std::string Prefix = T.getName().Name.str() + ".";
  FI.FieldNames = {Prefix + "last_call"};
  chooseTaskWords(T, FI);
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
  for (const ParamDecl *P : T.Params)
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
  for (const VarDecl *V : T.Locals) {
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
      llvm::any_of(T.Params, [](const ParamDecl *P) {
        return needsDestroy(P->Ty);
      }) ||
      llvm::any_of(T.Locals,
                   [](const VarDecl *V) { return needsDestroy(V->Ty); });
  if (Destructible) {
    FI.LiveField = Fields.size();
    Fields.push_back(llvm::Type::getInt8Ty(Ctx));
    FI.FieldNames.push_back(Prefix + "live");
  }
  std::string Name = "bs.frame.";
  if (T.Module)
    Name += T.Module->Name + ".";
  Name += T.getName().Name.str();
  FI.Ty = llvm::StructType::create(Ctx, Fields, Name);
}

void ModuleEmitter::addTraceRecord(
    llvm::SmallVectorImpl<llvm::Type *> &StateFields) {
  BehaviorLayout::TraceLayout &Trace = Layout.Trace;
  Trace = {};
  if (!Opts.Instrument)
    return;
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
  StateFields.push_back(llvm::ArrayType::get(llvm::Type::getInt32Ty(Ctx),
                                             Trace.RecordSize / 4));
}

void ModuleEmitter::recordStateLayout() {
  const llvm::DataLayout &DL = M.getDataLayout();
  const llvm::StructLayout *SL = DL.getStructLayout(StateTy);
  Layout.StateSize = DL.getTypeAllocSize(StateTy);
  Layout.StateAlign = DL.getABITypeAlign(StateTy).value();
  if (Opts.Instrument)
    Layout.Trace.Offset = SL->getElementOffset(TraceRecordField);
  if (Opts.CycleBudget)
    Layout.Budget.Offset = SL->getElementOffset(BudgetRecordField);
  if (AssertionCountersField)
    Layout.Assertions.Offset = SL->getElementOffset(AssertionCountersField);
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

//===----------------------------------------------------------------------===//
// The layout of input and output, for logs
//===----------------------------------------------------------------------===//

/// Appends what decides where class `C`'s bytes lie: its size and
/// alignment and, per field, its offset, storage, code and extents, with
/// the layout of a class-typed field's class.
static void describeLayout(const NativeClass *C, std::string &Text) {
  if (!C) {
    Text += "none;";
    return;
  }
  Text += C->QualifiedName + " " + std::to_string(C->Size) + " " +
          std::to_string(C->Align) + "{";
  for (const NativeFunction &F : C->Members) {
    if (F.Kind != NativeFunction::Field || !F.FieldOffset)
      continue;
    Text += F.Name + "@" + std::to_string(*F.FieldOffset) + ":" +
            std::to_string(F.Result.TheCode) + "/" +
            std::to_string(F.Result.StorageSize);
    for (uint32_t E : F.Result.Extents)
      Text += "[" + std::to_string(E) + "]";
    if (F.Result.TheCode == NativeType::Class && F.Result.TheClass != C)
      describeLayout(F.Result.TheClass, Text);
    Text += ";";
  }
  Text += "}";
}

std::string bsc::getIOLayoutHash(const Behavior &B) {
  std::string Text = "bsc-io-layout-1\n";
  describeLayout(B.World ? B.World->Input : nullptr, Text);
  describeLayout(B.World ? B.World->Output : nullptr, Text);
  return llvm::utohexstr(llvm::xxh3_64bits(Text), /*LowerCase=*/true, 16);
}

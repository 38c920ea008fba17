//===- CGEntries.cpp - the module's functions and exports -----------------===//
//
// Everything the module has besides the bodies of funcs and tasks: the
// declarations of their functions (in source order), the destroy functions
// of frames holding class values, the exported C entries, the
// `bs_<B>_info` table (bscript.h bs_behavior_info) with its debug tables,
// and the optional program `main`.
//
//===----------------------------------------------------------------------===//
#include "ModuleEmitter.h"
#include "bscript/bscript.h"
#include "llvm/ADT/DenseSet.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/DerivedTypes.h"
#include "llvm/IR/Function.h"
#include "llvm/IR/GlobalVariable.h"

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

llvm::Function *ModuleEmitter::getFunction(const CallableDecl *D) const {
  auto It = Functions.find(D);
  assert(It != Functions.end() && "callable is not part of the behavior");
  return It->second;
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
        if (const NativeClass *C = It->second->getClass())
          IRB.CreateCall(getLifeThunk(C, C->Destroy, 1),
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
  auto *AssertionTy = llvm::StructType::create(
      Ctx, {Ptr, Ptr, I32, I32, Ptr, Ptr}, "bs_assertion_info");
  auto *AssertionsTy = llvm::StructType::create(Ctx, {I32, I32, I32, Ptr},
                                                "bs_assertion_layout");
  auto *InfoTy = llvm::StructType::create(
      Ctx,
      {I32, I32, I32, I32, Ptr, I32, Ptr, Ptr, Ptr, TraceTy, BudgetTy,
       AssertionsTy},
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
               getBudgetInfo(BudgetTy, LoopTy),
               getAssertionInfo(AssertionsTy, AssertionTy)});
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

  // Then `input` and `output`, the world's objects on main's stack.
  IRB.SetInsertPoint(Start);
  // `--flight-recorder`: the runtime records the cycles into the file
  // $BS_FLIGHT_LOG names (a null recorder, recording nothing, without it).
  llvm::Value *Flight = nullptr;
  llvm::FunctionCallee FlightBegin, FlightEnd;
  if (Opts.FlightRecorder) {
    Flight = IRB.CreateCall(
        M.getOrInsertFunction("bs_flight_program_start",
                              llvm::FunctionType::get(Ptr, {Ptr, Ptr, Ptr},
                                                      false)),
        {getFlightTable(), Info, getString(Entry->getQualifiedName())},
        "flight");
    llvm::FunctionType *StepTy = llvm::FunctionType::get(
        llvm::Type::getVoidTy(Ctx), {Ptr, Ptr}, false);
    FlightBegin = M.getOrInsertFunction("bs_flight_begin", StepTy);
    FlightEnd = M.getOrInsertFunction("bs_flight_end", StepTy);
  }
  const NativeClass *WorldClasses[2] = {
      B.World ? B.World->Input : nullptr, B.World ? B.World->Output : nullptr};
  llvm::Value *WorldObjects[2];
  constructWorldObjects(IRB, WorldClasses,
                        llvm::cast<llvm::Instruction>(InitResult),
                        WorldObjects);
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
  if (Flight)
    IRB.CreateCall(FlightBegin, {Flight, State});
  emitBudgetStart(IRB, State);
  llvm::Function *Callee = getFunction(Entry);
  llvm::SmallVector<llvm::Value *, 4> Args = {State};
  // The driver refuses entries with parameters; zeros keep the IR valid.
  for (unsigned A = 1; A < Callee->arg_size(); ++A)
    Args.push_back(llvm::Constant::getNullValue(Callee->getArg(A)->getType()));
  IRB.CreateCall(Callee, Args);
  if (Flight)
    IRB.CreateCall(FlightEnd, {Flight, State});
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
  // `--assertions=count`: the assertions that failed, on stderr, and the
  // program's status says whether any did.
  llvm::Value *Status = llvm::ConstantInt::get(I32, 0);
  if (Opts.Assertions == AssertionMode::Count && !B.Assertions.empty())
    Status = IRB.CreateCall(
        M.getOrInsertFunction("bs_report_assertions",
                              llvm::FunctionType::get(I32, {Ptr, Ptr}, false)),
        {State, Info}, "assertions.failed");
  if (Flight)
    IRB.CreateCall(
        M.getOrInsertFunction(
            "bs_flight_program_end",
            llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), {Ptr}, false)),
        {Flight});
  IRB.CreateCall(Destroy, {State, Info});
  for (unsigned K = 0; K < 2; ++K)
    if (needsDestroy(WorldClasses[K]))
      IRB.CreateCall(getLifeThunk(WorldClasses[K],
                                  WorldClasses[K]->Destroy, 1),
                     {WorldObjects[K]});
  IRB.CreateRet(Status);
}

// `input` and `output` of the world module are objects on main's stack,
// constructed as `bsc run` constructs them (zeroed, then the construct
// thunk) once the state is accepted; generated code reaches them through
// the pointers bs_begin_cycle stores in the state header, so a behavior
// that reads input must never get null. The driver refuses a class that
// can be neither constructed nor start as zero bytes.
void ModuleEmitter::constructWorldObjects(
    llvm::IRBuilderBase &IRB, const NativeClass *const (&Classes)[2],
    llvm::Instruction *AllocasBefore, llvm::Value *(&Objects)[2]) {
  llvm::Constant *Null = llvm::ConstantPointerNull::get(
      llvm::PointerType::getUnqual(Ctx));
  for (unsigned K = 0; K < 2; ++K) {
    const NativeClass *C = Classes[K];
    Objects[K] = Null;
    if (!C)
      continue;
    llvm::Type *Ty = getClassMemoryType(C);
    auto *A = new llvm::AllocaInst(Ty, 0, K == 0 ? "input" : "output",
                                   AllocasBefore);
    A->setAlignment(M.getDataLayout().getABITypeAlign(Ty));
    emitClassInit(IRB, C, A);
    Objects[K] = A;
  }
}

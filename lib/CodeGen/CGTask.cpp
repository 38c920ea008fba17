//===- CGTask.cpp - lowering tasks: generators by hand --------------------===//
//
// A task is a singleton generator. Its function runs one step per call:
//
//   entry:     if ([T.state <= 0 ||] cycle - frame.last_call > 1)
//                goto reset
//   reset:     [destroy(frame) if live]; T.state = running;
//              [T.resume = k]; class values constructed;
//              [frame.live = 1]; goto start
//   running:   [resume = T.resume]
//   dispatch:  frame.last_call = cycle; [frame.params = args]
//              switch (resume) { k: resume.k; default: start }
//   start:     the body...
//   yield k:   [T.resume = k]; [T.state = v];
//              [trace.slot = k; [trace.word = v]]; ret [v]
//   resume.k:  ...the code after the k-th yield
//   end:       [destroy(frame)]; T.state = done;
//              [frame.last_call = cycle ^ ended]; [trace.slot = finished];
//              ret [done]
//
// The task header. A frame starts with the task's last call (4 bytes).
// Its resume point (T.resume) and state (T.state) are as narrow as their
// values allow (ModuleEmitter::chooseTaskWords): the resume point counts
// the yields, a byte up to 255 of them; the state takes a byte when every
// state the task stores is a constant from -128 to 127 (running at the
// reset, done at the end, each yield's). Narrow ones sit in the task's
// narrow header among the others after the frames, widest first, so that
// they cost no padding: a task's header is 6 bytes rather than 12
// (bscript.h bs_task_info). The resume point is switched on in its own
// type; the state is read sign-extended, stored truncated.
//
// The result. In optimised code a task's function returns the state it
// left, which is what its frame's state holds after the call.
// `taskState(T)` right after a call of T in the same block, with no other
// call between (which might call T again), is that result rather than a
// load: the caller of a task that yields values need not read them back
// through memory (not on i386: ModuleEmitter::readsReturnedStates). Calls
// that ignore it let LLVM drop the result (dead argument elimination of
// internal functions). At -O0 and in the JIT's modules tasks return void.
//
// The trace record (`--instrument`, bscript.h "Trace records"): every way
// out of a call writes the task's slot in the state's record, a constant
// (the resume point, or "finished"), and a yield of a value computed at
// run time writes the value into the task's word. One store, where the
// value is known; the embedding zeroes the slots before each cycle, so a
// slot left 0 is a task that was not called.
//
// The last call. Each call records the cycle in frame.last_call, with
// bit 31 flipped if the call ended the task (done or failure); a new
// state's frames read "ended in cycle 0" (bs_state_init). So the unsigned
// gap from last_call to the cycle is 0 or 1 exactly when the task is
// running and was called in this cycle or the previous one, and more
// otherwise: the task starts again. (An ended task not called again for
// 2^31 cycles, 2.3 years at 30 Hz, sees a gap of 0 or 1 again; so does a
// running one after 2^32 cycles.) A task that yields only running or
// constants (YieldPlan::OnlyRunning; most do) marks every ending so, and
// its entry tests the gap alone. Other tasks may end by `yield v` with a
// v <= 0 known only at run time: they test the state too.
//
// Which stores. Only what a later call reads is stored. `resume` is read
// only when the state is running, and every way out of a call either
// stores it (a yield) or leaves the state done or failed (the end, `yield`
// of a value <= 0), so neither the reset nor the end stores it. The reset
// stores state = running (a task that is executing reports running,
// docs/language.md). Most tasks yield nothing but "running" (a plain
// `yield`) besides ending with a constant: their yields leave the state
// alone, and a running call tells the optimiser the state is 1. A task
// with a single yield that keeps it running (most loops) gets that resume
// point at the reset too, and the yield itself stores nothing: it is a
// `ret`. A scalar local gets its value where it is declared, before any
// use, so the reset does not zero it, unless a nested func may read it
// before its declaration (VarDecl::ReadBeforeDeclared). The frame holds
// only what a later call or a nested func reads (keepsInFrame): the body
// reads its parameters from the arguments, and a local that is in scope
// at no yield is an alloca. The JIT's debugger (CodeGenOptions::Probes)
// shows frames between cycles, so there every field is kept exact: all
// parameters and locals, resume 0 when not running, zeroed locals.

// Frames with class values whose destructor is not trivial end with an
// `i8 live` field and have a function `bs.<M>.<task>.destroy(state)` that
// destroys the values if live (newest first) and clears it. The values are
// constructed at the reset and destroyed when the task finishes, at its
// next reset (a running task that missed a cycle) or by bs_state_destroy.
//
// This is done by hand rather than with LLVM's coroutine intrinsics because
// the frame must be a struct whose size is fixed before any optimisation
// runs (it is part of the object's interface and must match at -O0 to -O3),
// and because a coroutine frame would be heap-allocated. The body needs no
// special care: every local that may outlive a call lives in the frame, and
// parameters are re-read from the arguments (fresh on every call), so no
// SSA value is live across a yield and the switch may enter any loop.
//
// The reset rule is language.md's rule 4: start again from the top when the
// last call finished (done or failure, which includes never having run:
// the state starts zeroed) or when the task was called neither in the
// previous cycle nor yet in this one. The gap is computed unsigned so that
// the cycle counter may wrap.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "llvm/IR/Constants.h"
#include "llvm/IR/IntrinsicInst.h"
#include <optional>

using namespace bsc;
using namespace bsc::codegen;
using Access = ModuleEmitter::Access;

llvm::Value *FunctionEmitter::getFrameFieldPtr(const TaskDecl *T,
                                               unsigned Field) {
  llvm::Value *&Addr = FieldAddrs[{T, Field}];
  if (Addr)
    return Addr;
  const FrameInfo &FI = CGM.getFrame(T);
  // One GEP from the state, {0, frame, field}: a constant offset, computed
  // once at the top of the entry block so every use shares one name.
  llvm::IRBuilder<> EntryBuilder(EntryPoint);
  llvm::Value *Idx[] = {EntryBuilder.getInt32(0),
                        EntryBuilder.getInt32(FI.StateFieldNo),
                        EntryBuilder.getInt32(Field)};
  Addr = EntryBuilder.CreateInBoundsGEP(CGM.getStateType(), StatePtr, Idx,
                                        FI.FieldNames[Field]);
  return Addr;
}

llvm::Value *FunctionEmitter::getTaskWordPtr(const TaskDecl *T, TaskWord W) {
  const FrameInfo &FI = CGM.getFrame(T);
  const TaskWordInfo &Word = FI.getWord(W);
  if (Word.InFrame)
    return getFrameFieldPtr(T, Word.Field);
  llvm::Value *&Addr = WordAddrs[{T, unsigned(W)}];
  if (Addr)
    return Addr;
  llvm::IRBuilder<> EntryBuilder(EntryPoint);
  llvm::Value *Idx[] = {EntryBuilder.getInt32(0),
                        EntryBuilder.getInt32(CGM.getHeadersField()),
                        EntryBuilder.getInt32(FI.HeaderFieldNo),
                        EntryBuilder.getInt32(Word.Field)};
  Addr = EntryBuilder.CreateInBoundsGEP(
      CGM.getStateType(), StatePtr, Idx,
      T->getName().Name + (W == TaskWord::Resume ? ".resume" : ".state"));
  return Addr;
}

llvm::Value *FunctionEmitter::loadResume(const TaskDecl *T) {
  // In its own type: the dispatch switches on it, and yields store
  // constants, so the resume point never needs widening.
  return createLoad(Access::State, CGM.getFrame(T).Resume.Ty,
                    getTaskWordPtr(T, TaskWord::Resume), "resume");
}

void FunctionEmitter::storeResume(const TaskDecl *T, unsigned Point) {
  createStore(Access::State,
              llvm::ConstantInt::get(CGM.getFrame(T).Resume.Ty, Point),
              getTaskWordPtr(T, TaskWord::Resume));
}

llvm::Value *FunctionEmitter::loadTaskState(const TaskDecl *T,
                                            const llvm::Twine &Name) {
  llvm::Value *V = createLoad(Access::State, CGM.getFrame(T).State.Ty,
                              getTaskWordPtr(T, TaskWord::State), Name);
  return Builder.CreateSExt(V, Builder.getInt32Ty());
}

void FunctionEmitter::storeTaskState(const TaskDecl *T, llvm::Value *State) {
  // A narrow state holds every value the task can store (chooseTaskWords).
  createStore(Access::State,
              Builder.CreateTrunc(State, CGM.getFrame(T).State.Ty),
              getTaskWordPtr(T, TaskWord::State));
}

llvm::Value *FunctionEmitter::emitTaskState(const TaskDecl *T) {
  // Right after a call of T: what the call returned ("The result").
  if (CGM.readsReturnedStates() && LastTaskCall &&
      LastTaskCall->getCalledFunction() == CGM.getFunction(T) &&
      LastTaskCall->getParent() == Builder.GetInsertBlock() &&
      !llvm::any_of(llvm::make_range(std::next(LastTaskCall->getIterator()),
                                     Builder.GetInsertPoint()),
                    [](const llvm::Instruction &I) {
                      return llvm::isa<llvm::CallBase>(I) &&
                             !llvm::isa<llvm::IntrinsicInst>(I);
                    }))
    return LastTaskCall;
  // A never-called task reports done: the state starts zeroed.
  return loadTaskState(T, "taskstate");
}

std::optional<int64_t> codegen::getConstantState(const Expr *E) {
  if (!E)
    return TaskRunning;
  if (const auto *L = llvm::dyn_cast<IntLiteralExpr>(E))
    return L->Value;
  if (const auto *N = llvm::dyn_cast<NameExpr>(E)) {
    if (N->Kind == NameKind::EnumValue)
      return N->EnumValue;
    if (N->Kind == NameKind::Constant && !N->Const->Ty->isBool())
      return N->Const->Value.Int;
  }
  if (const auto *U = llvm::dyn_cast<UnaryExpr>(E))
    if (U->Op == UnaryOp::Neg)
      if (const auto *L = llvm::dyn_cast<IntLiteralExpr>(U->Operand))
        return -static_cast<int64_t>(L->Value);
  return std::nullopt;
}

YieldPlan codegen::planYields(const TaskDecl &T) {
  YieldPlan P;
  unsigned Running = 0;
  for (const YieldStmt *Y : T.Yields) {
    std::optional<int64_t> V = getConstantState(Y->Value);
    if (!V)
      P.ComputedStates = true;
    if (V && *V <= TaskDone)
      continue; // Ends the task.
    if (!V || *V != TaskRunning)
      P.OnlyRunning = false;
    ++Running;
    P.SingleResume = Y->ResumePoint;
  }
  if (Running != 1)
    P.SingleResume = 0;
  return P;
}

void FunctionEmitter::emitTaskPrologue() {
  llvm::LLVMContext &Ctx = CGM.getContext();
  const FrameInfo &FI = CGM.getFrame(Task);
  llvm::Type *I32 = Builder.getInt32Ty();
  // Locals whose values never outlive a call are allocas, as a func's.
  for (const VarDecl *V : Task->Locals)
    if (!CGM.keepsInFrame(V))
      Slots[V] = createSlot(V->Ty, V->getName().Name);

  llvm::Value *LastAddr = getFrameFieldPtr(Task, FrameLastCall);
  Plan = planYields(*Task);
  Cycle = createLoad(Access::State, I32,
                     Builder.CreateConstInBoundsGEP2_32(
                         CGM.getStateType(), StatePtr, 0, StateCycle,
                         "cycle.addr"),
                     "cycle");
  llvm::Value *Last = createLoad(Access::State, I32, LastAddr, "last.call");
  llvm::Value *Gap = Builder.CreateSub(Cycle, Last, "gap");
  llvm::Value *Reset =
      Builder.CreateICmpUGT(Gap, Builder.getInt32(1), "must.reset");
  if (!Plan.OnlyRunning) {
    llvm::Value *State = loadTaskState(Task, "prev.state");
    llvm::Value *Finished =
        Builder.CreateICmpSLE(State, Builder.getInt32(TaskDone), "finished");
    Reset = Builder.CreateOr(Finished, Reset, "must.reset");
  }

  llvm::BasicBlock *ResetBB = llvm::BasicBlock::Create(Ctx, "reset", Fn);
  llvm::BasicBlock *RunningBB = llvm::BasicBlock::Create(Ctx, "running", Fn);
  llvm::BasicBlock *DispatchBB = llvm::BasicBlock::Create(Ctx, "dispatch", Fn);
  Builder.CreateCondBr(Reset, ResetBB, RunningBB);

  // A running task continues after its last yield.
  Builder.SetInsertPoint(RunningBB);
  // Only running (1) can be stored where the state stays > 0: telling the
  // optimiser so lets a caller's check of this call's state fold (and at
  // -O0, where nothing folds, the load would only cost time).
  if (Plan.OnlyRunning && CGM.getOptions().OptLevel > 0)
    Builder.CreateAssumption(Builder.CreateICmpEQ(
        loadTaskState(Task, "prev.state"),
        Builder.getInt32(TaskRunning)));
  llvm::IntegerType *ResumeTy = FI.Resume.Ty;
  llvm::Value *Resumed = llvm::ConstantInt::get(ResumeTy, Plan.SingleResume);
  if (!Plan.SingleResume)
    Resumed = loadResume(Task);
  Builder.CreateBr(DispatchBB);

  // Fresh class values, constructed (parameters first: they are assigned
  // at every call), after destroying what a running task left behind (a
  // missed cycle) through the frame's destroy function. Scalars need no
  // store (above), except in exact frames and those a nested func may read
  // before their declaration: one store per field, never memset (no libc).
  Builder.SetInsertPoint(ResetBB);
  bool ExactFrames = CGM.getOptions().Probes;
  if (FI.Destroy)
    Builder.CreateCall(FI.Destroy, {StatePtr});
  if (Plan.SingleResume)
    storeResume(Task, Plan.SingleResume);
  else if (ExactFrames)
    storeResume(Task, 0);
  // Running from here on (docs/language.md: an executing task is running).
  storeTaskState(Task, Builder.getInt32(TaskRunning));
  for (const ParamDecl *P : Task->Params)
    if (P->Ty->isClass())
      emitClassInit(P->Ty->getClass(),
                    getFrameFieldPtr(Task, FI.Fields.lookup(P)));
  for (const VarDecl *V : Task->Locals) {
    if (V->Ty->isClass())
      emitClassInit(V->Ty->getClass(),
                    getFrameFieldPtr(Task, FI.Fields.lookup(V)));
    else if (ExactFrames || V->ReadBeforeDeclared)
      createStore(Access::State, CGM.getZeroValue(V->Ty),
                  getFrameFieldPtr(Task, FI.Fields.lookup(V)));
  }
  if (FI.LiveField)
    createStore(Access::State, Builder.getInt8(1),
                getFrameFieldPtr(Task, FI.LiveField));
  llvm::BasicBlock *ResetEnd = Builder.GetInsertBlock();
  Builder.CreateBr(DispatchBB);

  // Parameters are re-evaluated at every call (rule 2): the body reads the
  // arguments; nested funcs read the copies in the frame.
  Builder.SetInsertPoint(DispatchBB);
  llvm::PHINode *Resume = Builder.CreatePHI(ResumeTy, 2, "resume.point");
  Resume->addIncoming(llvm::ConstantInt::get(ResumeTy, 0), ResetEnd);
  Resume->addIncoming(Resumed, RunningBB);
  createStore(Access::State, Cycle, LastAddr);
  for (const ParamDecl *P : Task->Params)
    if (CGM.keepsInFrame(P))
      emitStore(P->Ty, Fn->getArg(P->Index + 1),
                getFrameFieldPtr(Task, FI.Fields.lookup(P)));
  llvm::BasicBlock *StartBB = llvm::BasicBlock::Create(Ctx, "start", Fn);
  // An out-of-range resume point cannot happen (only yields store it); the
  // default restarts the body rather than doing anything undefined.
  ResumeSwitch = Builder.CreateSwitch(Resume, StartBB, Task->Yields.size());
  Builder.SetInsertPoint(StartBB);
}

void FunctionEmitter::emitTaskFinish(int32_t State) {
  // A finished task's values are dead: the next call resets the frame.
  if (llvm::Function *Destroy = CGM.getFrame(Task).Destroy)
    Builder.CreateCall(Destroy, {StatePtr});
  if (CGM.getOptions().Probes)
    storeResume(Task, 0);
  storeTaskState(Task, Builder.getInt32(State));
  markEnded();
  const BehaviorLayout::TraceLayout &Trace = CGM.getLayout().Trace;
  recordTraceExit(State == TaskDone ? Trace.finishedSlot()
                                    : Trace.budgetFailedSlot(),
                  nullptr);
  emitTaskReturn(Builder.getInt32(State));
}

void FunctionEmitter::emitTaskReturn(llvm::Value *State) {
  if (CGM.tasksReturnStates())
    Builder.CreateRet(State);
  else
    Builder.CreateRetVoid();
}

void FunctionEmitter::markEnded() {
  // "The last call" above: the next call starts from the top.
  if (Plan.OnlyRunning)
    createStore(Access::State,
                Builder.CreateXor(Cycle, Builder.getInt32(LastCallEnded)),
                getFrameFieldPtr(Task, FrameLastCall));
}

void FunctionEmitter::recordTraceExit(uint32_t Slot,
                                      llvm::Value *ComputedState) {
  const BehaviorLayout::TraceLayout &Trace = CGM.getLayout().Trace;
  if (!Trace.RecordSize)
    return;
  unsigned Index = CGM.getFrame(Task).TaskIndex;
  llvm::Value *Record = Builder.CreateConstInBoundsGEP2_32(
      CGM.getStateType(), StatePtr, 0, CGM.getTraceRecordField(), "trace");
  llvm::Type *SlotTy = Builder.getIntNTy(8 * Trace.SlotBytes);
  createStore(Access::TraceRecord, llvm::ConstantInt::get(SlotTy, Slot),
              Builder.CreateConstInBoundsGEP1_64(SlotTy, Record, Index,
                                                 "trace.slot"));
  if (ComputedState)
    createStore(Access::TraceRecord, ComputedState,
                Builder.CreateConstInBoundsGEP1_64(
                    Builder.getInt8Ty(), Record, *Trace.StateWords[Index],
                    "trace.state"));
}

void FunctionEmitter::emitTaskEpilogue() {
  // Falling off the end: done, and the next call starts from the top.
  if (!Builder.GetInsertBlock()->getTerminator())
    emitTaskFinish();
}

llvm::Value *FunctionEmitter::emitToTaskState(const Expr *E) {
  llvm::Value *V = emitExpr(E);
  // int, TaskState and enums are already i32; a bool state is 0/1.
  if (V->getType()->isIntegerTy(1))
    return Builder.CreateZExt(V, Builder.getInt32Ty());
  return V;
}

void FunctionEmitter::emitYield(const YieldStmt &S) {
  assert(Task && "Sema allows yield only in tasks");
  assert(S.ResumePoint > 0 && "Sema numbers every yield");
  llvm::Value *State =
      S.Value ? emitToTaskState(S.Value) : Builder.getInt32(TaskRunning);
  popTemps(0); // The value's temporaries are allocas of this call.
  // "Which stores" above: the reset did what a running yield leaves out.
  std::optional<int64_t> Constant = getConstantState(S.Value);
  bool Ends = Constant && *Constant <= TaskDone;
  if (Ends || S.ResumePoint != Plan.SingleResume)
    storeResume(Task, S.ResumePoint);
  if (Ends || !Plan.OnlyRunning)
    storeTaskState(Task, State);
  if (Ends)
    markEnded();
  recordTraceExit(S.ResumePoint, Constant ? nullptr : State);
  emitTaskReturn(State);

  // The code after the yield; a yield that ends the task is never resumed
  // (the next call starts from the top), so nothing jumps there.
  llvm::BasicBlock *ResumeBB = llvm::BasicBlock::Create(
      CGM.getContext(), "resume." + llvm::Twine(S.ResumePoint), Fn);
  if (!Ends)
    ResumeSwitch->addCase(
        llvm::ConstantInt::get(CGM.getFrame(Task).Resume.Ty, S.ResumePoint),
        ResumeBB);
  Builder.SetInsertPoint(ResumeBB);
}

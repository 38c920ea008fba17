//===- CGBudget.cpp - a cycle that always ends: the loop budget -----------===//
//
// `--cycle-budget=N` (bscript.h "Cycle budgets"). A behavior whose loop
// runs away hangs the robot's control thread; the compile-time check
// (lib/Sema/SemaLoops.cpp) finds the common mistakes, and the budget stops
// what is left at run time, on the robot:
//
//   entry:      if (rec.cycle != state.cycle) { rec.cycle = state.cycle;
//                                               rec.used = 0 }
//   back edge:  if (rec.used == N) goto ran_out     (unlikely)
//               rec.used += 1; goto head
//   ran_out:    bs.budget.ran_out(state, loop)      (records it, once)
//               task: state = failure, ret failure  (CGTask's ending)
//               func: ret zero                      (after its cleanups)
//
// A task's loop that yields on every way round (Sema's
// ForStmt::YieldsEveryPass) is not charged: each of its passes needs a
// call of its task, since a yield returns, so it cannot run away by
// itself; a runaway cycle must take some charged back edge without end
// (the calls that resume it come from straight code, bounded, or from a
// loop, charged or bounded the same way up to the entry). That keeps the
// cost off the cycle loops every behavior is made of.
//
// Once the budget is spent every later back edge of the cycle takes the
// same way out, so the tasks above the runaway loop fail in turn as their
// own loops come round, and the cycle returns. Straight code in between
// runs on: it ends without a loop. The record lives after the frames
// (and the trace record) and has a TBAA class of its own, so charging it
// reloads nothing else. A loop's number is its place in the loop table
// (BehaviorLayout::Budget::Loops), which the info table exports with the
// owner's name and the line, for the robot's log and `bsc run`.
//
// Without the option nothing here runs: no record, no charge, the same
// code as before.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "bscript/bscript.h"
#include "llvm/IR/MDBuilder.h"
#include <cstddef>

using namespace bsc;
using namespace bsc::codegen;
using Access = ModuleEmitter::Access;

// The record's words as bscript.h lays them out.
static_assert(sizeof(bs_budget_record) ==
              4 * ModuleEmitter::BudgetRecordWords);
static_assert(offsetof(bs_budget_record, cycle) ==
              4 * ModuleEmitter::BudgetCycle);
static_assert(offsetof(bs_budget_record, used) ==
              4 * ModuleEmitter::BudgetUsed);
static_assert(offsetof(bs_budget_record, ran_out) ==
              4 * ModuleEmitter::BudgetRanOut);
static_assert(offsetof(bs_budget_record, loop) ==
              4 * ModuleEmitter::BudgetLoop);
static_assert(offsetof(bs_budget_record, loop_cycle) ==
              4 * ModuleEmitter::BudgetLoopCycle);

llvm::Value *ModuleEmitter::getBudgetWordPtr(llvm::IRBuilderBase &IRB,
                                             llvm::Value *State,
                                             BudgetWord W) {
  llvm::Value *Idx[] = {IRB.getInt32(0), IRB.getInt32(BudgetRecordField),
                        IRB.getInt32(W)};
  return IRB.CreateInBoundsGEP(StateTy, State, Idx, "budget.word");
}

llvm::LoadInst *ModuleEmitter::loadBudgetWord(llvm::IRBuilderBase &IRB,
                                             llvm::Value *Addr,
                                             const llvm::Twine &Name) {
  llvm::LoadInst *L = IRB.CreateLoad(IRB.getInt32Ty(), Addr, Name);
  L->setMetadata(llvm::LLVMContext::MD_tbaa, getAccessTag(Access::Budget));
  return L;
}

void ModuleEmitter::storeBudgetWord(llvm::IRBuilderBase &IRB, llvm::Value *V,
                                    llvm::Value *Addr) {
  IRB.CreateStore(V, Addr)->setMetadata(llvm::LLVMContext::MD_tbaa,
                                        getAccessTag(Access::Budget));
}

unsigned ModuleEmitter::addBudgetLoop(const CallableDecl *Owner,
                                      llvm::SMLoc Loc) {
  Layout.Budget.Loops.push_back({Owner, Loc});
  return Layout.Budget.Loops.size();
}

llvm::Function *ModuleEmitter::getBudgetRanOut() {
  if (BudgetRanOutFn)
    return BudgetRanOutFn;
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Type *Ptr = llvm::PointerType::getUnqual(Ctx);
  BudgetRanOutFn = llvm::Function::Create(
      llvm::FunctionType::get(llvm::Type::getVoidTy(Ctx), {Ptr, I32}, false),
      llvm::GlobalValue::InternalLinkage, "bs.budget.ran_out", M);
  addCommonAttributes(BudgetRanOutFn);
  // Reached once per cycle that runs out: keep it out of the loops.
  BudgetRanOutFn->addFnAttr(llvm::Attribute::Cold);
  BudgetRanOutFn->addFnAttr(llvm::Attribute::NoInline);
  llvm::Value *State = BudgetRanOutFn->getArg(0);
  llvm::Value *Loop = BudgetRanOutFn->getArg(1);
  State->setName(StateParamName);
  Loop->setName("loop");
  auto *Entry = llvm::BasicBlock::Create(Ctx, "entry", BudgetRanOutFn);
  auto *First = llvm::BasicBlock::Create(Ctx, "first", BudgetRanOutFn);
  auto *Done = llvm::BasicBlock::Create(Ctx, "done", BudgetRanOutFn);
  llvm::IRBuilder<> IRB(Entry);
  auto Word = [&](BudgetWord W) { return getBudgetWordPtr(IRB, State, W); };
  // The first loop to run out in a cycle is the runaway one; the loops
  // above it that end after it are not news.
  llvm::Value *Cycle = loadBudgetWord(IRB, Word(BudgetCycle), "cycle");
  llvm::Value *Again = IRB.CreateAnd(
      IRB.CreateICmpNE(loadBudgetWord(IRB, Word(BudgetLoop)),
                       IRB.getInt32(0)),
      IRB.CreateICmpEQ(loadBudgetWord(IRB, Word(BudgetLoopCycle)), Cycle),
      "again");
  IRB.CreateCondBr(Again, Done, First);
  IRB.SetInsertPoint(First);
  storeBudgetWord(IRB,
                  IRB.CreateAdd(loadBudgetWord(IRB, Word(BudgetRanOut)),
                                IRB.getInt32(1)),
                  Word(BudgetRanOut));
  storeBudgetWord(IRB, Loop, Word(BudgetLoop));
  storeBudgetWord(IRB, Cycle, Word(BudgetLoopCycle));
  // `--instrument`: the cycle's trace record says it too.
  const BehaviorLayout::TraceLayout &Trace = Layout.Trace;
  if (Trace.BudgetWord) {
    llvm::Value *Record = IRB.CreateConstInBoundsGEP2_32(
        StateTy, State, 0, TraceRecordField, "trace");
    IRB.CreateStore(Loop, IRB.CreateConstInBoundsGEP1_64(
                              IRB.getInt8Ty(), Record, *Trace.BudgetWord))
        ->setMetadata(llvm::LLVMContext::MD_tbaa,
                      getAccessTag(Access::TraceRecord));
  }
  IRB.CreateBr(Done);
  IRB.SetInsertPoint(Done);
  IRB.CreateRetVoid();
  return BudgetRanOutFn;
}

void ModuleEmitter::emitBudgetStart(llvm::IRBuilderBase &IRB,
                                    llvm::Value *State) {
  if (!Opts.CycleBudget)
    return;
  llvm::LoadInst *Now = IRB.CreateLoad(
      IRB.getInt32Ty(),
      IRB.CreateConstInBoundsGEP2_32(StateTy, State, 0, StateCycle), "cycle");
  Now->setMetadata(llvm::LLVMContext::MD_tbaa, getAccessTag(Access::State));
  llvm::Value *CycleAddr = getBudgetWordPtr(IRB, State, BudgetCycle);
  llvm::Value *Counted = loadBudgetWord(IRB, CycleAddr, "budget.cycle");
  llvm::Value *Fresh = IRB.CreateICmpNE(Counted, Now, "budget.new.cycle");
  llvm::Function *F = IRB.GetInsertBlock()->getParent();
  auto *Reset = llvm::BasicBlock::Create(Ctx, "budget.reset", F);
  auto *Go = llvm::BasicBlock::Create(Ctx, "budget.counted", F);
  IRB.CreateCondBr(Fresh, Reset, Go);
  IRB.SetInsertPoint(Reset);
  storeBudgetWord(IRB, Now, CycleAddr);
  storeBudgetWord(IRB, IRB.getInt32(0),
                  getBudgetWordPtr(IRB, State, BudgetUsed));
  IRB.CreateBr(Go);
  IRB.SetInsertPoint(Go);
}

llvm::Constant *ModuleEmitter::getBudgetInfo(llvm::StructType *LayoutTy,
                                             llvm::StructType *LoopTy) {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Constant *Null =
      llvm::ConstantPointerNull::get(llvm::PointerType::getUnqual(Ctx));
  const BehaviorLayout::BudgetLayout &Budget = Layout.Budget;
  llvm::Constant *Loops = Null;
  if (!Budget.Loops.empty()) {
    std::vector<llvm::Constant *> Elts;
    for (const BehaviorLayout::BudgetLayout::Loop &L : Budget.Loops) {
      std::pair<unsigned, unsigned> LineCol{0, 0};
      if (Opts.Sources && Opts.Sources->FindBufferContainingLoc(L.Loc))
        LineCol = Opts.Sources->getLineAndColumn(L.Loc);
      int32_t Task = -1;
      if (const auto *T = llvm::dyn_cast<TaskDecl>(L.Owner))
        Task = getFrame(T).TaskIndex;
      Elts.push_back(llvm::ConstantStruct::get(
          LoopTy, {getString(L.Owner->getQualifiedName()),
                   llvm::ConstantInt::get(I32, LineCol.first),
                   llvm::ConstantInt::get(I32, LineCol.second),
                   llvm::ConstantInt::get(I32, Task, /*IsSigned=*/true)}));
    }
    auto *ArrTy = llvm::ArrayType::get(LoopTy, Elts.size());
    Loops = new llvm::GlobalVariable(
        M, ArrTy, /*isConstant=*/true, llvm::GlobalValue::PrivateLinkage,
        llvm::ConstantArray::get(ArrTy, Elts),
        "bs_" + Opts.BehaviorName + "_loops");
  }
  return llvm::ConstantStruct::get(
      LayoutTy, {llvm::ConstantInt::get(I32, Budget.Budget),
                 llvm::ConstantInt::get(I32, Budget.Offset),
                 llvm::ConstantInt::get(I32, Budget.Loops.size()), Loops});
}

void FunctionEmitter::emitBudgetCharge(const ForStmt &S) {
  llvm::LLVMContext &Ctx = CGM.getContext();
  unsigned Loop = CGM.addBudgetLoop(&D, S.getLoc());
  llvm::Value *UsedAddr =
      CGM.getBudgetWordPtr(Builder, StatePtr, ModuleEmitter::BudgetUsed);
  llvm::Value *Used = createLoad(Access::Budget, Builder.getInt32Ty(),
                                 UsedAddr, "budget.used");
  llvm::Value *Spent = Builder.CreateICmpEQ(
      Used, Builder.getInt32(CGM.getOptions().CycleBudget), "budget.spent");
  auto *RanOut = llvm::BasicBlock::Create(Ctx, "budget.ran_out", Fn);
  auto *Go = llvm::BasicBlock::Create(Ctx, "budget.go", Fn);
  Builder.CreateCondBr(Spent, RanOut, Go,
                       llvm::MDBuilder(Ctx).createUnlikelyBranchWeights());

  Builder.SetInsertPoint(RanOut);
  Builder.CreateCall(CGM.getBudgetRanOut(),
                     {StatePtr, Builder.getInt32(Loop)});
  if (Task)
    emitTaskFinish(TaskFailure);
  else
    emitFuncZeroReturn();

  Builder.SetInsertPoint(Go);
  createStore(Access::Budget, Builder.CreateAdd(Used, Builder.getInt32(1)),
              UsedAddr);
}

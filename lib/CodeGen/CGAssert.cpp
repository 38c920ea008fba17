//===- CGAssert.cpp - assert(cond[, "message"]) ---------------------------===//
//
// What an assertion compiles to depends on CodeGenOptions::Assertions
// (bscript.h "Assertions", docs/language.md "Assertions"):
//
//   None    nothing; the condition is not evaluated (Sema made sure that
//           evaluating it changes nothing)
//   Count   if (!cond) state.assertions[k] += 1          (unlikely)
//   Trap    if (!cond) llvm.trap                          (unlikely)
//   Verify  bs.verify.check(cond, index, is-assume): `bsc verify` reads it
//   Report  record = {site, mask 0}; evaluate cond writing its operands
//           into the record (as CGExplain.cpp does for `:why`);
//           if (!cond) { bs.assert.record = record; llvm.trap }
//
// Report is the JIT's: the trap raises SIGILL, the session's guard ends
// the cycle, and the driver finds the assertion's record in
// bs.assert.record and reports it with the values the cycle computed. The
// record is on the stack while the condition runs, since a func the
// condition calls may hold assertions of its own.
//
// The table bs_behavior_info.assertions lists every assertion with its
// place, text and message for Count and Trap, so that a robot's log can
// name what failed.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"
#include "bscript/bscript.h"
#include "llvm/IR/Intrinsics.h"
#include "llvm/IR/MDBuilder.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/SourceMgr.h"

using namespace bsc;
using namespace bsc::codegen;

unsigned ModuleEmitter::getAssertionIndex(const AssertStmt *S) {
  if (AssertionIndex.empty())
    for (unsigned I = 0; I < B.Assertions.size(); ++I)
      AssertionIndex[B.Assertions[I].S] = I;
  auto It = AssertionIndex.find(S);
  assert(It != AssertionIndex.end() && "Sema lists every assertion");
  return It->second;
}

llvm::Value *ModuleEmitter::getAssertionCounterPtr(llvm::IRBuilderBase &IRB,
                                                   llvm::Value *State,
                                                   unsigned Index) {
  return IRB.CreateConstInBoundsGEP2_32(
      StateTy->getElementType(AssertionCountersField),
      IRB.CreateConstInBoundsGEP2_32(StateTy, State, 0,
                                     AssertionCountersField),
      0, Index, "assertion.counter");
}

llvm::GlobalVariable *ModuleEmitter::getAssertRecord() {
  if (llvm::GlobalVariable *G = M.getGlobalVariable(AssertRecordSymbol))
    return G;
  auto *Ty = llvm::ArrayType::get(llvm::Type::getInt8Ty(Ctx),
                                  AssertRecordCapacity);
  auto *G = new llvm::GlobalVariable(
      M, Ty, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
      llvm::Constant::getNullValue(Ty), AssertRecordSymbol);
  G->setAlignment(llvm::Align(8));
  return G;
}

/// The condition as written, for the table.
static std::string getConditionText(const AssertStmt &S) {
  llvm::SMRange R = S.Cond->getRange();
  if (!R.Start.isValid() || !R.End.isValid() ||
      R.End.getPointer() < R.Start.getPointer())
    return "";
  return std::string(R.Start.getPointer(),
                     R.End.getPointer() - R.Start.getPointer());
}

llvm::Constant *ModuleEmitter::getAssertionInfo(llvm::StructType *LayoutTy,
                                                llvm::StructType *EntryTy) {
  llvm::Type *I32 = llvm::Type::getInt32Ty(Ctx);
  llvm::Constant *Null =
      llvm::ConstantPointerNull::get(llvm::PointerType::getUnqual(Ctx));
  AssertionMode Mode = Opts.Assertions;
  bool Listed = (Mode == AssertionMode::Count || Mode == AssertionMode::Trap) &&
                !B.Assertions.empty();
  llvm::Constant *Table = Null;
  if (Listed) {
    std::vector<llvm::Constant *> Elts;
    for (const Behavior::Assertion &A : B.Assertions) {
      std::pair<unsigned, unsigned> LineCol{0, 0};
      std::string File;
      if (unsigned Buffer = Opts.Sources
                                ? Opts.Sources->FindBufferContainingLoc(
                                      A.S->getLoc())
                                : 0) {
        LineCol = Opts.Sources->getLineAndColumn(A.S->getLoc(), Buffer);
        File = llvm::sys::path::filename(
                   Opts.Sources->getMemoryBuffer(Buffer)->getBufferIdentifier())
                   .str();
      }
      Elts.push_back(llvm::ConstantStruct::get(
          EntryTy,
          {getString(A.Owner->getQualifiedName()), getString(File),
           llvm::ConstantInt::get(I32, LineCol.first),
           llvm::ConstantInt::get(I32, LineCol.second),
           getString(getConditionText(*A.S)),
           A.S->Message ? getString(A.S->Message->Value) : Null}));
    }
    auto *ArrTy = llvm::ArrayType::get(EntryTy, Elts.size());
    Table = new llvm::GlobalVariable(
        M, ArrTy, /*isConstant=*/true, llvm::GlobalValue::PrivateLinkage,
        llvm::ConstantArray::get(ArrTy, Elts),
        "bs_" + Opts.BehaviorName + "_assertions");
  }
  // Report is the JIT's, which has no table.
  uint32_t CMode = Mode == AssertionMode::Count  ? BS_ASSERTIONS_COUNT
                   : Mode == AssertionMode::Trap ? BS_ASSERTIONS_TRAP
                                                 : BS_ASSERTIONS_NONE;
  return llvm::ConstantStruct::get(
      LayoutTy,
      {llvm::ConstantInt::get(I32, CMode),
       llvm::ConstantInt::get(I32, Layout.Assertions.Offset),
       llvm::ConstantInt::get(I32, Listed ? B.Assertions.size() : 0), Table});
}

void FunctionEmitter::emitAssert(const AssertStmt &S) {
  AssertionMode Mode = CGM.getOptions().Assertions;
  if (Mode == AssertionMode::None)
    return;
  llvm::LLVMContext &Ctx = CGM.getContext();
  llvm::Value *Holds;
  llvm::AllocaInst *Record = nullptr;
  uint32_t RecordSize = 0;
  // The JIT's recorder is told where the condition's calls into C++ are:
  // a replay of a robot's log makes them for real when the robot's object
  // left its assertions out (bsc/JIT/Boundary.h).
  llvm::FunctionCallee MarkAssertion;
  if (CGM.getOptions().Boundary) {
    MarkAssertion = CGM.getModule().getOrInsertFunction(
        "bs_boundary_assertion",
        llvm::FunctionType::get(Builder.getVoidTy(), {Builder.getInt32Ty()},
                                false));
    Builder.CreateCall(MarkAssertion, {Builder.getInt32(1)});
  }
  if (Mode == AssertionMode::Report) {
    Holds = emitRecordedCond(
        ExplainSite::Assert, S.getLoc(), S.Cond,
        [&](unsigned Number, uint32_t Size) -> llvm::Value * {
          // In the entry block: a loop must not grow the stack.
          llvm::IRBuilder<> Entry(EntryPoint);
          Record = Entry.CreateAlloca(
              llvm::ArrayType::get(Builder.getInt8Ty(), Size), nullptr,
              "assert.record");
          Record->setAlignment(llvm::Align(8));
          RecordSize = Size;
          Builder.CreateAlignedStore(Builder.getInt32(Number), Record,
                                     llvm::Align(8));
          Builder.CreateAlignedStore(
              Builder.getInt64(0),
              Builder.CreateConstInBoundsGEP1_32(Builder.getInt8Ty(), Record,
                                                 8),
              llvm::Align(8));
          return Record;
        });
  } else {
    Holds = emitFullCond(S.Cond);
  }
  if (MarkAssertion)
    Builder.CreateCall(MarkAssertion, {Builder.getInt32(0)});
  if (Mode == AssertionMode::Verify) {
    llvm::FunctionCallee Check = CGM.getModule().getOrInsertFunction(
        VerifyCheckSymbol,
        llvm::FunctionType::get(
            Builder.getVoidTy(),
            {Builder.getInt1Ty(), Builder.getInt32Ty(), Builder.getInt1Ty()},
            false));
    // It reads nothing and writes nothing the behavior sees, so the
    // optimiser keeps the code around it as it would be without it.
    if (auto *F = llvm::dyn_cast<llvm::Function>(Check.getCallee()))
      F->setMemoryEffects(llvm::MemoryEffects::inaccessibleMemOnly());
    Builder.CreateCall(Check, {Holds, Builder.getInt32(CGM.getAssertionIndex(&S)),
                               Builder.getInt1(S.IsAssume)});
    return;
  }
  auto *Failed = llvm::BasicBlock::Create(Ctx, "assert.failed", Fn);
  auto *Go = llvm::BasicBlock::Create(Ctx, "assert.ok", Fn);
  Builder.CreateCondBr(Holds, Go, Failed,
                       llvm::MDBuilder(Ctx).createLikelyBranchWeights());
  Builder.SetInsertPoint(Failed);
  if (Mode == AssertionMode::Count) {
    llvm::Value *Counter = CGM.getAssertionCounterPtr(
        Builder, StatePtr, CGM.getAssertionIndex(&S));
    Builder.CreateStore(
        Builder.CreateAdd(Builder.CreateLoad(Builder.getInt32Ty(), Counter),
                          Builder.getInt32(1)),
        Counter);
    Builder.CreateBr(Go);
  } else {
    if (Record)
      Builder.CreateMemCpy(CGM.getAssertRecord(), llvm::MaybeAlign(8), Record,
                           llvm::MaybeAlign(8), RecordSize);
    Builder.CreateIntrinsic(llvm::Intrinsic::trap, {}, {});
    Builder.CreateUnreachable();
  }
  Builder.SetInsertPoint(Go);
}

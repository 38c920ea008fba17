//===- CGCoverage.cpp - counters of what a run exercised -------------------===//
//
// CodeGenOptions::Coverage, for `bsc run/replay --coverage` and the REPL's
// `:coverage` (docs/testing-behaviors.md): one 64-bit counter per
//
//   call of a func or task      at the top of its entry block, before a
//                               task's resume dispatch: every call counts
//   statement                   as it starts (blocks aside): a `yield`
//                               counts when it is reached, a `for` when it
//                               is entered, its `init` and `step` each time
//   `if` / `for` condition      two counters: counter[true] += holds,
//                               counter[false] += !holds (no branch)
//
// in the global bs.coverage.counters; BehaviorLayout::CoverageSites says
// what each counts, and lib/Run/Coverage.cpp turns them into an lcov
// tracefile and a summary. Only the JIT's modules have them, like the
// probes: the values computed do not change, and objects for the robot
// never count. The counters are sized once every function is emitted, so
// the code adds to a placeholder that finishCoverage replaces.
//
//===----------------------------------------------------------------------===//
#include "FunctionEmitter.h"

using namespace bsc;
using namespace bsc::codegen;

unsigned ModuleEmitter::addCoverageSite(CoverageSite Site) {
  Layout.CoverageSites.push_back(Site);
  return Layout.CoverageSites.size() - 1;
}

void ModuleEmitter::emitCoverageAdd(llvm::IRBuilderBase &IRB, unsigned Index,
                                    llvm::Value *By) {
  llvm::Type *I64 = IRB.getInt64Ty();
  if (!CoveragePlaceholder)
    CoveragePlaceholder = new llvm::GlobalVariable(
        M, I64, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
        nullptr, "bs.coverage.placeholder");
  llvm::Value *Addr = IRB.CreateConstInBoundsGEP1_64(I64, CoveragePlaceholder,
                                                     Index, "coverage");
  IRB.CreateStore(IRB.CreateAdd(IRB.CreateLoad(I64, Addr), By), Addr);
}

void ModuleEmitter::finishCoverage() {
  if (!CoveragePlaceholder)
    return;
  auto *Ty = llvm::ArrayType::get(llvm::Type::getInt64Ty(Ctx),
                                  Layout.CoverageSites.size());
  auto *G = new llvm::GlobalVariable(
      M, Ty, /*isConstant=*/false, llvm::GlobalValue::ExternalLinkage,
      llvm::Constant::getNullValue(Ty), CoverageCountersSymbol);
  G->setAlignment(llvm::Align(8));
  CoveragePlaceholder->replaceAllUsesWith(G);
  CoveragePlaceholder->eraseFromParent();
  CoveragePlaceholder = nullptr;
}

void FunctionEmitter::emitStmtCount(const Stmt &S) {
  if (!CGM.getOptions().Coverage || llvm::isa<BlockStmt>(S) ||
      llvm::isa<FuncDeclStmt>(S))
    return;
  unsigned Index = CGM.addCoverageSite({CoverageSite::Stmt, &S, &D});
  CGM.emitCoverageAdd(Builder, Index, Builder.getInt64(1));
}

void FunctionEmitter::emitBranchCount(const Stmt &S, const Expr *Cond,
                                      llvm::Value *Holds) {
  // `for(; true; yield)` has one way only.
  if (!CGM.getOptions().Coverage || llvm::isa<BoolLiteralExpr>(Cond))
    return;
  unsigned True = CGM.addCoverageSite({CoverageSite::True, &S, &D});
  unsigned False = CGM.addCoverageSite({CoverageSite::False, &S, &D});
  llvm::Value *One = Builder.CreateZExt(Holds, Builder.getInt64Ty());
  CGM.emitCoverageAdd(Builder, True, One);
  CGM.emitCoverageAdd(Builder, False,
                      Builder.CreateSub(Builder.getInt64(1), One));
}

void FunctionEmitter::emitCallCount() {
  unsigned Index = CGM.addCoverageSite({CoverageSite::Call, &D, &D});
  llvm::IRBuilderBase::InsertPointGuard Guard(Builder);
  llvm::Instruction *First = EntryPoint->getNextNode();
  Builder.SetInsertPoint(First);
  Builder.SetCurrentDebugLocation(First->getDebugLoc());
  CGM.emitCoverageAdd(Builder, Index, Builder.getInt64(1));
}

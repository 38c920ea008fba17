//===- Optimize.cpp - the -O0..-O3 pipelines -------------------------------===//
//
// LLVM's own default pipelines from the new pass manager; bsc adds no passes
// of its own. One thing is changed: the target library info says the
// target has no C library at all, because the generated object must link
// into robot software with only the runtime shim (architecture.md). Without
// that, loop idiom recognition could turn a loop that zeroes a frame into a
// memset call, and the optimiser could call libm.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/Analysis/TargetLibraryInfo.h"
#include "llvm/IR/Module.h"
#include "llvm/Passes/PassBuilder.h"

using namespace bsc;

static llvm::OptimizationLevel getLevel(unsigned OptLevel) {
  switch (OptLevel) {
  case 0:
    return llvm::OptimizationLevel::O0;
  case 1:
    return llvm::OptimizationLevel::O1;
  case 2:
    return llvm::OptimizationLevel::O2;
  }
  return llvm::OptimizationLevel::O3;
}

void bsc::optimizeModule(llvm::Module &M, llvm::TargetMachine *TM,
                         unsigned OptLevel) {
  llvm::LoopAnalysisManager LAM;
  llvm::FunctionAnalysisManager FAM;
  llvm::CGSCCAnalysisManager CGAM;
  llvm::ModuleAnalysisManager MAM;

  llvm::PipelineTuningOptions PTO;
  llvm::PassBuilder PB(TM, PTO);

  // Registered before the defaults, so it wins over the triple's library.
  llvm::TargetLibraryInfoImpl TLII(llvm::Triple(M.getTargetTriple()));
  TLII.disableAllFunctions();
  FAM.registerPass([&] { return llvm::TargetLibraryAnalysis(TLII); });

  PB.registerModuleAnalyses(MAM);
  PB.registerCGSCCAnalyses(CGAM);
  PB.registerFunctionAnalyses(FAM);
  PB.registerLoopAnalyses(LAM);
  PB.crossRegisterProxies(LAM, FAM, CGAM, MAM);

  llvm::OptimizationLevel Level = getLevel(OptLevel);
  llvm::ModulePassManager MPM = OptLevel == 0
                                    ? PB.buildO0DefaultPipeline(Level)
                                    : PB.buildPerModuleDefaultPipeline(Level);
  MPM.run(M, MAM);
}

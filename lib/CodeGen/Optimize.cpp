//===- Optimize.cpp - the -O0..-O3 pipelines -------------------------------===//
//
// LLVM's own default pipelines from the new pass manager; bsc adds no passes
// of its own. The target library info says the target has no C library at
// all, because the generated object must link into robot software with
// only the runtime shim (architecture.md). Without that, loop idiom
// recognition could turn a loop that zeroes a frame into a memset call, and
// the optimiser could call libm. And two LLVM options get other defaults
// (setPipelineDefaults): SimplifyCFG does not sink instructions common to
// the predecessors of a block, and GVN searches fewer blocks for a load's
// value.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/Analysis/TargetLibraryInfo.h"
#include "llvm/IR/Module.h"
#include "llvm/Passes/PassBuilder.h"
#include "llvm/Support/CommandLine.h"

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

/// The inliner's threshold at -O1 and up (bench/README.md, 2026-11-25: the
/// wide benchmark -2.5% on i586 and x86_64 against 225, its code +10%).
static constexpr int InlineThreshold = 275;

/// LLVM options whose defaults bsc's pipelines change, unless the command
/// line sets them. LLVM reads them as globals (cl::opt) and offers no
/// pipeline option for them.
static void setPipelineDefaults() {
  static const std::pair<llvm::StringRef, llvm::StringRef> Defaults[] = {
      // A task's exits store their resume point and state and return; once
      // the task is inlined, sinking merges those stores into one store of
      // PHIs, which costs a move per exit and, on i586, spills
      // (bench/README.md: 2 to 6% fewer instructions per cycle, and
      // smaller code).
      {"simplifycfg-sink-common", "false"},
      // GVN's memory dependence analysis looks for a load's value through
      // up to 200 predecessor blocks. A behavior inlines into one large
      // function of many small blocks that read and write the state, where
      // those searches were a third of the optimiser's work; 40 blocks find
      // everything the benchmarks gain from (bench/README.md).
      {"memdep-block-number-limit", "40"},
  };
  llvm::StringMap<llvm::cl::Option *> &Options =
      llvm::cl::getRegisteredOptions();
  for (auto [Name, Value] : Defaults) {
    llvm::cl::Option *O = Options.lookup(Name);
    assert(O && "an option of LLVM 19 that bsc sets");
    // Setting it counts as an occurrence: once per process.
    if (O && O->getNumOccurrences() == 0)
      O->addOccurrence(0, Name, Value);
  }
}

void bsc::optimizeModule(llvm::Module &M, llvm::TargetMachine *TM,
                         unsigned OptLevel) {
  setPipelineDefaults();
  llvm::LoopAnalysisManager LAM;
  llvm::FunctionAnalysisManager FAM;
  llvm::CGSCCAnalysisManager CGAM;
  llvm::ModuleAnalysisManager MAM;

  llvm::PipelineTuningOptions PTO;
  // Behaviors are many small state machines, where a call costs more of
  // the work than in most C++: inline a little more than clang's -O2 (225).
  PTO.InlinerThreshold = InlineThreshold;
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

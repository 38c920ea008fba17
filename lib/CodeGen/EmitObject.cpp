//===- EmitObject.cpp - assembly and object files --------------------------===//
//
// Machine code generation still runs on the legacy pass manager in LLVM 19
// (TargetMachine::addPassesToEmitFile), so this is the one place bsc uses it.
// As in Optimize.cpp, the target library info has no C functions.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/Analysis/TargetLibraryInfo.h"
#include "llvm/IR/LegacyPassManager.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

llvm::Error bsc::emitMachineCode(llvm::Module &M, llvm::TargetMachine &TM,
                                 llvm::CodeGenFileType Kind,
                                 llvm::raw_pwrite_stream &OS) {
  M.setDataLayout(TM.createDataLayout());
  M.setTargetTriple(TM.getTargetTriple().str());

  llvm::legacy::PassManager PM;
  llvm::TargetLibraryInfoImpl TLII(TM.getTargetTriple());
  TLII.disableAllFunctions();
  PM.add(new llvm::TargetLibraryInfoWrapperPass(TLII));
  if (TM.addPassesToEmitFile(PM, OS, nullptr, Kind))
    return llvm::createStringError(
        "LLVM cannot emit " +
        llvm::StringRef(Kind == llvm::CodeGenFileType::AssemblyFile
                            ? "assembly"
                            : "object files") +
        " for " + TM.getTargetTriple().str());
  PM.run(M);
  return llvm::Error::success();
}

//===- EmitObject.cpp - assembly and object files --------------------------===//
//
// Machine code generation still runs on the legacy pass manager in LLVM 19
// (TargetMachine::addPassesToEmitFile), so this is the one place bsc uses it.
// As in Optimize.cpp, the target library info has no C functions.
//
// Back ends report what they cannot lower through the LLVMContext or, for
// some targets, report_fatal_error; BackendErrorReporter turns both into a
// `bsc: error:` and exit status 1 instead of LLVM's "LLVM ERROR" or abort.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/Target.h"
#include "llvm/Analysis/TargetLibraryInfo.h"
#include "llvm/IR/DiagnosticInfo.h"
#include "llvm/IR/DiagnosticPrinter.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/LegacyPassManager.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/Signals.h"
#include "llvm/Support/raw_ostream.h"
#include <cstdlib>

using namespace bsc;

bool bsc::emitMachineCode(llvm::Module &M, llvm::TargetMachine &TM,
                          llvm::CodeGenFileType Kind,
                          llvm::raw_pwrite_stream &OS,
                          DiagnosticEngine &Diags) {
  if (!checkMachineCodeSupport(TM.getTargetTriple(), Kind, Diags))
    return false;
  M.setDataLayout(TM.createDataLayout());
  M.setTargetTriple(TM.getTargetTriple().str());

  llvm::legacy::PassManager PM;
  llvm::TargetLibraryInfoImpl TLII(TM.getTargetTriple());
  TLII.disableAllFunctions();
  PM.add(new llvm::TargetLibraryInfoWrapperPass(TLII));
  // Fails when the target has no MC code emitter or assembler back end for
  // the triple's object format (SPIR-V, NVPTX, ...).
  if (TM.addPassesToEmitFile(PM, OS, nullptr, Kind)) {
    const llvm::Triple &T = TM.getTargetTriple();
    if (Kind == llvm::CodeGenFileType::ObjectFile)
      Diags.report(llvm::SMLoc(), diag::err_no_object_writer)
          << T.str()
          << llvm::Triple::getObjectFormatTypeName(T.getObjectFormat());
    else
      Diags.report(llvm::SMLoc(), diag::err_backend_failed)
          << T.str() << "LLVM cannot write assembly for it";
    return false;
  }
  PM.run(M);
  return !Diags.hasErrors();
}

BackendErrorReporter::BackendErrorReporter(llvm::LLVMContext &Ctx,
                                           DiagnosticEngine &Diags,
                                           std::string Target,
                                           std::function<void()> PrintAndExit)
    : Ctx(Ctx), Diags(Diags), Target(std::move(Target)),
      PrintAndExit(std::move(PrintAndExit)) {
  llvm::install_fatal_error_handler(handleFatal, this);
  Ctx.setDiagnosticHandlerCallBack(handleDiagnostic, this);
}

BackendErrorReporter::~BackendErrorReporter() {
  llvm::remove_fatal_error_handler();
  Ctx.setDiagnosticHandlerCallBack(nullptr, nullptr);
}

void BackendErrorReporter::handleFatal(void *Self, const char *Reason,
                                       bool GenCrashDiag) {
  auto &R = *static_cast<BackendErrorReporter *>(Self);
  R.Diags.report(llvm::SMLoc(), diag::err_backend_failed)
      << R.Target << Reason;
  R.PrintAndExit();
  // What report_fatal_error would do next, minus the abort() it does for
  // some errors: remove the output files, and exit without running static
  // destructors over LLVM's broken state.
  llvm::sys::RunInterruptHandlers();
  std::_Exit(1);
}

void BackendErrorReporter::handleDiagnostic(const llvm::DiagnosticInfo *DI,
                                            void *Self) {
  if (DI->getSeverity() != llvm::DS_Error)
    return;
  auto &R = *static_cast<BackendErrorReporter *>(Self);
  std::string Message;
  llvm::raw_string_ostream OS(Message);
  llvm::DiagnosticPrinterRawOStream DP(OS);
  DI->print(DP);
  R.Diags.report(llvm::SMLoc(), diag::err_backend_failed)
      << R.Target << llvm::StringRef(Message).split('\n').first;
}

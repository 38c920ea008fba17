//===- Output.cpp - files bsc writes --------------------------------------===//
#include "bsc/Basic/Output.h"
#include "llvm/Support/FileSystem.h"

using namespace bsc;

std::unique_ptr<llvm::ToolOutputFile>
bsc::openOutput(DiagnosticEngine &Diags, llvm::StringRef Path, bool Text) {
  std::error_code EC;
  if (Path != "-" && llvm::sys::fs::is_directory(Path)) {
    Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << "is a directory";
    return nullptr;
  }
  auto Out = std::make_unique<llvm::ToolOutputFile>(
      Path, EC, Text ? llvm::sys::fs::OF_Text : llvm::sys::fs::OF_None);
  if (EC) {
    Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    return nullptr;
  }
  return Out;
}

bool bsc::keepOutput(DiagnosticEngine &Diags, llvm::ToolOutputFile &Out,
                     llvm::StringRef Path) {
  Out.os().close();
  if (Out.os().has_error()) {
    Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << Out.os().error().message();
    Out.os().clear_error();
    return false;
  }
  Out.keep();
  return true;
}

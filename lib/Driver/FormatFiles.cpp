//===- FormatFiles.cpp - `bsc format`: files in the canonical layout ------===//
//
// Reads each file as the compiler does (so a missing file or a directory
// is the usual error), formats it with lib/Format and prints, rewrites or
// checks it. A file is rewritten only when it changes, through a temporary
// file renamed over it, so that an interrupted run never leaves half a file.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Format/Format.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/ToolOutputFile.h"

using namespace bsc;

/// Rewrites `Path` with `Text`. Returns false after reporting.
static bool rewriteFile(Compilation &C, llvm::StringRef Path,
                        llvm::StringRef Text) {
  std::error_code EC;
  llvm::ToolOutputFile Out((Path + ".bsc-format").str(), EC,
                           llvm::sys::fs::OF_None);
  if (!EC) {
    Out.os() << Text;
    Out.os().close();
    if (!Out.os().has_error())
      EC = llvm::sys::fs::rename(Path + ".bsc-format", Path);
    else
      EC = Out.os().error();
  }
  if (EC) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    Out.os().clear_error();
    return false;
  }
  Out.keep();
  return true;
}

int bsc::formatCommand(Compilation &C, const FormatCommandOptions &Opts,
                       llvm::raw_ostream &OS) {
  if (Opts.InPlace && Opts.Check) {
    C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << "-i" << "--check";
    return finishCompilation(C);
  }
  if (Opts.Files.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    return finishCompilation(C);
  }
  bool WouldChange = false;
  for (const std::string &Path : Opts.Files) {
    unsigned ID = addSourceFile(C, Path);
    if (!ID)
      continue;
    auto F = format::formatBuffer(C.SM, ID, C.Diags);
    if (!F)
      return finishWithInternalError(C, F.takeError());
    if (!*F)
      continue;
    llvm::StringRef Before = C.SM.getMemoryBuffer(ID)->getBuffer();
    bool Changes = Before != (*F)->Text;
    if (Opts.Check) {
      if (Changes)
        OS << Path << "\n";
      WouldChange |= Changes;
    } else if (Opts.InPlace) {
      if (Changes)
        rewriteFile(C, Path, (*F)->Text);
    } else {
      OS << (*F)->Text;
    }
  }
  OS.flush();
  int Status = finishCompilation(C);
  return Status ? Status : WouldChange;
}

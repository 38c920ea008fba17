//===- FormatFiles.cpp - `bsc format`: files in the canonical layout ------===//
//
// Reads each file as the compiler does (so a missing file or a directory
// is the usual error), or standard input for `-`, formats it with
// lib/Format and prints, rewrites or checks it. A file is rewritten only when it changes, through a temporary
// file renamed over it, so that an interrupted run never leaves half a file.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/Format/Format.h"
#include "llvm/ADT/STLExtras.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
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

/// `-`: standard input, read whole as `<stdin>` (an editor's buffer piped
/// through `bsc format -`). 0 after reporting.
static unsigned addStandardInput(Compilation &C) {
  auto BufOrErr = llvm::MemoryBuffer::getSTDIN();
  if (!BufOrErr) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_open_file)
        << "-" << BufOrErr.getError().message();
    return 0;
  }
  return C.SM.AddNewSourceBuffer(
      llvm::MemoryBuffer::getMemBufferCopy((*BufOrErr)->getBuffer(),
                                           "<stdin>"),
      llvm::SMLoc());
}

int bsc::formatCommand(Compilation &C, const FormatCommandOptions &Opts,
                       llvm::raw_ostream &OS) {
  // --check tells "needs formatting" (1) from an error (2).
  auto Finish = [&] {
    int Status = finishCompilation(C);
    return Status && Opts.Check ? 2 : Status;
  };
  if (Opts.InPlace && Opts.Check) {
    C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << "-i" << "--check";
    return Finish();
  }
  if (Opts.Files.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    return Finish();
  }
  if (llvm::count(Opts.Files, "-") > 1 ||
      (Opts.InPlace && llvm::is_contained(Opts.Files, "-"))) {
    C.Diags.report(llvm::SMLoc(), diag::err_format_stdin)
        << (Opts.InPlace ? "-i cannot rewrite it" : "it can be read once");
    return Finish();
  }
  bool WouldChange = false;
  for (const std::string &Given : Opts.Files) {
    bool Stdin = Given == "-";
    unsigned ID = Stdin ? addStandardInput(C) : addSourceFile(C, Given);
    llvm::StringRef Path = Stdin ? "<stdin>" : llvm::StringRef(Given);
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
  int Status = Finish();
  return Status ? Status : WouldChange;
}

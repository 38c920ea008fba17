//===- Output.h - files bsc writes ------------------------------*- C++ -*-===//
//
// Every file bsc writes (objects, headers, recordings, coverage, JUnit,
// pages) is opened here, so that a file that cannot be written is one
// diagnostic, worded the same everywhere.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_OUTPUT_H
#define BSC_BASIC_OUTPUT_H

#include "bsc/Basic/Diagnostic.h"
#include "llvm/Support/ToolOutputFile.h"
#include <memory>

namespace bsc {

/// Opens `Path` for writing ("-" is stdout); reports failure
/// (err_cannot_write_output) and returns null. The file is removed again
/// unless the caller keeps it (ToolOutputFile::keep).
std::unique_ptr<llvm::ToolOutputFile>
openOutput(DiagnosticEngine &Diags, llvm::StringRef Path, bool Text);

/// Closes what openOutput opened at `Path` and keeps it; false after
/// reporting a write that failed (a full disk), and the file is removed.
bool keepOutput(DiagnosticEngine &Diags, llvm::ToolOutputFile &Out,
                llvm::StringRef Path);

} // namespace bsc

#endif

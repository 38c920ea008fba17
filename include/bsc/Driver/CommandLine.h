//===- CommandLine.h - checking bsc's words before llvm::cl -----*- C++ -*-===//
//
// llvm::cl takes an unknown `--check` for the one-letter options
// `-c -h -e -c -k` grouped, prints the help at `-h` and exits 0, and lets
// a subcommand fall back to the top level's options (`bsc run -c` would be
// silently ignored). These checks run around its parsing so that each of
// those is a `bsc: error:` with exit status 1, with a "did you mean" for a
// misspelt option. They take the tool's registered options, whatever they
// are.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DRIVER_COMMANDLINE_H
#define BSC_DRIVER_COMMANDLINE_H

#include "bsc/Basic/Diagnostic.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/Support/CommandLine.h"

namespace bsc {

/// Checks the words of the command line before llvm::cl parses them: a word
/// in the subcommand's place that is neither a subcommand nor a file, and an
/// option no subcommand has, are errors (with the nearest option of
/// `Category`, the tool's own, as a note). Reports and returns false.
bool checkCommandLine(DiagnosticEngine &Diags,
                      llvm::ArrayRef<const char *> Args,
                      llvm::cl::OptionCategory &Category);

/// Reports options of plain compilation given to subcommand `Sub` (after
/// parsing). Returns false if there was one.
bool checkSubcommandOptions(DiagnosticEngine &Diags, llvm::cl::SubCommand &Sub);

} // namespace bsc

#endif

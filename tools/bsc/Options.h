//===- Options.h - bsc's command line --------------------------*- C++ -*-===//
//
// What bsc.cpp needs of the options Options.cpp defines: the category and
// subcommands (for the checks around llvm::cl's parsing), and after
// parsing, every value in the option structs of the libraries.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_TOOLS_BSC_OPTIONS_H
#define BSC_TOOLS_BSC_OPTIONS_H

#include "bsc/Debug/TraceDecode.h"
#include "bsc/Driver/Driver.h"
#include "bsc/Timeline/Timeline.h"
#include "llvm/Support/CommandLine.h"
#include <string>
#include <vector>

namespace bsc::tool {

/// bsc's own options (those of LLVM's libraries are hidden).
extern llvm::cl::OptionCategory BscCategory;
extern llvm::cl::SubCommand RunCmd, ReplCmd, TraceDecodeCmd, TimelineCmd,
    FormatCmd, LspCmd, DapCmd, ReplayCmd, ConvertCmd, VerifyCmd;

/// The command line after parsing.
struct CommandLine {
  FrontendOptions Frontend; ///< Without the target and standard modules.
  std::string TargetName;   ///< -target; empty: the host.
  std::string RuntimeDir;   ///< --runtime-dir.
  std::vector<std::string> Warnings; ///< The -W options, without `-W`.
  bool DumpBindings = false;
  CompileOptions Compile;
  RunCommandOptions Run;
  ReplCommandOptions Repl;
  debug::TraceDecodeOptions TraceDecode;
  timeline::TimelineOptions Timeline;
  FormatCommandOptions Format;
  ReplayCommandOptions Replay;
  ConvertCommandOptions Convert;
  VerifyCommandOptions Verify;
};

CommandLine readCommandLine();

/// --verify: the diagnostics are checked rather than printed. Read before
/// parsing too (false then), when the checks of the words fail.
bool verifyGiven();

/// --runtime-dir, for the version printer, which llvm::cl calls while it
/// parses.
std::string getRuntimeDir();

} // namespace bsc::tool

#endif

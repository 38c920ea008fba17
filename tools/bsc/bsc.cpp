//===- bsc.cpp - the b-script compiler driver -----------------------------===//
//
// Dispatches each command to the library that does it, as clang's driver
// does; the options are in Options.cpp, the work in lib/Driver (Driver.h)
// lib/Debug and lib/Timeline:
//
//   bsc [options] FILE.bs...          compile (Driver.h's compile): a
//                                     program, -c, -S, --emit-header, or a
//                                     stage with --emit=tokens|ast|llvm|...
//   bsc run [options] FILE.bs...      JIT on the host, N cycles of the entry
//   bsc repl [options] FILE.bs...     the debugger
//   bsc replay --logs DIR FILE.bs...  every recording under DIR replayed
//   bsc trace-decode --object B.o LOG a robot's trace log
//   bsc timeline REC [REC2] -o P.html a run drawn (lib/Timeline)
//   bsc format [-i|--check] FILE.bs... the canonical layout (lib/Format)
//   bsc lsp                           the language server (lib/LSP)
//
// Everything the user can get wrong on the command line (a bad option value,
// a missing entry, an unknown target, an unwritable output, a missing
// linker or runtime) becomes a `bsc: error: ...` diagnostic and exit 1.
//
//===----------------------------------------------------------------------===//
#include "Options.h"
#include "bsc/Driver/CommandLine.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;
using namespace bsc::tool;
namespace cl = llvm::cl;

namespace {
/// Prints the diagnostics (or verifies them) and returns the exit status.
int finish(Compilation &C) { return finishCompilation(C, verifyGiven()); }

/// The path bsc was started as, for the version printer (which cl calls
/// without arguments).
const char *Argv0ForVersion = "bsc";

void printBscVersion(llvm::raw_ostream &OS) {
  printVersion(OS, {BSC_VERSION, BSC_LLVM_VERSION, getRuntimeDir(),
                    Argv0ForVersion});
}

/// The command after the command line is parsed and -W applied.
int dispatch(Compilation &C, CommandLine &CL, const char *Argv0) {
  // `run` and `repl` are for the host's JIT, whatever -target says.
  ToolChain TC = getToolChain(RunCmd || ReplCmd || ReplayCmd || TimelineCmd ||
                                      ConvertCmd
                                  ? ""
                                  : CL.TargetName,
                              CL.RuntimeDir, Argv0);
  FrontendOptions &Opts = CL.Frontend;
  Opts.Target = TC.getTriple();
  addStandardModules(TC, Opts);

  if (CL.DumpBindings) {
    if (readBindingObjects(C, Opts))
      bind::dumpBindings(C.Bindings, llvm::outs());
    return finish(C);
  }
  if (RunCmd)
    return checkSubcommandOptions(C.Diags, RunCmd)
               ? runCommand(C, Opts, CL.Run)
               : finish(C);
  if (ReplCmd)
    return checkSubcommandOptions(C.Diags, ReplCmd)
               ? replCommand(C, Opts, CL.Repl)
               : finish(C);
  if (TimelineCmd)
    return checkSubcommandOptions(C.Diags, TimelineCmd)
               ? timelineCommand(C, Opts, CL.Timeline)
               : finish(C);
  if (ReplayCmd)
    return checkSubcommandOptions(C.Diags, ReplayCmd)
               ? replayCommand(C, Opts, CL.Replay)
               : finish(C);
  if (ConvertCmd)
    return checkSubcommandOptions(C.Diags, ConvertCmd)
               ? convertCommand(C, Opts, CL.Convert)
               : finish(C);
  if (LspCmd)
    return checkSubcommandOptions(C.Diags, LspCmd)
               ? lspCommand(CL.RuntimeDir, Argv0)
               : finish(C);
  if (FormatCmd)
    return checkSubcommandOptions(C.Diags, FormatCmd)
               ? formatCommand(C, CL.Format, llvm::outs())
               : finish(C);
  if (TraceDecodeCmd) {
    debug::decodeTraceLog(CL.TraceDecode, C.Diags, llvm::outs());
    return finish(C);
  }
  return compile(C, Opts, CL.Compile, TC);
}
} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM X(argc, argv);
  for (cl::SubCommand *Sub :
       {&cl::SubCommand::getTopLevel(), &RunCmd, &TraceDecodeCmd, &ReplCmd,
        &TimelineCmd, &FormatCmd, &LspCmd, &ReplayCmd, &ConvertCmd})
    cl::HideUnrelatedOptions(BscCategory, *Sub);
  Argv0ForVersion = argv[0];
  cl::SetVersionPrinter(printBscVersion);
  Compilation C;
  if (!checkCommandLine(C.Diags, llvm::ArrayRef(argv, argc), BscCategory))
    return finish(C);
  cl::ParseCommandLineOptions(argc, argv,
                              "bsc: the b-script compiler for robot behaviors\n");
  CommandLine CL = readCommandLine();
  if (!applyWarningOptions(C.Diags, CL.Warnings))
    return finish(C);
  return dispatch(C, CL, argv[0]);
}

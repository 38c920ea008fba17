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
//   bsc dap                           the debug adapter (lib/DAP)
//   bsc verify --cycles N FILE.bs...  assertions for every input (lib/Verify)
//   bsc convert FROM -o TO            a recording in the other format
//
// Every subcommand is a row of one table (Subcommands below).
//
// Everything the user can get wrong on the command line (a bad option value,
// a missing entry, an unknown target, an unwritable output, a missing
// linker or runtime) becomes a `bsc: error: ...` diagnostic and exit 1.
//
//===----------------------------------------------------------------------===//
#include "Options.h"
#include "bsc/Driver/CommandLine.h"
#include "bsc/Run/Run.h"
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

/// A subcommand: its options' subcommand, whether it runs on the host
/// whatever -target says (the JIT's commands), and what it runs.
struct Subcommand {
  cl::SubCommand *Cmd;
  bool OnHost;
  int (*Run)(Compilation &C, CommandLine &CL, const char *Argv0);
};

/// Every subcommand: dispatch, the check of their options and the hiding of
/// the others' in `--help` go through this table. Without one, bsc
/// compiles (Driver.h's compile).
const Subcommand Subcommands[] = {
    {&RunCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return runCommand(C, CL.Frontend, CL.Run);
     }},
    {&ReplCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return replCommand(C, CL.Frontend, CL.Repl);
     }},
    {&ReplayCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return replayCommand(C, CL.Frontend, CL.Replay);
     }},
    {&TimelineCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return timelineCommand(C, CL.Frontend, CL.Timeline);
     }},
    {&ConvertCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return convertCommand(C, CL.Frontend, CL.Convert);
     }},
    {&TraceDecodeCmd, false,
     [](Compilation &C, CommandLine &CL, const char *) {
       CL.TraceDecode.ReadFlightLog = readFlightLogTraces;
       debug::decodeTraceLog(CL.TraceDecode, C.Diags, llvm::outs());
       return finish(C);
     }},
    {&FormatCmd, false,
     [](Compilation &C, CommandLine &CL, const char *) {
       return formatCommand(C, CL.Format, llvm::outs());
     }},
    {&LspCmd, false,
     [](Compilation &, CommandLine &CL, const char *Argv0) {
       return lspCommand(CL.RuntimeDir, Argv0);
     }},
    {&VerifyCmd, true,
     [](Compilation &C, CommandLine &CL, const char *) {
       return verifyCommand(C, CL.Frontend, CL.Verify);
     }},
    {&DapCmd, true,
     [](Compilation &, CommandLine &CL, const char *Argv0) {
       return dapCommand(CL.RuntimeDir, Argv0);
     }},
};

/// The command after the command line is parsed and -W applied.
int dispatch(Compilation &C, CommandLine &CL, const char *Argv0) {
  const Subcommand *Sub = nullptr;
  for (const Subcommand &S : Subcommands)
    if (*S.Cmd)
      Sub = &S;
  ToolChain TC = getToolChain(Sub && Sub->OnHost ? "" : CL.TargetName,
                              CL.RuntimeDir, Argv0);
  FrontendOptions &Opts = CL.Frontend;
  Opts.Target = TC.getTriple();
  addStandardModules(TC, Opts);

  if (CL.DumpBindings) {
    if (readBindingObjects(C, Opts))
      bind::dumpBindings(C.Bindings, llvm::outs());
    return finish(C);
  }
  if (!Sub)
    return compile(C, Opts, CL.Compile, TC);
  if (!checkSubcommandOptions(C.Diags, *Sub->Cmd))
    return finish(C);
  return Sub->Run(C, CL, Argv0);
}
} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM X(argc, argv);
  cl::HideUnrelatedOptions(BscCategory, cl::SubCommand::getTopLevel());
  for (const Subcommand &Sub : Subcommands)
    cl::HideUnrelatedOptions(BscCategory, *Sub.Cmd);
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

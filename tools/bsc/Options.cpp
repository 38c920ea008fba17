//===- Options.cpp - bsc's command line -----------------------------------===//
//
// Every option of bsc, its subcommands' included: the tool's interface,
// defined with llvm::cl as LLVM's tools do, and read after parsing into the
// option structs of lib/Driver and lib/Debug (readCommandLine). Values
// are copied as the user wrote them: what a valid one is, is the
// library's policy (Driver.h), so that every mistake is a `bsc: error:`.
//
//===----------------------------------------------------------------------===//
#include "Options.h"
#include "llvm/Support/CommandLine.h"

using namespace bsc;
using namespace bsc::tool;
namespace cl = llvm::cl;

cl::OptionCategory tool::BscCategory("bsc options");
cl::SubCommand tool::RunCmd("run", "Run a behavior on the host in a JIT, one call "
                             "of the entry per cycle");
cl::SubCommand tool::ReplCmd("repl", "Debug a behavior in a JIT: step cycles, look "
                               "at tasks, evaluate b-script between cycles");
cl::SubCommand tool::TraceDecodeCmd(
    "trace-decode",
    "Print a robot's trace log as `bsc run --trace` does, with the tables of "
    "an object compiled with --instrument");
cl::SubCommand tool::TimelineCmd(
    "timeline",
    "Draw a recorded run, or two to compare, as one self-contained HTML page");
cl::SubCommand tool::ReplayCmd(
    "replay", "Replay every recording under a folder against a behavior, "
              "compiled once; a log passes when every recorded output matches");
cl::SubCommand tool::ConvertCmd(
    "convert", "Write a recording (JSON lines) as a binary log (.bslog), or a "
               "binary log as JSON lines, with the behavior's layout");
cl::SubCommand tool::LspCmd(
    "lsp", "Serve editors: a Language Server Protocol server on standard "
           "input and output (docs/editors.md)");
cl::SubCommand tool::DapCmd(
    "dap", "Debug in editors: a Debug Adapter Protocol server on standard "
           "input and output, over the REPL's session (docs/editors.md)");
cl::SubCommand tool::VerifyCmd(
    "verify", "Check the behavior's assertions for every input sequence of N "
              "cycles that its assumptions allow, with Z3 (docs/verify.md)");
cl::SubCommand tool::FormatCmd(
    "format", "Print b-script files in the one canonical layout, or rewrite "
              "them (-i), or name those that would change (--check)");


namespace {
/// Where each option is: the compiler (the top level), `bsc run`,
/// `bsc repl`, `bsc trace-decode`, or several; all are bsc's own.
#define BSC_TOP cl::cat(BscCategory)
#define BSC_RUN BSC_TOP, cl::sub(RunCmd)
#define BSC_REPL BSC_TOP, cl::sub(ReplCmd)
#define BSC_JIT BSC_RUN, cl::sub(ReplCmd)
#define BSC_DECODE BSC_TOP, cl::sub(TraceDecodeCmd)
#define BSC_TIMELINE BSC_TOP, cl::sub(TimelineCmd)
#define BSC_FORMAT BSC_TOP, cl::sub(FormatCmd)
/// Options shared by the compiler and `bsc run` are in both subcommands...
#define BSC_BOTH                                                               \
  BSC_TOP, cl::sub(cl::SubCommand::getTopLevel()), cl::sub(RunCmd)
/// ...and those the REPL takes too.
#define BSC_ALL BSC_BOTH, cl::sub(ReplCmd), cl::sub(ReplayCmd)
#define BSC_REPLAY BSC_TOP, cl::sub(ReplayCmd)

cl::list<std::string> InputFiles(cl::Positional, cl::desc("<file.bs>..."),
                                 BSC_ALL, cl::sub(VerifyCmd));
cl::list<std::string>
    IncludeDirs("I", cl::Prefix, cl::desc("Search folder for required modules"),
                cl::value_desc("dir"), BSC_ALL, cl::sub(TimelineCmd),
                cl::sub(ConvertCmd), cl::sub(VerifyCmd));
cl::opt<std::string>
    EntryName("entry",
              cl::desc("The task or func called once per cycle (default: "
                       "'main' of the first file's module)"),
              cl::value_desc("Module::name"), cl::init("main"), BSC_ALL,
              cl::sub(TimelineCmd), cl::sub(ConvertCmd), cl::sub(VerifyCmd));
cl::list<std::string> ExportNames(
    "export",
    cl::desc("Export these funcs and tasks as the object's entries (default: "
             "the behavior's roots, which nothing in it calls); the rest "
             "is internal"),
    cl::value_desc("Module::name,..."), cl::CommaSeparated, BSC_TOP);
cl::opt<std::string> CyclesArg("cycles",
                               cl::desc("Execution cycles to run (default 1)"),
                               cl::value_desc("N"), cl::init("1"), BSC_BOTH,
                               cl::sub(VerifyCmd));
cl::list<std::string> ModelFiles(
    "model",
    cl::desc("A b-script module whose funcs stand for registered C++ "
             "(`Math_abs` for Math::abs; repeatable; docs/verify.md)"),
    cl::value_desc("file.bs"), cl::sub(VerifyCmd));
cl::opt<std::string> SolverTimeoutArg(
    "solver-timeout",
    cl::desc("Seconds one question to the solver may take (default 600); "
             "one that takes longer makes the result not fully explored"),
    cl::value_desc("S"), cl::sub(VerifyCmd));
cl::opt<std::string> LoopLimitArg(
    "loop-limit",
    cl::desc("Passes of a loop the verifier follows in one cycle (default "
             "16); a loop that can run more is not fully explored"),
    cl::value_desc("N"), cl::sub(VerifyCmd));
cl::opt<std::string>
    OptLevelArg("O", cl::Prefix,
                cl::desc("Optimisation level 0..3 (default 0)"),
                cl::value_desc("level"), cl::init("0"), BSC_ALL);

cl::opt<std::string>
    RecordFile("record",
               cl::desc("Write each cycle's input and output as one JSON line"),
               cl::value_desc("file.jsonl"), BSC_RUN);
cl::opt<std::string> ReplayFile(
    "replay",
    cl::desc("Feed each cycle's input from a JSON-lines file and compare "
             "the outputs it records"),
    cl::value_desc("file.jsonl"), BSC_RUN);
// A string, not an enum: llvm::cl's own message for a bad value is not a
// `bsc: error:` (parseTraceMode reports it).
cl::opt<std::string> TraceArg(
    "trace", cl::ValueOptional,
    cl::desc("Print the active task hierarchy after each cycle; with "
             "'=changes', only the cycles where it, a task's state or a "
             "line changed"),
    cl::value_desc("changes"), BSC_RUN);
cl::opt<bool> PrintOutputFlag("print-output",
                              cl::desc("Print the output after each cycle "
                                       "as JSON"),
                              BSC_RUN);
cl::opt<std::string> CycleLimitArg(
    "cycle-limit",
    cl::desc("Stop a cycle that runs longer than this (milliseconds; "
             "default 3000, 0: no limit)"),
    cl::value_desc("ms"), cl::init("3000"), BSC_JIT, cl::sub(ReplayCmd));
cl::opt<std::string> WorldLibrary(
    "world",
    cl::desc("A shared library that feeds input and reads output around "
             "every cycle (bs_world_init/begin/end/exit, docs/repl.md); "
             "with a replay only its init and exit run"),
    cl::value_desc("lib.so"), BSC_JIT, cl::sub(ReplayCmd));
cl::list<std::string> IgnoreFields(
    "ignore",
    cl::desc("A replay does not compare this output member, or any member "
             "under it (output.walkTarget, or walkTarget); repeatable"),
    cl::value_desc("member"), BSC_RUN, cl::sub(ReplayCmd));
cl::list<std::string> Tolerances(
    "tolerance",
    cl::desc("A replay takes this float output member (or any under it) as "
             "equal when it differs by at most ABS; repeatable"),
    cl::value_desc("member=abs"), BSC_RUN, cl::sub(ReplayCmd));
cl::opt<bool> UpdateFlag(
    "update",
    cl::desc("Record each log again with this behavior's outputs on its own "
             "inputs (open loop), and say what changed"),
    cl::sub(ReplayCmd));
cl::opt<std::string> FindArg(
    "find",
    cl::desc("Ask this condition (a line of b-script of type bool, as the "
             "REPL takes it: task fields, input, output; or a task's name: "
             "it ran) after every cycle of every log: the stretches of "
             "cycles in which it holds, with the values of its parts"),
    cl::value_desc("expr"), cl::sub(ReplayCmd));
cl::opt<std::string> LastingArg(
    "lasting",
    cl::desc("With --find: only stretches of at least N consecutive cycles "
             "count"),
    cl::value_desc("N"), cl::sub(ReplayCmd));
cl::opt<bool> FindFirstFlag(
    "first",
    cl::desc("With --find: replay each log only up to the first cycle the "
             "condition holds in"),
    cl::sub(ReplayCmd));
cl::opt<bool> RegressionFlag(
    "regression",
    cl::desc("Replay in regression mode: inputs from the recording, "
             "registered C++ called for real, even when the recording is "
             "of this very behavior (docs/repl.md, \"Recordings\")"),
    BSC_RUN, cl::sub(ReplayCmd));
cl::opt<std::string> WorldOutput(
    "world-output",
    cl::desc("Write what the --world library and registered C++ print "
             "during cycles to this file instead of standard output"),
    cl::value_desc("file"), BSC_JIT);
cl::opt<std::string> RobotsArg(
    "robots",
    cl::desc("Run a team: N states of the behavior in one process, each "
             "with its own input, output and user pointer, stepped in "
             "index order each cycle (default 1)"),
    cl::value_desc("N"), BSC_JIT);
cl::opt<std::string> BatchFile(
    "batch",
    cl::desc("Read the REPL's lines from this file, without a prompt (also "
             "when standard input is not a terminal)"),
    cl::value_desc("file"), BSC_REPL);

cl::opt<std::string>
    RuntimeDirArg("runtime-dir",
                  cl::desc("The folder holding the runtime libraries (default: "
                           "$BSCRIPT_RUNTIME_DIR, else ../lib/bscript or "
                           "../lib beside bsc's folder)"),
                  cl::value_desc("dir"), BSC_ALL);
cl::opt<bool> DepFileFlag(
    "MD",
    cl::desc("Also write a make-style dependency file: the output "
             "depends on every module file read and every --bind object"),
    BSC_TOP);
cl::opt<std::string> DepFilePath(
    "MF",
    cl::desc("The dependency file's name (default: the output's, with "
             "'.d')"),
    cl::value_desc("file"), BSC_TOP);
cl::opt<bool> InstrumentFlag(
    "instrument",
    cl::desc("Make every task call write the state's trace record, and embed "
             "the debugger's tables (task names, yield lines) in the object, "
             "for `bsc trace-decode` of robot trace logs"),
    BSC_TOP);
cl::opt<bool> FlightRecorderFlag(
    "flight-recorder",
    cl::desc("Log every cycle's input changes and the effects of calls "
             "into registered C++ into the robot's flight recorder "
             "(bscript/flight.h; a program bsc links writes the file "
             "$BS_FLIGHT_LOG names), so that `bsc run --replay`, the REPL, "
             "`bsc replay` and `bsc timeline` replay the robot's game "
             "exactly"),
    BSC_TOP);
cl::opt<std::string> AssertionsArg(
    "assertions",
    cl::desc("What `assert` compiles to in objects and programs: none (the "
             "default: left out), count (a counter per assertion in the "
             "state, bscript.h \"Assertions\") or trap (a failure stops "
             "the robot); `bsc run` and the REPL always check them"),
    cl::value_desc("none|count|trap"), BSC_TOP);
cl::opt<std::string> CycleBudgetArg(
    "cycle-budget",
    cl::desc("Give each cycle N loop passes: a task whose loop runs past them "
             "fails and the cycle returns; the state records the loop "
             "(bscript.h, \"Cycle budgets\")"),
    cl::value_desc("N"), BSC_BOTH, cl::sub(ReplCmd));
cl::opt<std::string>
    TraceObject("object", cl::desc("The object compiled with --instrument"),
                cl::value_desc("file.o"), BSC_DECODE, cl::Required);
cl::opt<std::string> TraceLog(cl::Positional, cl::desc("<trace log>"),
                              BSC_DECODE, cl::Required);
cl::list<std::string>
    TimelineRecords(cl::Positional,
                    cl::desc("<recording.jsonl> [<other.jsonl>]"),
                    BSC_TIMELINE);
cl::opt<std::string> TimelineObject(
    "object",
    cl::desc("The object compiled with --instrument whose tables name the "
             "tasks of robot trace logs (a record may also be a recording, "
             "to compare the robot's run with the JIT's)"),
    cl::value_desc("file.o"), BSC_TIMELINE);
cl::list<std::string> BehaviorFiles(
    "behavior",
    cl::desc("The behavior's files, whose layout of input and output binary "
             "logs (.bslog) are read with (the timeline replays them), with "
             "--bind and --entry as for `bsc run`"),
    cl::value_desc("file.bs,..."), cl::CommaSeparated, BSC_TIMELINE,
    cl::sub(ConvertCmd));
cl::opt<std::string> ConvertInput(cl::Positional,
                                  cl::desc("<recording.jsonl|log.bslog>"),
                                  cl::sub(ConvertCmd), cl::cat(BscCategory));
cl::opt<std::string> ConvertOutput(
    "o", cl::desc("The file to write: a binary log if it ends in '.bslog', "
                  "else JSON lines"),
    cl::value_desc("file"), cl::sub(ConvertCmd), cl::cat(BscCategory));
cl::opt<std::string> ShrinkLog(
    "shrink",
    cl::desc("Write the shortest recording that fails as this failing JSON "
             "recording does (-o, default: its name with '.shrunk.jsonl')"),
    cl::value_desc("log.jsonl"), cl::sub(ReplayCmd));
cl::opt<std::string> ShrinkOutput(
    "o", cl::desc("With --shrink: the recording to write"),
    cl::value_desc("file.jsonl"), cl::sub(ReplayCmd), cl::cat(BscCategory));
cl::opt<std::string> TimelineOutput(
    "o",
    cl::desc("The page to write (default: the first record's name with "
             "'.html')"),
    cl::value_desc("file.html"), BSC_TIMELINE);
cl::opt<std::string> CoverageFile(
    "coverage",
    cl::desc("Write what the run (or every replayed log) exercised as an "
             "lcov tracefile: line hits, both ways of each if and for "
             "condition, calls of each task and func"),
    cl::value_desc("file.info"), BSC_RUN, cl::sub(ReplayCmd));
cl::opt<std::string> CoverageFloor(
    "fail-under",
    cl::desc("Exit with status 1 if fewer than this percentage of the "
             "behavior's lines ran"),
    cl::value_desc("percent"), BSC_RUN, cl::sub(ReplayCmd));
cl::opt<std::string> ReplayLogs(
    "logs", cl::desc("The folder whose recordings (*.jsonl, also in its "
                     "subfolders) to replay"),
    cl::value_desc("dir"), BSC_REPLAY);
cl::opt<std::string> ReplayShard(
    "shard",
    cl::desc("Replay the K-th of N slices of the sorted logs (every N-th "
             "from the K-th), for a CI matrix or a cluster's array job"),
    cl::value_desc("K/N"), BSC_REPLAY);
cl::opt<std::string> ReplayJobs(
    "jobs",
    cl::desc("Replay in N worker processes (default: one per core; 1: in "
             "this process)"),
    cl::value_desc("N"), BSC_REPLAY);
cl::opt<std::string> ReplayJUnit(
    "junit", cl::desc("Write JUnit XML, one test case per log"),
    cl::value_desc("file.xml"), BSC_REPLAY);
cl::list<std::string> FormatFiles(cl::Positional, cl::desc("<file.bs>..."),
                                  BSC_FORMAT);
cl::opt<bool> FormatInPlace("i",
                            cl::desc("Rewrite each file that is not in the "
                                     "layout, instead of printing it"),
                            BSC_FORMAT);
cl::opt<bool> FormatCheck(
    "check",
    cl::desc("Print the name of each file that is not in the layout and exit "
             "with status 1 if there is one (for CI)"),
    BSC_FORMAT);
cl::opt<bool> TraceChangesFlag(
    "changes",
    cl::desc("Print only the cycles whose line differs from the cycle "
             "before's, as `bsc run --trace=changes`"),
    BSC_DECODE);

cl::opt<bool> SyntaxOnly("fsyntax-only",
                         cl::desc("Check the program; produce no output"),
                         BSC_TOP);
cl::opt<bool> Verify("verify",
                     cl::desc("Check diagnostics against the source's "
                              "'# expected-error {{...}}' comments"),
                     BSC_TOP);
cl::opt<EmitKind> Emit(
    "emit", cl::desc("Stop at a stage and print it"),
    cl::init(EmitKind::Default),
    cl::values(clEnumValN(EmitKind::Tokens, "tokens",
                          "the tokens of each file"),
               clEnumValN(EmitKind::AST, "ast", "the syntax tree (parse only)"),
               clEnumValN(EmitKind::TypedAST, "typed-ast",
                          "the syntax tree after semantic checks"),
               clEnumValN(EmitKind::Graph, "graph",
                          "the call graph of funcs and tasks (Graphviz DOT)"),
               clEnumValN(EmitKind::LLVM, "llvm", "the LLVM IR (after -O)"),
               clEnumValN(EmitKind::Asm, "asm", "the target's assembly"),
               clEnumValN(EmitKind::Obj, "obj", "the object file")),
    BSC_TOP);
cl::opt<bool> EmitLLVMFlag("emit-llvm", cl::desc("Same as --emit=llvm"),
                           BSC_TOP);
cl::opt<bool> CompileOnly("c",
                          cl::desc("Write an object file to embed "
                                   "(default name: <first file>.o)"),
                          BSC_TOP);
cl::opt<bool> AssembleOnly("S",
                           cl::desc("Write assembly (default name: "
                                    "<first file>.s)"),
                           BSC_TOP);
cl::opt<bool> EmitHeaderFlag(
    "emit-header",
    cl::desc("Write the typed C header of the behavior for the target"),
    BSC_TOP);
cl::opt<std::string> OutputFile("o", cl::desc("Output file ('-' for stdout)"),
                                cl::value_desc("file"), BSC_TOP,
                                cl::sub(cl::SubCommand::getTopLevel()),
                                cl::sub(VerifyCmd));
cl::opt<std::string>
    TargetArg("target",
              cl::desc("i586 (the robot: Geode, PIC, ELF32), x86_64, or any "
                       "LLVM triple (default: the host; programs only for "
                       "the host and i586)"),
              cl::value_desc("target"), BSC_TOP);
cl::opt<std::string>
    CPUArg("mcpu",
           cl::desc("Target CPU (default: geode for i586, x86-64 for x86_64, "
                    "else generic or the target's oldest)"),
           cl::value_desc("cpu"), BSC_TOP);
cl::opt<std::string> BehaviorNameArg(
    "behavior-name",
    cl::desc("Prefix of the exported symbols (default: the first file's "
             "module name)"),
    cl::value_desc("name"), BSC_TOP);
cl::list<std::string>
    BindObjects("bind",
                cl::desc("A binding object, archive or shared library "
                         "registering C++ for the scripts (repeatable; read "
                         "for -target)"),
                cl::value_desc("obj"), BSC_ALL, cl::sub(TimelineCmd),
                cl::sub(ConvertCmd), cl::sub(VerifyCmd));
cl::opt<bool> DumpBindings("dump-bindings",
                           cl::desc("Print what the standard modules and the "
                                    "--bind objects register, and exit"),
                           BSC_TOP);
/// -W's help, from the diagnostics' table of warning groups. Defined before
/// WarningOptions, whose description refers to it.
const std::string WarningHelp =
    "-Wno-<group>: silence a group of warnings; -Werror: warnings are "
    "errors; -Werror=<group>: that group's are (groups: " +
    DiagnosticEngine::getWarningGroupList() + ")";
cl::list<std::string> WarningOptions("W", cl::Prefix, cl::desc(WarningHelp),
                                     cl::value_desc("no-group|error[=group]"),
                                     BSC_BOTH);
cl::opt<bool> DebugInfo("g",
                        cl::desc("Emit DWARF debug information (for `run` "
                                 "and `repl`: register the JIT's code with "
                                 "gdb)"),
                        BSC_ALL);

/// A given option's value; std::nullopt when it is not on the command line.
std::optional<std::string> given(const cl::opt<std::string> &O) {
  if (O.getNumOccurrences() == 0)
    return std::nullopt;
  return O.getValue();
}

BackendArgs getBackendArgs() {
  return {TargetArg, CPUArg, OptLevelArg, CyclesArg};
}

CompileOptions getCompileOptions() {
  CompileOptions Opts;
  Opts.Backend = getBackendArgs();
  Opts.Modes = {SyntaxOnly,     Verify,       CompileOnly, AssembleOnly,
                EmitHeaderFlag, EmitLLVMFlag, Emit};
  Opts.OutputFile = OutputFile;
  Opts.Exports.assign(ExportNames.begin(), ExportNames.end());
  Opts.EntryName = EntryName;
  Opts.BehaviorName = BehaviorNameArg;
  Opts.CycleBudget = given(CycleBudgetArg);
  Opts.Assertions = given(AssertionsArg);
  Opts.DebugInfo = DebugInfo;
  Opts.Instrument = InstrumentFlag;
  Opts.FlightRecorder = FlightRecorderFlag;
  Opts.DepFile = {DepFileFlag, DepFilePath};
  return Opts;
}

RunCommandOptions getRunOptions() {
  RunCommandOptions Opts;
  Opts.Backend = getBackendArgs();
  Opts.CyclesGiven = CyclesArg.getNumOccurrences() != 0;
  Opts.EntryName = EntryName;
  Opts.RecordPath = RecordFile;
  Opts.ReplayPath = ReplayFile;
  Opts.CycleLimit = CycleLimitArg;
  Opts.Trace = given(TraceArg);
  Opts.CycleBudget = given(CycleBudgetArg);
  Opts.PrintOutput = PrintOutputFlag;
  Opts.DebugInfo = DebugInfo;
  Opts.WorldLibrary = WorldLibrary;
  Opts.WorldOutput = WorldOutput;
  Opts.Robots = given(RobotsArg);
  Opts.Coverage = {CoverageFile, CoverageFloor};
  Opts.Regression = RegressionFlag;
  Opts.Compare = {{IgnoreFields.begin(), IgnoreFields.end()},
                  {Tolerances.begin(), Tolerances.end()}};
  return Opts;
}

ReplayCommandOptions getReplayOptions() {
  ReplayCommandOptions Opts;
  Opts.Backend = getBackendArgs();
  Opts.EntryName = EntryName;
  Opts.LogsDir = ReplayLogs;
  Opts.Shard = ReplayShard;
  Opts.JUnitPath = ReplayJUnit;
  Opts.CycleLimit = CycleLimitArg;
  Opts.DebugInfo = DebugInfo;
  Opts.Coverage = {CoverageFile, CoverageFloor};
  Opts.Jobs = ReplayJobs;
  Opts.WorldLibrary = WorldLibrary;
  Opts.Regression = RegressionFlag;
  Opts.Compare = {{IgnoreFields.begin(), IgnoreFields.end()},
                  {Tolerances.begin(), Tolerances.end()}};
  Opts.Update = UpdateFlag;
  Opts.Find = given(FindArg);
  Opts.Lasting = LastingArg;
  Opts.Shrink = ShrinkLog;
  Opts.ShrinkOutput = ShrinkOutput;
  Opts.FindFirst = FindFirstFlag;
  return Opts;
}

ReplCommandOptions getReplOptions() {
  ReplCommandOptions Opts;
  Opts.Backend = getBackendArgs();
  Opts.EntryName = EntryName;
  Opts.CycleLimit = CycleLimitArg;
  Opts.BatchFile = BatchFile;
  Opts.WorldLibrary = WorldLibrary;
  Opts.WorldOutput = WorldOutput;
  Opts.Robots = given(RobotsArg);
  Opts.CycleBudget = given(CycleBudgetArg);
  Opts.DebugInfo = DebugInfo;
  return Opts;
}
} // namespace

bool tool::verifyGiven() { return Verify; }

std::string tool::getRuntimeDir() { return RuntimeDirArg; }

tool::CommandLine tool::readCommandLine() {
  CommandLine CL;
  FrontendOptions &F = CL.Frontend;
  F.Inputs.assign(InputFiles.begin(), InputFiles.end());
  F.IncludeDirs.assign(IncludeDirs.begin(), IncludeDirs.end());
  F.BindObjects.assign(BindObjects.begin(), BindObjects.end());
  CL.TargetName = TargetArg;
  CL.RuntimeDir = RuntimeDirArg;
  CL.Warnings.assign(WarningOptions.begin(), WarningOptions.end());
  CL.DumpBindings = DumpBindings;
  CL.Compile = getCompileOptions();
  CL.Run = getRunOptions();
  CL.Repl = getReplOptions();
  CL.Verify.EntryName = EntryName;
  CL.Verify.Cycles =
      CyclesArg.getNumOccurrences() ? std::optional<std::string>(CyclesArg)
                                    : std::nullopt;
  CL.Verify.CounterexamplePath = OutputFile;
  F.Models.assign(ModelFiles.begin(), ModelFiles.end());
  if (LoopLimitArg.getNumOccurrences())
    CL.Verify.LoopLimit = LoopLimitArg;
  if (SolverTimeoutArg.getNumOccurrences())
    CL.Verify.SolverTimeout = SolverTimeoutArg;
  CL.TraceDecode.ObjectPath = TraceObject;
  CL.TraceDecode.LogPath = TraceLog;
  CL.TraceDecode.OnlyChanges = TraceChangesFlag;
  CL.Timeline = {{TimelineRecords.begin(), TimelineRecords.end()},
                 TimelineObject,
                 TimelineOutput,
                 {BehaviorFiles.begin(), BehaviorFiles.end()},
                 EntryName,
                 {}};
  CL.Replay = getReplayOptions();
  CL.Convert = {ConvertInput, ConvertOutput,
                {BehaviorFiles.begin(), BehaviorFiles.end()}, EntryName};
  CL.Format = {{FormatFiles.begin(), FormatFiles.end()},
               FormatInPlace,
               FormatCheck};
  return CL;
}

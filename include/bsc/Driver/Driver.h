//===- Driver.h - what bsc's commands do -----------------------*- C++ -*-===//
//
// The work behind bsc's command line, as clang's Driver library is behind
// its thin `clang` tool: tools/bsc defines the options (llvm::cl, the
// tool's interface), copies them into the plain structs below and calls
// one entry function per command:
//
//   compile      the top-level command: a program, an object, assembly,
//                IR, the C header, or a front-end stage (--emit=tokens,
//                ast, typed-ast, graph: emitFrontendStage)
//   runCommand   `bsc run`
//   replCommand  `bsc repl`
//
// (`bsc trace-decode` is lib/Debug's decodeTraceLog.) Option values are
// checked here, not in the tool, because what a valid value is (an -O
// level, a cycle count, a warning group) is policy the tests pin; the
// structs hold them as the user wrote them, and each is checked where the
// command used to, so that the order of the messages is the driver's.
//
// Every entry reports into the Compilation's DiagnosticEngine; those that
// return an int print the diagnostics (finishCompilation) and return the
// exit status.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DRIVER_DRIVER_H
#define BSC_DRIVER_DRIVER_H

#include "bsc/Basic/Output.h"
#include "bsc/AST/Layout.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Debug/Trace.h"
#include "bsc/Driver/ToolChain.h"
#include "bsc/Frontend/Frontend.h"
#include "bsc/Timeline/Timeline.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/ToolOutputFile.h"
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace llvm {
class TargetMachine;
class raw_ostream;
} // namespace llvm

namespace bsc {

/// Limit of --cycles: a run of more than a day of 30 Hz cycles is a typo.
constexpr unsigned MaxCycles = 100000000;

/// Limit of --cycle-limit in milliseconds: a day. Anything longer is a
/// typo, and itimer values must stay small.
constexpr unsigned MaxCycleLimitMs = 86400000;

/// Prints the diagnostics of `C` (with `Verify`, checks them against the
/// sources' `# expected-...` comments instead) and returns the exit status.
int finishCompilation(Compilation &C, bool Verify = false);

/// finishCompilation, then an internal error (a bug in bsc, not in the
/// program: see Target.h); returns the exit status 1.
int finishWithInternalError(Compilation &C, llvm::Error E);

//===-- Option values ---------------------------------------------------===//

/// The options every back-end path needs, checked.
struct BackendOptions {
  TargetOptions Target;
  unsigned Cycles = 1;
};

/// -target, -mcpu, -O and --cycles as written.
struct BackendArgs {
  std::string Target, CPU, OptLevel = "0", Cycles = "1";
};

/// Checks -O and --cycles and resolves -target; reports and returns false
/// if one is bad.
bool parseBackendOptions(DiagnosticEngine &Diags, const BackendArgs &Args,
                         BackendOptions &Out);

/// Applies -Wno-<group>, -Werror and -Werror=<group> (each without its
/// `-W`); reports and returns false on one that names no group.
bool applyWarningOptions(DiagnosticEngine &Diags,
                         llvm::ArrayRef<std::string> Options);

/// Checks --assertions (none, count or trap; std::nullopt: none); false
/// after reporting another value.
bool parseAssertionMode(DiagnosticEngine &Diags,
                        const std::optional<std::string> &Arg,
                        AssertionMode &Mode);
/// Checks --cycle-budget (1 to 2^32 - 1 loop passes; std::nullopt, the
/// option not given, is 0: none). Reports and returns false if it is bad.
bool parseCycleBudget(DiagnosticEngine &Diags,
                      const std::optional<std::string> &Arg, uint32_t &Passes);

/// Checks `--trace[=changes|=TASK]` (std::nullopt: not given); a name
/// goes into `Task` (the runner checks it). Reports and returns false if
/// it is bad.
bool parseTraceMode(DiagnosticEngine &Diags,
                    const std::optional<std::string> &Arg,
                    debug::TraceMode &Mode, std::string &Task);

/// `--robots N` into N (1 if not given); false after reporting a value
/// that is not a number from 1 to MaxRobots.
bool parseRobots(DiagnosticEngine &Diags,
                 const std::optional<std::string> &Arg, unsigned &Robots);

/// Checks --cycle-limit; reports and returns false if it is bad.
bool parseCycleLimit(DiagnosticEngine &Diags, llvm::StringRef Arg,
                     unsigned &Ms);

/// The standard modules of `TC`'s target for the front end: its runtime
/// archive, or, for a target with a runtime that is not found, what was
/// looked for (reported when `io` is needed). Nothing for other targets.
void addStandardModules(const ToolChain &TC, FrontendOptions &Opts);

/// What `bsc --version` prints besides the tool's own versions.
struct VersionInfo {
  std::string BscVersion, LLVMVersion;
  /// --runtime-dir and argv[0], to find the runtimes as bsc does.
  std::string RuntimeDir;
  const char *Argv0 = "bsc";
};

/// `bsc --version`: bsc's and LLVM's versions, the default target, and the
/// runtimes bsc links programs with (and where it looked).
void printVersion(llvm::raw_ostream &OS, const VersionInfo &Info);

//===-- What the command line asks for ----------------------------------===//

/// `--emit=`: the places the pipeline can stop.
enum class EmitKind { Default, Tokens, AST, TypedAST, Graph, LLVM, Asm, Obj };

/// The options that choose the top-level command's output.
struct OutputModes {
  bool SyntaxOnly = false, Verify = false, CompileOnly = false,
       AssembleOnly = false, EmitHeader = false, EmitLLVM = false;
  EmitKind Emit = EmitKind::Default;
};

/// Reports options that ask for two different outputs (--verify with
/// -fsyntax-only is one).
bool checkOutputModes(DiagnosticEngine &Diags, const OutputModes &Modes);

/// `--emit=` with --emit-llvm folded in.
EmitKind getEmitKind(const OutputModes &Modes);

/// What the top-level command produces when it goes past the front end.
enum class OutputKind { LLVM, Asm, Obj, Header, Program };

/// The output of checked modes past the front end (-c, -S, --emit=...).
OutputKind getOutputKind(const OutputModes &Modes);

//===-- Commands --------------------------------------------------------===//

/// `--emit=tokens|ast|typed-ast|graph` (the graph to `OutputFile` or
/// stdout). Returns the exit status.
int emitFrontendStage(Compilation &C, const FrontendOptions &Opts,
                      EmitKind Stage, llvm::StringRef OutputFile);

/// -MD and -MF.
struct DepFileOptions {
  bool Enabled = false;
  /// -MF; empty: the output's name with `.d`.
  std::string Path;
};

/// The dependency file's name: Opts.Path, else `Output` with `.d`;
/// std::nullopt when that would be stdout's ("-").
std::optional<std::string> getDepFilePath(const DepFileOptions &Opts,
                                          llvm::StringRef Output);

/// Writes `Output: Inputs...` as make and Ninja read it, one input a line,
/// with spaces and `#` escaped by `\` and `$` as `$$`.
void writeDependencies(llvm::raw_ostream &OS, llvm::StringRef Output,
                       llvm::ArrayRef<std::string> Inputs);

/// -MD: writes the dependency file of `Output`, which depends on every
/// module file read and every binding object. Nothing without
/// Opts.Enabled; reports and returns false on failure.
bool writeDepFile(Compilation &C, const DepFileOptions &Opts,
                  llvm::StringRef Output,
                  llvm::ArrayRef<std::string> BindObjects);

/// For a 32-bit x86 target (the robot), reports each binding object that
/// holds instructions the target CPU lacks: it would die of SIGILL there.
bool checkBindingCPU(DiagnosticEngine &Diags, const llvm::TargetMachine &TM,
                     llvm::ArrayRef<std::string> BindObjects);

/// Links `Object` with the runtime shim and the binding objects into the
/// program `Output` with TC's link command. Reports and returns false.
bool linkProgram(DiagnosticEngine &Diags, const ToolChain &TC,
                 llvm::StringRef Object, llvm::StringRef Output,
                 llvm::ArrayRef<std::string> BindObjects);

/// The top-level command (no subcommand) as written on the command line;
/// compile checks the values.
struct CompileOptions {
  BackendArgs Backend;
  OutputModes Modes;
  /// -o; empty: stdout for IR, the header and --emit=graph, `a.out` for a
  /// program, and for assembly and objects stdout with --emit=, else
  /// `<first input without .bs>.s` or `.o` in the current folder.
  std::string OutputFile;
  /// --export; empty: the behavior's roots.
  std::vector<std::string> Exports;
  /// --entry of a program.
  std::string EntryName;
  /// --behavior-name; empty: the first input's module.
  std::string BehaviorName;
  std::optional<std::string> CycleBudget;
  /// --assertions=none|count|trap; std::nullopt: none.
  std::optional<std::string> Assertions;
  bool DebugInfo = false, Instrument = false;
  /// --flight-recorder (CodeGenOptions::FlightRecorder).
  bool FlightRecorder = false;
  DepFileOptions DepFile;
};

/// The top-level command: checks the output modes, stops at a front-end
/// stage (emitFrontendStage), after the front end (-fsyntax-only, --verify),
/// or generates code for the checked behavior and writes what the modes
/// name (a program is linked with TC's runtime). Returns the exit status
/// after printing (or verifying) the diagnostics.
int compile(Compilation &C, const FrontendOptions &FOpts,
            const CompileOptions &Opts, const ToolChain &TC);

/// `--coverage FILE` and `--fail-under PERCENT` of `bsc run` and `bsc
/// replay`, as written.
struct CoverageArgs {
  std::string Path, Floor;
};

/// `--ignore` and `--tolerance` of `bsc run --replay` and `bsc replay`, as
/// written.
struct CompareArgs {
  std::vector<std::string> Ignore, Tolerance;
};

/// `bsc run` as written on the command line.
struct RunCommandOptions {
  BackendArgs Backend;
  bool CyclesGiven = false;
  std::string EntryName, RecordPath, ReplayPath, CycleLimit;
  std::optional<std::string> Trace, CycleBudget;
  bool PrintOutput = false, DebugInfo = false;
  std::string WorldLibrary, WorldOutput;
  CoverageArgs Coverage;
  std::optional<std::string> Robots; ///< --robots N, if given.
  bool Regression = false; ///< --regression.
  CompareArgs Compare;
};

/// `bsc run`: the behavior in the host JIT, --cycles calls of --entry.
/// Returns the exit status.
int runCommand(Compilation &C, const FrontendOptions &FOpts,
               const RunCommandOptions &Opts);

/// `bsc replay` as written on the command line.
struct ReplayCommandOptions {
  BackendArgs Backend;
  std::string EntryName, LogsDir, Shard, JUnitPath, CycleLimit;
  bool DebugInfo = false;
  CoverageArgs Coverage;
  std::string Jobs; ///< --jobs; empty: one worker per core.
  std::string WorldLibrary; ///< --world: its init and exit per log.
  bool Regression = false;  ///< --regression.
  CompareArgs Compare;
  bool Update = false; ///< --update.
  std::optional<std::string> Find; ///< --find.
  std::string Shrink, ShrinkOutput; ///< --shrink, -o.
  std::string Lasting; ///< --lasting.
  bool FindFirst = false; ///< --first.
};

/// `bsc replay`: the behavior compiled once into the host JIT, every
/// recording under --logs replayed against it. Returns the exit status.
int replayCommand(Compilation &C, const FrontendOptions &FOpts,
                  const ReplayCommandOptions &Opts);

/// `bsc timeline`: with --behavior, the behavior is loaded into the host
/// JIT to read binary logs (TimelineOptions::ReplayLog). Returns the exit
/// status.
int timelineCommand(Compilation &C, const FrontendOptions &FOpts,
                    timeline::TimelineOptions Opts);

/// `bsc convert` as written on the command line.
struct ConvertCommandOptions {
  std::string From, To;
  std::vector<std::string> BehaviorFiles; ///< --behavior
  std::string EntryName;
};

/// `bsc convert`: a recording as a binary log or back (convertRecording),
/// with the behavior loaded for its layout. Returns the exit status.
int convertCommand(Compilation &C, const FrontendOptions &FOpts,
                   const ConvertCommandOptions &Opts);

/// `bsc repl` as written on the command line.
struct ReplCommandOptions {
  BackendArgs Backend;
  std::string EntryName, CycleLimit, BatchFile, WorldLibrary, WorldOutput;
  std::optional<std::string> Robots; ///< --robots N, if given.
  std::optional<std::string> CycleBudget;
  bool DebugInfo = false;
};

/// `bsc repl`: checks the options, then hands over to the REPL, which loads
/// (and reloads) the files itself. Returns the exit status.
int replCommand(Compilation &C, const FrontendOptions &FOpts,
                const ReplCommandOptions &Opts);

/// `bsc format` as written on the command line.
struct FormatCommandOptions {
  std::vector<std::string> Files;
  bool InPlace = false; ///< -i: rewrite each file that changes.
  bool Check = false;   ///< --check: name each file that would change.
};

/// `bsc format`: prints each file in the canonical layout (Format.h),
/// rewrites it (-i), or names the files that would change (--check, exit
/// status 1 if any, 2 after an error). `-` is standard input (`<stdin>`).
/// A file with syntax errors is reported and left alone; the others are
/// still formatted. Returns the exit status.
int formatCommand(Compilation &C, const FormatCommandOptions &Opts,
                  llvm::raw_ostream &OS);

/// `bsc lsp`: the language server on standard input and output until the
/// client says `exit` (lib/LSP). Returns the exit status.
int lspCommand(llvm::StringRef RuntimeDir, const char *Argv0);

/// `bsc verify` as written on the command line.
struct VerifyCommandOptions {
  std::string EntryName, CounterexamplePath;
  std::optional<std::string> Cycles;    ///< --cycles N, if given.
  std::optional<std::string> LoopLimit; ///< --loop-limit N, if given.
  std::optional<std::string> SolverTimeout; ///< --solver-timeout S.
};

/// `bsc verify` (lib/Verify): checks the options, then the behavior's
/// assertions for every input of N cycles. Returns the exit status.
int verifyCommand(Compilation &C, const FrontendOptions &FOpts,
                  const VerifyCommandOptions &Opts);

/// `bsc dap`: the debug adapter on standard input and output until the
/// client disconnects (lib/DAP); behaviors run on the host with its
/// standard modules. Returns the exit status.
int dapCommand(llvm::StringRef RuntimeDir, const char *Argv0);

} // namespace bsc

#endif

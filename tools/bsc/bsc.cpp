//===- bsc.cpp - the b-script compiler driver -----------------------------===//
//
// Wires the phases together; the phases themselves never print. Each
// `--emit=` value names a place where the pipeline can stop and dump what it
// has (MLIR Toy's -emit), which is what the tests look at.
//
//   bsc [options] FILE.bs...          a program linked with the runtime shim
//   bsc -c / -S                       an object / assembly to embed
//   bsc --emit-header                 the typed C header of the behavior
//   bsc --emit=graph                  the call graph of funcs and tasks (DOT)
//   bsc run [options] FILE.bs...      JIT on the host, N cycles of the entry
//
// Everything the user can get wrong on the command line (a bad option value,
// a missing entry, an unknown target, an unwritable output, a missing
// linker or runtime) becomes a `bsc: error: ...` diagnostic and exit 1.
//
//===----------------------------------------------------------------------===//
#include "bsc/CodeGen/EmitHeader.h"
#include "bsc/Bind/Bind.h"
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/CodeGen/Target.h"
#include "bsc/Driver/ToolChain.h"
#include "bsc/Frontend/Frontend.h"
#include "bsc/JIT/JIT.h"
#include "bsc/Debug/Trace.h"
#include "bsc/Debug/Values.h"
#include "bsc/REPL/Debugger.h"
#include "bsc/REPL/Repl.h"
#include "llvm/Object/ObjectFile.h"
#include "llvm/Support/MemoryBuffer.h"
#include "bsc/Parse/Lexer.h"
#include "bsc/Parse/Parser.h"
#include "bsc/Sema/CallGraph.h"
#include "llvm/ADT/ScopeExit.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/StringSet.h"
#include "llvm/Demangle/Demangle.h"
#include "llvm/Support/CommandLine.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/InitLLVM.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Program.h"
#include "llvm/Support/ToolOutputFile.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"
#include <cstdlib>

using namespace bsc;
namespace cl = llvm::cl;

namespace {
enum class EmitKind { Default, Tokens, AST, TypedAST, Graph, LLVM, Asm, Obj };

cl::OptionCategory BscCategory("bsc options");
cl::SubCommand RunCmd("run", "Run a behavior on the host in a JIT, one call "
                             "of the entry per cycle");
cl::SubCommand ReplCmd("repl", "Debug a behavior in a JIT: step cycles, look "
                               "at tasks, evaluate b-script between cycles");
cl::SubCommand TraceDecodeCmd(
    "trace-decode",
    "Print a robot's trace log as `bsc run --trace` does, with the tables of "
    "an object compiled with --instrument");

/// Options shared by the compiler and `bsc run` are in both subcommands.
#define BSC_BOTH cl::sub(cl::SubCommand::getTopLevel()), cl::sub(RunCmd)
/// ...and those the REPL takes too.
#define BSC_ALL BSC_BOTH, cl::sub(ReplCmd)

cl::list<std::string> InputFiles(cl::Positional, cl::desc("<file.bs>..."),
                                 cl::cat(BscCategory), BSC_ALL);
cl::list<std::string> IncludeDirs("I", cl::Prefix,
                                  cl::desc("Search folder for required modules"),
                                  cl::value_desc("dir"), cl::cat(BscCategory),
                                  BSC_ALL);
cl::opt<std::string>
    EntryName("entry",
              cl::desc("The task or func called once per cycle (default: "
                       "'main' of the first file's module)"),
              cl::value_desc("Module::name"), cl::init("main"),
              cl::cat(BscCategory), BSC_ALL);
cl::list<std::string> ExportNames(
    "export",
    cl::desc("Export these funcs and tasks as the object's entries (default: "
             "the behavior's roots, which nothing in it calls); the rest "
             "is internal"),
    cl::value_desc("Module::name,..."), cl::CommaSeparated,
    cl::cat(BscCategory));
cl::opt<std::string> CyclesArg("cycles",
                               cl::desc("Execution cycles to run (default 1)"),
                               cl::value_desc("N"), cl::init("1"),
                               cl::cat(BscCategory), BSC_BOTH);
cl::opt<std::string> OptLevelArg("O", cl::Prefix,
                                 cl::desc("Optimisation level 0..3 (default 0)"),
                                 cl::value_desc("level"), cl::init("0"),
                                 cl::cat(BscCategory), BSC_ALL);

cl::opt<std::string> RecordFile(
    "record",
    cl::desc("Write each cycle's input and output as one JSON line"),
    cl::value_desc("file.jsonl"), cl::cat(BscCategory), cl::sub(RunCmd));
cl::opt<std::string> ReplayFile(
    "replay",
    cl::desc("Feed each cycle's input from a JSON-lines file and compare "
             "the outputs it records"),
    cl::value_desc("file.jsonl"), cl::cat(BscCategory), cl::sub(RunCmd));
// A string, not an enum: llvm::cl's own message for a bad value is not a
// `bsc: error:` (parseTraceMode reports it).
cl::opt<std::string> TraceArg(
    "trace", cl::ValueOptional,
    cl::desc("Print the active task hierarchy after each cycle; with "
             "'=changes', only the cycles where it, a task's state or a "
             "line changed"),
    cl::value_desc("changes"), cl::cat(BscCategory), cl::sub(RunCmd));
cl::opt<bool> PrintOutputFlag("print-output",
                              cl::desc("Print the output after each cycle "
                                       "as JSON"),
                              cl::cat(BscCategory), cl::sub(RunCmd));
cl::opt<std::string> CycleLimitArg(
    "cycle-limit",
    cl::desc("Stop a cycle that runs longer than this (milliseconds; "
             "default 3000, 0: no limit)"),
    cl::value_desc("ms"), cl::init("3000"), cl::cat(BscCategory),
    cl::sub(RunCmd), cl::sub(ReplCmd));
cl::opt<std::string> WorldLibrary(
    "world",
    cl::desc("A shared library that feeds input and reads output around "
             "every cycle (bs_world_init/begin/end/exit, docs/repl.md)"),
    cl::value_desc("lib.so"), cl::cat(BscCategory), cl::sub(RunCmd),
    cl::sub(ReplCmd));
cl::opt<std::string> WorldOutput(
    "world-output",
    cl::desc("Write what the --world library prints to this file instead of "
             "standard output"),
    cl::value_desc("file"), cl::cat(BscCategory), cl::sub(RunCmd),
    cl::sub(ReplCmd));
cl::opt<std::string> BatchFile(
    "batch",
    cl::desc("Read the REPL's lines from this file, without a prompt (also "
             "when standard input is not a terminal)"),
    cl::value_desc("file"), cl::cat(BscCategory), cl::sub(ReplCmd));

cl::opt<std::string> RuntimeDirArg(
    "runtime-dir",
    cl::desc("The folder holding the runtime libraries (default: "
             "$BSCRIPT_RUNTIME_DIR, else ../lib/bscript or ../lib beside bsc's folder)"),
    cl::value_desc("dir"), cl::cat(BscCategory), BSC_ALL);
cl::opt<bool> DepFileFlag(
    "MD", cl::desc("Also write a make-style dependency file: the output "
                   "depends on every module file read and every --bind object"),
    cl::cat(BscCategory));
cl::opt<std::string> DepFilePath(
    "MF", cl::desc("The dependency file's name (default: the output's, with "
                   "'.d')"),
    cl::value_desc("file"), cl::cat(BscCategory));
cl::opt<bool> InstrumentFlag(
    "instrument",
    cl::desc("Make every task call write the state's trace record, and embed "
             "the debugger's tables (task names, yield lines) in the object, "
             "for `bsc trace-decode` of robot trace logs"),
    cl::cat(BscCategory));
cl::opt<std::string> CycleBudgetArg(
    "cycle-budget",
    cl::desc("Give each cycle N loop passes: a task whose loop runs past them "
             "fails and the cycle returns; the state records the loop "
             "(bscript.h, \"Cycle budgets\")"),
    cl::value_desc("N"), BSC_BOTH, cl::cat(BscCategory));
cl::opt<std::string> TraceObject(
    "object", cl::desc("The object compiled with --instrument"),
    cl::value_desc("file.o"), cl::cat(BscCategory), cl::sub(TraceDecodeCmd),
    cl::Required);
cl::opt<std::string> TraceLog(cl::Positional, cl::desc("<trace log>"),
                              cl::cat(BscCategory), cl::sub(TraceDecodeCmd),
                              cl::Required);
cl::opt<bool> TraceChangesFlag(
    "changes",
    cl::desc("Print only the cycles whose line differs from the cycle "
             "before's, as `bsc run --trace=changes`"),
    cl::cat(BscCategory), cl::sub(TraceDecodeCmd));

cl::opt<bool> SyntaxOnly("fsyntax-only",
                         cl::desc("Check the program; produce no output"),
                         cl::cat(BscCategory));
cl::opt<bool> Verify("verify",
                     cl::desc("Check diagnostics against the source's "
                              "'# expected-error {{...}}' comments"),
                     cl::cat(BscCategory));
cl::opt<EmitKind> Emit(
    "emit", cl::desc("Stop at a stage and print it"), cl::init(EmitKind::Default),
    cl::values(clEnumValN(EmitKind::Tokens, "tokens", "the tokens of each file"),
               clEnumValN(EmitKind::AST, "ast", "the syntax tree (parse only)"),
               clEnumValN(EmitKind::TypedAST, "typed-ast",
                          "the syntax tree after semantic checks"),
               clEnumValN(EmitKind::Graph, "graph",
                          "the call graph of funcs and tasks (Graphviz DOT)"),
               clEnumValN(EmitKind::LLVM, "llvm", "the LLVM IR (after -O)"),
               clEnumValN(EmitKind::Asm, "asm", "the target's assembly"),
               clEnumValN(EmitKind::Obj, "obj", "the object file")),
    cl::cat(BscCategory));
cl::opt<bool> EmitLLVMFlag("emit-llvm", cl::desc("Same as --emit=llvm"),
                           cl::cat(BscCategory));
cl::opt<bool> CompileOnly("c", cl::desc("Write an object file to embed "
                                        "(default name: <first file>.o)"),
                          cl::cat(BscCategory));
cl::opt<bool> AssembleOnly("S", cl::desc("Write assembly (default name: "
                                         "<first file>.s)"),
                           cl::cat(BscCategory));
cl::opt<bool> EmitHeaderFlag(
    "emit-header",
    cl::desc("Write the typed C header of the behavior for the target"),
    cl::cat(BscCategory));
cl::opt<std::string> OutputFile("o", cl::desc("Output file ('-' for stdout)"),
                                cl::value_desc("file"), cl::cat(BscCategory));
cl::opt<std::string>
    TargetArg("target",
              cl::desc("i586 (the robot: Geode, PIC, ELF32), x86_64, or any "
                       "LLVM triple (default: the host; programs only for "
                       "the host and i586)"),
              cl::value_desc("target"), cl::cat(BscCategory));
cl::opt<std::string>
    CPUArg("mcpu",
           cl::desc("Target CPU (default: geode for i586, x86-64 for x86_64, "
                    "else generic or the target's oldest)"),
           cl::value_desc("cpu"), cl::cat(BscCategory));
cl::opt<std::string> BehaviorNameArg(
    "behavior-name",
    cl::desc("Prefix of the exported symbols (default: the first file's "
             "module name)"),
    cl::value_desc("name"), cl::cat(BscCategory));
cl::list<std::string>
    BindObjects("bind",
                cl::desc("A binding object, archive or shared library "
                         "registering C++ for the scripts (repeatable; read "
                         "for -target)"),
                cl::value_desc("obj"), cl::cat(BscCategory), BSC_ALL);
cl::opt<bool> DumpBindings("dump-bindings",
                           cl::desc("Print what the standard modules and the "
                                    "--bind objects register, and exit"),
                           cl::cat(BscCategory));
/// -W's help, from the diagnostics' table of warning groups. Defined before
/// WarningOptions, whose description refers to it.
const std::string WarningHelp =
    "-Wno-<group>: silence a group of warnings; -Werror: warnings are "
    "errors; -Werror=<group>: that group's are (groups: " +
    DiagnosticEngine::getWarningGroupList() + ")";
cl::list<std::string>
    WarningOptions("W", cl::Prefix, cl::desc(WarningHelp),
                   cl::value_desc("no-group|error[=group]"),
                   cl::cat(BscCategory), BSC_BOTH);
cl::opt<bool> DebugInfo("g",
                        cl::desc("Emit DWARF debug information (for `run` "
                                 "and `repl`: register the JIT's code with "
                                 "gdb)"),
                        cl::cat(BscCategory), BSC_ALL);

/// Limit of --cycles: a run of more than a day of 30 Hz cycles is a typo.
constexpr unsigned MaxCycles = 100000000;

/// Prints the diagnostics (or verifies them) and returns the exit status.
int finish(Compilation &C) {
  if (Verify)
    return verifyDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs()) ? 0
                                                                           : 1;
  printDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs(),
                   llvm::WithColor(llvm::errs()).colorsEnabled());
  return C.Diags.hasErrors() ? 1 : 0;
}

/// Prints the diagnostics so far, then an internal error (a bug in bsc, not
/// in the program: see Target.h), and returns the exit status 1.
int finishWithInternalError(Compilation &C, llvm::Error E) {
  finish(C);
  llvm::WithColor::error(llvm::errs(), "bsc")
      << "internal error: " << llvm::toString(std::move(E)) << "\n";
  return 1;
}

int emitTokens(Compilation &C) {
  if (InputFiles.empty())
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
  for (const std::string &Path : InputFiles)
    if (unsigned ID = addSourceFile(C, Path))
      dumpTokens(C.SM, ID, C.Diags, llvm::outs());
  return finish(C);
}

int emitAST(Compilation &C, const FrontendOptions &Opts) {
  if (Emit == EmitKind::AST)
    loadModules(C, Opts);
  else
    runFrontend(C, Opts);
  for (ModuleAST *M : C.Modules)
    dumpAST(*M, llvm::outs());
  return finish(C);
}

bool isIdentifier(llvm::StringRef S) {
  if (S.empty() || !(llvm::isAlpha(S[0]) || S[0] == '_'))
    return false;
  return llvm::all_of(S, [](char Ch) { return llvm::isAlnum(Ch) || Ch == '_'; });
}

/// The options every back-end path needs, checked.
struct BackendOptions {
  TargetOptions Target;
  unsigned Cycles = 1;
};

/// Checks -O and --cycles; reports and returns false if one is bad.
bool parseBackendOptions(DiagnosticEngine &Diags, BackendOptions &Out) {
  bool OK = true;
  if (std::optional<unsigned> Level = parseOptLevel(OptLevelArg)) {
    Out.Target.OptLevel = *Level;
  } else {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << OptLevelArg.getValue() << "-O";
    OK = false;
  }
  unsigned Cycles;
  if (llvm::StringRef(CyclesArg).getAsInteger(10, Cycles) ||
      Cycles > MaxCycles) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << CyclesArg.getValue() << "--cycles";
    OK = false;
  } else {
    Out.Cycles = Cycles;
  }
  Out.Target.Triple = resolveTargetTriple(TargetArg);
  Out.Target.Spelling = TargetArg;
  Out.Target.CPU = CPUArg;
  return OK;
}

/// Applies the -Wno-<group>, -Werror and -Werror=<group> options; reports
/// and returns false on one that names no group.
bool applyWarningOptions(DiagnosticEngine &Diags) {
  bool OK = true;
  for (const std::string &Option : WarningOptions) {
    llvm::StringRef Group = Option;
    if (Group == "error") {
      Diags.promoteAllWarnings();
      continue;
    }
    bool Known = Group.consume_front("no-") ? Diags.ignoreWarningGroup(Group)
                 : Group.consume_front("error=")
                     ? Diags.promoteWarningGroup(Group)
                     : false;
    if (!Known) {
      Diags.report(llvm::SMLoc(), diag::err_unknown_warning_option)
          << Option << DiagnosticEngine::getWarningGroupList();
      OK = false;
    }
  }
  return OK;
}

/// Checks --cycle-budget (1 to 2^32 - 1 loop passes; unset is 0, none);
/// reports and returns false if it is bad.
bool parseCycleBudget(DiagnosticEngine &Diags, uint32_t &Passes) {
  Passes = 0;
  if (CycleBudgetArg.getNumOccurrences() == 0)
    return true;
  if (llvm::StringRef(CycleBudgetArg).getAsInteger(10, Passes) || !Passes) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << CycleBudgetArg.getValue() << "--cycle-budget";
    return false;
  }
  return true;
}

/// Checks `--trace[=changes]`; reports and returns false if it is bad.
bool parseTraceMode(DiagnosticEngine &Diags, debug::TraceMode &Mode) {
  Mode = debug::TraceMode::Off;
  if (TraceArg.getNumOccurrences() == 0)
    return true;
  if (TraceArg.empty())
    Mode = debug::TraceMode::EveryCycle;
  else if (TraceArg == "changes")
    Mode = debug::TraceMode::Changes;
  else {
    Diags.report(llvm::SMLoc(), diag::err_bad_trace_mode)
        << TraceArg.getValue();
    return false;
  }
  return true;
}

/// Checks --cycle-limit; reports and returns false if it is bad.
bool parseCycleLimit(DiagnosticEngine &Diags, unsigned &Ms) {
  // A day: anything longer is a typo, and itimer values must stay small.
  constexpr unsigned MaxCycleLimitMs = 86400000;
  if (llvm::StringRef(CycleLimitArg).getAsInteger(10, Ms) ||
      Ms > MaxCycleLimitMs) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << CycleLimitArg.getValue() << "--cycle-limit";
    return false;
  }
  return true;
}

/// The behavior name: --behavior-name, or the first input's module.
std::string getBehaviorName(Compilation &C) {
  if (!BehaviorNameArg.empty()) {
    if (!isIdentifier(BehaviorNameArg)) {
      C.Diags.report(llvm::SMLoc(), diag::err_bad_behavior_name)
          << BehaviorNameArg.getValue();
      return "";
    }
    return BehaviorNameArg;
  }
  return C.Modules.empty() ? "" : C.Modules.front()->Name;
}

/// Opens `Path` for writing ("-" is stdout); reports failure.
std::unique_ptr<llvm::ToolOutputFile> openOutput(Compilation &C,
                                                 llvm::StringRef Path,
                                                 bool Text) {
  std::error_code EC;
  if (Path != "-" && llvm::sys::fs::is_directory(Path)) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << "is a directory";
    return nullptr;
  }
  auto Out = std::make_unique<llvm::ToolOutputFile>(
      Path, EC, Text ? llvm::sys::fs::OF_Text : llvm::sys::fs::OF_None);
  if (EC) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << Path << EC.message();
    return nullptr;
  }
  return Out;
}

/// `--emit=graph`: the static call graph of the checked behavior, to -o or
/// stdout; nothing when the behavior has errors.
int emitGraph(Compilation &C, const FrontendOptions &Opts) {
  if (!runFrontend(C, Opts))
    return finish(C);
  auto Out = openOutput(C, OutputFile.empty() ? "-" : OutputFile.getValue(),
                        true);
  if (!Out)
    return finish(C);
  writeCallGraphDOT(C.Checked, C.SM, Out->os());
  Out->keep();
  return finish(C);
}

/// `<first input without .bs><Ext>` in the current folder.
std::string defaultOutputName(llvm::StringRef Ext) {
  llvm::StringRef Stem = llvm::sys::path::stem(InputFiles.front());
  return (Stem + Ext).str();
}

/// The path bsc was started as, for the version printer (which cl calls
/// without arguments).
const char *Argv0ForVersion = "bsc";

/// `bsc --version`: bsc's and LLVM's versions, the default target, and the
/// runtimes this bsc links programs with (and where it looked).
void printVersion(llvm::raw_ostream &OS) {
  OS << "bsc " << BSC_VERSION << " (b-script compiler for robot behaviors)\n"
     << "LLVM " << BSC_LLVM_VERSION << "\n"
     << "default target: " << resolveTargetTriple("").str() << "\n";
  for (const char *Target : {"x86_64", "i586"}) {
    ToolChain TC = getToolChain(Target, RuntimeDirArg, Argv0ForVersion);
    OS << "runtime (" << Target << "): ";
    if (std::optional<std::string> Path = TC.findRuntime())
      OS << *Path << "\n";
    else
      OS << TC.getRuntimeArchiveName() << " missing (looked in "
         << TC.describeRuntimeSearch() << ")\n";
  }
}

/// Links `Object` with the runtime shim into the program `Output`.
/// Reports and returns false on failure.
bool linkProgram(Compilation &C, const ToolChain &TC, llvm::StringRef Object,
                 llvm::StringRef Output,
                 llvm::ArrayRef<std::string> BindObjects) {
  std::optional<std::string> Runtime = TC.findRuntime();
  if (!Runtime) {
    C.Diags.report(llvm::SMLoc(), diag::err_runtime_missing)
        << TC.getRuntimeArchiveName() << TC.describeRuntimeSearch();
    return false;
  }
  std::optional<Command> Link =
      TC.getLinkCommand(Object, BindObjects, *Runtime, Output);
  if (!Link) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_linker)
        << TC.getTriple().str() << "neither 'cc' nor 'clang-19' is on PATH";
    return false;
  }
  llvm::SmallVector<llvm::StringRef, 8> ArgRefs(Link->Args.begin(),
                                                Link->Args.end());
  std::string ErrMsg;
  int RC = llvm::sys::ExecuteAndWait(Link->Program, ArgRefs, std::nullopt, {},
                                     0, 0, &ErrMsg);
  if (RC != 0) {
    C.Diags.report(llvm::SMLoc(), diag::err_link_failed)
        << Output << Link->Program << RC;
    return false;
  }
  return true;
}

/// For a 32-bit x86 target (the robot), reports each --bind object that
/// holds instructions the target CPU lacks: it would die of SIGILL there.
bool checkBindingCPU(Compilation &C, const llvm::TargetMachine &TM) {
  if (TM.getTargetTriple().getArch() != llvm::Triple::x86)
    return true;
  bool OK = true;
  for (const std::string &Path : BindObjects) {
    llvm::Expected<CPUMismatch> Found = findInstructionsCPULacks(TM, Path);
    if (!Found) {
      llvm::consumeError(Found.takeError()); // The reader reported it.
      continue;
    }
    if (!Found->Count)
      continue;
    std::string More =
        Found->Count > 1
            ? " (and " + std::to_string(Found->Count - 1) + " more)"
            : "";
    C.Diags.report(llvm::SMLoc(), diag::err_bind_cpu_lacks)
        << Path << Found->Function << Found->Instruction
        << TM.getTargetCPU().str() << More;
    OK = false;
  }
  return OK;
}

/// -MD: writes `Output: sources and binding objects` for make and Ninja
/// (spaces escaped as make wants). Reports and returns false on failure.
bool writeDepFile(Compilation &C, llvm::StringRef Output) {
  if (!DepFileFlag)
    return true;
  std::string Path = DepFilePath;
  if (Path.empty()) {
    if (Output == "-") {
      C.Diags.report(llvm::SMLoc(), diag::err_depfile_needs_path);
      return false;
    }
    llvm::SmallString<256> D(Output);
    llvm::sys::path::replace_extension(D, ".d");
    Path = std::string(D);
  }
  auto Out = openOutput(C, Path, /*Text=*/true);
  if (!Out)
    return false;
  auto Escaped = [](llvm::StringRef S) {
    std::string E;
    for (char Ch : S) {
      if (Ch == ' ' || Ch == '#')
        E += '\\';
      else if (Ch == '$')
        E += '$';
      E += Ch;
    }
    return E;
  };
  llvm::raw_ostream &OS = Out->os();
  OS << Escaped(Output) << ":";
  for (const ModuleAST *M : C.Modules)
    OS << " \\\n  " << Escaped(M->Path);
  for (const std::string &Obj : BindObjects)
    OS << " \\\n  " << Escaped(Obj);
  OS << "\n";
  Out->keep();
  return true;
}

/// What the top-level command produces when it goes past the front end.
enum class OutputKind { LLVM, Asm, Obj, Header, Program };

int compile(Compilation &C, const BackendOptions &BOpts, OutputKind Kind,
            const ToolChain &TC) {
  // Back-end errors (and report_fatal_error, which some targets call as
  // early as creating the machine) become diagnostics and exit status 1.
  llvm::LLVMContext Ctx;
  BackendErrorReporter Reporter(
      Ctx, C.Diags, BOpts.Target.Triple.str(),
      [&] { finish(C); });
  std::unique_ptr<llvm::TargetMachine> TM =
      createTargetMachine(BOpts.Target, C.Diags);
  if (!TM)
    return finish(C);
  if (Kind == OutputKind::Program && !TC.hasRuntime()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_runtime_for_target)
        << TM->getTargetTriple().str();
    return finish(C);
  }
  if (DebugInfo && Kind != OutputKind::LLVM && Kind != OutputKind::Header &&
      !supportsDebugInfo(TM->getTargetTriple())) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_debug_info_for_target)
        << TM->getTargetTriple().str();
    return finish(C);
  }
  if (!checkBindingCPU(C, *TM))
    return finish(C);
  CodeGenOptions CGOpts;
  CGOpts.Instrument = InstrumentFlag;
  if (!parseCycleBudget(C.Diags, CGOpts.CycleBudget))
    return finish(C);
  CGOpts.NarrowX87Floats = usesX87Floats(*TM);
  CGOpts.DebugInfo = DebugInfo;
  CGOpts.Sources = &C.SM;
  CGOpts.OptLevel = BOpts.Target.OptLevel;
  CGOpts.BehaviorName = getBehaviorName(C);
  if (CGOpts.BehaviorName.empty())
    return finish(C);
  if (!ExportNames.empty()) {
    CGOpts.Exports = findExports(C, ExportNames);
    if (!CGOpts.Exports)
      return finish(C);
  }
  if (Kind == OutputKind::Program) {
    CGOpts.ProgramEntry = findProgramEntry(C, EntryName);
    if (!CGOpts.ProgramEntry)
      return finish(C);
    CGOpts.ProgramCycles = BOpts.Cycles;
  }

  BehaviorLayout Layout;
  std::unique_ptr<llvm::Module> M =
      emitLLVM(C.Checked, Ctx, TM->getTargetTriple(), TM->createDataLayout(),
               CGOpts, Layout);
  if (llvm::Error E = verifyGeneratedModule(*M))
    return finishWithInternalError(C, std::move(E));
  if (CGOpts.Instrument)
    defineDebugTables(*M, Layout,
                      debug::toJSONString(debug::toJSON(
                          debug::buildDebugTables(C.Checked, Layout, C.SM))));

  if (Kind == OutputKind::Header) {
    auto Out = openOutput(C, OutputFile.empty() ? "-" : OutputFile.getValue(), true);
    if (!Out)
      return finish(C);
    writeBehaviorHeader(C.Checked, Layout, CGOpts.BehaviorName,
                        TM->getTargetTriple(), TM->createDataLayout(),
                        Out->os());
    Out->keep();
    writeDepFile(C, OutputFile.empty() ? "-" : OutputFile.getValue());
    return finish(C);
  }

  optimizeModule(*M, TM.get(), BOpts.Target.OptLevel);

  switch (Kind) {
  case OutputKind::LLVM: {
    auto Out = openOutput(C, OutputFile.empty() ? "-" : OutputFile.getValue(), true);
    if (!Out)
      return finish(C);
    M->print(Out->os(), nullptr);
    Out->keep();
    writeDepFile(C, OutputFile.empty() ? "-" : OutputFile.getValue());
    return finish(C);
  }
  case OutputKind::Asm:
  case OutputKind::Obj: {
    bool IsAsm = Kind == OutputKind::Asm;
    std::string Path = OutputFile;
    if (Path.empty())
      Path = Emit != EmitKind::Default ? "-"
                                       : defaultOutputName(IsAsm ? ".s" : ".o");
    auto Out = openOutput(C, Path, IsAsm);
    if (!Out)
      return finish(C);
    if (!emitMachineCode(*M, *TM,
                         IsAsm ? llvm::CodeGenFileType::AssemblyFile
                               : llvm::CodeGenFileType::ObjectFile,
                         Out->os(), C.Diags))
      return finish(C);
    Out->keep();
    writeDepFile(C, Path);
    return finish(C);
  }
  case OutputKind::Program: {
    std::string Path = OutputFile.empty() ? "a.out" : OutputFile.getValue();
    // Check the output before the work of linking, and so that the error
    // names the file rather than coming from the linker.
    if (!openOutput(C, Path, false))
      return finish(C);
    int FD;
    llvm::SmallString<128> ObjPath;
    if (std::error_code EC = llvm::sys::fs::createTemporaryFile(
            "bsc-" + CGOpts.BehaviorName, "o", FD, ObjPath)) {
      C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
          << "a temporary object file" << EC.message();
      return finish(C);
    }
    auto RemoveObj =
        llvm::make_scope_exit([&] { llvm::sys::fs::remove(ObjPath); });
    {
      llvm::raw_fd_ostream ObjOS(FD, /*shouldClose=*/true);
      if (!emitMachineCode(*M, *TM, llvm::CodeGenFileType::ObjectFile, ObjOS,
                           C.Diags))
        return finish(C);
    }
    if (!checkBindingImports(C, *M, BindObjects) ||
        !linkProgram(C, TC, ObjPath, Path, BindObjects))
      llvm::sys::fs::remove(Path);
    else
      writeDepFile(C, Path);
    return finish(C);
  }
  case OutputKind::Header:
    break;
  }
  return finish(C);
}

/// `--world-output` redirects the world's prints: without `--world` it is
/// a mistake.
static bool checkWorldOutputOption(Compilation &C) {
  if (WorldOutput.empty() || !WorldLibrary.empty())
    return true;
  C.Diags.report(llvm::SMLoc(), diag::err_option_needs_option)
      << "--world-output" << "--world";
  return false;
}

/// `bsc run`: the behavior in the host JIT, --cycles calls of --entry.
int runJIT(Compilation &C, const FrontendOptions &FOpts) {
  BackendOptions BOpts;
  bool OptionsOK = parseBackendOptions(C.Diags, BOpts);
  RunOptions ROpts;
  ROpts.Cycles = BOpts.Cycles;
  ROpts.CyclesGiven = CyclesArg.getNumOccurrences() != 0;
  ROpts.RecordPath = RecordFile;
  ROpts.ReplayPath = ReplayFile;
  ROpts.PrintOutput = PrintOutputFlag;
  OptionsOK &= parseTraceMode(C.Diags, ROpts.Trace);
  OptionsOK &= parseCycleLimit(C.Diags, ROpts.CycleLimitMs);
  uint32_t CycleBudget = 0;
  OptionsOK &= parseCycleBudget(C.Diags, CycleBudget);
  if (!runFrontend(C, FOpts) || !OptionsOK)
    return finish(C);
  const CallableDecl *Entry = findProgramEntry(C, EntryName);
  if (!Entry)
    return finish(C);
  LoadOptions LOpts;
  LOpts.OptLevel = BOpts.Target.OptLevel;
  LOpts.StandardModules = FOpts.StandardModules;
  LOpts.BindObjects = FOpts.BindObjects;
  LOpts.DebugInfo = DebugInfo;
  LOpts.CycleBudget = CycleBudget;
  auto Loaded = loadBehavior(C, *Entry, LOpts);
  if (!Loaded)
    return finishWithInternalError(C, Loaded.takeError());
  if (!*Loaded)
    return finish(C);
  if (!WorldLibrary.empty() && !ReplayFile.empty()) {
    // A replay feeds the recorded input; the world would overwrite it.
    C.Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << "--world" << "--replay";
    return finish(C);
  }
  if (!checkWorldOutputOption(C))
    return finish(C);
  int WorldOutputFd = -1;
  if (!WorldOutput.empty() &&
      (WorldOutputFd = openWorldOutput(C, WorldOutput)) < 0)
    return finish(C);
  auto Session = startSession(C, **Loaded);
  if (!Session)
    return finishWithInternalError(C, Session.takeError());
  if (*Session)
    (*Session)->setWorldOutput(WorldOutputFd);
  if (*Session && (WorldLibrary.empty() ||
                   attachWorldLibrary(C, **Loaded, **Session, WorldLibrary,
                                      ROpts.CycleLimitMs)))
    runBehavior(C, **Loaded, **Session, ROpts, llvm::outs());
  return finish(C);
}

/// `bsc repl`: checks the options, then hands over to the REPL, which loads
/// (and reloads) the files itself.
int runReplCommand(Compilation &C, const FrontendOptions &FOpts) {
  BackendOptions BOpts;
  bool OK = parseBackendOptions(C.Diags, BOpts);
  ReplOptions Opts;
  OK &= parseCycleLimit(C.Diags, Opts.CycleLimitMs);
  if (InputFiles.empty()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    OK = false;
  }
  OK &= checkWorldOutputOption(C);
  if (!OK)
    return finish(C);
  Opts.Frontend = FOpts;
  Opts.Load.OptLevel = BOpts.Target.OptLevel;
  Opts.Load.StandardModules = FOpts.StandardModules;
  Opts.Load.BindObjects = FOpts.BindObjects;
  Opts.Load.DebugInfo = DebugInfo;
  Opts.EntryName = EntryName;
  Opts.BatchFile = BatchFile;
  Opts.WorldLibrary = WorldLibrary;
  Opts.WorldOutput = WorldOutput;
  return runRepl(Opts, llvm::outs());
}

/// `bsc trace-decode --object B.o LOG`: the tables from the object's
/// DebugTablesSection, the records from the log (bscript.h, "Trace logs").
int decodeTrace(Compilation &C) {
  auto Fail = [&](const llvm::Twine &Path, const llvm::Twine &Why) {
    C.Diags.report(llvm::SMLoc(), diag::err_trace_decode)
        << Path.str() << Why.str();
    return finish(C);
  };
  auto Obj = llvm::object::ObjectFile::createObjectFile(TraceObject);
  if (!Obj)
    return Fail(TraceObject, llvm::toString(Obj.takeError()));
  std::optional<llvm::StringRef> Text;
  for (const llvm::object::SectionRef &Sec : Obj->getBinary()->sections()) {
    llvm::Expected<llvm::StringRef> Name = Sec.getName();
    if (!Name) {
      llvm::consumeError(Name.takeError());
      continue;
    }
    if (*Name != DebugTablesSection)
      continue;
    llvm::Expected<llvm::StringRef> Contents = Sec.getContents();
    if (!Contents)
      return Fail(TraceObject, llvm::toString(Contents.takeError()));
    Text = Contents->split('\0').first;
  }
  if (!Text) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_debug_tables)
        << TraceObject.getValue();
    return finish(C);
  }
  llvm::Expected<debug::DebugTables> Tables = debug::parseDebugTables(*Text);
  if (!Tables)
    return Fail(TraceObject, llvm::toString(Tables.takeError()));
  auto Log = llvm::MemoryBuffer::getFile(TraceLog, /*IsText=*/false,
                                         /*RequiresNullTerminator=*/false);
  if (!Log)
    return Fail(TraceLog, Log.getError().message());
  auto Cycles =
      debug::parseTraceLog((*Log)->getBuffer(), *Tables);
  if (!Cycles)
    return Fail(TraceLog, llvm::toString(Cycles.takeError()));
  debug::TraceFilter Traces(TraceChangesFlag ? debug::TraceMode::Changes
                                             : debug::TraceMode::EveryCycle);
  for (const debug::LoggedCycle &Cycle : *Cycles) {
    std::string Trace = debug::formatTraceLine(*Tables, Cycle.Records);
    if (Traces.shouldPrint(Trace))
      llvm::outs() << "cycle " << Cycle.Cycle << ": " << Trace << "\n";
    // Printed whether or not its cycle's line is: it names the cycle.
    std::string Budget = debug::formatBudgetLine(*Tables, Cycle);
    if (!Budget.empty())
      llvm::outs() << Budget << "\n";
  }
  return finish(C);
}

/// Reports options of plain compilation given to `bsc run` or `bsc repl`:
/// llvm::cl lets a subcommand fall back to the top level's options, which
/// would silently ignore them (`bsc run -c`).
bool checkSubcommandOptions(DiagnosticEngine &Diags, cl::SubCommand &Sub) {
  const auto &RunOptions = cl::getRegisteredOptions(Sub);
  bool OK = true;
  for (const auto &[Name, Opt] :
       cl::getRegisteredOptions(cl::SubCommand::getTopLevel())) {
    if (Opt->getNumOccurrences() == 0 || RunOptions.count(Name))
      continue;
    Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << ("-" + Name.str()) << Sub.getName();
    OK = false;
  }
  return OK;
}

/// The option `Name` (without dashes and `=value`) as `Sub` parses it: its
/// own, else the top level's (llvm::cl falls back to them, and
/// checkSubcommandOptions names those a subcommand does not take), else a
/// Prefix option written with its value attached (`-O2`, `-Ifolder`).
/// `Attached` says whether the value is part of `Name`.
cl::Option *findOption(cl::SubCommand &Sub, llvm::StringRef Name,
                       bool &Attached) {
  Attached = false;
  for (cl::SubCommand *S : {&Sub, &cl::SubCommand::getTopLevel()}) {
    const auto &Options = cl::getRegisteredOptions(*S);
    if (cl::Option *O = Options.lookup(Name))
      return O;
    for (const auto &[Key, O] : Options)
      if (O->getFormattingFlag() == cl::Prefix && Name.starts_with(Key)) {
        Attached = true;
        return O;
      }
  }
  return nullptr;
}

/// The name of bsc's own option nearest to a misspelt `Name`, if one is
/// at most a third of its length away.
std::optional<std::string> findNearOption(cl::SubCommand &Sub,
                                          llvm::StringRef Name) {
  std::optional<std::string> Best;
  unsigned BestDistance = std::max<size_t>(1, Name.size() / 3) + 1;
  for (const auto &[Key, O] : cl::getRegisteredOptions(Sub)) {
    if (!llvm::is_contained(O->Categories, &BscCategory) || Key.size() < 2)
      continue;
    unsigned D = Name.edit_distance(Key, true, BestDistance);
    if (D < BestDistance) {
      BestDistance = D;
      Best = "--" + Key.str();
    }
  }
  return Best;
}

/// Checks the words of the command line before llvm::cl parses them, which
/// would take an unknown `--check` for the one-letter options `-c -h -e -c
/// -k` grouped, print the help at `-h` and exit 0. A word in the
/// subcommand's place that is neither a subcommand nor a file, and an
/// option no subcommand has, are errors. Reports and returns false.
bool checkCommandLine(DiagnosticEngine &Diags,
                      llvm::ArrayRef<const char *> Args) {
  cl::SubCommand *Sub = &cl::SubCommand::getTopLevel();
  size_t I = 1;
  std::vector<std::string> SubNames;
  for (cl::SubCommand *S : cl::getRegisteredSubcommands()) {
    if (S->getName().empty())
      continue; // The top level and "all".
    SubNames.push_back("'" + S->getName().str() + "'");
    if (Args.size() > 1 && S->getName() == Args[1]) {
      Sub = S;
      I = 2;
    }
  }
  if (I == 1 && Args.size() > 1) {
    llvm::StringRef First = Args[1];
    bool Word = !First.empty() && llvm::all_of(First, [](char Ch) {
      return llvm::isAlnum(Ch) || Ch == '-' || Ch == '_';
    });
    if (Word && First[0] != '-' && !llvm::sys::fs::exists(First)) {
      llvm::sort(SubNames);
      Diags.report(llvm::SMLoc(), diag::err_unknown_subcommand)
          << First << llvm::join(SubNames, ", ");
      return false;
    }
  }
  bool OK = true;
  for (; I < Args.size(); ++I) {
    llvm::StringRef Arg = Args[I];
    if (Arg == "--")
      break;
    if (Arg.size() < 2 || Arg[0] != '-')
      continue;
    auto [Name, Value] = Arg.drop_front(Arg.starts_with("--") ? 2 : 1).split('=');
    // `-h` is llvm::cl's alias of --help, registered while it parses.
    if (Name == "h")
      continue;
    bool Attached;
    cl::Option *O = findOption(*Sub, Name, Attached);
    if (!O) {
      std::string Command = Sub->getName().empty()
                                ? std::string("bsc")
                                : ("bsc " + Sub->getName()).str();
      Diags.report(llvm::SMLoc(), diag::err_unknown_option) << Arg << Command;
      if (std::optional<std::string> Near = findNearOption(*Sub, Name))
        Diags.report(llvm::SMLoc(), diag::note_did_you_mean) << *Near;
      OK = false;
      continue;
    }
    // `-o FILE`: the next word is the value, whatever it looks like.
    if (O->getValueExpectedFlag() == cl::ValueRequired && !Attached &&
        !Arg.contains('='))
      ++I;
  }
  return OK;
}

/// Reports options that ask for two different outputs.
bool checkConflicts(DiagnosticEngine &Diags) {
  llvm::SmallVector<const char *, 4> Modes;
  if (SyntaxOnly)
    Modes.push_back("-fsyntax-only");
  if (Verify)
    Modes.push_back("--verify");
  if (CompileOnly)
    Modes.push_back("-c");
  if (AssembleOnly)
    Modes.push_back("-S");
  if (EmitHeaderFlag)
    Modes.push_back("--emit-header");
  if (Emit != EmitKind::Default)
    Modes.push_back("--emit");
  if (EmitLLVMFlag)
    Modes.push_back("--emit-llvm");
  // --verify checks the diagnostics of a front-end run: -fsyntax-only with it
  // says the same thing twice.
  if (Modes.size() == 2 && SyntaxOnly && Verify)
    return true;
  if (Modes.size() > 1) {
    Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << Modes[0] << Modes[1];
    return false;
  }
  return true;
}
} // namespace

int main(int argc, char **argv) {
  llvm::InitLLVM X(argc, argv);
  cl::HideUnrelatedOptions(BscCategory);
  cl::HideUnrelatedOptions(BscCategory, RunCmd);
  cl::HideUnrelatedOptions(BscCategory, TraceDecodeCmd);
  cl::HideUnrelatedOptions(BscCategory, ReplCmd);
  Argv0ForVersion = argv[0];
  cl::SetVersionPrinter(printVersion);
  Compilation C;
  if (!checkCommandLine(C.Diags, llvm::ArrayRef(argv, argc)))
    return finish(C);
  cl::ParseCommandLineOptions(argc, argv,
                              "bsc: the b-script compiler for robot behaviors\n");

  if (!applyWarningOptions(C.Diags))
    return finish(C);
  FrontendOptions Opts;
  Opts.Inputs.assign(InputFiles.begin(), InputFiles.end());
  Opts.IncludeDirs.assign(IncludeDirs.begin(), IncludeDirs.end());
  Opts.BindObjects.assign(BindObjects.begin(), BindObjects.end());
  // `run` and `repl` are for the host's JIT, whatever -target says.
  ToolChain TC = getToolChain(
      RunCmd || ReplCmd ? llvm::StringRef() : llvm::StringRef(TargetArg),
      RuntimeDirArg, argv[0]);
  Opts.Target = TC.getTriple();
  if (TC.hasRuntime()) {
    if (std::optional<std::string> Runtime = TC.findRuntime())
      Opts.StandardModules = {*Runtime};
    else
      Opts.MissingRuntime = {TC.getRuntimeArchiveName().str(),
                             TC.describeRuntimeSearch()};
  }

  if (DumpBindings) {
    if (readBindingObjects(C, Opts))
      bind::dumpBindings(C.Bindings, llvm::outs());
    return finish(C);
  }

  if (RunCmd)
    return checkSubcommandOptions(C.Diags, RunCmd) ? runJIT(C, Opts)
                                                   : finish(C);
  if (ReplCmd)
    return checkSubcommandOptions(C.Diags, ReplCmd) ? runReplCommand(C, Opts)
                                                    : finish(C);
  if (TraceDecodeCmd)
    return decodeTrace(C);

  if (!checkConflicts(C.Diags))
    return finish(C);
  if (EmitLLVMFlag)
    Emit = EmitKind::LLVM;
  switch (Emit) {
  case EmitKind::Tokens:
    return emitTokens(C);
  case EmitKind::AST:
  case EmitKind::TypedAST:
    return emitAST(C, Opts);
  case EmitKind::Graph:
    return emitGraph(C, Opts);
  case EmitKind::Default:
  case EmitKind::LLVM:
  case EmitKind::Asm:
  case EmitKind::Obj:
    break;
  }

  BackendOptions BOpts;
  bool OptionsOK = parseBackendOptions(C.Diags, BOpts);
  if (!runFrontend(C, Opts) || !OptionsOK || SyntaxOnly || Verify)
    return finish(C);

  OutputKind Kind = OutputKind::Program;
  if (Emit == EmitKind::LLVM)
    Kind = OutputKind::LLVM;
  else if (Emit == EmitKind::Asm || AssembleOnly)
    Kind = OutputKind::Asm;
  else if (Emit == EmitKind::Obj || CompileOnly)
    Kind = OutputKind::Obj;
  else if (EmitHeaderFlag)
    Kind = OutputKind::Header;
  return compile(C, BOpts, Kind, TC);
}

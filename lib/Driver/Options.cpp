//===- Options.cpp - checking the values of bsc's options -----------------===//
//
// What a valid option value is, and what the output options ask for. The
// tool only copies the values here; every message about them is a
// diagnostic of the table (`bsc: error: ...`, exit status 1), never
// llvm::cl's own.
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/ADT/SmallVector.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/WithColor.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

int bsc::finishCompilation(Compilation &C, bool Verify) {
  if (Verify)
    return verifyDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs()) ? 0
                                                                           : 1;
  printDiagnostics(C.SM, C.Diags.getDiagnostics(), llvm::errs(),
                   llvm::WithColor(llvm::errs()).colorsEnabled());
  return C.Diags.hasErrors() ? 1 : 0;
}

int bsc::finishWithInternalError(Compilation &C, llvm::Error E) {
  finishCompilation(C);
  reportInternalError(std::move(E));
  return 1;
}

bool bsc::parseBackendOptions(DiagnosticEngine &Diags, const BackendArgs &Args,
                              BackendOptions &Out) {
  bool OK = true;
  if (std::optional<unsigned> Level = parseOptLevel(Args.OptLevel)) {
    Out.Target.OptLevel = *Level;
  } else {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << Args.OptLevel << "-O";
    OK = false;
  }
  unsigned Cycles;
  if (llvm::StringRef(Args.Cycles).getAsInteger(10, Cycles) ||
      Cycles > MaxCycles) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << Args.Cycles << "--cycles";
    OK = false;
  } else {
    Out.Cycles = Cycles;
  }
  Out.Target.Triple = resolveTargetTriple(Args.Target);
  Out.Target.Spelling = Args.Target;
  Out.Target.CPU = Args.CPU;
  return OK;
}

bool bsc::applyWarningOptions(DiagnosticEngine &Diags,
                              llvm::ArrayRef<std::string> Options) {
  bool OK = true;
  for (const std::string &Option : Options) {
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

bool bsc::parseAssertionMode(DiagnosticEngine &Diags,
                             const std::optional<std::string> &Arg,
                             AssertionMode &Mode) {
  Mode = AssertionMode::None;
  if (!Arg || *Arg == "none")
    return true;
  if (*Arg == "count")
    Mode = AssertionMode::Count;
  else if (*Arg == "trap")
    Mode = AssertionMode::Trap;
  else {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << *Arg << "--assertions";
    return false;
  }
  return true;
}

bool bsc::parseCycleBudget(DiagnosticEngine &Diags,
                           const std::optional<std::string> &Arg,
                           uint32_t &Passes) {
  Passes = 0;
  if (!Arg)
    return true;
  if (llvm::StringRef(*Arg).getAsInteger(10, Passes) || !Passes) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << *Arg << "--cycle-budget";
    return false;
  }
  return true;
}

bool bsc::parseTraceMode(DiagnosticEngine &Diags,
                         const std::optional<std::string> &Arg,
                         debug::TraceMode &Mode, std::string &Task) {
  Mode = debug::TraceMode::Off;
  if (!Arg)
    return true;
  if (Arg->empty())
    Mode = debug::TraceMode::EveryCycle;
  else if (*Arg == "changes")
    Mode = debug::TraceMode::Changes;
  else if (llvm::all_of(*Arg, [](char Ch) {
             return llvm::isAlnum(Ch) || Ch == '_' || Ch == ':';
           }) && !llvm::isDigit(Arg->front())) {
    // A task's name: its subtree, on the cycles where it changes; the
    // runner checks that the behavior has it.
    Mode = debug::TraceMode::Changes;
    Task = *Arg;
  } else {
    Diags.report(llvm::SMLoc(), diag::err_bad_trace_mode) << *Arg;
    return false;
  }
  return true;
}

bool bsc::parseRobots(DiagnosticEngine &Diags,
                      const std::optional<std::string> &Arg,
                      unsigned &Robots) {
  Robots = 1;
  if (!Arg)
    return true;
  if (llvm::StringRef(*Arg).getAsInteger(10, Robots) || Robots < 1 ||
      Robots > MaxRobots) {
    Diags.report(llvm::SMLoc(), diag::err_bad_robots) << *Arg << MaxRobots;
    return false;
  }
  return true;
}

bool bsc::parseCycleLimit(DiagnosticEngine &Diags, llvm::StringRef Arg,
                          unsigned &Ms) {
  if (Arg.getAsInteger(10, Ms) || Ms > MaxCycleLimitMs) {
    Diags.report(llvm::SMLoc(), diag::err_bad_option_value)
        << Arg << "--cycle-limit";
    return false;
  }
  return true;
}

void bsc::addStandardModules(const ToolChain &TC, FrontendOptions &Opts) {
  if (!TC.hasRuntime())
    return;
  if (std::optional<std::string> Runtime = TC.findRuntime())
    Opts.StandardModules = {*Runtime};
  else
    Opts.MissingRuntime = {TC.getRuntimeArchiveName().str(),
                           TC.describeRuntimeSearch()};
}

void bsc::printVersion(llvm::raw_ostream &OS, const VersionInfo &Info) {
  OS << "bsc " << Info.BscVersion
     << " (b-script compiler for robot behaviors)\n"
     << "LLVM " << Info.LLVMVersion << "\n"
     << "default target: " << resolveTargetTriple("").str() << "\n";
  for (const char *Target : {"x86_64", "i586"}) {
    ToolChain TC = getToolChain(Target, Info.RuntimeDir, Info.Argv0);
    OS << "runtime (" << Target << "): ";
    if (std::optional<std::string> Path = TC.findRuntime())
      OS << *Path << "\n";
    else
      OS << TC.getRuntimeArchiveName() << " missing (looked in "
         << TC.describeRuntimeSearch() << ")\n";
  }
}

bool bsc::checkOutputModes(DiagnosticEngine &Diags, const OutputModes &M) {
  llvm::SmallVector<const char *, 4> Modes;
  if (M.SyntaxOnly)
    Modes.push_back("-fsyntax-only");
  if (M.Verify)
    Modes.push_back("--verify");
  if (M.CompileOnly)
    Modes.push_back("-c");
  if (M.AssembleOnly)
    Modes.push_back("-S");
  if (M.EmitHeader)
    Modes.push_back("--emit-header");
  if (M.Emit != EmitKind::Default)
    Modes.push_back("--emit");
  if (M.EmitLLVM)
    Modes.push_back("--emit-llvm");
  // --verify checks the diagnostics of a front-end run: -fsyntax-only with it
  // says the same thing twice.
  if (Modes.size() == 2 && M.SyntaxOnly && M.Verify)
    return true;
  if (Modes.size() > 1) {
    Diags.report(llvm::SMLoc(), diag::err_conflicting_options)
        << Modes[0] << Modes[1];
    return false;
  }
  return true;
}

EmitKind bsc::getEmitKind(const OutputModes &Modes) {
  return Modes.EmitLLVM ? EmitKind::LLVM : Modes.Emit;
}

OutputKind bsc::getOutputKind(const OutputModes &Modes) {
  EmitKind Emit = getEmitKind(Modes);
  if (Emit == EmitKind::LLVM)
    return OutputKind::LLVM;
  if (Emit == EmitKind::Asm || Modes.AssembleOnly)
    return OutputKind::Asm;
  if (Emit == EmitKind::Obj || Modes.CompileOnly)
    return OutputKind::Obj;
  if (Modes.EmitHeader)
    return OutputKind::Header;
  return OutputKind::Program;
}

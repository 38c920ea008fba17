//===- Compile.cpp - from a checked behavior to the file asked for --------===//
//
// The top-level command past the front end: the target machine, the checks
// that need it (a runtime for programs, DWARF support, the binding objects'
// instructions), code generation, then one writer per output kind. A
// program is an object in a temporary file linked with the runtime shim.
// Every early return prints the diagnostics so far (finishCompilation): the
// back end's fatal errors print them too (BackendErrorReporter).
//
//===----------------------------------------------------------------------===//
#include "bsc/Driver/Driver.h"
#include "bsc/CodeGen/CodeGen.h"
#include "bsc/CodeGen/EmitHeader.h"
#include "bsc/Debug/Values.h"
#include "bsc/Parse/Lexer.h"
#include "bsc/Bind/Bind.h"
#include "bsc/Sema/CallGraph.h"
#include "llvm/ADT/ScopeExit.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/IR/LLVMContext.h"
#include "llvm/IR/Module.h"
#include "llvm/Support/ErrorHandling.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Program.h"
#include "llvm/Support/raw_ostream.h"

using namespace bsc;

int bsc::emitFrontendStage(Compilation &C, const FrontendOptions &Opts,
                           EmitKind Stage, llvm::StringRef OutputFile) {
  switch (Stage) {
  case EmitKind::Tokens:
    if (Opts.Inputs.empty())
      C.Diags.report(llvm::SMLoc(), diag::err_no_input_files);
    for (const std::string &Path : Opts.Inputs)
      if (unsigned ID = addSourceFile(C, Path))
        dumpTokens(C.SM, ID, C.Diags, llvm::outs());
    break;
  case EmitKind::AST:
  case EmitKind::TypedAST:
    if (Stage == EmitKind::AST)
      loadModules(C, Opts);
    else
      runFrontend(C, Opts);
    for (ModuleAST *M : C.Modules)
      dumpAST(*M, llvm::outs());
    break;
  case EmitKind::Graph: {
    // Nothing when the behavior has errors.
    if (!runFrontend(C, Opts))
      break;
    auto Out = openOutput(C.Diags, OutputFile.empty() ? "-" : OutputFile, true);
    if (!Out)
      break;
    writeCallGraphDOT(C.Checked, C.SM, Out->os());
    Out->keep();
    break;
  }
  case EmitKind::Default:
  case EmitKind::LLVM:
  case EmitKind::Asm:
  case EmitKind::Obj:
    llvm_unreachable("not a front-end stage");
  }
  return finishCompilation(C);
}

bool bsc::linkProgram(DiagnosticEngine &Diags, const ToolChain &TC,
                      llvm::StringRef Object, llvm::StringRef Output,
                      llvm::ArrayRef<std::string> BindObjects) {
  std::optional<std::string> Runtime = TC.findRuntime();
  if (!Runtime) {
    Diags.report(llvm::SMLoc(), diag::err_runtime_missing)
        << TC.getRuntimeArchiveName() << TC.describeRuntimeSearch();
    return false;
  }
  std::optional<Command> Link =
      TC.getLinkCommand(Object, BindObjects, *Runtime, Output);
  if (!Link) {
    Diags.report(llvm::SMLoc(), diag::err_no_linker)
        << TC.getTriple().str() << "neither 'cc' nor 'clang-19' is on PATH";
    return false;
  }
  llvm::SmallVector<llvm::StringRef, 8> ArgRefs(Link->Args.begin(),
                                                Link->Args.end());
  std::string ErrMsg;
  int RC = llvm::sys::ExecuteAndWait(Link->Program, ArgRefs, std::nullopt, {},
                                     0, 0, &ErrMsg);
  if (RC != 0) {
    Diags.report(llvm::SMLoc(), diag::err_link_failed)
        << Output << Link->Program << RC;
    return false;
  }
  return true;
}

bool bsc::checkBindingCPU(DiagnosticEngine &Diags,
                          const llvm::TargetMachine &TM,
                          llvm::ArrayRef<std::string> BindObjects) {
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
    Diags.report(llvm::SMLoc(), diag::err_bind_cpu_lacks)
        << Path << Found->Function << Found->Instruction
        << TM.getTargetCPU().str() << More;
    OK = false;
  }
  return OK;
}

namespace {
/// One compile(): the options, the machine and what code generation made.
struct CompileJob {
  Compilation &C;
  const CompileOptions &Opts;
  const FrontendOptions &FOpts;
  const BackendOptions &BOpts;
  const OutputKind Kind;
  const ToolChain &TC;
  llvm::LLVMContext &Ctx;
  std::unique_ptr<llvm::TargetMachine> TM;
  CodeGenOptions CGOpts;
  BehaviorLayout Layout;
  std::unique_ptr<llvm::Module> M;

  CompileJob(Compilation &C, const CompileOptions &Opts,
             const FrontendOptions &FOpts, const BackendOptions &BOpts,
             const ToolChain &TC, llvm::LLVMContext &Ctx)
      : C(C), Opts(Opts), FOpts(FOpts), BOpts(BOpts),
        Kind(getOutputKind(Opts.Modes)), TC(TC), Ctx(Ctx) {}

  bool checkTarget();
  bool setUpCodeGen();
  std::string getOutputPath() const;
  bool writeText(bool Header);
  bool writeMachineCode(bool IsAsm);
  bool writeProgram();
};
} // namespace

static bool isIdentifier(llvm::StringRef S) {
  if (S.empty() || !(llvm::isAlpha(S[0]) || S[0] == '_'))
    return false;
  return llvm::all_of(S, [](char Ch) { return llvm::isAlnum(Ch) || Ch == '_'; });
}

/// What the machine decides: a runtime for programs, DWARF, and whether the
/// binding objects run on its CPU.
bool CompileJob::checkTarget() {
  const llvm::Triple &T = TM->getTargetTriple();
  if (Kind == OutputKind::Program && !TC.hasRuntime()) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_runtime_for_target) << T.str();
    return false;
  }
  if (Opts.DebugInfo && Kind != OutputKind::LLVM &&
      Kind != OutputKind::Header && !supportsDebugInfo(T)) {
    C.Diags.report(llvm::SMLoc(), diag::err_no_debug_info_for_target)
        << T.str();
    return false;
  }
  return checkBindingCPU(C.Diags, *TM, FOpts.BindObjects);
}

/// CodeGenOptions from the options; reports a bad one.
bool CompileJob::setUpCodeGen() {
  CGOpts.Instrument = Opts.Instrument;
  if (!parseCycleBudget(C.Diags, Opts.CycleBudget, CGOpts.CycleBudget) ||
      !parseAssertionMode(C.Diags, Opts.Assertions, CGOpts.Assertions))
    return false;
  CGOpts.NarrowX87Floats = usesX87Floats(*TM);
  CGOpts.DebugInfo = Opts.DebugInfo;
  CGOpts.Sources = &C.SM;
  CGOpts.OptLevel = BOpts.Target.OptLevel;
  if (!Opts.BehaviorName.empty()) {
    if (!isIdentifier(Opts.BehaviorName)) {
      C.Diags.report(llvm::SMLoc(), diag::err_bad_behavior_name)
          << Opts.BehaviorName;
      return false;
    }
    CGOpts.BehaviorName = Opts.BehaviorName;
  } else if (!C.Modules.empty()) {
    CGOpts.BehaviorName = C.Modules.front()->Name;
  } else {
    return false;
  }
  if (!Opts.Exports.empty()) {
    CGOpts.Exports = findExports(C, Opts.Exports);
    if (!CGOpts.Exports)
      return false;
  }
  if (Kind == OutputKind::Program) {
    CGOpts.ProgramEntry = findProgramEntry(C, Opts.EntryName);
    if (!CGOpts.ProgramEntry)
      return false;
    CGOpts.ProgramCycles = BOpts.Cycles;
  }
  if (Opts.FlightRecorder) {
    // Each exported entry's hash, and the entry a program's main calls
    // (which records into $BS_FLIGHT_LOG).
    CGOpts.FlightRecorder = true;
    std::vector<const CallableDecl *> Entries =
        CGOpts.Exports ? *CGOpts.Exports : findBehaviorRoots(C.Checked);
    if (CGOpts.ProgramEntry && !llvm::is_contained(Entries, CGOpts.ProgramEntry))
      Entries.push_back(CGOpts.ProgramEntry);
    for (const CallableDecl *D : Entries)
      CGOpts.FlightEntries.push_back(
          {D->getQualifiedName(), computeBehaviorHash(C, *D)});
  }
  return true;
}

std::string CompileJob::getOutputPath() const {
  if (!Opts.OutputFile.empty())
    return Opts.OutputFile;
  switch (Kind) {
  case OutputKind::LLVM:
  case OutputKind::Header:
    return "-";
  case OutputKind::Asm:
  case OutputKind::Obj:
    if (getEmitKind(Opts.Modes) != EmitKind::Default)
      return "-";
    return (llvm::sys::path::stem(FOpts.Inputs.front()) +
            (Kind == OutputKind::Asm ? ".s" : ".o"))
        .str();
  case OutputKind::Program:
    return "a.out";
  }
  llvm_unreachable("covered switch");
}

/// The C header or the IR.
bool CompileJob::writeText(bool Header) {
  std::string Path = getOutputPath();
  auto Out = openOutput(C.Diags, Path, true);
  if (!Out)
    return false;
  if (Header)
    writeBehaviorHeader(Layout, CGOpts.BehaviorName, TM->getTargetTriple(),
                        TM->createDataLayout(), Out->os());
  else
    M->print(Out->os(), nullptr);
  Out->keep();
  return writeDepFile(C, Opts.DepFile, Path, FOpts.BindObjects);
}

bool CompileJob::writeMachineCode(bool IsAsm) {
  std::string Path = getOutputPath();
  auto Out = openOutput(C.Diags, Path, IsAsm);
  if (!Out)
    return false;
  if (!emitMachineCode(*M, *TM,
                       IsAsm ? llvm::CodeGenFileType::AssemblyFile
                             : llvm::CodeGenFileType::ObjectFile,
                       Out->os(), C.Diags))
    return false;
  Out->keep();
  return writeDepFile(C, Opts.DepFile, Path, FOpts.BindObjects);
}

bool CompileJob::writeProgram() {
  std::string Path = getOutputPath();
  // Check the output before the work of linking, and so that the error
  // names the file rather than coming from the linker.
  if (!openOutput(C.Diags, Path, false))
    return false;
  int FD;
  llvm::SmallString<128> ObjPath;
  if (std::error_code EC = llvm::sys::fs::createTemporaryFile(
          "bsc-" + CGOpts.BehaviorName, "o", FD, ObjPath)) {
    C.Diags.report(llvm::SMLoc(), diag::err_cannot_write_output)
        << "a temporary object file" << EC.message();
    return false;
  }
  auto RemoveObj =
      llvm::make_scope_exit([&] { llvm::sys::fs::remove(ObjPath); });
  {
    llvm::raw_fd_ostream ObjOS(FD, /*shouldClose=*/true);
    if (!emitMachineCode(*M, *TM, llvm::CodeGenFileType::ObjectFile, ObjOS,
                         C.Diags))
      return false;
  }
  if (!bind::checkBindingImports(
          C.Diags,
          bind::getBindingImports(C.Checked.BindingModules,
                                  getUndefinedSymbols(*M)),
          FOpts.BindObjects) ||
      !linkProgram(C.Diags, TC, ObjPath, Path, FOpts.BindObjects)) {
    llvm::sys::fs::remove(Path);
    return false;
  }
  return writeDepFile(C, Opts.DepFile, Path, FOpts.BindObjects);
}

/// Generates code for the checked behavior and writes the output.
static int generateCode(Compilation &C, const FrontendOptions &FOpts,
                        const CompileOptions &Opts, const BackendOptions &BOpts,
                        const ToolChain &TC) {
  // Back-end errors (and report_fatal_error, which some targets call as
  // early as creating the machine) become diagnostics and exit status 1.
  llvm::LLVMContext Ctx;
  BackendErrorReporter Reporter(Ctx, C.Diags, BOpts.Target.Triple.str(),
                                [&] { finishCompilation(C); });
  CompileJob Job(C, Opts, FOpts, BOpts, TC, Ctx);
  Job.TM = createTargetMachine(BOpts.Target, C.Diags);
  if (!Job.TM || !Job.checkTarget() || !Job.setUpCodeGen())
    return finishCompilation(C);

  Job.M = emitLLVM(C.Checked, Ctx, Job.TM->getTargetTriple(),
                   Job.TM->createDataLayout(), Job.CGOpts, Job.Layout);
  if (llvm::Error E = verifyGeneratedModule(*Job.M))
    return finishWithInternalError(C, std::move(E));
  if (Job.CGOpts.Instrument)
    defineDebugTables(*Job.M, Job.Layout,
                      debug::toJSONString(debug::toJSON(debug::buildDebugTables(
                          C.Checked, Job.Layout, C.SM))));
  if (Job.Kind == OutputKind::Header) {
    Job.writeText(/*Header=*/true);
    return finishCompilation(C);
  }

  optimizeModule(*Job.M, Job.TM.get(), BOpts.Target.OptLevel);
  switch (Job.Kind) {
  case OutputKind::LLVM:
    Job.writeText(/*Header=*/false);
    break;
  case OutputKind::Asm:
  case OutputKind::Obj:
    Job.writeMachineCode(Job.Kind == OutputKind::Asm);
    break;
  case OutputKind::Program:
    Job.writeProgram();
    break;
  case OutputKind::Header:
    break;
  }
  return finishCompilation(C);
}

int bsc::compile(Compilation &C, const FrontendOptions &FOpts,
                 const CompileOptions &Opts, const ToolChain &TC) {
  const OutputModes &Modes = Opts.Modes;
  if (!checkOutputModes(C.Diags, Modes))
    return finishCompilation(C, Modes.Verify);
  switch (EmitKind Stage = getEmitKind(Modes)) {
  case EmitKind::Tokens:
  case EmitKind::AST:
  case EmitKind::TypedAST:
  case EmitKind::Graph:
    return emitFrontendStage(C, FOpts, Stage, Opts.OutputFile);
  case EmitKind::Default:
  case EmitKind::LLVM:
  case EmitKind::Asm:
  case EmitKind::Obj:
    break;
  }
  BackendOptions BOpts;
  bool OptionsOK = parseBackendOptions(C.Diags, Opts.Backend, BOpts);
  if (!runFrontend(C, FOpts) || !OptionsOK || Modes.SyntaxOnly || Modes.Verify)
    return finishCompilation(C, Modes.Verify);
  return generateCode(C, FOpts, Opts, BOpts, TC);
}

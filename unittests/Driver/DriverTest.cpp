//===- DriverTest.cpp - option values, output modes, the dependency file --===//
#include "bsc/Driver/Driver.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

std::vector<std::string> messages(const DiagnosticEngine &Diags) {
  std::vector<std::string> Result;
  for (const Diagnostic &D : Diags.getDiagnostics())
    Result.push_back(D.Message);
  return Result;
}

TEST(DepFileTest, OneRuleWithEveryInputOnItsOwnLine) {
  std::string S;
  llvm::raw_string_ostream OS(S);
  writeDependencies(OS, "out/b.o", {"/src/B.bs", "/src/Motion.bs", "bind.o"});
  EXPECT_EQ(OS.str(), "out/b.o: \\\n  /src/B.bs \\\n  /src/Motion.bs \\\n"
                      "  bind.o\n");
}

TEST(DepFileTest, EscapesAsMakeReadsNames) {
  std::string S;
  llvm::raw_string_ostream OS(S);
  writeDependencies(OS, "my out.o", {"a#1.bs", "cost$.bs"});
  EXPECT_EQ(OS.str(), "my\\ out.o: \\\n  a\\#1.bs \\\n  cost$$.bs\n");
}

TEST(DepFileTest, NoInputs) {
  std::string S;
  llvm::raw_string_ostream OS(S);
  writeDependencies(OS, "b.o", {});
  EXPECT_EQ(OS.str(), "b.o:\n");
}

TEST(DepFileTest, PathIsMFElseTheOutputsWithD) {
  EXPECT_EQ(getDepFilePath({true, ""}, "out/b.o"), "out/b.d");
  EXPECT_EQ(getDepFilePath({true, ""}, "robot"), "robot.d");
  EXPECT_EQ(getDepFilePath({true, "deps/x.d"}, "b.o"), "deps/x.d");
  EXPECT_EQ(getDepFilePath({true, "x.d"}, "-"), "x.d");
  // Standard output has no name to derive one from.
  EXPECT_EQ(getDepFilePath({true, ""}, "-"), std::nullopt);
}

TEST(DepFileTest, WritesTheFileOnlyWithMD) {
  llvm::SmallString<128> Dir;
  ASSERT_FALSE(llvm::sys::fs::createUniqueDirectory("bsc-depfile", Dir));
  std::string Out = (Dir + "/b.o").str(), Dep = (Dir + "/b.d").str();
  Compilation C;
  EXPECT_TRUE(writeDepFile(C, {false, ""}, Out, {"bind.o"}));
  EXPECT_FALSE(llvm::sys::fs::exists(Dep));
  EXPECT_TRUE(writeDepFile(C, {true, ""}, Out, {"bind.o"}));
  auto Text = llvm::MemoryBuffer::getFile(Dep);
  ASSERT_TRUE(bool(Text));
  EXPECT_EQ((*Text)->getBuffer(), Out + ": \\\n  bind.o\n");
  EXPECT_FALSE(C.Diags.hasErrors());
  llvm::sys::fs::remove_directories(Dir);
}

TEST(DepFileTest, StandardOutputNeedsMF) {
  Compilation C;
  EXPECT_FALSE(writeDepFile(C, {true, ""}, "-", {}));
  ASSERT_EQ(C.Diags.getDiagnostics().size(), 1u);
  EXPECT_EQ(C.Diags.getDiagnostics()[0].Kind, diag::err_depfile_needs_path);
}

TEST(OptionsTest, BackendValues) {
  DiagnosticEngine Diags;
  BackendOptions Out;
  BackendArgs Args;
  Args.Target = "i586";
  Args.OptLevel = "2";
  Args.Cycles = "30";
  EXPECT_TRUE(parseBackendOptions(Diags, Args, Out));
  EXPECT_EQ(Out.Target.OptLevel, 2u);
  EXPECT_EQ(Out.Cycles, 30u);
  EXPECT_EQ(Out.Target.Triple.str(), "i586-unknown-linux-gnu");
  EXPECT_EQ(Out.Target.Spelling, "i586");
  Args.OptLevel = "4";
  Args.Cycles = std::to_string(MaxCycles + 1);
  EXPECT_FALSE(parseBackendOptions(Diags, Args, Out));
  // Both are reported, -O first.
  auto M = messages(Diags);
  ASSERT_EQ(M.size(), 2u);
  EXPECT_NE(M[0].find("-O"), std::string::npos);
  EXPECT_NE(M[1].find("--cycles"), std::string::npos);
}

TEST(OptionsTest, CycleBudgetTraceAndLimit) {
  DiagnosticEngine Diags;
  uint32_t Passes = 7;
  EXPECT_TRUE(parseCycleBudget(Diags, std::nullopt, Passes));
  EXPECT_EQ(Passes, 0u);
  EXPECT_TRUE(parseCycleBudget(Diags, std::string("20000"), Passes));
  EXPECT_EQ(Passes, 20000u);
  EXPECT_FALSE(parseCycleBudget(Diags, std::string("0"), Passes));
  EXPECT_FALSE(parseCycleBudget(Diags, std::string("4294967296"), Passes));
  debug::TraceMode Mode;
  std::string Task;
  EXPECT_TRUE(parseTraceMode(Diags, std::nullopt, Mode, Task));
  EXPECT_EQ(Mode, debug::TraceMode::Off);
  EXPECT_TRUE(parseTraceMode(Diags, std::string(""), Mode, Task));
  EXPECT_EQ(Mode, debug::TraceMode::EveryCycle);
  EXPECT_TRUE(parseTraceMode(Diags, std::string("changes"), Mode, Task));
  EXPECT_EQ(Mode, debug::TraceMode::Changes);
  EXPECT_TRUE(Task.empty());
  // A name is a task's subtree (the runner checks the behavior has it).
  EXPECT_TRUE(parseTraceMode(Diags, std::string("Head::look"), Mode, Task));
  EXPECT_EQ(Mode, debug::TraceMode::Changes);
  EXPECT_EQ(Task, "Head::look");
  EXPECT_FALSE(parseTraceMode(Diags, std::string("no-name"), Mode, Task));
  unsigned Ms;
  EXPECT_TRUE(parseCycleLimit(Diags, "0", Ms));
  EXPECT_TRUE(parseCycleLimit(Diags, std::to_string(MaxCycleLimitMs), Ms));
  EXPECT_FALSE(parseCycleLimit(Diags, std::to_string(MaxCycleLimitMs + 1), Ms));
  EXPECT_EQ(Diags.getNumErrors(), 4u);
}

TEST(OptionsTest, WarningGroups) {
  DiagnosticEngine Diags;
  EXPECT_TRUE(applyWarningOptions(Diags, {"error"}));
  EXPECT_FALSE(applyWarningOptions(Diags, {"no-such-group"}));
  EXPECT_FALSE(applyWarningOptions(Diags, {"error=no-such-group"}));
  EXPECT_EQ(Diags.getNumErrors(), 2u);
}

TEST(OptionsTest, OutputModes) {
  DiagnosticEngine Diags;
  OutputModes M;
  EXPECT_EQ(getOutputKind(M), OutputKind::Program);
  M.CompileOnly = true;
  EXPECT_EQ(getOutputKind(M), OutputKind::Obj);
  EXPECT_TRUE(checkOutputModes(Diags, M));
  M.AssembleOnly = true;
  EXPECT_FALSE(checkOutputModes(Diags, M));
  M = OutputModes();
  M.EmitLLVM = true;
  EXPECT_EQ(getEmitKind(M), EmitKind::LLVM);
  EXPECT_EQ(getOutputKind(M), OutputKind::LLVM);
  M = OutputModes();
  M.Emit = EmitKind::Asm;
  EXPECT_EQ(getOutputKind(M), OutputKind::Asm);
  M = OutputModes();
  M.EmitHeader = true;
  EXPECT_EQ(getOutputKind(M), OutputKind::Header);
  // --verify checks a front-end run: with -fsyntax-only it is no conflict.
  M = OutputModes();
  M.SyntaxOnly = M.Verify = true;
  EXPECT_TRUE(checkOutputModes(Diags, M));
  EXPECT_EQ(Diags.getNumErrors(), 1u);
}

} // namespace

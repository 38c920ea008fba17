//===- FrontendTest.cpp - reading files, requires, --verify ---------------===//
#include "bsc/Frontend/Frontend.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/MemoryBuffer.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "gtest/gtest.h"

using namespace bsc;

namespace {

/// A fresh folder of .bs files, removed at the end of the test.
class TempDir {
public:
  TempDir() { llvm::sys::fs::createUniqueDirectory("bsc-frontend", Path); }
  ~TempDir() { llvm::sys::fs::remove_directories(Path); }
  std::string write(llvm::StringRef Name, llvm::StringRef Text) {
    llvm::SmallString<128> File(Path);
    llvm::sys::path::append(File, Name);
    std::error_code EC;
    llvm::raw_fd_ostream OS(File, EC);
    OS << Text;
    return std::string(File);
  }
  std::string path() const { return std::string(Path); }

private:
  llvm::SmallString<128> Path;
};

/// Options whose standard modules are the built host runtime's (CMake
/// passes its path), as the driver sets them for the host.
FrontendOptions hostOptions() {
  FrontendOptions O;
  O.StandardModules = {BSC_HOST_RUNTIME};
  return O;
}

std::vector<std::string> messages(const Compilation &C) {
  std::vector<std::string> Result;
  for (const Diagnostic &D : C.Diags.getDiagnostics())
    Result.push_back(D.Message);
  return Result;
}

TEST(FrontendTest, ModuleNameIsFileNameWithoutExtension) {
  EXPECT_EQ(moduleNameForPath("/a/b/Motion.bs"), "Motion");
  EXPECT_EQ(moduleNameForPath("fib.bs"), "fib");
  EXPECT_EQ(moduleNameForPath("dir/noext"), "noext");
}

TEST(FrontendTest, MissingFileAndDirectoryAreReported) {
  TempDir Dir;
  Compilation C;
  EXPECT_EQ(addSourceFile(C, Dir.path() + "/nope.bs"), 0u);
  EXPECT_EQ(addSourceFile(C, Dir.path()), 0u);
  auto M = messages(C);
  ASSERT_EQ(M.size(), 2u);
  EXPECT_NE(M[0].find("cannot open"), std::string::npos);
  EXPECT_NE(M[1].find("is a directory"), std::string::npos);
}

TEST(FrontendTest, RejectsFileNamesThatAreNotIdentifiers) {
  TempDir Dir;
  Compilation C;
  FrontendOptions O;
  O.Inputs = {Dir.write("my-behavior.bs", "func f()\n    return\n")};
  EXPECT_FALSE(loadModules(C, O));
  ASSERT_EQ(messages(C).size(), 1u);
  EXPECT_EQ(messages(C)[0], "module name 'my-behavior' (from file '" +
                                O.Inputs[0] + "') is not an identifier");
}

TEST(FrontendTest, ResolvesScriptNativeUnknownAndCyclicRequires) {
  TempDir Dir;
  Dir.write("B.bs", "requires \"A\"\nfunc g()\n    return\n");
  Compilation C;
  FrontendOptions O = hostOptions();
  O.Inputs = {Dir.write("A.bs", "requires \"B\"\nrequires \"io\"\n"
                                "requires \"Nowhere\"\nfunc f()\n    return\n")};
  EXPECT_FALSE(loadModules(C, O)); // Nowhere is unknown.
  ASSERT_EQ(C.Modules.size(), 2u);
  ModuleAST &A = *C.Modules[0];
  ASSERT_EQ(A.Requires.size(), 3u);
  EXPECT_EQ(A.Requires[0].Script, C.Modules[1]);
  EXPECT_NE(A.Requires[1].Native, nullptr);
  EXPECT_EQ(A.Requires[2].Script, nullptr);
  EXPECT_EQ(A.Requires[2].Native, nullptr);
  // The cycle A -> B -> A is fine: B's require binds to the loaded A.
  EXPECT_EQ(C.Modules[1]->Requires[0].Script, &A);
  auto M = messages(C);
  ASSERT_EQ(M.size(), 1u);
  EXPECT_NE(M[0].find("no module named 'Nowhere'"), std::string::npos);
}

TEST(FrontendTest, SearchesIncludeDirsAfterTheRequiringFolder) {
  TempDir Main, Lib;
  Lib.write("Util.bs", "func u()\n    return\n");
  Compilation C;
  FrontendOptions O;
  O.Inputs = {Main.write("M.bs", "requires \"Util\"\nfunc f()\n    Util::u()\n")};
  O.IncludeDirs = {Lib.path()};
  EXPECT_TRUE(loadModules(C, O)) << (messages(C).empty() ? "" : messages(C)[0]);
  ASSERT_EQ(C.Modules.size(), 2u);
  EXPECT_EQ(C.Modules[1]->Name, "Util");
}

TEST(FrontendTest, SelfAndDuplicateRequires) {
  TempDir Dir;
  Compilation C;
  FrontendOptions O = hostOptions();
  O.Inputs = {Dir.write("S.bs", "requires \"io\"\nrequires \"io\"\n"
                                "requires \"S\"\nfunc f()\n    return\n")};
  EXPECT_FALSE(loadModules(C, O));
  auto M = messages(C);
  ASSERT_EQ(M.size(), 2u);
  EXPECT_EQ(M[0], "module 'io' is required more than once");
  EXPECT_EQ(M[1], "module 'S' requires itself");
}

/// `io` is an ordinary binding module in each runtime archive: read for the
/// archive's target, its functions have the C functions' signatures (bool
/// for printb, whose C function takes int32_t) and are called through
/// Bind.h thunks.
TEST(FrontendTest, StandardModulesComeFromTheRuntimeArchive) {
  const std::pair<const char *, const char *> Runtimes[] = {
      {"x86_64-unknown-linux-gnu", BSC_HOST_RUNTIME},
      {"i586-unknown-linux-gnu", BSC_I586_RUNTIME}};
  for (const auto &[Triple, Archive] : Runtimes) {
    SCOPED_TRACE(Triple);
    Compilation C;
    FrontendOptions O;
    O.Target = llvm::Triple(Triple);
    O.StandardModules = {Archive};
    ASSERT_TRUE(readBindingObjects(C, O))
        << (messages(C).empty() ? "" : messages(C)[0]);
    const NativeModule *IO = C.Natives.find("io");
    ASSERT_NE(IO, nullptr);
    EXPECT_EQ(IO->File, std::string(Archive) + "(io_module.cpp.o)");
    EXPECT_EQ(IO->Classes.size(), 0u);
    const std::pair<const char *, NativeType::Code> Want[] = {
        {"printi", NativeType::Int},
        {"printf", NativeType::Float},
        {"printb", NativeType::Bool},
        {"prints", NativeType::String}};
    ASSERT_EQ(IO->Functions.size(), 4u);
    for (const auto &[Name, Param] : Want) {
      const NativeFunction *F = IO->findFunction(Name);
      ASSERT_NE(F, nullptr) << Name;
      EXPECT_EQ(F->Kind, NativeFunction::Function);
      ASSERT_EQ(F->Params.size(), 1u);
      EXPECT_EQ(F->Params[0].TheCode, Param) << Name;
      EXPECT_EQ(F->Result.TheCode, NativeType::Void);
      EXPECT_TRUE(llvm::StringRef(F->Symbol).starts_with("_ZN2bs6detail8CallImpl"))
          << F->Symbol;
    }
    EXPECT_NE(IO->findFunction("printi")->Symbol.find("bs_io_printi"),
              std::string::npos);
  }
}

TEST(FrontendTest, MissingStandardModulesAreReported) {
  Compilation C;
  FrontendOptions O;
  O.MissingRuntime = {"libbscript_rt.a", "'/a/lib/bscript', '/a/lib'"};
  EXPECT_FALSE(readBindingObjects(C, O));
  EXPECT_EQ(messages(C),
            std::vector<std::string>{
                "runtime library 'libbscript_rt.a' not found (looked in "
                "'/a/lib/bscript', '/a/lib'); point --runtime-dir or "
                "BSCRIPT_RUNTIME_DIR at the folder that holds it"});
  EXPECT_EQ(C.Natives.find("io"), nullptr);
}

/// A buffer named t.bs holding `Text`, and a diagnostic at line `Line`.
struct VerifyFixture {
  llvm::SourceMgr SM;
  std::vector<Diagnostic> Diags;
  explicit VerifyFixture(llvm::StringRef Text) {
    SM.AddNewSourceBuffer(llvm::MemoryBuffer::getMemBufferCopy(Text, "t.bs"),
                          llvm::SMLoc());
  }
  void diag(unsigned Line, Severity S, std::string Message) {
    llvm::StringRef Text = SM.getMemoryBuffer(1)->getBuffer();
    const char *P = Text.data();
    for (unsigned L = 1; L < Line; ++L)
      P = strchr(P, '\n') + 1;
    Diags.push_back({diag::err_undeclared_name, S,
                     llvm::SMLoc::getFromPointer(P), std::move(Message), {},
                     {}});
  }
  bool verify(std::string &Out) {
    llvm::raw_string_ostream OS(Out);
    return verifyDiagnostics(SM, Diags, OS);
  }
};

TEST(VerifyTest, MatchesBySeverityLineAndSubstring) {
  VerifyFixture F("x  # expected-error {{undeclared name 'x'}}\n"
                  "# expected-warning@+1 {{never}}\n"
                  "y\n");
  F.diag(1, Severity::Error, "use of undeclared name 'x'");
  F.diag(3, Severity::Warning, "code is never executed");
  std::string Out;
  EXPECT_TRUE(F.verify(Out)) << Out;
  EXPECT_EQ(Out, "");
}

TEST(VerifyTest, ReportsMissingAndUnexpectedDiagnostics) {
  VerifyFixture F("x  # expected-error {{undeclared}}\ny\n");
  F.diag(2, Severity::Error, "use of undeclared name 'y'");
  std::string Out;
  EXPECT_FALSE(F.verify(Out));
  EXPECT_EQ(Out, "error: 'error' diagnostics expected but not seen:\n"
                 "  File t.bs Line 1: undeclared\n"
                 "error: 'error' diagnostics seen but not expected:\n"
                 "  File t.bs Line 2: use of undeclared name 'y'\n");
}

TEST(VerifyTest, SeverityMustMatchAndEachExpectationIsUsedOnce) {
  VerifyFixture F("x  # expected-warning {{a}}\n");
  F.diag(1, Severity::Error, "a");
  F.diag(1, Severity::Warning, "a");
  F.diag(1, Severity::Warning, "a");
  std::string Out;
  EXPECT_FALSE(F.verify(Out));
  EXPECT_NE(Out.find("'error' diagnostics seen but not expected"),
            std::string::npos);
  EXPECT_NE(Out.find("'warning' diagnostics seen but not expected"),
            std::string::npos);
}

TEST(VerifyTest, MalformedExpectationsFail) {
  VerifyFixture F("# expected-error {{no end\n# expected-bogus {{x}}\n"
                  "# expected-error@-5 {{x}}\n");
  std::string Out;
  EXPECT_FALSE(F.verify(Out));
  EXPECT_NE(Out.find("expected '}}'"), std::string::npos);
  EXPECT_NE(Out.find("unknown kind"), std::string::npos);
  EXPECT_NE(Out.find("points before the first line"), std::string::npos);
}

} // namespace

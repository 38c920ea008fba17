//===- ToolChainTest.cpp - the target policy bsc and bsread share ---------===//
#include "bsc/Driver/ToolChain.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/raw_ostream.h"
#include "llvm/TargetParser/Host.h"
#include "gtest/gtest.h"
#include <cstdlib>

using namespace bsc;

namespace {

/// A fresh folder, removed at the end of the test.
class TempDir {
public:
  TempDir() { llvm::sys::fs::createUniqueDirectory("bsc-driver", Path); }
  ~TempDir() { llvm::sys::fs::remove_directories(Path); }
  std::string touch(llvm::StringRef Name) {
    llvm::SmallString<128> File(Path);
    llvm::sys::path::append(File, Name);
    std::error_code EC;
    llvm::raw_fd_ostream OS(File, EC);
    return std::string(File);
  }
  std::string path() const { return std::string(Path); }

private:
  llvm::SmallString<128> Path;
};

/// Sets an environment variable for one test and restores it.
class ScopedEnv {
public:
  ScopedEnv(const char *Name, const char *Value) : Name(Name) {
    if (const char *Old = std::getenv(Name))
      Saved = Old;
    if (Value)
      setenv(Name, Value, 1);
    else
      unsetenv(Name);
  }
  ~ScopedEnv() {
    if (Saved)
      setenv(Name, Saved->c_str(), 1);
    else
      unsetenv(Name);
  }

private:
  const char *Name;
  std::optional<std::string> Saved;
};

TEST(ToolChainTest, TheDefaultTargetIsTheProcessTriple) {
  // One host for the compiler, --version, bsread and the JIT: the triple
  // the host runtime is built for, not LLVM's configured default.
  llvm::Triple Host(llvm::sys::getProcessTriple());
  EXPECT_EQ(getHostTriple(), Host);
  EXPECT_EQ(resolveTargetTriple(""), Host);
  EXPECT_TRUE(ToolChain(resolveTargetTriple(""), {}).hasRuntime());
}

TEST(ToolChainTest, TargetSpellings) {
  EXPECT_EQ(resolveTargetTriple("i586").str(), "i586-unknown-linux-gnu");
  EXPECT_EQ(resolveTargetTriple("x86_64").str(), "x86_64-unknown-linux-gnu");
  EXPECT_EQ(resolveTargetTriple("aarch64-linux-gnu").str(),
            "aarch64-unknown-linux-gnu");
}

TEST(ToolChainTest, RuntimesForThe32BitRobotAndTheHostOnly) {
  ToolChain I586(resolveTargetTriple("i586"), {});
  EXPECT_TRUE(I586.hasRuntime());
  EXPECT_EQ(I586.getRuntimeArchiveName(), "libbscript_rt_i586.a");
  ToolChain Host(resolveTargetTriple(""), {});
  EXPECT_EQ(Host.getRuntimeArchiveName(), "libbscript_rt.a");
  // Not Linux, or not the host's architecture: objects, but no runtime.
  for (const char *T : {"x86_64-apple-darwin", "riscv64-unknown-linux-gnu",
                        "wasm32-unknown-unknown"}) {
    ToolChain TC(resolveTargetTriple(T), {});
    if (TC.getTriple().getArch() == getHostTriple().getArch() &&
        TC.getTriple().isOSLinux())
      continue;
    EXPECT_FALSE(TC.hasRuntime()) << T;
    EXPECT_EQ(TC.getRuntimeArchiveName(), "") << T;
    EXPECT_EQ(TC.findRuntime(), std::nullopt) << T;
  }
}

TEST(ToolChainTest, RuntimeSearchFolders) {
  EXPECT_EQ(getRuntimeSearchDirs("/rt", "/opt/bscript/bin/bsc"),
            std::vector<std::string>{"/rt"});
  EXPECT_EQ(getRuntimeSearchDirs("", "/opt/bscript/bin/bsc"),
            (std::vector<std::string>{"/opt/bscript/lib/bscript",
                                      "/opt/bscript/lib"}));
  ToolChain TC(resolveTargetTriple("i586"), {"/a", "/b"});
  EXPECT_EQ(TC.describeRuntimeSearch(), "'/a', '/b'");
}

TEST(ToolChainTest, FindsTheRuntimeInTheFirstFolderThatHasIt) {
  TempDir First, Second;
  std::string Archive = Second.touch("libbscript_rt_i586.a");
  ToolChain TC(resolveTargetTriple("i586"), {First.path(), Second.path()});
  EXPECT_EQ(TC.findRuntime(), Archive);
  ToolChain Host(resolveTargetTriple(""), {First.path(), Second.path()});
  EXPECT_EQ(Host.findRuntime(), std::nullopt);
}

TEST(ToolChainTest, RuntimeDirOptionThenEnvironmentThenExecutable) {
  ScopedEnv Env("BSCRIPT_RUNTIME_DIR", "/from-env");
  EXPECT_EQ(getToolChain("i586", "/from-option", "bsc").getRuntimeSearchDirs(),
            std::vector<std::string>{"/from-option"});
  EXPECT_EQ(getToolChain("i586", "", "bsc").getRuntimeSearchDirs(),
            std::vector<std::string>{"/from-env"});
  ScopedEnv NoEnv("BSCRIPT_RUNTIME_DIR", nullptr);
  std::vector<std::string> Dirs =
      getToolChain("", "", "bsc").getRuntimeSearchDirs();
  ASSERT_EQ(Dirs.size(), 2u);
  EXPECT_EQ(llvm::sys::path::filename(Dirs[0]), "bscript");
  EXPECT_EQ(llvm::sys::path::filename(Dirs[1]), "lib");
  EXPECT_EQ(getToolChain("", "", "bsc").getTriple(), getHostTriple());
}

TEST(ToolChainTest, LinkCommand) {
  ToolChain TC(resolveTargetTriple("i586"), {});
  std::optional<Command> Link =
      TC.getLinkCommand("b.o", {"bind.o"}, "/rt/libbscript_rt_i586.a", "prog");
  if (!Link)
    GTEST_SKIP() << "neither cc nor clang-19 is on PATH";
  std::vector<std::string> &A = Link->Args;
  // The 32-bit robot: cc -m32, or clang-19 for the triple.
  EXPECT_TRUE(llvm::is_contained(A, "-m32") ||
              llvm::is_contained(A, "--target=i586-unknown-linux-gnu"));
  // The object, the binding objects, then the runtime; C++ and libm for
  // the bindings' thunks; the output last.
  auto At = [&](llvm::StringRef S) {
    return std::find(A.begin(), A.end(), S) - A.begin();
  };
  EXPECT_LT(At("b.o"), At("bind.o"));
  EXPECT_LT(At("bind.o"), At("/rt/libbscript_rt_i586.a"));
  EXPECT_TRUE(llvm::is_contained(A, "-lstdc++"));
  EXPECT_EQ(A[A.size() - 2], "-o");
  EXPECT_EQ(A.back(), "prog");
  std::optional<Command> NoBind =
      TC.getLinkCommand("b.o", {}, "/rt/libbscript_rt_i586.a", "prog");
  ASSERT_TRUE(NoBind);
  EXPECT_FALSE(llvm::is_contained(NoBind->Args, "-lstdc++"));
}

} // namespace

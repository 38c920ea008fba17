//===- ToolChain.cpp - what bsc needs to know about a target --------------===//
#include "bsc/Driver/ToolChain.h"
#include "llvm/ADT/StringExtras.h"
#include "llvm/BinaryFormat/Magic.h"
#include "llvm/Support/FileSystem.h"
#include "llvm/TargetParser/Host.h"
#include "llvm/Support/Path.h"
#include "llvm/Support/Program.h"
#include <cstdlib>

using namespace bsc;

std::vector<std::string>
bsc::getRuntimeSearchDirs(llvm::StringRef Override,
                          llvm::StringRef Executable) {
  if (!Override.empty())
    return {Override.str()};
  llvm::SmallString<256> Prefix(Executable);
  llvm::sys::path::remove_filename(Prefix); // bin
  llvm::sys::path::remove_filename(Prefix); // the prefix or the build tree
  llvm::SmallString<256> Installed(Prefix), Built(Prefix);
  llvm::sys::path::append(Installed, "lib", "bscript");
  llvm::sys::path::append(Built, "lib");
  return {std::string(Installed), std::string(Built)};
}

ToolChain::ToolChain(llvm::Triple T, std::vector<std::string> RuntimeSearchDirs)
    : T(std::move(T)), SearchDirs(std::move(RuntimeSearchDirs)) {}

bool ToolChain::hasRuntime() const {
  llvm::Triple Host = getHostTriple();
  return (T.getArch() == llvm::Triple::x86 || T.getArch() == Host.getArch()) &&
         T.isOSLinux() && T.isOSBinFormatELF();
}

llvm::StringRef ToolChain::getRuntimeArchiveName() const {
  if (!hasRuntime())
    return "";
  return T.getArch() == llvm::Triple::x86 ? "libbscript_rt_i586.a"
                                          : "libbscript_rt.a";
}

std::optional<std::string> ToolChain::findRuntime() const {
  if (!hasRuntime())
    return std::nullopt;
  for (const std::string &Dir : SearchDirs) {
    llvm::SmallString<256> Path(Dir);
    llvm::sys::path::append(Path, getRuntimeArchiveName());
    if (llvm::sys::fs::exists(Path))
      return std::string(Path);
  }
  return std::nullopt;
}

std::string ToolChain::describeRuntimeSearch() const {
  std::string S;
  llvm::ListSeparator Sep(", ");
  for (const std::string &Dir : SearchDirs)
    S += (llvm::Twine(Sep) + "'" + Dir + "'").str();
  return S;
}

std::optional<Command>
ToolChain::getLinkCommand(llvm::StringRef Object,
                          llvm::ArrayRef<std::string> BindObjects,
                          llvm::StringRef Runtime,
                          llvm::StringRef Output) const {
  Command C;
  if (auto CC = llvm::sys::findProgramByName("cc")) {
    C.Program = *CC;
    C.Args = {"cc"};
    if (T.getArch() == llvm::Triple::x86)
      C.Args.push_back("-m32");
  } else if (auto Clang = llvm::sys::findProgramByName("clang-19")) {
    C.Program = *Clang;
    C.Args = {"clang-19", "--target=" + T.str(), "-fuse-ld=lld"};
  } else {
    return std::nullopt;
  }
  C.Args.push_back(Object.str());
  for (const std::string &Bind : BindObjects) {
    llvm::file_magic Magic;
    if (llvm::identify_magic(Bind, Magic) ||
        Magic != llvm::file_magic::elf_shared_object) {
      C.Args.push_back(Bind);
      continue;
    }
    // A shared library: by absolute path, and its directory as the
    // program's run path, so that the program runs from any directory.
    llvm::SmallString<256> Abs(Bind);
    llvm::sys::fs::make_absolute(Abs);
    llvm::sys::path::remove_dots(Abs, /*remove_dot_dot=*/true);
    C.Args.push_back(std::string(Abs));
    C.Args.push_back("-Wl,-rpath," + llvm::sys::path::parent_path(Abs).str());
  }
  C.Args.push_back(Runtime.str());
  // The binding objects' thunks need the C++ runtime and libm (the
  // runtime's own io thunks need neither).
  if (!BindObjects.empty())
    C.Args.insert(C.Args.end(), {"-lstdc++", "-lm"});
  C.Args.insert(C.Args.end(), {"-o", Output.str()});
  return C;
}

ToolChain bsc::getToolChain(llvm::StringRef Name, llvm::StringRef RuntimeDir,
                            const char *Argv0) {
  std::string Override = RuntimeDir.str();
  if (const char *Env = std::getenv("BSCRIPT_RUNTIME_DIR");
      Override.empty() && Env)
    Override = Env;
  std::string Exe =
      llvm::sys::fs::getMainExecutable(Argv0, (void *)&bsc::getToolChain);
  return ToolChain(resolveTargetTriple(Name),
                   getRuntimeSearchDirs(Override, Exe));
}

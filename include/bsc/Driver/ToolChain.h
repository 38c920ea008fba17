//===- ToolChain.h - what bsc needs to know about a target -----*- C++ -*-===//
//
// The one place of target policy outside the code generator (as clang's
// ToolChain): how a `-target` spelling becomes a triple (its function,
// resolveTargetTriple, sits in Basic/TargetName.h for bsread), which runtime
// shim a target has (and with it the standard module `io` and standalone
// programs), where an installed or built bsc finds that runtime, and how a
// program is linked. The code generator's own target facts (the default
// CPU, which back ends can write objects) stay in CodeGen/Target.h.
//
// The runtimes are built for two targets: 32-bit x86 Linux (the robot, as
// i586) and the host. Every other triple gets objects, assembly and IR but
// no `io` and no programs.
//
// The default target is the host, and the host is one triple everywhere:
// the process's own (getHostTriple). That is what the host runtime is
// built for and what `bsc run`'s JIT executes, so `bsc` without -target,
// `bsc --dump-bindings`, `bsread` and `bsc --version` all name it. LLVM's
// configured default triple (sys::getDefaultTargetTriple) is not used: on
// an LLVM configured as a cross compiler it names another machine, and
// then bsc would compile for a target it has no runtime for while its JIT
// ran another. Both tools build their ToolChain with getToolChain.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_DRIVER_TOOLCHAIN_H
#define BSC_DRIVER_TOOLCHAIN_H

#include "bsc/Basic/TargetName.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/TargetParser/Triple.h"
#include <optional>
#include <string>
#include <vector>

namespace bsc {

/// Where the runtime archives are looked for: the folder given with
/// --runtime-dir or $BSCRIPT_RUNTIME_DIR if any, else beside bsc's own
/// executable: `<bin>/../lib/bscript` (an installation) and `<bin>/../lib`
/// (the build tree), in that order.
std::vector<std::string> getRuntimeSearchDirs(llvm::StringRef Override,
                                              llvm::StringRef Executable);

/// A program to run with its arguments (Args[0] is the program's name).
struct Command {
  std::string Program;
  std::vector<std::string> Args;
};

class ToolChain {
public:
  ToolChain(llvm::Triple T, std::vector<std::string> RuntimeSearchDirs);

  const llvm::Triple &getTriple() const { return T; }
  /// Whether bsc ships a runtime for the target (32-bit x86 Linux, or the
  /// host's architecture on Linux): only then does it have the standard
  /// modules and standalone programs.
  bool hasRuntime() const;
  /// The runtime archive's file name (libbscript_rt_i586.a for 32-bit
  /// x86, libbscript_rt.a for the host); empty without a runtime.
  llvm::StringRef getRuntimeArchiveName() const;
  /// The runtime archive in the first search folder that has it.
  std::optional<std::string> findRuntime() const;
  /// The search folders quoted and joined, for "looked in ...".
  std::string describeRuntimeSearch() const;
  const std::vector<std::string> &getRuntimeSearchDirs() const {
    return SearchDirs;
  }
  /// The command that links `Object`, the binding objects and `Runtime`
  /// into the program `Output`: the system's `cc` (with -m32 for 32-bit
  /// x86), else clang-19 with lld. std::nullopt if neither is on PATH.
  std::optional<Command> getLinkCommand(llvm::StringRef Object,
                                        llvm::ArrayRef<std::string> BindObjects,
                                        llvm::StringRef Runtime,
                                        llvm::StringRef Output) const;

private:
  llvm::Triple T;
  std::vector<std::string> SearchDirs;
};

/// The toolchain of `-target Name` (the host for the empty name) with the
/// runtime search folders of the running tool: `RuntimeDir` (--runtime-dir)
/// if given, else $BSCRIPT_RUNTIME_DIR if set, else beside the executable
/// started as `Argv0`. bsc and bsread both take their target from here.
ToolChain getToolChain(llvm::StringRef Name, llvm::StringRef RuntimeDir,
                       const char *Argv0);

} // namespace bsc

#endif

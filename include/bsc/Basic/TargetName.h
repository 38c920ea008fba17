//===- TargetName.h - the triple a `-target` spelling stands for -*- C++ -*-===//
//
// The spelling of targets, below everything that needs it: the driver's
// ToolChain (Driver/ToolChain.h, the rest of the target policy), and
// `bsread`, which reads binding objects for a target and links nothing
// else. The host is one triple everywhere, the process's own
// (ToolChain.h says why not LLVM's configured default).
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BASIC_TARGETNAME_H
#define BSC_BASIC_TARGETNAME_H

#include "llvm/ADT/StringRef.h"
#include "llvm/TargetParser/Triple.h"

namespace bsc {

/// The host: the triple of the running process (sys::getProcessTriple), the
/// one the host runtime is built for and the JIT runs.
llvm::Triple getHostTriple();

/// The triple `-target Name` stands for: "i586" is i586-unknown-linux-gnu,
/// "x86_64" is x86_64-unknown-linux-gnu, the empty string is the host, and
/// anything else is normalised as an LLVM triple. Does not check that LLVM
/// supports it (createTargetMachine does).
llvm::Triple resolveTargetTriple(llvm::StringRef Name);

} // namespace bsc

#endif

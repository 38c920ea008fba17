//===- EmitHeader.h - bsc --emit-header -------------------------*- C++ -*-===//
//
// The typed C face of one compiled behavior for one target: the size and
// alignment of its state, a state type with exactly that size and alignment,
// the info struct and the entries with C types, and small inline wrappers.
// It is generated rather than written by hand because the state size is a
// property of the target (i586 has 4-byte pointers) and of the program.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_CODEGEN_EMITHEADER_H
#define BSC_CODEGEN_EMITHEADER_H

#include "bsc/CodeGen/CodeGen.h"
#include "llvm/Support/raw_ostream.h"

namespace bsc {

/// Writes the header of behavior `Name` compiled for `T` with layout `L`.
void writeBehaviorHeader(const BehaviorLayout &L, llvm::StringRef Name,
                         const llvm::Triple &T, const llvm::DataLayout &DL,
                         llvm::raw_ostream &OS);

} // namespace bsc

#endif

//===- ELFChecks.h - refuse damaged section headers before reading -*- C++ -*-===//
//
// llvm::object's ELFObjectFile trusts the section headers: its relocation
// iterators divide by sh_entsize, its symbol iterators run to sh_size
// divided by the entry size without looking at the file size, and several
// accessors end the process with "LLVM ERROR" when an entry cannot be
// read. The binding reader, the symbol check of the driver and (through
// the reader, which runs first) the JIT all walk symbols and relocations
// with them, so every file they read goes through this check first: with
// ELFFile's bounds-checked accessors, every table those iterators reach
// must be inside the file, hold whole entries of the right size and point
// at sections that exist and have the right type. After it, no walk can
// fault, abort or run more iterations than the file has bytes.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_LIB_BIND_ELFCHECKS_H
#define BSC_LIB_BIND_ELFCHECKS_H

#include "llvm/Object/ELFObjectFile.h"
#include "llvm/Support/Error.h"

namespace bsc {
namespace bind {

/// The first problem with the section or program headers of `Obj` that
/// would make ELFObjectFile's walks fault, abort or spin, as a ProblemError
/// of kind err_bind_damaged, or success.
llvm::Error checkSectionHeaders(const llvm::object::ELFObjectFileBase &Obj);

} // namespace bind
} // namespace bsc

#endif

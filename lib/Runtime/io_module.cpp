//===- io_module.cpp - the standard module `io`, registered with Bind.h ---===//
//
// `io` is an ordinary binding module: bsc reads this descriptor from the
// runtime archive of the compilation's target exactly as it reads a --bind
// object, and generated code calls the thunks below, never io.c directly.
// The functions themselves stay plain C in io.c, so a robot without stdout
// replaces io.c and keeps this file.
//
// Built for the host and for i586 without exceptions and RTTI; the thunks
// need nothing from libstdc++, so C programs link the runtime with `cc`.
//
//===----------------------------------------------------------------------===//
#include "bscript/Bind.h"
#include "bscript/bscript.h"

namespace bs::io {
/// b-script's bool: the C function takes it as int32_t.
inline void printb(bool Value) noexcept { bs_io_printb(Value); }
} // namespace bs::io

BS_MODULE(io,
  registerFunction<&bs_io_printi>(module, "printi", "bs_io_printi");
  registerFunction<&bs_io_printf>(module, "printf", "bs_io_printf");
  registerFunction<&bs::io::printb>(module, "printb", "bs_io_printb");
  registerFunction<&bs_io_prints>(module, "prints", "bs_io_prints");
)

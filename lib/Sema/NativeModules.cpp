//===- NativeModules.cpp - the native modules that ship with bsc ----------===//
//
// Only `io` today: the paper's Fig. 1a prints with `io::printi`, and the
// siblings for the other scalar types make test programs easy to write. The
// symbols are plain C functions of lib/Runtime, so the description below is
// all the front end needs; binding modules read with --bind will produce
// the same description from an object file.
//
//===----------------------------------------------------------------------===//
#include "bsc/AST/Native.h"

using namespace bsc;

NativeRegistry bsc::makeBuiltinNativeRegistry() {
  NativeRegistry R;
  auto IO = std::make_unique<NativeModule>();
  IO->Name = "io";
  struct {
    const char *Name;
    NativeType::Code Param;
  } Prints[] = {{"printi", NativeType::Int},
                {"printf", NativeType::Float},
                {"printb", NativeType::Bool},
                {"prints", NativeType::String}};
  for (const auto &P : Prints) {
    NativeFunction F;
    F.Name = P.Name;
    F.Symbol = std::string("bs_io_") + P.Name;
    NativeType Param;
    Param.TheCode = P.Param;
    F.Params.push_back(Param);
    F.Result.TheCode = NativeType::Void;
    IO->Functions.push_back(std::move(F));
  }
  R.Modules.push_back(std::move(IO));
  return R;
}

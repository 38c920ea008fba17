//===- Native.h - what native (C/C++-registered) modules provide -*- C++ -*-===//
//
// A native module is registered from C/C++ rather than written in b-script:
// the built-in `io` today, binding objects read with --bind later. Sema only
// sees this description, so where it came from (built in, or read from an
// ELF binding object) does not matter to the front end.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_NATIVE_H
#define BSC_AST_NATIVE_H

#include <cstdint>
#include <memory>
#include <string>
#include <vector>

namespace bsc {

/// A type as a native signature spells it: a scalar, or a registered enum or
/// class named by its b-script name (`Module::Name`).
struct NativeType {
  enum Code { Void, Bool, Int, Float, String, Enum, Class };
  Code TheCode = Void;
  std::string Name; ///< Qualified b-script name for Enum and Class.
};

struct NativeFunction {
  std::string Name;   ///< b-script name inside its module (`printi`).
  std::string Symbol; ///< Symbol the generated code calls (plain C ABI).
  std::vector<NativeType> Params;
  NativeType Result;
};

struct NativeEnum {
  struct Value {
    std::string Name;
    int32_t Number;
  };
  std::string Name; ///< Unqualified name inside its module (`MotionType`).
  std::vector<Value> Values;
};

struct NativeModule {
  std::string Name;
  std::vector<NativeFunction> Functions;
  std::vector<NativeEnum> Enums;

  const NativeFunction *findFunction(const std::string &N) const {
    for (const NativeFunction &F : Functions)
      if (F.Name == N)
        return &F;
    return nullptr;
  }
  const NativeEnum *findEnum(const std::string &N) const {
    for (const NativeEnum &E : Enums)
      if (E.Name == N)
        return &E;
    return nullptr;
  }
};

/// The native modules one compilation can `require`.
struct NativeRegistry {
  std::vector<std::unique_ptr<NativeModule>> Modules;

  const NativeModule *find(const std::string &Name) const {
    for (const auto &M : Modules)
      if (M->Name == Name)
        return M.get();
    return nullptr;
  }
};

/// The registry of the native modules that ship with bsc (today: `io`).
NativeRegistry makeBuiltinNativeRegistry();

} // namespace bsc

#endif

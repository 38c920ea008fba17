//===- Native.h - what native (C/C++-registered) modules provide -*- C++ -*-===//
//
// A native module is registered from C++ with bscript/Bind.h rather than
// written in b-script: the standard `io` (read from the runtime archive) and
// the modules of the binding objects given with --bind. lib/Bind reads them
// and converts its BindingModel into this form (bind::addToNativeRegistry).
// Sema and CodeGen only see this description, so where a module came from
// does not matter to them, and the AST library does not depend on the ELF
// reader.
//
// Why a description of its own rather than the BindingModel itself: the
// front end wants resolved pointers (a parameter's class, a member's owner)
// where the reader's model has module/index pairs, and unit tests build
// small registries by hand. The conversion keeps everything the back end needs
// (thunk symbols, field offsets, sizes, alignments, life-cycle thunks), so
// CodeGen never has to go back to the BindingModel.
//
// Pointers between the records (NativeType::Class, NativeClass::Module, ...)
// point into the NativeModules of one NativeRegistry, which owns its modules
// through unique_ptrs: they stay valid as long as the registry lives and the
// modules' vectors are not changed after conversion.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_AST_NATIVE_H
#define BSC_AST_NATIVE_H

#include "llvm/ADT/StringRef.h"
#include <cstdint>
#include <memory>
#include <optional>
#include <string>
#include <vector>

namespace bsc {

struct NativeClass;
struct NativeEnum;
struct NativeModule;

/// A type as a native signature spells it: a scalar, or a registered enum or
/// class named by its b-script name (`Module::Name`).
struct NativeType {
  enum Code { Void, Bool, Int, Float, String, Enum, Class };
  Code TheCode = Void;
  std::string Name; ///< Qualified b-script name for Enum and Class.
  /// Enum and Class types of binding modules: the registered entity. Null
  /// for a hand-made description that only names it (then Sema looks the
  /// enum up by Name among the required modules).
  const NativeEnum *TheEnum = nullptr;
  const NativeClass *TheClass = nullptr;
  /// A class parameter declared as a non-const `T&`: the callee may modify
  /// the argument (the thunk gets `T *`). By value and `const T&` both
  /// travel as `const T *`.
  bool MutableRef = false;
  /// sizeof the C++ type on the target (a `double` field keeps its 8
  /// bytes while its b-script type is float); 0 when not known (a
  /// hand-made description).
  uint32_t StorageSize = 0;
  /// An unsigned integer, or an enum with an unsigned underlying type: a
  /// storage narrower than int is zero-extended when read, not
  /// sign-extended (`uint8_t` 250 reads as 250).
  bool Unsigned = false;
  /// An array field (`float m[3][3]`): its extents, outermost first; the
  /// rest describes one element (StorageSize is the element's). Only
  /// fields are arrays.
  std::vector<uint32_t> Extents;

  bool isArray() const { return !Extents.empty(); }
};

/// A default argument restated with `.defaults(...)`: scalars and enums
/// only. Bool and enum parameters use Int.
struct NativeDefault {
  bool IsFloat = false;
  int32_t Int = 0;
  float Float = 0;
};

/// One registered member: a module function (the only kind `io` has), or a
/// field, property, method or class-scope function of a registered class.
/// The thunk shapes are those of bindings.md ("The descriptor"):
///   Function/Method: wire(R) Symbol([T *self,] wire(A)...), or
///                    void Symbol(R *out, [T *self,] wire(A)...) when
///                    ResultViaOut;
///   Field/Property:  the getter Symbol(const T *self) as above, and
///                    void Setter(T *self, wire(R) value).
struct NativeFunction {
  enum MemberKind { Function, Method, Field, Property };
  MemberKind Kind = Function;
  std::string Name;    ///< b-script name (`printi`, `abs`, `_plus_`, `x`).
  std::string Symbol;  ///< Call or getter symbol (plain C ABI).
  std::string Setter;  ///< Fields and properties: setter; empty if read-only.
  /// Fields: the offset in the owner (the back end may access the field
  /// directly instead of calling the getter).
  std::optional<uint64_t> FieldOffset;
  std::vector<NativeType> Params; ///< Without the object of a method.
  /// The registered names of Params (`{"v", "min", "max"}`), for messages;
  /// empty, or "" for each parameter, when the registration gives none.
  std::vector<std::string> ParamNames;
  /// Defaults of the last Defaults.size() parameters, in order.
  std::vector<NativeDefault> Defaults;
  NativeType Result; ///< Fields and properties: their type.
  /// Methods, fields, properties and class-scope functions: the class.
  const NativeClass *Owner = nullptr;
  bool ConstSelf = false;    ///< The method does not modify its object.
  bool ReadOnly = false;     ///< A field or property without setter.
  bool ResultViaOut = false; ///< Class result through `R *out`.
  /// The thunk's first argument after the object is the state
  /// (`bs::Context &`): generated code passes it, the script does not.
  bool TakesContext = false;
  /// Registered `.pure()`: the result depends on the arguments alone and
  /// the call changes nothing, so a re-run calls it again instead of
  /// taking it from a record (bsc/JIT/Boundary.h).
  bool Pure = false;

  /// Methods, fields and properties take the object; functions do not.
  bool hasSelf() const { return Kind != Function; }
  bool isData() const { return Kind == Field || Kind == Property; }
  /// The number of leading parameters that have no default.
  size_t getMinArgs() const { return Params.size() - Defaults.size(); }
};

/// A registered member that b-script cannot call, and why (an out
/// parameter): Sema reports the reason instead of "no member".
struct UnusableMember {
  std::string Name;
  std::string Reason;
};

/// The member named `N` of `List`, or null.
inline const UnusableMember *
findUnusable(const std::vector<UnusableMember> &List, llvm::StringRef N) {
  for (const UnusableMember &U : List)
    if (U.Name == N)
      return &U;
  return nullptr;
}

/// A registered C++ class: a value type of b-script.
struct NativeClass {
  std::string Name;          ///< Inside its module (`Vector2f`).
  std::string QualifiedName; ///< `Math::Vector2f`.
  std::string CppName;       ///< As registered, for messages; may be empty.
  const NativeModule *Module = nullptr;
  uint64_t Size = 0, Align = 1; ///< On the compilation's target.
  bool DefaultConstructible = false;
  bool TriviallyDestructible = false;
  /// Values may be copied with memcpy instead of the Copy/Assign thunks.
  bool CopiesAsBytes = false;
  /// Life-cycle thunks (empty when C++ lacks the operation):
  /// void construct(T *), copy(T *dst, const T *src),
  /// assign(T *dst, const T *src), destroy(T *).
  std::string Construct, Copy, Assign, Destroy;
  std::vector<NativeFunction> Members;
  /// `.ctor<A...>()`: functions (Kind Function, Owner this class) that
  /// return a value of this class.
  std::vector<NativeFunction> Constructors;
  std::vector<UnusableMember> Unusable;

  const NativeFunction *findMember(llvm::StringRef N) const {
    for (const NativeFunction &M : Members)
      if (M.Name == N)
        return &M;
    return nullptr;
  }
};

struct NativeEnum {
  struct Value {
    std::string Name;
    int32_t Number;
  };
  std::string Name; ///< Unqualified name inside its module (`MotionType`).
  std::vector<Value> Values;
  const NativeModule *Module = nullptr; ///< Set for binding modules.
};

/// `registerConstant(module, "off", 10000)`: a value known when bsc reads
/// the binding, used as a script's own constants are.
struct NativeConstant {
  std::string Name;
  NativeType Type; ///< Int, Float, Bool or Enum.
  int32_t Int = 0; ///< Int, Bool (0/1) and Enum.
  float Float = 0;
};

struct NativeModule {
  std::string Name;
  std::vector<NativeFunction> Functions;
  std::vector<NativeConstant> Constants;
  std::vector<NativeEnum> Enums;
  std::vector<NativeClass> Classes;
  /// Module functions b-script cannot call.
  std::vector<UnusableMember> Unusable;
  /// The types of `input` and `output`, if this module declares them (it is
  /// then the world module: its names are visible unqualified everywhere).
  const NativeClass *Input = nullptr;
  const NativeClass *Output = nullptr;
  std::string File; ///< The binding object it came from.
  /// Where it is registered (BS_MODULE's file and line), if known.
  std::string PlaceFile;
  unsigned PlaceLine = 0;
  uint64_t Hash = 0; ///< bs::moduleHash of the descriptor (bindings.md).
  /// Shipped in the runtime archive (`io`): it goes with the runtime bsc
  /// links, so the behavior neither records its hash nor looks for its
  /// thunks among the --bind objects.
  bool Standard = false;

  const NativeConstant *findConstant(llvm::StringRef N) const {
    for (const NativeConstant &C : Constants)
      if (C.Name == N)
        return &C;
    return nullptr;
  }
  const NativeFunction *findFunction(llvm::StringRef N) const {
    for (const NativeFunction &F : Functions)
      if (F.Name == N)
        return &F;
    return nullptr;
  }
  const NativeEnum *findEnum(llvm::StringRef N) const {
    for (const NativeEnum &E : Enums)
      if (E.Name == N)
        return &E;
    return nullptr;
  }
  const NativeClass *findClass(llvm::StringRef N) const {
    for (const NativeClass &C : Classes)
      if (C.Name == N)
        return &C;
    return nullptr;
  }
  bool isWorld() const { return Input || Output; }
};

/// The native modules one compilation can `require`.
struct NativeRegistry {
  std::vector<std::unique_ptr<NativeModule>> Modules;

  const NativeModule *find(llvm::StringRef Name) const {
    for (const auto &M : Modules)
      if (M->Name == Name)
        return M.get();
    return nullptr;
  }
  /// The module declaring `input`/`output`, or null (lib/Bind allows one).
  const NativeModule *getWorld() const {
    for (const auto &M : Modules)
      if (M->isWorld())
        return M.get();
    return nullptr;
  }
};

} // namespace bsc

#endif

//===- Bind.h - what compiled binding objects register ---------*- C++ -*-===//
//
// Robot code registers C++ types and functions with bscript/Bind.h; each
// BS_MODULE becomes one constexpr descriptor `bs_module_<Name>` in section
// `bs_modules` of the compiled binding object. This library reads those
// descriptors back from ELF relocatable objects, archives and shared
// libraries (following the relocations, or a library's dynamic relocations,
// to the symbols of type keys and thunks) and hands the rest of
// bsc a plain model: modules, classes with their target size and alignment,
// members with their thunk symbols, field offsets and signatures, enums, and
// the declared `input` and `output` types.
//
// Why read the object instead of an interface file: the object is what gets
// linked, so the sizes, offsets and symbol names bsc compiles against are
// exactly the ones of the code it will call (bindings.md "How bsc finds
// modules"). The model never holds host pointers into the object.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_BIND_BIND_H
#define BSC_BIND_BIND_H

#include "bsc/Basic/Diagnostic.h"
#include "bscript/descriptor.h"
#include "llvm/ADT/ArrayRef.h"
#include "llvm/ADT/StringRef.h"
#include "llvm/Support/Error.h"
#include "llvm/Support/MemoryBufferRef.h"
#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace llvm {
class raw_ostream;
class Triple;
} // namespace llvm

namespace bsc {
struct NativeRegistry;
struct NativeModule;

namespace bind {

/// The descriptor version this reader understands (bscript/descriptor.h).
constexpr uint32_t SupportedVersion = BS_DESCRIPTOR_VERSION;

/// How a value travels through a thunk (bindings.md "Thunks"): Bool, Int and
/// Enum as i32, Float as float, String as `const char *`, Class as a pointer.
/// The values are the descriptor's codes (bs_type_code).
enum class TypeCode : uint8_t {
  Void = BS_CODE_VOID,
  Bool = BS_CODE_BOOL,
  Int = BS_CODE_INT,
  Float = BS_CODE_FLOAT,
  String = BS_CODE_STRING,
  Enum = BS_CODE_ENUM,
  Class = BS_CODE_CLASS,
  Context = BS_CODE_CONTEXT ///< The first parameter only: the state.
};

/// Flags of a BoundType (bs::detail::TypeFlag).
enum TypeFlags : unsigned {
  TF_Const = BS_TYPE_CONST,       ///< const-qualified (const T&, or a const field)
  TF_Ref = BS_TYPE_REF,           ///< declared as a C++ reference
  TF_Unsigned = BS_TYPE_UNSIGNED, ///< unsigned integer, or enum with unsigned storage
  TF_Pointer = BS_TYPE_POINTER,   ///< travels as a pointer: classes; int&/float&/bool& out
};

/// A parameter, result or field type.
struct BoundType {
  TypeCode Code = TypeCode::Void;
  unsigned Flags = 0;
  uint32_t StorageSize = 0; ///< sizeof the C++ type on the target.
  /// Enum and Class: the symbol of bs::TypeKey<T>::id, and after resolution
  /// the registering module and the index of the class or enum in it.
  std::string Key;
  int Module = -1;
  int Index = -1;
  /// An array field (`float m[3][3]`): its extents, outermost first; the
  /// rest of the type describes one element.
  std::vector<uint32_t> Extents;

  bool isArray() const { return !Extents.empty(); }
  bool isScalar() const {
    return Code != TypeCode::Enum && Code != TypeCode::Class &&
           Code != TypeCode::Context;
  }
  /// A non-const scalar reference parameter (int&, float&, bool&): the
  /// argument is a pointer to storage of StorageSize bytes. Classes and the
  /// context travel as pointers too, and are not out-parameters.
  bool isOutPointer() const {
    return Code != TypeCode::Class && Code != TypeCode::Context &&
           (Flags & TF_Pointer);
  }
};

enum class DefaultKind : uint8_t { None, Int, Float };

struct BoundParam {
  BoundType Type;
  std::string Name; ///< Usually empty: C++ parameter names are not visible.
  DefaultKind Default = DefaultKind::None;
  int32_t DefaultInt = 0;
  float DefaultFloat = 0;
};

enum class MemberKind : uint8_t {
  Field = BS_KIND_FIELD,
  Property = BS_KIND_PROPERTY,
  Method = BS_KIND_METHOD,
  Function = BS_KIND_FUNCTION,
  Constructor = BS_KIND_CONSTRUCTOR, ///< `.ctor<A...>()`: a Function of the
                                     ///< class's scope returning the class.
  Constant = BS_KIND_CONSTANT        ///< registerConstant: Value, no thunk.
};

/// Flags of a BoundMember (bs::detail::MemberFlag).
enum MemberFlags : unsigned {
  MF_ConstSelf = BS_MEMBER_CONST_SELF, ///< Does not modify the object.
  MF_ReadOnly = BS_MEMBER_READ_ONLY,   ///< Field or property without setter.
  MF_ResultOut = BS_MEMBER_RESULT_OUT, ///< Class result: the thunk's first parameter is `R *out`.
  MF_Pure = BS_MEMBER_PURE,           ///< `.pure()`: no effects.
};

/// A field, property, method or function. The thunk shapes:
///   Method/Function: wire(R) Thunk([T *self,] wire(A)...)
///                    or void Thunk(R *out, [T *self,] wire(A)...)
///   Field/Property:  wire(R) Thunk(const T *self) or void Thunk(R *out,
///                    const T *self); void Setter(T *self, wire(R) value)
///                    with a class value passed as `const R *`.
struct BoundMember {
  MemberKind Kind = MemberKind::Function;
  std::string Name;    ///< b-script name.
  std::string CppName; ///< For messages; may be empty.
  std::string Thunk;   ///< Call or getter thunk symbol.
  std::string Setter;  ///< Setter thunk symbol; empty if read-only.
  std::optional<uint64_t> FieldOffset; ///< Fields: offset in the class.
  BoundType Result;                    ///< Fields/properties: their type.
  unsigned Flags = 0;
  std::vector<BoundParam> Params;
  /// Constants: the value (an int, enum or bool; a float's bits).
  uint32_t Value = 0;

  bool isConstSelf() const { return Flags & MF_ConstSelf; }
  bool isReadOnly() const { return Flags & MF_ReadOnly; }
  bool resultViaOut() const { return Flags & MF_ResultOut; }
  bool isPure() const { return Flags & MF_Pure; }
  /// Methods, fields and properties take the object; functions,
  /// constructors and constants do not.
  bool hasSelf() const {
    return Kind == MemberKind::Field || Kind == MemberKind::Property ||
           Kind == MemberKind::Method;
  }
};

/// Flags of a BoundClass (bs::detail::ClassFlag).
enum ClassFlags : unsigned {
  CF_TriviallyCopyable = BS_CLASS_TRIVIALLY_COPYABLE,
  CF_TriviallyDestructible = BS_CLASS_TRIVIALLY_DESTRUCTIBLE,
  CF_DefaultConstructible = BS_CLASS_DEFAULT_CONSTRUCTIBLE,
  CF_CopyConstructible = BS_CLASS_COPY_CONSTRUCTIBLE,
  CF_CopyAssignable = BS_CLASS_COPY_ASSIGNABLE,
  CF_StandardLayout = BS_CLASS_STANDARD_LAYOUT,
  CF_CopyAsBytes = BS_CLASS_COPY_AS_BYTES, ///< The registration allows memcpy copies.
};

struct BoundClass {
  std::string Name;    ///< b-script name inside its module.
  std::string CppName; ///< As registered; may be empty.
  std::string Key;     ///< bs::TypeKey<T>::id symbol.
  uint64_t Size = 0, Align = 1;
  unsigned Flags = 0;
  /// Life-cycle thunks (empty when C++ lacks the operation):
  /// void construct(T *), copy(T *dst, const T *src),
  /// assign(T *dst, const T *src), destroy(T *).
  std::string Construct, Copy, Assign, Destroy;
  std::vector<BoundMember> Members; ///< Fields, properties, methods and
                                    ///< functions in the class's scope.

  /// bsc may copy values with memcpy instead of calling Copy/Assign.
  bool copiesAsBytes() const {
    return Flags & (CF_TriviallyCopyable | CF_CopyAsBytes);
  }
  const BoundMember *findMember(llvm::StringRef N) const;
};

struct BoundEnum {
  struct Value {
    std::string Name;
    int32_t Number;
  };
  std::string Name, CppName, Key;
  uint32_t Size = 4;
  bool Scoped = false, Signed = true;
  std::vector<Value> Values;
};

struct BoundModule {
  std::string Name;
  std::string File;   ///< "x.o" or "lib.a(x.o)".
  /// Where BS_MODULE is in the C++ source (its __FILE__, as the compiler
  /// was given it, and line); empty from an older Bind.h.
  std::string PlaceFile;
  unsigned PlaceLine = 0;
  std::string Symbol; ///< bs_module_<Name>.
  uint32_t Version = 0;
  std::vector<BoundClass> Classes;
  std::vector<BoundMember> Functions; ///< Module-level functions.
  std::vector<BoundMember> Constants; ///< registerConstant.
  std::vector<BoundEnum> Enums;
  int InputClass = -1;  ///< Index in Classes of the type of `input`.
  int OutputClass = -1; ///< Index in Classes of the type of `output`.
  /// bs::moduleHash of the descriptor: changes when a size, an offset or a
  /// signature changes, even if no symbol name does.
  uint64_t Hash = 0;

  const BoundClass *findClass(llvm::StringRef N) const;
  const BoundEnum *findEnum(llvm::StringRef N) const;
  const BoundMember *findFunction(llvm::StringRef N) const;
};

/// Everything the binding objects of one compilation register.
struct BindingModel {
  unsigned PointerSize = 0;
  std::vector<BoundModule> Modules;

  const BoundModule *findModule(llvm::StringRef N) const;
  /// The module declaring `input`/`output` (its names are visible
  /// unqualified in scripts), or null.
  const BoundModule *getWorldModule() const;
  const BoundClass *getClass(const BoundType &T) const;
  const BoundEnum *getEnum(const BoundType &T) const;
  /// "Module::Name" of a resolved enum or class type.
  std::string getQualifiedName(const BoundType &T) const;
};

/// One problem with the binding objects: a kind of DiagnosticKinds.def and
/// its arguments, the first of which is the place (`file: Module::Class.m`).
struct BindProblem {
  diag::Kind Kind;
  std::vector<std::string> Args;
  /// The message, formatted from the diagnostics table.
  std::string format() const;
};

/// Every problem one readBindings call found, in the order of the files.
class BindingError : public llvm::ErrorInfo<BindingError> {
public:
  static char ID;
  explicit BindingError(std::vector<BindProblem> Problems)
      : Problems(std::move(Problems)) {}
  std::vector<BindProblem> Problems;
  /// One formatted message per line.
  void log(llvm::raw_ostream &OS) const override;
  std::error_code convertToErrorCode() const override {
    return llvm::inconvertibleErrorCode();
  }
};

/// Reads the binding objects or archives that will be linked into the
/// program for `Target` (bindings.md "How bsc finds modules") and resolves
/// every type across them. The error is a BindingError holding every
/// problem, each naming the file and the member path
/// (`Vector2f.dot param 0`).
llvm::Expected<BindingModel> readBindings(llvm::ArrayRef<std::string> Paths,
                                          const llvm::Triple &Target);

/// The same for buffers already in memory (tests); each buffer's
/// identifier is used as its file name.
llvm::Expected<BindingModel>
readBindingBuffers(llvm::ArrayRef<llvm::MemoryBufferRef> Buffers,
                   const llvm::Triple &Target);

/// Prints what the model registers, one line per entity (bsc
/// --dump-bindings).
void dumpBindings(const BindingModel &Model, llvm::raw_ostream &OS);

/// Why b-script cannot call a registered member (an `int&`, `float&` or
/// `bool&` out-parameter: b-script passes scalars by value), or "" if it
/// can. --dump-bindings lists such members as skipped, and Sema gives the
/// reason when a script uses one.
std::string getUnusableReason(const BoundMember &M);

/// Adds every module of `Model` to `Registry` in the Native.h form that
/// Sema and CodeGen read: classes with their members, module functions,
/// enums, and the `input`/`output` classes, with types resolved to
/// pointers. Returns the "Module::name" / "Module::Class.member" of the
/// members left out: those with `int&`, `float&` or `bool&` out
/// parameters, which b-script cannot pass.
std::vector<std::string> addToNativeRegistry(const BindingModel &Model,
                                             NativeRegistry &Registry);

/// The thunk and descriptor symbols of binding modules: what a behavior
/// compiled against them may import from the binding objects.
std::vector<std::string>
getBindingSymbols(llvm::ArrayRef<const NativeModule *> Modules);

/// Those of `Wanted` that no binding object or archive of `Paths` defines
/// (as a global or weak symbol), in the order of `Wanted`. A behavior that
/// imports one of them is stale against the bindings it is linked with.
/// Files that cannot be read are skipped (readBindings reports them).
std::vector<std::string>
findUndefinedSymbols(llvm::ArrayRef<std::string> Paths,
                     llvm::ArrayRef<std::string> Wanted);

/// Those of `Undefined` (the symbols a compiled behavior leaves undefined)
/// that are thunks or descriptors of `Modules`: what the behavior imports
/// from the binding objects.
std::vector<std::string>
getBindingImports(llvm::ArrayRef<const NativeModule *> Modules,
                  llvm::ArrayRef<std::string> Undefined);

/// Reports each of `Imports` (getBindingImports) that no file of `Paths`
/// defines: the behavior was compiled against a binding header newer than
/// its objects, and a linker or the JIT would fail on it with a bare
/// "undefined symbol". False if there is one.
bool checkBindingImports(DiagnosticEngine &Diags,
                         llvm::ArrayRef<std::string> Imports,
                         llvm::ArrayRef<std::string> Paths);

} // namespace bind
} // namespace bsc

#endif

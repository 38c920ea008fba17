//===- bscript/Bind.h - register C++ types and functions for b-script -----===//
//
// Robot code includes this header to make C++ types, functions and enums
// callable from compiled b-script:
//
//   BS_MODULE(Math,
//     registerClass<Eigen::Vector2f>(module, "Vector2f", "Eigen::Vector2f")
//       .prop<bs::mut(&Eigen::Vector2f::x)>("x")
//       .func<&Eigen::Vector2f::norm>("abs", "norm")
//       .func<&bs::op::plus<Eigen::Vector2f>>("_plus_", "operator+");
//     registerFunction<(float (*)(float))&std::fabs>(module, "fabs", "fabs");
//   )
//
// Why it is built this way (docs/bindings.md has the user's view):
//  - Nobody writes a signature twice. Every callable is a template argument,
//    so its C++ type gives the b-script signature, and the C++ compiler that
//    builds the bindings for the robot gives the target's sizes, alignments
//    and field offsets.
//  - No static initialisers. BS_MODULE evaluates its body twice at compile
//    time (count, then fill) and defines ONE constexpr object,
//    `extern "C" bs_module_<Name>`, in section `bs_modules`. bsc reads it
//    from the compiled object through the object's relocations; a program
//    can also walk it in-process via __start_bs_modules/__stop_bs_modules.
//  - bsc never implements the C++ ABI. Each registered member gets a thunk
//    with a plain C signature (a static member function of a class template,
//    noexcept); the descriptor points at a "holder" object that holds a
//    typed pointer to the thunk, because constexpr cannot turn a function
//    pointer into `const void *`.
//  - Type identity is the symbol name of `bs::TypeKey<T>::id`, identical in
//    every object and for every compiler.
//
// The descriptor layout is stated once, in bscript/descriptor.h, which bsc's
// reader and the runtime read it by; the structs in bs::detail::rec below
// write it, and static assertions pin each of their fields to it.
//
// Needs C++20 (lambdas and class-type values as template arguments, constexpr
// placement of records). No RTTI, no exceptions, no heap.
//
//===----------------------------------------------------------------------===//
#ifndef BSCRIPT_BIND_H
#define BSCRIPT_BIND_H

#if __cplusplus < 202002L
#error "bscript/Bind.h needs C++20: compile the bindings with -std=c++20"
#endif

#include "bscript.h"
#include "descriptor.h"

#include <cstddef>
#include <cstdint>
#include <new>
#include <type_traits>
#include <utility>

namespace bs {

/// The descriptor format version that this header writes.
inline constexpr std::uint32_t DescriptorVersion = BS_DESCRIPTOR_VERSION;

/// The identity of a registered C++ type: bsc knows a type by the symbol
/// name of its key. A mutable char, so that identical-code folding cannot
/// merge the keys of two types.
template <class T> struct TypeKey {
  static inline char id = 0;
};

class Module;

namespace detail {

using u32 = std::uint32_t;
using i32 = std::int32_t;

inline constexpr u32 None = BS_NO_INDEX;

// The codes and flags as descriptor.h states them.
/// Type codes of parameters, results and fields.
enum Code : u32 {
  CodeVoid = BS_CODE_VOID,
  CodeBool = BS_CODE_BOOL,
  CodeInt = BS_CODE_INT,
  CodeFloat = BS_CODE_FLOAT,
  CodeString = BS_CODE_STRING,
  CodeEnum = BS_CODE_ENUM,
  CodeClass = BS_CODE_CLASS,
  CodeContext = BS_CODE_CONTEXT,
};

/// Flags of a parameter or result type.
enum TypeFlag : u32 {
  TypeConst = BS_TYPE_CONST,
  TypeRef = BS_TYPE_REF,
  TypeUnsigned = BS_TYPE_UNSIGNED,
  TypePointer = BS_TYPE_POINTER,
};

enum MemberKind : u32 {
  KindField = BS_KIND_FIELD,
  KindProperty = BS_KIND_PROPERTY,
  KindMethod = BS_KIND_METHOD,
  KindFunction = BS_KIND_FUNCTION,
  KindConstructor = BS_KIND_CONSTRUCTOR,
  KindConstant = BS_KIND_CONSTANT,
};

/// Flags of a member.
enum MemberFlag : u32 {
  MemberConstSelf = BS_MEMBER_CONST_SELF,
  MemberReadOnly = BS_MEMBER_READ_ONLY,
  MemberResultOut = BS_MEMBER_RESULT_OUT,
};

/// Flags of a class.
enum ClassFlag : u32 {
  ClassTriviallyCopyable = BS_CLASS_TRIVIALLY_COPYABLE,
  ClassTriviallyDestructible = BS_CLASS_TRIVIALLY_DESTRUCTIBLE,
  ClassDefaultConstructible = BS_CLASS_DEFAULT_CONSTRUCTIBLE,
  ClassCopyConstructible = BS_CLASS_COPY_CONSTRUCTIBLE,
  ClassCopyAssignable = BS_CLASS_COPY_ASSIGNABLE,
  ClassStandardLayout = BS_CLASS_STANDARD_LAYOUT,
  ClassCopyAsBytes = BS_CLASS_COPY_AS_BYTES,
};

enum EnumFlag : u32 {
  EnumScoped = BS_ENUM_SCOPED,
  EnumSigned = BS_ENUM_SIGNED,
};

enum DefaultKind : u32 {
  DefaultNone = BS_DEFAULT_NONE,
  DefaultInt = BS_DEFAULT_INT,
  DefaultFloat = BS_DEFAULT_FLOAT,
};

namespace rec {
// The records of the descriptor. No record has internal padding on i386 or
// x86-64 (checked below), so the bytes of a descriptor are fully defined.

/// Offsets are relative to the start of the descriptor; string fields are
/// offsets into the string table, 0 being the empty string.
struct Header {
  char magic[8]; // "BSMOD\0\0\1"
  u32 version;
  u32 headerSize;
  u32 ptrSize;
  u32 name;
  u32 totalSize;
  u32 flags;       // none yet
  u32 inputClass;  // index of the class of `input`, or None
  u32 outputClass; // index of the class of `output`, or None
  u32 numClasses, classOffset, classSize;
  u32 numMembers, memberOffset, memberSize;
  u32 numParams, paramOffset, paramSize;
  u32 numEnums, enumOffset, enumSize;
  u32 numValues, valueOffset, valueSize;
  u32 stringOffset, stringSize;
  u32 reserved;
};

struct Class {
  const void *key;  // &TypeKey<T>::id
  const void *life; // holder of {construct, copy, assign, destroy}
  u32 name, cppName;
  u32 size, align;
  u32 flags; // ClassFlag
  u32 reserved;
};

struct Member {
  const void *thunk;     // holder of the call or getter thunk
  const void *thunk2;    // holder of the setter thunk, or null
  const void *memptr;    // fields: holder of the data member pointer
  const void *resultKey; // TypeKey of a class or enum result/field type
  u32 kind;              // MemberKind
  u32 owner;             // class index, or None for module functions
  u32 name, cppName;
  u32 resultCode, resultFlags, resultSize;
  u32 flags; // MemberFlag
  u32 firstParam, numParams;
  // Appended in descriptor version 1 (readers of shorter records read 0):
  u32 extent[4]; // an array field: its extents, outermost first, then 0s
  // Appended in descriptor version 2:
  u32 value; // a constant: its i32 value, or the bits of its float
  u32 reserved;
};

struct Param {
  const void *key; // TypeKey of a class or enum parameter
  u32 code, flags, size;
  u32 name;
  u32 defaultKind;
  i32 defaultInt;
  float defaultFloat;
  u32 reserved;
};

struct Enum {
  const void *key;
  u32 name, cppName;
  u32 size, flags;
  u32 firstValue, numValues;
};

struct Value {
  u32 name;
  i32 value;
};

// Every field where descriptor.h says it is: word W of a record with N
// pointers is at N * sizeof(void *) + 4 * W.
#define BS_AT_WORD(Rec, Field, Pointers, Word)                                 \
  static_assert(offsetof(Rec, Field) == (Pointers) * sizeof(void *) + 4 * (Word), \
                #Rec "::" #Field " is not where descriptor.h puts it")
#define BS_AT_POINTER(Rec, Field, Index)                                       \
  static_assert(offsetof(Rec, Field) == (Index) * sizeof(void *),             \
                #Rec "::" #Field " is not where descriptor.h puts it")
static_assert(sizeof(Header) == BS_DESCRIPTOR_HEADER_SIZE);
static_assert(offsetof(Header, version) == BS_HDR_VERSION &&
              offsetof(Header, headerSize) == BS_HDR_HEADER_SIZE &&
              offsetof(Header, ptrSize) == BS_HDR_PTR_SIZE &&
              offsetof(Header, name) == BS_HDR_NAME &&
              offsetof(Header, totalSize) == BS_HDR_TOTAL_SIZE &&
              offsetof(Header, flags) == BS_HDR_FLAGS &&
              offsetof(Header, inputClass) == BS_HDR_INPUT_CLASS &&
              offsetof(Header, outputClass) == BS_HDR_OUTPUT_CLASS &&
              offsetof(Header, numClasses) == BS_HDR_TABLE(BS_TABLE_CLASSES) &&
              offsetof(Header, numMembers) == BS_HDR_TABLE(BS_TABLE_MEMBERS) &&
              offsetof(Header, numParams) == BS_HDR_TABLE(BS_TABLE_PARAMS) &&
              offsetof(Header, numEnums) == BS_HDR_TABLE(BS_TABLE_ENUMS) &&
              offsetof(Header, numValues) == BS_HDR_TABLE(BS_TABLE_VALUES) &&
              offsetof(Header, stringOffset) == BS_HDR_STRING_OFFSET &&
              offsetof(Header, stringSize) == BS_HDR_STRING_SIZE,
              "the header is not as descriptor.h lays it out");
BS_AT_POINTER(Class, key, BS_CLASS_KEY);
BS_AT_POINTER(Class, life, BS_CLASS_LIFE);
BS_AT_WORD(Class, name, BS_CLASS_POINTERS, BS_CLASS_NAME);
BS_AT_WORD(Class, cppName, BS_CLASS_POINTERS, BS_CLASS_CPP_NAME);
BS_AT_WORD(Class, size, BS_CLASS_POINTERS, BS_CLASS_SIZE);
BS_AT_WORD(Class, align, BS_CLASS_POINTERS, BS_CLASS_ALIGN);
BS_AT_WORD(Class, flags, BS_CLASS_POINTERS, BS_CLASS_FLAGS);
static_assert(sizeof(Class) == BS_CLASS_POINTERS * sizeof(void *) + 4 * BS_CLASS_WORDS);
BS_AT_POINTER(Member, thunk, BS_MEMBER_THUNK);
BS_AT_POINTER(Member, thunk2, BS_MEMBER_SETTER);
BS_AT_POINTER(Member, memptr, BS_MEMBER_MEMPTR);
BS_AT_POINTER(Member, resultKey, BS_MEMBER_RESULT_KEY);
BS_AT_WORD(Member, kind, BS_MEMBER_POINTERS, BS_MEMBER_KIND);
BS_AT_WORD(Member, owner, BS_MEMBER_POINTERS, BS_MEMBER_OWNER);
BS_AT_WORD(Member, name, BS_MEMBER_POINTERS, BS_MEMBER_NAME);
BS_AT_WORD(Member, cppName, BS_MEMBER_POINTERS, BS_MEMBER_CPP_NAME);
BS_AT_WORD(Member, resultCode, BS_MEMBER_POINTERS, BS_MEMBER_RESULT_CODE);
BS_AT_WORD(Member, resultFlags, BS_MEMBER_POINTERS, BS_MEMBER_RESULT_FLAGS);
BS_AT_WORD(Member, resultSize, BS_MEMBER_POINTERS, BS_MEMBER_RESULT_SIZE);
BS_AT_WORD(Member, flags, BS_MEMBER_POINTERS, BS_MEMBER_FLAGS);
BS_AT_WORD(Member, firstParam, BS_MEMBER_POINTERS, BS_MEMBER_FIRST_PARAM);
BS_AT_WORD(Member, numParams, BS_MEMBER_POINTERS, BS_MEMBER_NUM_PARAMS);
BS_AT_WORD(Member, extent, BS_MEMBER_POINTERS, BS_MEMBER_EXTENT);
static_assert(sizeof(Member::extent) == 4 * BS_MEMBER_MAX_EXTENTS);
BS_AT_WORD(Member, value, BS_MEMBER_POINTERS, BS_MEMBER_VALUE);
static_assert(sizeof(Member) == BS_MEMBER_POINTERS * sizeof(void *) + 4 * BS_MEMBER_WORDS);
BS_AT_POINTER(Param, key, BS_PARAM_KEY);
BS_AT_WORD(Param, code, BS_PARAM_POINTERS, BS_PARAM_CODE);
BS_AT_WORD(Param, flags, BS_PARAM_POINTERS, BS_PARAM_FLAGS);
BS_AT_WORD(Param, size, BS_PARAM_POINTERS, BS_PARAM_SIZE);
BS_AT_WORD(Param, name, BS_PARAM_POINTERS, BS_PARAM_NAME);
BS_AT_WORD(Param, defaultKind, BS_PARAM_POINTERS, BS_PARAM_DEFAULT_KIND);
BS_AT_WORD(Param, defaultInt, BS_PARAM_POINTERS, BS_PARAM_DEFAULT_INT);
BS_AT_WORD(Param, defaultFloat, BS_PARAM_POINTERS, BS_PARAM_DEFAULT_FLOAT);
static_assert(sizeof(Param) == BS_PARAM_POINTERS * sizeof(void *) + 4 * BS_PARAM_WORDS);
BS_AT_POINTER(Enum, key, BS_ENUM_KEY);
BS_AT_WORD(Enum, name, BS_ENUM_POINTERS, BS_ENUM_NAME);
BS_AT_WORD(Enum, cppName, BS_ENUM_POINTERS, BS_ENUM_CPP_NAME);
BS_AT_WORD(Enum, size, BS_ENUM_POINTERS, BS_ENUM_SIZE);
BS_AT_WORD(Enum, flags, BS_ENUM_POINTERS, BS_ENUM_FLAGS);
BS_AT_WORD(Enum, firstValue, BS_ENUM_POINTERS, BS_ENUM_FIRST_VALUE);
BS_AT_WORD(Enum, numValues, BS_ENUM_POINTERS, BS_ENUM_NUM_VALUES);
static_assert(sizeof(Enum) == BS_ENUM_POINTERS * sizeof(void *) + 4 * BS_ENUM_WORDS);
BS_AT_WORD(Value, name, BS_VALUE_POINTERS, BS_VALUE_NAME);
BS_AT_WORD(Value, value, BS_VALUE_POINTERS, BS_VALUE_VALUE);
static_assert(sizeof(Value) == 4 * BS_VALUE_WORDS);
#undef BS_AT_WORD
#undef BS_AT_POINTER
} // namespace rec

/// The descriptor: the header, then each table, then the strings. A table
/// with no records still has one (zero) slot; its count says 0.
template <u32 NC, u32 NM, u32 NP, u32 NE, u32 NV, u32 NS> struct ModuleData {
  rec::Header header;
  rec::Class classes[NC ? NC : 1];
  rec::Member members[NM ? NM : 1];
  rec::Param params[NP ? NP : 1];
  rec::Enum enums[NE ? NE : 1];
  rec::Value values[NV ? NV : 1];
  char strings[NS];
};

struct Counts {
  u32 classes = 0, members = 0, params = 0, enums = 0, values = 0;
  u32 strings = 1; // the leading NUL of the empty string
};

struct Tables {
  rec::Class *classes = nullptr;
  rec::Member *members = nullptr;
  rec::Param *params = nullptr;
  rec::Enum *enums = nullptr;
  rec::Value *values = nullptr;
  char *strings = nullptr;
};

template <class...> struct List {};
template <class...> inline constexpr bool AlwaysFalse = false;
template <auto...> inline constexpr bool AlwaysFalseV = false;

/// Holds a typed function pointer so that the descriptor can point at it.
template <auto Fn> struct Holder {
  static constexpr decltype(Fn) fn = Fn;
};

} // namespace detail

/// Errors found while a module's body is evaluated at compile time. Each is
/// reported by the compiler as a call to a non-constexpr function whose name
/// says what is wrong; they are never called at run time.
namespace error {
inline void class_registered_twice_in_one_module() {}
inline void input_type_must_be_registered_in_the_same_module() {}
inline void output_type_must_be_registered_in_the_same_module() {}
inline void input_declared_twice() {}
inline void output_declared_twice() {}
inline void defaults_for_more_parameters_than_the_member_has() {}
inline void defaults_without_a_preceding_func() {}
inline void default_value_does_not_match_the_parameter_type() {}
inline void enum_values_must_directly_follow_their_registerEnum() {}
inline void empty_name() {}
inline void constant_value_does_not_fit_in_an_int() {}
inline void parameter_named_twice() {}
} // namespace error

/// The running behavior, for registered C++ that needs to know which robot
/// calls it: a function or method whose first C++ parameter is
/// `bs::Context &` gets it from generated code, and the script does not
/// pass it (docs/bindings.md "Per-robot context"). It is the state's
/// header (bs_state_header); nothing to construct or copy.
class Context {
public:
  Context() = delete;
  Context(const Context &) = delete;
  Context &operator=(const Context &) = delete;
  /// What the embedding attached with bs_state_set_user (null if nothing).
  void *user() const noexcept { return Header.user; }
  template <class T> T *user() const noexcept {
    return static_cast<T *>(Header.user);
  }
  /// This cycle's `input` and `output` objects.
  const void *input() const noexcept { return Header.input; }
  void *output() const noexcept { return Header.output; }
  /// The behavior's cycle number (the first cycle is 1).
  std::uint32_t cycle() const noexcept { return Header.cycle; }

private:
  bs_state_header Header;
};
static_assert(sizeof(Context) == sizeof(bs_state_header) &&
              std::is_standard_layout_v<Context>);

//===----------------------------------------------------------------------===//
// Overload selection and evaluating operators
//===----------------------------------------------------------------------===//

/// Selects the non-const overload of a member function: `bs::mut(&V::x)`.
template <class R, class C, class... A, bool NE>
constexpr auto mut(R (C::*P)(A...) noexcept(NE)) {
  return P;
}
/// Selects the const overload of a member function: `bs::cnst(&V::x)`.
template <class R, class C, class... A, bool NE>
constexpr auto cnst(R (C::*P)(A...) const noexcept(NE)) {
  return P;
}
/// Selects an overload by its signature:
/// `bs::overload<float(float)>(&std::fabs)`,
/// `bs::overload<V(const V &) const>(&V::operator-)`.
template <class Sig> constexpr auto overload(Sig *P) { return P; }
template <class Sig, class C> constexpr auto overload(Sig C::*P) { return P; }

/// Evaluating operators: Eigen's operators return lazy expression templates
/// that refer to their operands, so a thunk must evaluate into a V.
namespace op {
template <class V> V plus(const V &A, const V &B) { return V(A + B); }
template <class V> V minus(const V &A, const V &B) { return V(A - B); }
template <class V> V neg(const V &A) { return V(-A); }
/// V * V; for a vector times a scalar use scale.
template <class V> V times(const V &A, const V &B) { return V(A * B); }
template <class V> V divide(const V &A, const V &B) { return V(A / B); }
template <class V, class S = float> V scale(const V &A, S B) {
  return V(A * B);
}
template <class V, class S = float> V divideBy(const V &A, S B) {
  return V(A / B);
}
template <class V> bool equals(const V &A, const V &B) {
  return bool(A == B);
}
template <class V> bool notEquals(const V &A, const V &B) {
  return bool(A != B);
}
} // namespace op

/// The paper's argument order without macros:
/// `.func("abs", bs::fn<&V::norm>)`, `registerFunction(module, "f", bs::fn<&f>)`.
template <auto F> struct FnTag {};
template <auto F> inline constexpr FnTag<F> fn{};

/// The C++ name a registration may give for messages and dumps
/// (`"Math::fabs"`). A class rather than `const char *`, so that a braced
/// list of one parameter name (`{"v"}`) picks the overload that takes
/// parameter names instead of becoming the C++ name.
struct CppName {
  const char *Text;
  constexpr CppName(const char *Text = nullptr) : Text(Text) {}
};

/// Parameter names, one per parameter the script writes (without the
/// object of a method and a leading `bs::Context &`), in order:
/// `registerFunction<&between>(module, "between", {"v", "min", "max"})`.
/// bsc shows them in `--dump-bindings` and in messages.
template <std::size_t N> using ParamNames = const char *const (&)[N];

namespace detail {

//===----------------------------------------------------------------------===//
// Types on the wire
//===----------------------------------------------------------------------===//

template <class T> constexpr const void *keyOf() {
  if constexpr (std::is_same_v<T, Context>)
    return nullptr; // Not a registered type: the state.
  else if constexpr (std::is_enum_v<T> || std::is_class_v<T>)
    return &TypeKey<T>::id;
  else
    return nullptr;
}

template <class D> constexpr void checkScalar() {
  static_assert(!std::is_integral_v<D> || sizeof(D) <= 4,
                "bs: 64-bit integers are not supported: b-script's int is 32 "
                "bits (use int32_t, or wrap the function in a lambda)");
  static_assert(!std::is_floating_point_v<D> || sizeof(D) <= 8,
                "bs: long double is not supported (use float or double)");
  static_assert(std::is_same_v<D, const char *> || !std::is_pointer_v<D>,
                "bs: raw pointers are not supported: pass registered classes "
                "by value or by reference");
  static_assert(!std::is_member_pointer_v<D> && !std::is_array_v<D> &&
                    !std::is_function_v<D> && !std::is_union_v<D> &&
                    !std::is_null_pointer_v<D>,
                "bs: unsupported type: use bool, integers of up to 32 bits, "
                "float, double, enums, const char * or registered classes");
}

/// How a C++ type A (as a parameter) travels: W is the wire type, from()
/// turns the wire value back into an argument for A.
template <class A> struct ParamWire {
  using D = std::remove_cvref_t<A>;
  static constexpr bool IsLRef = std::is_lvalue_reference_v<A>;
  static constexpr bool IsMutRef =
      IsLRef && !std::is_const_v<std::remove_reference_t<A>>;
  static constexpr bool IsRRef = std::is_rvalue_reference_v<A>;

  static consteval u32 code() {
    if constexpr (std::is_same_v<D, bool>)
      return CodeBool;
    else if constexpr (std::is_integral_v<D>)
      return CodeInt;
    else if constexpr (std::is_floating_point_v<D>)
      return CodeFloat;
    else if constexpr (std::is_enum_v<D>)
      return CodeEnum;
    else if constexpr (std::is_class_v<D>)
      return CodeClass;
    else
      return CodeString;
  }
  static constexpr u32 C = (checkScalar<D>(), code());
  static constexpr bool ByPointer = C == CodeClass || (IsMutRef && C != CodeString);

  static_assert(!IsMutRef || C == CodeClass || std::is_same_v<D, int> ||
                    std::is_same_v<D, float> || std::is_same_v<D, bool>,
                "bs: a non-const reference parameter must be a registered "
                "class or exactly int&, float& or bool& (b-script has no "
                "storage of other scalar types); wrap the function in a "
                "lambda");
  static_assert(!IsRRef || C == CodeClass,
                "bs: rvalue references to scalars are not supported");

  using W = std::conditional_t<
      ByPointer,
      std::conditional_t<IsMutRef, D *, const D *>,
      std::conditional_t<C == CodeFloat, float,
                         std::conditional_t<C == CodeString, const char *,
                                            i32>>>;

  static constexpr decltype(auto) from(W V) noexcept {
    if constexpr (ByPointer) {
      if constexpr (IsRRef)
        return D(*V);
      else
        return (*V);
    } else if constexpr (C == CodeBool) {
      return bool(V != 0);
    } else if constexpr (C == CodeString) {
      return V;
    } else {
      return static_cast<D>(V);
    }
  }

  static constexpr u32 flags() {
    u32 F = 0;
    if (std::is_const_v<std::remove_reference_t<A>>)
      F |= TypeConst;
    if (IsLRef || IsRRef)
      F |= TypeRef;
    if constexpr (std::is_integral_v<D> && !std::is_same_v<D, bool>) {
      if (std::is_unsigned_v<D>)
        F |= TypeUnsigned;
    } else if constexpr (std::is_enum_v<D>) {
      if (std::is_unsigned_v<std::underlying_type_t<D>>)
        F |= TypeUnsigned;
    }
    if (ByPointer)
      F |= TypePointer;
    return F;
  }
  static constexpr u32 size() {
    if constexpr (C == CodeString)
      return sizeof(const char *);
    else
      return sizeof(D);
  }
};

/// `bs::Context &`: the state pointer generated code passes.
template <> struct ParamWire<Context &> {
  using D = Context;
  static constexpr u32 C = CodeContext;
  static constexpr bool ByPointer = true;
  using W = Context *;
  static constexpr Context &from(W V) noexcept { return *V; }
  static constexpr u32 flags() { return TypeRef | TypePointer; }
  static constexpr u32 size() { return sizeof(void *); }
};

/// Whether A... starts with `bs::Context &` (which the script does not pass).
template <class... A> consteval bool contextFirst() {
  bool Is[] = {false, std::is_same_v<std::remove_cvref_t<A>, Context>...};
  return sizeof...(A) > 0 && Is[1];
}

/// Whether `bs::Context &` appears anywhere but first in A...
template <class... A> consteval bool contextNotFirst() {
  bool Seen[] = {false, std::is_same_v<std::remove_cvref_t<A>, Context>...};
  for (std::size_t I = 2; I < sizeof(Seen); ++I)
    if (Seen[I])
      return true;
  return false;
}

/// How a result of C++ type R travels: scalars as W, classes through an
/// out pointer to raw storage (Out).
template <class R> struct ResultWire {
  using D = std::remove_cvref_t<R>;
  static consteval u32 code() {
    if constexpr (std::is_void_v<D>)
      return CodeVoid;
    else
      return ParamWire<D>::C;
  }
  static constexpr u32 C = code();
  static constexpr bool Out = C == CodeClass;
  using W = std::conditional_t<
      C == CodeVoid || Out, void,
      std::conditional_t<C == CodeFloat, float,
                         std::conditional_t<C == CodeString, const char *,
                                            i32>>>;

  template <class X> static constexpr W to(X &&V) noexcept {
    if constexpr (C == CodeBool)
      return V ? 1 : 0;
    else
      return static_cast<W>(V);
  }
  static constexpr u32 flags() {
    u32 F = 0;
    if constexpr (!std::is_void_v<D>) {
      if (std::is_const_v<std::remove_reference_t<R>>)
        F |= TypeConst;
      if (std::is_reference_v<R>)
        F |= TypeRef;
      if constexpr (std::is_integral_v<D> && !std::is_same_v<D, bool>) {
        if (std::is_unsigned_v<D>)
          F |= TypeUnsigned;
      } else if constexpr (std::is_enum_v<D>) {
        if (std::is_unsigned_v<std::underlying_type_t<D>>)
          F |= TypeUnsigned;
      }
    }
    return F;
  }
  static constexpr u32 size() {
    if constexpr (std::is_void_v<D>)
      return 0;
    else
      return ParamWire<D>::size();
  }
};

//===----------------------------------------------------------------------===//
// Callables: member functions, free functions, lambdas
//===----------------------------------------------------------------------===//

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic push
// GCC 12 warns about (obj.*F)() with a false strict-aliasing positive.
#pragma GCC diagnostic ignored "-Wstrict-aliasing"
#endif

/// What a callable F looks like when registered on class T (T is void for
/// module functions): its result, whether it takes the object (Self is T,
/// const T, or void) and its remaining parameters.
template <class T, auto F, class FT = std::remove_cv_t<decltype(F)>>
struct Callable;

template <class T, auto F, class R, class C, bool IsConst, class... A>
struct MemberCallable {
  static_assert(!std::is_void_v<T>,
                "bs: registerFunction needs a free function or a lambda; "
                "register member functions with registerClass<T>(...).func");
  static_assert(std::is_void_v<T> || std::is_base_of_v<C, T>,
                "bs: the member must belong to the registered class or one "
                "of its bases");
  using Ret = R;
  using Self = std::conditional_t<IsConst, const T, T>;
  using Args = List<A...>;
  static constexpr bool HasSelf = true;
  template <class... X> static decltype(auto) invoke(Self *S, X &&...Xs) {
    return (S->*F)(std::forward<X>(Xs)...);
  }
};

template <class T, class A0>
inline constexpr bool IsSelfParam =
    !std::is_void_v<T> && std::is_same_v<std::remove_cvref_t<A0>, T> &&
    !std::is_rvalue_reference_v<A0>;

/// A free function or lambda. On a class, a first parameter T&, const T& or
/// T makes it a method.
template <class T, auto F, class R, class... A> struct FreeCallable {
  using Ret = R;
  using Self = void;
  using Args = List<A...>;
  static constexpr bool HasSelf = false;
  template <class... X> static decltype(auto) invoke(X &&...Xs) {
    return F(std::forward<X>(Xs)...);
  }
};

template <class T, auto F, class R, class A0, class... A>
  requires IsSelfParam<T, A0>
struct FreeCallable<T, F, R, A0, A...> {
  using Ret = R;
  using Self = std::conditional_t<std::is_lvalue_reference_v<A0> &&
                                      !std::is_const_v<std::remove_reference_t<A0>>,
                                  T, const T>;
  using Args = List<A...>;
  static constexpr bool HasSelf = true;
  template <class... X> static decltype(auto) invoke(Self *S, X &&...Xs) {
    return F(*S, std::forward<X>(Xs)...);
  }
};

template <class T, auto F, class R, class C, class... A, bool NE>
struct Callable<T, F, R (C::*)(A...) noexcept(NE)>
    : MemberCallable<T, F, R, C, false, A...> {};
template <class T, auto F, class R, class C, class... A, bool NE>
struct Callable<T, F, R (C::*)(A...) const noexcept(NE)>
    : MemberCallable<T, F, R, C, true, A...> {};
template <class T, auto F, class R, class C, class... A, bool NE>
struct Callable<T, F, R (C::*)(A...) & noexcept(NE)>
    : MemberCallable<T, F, R, C, false, A...> {};
template <class T, auto F, class R, class C, class... A, bool NE>
struct Callable<T, F, R (C::*)(A...) const & noexcept(NE)>
    : MemberCallable<T, F, R, C, true, A...> {};
template <class T, auto F, class R, class... A, bool NE>
struct Callable<T, F, R (*)(A...) noexcept(NE)>
    : FreeCallable<T, F, R, A...> {};

template <class Op> struct ClosureSig {
  static_assert(AlwaysFalse<Op>,
                "bs: unsupported callable: use a member function pointer, a "
                "function pointer or a captureless, non-generic lambda");
};
template <class L, class R, class... A, bool NE>
struct ClosureSig<R (L::*)(A...) const noexcept(NE)> {
  template <class T, auto F> using Type = FreeCallable<T, F, R, A...>;
};

template <class FT, class = void> struct HasCallOperator : std::false_type {};
template <class FT>
struct HasCallOperator<FT, std::void_t<decltype(&FT::operator())>>
    : std::true_type {};

template <class FT, bool = HasCallOperator<FT>::value> struct ClosureOf {
  static_assert(AlwaysFalse<FT>,
                "bs: unsupported callable: use a member function pointer, a "
                "function pointer or a captureless, non-generic lambda (an "
                "overload set needs bs::mut, bs::cnst or bs::overload<Sig>)");
  template <class T, auto F> using Type = FreeCallable<T, F, void>;
};
template <class FT> struct ClosureOf<FT, true> {
  template <class T, auto F>
  using Type = typename ClosureSig<decltype(&FT::operator())>::template Type<T, F>;
};

/// Lambdas and other function objects.
template <class T, auto F, class FT>
struct Callable : ClosureOf<FT>::template Type<T, F> {
  static_assert(!std::is_member_object_pointer_v<FT>,
                "bs: a data member pointer needs .var<&T::m>, not .func");
};

//===----------------------------------------------------------------------===//
// Thunks: plain C ABI, noexcept, static members of class templates (their
// names match between GCC and Clang; function templates' do not).
//===----------------------------------------------------------------------===//


template <class T, auto F, bool Out, bool HasSelf, class Args> struct CallImpl;

template <class T, auto F, class... A>
struct CallImpl<T, F, false, false, List<A...>> {
  using C = Callable<T, F>;
  using RW = ResultWire<typename C::Ret>;
  static typename RW::W call(typename ParamWire<A>::W... Xs) noexcept {
    if constexpr (std::is_void_v<typename RW::W>)
      C::invoke(ParamWire<A>::from(Xs)...);
    else
      return RW::to(C::invoke(ParamWire<A>::from(Xs)...));
  }
};

template <class T, auto F, class... A>
struct CallImpl<T, F, false, true, List<A...>> {
  using C = Callable<T, F>;
  using RW = ResultWire<typename C::Ret>;
  static typename RW::W call(typename C::Self *Self,
                             typename ParamWire<A>::W... Xs) noexcept {
    if constexpr (std::is_void_v<typename RW::W>)
      C::invoke(Self, ParamWire<A>::from(Xs)...);
    else
      return RW::to(C::invoke(Self, ParamWire<A>::from(Xs)...));
  }
};

template <class T, auto F, class... A>
struct CallImpl<T, F, true, false, List<A...>> {
  using C = Callable<T, F>;
  using R = typename ResultWire<typename C::Ret>::D;
  static void call(R *Out, typename ParamWire<A>::W... Xs) noexcept {
    ::new (static_cast<void *>(Out)) R(C::invoke(ParamWire<A>::from(Xs)...));
  }
};

template <class T, auto F, class... A>
struct CallImpl<T, F, true, true, List<A...>> {
  using C = Callable<T, F>;
  using R = typename ResultWire<typename C::Ret>::D;
  static void call(R *Out, typename C::Self *Self,
                   typename ParamWire<A>::W... Xs) noexcept {
    ::new (static_cast<void *>(Out))
        R(C::invoke(Self, ParamWire<A>::from(Xs)...));
  }
};

template <class T, auto F, class C = Callable<T, F>>
using CallOf = CallImpl<T, F, ResultWire<typename C::Ret>::Out, C::HasSelf,
                        typename C::Args>;

/// Field access: get(self) / get(out, self) and set(self, value).
template <class T, auto M> struct MemberPtrTraits;
template <class T, class X, class C, X C::*M> struct MemberPtrTraits<T, M> {
  static_assert(std::is_base_of_v<C, T>,
                "bs: the member must belong to the registered class or one "
                "of its bases");
  using Type = X;
};

template <class T, auto M,
          bool IsClass = std::is_class_v<typename MemberPtrTraits<T, M>::Type>>
struct FieldImpl {
  using X = typename MemberPtrTraits<T, M>::Type;
  using D = std::remove_cv_t<X>;
  using PW = ParamWire<const D &>;
  static typename ResultWire<D>::W get(const T *Self) noexcept {
    return ResultWire<D>::to(Self->*M);
  }
  static void set(T *Self, typename PW::W V) noexcept {
    Self->*M = PW::from(V);
  }
};
template <class T, auto M> struct FieldImpl<T, M, true> {
  using X = typename MemberPtrTraits<T, M>::Type;
  using D = std::remove_cv_t<X>;
  static void get(D *Out, const T *Self) noexcept {
    ::new (static_cast<void *>(Out)) D(Self->*M);
  }
  static void set(T *Self, const D *V) noexcept { Self->*M = *V; }
};

/// The data member pointer as a member of T: its bytes are the offset.
template <class T, auto M> struct FieldHolder {
  static constexpr typename MemberPtrTraits<T, M>::Type T::*ptr = M;
};

/// Properties: a getter without parameters, and a setter with one (or, for
/// a getter that returns a mutable reference, an assignment through it).
template <class T, auto G> struct PropGetter {
  using C = Callable<T, G>;
  static_assert(C::HasSelf && std::is_same_v<typename C::Args, List<>>,
                "bs: a property getter must be a member function without "
                "parameters, or take the object as its only parameter");
  static_assert(!std::is_void_v<typename C::Ret>,
                "bs: a property getter must return a value");
  using R = typename C::Ret;
  using D = std::remove_cvref_t<R>;
  static constexpr bool RefGetter =
      std::is_lvalue_reference_v<R> &&
      !std::is_const_v<std::remove_reference_t<R>>;
  // A getter that needs a non-const object (bs::mut(&V::x)) only reads.
  static typename C::Self *self(const T *S) {
    return const_cast<typename C::Self *>(S);
  }
};

template <class T, auto G, bool Out = std::is_class_v<typename PropGetter<T, G>::D>>
struct PropGetImpl {
  using P = PropGetter<T, G>;
  static typename ResultWire<typename P::D>::W get(const T *Self) noexcept {
    return ResultWire<typename P::D>::to(P::C::invoke(P::self(Self)));
  }
};
template <class T, auto G> struct PropGetImpl<T, G, true> {
  using P = PropGetter<T, G>;
  static void get(typename P::D *Out, const T *Self) noexcept {
    ::new (static_cast<void *>(Out)) typename P::D(P::C::invoke(P::self(Self)));
  }
};

/// Setter of a getter that returns a mutable reference.
template <class T, auto G> struct PropRefSetImpl {
  using P = PropGetter<T, G>;
  using PW = ParamWire<const typename P::D &>;
  static void set(T *Self, typename PW::W V) noexcept {
    P::C::invoke(Self) = PW::from(V);
  }
};

template <class T, auto S, class C = Callable<T, S>> struct PropSetArg {
  static_assert(AlwaysFalseV<S>,
                "bs: a property setter must be a member function with one "
                "parameter, or take the object and one value");
};
template <class T, auto S, class C>
  requires(C::HasSelf && !std::is_const_v<typename C::Self>)
struct PropSetArg<T, S, C> {
  template <class L> struct One {
    static_assert(AlwaysFalse<L>, "bs: a property setter takes exactly one "
                                  "value");
  };
  template <class A> struct One<List<A>> {
    using Type = A;
  };
  using Type = typename One<typename C::Args>::Type;
};

/// Setter given as a function; its result, if any, is ignored.
template <class T, auto S> struct PropSetImpl {
  using C = Callable<T, S>;
  using PW = ParamWire<typename PropSetArg<T, S>::Type>;
  static void set(T *Self, typename PW::W V) noexcept {
    (void)C::invoke(Self, PW::from(V));
  }
};

/// Life cycle of class values in b-script frames and temporaries.
template <class T> struct Life {
  static void construct(T *P) noexcept { ::new (static_cast<void *>(P)) T(); }
  static void copy(T *Dst, const T *Src) noexcept {
    ::new (static_cast<void *>(Dst)) T(*Src);
  }
  static void assign(T *Dst, const T *Src) noexcept { *Dst = *Src; }
  static void destroy(T *P) noexcept { P->~T(); }
};

template <class T> struct LifeFns {
  void (*construct)(T *) noexcept;
  void (*copy)(T *, const T *) noexcept;
  void (*assign)(T *, const T *) noexcept;
  void (*destroy)(T *) noexcept;
};

template <class T> constexpr LifeFns<T> lifeFns() {
  LifeFns<T> L{nullptr, nullptr, nullptr, nullptr};
  if constexpr (std::is_default_constructible_v<T>)
    L.construct = &Life<T>::construct;
  if constexpr (std::is_copy_constructible_v<T>)
    L.copy = &Life<T>::copy;
  if constexpr (std::is_copy_assignable_v<T>)
    L.assign = &Life<T>::assign;
  if constexpr (std::is_destructible_v<T>)
    L.destroy = &Life<T>::destroy;
  return L;
}

template <class T> struct LifeHolder {
  static constexpr LifeFns<T> fns = lifeFns<T>();
};

#if defined(__GNUC__) && !defined(__clang__)
#pragma GCC diagnostic pop
#endif

template <auto Fn> constexpr const void *holder() {
  return &Holder<Fn>::fn;
}

/// The parameter records of a callable.
template <class L> struct ParamsOf;
template <class... A> struct ParamsOf<List<A...>> {
  static constexpr u32 Count = sizeof...(A);
  /// The parameters a script writes: without a leading `bs::Context &`.
  static constexpr std::size_t ScriptCount =
      sizeof...(A) - (contextFirst<A...>() ? 1 : 0);
  static_assert(!contextNotFirst<A...>(),
                "bs: bs::Context & must be the first parameter (after the "
                "object of a method)");
  template <class Emit> static constexpr void each(Emit &&E) {
    (E(keyOf<std::remove_cvref_t<A>>(), ParamWire<A>::C, ParamWire<A>::flags(),
       ParamWire<A>::size()),
     ...);
  }
};

constexpr bool isEmpty(const char *S) { return !S || !*S; }

} // namespace detail

//===----------------------------------------------------------------------===//
// The module builder
//===----------------------------------------------------------------------===//

/// The `module` of a BS_MODULE body. It is evaluated twice at compile time:
/// first with no tables to count records and string bytes, then with tables
/// that point into the descriptor. Not for use outside BS_MODULE.
class Module {
public:
  constexpr Module(const char *Name, detail::Tables Ts) : Tabs(Ts) {
    HeaderName = str(Name);
  }

  // The rest is used by the builders below.
  detail::Tables Tabs;
  detail::Counts N;
  detail::u32 HeaderName = 0;
  detail::u32 LastMember = detail::None;
  detail::u32 LastEnum = detail::None;
  const void *InputKey = nullptr;
  const void *OutputKey = nullptr;

  constexpr bool filling() const { return Tabs.strings != nullptr; }

  constexpr detail::u32 str(const char *S) {
    if (detail::isEmpty(S))
      return 0;
    detail::u32 Len = 0;
    while (S[Len])
      ++Len;
    detail::u32 Off = N.strings;
    if (filling())
      for (detail::u32 I = 0; I <= Len; ++I)
        Tabs.strings[Off + I] = S[I];
    N.strings += Len + 1;
    return Off;
  }

  constexpr detail::u32 addClass(const void *Key, const void *Life,
                                 const char *Name, const char *CppName,
                                 detail::u32 Size, detail::u32 Align,
                                 detail::u32 Flags) {
    if (detail::isEmpty(Name))
      error::empty_name();
    detail::u32 I = N.classes++;
    detail::u32 NameOff = str(Name), CppOff = str(CppName);
    if (filling()) {
      for (detail::u32 J = 0; J < I; ++J)
        if (Tabs.classes[J].key == Key)
          error::class_registered_twice_in_one_module();
      Tabs.classes[I] = {Key, Life, NameOff, CppOff, Size, Align, Flags, 0};
    }
    LastMember = detail::None;
    return I;
  }

  constexpr detail::rec::Member *member(detail::u32 I) {
    return filling() ? &Tabs.members[I] : nullptr;
  }

  /// Appends a member record; returns its index.
  constexpr detail::u32 addMember(detail::u32 Kind, detail::u32 Owner,
                                  const char *Name, const char *CppName) {
    if (detail::isEmpty(Name))
      error::empty_name();
    detail::u32 I = N.members++;
    detail::u32 NameOff = str(Name), CppOff = str(CppName);
    if (filling()) {
      detail::rec::Member &M = Tabs.members[I];
      M = {};
      M.kind = Kind;
      M.owner = Owner;
      M.name = NameOff;
      M.cppName = CppOff;
      M.firstParam = N.params;
    }
    LastMember = I;
    return I;
  }

  /// Appends a parameter record to the last member; Name may be null.
  constexpr void addParam(const void *Key, detail::u32 Code, detail::u32 Flags,
                          detail::u32 Size, const char *Name = nullptr) {
    detail::u32 I = N.params++;
    detail::u32 NameOff = str(Name);
    if (filling()) {
      Tabs.params[I] = {Key, Code, Flags, Size, NameOff, detail::DefaultNone,
                        0, 0.0f, 0};
      ++Tabs.members[LastMember].numParams;
    }
  }

  template <class... D> constexpr void setDefaults(const D &...Ds);

  constexpr detail::u32 addEnum(const void *Key, const char *Name,
                                const char *CppName, detail::u32 Size,
                                detail::u32 Flags) {
    if (detail::isEmpty(Name))
      error::empty_name();
    detail::u32 I = N.enums++;
    detail::u32 NameOff = str(Name), CppOff = str(CppName);
    if (filling())
      Tabs.enums[I] = {Key, NameOff, CppOff, Size, Flags, N.values, 0};
    LastEnum = I;
    LastMember = detail::None;
    return I;
  }

  constexpr void addValue(detail::u32 Enum, const char *Name,
                          detail::i32 Value) {
    if (detail::isEmpty(Name))
      error::empty_name();
    if (Enum != LastEnum)
      error::enum_values_must_directly_follow_their_registerEnum();
    detail::u32 I = N.values++;
    detail::u32 NameOff = str(Name);
    if (filling()) {
      Tabs.values[I] = {NameOff, Value};
      ++Tabs.enums[Enum].numValues;
    }
  }

  /// The index of the class with this key, or None.
  constexpr detail::u32 findClass(const void *Key) const {
    for (detail::u32 I = 0; I < N.classes; ++I)
      if (Tabs.classes[I].key == Key)
        return I;
    return detail::None;
  }
};

namespace detail {

/// Fills in the result fields of member record M for C++ type R.
/// The extents of array type X, outermost first.
template <class X> constexpr void setExtents(u32 *Extent) {
  if constexpr (std::is_array_v<X>) {
    *Extent = u32(std::extent_v<X>);
    setExtents<std::remove_extent_t<X>>(Extent + 1);
  }
}

template <class R> constexpr void setResult(rec::Member *M) {
  if (!M)
    return;
  using RW = ResultWire<R>;
  M->resultCode = RW::C;
  M->resultFlags = RW::flags();
  M->resultSize = RW::size();
  M->resultKey = keyOf<typename RW::D>();
  if (RW::Out)
    M->flags |= MemberResultOut;
}

/// Whether two names are equal (strcmp, usable at compile time).
constexpr bool sameName(const char *A, const char *B) {
  while (*A && *A == *B)
    ++A, ++B;
  return *A == *B;
}

/// Records a callable F as member `Name` of class Owner (None: a module
/// function) and returns its index. Params, if given, names each parameter
/// the script writes (ParamsOf::ScriptCount of them).
template <class T, auto F>
constexpr u32 addCallable(Module &Mod, u32 Owner, const char *Name,
                          const char *CppName,
                          const char *const *Params = nullptr) {
  using C = Callable<T, F>;
  constexpr std::size_t NumNamed = ParamsOf<typename C::Args>::ScriptCount;
  if (Params)
    for (std::size_t I = 0; I < NumNamed; ++I) {
      if (isEmpty(Params[I]))
        error::empty_name();
      for (std::size_t J = 0; J < I; ++J)
        if (sameName(Params[I], Params[J]))
          error::parameter_named_twice();
    }
  u32 Kind = C::HasSelf ? KindMethod : KindFunction;
  u32 I = Mod.addMember(Kind, Owner, Name, CppName);
  if (rec::Member *M = Mod.member(I)) {
    M->thunk = holder<&CallOf<T, F>::call>();
    if constexpr (C::HasSelf)
      if (std::is_const_v<typename C::Self>)
        M->flags |= MemberConstSelf;
    setResult<typename C::Ret>(M);
  }
  std::size_t Next = 0;
  ParamsOf<typename C::Args>::each(
      [&](const void *Key, u32 Code, u32 Flags, u32 Size) {
        const char *ParamName = nullptr;
        if (Params && Code != CodeContext)
          ParamName = Params[Next++];
        Mod.addParam(Key, Code, Flags, Size, ParamName);
      });
  return I;
}

/// addCallable with N parameter names, which must be one per parameter the
/// script passes: known here, so a wrong count is a static_assert.
template <class T, auto F, std::size_t N>
constexpr void addNamedCallable(Module &Mod, u32 Owner, const char *Name,
                                const char *CppName,
                                const char *const (&Params)[N]) {
  using Args = typename Callable<T, F>::Args;
  constexpr bool OneEach = N == ParamsOf<Args>::ScriptCount;
  static_assert(OneEach, "bs: give one name per parameter the script passes "
                         "(not the object of a method, not bs::Context &)");
  if constexpr (OneEach) // No follow-on errors from reading past Params.
    addCallable<T, F>(Mod, Owner, Name, CppName, Params);
}

/// The constructor T(A...) as a function returning T: the thunk of a
/// `.ctor<A...>()` (a template with external linkage, so generated code
/// calls it by name like any other thunk).
template <class T, class... A> T construct(A... Args) {
  return T(Args...);
}

template <class X> constexpr void setDefault(rec::Param &P, const X &V) {
  static_assert(std::is_arithmetic_v<X> || std::is_enum_v<X>,
                "bs: .defaults(...) takes scalar values only (bool, int, "
                "float, enum); class-typed defaults are not supported");
  bool Ok;
  if constexpr (std::is_floating_point_v<X>) {
    Ok = P.code == CodeFloat;
    P.defaultKind = DefaultFloat;
    P.defaultFloat = static_cast<float>(V);
  } else if constexpr (std::is_enum_v<X>) {
    Ok = P.code == CodeEnum && P.key == keyOf<X>();
    P.defaultKind = DefaultInt;
    P.defaultInt = static_cast<i32>(V);
  } else if constexpr (std::is_same_v<X, bool>) {
    Ok = P.code == CodeBool;
    P.defaultKind = DefaultInt;
    P.defaultInt = V ? 1 : 0;
  } else {
    Ok = P.code == CodeInt || P.code == CodeFloat;
    if (P.code == CodeFloat) {
      P.defaultKind = DefaultFloat;
      P.defaultFloat = static_cast<float>(V);
    } else {
      P.defaultKind = DefaultInt;
      P.defaultInt = static_cast<i32>(V);
    }
  }
  if (!Ok)
    error::default_value_does_not_match_the_parameter_type();
}

} // namespace detail

template <class... D> constexpr void Module::setDefaults(const D &...Ds) {
  if (LastMember == detail::None) {
    error::defaults_without_a_preceding_func();
    return;
  }
  if (!filling())
    return;
  detail::rec::Member &M = Tabs.members[LastMember];
  if (sizeof...(D) > M.numParams) {
    error::defaults_for_more_parameters_than_the_member_has();
    return;
  }
  detail::u32 I = M.firstParam + M.numParams - sizeof...(D);
  (detail::setDefault(Tabs.params[I++], Ds), ...);
}

//===----------------------------------------------------------------------===//
// Registration API
//===----------------------------------------------------------------------===//

/// Registers members of class T; returned by registerClass.
template <class T> class ClassBuilder {
public:
  constexpr ClassBuilder(Module &M, detail::u32 Index) : M(&M), Index(Index) {}

  /// A data member: `.var<&T::m>("m")`. Read-only if the member is const.
  /// An array member (`int32_t wide[8]`, `float m[3][3]`) is indexed in
  /// b-script by its offset; it has no thunks.
  template <auto Ptr>
  constexpr ClassBuilder &var(const char *Name, const char *CppName = nullptr) {
    static_assert(std::is_member_object_pointer_v<decltype(Ptr)>,
                  "bs: .var needs a data member pointer (&T::m); use .prop or "
                  ".func for member functions");
    using namespace detail;
    using X = typename MemberPtrTraits<T, Ptr>::Type;
    using E = std::remove_all_extents_t<X>; // X itself unless an array
    static_assert(std::rank_v<X> <= 4,
                  "bs: array fields have at most 4 dimensions");
    (void)ParamWire<std::remove_cv_t<E>>::C; // rejects unsupported types
    u32 I = M->addMember(KindField, Index, Name, CppName);
    if (rec::Member *R = M->member(I)) {
      setResult<E>(R);
      if constexpr (std::is_array_v<X>) {
        setExtents<X>(R->extent);
        R->flags &= ~MemberResultOut; // no getter
      } else {
        R->thunk = holder<&FieldImpl<T, Ptr>::get>();
        if constexpr (!std::is_const_v<X>)
          R->thunk2 = holder<&FieldImpl<T, Ptr>::set>();
      }
      if constexpr (std::is_const_v<E>)
        R->flags |= MemberReadOnly;
      R->memptr = &FieldHolder<T, Ptr>::ptr;
      R->flags |= MemberConstSelf;
    }
    M->LastMember = detail::None;
    return *this;
  }

  /// A property: `.prop<getter>("p")` or `.prop<getter, setter>("p")`. A
  /// getter returning a mutable reference (`bs::mut(&V::x)`) gives
  /// read/write access on its own. `0` stands for "no setter".
  template <auto Getter, auto Setter = 0>
  constexpr ClassBuilder &prop(const char *Name,
                               const char *CppName = nullptr) {
    static_assert(!std::is_member_object_pointer_v<decltype(Getter)>,
                  "bs: a data member pointer needs .var<&T::m>, not .prop");
    using namespace detail;
    using P = PropGetter<T, Getter>;
    u32 I = M->addMember(KindProperty, Index, Name, CppName);
    if (rec::Member *R = M->member(I)) {
      R->thunk = holder<&PropGetImpl<T, Getter>::get>();
      constexpr bool HasSetter = !std::is_same_v<decltype(Setter), int>;
      if constexpr (HasSetter)
        R->thunk2 = holder<&PropSetImpl<T, Setter>::set>();
      else if constexpr (P::RefGetter)
        R->thunk2 = holder<&PropRefSetImpl<T, Getter>::set>();
      else
        R->flags |= MemberReadOnly;
      R->flags |= MemberConstSelf;
      setResult<typename P::D>(R);
    }
    M->LastMember = detail::None;
    return *this;
  }

  /// A method: a member function of T or of a base of T, a free function
  /// or lambda whose first parameter is T&/const T&/T, or (without such a
  /// parameter) a function in the class's scope.
  template <auto F>
  constexpr ClassBuilder &func(const char *Name, CppName Cpp = {}) {
    detail::addCallable<T, F>(*M, Index, Name, Cpp.Text);
    return *this;
  }
  /// ...with the names of its parameters: `.func<&V::dot>("dot", {"other"})`.
  template <auto F, std::size_t N>
  constexpr ClassBuilder &func(const char *Name, ParamNames<N> Params,
                               CppName Cpp = {}) {
    detail::addNamedCallable<T, F, N>(*M, Index, Name, Cpp.Text, Params);
    return *this;
  }

  /// The paper's argument order: `.func("abs", bs::fn<&V::norm>, "norm")`.
  template <auto F>
  constexpr ClassBuilder &func(const char *Name, FnTag<F>, CppName Cpp = {}) {
    return func<F>(Name, Cpp);
  }
  template <auto F, std::size_t N>
  constexpr ClassBuilder &func(const char *Name, FnTag<F>,
                               ParamNames<N> Params, CppName Cpp = {}) {
    return func<F>(Name, Params, Cpp);
  }
  template <auto Ptr>
  constexpr ClassBuilder &var(const char *Name, FnTag<Ptr>,
                              const char *CppName = nullptr) {
    return var<Ptr>(Name, CppName);
  }

  /// A constructor T(A...): the script writes `Module::T(a, ...)`, and the
  /// constructors of one class are told apart by their parameters.
  template <class... A> constexpr ClassBuilder &ctor() {
    return addCtor<A...>(nullptr);
  }
  /// ...with the names of its parameters: `.ctor<float, float>({"x", "y"})`.
  template <class... A, std::size_t N>
  constexpr ClassBuilder &ctor(ParamNames<N> Params) {
    static_assert(N == sizeof...(A),
                  "bs: give one name per parameter of the constructor");
    if constexpr (N == sizeof...(A))
      addCtor<A...>(Params);
    return *this;
  }

  /// Restates the C++ default arguments of the trailing parameters of the
  /// preceding .func or .ctor (templates cannot see default arguments).
  template <class... D> constexpr ClassBuilder &defaults(const D &...Ds) {
    M->setDefaults(Ds...);
    return *this;
  }

  /// Opts in to copying values of T with memcpy instead of the copy thunk
  /// (for classes such as Eigen's whose copy constructor is user-provided
  /// but equivalent to a byte copy).
  constexpr ClassBuilder &copyAsBytes() {
    if (M->filling())
      M->Tabs.classes[Index].flags |= detail::ClassCopyAsBytes;
    return *this;
  }

private:
  template <class... A>
  constexpr ClassBuilder &addCtor(const char *const *Params) {
    static_assert(std::is_constructible_v<T, A...>,
                  "bs: .ctor<A...>() needs a constructor T(A...)");
    static_assert(std::is_move_constructible_v<T> ||
                      std::is_copy_constructible_v<T>,
                  "bs: .ctor<A...>() returns T by value");
    detail::u32 I = detail::addCallable<void, &detail::construct<T, A...>>(
        *M, Index, "_ctor_", nullptr, Params);
    if (detail::rec::Member *R = M->member(I))
      R->kind = detail::KindConstructor;
    return *this;
  }

  Module *M;
  detail::u32 Index;
};

/// Registers a module function; returned by registerFunction.
class FunctionBuilder {
public:
  constexpr explicit FunctionBuilder(Module &M) : M(&M) {}
  template <class... D> constexpr FunctionBuilder &defaults(const D &...Ds) {
    M->setDefaults(Ds...);
    return *this;
  }

private:
  Module *M;
};

/// Registers values of enum E; returned by registerEnum.
template <class E> class EnumBuilder {
public:
  constexpr EnumBuilder(Module &M, detail::u32 Index) : M(&M), Index(Index) {}
  constexpr EnumBuilder &value(const char *Name, E V) {
    M->addValue(Index, Name, static_cast<detail::i32>(V));
    return *this;
  }

private:
  Module *M;
  detail::u32 Index;
};

namespace registration {

/// Registers class T as `Name` (a b-script identifier); CppName is for
/// messages and dumps.
template <class T>
constexpr ClassBuilder<T> registerClass(Module &M, const char *Name,
                                        const char *CppName = nullptr) {
  static_assert(std::is_class_v<T> && !std::is_union_v<T>,
                "bs: registerClass<T> needs a class type");
  static_assert(!std::is_abstract_v<T>,
                "bs: an abstract class cannot be a b-script value");
  static_assert(std::is_destructible_v<T>,
                "bs: a registered class needs an accessible destructor");
  using namespace detail;
  u32 Flags = 0;
  if (std::is_trivially_copyable_v<T>)
    Flags |= ClassTriviallyCopyable;
  if (std::is_trivially_destructible_v<T>)
    Flags |= ClassTriviallyDestructible;
  if (std::is_default_constructible_v<T>)
    Flags |= ClassDefaultConstructible;
  if (std::is_copy_constructible_v<T>)
    Flags |= ClassCopyConstructible;
  if (std::is_copy_assignable_v<T>)
    Flags |= ClassCopyAssignable;
  if (std::is_standard_layout_v<T>)
    Flags |= ClassStandardLayout;
  u32 I = M.addClass(&TypeKey<T>::id, &LifeHolder<T>::fns, Name, CppName,
                     sizeof(T), alignof(T), Flags);
  return ClassBuilder<T>(M, I);
}

/// Registers a module function: `registerFunction<&f>(module, "f")`.
template <auto F>
constexpr FunctionBuilder registerFunction(Module &M, const char *Name,
                                           CppName Cpp = {}) {
  detail::addCallable<void, F>(M, detail::None, Name, Cpp.Text);
  return FunctionBuilder(M);
}
/// ...with the names of its parameters:
/// `registerFunction<&between>(module, "between", {"v", "min", "max"})`.
template <auto F, std::size_t N>
constexpr FunctionBuilder registerFunction(Module &M, const char *Name,
                                           ParamNames<N> Params,
                                           CppName Cpp = {}) {
  detail::addNamedCallable<void, F, N>(M, detail::None, Name, Cpp.Text,
                                       Params);
  return FunctionBuilder(M);
}

/// The paper's argument order: `registerFunction(module, "f", bs::fn<&f>)`.
template <auto F>
constexpr FunctionBuilder registerFunction(Module &M, const char *Name,
                                           FnTag<F>, CppName Cpp = {}) {
  return registerFunction<F>(M, Name, Cpp);
}
template <auto F, std::size_t N>
constexpr FunctionBuilder registerFunction(Module &M, const char *Name,
                                           FnTag<F>, ParamNames<N> Params,
                                           CppName Cpp = {}) {
  return registerFunction<F>(M, Name, Params, Cpp);
}

/// Registers a constant of the module: `registerConstant(module, "off",
/// 10000)` is `Module::off` in scripts. An int, float, bool or registered
/// enum value; computed here at compile time, so the script's constant
/// folds like its own.
template <class X>
constexpr void registerConstant(Module &M, const char *Name, const X &V,
                                const char *CppName = nullptr) {
  static_assert(std::is_arithmetic_v<X> || std::is_enum_v<X>,
                "bs: registerConstant takes an int, float, bool or enum "
                "value");
  using namespace detail;
  u32 I = M.addMember(KindConstant, None, Name, CppName);
  rec::Member *R = M.member(I);
  if (!R)
    return;
  setResult<X>(R);
  R->flags |= MemberReadOnly;
  if constexpr (std::is_floating_point_v<X>) {
    R->value = __builtin_bit_cast(u32, static_cast<float>(V));
  } else if constexpr (std::is_same_v<X, bool>) {
    R->value = V ? 1 : 0;
  } else {
    auto N = static_cast<long long>(V);
    if (N < -2147483647LL - 1 || N > 2147483647LL)
      error::constant_value_does_not_fit_in_an_int();
    R->value = static_cast<u32>(static_cast<i32>(N));
  }
}

/// Registers enum E as `Name`; add its values with .value("a", E::a).
template <class E>
constexpr EnumBuilder<E> registerEnum(Module &M, const char *Name,
                                      const char *CppName = nullptr) {
  static_assert(std::is_enum_v<E>, "bs: registerEnum<E> needs an enum type");
  static_assert(sizeof(E) <= 4,
                "bs: enums with 64-bit storage are not supported");
  using namespace detail;
  u32 Flags = 0;
  if (!std::is_convertible_v<E, std::underlying_type_t<E>>)
    Flags |= EnumScoped;
  if (std::is_signed_v<std::underlying_type_t<E>>)
    Flags |= EnumSigned;
  u32 I = M.addEnum(&TypeKey<E>::id, Name, CppName, sizeof(E), Flags);
  return EnumBuilder<E>(M, I);
}

/// Declares T (registered in this module) as the type of b-script's
/// read-only global `input`. The names this module registers are visible
/// unqualified in every script.
template <class T> constexpr void registerInput(Module &M) {
  static_assert(std::is_class_v<T>, "bs: the input type must be a class");
  if (M.InputKey)
    error::input_declared_twice();
  M.InputKey = &TypeKey<T>::id;
}

/// Declares T (registered in this module) as the type of b-script's
/// write-only global `output`.
template <class T> constexpr void registerOutput(Module &M) {
  static_assert(std::is_class_v<T>, "bs: the output type must be a class");
  if (M.OutputKey)
    error::output_declared_twice();
  M.OutputKey = &TypeKey<T>::id;
}

} // namespace registration

using registration::registerClass;
using registration::registerConstant;
using registration::registerEnum;
using registration::registerFunction;
using registration::registerInput;
using registration::registerOutput;

namespace detail {

template <class Body> constexpr Counts countModule() {
  Module M(Body::name, Tables{});
  Body::run(M);
  return M.N;
}

/// Builds the descriptor of BS_MODULE body Body.
template <class Body> constexpr auto buildModule() {
  constexpr Counts C = countModule<Body>();
  using Data = ModuleData<C.classes, C.members, C.params, C.enums, C.values,
                          C.strings>;
  Data D{};
  Module M(Body::name, Tables{D.classes, D.members, D.params, D.enums,
                              D.values, D.strings});
  Body::run(M);

  rec::Header &H = D.header;
  const char Magic[8] = {BS_DESCRIPTOR_MAGIC[0], BS_DESCRIPTOR_MAGIC[1],
                         BS_DESCRIPTOR_MAGIC[2], BS_DESCRIPTOR_MAGIC[3],
                         BS_DESCRIPTOR_MAGIC[4], BS_DESCRIPTOR_MAGIC[5],
                         BS_DESCRIPTOR_MAGIC[6], BS_DESCRIPTOR_MAGIC[7]};
  for (int I = 0; I < 8; ++I)
    H.magic[I] = Magic[I];
  H.version = DescriptorVersion;
  H.headerSize = sizeof(rec::Header);
  H.ptrSize = sizeof(void *);
  H.name = M.HeaderName;
  H.totalSize = sizeof(Data);
  H.flags = 0;
  H.inputClass = None;
  H.outputClass = None;
  if (M.InputKey) {
    H.inputClass = M.findClass(M.InputKey);
    if (H.inputClass == None)
      error::input_type_must_be_registered_in_the_same_module();
  }
  if (M.OutputKey) {
    H.outputClass = M.findClass(M.OutputKey);
    if (H.outputClass == None)
      error::output_type_must_be_registered_in_the_same_module();
  }
  H.numClasses = C.classes;
  H.classOffset = offsetof(Data, classes);
  H.classSize = sizeof(rec::Class);
  H.numMembers = C.members;
  H.memberOffset = offsetof(Data, members);
  H.memberSize = sizeof(rec::Member);
  H.numParams = C.params;
  H.paramOffset = offsetof(Data, params);
  H.paramSize = sizeof(rec::Param);
  H.numEnums = C.enums;
  H.enumOffset = offsetof(Data, enums);
  H.enumSize = sizeof(rec::Enum);
  H.numValues = C.values;
  H.valueOffset = offsetof(Data, values);
  H.valueSize = sizeof(rec::Value);
  H.stringOffset = offsetof(Data, strings);
  H.stringSize = C.strings;
  return D;
}

} // namespace detail

/// The descriptor hash that bsc records for staleness checks
/// (bs_descriptor_hash), computed in-process from a descriptor (e.g. found
/// between __start_bs_modules and __stop_bs_modules).
inline std::uint64_t moduleHash(const void *Descriptor) {
  using namespace detail;
  const unsigned char *B = static_cast<const unsigned char *>(Descriptor);
  // Declarations of `bs_module_X` name its Header, but the descriptor is
  // the tables and strings behind it too: hide the declared object's size,
  // or the optimiser and -fsanitize=object-size take the reads past the
  // header for reads past the object.
  __asm__("" : "+r"(B));
  // A field's offset: the bytes of the data member pointer its holder holds.
  auto FieldOffset = [](void *D, std::uint32_t I, std::int64_t *Off) -> int {
    const unsigned char *Bytes = static_cast<const unsigned char *>(D);
    std::uint32_t Table = bs_descriptor_u32(Bytes + BS_HDR_TABLE(BS_TABLE_MEMBERS) + 4);
    std::uint32_t Size = bs_descriptor_u32(Bytes + BS_HDR_TABLE(BS_TABLE_MEMBERS) + 8);
    const void *Holder;
    __builtin_memcpy(&Holder,
                     Bytes + Table + I * Size + BS_MEMBER_MEMPTR * sizeof(void *),
                     sizeof Holder);
    if (!Holder)
      return 0;
    std::ptrdiff_t P;
    __builtin_memcpy(&P, Holder, sizeof P);
    *Off = P;
    return 1;
  };
  return bs_descriptor_hash(B, FieldOffset, const_cast<unsigned char *>(B));
}

} // namespace bs

/// The attributes of a descriptor: kept by the compiler (used) and by
/// linkers with --gc-sections (retain), 8-aligned so that readers can step
/// through a section of several descriptors, visible to the firmware even
/// under -fvisibility=hidden.
#define BS_DESCRIPTOR_ATTRIBUTES                                               \
  __attribute__((used, retain, section("bs_modules"), aligned(8),             \
                 visibility("default")))

/// Defines binding module `Name` (a b-script identifier). The body is a
/// sequence of registrations on `module`; it runs at compile time only.
#define BS_MODULE(Name, ...)                                                   \
  struct bs_module_body_##Name {                                               \
    static constexpr const char name[] = #Name;                                \
    static constexpr void run(::bs::Module &module) {                          \
      using namespace ::bs::registration;                                      \
      __VA_ARGS__;                                                             \
    }                                                                          \
  };                                                                           \
  extern "C" BS_DESCRIPTOR_ATTRIBUTES constexpr auto bs_module_##Name =        \
      ::bs::detail::buildModule<bs_module_body_##Name>();

#endif // BSCRIPT_BIND_H

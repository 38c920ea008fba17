//===- bscript/BindDetail.h - how Bind.h writes a descriptor ----*- C++ -*-===//
//
// The machinery behind bscript/Bind.h, which includes it: the descriptor's
// records (bs::detail::rec, pinned to bscript/descriptor.h), how each C++
// type travels between generated code and C++ (the wire types), what a
// registered callable looks like, and the thunks with a plain C signature
// that generated code calls. Nothing here is for robot code to use; read
// Bind.h for the registration API.
//
//===----------------------------------------------------------------------===//
#ifndef BSCRIPT_BINDDETAIL_H
#define BSCRIPT_BINDDETAIL_H

#ifndef BSCRIPT_BIND_H
#error "include bscript/Bind.h, not bscript/BindDetail.h"
#endif

namespace bs {

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
  MemberPure = BS_MEMBER_PURE,
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
  u32 place;
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
              offsetof(Header, stringSize) == BS_HDR_STRING_SIZE &&
              offsetof(Header, place) == BS_HDR_PLACE,
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
  /// Where BS_MODULE is (BS_HDR_PLACE): after the strings, outside the
  /// module hash.
  char place[BS_PLACE_SIZE];
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

namespace detail {

/// The extents of array type X, outermost first.
template <class X> constexpr void setExtents(u32 *Extent) {
  if constexpr (std::is_array_v<X>) {
    *Extent = u32(std::extent_v<X>);
    setExtents<std::remove_extent_t<X>>(Extent + 1);
  }
}

/// Fills in the result fields of member record M for C++ type R.
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

/// Records a callable F as member `Name` of class Owner (None: a module
/// function) and returns its index; defined after Module, whose records it
/// adds. Params, if given, names each parameter the script writes.
template <class T, auto F>
constexpr u32 addCallable(Module &Mod, u32 Owner, const char *Name,
                          const char *CppName,
                          const char *const *Params = nullptr);

/// addCallable with N parameter names, one per parameter the script passes.
template <class T, auto F, std::size_t N>
constexpr void addNamedCallable(Module &Mod, u32 Owner, const char *Name,
                                const char *CppName,
                                const char *const (&Params)[N]);

} // namespace detail

} // namespace bs

#endif // BSCRIPT_BINDDETAIL_H

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
inline void pure_without_a_preceding_func() {}
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

} // namespace bs

// The records, wire types, callables and thunks the builders below use.
#include "BindDetail.h"

namespace bs {

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
  /// `.pure()`: marks the preceding func as pure.
  constexpr void setPure();

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

  /// Declares the preceding .func pure: its result depends on its
  /// arguments (and object) only, and it changes nothing and prints
  /// nothing. The REPL's time travel and exact replays then call it again
  /// rather than keep its result (docs/bindings.md, "Pure functions").
  constexpr ClassBuilder &pure() {
    M->setPure();
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
  /// Declares the function pure (ClassBuilder::pure).
  constexpr FunctionBuilder &pure() {
    M->setPure();
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
    static constexpr const char file[] = __FILE__;                             \
    static constexpr unsigned line = __LINE__;                                 \
    static constexpr void run(::bs::Module &module) {                          \
      using namespace ::bs::registration;                                      \
      __VA_ARGS__;                                                             \
    }                                                                          \
  };                                                                           \
  extern "C" BS_DESCRIPTOR_ATTRIBUTES constexpr auto bs_module_##Name =        \
      ::bs::detail::buildModule<bs_module_body_##Name>();


//===----------------------------------------------------------------------===//
// How the builders fill the descriptor
//===----------------------------------------------------------------------===//

namespace bs {

namespace detail {

/// Records a callable F as member `Name` of class Owner (None: a module
/// function) and returns its index. Params, if given, names each parameter
/// the script writes (ParamsOf::ScriptCount of them).
template <class T, auto F>
constexpr u32 addCallable(Module &Mod, u32 Owner, const char *Name,
                          const char *CppName,
                          const char *const *Params) {
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

constexpr void Module::setPure() {
  if (LastMember == detail::None) {
    error::pure_without_a_preceding_func();
    return;
  }
  if (filling())
    Tabs.members[LastMember].flags |= detail::MemberPure;
}

namespace detail {

/// `file:line` into Place (BS_PLACE_SIZE bytes, NUL-terminated), keeping
/// the end of a path too long for it.
constexpr void writePlace(char *Place, const char *File, unsigned Line) {
  char Digits[12] = {};
  int N = 0;
  do {
    Digits[N++] = char('0' + Line % 10);
    Line /= 10;
  } while (Line);
  std::size_t FileLen = 0;
  while (File[FileLen])
    ++FileLen;
  std::size_t Room = BS_PLACE_SIZE - 2 - N; // ':' and the NUL.
  const char *Tail = FileLen > Room ? File + (FileLen - Room) : File;
  std::size_t At = 0;
  for (; *Tail; ++Tail)
    Place[At++] = *Tail;
  Place[At++] = ':';
  while (N)
    Place[At++] = Digits[--N];
  Place[At] = 0;
}

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
  H.place = offsetof(Data, place);
  writePlace(D.place, Body::file, Body::line);
  return D;
}

} // namespace detail

} // namespace bs

#endif // BSCRIPT_BIND_H

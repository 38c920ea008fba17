// Registrations that must not compile; unittests/Bind/CMakeLists.txt builds
// each CASE with GCC and Clang and checks the message. Without CASE the
// file is valid.
#include <bscript/Bind.h>

struct A {
  int v = 0;
  int f() const { return v; }
  int &get() { return v; }
  const int &get() const { return v; }
};
struct B {
  int g() const { return 1; }
};
struct C {
  int w = 0;
};
struct G {
  int grid[2][3] = {};
  float deep[1][1][1][1][1] = {};
  int *ptrs[2] = {};
};
enum class E { a, b };
enum class F { x };
long long wide(long long X) { return X; }
int *raw(int *P) { return P; }
void outShort(short &S) { S = 1; }
int plain(int X) { return X; }
int two(int X, int Y) { return X + Y; }
int withContext(bs::Context &, int X) { return X; }

#ifndef CASE
#define CASE 0
#endif

BS_MODULE(Cases,
  auto a = registerClass<A>(module, "A");
#if CASE == 1 // a member of an unrelated class
  a.func<&B::g>("g");
#elif CASE == 2 // an unsupported wire type
  registerFunction<&wide>(module, "wide");
#elif CASE == 3
  registerFunction<&raw>(module, "raw");
#elif CASE == 4 // a non-const reference to a non-exact scalar
  registerFunction<&outShort>(module, "outShort");
#elif CASE == 5 // an overload set: use bs::mut, bs::cnst or bs::overload
  a.prop<&A::get>("get");
#elif CASE == 6 // a reinterpret-cast function pointer
  registerFunction<(int (*)(int))(void *)&plain>(module, "plain");
#elif CASE == 7
  a.var<&A::f>("f");
#elif CASE == 8 // a default of the wrong type
  registerFunction<&plain>(module, "plain").defaults(1.5f);
#elif CASE == 9
  registerClass<A>(module, "A2");
#elif CASE == 10
  registerInput<C>(module);
#elif CASE == 11 // a generic lambda
  registerFunction<[](auto X) { return X; }>(module, "generic");
#elif CASE == 12
  registerFunction<&plain>(module, "plain").defaults(1, 2);
#elif CASE == 13
  auto e = registerEnum<E>(module, "E");
  registerEnum<F>(module, "F").value("x", F::x);
  e.value("a", E::a);
#elif CASE == 14 // an array field of five dimensions
  registerClass<G>(module, "G").var<&G::deep>("deep");
#elif CASE == 15 // an array of an unsupported element type
  registerClass<G>(module, "G").var<&G::ptrs>("ptrs");
#elif CASE == 16 // parameter names: one too few
  registerFunction<&plain>(module, "plain", {"a", "b"});
#elif CASE == 17 // parameter names of a constructor: one too many
  registerClass<G>(module, "G").ctor<>({"x"});
#elif CASE == 18 // the same parameter name twice
  registerFunction<&two>(module, "two", {"a", "a"});
#elif CASE == 19 // .pure() after a field, not a function
  a.var<&A::v>("v").pure();
#else
  a.var<&A::v>("v").prop<bs::mut(&A::get)>("get");
  registerClass<G>(module, "G").var<&G::grid>("grid");
  // Names: one (not taken for the C++ name), none for bs::Context &.
  registerFunction<&plain>(module, "plain", {"x"});
  registerFunction<&withContext>(module, "withContext", {"x"}, "withContext");
  registerFunction<&two>(module, "twoPure").pure(); // .pure() is fine here
#endif
)

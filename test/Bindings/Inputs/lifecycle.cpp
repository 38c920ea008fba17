// Bindings for the lifetime tests (test/Bindings/lifecycle*.test,
// test/CodeGen/lifecycle.bs, test/Embedding/destroy.test): classes whose
// constructors and destructor count, so that a run can show that every
// value bsc constructs is destroyed exactly once.
//
// - Counted: default, copy and assign; the destructor prints "~n live"
//   (its value, then how many Counted are still alive) so the order of
//   destructions is visible in the output.
// - Fixed: copy-constructible but not assignable (a const member): bsc
//   assigns it by destroying and copy-constructing.
// - Pinned: not copyable (deleted copy constructor and assignment).
// - Handle: no default constructor, a destructor that counts (its Counted):
//   only a func may hold one, initialised.
// - Plain: no default constructor, but trivially copyable and destructible,
//   so it may start as zero bytes anywhere.
#include <bscript/Bind.h>
#include <cstdio>

namespace lc {
int Made = 0, Destroyed = 0;

struct Counted {
  int n = 0;
  Counted() { ++Made; }
  Counted(const Counted &O) : n(O.n) { ++Made; }
  Counted &operator=(const Counted &O) = default;
  ~Counted() {
    ++Destroyed;
    std::printf("~%d %d\n", n, Made - Destroyed);
    n = -1000; // a use after destruction shows up as -1000
  }
  Counted plus(const Counted &O) const {
    Counted R;
    R.n = n + O.n;
    return R;
  }
  bool positive() const { return n > 0; }
};

Counted make(int N) {
  Counted C;
  C.n = N;
  return C;
}
int live() { return Made - Destroyed; }
int made() { return Made; }

struct Fixed {
  const int id;
  Counted c;
  Fixed() : id(0) {}
  Fixed(const Fixed &O) = default;
  int get() const { return c.n; }
};

struct Pinned {
  int n = 0;
  Pinned() = default;
  Pinned(const Pinned &) = delete;
  Pinned &operator=(const Pinned &) = delete;
  ~Pinned() {}
};

struct Handle {
  Counted c;
  explicit Handle(int N) { c.n = N; }
  int get() const { return c.n; }
};
Handle handle(int N) { return Handle(N); }

struct Plain {
  int v;
  explicit Plain(int V) : v(V) {}
};
Plain plain(int V) { return Plain(V); }
} // namespace lc

BS_MODULE(Life,
  registerClass<lc::Counted>(module, "Counted")
    .var<&lc::Counted::n>("n")
    .func<&lc::Counted::plus>("plus")
    .func<&lc::Counted::positive>("positive");
  registerFunction<&lc::make>(module, "make");
  registerFunction<&lc::live>(module, "live");
  registerFunction<&lc::made>(module, "made");
  registerClass<lc::Fixed>(module, "Fixed")
    .func<&lc::Fixed::get>("get");
  registerClass<lc::Pinned>(module, "Pinned")
    .var<&lc::Pinned::n>("n");
  registerClass<lc::Handle>(module, "Handle")
    .func<&lc::Handle::get>("get");
  registerFunction<&lc::handle>(module, "handle");
  registerClass<lc::Plain>(module, "Plain")
    .var<&lc::Plain::v>("v");
  registerFunction<&lc::plain>(module, "plain");
)

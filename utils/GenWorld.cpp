// The binding module of utils/gen-program.py's random programs: the world
// module `Gen`, so that differential testing (utils/diff-test.py) reaches
// registered C++ as behaviors do: class values with fields, properties,
// methods, operators and constructors, array fields of every element kind
// (clamped computed indices), registered enums and constants, functions
// with C++ defaults and a `bs::Context &`, and `input`/`output`.
//
// test/CMakeLists.txt compiles it with GCC for the host and for i586
// (bind-objects/GenWorld.{host,i586}.o), as a robot build would. What C++
// computes must be the same on both: each float result is one IEEE
// operation on floats (an x87 result rounded to float then equals the SSE
// one), integer arithmetic wraps through uint32_t (no signed overflow), and
// a NaN is printed as "nan" whatever its sign bit.
#include <bscript/Bind.h>
#include <cstdint>
#include <cstdio>

namespace gen {
enum class Mode : std::uint8_t { idle = 0, walk = 1, kick = 2 };

struct Vec {
  float x = 0, y = 0;
  Vec() = default;
  Vec(float X, float Y) : x(X), y(Y) {}
  explicit Vec(int N) : x(float(N)), y(0.5f) {}
  int quad() const { return (x < 0 ? 1 : 0) + (y < 0 ? 2 : 0); }
  void flip() {
    float T = x;
    x = y;
    y = T;
  }
};
Vec plus(const Vec &A, const Vec &B) { return {A.x + B.x, A.y + B.y}; }
Vec minus(const Vec &A, const Vec &B) { return {A.x - B.x, A.y - B.y}; }
Vec times(const Vec &A, float F) { return {A.x * F, A.y * F}; }
Vec negate(const Vec &A) { return {-A.x, -A.y}; }
bool equals(const Vec &A, const Vec &B) { return A.x == B.x && A.y == B.y; }
bool less(const Vec &A, const Vec &B) { return A.x < B.x; }

struct Buf {
  std::int32_t vals[4] = {3, -1, 7, 100};
  float grid[2][3] = {{0.5f, -1.5f, 2.0f}, {1e30f, -0.0f, 3.25f}};
  std::int16_t small[3] = {-2, 300, -32768};
  std::uint8_t bytes[2] = {250, 7};
  double dbl[2] = {0.25, -1e40};
  bool flags[2] = {true, false};
  Mode modes[2] = {Mode::walk, Mode::kick};
  Vec pts[2] = {{1.5f, -2.0f}, {0.25f, 8.0f}};
  int tag = 0;
  int getTag() const { return tag; }
  void setTag(int T) { tag = int(std::uint32_t(T) * 2u); }
};
/// A method written as a free function: the sum of vals, wrapping.
int total(const Buf &B) {
  std::uint32_t Sum = 0;
  for (std::int32_t V : B.vals)
    Sum += std::uint32_t(V);
  return int(Sum);
}

int mix(int A, int B) { return int(std::uint32_t(A) * 31u + std::uint32_t(B)); }

// Calls with effects, which the REPL's time travel and exact replays must
// take from their record (docs/repl.md "Going back in time"): a counter
// and a random generator with hidden C++ state, and a write to `input`
// through the context, as a simulation stepped by the behavior would.
inline std::uint32_t Ticks = 0, Seed = 7;
int tick() { return int(++Ticks); }
int rnd() {
  Seed = Seed * 1103515245u + 12345u;
  return int((Seed >> 16) & 0x7fffu);
}

float nudge(float V) { return V + 0.25f; }
int cycleOf(bs::Context &C) { return int(C.cycle()); }

struct In {
  int time = 1000;
  std::int32_t vals[3] = {5, -6, 2147483647};
  float dist[2] = {0.5f, 1e30f};
  Vec ball{3.0f, -4.0f};
  Mode mode = Mode::walk;
  bool seen = true;
};
/// Adds V to the input's time, wrapping, through the context's pointer.
void poke(bs::Context &C, int V) {
  auto *I = static_cast<In *>(const_cast<void *>(C.input()));
  I->time = int(std::uint32_t(I->time) + std::uint32_t(V));
}

static void printFloat(float V) {
  if (V != V)
    std::printf(" nan");
  else
    std::printf(" %g", double(V));
}

/// The output is write-only in b-script: it shows what the behavior wrote
/// when the program ends (bsc run and programs destroy it last).
struct Out {
  std::int32_t vals[3] = {};
  float head[2][2] = {};
  std::int16_t small[2] = {};
  Vec target;
  Mode mode = Mode::idle;
  ~Out() {
    std::printf("out");
    for (std::int32_t V : vals)
      std::printf(" %d", int(V));
    for (auto &Row : head)
      for (float V : Row)
        printFloat(V);
    std::printf(" %d %d", int(small[0]), int(small[1]));
    printFloat(target.x);
    printFloat(target.y);
    std::printf(" %d\n", int(mode));
  }
};
} // namespace gen

using gen::Buf;
using gen::Vec;

BS_MODULE(Gen,
  registerEnum<gen::Mode>(module, "Mode")
    .value("idle", gen::Mode::idle)
    .value("walk", gen::Mode::walk)
    .value("kick", gen::Mode::kick);
  registerClass<Vec>(module, "Vec", "gen::Vec")
    .ctor<>()
    .ctor<float, float>()
    .ctor<int>()
    .var<&Vec::x>("x")
    .var<&Vec::y>("y")
    .func<&Vec::quad>("quad")
    .func<&Vec::flip>("flip")
    .func<&gen::plus>("_plus_")
    .func<&gen::minus>("_min_")
    .func<&gen::times>("_mul_")
    .func<&gen::negate>("_neg_")
    .func<&gen::equals>("_eq_")
    .func<&gen::less>("_lt_");
  registerClass<Buf>(module, "Buf", "gen::Buf")
    .ctor<>()
    .var<&Buf::vals>("vals")
    .var<&Buf::grid>("grid")
    .var<&Buf::small>("small")
    .var<&Buf::bytes>("bytes")
    .var<&Buf::dbl>("dbl")
    .var<&Buf::flags>("flags")
    .var<&Buf::modes>("modes")
    .var<&Buf::pts>("pts")
    .prop<&Buf::getTag, &Buf::setTag>("tag")
    .func<&gen::total>("total");
  registerFunction<&gen::mix>(module, "mix").defaults(3).pure();
  registerFunction<&gen::tick>(module, "tick");
  registerFunction<&gen::rnd>(module, "rnd");
  registerFunction<&gen::poke>(module, "poke");
  registerFunction<&gen::nudge>(module, "nudge");
  registerFunction<&gen::cycleOf>(module, "cycleOf");
  registerConstant(module, "LIMIT", 7);
  registerConstant(module, "HALF", 0.5f);
  registerConstant(module, "START", gen::Mode::walk);
  registerClass<gen::In>(module, "In", "gen::In")
    .var<&gen::In::time>("time")
    .var<&gen::In::vals>("vals")
    .var<&gen::In::dist>("dist")
    .var<&gen::In::ball>("ball")
    .var<&gen::In::mode>("mode")
    .var<&gen::In::seen>("seen");
  registerClass<gen::Out>(module, "Out", "gen::Out")
    .var<&gen::Out::vals>("vals")
    .var<&gen::Out::head>("head")
    .var<&gen::Out::small>("small")
    .var<&gen::Out::target>("target")
    .var<&gen::Out::mode>("mode")
    .copyAsBytes(); // Its destructor only prints: the REPL may keep copies.
  registerInput<gen::In>(module);
  registerOutput<gen::Out>(module);
)

// Bindings for the front-end tests of registered classes (test/Bindings/*.bs):
// a value class with fields, methods (const and not), defaults and
// operators; module functions taking classes; and a world module whose
// input/output types have nested classes, read-only members, properties
// and a non-const method. Built for the host and i586 by test/CMakeLists.txt.
#include <bscript/Bind.h>

namespace t {
struct Vec {
  float x = 0, y = 0;
  float len() const { return x * x + y * y; }
  void scale(float F) { x *= F, y *= F; }
  void move(float DX, float DY = 1.5f, bool Twice = false) {
    x += Twice ? 2 * DX : DX;
    y += DY;
  }
};
Vec add(const Vec &A, const Vec &B) { return {A.x + B.x, A.y + B.y}; }
Vec sub(const Vec &A, const Vec &B) { return {A.x - B.x, A.y - B.y}; }
Vec neg(const Vec &A) { return {-A.x, -A.y}; }
Vec mul(const Vec &A, float F) { return {A.x * F, A.y * F}; }
bool eq(const Vec &A, const Vec &B) { return A.x == B.x && A.y == B.y; }
bool lt(const Vec &A, const Vec &B) { return A.len() < B.len(); }
Vec make(float X, float Y) { return {X, Y}; }
void bump(Vec &V) { V.x += 1; }
int twice(int V) { return 2 * V; }

enum class Color { red, green };

/// A const field is read-only (and makes the class non-assignable, so it
/// is never a field itself).
struct Tag {
  const int id = 3;
  int n = 0;
};
struct Sensor {
  Vec pos;
  int count = 0;
  int getCount() const { return count; }
  void setCount(int C) { count = C; }
  void tick() { ++count; }
  float read() const { return pos.x; }
};
struct In {
  Sensor sensor;
  Vec target;
  int time = 0;
  Color color = Color::red;
};
struct Out {
  Vec walk;
  int motion = 0;
  Color color = Color::red;
};
} // namespace t

using t::Vec;

BS_MODULE(Geo,
  registerClass<Vec>(module, "Vec", "t::Vec")
    .var<&Vec::x>("x")
    .var<&Vec::y>("y")
    .func<&Vec::len>("len")
    .func<&Vec::scale>("scale")
    .func<&Vec::move>("move").defaults(1.5f, false)
    .func<&t::add>("_plus_")
    .func<&t::sub>("_min_")
    .func<&t::neg>("_neg_")
    .func<&t::mul>("_mul_")
    .func<&t::eq>("_eq_")
    .func<&t::lt>("_lt_");
  registerFunction<&t::make>(module, "make");
  registerFunction<&t::bump>(module, "bump");
  registerFunction<&t::twice>(module, "twice").defaults(4);
)

BS_MODULE(Robot,
  registerEnum<t::Color>(module, "Color")
    .value("red", t::Color::red)
    .value("green", t::Color::green);
  registerClass<t::Tag>(module, "Tag")
    .var<&t::Tag::id>("id")
    .var<&t::Tag::n>("n");
  registerClass<t::Sensor>(module, "Sensor")
    .var<&t::Sensor::pos>("pos")
    .prop<&t::Sensor::getCount, &t::Sensor::setCount>("count")
    .prop<&t::Sensor::getCount>("countRO")
    .func<&t::Sensor::tick>("tick")
    .func<&t::Sensor::read>("read");
  registerClass<t::In>(module, "In")
    .var<&t::In::sensor>("sensor")
    .var<&t::In::target>("target")
    .var<&t::In::time>("time")
    .var<&t::In::color>("color");
  registerClass<t::Out>(module, "Out")
    .var<&t::Out::walk>("walk")
    .var<&t::Out::motion>("motion")
    .var<&t::Out::color>("color");
  registerInput<t::In>(module);
  registerOutput<t::Out>(module);
)

// Every registration form of bscript/Bind.h; read back by unittests/Bind.
#include <bscript/Bind.h>
#include <cmath>

namespace geo {
struct Base {
  int id = 7;
  int getId() const { return id; }
};
struct Point : Base {
  float x = 0, y = 0;
  double weight = 1.0; // 4-aligned on i386, 8 on x86-64
  const int version = 3;
  bool flag = false;
  Point() = default;
  Point(float x, float y) : x(x), y(y) {}
  Point &operator=(const Point &O) {
    x = O.x;
    y = O.y;
    return *this;
  }
  Point(const Point &) = default;
  float length() const { return std::sqrt(x * x + y * y); }
  void scale(float f) { x *= f, y *= f; }
  Point plus(const Point &o) const { return Point(x + o.x, y + o.y); }
  float &rx() { return x; }
  const float &rx() const { return x; }
  float getY() const { return y; }
  void setY(float v) { y = v; }
  void move(float dx, float dy = 1.5f, bool twice = false) {
    x += twice ? 2 * dx : dx;
    y += dy;
  }
  unsigned short tag() const { return 5; }
};
enum Color : unsigned char { red, green = 5, blue = 200 };
enum class Mode : int { off = -1, on = 1 };

float dist(const Point &a, const Point &b) { return a.plus(b).length(); }
void reset(Point &p) { p = Point(); }
int twice(int v) { return 2 * v; }
Mode flip(Mode m) { return m == Mode::on ? Mode::off : Mode::on; }
void outParams(int &i, float &f, bool &b) {
  i = 1;
  f = 2;
  b = true;
}
Point origin() { return Point(); }
const char *greet(const char *who) { return who; }
} // namespace geo

using geo::Point;

BS_MODULE(Forms,
  registerClass<Point>(module, "Point", "geo::Point")
    .var<&Point::x>("x")
    .var<&Point::y>("y")
    .var<&Point::weight>("weight")
    .var<&Point::version>("version")
    .var<&Point::flag>("flag")
    .var<&Point::id>("id")
    .func<&Point::length>("length")
    .func<&Point::scale>("scale")
    .func<&Point::plus>("_plus_", "plus")
    .func<&Point::getId>("getId")
    .func<&Point::tag>("tag")
    .func<&Point::move>("move", {"dx", "dy", "twice"}).defaults(1.5f, false)
    .prop<bs::mut(&Point::rx)>("rx")
    .prop<bs::cnst(&Point::rx)>("crx")
    .prop<&Point::getY, &Point::setY>("py")
    .func<&geo::dist>("dist", {"other"})
    .func<&geo::reset>("reset")
    .func<[](const Point &a, const Point &b) { return Point(a.x - b.x, a.y - b.y); }>("_min_", "operator-")
    .func<[](const Point &a) { return Point(-a.x, -a.y); }>("_neg_")
    .func<&geo::origin>("origin");
  registerEnum<geo::Color>(module, "Color", "geo::Color")
    .value("red", geo::red).value("green", geo::green).value("blue", geo::blue);
  registerEnum<geo::Mode>(module, "Mode").value("off", geo::Mode::off).value("on", geo::Mode::on);
  registerFunction<&geo::twice>(module, "twice", {"v"}, "geo::twice").defaults(4);
  registerFunction<&geo::flip>(module, "flip").defaults(geo::Mode::on);
  registerFunction<&geo::outParams>(module, "outParams");
  registerFunction<bs::overload<float(float)>(&std::fabs)>(module, "fabs", "std::fabs");
  registerFunction(module, "twice2", bs::fn<&geo::twice>, {"v"});
  registerFunction<&geo::greet>(module, "greet");
  registerFunction<[](int a, int b) { return (a > b) ? a : b; }>(module, "max");
)

// Used by ctors_constants.test: constructors (.ctor<A...>()) and module
// constants (registerConstant) of a binding module.
#include <bscript/Bind.h>

namespace geo {
struct Pose2f {
  float x = 0, y = 0, rotation = 0;
  Pose2f() = default;
  Pose2f(float R) : rotation(R) {}
  Pose2f(float X, float Y, float R = 0.25f) : x(X), y(Y), rotation(R) {}
  Pose2f(int X, int Y) : x(float(X) * 10), y(float(Y) * 10) {}
};
struct NoCtor {
  int v = 0;
};
struct Pair {
  float a = 0, b = 0;
  Pair(float A, int B) : a(A), b(float(B)) {}
  Pair(int A, float B) : a(float(A)), b(B) {}
};
enum class Side { left = 1, right = 2 };
} // namespace geo

BS_MODULE(Geo,
  registerClass<geo::Pose2f>(module, "Pose2f")
    .var<&geo::Pose2f::x>("x")
    .var<&geo::Pose2f::y>("y")
    .var<&geo::Pose2f::rotation>("rotation")
    .ctor<>()
    .ctor<float>({"rotation"})
    .ctor<float, float, float>({"x", "y", "rotation"}).defaults(0.25f)
    .ctor<int, int>()
    // A method with the context after the object: the cycle it ran in.
    .func<[](const geo::Pose2f &P, bs::Context &C) {
      return P.x + float(C.cycle());
    }>("xPlusCycle");
  registerClass<geo::NoCtor>(module, "NoCtor").var<&geo::NoCtor::v>("v");
  registerClass<geo::Pair>(module, "Pair")
    .var<&geo::Pair::a>("a")
    .ctor<float, int>()
    .ctor<int, float>();
  registerEnum<geo::Side>(module, "Side")
    .value("left", geo::Side::left)
    .value("right", geo::Side::right);
  registerConstant(module, "off", 10000);
  registerConstant(module, "half", 0.5f);
  registerConstant(module, "enabled", true);
  registerConstant(module, "favourite", geo::Side::right);
)

// Eigen types in bindings: members inherited from Eigen's bases, overload
// sets, lazy operators, 16-byte alignment on geode, double fields.
#include <Eigen/Dense>
#include <bscript/Bind.h>

using Eigen::Vector2d;
using Eigen::Vector2f;
using Eigen::Vector4f;

struct Pose {
  Vector2f translation = Vector2f::Zero();
  float rotation = 0;
  double stamp = 0; // 4-aligned on i386, 8 on x86-64
};

struct Aligned {
  char tag = 0;
  Vector4f v = Vector4f::Zero(); // 16-aligned even on geode
};

BS_MODULE(Geo,
  registerClass<Vector2f>(module, "Vector2f", "Eigen::Vector2f")
    .prop<bs::mut(&Vector2f::x)>("x")
    .prop<bs::cnst(&Vector2f::y)>("y")
    .func<&Vector2f::norm>("abs", "norm")
    .func<&Vector2f::squaredNorm>("squaredNorm")
    .func<&Vector2f::normalized>("normalized")
    .func<bs::overload<void()>(&Vector2f::normalize)>("normalize")
    .func<&bs::op::plus<Vector2f>>("_plus_", "operator+")
    .func<&bs::op::minus<Vector2f>>("_min_", "operator-")
    .func<&bs::op::neg<Vector2f>>("_neg_")
    .func<&bs::op::scale<Vector2f>>("_mul_")
    .func<&bs::op::equals<Vector2f>>("_eq_")
    .func<[](const Vector2f &A, const Vector2f &B) { return A.dot(B); }>("dot");
  registerClass<Vector4f>(module, "Vector4f", "Eigen::Vector4f")
    .func<&Vector4f::norm>("abs")
    .func<&bs::op::plus<Vector4f>>("_plus_");
  registerClass<Vector2d>(module, "Vector2d", "Eigen::Vector2d")
    .prop<bs::mut(&Vector2d::x)>("x")
    .func<&Vector2d::norm>("abs");
  registerClass<Pose>(module, "Pose")
    .var<&Pose::translation>("translation")
    .var<&Pose::rotation>("rotation")
    .var<&Pose::stamp>("stamp");
  registerClass<Aligned>(module, "Aligned")
    .var<&Aligned::tag>("tag")
    .var<&Aligned::v>("v");
  registerFunction<[](float X, float Y) { return Vector2f(X, Y); }>(module, "vec");
)

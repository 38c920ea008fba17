//===- SoccerBindings.cpp - the soccer world of the paper's examples ------===//
//
// The bindings that the paper's programs (shared/conformance/paper: Kick.bs,
// Motion.bs, Head.bs, Behavior.bs) assume, registered the way robot code
// registers its own types (docs/bindings.md):
//
//   module Math:  class Vector2f (Eigen::Vector2f) with fields x, y, method
//                 abs() (the Euclidean norm), operators + and - (_plus_,
//                 _min_), and function fabs(float x).
//   module World: enum MotionType {stand, walk, kick}; the type of `input`
//                 (ball.position, oppGoal, time in ms, executedMotion) and of
//                 `output` (motion, walkTarget, headTarget). World declares
//                 input and output, so its names (MotionType, ...) are
//                 visible unqualified in every script, as in the paper.
//
// Build it for the robot like any binding object, e.g.
//   g++ -std=c++20 -m32 -march=i586 -mtune=geode -O2 -I/usr/include/eigen3 -c
//   clang++ -std=c++20 --target=i586-linux-gnu -march=geode -O2 ... -c
// and pass the object to bsc with --bind (the same object that is linked).
//
//===----------------------------------------------------------------------===//
#include "SoccerWorld.h"

#include <bscript/Bind.h>
#include <cmath>

namespace Math {
/// The paper's `fabs`; a wrapper so the registration names one function.
float fabs(float X) { return std::fabs(X); }
} // namespace Math

using Math::Vector2f;

// The math is pure: the REPL's time travel and exact replays call it again
// rather than keep its results (docs/bindings.md, "Pure functions").
// bench/repl.sh also builds it with -DSOCCER_KEEP_MATH to measure both ways.
#ifdef SOCCER_KEEP_MATH
#define SOCCER_PURE
#else
#define SOCCER_PURE .pure()
#endif

BS_MODULE(Math,
  registerClass<Vector2f>(module, "Vector2f", "Eigen::Vector2f")
    // Eigen's x()/y() are overloaded (const and non-const) and inherited
    // from DenseCoeffsBase: pick the non-const one, which returns float&
    // and so gives read/write access.
    .prop<bs::mut(&Vector2f::x)>("x")
    .prop<bs::mut(&Vector2f::y)>("y")
    .func<&Vector2f::norm>("abs", "norm") SOCCER_PURE
    // Eigen's operators return lazy expressions: evaluate them.
    .func<&bs::op::plus<Vector2f>>("_plus_", "operator+") SOCCER_PURE
    .func<&bs::op::minus<Vector2f>>("_min_", "operator-") SOCCER_PURE
    .func<&bs::op::neg<Vector2f>>("_neg_", "operator-") SOCCER_PURE
    .func<&bs::op::scale<Vector2f>>("_mul_", "operator*") SOCCER_PURE
    .func<&bs::op::divideBy<Vector2f>>("_div_", "operator/") SOCCER_PURE
    .func<&bs::op::equals<Vector2f>>("_eq_", "operator==") SOCCER_PURE
    .func<&bs::op::notEquals<Vector2f>>("_ne_", "operator!=") SOCCER_PURE
    // dot() takes `const MatrixBase<D>&`: wrap it so the parameter is a
    // registered type.
    .func<[](const Vector2f &A, const Vector2f &B) { return A.dot(B); }>(
        "dot", {"other"}, "dot") SOCCER_PURE
    .copyAsBytes();
  // The parameter names show in --dump-bindings and in messages.
  registerFunction<&Math::fabs>(module, "fabs", {"x"}, "Math::fabs") SOCCER_PURE;
)

BS_MODULE(World,
  registerEnum<MotionType>(module, "MotionType")
    .value("stand", MotionType::stand)
    .value("walk", MotionType::walk)
    .value("kick", MotionType::kick);
  registerClass<BallModel>(module, "BallModel")
    .var<&BallModel::position>("position");
  registerClass<BehaviorInput>(module, "BehaviorInput")
    .var<&BehaviorInput::ball>("ball")
    .var<&BehaviorInput::oppGoal>("oppGoal")
    .var<&BehaviorInput::time>("time")
    .var<&BehaviorInput::executedMotion>("executedMotion");
  registerClass<BehaviorOutput>(module, "BehaviorOutput")
    .var<&BehaviorOutput::motion>("motion")
    .var<&BehaviorOutput::walkTarget>("walkTarget")
    .var<&BehaviorOutput::headTarget>("headTarget");
  registerInput<BehaviorInput>(module);
  registerOutput<BehaviorOutput>(module);
)

//===- SoccerWorld.h - the robot-side types of the soccer examples --------===//
//
// What the robot code of the paper's examples would declare: the behavior's
// input (world model) and output (motion and head requests). Shared by the
// bindings (SoccerBindings.cpp) and by any host program that runs the
// compiled behavior.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_EXAMPLES_SOCCER_WORLD_H
#define BSC_EXAMPLES_SOCCER_WORLD_H

#include <Eigen/Dense>

namespace Math {
using Vector2f = Eigen::Vector2f;
float fabs(float X);
} // namespace Math

enum class MotionType { stand, walk, kick };

struct BallModel {
  Math::Vector2f position = Math::Vector2f::Zero(); ///< mm, robot-relative
};

struct BehaviorInput {
  BallModel ball;
  Math::Vector2f oppGoal = Math::Vector2f::Zero(); ///< mm, robot-relative
  int time = 0;                                    ///< ms
  MotionType executedMotion = MotionType::stand;
};

struct BehaviorOutput {
  MotionType motion = MotionType::stand;
  Math::Vector2f walkTarget = Math::Vector2f::Zero();
  Math::Vector2f headTarget = Math::Vector2f::Zero();
};

#endif

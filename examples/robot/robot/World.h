// The robot's view of the world, as its C++ code declares it: what the
// behavior senses (Input) and what it asks for (Output).
#ifndef ROBOT_WORLD_H
#define ROBOT_WORLD_H

namespace robot {
struct Vec2 {
  float x = 0, y = 0;
};
enum class Motion { stand, walk, kick };
struct Input {
  int cycle = 0;
  Vec2 self; ///< where the robot is
  Vec2 ball;
};
struct Output {
  Motion motion = Motion::stand;
  Vec2 target; ///< where to walk
};
} // namespace robot

#endif

// The world of docs/language.md's CABSL idiom (cabsl_option.test,
// world.test): what the robot gives the behavior and what it reads back.
#ifndef CABSL_WORLD_H
#define CABSL_WORLD_H

namespace sw {
struct In {
  int time = 0;
  float ballDistance = 0;
  bool ballSeen = false;
};
struct Out {
  int motion = 0; // 0 stand, 1 walk, 2 align, 3 kick
  float kickPower = 0;
};
} // namespace sw

#endif

// team.h - the types the robots and their bindings share.
#ifndef TEAM_H
#define TEAM_H

namespace team {
enum class HeadMode { lookForward, lookAtBall, sweep };

struct Input {
  bool ballSeen = false;
  float ballDistance = 0;
};
struct Output {
  int headPan = 0;
  float walkSpeed = 0;
};

/// One robot's blackboard: what bs_state_set_user attaches to its state.
struct Robot {
  const char *name;
  HeadMode headMode = HeadMode::lookForward;
};
} // namespace team

#endif

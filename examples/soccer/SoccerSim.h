//===- SoccerSim.h - a small deterministic 2-D soccer world ---------------===//
//
// The closed-loop world of the soccer example (host.cpp): one robot, one
// ball and the opponent goal on a flat field, stepped once per 30 Hz cycle.
// The state is integer millimetres, so the world behaves identically on
// i586 (x87) and x86-64; the behavior sees it as floats that are exact
// (integers far below 2^24).
//
// Rules (the lit tests derive their expected cycle numbers from these):
// - cycle n (1, 2, ...) has time (n - 1) * 33 ms;
// - the robot never turns: robot-relative is field position minus robot
//   position;
// - walk: the robot moves toward output.walkTarget (robot-relative) by
//   WalkSpeed mm per cycle, each coordinate dx * WalkSpeed / |d| truncated
//   toward zero, |d| the integer square root of dx^2 + dy^2; a target
//   nearer than WalkSpeed is reached exactly;
// - kick: a kick request while the motion layer stands starts a kick of
//   KickCycles cycles; input.executedMotion is kick in the KickCycles cycles
//   after the request, then stand again. At the end of the kick's
//   KickContact-th cycle the foot meets the ball: if the ball is at most
//   KickRange mm away it moves KickDistance mm further along the line from
//   robot to ball (integer arithmetic as for walking). Requests during a
//   kick are ignored;
// - stand: nothing moves.
//
//===----------------------------------------------------------------------===//
#ifndef BSC_EXAMPLES_SOCCER_SIM_H
#define BSC_EXAMPLES_SOCCER_SIM_H

#include "SoccerWorld.h"

#include <cstdint>

namespace soccer {

/// An integer field position or offset in millimetres.
struct Point {
  int32_t x = 0, y = 0;
};

/// The integer square root (floor) of a non-negative value.
int64_t isqrt(int64_t V);

/// |P| in whole millimetres (floor of the Euclidean norm).
int32_t length(Point P);

class World {
public:
  static constexpr int CycleMs = 33;
  static constexpr int WalkSpeed = 10;     ///< mm per cycle
  static constexpr int KickCycles = 10;    ///< executedMotion == kick this long
  static constexpr int KickContact = 5;    ///< the kick's cycle that hits
  static constexpr int KickRange = 150;    ///< mm: nearer balls are hit
  static constexpr int KickDistance = 2000; ///< mm the hit ball travels

  /// Robot at the origin; ball and opponent goal at these field positions.
  World(Point Ball, Point OppGoal);

  /// The behavior's input for the current cycle.
  void fillInput(BehaviorInput &In) const;

  /// Executes the behavior's output of the current cycle and advances to
  /// the next cycle. Returns what the motion layer did (see Event).
  enum Event { None, KickStarted, BallKicked, KickMissed, KickFinished };
  Event step(const BehaviorOutput &Out);

  int cycle() const { return Cycle; }
  int timeMs() const { return (Cycle - 1) * CycleMs; }
  Point robot() const { return Robot; }
  Point ball() const { return Ball; }
  /// Ball relative to the robot.
  Point ballRel() const { return {Ball.x - Robot.x, Ball.y - Robot.y}; }
  int32_t ballDistance() const { return length(ballRel()); }
  MotionType executed() const {
    return KickPhase > 0 ? MotionType::kick : MotionType::stand;
  }
  bool ballWasKicked() const { return Kicked; }

private:
  Point Robot, Ball, Goal;
  int Cycle = 1;
  int KickPhase = 0; ///< 0: standing/walking; k: in the kick's k-th cycle
  bool Kicked = false;
};

} // namespace soccer

#endif

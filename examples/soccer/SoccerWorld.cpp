//===- SoccerWorld.cpp - a small deterministic 2-D soccer world -----------===//
//
// See SoccerSim.h for the rules. Everything is integer arithmetic; the only
// floats are the behavior's input and output, which hold exact integers.
//
//===----------------------------------------------------------------------===//
#include "SoccerSim.h"

namespace soccer {

int64_t isqrt(int64_t V) {
  if (V <= 0)
    return 0;
  int64_t R = 0, Bit = int64_t(1) << 62;
  while (Bit > V)
    Bit >>= 2;
  while (Bit != 0) {
    if (V >= R + Bit) {
      V -= R + Bit;
      R = (R >> 1) + Bit;
    } else {
      R >>= 1;
    }
    Bit >>= 2;
  }
  return R;
}

int32_t length(Point P) {
  return int32_t(isqrt(int64_t(P.x) * P.x + int64_t(P.y) * P.y));
}

/// Rounds a float that the behavior copied from an exact integer input (or
/// computed from such) to the nearest millimetre, the same way on x87 and
/// SSE.
static int32_t toMm(float F) {
  return F >= 0 ? int32_t(F + 0.5f) : -int32_t(-F + 0.5f);
}

/// D scaled to length Len (truncated toward zero per coordinate).
static Point scaled(Point D, int32_t Len) {
  int64_t L = length(D);
  if (L == 0)
    return {};
  return {int32_t(int64_t(D.x) * Len / L), int32_t(int64_t(D.y) * Len / L)};
}

World::World(Point Ball, Point OppGoal) : Ball(Ball), Goal(OppGoal) {}

void World::fillInput(BehaviorInput &In) const {
  Point B = ballRel();
  In.ball.position = Math::Vector2f(float(B.x), float(B.y));
  In.oppGoal = Math::Vector2f(float(Goal.x - Robot.x), float(Goal.y - Robot.y));
  In.time = timeMs();
  In.executedMotion = executed();
}

World::Event World::step(const BehaviorOutput &Out) {
  Event E = None;
  if (KickPhase > 0) {
    // Kicking: requests are ignored until the kick is over.
    if (KickPhase == KickContact) {
      Point B = ballRel();
      if (length(B) <= KickRange) {
        Point D = scaled(B, KickDistance);
        Ball.x += D.x;
        Ball.y += D.y;
        Kicked = true;
        E = BallKicked;
      } else {
        E = KickMissed;
      }
    }
    if (++KickPhase > KickCycles) {
      KickPhase = 0;
      E = KickFinished;
    }
  } else if (Out.motion == MotionType::kick) {
    KickPhase = 1;
    E = KickStarted;
  } else if (Out.motion == MotionType::walk) {
    Point T{toMm(Out.walkTarget.x()), toMm(Out.walkTarget.y())};
    Point D = length(T) <= WalkSpeed ? T : scaled(T, WalkSpeed);
    Robot.x += D.x;
    Robot.y += D.y;
  }
  ++Cycle;
  return E;
}

} // namespace soccer

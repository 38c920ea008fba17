//===- stub/world-test.cpp - the soccer world's rules, scripted -----------===//
//
// Drives soccer::World (SoccerWorld.cpp) with scripted outputs, no
// behavior: the corner cases the closed loop does not reach. Prints one
// line per check; test/Bindings/soccer-world.test runs it for both targets.
//
//===----------------------------------------------------------------------===//
#include "SoccerSim.h"

#include <cstdio>

using soccer::World;

static int Failures = 0;
static void check(bool OK, const char *What) {
  std::printf("%s: %s\n", OK ? "ok" : "FAIL", What);
  Failures += !OK;
}

static BehaviorOutput request(MotionType M, float X = 0, float Y = 0) {
  BehaviorOutput Out;
  Out.motion = M;
  Out.walkTarget = Math::Vector2f(X, Y);
  return Out;
}

int main() {
  check(soccer::isqrt(0) == 0 && soccer::isqrt(99) == 9 &&
            soccer::isqrt(100) == 10 &&
            soccer::isqrt(int64_t(3000000000) * 3000000000) == 3000000000 &&
            soccer::isqrt(int64_t(3000000000) * 3000000000 - 1) == 2999999999,
        "isqrt");

  {
    World W({800, 600}, {4500, 0});
    BehaviorInput In;
    W.fillInput(In);
    check(In.ball.position == Math::Vector2f(800, 600) &&
              In.oppGoal == Math::Vector2f(4500, 0) && In.time == 0 &&
              In.executedMotion == MotionType::stand,
          "input of cycle 1");
    W.step(request(MotionType::walk, 800, 600));
    W.fillInput(In);
    check(W.cycle() == 2 && In.time == 33 &&
              In.ball.position == Math::Vector2f(792, 594),
          "a walking step is (8, 6) toward (800, 600)");
    W.step(request(MotionType::walk, 3, -4));
    check(W.robot().x == 11 && W.robot().y == 2,
          "a target nearer than a step is reached exactly");
    W.step(request(MotionType::walk, -0.6f, 0.4f));
    check(W.robot().x == 10 && W.robot().y == 2,
          "walk targets round to the nearest millimetre");
    W.step(request(MotionType::stand, 500, 500));
    check(W.robot().x == 10 && W.robot().y == 2, "stand does not move");
  }

  {
    // A kick 1000 mm from the ball misses; requests during it are ignored.
    World W({1000, 0}, {4500, 0});
    check(W.step(request(MotionType::kick)) == World::KickStarted,
          "a kick request starts the kick");
    bool AllKick = true, Missed = false;
    for (int K = 1; K <= World::KickCycles; ++K) {
      AllKick &= W.executed() == MotionType::kick;
      World::Event E = W.step(request(MotionType::walk, 1000, 0));
      Missed |= E == World::KickMissed && K == World::KickContact;
      if (K == World::KickCycles)
        check(E == World::KickFinished, "the kick finishes after 10 cycles");
    }
    check(AllKick, "executedMotion is kick for 10 cycles");
    check(Missed && !W.ballWasKicked() && W.ball().x == 1000,
          "a ball out of range is missed");
    check(W.executed() == MotionType::stand && W.robot().x == 0,
          "stand again; walking during the kick was ignored");
  }

  {
    // In range: the ball flies KickDistance along robot -> ball.
    World W({0, -150}, {4500, 0});
    W.step(request(MotionType::kick));
    for (int K = 1; K <= World::KickCycles; ++K)
      W.step(request(MotionType::stand));
    check(W.ballWasKicked() && W.ball().x == 0 && W.ball().y == -2150,
          "a ball 150 mm away is kicked 2000 mm");
  }
  return Failures != 0;
}

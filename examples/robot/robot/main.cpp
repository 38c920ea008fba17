// The robot program: a small deterministic world with two players, each
// run by its own compiled behavior (striker.h and keeper.h are generated
// by bscript_add_behavior). Every cycle each player senses, its behavior
// runs once, and the world applies what it asked for: a walking player
// moves up to 0.5 along each axis towards its target, a kick moves the
// ball by (2, -0.5).
#include "World.h"
#include "keeper.h"
#include "striker.h"

#include <cstdio>

using namespace robot;

namespace {
constexpr int Cycles = 30;

float stepTowards(float From, float To) {
  float D = To - From;
  return From + (D > 0.5f ? 0.5f : D < -0.5f ? -0.5f : D);
}

void move(Vec2 &Pos, const Output &Out) {
  if (Out.motion != Motion::walk)
    return;
  Pos.x = stepTowards(Pos.x, Out.target.x);
  Pos.y = stepTowards(Pos.y, Out.target.y);
}
} // namespace

int main() {
  bs_striker_state Striker;
  bs_keeper_state Keeper;
  if (bs_striker_init(&Striker) != 0 || bs_keeper_init(&Keeper) != 0) {
    std::puts("cannot initialise the behaviors");
    return 1;
  }
  Vec2 Ball{3, 1}, StrikerPos{0, 0}, KeeperPos{-4.5f, 0};
  Output StrikerOut, KeeperOut;
  int Kicks = 0;
  for (int Cycle = 1; Cycle <= Cycles; ++Cycle) {
    Input StrikerIn{Cycle, StrikerPos, Ball}, KeeperIn{Cycle, KeeperPos, Ball};
    bs_striker_begin_cycle(&Striker, &StrikerIn, &StrikerOut);
    bs_striker_call__striker__main(&Striker);
    bs_keeper_begin_cycle(&Keeper, &KeeperIn, &KeeperOut);
    bs_keeper_call__keeper__main(&Keeper);
    move(StrikerPos, StrikerOut);
    move(KeeperPos, KeeperOut);
    if (StrikerOut.motion == Motion::kick) {
      Ball.x += 2;
      Ball.y -= 0.5f;
      ++Kicks;
      std::printf("cycle %d: kick from (%g, %g), ball now at (%g, %g)\n",
                  Cycle, StrikerPos.x, StrikerPos.y, Ball.x, Ball.y);
    }
  }
  std::printf("after %d cycles: %d kicks, striker at (%g, %g), keeper at "
              "(%g, %g)\n",
              Cycles, Kicks, StrikerPos.x, StrikerPos.y, KeeperPos.x,
              KeeperPos.y);
  bs_striker_destroy(&Striker);
  bs_keeper_destroy(&Keeper);
  return 0;
}

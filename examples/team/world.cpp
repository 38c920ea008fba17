// world.cpp - the team world of examples/team (bscript/world.h): one
// library simulates every robot on a line of pitch with one ball. Built
// with -shared -fPIC for `bsc run --robots N --world`, and as an object
// linked into team.cpp, the program that runs the same loop on the robot's
// CPU.
//
// The rules, all in whole centimetres: the ball starts at 60, the players
// at the table's positions. Every robot's cycle sees the world as the last
// one left it (bs_team_begin); the world moves only after the last robot's
// bs_team_end, in robot order: a player with the ball that asks to kick
// sends it `kick` forward and lets it go; any other moves by `walk`, capped
// at its maxSpeed, and a player with the ball takes it along. Then, if the
// ball is free, the first player (by index) standing on it takes it.
#include "pitch.h"
#include <bscript/world.h>
#include <algorithm>
#include <cstdio>
#include <vector>

namespace {
using pitch::Player;

/// The squad: robot K is the K-th (a larger team gets more bobs).
const Player Squad[] = {{"alice", 0, 15, 50}, {"bob", 110, 10, 40},
                        {"carol", 200, 12, 30}};

struct Pitch {
  std::vector<Player> Players;
  int Ball = 60;
  int Owner = -1; ///< The robot with the ball, or -1.
  unsigned Kicks = 0;
};

void print(const Pitch &P, uint32_t Cycle) {
  std::printf("cycle %u:", Cycle);
  for (const Player &Pl : P.Players)
    std::printf(" %s %d,", Pl.name, Pl.position);
  std::printf(" ball %d\n", P.Ball);
}

/// After the last robot's cycle: everyone moves, then a free ball is taken.
void advance(Pitch &P, uint32_t Cycle) {
  for (int K = 0; K < int(P.Players.size()); ++K) {
    Player &Pl = P.Players[K];
    if (P.Owner == K && Pl.request.kick > 0) {
      P.Ball += Pl.request.kick;
      P.Owner = -1;
      ++P.Kicks;
      std::printf("cycle %u: %s kicks the ball to %d\n", Cycle, Pl.name,
                  P.Ball);
      continue;
    }
    Pl.position += std::clamp(Pl.request.walk, -Pl.maxSpeed, Pl.maxSpeed);
    if (P.Owner == K)
      P.Ball = Pl.position;
  }
  for (int K = 0; P.Owner < 0 && K < int(P.Players.size()); ++K)
    if (P.Players[K].position == P.Ball) {
      P.Owner = K;
      std::printf("cycle %u: %s has the ball\n", Cycle, P.Players[K].name);
    }
  print(P, Cycle);
}
} // namespace

extern "C" void *bs_team_init(unsigned Robots) {
  auto *P = new Pitch;
  for (unsigned K = 0; K < Robots; ++K)
    P->Players.push_back(Squad[std::min<unsigned>(K, std::size(Squad) - 1)]);
  std::printf("%u robots, ball at %d\n", Robots, P->Ball);
  return P;
}

extern "C" void *bs_team_robot(void *Team, unsigned Robot, void *, void *) {
  return &static_cast<Pitch *>(Team)->Players[Robot];
}

extern "C" void bs_team_begin(void *Team, unsigned Robot, void *Input, void *,
                              uint32_t) {
  const Pitch &P = *static_cast<Pitch *>(Team);
  auto &In = *static_cast<pitch::Input *>(Input);
  In.ballOffset = P.Ball - P.Players[Robot].position;
  In.haveBall = P.Owner == int(Robot);
  In.mateHasBall = P.Owner >= 0 && P.Owner != int(Robot);
  In.kickPower = P.Players[Robot].kickPower;
}

extern "C" void bs_team_end(void *Team, unsigned Robot, const void *,
                            void *Output, uint32_t Cycle) {
  Pitch &P = *static_cast<Pitch *>(Team);
  P.Players[Robot].request = *static_cast<const pitch::Output *>(Output);
  if (Robot + 1 == P.Players.size())
    advance(P, Cycle);
}

extern "C" void bs_team_exit(void *Team) {
  auto *P = static_cast<Pitch *>(Team);
  std::printf("%u kick(s); the ball is at %d\n", P->Kicks, P->Ball);
  delete P;
}

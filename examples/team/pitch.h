// pitch.h - the types of examples/team: each robot's input and output, and
// the tiny world they share (world.cpp): a line of pitch with one ball.
#ifndef PITCH_H
#define PITCH_H

namespace pitch {

/// What a robot sees before its cycle (bs_team_begin fills it).
struct Input {
  int ballOffset = 0;       ///< The ball's position minus the robot's.
  bool haveBall = false;    ///< This robot has the ball.
  bool mateHasBall = false; ///< Another robot of the team has it.
  int kickPower = 0;        ///< How far this robot kicks.
};

/// What a robot asks for (bs_team_end reads it).
struct Output {
  int walk = 0; ///< Steps along the line; the world caps it at maxSpeed.
  int kick = 0; ///< With the ball: kick it this far forward (0: keep it).
};

/// One robot in the world, and its user pointer (bs_team_robot), which
/// registered C++ could read through bs::Context. The behavior gets what
/// it needs of it through its input instead, so that a recording holds
/// all it depends on and replays without the world.
struct Player {
  const char *name = "";
  int position = 0;
  int maxSpeed = 10;
  int kickPower = 0;
  Output request; ///< This cycle's output, applied after the last robot's.
};

} // namespace pitch

#endif

//===- host.cpp - the paper's soccer behavior in a closed loop ------------===//
//
// Robot code in miniature: owns the compiled behavior's state, runs the
// 30 Hz sense-think-act loop against the deterministic world of
// SoccerSim.h, and prints a short trace of what happens. Exits 0 once the
// behavior's entry task is done after the ball was kicked, 1 if it fails,
// finishes without a kick, or has not finished after MaxCycles cycles. A
// kick that the motion layer is still executing when the entry is done
// (Kick.bs is done as soon as the kick has started) is run to its end
// before the result is judged.
//
// "behavior.h" is `bsc --emit-header --behavior-name soccer` of the program;
// SOCCER_MODULE names the module whose gotoBallAndKick is the entry
// (Behavior: the paper's Fig. 2c; Kick: Fig. 1c). run-i586 and run-host
// build it; stub/behavior.h stands in for the compiled behavior to test the
// world and this file without the compiler.
//
// Built with SOCCER_FLIGHT (build-run.sh does with $SOCCER_FLIGHT_LOG, and
// compiles the behavior with --flight-recorder), it writes the robot's
// flight log to $SOCCER_FLIGHT_LOG: every cycle the entry runs, what the
// behavior observed, for `bsc run --replay` and the REPL at the desk
// (docs/repl.md, "The robot's log").
//
//===----------------------------------------------------------------------===//
#include "SoccerSim.h"
#include "behavior.h"

#include <cstdio>
#include <cstdlib>

#ifdef SOCCER_FLIGHT
#include <bscript/flight.h>
#endif

#ifndef SOCCER_MODULE
#define SOCCER_MODULE Behavior
#endif
#define SOCCER_CAT3(A, B, C) A##B##C
#define SOCCER_XCAT3(A, B, C) SOCCER_CAT3(A, B, C)
#define SOCCER_STR(A) #A
#define SOCCER_XSTR(A) SOCCER_STR(A)
#define SOCCER_CALL                                                            \
  SOCCER_XCAT3(bs_soccer_call__, SOCCER_MODULE, __gotoBallAndKick)
#define SOCCER_STATE_OF                                                        \
  SOCCER_XCAT3(bs_soccer_state_of__, SOCCER_MODULE, __gotoBallAndKick)

namespace {

constexpr int MaxCycles = 600;
constexpr int ReportEvery = 10; ///< cycles between "walking" lines

// The state storage the robot owns: size and alignment from the header.
bs_soccer_state State;

#ifdef SOCCER_FLIGHT
// The flight recorder's memory and the log file its full blocks go to (a
// robot would queue them for a writer thread; fwrite will do here).
alignas(8) unsigned char FlightMemory[1 << 16];
bs_flight_recorder Flight;
FILE *FlightLog;

void writeBlock(void *, const void *Bytes, uint32_t Size) {
  std::fwrite(Bytes, 1, Size, FlightLog);
}

bool startFlightLog() {
  const char *Path = std::getenv("SOCCER_FLIGHT_LOG");
  FlightLog = Path ? std::fopen(Path, "wb") : nullptr;
  if (!FlightLog) {
    std::printf("cannot write the flight log '%s'\n", Path ? Path : "");
    return false;
  }
  bs_flight_config Config = {
      &bs_soccer_flight, &bs_soccer_info,
      SOCCER_XSTR(SOCCER_MODULE) "::gotoBallAndKick", FlightMemory,
      sizeof FlightMemory, 16384, 3, 0, writeBlock, nullptr};
  if (int Code = bs_flight_start(&Flight, &Config)) {
    std::printf("bs_flight_start failed: %d\n", Code);
    return false;
  }
  return true;
}

void flightBegin() { bs_flight_begin(&Flight, &State); }
void flightEnd() { bs_flight_end(&Flight, &State); }
void endFlightLog() {
  bs_flight_flush(&Flight);
  std::fclose(FlightLog);
}
#else
bool startFlightLog() { return true; }
void flightBegin() {}
void flightEnd() {}
void endFlightLog() {}
#endif

const char *name(MotionType M) {
  switch (M) {
  case MotionType::stand:
    return "stand";
  case MotionType::walk:
    return "walk";
  case MotionType::kick:
    return "kick";
  }
  return "?";
}

const char *headName(const BehaviorInput &In, const BehaviorOutput &Out) {
  if (Out.headTarget == In.ball.position)
    return "head looks at ball";
  if (Out.headTarget == In.oppGoal)
    return "head looks at goal";
  if (Out.headTarget == Math::Vector2f::Zero())
    return "head target not set";
  return "head looks elsewhere";
}

} // namespace

/// Ends the run with `Status`: the behavior's class values (locals of
/// tasks still running) are destroyed before the state goes away.
int finish(int Status) {
  endFlightLog();
  bs_soccer_destroy(&State);
  return Status;
}

int main() {
  if (bs_soccer_info.state_size != BS_SOCCER_STATE_SIZE ||
      bs_soccer_info.state_align != BS_SOCCER_STATE_ALIGN) {
    std::printf("header and object disagree\n");
    return 2;
  }
  if (bs_soccer_init(&State) != 0) {
    std::printf("bs_soccer_init failed\n");
    return 2;
  }
  if (!startFlightLog())
    return 2;

  // The ball 1000 mm away (a 3-4-5 triangle: every walking step is exactly
  // (8, 6) mm), the opponent goal 4500 mm straight ahead.
  soccer::World W({800, 600}, {4500, 0});
  std::printf("%s::gotoBallAndKick: ball %d mm away at (%d, %d), "
              "walking %d mm/cycle\n",
              SOCCER_XSTR(SOCCER_MODULE), W.ballDistance(), W.ball().x,
              W.ball().y, soccer::World::WalkSpeed);

  MotionType LastRequest = MotionType::stand;
  const char *LastHead = "";
  bool First = true;
  bool Done = false; // the entry task is done: only the motion layer runs
  for (int I = 0; I < MaxCycles; ++I) {
    int N = W.cycle();
    BehaviorInput In;
    W.fillInput(In);
    // Robot code builds its requests afresh every frame.
    BehaviorOutput Out;

    // begin_cycle every frame, also when the entry is not called.
    bs_soccer_begin_cycle(&State, &In, &Out);
    int D = W.ballDistance();
    int32_t TaskState = BS_TASK_DONE;
    if (!Done) {
      // The log holds the cycles the entry runs: once it is done, the
      // robot stops calling it (and the log ends).
      flightBegin();
      SOCCER_CALL(&State);
      flightEnd();
      TaskState = SOCCER_STATE_OF(&State);

      if (First || Out.motion != LastRequest) {
        if (Out.motion == MotionType::walk)
          std::printf("cycle %d: request walk, ball %d mm\n", N, D);
        else
          std::printf("cycle %d: request %s\n", N, name(Out.motion));
      } else if (Out.motion == MotionType::walk && N % ReportEvery == 0) {
        std::printf("cycle %d: walking, ball %d mm\n", N, D);
      }
      LastRequest = Out.motion;
      const char *Head = headName(In, Out);
      if (Head != LastHead)
        std::printf("cycle %d: %s\n", N, Head);
      LastHead = Head;
      First = false;
    }

    switch (W.step(Out)) {
    case soccer::World::None:
      break;
    case soccer::World::KickStarted:
      std::printf("cycle %d: motion layer starts the kick\n", N);
      break;
    case soccer::World::BallKicked:
      std::printf("cycle %d: ball kicked, now %d mm away\n", N,
                  W.ballDistance());
      break;
    case soccer::World::KickMissed:
      std::printf("cycle %d: kick missed the ball (%d mm away)\n", N, D);
      break;
    case soccer::World::KickFinished:
      std::printf("cycle %d: kick finished\n", N);
      break;
    }

    if (!Done) {
      if (TaskState < 0) {
        std::printf("cycle %d: gotoBallAndKick failed\n", N);
        return finish(1);
      }
      if (TaskState == BS_TASK_DONE) {
        std::printf("cycle %d: gotoBallAndKick done\n", N);
        Done = true;
      }
    }
    // Done, and the motion layer has finished a kick that was under way.
    if (Done && W.executed() != MotionType::kick) {
      if (!W.ballWasKicked()) {
        std::printf("the ball was not kicked\n");
        return finish(1);
      }
      std::printf("success: the ball was kicked, %d mm away after %d "
                  "cycles\n",
                  W.ballDistance(), N);
      return finish(0);
    }
  }
  std::printf("gotoBallAndKick still running after %d cycles\n", MaxCycles);
  return finish(1);
}

// flight-recorder.test: Game.bs (Inputs/boundary) run as a robot runs it,
// with the flight recorder (bscript/flight.h) writing the robot's log.
//   game_flight CYCLES LOG [pull [TRACE_LOG]]
// prints each cycle's output as `bsc run --print-output` does. The blocks
// go to LOG through the callback, or with `pull` wait in a ring of two
// small blocks that the loop pulls after each cycle (so that records move
// to the next block). With TRACE_LOG (an object built with --instrument)
// it also writes the classic trace log for `bsc trace-decode`. The entry
// the recorder is told of is Game::game, or $FLIGHT_ENTRY.
#include "game.h"
#include "sim.h"
#include <bscript/flight.h>
#include <bscript/world.h> // The hooks of world.cpp, called as the JIT does.
#include <cstdio>
#include <cstdlib>
#include <cstring>


static void printFloat(float V) {
  char Buf[32];
  for (int Digits = 1; Digits <= 9; ++Digits) {
    std::snprintf(Buf, sizeof Buf, "%.*g", Digits, double(V));
    if (std::strtof(Buf, nullptr) == V)
      break;
  }
  std::fputs(Buf, stdout);
}

static void writeBlock(void *File, const void *Bytes, uint32_t Size) {
  std::fwrite(Bytes, 1, Size, static_cast<FILE *>(File));
}

alignas(8) static unsigned char Memory[1 << 16];

int main(int argc, char **argv) {
  if (argc < 3)
    return 2;
  unsigned Cycles = unsigned(std::atoi(argv[1]));
  FILE *Log = std::fopen(argv[2], "wb");
  bool Pull = argc > 3 && std::strcmp(argv[3], "pull") == 0;
  FILE *TraceLog = argc > 4 ? std::fopen(argv[4], "wb") : nullptr;
  if (!Log)
    return 2;
  static bs_game_state State;
  if (bs_game_init(&State) != BS_INIT_OK)
    return 2;
  bs_flight_recorder Recorder;
  const char *Entry = std::getenv("FLIGHT_ENTRY");
  bs_flight_config Config = {&bs_game_flight, &bs_game_info,
                             Entry ? Entry : "Game::game",
                             Memory, sizeof Memory,
                             Pull ? 1024u : 4096u, Pull ? 2u : 4u,
                             Pull ? 7u : 0u,
                             Pull ? nullptr : writeBlock, Log};
  if (int E = bs_flight_start(&Recorder, &Config)) {
    std::fprintf(stderr, "bs_flight_start: %d\n", E);
    return 2;
  }
  sim::In In{};
  sim::Out Out{};
  void *User = bs_world_init(&In, &Out);
  bs_state_set_user(&State, User);
  for (uint32_t Cycle = 1; Cycle <= Cycles; ++Cycle) {
    bs_game_begin_cycle(&State, &In, &Out);
    bs_trace_begin(&State, &bs_game_info);
    bs_world_begin(User, &In, &Out, Cycle);
    bs_flight_begin(&Recorder, &State);
    bs_game_call__Game__game(&State);
    bs_flight_end(&Recorder, &State);
    bs_world_end(User, &In, &Out, Cycle);
    if (TraceLog) {
      std::fwrite(&Cycle, 4, 1, TraceLog);
      std::fwrite(bs_trace_record(&State, &bs_game_info), 1,
                  bs_game_info.trace.record_size, TraceLog);
    }
    const void *Bytes;
    uint32_t Size;
    while (Pull && bs_flight_pull(&Recorder, &Bytes, &Size)) {
      std::fwrite(Bytes, 1, Size, Log);
      bs_flight_release(&Recorder);
    }
    std::printf("{\"cycle\":%u,\"output\":{\"headMode\":%d,\"motion\":%d,"
                "\"speed\":",
                unsigned(Cycle), Out.headMode, Out.motion);
    printFloat(Out.speed);
    std::printf("}}\n");
  }
  bs_flight_flush(&Recorder);
  const void *Bytes;
  uint32_t Size;
  while (Pull && bs_flight_pull(&Recorder, &Bytes, &Size)) {
    std::fwrite(Bytes, 1, Size, Log);
    bs_flight_release(&Recorder);
  }
  std::fclose(Log);
  if (TraceLog)
    std::fclose(TraceLog);
  if (bs_flight_lost(&Recorder))
    std::fprintf(stderr, "lost %u cycles\n", bs_flight_lost(&Recorder));
  bs_world_exit(User);
  bs_game_destroy(&State);
  return 0;
}

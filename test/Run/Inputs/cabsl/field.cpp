// cabsl_option.test's world library for `bsc run --world`: feeds the same
// inputs as inputs.jsonl (time in steps of 100, the ball near from cycle
// 3, not seen in cycle 5) and reads what the behavior wrote.
#include "world.h"
#include <cstdint>
#include <cstdio>

namespace {
using sw::In;
using sw::Out;

struct Field {
  int kicks = 0;
};
} // namespace

extern "C" void *bs_world_init(void *Input, void *Output) {
  std::printf("init %s\n", Input && Output ? "with input and output" : "?");
  return new Field;
}

extern "C" void bs_world_begin(void *User, void *Input, void *, uint32_t Cycle) {
  (void)User;
  auto *I = static_cast<In *>(Input);
  I->time = int(Cycle - 1) * 100;
  I->ballDistance = Cycle < 3 ? 500.0f : 150.0f;
  I->ballSeen = Cycle != 5;
}

extern "C" void bs_world_end(void *User, const void *, void *Output,
                             uint32_t Cycle) {
  auto *F = static_cast<Field *>(User);
  if (static_cast<Out *>(Output)->kickPower > 0)
    ++F->kicks;
  std::printf("end of cycle %u: motion %d\n", unsigned(Cycle),
              static_cast<Out *>(Output)->motion);
}

extern "C" void bs_world_exit(void *User) {
  auto *F = static_cast<Field *>(User);
  std::printf("exit after %d cycles with the kick power set\n", F->kicks);
  delete F;
}

// world.test: world libraries that crash or hang, one per -D: CRASH_INIT
// (bs_world_init), CRASH_BEGIN (bs_world_begin of cycle 2), HANG_END
// (bs_world_end never returns).
#include <cstdint>

extern "C" void *bs_world_init(void *, void *) {
#ifdef CRASH_INIT
  volatile int *P = nullptr;
  *P = 1;
#endif
  return nullptr;
}

extern "C" void bs_world_begin(void *, void *, void *, uint32_t Cycle) {
#ifdef CRASH_BEGIN
  if (Cycle == 2) {
    volatile int *P = nullptr;
    *P = 1;
  }
#endif
  (void)Cycle;
}

extern "C" void bs_world_end(void *, const void *, void *, uint32_t) {
#ifdef HANG_END
  for (volatile int I = 0;; I = I + 1) {
  }
#endif
}

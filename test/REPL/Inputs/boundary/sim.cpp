// Registered C++ with every kind of effect time travel and replay must
// survive (test/REPL/boundary*.test), module Sys:
// (a) init keeps a pointer to `input`; step() advances a simulation and
//     writes the next cycle's input through it;
// (b) random() and clock() return values that depend on hidden C++ state;
// (c) setHeadMode()/headMode() keep a blackboard behind the user pointer
//     (set by world.cpp's bs_world_init);
// (d) say() prints;
// (e) phase() returns a string in a buffer it overwrites on every call;
// and a cheat: level() is registered pure but returns what bump() changed,
// C++ state outside anything the behavior can see.
#include "sim.h"
#include <bscript/Bind.h>
#include <cstdio>

namespace sim {
inline In *Kept = nullptr;
inline uint32_t Seed = 12345;
inline int Ticks = 0;
inline int Hidden = 0;

inline void init(bs::Context &C) {
  Kept = static_cast<In *>(const_cast<void *>(C.input()));
}
inline void step() {
  if (!Kept)
    return;
  Kept->time += 33;
  Kept->ballX -= 7.5f;
  if (Kept->gameState == 0 && Kept->time > 100)
    Kept->gameState = 1;
  if (Kept->time > 1200)
    Kept->gameState = 2;
}
inline int random() {
  Seed = Seed * 1103515245u + 12345u;
  return int((Seed >> 16) & 0x7fff);
}
inline int clock() { return Ticks += 33; }
inline void setHeadMode(bs::Context &C, int Mode) {
  auto *B = C.user<Board>();
  B->headMode = Mode;
  ++B->writes;
}
inline int headMode(bs::Context &C) { return C.user<Board>()->headMode; }
inline void say(int N) { std::printf("say %d\n", N); }
inline void bump() { ++Hidden; }
inline int level() { return Hidden; }
inline int twice(int X) { return 2 * X; }
inline char PhaseText[8];
inline int Phases = 0;
inline const char *phase() {
  std::snprintf(PhaseText, sizeof PhaseText, "%s",
                (++Phases / 5) % 2 ? "odd" : "even");
  return PhaseText;
}
} // namespace sim

BS_MODULE(Sys,
  registerClass<sim::In>(module, "In")
    .var<&sim::In::time>("time")
    .var<&sim::In::gameState>("gameState")
    .var<&sim::In::ballX>("ballX")
    .var<&sim::In::button>("button");
  registerClass<sim::Out>(module, "Out")
    .var<&sim::Out::motion>("motion")
    .var<&sim::Out::speed>("speed")
    .var<&sim::Out::headMode>("headMode");
  registerInput<sim::In>(module);
  registerOutput<sim::Out>(module);
  registerFunction<&sim::init>(module, "init");
  registerFunction<&sim::step>(module, "step");
  registerFunction<&sim::random>(module, "random");
  registerFunction<&sim::clock>(module, "clock");
  registerFunction<&sim::setHeadMode>(module, "setHeadMode");
  registerFunction<&sim::headMode>(module, "headMode");
  registerFunction<&sim::say>(module, "say");
  registerFunction<&sim::bump>(module, "bump");
  registerFunction<&sim::level>(module, "level").pure();
  registerFunction<&sim::twice>(module, "twice").pure();
  registerFunction<&sim::phase>(module, "phase");
)

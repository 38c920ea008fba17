// The world module of the boundary tests (test/REPL/boundary*.test): a
// behavior whose registered C++ has effects. See sim.cpp.
#ifndef BOUNDARY_SIM_H
#define BOUNDARY_SIM_H
#include <cstdint>

namespace sim {
struct In {
  int time;
  int gameState; // 0 initial, 1 playing, 2 finished
  float ballX;
  int button;
};
struct Out {
  int motion;
  float speed;
  int headMode;
};
/// What the world keeps behind the state's user pointer.
struct Board {
  int headMode;
  int writes;
};
} // namespace sim
#endif

// Used by program_world.test: the world module of a standalone program.
// Every field of `input` has a default that only the constructor sets, so
// a program that left input zeroed (or null) would print something else;
// Out's destructor prints what the script wrote, after the last cycle.
// With -DNO_DEFAULT, `input` has no default constructor and a destructor:
// a program cannot construct it.
#include <bscript/Bind.h>
#include <cstdio>

namespace pw {
struct Vec {
  float x = 1.5f;
  float y = -2.0f;
};
enum class Mode { idle = 3, run = 8 };
struct In {
#ifdef NO_DEFAULT
  explicit In(int T) : time(T) {}
  ~In() {}
#endif
  int time = 42;
  float speed = 2.5f;
  bool ready = true;
  Vec target;
  Mode mode = Mode::run;
};
struct Out {
  int motion = 7;
  float speed = 0.25f;
  Vec walk;
  ~Out() { std::printf("~out %d %g %g %g\n", motion, speed, walk.x, walk.y); }
};
} // namespace pw

BS_MODULE(PWorld,
  registerClass<pw::Vec>(module, "Vec")
    .var<&pw::Vec::x>("x")
    .var<&pw::Vec::y>("y");
  registerEnum<pw::Mode>(module, "Mode")
    .value("idle", pw::Mode::idle)
    .value("run", pw::Mode::run);
  registerClass<pw::In>(module, "In")
    .var<&pw::In::time>("time")
    .var<&pw::In::speed>("speed")
    .var<&pw::In::ready>("ready")
    .var<&pw::In::target>("target")
    .var<&pw::In::mode>("mode");
  registerClass<pw::Out>(module, "Out")
    .var<&pw::Out::motion>("motion")
    .var<&pw::Out::speed>("speed")
    .var<&pw::Out::walk>("walk");
  registerInput<pw::In>(module);
  registerOutput<pw::Out>(module);
)

// Used by the test/DebugInfo tests: a world module with a class, an enum and
// a registered function a debugger can stop in (dw::noteKick), compiled with
// -g so that a backtrace goes from C++ back through the compiled tasks.
#include <bscript/Bind.h>

namespace dw {
struct Vec {
  float x = 0;
  float y = 0;
};
enum class Mode { stand = 0, walk = 4, kick = 9 };
struct In {
  int time = 0;
  short battery = 7;
  double heading = 0.5;
  Vec ball;
};
struct Out {
  Mode mode = Mode::stand;
  Vec target;
  int kicks = 0;
};
// Not inline, so that gdb can break on it by name.
__attribute__((noinline)) int noteKick(int power) { return power + 1; }
} // namespace dw

BS_MODULE(KickWorld,
  registerClass<dw::Vec>(module, "Vec")
    .var<&dw::Vec::x>("x")
    .var<&dw::Vec::y>("y");
  registerEnum<dw::Mode>(module, "Mode")
    .value("stand", dw::Mode::stand)
    .value("walk", dw::Mode::walk)
    .value("kick", dw::Mode::kick);
  registerClass<dw::In>(module, "In")
    .var<&dw::In::time>("time")
    .var<&dw::In::battery>("battery")
    .var<&dw::In::heading>("heading")
    .var<&dw::In::ball>("ball");
  registerClass<dw::Out>(module, "Out")
    .var<&dw::Out::mode>("mode")
    .var<&dw::Out::target>("target")
    .var<&dw::Out::kicks>("kicks");
  registerFunction<&dw::noteKick>(module, "noteKick");
  registerInput<dw::In>(module);
  registerOutput<dw::Out>(module);
)

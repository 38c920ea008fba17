// Used by test/Run/cabsl_option.test: the world of docs/language.md's
// idiom "a CABSL option as a task".
#include <bscript/Bind.h>

namespace sw {
struct In {
  int time = 0;
  float ballDistance = 0;
  bool ballSeen = false;
};
struct Out {
  int motion = 0; // 0 stand, 1 walk, 2 align, 3 kick
  float kickPower = 0;
};
} // namespace sw

BS_MODULE(Robot,
  registerClass<sw::In>(module, "In")
    .var<&sw::In::time>("time")
    .var<&sw::In::ballDistance>("ballDistance")
    .var<&sw::In::ballSeen>("ballSeen");
  registerClass<sw::Out>(module, "Out")
    .var<&sw::Out::motion>("motion")
    .var<&sw::Out::kickPower>("kickPower");
  registerInput<sw::In>(module);
  registerOutput<sw::Out>(module);
)

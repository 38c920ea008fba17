// Used by test/Run/cabsl_option.test: the world of docs/language.md's
// idiom "a CABSL option as a task".
#include "world.h"
#include <bscript/Bind.h>

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

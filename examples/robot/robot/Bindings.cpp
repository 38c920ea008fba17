// Registers the robot's world for b-script (docs/bindings.md): module
// Robot, whose Input and Output are the behaviors' `input` and `output`.
#include "World.h"

#include <bscript/Bind.h>

using namespace robot;

BS_MODULE(Robot,
  registerClass<Vec2>(module, "Vec2")
    .var<&Vec2::x>("x")
    .var<&Vec2::y>("y");
  registerEnum<Motion>(module, "Motion")
    .value("stand", Motion::stand)
    .value("walk", Motion::walk)
    .value("kick", Motion::kick);
  registerClass<Input>(module, "Input")
    .var<&Input::cycle>("cycle")
    .var<&Input::self>("self")
    .var<&Input::ball>("ball");
  registerClass<Output>(module, "Output")
    .var<&Output::motion>("motion")
    .var<&Output::target>("target");
  registerInput<Input>(module);
  registerOutput<Output>(module);
)

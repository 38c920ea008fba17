// bindings.cpp - the world module of examples/team: the robots' input and
// output classes, and kickPower(), which reads the robot's own player
// through bs::Context (its user pointer), so each robot kicks with its
// own strength although all run the same behavior.
#include "pitch.h"
#include <bscript/Bind.h>

namespace pitch {
int kickPower(bs::Context &C) { return C.user<Player>()->kickPower; }
} // namespace pitch

BS_MODULE(Pitch,
  registerClass<pitch::Input>(module, "Input")
    .var<&pitch::Input::ballOffset>("ballOffset")
    .var<&pitch::Input::haveBall>("haveBall")
    .var<&pitch::Input::mateHasBall>("mateHasBall");
  registerClass<pitch::Output>(module, "Output")
    .var<&pitch::Output::walk>("walk")
    .var<&pitch::Output::kick>("kick");
  registerInput<pitch::Input>(module);
  registerOutput<pitch::Output>(module);
  registerFunction<&pitch::kickPower>(module, "kickPower");
)

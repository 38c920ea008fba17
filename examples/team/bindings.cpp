// bindings.cpp - the world module of examples/team: the robots' input and
// output classes.
#include "pitch.h"
#include <bscript/Bind.h>

BS_MODULE(Pitch,
  registerClass<pitch::Input>(module, "Input")
    .var<&pitch::Input::ballOffset>("ballOffset")
    .var<&pitch::Input::haveBall>("haveBall")
    .var<&pitch::Input::mateHasBall>("mateHasBall")
    .var<&pitch::Input::kickPower>("kickPower");
  registerClass<pitch::Output>(module, "Output")
    .var<&pitch::Output::walk>("walk")
    .var<&pitch::Output::kick>("kick");
  registerInput<pitch::Input>(module);
  registerOutput<pitch::Output>(module);
)

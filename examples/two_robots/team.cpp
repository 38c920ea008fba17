// team.cpp - the C++ side of two robots in one process: the world module
// (each robot's input and output) and a per-robot blackboard reached
// through bs::Context, never a process global.
#include "team.h"
#include <bscript/Bind.h>

namespace team {

// The head control mode, set by the options of a cycle and read by the head
// control later in the same cycle: CABSL keeps such a blackboard per robot.
void requestHeadMode(bs::Context &C, HeadMode M) {
  C.user<Robot>()->headMode = M;
}
HeadMode headMode(bs::Context &C) { return C.user<Robot>()->headMode; }
const char *robotName(bs::Context &C) { return C.user<Robot>()->name; }
int cycleOfRobot(bs::Context &C) { return int(C.cycle()); }
// The context's input and output are the cycle's `input` and `output`.
bool contextSeesBall(bs::Context &C) {
  auto *In = static_cast<const Input *>(C.input());
  auto *Out = static_cast<Output *>(C.output());
  return In && Out && In->ballSeen;
}

} // namespace team

BS_MODULE(Team,
  registerEnum<team::HeadMode>(module, "HeadMode")
    .value("lookForward", team::HeadMode::lookForward)
    .value("lookAtBall", team::HeadMode::lookAtBall)
    .value("sweep", team::HeadMode::sweep);
  registerClass<team::Input>(module, "Input")
    .var<&team::Input::ballSeen>("ballSeen")
    .var<&team::Input::ballDistance>("ballDistance");
  registerClass<team::Output>(module, "Output")
    .var<&team::Output::headPan>("headPan")
    .var<&team::Output::walkSpeed>("walkSpeed");
  registerInput<team::Input>(module);
  registerOutput<team::Output>(module);
  registerFunction<&team::requestHeadMode>(module, "requestHeadMode");
  registerFunction<&team::headMode>(module, "headMode");
  registerFunction<&team::robotName>(module, "robotName");
  registerFunction<&team::cycleOfRobot>(module, "cycleOfRobot");
  registerFunction<&team::contextSeesBall>(module, "contextSeesBall");
  registerConstant(module, "sweepPan", 60);
)

// A robot's own module named `io`: the runtime archive already registers
// one, so bsc must report the second registration.
#include "bscript/Bind.h"

namespace robot {
void say(int) {}
} // namespace robot

BS_MODULE(io, registerFunction<&robot::say>(module, "printi");)

// Registers a function that another object of the robot build defines
// (impl.cpp): bsc run needs both objects (jit-undefined-symbol.test).
#include <bscript/Bind.h>
int tripled(int X);
BS_MODULE(Split, registerFunction<&tripled>(module, "tripled");)

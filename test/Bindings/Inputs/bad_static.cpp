// A static function has internal linkage: its thunk cannot be called by name.
#include <bscript/Bind.h>
static int hidden(int X) { return X + 1; }
BS_MODULE(BadStatic, registerFunction<&hidden>(module, "hidden");)

// Used by damaged-objects.test: a binding module small enough that every
// field of every section header can be damaged in turn.
#include <bscript/Bind.h>

int twice(int X) { return 2 * X; }

BS_MODULE(Tiny,
  registerFunction<&twice>(module, "twice");
)

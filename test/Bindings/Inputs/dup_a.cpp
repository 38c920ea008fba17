// With dup_b.cpp: the same C++ class registered by two modules.
#include <bscript/Bind.h>
struct Shared {
  int v = 0;
};
BS_MODULE(DupA, registerClass<Shared>(module, "Shared").var<&Shared::v>("v");)

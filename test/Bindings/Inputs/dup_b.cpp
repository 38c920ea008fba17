// With dup_a.cpp: the same C++ class registered by two modules.
#include <bscript/Bind.h>
struct Shared {
  int v = 0;
};
BS_MODULE(DupB, registerClass<Shared>(module, "Other").var<&Shared::v>("v");)

// A class in an anonymous namespace: its type key has internal linkage.
#include <bscript/Bind.h>
namespace {
struct Secret {
  int v = 0;
};
} // namespace
BS_MODULE(BadAnon, registerClass<Secret>(module, "Secret").var<&Secret::v>("v");)

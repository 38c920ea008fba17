// Used by world_names.test: a world module with a function, an enum and
// classes, whose names scripts use unqualified.
#include <bscript/Bind.h>

namespace wn {
enum class Activity { idle = 0, walking = 2 };
struct In {
  int time = 40;
};
struct Out {
  int motion = 0;
};
inline int clampAngle(int a) { return a > 90 ? 90 : a < -90 ? -90 : a; }
} // namespace wn

BS_MODULE(Robot,
  registerEnum<wn::Activity>(module, "Activity")
    .value("idle", wn::Activity::idle)
    .value("walking", wn::Activity::walking);
  registerClass<wn::In>(module, "In").var<&wn::In::time>("time");
  registerClass<wn::Out>(module, "Out").var<&wn::Out::motion>("motion");
  registerFunction<&wn::clampAngle>(module, "clampAngle");
  registerInput<wn::In>(module);
  registerOutput<wn::Out>(module);
)

// Used by lifecycle.test: `input` and `output` of classes with a destructor,
// which `bsc run` constructs before the first cycle and destroys at the end.
#include <bscript/Bind.h>
#include <cstdio>

namespace lw {
struct Part {
  int n = 0;
  ~Part() { std::printf("~part %d\n", n); }
};
struct In {
  Part p;
};
struct Out {
  Part p;
};
} // namespace lw

BS_MODULE(LifeWorld,
  registerClass<lw::Part>(module, "Part")
    .var<&lw::Part::n>("n");
  registerClass<lw::In>(module, "In")
    .var<&lw::In::p>("p");
  registerClass<lw::Out>(module, "Out")
    .var<&lw::Out::p>("p");
  registerInput<lw::In>(module);
  registerOutput<lw::Out>(module);
)

// Bindings for test/CodeGen/classes.bs: a 16-aligned class with a class
// result and a scalar method, and (module Res) a class that is not trivially
// destructible.
#include <bscript/Bind.h>

namespace al {
struct alignas(16) Quad {
  float a = 0, b = 0, c = 0, d = 0;
  float sum() const { return a + b + c + d; }
};
Quad twice(const Quad &Q) { return {2 * Q.a, 2 * Q.b, 2 * Q.c, 2 * Q.d}; }
struct Res {
  int n = 0;
  ~Res() { n = -1; }
};
} // namespace al

BS_MODULE(Al,
  registerClass<al::Quad>(module, "Quad")
    .var<&al::Quad::a>("a")
    .var<&al::Quad::d>("d")
    .func<&al::Quad::sum>("sum")
    .func<&al::twice>("twice");
)

BS_MODULE(Res,
  registerClass<al::Res>(module, "Res")
    .var<&al::Res::n>("n");
)

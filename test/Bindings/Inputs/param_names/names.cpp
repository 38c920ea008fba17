// Used by param-names.test: parameter names given at registration
// (docs/bindings.md, "Parameter names"), for functions, methods,
// constructors and a function taking bs::Context, and one without names.
#include <bscript/Bind.h>

namespace pn {
struct Range {
  float lo = 0, hi = 1;
  Range() = default;
  Range(float L, float H) : lo(L), hi(H) {}
};
float between(float V, float Min, float Max) {
  return V < Min ? Min : V > Max ? Max : V;
}
float clampInto(const Range &R, float V) { return between(V, R.lo, R.hi); }
int ahead(bs::Context &C, int Steps) { return Steps + int(C.cycle()); }
int unnamed(int A, int B) { return A - B; }
} // namespace pn

BS_MODULE(Names,
  registerClass<pn::Range>(module, "Range")
    .var<&pn::Range::lo>("lo")
    .var<&pn::Range::hi>("hi")
    .ctor<>()
    .ctor<float, float>({"lo", "hi"})
    .func<&pn::clampInto>("clamp", {"v"});
  registerFunction<&pn::between>(module, "between", {"v", "min", "max"},
                                 "pn::between");
  registerFunction<&pn::ahead>(module, "ahead", {"steps"});
  registerFunction<&pn::unnamed>(module, "unnamed");
)

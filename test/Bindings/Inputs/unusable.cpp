// Used by unusable.test: a method and a function with scalar out
// parameters, which b-script cannot pass.
#include <bscript/Bind.h>
struct P {
  float x = 1;
  void get(float &out) const { out = x; }
  float len() const { return x; }
};
void fill(int &n) { n = 3; }
BS_MODULE(OutP,
  registerClass<P>(module, "P").var<&P::x>("x").func<&P::get>("get").func<&P::len>("len");
  registerFunction<&fill>(module, "fill");
)

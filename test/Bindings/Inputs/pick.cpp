// Used by binding-cpu.test: a function that GCC compiles to CMOV for an
// i686 (and to SSE with -msse2 -mfpmath=sse), which a Geode lacks.
#include <bscript/Bind.h>
__attribute__((noinline)) int pick(int a, int b) { return a > b ? a : b; }
__attribute__((noinline)) float half(float x) { return x * 0.5f; }
BS_MODULE(Pick,
  registerFunction<&pick>(module, "pick");
  registerFunction<&half>(module, "half");
)

// Functions kept internal (static, anonymous namespace), registered through
// lambdas written inside BS_MODULE: the lambdas' thunks belong to the
// external descriptor, so generated code can call them by name
// (docs/bindings.md, "Registered functions have external linkage").
#include <bscript/Bind.h>
static int tripled(int X) { return 3 * X; }
namespace {
float halved(float X) { return X / 2; }
} // namespace
BS_MODULE(Internal,
  registerFunction<[](int X) { return tripled(X); }>(module, "tripled");
  registerFunction<[](float X) { return halved(X); }>(module, "halved");
)

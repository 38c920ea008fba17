// A lambda at namespace scope has internal linkage (Clang names it $_0).
#include <bscript/Bind.h>
constexpr auto Twice = [](int X) { return 2 * X; };
BS_MODULE(BadLambda, registerFunction<Twice>(module, "twice");)

// Two binding modules for shared-library.test, built into one shared
// library: Zeta is defined before Alpha, so in the library's bs_modules
// section (and in --dump-bindings) Zeta comes first although its name
// sorts last. Values chosen so that every call shows in the output.
#include <bscript/Bind.h>

struct Counter {
  int count = 0;
  float scale = 1.5f;
  int bump(int By) { return count += By; }
  float scaled() const { return scale * float(count); }
};

int triple(int X) { return 3 * X; }

enum class Mode { slow = 1, fast = 7 };

int modeValue(Mode M) { return int(M) * 10; }

BS_MODULE(Zeta,
  registerClass<Counter>(module, "Counter")
    .var<&Counter::count>("count")
    .var<&Counter::scale>("scale")
    .func<&Counter::bump>("bump")
    .func<&Counter::scaled>("scaled");
  registerFunction<&triple>(module, "triple");
  registerFunction<[](int A, int B) { return A - B; }>(module, "minus");
)

BS_MODULE(Alpha,
  registerEnum<Mode>(module, "Mode")
    .value("slow", Mode::slow)
    .value("fast", Mode::fast);
  registerFunction<&modeValue>(module, "modeValue");
)

// Used by gdb-shadow.test and dwarf-classes.test: a class registered by
// value with its fields (.var: gdb shows them by their offsets), one with a
// field and a property (a getter: no member in DWARF), and a function a
// debugger can stop in (sw::note), compiled with -g.
#include <bscript/Bind.h>

namespace sw {
struct Vector2f {
  float x = 0;
  float y = 0;
};
struct Heading {
  float turns = 0;
  int laps = 0;
  float degrees() const { return turns * 360; }
};
// Not inline, so that gdb can break on it by name.
__attribute__((noinline)) int note(int V) { return V + 1; }
} // namespace sw

BS_MODULE(Shapes,
  registerClass<sw::Vector2f>(module, "Vector2f")
    .var<&sw::Vector2f::x>("x")
    .var<&sw::Vector2f::y>("y");
  registerClass<sw::Heading>(module, "Heading")
    .prop<&sw::Heading::degrees>("degrees")
    .var<&sw::Heading::laps>("laps");
  registerFunction<&sw::note>(module, "note");
)

// Used by gdb-properties.test and dwarf-classes.test: classes with
// properties (getters, no place in the object) beside their fields. gdb
// calls the getters through bsc's DWARF and the pretty-printer
// (tools/gdb/bscript_printers.py): a scalar one of each kind, a
// class-valued one (listed, not called), and one whose getter crashes.
#include <bscript/Bind.h>

namespace gauges {
struct Point {
  float x = 0;
  float y = 0;
};
struct Odometer {
  float meters = 0;
  int *counter = nullptr; // Never set: fault() reads through null.
  float km() const { return meters / 1000; }
  int laps() const { return int(meters) / 400; }
  bool moving() const { return meters > 0; }
  Point last() const { return {meters, 1}; }
  int fault() const { return *counter; }
};
} // namespace gauges

BS_MODULE(Gauges,
  registerClass<gauges::Point>(module, "Point")
    .var<&gauges::Point::x>("x")
    .var<&gauges::Point::y>("y");
  registerClass<gauges::Odometer>(module, "Odometer")
    .var<&gauges::Odometer::meters>("meters")
    .prop<&gauges::Odometer::km>("km")
    .prop<&gauges::Odometer::laps>("laps")
    .prop<&gauges::Odometer::moving>("moving")
    .prop<&gauges::Odometer::last>("last")
    .prop<&gauges::Odometer::fault>("fault");
)

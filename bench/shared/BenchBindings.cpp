//===- BenchBindings.cpp - input and output of the shared benchmark -------===//
//
// Registers the harness's In and Out records (../../../shared/bench/
// harness.h) as the behavior's `input` and `output`. b-script has no arrays,
// so `Out::wide[8]` is registered through BenchOut, a record with the same
// layout and the eight elements as fields wide0..wide7; the static
// assertions below hold the two layouts together.
//
//===----------------------------------------------------------------------===//
#include "harness.h"

#include <bscript/Bind.h>

#include <cstddef>

struct BenchOut {
  int32_t motion, walkX, walkY, speed, headX, headY, headMode, kicks, failures;
  int32_t wide0, wide1, wide2, wide3, wide4, wide5, wide6, wide7;
};
static_assert(sizeof(BenchOut) == sizeof(Out) && alignof(BenchOut) == alignof(Out));
static_assert(offsetof(BenchOut, failures) == offsetof(Out, failures));
static_assert(offsetof(BenchOut, wide0) == offsetof(Out, wide) &&
              offsetof(BenchOut, wide7) == offsetof(Out, wide) + 7 * sizeof(int32_t));

BS_MODULE(Bench,
  registerClass<In>(module, "In")
    .var<&In::frame>("frame")
    .var<&In::time>("time")
    .var<&In::rx>("rx")
    .var<&In::ry>("ry")
    .var<&In::bx>("bx")
    .var<&In::by>("by")
    .var<&In::kickDone>("kickDone");
  registerClass<BenchOut>(module, "Out")
    .var<&BenchOut::motion>("motion")
    .var<&BenchOut::walkX>("walkX")
    .var<&BenchOut::walkY>("walkY")
    .var<&BenchOut::speed>("speed")
    .var<&BenchOut::headX>("headX")
    .var<&BenchOut::headY>("headY")
    .var<&BenchOut::headMode>("headMode")
    .var<&BenchOut::kicks>("kicks")
    .var<&BenchOut::failures>("failures")
    .var<&BenchOut::wide0>("wide0")
    .var<&BenchOut::wide1>("wide1")
    .var<&BenchOut::wide2>("wide2")
    .var<&BenchOut::wide3>("wide3")
    .var<&BenchOut::wide4>("wide4")
    .var<&BenchOut::wide5>("wide5")
    .var<&BenchOut::wide6>("wide6")
    .var<&BenchOut::wide7>("wide7");
  registerInput<In>(module);
  registerOutput<BenchOut>(module);
)

//===- BenchBindings.cpp - input and output of the shared benchmark -------===//
//
// Registers the harness's In and Out records (../../../shared/bench/
// harness.h) as the behavior's `input` and `output`, as a robot team would:
// each field as it is declared, `Out::wide[8]` as an array field.
//
//===----------------------------------------------------------------------===//
#include "harness.h"

#include <bscript/Bind.h>

BS_MODULE(Bench,
  registerClass<In>(module, "In")
    .var<&In::frame>("frame")
    .var<&In::time>("time")
    .var<&In::rx>("rx")
    .var<&In::ry>("ry")
    .var<&In::bx>("bx")
    .var<&In::by>("by")
    .var<&In::kickDone>("kickDone");
  registerClass<Out>(module, "Out")
    .var<&Out::motion>("motion")
    .var<&Out::walkX>("walkX")
    .var<&Out::walkY>("walkY")
    .var<&Out::speed>("speed")
    .var<&Out::headX>("headX")
    .var<&Out::headY>("headY")
    .var<&Out::headMode>("headMode")
    .var<&Out::kicks>("kicks")
    .var<&Out::failures>("failures")
    .var<&Out::wide>("wide");
  registerInput<In>(module);
  registerOutput<Out>(module);
)

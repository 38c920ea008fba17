// Used by arrays.test: array fields of registered classes, of every element
// kind bsc reads by offset (int32, int16, uint8, float, double, bool, enum,
// string, a registered class), one and two dimensions, and const elements.
// The world module's `input` and `output` have array fields too, so that
// `bsc run --record`/`--replay` and the world loop are covered. The C++
// functions read the storage back, so a test sees where the script wrote,
// not only what b-script reads back.
#include <bscript/Bind.h>
#include <cstdint>
#include <cstdio>

namespace ar {
enum class Mode : std::uint8_t { idle = 0, walk = 1, kick = 2 };
struct P {
  float x = 0, y = 0;
};
struct Grid {
  std::int32_t wide[8] = {10, 11, 12, 13, 14, 15, 16, 17};
  float m[3][3] = {{1, 2, 3}, {4, 5, 6}, {7, 8, 9}};
  std::int16_t small[3] = {-1, -300, 7};
  std::uint8_t bytes[4] = {250, 1, 2, 3};
  double d[2] = {0.25, -0.5};
  bool flags[3] = {true, false, true};
  Mode modes[2] = {Mode::walk, Mode::kick};
  P pts[3] = {{1, 2}, {3, 4}, {5, 6}};
  const char *names[2] = {"left", "right"};
  const std::int32_t fixed[2] = {42, 43};
};
int wideAt(const Grid &G, int I) { return G.wide[I]; }
float mAt(const Grid &G, int I, int J) { return G.m[I][J]; }
int bytesAt(const Grid &G, int I) { return G.bytes[I]; }
double dAt(const Grid &G, int I) { return G.d[I]; }
float ptX(const Grid &G, int I) { return G.pts[I].x; }

struct In {
  int time = 0;
  float dist[4] = {0.5f, 1.5f, 2.5f, 3.5f};
};
struct Out {
  std::int32_t wide[8] = {};
  float head[2][2] = {};
  ~Out() {
    std::printf("~out");
    for (int W : wide)
      std::printf(" %d", W);
    std::printf(" | %g %g %g %g\n", head[0][0], head[0][1], head[1][0],
                head[1][1]);
  }
};
} // namespace ar

BS_MODULE(Arrays,
  registerEnum<ar::Mode>(module, "Mode")
    .value("idle", ar::Mode::idle)
    .value("walk", ar::Mode::walk)
    .value("kick", ar::Mode::kick);
  registerClass<ar::P>(module, "P")
    .var<&ar::P::x>("x")
    .var<&ar::P::y>("y");
  registerClass<ar::Grid>(module, "Grid")
    .var<&ar::Grid::wide>("wide")
    .var<&ar::Grid::m>("m")
    .var<&ar::Grid::small>("small")
    .var<&ar::Grid::bytes>("bytes")
    .var<&ar::Grid::d>("d")
    .var<&ar::Grid::flags>("flags")
    .var<&ar::Grid::modes>("modes")
    .var<&ar::Grid::pts>("pts")
    .var<&ar::Grid::names>("names")
    .var<&ar::Grid::fixed>("fixed");
  registerFunction<&ar::wideAt>(module, "wideAt");
  registerFunction<&ar::mAt>(module, "mAt");
  registerFunction<&ar::bytesAt>(module, "bytesAt");
  registerFunction<&ar::dAt>(module, "dAt");
  registerFunction<&ar::ptX>(module, "ptX");
  registerClass<ar::In>(module, "In")
    .var<&ar::In::time>("time")
    .var<&ar::In::dist>("dist");
  registerClass<ar::Out>(module, "Out")
    .var<&ar::Out::wide>("wide")
    .var<&ar::Out::head>("head");
  registerInput<ar::In>(module);
  registerOutput<ar::Out>(module);
)

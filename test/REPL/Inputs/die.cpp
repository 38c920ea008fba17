// A binding that ends its process when asked to: abort() raises SIGABRT,
// which the cycle guard does not catch (as a robot's failed assert), so a
// `bsc replay --jobs` worker dies on it (test/REPL/replay-jobs.test).
#include <bscript/Bind.h>
#include <cstdlib>

namespace Die {
int when(int Time) {
  if (Time > 100)
    std::abort();
  return Time;
}
} // namespace Die

BS_MODULE(Die,
  registerFunction<&Die::when>(module, "when", "Die::when");
)

// A binding whose function crashes when asked to: `bsc run` must report the
// signal and the binding instead of dying, and a function that never
// returns, which the cycle limit must stop (test/REPL/run-guard.test).
#include <bscript/Bind.h>

namespace Crash {
int poke(int Where) {
  volatile int *Null = nullptr;
  return Where > 0 ? *Null : Where;
}
/// Never returns for a positive argument.
int spin(int N) {
  volatile int Count = N;
  while (Count > 0)
    Count = Count + 1 > 0 ? Count + 1 : 1;
  return Count;
}
} // namespace Crash

BS_MODULE(Crash,
  registerFunction<&Crash::poke>(module, "poke", "Crash::poke");
  registerFunction<&Crash::spin>(module, "spin", "Crash::spin");
)

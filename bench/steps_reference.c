/* The same state machines as Steps.bs, written by hand in C the way a robot
 * programmer would without b-script: explicit phase variables and a switch.
 * This is the reference the benchmark compares bsc's output against. */
#include <stdlib.h>

struct child { int phase, n, k, state; };
struct parent { int started, rounds; struct child child; };

static void child_step(struct child *c, int limit) {
  if (c->state <= 0) { c->phase = 0; c->n = 0; c->k = 0; }
  switch (c->phase) {
  case 0:
    if (c->n < limit) { c->n += 1; c->state = 1; return; }
    c->phase = 1; c->state = 1; return;
  case 1:
    c->phase = 2; c->k = 0;
    /* fall through */
  case 2:
    if (c->k < 2) { c->k += 1; c->state = 1; return; }
    c->state = 0; return;
  }
}

static void parent_step(struct parent *p) {
  child_step(&p->child, 5);
  if (p->child.state == 0)
    p->rounds += 1;
}

int main(int argc, char **argv) {
  static struct parent p;
  long cycles = argc > 1 ? atol(argv[1]) : 1;
  for (long i = 0; i < cycles; ++i) {
    __asm__ volatile("" ::: "memory"); /* one cycle at a time, as a robot */
    parent_step(&p);
  }
  return p.rounds == 0 && cycles > 20;
}

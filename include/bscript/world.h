/*===- bscript/world.h - the hooks of a world library --------------------===*
 *
 * A world library (`bsc run --world LIB.so`, `bsc repl --world LIB.so`,
 * docs/repl.md "A closed loop" and "A team in one process") simulates what
 * the robot's software does around the behavior: it fills `input` before
 * each cycle and reads `output` after it. It is a shared library (built
 * with -shared -fPIC) exporting these functions with C linkage; bsc looks
 * them up by name, so a library defines them, this header only declares
 * them (including it checks the definitions' signatures).
 *
 * A robot world (bs_world_*) simulates one robot. With `--robots N` each
 * robot gets its own: bs_world_init runs once per robot, and the N worlds
 * know nothing of each other.
 *
 * A team world (bs_team_*) simulates the whole team at once: a library
 * that exports bs_team_init is one, whatever else it exports. Each cycle
 * the robots run in index order, each as begin, entry, end; so a world that
 * moves everything at once does it in the last robot's bs_team_end
 * (robot == robots - 1), and every robot's bs_team_begin sees the same
 * world.
 *
 *===----------------------------------------------------------------------===*/
#ifndef BSCRIPT_WORLD_H
#define BSCRIPT_WORLD_H

#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/* A robot world. */

/** Once, after `input` and `output` are constructed; the result becomes
 *  the state's user pointer (bs::Context::user()). Required. */
void *bs_world_init(void *input, void *output);
/** Right after bs_world_init: which robot of how many this world is
 *  (`--robots N`, robots counted from 0; robot 0 of 1 without), so that
 *  the N robot worlds of a team can differ (a seed, a side of the pitch).
 *  Optional. */
void bs_world_robot(void *user, unsigned robot, unsigned robots);
/** Before each cycle's entry; `cycle` counts from 1. Required. */
void bs_world_begin(void *user, void *input, void *output, uint32_t cycle);
/** After each cycle's entry. Optional. */
void bs_world_end(void *user, const void *input, void *output,
                  uint32_t cycle);
/** When the run ends, before the state is destroyed. Optional. */
void bs_world_exit(void *user);

/* A team world: `team` is what bs_team_init returned, `robot` the robot's
 * index, 0 to robots - 1. */

/** Once, before any robot; `robots` is --robots' N. Required. */
void *bs_team_init(unsigned robots);
/** Once per robot, in index order, after bs_team_init; the result becomes
 *  that robot's user pointer (bs::Context::user()). Optional: without it
 *  every robot's user pointer is `team`. */
void *bs_team_robot(void *team, unsigned robot, void *input, void *output);
/** Before robot `robot`'s entry in each cycle. Required. */
void bs_team_begin(void *team, unsigned robot, void *input, void *output,
                   uint32_t cycle);
/** After robot `robot`'s entry in each cycle. Optional. */
void bs_team_end(void *team, unsigned robot, const void *input, void *output,
                 uint32_t cycle);
/** Once when the run ends, before the robots' states are destroyed.
 *  Optional. */
void bs_team_exit(void *team);

#ifdef __cplusplus
}
#endif

#endif /* BSCRIPT_WORLD_H */

/*===- flight.h - the robot's flight recorder -----------------------------===*
 *
 * A behavior compiled with `bsc -c --flight-recorder` logs, per cycle, what
 * it observed: the words of `input` that changed since the cycle before
 * (whole in key cycles), every call into registered C++ that is not
 * registered `.pure()` with its result and the bytes of `input`, `output`
 * and its pointer arguments that it changed, and the `output` the cycle
 * left. With the behavior's sources and bindings, `bsc run --replay`,
 * `bsc repl`, `bsc replay --logs` and `bsc timeline` replay such a log
 * exactly at the desk (docs/repl.md, "The robot's log").
 *
 * The recorder writes into memory the robot program gives it: a ring of
 * blocks of fixed size and three copies of the world's objects. It never
 * allocates and makes no system call; a full block is handed to the
 * program's own log writer, either through a callback at once (inside the
 * cycle, so it should only copy or queue the block) or through
 * bs_flight_pull, from another thread or between cycles. Written one after
 * the other, the blocks are a log file (".bslog"), starting with the first.
 *
 *   static unsigned char memory[...];   // bs_flight_memory_size(...)
 *   bs_flight_recorder recorder;
 *   bs_flight_config config = {&bs_Soccer_flight, &bs_Soccer_info,
 *                              "Soccer::play", memory, sizeof memory,
 *                              16384, 4, 0, write_block, log_file};
 *   if (bs_flight_start(&recorder, &config) != BS_FLIGHT_OK) ...
 *   each cycle:
 *     bs_begin_cycle(state, &input, &output);
 *     bs_flight_begin(&recorder, state);
 *     bs_Soccer__Soccer__play(state);
 *     bs_flight_end(&recorder, state);
 *   at the end: bs_flight_flush(&recorder);
 *
 * One recorded cycle runs at a time in a process: calls into C++ find the
 * recorder that bs_flight_begin made current (the runtime needs no
 * thread-local storage). Robots stepped one after the other in one process
 * each have a recorder of their own.
 *===----------------------------------------------------------------------===*/
#ifndef BSCRIPT_FLIGHT_H
#define BSCRIPT_FLIGHT_H

#include "bscript.h"

#ifdef __cplusplus
extern "C" {
#endif

/** The table's version; bs_flight_start refuses another. */
#define BS_FLIGHT_VERSION 1

/** A call site of registered C++, as generated code hands it over. */
typedef struct bs_flight_site {
  const char *name;          /**< "Module::function", "Class.method (set)" */
  uint32_t flags;            /**< BS_FLIGHT_SITE_* */
  uint32_t result_size;      /**< Bytes of its result; 0: void. */
  uint32_t num_ptrs;         /**< Pointer arguments it may write... */
  const uint32_t *ptr_sizes; /**< ...and their sizes. */
  uint32_t index;            /**< In bs_flight_table.sites. */
} bs_flight_site;

/** The result is a string (its characters are logged). */
#define BS_FLIGHT_SITE_STRING 1
/** The standard `io` module, which only prints: not logged. */
#define BS_FLIGHT_SITE_STANDARD 2

/** An exported entry and the hash a log of it carries. */
typedef struct bs_flight_entry {
  const char *name; /**< "Soccer::play" */
  const char *hash; /**< 16 hex digits: the behavior, its bindings, entry. */
} bs_flight_entry;

/** `bs_<Behavior>_flight`, exported by an object with --flight-recorder. */
typedef struct bs_flight_table {
  uint32_t version; /**< BS_FLIGHT_VERSION */
  uint32_t num_sites;
  const bs_flight_site *const *sites;
  uint32_t input_size, output_size; /**< Of the world's objects. */
  const char *target;               /**< "i586", "x86_64" */
  const char *layout; /**< 16 hex digits: how input and output are laid out. */
  uint32_t num_entries;
  const bs_flight_entry *entries;
  /** Whether the object evaluates its assertions' conditions (and so
   *  makes and logs their calls): --assertions=count or trap. */
  uint32_t assertions;
} bs_flight_table;

/** bs_flight_start's settings. */
typedef struct bs_flight_config {
  const bs_flight_table *table;
  /** With `--instrument`, each cycle's trace record is logged too; may be
   *  NULL. */
  const bs_behavior_info *info;
  /** The entry the program calls each cycle, as in table->entries. */
  const char *entry;
  /** bs_flight_memory_size(table, block_bytes, num_blocks) bytes,
   *  8-aligned, that the recorder owns until the program stops using it. */
  void *memory;
  uint32_t memory_bytes;
  /** The size of a block as handed over (at least 1024; 16384 suits a
   *  robot that writes its log in pages), and how many the ring holds
   *  (at least 2). */
  uint32_t block_bytes, num_blocks;
  /** Every how many cycles the input and output are logged whole (0:
   *  256). */
  uint32_t key_every;
  /** Called with each full block; NULL: blocks wait for bs_flight_pull. */
  void (*on_block)(void *user, const void *bytes, uint32_t size);
  void *user;
} bs_flight_config;

/** bs_flight_start's results. */
#define BS_FLIGHT_OK 0
#define BS_FLIGHT_BAD_TABLE (-1)    /**< NULL, or of another version. */
#define BS_FLIGHT_NO_ENTRY (-2)     /**< `entry` is not in the table. */
#define BS_FLIGHT_SMALL_MEMORY (-3) /**< Less than bs_flight_memory_size. */
#define BS_FLIGHT_SMALL_BLOCK (-4)  /**< Fewer than 2 blocks, or too small
                                         for the header and a key cycle. */

/** The recorder. Its members are the runtime's. */
typedef struct bs_flight_recorder {
  const bs_flight_table *table;
  const bs_behavior_info *info;
  unsigned char *input_seen, *output_seen, *output_before;
  unsigned char *ring;
  uint32_t block_bytes, num_blocks, key_every;
  void (*on_block)(void *user, const void *bytes, uint32_t size);
  void *user;
  const unsigned char *input;
  unsigned char *output;
  uint32_t filling;      /**< The block being written... */
  unsigned char *records; /**< ...and where its records start. */
  uint32_t used;         /**< Its bytes so far, after its header. */
  uint32_t cycle_at;     /**< Where the running cycle's record starts. */
  uint32_t calls_at;     /**< Where its calls' bytes start. */
  uint32_t num_calls;
  uint32_t cycle, cycles, lost, lost_from, lost_total;
  uint32_t pulled, ready; /**< Blocks handed out, blocks waiting. */
  int recording;          /**< In a cycle whose record is being written. */
  int first_block;        /**< The block being written is the log's first. */
  void *previous;         /**< The recorder current before begin. */
} bs_flight_recorder;

/** The memory a recorder needs for `num_blocks` blocks of `block_bytes`. */
uint32_t bs_flight_memory_size(const bs_flight_table *table,
                               uint32_t block_bytes, uint32_t num_blocks);

/** Starts a log in `config->memory`: writes its header. BS_FLIGHT_OK or
 *  one of the errors above. */
int bs_flight_start(bs_flight_recorder *recorder,
                    const bs_flight_config *config);

/** Starts the cycle's record: after bs_begin_cycle, before the entry (a
 *  NULL recorder records nothing). */
void bs_flight_begin(bs_flight_recorder *recorder, const void *state);

/** Ends the cycle's record: after the entry calls. */
void bs_flight_end(bs_flight_recorder *recorder, const void *state);

/** Closes the block being written, if it has records, and hands it over:
 *  at the end of a game, before the program stops. */
void bs_flight_flush(bs_flight_recorder *recorder);

/** Without a callback: the oldest full block (1) or none (0). The block
 *  stays valid until bs_flight_release. */
int bs_flight_pull(bs_flight_recorder *recorder, const void **bytes,
                   uint32_t *size);
void bs_flight_release(bs_flight_recorder *recorder);

/** Cycles that found no free block (the log writer did not keep up) or did
 *  not fit in one; the log says where, and a replay stops there. */
static inline uint32_t bs_flight_lost(const bs_flight_recorder *recorder) {
  return recorder->lost_total;
}

/** Programs bsc links with --flight-recorder call these around their
 *  cycles: the log goes to the file $BS_FLIGHT_LOG names (none without it:
 *  then NULL, which bs_flight_begin and bs_flight_end take as "record
 *  nothing"). They use stdio, like the io module. */
bs_flight_recorder *bs_flight_program_start(const bs_flight_table *table,
                                            const bs_behavior_info *info,
                                            const char *entry);
void bs_flight_program_end(bs_flight_recorder *recorder);

/** What generated code calls around each call of registered C++. */
void bs_flight_enter(const bs_flight_site *site);
void bs_flight_leave(const bs_flight_site *site, void *result,
                     void *const *ptrs);

#ifdef __cplusplus
}
#endif

#endif /* BSCRIPT_FLIGHT_H */

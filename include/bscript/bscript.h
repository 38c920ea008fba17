/*===- bscript.h - the C API of a compiled b-script behavior -------------===*
 *
 * What robot code includes to run a behavior that bsc compiled. The
 * generated object keeps all of its mutable state in one block of memory
 * that the embedding provides (a static, a member of a robot object, one per
 * simulated robot): generated code has no mutable globals and never
 * allocates. Resetting a behavior is re-initialising its state.
 *
 * For a behavior named B (bsc --behavior-name, default: the first input's
 * module name) the object exports:
 *   const bs_behavior_info bs_B_info;        sizes and the task table
 *   void bs_B__M__f(void *state, args...);   one entry per top-level func or
 *                                            task f of module M whose
 *                                            parameters are int/float/bool;
 *                                            a func's result is returned
 * `bsc --emit-header` writes the typed face of these for one behavior.
 *
 * A behavior compiled with `bsc --bind` also refers to the descriptor
 * `bs_module_<Name>` of every binding module it was compiled against and
 * records the descriptor's hash; bs_state_init refuses to start when a
 * linked descriptor has another hash (the script is stale: sizes, offsets
 * or signatures changed since it was compiled).
 *
 * A cycle: bs_begin_cycle(state, &input, &output), then call the entry.
 * When the robot stops the behavior: bs_state_destroy(state, &bs_B_info),
 * which destroys the C++ values running tasks keep in the state.
 *===----------------------------------------------------------------------===*/
#ifndef BSCRIPT_BSCRIPT_H
#define BSCRIPT_BSCRIPT_H

#include <stddef.h>
#include <stdint.h>

#ifdef __cplusplus
extern "C" {
#endif

/** Bumped whenever the layout below changes; bs_behavior_info carries it. */
#define BS_ABI_VERSION 10

/** Task states (language.md): > 0 running, 0 done, < 0 failure. */
#define BS_TASK_DONE 0
#define BS_TASK_RUNNING 1
#define BS_TASK_FAILURE (-1)

/** The start of every behavior state. */
typedef struct bs_state_header {
  uint32_t cycle;     /**< Execution cycle; bs_begin_cycle increments it. */
  const void *input;  /**< The `input` global of this cycle. */
  void *output;       /**< The `output` global of this cycle. */
  /** The embedding's per-robot pointer (bs_state_set_user), which
   *  registered C++ reads through bs::Context::user(); NULL after
   *  bs_state_init. */
  void *user;
} bs_state_header;

/** The bit of a task's last call that marks an ending call. */
#define BS_LAST_CALL_ENDED 0x80000000u

/** Where a task keeps its header inside the state. Every task has
 *  - its last call (uint32 at frame_offset, the start of its frame): the
 *    cycle of its most recent call, with bit 31 flipped if that call ended
 *    the task (done or failure); bs_state_init sets 0x80000000 ("ended in
 *    cycle 0"). A task was called in this cycle or the previous one if
 *    cycle - last_call is 0 or 1 (unsigned): one subtraction;
 *  - its resume point (unsigned, resume_bytes wide, at resume_offset):
 *    0: start from the top; k: after the k-th yield;
 *  - its state (signed, state_bytes wide, at state_offset): the task state
 *    its most recent call left.
 *  The resume point and the state are as narrow as the task's values
 *  allow: 1 byte up to 255 yields, 2 up to 65535; a state of 1 byte when
 *  every state the task yields is a constant from -128 to 127. Narrow ones
 *  sit with the other tasks' after the frames, so that the state holds no
 *  padding for them; 4-byte ones follow the last call in the frame. Read
 *  them with bs_task_state_at and bs_task_resume_at. */
typedef struct bs_task_info {
  const char *name;       /**< "Module::task" */
  uint32_t frame_offset;  /**< Of its frame, which starts with last_call. */
  uint32_t resume_offset; /**< Of its resume point. */
  uint32_t state_offset;  /**< Of its state. */
  uint8_t resume_bytes;   /**< 1, 2 or 4. */
  uint8_t state_bytes;    /**< 1 or 4. */
} bs_task_info;

/** bs_state_init's results. */
#define BS_INIT_OK 0
#define BS_INIT_BAD_INFO (-1)       /**< Another ABI version, or misaligned. */
#define BS_INIT_STALE_BINDINGS (-2) /**< See bs_check_bindings. */
/** The generated header's bs_B_init: the object's state size is not the
 *  header's (the two come from different compilations: another target or
 *  script, or `--instrument` on one of them only). */
#define BS_INIT_WRONG_SIZE (-3)

/** A binding module the behavior was compiled against. */
typedef struct bs_binding_module {
  const char *name;       /**< "Math" */
  const void *descriptor; /**< &bs_module_Math, as linked */
  uint64_t hash;          /**< bs_binding_hash of the descriptor bsc read */
} bs_binding_module;

/** Trace records (`bsc --instrument`). Every task call of an instrumented
 *  behavior writes into the state's trace record which yield its task now
 *  waits at, so that the robot can log the active hierarchy for the price
 *  of a store or two per task call. The record is `record_size` bytes,
 *  4-aligned, at `offset` in the state: one slot per task (task-table
 *  order) of `slot_bytes` bytes (1; 2 if a task has more than 254 yields,
 *  4 past 65534), little-endian, which holds
 *    0               the task was not called in this cycle,
 *    k (1, 2, ...)   its last call this cycle stopped at its k-th yield,
 *    all ones        its last call finished it (done);
 *  then, from byte `clear_size` on, one int32 per task that yields values
 *  computed at run time (`yield acc + 1`): the state it yielded, valid when
 *  its slot names such a yield. bs_trace_begin clears the slots. */
typedef struct bs_trace_layout {
  uint32_t record_size; /**< Bytes of the record; 0: not instrumented. */
  uint32_t clear_size;  /**< Bytes of slots, which bs_trace_begin zeroes. */
  uint32_t slot_bytes;  /**< 1, 2 or 4. */
  uint32_t offset;      /**< Of the record inside the state. */
} bs_trace_layout;

/** Cycle budgets (`bsc --cycle-budget=N`). Every pass of a loop of a task
 *  or func, at the jump back to its head, costs one of the cycle's N
 *  passes; a task's loop that yields on every way round is free (it takes
 *  one pass per call of its task, and the calls are counted where they
 *  loop). When none is left, the loop ends its func (which returns its
 *  result's zero) or its task (which fails: TaskState::failure, and starts
 *  from the top at its next call), and so does every loop that runs
 *  after it in the same cycle: the cycle returns. The budget starts again
 *  with the next cycle (at the first entry call whose bs_state_header.cycle
 *  differs). The state holds a bs_budget_record at `offset` that says
 *  which loop ran out first; behaviors compiled without the option have
 *  none (budget 0). */
typedef struct bs_loop_info {
  const char *owner; /**< "Module::task" or "Module::func" */
  uint32_t line;     /**< Of the loop's `for`, in the owner's file. */
  uint32_t column;
  int32_t task;      /**< The owner's index in bs_behavior_info.tasks, or -1
                          for a func (which returns its result's zero). */
} bs_loop_info;

typedef struct bs_budget_layout {
  uint32_t budget;           /**< N loop passes per cycle; 0: none. */
  uint32_t offset;           /**< Of the bs_budget_record in the state. */
  uint32_t num_loops;        /**< The loops the budget counts, in order. */
  const bs_loop_info *loops;
} bs_budget_layout;

typedef struct bs_budget_record {
  uint32_t cycle;      /**< The cycle `used` counts in. */
  uint32_t used;       /**< Loop passes run in that cycle (at most budget). */
  uint32_t ran_out;    /**< Cycles whose budget ran out, since bs_state_init. */
  uint32_t loop;       /**< 1 + the index in bs_budget_layout.loops of the
                            loop that ran out first in the last such cycle;
                            0: never ran out. */
  uint32_t loop_cycle; /**< That cycle. */
} bs_budget_record;

/** Assertions (`assert(cond[, "message"])`, `bsc --assertions=MODE`). An
 *  object leaves them out by default (BS_ASSERTIONS_NONE: the conditions
 *  are not evaluated). With BS_ASSERTIONS_COUNT every failure adds one to
 *  the assertion's counter, a uint32_t in the state at `offset` + 4 * its
 *  index (bs_assertion_failures), and the behavior goes on; with
 *  BS_ASSERTIONS_TRAP a failure executes a trap instruction (SIGILL). */
#define BS_ASSERTIONS_NONE 0
#define BS_ASSERTIONS_COUNT 1
#define BS_ASSERTIONS_TRAP 2

typedef struct bs_assertion_info {
  const char *owner;     /**< "Module::task" or "Module::func" */
  const char *file;      /**< The owner's file, without folders. */
  uint32_t line;         /**< Of the `assert`. */
  uint32_t column;
  const char *condition; /**< As written, e.g. "ballDistance < 500". */
  const char *message;   /**< The message, or NULL. */
} bs_assertion_info;

typedef struct bs_assertion_layout {
  uint32_t mode;           /**< BS_ASSERTIONS_*. */
  uint32_t offset;         /**< COUNT: of the counters in the state. */
  uint32_t num_assertions; /**< In module and source order; 0 with NONE. */
  const bs_assertion_info *assertions;
} bs_assertion_layout;

typedef struct bs_behavior_info {
  uint32_t abi_version; /**< BS_ABI_VERSION of the compiler that made it. */
  uint32_t state_size;  /**< Bytes of state the embedding must provide... */
  uint32_t state_align; /**< ...aligned to this. */
  uint32_t num_tasks;
  const bs_task_info *tasks;
  uint32_t num_modules; /**< Binding modules it was compiled against. */
  const bs_binding_module *modules;
  /** Destroys the registered class values that the state's task frames
   *  hold (those whose C++ destructor does something); NULL when the
   *  behavior has none. Called through bs_state_destroy. */
  void (*destroy)(void *state);
  /** `bsc --instrument`: the debugger's static tables of the behavior as
   *  JSON text (task names, yield lines, frame fields, callers), which
   *  `bsc trace-decode` reads to turn a trace log into text; NULL
   *  otherwise. Also in the object's section `.bs_debug_tables`. */
  const char *debug_tables;
  /** `bsc --instrument`: where the behavior writes its trace record ("Trace
   *  records" below); all zero otherwise. */
  bs_trace_layout trace;
  /** `bsc --cycle-budget=N`: the budget, its record and the loop table
   *  ("Cycle budgets" above); all zero otherwise. */
  bs_budget_layout budget;
  /** `bsc --assertions=count|trap`: the assertions ("Assertions" above);
   *  all zero with the default, none. */
  bs_assertion_layout assertions;
} bs_behavior_info;

/** Zeroes a state: every task reports done and starts from the top at its
 *  next call. Returns BS_INIT_OK; BS_INIT_BAD_INFO if `info` is from another
 *  ABI version or the storage is misaligned; BS_INIT_STALE_BINDINGS (state
 *  untouched) if a linked binding module differs from the one the behavior
 *  was compiled against. */
int bs_state_init(void *state, const bs_behavior_info *info);

/** Ends the life of a state: runs the C++ destructor of every registered
 *  class value that a task frame holds (tasks that are running keep their
 *  locals in the state across cycles). Call it once when the behavior
 *  stops, before the storage is freed or reused; afterwards initialise the
 *  state again before the next cycle. A state that bs_state_init zeroed
 *  and that never ran, or one destroyed already, holds nothing to destroy
 *  (calling it again is harmless). Does nothing if `info` is from another
 *  ABI version. */
void bs_state_destroy(void *state, const bs_behavior_info *info);

/** The name of the first binding module whose linked descriptor does not
 *  have the hash the behavior was compiled against, or NULL if all match:
 *  for a message such as "the behavior was compiled against binding module
 *  'Math' whose descriptor has changed; recompile the scripts". */
const char *bs_check_bindings(const bs_behavior_info *info);

/** The hash of a binding module's descriptor (`&bs_module_Math`), the same
 *  as bs::moduleHash of bscript/Bind.h and bsc's (docs/bindings.md). */
uint64_t bs_binding_hash(const void *descriptor);

/** What a program does when bs_state_init returned `code` (not BS_INIT_OK):
 *  prints why on stderr and returns the exit status 1. Programs that bsc
 *  links call it; it uses stdio, like the io module. */
int bs_report_init_failure(const bs_behavior_info *info, int code);

/** Starts the trace record of the cycle that is about to run (after
 *  bs_begin_cycle, before the entry): zeroes its slots. Does nothing for a
 *  behavior compiled without `--instrument`.
 *
 *  Trace logs: a robot that logs its behavior writes, per cycle, the
 *  little-endian uint32 cycle (the state's bs_state_header.cycle) and the
 *  cycle's record (bs_trace_record, record_size bytes) after the entry
 *  calls. `bsc trace-decode --object B.o LOG` prints them as `bsc run
 *  --trace` does, with the names and lines of the tables an object compiled
 *  with `bsc --instrument` carries. */
void bs_trace_begin(void *state, const bs_behavior_info *info);

/** The trace record inside the state, or NULL for a behavior compiled
 *  without `--instrument`. */
const void *bs_trace_record(const void *state, const bs_behavior_info *info);

/** Starts the next execution cycle with this cycle's input and output. */
void bs_begin_cycle(void *state, const void *input, void *output);

/** bs_trace_begin inline, given the layout (bs_trace_layout.offset and
 *  clear_size): the header of --emit-header uses it with constants. */
static inline void bs_trace_begin_inline(void *state, uint32_t offset,
                                         uint32_t clear_size) {
  unsigned char *slots = (unsigned char *)state + offset;
  for (uint32_t i = 0; i < clear_size; ++i)
    slots[i] = 0;
}

/** bs_begin_cycle inline, for the robot's loop: it costs no call (the
 *  header of --emit-header uses it). */
static inline void bs_begin_cycle_inline(void *state, const void *input,
                                         void *output) {
  bs_state_header *header = (bs_state_header *)state;
  header->cycle += 1;
  header->input = input;
  header->output = output;
}

/** Attaches the embedding's per-robot data (a blackboard, the robot's
 *  world) to a state, after bs_state_init: registered functions and
 *  methods whose first C++ parameter is `bs::Context &` read it with
 *  `user()` (docs/bindings.md "Per-robot context"). Two robots in one
 *  process are two states with two user pointers. */
static inline void bs_state_set_user(void *state, void *user) {
  ((bs_state_header *)state)->user = user;
}

/** The pointer bs_state_set_user attached (NULL if none). */
static inline void *bs_state_user(const void *state) {
  return ((const bs_state_header *)state)->user;
}

/** A task's state (bs_task_info): what its most recent call left,
 *  BS_TASK_DONE if it was never called. */
static inline int32_t bs_task_state_at(const void *state,
                                       const bs_task_info *task) {
  const unsigned char *at = (const unsigned char *)state + task->state_offset;
  if (task->state_bytes == 1)
    return *(const int8_t *)at;
  return *(const int32_t *)at;
}

/** A task's resume point (bs_task_info): 0 to start from the top, k to go
 *  on after its k-th yield. */
static inline uint32_t bs_task_resume_at(const void *state,
                                         const bs_task_info *task) {
  const unsigned char *at = (const unsigned char *)state + task->resume_offset;
  if (task->resume_bytes == 1)
    return *at;
  if (task->resume_bytes == 2)
    return *(const uint16_t *)at;
  return *(const uint32_t *)at;
}

/** A task's last call (bs_task_info). */
static inline uint32_t bs_task_last_call_at(const void *state,
                                            const bs_task_info *task) {
  return *(const uint32_t *)((const unsigned char *)state +
                             task->frame_offset);
}

/** The budget record of a behavior compiled with `--cycle-budget`, or NULL
 *  ("Cycle budgets" above). */
static inline const bs_budget_record *
bs_budget_record_at(const void *state, const bs_behavior_info *info) {
  if (!info->budget.budget)
    return NULL;
  return (const bs_budget_record *)((const unsigned char *)state +
                                    info->budget.offset);
}

/** The loop whose budget ran out in the state's current cycle (after the
 *  cycle's entry calls), or NULL if none did: for a robot's log line such
 *  as "cycle 812: loop of Striker::approach (line 40) ran out of budget". */
static inline const bs_loop_info *
bs_budget_ran_out(const void *state, const bs_behavior_info *info) {
  const bs_budget_record *record = bs_budget_record_at(state, info);
  if (!record || !record->loop ||
      record->loop_cycle != ((const bs_state_header *)state)->cycle ||
      record->loop > info->budget.num_loops)
    return NULL;
  return &info->budget.loops[record->loop - 1];
}

/** Prints on stderr which loop ran out of its budget in the state's current
 *  cycle, if one did (bs_budget_ran_out), and returns 1 then, else 0.
 *  Programs that bsc links with `--cycle-budget` call it after each cycle;
 *  it uses stdio, like the io module. */
int bs_report_budget(const void *state, const bs_behavior_info *info);

/** How often assertion `index` (bs_assertion_layout.assertions) failed
 *  since bs_state_init; 0 unless compiled with `--assertions=count`. */
static inline uint32_t bs_assertion_failures(const void *state,
                                             const bs_behavior_info *info,
                                             uint32_t index) {
  if (info->assertions.mode != BS_ASSERTIONS_COUNT ||
      index >= info->assertions.num_assertions)
    return 0;
  return ((const uint32_t *)((const unsigned char *)state +
                             info->assertions.offset))[index];
}

/** Prints on stderr every assertion that failed (bs_assertion_failures),
 *  with its place and count, and returns 1 if one did, else 0. Programs
 *  that bsc links with `--assertions=count` call it after the last cycle
 *  and exit with its result; it uses stdio, like the io module. */
int bs_report_assertions(const void *state, const bs_behavior_info *info);

/** The state that task `name` ("Module::task") left at its most recent call
 *  (BS_TASK_DONE if never called); `found` (may be NULL) tells whether the
 *  behavior has such a task. */
int32_t bs_task_state(const void *state, const bs_behavior_info *info,
                      const char *name, int *found);

/** The C functions of the standard module `io`: each prints its value and a
 *  newline. printf uses "%g"; printb prints true/false (nonzero is true).
 *  Scripts reach them through the thunks of the runtime's io_module.cpp,
 *  which registers them with bscript/Bind.h; a robot without stdout
 *  replaces these (io.c) and keeps the registration. */
void bs_io_printi(int32_t value);
void bs_io_printf(float value);
void bs_io_printb(int32_t value);
void bs_io_prints(const char *value);

#ifdef __cplusplus
}
#endif

#endif /* BSCRIPT_BSCRIPT_H */

/*===- bscript.c - the runtime shim of compiled behaviors ----------------===*
 *
 * The whole runtime a compiled behavior needs besides `io`: initialising a
 * state, starting a cycle, reading a task's state by name (include/bscript/
 * bscript.h). It stays tiny and free of libc (loops instead of memset and
 * strcmp; CMake also stops the compiler from turning them back into calls)
 * so that it links into any robot software, and so that the same file serves
 * the host, the JIT and the robot.
 *===----------------------------------------------------------------------===*/
#include "bscript/bscript.h"

int bs_state_init(void *state, const bs_behavior_info *info) {
  if (!state || !info || info->abi_version != BS_ABI_VERSION)
    return -1;
  if (info->state_align == 0 ||
      (uintptr_t)state % (uintptr_t)info->state_align != 0)
    return -1;
  /* Zero state: cycle 0, every frame's state done and resume point 0, so
   * every task starts from the top at its first call. */
  unsigned char *bytes = (unsigned char *)state;
  for (uint32_t i = 0; i < info->state_size; ++i)
    bytes[i] = 0;
  return 0;
}

void bs_begin_cycle(void *state, const void *input, void *output) {
  bs_state_header *header = (bs_state_header *)state;
  header->cycle += 1;
  header->input = input;
  header->output = output;
}

/* Whether two NUL-terminated strings are equal. */
static int bs_same_name(const char *a, const char *b) {
  while (*a && *a == *b) {
    ++a;
    ++b;
  }
  return *a == *b;
}

int32_t bs_task_state(const void *state, const bs_behavior_info *info,
                      const char *name, int *found) {
  if (found)
    *found = 0;
  if (!state || !info || !name)
    return BS_TASK_DONE;
  for (uint32_t i = 0; i < info->num_tasks; ++i) {
    if (!bs_same_name(info->tasks[i].name, name))
      continue;
    if (found)
      *found = 1;
    const bs_frame_header *frame =
        (const bs_frame_header *)((const unsigned char *)state +
                                  info->tasks[i].frame_offset);
    return frame->state;
  }
  return BS_TASK_DONE;
}

/*===- bscript.c - the runtime shim of compiled behaviors ----------------===*
 *
 * The whole runtime a compiled behavior needs besides `io`: initialising a
 * state, starting a cycle and its trace record, reading a task's state by
 * name, checking the linked binding modules against the hashes the behavior
 * was compiled with (include/bscript/bscript.h). It stays tiny and free of
 * libc (loops instead of memset and strcmp; CMake also stops the compiler
 * from turning them back into calls) so that it links into any robot
 * software, and so that the same file serves the host, the JIT and the
 * robot. bs_state_destroy runs the behavior's own destroy function
 * (bs_behavior_info.destroy), which calls the class destructors' thunks.
 *===----------------------------------------------------------------------===*/
#include "bscript/bscript.h"
#include "bscript/descriptor.h"

/* The pointer stored at `p` (a descriptor's "P" field, relocated). */
static const unsigned char *bs_read_pointer(const unsigned char *p) {
  uintptr_t value = 0;
  for (unsigned i = 0; i < sizeof value; ++i)
    value |= (uintptr_t)p[i] << (8 * i);
  return (const unsigned char *)value;
}

/* A field's offset for bs_descriptor_hash: the bytes of the Itanium data
 * member pointer that member `index`'s holder holds, a ptrdiff_t. */
static int bs_field_offset(void *descriptor, uint32_t index, int64_t *offset) {
  const unsigned char *d = (const unsigned char *)descriptor;
  const unsigned char *h = d + BS_HDR_TABLE(BS_TABLE_MEMBERS);
  const unsigned char *holder = bs_read_pointer(
      d + bs_descriptor_u32(h + 4) + index * bs_descriptor_u32(h + 8) +
      BS_MEMBER_MEMPTR * sizeof(void *));
  if (!holder)
    return 0;
  uint64_t raw = 0;
  for (unsigned k = 0; k < sizeof(ptrdiff_t); ++k)
    raw |= (uint64_t)holder[k] << (8 * k);
  /* Sign-extend a 32-bit ptrdiff_t. */
  unsigned unused = 64 - 8 * (unsigned)sizeof(ptrdiff_t);
  *offset = (int64_t)(raw << unused) >> unused;
  return 1;
}

uint64_t bs_binding_hash(const void *descriptor) {
  return bs_descriptor_hash((const unsigned char *)descriptor, bs_field_offset,
                            (void *)descriptor);
}

const char *bs_check_bindings(const bs_behavior_info *info) {
  if (!info || info->abi_version != BS_ABI_VERSION)
    return 0;
  for (uint32_t i = 0; i < info->num_modules; ++i) {
    const bs_binding_module *m = &info->modules[i];
    if (!m->descriptor || bs_binding_hash(m->descriptor) != m->hash)
      return m->name;
  }
  return 0;
}

int bs_state_init(void *state, const bs_behavior_info *info) {
  if (!state || !info || info->abi_version != BS_ABI_VERSION)
    return BS_INIT_BAD_INFO;
  if (info->state_align == 0 ||
      (uintptr_t)state % (uintptr_t)info->state_align != 0)
    return BS_INIT_BAD_INFO;
  if (bs_check_bindings(info))
    return BS_INIT_STALE_BINDINGS;
  /* Zero state: cycle 0, every task's state done and resume point 0, and
   * its last call one that ended the task in cycle 0, so every task starts
   * from the top at its first call. */
  unsigned char *bytes = (unsigned char *)state;
  for (uint32_t i = 0; i < info->state_size; ++i)
    bytes[i] = 0;
  for (uint32_t i = 0; i < info->num_tasks; ++i)
    *(uint32_t *)(bytes + info->tasks[i].frame_offset) = BS_LAST_CALL_ENDED;
  return BS_INIT_OK;
}

void bs_state_destroy(void *state, const bs_behavior_info *info) {
  /* Each frame records whether its values are constructed, so a zeroed
   * state and a destroyed one are both left alone. */
  if (state && info && info->abi_version == BS_ABI_VERSION && info->destroy)
    info->destroy(state);
}

void bs_begin_cycle(void *state, const void *input, void *output) {
  bs_begin_cycle_inline(state, input, output);
}

void bs_trace_begin(void *state, const bs_behavior_info *info) {
  if (bs_trace_record(state, info))
    bs_trace_begin_inline(state, info->trace.offset, info->trace.clear_size);
}

const void *bs_trace_record(const void *state, const bs_behavior_info *info) {
  if (!state || !info || info->abi_version != BS_ABI_VERSION ||
      !info->trace.record_size)
    return 0;
  return (const unsigned char *)state + info->trace.offset;
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
    return bs_task_state_at(state, &info->tasks[i]);
  }
  return BS_TASK_DONE;
}

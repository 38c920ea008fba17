/*===- bscript.c - the runtime shim of compiled behaviors ----------------===*
 *
 * The whole runtime a compiled behavior needs besides `io`: initialising a
 * state, starting a cycle, reading a task's state by name, checking the
 * linked binding modules against the hashes the behavior was compiled with
 * (include/bscript/bscript.h). It stays tiny and free of libc (loops instead of memset and
 * strcmp; CMake also stops the compiler from turning them back into calls)
 * so that it links into any robot software, and so that the same file serves
 * the host, the JIT and the robot. bs_state_destroy runs the behavior's
 * own destroy function (bs_behavior_info.destroy), which calls the class
 * destructors' thunks.
 *===----------------------------------------------------------------------===*/
#include "bscript/bscript.h"

/* The little-endian 32-bit word at `p` (descriptors are little-endian and
 * need not be aligned for this reader). */
static uint32_t bs_read_u32(const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
         (uint32_t)p[3] << 24;
}

/* The pointer stored at `p` (a descriptor's "P" field, relocated). */
static const unsigned char *bs_read_pointer(const unsigned char *p) {
  uintptr_t value = 0;
  for (unsigned i = 0; i < sizeof value; ++i)
    value |= (uintptr_t)p[i] << (8 * i);
  return (const unsigned char *)value;
}

/* FNV-1a 64, one byte at a time. */
static uint64_t bs_fnv(uint64_t hash, unsigned char byte) {
  return (hash ^ byte) * 0x100000001b3ull;
}

/* The descriptor header's fields (byte offsets, docs/bindings.md) and the
 * tables whose records start with pointer fields: {count, offset, record
 * size} at these header offsets, and how many pointers each record has. */
enum { BS_HDR_PTRSIZE = 16, BS_HDR_STRINGS = 100 };
static const struct {
  unsigned char header_offset, pointers;
} bs_pointer_tables[] = {{40, 2} /* classes */, {52, 4} /* members */,
                         {64, 1} /* params */, {76, 1} /* enums */};
enum { BS_HDR_MEMBERS = 52, BS_MEMBER_MEMPTR = 2 };

/* Whether byte `i` of the descriptor lies in a pointer field. */
static int bs_in_pointer(const unsigned char *d, uint32_t i) {
  uint32_t ptr_size = bs_read_u32(d + BS_HDR_PTRSIZE);
  for (unsigned t = 0; t < sizeof bs_pointer_tables / sizeof *bs_pointer_tables;
       ++t) {
    const unsigned char *h = d + bs_pointer_tables[t].header_offset;
    uint32_t count = bs_read_u32(h), offset = bs_read_u32(h + 4),
             size = bs_read_u32(h + 8);
    if (i >= offset && i - offset < count * size)
      return (i - offset) % size < bs_pointer_tables[t].pointers * ptr_size;
  }
  return 0;
}

uint64_t bs_binding_hash(const void *descriptor) {
  const unsigned char *d = (const unsigned char *)descriptor;
  uint64_t hash = 0xcbf29ce484222325ull;
  /* The bytes up to the end of the string table, pointer fields as zero
   * (they hold addresses, which differ from program to program)... */
  uint32_t end = bs_read_u32(d + BS_HDR_STRINGS) +
                 bs_read_u32(d + BS_HDR_STRINGS + 4);
  for (uint32_t i = 0; i < end; ++i)
    hash = bs_fnv(hash, bs_in_pointer(d, i) ? 0 : d[i]);
  /* ...then the offset of every field (the bytes of the Itanium data member
   * pointer its holder holds), as 8 little-endian bytes in member order. */
  uint32_t ptr_size = bs_read_u32(d + BS_HDR_PTRSIZE);
  uint32_t count = bs_read_u32(d + BS_HDR_MEMBERS),
           offset = bs_read_u32(d + BS_HDR_MEMBERS + 4),
           size = bs_read_u32(d + BS_HDR_MEMBERS + 8);
  for (uint32_t m = 0; m < count; ++m) {
    const unsigned char *holder = bs_read_pointer(
        d + offset + m * size + BS_MEMBER_MEMPTR * ptr_size);
    if (!holder)
      continue;
    uint64_t raw = 0;
    for (unsigned k = 0; k < sizeof(ptrdiff_t); ++k)
      raw |= (uint64_t)holder[k] << (8 * k);
    /* Sign-extend a 32-bit ptrdiff_t, as the C++ hash does. */
    unsigned unused = 64 - 8 * (unsigned)sizeof(ptrdiff_t);
    uint64_t field_offset = (uint64_t)((int64_t)(raw << unused) >> unused);
    for (unsigned k = 0; k < 8; ++k)
      hash = bs_fnv(hash, (unsigned char)(field_offset >> (8 * k)));
  }
  return hash;
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
  /* Zero state: cycle 0, every frame's state done and resume point 0, and
   * its last call one that ended the task in cycle 0, so every task starts
   * from the top at its first call. */
  unsigned char *bytes = (unsigned char *)state;
  for (uint32_t i = 0; i < info->state_size; ++i)
    bytes[i] = 0;
  for (uint32_t i = 0; i < info->num_tasks; ++i)
    ((bs_frame_header *)(bytes + info->tasks[i].frame_offset))->last_call =
        BS_LAST_CALL_ENDED;
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

uint32_t bs_trace_snapshot(const void *state, const bs_behavior_info *info,
                           bs_activation *out, uint32_t capacity) {
  if (!state || !info || info->abi_version != BS_ABI_VERSION)
    return 0;
  const unsigned char *bytes = (const unsigned char *)state;
  uint32_t cycle = ((const bs_state_header *)state)->cycle, count = 0;
  if (cycle == 0)
    return 0;
  for (uint32_t i = 0; i < info->num_tasks; ++i) {
    const bs_frame_header *frame =
        (const bs_frame_header *)(bytes + info->tasks[i].frame_offset);
    /* Every call records the cycle (bit 31 flipped if the call ended the
     * task): the tasks called in this one. */
    if (((frame->last_call ^ cycle) & ~BS_LAST_CALL_ENDED) != 0)
      continue;
    if (count < capacity) {
      out[count].task = (uint16_t)i;
      out[count].resume = (uint16_t)frame->resume;
      out[count].state = frame->state;
    }
    ++count;
  }
  return count;
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

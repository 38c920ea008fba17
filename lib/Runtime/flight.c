/*===- flight.c - the robot's flight recorder ------------------------------===*
 *
 * Writes the binary log format of docs/repl.md "The robot's log" (bsc's
 * reader: lib/Run/BinaryLog.cpp) into the ring of bscript/flight.h. A
 * block in the ring is 8 bytes of room for the file's magic (used by the
 * log's first block only), the block's 12-byte header, then records. A
 * cycle record is written as the cycle runs; the counts that are only
 * known at its end (calls, runs) are LEB128 numbers padded to a fixed
 * width and filled in then. A record that outgrows its block moves to the
 * next one; one that outgrows an empty block, or a cycle that finds no
 * free block, is lost and logged as such ('G').
 *
 * No libc: the loops below are the copies and comparisons.
 *===----------------------------------------------------------------------===*/
#include "bscript/flight.h"

#define NO_BLOCK 0xffffffffu
#define MAGIC_ROOM 8u
#define BLOCK_HEADER 12u
/* What a cycle record holds besides its runs: tag, numbers, counts. */
#define RECORD_SLACK 48u

/* The recorder whose cycle runs now, which calls into C++ report to: a
 * plain static, as the runtime needs nothing from libc (no TLS). One
 * recorded cycle runs at a time in a process; a cycle recorded inside
 * another's (a second behavior called from C++) restores the outer one. */
static bs_flight_recorder *bs_flight_current;

/* A word that may lie anywhere and alias anything: copies and comparisons
 * go four bytes at a time, and compile to plain loads on x86. */
typedef uint32_t bs_word __attribute__((may_alias, aligned(1)));

static uint32_t align8(uint32_t n) { return (n + 7u) & ~7u; }

static void copy_bytes(unsigned char *to, const unsigned char *from,
                       uint32_t n) {
  uint32_t i = 0;
  for (; i + 4 <= n; i += 4)
    *(bs_word *)(to + i) = *(const bs_word *)(from + i);
  for (; i < n; ++i)
    to[i] = from[i];
}

static int same_text(const char *a, const char *b) {
  while (*a && *a == *b) {
    ++a;
    ++b;
  }
  return *a == *b;
}

static uint32_t text_length(const char *s) {
  uint32_t n = 0;
  while (s && s[n])
    ++n;
  return n;
}

uint32_t bs_flight_memory_size(const bs_flight_table *table,
                               uint32_t block_bytes, uint32_t num_blocks) {
  if (!table)
    return 0;
  return align8(table->input_size) + 2u * align8(table->output_size) +
         num_blocks * align8(MAGIC_ROOM + block_bytes);
}

/*--- Writing into the block being filled ---------------------------------*/

static unsigned char *slot_of(bs_flight_recorder *r, uint32_t slot) {
  return r->ring + slot * align8(MAGIC_ROOM + r->block_bytes);
}


static uint32_t capacity(const bs_flight_recorder *r) {
  return r->block_bytes - BLOCK_HEADER;
}

static uint32_t room(const bs_flight_recorder *r) {
  return r->used == NO_BLOCK ? 0 : capacity(r) - r->used;
}

/* Writing goes through a cursor `p` into the block being filled, which
 * the callers keep in a local and store back into `used` when done: the
 * stores of bytes then cannot make the compiler reload the recorder. */
static unsigned char *cursor(bs_flight_recorder *r) {
  return r->records + r->used;
}
static void settle(bs_flight_recorder *r, const unsigned char *p) {
  r->used = (uint32_t)(p - r->records);
}

static unsigned char *put_uleb(unsigned char *p, uint32_t v) {
  while (v >= 0x80u) {
    *p++ = (unsigned char)(v | 0x80u);
    v >>= 7;
  }
  *p++ = (unsigned char)v;
  return p;
}

/* A number written later (patch_uleb): three bytes of LEB128, up to
 * 2^21 - 1. */
static unsigned char *reserve_uleb(unsigned char *p) {
  p[0] = 0x80;
  p[1] = 0x80;
  p[2] = 0x00;
  return p + 3;
}

static void patch_uleb(unsigned char *p, uint32_t v) {
  p[0] = (unsigned char)((v & 0x7fu) | 0x80u);
  p[1] = (unsigned char)(((v >> 7) & 0x7fu) | 0x80u);
  p[2] = (unsigned char)((v >> 14) & 0x7fu);
}

static unsigned char *put_bytes(unsigned char *p, const void *bytes,
                                uint32_t n) {
  copy_bytes(p, (const unsigned char *)bytes, n);
  return p + n;
}

static unsigned char *put_text(unsigned char *p, const char *s) {
  uint32_t n = text_length(s);
  return put_bytes(put_uleb(p, n), s, n);
}

/* The runs where `now` differs from `seen` (n bytes, at `base` in the
 * view): whole words of four bytes (a tail of fewer, byte by byte), not
 * joined across equal words (a gap costs less than the word). `seen`
 * becomes `now`. Continues the run list whose previous run ended at
 * *prev, adding to *runs. */
static unsigned char *put_runs(unsigned char *p, const unsigned char *now,
                               unsigned char *seen, uint32_t n, uint32_t base,
                               uint32_t *prev, uint32_t *runs) {
  uint32_t i = 0, words = n & ~3u;
  while (i < n) {
    while (i < words &&
           *(const bs_word *)(now + i) == *(const bs_word *)(seen + i))
      i += 4;
    if (i >= words)
      while (i < n && now[i] == seen[i])
        ++i;
    if (i >= n)
      break;
    uint32_t start = i;
    if (i < words) {
      do {
        *(bs_word *)(seen + i) = *(const bs_word *)(now + i);
        i += 4;
      } while (i < words &&
               *(const bs_word *)(now + i) != *(const bs_word *)(seen + i));
    } else {
      do {
        seen[i] = now[i];
        ++i;
      } while (i < n && now[i] != seen[i]);
    }
    p = put_uleb(p, base + start - *prev);
    p = put_uleb(p, i - start);
    p = put_bytes(p, seen + start, i - start);
    *prev = base + i;
    ++*runs;
  }
  return p;
}

/* The worst a run list over n bytes takes: a run every other word (or
 * byte, in the tail), each with a gap and a length of up to 3 bytes. */
static uint32_t runs_bound(uint32_t n) { return 4u * n + 8u; }

/*--- Blocks ------------------------------------------------------------------*/

static void hand_over(bs_flight_recorder *r) {
  unsigned char *slot = slot_of(r, r->filling);
  unsigned char *head = slot + MAGIC_ROOM;
  uint32_t n = r->used;
  for (int k = 0; k < 4; ++k) {
    head[k] = (unsigned char)(n >> (8 * k));
    head[4 + k] = (unsigned char)(n >> (8 * k));
  }
  head[8] = head[9] = head[10] = head[11] = 0; /* raw */
  const unsigned char *from = head;
  uint32_t size = BLOCK_HEADER + n;
  if (r->first_block) {
    static const unsigned char magic[8] = {'B', 'S', 'L', 'O', 'G', 0x1a, 1, 0};
    copy_bytes(slot, magic, 8);
    from = slot;
    size += 8;
    r->first_block = 0;
  }
  r->used = NO_BLOCK;
  if (r->on_block) {
    r->on_block(r->user, from, size);
    ++r->ready;
    ++r->pulled;
  } else {
    __atomic_store_n(&r->ready, r->ready + 1, __ATOMIC_RELEASE);
  }
}

/* Starts the next block if the ring has a free slot. */
static int open_block(bs_flight_recorder *r) {
  if (r->used != NO_BLOCK)
    return 1;
  uint32_t waiting = r->ready - __atomic_load_n(&r->pulled, __ATOMIC_ACQUIRE);
  if (waiting >= r->num_blocks)
    return 0;
  r->filling = r->ready % r->num_blocks;
  r->records = slot_of(r, r->filling) + MAGIC_ROOM + BLOCK_HEADER;
  r->used = 0;
  return 1;
}

/* Drops the running cycle's record: it is lost, which the log says
 * before the next cycle it keeps. */
static void lose_cycle(bs_flight_recorder *r) {
  if (r->recording && r->used != NO_BLOCK)
    r->used = r->cycle_at;
  r->recording = 0;
  if (!r->lost)
    r->lost_from = r->cycle;
  ++r->lost;
  ++r->lost_total;
}

/* Room for `more` bytes in the running cycle's record: if its block is
 * too full, the record moves to the next block (whose slot is another
 * one: there are at least two), and the block is handed over without it.
 * Returns 0 after losing the cycle if there is no free block or the
 * record would not fit in an empty one. */
static int make_room(bs_flight_recorder *r, uint32_t more) {
  if (!r->recording)
    return 0;
  if (room(r) >= more)
    return 1;
  uint32_t length = r->used - r->cycle_at;
  if (r->cycle_at == 0 || length + more > capacity(r)) {
    lose_cycle(r);
    return 0;
  }
  const unsigned char *from = r->records + r->cycle_at;
  uint32_t moved = r->cycle_at;
  r->used = r->cycle_at;
  hand_over(r); /* Its bytes stay in the slot until the ring comes round. */
  if (!open_block(r)) {
    r->used = NO_BLOCK;
    lose_cycle(r);
    return 0;
  }
  copy_bytes(r->records, from, length);
  r->used = length;
  r->cycle_at = 0;
  r->calls_at -= moved;
  return 1;
}

/*--- The log -------------------------------------------------------------*/

int bs_flight_start(bs_flight_recorder *r, const bs_flight_config *c) {
  const bs_flight_table *t = c ? c->table : 0;
  if (!t || t->version != BS_FLIGHT_VERSION)
    return BS_FLIGHT_BAD_TABLE;
  const char *hash = 0;
  for (uint32_t i = 0; i < t->num_entries && c->entry; ++i)
    if (same_text(t->entries[i].name, c->entry))
      hash = t->entries[i].hash;
  if (!hash)
    return BS_FLIGHT_NO_ENTRY;
  if (c->num_blocks < 2 || c->block_bytes < 1024 ||
      c->block_bytes > (1u << 21)) /* Counts are 3-byte LEB128. */
    return BS_FLIGHT_SMALL_BLOCK;
  if (!c->memory || ((uintptr_t)c->memory & 7u) ||
      c->memory_bytes < bs_flight_memory_size(t, c->block_bytes, c->num_blocks))
    return BS_FLIGHT_SMALL_MEMORY;
  uint32_t header = 64 + text_length(c->entry) + text_length(t->target);
  for (uint32_t i = 0; i < t->num_sites; ++i)
    header += 4 + text_length(t->sites[i]->name);
  uint32_t trace = c->info ? c->info->trace.record_size : 0;
  uint32_t key = RECORD_SLACK + t->input_size + t->output_size + trace;
  if (header + key > c->block_bytes - BLOCK_HEADER)
    return BS_FLIGHT_SMALL_BLOCK;

  bs_flight_recorder zero = {0};
  *r = zero;
  r->table = t;
  r->info = c->info && c->info->abi_version == BS_ABI_VERSION ? c->info : 0;
  unsigned char *m = (unsigned char *)c->memory;
  r->input_seen = m;
  m += align8(t->input_size);
  r->output_seen = m;
  m += align8(t->output_size);
  r->output_before = m;
  m += align8(t->output_size);
  r->ring = m;
  r->block_bytes = c->block_bytes;
  r->num_blocks = c->num_blocks;
  r->key_every = c->key_every ? c->key_every : 256;
  r->on_block = c->on_block;
  r->user = c->user;
  r->first_block = 1;
  r->used = NO_BLOCK;
  open_block(r);
  unsigned char *p = cursor(r);
  *p++ = 'H';
  p = put_text(p, hash);
  p = put_text(p, c->entry);
  p = put_text(p, t->target);
  p = put_text(p, t->layout);
  p = put_uleb(p, 0); /* no state in the view */
  p = put_uleb(p, t->input_size);
  p = put_uleb(p, t->output_size);
  p = put_uleb(p, 1); /* one robot */
  p = put_uleb(p, t->num_sites);
  for (uint32_t i = 0; i < t->num_sites; ++i)
    p = put_text(p, t->sites[i]->name);
  p = put_uleb(p, t->assertions ? 1 : 0);
  settle(r, p);
  return BS_FLIGHT_OK;
}

void bs_flight_begin(bs_flight_recorder *r, const void *state) {
  if (!r)
    return;
  const bs_state_header *h = (const bs_state_header *)state;
  const bs_flight_table *t = r->table;
  r->input = (const unsigned char *)h->input;
  r->output = (unsigned char *)h->output;
  r->cycle = h->cycle;
  r->previous = bs_flight_current;
  bs_flight_current = r;
  r->num_calls = 0;
  r->recording = 0;
  /* The record's start and input (and what was lost before it) go into
   * one block: the current one, or the next if it is too full. */
  uint32_t need = 2 * RECORD_SLACK + runs_bound(t->input_size) +
                  runs_bound(t->output_size);
  if (room(r) < need && r->used != NO_BLOCK && r->used)
    hand_over(r);
  if (!open_block(r) || room(r) < need) {
    lose_cycle(r);
    return;
  }
  unsigned char *p = cursor(r);
  if (r->lost) {
    /* Say what was lost before the next cycle that is kept. */
    *p++ = 'G';
    p = put_uleb(p, 0);
    p = put_uleb(p, r->lost_from);
    p = put_uleb(p, r->lost);
    r->lost = 0;
  }
  r->recording = 1;
  r->cycle_at = (uint32_t)(p - r->records);
  int key = r->cycles % r->key_every == 0;
  int trace = r->info && r->info->trace.record_size;
  *p++ = 'C';
  p = put_uleb(p, 0);
  p = put_uleb(p, r->cycle);
  *p++ = (unsigned char)((key ? 1 : 0) | (trace ? 2 : 0));
  /* The input, and the output as the robot's software left it since the
   * cycle before (a robot may build its requests afresh each frame). */
  if (key) {
    p = put_bytes(p, r->input, t->input_size);
    copy_bytes(r->input_seen, r->input, t->input_size);
    p = put_bytes(p, r->output, t->output_size);
    copy_bytes(r->output_seen, r->output, t->output_size);
  } else {
    unsigned char *count = p;
    uint32_t prev = 0, runs = 0;
    p = put_runs(reserve_uleb(p), r->input, r->input_seen, t->input_size, 0,
                 &prev, &runs);
    patch_uleb(count, runs);
    count = p;
    prev = runs = 0;
    p = put_runs(reserve_uleb(p), r->output, r->output_seen, t->output_size,
                 0, &prev, &runs);
    patch_uleb(count, runs);
  }
  /* The number of calls and their bytes' length, filled in at the end. */
  p = reserve_uleb(reserve_uleb(p));
  settle(r, p);
  r->calls_at = r->used;
}

void bs_flight_enter(const bs_flight_site *site) {
  bs_flight_recorder *r = bs_flight_current;
  if (!r || !r->recording || (site->flags & BS_FLIGHT_SITE_STANDARD))
    return;
  /* What the call writes of `output` is told from what it was before. */
  copy_bytes(r->output_before, r->output, r->table->output_size);
}

void bs_flight_leave(const bs_flight_site *site, void *result,
                     void *const *ptrs) {
  bs_flight_recorder *r = bs_flight_current;
  if (!r || !r->recording || (site->flags & BS_FLIGHT_SITE_STANDARD))
    return;
  const bs_flight_table *t = r->table;
  const char *text = 0;
  uint32_t result_bytes = site->result_size;
  if (site->flags & BS_FLIGHT_SITE_STRING) {
    text = result ? *(const char *const *)result : 0;
    result_bytes = text_length(text);
  }
  uint32_t need = 16 + result_bytes + runs_bound(t->input_size) +
                  runs_bound(t->output_size);
  for (uint32_t i = 0; i < site->num_ptrs; ++i)
    need += 4 + site->ptr_sizes[i];
  if (!make_room(r, need))
    return;
  unsigned char *p = cursor(r);
  p = put_uleb(p, site->index << 1 |
                      ((site->flags & BS_FLIGHT_SITE_STRING) ? 1 : 0));
  p = put_uleb(p, result_bytes);
  if (text)
    p = put_bytes(p, text, result_bytes);
  else if (result && result_bytes)
    p = put_bytes(p, result, result_bytes);
  p = put_uleb(p, ptrs ? site->num_ptrs : 0);
  for (uint32_t i = 0; ptrs && i < site->num_ptrs; ++i) {
    p = put_uleb(p, site->ptr_sizes[i]);
    p = put_bytes(p, ptrs[i], site->ptr_sizes[i]);
  }
  /* The runs of the view (input, then output) the call changed. */
  unsigned char *count = p;
  uint32_t prev = 0, runs = 0;
  p = put_runs(reserve_uleb(p), r->input, r->input_seen, t->input_size, 0,
               &prev, &runs);
  p = put_runs(p, r->output, r->output_before, t->output_size, t->input_size,
               &prev, &runs);
  patch_uleb(count, runs);
  settle(r, p);
  ++r->num_calls;
}

void bs_flight_end(bs_flight_recorder *r, const void *state) {
  if (!r)
    return;
  bs_flight_current = (bs_flight_recorder *)r->previous;
  if (!r->recording)
    return; /* Lost. */
  const bs_flight_table *t = r->table;
  uint32_t trace = r->info ? r->info->trace.record_size : 0;
  if (!make_room(r, RECORD_SLACK + runs_bound(t->output_size) + trace))
    return;
  patch_uleb(r->records + r->calls_at - 6, r->num_calls);
  patch_uleb(r->records + r->calls_at - 3, r->used - r->calls_at);
  unsigned char *p = cursor(r);
  if (r->cycles % r->key_every == 0) {
    p = put_bytes(p, r->output, t->output_size);
    copy_bytes(r->output_seen, r->output, t->output_size);
  } else {
    unsigned char *count = p;
    uint32_t prev = 0, runs = 0;
    p = put_runs(reserve_uleb(p), r->output, r->output_seen, t->output_size,
                 0, &prev, &runs);
    patch_uleb(count, runs);
  }
  if (trace) {
    p = put_uleb(p, trace);
    p = put_bytes(p, bs_trace_record(state, r->info), trace);
  }
  settle(r, p);
  r->recording = 0;
  ++r->cycles;
}

void bs_flight_flush(bs_flight_recorder *r) {
  if (r->used != NO_BLOCK && r->used)
    hand_over(r);
}

int bs_flight_pull(bs_flight_recorder *r, const void **bytes,
                   uint32_t *size) {
  uint32_t ready = __atomic_load_n(&r->ready, __ATOMIC_ACQUIRE);
  if (r->on_block || ready == r->pulled)
    return 0;
  unsigned char *slot = slot_of(r, r->pulled % r->num_blocks);
  unsigned char *head = slot + MAGIC_ROOM;
  uint32_t n = (uint32_t)head[0] | (uint32_t)head[1] << 8 |
               (uint32_t)head[2] << 16 | (uint32_t)head[3] << 24;
  int first = r->pulled == 0; /* The log's first block has the magic. */
  *bytes = first ? slot : head;
  *size = BLOCK_HEADER + n + (first ? 8 : 0);
  return 1;
}

void bs_flight_release(bs_flight_recorder *r) {
  uint32_t ready = __atomic_load_n(&r->ready, __ATOMIC_ACQUIRE);
  if (!r->on_block && r->pulled != ready)
    __atomic_store_n(&r->pulled, r->pulled + 1, __ATOMIC_RELEASE);
}

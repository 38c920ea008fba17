/*===- bscript/descriptor.h - the binding descriptor's layout -------------===*
 *
 * The one statement of the binding descriptor format (docs/bindings.md, "The
 * descriptor"), in C so that all three of its users share it:
 *  - bscript/Bind.h writes descriptors as C++ structs; static assertions
 *    there pin every struct field to the offsets below;
 *  - bsc's reader (lib/Bind) reads them out of compiled objects;
 *  - the runtime (lib/Runtime/bscript.c) hashes them in-process, without
 *    libc, to find stale bindings.
 * The module hash is computed by one function, bs_descriptor_hash, for all
 * three.
 *
 * A descriptor is a header, then five tables of records, then a string
 * table; all little-endian, offsets relative to the descriptor's start.
 * Every record starts with its pointer-sized fields ("P": 4 bytes on i386,
 * 8 on x86-64), then 32-bit words. Readers step records by the record
 * sizes stored in the header, so later versions may append words.
 *
 *===----------------------------------------------------------------------===*/
#ifndef BSCRIPT_DESCRIPTOR_H
#define BSCRIPT_DESCRIPTOR_H

#include <stdint.h>

/* The format version a writer stores and a reader accepts up to. */
#define BS_DESCRIPTOR_VERSION 2u
/* "BSMOD\0\0\1": the first eight bytes. */
#define BS_DESCRIPTOR_MAGIC "BSMOD\0\0\1"
#define BS_DESCRIPTOR_HEADER_SIZE 112u
/* A class, enum or member index that names nothing. */
#define BS_NO_INDEX 0xffffffffu

/* Byte offsets of the header's fields (u32 unless noted). */
enum bs_header_field {
  BS_HDR_MAGIC = 0, /* char[8] */
  BS_HDR_VERSION = 8,
  BS_HDR_HEADER_SIZE = 12,
  BS_HDR_PTR_SIZE = 16,
  BS_HDR_NAME = 20,
  BS_HDR_TOTAL_SIZE = 24,
  BS_HDR_FLAGS = 28,
  BS_HDR_INPUT_CLASS = 32,  /* class index or BS_NO_INDEX */
  BS_HDR_OUTPUT_CLASS = 36, /* class index or BS_NO_INDEX */
  /* {count, offset, record size} of each table, in bs_table order. */
  BS_HDR_TABLES = 40,
  BS_HDR_STRING_OFFSET = 100,
  BS_HDR_STRING_SIZE = 104,
  /* Where the module is registered: the offset of BS_PLACE_SIZE bytes after
   * the string table holding `file:line` of BS_MODULE, NUL-terminated (a
   * long path keeps its end); 0 in objects of Bind.h before it was added.
   * The module hash ends with the string table: moving a registration
   * changes nothing bsc checks. */
  BS_HDR_PLACE = 108
};

/* The bytes of the place of registration (BS_HDR_PLACE). */
#define BS_PLACE_SIZE 256u

enum bs_table {
  BS_TABLE_CLASSES,
  BS_TABLE_MEMBERS,
  BS_TABLE_PARAMS,
  BS_TABLE_ENUMS,
  BS_TABLE_VALUES,
  BS_NUM_TABLES
};

/* The header offset of table T's {count, offset, record size}. */
#define BS_HDR_TABLE(T) (BS_HDR_TABLES + 12u * (uint32_t)(T))

/* Each record: its pointer fields (indices), its words (indices), and the
 * counts of both. A record is at least POINTERS * P + 4 * WORDS bytes. */
enum bs_class_field {
  BS_CLASS_KEY = 0,  /* P: &bs::TypeKey<T>::id */
  BS_CLASS_LIFE = 1, /* P: holder of {construct, copy, assign, destroy} */
  BS_CLASS_POINTERS = 2,
  BS_CLASS_NAME = 0,
  BS_CLASS_CPP_NAME = 1,
  BS_CLASS_SIZE = 2,
  BS_CLASS_ALIGN = 3,
  BS_CLASS_FLAGS = 4,
  BS_CLASS_RESERVED = 5,
  BS_CLASS_WORDS = 6
};

enum bs_member_field {
  BS_MEMBER_THUNK = 0,      /* P: holder of the call or getter thunk */
  BS_MEMBER_SETTER = 1,     /* P: holder of the setter thunk, or null */
  BS_MEMBER_MEMPTR = 2,     /* P: fields: holder of the data member pointer */
  BS_MEMBER_RESULT_KEY = 3, /* P: TypeKey of a class or enum result */
  BS_MEMBER_POINTERS = 4,
  BS_MEMBER_KIND = 0,
  BS_MEMBER_OWNER = 1, /* class index, or BS_NO_INDEX for module functions */
  BS_MEMBER_NAME = 2,
  BS_MEMBER_CPP_NAME = 3,
  BS_MEMBER_RESULT_CODE = 4,
  BS_MEMBER_RESULT_FLAGS = 5,
  BS_MEMBER_RESULT_SIZE = 6,
  BS_MEMBER_FLAGS = 7,
  BS_MEMBER_FIRST_PARAM = 8,
  BS_MEMBER_NUM_PARAMS = 9,
  /* Appended for array fields: the extents, outermost first, then zeros.
   * A record that ends before them (an older Bind.h) has no extents. */
  BS_MEMBER_EXTENT = 10,
  BS_MEMBER_MAX_EXTENTS = 4,
  /* Appended in version 2: a constant's value (i32, or the f32 bits). A
   * record that ends before it (version 1) is not a constant. */
  BS_MEMBER_VALUE = 14,
  BS_MEMBER_RESERVED = 15, /* keeps records a multiple of 8 bytes */
  BS_MEMBER_WORDS = 16,
  BS_MEMBER_WORDS_WITHOUT_EXTENTS = 10
};

enum bs_param_field {
  BS_PARAM_KEY = 0, /* P: TypeKey of a class or enum parameter */
  BS_PARAM_POINTERS = 1,
  BS_PARAM_CODE = 0,
  BS_PARAM_FLAGS = 1,
  BS_PARAM_SIZE = 2,
  BS_PARAM_NAME = 3,
  BS_PARAM_DEFAULT_KIND = 4,
  BS_PARAM_DEFAULT_INT = 5,   /* i32 */
  BS_PARAM_DEFAULT_FLOAT = 6, /* f32 */
  BS_PARAM_RESERVED = 7,
  BS_PARAM_WORDS = 8
};

enum bs_enum_field {
  BS_ENUM_KEY = 0, /* P */
  BS_ENUM_POINTERS = 1,
  BS_ENUM_NAME = 0,
  BS_ENUM_CPP_NAME = 1,
  BS_ENUM_SIZE = 2,
  BS_ENUM_FLAGS = 3,
  BS_ENUM_FIRST_VALUE = 4,
  BS_ENUM_NUM_VALUES = 5,
  BS_ENUM_WORDS = 6
};

enum bs_value_field {
  BS_VALUE_POINTERS = 0,
  BS_VALUE_NAME = 0,
  BS_VALUE_VALUE = 1, /* i32 */
  BS_VALUE_WORDS = 2
};

/* The pointer fields that start each table's records, in bs_table order. */
#define BS_TABLE_POINTERS                                                      \
  { BS_CLASS_POINTERS, BS_MEMBER_POINTERS, BS_PARAM_POINTERS,                 \
    BS_ENUM_POINTERS, BS_VALUE_POINTERS }
/* ...and the words after them (the minimum a reader accepts). */
#define BS_TABLE_MIN_WORDS                                                     \
  { BS_CLASS_WORDS, BS_MEMBER_WORDS_WITHOUT_EXTENTS, BS_PARAM_WORDS,          \
    BS_ENUM_WORDS, BS_VALUE_WORDS }

/* The values of the fields. Type codes (member results, parameters): */
enum bs_type_code {
  BS_CODE_VOID = 0, /* results only */
  BS_CODE_BOOL = 1,
  BS_CODE_INT = 2,
  BS_CODE_FLOAT = 3,
  BS_CODE_STRING = 4, /* const char * */
  BS_CODE_ENUM = 5,
  BS_CODE_CLASS = 6,
  /* Parameters only, the first: `bs::Context &`, the running behavior's
   * state (bscript.h's bs_state_header), which generated code passes and
   * the script does not write. */
  BS_CODE_CONTEXT = 7
};
/* Flags of a result or parameter type. */
enum bs_type_flag {
  BS_TYPE_CONST = 1,    /* const-qualified (const T&, or a const field) */
  BS_TYPE_REF = 2,      /* declared as a C++ reference */
  BS_TYPE_UNSIGNED = 4, /* unsigned integer, or enum with unsigned storage */
  BS_TYPE_POINTER = 8   /* travels as a pointer: classes; int&/float&/bool& */
};
enum bs_member_kind {
  BS_KIND_FIELD = 0,
  BS_KIND_PROPERTY = 1,
  BS_KIND_METHOD = 2,
  BS_KIND_FUNCTION = 3,
  /* Version 2: */
  BS_KIND_CONSTRUCTOR = 4, /* owner: the class; result: the class */
  BS_KIND_CONSTANT = 5     /* owner: none; no thunk; the value in VALUE */
};
enum bs_member_flag {
  BS_MEMBER_CONST_SELF = 1, /* does not modify the object */
  BS_MEMBER_READ_ONLY = 2,  /* a field or property without setter */
  BS_MEMBER_RESULT_OUT = 4, /* class result: the thunk's first parameter is `R *out` */
  BS_MEMBER_PURE = 8        /* .pure(): depends on its arguments only, changes nothing */
};
enum bs_class_flag {
  BS_CLASS_TRIVIALLY_COPYABLE = 1,
  BS_CLASS_TRIVIALLY_DESTRUCTIBLE = 2,
  BS_CLASS_DEFAULT_CONSTRUCTIBLE = 4,
  BS_CLASS_COPY_CONSTRUCTIBLE = 8,
  BS_CLASS_COPY_ASSIGNABLE = 16,
  BS_CLASS_STANDARD_LAYOUT = 32,
  BS_CLASS_COPY_AS_BYTES = 64 /* registration opted in: memcpy copies */
};
enum bs_enum_flag { BS_ENUM_SCOPED = 1, BS_ENUM_SIGNED = 2 };
enum bs_default_kind {
  BS_DEFAULT_NONE = 0,
  BS_DEFAULT_INT = 1, /* int, bool and enum defaults */
  BS_DEFAULT_FLOAT = 2
};

static inline uint32_t bs_descriptor_u32(const unsigned char *p) {
  return (uint32_t)p[0] | (uint32_t)p[1] << 8 | (uint32_t)p[2] << 16 |
         (uint32_t)p[3] << 24;
}

/* Whether byte `i` of descriptor `d` lies in a pointer field of a record. */
static inline int bs_descriptor_in_pointer(const unsigned char *d, uint32_t i) {
  static const unsigned char pointers[BS_NUM_TABLES] = BS_TABLE_POINTERS;
  uint32_t ptr_size = bs_descriptor_u32(d + BS_HDR_PTR_SIZE);
  for (unsigned t = 0; t < BS_NUM_TABLES; ++t) {
    const unsigned char *h = d + BS_HDR_TABLE(t);
    uint32_t count = bs_descriptor_u32(h), offset = bs_descriptor_u32(h + 4),
             size = bs_descriptor_u32(h + 8);
    if (size && i >= offset && (i - offset) / size < count)
      return (i - offset) % size < pointers[t] * ptr_size;
  }
  return 0;
}

/* Gives the offset of member `index`'s field (the bytes of the Itanium data
 * member pointer its memptr holder holds) in `*offset` and returns 1; returns
 * 0 for a member without one. */
typedef int (*bs_field_offset_fn)(void *context, uint32_t index,
                                  int64_t *offset);

/* The module hash that bsc records and the runtime checks for staleness:
 * FNV-1a 64 over the descriptor's bytes up to the end of its string table,
 * every pointer field read as zero (they hold addresses), followed by each
 * field's offset as 8 little-endian bytes, in member order. */
static inline uint64_t bs_descriptor_hash(const unsigned char *d,
                                          bs_field_offset_fn field_offset,
                                          void *context) {
  uint64_t hash = 0xcbf29ce484222325ull;
  uint32_t end = bs_descriptor_u32(d + BS_HDR_STRING_OFFSET) +
                 bs_descriptor_u32(d + BS_HDR_STRING_SIZE);
  for (uint32_t i = 0; i < end; ++i) {
    hash ^= bs_descriptor_in_pointer(d, i) ? 0 : d[i];
    hash *= 0x100000001b3ull;
  }
  uint32_t members = bs_descriptor_u32(d + BS_HDR_TABLE(BS_TABLE_MEMBERS));
  for (uint32_t m = 0; m < members; ++m) {
    int64_t offset;
    if (!field_offset(context, m, &offset))
      continue;
    for (unsigned k = 0; k < 8; ++k) {
      hash ^= (unsigned char)((uint64_t)offset >> (8 * k));
      hash *= 0x100000001b3ull;
    }
  }
  return hash;
}

#endif /* BSCRIPT_DESCRIPTOR_H */

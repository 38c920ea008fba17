// A hand-written descriptor (bscript/Bind.h layout, member records with
// the extents appended) of module "BadArray": class Box (8 bytes) with an
// array field `a` of 4 ints, which would reach past the object, and a
// property `p` marked as an array of 2. Bind.h cannot produce either (the
// C++ compiler gives the offset and extents of a real member); they stand
// for a damaged or forged object, which bsc must not trust with indexing.
#ifdef __x86_64__
#define PTR .quad
#define PTR_SIZE 8
#else
#define PTR .long
#define PTR_SIZE 4
#endif
#define CLASS_SIZE (2 * PTR_SIZE + 24)
#define MEMBER_SIZE (4 * PTR_SIZE + 56)
#define MEMBERS (112 + CLASS_SIZE)
#define STRINGS (MEMBERS + 2 * MEMBER_SIZE)

	.section	.data.rel.ro,"aw",@progbits
	.globl	bad_array_key
	.globl	bad_array_offset
	.globl	bad_array_getter
	.p2align	3
bad_array_key:
	PTR	0
bad_array_offset:
	PTR	0
bad_array_getter:
	PTR	bad_array_thunk
	.text
	.globl	bad_array_thunk
bad_array_thunk:
	ret
	.section	bs_modules,"a",@progbits
	.globl	bs_module_BadArray
	.p2align	3
bs_module_BadArray:
	.ascii	"BSMOD\0\0\1"
	// version, header size, pointer size, name, total size, flags, no
	// input, no output class
	.long	1, 112, PTR_SIZE, 1, STRINGS + 20, 0, 0xffffffff, 0xffffffff
	// {count, offset, record size}: classes, members, params, enums, values
	.long	1, 112, CLASS_SIZE
	.long	2, MEMBERS, MEMBER_SIZE
	.long	0, STRINGS, PTR_SIZE + 32
	.long	0, STRINGS, PTR_SIZE + 24
	.long	0, STRINGS, 8
	// string table offset and size, reserved
	.long	STRINGS, 20, 0
	// Class Box: key, no life thunks; name, no C++ name, size 8, align 4,
	// trivially copyable.
	PTR	bad_array_key, 0
	.long	10, 0, 8, 4, 1, 0
	// Field a: no thunks, offset 0, int[4] (16 bytes in an 8-byte Box).
	PTR	0, 0, bad_array_offset, 0
	.long	0, 0, 14, 0, 2, 0, 4, 0, 0, 0
	.long	4, 0, 0, 0
	// Property p: a getter, an int[2] (only fields are arrays).
	PTR	bad_array_getter, 0, 0, 0
	.long	1, 0, 16, 0, 2, 0, 4, 2, 0, 0
	.long	2, 0, 0, 0
	.ascii	"\0BadArray\0Box\0a\0p\0\0\0"

// A hand-written descriptor (bscript/Bind.h layout) of module "Gone" with
// one function `int f()` whose thunk the object does not define: the holder
// refers to the undefined symbol `gone_f_thunk`. C++ cannot produce this (a
// thunk is a template instantiation in the same object); it stands for a
// behavior linked with binding objects that lack a thunk it calls. For
// i386 and x86-64: P fields are pointer-sized, so the member record is
// 4 * 4 + 40 or 4 * 8 + 40 bytes and the string table moves.
#ifdef __x86_64__
#define PTR .quad
#define PTR_SIZE 8
#else
#define PTR .long
#define PTR_SIZE 4
#endif
#define MEMBER_SIZE (4 * PTR_SIZE + 40)
#define STRINGS (112 + MEMBER_SIZE)

	.section	.data.rel.ro,"aw",@progbits
	.globl	gone_f_holder
	.p2align	3
gone_f_holder:
	PTR	gone_f_thunk
	.section	bs_modules,"a",@progbits
	.globl	bs_module_Gone
	.p2align	3
bs_module_Gone:
	.ascii	"BSMOD\0\0\1"
	// version, header size, pointer size, name, total size, flags, no
	// input, no output class
	.long	1, 112, PTR_SIZE, 1, STRINGS + 8, 0, 0xffffffff, 0xffffffff
	// {count, offset, record size}: classes, members, params, enums, values
	.long	0, 112, 2 * PTR_SIZE + 24
	.long	1, 112, MEMBER_SIZE
	.long	0, STRINGS, PTR_SIZE + 32
	.long	0, STRINGS, PTR_SIZE + 24
	.long	0, STRINGS, 8
	// string table offset and size, reserved
	.long	STRINGS, 8, 0
	// The member: thunk holder, no setter, no field, no result key; then
	// kind 3 (function), no owner, name "f", no C++ name, result int (4
	// bytes), no flags, no parameters.
	PTR	gone_f_holder, 0, 0, 0
	.long	3, 0xffffffff, 6, 0, 2, 0, 4, 0, 0, 0
	.ascii	"\0Gone\0f\0"

# The key field uses a PC-relative relocation: bsc accepts only R_386_32.
# A hand-written i386 descriptor (bscript/Bind.h layout, one class "K").
	.data
	.globl	key
key:	.byte	0
	.section	bs_modules,"a",@progbits
	.globl	bs_module_Bad
	.p2align	3
bs_module_Bad:
	.ascii	"BSMOD\0\0\1"
	.long	1, 112, 4, 1, 151, 0, 0xffffffff, 0xffffffff
	.long	1, 112, 32
	.long	0, 144, 56
	.long	0, 144, 36
	.long	0, 144, 28
	.long	0, 144, 8
	.long	144, 7, 0
	.long	key - .
	.long	0
	.long	5, 0, 4, 4, 0, 0
	.ascii	"\0Bad\0K\0"

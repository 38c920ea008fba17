/*===- io.c - the standard native module `io` ----------------------------===*
 *
 * `io::printi/printf/printb/prints` print a value and a newline on stdout.
 * This is the one part of the shim that uses libc (stdio): a robot that has
 * no stdout replaces this file, not the generated code and not
 * io_module.cpp, which registers these functions as the module `io`.
 *===----------------------------------------------------------------------===*/
#include "bscript/bscript.h"
#include <stdio.h>

void bs_io_printi(int32_t value) { printf("%d\n", (int)value); }

/* Every NaN prints as "nan": its sign bit depends on where it was made (the
 * FPU's default NaN is negative, a constant LLVM folded is positive), and
 * the same program must print the same text on every target. */
void bs_io_printf(float value) {
  if (value != value)
    puts("nan");
  else
    printf("%g\n", (double)value);
}

void bs_io_printb(int32_t value) { puts(value ? "true" : "false"); }

void bs_io_prints(const char *value) { puts(value ? value : ""); }

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

void bs_io_printf(float value) { printf("%g\n", (double)value); }

void bs_io_printb(int32_t value) { puts(value ? "true" : "false"); }

void bs_io_prints(const char *value) { puts(value ? value : ""); }

#!/usr/bin/env python3
"""Checks that compiled behaviors are "runtime safe" on every target: no
trap, no `unreachable`, and no call to anything but the runtime shim, the
bindings and the compiler's own support routines (libgcc / compiler-rt
`__`-names, which a target without a divide instruction needs).

    check-runtime-safety.py BSC TRIPLES FILE.bs [--jobs N]

For each triple of the TRIPLES list (one a line, `#` comments), FILE.bs is
compiled to LLVM IR and to an object at -O0 and -O2. A triple bsc refuses
(`bsc: error:`, exit 1: see test/Target/all-triples.test) is skipped. Fails
on:
  - `unreachable`, llvm.trap, llvm.debugtrap or llvm.ubsantrap in the IR;
  - an x86 object whose code has `ud2`;
  - an undefined symbol that is not `bs_*`, a symbol the linker defines
    (ALLOWED) or a `__` support routine, or that is a libc/libm routine
    under any name.
Prints one line per triple and level, and `N checked, M failed`.
"""
import concurrent.futures
import os
import re
import subprocess
import sys
import tempfile

TRAPS = re.compile(r'\bunreachable\b|@llvm\.(trap|debugtrap|ubsantrap)\b')
# Besides the shim and the support routines: symbols the linker defines
# for position-independent code (the GOT on x86, MIPS's _gp_disp, PPC64's
# .TOC.) and MSVC's _fltused, a marker that the object uses floats.
ALLOWED = re.compile(
    r'^(_?bs_|__|(_GLOBAL_OFFSET_TABLE_|_gp_disp|\.TOC\.|_fltused)$)')
# libc and libm under the names compilers call them, also with `__`.
FORBIDDEN = re.compile(
    r'^_*(mem(set|cpy|move|cmp)|str\w+|abort|exit|malloc|free|calloc|'
    r'realloc|printf|puts|(sqrt|floor|ceil|trunc|round|fmod|pow|exp|log|'
    r'sin|cos|tan|fabs)f?(_finite)?)$')


def run(cmd):
    return subprocess.run(cmd, capture_output=True, text=True, timeout=120)


def check(bsc, triple, level, source, tmp):
    name = '%s -O%s' % (triple, level)
    ir = run([bsc, '-target', triple, '-O%s' % level, '--emit=llvm', source,
              '-o', '-'])
    if ir.returncode == 1 and 'bsc: error:' in ir.stderr:
        return name, 'skipped', ''
    if ir.returncode != 0:
        return name, 'FAILED', 'IR: exit %d: %s' % (ir.returncode, ir.stderr)
    for line in ir.stdout.splitlines():
        if not line.startswith(';') and TRAPS.search(line):
            return name, 'FAILED', 'IR has a trap: ' + line.strip()
    obj = os.path.join(tmp, '%s-O%s.o' % (triple, level))
    compiled = run([bsc, '-target', triple, '-O%s' % level, '-c', source,
                    '-o', obj])
    if compiled.returncode != 0:
        # -S-only targets (no object writer) were checked at the IR.
        return name, 'ok', 'ir only'
    nm = run(['llvm-nm-19', '-u', obj])
    for line in nm.stdout.split():
        sym = line.strip()
        if sym in ('U', 'w', 'v') or not sym:
            continue
        if FORBIDDEN.match(sym) or not ALLOWED.match(sym):
            return name, 'FAILED', 'calls ' + sym
    if re.match(r'(i[3-6]86|x86_64)', triple):
        dis = run(['llvm-objdump-19', '-d', obj])
        if re.search(r'\bud2\b', dis.stdout):
            return name, 'FAILED', 'has ud2'
    return name, 'ok', ''


def main(argv):
    args = [a for a in argv[1:] if not a.startswith('--jobs')]
    jobs = 2
    for a in argv[1:]:
        if a.startswith('--jobs='):
            jobs = int(a.split('=', 1)[1])
    if len(args) != 3:
        sys.stderr.write(__doc__)
        return 2
    bsc, triples_file, source = args
    with open(triples_file) as f:
        triples = [l.split('#')[0].strip() for l in f]
    triples = [t for t in triples if t]
    failed = checked = 0
    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ThreadPoolExecutor(jobs) as pool:
        futures = [pool.submit(check, bsc, t, level, source, tmp)
                   for t in triples for level in ('0', '2')]
        for fut in futures:
            name, status, detail = fut.result()
            print(name, status, detail)
            if status == 'skipped':
                continue
            checked += 1
            failed += status == 'FAILED'
    print('%d checked, %d failed' % (checked, failed))
    return 1 if failed else 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))

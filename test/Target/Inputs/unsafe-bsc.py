#!/usr/bin/env python3
"""A stand-in for bsc that produces what runtime-safety.test must catch:
IR with a trap for i586, and for x86_64 an object that calls memset."""
import subprocess
import sys

args = sys.argv[1:]
triple = args[args.index('-target') + 1]
out = args[args.index('-o') + 1]
if '--emit=llvm' in args:
    print('define void @f() {\n  call void @llvm.trap()\n  ret void\n}'
          if triple.startswith('i586') else 'define void @f() {\n  ret void\n}')
    sys.exit(0)
src = out + '.c'
with open(src, 'w') as f:
    f.write('void *memset(void *, int, unsigned long);\n'
            'void bs_f(char *p) { memset(p, 0, 64); }\n')
sys.exit(subprocess.call(['cc', '-c', '-O0', src, '-o', out]))

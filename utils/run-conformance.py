#!/usr/bin/env python3
"""Compiles and runs every program under shared/conformance/.

The conformance folder holds programs others wrote (the paper's figures, and
more over time); the suite runs them unchanged. Every `X.bs` is compiled for
the host and for i586 (for i586 also with -g -O2) with the soccer world
bindings that folder's README describes. A program with an `X.expected`
beside it is also run, in the JIT and as an i586 program, and its output
must equal that file. New programs are picked up without touching the test.

usage: run-conformance.py BSC RUN_I586 CONFORMANCE_DIR HOST_BIND_OBJ I586_BIND_OBJ WORK_DIR
"""
import os
import subprocess
import sys

def run(cmd, **kw):
    return subprocess.run(cmd, capture_output=True, timeout=120, **kw)

def main():
    if len(sys.argv) != 7:
        print(__doc__.strip().splitlines()[-1], file=sys.stderr)
        return 2
    bsc, run_i586, root, host_obj, i586_obj, work = sys.argv[1:7]
    os.makedirs(work, exist_ok=True)
    failures, ran, compiled = [], 0, 0
    programs = sorted(os.path.join(d, f) for d, _, files in os.walk(root)
                      for f in files if f.endswith('.bs'))
    for n, src in enumerate(programs):
        name = os.path.relpath(src, root)
        out = os.path.join(work, f'p{n}')
        steps = [
            ('host -c', [bsc, '-c', '--bind', host_obj, src, '-o', out + '.host.o']),
            ('i586 -c', [bsc, '-target', 'i586', '-c', '--bind', i586_obj, src,
                         '-o', out + '.i586.o']),
            # Debug information for everything a program holds.
            ('i586 -g -O2 -c', [bsc, '-target', 'i586', '-g', '-O2', '-c',
                                '--bind', i586_obj, src, '-o', out + '.g.o']),
        ]
        expected_path = src[:-3] + '.expected'
        expected = open(expected_path, 'rb').read() if os.path.exists(expected_path) else None
        if expected is not None:
            steps += [
                ('bsc run', [bsc, 'run', '--bind', host_obj, src]),
                ('i586 program', [bsc, '-target', 'i586', '--bind', i586_obj, src,
                                  '-o', out + '.i586']),
                ('i586 run', [sys.executable, run_i586, out + '.i586']),
            ]
        ok = True
        for label, cmd in steps:
            p = run(cmd)
            if p.returncode != 0:
                failures.append(f'{name}: {label} exited {p.returncode}: '
                                + p.stderr.decode(errors='replace')[-1500:])
                ok = False
                break
            if label in ('bsc run', 'i586 run') and p.stdout != expected:
                failures.append(f'{name}: {label} output differs from '
                                f'{os.path.basename(expected_path)}')
                ok = False
                break
        if ok:
            if expected is not None:
                ran += 1
            compiled += 1
            print(f'ok {name}' + (' (ran, output matches)' if expected is not None else ' (compiled)'))
    for f in failures:
        print('FAIL', f)
    print(f'{len(programs)} programs: {compiled} compiled for host and i586, '
          f'{ran} ran and matched, {len(failures)} failed')
    return 1 if failures or not programs else 0

if __name__ == '__main__':
    sys.exit(main())

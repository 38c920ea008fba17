#!/usr/bin/env python3
"""Runs bsc over damaged programs and fails on a crash, hang or bad status.

"Bad input gets a clear error, never a crash": for every seed program, this
makes deterministic variants (every prefix at line and token boundaries,
deleted and duplicated lines, re-indented lines, swapped tokens, random
bytes spliced in) and checks that `bsc <args> FILE` exits with 0 or 1 within
a time limit and that any error output is in the `file:line:col: error:`
or `bsc: error:` form. Seeded, so a failure reproduces.

usage: robustness-check.py BSC SEED.bs... [--args ARGS] [--count N]
"""
import argparse
import os
import random
import re
import subprocess
import sys
import tempfile

TOKEN = re.compile(rb'[A-Za-z_][A-Za-z_0-9]*|\d+(?:\.\d+)?|::|[-+*/%<>=!&|]=?|\S')
PIECES = [b'(', b')', b'::', b'yield', b'task', b'func', b'\t', b'    ', b'"',
          b'#', b'\x00', b'\xff', b'1e99', b'0x', b'taskState(', b'\n',
          b'for(;;)', b'if(', b'else', b'return 1', b'9999999999', b'.']

def variants(src, rng, count):
    lines = src.split(b'\n')
    toks = [m.span() for m in TOKEN.finditer(src)]
    # Prefixes: a truncated file must still get diagnostics, not a crash.
    for i in range(len(lines)):
        yield b'\n'.join(lines[:i])
    for _, end in toks[::max(1, len(toks) // 40)]:
        yield src[:end]
    for _ in range(count):
        kind = rng.randrange(6)
        if kind == 0 and lines:  # delete a line
            i = rng.randrange(len(lines))
            yield b'\n'.join(lines[:i] + lines[i + 1:])
        elif kind == 1 and lines:  # duplicate a line
            i = rng.randrange(len(lines))
            yield b'\n'.join(lines[:i] + [lines[i]] + lines[i:])
        elif kind == 2 and lines:  # re-indent a line
            i = rng.randrange(len(lines))
            ls = list(lines)
            ls[i] = b' ' * rng.randrange(12) + ls[i].lstrip()
            yield b'\n'.join(ls)
        elif kind == 3 and len(toks) > 1:  # swap two tokens
            (a0, a1), (b0, b1) = sorted(rng.sample(toks, 2))
            yield src[:a0] + src[b0:b1] + src[a1:b0] + src[a0:a1] + src[b1:]
        elif kind == 4 and toks:  # replace a token by a piece
            a0, a1 = rng.choice(toks)
            yield src[:a0] + rng.choice(PIECES) + src[a1:]
        else:  # splice random bytes
            at = rng.randrange(len(src) + 1)
            junk = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 8)))
            yield src[:at] + junk + src[at:]

DIAG_LINE = re.compile(rb'^(\S.*:\d+:\d+: (error|warning|note): |bsc: (error|fatal): )')

def check(bsc, args, path):
    try:
        p = subprocess.run([bsc] + args + [path], capture_output=True, timeout=20)
    except subprocess.TimeoutExpired:
        return 'timed out'
    if p.returncode not in (0, 1):
        return f'exit status {p.returncode}\n' + p.stderr.decode(errors='replace')[-2000:]
    if p.returncode == 1 and not any(DIAG_LINE.match(l) for l in p.stderr.splitlines()):
        return 'exit status 1 without a diagnostic\n' + p.stderr.decode(errors='replace')[-2000:]
    return None

def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('bsc')
    ap.add_argument('seeds', nargs='+')
    ap.add_argument('--args', default='-fsyntax-only')
    ap.add_argument('--count', type=int, default=150)
    ap.add_argument('--seed', type=int, default=1)
    opts = ap.parse_args()
    rng = random.Random(opts.seed)
    failures = runs = 0
    with tempfile.TemporaryDirectory() as tmp:
        for seed in opts.seeds:
            src = open(seed, 'rb').read()
            name = os.path.basename(seed)
            # The seed's sibling modules come along, so that `requires`
            # resolve and Sema sees the damaged module in context.
            folder = os.path.dirname(os.path.abspath(seed))
            for sibling in os.listdir(folder):
                if sibling.endswith('.bs'):
                    with open(os.path.join(tmp, sibling), 'wb') as f:
                        f.write(open(os.path.join(folder, sibling), 'rb').read())
            for n, text in enumerate(variants(src, rng, opts.count)):
                path = os.path.join(tmp, name)  # keep the module name
                with open(path, 'wb') as f:
                    f.write(text)
                runs += 1
                problem = check(opts.bsc, opts.args.split(), path)
                if problem:
                    failures += 1
                    keep = os.path.join(tmp, '..', f'bsc-robustness-{name}-{n}.bs')
                    with open(keep, 'wb') as f:
                        f.write(text)
                    print(f'FAIL {name} variant {n} (kept as {os.path.abspath(keep)}): {problem}')
    print(f'{runs} variants, {failures} failures')
    return 1 if failures else 0

if __name__ == '__main__':
    sys.exit(main())

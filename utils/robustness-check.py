#!/usr/bin/env python3
"""Runs bsc over damaged programs or recordings and fails on a crash, hang or
bad status.

"Bad input gets a clear error, never a crash". Seeded, so a failure
reproduces.

Programs (the default): for every seed program, this makes deterministic
variants (every prefix at line and token boundaries, deleted and duplicated
lines, re-indented lines, swapped tokens, random bytes spliced in) and
checks that `bsc <args> FILE` exits with 0 or 1 within a time limit and
that any error output is in the `file:line:col: error:` or `bsc: error:`
form.

Recordings (--recordings): the seeds are JSON-lines recordings of `bsc run
--record`, and ARGS has `{}` where the damaged file goes (`run --bind W.o
--replay {} B.bs`). Every variant is damaged beyond doubt (truncated lines,
values of the wrong type, numbers out of every range, NaN and other bare
words, bytes that are never JSON, lines of a megabyte, nesting 100,000
deep), so each must exit 1 with a `VARIANT:line:col: error:` diagnostic;
the undamaged seed must exit 0 (the command does work). With --write DIR
the variants are written there instead, for the fuzz replay driver.

usage: robustness-check.py BSC SEED.bs... [--args ARGS] [--count N]
       robustness-check.py BSC REC.jsonl... --recordings --args ARGS [--count N]
       robustness-check.py - REC.jsonl... --recordings --write DIR [--count N]
"""
import argparse
import concurrent.futures
import json
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

# --- Recordings -----------------------------------------------------------

# Bytes that are never JSON anywhere: control characters other than
# whitespace, and bytes that never occur in UTF-8.
NEVER_JSON = bytes(list(range(0, 9)) + [11, 12] + list(range(14, 32)) +
                   [0xc0, 0xc1] + list(range(0xf5, 0x100)))
# Not numbers, where a number was. (llvm::json reads `.5`, `+1`, `01` and
# `1.` as the numbers they look like, so they are not damage here.)
BARE_WORDS = [b'NaN', b'-NaN', b'nan', b'Infinity', b'-Infinity', b'inf',
              b'0x10', b'1e', b'1e+', b'-', b'--1', b'1.5.5', b'1_000']
# Numbers beyond every float and every int64: wrong for any member.
HUGE = [b'1e39', b'-1e39', b'3.5e38', b'1e300', b'-1e300', b'1e999',
        b'123456789012345678901234567890123456789012']
# A value of another JSON type, by the type of the value it replaces.
WRONG_TYPE = {
    'number': [True, False, 'x', [], {}, [1, 2]],
    'string': [True, False, [], {}, {'a': 1}],
    'bool': [1, 0, 'true', [], {}],
    'object': [1, 'x', True, [], None, 'NaN'],
    'array': [1, 'x', True, {}, [], None],
    'null': [1, True, [], {}],  # null is a string member's null pointer
}
MEGABYTE = 1 << 20
DEEP = 100000
BARE = '\ue000bare\ue000'  # stands for a bare word until the line is text


def json_type(v):
    if isinstance(v, bool):
        return 'bool'
    if isinstance(v, (int, float)):
        return 'number'
    return {str: 'string', dict: 'object', list: 'array',
            type(None): 'null'}[type(v)]


def nodes(v, path=()):
    """Every path below the input and output of a parsed line."""
    items = v.items() if isinstance(v, dict) else \
        enumerate(v) if isinstance(v, list) else ()
    for k, sub in items:
        yield path + (k,), sub
        yield from nodes(sub, path + (k,))


def replaced(v, path, new):
    if not path:
        return new
    v = dict(v) if isinstance(v, dict) else list(v)
    v[path[0]] = replaced(v[path[0]], path[1:], new)
    return v


def dump(v, bare=b''):
    text = json.dumps(v, separators=(',', ':')).encode()
    return text.replace(json.dumps(BARE).encode(), bare)


def damage_value(line, rng, kind):
    """The line with one value under input/output damaged, or None."""
    try:
        top = json.loads(line)
    except ValueError:
        return None
    if not isinstance(top, dict):
        return None
    paths = [(p, v) for k in ('input', 'output') if k in top
             for p, v in nodes(top[k], (k,))]
    if kind == 'wrong-type':
        if not paths:
            return None
        path, v = rng.choice(paths)
        return dump(replaced(top, path, rng.choice(WRONG_TYPE[json_type(v)])))
    if kind == 'unknown-member':
        objs = [(p, v) for p, v in paths if isinstance(v, dict) and v]
        objs += [((k,), top[k]) for k in ('input', 'output')
                 if isinstance(top.get(k), dict) and top[k]]
        if not objs:
            return None
        path, v = rng.choice(objs)
        key = rng.choice(sorted(v))
        renamed = {(k + rng.choice(['_', 'X', ' ']) if k == key else k): sub
                   for k, sub in v.items()}
        return dump(replaced(top, path, renamed))
    numbers = [p for p, v in paths if json_type(v) == 'number']
    if not numbers:
        return None
    path = rng.choice(numbers)
    words = HUGE if kind == 'huge' else BARE_WORDS
    return dump(replaced(top, path, BARE), rng.choice(words))


def damage_line(line, rng, kind):
    """The damaged text of one line of a recording (without its newline)."""
    if kind == 'garbage':
        at = rng.randrange(len(line) + 1)
        junk = bytes(rng.choice(NEVER_JSON) for _ in range(rng.randrange(1, 9)))
        return line[:at] + junk + line[at:]
    if kind == 'not-an-object':
        return rng.choice([b'[]', b'1', b'"input"', b'null', b'true', b'[' + line + b']'])
    if kind == 'unknown-key':
        return rng.choice([b'{"inputs":{}}', b'{"Input":{}}', b'{"":1}',
                           line[:-1] + b',"cycles":1}'])
    if kind == 'long-line':
        return rng.choice([
            b' ' * MEGABYTE + b'x',
            line[:-1] + b',"' + b'k' * MEGABYTE + b'":1}',
            b'{"input":{"' + b'k' * MEGABYTE + b'":1}}',
            line[:-1] + b' ' * MEGABYTE + b'x}',
            b'{"input":{"time":' + b'9' * MEGABYTE + b'}}',
        ])
    if kind == 'deep':
        return rng.choice([
            b'[' * DEEP,
            b'{"a":' * DEEP,
            b'[{"a":' * DEEP,
            b'{"input":' + b'[' * DEEP,
            # Valid JSON, closed, but nested past bsc's limit.
            b'{"input":{"time":' + b'[' * 300 + b'1' + b']' * 300 + b'}}',
            b'{"input":' + b'{"a":' * 300 + b'1' + b'}' * 301,
            # Brackets in a string are not nesting; the key is still unknown.
            b'{"' + b'[' * DEEP + b'":1}',
            b'{"input":{"\\"' + b'{' * DEEP + b'":1}}',
        ])
    if kind == 'truncate':
        return line[:rng.randrange(1, len(line))]
    return damage_value(line, rng, kind)


RECORDING_KINDS = ['truncate', 'wrong-type', 'unknown-member', 'huge', 'nan',
                   'garbage', 'not-an-object', 'unknown-key', 'long-line',
                   'deep']


def recording_variants(src, rng, count):
    """(kind, text) pairs, `count` of them, each certainly not replayable."""
    lines = [l for l in src.split(b'\n') if l.strip()]
    made = 0
    while made < count:
        kind = RECORDING_KINDS[made % len(RECORDING_KINDS)]
        i = rng.randrange(len(lines))
        bad = damage_line(lines[i], rng, kind)
        if bad is None:
            continue
        # A truncated file ends in the cut line; other damage keeps the rest.
        rest = [] if kind == 'truncate' else lines[i + 1:]
        yield kind, b'\n'.join(lines[:i] + [bad] + rest) + b'\n'
        made += 1


def check_recording(bsc, args, path, timeout):
    """None if `bsc ARGS` refused the damaged recording at `path` cleanly."""
    cmd = [bsc] + [path if a == '{}' else a for a in args]
    try:
        p = subprocess.run(cmd, capture_output=True, timeout=timeout)
    except subprocess.TimeoutExpired:
        return 'timed out'
    err = p.stderr.decode(errors='replace')
    tail = err[-2000:]
    if p.returncode != 1:
        return f'exit status {p.returncode}\n{tail}'
    if 'LLVM ERROR' in err or 'PLEASE submit' in err:
        return f'an internal error\n{tail}'
    here = re.compile(re.escape(path) + r':\d+:\d+: error: ')
    if not any(here.match(l) for l in err.splitlines()):
        return f'no `{path}:line:col: error:` diagnostic\n{tail}'
    return None


def recordings_main(opts):
    rng = random.Random(opts.seed)
    args = opts.args.split()
    if not opts.write and '{}' not in args:
        print('--recordings needs {} in --args, or --write', file=sys.stderr)
        return 2
    all_variants = []
    for seed in opts.seeds:
        src = open(seed, 'rb').read()
        name = os.path.splitext(os.path.basename(seed))[0]
        for n, (kind, text) in enumerate(recording_variants(src, rng, opts.count)):
            all_variants.append((seed, f'{name}-{n}-{kind}.jsonl', kind, text))
    if opts.write:
        os.makedirs(opts.write, exist_ok=True)
        for _, file, _, text in all_variants:
            with open(os.path.join(opts.write, file), 'wb') as f:
                f.write(text)
        print(f'{len(all_variants)} variants written')
        return 0
    for seed in opts.seeds:
        # The positive control: the command replays the undamaged seed.
        p = subprocess.run([opts.bsc] + [seed if a == '{}' else a for a in args],
                           capture_output=True, timeout=opts.timeout)
        if p.returncode != 0:
            print(f'FAIL: the undamaged {seed}: exit status {p.returncode}\n'
                  + p.stderr.decode(errors='replace')[-2000:])
            return 1
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        def run(variant):
            _, file, _, text = variant
            path = os.path.join(tmp, file)
            with open(path, 'wb') as f:
                f.write(text)
            return check_recording(opts.bsc, args, path, opts.timeout)
        with concurrent.futures.ThreadPoolExecutor(opts.jobs) as pool:
            for (seed, file, kind, text), problem in zip(
                    all_variants, pool.map(run, all_variants)):
                if problem:
                    failures += 1
                    os.makedirs(opts.keep, exist_ok=True)
                    keep = os.path.join(opts.keep, f'bsc-robustness-{file}')
                    with open(keep, 'wb') as f:
                        f.write(text)
                    print(f'FAIL {kind} variant of {seed} (kept as {keep}): {problem}')
    print(f'{len(all_variants)} damaged recordings, {failures} failures')
    return 1 if failures else 0


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument('bsc')
    ap.add_argument('seeds', nargs='+')
    ap.add_argument('--args', default='-fsyntax-only')
    ap.add_argument('--count', type=int, default=150)
    ap.add_argument('--seed', type=int, default=1)
    ap.add_argument('--recordings', action='store_true',
                    help='the seeds are JSON-lines recordings; {} in ARGS is the variant')
    ap.add_argument('--write', metavar='DIR',
                    help='with --recordings: write the variants to DIR, run nothing')
    ap.add_argument('--keep', metavar='DIR', default=tempfile.gettempdir(),
                    help='with --recordings: where failing variants are kept')
    ap.add_argument('--jobs', type=int, default=2)
    ap.add_argument('--timeout', type=float, default=20)
    opts = ap.parse_args()
    if opts.recordings:
        return recordings_main(opts)
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

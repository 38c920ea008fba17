"""Runs bsc on generated inputs and fails unless every run exits with 0 or
1 (a crash, an assertion or a signal gives something else) within a time
limit. `not` cannot tell a crash from a diagnosed error, hence this script.

usage: survive.py BSC WORKDIR MODE [SOURCE]
"""
import os
import random
import subprocess
import sys
import time

bsc, workdir, mode = sys.argv[1:4]
os.makedirs(workdir, exist_ok=True)


def run(data, args=("--emit=ast",), name="m.bs", limit=60.0, want=(0, 1)):
    path = os.path.join(workdir, name)
    with open(path, "wb") as f:
        f.write(data)
    start = time.time()
    proc = subprocess.run([bsc, *args, path], stdout=subprocess.DEVNULL,
                          stderr=subprocess.PIPE, timeout=limit)
    took = time.time() - start
    if proc.returncode not in want or took > limit:
        sys.stderr.buffer.write(proc.stderr[-2000:])
        sys.exit("bsc %s on %r (%d bytes): exit %d after %.1fs" %
                 (" ".join(args), data[:60], len(data), proc.returncode, took))
    return proc


modes = ("--emit=tokens",), ("--emit=ast",), ("-fsyntax-only",)
rng = random.Random(1234)
if mode == "random":
    for i in range(30):
        data = bytes(rng.randrange(256) for _ in range(rng.randrange(1, 4000)))
        run(data, modes[i % 3])
    # Random text made of b-script's own characters is nastier than noise.
    alphabet = b"task func if else for yield ()(),.:;+-*/%!<>=&|\"\\#\n\n    \t0x9e.ab"
    for i in range(60):
        data = bytes(rng.choice(alphabet) for _ in range(rng.randrange(1, 3000)))
        run(data, modes[i % 3])
elif mode == "bytes":
    tests = [b"\0", b"task t()\n    a(\0)\n", b"\0\0\0\n\0", b"\xc3\xa9\n",
             b"task t()\n    io::prints(\"\xff\xfe\0\")\n",
             b"# \xff\xfe\xc3\n", b"task t(\xe2\x82\xac)\n", b"\xef\xbb\xbftask t()\n",
             b"task t()\n\x0b\x0c    yield\n", b"\r\n\r\n task t()\r\n    yield\r\n"]
    for data in tests:
        for args in modes:
            run(data, args)
elif mode == "prefixes":
    source = open(sys.argv[4], "rb").read()
    # Each prefix in a folder of its own, several at a time.
    from concurrent.futures import ThreadPoolExecutor
    def one(n):
        run(source[:n], ("--emit=ast",), name="p%d/Behavior.bs" % n)
    for n in range(len(source) + 1):
        os.makedirs(os.path.join(workdir, "p%d" % n), exist_ok=True)
    with ThreadPoolExecutor(max_workers=os.cpu_count() or 4) as pool:
        list(pool.map(one, range(len(source) + 1)))
elif mode == "big":
    # About 10 MB of valid code must parse quickly (linear time).
    body = b"".join(b"    int v%d = (v + %d) * 3 %% 7 - io::f(a.b.c(%d), 2.5)\n"
                    % (i, i, i) for i in range(40))
    parts, size, i = [], 0, 0
    while size < 10 * 1024 * 1024:
        chunk = b"task t%d(int v, Math::Vector2f a)\n%s    for(; v < 3; yield)\n        v += 1\n" % (i, body)
        parts.append(chunk)
        size += len(chunk)
        i += 1
    # The limits leave room for a Debug build on a busy machine; a release
    # build parses this in about a second.
    run(b"".join(parts), ("--emit=ast",), limit=60.0, want=(0,))
    # And 10 MB of garbage and of unclosed brackets and blank lines.
    run(bytes(rng.randrange(256) for _ in range(10 * 1024 * 1024)), limit=30.0)
    run(b"task t()\n    a(" + b"\n" * (10 * 1024 * 1024), limit=30.0)
    run(b"task t()\n    x = " + b"-" * (1024 * 1024) + b"1\n", limit=30.0)
    run(b"task t()\n    x = a" + b".b" * (512 * 1024) + b"\n", limit=30.0)
else:
    sys.exit("unknown mode " + mode)

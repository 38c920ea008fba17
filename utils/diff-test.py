#!/usr/bin/env python3
"""Differential testing: random programs through six configurations of bsc.

usage: diff-test.py [--bsc PATH] [--bind-objs DIR] [--seeds A:B]
                    [--cycles N] [--jobs J] [--keep DIR] [--timeout S]
                    [--campaign [--minutes M]]

For each seed in A:B (A inclusive, B exclusive, as Python's range),
utils/gen-program.py makes a well-typed program, and this script runs it

  jit-O0   bsc run -O0 --cycles N P.bs
  jit-O2   bsc run -O2 --coverage F --cycles N P.bs
  host-O0  bsc -O0 --cycles N P.bs -o prog; prog
  host-O2  bsc -O2 --cycles N P.bs -o prog; prog
  i586-O0  bsc -target i586 -O0 --cycles N P.bs -o prog; utils/run-i586 prog
  i586-O2  bsc -target i586 -O2 --cycles N P.bs -o prog; utils/run-i586 prog

and, for every third seed, the boundary to registered C++ (docs/repl.md,
"Going back in time" and "Recordings"; the generator's Gen::tick, rnd and
poke have effects):

  jit-record  bsc run -O0 --cycles N --record R.jsonl P.bs
  jit-replay  bsc run -O2 --replay R.jsonl P.bs    (exactly: calls from R)
  jit-travel  bsc repl: :run N, :goto 1, :goto N, :back 1 (every re-run
              cycle is checked against the live one; no "parted from its
              record" may appear)
  i586-flight bsc -target i586 -O2 --flight-recorder --cycles N P.bs -o prog;
              BS_FLIGHT_LOG=L prog; bsc run -O0 --replay L P.bs (the
              robot's flight log replayed exactly: docs/repl.md "The
              robot's log")

each with `--bind DIR/GenWorld.<host|i586>.o` (the world module `Gen` of
utils/GenWorld.cpp, which test/CMakeLists.txt builds into
build/test/bind-objects, the default DIR beside the default bsc), and one
seed in four with `--cycle-budget=K` (K of 1, 2, 3, 5 or 8 passes, by the
seed), so that budgets run out mid-cycle in all six alike; it compares
their standard output and exit status. The language defines
every result (docs/language.md: division by zero, saturating int(float),
IEEE singles on every target), so all six must agree. A failure is a
mismatch, a compile error (the generator promises well-typed programs), a
crash (exit by signal, "LLVM ERROR", an assertion), a run that takes longer
than --timeout seconds, or a program that reports "SELF-CHECK FAILED" (a
module constant that differs from its expression computed at run time). For each, the seed, the configurations and a diff
against jit-O0 are printed and the program and its outputs are kept in
--keep DIR/seed-S/. The last line is `N seeds, 6 configurations, M failures`
and the exit status is 1 if M > 0.

--campaign is the long-running mode: seeds from A on (B may be left out:
`--seeds 5000:`), a progress line every --progress seconds, until B or
--minutes have passed; failures are kept and counted, never stop it.
"""
import argparse
import concurrent.futures
import difflib
import importlib.util
import os
import shutil
import subprocess
import sys
import tempfile
import threading
import time

HERE = os.path.dirname(os.path.abspath(__file__))
CONFIGS = ["jit-O0", "jit-O2", "host-O0", "host-O2", "i586-O0", "i586-O2"]
BOUNDARY_CONFIGS = ["jit-record", "jit-replay", "i586-flight"]


def load_generator():
    spec = importlib.util.spec_from_file_location(
        "gen_program", os.path.join(HERE, "gen-program.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


GEN = load_generator()


def run(cmd, timeout, env=None):
    """(status, stdout, stderr); status is 'timeout' on a timeout. `env`:
    variables added to the environment."""
    try:
        p = subprocess.run(cmd, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=timeout,
                           env=dict(os.environ, **env) if env else None)
        return p.returncode, p.stdout, p.stderr
    except subprocess.TimeoutExpired as e:
        return "timeout", e.stdout or b"", e.stderr or b""


def crashed(status, err):
    return (status == "timeout" or (isinstance(status, int) and status < 0)
            or b"LLVM ERROR" in err or b"Assertion" in err
            or b"Stack dump" in err or b"Segmentation fault" in err)


def budget_option(seed):
    """`--cycle-budget` for one seed in four: small enough to run out."""
    if seed % 4 != 1:
        return []
    # The generator's counted loops take 1 to 4 passes and its cycle loops
    # none (they yield on every way round), so a few passes run out.
    return ["--cycle-budget=" + str([1, 2, 3, 5, 8][(seed // 4) % 5])]


def bind_host(args):
    return ["--bind", os.path.join(args.bind_objs, "GenWorld.host.o")]


def check_travel(args, d, src, bind):
    """jit-travel: runs the cycles live in the REPL (which has no cycle
    budget), then goes back and forth; the REPL compares every re-run cycle
    with the live one."""
    session = os.path.join(d, "travel.txt")
    n = args.cycles
    with open(session, "w") as f:
        f.write(f":run {n}\n:goto 1\n:goto {n}\n:back 1\n:goto {max(1, n // 2)}\n")
    st, out, err = run([args.bsc, "repl", "--batch", session] + bind + [src],
                       args.timeout)
    text = (out + err).decode(errors="replace")
    if crashed(st, err) or "parted from its record" in text or "internal error" in text:
        return ["jit-travel: a re-run differs from the live run or failed:\n" + text[-2000:]]
    return []


def check_seed(seed, args, workdir):
    """Runs one seed; returns (seed, problems, outputs, program)."""
    prog = GEN.Gen(seed).program()
    d = os.path.join(workdir, f"seed-{seed}")
    os.makedirs(d, exist_ok=True)
    src = os.path.join(d, "prog.bs")
    with open(src, "w") as f:
        f.write(prog)
    cyc = ["--cycles", str(args.cycles)] + budget_option(seed)
    outputs = {}
    problems = []
    record = os.path.join(d, "run.jsonl")
    boundary = seed % 3 == 0
    for cfg in CONFIGS + (BOUNDARY_CONFIGS if boundary else []):
        kind, opt = cfg.split("-")
        bind = ["--bind", os.path.join(args.bind_objs,
                                       "GenWorld.i586.o" if kind == "i586" else "GenWorld.host.o")]
        if cfg == "jit-record":
            st, out, err = run([args.bsc, "run", "-O0"] + cyc + bind + ["--record", record, src],
                               args.timeout)
        elif cfg == "jit-replay":
            if not os.path.exists(record):  # The live run broke off.
                continue
            st, out, err = run([args.bsc, "run", "-O2", "--replay", record] + budget_option(seed)
                               + bind + [src], args.timeout)
        elif cfg == "i586-flight":
            exe, log = os.path.join(d, cfg), os.path.join(d, "flight.bslog")
            st, out, err = run([args.bsc, "-target", "i586", "-O2", "--flight-recorder"] + cyc
                               + bind + [src, "-o", exe], args.timeout)
            if st == 0:
                st, out, err = run([sys.executable, os.path.join(HERE, "run-i586"), exe],
                                   args.timeout, {"BS_FLIGHT_LOG": log})
            if st == 0 and os.path.exists(log):
                host = ["--bind", os.path.join(args.bind_objs, "GenWorld.host.o")]
                st, out, err = run([args.bsc, "run", "-O0", "--replay", log]
                                   + budget_option(seed) + host + [src], args.timeout)
            elif st == 0:
                problems.append(f"{cfg}: the program wrote no flight log")
        elif kind == "jit":
            # The optimised JIT also counts coverage, which must change
            # nothing the program prints.
            cov = ["--coverage", os.path.join(d, "coverage.info")] if opt == "O2" else []
            st, out, err = run([args.bsc, "run", "-" + opt] + cyc + bind + cov + [src],
                               args.timeout)
        else:
            exe = os.path.join(d, cfg)
            target = ["-target", "i586"] if kind == "i586" else []
            st, out, err = run([args.bsc] + target + ["-" + opt] + cyc + bind + [src, "-o", exe],
                               args.timeout)
            if st == 0:
                runner = ([sys.executable, os.path.join(HERE, "run-i586")]
                          if kind == "i586" else [])
                st, out, err = run(runner + [exe], args.timeout)
            elif not crashed(st, err):
                problems.append(f"{cfg}: does not compile:\n"
                                + err.decode(errors="replace")[:2000])
        if crashed(st, err):
            problems.append(f"{cfg}: " + ("timeout" if st == "timeout" else f"status {st}")
                            + "\n" + err.decode(errors="replace")[-2000:])
        if b"SELF-CHECK FAILED" in out:
            problems.append(f"{cfg}: a constant differs from its expression at run time:\n"
                            + "\n".join(l.decode(errors="replace") for l in out.splitlines()
                                         if b"SELF-CHECK FAILED" in l)[:2000])
        outputs[cfg] = (st, out, err)
    if boundary:
        problems += check_travel(args, d, src, bind_host(args))
    ref_st, ref_out, _ = outputs[CONFIGS[0]]
    for cfg in [c for c in CONFIGS + BOUNDARY_CONFIGS if c in outputs][1:]:
        st, out, _ = outputs[cfg]
        if (st, out) != (ref_st, ref_out):
            diff = difflib.unified_diff(
                ref_out.decode(errors="replace").splitlines(),
                out.decode(errors="replace").splitlines(),
                CONFIGS[0], cfg, lineterm="", n=2)
            lines = list(diff)
            text = "\n".join(lines[:40]) + ("\n..." if len(lines) > 40 else "")
            a, b = ref_out.splitlines(), out.splitlines()
            at = next((i for i, (x, y) in enumerate(zip(a, b)) if x != y), min(len(a), len(b)))
            first = (f"first difference at line {at + 1}: "
                     f"{a[at] if at < len(a) else b'<end>'!r} and "
                     f"{b[at] if at < len(b) else b'<end>'!r}")
            problems.append(f"{CONFIGS[0]} (status {ref_st}) and {cfg} (status {st}) differ, "
                            + first + "\n" + text)
    return seed, problems, outputs, prog


def keep(seed, outputs, prog, problems, keepdir):
    d = os.path.join(keepdir, f"seed-{seed}")
    os.makedirs(d, exist_ok=True)
    with open(os.path.join(d, "prog.bs"), "w") as f:
        f.write(prog)
    for cfg, (st, out, err) in outputs.items():
        with open(os.path.join(d, cfg + ".out"), "wb") as f:
            f.write(out)
        with open(os.path.join(d, cfg + ".err"), "wb") as f:
            f.write(err + f"\n[status {st}]\n".encode())
    with open(os.path.join(d, "problems.txt"), "w") as f:
        f.write("\n\n".join(problems) + "\n")
    return d


def parse_seeds(text, campaign):
    a, sep, b = text.partition(":")
    if not sep:
        return int(a), int(a) + 1
    start = int(a) if a else 0
    if b:
        return start, int(b)
    if not campaign:
        raise SystemExit("diff-test.py: --seeds A:B needs B outside --campaign")
    return start, None


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bsc", default=os.path.join(HERE, "..", "build", "bin", "bsc"))
    ap.add_argument("--bind-objs", help="the folder of GenWorld.host.o and GenWorld.i586.o "
                    "(default: test/bind-objects in bsc's build folder)")
    ap.add_argument("--seeds", default="0:100", help="A:B, A inclusive, B exclusive")
    ap.add_argument("--cycles", type=int, default=8)
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 1)
    ap.add_argument("--keep", default="diff-test-failures",
                    help="folder for the programs that fail")
    ap.add_argument("--timeout", type=float, default=20.0, help="seconds per compile or run")
    ap.add_argument("--campaign", action="store_true", help="long-running mode")
    ap.add_argument("--minutes", type=float, help="campaign: stop after this long")
    ap.add_argument("--progress", type=float, default=30.0,
                    help="campaign: seconds between progress lines")
    ap.add_argument("-v", "--verbose", action="store_true", help="a line per seed")
    args = ap.parse_args()
    args.bsc = os.path.abspath(args.bsc)
    if not os.access(args.bsc, os.X_OK):
        sys.stderr.write(f"diff-test.py: no bsc at {args.bsc}\n")
        return 2
    if not args.bind_objs:
        args.bind_objs = os.path.join(os.path.dirname(os.path.realpath(args.bsc)), "..",
                                      "test", "bind-objects")
    for obj in ("GenWorld.host.o", "GenWorld.i586.o"):
        if not os.path.isfile(os.path.join(args.bind_objs, obj)):
            sys.stderr.write(f"diff-test.py: no {obj} in {args.bind_objs} "
                             "(build the lit tests' binding objects, or give --bind-objs)\n")
            return 2
    start, stop = parse_seeds(args.seeds, args.campaign)
    deadline = time.time() + args.minutes * 60 if args.minutes else None

    def seeds():
        s = start
        while (stop is None or s < stop) and (deadline is None or time.time() < deadline):
            yield s
            s += 1

    began = time.time()
    done = 0
    failures = []
    lock = threading.Lock()
    last_report = [began]
    workdir = tempfile.mkdtemp(prefix="bsc-diff-")
    try:
        with concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
            pending = set()
            it = seeds()
            exhausted = False
            while pending or not exhausted:
                while not exhausted and len(pending) < 2 * args.jobs:
                    s = next(it, None)
                    if s is None:
                        exhausted = True
                    else:
                        pending.add(pool.submit(check_seed, s, args, workdir))
                finished, pending = concurrent.futures.wait(
                    pending, return_when=concurrent.futures.FIRST_COMPLETED)
                for fut in finished:
                    seed, problems, outputs, prog = fut.result()
                    shutil.rmtree(os.path.join(workdir, f"seed-{seed}"), ignore_errors=True)
                    with lock:
                        done += 1
                        if problems:
                            failures.append(seed)
                            kept = keep(seed, outputs, prog, problems, args.keep)
                            print(f"FAIL seed {seed} (kept in {kept}):")
                            for p in problems:
                                print("  " + p.replace("\n", "\n  "))
                        elif args.verbose:
                            print(f"ok seed {seed}")
                        now = time.time()
                        if args.campaign and now - last_report[0] >= args.progress:
                            last_report[0] = now
                            print(f"progress: {done} seeds, {len(failures)} failures, "
                                  f"{now - began:.0f} s, {done / (now - began):.2f} seeds/s",
                                  flush=True)
                        sys.stdout.flush()
    except KeyboardInterrupt:
        print("interrupted")
    finally:
        shutil.rmtree(workdir, ignore_errors=True)
    elapsed = time.time() - began
    if failures:
        print("failing seeds: " + " ".join(str(s) for s in sorted(failures)))
    if args.campaign:
        print(f"campaign: seeds {start} to {start + done - 1}, {elapsed:.0f} s")
    print(f"{done} seeds, {len(CONFIGS)} configurations, {len(failures)} failures")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main())

#!/usr/bin/env python3
"""Compiles one behavior for every triple of a list, with -c, -S and
--emit=llvm, and checks that bsc never crashes on a target.

usage: check-targets.py BSC TRIPLES INPUT [--jobs N] [-O LEVEL] [-g]

For each triple and mode, bsc must either succeed and write a non-empty
output (an object file in a format LLVM writes, for ELF with the machine of
the triple's architecture) or exit with status 1, print `bsc: error:` (or
`file:line:col: error:`) and
leave no output behind. A signal, another status, LLVM's "LLVM ERROR" or
"PLEASE submit a bug report", or an internal error fails the check.

Prints one line per triple and mode ("TRIPLE MODE ok FORMAT" or
"TRIPLE MODE error: MESSAGE"), in the order of the list, then a summary;
exits 1 if any check failed.
"""
import argparse
import concurrent.futures
import os
import re
import struct
import subprocess
import sys
import tempfile

MODES = ["-c", "-S", "--emit=llvm"]

# ELF e_machine of each architecture prefix (longest prefix wins).
ELF_MACHINES = {
    "i386": 3, "i486": 3, "i586": 3, "i686": 3, "x86_64": 62,
    "aarch64": 183, "arm64": 183, "arm": 40, "thumb": 40,
    "avr": 83, "bpf": 247, "hexagon": 164, "lanai": 244,
    "loongarch": 258, "m68k": 4, "mips": 8, "msp430": 105,
    "powerpc64": 21, "powerpc": 20, "riscv": 243, "sparcv9": 43,
    "sparc64": 43, "sparcel": 2, "sparc": 2, "s390x": 22, "ve": 251,
    "xtensa": 94,
}

# A diagnostic: `bsc: error:`, or `file:line:col: error:` (an input that
# requires a module the target has no runtime for, say).
ERROR = re.compile(r"^(bsc|\S+:\d+:\d+): error: ")

BAD_TEXT = ["LLVM ERROR", "PLEASE submit a bug report", "Stack dump",
            "internal error"]


def object_format(data):
    """The format of an object file, from its magic number."""
    if data[:4] == b"\x7fELF":
        return "elf"
    if data[:4] in (b"\xfe\xed\xfa\xce", b"\xce\xfa\xed\xfe",
                    b"\xfe\xed\xfa\xcf", b"\xcf\xfa\xed\xfe"):
        return "macho"
    if data[:4] == b"\0asm":
        return "wasm"
    if data[:2] in (b"\x01\xdf", b"\x01\xf7"):
        return "xcoff"
    if data[:1] == b"\x03":
        return "goff"
    # COFF: a machine field LLVM writes for x86, ARM and AArch64.
    if data[:2] in (b"\x4c\x01", b"\x64\x86", b"\xc4\x01", b"\x64\xaa"):
        return "coff"
    return None


def elf_machine(data):
    endian = "<" if data[5] == 1 else ">"
    return struct.unpack(endian + "H", data[18:20])[0]


def expected_machine(triple):
    arch = triple.split("-")[0]
    best = None
    for prefix in ELF_MACHINES:
        if arch.startswith(prefix) and len(prefix) > len(best or ""):
            best = prefix
    return ELF_MACHINES.get(best)


def check(bsc, triple, mode, inp, opt, debug, tmp):
    out = os.path.join(tmp, triple + mode.replace("=", "_"))
    flags = ["-g"] if debug else []
    p = subprocess.run([bsc, "-target", triple, "-O" + opt, *flags, mode, inp,
                        "-o", out], capture_output=True, text=True)
    err = p.stderr
    problems = []
    if p.returncode not in (0, 1):
        problems.append(f"exit status {p.returncode}")
    for text in BAD_TEXT:
        if text in err:
            problems.append(f"printed '{text}'")
    if p.returncode == 1:
        first = next((l for l in err.splitlines() if ERROR.match(l)), None)
        if first is None:
            problems.append("exit status 1 without 'bsc: error:'")
        if os.path.exists(out):
            problems.append("left an output behind")
        result = "error: " + (ERROR.sub("", first) if first else "")
    elif p.returncode == 0:
        data = open(out, "rb").read() if os.path.exists(out) else b""
        result = "ok"
        if not data:
            problems.append("no output")
        elif mode == "-c":
            fmt = object_format(data)
            if fmt is None:
                problems.append("object file of unknown format")
            else:
                result = "ok " + fmt
            want = expected_machine(triple)
            if fmt == "elf" and want is not None and elf_machine(data) != want:
                problems.append(f"ELF machine {elf_machine(data)}, "
                                f"expected {want}")
    else:
        result = "crash"
    return triple, mode, result, problems, err


def main():
    ap = argparse.ArgumentParser()
    ap.add_argument("bsc")
    ap.add_argument("triples")
    ap.add_argument("input")
    ap.add_argument("--jobs", type=int, default=os.cpu_count() or 2)
    ap.add_argument("-O", dest="opt", default="0")
    ap.add_argument("-g", dest="debug", action="store_true",
                    help="with debug information")
    args = ap.parse_args()
    triples = []
    for line in open(args.triples):
        line = line.split("#")[0].strip()
        if line:
            triples.append(line)
    jobs = [(t, m) for t in triples for m in MODES]
    failed = 0
    counts = {"ok": 0, "error": 0}
    with tempfile.TemporaryDirectory() as tmp, \
            concurrent.futures.ThreadPoolExecutor(args.jobs) as pool:
        futures = [pool.submit(check, args.bsc, t, m, args.input, args.opt,
                               args.debug, tmp)
                   for t, m in jobs]
        for f in futures:
            triple, mode, result, problems, err = f.result()
            counts["ok" if result.startswith("ok") else "error"] += 1
            print(f"{triple} {mode} {result}")
            if problems:
                failed += 1
                print(f"FAIL: {triple} {mode}: {'; '.join(problems)}")
                for line in err.splitlines()[:8]:
                    print(f"  | {line}")
    print(f"{len(triples)} triples, {len(jobs)} compilations: "
          f"{counts['ok']} succeeded, {counts['error']} refused with a "
          f"diagnostic, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

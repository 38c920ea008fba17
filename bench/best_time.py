#!/usr/bin/env python3
"""The best wall time of N runs of a command (stdout discarded), printed in
seconds: the benchmarks' timer, since the machines are shared and noisy.

    best_time.py N COMMAND [ARGS...]
"""
import subprocess
import sys
import time


def main(argv):
    if len(argv) < 3 or not argv[1].isdigit():
        sys.stderr.write(__doc__)
        return 2
    best = None
    for _ in range(int(argv[1])):
        start = time.perf_counter()
        subprocess.run(argv[2:], stdout=subprocess.DEVNULL, check=True)
        elapsed = time.perf_counter() - start
        best = elapsed if best is None else min(best, elapsed)
    print("%.4f" % best)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))

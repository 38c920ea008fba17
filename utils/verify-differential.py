#!/usr/bin/env python3
"""`bsc verify` on random programs (utils/gen-program.py --falsifiable: assertions that can fail), each with its
world (utils/GenWorld.cpp) and the models of its pure C++
(utils/GenModels.bs): every run ends with a result (0 verified, 1 a
counterexample, 2 not fully explored, each with its message), never a
crash, an internal error or a hang; and every counterexample's recording,
replayed by `bsc run --replay`, fails the same assertion in the same
cycle (test/Verify/generated.test).

  verify-differential.py BSC GEN BIND MODELS OUT SEED...
prints one line per seed: `seed S status N said|silent|internal
replayed|differs|-`."""
import re
import subprocess
import sys

# Seconds per question to the solver: a random program's float arithmetic
# can make one hard, and the answer is then "not fully explored".
SOLVER_TIMEOUT = "10"


def main():
    bsc, gen, bind, models, out = sys.argv[1:6]
    for seed in sys.argv[6:]:
        path = "%s/p%s.bs" % (out, seed)
        cex = "%s/p%s.jsonl" % (out, seed)
        text = subprocess.run([sys.executable, gen, "--falsifiable", seed],
                              capture_output=True,
                              text=True, check=True).stdout
        open(path, "w").write(text)
        r = subprocess.run([bsc, "verify", "--bind", bind, "--model", models,
                            "--cycles", "3", "--solver-timeout",
                            SOLVER_TIMEOUT, "-o", cex, path],
                           capture_output=True, text=True, timeout=300)
        said = {0: "verified" in r.stdout,
                1: "assertion can fail" in r.stderr,
                2: "not fully explored" in r.stderr}.get(r.returncode, False)
        verdict = ("internal" if "internal error" in r.stderr
                   else "said" if said else "silent")
        replay = "-"
        if r.returncode == 1:
            found = re.search(r"^(\S+:\d+:\d+): error: cycle (\d+): assertion "
                              r"can fail: (.*)$", r.stderr, re.M)
            p = subprocess.run([bsc, "run", "--bind", bind, "--replay", cex,
                                path], capture_output=True, text=True,
                               timeout=300)
            want = found and "%s: error: cycle %s: assertion failed: %s" % (
                found.group(1), found.group(2), found.group(3))
            replay = "replayed" if want and want in p.stderr else "differs"
            if replay == "differs":
                sys.stderr.write("seed %s: verify said\n%s\nthe replay said\n%s\n"
                                 % (seed, r.stderr, p.stderr))
        print("seed", seed, "status", r.returncode, verdict, replay)


if __name__ == "__main__":
    main()

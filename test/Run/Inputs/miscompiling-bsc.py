#!/usr/bin/env python3
"""A bsc that miscompiles for i586 at -O2, for test/Run/differential-detects.test.

It runs the real bsc ($REAL_BSC) for everything else; `-target i586 -O2 ...
-o PROG` writes a PROG that prints something else.
"""
import os
import sys

args = sys.argv[1:]
if "-target" in args and "-O2" in args and "-o" in args:
    out = args[args.index("-o") + 1]
    with open(out, "w") as f:
        f.write("#!/bin/sh\necho miscompiled\n")
    os.chmod(out, 0o755)
    sys.exit(0)
os.execv(os.environ["REAL_BSC"], [os.environ["REAL_BSC"]] + args)

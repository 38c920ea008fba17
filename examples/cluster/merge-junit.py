#!/usr/bin/env python3
"""Adds up the JUnit files of `bsc replay --shard K/N` slices.

    merge-junit.py RESULTS_DIR [-o merged.xml]

Reads RESULTS_DIR/slice-K-of-N.xml (replay-array.sh writes them), checks
that every slice of one N is there, writes one JUnit file with every log's
test case (sorted by log, as a whole `bsc replay` orders them) and prints
`N passed, M failed` as bsc replay does. Exits 1 if a log failed, 2 if a
slice is missing or unreadable: a missing slice would pass logs unseen.
In Slurm, run it after the array job:
    sbatch --dependency=afterany:<array job id> --wrap \
        "examples/cluster/merge-junit.py replay-results -o replay.xml"
"""
import argparse
import os
import re
import sys
import xml.etree.ElementTree as ET


def fail(message):
    print(f"merge-junit.py: error: {message}", file=sys.stderr)
    sys.exit(2)


def read_slices(folder):
    """{K: root} of the slices, and their N; exits 2 on a mistake."""
    slices, counts = {}, set()
    try:
        names = sorted(os.listdir(folder))
    except OSError as e:
        fail(f"cannot read {folder}: {e.strerror}")
    for name in names:
        m = re.fullmatch(r"slice-(\d+)-of-(\d+)\.xml", name)
        if not m:
            continue
        k, n = int(m.group(1)), int(m.group(2))
        counts.add(n)
        try:
            slices[k] = ET.parse(os.path.join(folder, name)).getroot()
        except (ET.ParseError, OSError) as e:
            fail(f"cannot read {name}: {e}")
    if len(counts) != 1:
        found = ", ".join(str(n) for n in sorted(counts)) or "none"
        fail(f"{folder} must hold the slices of one array job "
             f"(slice-K-of-N.xml); slice counts found: {found}")
    n = counts.pop()
    missing = [str(k) for k in range(1, n + 1) if k not in slices]
    if missing:
        fail(f"slices {', '.join(missing)} of {n} are missing from "
             f"{folder}: their logs were not replayed")
    return slices, n


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("results", help="the folder of slice-K-of-N.xml")
    parser.add_argument("-o", dest="output", help="the merged JUnit file")
    args = parser.parse_args()
    slices, _ = read_slices(args.results)
    cases = [c for root in slices.values() for c in root.iter("testcase")]
    cases.sort(key=lambda c: c.get("name", ""))
    failed = sum(1 for c in cases if c.find("failure") is not None)
    if args.output:
        suite = ET.Element("testsuite", name="bsc replay",
                           tests=str(len(cases)), failures=str(failed))
        suite.extend(cases)
        ET.ElementTree(suite).write(args.output, encoding="UTF-8",
                                    xml_declaration=True)
    print(f"{len(cases) - failed} passed, {failed} failed")
    return 1 if failed else 0


if __name__ == "__main__":
    sys.exit(main())

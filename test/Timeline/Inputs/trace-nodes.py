"""Prints, for each cycle named, the tasks of a `bsc trace-decode` line as
the timeline page lists them: each task once, `short [state, place]`,
sorted (the page orders siblings by lane, the trace by the task table).

usage: trace-nodes.py TRACE CYCLE..."""
import re
import sys

lines = {}
for line in open(sys.argv[1]):
    cycle, _, trace = line.rstrip("\n").partition(": ")
    lines[int(cycle.split()[1])] = trace
for cycle in sys.argv[2:]:
    nodes = set()
    for path in lines[int(cycle)].split("; "):
        nodes.update(re.findall(r"(\w+ \[[^\]]*\])", path))
    print("cycle %s: %s" % (cycle, "; ".join(sorted(nodes))))

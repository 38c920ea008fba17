"""What `bsc replay --find` must find in replay-triage.test's corpus,
computed from the recordings themselves (not by bsc): for each log, the
stretches of cycles in which the ball is nearer than 200 while the robot
walks (near), or those in which Head::lookAtOppGoal ran for 10 cycles or
more (opp), each log as `bsc replay --find` prints it: its PASS line, then
a line per stretch (without the values of its parts).

usage: stretches.py near|opp LOG..."""
import json
import math
import sys

NEAR = "input.ball.position.abs() < 200 && output.motion == MotionType::walk"


def stretches(cycles, holds, lasting=1):
    found, start, last = [], None, None
    for c in cycles:
        if holds(c):
            if start is None:
                start = c["cycle"]
            last = c["cycle"]
        else:
            if start is not None and last - start + 1 >= lasting:
                found.append((start, last))
            start = None
    if start is not None and last - start + 1 >= lasting:
        found.append((start, last))
    return found


def show(found, text):
    for first, last in found:
        if first == last:
            print("  cycle %d: %s" % (first, text))
        else:
            print("  cycles %d to %d (%d cycles): %s"
                  % (first, last, last - first + 1, text))


for path in sys.argv[2:]:
    cycles = [c for c in (json.loads(l) for l in open(path) if l.strip())
              if "cycle" in c]
    near = lambda c: (math.hypot(c["input"]["ball"]["position"]["x"],
                                 c["input"]["ball"]["position"]["y"]) < 200
                      and c["output"]["motion"] == "walk")
    opp = lambda c: any(t["task"] == "Head::lookAtOppGoal" for t in c["tasks"])
    print("PASS %s (%d cycles)" % (path, len(cycles)))
    if sys.argv[1] == "near":
        show(stretches(cycles, near), NEAR)
    else:
        show(stretches(cycles, opp, 10), "Head::lookAtOppGoal")

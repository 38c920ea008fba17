"""What the timeline tests check the page against, read from a recording
itself (not from the page): the first cycle whose output is a kick, the
motion a cycle later, the first cycle in which executeKick is done, and
the hierarchy at the kick as the recording holds it. It also writes the
browser steps that need those cycles (utils/browser.py's step language).

usage: soccer-facts.py RUN.jsonl STEPS-IN STEPS-OUT
STEPS-IN's @KICK@ and @DONE@ become the cycles."""
import json
import sys

# The cycles, without the header line (docs/repl.md "Recordings").
cycles = [c for c in (json.loads(line) for line in open(sys.argv[1])
                      if line.strip()) if "cycle" in c]
kick = next(c for c in cycles if c["output"]["motion"] == "kick")
after = next(c for c in cycles if c["cycle"] == kick["cycle"] + 1)
done = next(c for c in cycles
            if any(t["task"] == "Motion::executeKick" and t["state"] == "done"
                   for t in c["tasks"]))
print("first kick: %d" % kick["cycle"])
print("motion after it: %s" % after["output"]["motion"])
print("executeKick done: %d" % done["cycle"])
print("cycles: %d" % len(cycles))
for t in kick["tasks"]:
    print("at the kick: %s [%s%s]" % (t["task"].split("::")[1], t["state"],
                                      ", " + t["at"] if "at" in t else ""))
steps = open(sys.argv[2]).read()
steps = steps.replace("@KICK@", str(kick["cycle"]))
steps = steps.replace("@DONE@", str(done["cycle"]))
open(sys.argv[3], "w").write(steps)

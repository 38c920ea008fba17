"""Damaged copies of a recording of Game.bs for boundary-record.test:
swapped.jsonl (cycle 2's say and random calls swapped), missing.jsonl
(cycle 2's last two calls dropped), badhex.jsonl, outside.jsonl, future.jsonl
and twice.jsonl (the header again in the middle)."""
import json
import sys

lines = open(sys.argv[1]).read().splitlines()
out = sys.argv[2]


def write(name, ls):
    with open(out + "/" + name, "w") as f:
        f.write("\n".join(ls) + "\n")


def edit(index, fn):
    copy = list(lines)
    d = json.loads(copy[index])
    fn(d)
    copy[index] = json.dumps(d)
    return copy


def swap(d):
    c = d["calls"]
    c[1], c[2] = c[2], c[1]


assert [c["fn"] for c in json.loads(lines[2])["calls"]][1:3] == \
    ["Sys::random", "Sys::say"]
write("swapped.jsonl", edit(2, swap))
write("missing.jsonl", edit(2, lambda d: d["calls"].__delitem__(slice(4, None))))
write("badhex.jsonl", edit(2, lambda d: d["calls"][1].update(result="xyz")))
write("outside.jsonl",
      edit(2, lambda d: d["calls"][0]["writes"].append(["input", 99, "0000"])))
write("future.jsonl", edit(0, lambda d: d["recording"].update(format=3)))
write("twice.jsonl", lines[:2] + [lines[0]] + lines[2:])

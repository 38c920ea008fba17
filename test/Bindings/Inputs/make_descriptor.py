#!/usr/bin/env python3
"""Writes an i386 assembly binding object with one hand-made descriptor.

usage: make_descriptor.py VARIANT MODULE > out.s

The descriptor follows include/bscript/descriptor.h: module MODULE with a
class K (method get), a module function f(int x) and an enum E { a }. It
is what bscript/Bind.h would emit, except for the one field VARIANT breaks,
so that each reader error of test/Bindings/descriptor-errors.test comes
from a file that is otherwise valid ("good" breaks nothing).
"""
import sys

variant, module = sys.argv[1], sys.argv[2]
P = 4
NO_INDEX = 0xffffffff

strings = ["", module, "K", "get", "f", "E", "a", "x"]
offsets, pos = {}, 0
for s in strings:
    offsets[s] = pos
    pos += len(s) + 1
string_bytes = pos

key, ekey = f"key_{module}", f"ekey_{module}"
# Records: pointer fields (symbol names, 0, or a literal), then words.
classes = [([key, 0], [offsets["K"], 0, 4, 4, 0, 0])]
members = [
    # get: a method of K returning int.
    ([f"holder_get_{module}", 0, 0, 0],
     [2, 0, offsets["get"], 0, 2, 0, 4, 0, 0, 0, 0, 0, 0, 0]),
    # f(int x): a module function.
    ([f"holder_f_{module}", 0, 0, 0],
     [3, NO_INDEX, offsets["f"], 0, 0, 0, 0, 0, 0, 1, 0, 0, 0, 0]),
]
params = [([0], [2, 0, 4, offsets["x"], 0, 0, 0, 0])]
enums = [([ekey], [offsets["E"], 0, 4, 0, 0, 1])]
values = [([], [offsets["a"], 0])]
header = {"version": 1, "ptr_size": P, "input": NO_INDEX,
          "output": NO_INDEX, "place": None}
section = "bs_modules"
tables_far = False

if variant == "ptrsize":
    header["ptr_size"] = 8
elif variant == "name":
    offsets_name = offsets["K"]  # names the module 'K'
    header["name"] = offsets_name
elif variant == "section":
    section = ".data.descriptor"
elif variant == "noreloc":
    classes[0][0][0] = "1"  # a non-null pointer without a relocation
elif variant == "nosym":
    classes[0][0][0] = key + "+1"  # points between symbols
elif variant == "nokey":
    classes[0][0][0] = 0
elif variant == "align":
    classes[0][1][3] = 3
elif variant == "modfield":
    members[1][1][0] = 0  # a module member that is a field
elif variant == "nothunk":
    members[0][0][0] = 0
elif variant == "typecode":
    members[0][1][4] = 42
elif variant == "tables":
    tables_far = True
elif variant == "input":
    header["input"] = 0
elif variant == "placed":
    header["place"] = "after"  # BS_PLACE_SIZE bytes after the strings
elif variant == "place":
    header["place"] = "strings"  # points into the string table
elif variant != "good":
    sys.exit(f"unknown variant {variant}")

tables = [classes, members, params, enums, values]
pointers = [2, 4, 1, 1, 0]
words = [6, 14, 8, 6, 2]
sizes = [p * P + 4 * w for p, w in zip(pointers, words)]
offset, table_fields = 112, []
for t, recs in enumerate(tables):
    table_fields.append((len(recs), offset + (4096 if tables_far and t == 0 else 0),
                         sizes[t]))
    offset += len(recs) * sizes[t]
string_offset = offset
total = string_offset + string_bytes
PLACE_SIZE = 256
place_text = "Bad.cpp:7"
place = 0
if header["place"] == "after":
    place = total
    total += PLACE_SIZE
elif header["place"] == "strings":
    place = string_offset

def escape(s):
    return s.replace("\\", "\\\\").replace('"', '\\"')

out = []
out.append("\t.text")
for name in ("get", "f"):
    out.append(f"\t.globl\tthunk_{name}_{module}")
    out.append(f"thunk_{name}_{module}:\n\tret")
out.append("\t.data")
for sym in (key, ekey):
    out.append(f"\t.globl\t{sym}\n{sym}:\t.byte\t0\n\t.byte\t0")
for name in ("get", "f"):
    out.append(f"\t.p2align\t2\nholder_{name}_{module}:\t.long\tthunk_{name}_{module}")
out.append(f'\t.section\t{section},"a",@progbits')
out.append(f"\t.globl\tbs_module_{module}\n\t.p2align\t3\nbs_module_{module}:")
out.append('\t.ascii\t"BSMOD\\0\\0\\1"')
out.append("\t.long\t%d, 112, %d, %d, %d, 0, %d, %d" % (
    header["version"], header["ptr_size"], header.get("name", offsets[module]),
    total, header["input"], header["output"]))
for count, off, size in table_fields:
    out.append(f"\t.long\t{count}, {off}, {size}")
out.append(f"\t.long\t{string_offset}, {string_bytes}, {place}")
for recs in tables:
    for ptrs, ws in recs:
        for p in ptrs:
            out.append(f"\t.long\t{p}")
        out.append("\t.long\t" + ", ".join(str(w) for w in ws))
out.append('\t.ascii\t"' + "".join(escape(s) + "\\0" for s in strings) + '"')
if header["place"] == "after":
    out.append('\t.ascii\t"' + place_text + '"')
    out.append("\t.zero\t%d" % (PLACE_SIZE - len(place_text)))
print("\n".join(out))

#!/usr/bin/env python3
"""check_docs.py DOC_ROOT INCLUDE_DIR: checks the installed documentation.

Every relative Markdown link in a .md file under DOC_ROOT (outside code)
must name a file or folder that exists, and the version numbers the
documents quote must be those of the installed headers: BS_ABI_VERSION
(bscript.h) and BS_DESCRIPTOR_VERSION (descriptor.h). Prints one line per
problem and exits 1 if there is any."""
import pathlib
import re
import sys

root, include = pathlib.Path(sys.argv[1]), pathlib.Path(sys.argv[2])


def header_value(name, macro):
    text = (include / "bscript" / name).read_text()
    return int(re.search(r"#define %s (\d+)" % macro, text).group(1))


abi = header_value("bscript.h", "BS_ABI_VERSION")
descriptor = header_value("descriptor.h", "BS_DESCRIPTOR_VERSION")
# What a document may say about either version, and which it means.
quoted = [
    (re.compile(r"`BS_ABI_VERSION`[,;] (\d+)"), abi, "BS_ABI_VERSION"),
    (re.compile(r"ABI version is (\d+)"), abi, "BS_ABI_VERSION"),
    (re.compile(r"\(ABI (\d+)\)"), abi, "BS_ABI_VERSION"),
    (re.compile(r"u32 version \((\d+)"), descriptor, "BS_DESCRIPTOR_VERSION"),
    (re.compile(r"\.o, version (\d+), hash"), descriptor, "BS_DESCRIPTOR_VERSION"),
]

problems = []
docs = sorted(root.rglob("*.md"))
if not docs:
    problems.append(f"{root}: no documents")
for doc in docs:
    text = doc.read_text()
    for pattern, want, macro in quoted:
        for m in pattern.finditer(text):
            if int(m.group(1)) != want:
                line = text.count("\n", 0, m.start()) + 1
                problems.append(f"{doc}:{line}: says {m.group(0)!r}, "
                                f"but {macro} is {want}")
    prose = re.sub(r"```.*?```", "", text, flags=re.S)
    prose = re.sub(r"`[^`\n]*`", "", prose)
    for m in re.finditer(r"\[[^\]\n]*\]\(([^)\s]+)\)", prose):
        target = m.group(1).split("#")[0]
        if not target or re.match(r"[a-z]+:", target):
            continue
        if not (doc.parent / target).exists():
            problems.append(f"{doc}: link to '{m.group(1)}', "
                            "which is not installed")
for p in problems:
    print(p)
sys.exit(1 if problems else 0)

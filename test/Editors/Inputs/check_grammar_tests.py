#!/usr/bin/env python3
"""check_grammar_tests.py GRAMMAR TEST.bs...: the grammar tests' own checks.

vscode-tmgrammar-test compares scope names exactly: `- string` forbids a
scope named `string`, which no token has, so such an assertion passes
whatever the grammar does. This script makes the tests able to fail:

- every scope an assertion names (required or forbidden) is a scope the
  grammar can give;
- every scope the grammar can give is required by some assertion (each
  rule is tested);
- every test file has a header and assertions.

Prints one line per problem and exits 1 if there is any, else prints a
summary line."""
import json
import re
import sys

ASSERTION = re.compile(r"^#\s*(\^+(?:\s*\^+)*|<~*-+)(.*)$")


def grammar_scopes(node, found):
    """The scope names of every rule and capture below node."""
    if isinstance(node, dict):
        for key in ("name", "contentName"):
            if isinstance(node.get(key), str):
                found.update(node[key].split())
        for value in node.values():
            grammar_scopes(value, found)
    elif isinstance(node, list):
        for value in node:
            grammar_scopes(value, found)
    return found


grammar_path, tests = sys.argv[1], sys.argv[2:]
ROOT = json.load(open(grammar_path))
# The top level's "name" is the language's display name, not a scope.
known = grammar_scopes({"patterns": ROOT["patterns"], "repository": ROOT["repository"]},
                       {ROOT["scopeName"]})
problems = []
required_somewhere = set()
count = 0
if not tests:
    problems.append("no test files")
for test in tests:
    lines = open(test).read().split("\n")
    if not re.match(r'^# SYNTAX TEST "%s"' % re.escape(ROOT["scopeName"]), lines[0]):
        problems.append(f"{test}:1: no '# SYNTAX TEST \"{ROOT['scopeName']}\"' header")
    in_file = 0
    for number, line in enumerate(lines[1:], start=2):
        m = ASSERTION.match(line)
        if not m:
            continue
        required, _, forbidden = m.group(2).partition(" - ")
        if m.group(2).strip().startswith("-"):
            required, forbidden = "", m.group(2).strip()[1:]
        for scope in required.split() + forbidden.split():
            if scope not in known:
                problems.append(f"{test}:{number}: '{scope}' is no scope of the grammar")
        required_somewhere.update(required.split())
        in_file += 1
    if in_file == 0:
        problems.append(f"{test}: no assertions")
    count += in_file
for scope in sorted(known - required_somewhere):
    problems.append(f"no test requires '{scope}'")
for p in problems:
    print(p)
if problems:
    sys.exit(1)
print(f"{count} assertions in {len(tests)} files name {len(required_somewhere)} scopes; "
      f"the grammar has {len(known)}")

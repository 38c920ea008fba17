#!/usr/bin/env python3
"""Fails when utils/gen-program.py never writes part of the language.

usage: check-generator-coverage.py --bsc BSC --bind-objs DIR [--seeds A:B]

Differential testing only finds disagreements in what the generator writes,
so the generator must keep up with the language (issue: two bugs hid in
constructs it never wrote). This script generates the programs of a range
of seeds, has bsc dump each one's typed AST (`--emit=typed-ast`, with the
generator's world module GenWorld.host.o), and collects what occurs:

- every AST node kind of include/bsc/AST/ASTNodes.def but the error nodes;
- every operator of include/bsc/AST/OperatorKinds.def on every kind of
  operand the language gives it (`==` on strings, enums, task states and
  class values, unary `-` on a class...), and the state kind tests;
- statement forms: `if` with and without `else`, `else if`; each part of a
  `for` head present and absent, in each of its forms; `return` with and
  without a value; `yield` with and without one;
- names, calls, members, indices and conversions of every kind, locals,
  parameters and constants of every type, defaults, named task states, and
  locals a reset zeroes.

The required sets come from the .def files where the language has a closed
set, so a new node kind or operator fails this check until the generator
writes it. Everything missing is listed; the exit status is 1 then.
"""
import argparse
import importlib.util
import os
import re
import subprocess
import sys
import tempfile

HERE = os.path.dirname(os.path.abspath(__file__))
ROOT = os.path.dirname(HERE)


def load_generator():
    spec = importlib.util.spec_from_file_location(
        "gen_program", os.path.join(HERE, "gen-program.py"))
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


def def_entries(path, macro):
    """The first arguments of MACRO(...) lines of a .def file."""
    with open(path) as f:
        return re.findall(rf"^{macro}\((\w+)(?:,\s*\"([^\"]*)\")?", f.read(), re.M)


def category(ty):
    """An operand's kind, from the type the dump prints."""
    if ty in ("int", "float", "bool", "string", "TaskState", "void"):
        return ty
    if ty.startswith("Gen::"):
        return "registered enum" if ty == "Gen::Mode" else "class"
    if "[" in ty:
        return "array"
    return "script enum"


def required():
    """What the generator must write: (feature, where it comes from)."""
    nodes = [n for n, _ in def_entries(os.path.join(ROOT, "include/bsc/AST/ASTNodes.def"), "(?:DECL|STMT|EXPR)")]
    ops = os.path.join(ROOT, "include/bsc/AST/OperatorKinds.def")
    binary = [s for _, s in def_entries(ops, "BINARY_OP")]
    unary = [s for _, s in def_entries(ops, "UNARY_OP")]
    assign = [s for _, s in def_entries(ops, "ASSIGN_OP")]
    req = set()
    for n in nodes:
        if not n.startswith("Error"):
            req.add(f"node {n}")
    # The operand kinds each operator takes (docs/language.md, Operators
    # and Registered classes; GenWorld's Vec has + - * == < and unary -).
    takes = {"+": ["int", "float", "class"], "-": ["int", "float", "class"],
             "*": ["int", "float", "class"], "/": ["int", "float"], "%": ["int"],
             "<": ["int", "float", "class"], "<=": ["int", "float"],
             ">": ["int", "float"], ">=": ["int", "float"],
             "==": ["int", "float", "bool", "string", "TaskState", "script enum",
                    "registered enum", "class"],
             "!=": ["int", "float", "bool", "string", "TaskState", "script enum",
                    "registered enum", "class"],
             "&&": ["bool"], "||": ["bool"]}
    for op in binary:
        for kind in takes[op]:  # a new operator fails here: say what it takes
            req.add(f"binary '{op}' on {kind}")
    for op in ("==", "!="):
        for kind in ("running", "failure"):
            req.add(f"binary '{op}' kind {kind}")
    unary_takes = {"-": ["int", "float", "class"], "!": ["bool"]}
    for op in unary:
        for kind in unary_takes[op]:
            req.add(f"unary '{op}' on {kind}")
    assign_takes = {"=": ["int", "float", "bool", "string", "TaskState", "script enum",
                          "registered enum", "class"],
                    "+=": ["int", "float"], "-=": ["int", "float"], "*=": ["int", "float"],
                    "/=": ["int", "float"], "%=": ["int"]}
    for op in assign:
        for kind in assign_takes[op]:
            req.add(f"assign '{op}' to {kind}")
    for target in ("local", "param", "field", "property", "element", "output"):
        req.add(f"assign to {target}")
    for form in ("if", "if-else", "else-if"):
        req.add(f"stmt {form}")
    for part, forms in (("init", ["none", "DeclStmt", "AssignStmt", "ExprStmt"]),
                        ("cond", ["none", "expr"]),
                        ("step", ["none", "AssignStmt", "ExprStmt", "YieldStmt"])):
        for form in forms:
            req.add(f"for {part} {form}")
    for form in ("return value", "return none in func", "return none in task",
                 "yield none", "yield int", "yield TaskState",
                 "assert", "assert with message", "assume", "assume with message"):
        req.add(f"stmt {form}")
    for kind in ("local", "param", "callable", "native", "enum", "const", "input", "output"):
        req.add(f"name {kind}")
    for kind in ("func", "task", "native", "method", "constructor"):
        req.add(f"call {kind}")
    for kind in ("func", "task", "native"):
        req.add(f"call {kind} with defaults")
    # Registered C++ with effects (hidden state, writes to input), which
    # time travel and exact replays take from their records.
    for fn in ("tick", "rnd", "poke"):
        req.add(f"call with effects Gen::{fn}")
    req.add("assert reading output")
    for kind in ("field", "property", "method"):
        req.add(f"member {kind}")
    for kind in ("constant", "clamped", "2-D"):
        req.add(f"index {kind}")
    for conv, froms in (("int", ["int", "float", "bool", "TaskState", "script enum",
                                 "registered enum"]),
                        ("float", ["int", "float"]), ("bool", ["bool"]),
                        ("implicit", ["int"])):
        for f in froms:
            req.add(f"conversion {conv} from {f}")
    for ty in ("int", "float", "bool", "string", "TaskState", "script enum",
               "registered enum", "class"):
        req.add(f"local of {ty}")
        req.add(f"param of {ty}")
        req.add(f"result of {ty}")
    for ty in ("int", "float", "bool", "string", "TaskState", "script enum", "registered enum"):
        req.add(f"const of {ty}")
        req.add(f"default of {ty}")
    for form in ("enum", "enum : TaskState", "enumerator explicit", "enumerator implicit",
                 "named state 1", "named state -1", "local zeroed at reset",
                 "nested func", "string literal", "registered constant"):
        req.add(form)
    return req


class Node:
    def __init__(self, indent, text):
        self.indent = indent
        self.text = text
        self.children = []
        self.parent = None

    @property
    def kind(self):
        return self.text.split(" ", 1)[0]

    @property
    def type(self):
        m = re.search(r" : (.+?)(?: zeroed-at-reset)? <\d+:\d+>$", self.text)
        return m.group(1) if m else ""


def parse_dump(text):
    roots, stack = [], []
    for line in text.splitlines():
        stripped = line.lstrip(" ")
        node = Node(len(line) - len(stripped), stripped)
        while stack and stack[-1].indent >= node.indent:
            stack.pop()
        if stack:
            node.parent = stack[-1]
            stack[-1].children.append(node)
        else:
            roots.append(node)
        stack.append(node)
    return roots


def walk(nodes):
    for n in nodes:
        yield n
        yield from walk(n.children)


def owner(node):
    while node and node.kind not in ("FuncDecl", "TaskDecl"):
        node = node.parent
    return node


def features(dump):
    found = set()
    for n in walk(parse_dump(dump)):
        k, t, c = n.kind, n.text, n.children
        if k.endswith(("Decl", "Stmt", "Expr")):
            found.add(f"node {k}")
        if k == "BinaryExpr" and c:
            op = re.search(r"'([^']+)'", t).group(1)
            found.add(f"binary '{op}' on {category(c[0].type)}")
            m = re.search(r" kind (running|failure)", t)
            if m:
                found.add(f"binary '{op}' kind {m.group(1)}")
        elif k == "UnaryExpr" and c:
            op = re.search(r"'([^']+)'", t).group(1)
            found.add(f"unary '{op}' on {category(c[0].type)}")
        elif k == "AssignStmt" and c:
            op = re.search(r"'([^']+)'", t).group(1)
            target = c[0]
            found.add(f"assign '{op}' to {category(target.type)}")
            if target.kind == "NameExpr":
                found.add(f"assign to {'local' if '-> local' in target.text else 'param'}")
            elif target.kind == "MemberExpr":
                found.add("assign to " + ("property" if "-> property" in target.text else "field"))
            elif target.kind == "IndexExpr":
                found.add("assign to element")
            root = target
            while root.children:
                root = root.children[0]
            if "-> output" in root.text:
                found.add("assign to output")
        elif k == "IfStmt":
            found.add("stmt if-else" if "has_else" in t else "stmt if")
            if "has_else" in t and len(c) > 2 and c[2].kind == "IfStmt":
                found.add("stmt else-if")
        elif k == "ForStmt" and len(c) == 4:
            init, cond, step = c[0], c[1], c[2]
            found.add("for init " + ("none" if init.text == "<<null>>" else init.kind))
            found.add("for cond " + ("none" if cond.text == "<<null>>" else "expr"))
            found.add("for step " + ("none" if step.text == "<<null>>" else step.kind))
        elif k == "ReturnStmt":
            if c:
                found.add("stmt return value")
            else:
                o = owner(n)
                found.add("stmt return none in " + ("task" if o and o.kind == "TaskDecl" else "func"))
        elif k == "AssertStmt":
            which = "assume" if t.startswith("AssertStmt assume") else "assert"
            found.add(f"stmt {which} with message" if len(c) > 1 else f"stmt {which}")
        elif k == "YieldStmt":
            found.add("stmt yield " + (category(c[0].type) if c else "none"))
        elif k == "NameExpr":
            m = re.search(r"-> (\w+)", t)
            if m:
                found.add(f"name {m.group(1)}")
            if "-> const" in t and re.search(r"'Gen::|'(LIMIT|HALF|START)'", t):
                found.add("registered constant")
        elif k == "CallExpr" and c:
            m = re.search(r"CallExpr (\w+)", t)
            kind = m.group(1) if m else ""
            callee = c[0]
            if kind == "native" and callee.kind == "NameExpr" and \
                    re.search(r"'([^']+)'", callee.text).group(1).split("::")[-1] == n.type.split("::")[-1]:
                kind = "constructor"
            found.add(f"call {kind}")
            if " defaults " in t:
                found.add(f"call {kind} with defaults")
        elif k == "MemberExpr":
            m = re.search(r"-> (\w+)", t)
            if m:
                found.add(f"member {m.group(1)}")
        elif k == "IndexExpr":
            if " constant" in t:
                found.add("index constant")
            if " clamped" in t:
                found.add("index clamped")
            if c and c[0].kind == "IndexExpr":
                found.add("index 2-D")
        elif k == "ConversionExpr" and c:
            m = re.search(r"ConversionExpr (?:'(\w+)'|(implicit))", t)
            conv = m.group(1) or m.group(2)
            found.add(f"conversion {conv} from {category(c[0].type)}")
        elif k == "VarDecl":
            found.add(f"local of {category(n.type)}")
            if "zeroed-at-reset" in t:
                found.add("local zeroed at reset")
        elif k == "ParamDecl":
            found.add(f"param of {category(n.type)}")
            if c:
                found.add(f"default of {category(n.type)}")
        elif k == "FuncDecl":
            found.add(f"result of {category(n.type)}")
            if " in '" in t:
                found.add("nested func")
        elif k == "ConstDecl":
            found.add(f"const of {category(n.type)}")
        elif k == "EnumDecl":
            found.add("enum : TaskState" if ": TaskState" in t else "enum")
        elif k == "StringLiteralExpr":
            found.add("string literal")
    return found


def source_features(program):
    """What the typed AST no longer shows: enumerators with and without
    a written value, and named task states of 1 and -1 (which must not
    compare as kinds)."""
    found = set()
    in_enum = in_state_enum = False
    value = 0
    for line in program.splitlines():
        if line.startswith("enum "):
            in_enum, in_state_enum = True, line.endswith(": TaskState")
            value = 1 if in_state_enum else 0
            continue
        m = re.match(r"    (\w+)(?: = (-?\d+))?$", line)
        if not in_enum or not m:
            in_enum = False
            continue
        found.add("enumerator " + ("explicit" if m.group(2) else "implicit"))
        value = int(m.group(2)) if m.group(2) else value
        if in_state_enum and value in (1, -1):
            found.add(f"named state {value}")
        value += 1
    for fn in ("tick", "rnd", "poke"):
        if f"Gen::{fn}(" in program:
            found.add(f"call with effects Gen::{fn}")
    if "assert(output." in program:
        found.add("assert reading output")
    return found


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--bsc", required=True)
    ap.add_argument("--bind-objs", required=True,
                    help="the folder of GenWorld.host.o (test/bind-objects)")
    ap.add_argument("--seeds", default="0:200", help="A:B, A inclusive, B exclusive")
    args = ap.parse_args()
    gen = load_generator()
    a, b = (int(x) for x in args.seeds.split(":"))
    world = os.path.join(args.bind_objs, "GenWorld.host.o")
    found = set()
    with tempfile.TemporaryDirectory(prefix="bsc-gencov-") as tmp:
        src = os.path.join(tmp, "prog.bs")
        for seed in range(a, b):
            program = gen.Gen(seed).program()
            with open(src, "w") as f:
                f.write(program)
            p = subprocess.run([args.bsc, "--emit=typed-ast", "--bind", world, src],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
            if p.returncode != 0:
                sys.stdout.write(f"seed {seed} does not compile:\n{p.stderr[:2000]}")
                return 1
            found |= features(p.stdout)
            found |= source_features(program)
    missing = sorted(required() - found)
    for m in missing:
        print(f"never generated: {m}")
    print(f"{b - a} programs, {len(required())} features required, {len(missing)} missing")
    return 1 if missing else 0


if __name__ == "__main__":
    sys.exit(main())

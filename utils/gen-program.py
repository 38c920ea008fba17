#!/usr/bin/env python3
"""Prints a random, well-typed b-script program for differential testing.

usage: gen-program.py SEED

The program depends only on SEED (Python's own `random.Random`, no hash
randomisation, no clock), so a failing seed reproduces anywhere. It requires
"io" and prints what it computes, so that `utils/diff-test.py` can compare
the output of several configurations of bsc (JIT and programs, -O0 and -O2,
host and i586). Most programs also use the world module `Gen` of
utils/GenWorld.cpp (give bsc `--bind GenWorld.<target>.o`); its `Out`
prints what the behavior wrote when the program ends.

What a program exercises (docs/language.md; utils/check-generator-coverage.py
checks that the generator writes every node kind, operator and form):
- tasks with `yield`, `yield <int>` (also 0 and negative: done and failure),
  `yield` of TaskState values (`TaskState::x`, named states of an
  `enum S : TaskState`, computed, passed in), `return`; locals kept across
  yields; read-only task parameters, re-evaluated at each call;
- nested task calls and func calls, top-level funcs and funcs nested in
  tasks, which read and update the task's parameters and locals, also
  before a local is declared (they then read the reset's zero). The call
  graph is acyclic by construction: callable i calls only callables j > i,
  and the entry `main` (a task or a func without parameters) is callable 0;
- `taskState(T)` compared with `TaskState::running/failure` (kinds), named
  states (numbers, also 1 and -1) and constants; implicit resets (parents
  call children on some cycles only), several calls in one cycle, and
  restarts of children that ended or failed, in the same cycle;
- int, float, bool and string values, script enums, TaskState values and
  module constants (of every constant type, in any order, computed at
  compile time; the program checks each against the same expression
  computed at run time and prints "SELF-CHECK FAILED" if they differ);
- default arguments left out at some calls, of funcs, tasks and C++;
- int `/` and `%` by zero and `INT_MIN / -1`, wrapping `+ - *`, hex
  literals, `int(float)` of huge, infinite and NaN values, conversions;
- `&&` and `||` whose right operand calls a func that prints;
- `assert(cond)` and `assert(cond, "message")` whose conditions always hold,
  and `assume(...)`s alike before them (what the environment guarantees)
  (`b || !b`, `i == i`) and call nothing: the JIT checks them, objects
  leave them out, and both must print the same; with `--falsifiable` the
  assertions (not the assumptions) can fail (`b`, `i != 2`), for `bsc
  verify`'s differential test (utils/verify-differential.py);
- bounded `for` loops (a counter only the step changes) with `break` and
  `continue`, and `for(...; yield)` loops in tasks;
- with `Gen`: class values (constructors, fields, a property, const and
  mutating methods, the operators `+ - * == != <` and unary `-`), array
  fields of every element kind indexed by constants and by computed
  indices (clamped), registered enums and constants, C++ defaults, a
  function with a `bs::Context &`, `input` read and `output` written.
Every loop terminates within a cycle: a loop either has a bounded counter or
yields at each step. `%` is on ints only, as Sema requires.
"""
import argparse
import random
import sys

INT_LITS = ["0", "1", "2", "3", "5", "7", "(-1)", "(-2)", "10", "100", "255",
            "1000", "65536", "46341", "2147483647", "(-2147483647 - 1)",
            "(-2147483648)", "0x7FFFFFFF", "0xFFFFFFFF", "0x80000000",
            "123456789", "(-99)"]
FLOAT_LITS = ["0.0", "1.0", "0.5", "2.5", "(-1.5)", "0.1", "3.14159", "100.0",
              "1e10", "3.0e38", "1.5e-3", "1e-30", "1e-40", "16777216.0",
              "16777217.0", "2147483648.0", "(-2147483904.0)", "1e30",
              "0.333", "7.0", "(-0.0)"]
STRING_LITS = ['""', '"a"', '"ab"', '"kick"', '"Kick"', '"kick "',
               '"tab\\there"', '"line\\n"', '"q\\"uote"', '"back\\\\"',
               '"x\\0y"', '"\u00e9t\u00e9"']
INT_OPS = ["+", "-", "*", "/", "%"]
FLOAT_OPS = ["+", "-", "*", "/"]
CMP_OPS = ["<", "<=", ">", ">=", "==", "!="]
STATES = ["TaskState::done", "TaskState::running", "TaskState::failure"]
SCALARS = ["int", "float", "bool"]
MODES = ["idle", "walk", "kick"]
# The array fields of utils/GenWorld.cpp: name -> (element type, extents).
BUF_ARRAYS = {"vals": ("int", [4]), "grid": ("float", [2, 3]),
              "small": ("int", [3]), "bytes": ("int", [2]),
              "dbl": ("float", [2]), "flags": ("bool", [2]),
              "modes": ("Mode", [2]), "pts": ("Vec", [2])}
IN_ARRAYS = {"vals": ("int", [3]), "dist": ("float", [2])}
OUT_ARRAYS = {"vals": ("int", [3]), "head": ("float", [2, 2]),
              "small": ("int", [2])}
# An upper bound of the work of one call of a callable (statements run,
# counting the callees' work and loop trips), so that the output of a
# program stays small: calls that would exceed it are not generated.
BUDGET = 400


class Callable:
    def __init__(self, index, name, is_task, params, ret):
        self.index = index
        self.name = name
        self.is_task = is_task
        self.params = params  # [(name, type, default text or None)]
        self.ret = ret        # None or a type (funcs only)
        self.nested = []      # nested funcs of a task
        self.cost = 1         # work of one call, callees included
        self.must = []        # callables this one calls for sure


class Scope:
    """Visible variables: name -> (type, assignable)."""

    def __init__(self, parent=None):
        self.parent = parent
        self.vars = {}

    def all(self):
        out = dict(self.parent.all()) if self.parent else {}
        out.update(self.vars)
        return out


class Ctx:
    """Where code is being generated."""

    def __init__(self, owner, in_task_body, callees, nested, scope):
        self.owner = owner              # the Callable whose body this is
        self.in_task_body = in_task_body  # yields allowed
        self.callees = callees          # top-level Callables that may be called
        self.nested = nested            # nested funcs that may be called
        self.scope = scope
        self.loop_depth = 0
        # Loop depths whose loops must not `continue`: their body, not
        # their step, counts the counter or yields.
        self.no_continue = set()
        # Inside loops bsc does not see as counted: no `yield`, which bsc
        # would warn a pass could skip.
        self.no_yield = 0
        self.stmt_depth = 0
        self.mult = 1                   # loop trips around the current point
        # Inside an assertion's condition: no calls of funcs, which may
        # print or write output (bsc requires it only of tasks and of what
        # changes state; printing is registered C++ it cannot see into).
        self.pure = 0


class Gen:
    def __init__(self, seed, falsifiable=False):
        self.rng = random.Random(seed)
        self.falsifiable = falsifiable  # assertions that can fail
        self.counter = 0
        self.lines = []
        self.tasks = []
        self.world = False     # uses the Gen module
        self.enums = {}        # plain enum name -> [(enumerator, value)]
        self.states = {}       # `enum S : TaskState` name -> [(enumerator, value)]
        self.consts = []       # [(name, type, expression)]

    def fresh(self, prefix):
        self.counter += 1
        return f"{prefix}{self.counter}"

    def emit(self, indent, text):
        self.lines.append("    " * indent + text)

    # ---------------------------------------------------------------- types
    def value_types(self):
        """Types a local, parameter or result may have in this program."""
        tys = ["int", "int", "float", "bool", "string", "TaskState"]
        tys += [f"enum:{e}" for e in self.enums]
        if self.world:
            tys += ["Mode", "Vec", "Vec", "Buf"]
        return tys

    def spell(self, ty):
        """The type as the program writes it (one of its spellings)."""
        r = self.rng
        if ty.startswith("enum:"):
            return ty[5:]
        if ty == "TaskState" and self.states and r.random() < 0.3:
            # `enum S : TaskState` names TaskState as a type.
            return r.choice(sorted(self.states))
        if ty in ("Mode", "Vec", "Buf"):
            # The world module's names are visible unqualified too.
            return ty if r.random() < 0.3 else f"Gen::{ty}"
        return ty

    @staticmethod
    def is_class(ty):
        return ty in ("Vec", "Buf")

    # ------------------------------------------------------------ constants
    def const_names(self, ty):
        return [n for n, t, _ in self.consts if t == ty]

    def const_expr(self, ty, depth=0):
        """A constant expression of type ty (docs/language.md "Module
        constants"): literals, enum values, other constants, operators."""
        r = self.rng
        names = self.const_names(ty)
        if names and r.random() < 0.25:
            return r.choice(names)
        leaf = depth >= 2 or r.random() < 0.4
        if ty == "int":
            if leaf:
                k = r.randrange(6)
                if k == 0 and self.enums:
                    e = r.choice(sorted(self.enums))
                    return f"int({e}::{r.choice(self.enums[e])[0]})"
                if k == 1 and self.world:
                    return r.choice(["Gen::LIMIT", "LIMIT"])
                if k == 2:
                    return f"int({self.const_expr('float', 2)})"
                return r.choice(INT_LITS)
            k = r.randrange(4)
            if k == 0:
                return f"(-{self.const_expr('int', depth + 1)})"
            if k == 1:
                return f"int({self.const_expr(r.choice(['bool', 'TaskState']), depth + 1)})"
            op = r.choice(INT_OPS)
            b = r.choice(["0", "(-1)"]) if op in "/%" and r.random() < 0.4 \
                else self.const_expr("int", depth + 1)
            return f"({self.const_expr('int', depth + 1)} {op} {b})"
        if ty == "float":
            if leaf:
                if self.world and r.random() < 0.15:
                    return "Gen::HALF"
                if r.random() < 0.2:
                    return self.const_expr("int", 2)  # converts implicitly
                return r.choice(FLOAT_LITS)
            k = r.randrange(4)
            if k == 0:
                return f"float({self.const_expr('int', depth + 1)})"
            if k == 1:
                return f"(-{self.const_expr('float', depth + 1)})"
            return (f"({self.const_expr('float', depth + 1)} {r.choice(FLOAT_OPS)} "
                    f"{self.const_expr(r.choice(['float', 'int']), depth + 1)})")
        if ty == "bool":
            if leaf:
                return r.choice(["true", "false"])
            k = r.randrange(6)
            if k == 0:
                return f"(!{self.const_expr('bool', depth + 1)})"
            if k == 1:
                return (f"({self.const_expr('bool', depth + 1)} {r.choice(['&&', '||', '==', '!='])} "
                        f"{self.const_expr('bool', depth + 1)})")
            if k == 2:
                return (f"({self.const_expr('string', depth + 1)} {r.choice(['==', '!='])} "
                        f"{self.const_expr('string', depth + 1)})")
            if k == 3:
                t = r.choice(["TaskState"] + [f"enum:{e}" for e in self.enums]
                             + (["Mode"] if self.world else []))
                return (f"({self.const_expr(t, depth + 1)} {r.choice(['==', '!='])} "
                        f"{self.const_expr(t, depth + 1)})")
            t = r.choice(["int", "float"])
            return (f"({self.const_expr(t, depth + 1)} {r.choice(CMP_OPS)} "
                    f"{self.const_expr(r.choice(['int', 'float']), depth + 1)})")
        if ty == "string":
            return r.choice(STRING_LITS)
        if ty == "TaskState":
            return self.state_value()
        if ty == "Mode":
            return r.choice(["Gen::START", "START", f"Mode::{r.choice(MODES)}",
                             f"Gen::Mode::{r.choice(MODES)}"])
        e = ty[5:]
        return f"{e}::{r.choice(self.enums[e])[0]}"

    def state_value(self):
        """A TaskState written as a constant: a kind or a named state."""
        r = self.rng
        if self.states and r.random() < 0.6:
            s = r.choice(sorted(self.states))
            return f"{s}::{r.choice(self.states[s])[0]}"
        return r.choice(STATES)

    def declare_types_and_constants(self):
        r = self.rng
        for _ in range(r.randint(0, 2)):
            name = self.fresh("Ph")
            values, nxt = [], 0
            for _ in range(r.randint(1, 4)):
                if r.random() < 0.3:
                    nxt = r.randint(-3, 6)  # repeats allowed, as in C
                    values.append((self.fresh("e"), nxt, True))
                else:
                    values.append((self.fresh("e"), nxt, False))
                nxt += 1
            self.enums[name] = [(n, v) for n, v, _ in values]
            self.emit(0, f"enum {name}")
            for n, v, explicit in values:
                self.emit(1, f"{n} = {v}" if explicit else n)
            self.emit(0, "")
        for _ in range(r.randint(0, 2)):
            name = self.fresh("St")
            values, nxt = [], 1
            for _ in range(r.randint(1, 4)):
                explicit = r.random() < 0.5 or nxt == 0
                if explicit:
                    # 1 and -1 too: named states of a kind's number.
                    nxt = r.choice([1, -1, 2, 5, -2, -7, 100])
                values.append((self.fresh("s"), nxt, explicit))
                nxt += 1
            self.states[name] = [(n, v) for n, v, _ in values]
            self.emit(0, f"enum {name} : TaskState")
            for n, v, explicit in values:
                self.emit(1, f"{n} = {v}" if explicit else n)
            self.emit(0, "")
        # Constants may use constants declared after them: made in order,
        # printed shuffled.
        made = []
        for _ in range(r.randint(0, 5)):
            ty = r.choice(["int", "int", "float", "bool", "string", "TaskState"]
                          + [f"enum:{e}" for e in self.enums]
                          + (["Mode"] if self.world else []))
            expr = self.const_expr(ty)
            name = self.fresh("K")
            self.consts.append((name, ty, expr))
            made.append(f"const {self.spell(ty)} {name} = {expr}")
        r.shuffle(made)
        for line in made:
            self.emit(0, line)

    def check_constants(self, ind):
        """Each constant against its expression computed at run time."""
        for name, ty, expr in self.consts:
            if ty == "float":
                same = f"({name} == ({expr}) || ({name} != {name} && ({expr}) != ({expr})))"
            elif ty == "TaskState":
                same = f"(int({name}) == int({expr}))"
            else:
                same = f"({name} == ({expr}))"
            self.emit(ind, f"if(!{same})")
            self.emit(ind + 1, f'io::prints("SELF-CHECK FAILED: {name}")')

    # ---------------------------------------------------------------- exprs
    def vars_of(self, ctx, ty, assignable=False):
        return sorted(n for n, (t, a) in ctx.scope.all().items()
                      if t == ty and (a or not assignable))

    def value_callees(self, ctx, ty):
        if ctx.pure:
            return []
        fs = [c for c in ctx.callees if not c.is_task and c.ret == ty]
        fs += [c for c in ctx.nested if c.ret == ty]
        return fs

    def afford(self, ctx, f, force=False):
        """Counts a call of f at the current point, if the budget allows."""
        extra = ctx.mult * f.cost
        if ctx.owner.cost + extra > BUDGET and not force:
            return False
        ctx.owner.cost += extra
        return True

    def args(self, ctx, params, depth):
        """Arguments for params, leaving out a tail of defaulted ones."""
        n = len(params)
        while n and params[n - 1][2] is not None and self.rng.random() < 0.5:
            n -= 1
        return ", ".join(self.expr(ctx, t, depth + 1) for _, t, _ in params[:n])

    def call_expr(self, ctx, f, depth):
        return f"{f.name}({self.args(ctx, f.params, depth)})"

    def try_call(self, ctx, ty, depth):
        fs = self.value_callees(ctx, ty)
        if fs:
            f = self.rng.choice(fs)
            if self.afford(ctx, f):
                return self.call_expr(ctx, f, depth)
        return None

    def index(self, ctx, extent, depth):
        """An index: a constant inside the array (checked at compile time)
        or a computed one, which may fall outside (clamped at run time)."""
        r = self.rng
        if depth >= 3 or r.random() < 0.4:
            return str(r.randrange(extent))
        vs = self.vars_of(ctx, "int")
        base = r.choice(vs) if vs else "Gen::cycleOf()"
        return f"({base} {r.choice(['+', '-', '*'])} {self.int_expr(ctx, depth + 1)})"

    def element(self, ctx, base, arrays, ty, depth=1):
        """`base.f[i]...` of an array field with elements of type ty."""
        names = sorted(n for n, (t, _) in arrays.items() if t == ty)
        if not names:
            return None
        name = self.rng.choice(names)
        _, extents = arrays[name]
        return base + f".{name}" + "".join(f"[{self.index(ctx, e, depth)}]"
                                           for e in extents)

    def class_vars(self, ctx, ty, assignable=False):
        return self.vars_of(ctx, ty, assignable) if self.world else []

    def world_int(self, ctx, depth):
        r = self.rng
        k = r.randrange(8)
        bufs = self.class_vars(ctx, "Buf")
        vecs = self.class_vars(ctx, "Vec")
        if k == 0:
            return self.element(ctx, "input", IN_ARRAYS, "int", depth)
        if k == 1 and bufs:
            return self.element(ctx, r.choice(bufs), BUF_ARRAYS, "int", depth)
        if k == 2:
            arg = self.int_expr(ctx, depth + 1)
            if r.random() < 0.5:
                return f"Gen::mix({arg})"
            return f"Gen::mix({arg}, {self.int_expr(ctx, depth + 1)})"
        if k == 3:
            # tick() and rnd() keep hidden C++ state: calls with effects.
            return r.choice(["Gen::cycleOf()", "input.time", "Gen::LIMIT", "LIMIT",
                             "Gen::tick()", "Gen::rnd()"])
        if k == 4:
            return f"{self.vec_expr(ctx, depth + 1)}.quad()"
        if k == 5 and bufs:
            return f"{r.choice(bufs)}.{r.choice(['total()', 'tag'])}"
        if k == 6:
            return f"int({self.mode_expr(ctx, depth + 1)})"
        if vecs:
            return f"int({r.choice(vecs)}.{r.choice(['x', 'y'])})"
        return None

    def int_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.3
        if leaf:
            vs = self.vars_of(ctx, "int")
            if vs and r.random() < 0.65:
                return r.choice(vs)
            cs = self.const_names("int")
            if cs and r.random() < 0.2:
                return r.choice(cs)
            return r.choice(INT_LITS)
        k = r.randrange(15)
        if k <= 4:
            op = r.choice(INT_OPS)
            a = self.int_expr(ctx, depth + 1)
            if op in "/%" and r.random() < 0.5:
                if r.random() < 0.2:
                    a = r.choice(["(-2147483647 - 1)", "(-2147483648)", "0x80000000"])
                b = r.choice(["0", "(-1)", "(0 * " + self.int_expr(ctx, depth + 1) + ")",
                              self.int_expr(ctx, depth + 1)])
            else:
                b = self.int_expr(ctx, depth + 1)
            return f"({a} {op} {b})"
        if k == 5:
            return f"(-{self.int_expr(ctx, depth + 1)})"
        if k == 6:
            return f"int({self.float_expr(ctx, depth + 1)})"
        if k == 7:
            return f"int({self.bool_expr(ctx, depth + 1)})"
        if k == 8 and self.tasks:
            return f"int(taskState({r.choice(self.tasks).name}))"
        if k == 9:
            call = self.try_call(ctx, "int", depth)
            if call:
                return call
        if k == 10:
            # Overflow on purpose.
            return f"({self.int_expr(ctx, depth + 1)} * 65537 + 2147483000)"
        if k == 11:
            ty = r.choice(["TaskState"] + [f"enum:{e}" for e in self.enums])
            conv = "int" if r.random() < 0.9 else "float"
            if conv == "float":
                return f"int(float({self.int_expr(ctx, depth + 1)}))"
            return f"int({self.expr(ctx, ty, depth + 1)})"
        if k == 12 and self.world:
            w = self.world_int(ctx, depth)
            if w:
                return w
        return self.int_expr(ctx, 3)

    def float_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.3
        if leaf:
            vs = self.vars_of(ctx, "float")
            if vs and r.random() < 0.6:
                return r.choice(vs)
            cs = self.const_names("float")
            if cs and r.random() < 0.2:
                return r.choice(cs)
            return r.choice(FLOAT_LITS)
        k = r.randrange(11)
        if k <= 3:
            op = r.choice(FLOAT_OPS)
            a = self.float_expr(ctx, depth + 1)
            # An int operand converts implicitly.
            b = (self.int_expr(ctx, depth + 1) if r.random() < 0.25
                 else self.float_expr(ctx, depth + 1))
            if r.random() < 0.5:
                a, b = b, a
            return f"({a} {op} {b})"
        if k == 4:
            return f"(-{self.float_expr(ctx, depth + 1)})"
        if k == 5:
            return f"float({r.choice([self.int_expr, self.float_expr])(ctx, depth + 1)})"
        if k == 6:
            call = self.try_call(ctx, "float", depth)
            if call:
                return call
        if k == 7:
            # An int where a float is expected converts implicitly.
            return self.int_expr(ctx, depth + 1)
        if k >= 8 and self.world:
            bufs = self.class_vars(ctx, "Buf")
            j = r.randrange(5)
            if j == 0:
                return self.element(ctx, "input", IN_ARRAYS, "float", depth)
            if j == 1 and bufs:
                return self.element(ctx, r.choice(bufs), BUF_ARRAYS, "float", depth)
            if j == 2:
                return f"Gen::nudge({self.float_expr(ctx, depth + 1)})"
            if j == 3:
                return f"{self.vec_expr(ctx, depth + 1)}.{r.choice(['x', 'y'])}"
            if bufs:
                return f"{r.choice(bufs)}.pts[{self.index(ctx, 2, depth)}].{r.choice(['x', 'y'])}"
            return r.choice(["Gen::HALF", "HALF", "input.ball.x"])
        return self.float_expr(ctx, 3)

    def bool_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.2
        if leaf:
            vs = self.vars_of(ctx, "bool")
            if vs and r.random() < 0.5:
                return r.choice(vs)
            cs = self.const_names("bool")
            if cs and r.random() < 0.2:
                return r.choice(cs)
            if r.random() < 0.3:
                return r.choice(["true", "false"])
            return f"({self.int_expr(ctx, 3)} {r.choice(CMP_OPS)} {self.int_expr(ctx, 3)})"
        k = r.randrange(16)
        if k <= 1:
            return f"({self.int_expr(ctx, depth + 1)} {r.choice(CMP_OPS)} {self.int_expr(ctx, depth + 1)})"
        if k == 2:
            a, b = self.float_expr(ctx, depth + 1), self.float_expr(ctx, depth + 1)
            if r.random() < 0.3:
                # Mixed int and float compare as floats.
                a = self.int_expr(ctx, depth + 1)
            return f"({a} {r.choice(CMP_OPS)} {b})"
        if k <= 4:
            # Short circuit: the right operand often prints.
            op = r.choice(["&&", "||"])
            a = self.bool_expr(ctx, depth + 1)
            fs = self.value_callees(ctx, "bool")
            f = r.choice(fs) if fs else None
            if f and r.random() < 0.6 and self.afford(ctx, f):
                b = self.call_expr(ctx, f, depth)
            else:
                b = self.bool_expr(ctx, depth + 1)
            return f"({a} {op} {b})"
        if k == 5:
            if r.random() < 0.2:
                return f"bool({self.bool_expr(ctx, depth + 1)})"
            return f"(!{self.bool_expr(ctx, depth + 1)})"
        if k <= 7:
            return self.state_test(ctx, depth)
        if k == 8:
            call = self.try_call(ctx, "bool", depth)
            if call:
                return call
        if k == 9:
            op = r.choice(["==", "!="])
            return f"({self.string_expr(ctx, depth + 1)} {op} {self.string_expr(ctx, depth + 1)})"
        if k == 10 and self.enums:
            ty = f"enum:{r.choice(sorted(self.enums))}"
            return f"({self.expr(ctx, ty, depth + 1)} {r.choice(['==', '!='])} {self.expr(ctx, ty, depth + 1)})"
        if k >= 11 and self.world:
            bufs = self.class_vars(ctx, "Buf")
            j = r.randrange(5)
            if j == 0:
                op = r.choice(["==", "!=", "<"])
                return f"({self.vec_expr(ctx, depth + 1)} {op} {self.vec_expr(ctx, depth + 1)})"
            if j == 1:
                return f"({self.mode_expr(ctx, depth + 1)} {r.choice(['==', '!='])} {self.mode_expr(ctx, depth + 1)})"
            if j == 2 and bufs:
                return self.element(ctx, r.choice(bufs), BUF_ARRAYS, "bool", depth)
            return "input.seen"
        return f"({self.bool_expr(ctx, depth + 1)} {r.choice(['==', '!='])} {self.bool_expr(ctx, depth + 1)})"

    def state_test(self, ctx, depth):
        """A TaskState compared: by kind against TaskState::running or
        ::failure written so, by number against anything else."""
        r = self.rng
        a = self.state_expr(ctx, depth + 1)
        b = self.state_expr(ctx, depth + 1) if r.random() < 0.3 else self.state_value()
        if r.random() < 0.3:
            a, b = b, a
        return f"({a} {r.choice(['==', '!='])} {b})"

    def state_oracle(self, ctx, ind):
        """A TaskState comparison checked against its meaning in numbers
        (docs/language.md, Tasks rule 4): a kind for `TaskState::running`
        and `::failure` written so, the number for anything else."""
        r = self.rng
        # Each side is evaluated twice, so neither may call anything: a
        # func's state may differ at its second call.
        a = self.state_operand(ctx)
        b = self.state_value() if r.random() < 0.7 else self.state_operand(ctx)
        kinds = {"TaskState::running": "> 0", "TaskState::failure": "< 0"}
        if b in kinds:
            meaning = f"int({a}) {kinds[b]}"
        elif a in kinds:
            meaning = f"int({b}) {kinds[a]}"
        else:
            meaning = f"int({a}) == int({b})"
        self.emit(ind, f"if(({a} == {b}) != ({meaning}))")
        # Named by a number: the operands may hold string literals.
        self.emit(ind + 1, f'io::prints("SELF-CHECK FAILED: state test {self.fresh("q")}")')

    def state_operand(self, ctx):
        """A TaskState without calls: taskState(T), a variable or constant,
        or a state written as a constant."""
        r = self.rng
        vs = self.vars_of(ctx, "TaskState") + self.const_names("TaskState")
        k = r.randrange(3)
        if k == 0 and self.tasks:
            return f"taskState({r.choice(self.tasks).name})"
        if k == 1 and vs:
            return r.choice(vs)
        return self.state_value()

    def state_expr(self, ctx, depth):
        r = self.rng
        k = r.randrange(6)
        if k <= 1 and self.tasks:
            return f"taskState({r.choice(self.tasks).name})"
        if k == 2:
            vs = self.vars_of(ctx, "TaskState") + self.const_names("TaskState")
            if vs:
                return r.choice(vs)
        if k == 3 and depth < 3:
            call = self.try_call(ctx, "TaskState", depth)
            if call:
                return call
        return self.state_value()

    def string_expr(self, ctx, depth):
        r = self.rng
        k = r.randrange(5)
        if k == 0:
            vs = self.vars_of(ctx, "string") + self.const_names("string")
            if vs:
                return r.choice(vs)
        if k == 1 and depth < 3:
            call = self.try_call(ctx, "string", depth)
            if call:
                return call
        return r.choice(STRING_LITS)

    def enum_expr(self, ctx, ty, depth):
        r = self.rng
        k = r.randrange(4)
        if k == 0:
            vs = self.vars_of(ctx, ty) + self.const_names(ty)
            if vs:
                return r.choice(vs)
        if k == 1 and depth < 3:
            call = self.try_call(ctx, ty, depth)
            if call:
                return call
        return self.const_expr(ty, 2)

    def mode_expr(self, ctx, depth):
        r = self.rng
        k = r.randrange(5)
        if k == 0:
            vs = self.vars_of(ctx, "Mode") + self.const_names("Mode")
            if vs:
                return r.choice(vs)
        if k == 1:
            return "input.mode"
        if k == 2:
            bufs = self.class_vars(ctx, "Buf")
            if bufs:
                return self.element(ctx, r.choice(bufs), BUF_ARRAYS, "Mode", depth)
        if k == 3 and depth < 3:
            call = self.try_call(ctx, "Mode", depth)
            if call:
                return call
        return self.const_expr("Mode", 2)

    def vec_expr(self, ctx, depth):
        r = self.rng
        vs = self.class_vars(ctx, "Vec")
        if depth >= 3 or r.random() < 0.3:
            if vs and r.random() < 0.7:
                return r.choice(vs)
            return r.choice(["Gen::Vec()", "Vec()", "input.ball"])
        k = r.randrange(8)
        if k == 0:
            return f"Gen::Vec({self.float_expr(ctx, depth + 1)}, {self.float_expr(ctx, depth + 1)})"
        if k == 1:
            return f"Vec({self.int_expr(ctx, depth + 1)})"
        if k == 2:
            op = r.choice(["+", "-"])
            return f"({self.vec_expr(ctx, depth + 1)} {op} {self.vec_expr(ctx, depth + 1)})"
        if k == 3:
            return f"({self.vec_expr(ctx, depth + 1)} * {self.float_expr(ctx, depth + 1)})"
        if k == 4:
            return f"(-{self.vec_expr(ctx, depth + 1)})"
        if k == 5:
            bufs = self.class_vars(ctx, "Buf")
            if bufs:
                return self.element(ctx, r.choice(bufs), BUF_ARRAYS, "Vec", depth)
        if k == 6:
            call = self.try_call(ctx, "Vec", depth)
            if call:
                return call
        return self.vec_expr(ctx, 3)

    def expr(self, ctx, ty, depth=0):
        if ty == "int":
            return self.int_expr(ctx, depth)
        if ty == "float":
            return self.float_expr(ctx, depth)
        if ty == "bool":
            return self.bool_expr(ctx, depth)
        if ty == "string":
            return self.string_expr(ctx, depth)
        if ty == "TaskState":
            return self.state_expr(ctx, depth)
        if ty == "Mode":
            return self.mode_expr(ctx, depth)
        if ty == "Vec":
            return self.vec_expr(ctx, depth)
        if ty == "Buf":
            vs = self.class_vars(ctx, "Buf")
            return self.rng.choice(vs) if vs else "Gen::Buf()"
        return self.enum_expr(ctx, ty, depth)

    # ----------------------------------------------------------- statements
    def print_stmt(self, ctx, ind, ty=None):
        r = self.rng
        ty = ty or r.choice(["int", "int", "float", "bool", "string", "TaskState"]
                            + ([f"enum:{r.choice(sorted(self.enums))}"] if self.enums else [])
                            + (["Mode", "Vec"] if self.world else []))
        if ty == "Vec":
            v = self.vec_expr(ctx, 1)
            self.emit(ind, f"io::printf({v}.{r.choice(['x', 'y'])})")
            return
        if ty in ("int", "float", "bool", "string"):
            fn = {"int": "printi", "float": "printf", "bool": "printb", "string": "prints"}[ty]
            self.emit(ind, f"io::{fn}({self.expr(ctx, ty)})")
            return
        self.emit(ind, f"io::printi(int({self.expr(ctx, ty)}))")

    def block(self, ctx, ind, n, parent_scope=None):
        saved = ctx.scope
        ctx.scope = Scope(parent_scope or saved)
        ctx.stmt_depth += 1
        for _ in range(n):
            self.stmt(ctx, ind)
        ctx.stmt_depth -= 1
        ctx.scope = saved

    def task_call(self, ctx, ind, t, force=False):
        if not self.afford(ctx, t, force):
            self.emit(ind, f"io::printi(int(taskState({t.name})))")
            return
        self.emit(ind, f"{t.name}({self.args(ctx, t.params, 0)})")

    def restart_if_ended(self, ctx, ind, t):
        """Calls t again in this cycle if it ended: a restart from the top."""
        if not self.afford(ctx, t):
            return
        test = self.rng.choice([
            f"taskState({t.name}) == TaskState::done || taskState({t.name}) == TaskState::failure",
            f"int(taskState({t.name})) <= 0",
            f"taskState({t.name}) != TaskState::running"])
        self.emit(ind, f"if({test})")
        self.emit(ind + 1, f"{t.name}({self.args(ctx, t.params, 0)})")
        self.emit(ind + 1, f"io::printi(int(taskState({t.name})))")

    def declare_local(self, ctx, ind):
        r = self.rng
        ty = r.choice(self.value_types())
        name = self.fresh("v")
        if r.random() < 0.15 or ty == "Buf":
            self.emit(ind, f"{self.spell(ty)} {name}")
        else:
            self.emit(ind, f"{self.spell(ty)} {name} = {self.expr(ctx, ty)}")
        ctx.scope.vars[name] = (ty, True)

    def assign_stmt(self, ctx, ind):
        """An assignment to a local, a func parameter, a member, an array
        element or a part of `output`; False if nothing fits."""
        r = self.rng
        k = r.randrange(6)
        if self.world and k == 0:
            return self.output_stmt(ctx, ind)
        if self.world and k == 1:
            return self.member_stmt(ctx, ind)
        ty = r.choice(self.value_types())
        vs = self.vars_of(ctx, ty, assignable=True)
        if not vs:
            return False
        v = r.choice(vs)
        if ty == "int":
            op = r.choice(["=", "+=", "-=", "*=", "/=", "%="])
        elif ty == "float":
            op = r.choice(["=", "+=", "-=", "*=", "/="])
        else:
            op = "="
        rhs = self.expr(ctx, ty)
        if op in ("/=", "%=") and r.random() < 0.4:
            rhs = r.choice(["0", "(-1)"])
        self.emit(ind, f"{v} {op} {rhs}")
        return True

    def member_stmt(self, ctx, ind):
        """A field, property or element of a local class value written, or
        a method that modifies it called."""
        r = self.rng
        bufs = self.class_vars(ctx, "Buf", assignable=True)
        vecs = self.class_vars(ctx, "Vec", assignable=True)
        k = r.randrange(4)
        if k == 0 and vecs:
            v = r.choice(vecs)
            if r.random() < 0.3:
                self.emit(ind, f"{v}.flip()")
            else:
                op = r.choice(["=", "+=", "-=", "*=", "/="])
                self.emit(ind, f"{v}.{r.choice(['x', 'y'])} {op} {self.float_expr(ctx, 1)}")
            return True
        if not bufs:
            return False
        b = r.choice(bufs)
        if k == 1:
            op = r.choice(["=", "+=", "-="])
            self.emit(ind, f"{b}.tag {op} {self.int_expr(ctx, 1)}")
            return True
        ty = r.choice(["int", "int", "float", "bool", "Mode", "Vec"])
        target = self.element(ctx, b, BUF_ARRAYS, ty)
        if ty == "Vec" and r.random() < 0.5:
            if r.random() < 0.3:
                self.emit(ind, f"{target}.flip()")
                return True
            target += f".{r.choice(['x', 'y'])}"
            ty = "float"
        op = "="
        if ty == "int":
            op = r.choice(["=", "+=", "-=", "*=", "/=", "%="])
        elif ty == "float":
            op = r.choice(["=", "+=", "-=", "*=", "/="])
        self.emit(ind, f"{target} {op} {self.expr(ctx, ty, 1)}")
        return True

    def output_stmt(self, ctx, ind):
        """`output` is write-only: only `=` to it or to its parts."""
        r = self.rng
        k = r.randrange(5)
        if k == 0:
            self.emit(ind, f"output.target = {self.vec_expr(ctx, 1)}")
        elif k == 1:
            self.emit(ind, f"output.target.{r.choice(['x', 'y'])} = {self.float_expr(ctx, 1)}")
        elif k == 2:
            self.emit(ind, f"output.mode = {self.mode_expr(ctx, 1)}")
        else:
            ty = r.choice(["int", "float"])
            self.emit(ind, f"{self.element(ctx, 'output', OUT_ARRAYS, ty)} = {self.expr(ctx, ty, 1)}")
        return True

    def stmt(self, ctx, ind):
        r = self.rng
        deep = ctx.stmt_depth >= 3
        if self.falsifiable and r.random() < 0.15:
            self.assert_stmt(ctx, ind)
            return
        k = r.randrange(22)
        if k <= 2:
            self.declare_local(ctx, ind)
            return
        if k <= 5:
            if not self.assign_stmt(ctx, ind):
                self.print_stmt(ctx, ind)
            return
        if k <= 8:
            self.print_stmt(ctx, ind)
            return
        if k == 9 and not deep:
            self.emit(ind, f"if({self.bool_expr(ctx, 0)})")
            self.block(ctx, ind + 1, r.randint(1, 3))
            if r.random() < 0.5:
                if r.random() < 0.3:
                    self.emit(ind, f"else if({self.bool_expr(ctx, 0)})")
                    self.block(ctx, ind + 1, r.randint(1, 2))
                self.emit(ind, "else")
                self.block(ctx, ind + 1, r.randint(1, 2))
            return
        if k == 10 and not deep and ctx.loop_depth < 3:
            self.bounded_loop(ctx, ind)
            return
        if k <= 12:
            tasks = [c for c in ctx.callees if c.is_task]
            if tasks:
                t = r.choice(tasks)
                if r.random() < 0.4:
                    self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
                    self.task_call(ctx, ind + 1, t)
                else:
                    self.task_call(ctx, ind, t)
                if r.random() < 0.5:
                    self.emit(ind, f"io::printi(int(taskState({t.name})))")
                if r.random() < 0.25:
                    self.restart_if_ended(ctx, ind, t)
                return
        if k == 13:
            fs = [c for c in ctx.callees if not c.is_task] + ctx.nested
            if fs:
                f = r.choice(fs)
                if self.afford(ctx, f):
                    self.emit(ind, self.call_expr(ctx, f, 0))
                    return
        if k == 14 and ctx.loop_depth > 0:
            self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
            if ctx.loop_depth in ctx.no_continue:
                self.emit(ind + 1, "break")
            else:
                self.emit(ind + 1, r.choice(["break", "continue"]))
            return
        if k == 16 and (ctx.in_task_body or not ctx.owner.ret) and r.random() < 0.3:
            self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
            self.emit(ind + 1, f'io::prints("{ctx.owner.name} returns")')
            self.emit(ind + 1, "return")
            return
        if k == 15 and ctx.in_task_body and not ctx.no_yield:
            y = r.random()
            if y < 0.45:
                self.emit(ind, "yield")
            elif y < 0.55:
                self.emit(ind, f"yield {r.choice(['2', '5', '(-3)', '0'])}")
            elif y < 0.65:
                # A computed state: running, done or failure by value.
                self.emit(ind, f"yield ({self.int_expr(ctx, 2)} % 3)")
            elif y < 0.8:
                self.emit(ind, f"yield {self.state_value()}")
            elif y < 0.87:
                self.emit(ind, f"yield {self.state_expr(ctx, 1)}")
            else:
                self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
                self.emit(ind + 1, f"yield {r.choice(['TaskState::failure', '(-1)', '4', self.state_value()])}")
            return
        if k == 18:
            self.state_oracle(ctx, ind)
            return
        if k == 19 and r.random() < 0.5:
            self.assert_stmt(ctx, ind)
            return
        if k == 17 and self.world:
            # A call as a statement: a const method or a C++ function.
            self.emit(ind, r.choice([f"{self.vec_expr(ctx, 1)}.quad()",
                                     f"Gen::mix({self.int_expr(ctx, 1)})",
                                     f"Gen::poke({self.int_expr(ctx, 1)})"]))
            return
        self.emit(ind, f'io::prints("{ctx.owner.name}:{self.fresh("s")}")')

    def assert_stmt(self, ctx, ind):
        """An assertion that always holds, so that the JIT (which checks
        it and would stop) and objects (which leave it out) agree; its
        condition still computes values of every kind."""
        r = self.rng
        ctx.pure += 1
        k = r.randrange(4 if self.world else 3)
        if k == 3:
            # An assertion may read what the cycle wrote to `output`.
            cond = r.choice(["output.vals[0] == output.vals[0]",
                             "output.mode == output.mode",
                             "output.target.x == output.target.x || true"])
        elif k == 0:
            b = self.bool_expr(ctx, 0)
            cond = f"{b} || !{b}"
        elif k == 1:
            i = self.int_expr(ctx, 0)
            cond = f"{i} == {i}"
        else:
            b = self.bool_expr(ctx, 0)
            cond = f"!({b} && !{b})"
        ctx.pure -= 1
        # An assumption and the assertion it guards: both hold, so runs
        # and objects agree whatever the keyword.
        keyword = "assume" if r.random() < 0.3 else "assert"
        if self.falsifiable and keyword == "assert":
            # The same draws, then a condition that some run breaks.
            ctx.pure += 1
            if r.random() < 0.5:
                cond = f"!({cond}) || {self.int_expr(ctx, 0)} != {r.randint(-2, 2)}"
            else:
                cond = f"!({cond}) || {self.bool_expr(ctx, 0)}"
            ctx.pure -= 1
        if r.random() < 0.5:
            self.emit(ind, f'{keyword}({cond}, "{ctx.owner.name} holds")')
        else:
            self.emit(ind, f"{keyword}({cond})")

    def bounded_loop(self, ctx, ind):
        """A loop of 1 to 4 trips with a counter only it changes, in every
        form a `for` head has (each part present or not)."""
        r = self.rng
        i = self.fresh("i")
        lo, hi = r.randint(-1, 1), r.randint(1, 3)
        scope = Scope(ctx.scope)
        scope.vars[i] = ("int", False)
        counts_in_body = False
        form = r.randrange(6)
        if form == 0:
            self.emit(ind, f"for(int {i} = {hi}; {i} > {lo}; {i} -= 1)")
        elif form == 1:
            # The counter declared before; the init is a call.
            self.emit(ind, f"int {i} = {lo}")
            ctx.scope.vars[i] = ("int", False)
            self.emit(ind, f'for(io::prints("loop {i}"); {i} < {hi}; {i} += 1)')
        elif form == 2:
            # No step: the body counts first.
            self.emit(ind, f"for(int {i} = {lo}; {i} < {hi};)")
            counts_in_body = True
        elif form == 3:
            # The step is a call; the body counts first.
            self.emit(ind, f"for(int {i} = {lo}; {i} < {hi}; io::prints(\"step {i}\"))")
            counts_in_body = True
        elif form == 4:
            # No condition: the body leaves first.
            self.emit(ind, f"for(int {i} = {lo};; {i} += 1)")
            self.emit(ind + 1, f"if({i} >= {hi})")
            self.emit(ind + 2, "break")
        else:
            self.emit(ind, f"for(int {i} = {lo}; {i} < {hi}; {i} += 1)")
        if counts_in_body:
            self.emit(ind + 1, f"{i} += 1")
        ctx.loop_depth += 1
        # bsc counts only `for(int i = A; i < B; i += C)` and its mirror
        # images (docs/language.md): the other forms must not yield.
        counted = form in (0, 5)
        if counts_in_body:
            ctx.no_continue.add(ctx.loop_depth)
        if not counted:
            ctx.no_yield += 1
        saved = ctx.mult
        ctx.mult *= hi - lo
        self.block(ctx, ind + 1, r.randint(1, 4), parent_scope=scope)
        ctx.mult = saved
        ctx.no_continue.discard(ctx.loop_depth)
        if not counted:
            ctx.no_yield -= 1
        ctx.loop_depth -= 1

    # ----------------------------------------------------------- callables
    def params(self, n, allow_class=True):
        """Parameters, the trailing ones sometimes with defaults."""
        out = []
        for _ in range(n):
            tys = [t for t in self.value_types() if allow_class or not self.is_class(t)]
            out.append([self.fresh("p"), self.rng.choice(tys), None])
        for p in reversed(out):
            if self.is_class(p[1]) or self.rng.random() < 0.5:
                break
            p[2] = self.const_expr(p[1], 1)
        return [tuple(p) for p in out]

    def param_list(self, params):
        return ", ".join(f"{self.spell(t)} {p}" + (f" = {d}" if d is not None else "")
                         for p, t, d in params)

    def result_types(self):
        return [None, "int", "float", "bool", "bool"] + self.rng.sample(
            self.value_types(), 2)

    def func_body(self, f, callees, nested, outer_scope, ind):
        scope = Scope(outer_scope)
        for p, t, _ in f.params:
            scope.vars[p] = (t, True)  # func parameters may be assigned
        ctx = Ctx(f, False, callees, nested, scope)
        ctx.stmt_depth = 1
        if f.index == 0 and self.consts:
            self.check_constants(ind)
        if self.rng.random() < 0.3:
            self.emit(ind, f'io::prints("{f.name}")')
        for c in f.must:
            if c.is_task:
                self.task_call(ctx, ind, c, force=True)
            else:
                self.afford(ctx, c, force=True)
                self.emit(ind, self.call_expr(ctx, c, 0))
        for _ in range(self.rng.randint(1, 4)):
            self.stmt(ctx, ind)
        if f.ret:
            if self.rng.random() < 0.3:
                self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
                self.emit(ind + 1, f"return {self.expr(ctx, f.ret)}")
            self.emit(ind, f"return {self.expr(ctx, f.ret)}")

    def nested_func(self, t, callees, scope):
        """A func nested in t; it sees scope (the task's parameters and
        the locals declared so far)."""
        r = self.rng
        ret = r.choice(self.result_types())
        nf = Callable(-1, self.fresh(f"{t.name}_f"), False,
                      self.params(r.randint(0, 2)), ret)
        head = f"func {nf.name}({self.param_list(nf.params)})" + \
            (f" : {self.spell(nf.ret)}" if nf.ret else "")
        self.emit(1, head)
        # A nested func calls only later top-level callables; it may update
        # the task's locals.
        self.func_body(nf, callees, [], scope, 2)
        t.nested.append(nf)
        return nf

    def task_body(self, t, callees):
        r = self.rng
        scope = Scope()
        for p, ty, _ in t.params:
            scope.vars[p] = (ty, False)  # task parameters are read-only
        ctx = Ctx(t, True, callees, [], scope)
        # Top-level locals kept across yields, then nested funcs that see them.
        n = self.fresh("n")
        self.emit(1, f"int {n} = 0")
        scope.vars[n] = ("int", False)  # only the cycle loop changes it
        if t.index == 0 and self.consts:
            self.check_constants(1)
        for _ in range(r.randint(1, 3)):
            ty = r.choice(self.value_types())
            v = self.fresh("l")
            if ty == "Buf":
                self.emit(1, f"{self.spell(ty)} {v}")
            else:
                self.emit(1, f"{self.spell(ty)} {v} = {self.expr(ctx, ty)}")
            scope.vars[v] = (ty, True)
        for _ in range(r.randint(0, 2)):
            self.nested_func(t, callees, scope)
        ctx.nested = list(t.nested)
        ctx.stmt_depth = 1
        self.emit(1, f'io::prints("{t.name} start")')
        if r.random() < 0.4:
            self.late_local(t, ctx, callees)
        for _ in range(r.randint(1, 3)):
            self.stmt(ctx, 1)
        if r.random() < 0.7:
            self.emit(1, "yield")
        for _ in range(r.randint(0, 2)):
            self.stmt(ctx, 1)
        # The cycle loop: counts calls, calls children on some cycles only.
        # It yields in its step, or at the end of its body (which then must
        # not `continue`, or a pass could skip the yield).
        bound = r.randint(2, 7)
        limit = r.choice(["true", f"{n} < {bound}"])
        form = r.randrange(3)
        if form == 0:
            self.emit(1, f"for(; {limit}; yield)")
        elif form == 1:
            self.emit(1, f"for({n} = 0; {limit}; yield)")
        else:
            self.emit(1, "for(;;)")
            if limit != "true":
                self.emit(2, f"if({n} >= {bound})")
                self.emit(3, "break")
            ctx.no_continue.add(1)
        self.emit(2, f"{n} += 1")
        self.emit(2, f"io::printi({n})")
        tasks = [c for c in callees if c.is_task and c not in t.must]
        for c in t.must + r.sample(tasks, min(len(tasks), r.randint(0, 1))):
            if r.random() < 0.6:
                # Skipped cycles reset a running child.
                self.emit(2, f"if({n} % {r.randint(2, 4)} != {r.randint(0, 1)})")
                ind = 3
            else:
                ind = 2
            if c.is_task:
                self.task_call(ctx, ind, c, force=True)
                self.emit(2, f"io::printi(int(taskState({c.name})))")
            else:
                self.afford(ctx, c, force=True)
                self.emit(ind, self.call_expr(ctx, c, 0))
        ctx.stmt_depth = 2
        ctx.loop_depth = 1
        self.block(ctx, 2, r.randint(2, 5))
        if form == 2:
            self.emit(2, "yield")
        ctx.no_continue.discard(1)
        ctx.loop_depth = 0
        end = r.random()
        if end < 0.3:
            self.emit(1, "yield TaskState::failure")
        elif end < 0.5:
            self.emit(1, f"yield {r.choice(['(-7)', '3', '0', self.state_value()])}")
        self.emit(1, f'io::prints("{t.name} end")')
        if end >= 0.5 and end < 0.6:
            self.emit(1, "return")

    def late_local(self, t, ctx, callees):
        """A local that a nested func reads, called before the local's
        declaration (and in its initializer): it reads the reset's zero."""
        r = self.rng
        late = self.fresh("late")
        ty = r.choice(["int", "int", "float", "bool"])
        peek = f"{t.name}_peek{self.counter}"
        read = {"int": late, "float": f"int({late})", "bool": f"int({late})"}[ty]
        self.emit(1, f"io::printi({peek}())")
        init = self.expr(ctx, ty, 1)
        if ty == "int" and r.random() < 0.5:
            init = f"{peek}() + {init}"
        self.emit(1, f"{ty} {late} = {init}")
        ctx.scope.vars[late] = (ty, True)
        nf = Callable(-1, peek, False, [], "int")
        self.emit(1, f"func {peek}() : int")
        self.emit(2, f"return {read}")
        t.nested.append(nf)
        ctx.nested.append(nf)

    def program(self):
        r = self.rng
        self.world = r.random() < 0.6
        count = r.randint(3, 7)
        self.emit(0, "# generated by utils/gen-program.py")
        self.emit(0, 'requires "io"')
        if self.world and r.random() < 0.5:
            self.emit(0, 'requires "Gen"')
        self.emit(0, "")
        self.declare_types_and_constants()
        callables = []
        for i in range(count):
            if i == 0:
                is_task = r.random() < 0.6
                c = Callable(0, "main", is_task, [], None)
            else:
                is_task = r.random() < 0.55
                name = self.fresh("t" if is_task else "f")
                ret = None if is_task else r.choice(self.result_types())
                c = Callable(i, name, is_task, self.params(r.randint(0, 3)), ret)
            callables.append(c)
        # Every callable but main has a caller above it.
        for j in range(1, count):
            callables[r.randrange(j)].must.append(callables[j])
        self.tasks = [c for c in callables if c.is_task]
        # Leaves first, so that a reader meets callees before callers.
        for c in reversed(callables):
            self.emit(0, "")
            callees = callables[c.index + 1:]
            ps = self.param_list(c.params)
            if c.is_task:
                self.emit(0, f"task {c.name}({ps})")
                self.task_body(c, callees)
            else:
                self.emit(0, f"func {c.name}({ps})" +
                          (f" : {self.spell(c.ret)}" if c.ret else ""))
                self.func_body(c, callees, [], None, 1)
        return "\n".join(self.lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("seed", type=int)
    ap.add_argument("--falsifiable", action="store_true",
                    help="assertions that can fail (for bsc verify)")
    args = ap.parse_args()
    sys.stdout.write(Gen(args.seed, args.falsifiable).program())


if __name__ == "__main__":
    main()

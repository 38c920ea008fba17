#!/usr/bin/env python3
"""Prints a random, well-typed b-script program for differential testing.

usage: gen-program.py SEED [--cycles N]

The program depends only on SEED (Python's own `random.Random`, no hash
randomisation, no clock), so a failing seed reproduces anywhere. It requires
"io" and prints what it computes, so that `utils/diff-test.py` can compare
the output of several configurations of bsc (JIT and programs, -O0 and -O2,
host and i586).

What a program exercises (docs/language.md):
- several tasks with `yield`, `yield <int>` (also 0 and negative: done and
  failure), `yield TaskState::failure` and `return`; locals kept across
  yields; task parameters (read-only, re-evaluated at each call);
- nested task calls and func calls, top-level funcs and funcs nested in
  tasks (which read the task's parameters and locals). The call graph is
  acyclic by construction: callable i calls only callables j > i, and the
  entry `main` (a task or a func without parameters) is callable 0;
- `taskState(T)` comparisons and implicit resets: parents call children on
  some cycles only (`if(n % 3 != 0)`), and several times in one cycle;
- int, float and bool values; int `/` and `%` by zero and `INT_MIN / -1`,
  wrapping `+ - *`, `int(float)` of huge, infinite and NaN values;
- `&&` and `||` whose right operand calls a func that prints;
- bounded `for` loops (a counter only the step changes) with `break` and
  `continue`, and `for(...; yield)` loops in tasks.
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
INT_OPS = ["+", "-", "*", "/", "%"]
FLOAT_OPS = ["+", "-", "*", "/"]
CMP_OPS = ["<", "<=", ">", ">=", "==", "!="]
STATES = ["TaskState::done", "TaskState::running", "TaskState::failure"]
# An upper bound of the work of one call of a callable (statements run,
# counting the callees' work and loop trips), so that the output of a
# program stays small: calls that would exceed it are not generated.
BUDGET = 400


class Callable:
    def __init__(self, index, name, is_task, params, ret):
        self.index = index
        self.name = name
        self.is_task = is_task
        self.params = params  # [(name, type)]
        self.ret = ret        # None, "int", "float", "bool" (funcs only)
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
        self.stmt_depth = 0
        self.mult = 1                   # loop trips around the current point


class Gen:
    def __init__(self, seed):
        self.rng = random.Random(seed)
        self.counter = 0
        self.lines = []
        self.tasks = []

    def fresh(self, prefix):
        self.counter += 1
        return f"{prefix}{self.counter}"

    def emit(self, indent, text):
        self.lines.append("    " * indent + text)

    # ---------------------------------------------------------------- exprs
    def vars_of(self, ctx, ty, assignable=False):
        return sorted(n for n, (t, a) in ctx.scope.all().items()
                      if t == ty and (a or not assignable))

    def value_callees(self, ctx, ty):
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

    def call_expr(self, ctx, f, depth):
        args = ", ".join(self.expr(ctx, t, depth + 1) for _, t in f.params)
        return f"{f.name}({args})"

    def int_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.3
        if leaf:
            vs = self.vars_of(ctx, "int")
            if vs and r.random() < 0.65:
                return r.choice(vs)
            return r.choice(INT_LITS)
        k = r.randrange(12)
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
            fs = self.value_callees(ctx, "int")
            if fs:
                f = r.choice(fs)
                if self.afford(ctx, f):
                    return self.call_expr(ctx, f, depth)
        if k == 10:
            # Overflow on purpose.
            return f"({self.int_expr(ctx, depth + 1)} * 65537 + 2147483000)"
        return self.int_expr(ctx, 3)

    def float_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.3
        if leaf:
            vs = self.vars_of(ctx, "float")
            if vs and r.random() < 0.6:
                return r.choice(vs)
            return r.choice(FLOAT_LITS)
        k = r.randrange(9)
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
            return f"float({self.int_expr(ctx, depth + 1)})"
        if k == 6:
            fs = self.value_callees(ctx, "float")
            if fs:
                f = r.choice(fs)
                if self.afford(ctx, f):
                    return self.call_expr(ctx, f, depth)
        if k == 7:
            # An int where a float is expected converts implicitly.
            return self.int_expr(ctx, depth + 1)
        return self.float_expr(ctx, 3)

    def bool_expr(self, ctx, depth):
        r = self.rng
        leaf = depth >= 3 or r.random() < 0.2
        if leaf:
            vs = self.vars_of(ctx, "bool")
            if vs and r.random() < 0.5:
                return r.choice(vs)
            if r.random() < 0.3:
                return r.choice(["true", "false"])
            return f"({self.int_expr(ctx, 3)} {r.choice(CMP_OPS)} {self.int_expr(ctx, 3)})"
        k = r.randrange(10)
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
        if k == 6 and self.tasks:
            t = r.choice(self.tasks)
            return f"(taskState({t.name}) {r.choice(['==', '!='])} {r.choice(STATES)})"
        if k == 7 and self.tasks:
            t = r.choice(self.tasks)
            return f"(int(taskState({t.name})) {r.choice(CMP_OPS)} {r.choice(['0', '1', '-1', '3'])})"
        if k == 8:
            fs = self.value_callees(ctx, "bool")
            if fs:
                f = r.choice(fs)
                if self.afford(ctx, f):
                    return self.call_expr(ctx, f, depth)
        return f"({self.bool_expr(ctx, depth + 1)} {r.choice(['==', '!='])} {self.bool_expr(ctx, depth + 1)})"

    def expr(self, ctx, ty, depth=0):
        if ty == "int":
            return self.int_expr(ctx, depth)
        if ty == "float":
            return self.float_expr(ctx, depth)
        return self.bool_expr(ctx, depth)

    # ----------------------------------------------------------- statements
    def print_stmt(self, ctx, ind, ty=None):
        ty = ty or self.rng.choice(["int", "int", "float", "bool"])
        fn = {"int": "printi", "float": "printf", "bool": "printb"}[ty]
        self.emit(ind, f"io::{fn}({self.expr(ctx, ty)})")

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
        args = ", ".join(self.expr(ctx, ty, 1) for _, ty in t.params)
        self.emit(ind, f"{t.name}({args})")

    def stmt(self, ctx, ind):
        r = self.rng
        deep = ctx.stmt_depth >= 3
        k = r.randrange(20)
        if k <= 2:
            ty = r.choice(["int", "int", "float", "bool"])
            name = self.fresh("v")
            if r.random() < 0.15:
                self.emit(ind, f"{ty} {name}")
            else:
                self.emit(ind, f"{ty} {name} = {self.expr(ctx, ty)}")
            ctx.scope.vars[name] = (ty, True)
            return
        if k <= 5:
            ty = r.choice(["int", "int", "float", "bool"])
            vs = self.vars_of(ctx, ty, assignable=True)
            if vs:
                v = r.choice(vs)
                if ty == "bool":
                    op = "="
                elif ty == "int":
                    op = r.choice(["=", "+=", "-=", "*=", "/=", "%="])
                else:
                    op = r.choice(["=", "+=", "-=", "*=", "/="])
                rhs = self.expr(ctx, ty)
                if op in ("/=", "%=") and r.random() < 0.4:
                    rhs = r.choice(["0", "(-1)"])
                self.emit(ind, f"{v} {op} {rhs}")
                return
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
            self.emit(ind + 1, r.choice(["break", "continue"]))
            return
        if k == 16 and ctx.in_task_body and r.random() < 0.3:
            self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
            self.emit(ind + 1, f'io::prints("{ctx.owner.name} returns")')
            self.emit(ind + 1, "return")
            return
        if k == 15 and ctx.in_task_body:
            y = r.random()
            if y < 0.5:
                self.emit(ind, "yield")
            elif y < 0.6:
                self.emit(ind, f"yield {r.choice(['2', '5', '(-3)', '0'])}")
            elif y < 0.7:
                # A computed state: running, done or failure by value.
                self.emit(ind, f"yield ({self.int_expr(ctx, 2)} % 3)")
            elif y < 0.8:
                self.emit(ind, f"yield {r.choice(STATES)}")
            else:
                self.emit(ind, f"if({self.bool_expr(ctx, 1)})")
                self.emit(ind + 1, f"yield {r.choice(['TaskState::failure', '(-1)', '4'])}")
            return
        self.emit(ind, f'io::prints("{ctx.owner.name}:{self.fresh("s")}")')

    def bounded_loop(self, ctx, ind):
        r = self.rng
        i = self.fresh("i")
        lo, hi = r.randint(-1, 1), r.randint(1, 3)
        self.emit(ind, f"for(int {i} = {lo}; {i} < {hi}; {i} += 1)")
        scope = Scope(ctx.scope)
        scope.vars[i] = ("int", False)
        ctx.loop_depth += 1
        saved = ctx.mult
        ctx.mult *= hi - lo
        self.block(ctx, ind + 1, r.randint(1, 4), parent_scope=scope)
        ctx.mult = saved
        ctx.loop_depth -= 1

    # ----------------------------------------------------------- callables
    def params(self, n):
        return [(self.fresh("p"), self.rng.choice(["int", "int", "float", "bool"]))
                for _ in range(n)]

    def func_body(self, f, callees, nested, outer_scope, ind):
        scope = Scope(outer_scope)
        for p, t in f.params:
            scope.vars[p] = (t, True)  # func parameters may be assigned
        ctx = Ctx(f, False, callees, nested, scope)
        ctx.stmt_depth = 1
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

    def task_body(self, t, callees):
        r = self.rng
        scope = Scope()
        for p, ty in t.params:
            scope.vars[p] = (ty, False)  # task parameters are read-only
        ctx = Ctx(t, True, callees, [], scope)
        # Top-level locals kept across yields, then nested funcs that see them.
        n = self.fresh("n")
        self.emit(1, f"int {n} = 0")
        scope.vars[n] = ("int", False)  # only the cycle loop changes it
        for _ in range(r.randint(1, 3)):
            ty = r.choice(["int", "float", "bool"])
            v = self.fresh("l")
            self.emit(1, f"{ty} {v} = {self.expr(ctx, ty)}")
            scope.vars[v] = (ty, True)
        for _ in range(r.randint(0, 2)):
            nf = Callable(-1, self.fresh(f"{t.name}_f"), False,
                          self.params(r.randint(0, 2)),
                          r.choice([None, "int", "float", "bool"]))
            ps = ", ".join(f"{ty} {p}" for p, ty in nf.params)
            head = f"func {nf.name}({ps})" + (f" : {nf.ret}" if nf.ret else "")
            self.emit(1, head)
            # A nested func calls only later top-level callables; it may
            # update the task's locals.
            self.func_body(nf, callees, [], scope, 2)
            t.nested.append(nf)
        ctx.nested = list(t.nested)
        ctx.stmt_depth = 1
        self.emit(1, f'io::prints("{t.name} start")')
        for _ in range(r.randint(1, 3)):
            self.stmt(ctx, 1)
        if r.random() < 0.7:
            self.emit(1, "yield")
        for _ in range(r.randint(0, 2)):
            self.stmt(ctx, 1)
        # The cycle loop: counts calls, calls children on some cycles only.
        limit = r.choice(["true", f"{n} < {r.randint(2, 7)}"])
        self.emit(1, f"for(; {limit}; yield)")
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
        ctx.loop_depth = 0
        end = r.random()
        if end < 0.3:
            self.emit(1, "yield TaskState::failure")
        elif end < 0.5:
            self.emit(1, f"yield {r.choice(['(-7)', '3', '0'])}")
        self.emit(1, f'io::prints("{t.name} end")')
        if end >= 0.5 and end < 0.6:
            self.emit(1, "return")

    def program(self):
        r = self.rng
        count = r.randint(3, 7)
        callables = []
        for i in range(count):
            if i == 0:
                is_task = r.random() < 0.6
                c = Callable(0, "main", is_task, [], None)
            else:
                is_task = r.random() < 0.55
                name = self.fresh("t" if is_task else "f")
                ret = None if is_task else r.choice([None, "int", "float", "bool", "bool"])
                c = Callable(i, name, is_task, self.params(r.randint(0, 3)), ret)
            callables.append(c)
        # Every callable but main has a caller above it.
        for j in range(1, count):
            callables[r.randrange(j)].must.append(callables[j])
        self.tasks = [c for c in callables if c.is_task]
        self.emit(0, f"# generated by utils/gen-program.py")
        self.emit(0, 'requires "io"')
        # Leaves first, so that a reader meets callees before callers.
        for c in reversed(callables):
            self.emit(0, "")
            callees = callables[c.index + 1:]
            ps = ", ".join(f"{ty} {p}" for p, ty in c.params)
            if c.is_task:
                self.emit(0, f"task {c.name}({ps})")
                self.task_body(c, callees)
            else:
                self.emit(0, f"func {c.name}({ps})" + (f" : {c.ret}" if c.ret else ""))
                self.func_body(c, callees, [], None, 1)
        return "\n".join(self.lines) + "\n"


def main():
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("seed", type=int)
    args = ap.parse_args()
    sys.stdout.write(Gen(args.seed).program())


if __name__ == "__main__":
    main()

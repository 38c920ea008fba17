#!/usr/bin/env python3
"""Writes a large behavior for the compile-time and REPL benchmarks.

    gen-behavior.py UNITS > Big.bs

Each unit is 26 lines: a helper func, a child task with three phases, and
a parent task that drives it, as behaviors do; `main` calls every parent.
100 units make about 2,600 lines.
"""
import sys

UNIT = '''func clamp{i}(int v, int lo, int hi) : int
    if(v < lo)
        return lo
    if(v > hi)
        return hi
    return v

task child{i}(int limit)
    int n = 0
    for(; n < limit; yield)
        n += 1
    yield
    for(int k = 0; k < 2; yield)
        k += 1

task parent{i}()
    int rounds = 0
    float speed = 0.5
    for(; true; yield)
        child{i}(clamp{i}(rounds + {i} % 7, 2, 6))
        if(taskState(child{i}) == TaskState::done)
            rounds += 1
            speed = speed * 1.5
        if(speed > 100.0)
            speed = 0.5

'''


def main(argv):
    if len(argv) != 2 or not argv[1].isdigit():
        sys.stderr.write(__doc__)
        return 2
    units = int(argv[1])
    out = [UNIT.format(i=i) for i in range(units)]
    out.append('func main()\n')
    out += ['    parent%d()\n' % i for i in range(units)]
    sys.stdout.write(''.join(out))
    return 0


if __name__ == '__main__':
    sys.exit(main(sys.argv))

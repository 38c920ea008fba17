#!/usr/bin/env python3
"""Writes the program of task-widths.test: tasks whose resume points and
states need 1, 2 or 4 bytes (bscript.h bs_task_info)."""
print('''requires "io"

# States at the edges of a byte, and past them.
task edge()
    yield 127
    yield -128

task far()
    yield 1000
    yield -129

# 300 yields: a resume point of 2 bytes.
task many()''')
for k in range(1, 301):
    print('    yield')
    if k in (254, 255, 256, 257):
        print('    io::printi(%d)' % k)
print('''    io::printi(300)

func main()
    for(int c = 0; c < 3; c += 1)
        edge()
        io::printi(int(taskState(edge)))
        far()
        io::printi(int(taskState(far)))
    for(int c = 0; c < 302; c += 1)
        many()
    io::printi(int(taskState(many)))''')

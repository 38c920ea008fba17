#!/usr/bin/env python3
"""Holds a conversation with `bsc repl` through a pipe, for tests that must
change files while the REPL runs (`:reload`).

    repl-driver.py SCRIPT -- BSC repl [options] FILE.bs...

SCRIPT has one REPL line per line, plus directives that the driver runs
itself once the REPL has answered every line before them:
    !replace FILE OLD NEW    replace the first OLD by NEW in FILE
(`\\n` in OLD and NEW stands for a newline). The REPL's standard output and
error are passed through in order.
"""
import subprocess
import sys


def main(argv):
    if '--' not in argv or argv.index('--') != 2:
        sys.stderr.write(__doc__)
        return 2
    script, command = argv[1], argv[3:]
    proc = subprocess.Popen(command, stdin=subprocess.PIPE,
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                            text=True, bufsize=1)
    sync = 0

    def wait_for_answers():
        # A string the REPL echoes back marks that it answered everything
        # sent before it.
        nonlocal sync
        sync += 1
        marker = '"sync %d"' % sync
        proc.stdin.write(marker + '\n')
        proc.stdin.flush()
        for line in proc.stdout:
            if line.rstrip('\n') == '(string) ' + marker:
                return
            sys.stdout.write(line)
        raise SystemExit('repl-driver: the REPL ended before answering')

    with open(script) as f:
        for line in f:
            line = line.rstrip('\n')
            if line.startswith('!replace '):
                wait_for_answers()
                _, path, old, new = line.split(' ', 3)
                old = old.replace('\\n', '\n').replace('\\s', ' ')
                new = new.replace('\\n', '\n').replace('\\s', ' ')
                with open(path) as src:
                    text = src.read()
                if old not in text:
                    raise SystemExit('repl-driver: %r not in %s' % (old, path))
                with open(path, 'w') as dst:
                    dst.write(text.replace(old, new, 1))
                continue
            proc.stdin.write(line + '\n')
            proc.stdin.flush()
    proc.stdin.close()
    for line in proc.stdout:
        sys.stdout.write(line)
    return proc.wait()


if __name__ == '__main__':
    sys.exit(main(sys.argv))

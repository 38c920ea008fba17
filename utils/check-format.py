#!/usr/bin/env python3
"""Checks `bsc format` on every .bs file under the given folders.

For each file that parses, the formatted text must
  - format to itself again (the layout is idempotent),
  - have the same syntax tree as the file (`bsc --emit=ast`, positions
    left out),
  - and, with --in-layout, be the file itself (the folder is formatted).
A file with syntax errors must be refused: `bsc format` reports an error
and exits 1, and the parser agrees that the file has one. Anything else
(a crash, a hang, a changed tree) is a failure. Prints one line per
failure and a summary; exits 1 on any failure.
"""
import argparse
import os
import re
import subprocess
import sys
import tempfile

SKIP_DIRS = {'.git', 'node_modules'}
POSITION = re.compile(r' <\d+:\d+>')


def bs_files(roots):
    for root in roots:
        for dirpath, dirs, files in os.walk(root):
            dirs[:] = sorted(d for d in dirs
                             if d not in SKIP_DIRS and not d.startswith('build'))
            for name in sorted(files):
                if name.endswith('.bs'):
                    yield os.path.join(dirpath, name)


def run(cmd):
    return subprocess.run(cmd, capture_output=True, timeout=60)


def first_module_tree(bsc, path):
    """The syntax tree of the file's own module, without positions."""
    out = run([bsc, '--emit=ast', path]).stdout.decode('utf-8', 'replace')
    lines = []
    for line in out.splitlines():
        if line.startswith('Module ') and lines:
            break
        lines.append(POSITION.sub('', line))
    return lines


def check(bsc, path, in_layout, tmp):
    """Returns (kind, problem): kind is 'formatted' or 'refused'."""
    original = open(path, 'rb').read()
    first = run([bsc, 'format', path])
    if first.returncode != 0:
        err = first.stderr.decode('utf-8', 'replace')
        if first.returncode != 1 or 'error:' not in err:
            return 'refused', f'exit status {first.returncode}: {err[:300]}'
        if run([bsc, '--emit=ast', path]).returncode == 0:
            return 'refused', 'refused a file the parser accepts: ' + err[:300]
        return 'refused', None
    # The copy has the file's name, so that its module name is the same.
    copy = os.path.join(tmp, os.path.basename(path))
    with open(copy, 'wb') as f:
        f.write(first.stdout)
    second = run([bsc, 'format', copy])
    if second.returncode != 0 or second.stdout != first.stdout:
        return 'formatted', 'formatting the formatted text changes it again'
    if first_module_tree(bsc, path) != first_module_tree(bsc, copy):
        return 'formatted', 'the formatted text has another syntax tree'
    if in_layout and first.stdout != original:
        return 'formatted', 'not in the layout: run bsc format -i on it'
    return 'formatted', None


def main():
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--bsc', required=True)
    p.add_argument('--in-layout', action='store_true',
                   help='the files must already be formatted')
    p.add_argument('--not-in-layout', action='append', default=[],
                   metavar='FILE', help='a file left out of the layout on '
                   'purpose (a test input); checked for all else')
    p.add_argument('roots', nargs='+')
    args = p.parse_args()
    counts = {'formatted': 0, 'refused': 0}
    failures = 0
    with tempfile.TemporaryDirectory() as tmp:
        for path in bs_files(args.roots):
            try:
                in_layout = args.in_layout and not any(
                    os.path.samefile(path, f) for f in args.not_in_layout)
                kind, problem = check(args.bsc, path, in_layout, tmp)
            except subprocess.TimeoutExpired:
                kind, problem = 'formatted', 'bsc took more than 60 s'
            counts[kind] += 1
            if problem:
                failures += 1
                print(f'{path}: {problem}')
    total = counts['formatted'] + counts['refused']
    print(f'{total} files: {counts["formatted"]} formatted, '
          f'{counts["refused"]} refused for syntax errors, {failures} failed')
    sys.exit(1 if failures or not total else 0)


if __name__ == '__main__':
    main()

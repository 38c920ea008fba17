#!/usr/bin/env python3
"""Fails if a diagnostic kind of DiagnosticKinds.def has no test.

A kind is covered when some file under the test folder spells out a whole
message of that kind: an `expected-<severity> {{...}}` text or a FileCheck
line (of any check prefix) containing `<severity>: <message>`. Arguments (%0, %1, ...) match any
text (an argument may be empty). This keeps the table and the tests from drifting apart (Carbon's rule:
every diagnostic kind has a test).
"""
import os
import re
import sys

def kinds(def_path):
    pat = re.compile(r'^DIAG\((\w+),\s*(\w+),\s*"((?:[^"\\]|\\.)*)"\)', re.M)
    for ident, sev, fmt in pat.findall(open(def_path).read()):
        fmt = fmt.encode().decode('unicode_escape')
        yield ident, sev.lower(), fmt

def message_regex(fmt):
    parts = re.split(r'%\d', fmt)
    return re.compile('^' + '.*?'.join(re.escape(p) for p in parts) + '$')

def spelled_messages(test_root):
    expected = re.compile(r'expected-(error|warning|note)(?:@[+-]\d+)?\s*\{\{(.*?)\}\}')
    checked = re.compile(r'(error|warning|note): (.*?)\s*$')
    found = []
    for dirpath, _, files in os.walk(test_root):
        for name in files:
            try:
                text = open(os.path.join(dirpath, name), encoding='utf-8',
                            errors='replace').read()
            except OSError:
                continue
            for line in text.splitlines():
                for sev, msg in expected.findall(line):
                    found.append((sev, msg))
                # FileCheck lines of any prefix (CHECK:, DUP:, ...).
                m = checked.search(line)
                if m:
                    found.append((m.group(1), m.group(2)))
    return found

def main():
    if len(sys.argv) != 3:
        sys.exit('usage: check-diagnostic-coverage.py DiagnosticKinds.def TEST_DIR')
    def_path, test_root = sys.argv[1], sys.argv[2]
    found = spelled_messages(test_root)
    missing = []
    for ident, sev, fmt in kinds(def_path):
        rx = message_regex(fmt)
        if not any(s == sev and rx.match(m) for s, m in found):
            missing.append(f'{ident}: "{fmt}"')
    for m in missing:
        print('untested diagnostic kind', m)
    print(f'{len(missing)} untested diagnostic kinds')
    return 1 if missing else 0

if __name__ == '__main__':
    sys.exit(main())

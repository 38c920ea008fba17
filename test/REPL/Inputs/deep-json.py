#!/usr/bin/env python3
"""Writes the deeply nested replay files of replay-bad-json.test into DIR.

usage: deep-json.py DIR
"""
import os
import sys

DEEP = 100000
CASES = {
    # The line that crashed bsc (SIGSEGV in llvm::json's parser).
    'brackets': '[' * DEEP,
    # A good line, then objects nested 100,000 deep.
    'objects': '{"input":{"time":1}}\n{"input":' + '{"a":' * DEEP,
    # 256 levels in all, closed: read; 257: refused.
    'at-limit': '{"input":{"time":' + '[' * 254 + '1' + ']' * 254 + '}}',
    'past-limit': '{"input":{"time":' + '[' * 255 + '1' + ']' * 255 + '}}',
    # Brackets in strings, also after an escaped quote, are not nesting.
    'in-string': '{"cycle":"' + '[' * DEEP + '","input":{"time":1}}\n'
                 '{"cycle":"\\"' + '{' * DEEP + '"}',
    # An escaped backslash ends the string; the brackets after it count.
    'after-backslash': '{"cycle":"\\\\","input":' + '[' * 300,
}

for name, text in CASES.items():
    with open(os.path.join(sys.argv[1], name + '.jsonl'), 'w') as f:
        f.write(text + '\n')

#!/usr/bin/env python3
"""Prints one closing line for the whole suite: `N passed, N failed`.

ctest counts each GoogleTest case and the lit suite as one test each; the
lit suite's own JUnit file breaks that one test down. The line counts unit
tests and lit tests individually (lit's UNSUPPORTED are reported as skipped).
"""
import sys
import xml.etree.ElementTree as ET

def count(path, skip_name=None):
    passed = failed = skipped = 0
    try:
        root = ET.parse(path).getroot()
    except (OSError, ET.ParseError):
        return None
    for case in root.iter('testcase'):
        if skip_name and case.get('name') == skip_name:
            continue
        if case.find('failure') is not None or case.find('error') is not None:
            failed += 1
        elif case.find('skipped') is not None:
            skipped += 1
        else:
            passed += 1
    return passed, failed, skipped

if len(sys.argv) != 3:
    sys.exit('usage: summarize-tests.py CTEST_JUNIT.xml LIT_JUNIT.xml')
ctest = count(sys.argv[1], skip_name='lit')
lit = count(sys.argv[2])
if ctest is None or lit is None:
    print('tests: results missing (the build or the suite did not run)')
    print('0 passed, 1 failed')
    sys.exit(1)
p, f, s = (a + b for a, b in zip(ctest, lit))
print(f'unit tests: {ctest[0]} passed, {ctest[1]} failed; '
      f'lit tests: {lit[0]} passed, {lit[1]} failed, {lit[2]} unsupported')
print(f'{p} passed, {f} failed, {s} skipped')

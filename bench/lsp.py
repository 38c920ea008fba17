#!/usr/bin/env python3
"""The language server's latency on a large behavior (issue 28's goals).

    bench/lsp.py [BUILD_DIR] [UNITS]

Generates a behavior of UNITS units (gen-behavior.py; 104 units are 2,700
lines), opens it in `bsc lsp`, and measures, each over 30 rounds:
  - edit -> diagnostics: an edit of one line until the server publishes
    the diagnostics of that version (the debounce included); goal 100 ms;
  - hover and completion: request to answer; goal 50 ms each.
The reference measured in the same run is `bsc --emit=ast` of the same file
from the command line (a process start and the front end), the best of 5.
Prints the median and the worst of each; exits 1 if a median misses its goal.
"""
import os
import statistics
import subprocess
import sys
import tempfile
import time

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, os.path.join(HERE, '..', 'utils'))
lsp_client = __import__('lsp-client')


def main():
    build = os.path.abspath(sys.argv[1] if len(sys.argv) > 1 else
                            os.path.join(HERE, '..', 'build'))
    units = int(sys.argv[2]) if len(sys.argv) > 2 else 104
    bsc = os.path.join(build, 'bin', 'bsc')
    with tempfile.TemporaryDirectory() as tmp:
        path = os.path.join(tmp, 'Big.bs')
        with open(path, 'w') as f:
            subprocess.run([sys.executable, os.path.join(HERE, 'gen-behavior.py'),
                            str(units)], stdout=f, check=True)
        lines = open(path).read().split('\n')
        print('behavior: %d lines (%d units)' % (len(lines), units))

        reference = []
        for _ in range(5):
            start = time.perf_counter()
            subprocess.run([bsc, '--emit=ast', path], stdout=subprocess.DEVNULL,
                           check=True)
            reference.append((time.perf_counter() - start) * 1000)
        print('reference: bsc --emit=ast from the command line %.1f ms'
              % min(reference))

        c = lsp_client.Client([bsc, 'lsp'], tmp, 30)
        c.request('initialize', {'processId': os.getpid(),
                                 'rootUri': 'file://' + tmp,
                                 'capabilities': {}})
        c.notify('initialized', {})
        c.versions['Big.bs'] = 1
        c.notify('textDocument/didOpen', {'textDocument': {
            'uri': c.uri('Big.bs'), 'languageId': 'bscript', 'version': 1,
            'text': '\n'.join(lines)}})
        uri = c.uri('Big.bs')

        def diagnostics_of(version):
            return c.wait_for(
                lambda m: m.get('method') == 'textDocument/publishDiagnostics'
                and m['params']['uri'] == uri
                and m['params'].get('version') == version)

        diagnostics_of(1)
        # The line `        rounds += 1` of the last unit: edited back and
        # forth between two values.
        target = max(i for i, l in enumerate(lines) if 'rounds += 1' in l)
        column = lines[target].index('1')
        edits, hovers, completions = [], [], []
        for n in range(30):
            start = time.perf_counter()
            c.change('Big.bs', [{'range': {
                'start': {'line': target, 'character': column},
                'end': {'line': target, 'character': column + 1}},
                'text': '2' if n % 2 == 0 else '1'}])
            if diagnostics_of(c.versions['Big.bs']) is None:
                sys.exit('lsp.py: no diagnostics after an edit')
            edits.append((time.perf_counter() - start) * 1000)

            pos = {'line': target, 'character': column - 4}  # `rounds`
            start = time.perf_counter()
            c.request('textDocument/hover', {'textDocument': {'uri': uri},
                                             'position': pos})
            hovers.append((time.perf_counter() - start) * 1000)
            start = time.perf_counter()
            c.request('textDocument/completion',
                      {'textDocument': {'uri': uri}, 'position': pos})
            completions.append((time.perf_counter() - start) * 1000)
        c.request('shutdown', None)
        c.notify('exit', None)
        c.proc.wait(10)

    missed = False
    for name, times, goal in (('edit -> diagnostics', edits, 100),
                              ('hover', hovers, 50),
                              ('completion', completions, 50)):
        median = statistics.median(times)
        missed |= median > goal
        print('%-20s median %6.1f ms, worst %6.1f ms (goal %d ms; %.2fx the '
              'reference)' % (name, median, max(times), goal,
                              median / min(reference)))
    sys.exit(1 if missed else 0)


if __name__ == '__main__':
    main()

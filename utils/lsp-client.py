#!/usr/bin/env python3
"""A scripted Language Server Protocol client for the tests of `bsc lsp`.

    lsp-client.py [--root DIR] [--timeout S] SCRIPT -- SERVER COMMAND...

starts the server, runs the script's steps in order and prints what the
server answers, one compact JSON line per answer (keys sorted, file URIs
under --root written as `file:///ROOT/...`), so that FileCheck can read it.
Every request must be answered within --timeout seconds (default 10): a
server that hangs or dies fails the script (exit status 1), as does a
malformed message from it.

Script lines (blank lines and lines starting with `#` are skipped; with
--prefix P only the lines `# P: STEP` count, so that a lit test holds its
script):
    initialize [JSON]            the initialize request (JSON: params to
                                 merge) and the initialized notification
    open PATH                    textDocument/didOpen with the file's text
    open-text PATH TEXT          didOpen with TEXT (\\n, \\t, \\\\); PATH may be
                                 `untitled:NAME`, a buffer never saved
    change PATH TEXT             didChange: the whole text (\\n, \\t, \\\\)
    change-file PATH FILE        didChange: the whole text of FILE
    edit PATH L C L C TEXT       didChange: an incremental edit of a range
    close PATH                   didClose
    write PATH TEXT              writes the file on disk (\\n escapes)
    request METHOD JSON          a request; prints `METHOD: RESULT`
    notify METHOD JSON           a notification
    every-request PATH           every request at three places of each
                                 line; prints how many were answered
    tokens PATH                  semanticTokens/full, decoded with the
                                 legend: one `token LINE:COL LEN TYPE.MODS`
                                 line each (0-based)
    raw TEXT                     bytes as they are (\\r\\n escapes), to
                                 damage the stream
    diagnostics PATH             waits for the next publishDiagnostics of
                                 PATH; prints `diagnostics NAME: JSON`
    no-diagnostics PATH S        fails if PATH gets diagnostics within S s
    answers                      prints the answers not waited for (to
                                 damaged messages), in order
    shutdown                     shutdown, then exit; prints the server's
                                 exit status
    exit                         exit alone; prints the exit status
In JSON, `URI(PATH)` becomes the file's URI and `TEXT(PATH)` its text as
a JSON string. PATH is relative to --root. Messages the server sends on
its own (logs, other diagnostics) are kept until a step waits for them.
"""
import argparse
import json
import os
import re
import select
import subprocess
import sys
import time


class ServerGone(Exception):
    pass


class Client:
    def __init__(self, cmd, root, timeout):
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE)
        self.root = os.path.abspath(root)
        self.timeout = timeout
        self.buf = b''
        self.pending = []
        self.next_id = 1
        self.versions = {}

    # --- the wire ---------------------------------------------------------
    def send(self, msg):
        body = json.dumps(msg).encode()
        self.write(b'Content-Length: %d\r\n\r\n' % len(body) + body)

    def write(self, data):
        try:
            self.proc.stdin.write(data)
            self.proc.stdin.flush()
        except BrokenPipeError:
            raise ServerGone('the server closed its input')

    def read_message(self, deadline):
        while True:
            header_end = self.buf.find(b'\r\n\r\n')
            if header_end >= 0:
                headers = self.buf[:header_end].decode('ascii', 'replace')
                m = re.search(r'Content-Length: *(\d+)', headers, re.I)
                if not m:
                    raise ServerGone('a message without Content-Length: '
                                     + repr(headers))
                length = int(m.group(1))
                start = header_end + 4
                if len(self.buf) >= start + length:
                    body = self.buf[start:start + length]
                    self.buf = self.buf[start + length:]
                    return json.loads(body)
            left = deadline - time.monotonic()
            if left <= 0:
                return None
            ready, _, _ = select.select([self.proc.stdout], [], [], left)
            if not ready:
                return None
            chunk = os.read(self.proc.stdout.fileno(), 65536)
            if not chunk:
                raise ServerGone('the server ended (status %s)'
                                 % self.proc.wait())
            self.buf += chunk

    def wait_for(self, match, timeout=None):
        for i, msg in enumerate(self.pending):
            if match(msg):
                return self.pending.pop(i)
        deadline = time.monotonic() + (timeout or self.timeout)
        while True:
            msg = self.read_message(deadline)
            if msg is None:
                return None
            if match(msg):
                return msg
            # A request from the server (workspace/configuration, ...):
            # answered with null, as a client without the feature would.
            if 'id' in msg and 'method' in msg:
                self.send({'jsonrpc': '2.0', 'id': msg['id'], 'result': None})
                continue
            self.pending.append(msg)

    # --- steps ------------------------------------------------------------
    def uri(self, path):
        if path.startswith('untitled:'):  # a buffer the editor has not saved
            return path
        return 'file://' + os.path.join(self.root, path)

    def expand(self, text):
        text = re.sub(r'URI\(([^)]*)\)',
                      lambda m: json.dumps(self.uri(m.group(1))), text)
        text = re.sub(r'TEXT\(([^)]*)\)',
                      lambda m: json.dumps(self.read(m.group(1))), text)
        return json.loads(text) if text.strip() else {}

    def read(self, path):
        with open(os.path.join(self.root, path), encoding='utf-8') as f:
            return f.read()

    def show(self, value):
        text = json.dumps(value, sort_keys=True, separators=(',', ':'))
        return text.replace('file://' + self.root + '/', 'file:///ROOT/')

    def request(self, method, params):
        rid = self.next_id
        self.next_id += 1
        self.send({'jsonrpc': '2.0', 'id': rid, 'method': method,
                   'params': params})
        msg = self.wait_for(lambda m: m.get('id') == rid and 'method' not in m)
        if msg is None:
            raise ServerGone('no answer to %s within %s s'
                             % (method, self.timeout))
        return msg

    def notify(self, method, params):
        self.send({'jsonrpc': '2.0', 'method': method, 'params': params})

    def change(self, path, changes):
        self.versions[path] = self.versions.get(path, 1) + 1
        self.notify('textDocument/didChange', {
            'textDocument': {'uri': self.uri(path),
                             'version': self.versions[path]},
            'contentChanges': changes})

    def step(self, line):
        word, _, rest = line.partition(' ')
        if word == 'initialize':
            params = {'processId': os.getpid(), 'rootUri': 'file://' + self.root,
                      'capabilities': {}}
            params.update(self.expand(rest))
            msg = self.request('initialize', params)
            print('initialize: ' + self.show(msg.get('result', msg)))
            caps = msg.get('result', {}).get('capabilities', {})
            self.legend = caps.get('semanticTokensProvider', {}).get('legend')
            self.notify('initialized', {})
        elif word == 'open':
            self.versions[rest] = 1
            self.notify('textDocument/didOpen', {'textDocument': {
                'uri': self.uri(rest), 'languageId': 'bscript', 'version': 1,
                'text': self.read(rest)}})
        elif word == 'open-text':
            path, _, text = rest.partition(' ')
            self.versions[path] = 1
            self.notify('textDocument/didOpen', {'textDocument': {
                'uri': self.uri(path), 'languageId': 'bscript', 'version': 1,
                'text': text.encode().decode('unicode_escape')}})
        elif word == 'change':
            path, _, text = rest.partition(' ')
            text = text.encode().decode('unicode_escape')
            self.change(path, [{'text': text}])
        elif word == 'change-file':
            path, _, other = rest.partition(' ')
            self.change(path, [{'text': self.read(other)}])
        elif word == 'edit':
            path, l1, c1, l2, c2, *text = rest.split(' ', 5)
            text = (text[0] if text else '').encode().decode('unicode_escape')
            self.change(path, [{'range': {
                'start': {'line': int(l1), 'character': int(c1)},
                'end': {'line': int(l2), 'character': int(c2)}},
                'text': text}])
        elif word == 'write':
            path, _, text = rest.partition(' ')
            with open(os.path.join(self.root, path), 'w') as f:
                f.write(text.encode().decode('unicode_escape'))
        elif word == 'close':
            self.versions.pop(rest, None)
            self.notify('textDocument/didClose',
                        {'textDocument': {'uri': self.uri(rest)}})
        elif word == 'request':
            method, _, params = rest.partition(' ')
            msg = self.request(method, self.expand(params))
            print(method + ': ' + self.show(msg.get('result', msg)))
        elif word == 'tokens':
            msg = self.request('textDocument/semanticTokens/full',
                               {'textDocument': {'uri': self.uri(rest)}})
            data = msg.get('result', {}).get('data', [])
            line = col = 0
            for i in range(0, len(data), 5):
                dl, dc, length, kind, mods = data[i:i + 5]
                col = col + dc if dl == 0 else dc
                line += dl
                names = [m for b, m in enumerate(self.legend['tokenModifiers'])
                         if mods & (1 << b)]
                print('token %d:%d %d %s%s' % (
                    line, col, length, self.legend['tokenTypes'][kind],
                    ''.join('.' + m for m in names)))
        elif word == 'every-request':
            # Each position-taking request at the start, middle and end of
            # every line, and the whole-document ones: all must be answered.
            text = self.read(rest)
            doc = {'uri': self.uri(rest)}
            answered = 0
            for method in ('textDocument/documentSymbol',
                           'textDocument/foldingRange',
                           'textDocument/semanticTokens/full',
                           'textDocument/formatting'):
                self.request(method, {'textDocument': doc,
                                      'options': {'tabSize': 4,
                                                  'insertSpaces': True}})
                answered += 1
            for n, line in enumerate(text.split('\n')):
                for c in sorted({0, len(line) // 2, len(line)}):
                    pos = {'line': n, 'character': c}
                    for method in ('hover', 'definition', 'completion',
                                   'signatureHelp', 'prepareRename'):
                        self.request('textDocument/' + method,
                                     {'textDocument': doc, 'position': pos})
                        answered += 1
            print('every-request %s: %d answered' % (rest, answered))
        elif word == 'notify':
            method, _, params = rest.partition(' ')
            self.notify(method, self.expand(params))
        elif word == 'raw':
            self.write(rest.encode().decode('unicode_escape').encode('latin-1'))
        elif word in ('diagnostics', 'no-diagnostics'):
            path, _, wait = rest.partition(' ')
            uri = self.uri(path)
            # Of the text last sent: an open document's diagnostics name
            # its version, and older ones are skipped.
            version = self.versions.get(path)
            msg = self.wait_for(
                lambda m: m.get('method') == 'textDocument/publishDiagnostics'
                and m['params']['uri'] == uri
                and m['params'].get('version', version) == version,
                float(wait) if wait else None)
            if word == 'no-diagnostics':
                if msg is not None:
                    raise ServerGone('unexpected diagnostics: '
                                     + self.show(msg['params']))
                print('no diagnostics for ' + path)
            elif msg is None:
                raise ServerGone('no diagnostics for %s within %s s'
                                 % (path, self.timeout))
            else:
                print('diagnostics %s: %s'
                      % (path, self.show(msg['params']['diagnostics'])))
        elif word == 'answers':
            # Answers the server sent without being waited for (to damaged
            # messages), in order, after letting it read what was sent.
            while self.wait_for(lambda m: False, 0.3) is not None:
                pass
            for msg in [m for m in self.pending if 'method' not in m]:
                print('answer: ' + self.show(msg))
            self.pending = [m for m in self.pending if 'method' in m]
        elif word == 'exit':
            self.notify('exit', None)
            try:
                print('exit status %d' % self.proc.wait(self.timeout))
            except subprocess.TimeoutExpired:
                raise ServerGone('the server did not exit')
        elif word == 'shutdown':
            msg = self.request('shutdown', None)
            print('shutdown: ' + self.show(msg.get('result', msg)))
            self.notify('exit', None)
            try:
                print('exit status %d' % self.proc.wait(self.timeout))
            except subprocess.TimeoutExpired:
                raise ServerGone('the server did not exit')
        else:
            raise SystemExit('lsp-client: unknown step: ' + line)


def main():
    argv = sys.argv[1:]
    if '--' not in argv:
        sys.exit('usage: lsp-client.py [--root DIR] [--timeout S] SCRIPT -- '
                 'SERVER...')
    cut = argv.index('--')
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument('--root', default='.')
    p.add_argument('--timeout', type=float, default=10)
    p.add_argument('--prefix', help='read only the lines `# PREFIX: step` '
                   '(the script inside a lit test)')
    p.add_argument('script')
    args = p.parse_args(argv[:cut])
    client = Client(argv[cut + 1:], args.root, args.timeout)
    status = 0
    try:
        for line in open(args.script, encoding='utf-8'):
            line = line.rstrip('\n')
            if args.prefix:
                head = '# %s: ' % args.prefix
                if not line.startswith(head):
                    continue
                line = line[len(head):]
            if line.strip() and not line.lstrip().startswith('#'):
                client.step(line)
                sys.stdout.flush()
    except (ServerGone, json.JSONDecodeError) as e:
        print('lsp-client: error: %s' % e)
        status = 1
    finally:
        if client.proc.poll() is None:
            client.proc.kill()
            client.proc.wait()
    sys.exit(status)


if __name__ == '__main__':
    main()

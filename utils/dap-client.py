#!/usr/bin/env python3
"""A scripted Debug Adapter Protocol client for the tests of `bsc dap`.

    dap-client.py [--root DIR] [--timeout S] [--prefix P] SCRIPT -- ADAPTER...

starts the adapter, runs the script's steps in order and prints what it
sends, one line per message, so that FileCheck can read it:

    NAME: {"body": ..., "success": true}     a response (keys sorted; seq,
                                             request_seq, type and command
                                             left out)
    event NAME: {...}                        an event's body
    CATEGORY| TEXT                           an output event, line by line
                                             (console, stderr, stdout)

Paths under --root are written `ROOT/...`. Every response must come within
--timeout seconds (default 20): an adapter that hangs or dies fails the
script (exit status 1), as does a malformed message from it.

Script lines (blank lines and lines starting with `#` are skipped; with
--prefix P only the lines `# P: STEP` count, so that a lit test holds its
script):
    request COMMAND [JSON]    a request; prints the messages up to and
                              including its response
    run COMMAND [JSON]        a request that resumes (continue, next, ...):
                              prints the messages up to the `stopped` (or
                              `terminated`) event after its response
    start JSON                initialize, launch with JSON, then
                              configurationDone: waits for `stopped`
    raw TEXT                  bytes as they are (\\r\\n escapes)
    wait EVENT                prints the messages up to the event EVENT
    storm SEED N PATH         N requests of random commands with random
                              arguments (disconnect and terminate left out;
                              setBreakpoints only on PATH); each must be
                              answered, a resume also stopped; prints how
                              many were and how many succeeded
    end                       closes the adapter's input; prints its exit
                              status
In JSON, `PATH(P)` becomes the absolute path of P under --root as a JSON
string, and `THREAD` the thread of the last stop.
"""
import argparse
import json
import os
import re
import select
import subprocess
import sys
import time


class AdapterGone(Exception):
    pass


class Client:
    def __init__(self, cmd, root, timeout):
        self.proc = subprocess.Popen(cmd, stdin=subprocess.PIPE,
                                     stdout=subprocess.PIPE, cwd=root)
        self.root = os.path.abspath(root)
        self.timeout = timeout
        self.buf = b''
        self.seq = 1
        self.thread = 1

    def write(self, data):
        try:
            self.proc.stdin.write(data)
            self.proc.stdin.flush()
        except BrokenPipeError:
            raise AdapterGone('the adapter closed its input')

    def send(self, command, arguments):
        msg = {'seq': self.seq, 'type': 'request', 'command': command}
        if arguments is not None:
            msg['arguments'] = arguments
        self.seq += 1
        body = json.dumps(msg).encode()
        self.write(b'Content-Length: %d\r\n\r\n' % len(body) + body)
        return msg['seq']

    def read_message(self):
        deadline = time.monotonic() + self.timeout
        while True:
            header_end = self.buf.find(b'\r\n\r\n')
            if header_end >= 0:
                headers = self.buf[:header_end].decode('ascii', 'replace')
                m = re.search(r'Content-Length: *(\d+)', headers, re.I)
                if not m:
                    raise AdapterGone('a message without Content-Length: '
                                      + repr(headers))
                length = int(m.group(1))
                start = header_end + 4
                if len(self.buf) >= start + length:
                    body = self.buf[start:start + length]
                    self.buf = self.buf[start + length:]
                    return json.loads(body)
            left = deadline - time.monotonic()
            if left <= 0:
                raise AdapterGone('no message within %s s' % self.timeout)
            ready, _, _ = select.select([self.proc.stdout], [], [], left)
            if not ready:
                raise AdapterGone('no message within %s s' % self.timeout)
            chunk = os.read(self.proc.stdout.fileno(), 65536)
            if not chunk:
                raise AdapterGone('the adapter ended (status %s)'
                                  % self.proc.wait())
            self.buf += chunk

    def show(self, msg):
        text = json.dumps(msg, sort_keys=True).replace(self.root, 'ROOT')
        msg = json.loads(text)
        if msg.get('type') == 'event':
            body = msg.get('body', {})
            if msg['event'] == 'output':
                for line in body.get('output', '').rstrip('\n').split('\n'):
                    print('%s| %s' % (body.get('category', 'console'), line))
                return
            if msg['event'] == 'stopped':
                self.thread = body.get('threadId', self.thread)
            print('event %s: %s' % (msg['event'],
                                    json.dumps(body, sort_keys=True)))
            return
        shown = {k: v for k, v in msg.items()
                 if k not in ('seq', 'request_seq', 'type', 'command')}
        print('%s: %s' % (msg.get('command'), json.dumps(shown, sort_keys=True)))

    def until(self, done):
        while True:
            msg = self.read_message()
            self.show(msg)
            if done(msg):
                return msg

    def request(self, command, arguments, resumes=False):
        seq = self.send(command, arguments)
        response = self.until(lambda m: m.get('type') == 'response'
                              and m.get('request_seq') == seq)
        if resumes and response.get('success'):
            self.wait('stopped', also='terminated')
        sys.stdout.flush()
        return response

    def wait(self, event, also=None):
        self.until(lambda m: m.get('type') == 'event'
                   and m.get('event') in (event, also))

    def storm(self, seed, count, path):
        import random
        rng = random.Random(seed)
        commands = ['threads', 'stackTrace', 'scopes', 'variables',
                    'setVariable', 'evaluate', 'exceptionInfo', 'completions',
                    'setBreakpoints', 'setFunctionBreakpoints',
                    'setExceptionBreakpoints', 'pause', 'bscript/gotoCycle',
                    'launch', 'attach', 'configurationDone', 'initialize',
                    'nothing', 'continue', 'next', 'stepIn', 'stepOut',
                    'stepBack', 'reverseContinue']
        resumes = {'continue', 'next', 'stepIn', 'stepOut', 'stepBack',
                   'reverseContinue'}
        names = ['threadId', 'frameId', 'variablesReference', 'name', 'value',
                 'expression', 'context', 'text', 'column', 'cycle', 'filters',
                 'breakpoints', 'source', 'line', 'condition', 'hitCondition',
                 'logMessage', 'program', 'startFrame', 'levels']

        def value(depth=0):
            kind = rng.randrange(9 if depth < 2 else 6)
            if kind == 0:
                return rng.choice([0, 1, 2, 3, -1, 7, 2**31, -2**40, 10**20])
            if kind == 1:
                return rng.choice(['', 'x', 'input', 'input.time', ':why',
                                   ':goto 2', ':back', 'n + 1', '{n', '% 0',
                                   ':step 2', 'striker', 'repl', 'hover',
                                   '\u00e9\u0000', ':record /nonexistent/x'])
            if kind == 2:
                return rng.random() * 1e6
            if kind == 3:
                return rng.choice([True, False, None])
            if kind == 4:
                return rng.choice([1, 2, 3])
            if kind == 5:
                return 'a' * rng.randrange(0, 300)
            if kind == 6:
                return [value(depth + 1) for _ in range(rng.randrange(4))]
            return {rng.choice(names): value(depth + 1)
                    for _ in range(rng.randrange(4))}

        answered = succeeded = 0
        for _ in range(count):
            command = rng.choice(commands)
            args = {rng.choice(names): value() for _ in range(rng.randrange(5))}
            if command == 'setBreakpoints':
                args['source'] = {'path': path}
            if rng.randrange(10) == 0:
                args = value()
            seq = self.send(command, args)
            while True:
                msg = self.read_message()
                if msg.get('type') == 'response' and msg.get('request_seq') == seq:
                    break
            answered += 1
            succeeded += bool(msg.get('success'))
            if command in resumes and msg.get('success'):
                while True:
                    ev = self.read_message()
                    if ev.get('type') == 'event' and ev.get('event') in ('stopped', 'terminated'):
                        break
        print('storm: %d answered, %d succeeded' % (answered, succeeded))

    def expand(self, text):
        text = re.sub(r'PATH\(([^)]*)\)',
                      lambda m: json.dumps(os.path.join(self.root,
                                                        m.group(1))), text)
        text = text.replace('THREAD', str(self.thread))
        return json.loads(text) if text.strip() else None

    def step(self, line):
        op, _, rest = line.partition(' ')
        rest = rest.strip()
        if op in ('request', 'run'):
            command, _, args = rest.partition(' ')
            self.request(command, self.expand(args), resumes=op == 'run')
        elif op == 'start':
            self.request('initialize', {'adapterID': 'bscript',
                                        'linesStartAt1': True,
                                        'columnsStartAt1': True})
            launch = self.request('launch', self.expand(rest))
            if not launch.get('success'):
                return
            self.wait('initialized')
            self.request('configurationDone', None, resumes=True)
        elif op == 'storm':
            seed, count, path = rest.split(' ', 2)
            self.storm(int(seed), int(count), os.path.join(self.root, path))
        elif op == 'raw':
            self.write(rest.encode().decode('unicode_escape').encode())
        elif op == 'wait':
            self.wait(rest)
        elif op == 'end':
            self.proc.stdin.close()
            while True:
                chunk = os.read(self.proc.stdout.fileno(), 65536)
                if not chunk:
                    break
                self.buf += chunk
            while self.buf.find(b'\r\n\r\n') >= 0:
                self.show(self.read_message())
            print('exit status %d' % self.proc.wait(timeout=self.timeout))
        else:
            raise SystemExit('dap-client: unknown step: ' + line)
        sys.stdout.flush()


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument('--root', default='.')
    parser.add_argument('--timeout', type=float, default=20)
    parser.add_argument('--prefix')
    parser.add_argument('script')
    parser.add_argument('adapter', nargs=argparse.REMAINDER)
    args = parser.parse_args()
    adapter = args.adapter[1:] if args.adapter[:1] == ['--'] else args.adapter
    with open(args.script) as f:
        lines = f.read().splitlines()
    steps = []
    for line in lines:
        if args.prefix:
            m = re.match(r'\s*#\s*%s:\s?(.*)$' % re.escape(args.prefix), line)
            if m:
                steps.append(m.group(1))
        elif line.strip() and not line.lstrip().startswith('#'):
            steps.append(line.strip())
    client = Client(adapter, args.root, args.timeout)
    try:
        for step in steps:
            client.step(step)
    except AdapterGone as e:
        sys.stdout.flush()
        print('dap-client: %s' % e, file=sys.stderr)
        return 1
    finally:
        if client.proc.poll() is None:
            client.proc.kill()
    return 0


if __name__ == '__main__':
    sys.exit(main())

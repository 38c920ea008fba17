#!/usr/bin/env python3
"""Drives headless Chromium over the DevTools protocol, for tests of the HTML
pages bsc writes (lit + FileCheck) and for the page benchmark.

    browser.py [--width 1400 --height 900] [--timeout 60] [--no-ready]
               PAGE.html STEPS
    browser.py [--width W --height H] [--timeout S] --first-paint PAGE.html

Standard library only.  Chromium (/usr/bin/chromium, or $BSC_CHROMIUM) is
started with --remote-debugging-pipe: it reads NUL-terminated JSON commands
from its fd 3 and writes NUL-terminated responses and events to its fd 4.  It
gets a fresh temporary profile and no network (every host name fails to
resolve), and it is killed, with all its processes, whatever happens.  Its
own output (D-Bus complaints and the like) is shown only if it fails to
start.  The viewport is exactly --width x --height CSS pixels at device pixel
ratio 1, the page behaves as if its window had the focus, smooth scrolling
is off, and alert/confirm/prompt dialogs are accepted (and listed by
`console`).

The page is opened as a file:// URL in a new tab; once its load event has
fired, the driver waits until document.body.dataset.ready == "1" (unless
--no-ready), then runs STEPS, one per line ('#' comments and blank lines are
ignored):

    wait-ready            wait until document.body.dataset.ready == "1"
    key NAME [N]          press and release a key N times (default 1): ArrowLeft
                          ArrowRight ArrowUp ArrowDown Home End PageUp PageDown
                          Enter Escape Tab Backspace Delete Space, or a single
                          character; modifiers as Shift+ArrowRight, Ctrl+a,
                          Alt+x, Meta+x (Shift+a gives "A"; no modifier is
                          added implicitly, so `key ?` has no shiftKey)
    click SELECTOR        mouse click at the centre of the first element the
                          CSS selector matches (scrolled into view if needed)
    click-at X Y          mouse click at client coordinates
    drag X1 Y1 X2 Y2      press at X1 Y1, move to X2 Y2 in 10 steps, release
    hover X Y             move the mouse to X Y
    type SELECTOR TEXT    focus the element, select its contents and insert
                          TEXT (the rest of the line) in their place
    text SELECTOR         print `text SELECTOR: <innerText>`, whitespace runs
                          collapsed to one space and trimmed
    eval JS               print `eval: <result as JSON>` (promises awaited;
                          `eval: undefined` for undefined)
    screenshot FILE       write a PNG of the viewport to FILE, print
                          `screenshot FILE`
    requests              print `requests: N network, M data`: the requests
                          the page made other than loading PAGE itself, data:
                          URLs counted apart
    console               print the console messages (`console: LEVEL: TEXT`)
                          and uncaught exceptions so far, in order, then the
                          browser's own messages (failed loads...) sorted; or
                          `console: none`.  Waits (5 s at most) for the
                          requests in flight to end first, as does `requests`
    sleep MS              wait MS milliseconds

A coordinate is a number or a JavaScript expression in backquotes evaluated
in the page, e.g.  click-at `bscTimeline.xForCycle(91)` `innerHeight/2`.
A selector is the rest of the line, or for `type` the first word; a selector
in backquotes may contain spaces.  After each input step the driver waits for
two animation frames so that the page has handled the input and rendered.

An uncaught exception in the page, a selector that matches nothing, a
JavaScript error in an expression, Chromium failing to start or crashing and
running past the timeout (60 s for the whole run) are errors: the driver
prints `browser.py: error: ...` (with the step's line number and text) to
standard error and exits with status 1.

--first-paint loads PAGE five times, each in a fresh tab, and prints the
medians of the first-contentful-paint time and of window.bscTimeline
.firstRenderMs (`n/a` where the page does not define it):
    first-contentful-paint: X ms
    ready: Y ms
"""
import argparse
import base64
import fcntl
import json
import os
import pathlib
import re
import select
import shutil
import signal
import statistics
import subprocess
import sys
import tempfile
import time
import urllib.parse

PROG = 'browser.py'
CHROMIUM = os.environ.get('BSC_CHROMIUM', '/usr/bin/chromium')
FIRST_PAINT_RUNS = 5


class Error(Exception):
    """A failure reported as `browser.py: error: <message>`."""


# --- Keys --------------------------------------------------------------------

# name -> (key, code, windowsVirtualKeyCode, text)
NAMED_KEYS = {
    'ArrowLeft': ('ArrowLeft', 'ArrowLeft', 37, ''),
    'ArrowUp': ('ArrowUp', 'ArrowUp', 38, ''),
    'ArrowRight': ('ArrowRight', 'ArrowRight', 39, ''),
    'ArrowDown': ('ArrowDown', 'ArrowDown', 40, ''),
    'Home': ('Home', 'Home', 36, ''),
    'End': ('End', 'End', 35, ''),
    'PageUp': ('PageUp', 'PageUp', 33, ''),
    'PageDown': ('PageDown', 'PageDown', 34, ''),
    'Enter': ('Enter', 'Enter', 13, '\r'),
    'Escape': ('Escape', 'Escape', 27, ''),
    'Tab': ('Tab', 'Tab', 9, ''),
    'Backspace': ('Backspace', 'Backspace', 8, ''),
    'Delete': ('Delete', 'Delete', 46, ''),
    'Space': (' ', 'Space', 32, ' '),
    'Insert': ('Insert', 'Insert', 45, ''),
}
for _i in range(1, 13):
    NAMED_KEYS['F%d' % _i] = ('F%d' % _i, 'F%d' % _i, 111 + _i, '')

# Punctuation on a US keyboard: unshifted, shifted, code, virtual key code.
PUNCTUATION = [
    ('-', '_', 'Minus', 189), ('=', '+', 'Equal', 187),
    ('[', '{', 'BracketLeft', 219), (']', '}', 'BracketRight', 221),
    ('\\', '|', 'Backslash', 220), (';', ':', 'Semicolon', 186),
    ("'", '"', 'Quote', 222), (',', '<', 'Comma', 188),
    ('.', '>', 'Period', 190), ('/', '?', 'Slash', 191),
    ('`', '~', 'Backquote', 192),
]
DIGIT_SHIFTED = ')!@#$%^&*('

MODIFIERS = {'Alt': 1, 'Ctrl': 2, 'Control': 2, 'Meta': 4, 'Cmd': 4,
             'Shift': 8}


def parse_key(spec):
    """Returns the Input.dispatchKeyEvent fields for a spec like Shift+a."""
    modifiers = 0
    name = spec
    while True:
        prefix, plus, rest = name.partition('+')
        if plus and rest and prefix in MODIFIERS:
            modifiers |= MODIFIERS[prefix]
            name = rest
        else:
            break
    if name in NAMED_KEYS:
        key, code, vk, text = NAMED_KEYS[name]
    elif len(name) == 1:
        c = name
        if modifiers & 8 and c.isalpha():
            c = c.upper()
        key, text = c, c
        if 'a' <= c.lower() <= 'z':
            code, vk = 'Key' + c.upper(), ord(c.upper())
        elif c.isdigit():
            code, vk = 'Digit' + c, ord(c)
        elif c in DIGIT_SHIFTED:
            d = str(DIGIT_SHIFTED.index(c))
            code, vk = 'Digit' + d, ord(d)
        elif c == ' ':
            code, vk = 'Space', 32
        else:
            code, vk = '', 0
            for plain, shifted, pcode, pvk in PUNCTUATION:
                if c in (plain, shifted):
                    code, vk = pcode, pvk
    else:
        raise Error('unknown key %r (named keys: %s, or a single character)'
                    % (name, ' '.join(NAMED_KEYS)))
    if modifiers & (1 | 2 | 4):
        text = ''  # Ctrl+a and the like insert nothing
    return {'key': key, 'code': code, 'windowsVirtualKeyCode': vk,
            'nativeVirtualKeyCode': vk, 'text': text, 'unmodifiedText': text,
            'modifiers': modifiers}


# --- Steps -------------------------------------------------------------------

STEP_ARGS = {  # step -> description of its arguments, for messages
    'wait-ready': '', 'key': 'NAME [N]', 'click': 'SELECTOR',
    'click-at': 'X Y', 'drag': 'X1 Y1 X2 Y2', 'hover': 'X Y',
    'type': 'SELECTOR TEXT', 'text': 'SELECTOR', 'eval': 'JS',
    'screenshot': 'FILE', 'requests': '', 'console': '', 'sleep': 'MS',
}


class Step:
    def __init__(self, lineno, text, name, args):
        self.lineno, self.text, self.name, self.args = lineno, text, name, args

    def where(self):
        return 'line %d: %s' % (self.lineno, self.text)


def split_words(s):
    """Splits on spaces; a word in backquotes may contain spaces. Returns
    (word, quoted) pairs."""
    words = []
    i = 0
    while i < len(s):
        if s[i].isspace():
            i += 1
        elif s[i] == '`':
            j = s.find('`', i + 1)
            if j < 0:
                raise Error('unterminated backquote')
            words.append((s[i + 1:j], True))
            i = j + 1
        else:
            j = i
            while j < len(s) and not s[j].isspace():
                j += 1
            words.append((s[i:j], False))
            i = j
    return words


def coordinate(word):
    """A coordinate word: ('num', float) or ('js', expression)."""
    text, quoted = word
    if quoted:
        return ('js', text)
    try:
        return ('num', float(text))
    except ValueError:
        raise Error('%r is not a number (put a JavaScript expression in '
                    'backquotes)' % text)


def selector_arg(rest):
    rest = rest.strip()
    if rest.startswith('`') and rest.endswith('`') and len(rest) > 1:
        return rest[1:-1]
    return rest


def parse_step(lineno, text):
    name, _, rest = text.partition(' ')
    rest = rest.strip()
    if name not in STEP_ARGS:
        raise Error('unknown step %r (steps: %s)'
                    % (name, ', '.join(STEP_ARGS)))
    usage = ('usage: %s %s' % (name, STEP_ARGS[name])).rstrip()
    if name in ('wait-ready', 'requests', 'console'):
        if rest:
            raise Error(usage)
        args = []
    elif name == 'key':
        words = rest.split()
        if len(words) not in (1, 2):
            raise Error(usage)
        count = 1
        if len(words) == 2:
            if not words[1].isdigit():
                raise Error(usage + ' (N a count)')
            count = int(words[1])
        args = [parse_key(words[0]), count]
    elif name in ('click', 'text'):
        if not rest:
            raise Error(usage)
        args = [selector_arg(rest)]
    elif name in ('click-at', 'hover', 'drag'):
        words = split_words(rest)
        if len(words) != (4 if name == 'drag' else 2):
            raise Error(usage)
        args = [coordinate(w) for w in words]
    elif name == 'type':
        if rest.startswith('`'):
            end = rest.find('`', 1)
            if end < 0:
                raise Error('unterminated backquote')
            sel, text_arg = rest[1:end], rest[end + 1:]
        else:
            sel, _, text_arg = rest.partition(' ')
        if not sel:
            raise Error(usage)
        args = [sel, text_arg[1:] if text_arg.startswith(' ') else text_arg]
    elif name in ('eval', 'screenshot'):
        if not rest:
            raise Error(usage)
        args = [rest]
    elif name == 'sleep':
        try:
            args = [float(rest)]
        except ValueError:
            raise Error(usage)
    return Step(lineno, text, name, args)


def read_steps(path):
    try:
        with open(path, encoding='utf-8') as f:
            lines = f.read().splitlines()
    except OSError as e:
        raise Error('cannot read %s: %s' % (path, e.strerror))
    steps = []
    for lineno, line in enumerate(lines, 1):
        text = line.strip()
        if not text or text.startswith('#'):
            continue
        try:
            steps.append(parse_step(lineno, text))
        except Error as e:
            raise Error('%s:%d: %s: %s' % (path, lineno, text, e))
    return steps


# --- The browser -------------------------------------------------------------

def spawn_with_pipe(argv, child_in, child_out, **kwargs):
    """Popen(argv) with child_in as the child's fd 3 and child_out as its fd
    4.  subprocess can only keep fds under their own numbers, so the parent's
    fds 3 and 4 are borrowed for the fork and put back afterwards."""
    saved = []
    for fd in (3, 4):
        try:
            saved.append((fd, fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10),
                          os.get_inheritable(fd)))
        except OSError:
            saved.append((fd, None, False))
    a = fcntl.fcntl(child_in, fcntl.F_DUPFD_CLOEXEC, 10)
    b = fcntl.fcntl(child_out, fcntl.F_DUPFD_CLOEXEC, 10)
    copies = [a, b]
    # The files for the standard streams too may be fds 3 or 4.
    for stream in ('stdin', 'stdout', 'stderr'):
        f = kwargs.get(stream)
        if f is not None and not (isinstance(f, int) and f < 0):
            fd = f if isinstance(f, int) else f.fileno()
            kwargs[stream] = fcntl.fcntl(fd, fcntl.F_DUPFD_CLOEXEC, 10)
            copies.append(kwargs[stream])
    try:
        os.dup2(a, 3)
        os.dup2(b, 4)
        return subprocess.Popen(argv, pass_fds=(3, 4), **kwargs)
    finally:
        for fd, copy, inheritable in saved:
            if copy is None:
                os.close(fd)
            else:
                os.dup2(copy, fd, inheritable=inheritable)
                os.close(copy)
        for fd in copies:
            os.close(fd)


class Browser:
    def __init__(self, deadline, timeout):
        self.deadline = deadline
        self.timeout = timeout
        self.next_id = 0
        self.responses = {}
        self.buffer = bytearray()  # an incomplete message
        self.proc = None
        self.profile = tempfile.mkdtemp(prefix='bsc-browser-')
        self.log = tempfile.TemporaryFile(prefix='bsc-browser-log-')
        self.session = None      # the page's sessionId
        self.starting = True
        self.reset_page_state()
        self.to_browser = self.from_browser = None

    def start(self, width, height):
        self.width, self.height = width, height
        to_browser_r, self.to_browser = os.pipe()
        self.from_browser, from_browser_w = os.pipe()
        argv = [CHROMIUM, '--headless=new', '--no-sandbox', '--disable-gpu',
                '--no-first-run', '--no-default-browser-check',
                '--disable-extensions', '--disable-background-networking',
                '--disable-sync', '--disable-component-update',
                '--host-resolver-rules=MAP * ~NOTFOUND',
                '--window-size=%d,%d' % (width, height),
                # Scrolling by keys ends before the step does.
                '--disable-smooth-scrolling',
                '--remote-debugging-pipe',
                '--user-data-dir=' + self.profile, 'about:blank']
        try:
            self.proc = spawn_with_pipe(
                argv, to_browser_r, from_browser_w, stdin=subprocess.DEVNULL,
                stdout=self.log, stderr=self.log, start_new_session=True)
        except OSError as e:
            raise Error('cannot start %s: %s' % (CHROMIUM, e.strerror))
        finally:
            os.close(to_browser_r)
            os.close(from_browser_w)
        self.call('Browser.getVersion')
        self.starting = False

    def reset_page_state(self):
        self.page_url = None
        self.lifecycle = []      # (loaderId, name)
        self.load_events = 0
        self.messages = []       # lines for `console`, in order
        self.log_entries = []    # the browser's own messages (Log domain)
        self.exceptions = []     # uncaught exceptions not yet reported
        self.requests = {}       # requestId -> url
        self.in_flight = set()   # requestIds
        self.crashed = False

    # Chromium's output, for when it fails.
    def chromium_output(self):
        self.log.seek(0)
        lines = self.log.read().decode('utf-8', 'replace').splitlines()
        # Without a session bus every start complains about D-Bus.
        lines = [l for l in lines if l.strip() and 'dbus' not in l][-20:]
        if not lines:
            return ''
        return '\nchromium said:\n' + '\n'.join('  ' + l for l in lines)

    def died(self, what):
        status = self.proc.poll()
        if status is None:
            try:
                self.proc.wait(timeout=1)
            except subprocess.TimeoutExpired:
                pass
            status = self.proc.poll()
        how = ''
        if status is not None:
            how = (' (killed by signal %d)' % -status if status < 0
                   else ' (exit status %d)' % status)
        if self.starting:
            return Error('chromium (%s) failed to start%s%s'
                         % (CHROMIUM, how, self.chromium_output()))
        return Error('chromium %s%s' % (what, how))

    def timed_out(self):
        if self.starting:
            return Error('chromium (%s) did not answer within %g s%s'
                         % (CHROMIUM, self.timeout, self.chromium_output()))
        return Error('timed out (%g s in all)' % self.timeout)

    # Protocol.
    def send(self, method, params=None, session=None):
        self.next_id += 1
        msg = {'id': self.next_id, 'method': method, 'params': params or {}}
        if session:
            msg['sessionId'] = session
        data = json.dumps(msg).encode() + b'\0'
        try:
            while data:
                n = os.write(self.to_browser, data)
                data = data[n:]
        except OSError:
            raise self.died('closed its end of the pipe')
        return self.next_id

    def call(self, method, params=None, session=None, deadline=None):
        """Sends a command and returns its result; CDP errors raise Error."""
        id = self.send(method, params, session)
        while id not in self.responses:
            self.pump(deadline)
        msg = self.responses.pop(id)
        if 'error' in msg:
            err = msg['error']
            raise Error('%s: %s%s' % (method, err.get('message', err),
                                      ': ' + err['data'] if 'data' in err
                                      else ''))
        return msg.get('result', {})

    def page(self, method, params=None, deadline=None):
        return self.call(method, params, self.session, deadline)

    def pump(self, deadline=None):
        """Waits (up to the deadline) for messages from the browser, handles
        the events and stores the responses.  Past the run's deadline is an
        error; past an earlier deadline, it just returns."""
        deadline = min(deadline or self.deadline, self.deadline)
        while True:
            remaining = deadline - time.monotonic()
            if remaining <= 0:
                if deadline < self.deadline:
                    return
                raise self.timed_out()
            ready, _, _ = select.select([self.from_browser], [], [],
                                        min(remaining, 0.5))
            if not ready:
                if self.proc.poll() is not None:
                    raise self.died('exited')
                continue
            try:
                chunk = os.read(self.from_browser, 1 << 20)
            except OSError as e:
                raise self.died('pipe read failed: %s' % e.strerror)
            if not chunk:
                raise self.died('closed its end of the pipe')
            self.buffer += chunk
            if b'\0' in chunk:
                *messages, rest = bytes(self.buffer).split(b'\0')
                self.buffer = bytearray(rest)
                for raw in messages:
                    self.handle(json.loads(raw))
                return

    def handle(self, msg):
        if 'id' in msg:
            self.responses[msg['id']] = msg
            return
        method = msg.get('method')
        params = msg.get('params', {})
        if msg.get('sessionId') != self.session or not self.session:
            return
        if method == 'Runtime.exceptionThrown':
            text = self.exception_text(params['exceptionDetails'])
            self.exceptions.append(text)
            self.messages.append('exception: ' + text)
        elif method == 'Runtime.consoleAPICalled':
            self.messages.append('%s: %s' % (params['type'],
                                             self.console_text(params)))
        elif method == 'Log.entryAdded':
            entry = params['entry']
            if entry.get('source') in ('console-api', 'javascript'):
                return  # also reported by the Runtime domain
            text = entry.get('text', '')
            url = entry.get('url')
            if url and entry.get('source') == 'network':
                text += ' (%s)' % self.show_url(url)
            self.log_entries.append('%s: %s' % (entry.get('level', 'log'),
                                                text))
        elif method == 'Network.requestWillBeSent':
            if 'redirectResponse' not in params:
                self.requests[params['requestId']] = params['request']['url']
            self.in_flight.add(params['requestId'])
        elif method in ('Network.loadingFinished', 'Network.loadingFailed'):
            self.in_flight.discard(params['requestId'])
        elif method == 'Page.lifecycleEvent':
            self.lifecycle.append((params.get('loaderId'), params['name']))
        elif method == 'Page.loadEventFired':
            self.load_events += 1
        elif method == 'Page.javascriptDialogOpening':
            self.messages.append('dialog: %s: %s' % (params.get('type'),
                                                     params.get('message')))
            self.send('Page.handleJavaScriptDialog',
                      {'accept': params.get('type') != 'beforeunload'},
                      self.session)
        elif method in ('Inspector.targetCrashed', 'Target.targetCrashed'):
            self.crashed = True
        elif method == 'Inspector.detached':
            self.crashed = True

    def show_url(self, url):
        """URLs of files next to the page are shown relative to it, so that
        the output does not depend on where the page is."""
        if self.page_url and url.startswith('file:'):
            base = self.page_url.rsplit('/', 1)[0] + '/'
            if url.startswith(base):
                return urllib.parse.unquote(url[len(base):])
        return url

    def exception_text(self, details):
        text = details.get('text', 'Uncaught')
        exc = details.get('exception') or {}
        if 'description' in exc:
            what = exc['description'].split('\n')[0]
        elif 'value' in exc:
            what = json.dumps(exc['value'])
        elif 'unserializableValue' in exc:
            what = exc['unserializableValue']
        else:
            what = exc.get('type', '')
        if what and what not in text:
            text = text + ' ' + what
        url = details.get('url')
        if not url:
            frames = (details.get('stackTrace') or {}).get('callFrames') or []
            if frames:
                url = frames[0].get('url')
        if url:
            text += ' (%s:%d:%d)' % (self.show_url(url),
                                     details.get('lineNumber', 0) + 1,
                                     details.get('columnNumber', 0) + 1)
        return text

    @staticmethod
    def remote_text(obj):
        """A console argument as the console shows it, roughly."""
        if 'value' in obj:
            v = obj['value']
            return v if isinstance(v, str) else json.dumps(v)
        if 'unserializableValue' in obj:
            return obj['unserializableValue']
        if obj.get('type') == 'undefined':
            return 'undefined'
        preview = obj.get('preview')
        if preview and preview.get('type') == 'object' and \
                preview.get('subtype') in (None, 'array'):
            def show(p):
                if p.get('type') == 'string':
                    return json.dumps(p.get('value', ''))
                return p.get('value', p.get('type'))
            props = preview.get('properties', [])
            more = ', …' if preview.get('overflow') else ''
            if preview.get('subtype') == 'array':
                return '[%s%s]' % (', '.join(show(p) for p in props), more)
            return '{%s%s}' % (', '.join('%s: %s' % (p['name'], show(p))
                                         for p in props), more)
        return obj.get('description', obj.get('type', '?'))

    def console_text(self, params):
        args = [self.remote_text(a) for a in params.get('args', [])]
        if args and params['args'][0].get('type') == 'string' and \
                '%' in args[0]:
            fmt, rest = args[0], args[1:]

            def sub(m):
                if m.group(0) == '%%':
                    return '%'
                if m.group(0) == '%c':
                    if rest:
                        rest.pop(0)
                    return ''
                return rest.pop(0) if rest else m.group(0)
            args = [re.sub(r'%[sdifoOc%]', sub, fmt)] + rest
        return ' '.join(args)

    # Page.
    def open(self, path, deadline=None):
        """Opens a fresh tab on path and waits for its load event."""
        self.reset_page_state()
        url = pathlib.Path(os.path.abspath(path)).as_uri()
        target = self.call('Target.createTarget',
                           {'url': 'about:blank'})['targetId']
        self.target = target
        self.session = self.call('Target.attachToTarget',
                                 {'targetId': target,
                                  'flatten': True})['sessionId']
        for method in ('Page.enable', 'Runtime.enable', 'Log.enable',
                       'Network.enable'):
            self.page(method)
        self.page('Page.setLifecycleEventsEnabled', {'enabled': True})
        # Headless Chromium keeps 87 pixels of the window for browser chrome
        # it does not draw: make the viewport the size asked for.
        self.page('Emulation.setDeviceMetricsOverride',
                  {'width': self.width, 'height': self.height,
                   'deviceScaleFactor': 1, 'mobile': False})
        # As if the window had the focus (document.hasFocus(), :focus).
        self.page('Emulation.setFocusEmulationEnabled', {'enabled': True})
        self.page_url = url
        self.lifecycle = []
        self.load_events = 0
        nav = self.page('Page.navigate', {'url': url})
        if nav.get('errorText'):
            raise Error('cannot load %s: %s' % (path, nav['errorText']))
        loader = nav.get('loaderId')
        while True:
            self.check_page()
            if loader and (loader, 'load') in self.lifecycle:
                break
            if not loader and self.load_events:
                break
            self.pump(deadline)
        self.check_page()

    def close_page(self):
        if self.session:
            self.call('Target.closeTarget', {'targetId': self.target})
            self.session = None

    def check_page(self):
        if self.crashed:
            raise Error('the page crashed')
        if self.exceptions:
            raise Error('uncaught exception: ' + self.exceptions[0])

    def evaluate(self, expression, what=None):
        """Evaluates expression in the page (awaiting a promise) and returns
        the result's RemoteObject (by value)."""
        result = self.page('Runtime.evaluate',
                           {'expression': expression, 'returnByValue': True,
                            'awaitPromise': True, 'userGesture': True})
        if 'exceptionDetails' in result:
            raise Error('%s threw: %s' % (
                what or 'the expression',
                self.exception_text(result['exceptionDetails'])))
        return result['result']

    def value(self, expression, what=None):
        return self.evaluate(expression, what).get('value')

    def settle(self):
        """Waits for two animation frames (or 500 ms if the page does not
        render), so that input has been handled and its effect drawn."""
        try:
            self.evaluate('new Promise(r => { let n = 0; const t = '
                          'setTimeout(r, 500); const f = () => ++n == 2 ? '
                          '(clearTimeout(t), r()) : requestAnimationFrame(f);'
                          ' requestAnimationFrame(f); })')
        except Error:
            pass  # e.g. the page navigated away
        self.check_page()

    def wait_network_idle(self, limit=5):
        """Waits until no request is in flight, for at most limit seconds."""
        end = time.monotonic() + limit
        while self.in_flight and time.monotonic() < end:
            self.pump(end)
        self.settle()

    def wait_ready(self):
        while True:
            self.check_page()
            if self.value('!!(document.body && '
                          'document.body.dataset.ready === "1")'):
                return
            self.pump(time.monotonic() + 0.02)

    def close(self):
        """Closes Chromium and kills whatever is left of it; removes the
        profile."""
        if self.proc:
            # Killed outright: closing it politely takes a third of a second
            # and leaves nothing that matters, the profile going anyway.
            try:
                os.killpg(self.proc.pid, signal.SIGKILL)
            except OSError:
                pass
            try:
                self.proc.wait(timeout=5)
            except subprocess.TimeoutExpired:
                pass
        for fd in (self.to_browser, self.from_browser):
            if fd is not None:
                os.close(fd)
        self.log.close()
        for _ in range(10):
            shutil.rmtree(self.profile, ignore_errors=True)
            if not os.path.exists(self.profile):
                break
            time.sleep(0.1)


# --- Running steps -----------------------------------------------------------

def mouse(browser, kind, x, y, button='none', buttons=0, count=0):
    browser.page('Input.dispatchMouseEvent',
                 {'type': kind, 'x': x, 'y': y, 'button': button,
                  'buttons': buttons, 'clickCount': count})


def point(browser, step, coords):
    out = []
    for kind, v in coords:
        if kind == 'js':
            r = browser.evaluate(v, '`%s`' % v)
            num = r.get('value')
            if not isinstance(num, (int, float)) or isinstance(num, bool) \
                    or num != num:
                raise Error('`%s` is %s, not a number'
                            % (v, json.dumps(num) if 'value' in r
                               else r.get('unserializableValue',
                                          r.get('type'))))
            v = num
        out.append(v)
    return out


def element_centre(browser, selector):
    r = browser.value(
        # The centre of the part of the element inside the viewport, after
        # scrolling it into view if no part is.
        '(() => { const e = document.querySelector(%s); if (!e) return null;'
        ' const vis = () => { const r = e.getBoundingClientRect();'
        '   const w = document.documentElement.clientWidth || innerWidth;'
        '   const h = document.documentElement.clientHeight || innerHeight;'
        '   const x0 = Math.max(r.left, 0), x1 = Math.min(r.right, w);'
        '   const y0 = Math.max(r.top, 0), y1 = Math.min(r.bottom, h);'
        '   return [(x0 + x1) / 2, (y0 + y1) / 2, x1 - x0, y1 - y0,'
        '           r.width, r.height]; };'
        ' let v = vis();'
        ' if (v[2] <= 0 || v[3] <= 0) {'
        '   e.scrollIntoView({block: "center", inline: "center"}); v = vis(); }'
        ' return v; })()' % json.dumps(selector),
        'the selector')
    if r is None:
        raise Error('no element matches %r' % selector)
    if r[4] <= 0 or r[5] <= 0:
        raise Error('the element %r has no size (hidden?)' % selector)
    if r[2] <= 0 or r[3] <= 0:
        raise Error('the element %r is not in the viewport even after '
                    'scrolling' % selector)
    return r[0], r[1]


def click(browser, x, y):
    mouse(browser, 'mouseMoved', x, y)
    mouse(browser, 'mousePressed', x, y, 'left', 1, 1)
    mouse(browser, 'mouseReleased', x, y, 'left', 0, 1)


def js_value_text(obj):
    if 'value' in obj:
        return json.dumps(obj['value'], ensure_ascii=False,
                          separators=(',', ':'))
    if 'unserializableValue' in obj:
        return obj['unserializableValue']
    return obj.get('type', 'undefined')


def run_step(browser, step, out):
    name, args = step.name, step.args
    if name == 'wait-ready':
        browser.wait_ready()
    elif name == 'key':
        fields, count = args
        for _ in range(count):
            down = dict(fields, type='keyDown' if fields['text']
                        else 'rawKeyDown')
            browser.page('Input.dispatchKeyEvent', down)
            browser.page('Input.dispatchKeyEvent', dict(fields, type='keyUp'))
        browser.settle()
    elif name == 'click':
        click(browser, *element_centre(browser, args[0]))
        browser.settle()
    elif name == 'click-at':
        click(browser, *point(browser, step, args))
        browser.settle()
    elif name == 'hover':
        x, y = point(browser, step, args)
        mouse(browser, 'mouseMoved', x, y)
        browser.settle()
    elif name == 'drag':
        x1, y1, x2, y2 = point(browser, step, args)
        mouse(browser, 'mouseMoved', x1, y1)
        mouse(browser, 'mousePressed', x1, y1, 'left', 1, 1)
        for i in range(1, 11):
            mouse(browser, 'mouseMoved', x1 + (x2 - x1) * i / 10,
                  y1 + (y2 - y1) * i / 10, 'left', 1)
        mouse(browser, 'mouseReleased', x2, y2, 'left', 0, 1)
        browser.settle()
    elif name == 'type':
        selector, text = args
        found = browser.value(
            '(() => { const e = document.querySelector(%s); if (!e) return '
            'false; e.focus(); if (typeof e.select === "function") e.select();'
            ' else if (e.isContentEditable) { const r = document.createRange();'
            ' r.selectNodeContents(e); const s = getSelection();'
            ' s.removeAllRanges(); s.addRange(r); } return true; })()'
            % json.dumps(selector), 'the selector')
        if not found:
            raise Error('no element matches %r' % selector)
        if text:
            browser.page('Input.insertText', {'text': text})
        else:
            browser.page('Input.dispatchKeyEvent',
                         dict(parse_key('Delete'), type='rawKeyDown'))
            browser.page('Input.dispatchKeyEvent',
                         dict(parse_key('Delete'), type='keyUp'))
        browser.settle()
    elif name == 'text':
        r = browser.value(
            '(() => { const e = document.querySelector(%s);'
            ' return e ? e.innerText : null; })()' % json.dumps(args[0]),
            'the selector')
        if r is None:
            raise Error('no element matches %r' % args[0])
        out('text %s: %s' % (args[0], ' '.join(r.split())))
    elif name == 'eval':
        out('eval: ' + js_value_text(browser.evaluate(args[0], 'the '
                                                      'expression')))
    elif name == 'screenshot':
        data = browser.page('Page.captureScreenshot', {'format': 'png'})
        try:
            with open(args[0], 'wb') as f:
                f.write(base64.b64decode(data['data']))
        except OSError as e:
            raise Error('cannot write %s: %s' % (args[0], e.strerror))
        out('screenshot ' + args[0])
    elif name == 'requests':
        browser.wait_network_idle()
        network = data = 0
        page = browser.page_url.split('#')[0]
        for url in browser.requests.values():
            if url.startswith('data:'):
                data += 1
            elif urllib.parse.unquote(url.split('#')[0]) != \
                    urllib.parse.unquote(page):
                network += 1
        out('requests: %d network, %d data' % (network, data))
    elif name == 'console':
        # The browser's own messages (failed loads, for one) come in the
        # order the requests happen to end: sort them.
        browser.wait_network_idle()
        lines = browser.messages + sorted(browser.log_entries)
        if not lines:
            out('console: none')
        for m in lines:
            out('console: ' + m)
    elif name == 'sleep':
        end = time.monotonic() + args[0] / 1000
        while time.monotonic() < end:
            browser.pump(end)
            browser.check_page()
    browser.check_page()


def out(line):
    sys.stdout.write(line + '\n')
    sys.stdout.flush()


def run_steps(browser, page, steps, wait_ready):
    try:
        browser.open(page)
        if wait_ready:
            browser.wait_ready()
    except Error as e:
        raise Error('loading %s: %s' % (page, e))
    for step in steps:
        try:
            run_step(browser, step, out)
        except Error as e:
            raise Error('%s: %s' % (step.where(), e))
    # Exceptions thrown after the last step count too.
    try:
        browser.settle()
    except Error as e:
        raise Error('after the last step: %s' % e)


def first_paint(browser, page, wait_ready):
    fcps, readies = [], []
    for run in range(FIRST_PAINT_RUNS):
        try:
            browser.open(page)
            if wait_ready:
                browser.wait_ready()
            while True:
                fcp = browser.value(
                    '(performance.getEntriesByName("first-contentful-paint")'
                    '[0] || {}).startTime')
                if fcp is not None:
                    break
                browser.check_page()
                browser.pump(time.monotonic() + 0.02)
            fcps.append(fcp)
            ready = browser.value(
                'window.bscTimeline ? window.bscTimeline.firstRenderMs : null')
            if isinstance(ready, (int, float)):
                readies.append(ready)
            browser.check_page()
            browser.close_page()
        except Error as e:
            raise Error('loading %s (run %d): %s' % (page, run + 1, e))
    out('first-contentful-paint: %.1f ms' % statistics.median_low(fcps))
    if len(readies) == FIRST_PAINT_RUNS:
        out('ready: %.1f ms' % statistics.median_low(readies))
    else:
        out('ready: n/a')


def main(argv):
    parser = argparse.ArgumentParser(
        prog=PROG, description='Drives headless Chromium over the DevTools '
        'protocol (see the comment at the top of utils/browser.py).')
    parser.add_argument('--width', type=int, default=1400)
    parser.add_argument('--height', type=int, default=900)
    parser.add_argument('--timeout', type=float, default=60,
                        help='seconds for the whole run (default 60)')
    parser.add_argument('--no-ready', action='store_true',
                        help='do not wait for data-ready="1" after loading')
    parser.add_argument('--first-paint', action='store_true',
                        help='print first-paint timings of PAGE')
    parser.add_argument('page')
    parser.add_argument('steps', nargs='?')
    opts = parser.parse_args(argv[1:])
    if opts.first_paint == (opts.steps is not None):
        parser.error('give either PAGE STEPS or --first-paint PAGE')

    # SIGTERM (lit's timeout, for one) and SIGHUP end the run like ^C, so that
    # Chromium is killed on the way out.
    def interrupted(signum, frame):
        raise KeyboardInterrupt
    signal.signal(signal.SIGTERM, interrupted)
    signal.signal(signal.SIGHUP, interrupted)

    browser = None
    try:
        if not os.path.isfile(opts.page):
            raise Error('no such file: %s' % opts.page)
        steps = None if opts.first_paint else read_steps(opts.steps)
        deadline = time.monotonic() + opts.timeout
        browser = Browser(deadline, opts.timeout)
        browser.start(opts.width, opts.height)
        if opts.first_paint:
            first_paint(browser, opts.page, not opts.no_ready)
        else:
            run_steps(browser, opts.page, steps, not opts.no_ready)
        return 0
    except Error as e:
        sys.stdout.flush()
        sys.stderr.write('%s: error: %s\n' % (PROG, e))
        return 1
    except KeyboardInterrupt:
        sys.stderr.write('%s: error: interrupted\n' % PROG)
        return 1
    finally:
        if browser:
            signal.signal(signal.SIGTERM, signal.SIG_IGN)
            signal.signal(signal.SIGHUP, signal.SIG_IGN)
            browser.close()


if __name__ == '__main__':
    sys.exit(main(sys.argv))

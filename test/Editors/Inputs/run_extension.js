// node run_extension.js SCENARIO EXTENSION_DIR SERVER_PATH [ARG...]
//
// Runs the extension's extension.js, with the real vscode-languageclient
// beside it, against a stand-in for the `vscode` module: a few parts of the
// API are real enough to watch (settings, commands, messages, the output
// channel, printed to stderr), the rest answers anything. It activates the
// extension with bscript.server.path = SERVER_PATH and bscript.server.args
// = ARGS, and prints what happens in SCENARIO:
//   start  wait for the server to be initialized; run the command
//          bscript.restartServer; change bscript.server.args to
//          ["--changed"]; change unrelated settings; deactivate
//   fail   wait for the error message, and a little; deactivate (a server
//          that cannot start)
//   crash  wait until the server was started 5 times (it crashes); deactivate
//   open   with the document $OPEN_DOCUMENT open: print the diagnostics the
//          server publishes for it and the edits of formatting it through
//          the server; deactivate (for a real `bsc lsp`)
//   debug  the debugger's contribution: the debug adapter the extension
//          starts, the configuration F5 makes for $OPEN_DOCUMENT (the
//          active editor) and for a launch.json without a program, and
//          the command bscript.gotoCycle against a debug session that
//          prints its custom requests; deactivate
// SERVER_PATH is typically Inputs/fake-bsc; $FAKE_BSC_LOG is its side.
'use strict';
const Module = require('module');
const fs = require('fs');
const path = require('path');

const [scenario, extensionDir, serverPath, ...serverArgs] = process.argv.slice(2);
const say = (line) => console.log(line);

// Anything: a function, a constructor, a class to extend, an object with
// any member, an event to subscribe to. Never a promise.
function anything(name) {
  const target = function () {};
  return new Proxy(target, {
    get(t, prop) {
      if (prop === 'then') return undefined;
      if (prop === Symbol.toPrimitive || prop === 'toString') return () => `<${name}>`;
      if (prop === Symbol.iterator) return function* () {};
      if (prop === 'prototype') return t.prototype;
      if (prop === 'dispose') return () => {};
      return anything(`${name}.${String(prop)}`);
    },
    apply() { return anything(`${name}()`); },
    construct() { return anything(`new ${name}`); },
  });
}

// An object whose own members are real and the rest is anything().
function partly(name, real) {
  return new Proxy(real, {
    get(t, prop) {
      if (prop in t) return t[prop];
      if (prop === 'then') return undefined;
      return anything(`${name}.${String(prop)}`);
    },
  });
}

const settings = {
  'bscript.server.path': serverPath,
  'bscript.server.args': serverArgs,
  'bscript.trace.server': process.env.TRACE_SERVER || 'off',
};
const configurationListeners = [];
const commands = {};
const disposable = { dispose() {} };

class EventEmitter {
  constructor() {
    this.listeners = [];
    this.event = (listener) => {
      this.listeners.push(listener);
      return { dispose: () => { this.listeners = this.listeners.filter((l) => l !== listener); } };
    };
  }
  fire(value) { this.listeners.slice().forEach((l) => l(value)); }
  dispose() { this.listeners = []; }
}

// The few value classes the client builds diagnostics and edits from.
class Position {
  constructor(line, character) { this.line = line; this.character = character; }
}
class Range {
  constructor(a, b, c, d) {
    [this.start, this.end] = typeof a === 'number' ? [new Position(a, b), new Position(c, d)] : [a, b];
  }
}
class Diagnostic {
  constructor(range, message, severity) { this.range = range; this.message = message; this.severity = severity; }
}
class TextEdit {
  constructor(range, newText) { this.range = range; this.newText = newText; }
}
class CancellationTokenSource {
  constructor() {
    this.token = { isCancellationRequested: false, onCancellationRequested: () => ({ dispose() {} }) };
  }
  cancel() { this.token.isCancellationRequested = true; }
  dispose() {}
}
class Uri {
  constructor(text) {
    this.text = text;
    this.scheme = text.slice(0, text.indexOf(':'));
    this.fsPath = this.scheme === 'file' ? decodeURIComponent(text.slice('file://'.length)) : text;
    this.path = this.fsPath;
  }
  static parse(text) { return new Uri(text); }
  static file(fsPath) { return new Uri('file://' + fsPath.split('/').map(encodeURIComponent).join('/')); }
  with() { return this; }
  toString() { return this.text; }
  toJSON() { return this.text; }
}
const SEVERITY = ['error', 'warning', 'information', 'hint'];

// $OPEN_DOCUMENT, open in the editor.
const documents = [];
if (process.env.OPEN_DOCUMENT) {
  const file = path.resolve(process.env.OPEN_DOCUMENT);
  const text = fs.readFileSync(file, 'utf8');
  documents.push({
    uri: Uri.file(file), fileName: file, languageId: 'bscript', version: 1,
    isClosed: false, isDirty: false, isUntitled: false, lineCount: text.split('\n').length,
    getText: () => text,
  });
}
const providers = {};
const diagnosticsSeen = [];
const debugRegistrations = {};
let activeDebugSession;
let inputBoxAnswer;

class DebugAdapterExecutable {
  constructor(command, args, options) { this.command = command; this.args = args; this.options = options; }
}

const vscode = partly('vscode', {
  EventEmitter, Position, Range, Diagnostic, TextEdit, Uri, CancellationTokenSource,
  DiagnosticSeverity: { Error: 0, Warning: 1, Information: 2, Hint: 3 },
  languages: partly('vscode.languages', {
    match(selector, document) {
      const list = Array.isArray(selector) ? selector : [selector];
      return list.some((f) => (typeof f === 'string' ? f === document.languageId
        : (!f.language || f.language === document.languageId) && (!f.scheme || f.scheme === document.uri.scheme))) ? 10 : 0;
    },
    createDiagnosticCollection(name) {
      return partly('diagnostics', {
        name,
        set(uri, diagnostics) {
          if (diagnostics && diagnostics.length) diagnosticsSeen.push(...diagnostics);
        },
        delete() {}, clear() {}, dispose() {},
      });
    },
    registerDocumentFormattingEditProvider(selector, provider) {
      providers.formatting = provider;
      return disposable;
    },
  }),
  Disposable: class Disposable {
    constructor(f) { this.f = f; }
    static from(...ds) { return new Disposable(() => ds.forEach((d) => d && d.dispose && d.dispose())); }
    dispose() { if (this.f) this.f(); }
  },
  workspace: partly('vscode.workspace', {
    workspaceFolders: undefined,
    textDocuments: documents,
    notebookDocuments: [],
    getConfiguration(section) {
      return partly('configuration', {
        get(key, fallback) {
          const full = section ? `${section}.${key}` : key;
          return full in settings ? settings[full] : fallback;
        },
      });
    },
    onDidChangeConfiguration(listener) {
      configurationListeners.push(listener);
      return disposable;
    },
    createFileSystemWatcher(glob) {
      say(`watcher: ${glob}`);
      return partly('watcher', { dispose() {} });
    },
  }),
  window: partly('vscode.window', {
    showErrorMessage(message) { errorMessages += 1; say(`error message: ${message}`); return Promise.resolve(undefined); },
    showWarningMessage(message) { say(`warning message: ${message}`); return Promise.resolve(undefined); },
    showInformationMessage(message) { say(`information message: ${message}`); return Promise.resolve(undefined); },
    showInputBox(options) {
      say(`input box: ${options.prompt}; "x" is ${options.validateInput('x')}, "12" is ${options.validateInput('12')}`);
      return Promise.resolve(inputBoxAnswer);
    },
    get activeTextEditor() { return documents.length ? { document: documents[0] } : undefined; },
    createOutputChannel(name) {
      say(`output channel: ${name}`);
      const log = (text) => process.stderr.write(`[${name}] ${text}`);
      return partly('channel', {
        name, append: log, appendLine: (t) => log(t + '\n'), show() {}, hide() {}, clear() {}, dispose() {},
        replace() {},
      });
    },
  }),
  DebugAdapterExecutable,
  debug: partly('vscode.debug', {
    registerDebugAdapterDescriptorFactory(type, factory) {
      say(`debug adapter factory: ${type}`);
      debugRegistrations.factory = factory;
      return disposable;
    },
    registerDebugConfigurationProvider(type, provider) {
      say(`debug configuration provider: ${type}`);
      debugRegistrations.provider = provider;
      return disposable;
    },
    get activeDebugSession() { return activeDebugSession; },
  }),
  commands: partly('vscode.commands', {
    registerCommand(id, callback) {
      say(`command: ${id}`);
      commands[id] = callback;
      return disposable;
    },
    executeCommand() { return Promise.resolve(undefined); },
  }),
  version: '1.90.0',
  env: partly('vscode.env', { language: 'en', appName: 'test', machineId: 'test', sessionId: 'test' }),
});

// As in VS Code's extension host, a promise rejected without a handler
// (vscode-languageclient leaves the write to a server that died
// unawaited) is logged, not fatal.
process.on('unhandledRejection', (reason) => process.stderr.write(`unhandled rejection: ${reason}\n`));

// require('vscode') anywhere gives the stand-in.
const resolve = Module._resolveFilename;
Module._resolveFilename = function (request, ...rest) {
  return request === 'vscode' ? 'vscode' : resolve.call(this, request, ...rest);
};
require.cache.vscode = { id: 'vscode', filename: 'vscode', loaded: true, exports: vscode };

const serverLog = process.env.FAKE_BSC_LOG;
const serverSaid = () => (serverLog && fs.existsSync(serverLog) ? fs.readFileSync(serverLog, 'utf8') : '');
let errorMessages = 0;
async function until(what, condition) {
  for (let i = 0; i < 200; i++) {
    if (condition()) return;
    await new Promise((r) => setTimeout(r, 25));
  }
  say(`timed out waiting for ${what}`);
  process.exit(1);
}
const count = (text, line) => text.split('\n').filter((l) => l === line).length;
const changeSettings = (keys) => configurationListeners.forEach((l) => l({
  affectsConfiguration: (section) => keys.some((k) => k === section || k.startsWith(section + '.')),
}));

async function main() {
  const extension = require(path.resolve(extensionDir, 'extension.js'));
  say(`exports: ${Object.keys(extension).sort().join(' ')}`);
  const context = { subscriptions: [], extensionPath: extensionDir, asAbsolutePath: (p) => path.join(extensionDir, p) };
  await extension.activate(context);
  if (scenario === 'fail') {
    // The error comes when the server's start fails, which a loaded
    // machine may delay past any fixed wait; then a little longer, in case
    // a second message follows (the tests say there is none).
    await until('an error message', () => errorMessages > 0);
    await new Promise((r) => setTimeout(r, 500));
    say('deactivate');
    await extension.deactivate();
    process.exit(0);
  }
  if (scenario === 'open') {
    const document = documents[0];
    await until('diagnostics', () => diagnosticsSeen.length > 0);
    for (const d of diagnosticsSeen) {
      say(`diagnostic: ${d.range.start.line + 1}:${d.range.start.character + 1}: ${SEVERITY[d.severity]}: ${d.message}`);
    }
    await until('formatting', () => providers.formatting);
    const token = new CancellationTokenSource().token;
    const edits = await providers.formatting.provideDocumentFormattingEdits(
      document, { tabSize: 4, insertSpaces: true }, token);
    for (const e of edits || []) {
      say(`edit: ${e.range.start.line + 1}:${e.range.start.character + 1}-${e.range.end.line + 1}:${e.range.end.character + 1}: ${JSON.stringify(e.newText)}`);
    }
    say('deactivate');
    await extension.deactivate();
    process.exit(0);
  }
  if (scenario === 'debug') {
    const descriptor = debugRegistrations.factory.createDebugAdapterDescriptor({}, undefined);
    say(`adapter: ${descriptor ? `${descriptor.command} ${descriptor.args.join(' ')}` : 'none'}`);
    const f5 = debugRegistrations.provider.resolveDebugConfiguration(undefined, {});
    say(`F5 without launch.json: ${JSON.stringify(f5)}`);
    const given = { type: 'bscript', request: 'launch', name: 'x', program: 'A.bs', robots: 2 };
    say(`launch.json: ${JSON.stringify(debugRegistrations.provider.resolveDebugConfiguration(undefined, given))}`);
    const bad = debugRegistrations.provider.resolveDebugConfiguration(undefined, { type: 'bscript', request: 'launch', name: 'y' });
    say(`without a program: ${bad}`);
    await commands['bscript.gotoCycle']();
    activeDebugSession = {
      type: 'bscript',
      customRequest(command, args) { say(`custom request: ${command} ${JSON.stringify(args)}`); return Promise.resolve({}); },
    };
    inputBoxAnswer = '12';
    await commands['bscript.gotoCycle']();
    inputBoxAnswer = undefined;
    await commands['bscript.gotoCycle']();
    say('deactivate');
    await extension.deactivate();
    process.exit(0);
  }
  if (scenario === 'crash') {
    await until('5 starts', () => count(serverSaid(), 'got: initialized') === 5);
    await new Promise((r) => setTimeout(r, 500));
    say(`server started ${serverSaid().split('\n').filter((l) => l.startsWith('started')).length} times`);
    say('deactivate');
    await extension.deactivate();
    process.exit(0);
  }
  await until('the server', () => count(serverSaid(), 'got: initialized') === 1);
  say('server initialized');
  await commands['bscript.restartServer']();
  await until('the restarted server', () => count(serverSaid(), 'got: initialized') === 2);
  say('server restarted');
  settings['bscript.server.args'] = ['--changed'];
  changeSettings(['bscript.server.args']);
  await until('the server with new arguments', () => count(serverSaid(), 'got: initialized') === 3);
  say('server restarted after a change of bscript.server.args');
  settings['bscript.inlayHints.parameterNames'] = true;
  changeSettings(['bscript.inlayHints.parameterNames']);
  await until('the server with inlay hints', () => count(serverSaid(), 'got: initialized') === 4);
  say('server restarted after a change of bscript.inlayHints.parameterNames');
  changeSettings(['editor.tabSize', 'bscript.trace.server']);
  await new Promise((r) => setTimeout(r, 300));
  say('deactivate');
  await extension.deactivate();
  await until('the server to exit', () => count(serverSaid(), 'exited') === 4);
  say(`server's log:\n${serverSaid()}`);
  process.exit(0);
}

main().catch((error) => { say(`failed: ${error && error.stack || error}`); process.exit(1); });

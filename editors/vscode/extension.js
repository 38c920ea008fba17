// The b-script extension: starts `bsc lsp` (the language server of bsc) for
// b-script documents and talks to it over stdin/stdout, and debugs
// behaviors with `bsc dap` (the debug type `bscript`). Highlighting comes
// from the TextMate grammar and works without the server.
//
// Settings: bscript.server.path (the bsc executable, for both), bscript.
// server.args (arguments after `lsp`), bscript.trace.server (read by the
// client itself).
'use strict';

const fs = require('fs');
const os = require('os');
const path = require('path');
const vscode = require('vscode');
const { CloseAction, ErrorAction, LanguageClient } = require('vscode-languageclient/node');

const CLIENT_ID = 'bscript';
const CLIENT_NAME = 'b-script Language Server';

let client;             // the running LanguageClient, if any
let outputChannel;      // kept across restarts so that the log stays in one place
let watcher;            // .bs files and bscript.json changed on disk, for the server
let pending = Promise.resolve();  // starts and stops, one after the other

// The folder a relative server path is relative to: the first workspace
// folder, else the home folder.
function baseFolder() {
  const folders = vscode.workspace.workspaceFolders;
  if (folders && folders.length > 0 && folders[0].uri.scheme === 'file') {
    return folders[0].uri.fsPath;
  }
  return os.homedir();
}

// `~/x`, `${workspaceFolder}/x` and `${userHome}/x` as a shell and VS Code's
// own settings would read them.
function expand(value) {
  let result = value.replace(/\$\{workspaceFolder\}/g, baseFolder())
                    .replace(/\$\{userHome\}/g, os.homedir());
  if (result === '~' || result.startsWith('~/')) {
    result = path.join(os.homedir(), result.slice(1));
  }
  return result;
}

function isExecutableFile(file) {
  try {
    if (!fs.statSync(file).isFile()) {
      return false;
    }
    fs.accessSync(file, fs.constants.X_OK);
    return true;
  } catch (e) {
    return false;
  }
}

// The file `command` runs: a path (relative to baseFolder()) or a name looked
// up in PATH (with PATHEXT on Windows). Undefined if there is none.
function resolveExecutable(command) {
  if (command.includes('/') || command.includes(path.sep)) {
    const file = path.resolve(baseFolder(), command);
    return isExecutableFile(file) ? file : undefined;
  }
  const extensions = process.platform === 'win32'
    ? ['', ...(process.env.PATHEXT || '.EXE;.CMD;.BAT').split(';')]
    : [''];
  for (const dir of (process.env.PATH || '').split(path.delimiter)) {
    if (!dir) {
      continue;
    }
    for (const ext of extensions) {
      const file = path.join(dir, command + ext);
      if (isExecutableFile(file)) {
        return file;
      }
    }
  }
  return undefined;
}

// What to start: { command, args } from the settings.
function serverCommand() {
  const config = vscode.workspace.getConfiguration('bscript');
  const setting = config.get('server.path');
  const command = expand(typeof setting === 'string' && setting.trim() !== '' ? setting.trim() : 'bsc');
  const extra = config.get('server.args');
  const args = ['lsp', ...(Array.isArray(extra) ? extra.map((a) => expand(String(a))) : [])];
  return { command, args };
}

async function showStartError(command, reason, withOutput) {
  const actions = withOutput ? ['Show Output', 'Open Settings'] : ['Open Settings'];
  const choice = await vscode.window.showErrorMessage(
    `b-script: cannot start the language server: ${reason}. ` +
    `Set "bscript.server.path" to the bsc executable (e.g. /opt/bscript/bin/bsc); ` +
    `it is started as \`${command} lsp\`.`,
    ...actions);
  if (choice === 'Open Settings') {
    await vscode.commands.executeCommand('workbench.action.openSettings', 'bscript.server.path');
  } else if (choice === 'Show Output') {
    outputChannel.show(true);
  }
}

// Until the server has answered `initialize`, the client's own messages
// (a connection that errs, closes, an initialization that failed) go to
// the output channel only: startClient says once what went wrong. After
// that a crash is handled as usual (restarted a few times, then reported).
class BscriptClient extends LanguageClient {
  constructor(serverOptions, clientOptions) {
    // Called only once the connection exists, long after super() returned.
    const errorHandler = {
      error: (error, message, count) => (this.initialized
        ? this.fallback.error(error, message, count)
        : { action: ErrorAction.Shutdown, handled: true }),
      closed: () => (this.initialized
        ? this.fallback.closed()
        : { action: CloseAction.DoNotRestart, handled: true }),
    };
    super(CLIENT_ID, CLIENT_NAME, serverOptions,
          { ...clientOptions, errorHandler, initializationFailedHandler: () => false });
    this.initialized = false;
    this.fallback = this.createDefaultErrorHandler();
  }

  error(message, data, showNotification) {
    super.error(message, data, this.initialized ? showNotification : false);
  }
}

async function startClient() {
  const { command, args } = serverCommand();
  const executable = resolveExecutable(command);
  if (!executable) {
    // One message of ours, rather than the client's own about a failed
    // connection: the user's next step is the setting.
    void showStartError(command, `'${command}' was not found or is not executable`, false);
    return;
  }
  // No transport: the client would add `--stdio` to the arguments. Without
  // one it talks over the process's stdin and stdout all the same.
  const serverOptions = {
    command: executable,
    args,
    options: { cwd: baseFolder() },
  };
  const clientOptions = {
    // Read by the server at initialize (docs/editors.md).
    initializationOptions: {
      parameterNameHints: vscode.workspace.getConfiguration('bscript').get('inlayHints.parameterNames') === true,
    },
    documentSelector: [
      { scheme: 'file', language: 'bscript' },
      { scheme: 'untitled', language: 'bscript' },
    ],
    synchronize: {
      // workspace/didChangeWatchedFiles: a module or a behavior's
      // configuration changed on disk (an edit elsewhere, a build).
      fileEvents: watcher,
    },
    outputChannel,
  };
  const started = new BscriptClient(serverOptions, clientOptions);
  client = started;
  try {
    await started.start();
    // start() may resolve without a server: when the connection closes
    // before the answer to `initialize` is read, the client forgets its
    // start promise and returns nothing (a race the client leaves open).
    if (!started.isRunning()) {
      throw new Error('the connection closed during initialize');
    }
    started.initialized = true;
  } catch (error) {
    if (client === started) {
      client = undefined;
    }
    outputChannel.appendLine(`b-script: '${executable} ${args.join(' ')}' did not start: ${error}`);
    void showStartError(command, `'${executable} ${args.join(' ')}' stopped before it answered ` +
                        '(its messages are in the output "b-script Language Server")', true);
  }
}

async function stopClient() {
  const running = client;
  client = undefined;
  if (running) {
    try {
      await running.stop();
    } catch (error) {
      // A server that died already cannot be stopped; it is gone either way.
    }
  }
}

// Queued, so that a burst of setting changes gives one server at the end.
function restart() {
  pending = pending.then(stopClient).then(startClient, startClient);
  return pending;
}

// The debug adapter: `bsc dap` from the same bsc as the language server.
const debugAdapterFactory = {
  createDebugAdapterDescriptor() {
    const { command } = serverCommand();
    const executable = resolveExecutable(command);
    if (!executable) {
      void vscode.window.showErrorMessage(
        `b-script: cannot debug: '${command}' was not found or is not executable. ` +
        'Set "bscript.server.path" to the bsc executable; the debugger is started as ' +
        `\`${command} dap\`.`);
      return undefined;
    }
    return new vscode.DebugAdapterExecutable(executable, ['dap'], { cwd: baseFolder() });
  },
};

// F5 without a launch.json debugs the b-script file in the editor; a
// configuration without a program is refused with a message.
const debugConfigurationProvider = {
  resolveDebugConfiguration(folder, config) {
    if (!config.type && !config.request && !config.name) {
      const editor = vscode.window.activeTextEditor;
      if (editor && editor.document.languageId === 'bscript') {
        config = { type: 'bscript', request: 'launch', name: 'Debug the behavior',
                   program: editor.document.fileName, stopOnEntry: true };
      }
    }
    if (!config.program) {
      void vscode.window.showErrorMessage(
        'b-script: a launch configuration names the behavior\'s files in "program"');
      return undefined;
    }
    return config;
  },
};

// b-script: Go to Cycle... (the debug console's `:goto N` as a command).
async function gotoCycle() {
  const session = vscode.debug.activeDebugSession;
  if (!session || session.type !== 'bscript') {
    void vscode.window.showErrorMessage('b-script: no b-script debug session is running');
    return;
  }
  const text = await vscode.window.showInputBox({
    prompt: 'The cycle to go to (back or forth in the session\'s history)',
    validateInput: (value) => (/^\s*\d+\s*$/.test(value) ? undefined : 'a cycle number, from 0'),
  });
  if (text === undefined) {
    return;
  }
  try {
    await session.customRequest('bscript/gotoCycle', { cycle: Number(text) });
  } catch (error) {
    void vscode.window.showErrorMessage(`b-script: ${error && error.message || error}`);
  }
}

function activate(context) {
  outputChannel = vscode.window.createOutputChannel(CLIENT_NAME);
  watcher = vscode.workspace.createFileSystemWatcher('**/{*.bs,bscript.json}');
  context.subscriptions.push(
    outputChannel,
    watcher,
    vscode.commands.registerCommand('bscript.restartServer', () => restart()),
    vscode.commands.registerCommand('bscript.gotoCycle', gotoCycle),
    vscode.debug.registerDebugAdapterDescriptorFactory('bscript', debugAdapterFactory),
    vscode.debug.registerDebugConfigurationProvider('bscript', debugConfigurationProvider),
    vscode.workspace.onDidChangeConfiguration((event) => {
      if (event.affectsConfiguration('bscript.server') ||
          event.affectsConfiguration('bscript.inlayHints')) {
        void restart();
      }
    }),
    { dispose: () => { void stopClient(); } });
  // Not awaited: activation does not wait for the server's answer.
  pending = pending.then(startClient);
}

function deactivate() {
  return stopClient();
}

module.exports = { activate, deactivate };

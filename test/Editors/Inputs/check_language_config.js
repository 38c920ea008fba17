// node check_language_config.js LANGUAGE_CONFIGURATION.json FILE_OR_DIR...
//
// Checks editors/vscode/language-configuration.json against real b-script:
// its patterns are compiled as VS Code compiles them (JavaScript RegExp),
// and in every .bs file (folders are searched) each code line outside
// parentheses must
// - match increaseIndentPattern and the onEnterRule that indents exactly
//   when the next code line is indented deeper (a block starts: task,
//   func, if, else, for, enum);
// - match the onEnterRule that outdents only when the next code line is
//   indented less (break, continue, return end their block);
// and a line starting with `else` must match decreaseIndentPattern.
// Also: `#` comments, () and [] brackets, "" auto-closed, folding by
// indentation. Prints one line per problem and a summary; exits 1 on any.
'use strict';
const fs = require('fs');
const path = require('path');

const [configPath, ...inputs] = process.argv.slice(2);
const config = JSON.parse(fs.readFileSync(configPath, 'utf8'));
const problems = [];
const expect = (ok, what) => { if (!ok) problems.push(what); };

expect(config.comments && config.comments.lineComment === '#', 'lineComment is not #');
const pairs = JSON.stringify(config.brackets);
expect(pairs === JSON.stringify([['(', ')'], ['[', ']']]), `brackets are ${pairs}`);
expect(config.autoClosingPairs.some((p) => p.open === '"' && p.close === '"'), '" is not auto-closed');
expect(config.folding && config.folding.offSide === true, 'folding is not offSide');

const increase = new RegExp(config.indentationRules.increaseIndentPattern);
const decrease = new RegExp(config.indentationRules.decreaseIndentPattern);
const enterRule = (kind) => config.onEnterRules.filter((r) => r.action.indent === kind)
  .map((r) => new RegExp(r.beforeText));
const indentRules = enterRule('indent');
const outdentRules = enterRule('outdent');
expect(indentRules.length === 1 && outdentRules.length === 1, 'expected one indent and one outdent onEnterRule');

function files(p) {
  if (fs.statSync(p).isDirectory()) {
    return fs.readdirSync(p).sort().flatMap((e) => files(path.join(p, e)));
  }
  return p.endsWith('.bs') ? [p] : [];
}

// The line without its comment and string contents, for counting parens.
function code(line) {
  return line.replace(/"(?:[^"\\]|\\.)*"?/g, '""').replace(/#.*$/, '');
}

let checked = 0, blocks = 0, outdents = 0;
const all = inputs.flatMap(files);
for (const file of all) {
  const lines = fs.readFileSync(file, 'utf8').split(/\r?\n/);
  const codeLines = [];
  let depth = 0;
  lines.forEach((line, i) => {
    const before = depth;
    for (const c of code(line)) {
      if (c === '(' || c === '[') depth++;
      if (c === ')' || c === ']') depth = Math.max(0, depth - 1);
    }
    if (code(line).trim() === '') return;
    // Only lines that start and end outside parentheses are statements.
    codeLines.push({ i, line, statement: before === 0 && depth === 0, indent: /^\s*/.exec(line)[0].length });
  });
  codeLines.forEach((l, k) => {
    if (!l.statement) return;
    const next = codeLines[k + 1];
    const opens = next !== undefined && next.indent > l.indent;
    const closes = next === undefined || next.indent < l.indent;
    const where = `${file}:${l.i + 1}: '${l.line.trim()}'`;
    checked++;
    if (opens) blocks++;
    expect(increase.test(l.line) === opens,
           `${where}: increaseIndentPattern ${opens ? 'misses a block header' : 'matches a line that opens no block'}`);
    expect(indentRules[0].test(l.line) === opens,
           `${where}: the indenting onEnterRule ${opens ? 'misses a block header' : 'matches a line that opens no block'}`);
    if (outdentRules[0].test(l.line)) {
      outdents++;
      expect(closes, `${where}: the outdenting onEnterRule matches, but the block goes on`);
    }
    if (/^\s*else\b/.test(l.line)) {
      expect(decrease.test(l.line), `${where}: decreaseIndentPattern misses else`);
    }
  });
}
problems.forEach((p) => console.log(p));
console.log(`${all.length} files, ${checked} statements, ${blocks} block headers, ${outdents} outdents, ${problems.length} problems`);
process.exit(problems.length ? 1 : 0);

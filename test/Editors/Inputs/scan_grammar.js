// node scan_grammar.js NODE_MODULES GRAMMAR FILE_OR_DIR...
//
// Tokenizes b-script programs (.bs files; folders are searched) with the
// TextMate grammar, by the vscode-textmate and vscode-oniguruma that
// vscode-tmgrammar-test brings, and reports what a correct program must
// not show:
// - a token the grammar calls invalid (invalid.illegal.*);
// - a declaration (task, func, enum, const, requires at the start of a
//   line) whose keyword does not get its scope, or that a region of an
//   earlier line (a parameter list, an enum body) still covers;
// - a task or func header whose name is not entity.name.function.bscript.
// Prints one line per problem and a summary; exits 1 on any problem.
'use strict';
const fs = require('fs');
const path = require('path');

const [modules, grammarPath, ...inputs] = process.argv.slice(2);
function bsFiles(p) {
  if (fs.statSync(p).isDirectory()) {
    return fs.readdirSync(p).sort().flatMap((e) => bsFiles(path.join(p, e)));
  }
  return p.endsWith('.bs') ? [p] : [];
}
const files = inputs.flatMap(bsFiles);
const textmate = require(path.join(modules, 'vscode-textmate'));
const oniguruma = require(path.join(modules, 'vscode-oniguruma'));

const KEYWORD_SCOPE = {
  task: 'storage.type.task.bscript',
  func: 'storage.type.function.bscript',
  enum: 'storage.type.enum.bscript',
  const: 'storage.modifier.const.bscript',
  requires: 'keyword.control.import.bscript',
};
const REGIONS = ['meta.function.parameters.bscript', 'meta.enum.bscript', 'string.quoted.double.bscript'];

async function main() {
  const wasm = fs.readFileSync(path.join(path.dirname(require.resolve(path.join(modules, 'vscode-oniguruma'))), 'onig.wasm'));
  await oniguruma.loadWASM(wasm.buffer.slice(wasm.byteOffset, wasm.byteOffset + wasm.byteLength));
  const registry = new textmate.Registry({
    onigLib: Promise.resolve({
      createOnigScanner: (sources) => new oniguruma.OnigScanner(sources),
      createOnigString: (s) => new oniguruma.OnigString(s),
    }),
    loadGrammar: async () => textmate.parseRawGrammar(fs.readFileSync(grammarPath, 'utf8'), grammarPath),
  });
  const grammar = await registry.loadGrammar('source.bscript');
  const problems = [];
  let lines = 0, declarations = 0;
  for (const file of files) {
    let stack = textmate.INITIAL;
    fs.readFileSync(file, 'utf8').split(/\r?\n/).forEach((line, i) => {
      const where = `${file}:${i + 1}`;
      const { tokens, ruleStack } = grammar.tokenizeLine(line, stack);
      stack = ruleStack;
      lines++;
      for (const t of tokens) {
        const bad = t.scopes.find((s) => s.startsWith('invalid.'));
        if (bad) {
          problems.push(`${where}:${t.startIndex + 1}: ${bad}: '${line.slice(t.startIndex, t.endIndex)}'`);
        }
      }
      const m = /^(\s*)(task|func|enum|const|requires)\b/.exec(line);
      if (!m) {
        return;
      }
      declarations++;
      const start = m[1].length;
      const first = tokens.find((t) => t.startIndex <= start && start < t.endIndex);
      if (!first.scopes.includes(KEYWORD_SCOPE[m[2]])) {
        problems.push(`${where}: '${m[2]}' is ${first.scopes.join(' ')}`);
      }
      const region = first.scopes.find((s) => REGIONS.includes(s) && !(m[2] === 'enum' && s === 'meta.enum.bscript'));
      if (region) {
        problems.push(`${where}: '${m[2]}' is inside ${region} of an earlier line`);
      }
      const header = /^\s*(?:task|func)\s+([A-Za-z_]\w*)/.exec(line);
      if (header) {
        const at = line.indexOf(header[1], start + 4);
        const name = tokens.find((t) => t.startIndex <= at && at < t.endIndex);
        if (!name.scopes.includes('entity.name.function.bscript')) {
          problems.push(`${where}: '${header[1]}' is ${name.scopes.join(' ')}`);
        }
      }
    });
  }
  problems.forEach((p) => console.log(p));
  console.log(`${files.length} files, ${lines} lines, ${declarations} declarations, ${problems.length} problems`);
  process.exit(problems.length ? 1 : 0);
}

main().catch((e) => { console.error(e); process.exit(2); });

// bsc timeline page, search.js: parsing and compiling search queries and
// finding the first, next or previous matching cycle.

// ---------------------------------------------------------------- search

// TASK | TASK = STATE | PATH OP VALUE
function parseQuery(text) {
  const q = text.trim();
  if (!q) throw new Error('type a query: TASK, TASK = STATE or PATH OP VALUE');
  const m = /^([^\s=!<>]+)\s*(==|=|!=|<=|>=|<|>)\s*(.*)$/.exec(q);
  if (!m) {
    if (/[\s=!<>]/.test(q)) throw new Error('expected TASK, TASK = STATE or PATH OP VALUE');
    return { name: q, op: null, value: null };
  }
  const value = m[3].trim();
  if (!value) throw new Error('a value is missing after ' + m[2]);
  return { name: m[1], op: m[2] === '==' ? '=' : m[2], value };
}

function unquote(v) {
  const m = /^"(.*)"$/.exec(v) || /^'(.*)'$/.exec(v);
  return m ? m[1] : v;
}

function findTask(run, name) { return run.tasks.find((t) => t.name === name || t.short === name); }

// Turns a parsed query into, per run, a sorted flat list of matching
// inclusive cycle intervals [s, e, s, e, ...] (null: the run lacks it).
function compileQuery(q) {
  const taskRuns = S.runs.map((run) => findTask(run, q.name));
  const seriesRuns = S.runs.map((run) => run.seriesByPath.get(q.name));
  if (taskRuns.some(Boolean) && (q.op === null || (q.op === '=' && !seriesRuns.some(Boolean)))) {
    return taskRuns.map((t) => t && taskIntervals(t, q.op === null ? null : unquote(q.value)));
  }
  if (q.op === '=' && taskRuns.some(Boolean)) {
    return taskRuns.map((t) => t && taskIntervals(t, unquote(q.value)));
  }
  if (seriesRuns.some(Boolean)) {
    if (q.op === null) throw new Error(q.name + ' is a field: add an operator and a value, e.g. ' + q.name + ' = 1');
    const s = seriesRuns.find(Boolean);
    const pred = valuePredicate(s.kind, q.op, q.value);
    return seriesRuns.map((sr) => sr && seriesIntervals(sr, pred));
  }
  if (q.op !== null && q.op !== '=' && taskRuns.some(Boolean)) throw new Error('a task takes only = STATE');
  throw new Error('no task or field named ' + q.name);
}

function taskIntervals(task, state) {
  const segs = task.segments, out = [];
  for (let i = 0; i < segs.length; i += 5) {
    if (state !== null && str(segs[i + 2]) !== state) continue;
    pushInterval(out, segs[i], segs[i + 1]);
  }
  return out;
}

function seriesIntervals(series, pred) {
  const ch = series.changes, out = [];
  for (let i = 0; i < ch.length; i += 2) {
    const end = i + 2 < ch.length ? ch[i + 2] - 1 : S.last;
    if (ch[i + 1] !== null && pred(ch[i + 1])) pushInterval(out, ch[i], end);
  }
  return out;
}

function pushInterval(out, s, e) {
  if (out.length && out[out.length - 1] + 1 >= s) out[out.length - 1] = Math.max(out[out.length - 1], e);
  else out.push(s, e);
}

// A predicate on one value of a series of the given kind.
function valuePredicate(kind, op, raw) {
  if (kind === 'bool') {
    if (op !== '=' && op !== '!=') throw new Error('a bool takes only = or !=');
    if (raw !== 'true' && raw !== 'false') throw new Error('expected true or false, not ' + raw);
    const want = raw === 'true';
    return (v) => (v === want) === (op === '=');
  }
  if (kind === 'number') {
    const want = toNumber(raw === 'NaN' || raw === 'Infinity' || raw === '-Infinity' ? raw : Number(unquote(raw)));
    if (Number.isNaN(want) && raw !== 'NaN') throw new Error(raw + ' is not a number');
    if (Number.isNaN(want)) {
      if (op !== '=' && op !== '!=') throw new Error('NaN takes only = or !=');
      return (v) => Number.isNaN(toNumber(v)) === (op === '=');
    }
    return (v) => compare(toNumber(v), op, want);
  }
  const want = unquote(raw);
  return (v) => compare(String(v), op, want);
}

function compare(a, op, b) {
  switch (op) {
    case '=': return a === b;
    case '!=': return a !== b;
    case '<': return a < b;
    case '<=': return a <= b;
    case '>': return a > b;
    default: return a >= b;
  }
}

// The first cycle >= from that lies in an interval and in the run.
function searchForward(run, iv, from) {
  const n = iv.length / 2;
  for (let i = lowerBound(n, (k) => iv[2 * k + 1] >= from); i < n; i++) {
    const p = nextIn(run.cycles, Math.max(from, iv[2 * i]));
    if (p !== null && p <= iv[2 * i + 1]) return p;
    if (p === null) return null;
  }
  return null;
}

// The last cycle <= to that lies in an interval and in the run.
function searchBackward(run, iv, to) {
  const n = iv.length / 2;
  for (let i = lowerBound(n, (k) => iv[2 * k] > to) - 1; i >= 0; i--) {
    const p = prevIn(run.cycles, Math.min(to, iv[2 * i + 1]));
    if (p !== null && p >= iv[2 * i]) return p;
    if (p === null) return null;
  }
  return null;
}

// Compiles the query in the box (cached while the text is unchanged).
function currentQuery() {
  const text = $('search').value;
  if (!S.query || S.query.text !== text) {
    try { S.query = { text, intervals: compileQuery(parseQuery(text)) }; } catch (e) { S.query = { text, error: e.message }; }
  }
  return S.query;
}

function runSearch(direction) {
  const q = currentQuery();
  if (q.error) { setSearchStatus(q.error, 'error'); return; }
  const hits = [];
  S.runs.forEach((run, r) => {
    const iv = q.intervals[r];
    if (!iv) return;
    const c = direction === 'prev' ? searchBackward(run, iv, S.cursor - 1)
      : searchForward(run, iv, direction === 'first' ? -Infinity : S.cursor + 1);
    if (c !== null) hits.push(c);
  });
  if (hits.length === 0) { setSearchStatus('not found', ''); return; }
  const c = direction === 'prev' ? Math.max(...hits) : Math.min(...hits);
  setCursor(c, true);
  setSearchStatus('cycle ' + c, 'found');
}

function setSearchStatus(text, cls) {
  const st = $('search-status');
  st.textContent = text;
  st.className = cls;
}

// bsc timeline page, data.js: reading and preparing the runs from the JSON
// data, lookups by cycle (present cycles, segments, values) and the states'
// colours.

// --------------------------------------------------------------- reading

function readData() {
  const node = $('bsc-timeline-data');
  const text = node ? node.textContent.trim() : '';
  if (!text || text.startsWith('@BSC_')) throw new Error('the page holds no timeline data');
  let data;
  try { data = JSON.parse(text); } catch (e) { throw new Error('the data is not valid JSON (' + e.message + ')'); }
  if (!data || typeof data !== 'object') throw new Error('the data is not an object');
  if (data.format !== 1) throw new Error('data format ' + data.format + ' is not supported (this page reads format 1)');
  if (!Array.isArray(data.runs) || data.runs.length === 0) throw new Error('the data has no runs');
  return data;
}

// Normalises one run and precomputes what drawing and lookups need.
function prepareRun(raw, index) {
  const run = {
    index,
    name: String(raw.name || 'run'),
    kind: raw.kind || 'record',
    // A team's file is a run per robot; `record` says which file.
    robot: Number.isInteger(raw.robot) && raw.robot >= 0 ? raw.robot : null,
    record: raw.record === 1 || (raw.record === undefined && index === 1) ? 1 : 0,
    cycles: Array.isArray(raw.cycles) ? raw.cycles : [],
    tasks: Array.isArray(raw.tasks) ? raw.tasks : [],
    series: Array.isArray(raw.series) ? raw.series : [],
    seriesByPath: new Map(),
  };
  run.tasks.forEach((t) => {
    t.segments = Array.isArray(t.segments) ? t.segments : [];
    t.fields = Array.isArray(t.fields) ? t.fields : [];
    t.short = t.short || t.name;
  });
  for (const s of run.series) run.seriesByPath.set(s.path, s);
  for (const t of run.tasks) for (const f of t.fields) if (f.series) run.seriesByPath.set(f.series.path, f.series);
  computeDepths(run);
  return run;
}

// A lane is indented by the task's depth where it first appears: the
// hierarchy can change from cycle to cycle, but labels that jump while
// scrubbing would be hard to follow.
function computeDepths(run) {
  const depth = new Array(run.tasks.length).fill(-1);
  const visit = (i, guard) => {
    if (depth[i] >= 0) return depth[i];
    const segs = run.tasks[i].segments;
    const parent = segs.length >= 5 ? segs[4] : -1;
    const ok = parent >= 0 && parent < run.tasks.length && guard < run.tasks.length;
    depth[i] = ok ? visit(parent, guard + 1) + 1 : 0;
    return depth[i];
  };
  run.tasks.forEach((t, i) => { t.depth = visit(i, 0); });
}

// The cycle domain and the merged list of cycles present in any run.
function computeDomain() {
  const all = [];
  for (const run of S.runs) for (const r of run.cycles) all.push([r[0], r[1]]);
  all.sort((a, b) => a[0] - b[0]);
  const merged = [];
  for (const r of all) {
    const top = merged[merged.length - 1];
    if (top && r[0] <= top[1] + 1) top[1] = Math.max(top[1], r[1]);
    else merged.push([r[0], r[1]]);
  }
  S.present = merged;
  S.first = merged.length ? merged[0][0] : 0;
  S.last = merged.length ? merged[merged.length - 1][1] : 0;
}

// ------------------------------------------------------- cycles and values

// Smallest cycle >= c in the ranges, or null.
function nextIn(ranges, c) {
  const i = lowerBound(ranges.length, (k) => ranges[k][1] >= c);
  if (i >= ranges.length) return null;
  return Math.max(c, ranges[i][0]);
}

// Largest cycle <= c in the ranges, or null.
function prevIn(ranges, c) {
  const i = lowerBound(ranges.length, (k) => ranges[k][0] > c) - 1;
  if (i < 0) return null;
  return Math.min(c, ranges[i][1]);
}

function isPresent(run, c) { return nextIn(run.cycles, c) === c; }

// The present cycle nearest to c (ties go to the earlier one).
function snapToPresent(c) {
  const a = prevIn(S.present, c), b = nextIn(S.present, c);
  if (a === null) return b === null ? c : b;
  if (b === null) return a;
  return c - a <= b - c ? a : b;
}

// Index of the segment of a task covering cycle c, or -1.
function segmentAt(task, c) {
  const segs = task.segments, n = segs.length / 5;
  const i = lowerBound(n, (k) => segs[5 * k + 1] >= c);
  return i < n && segs[5 * i] <= c ? i : -1;
}

// Index (in pairs) of the last change at or before cycle c, or -1.
function changeAt(series, c) {
  const ch = series.changes;
  return lowerBound(ch.length / 2, (k) => ch[2 * k] > c) - 1;
}

function valueAt(series, c) {
  if (!series) return null;
  const i = changeAt(series, c);
  return i < 0 ? null : series.changes[2 * i + 1];
}

function formatValue(v) {
  if (v === null || v === undefined) return 'null';
  if (typeof v === 'boolean') return v ? 'true' : 'false';
  return String(v);
}

// Numbers may come as the strings "NaN", "Infinity", "-Infinity".
function toNumber(v) {
  if (typeof v === 'number') return v;
  if (typeof v === 'boolean') return v ? 1 : 0;
  if (v === 'Infinity') return Infinity;
  if (v === '-Infinity') return -Infinity;
  return NaN;
}

// -------------------------------------------------------------- colours

function assignStateColors() {
  const names = new Set();
  for (const run of S.runs) for (const t of run.tasks) {
    for (let i = 2; i < t.segments.length; i += 5) names.add(str(t.segments[i]));
  }
  const taken = new Set();
  const sorted = [...names].sort();
  for (const name of sorted) {
    if (STATE_COLORS[name]) { S.stateColor.set(name, STATE_COLORS[name]); continue; }
    let h = 0;
    for (let i = 0; i < name.length; i++) h = (h * 31 + name.charCodeAt(i)) >>> 0;
    let k = h % PALETTE.length;
    // Probe for a free colour so two states on one page never share one.
    for (let tries = 0; tries < PALETTE.length && taken.has(k); tries++) k = (k + 1) % PALETTE.length;
    taken.add(k);
    S.stateColor.set(name, PALETTE[k]);
  }
}

function colorOf(stateName) { return S.stateColor.get(stateName) || '#888'; }

// Legend order: the three built-in states first, then the named ones.
function legendStates() {
  const names = [...S.stateColor.keys()];
  const rank = (n) => (n in STATE_COLORS ? Object.keys(STATE_COLORS).indexOf(n) : 9);
  return names.sort((a, b) => rank(a) - rank(b) || (a < b ? -1 : a > b ? 1 : 0));
}

// bsc timeline page, plots.js: the plots of number and bool series under
// the lanes, and the field chooser that adds and removes them.

// --------------------------------------------------------------- plots

// Every number or bool series that can be plotted, unique by path:
// input, output, then task fields.
function plotCandidates() {
  const seen = new Map();
  const add = (s) => {
    if (s && (s.kind === 'number' || s.kind === 'bool') && !seen.has(s.path)) seen.set(s.path, s.kind);
  };
  for (const run of S.runs) run.series.forEach(add);
  for (const run of S.runs) for (const t of run.tasks) for (const f of t.fields) add(f.series);
  return [...seen].map(([path, kind]) => ({ path, kind }));
}

// Per series, the change cycles and numeric values, plus a min/max tree
// over the change indices so one pixel column's range is O(log n).
function plotData(run, path) {
  run.plotCache = run.plotCache || new Map();
  if (run.plotCache.has(path)) return run.plotCache.get(path);
  const s = run.seriesByPath.get(path);
  let pd = null;
  if (s) {
    const n = s.changes.length / 2;
    const cyc = new Float64Array(n), val = new Float64Array(n);
    for (let i = 0; i < n; i++) {
      cyc[i] = s.changes[2 * i];
      const v = s.changes[2 * i + 1];
      val[i] = v === null ? NaN : toNumber(v);
    }
    pd = { cyc, val, n, tree: minMaxTree(val) };
  }
  run.plotCache.set(path, pd);
  return pd;
}

// A bottom-up segment tree of min and max; non-finite values are left out.
function minMaxTree(val) {
  let size = 1;
  while (size < val.length) size *= 2;
  const mn = new Float64Array(2 * size).fill(Infinity), mx = new Float64Array(2 * size).fill(-Infinity);
  for (let i = 0; i < val.length; i++) if (isFinite(val[i])) { mn[size + i] = val[i]; mx[size + i] = val[i]; }
  for (let i = size - 1; i >= 1; i--) {
    mn[i] = Math.min(mn[2 * i], mn[2 * i + 1]);
    mx[i] = Math.max(mx[2 * i], mx[2 * i + 1]);
  }
  return { size, mn, mx };
}

// [min, max] over indices lo..hi inclusive.
function queryMinMax(t, lo, hi) {
  let a = Infinity, b = -Infinity;
  for (let l = lo + t.size, r = hi + t.size + 1; l < r; l >>= 1, r >>= 1) {
    if (l & 1) { a = Math.min(a, t.mn[l]); b = Math.max(b, t.mx[l]); l++; }
    if (r & 1) { r--; a = Math.min(a, t.mn[r]); b = Math.max(b, t.mx[r]); }
  }
  return [a, b];
}

function plotRange(path) {
  let lo = Infinity, hi = -Infinity;
  for (const run of S.runs) {
    const pd = plotData(run, path);
    if (pd && pd.n) { lo = Math.min(lo, pd.tree.mn[1]); hi = Math.max(hi, pd.tree.mx[1]); }
  }
  if (lo > hi) return [0, 1];
  if (lo === hi) return [lo - 1, hi + 1];
  return [lo, hi];
}

function buildPlots() {
  const box = $('plots');
  box.textContent = '';
  S.canvases = Object.fromEntries(Object.entries(S.canvases).filter(([k]) => !k.startsWith('plot:')));
  if (S.plots.length === 0) {
    const hint = el('div', 'hint', plotCandidates().length
      ? 'Tick fields under "Plot fields" in the panel to plot them here.'
      : 'No numeric fields to plot.');
    box.appendChild(hint);
    return;
  }
  for (const path of S.plots) box.appendChild(plotRow(path));
}

function plotRow(path) {
  const row = el('div', 'row plot-row');
  row.dataset.plot = path;
  const label = el('div', 'label-col');
  label.appendChild(el('div', 'path', path)).title = path;
  const [lo, hi] = plotRange(path);
  label.appendChild(el('div', 'range', formatNum(lo) + ' \u2026 ' + formatNum(hi)));
  if (S.runs.length > 1) {
    const key = el('div', 'key');
    S.runs.forEach((run) => {
      const k = el('span', '', runTag(run));
      const sw = el('i');
      sw.style.background = runColor(run);
      k.prepend(sw);
      key.appendChild(k);
    });
    label.appendChild(key);
  }
  const remove = el('button', '', 'remove');
  remove.addEventListener('click', () => togglePlot(path, false));
  label.appendChild(remove);
  const col = el('div', 'canvas-col');
  const canvas = el('canvas');
  canvas.dataset.plot = path;
  col.appendChild(canvas);
  row.append(label, col);
  const cv = setupCanvas('plot:' + path, canvas);
  cv.path = path;
  cv.range = [lo, hi];
  attachScrub(canvas);
  return row;
}

function formatNum(v) {
  if (!isFinite(v)) return String(v);
  return Math.abs(v) >= 1e6 || (v !== 0 && Math.abs(v) < 1e-3) ? v.toExponential(3) : String(+v.toFixed(4));
}

function plotY(cv, v) {
  const [lo, hi] = cv.range, pad = 8;
  return pad + (hi - v) / (hi - lo) * (cv.h - 2 * pad);
}

function drawPlotBase(cv) {
  const g = cv.bctx;
  g.fillStyle = '#fff';
  g.fillRect(0, 0, cv.w, cv.h);
  g.strokeStyle = '#eef0f3';
  g.beginPath();
  for (const f of [0, 0.5, 1]) {
    const y = Math.round(plotY(cv, cv.range[0] + f * (cv.range[1] - cv.range[0]))) + 0.5;
    g.moveTo(0, y); g.lineTo(cv.w, y);
  }
  g.stroke();
  S.runs.forEach((run) => {
    const pd = plotData(run, cv.path);
    if (pd) drawPlotLine(g, cv, pd, runColor(run));
  });
  if (S.difference) drawDiffLine(g, cv.h);
}

// One vertical bar per pixel column from the column's min to its max (and
// to the previous column's last value, so steps join up): a step plot when
// zoomed in, a min/max envelope when zoomed out.
function drawPlotLine(g, cv, pd, color) {
  g.fillStyle = color;
  const k = S.view.span / cv.w;
  let prev = NaN;
  for (let x = 0; x < cv.w; x++) {
    const c0 = S.view.start + x * k, c1 = c0 + k;
    const lo = lowerBound(pd.n, (i) => pd.cyc[i] > c0) - 1;   // value at the column's start
    const hi = lowerBound(pd.n, (i) => pd.cyc[i] >= c1) - 1;  // last change inside it
    if (hi < 0) { prev = NaN; continue; }
    let [a, b] = queryMinMax(pd.tree, Math.max(lo, 0), hi);
    const last = pd.val[hi];
    if (a > b) { prev = NaN; continue; }                       // no finite value
    if (isFinite(prev)) { a = Math.min(a, prev); b = Math.max(b, prev); }
    const y0 = plotY(cv, b), y1 = plotY(cv, a);
    g.fillRect(x, Math.floor(y0) - 0.5, 1, Math.max(1.5, y1 - y0 + 1));
    prev = isFinite(last) ? last : NaN;
  }
}

function drawPlotOverlay(cv) {
  copyBase(cv);
  const g = cv.ctx;
  drawCursorLine(g, cv.h);
  // The values at the cursor, next to the cursor line.
  const x = xOf(S.cursor + 0.5);
  const parts = S.runs.map((run) => {
    const v = valueAt(run.seriesByPath.get(cv.path), S.cursor);
    return (S.runs.length > 1 ? runTag(run) + ' ' : '') + formatValue(v);
  });
  const text = parts.join('   ');
  g.font = '11px ui-monospace, "DejaVu Sans Mono", Menlo, monospace';
  const w = g.measureText(text).width + 8;
  const bx = x + 6 + w > cv.w ? x - 6 - w : x + 6;
  g.fillStyle = 'rgba(255,255,255,0.9)';
  g.fillRect(bx, 3, w, 15);
  g.fillStyle = '#1f2328';
  g.textAlign = 'left';
  g.textBaseline = 'middle';
  g.fillText(text, bx + 4, 11);
}

function togglePlot(path, on) {
  const i = S.plots.indexOf(path);
  if (on && i < 0) S.plots.push(path);
  if (!on && i >= 0) S.plots.splice(i, 1);
  const box = document.querySelector('#fields input[data-plot="' + cssEscape(path) + '"]');
  if (box) box.checked = on;
  buildPlots();
  invalidate(true);
  render();
}

function cssEscape(s) { return window.CSS && CSS.escape ? CSS.escape(s) : s.replace(/["\\]/g, '\\$&'); }

function buildFieldChooser() {
  const box = $('fields');
  box.textContent = '';
  const cands = plotCandidates();
  if (cands.length === 0) { box.appendChild(el('div', 'none', 'no numeric fields')); return; }
  for (const { path, kind } of cands) {
    const label = el('label');
    const cb = el('input');
    cb.type = 'checkbox';
    cb.dataset.plot = path;
    cb.addEventListener('change', () => togglePlot(path, cb.checked));
    label.append(cb, el('span', '', path), el('span', 'kind', kind));
    box.appendChild(label);
  }
  $('fields-filter').addEventListener('input', filterFields);
}

function filterFields() {
  const q = $('fields-filter').value.trim().toLowerCase();
  for (const label of $('fields').querySelectorAll('label')) {
    const path = label.querySelector('input').dataset.plot.toLowerCase();
    label.hidden = q !== '' && !path.includes(q);
  }
}

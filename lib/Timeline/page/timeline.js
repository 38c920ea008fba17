// bsc timeline: the page's script. Plain ES2020, no modules, no dependencies.
//
// The data (format 1, see the spec) is read from the JSON script element.
// Everything drawn over cycles goes onto canvases, painted per pixel column
// with a binary search to the interval under the column, so drawing costs
// O(pixels * log n) whatever the number of cycles. Each canvas keeps a "base"
// image (lanes, ticks, plot lines) that changes only when the view changes;
// moving the cursor just copies the base and draws the cursor on top.
(function () {
  'use strict';

  // ---------------------------------------------------------------- constants

  const LANE_H = 22;          // must match --lane-h in the CSS
  const RULER_H = 26;
  const OVERVIEW_H = 24;
  const PLOT_H = 90;
  const MAX_PX_PER_CYCLE = 160;
  const STATE_COLORS = { running: '#4a86d8', done: '#34a853', failure: '#d93025' };
  // Colours for named states and "state N", picked by a hash of the name so a
  // state keeps its colour from one page to the next.
  // Blue, green and red are left to running, done and failure.
  const PALETTE = ['#9c6ade', '#e8a33d', '#12a4a0', '#d45fa0', '#8a9a2c',
    '#c9743f', '#5c6bc0', '#a1887f', '#6d8a96', '#b15dc9', '#c8a600', '#2e7d6b'];
  const RUN_COLORS = ['#1a73e8', '#e37400'];
  const CURSOR = '#e8710a';
  const DIFF = '#c5221f';

  const $ = (id) => document.getElementById(id);

  // All mutable state of the page.
  const S = {
    runs: [],            // prepared runs (see prepareRun)
    strings: [],
    difference: null,
    first: 0, last: 0,   // cycle domain over all runs, inclusive
    present: [],         // union of all runs' cycle ranges, merged
    rows: [],            // lane rows in drawn order: {kind:'header'|'lane'|'empty', run, task}
    view: { start: 0, span: 1 },  // cycles [start, start+span) across the canvases
    width: 1,            // CSS px width of the canvases
    cursor: 0,
    plots: [],           // chosen plot paths, in the order chosen
    stateColor: new Map(),
    colorByIndex: [],    // string index -> colour, filled lazily
    canvases: {},        // name -> {el, base, ctx, bctx, w, h}
    dirty: { base: false, overlay: false },
    frame: 0,
    query: null,         // cached parsed search: {text, result}
    ready: false,
  };

  // ------------------------------------------------------------- small utils

  // First index i in [0, n) with pred(i) true, for a predicate that is false
  // then true; n when never true.
  function lowerBound(n, pred) {
    let lo = 0, hi = n;
    while (lo < hi) {
      const mid = (lo + hi) >> 1;
      if (pred(mid)) hi = mid; else lo = mid + 1;
    }
    return lo;
  }

  function clamp(v, lo, hi) { return v < lo ? lo : v > hi ? hi : v; }

  function el(tag, className, text) {
    const e = document.createElement(tag);
    if (className) e.className = className;
    if (text !== undefined) e.textContent = text;
    return e;
  }

  function str(i) { return i >= 0 && i < S.strings.length ? String(S.strings[i]) : '?'; }

  function runLetter(r) { return r === 0 ? 'A' : 'B'; }

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

  // ------------------------------------------------------------ the view

  function domainSpan() { return S.last + 1 - S.first; }

  function minSpan() { return Math.min(domainSpan(), Math.max(1, S.width / MAX_PX_PER_CYCLE)); }

  function xOf(c) { return (c - S.view.start) * S.width / S.view.span; }

  function cycleAtX(x) { return S.view.start + x * S.view.span / S.width; }

  function pxPerCycle() { return S.width / S.view.span; }

  function clampView() {
    const v = S.view;
    v.span = clamp(v.span, minSpan(), domainSpan());
    v.start = clamp(v.start, S.first, S.last + 1 - v.span);
  }

  function setView(start, span) {
    S.view.start = start;
    S.view.span = span;
    clampView();
    invalidate(true);
  }

  function fit() { setView(S.first, domainSpan()); }

  // Zoom keeping the cycle under `anchor` (a fractional cycle) in place.
  function zoomAround(anchor, factor) {
    const v = S.view;
    const span = clamp(v.span / factor, minSpan(), domainSpan());
    setView(anchor - (anchor - v.start) * span / v.span, span);
  }

  function zoomAtCursor(factor) {
    const c = S.cursor + 0.5;
    const inView = c >= S.view.start && c <= S.view.start + S.view.span;
    zoomAround(inView ? c : S.view.start + S.view.span / 2, factor);
  }

  function panBy(cycles) { setView(S.view.start + cycles, S.view.span); }

  // Scrolls the view (without zooming) so that cycle c is visible.
  function ensureVisible(c) {
    const v = S.view;
    if (c >= v.start && c + 1 <= v.start + v.span) return;
    setView(c + 0.5 - v.span / 2, v.span);
  }

  // --------------------------------------------------------- the cursor

  function setCursor(c, follow) {
    if (typeof c !== 'number' || !isFinite(c)) return;
    c = snapToPresent(Math.round(clamp(c, S.first, S.last)));
    if (follow) ensureVisible(c);
    if (c === S.cursor && S.ready) return;
    S.cursor = c;
    updatePanel();
    invalidate(false);
  }

  // Moves by `delta` cycles; a gap in the cycles is skipped in the direction
  // of the move.
  function moveCursor(delta) {
    const target = clamp(S.cursor + delta, S.first, S.last);
    let c = delta > 0 ? nextIn(S.present, target) : prevIn(S.present, target);
    if (c === null) c = delta > 0 ? prevIn(S.present, S.last) : nextIn(S.present, S.first);
    if (c !== null) setCursor(c, true);
  }

  // ------------------------------------------------------------ canvases

  function setupCanvas(name, elem) {
    const base = document.createElement('canvas');
    S.canvases[name] = { el: elem, base, ctx: elem.getContext('2d'), bctx: base.getContext('2d'), w: 0, h: 0 };
    return S.canvases[name];
  }

  // Sizes a canvas (and its base) to CSS w x h at the device pixel ratio;
  // the contexts draw in CSS pixels.
  function sizeCanvas(cv, w, h) {
    const dpr = window.devicePixelRatio || 1;
    w = Math.max(1, Math.floor(w));
    h = Math.max(1, Math.floor(h));
    if (cv.w !== w || cv.h !== h || cv.dpr !== dpr) {
      for (const c of [cv.el, cv.base]) { c.width = w * dpr; c.height = h * dpr; }
      cv.el.style.width = w + 'px';
      cv.el.style.height = h + 'px';
      cv.w = w; cv.h = h; cv.dpr = dpr;
    }
    cv.bctx.setTransform(dpr, 0, 0, dpr, 0, 0);
    cv.ctx.setTransform(dpr, 0, 0, dpr, 0, 0);
  }

  // Copies the base image onto the visible canvas, ready for the overlay.
  function copyBase(cv) {
    cv.ctx.setTransform(1, 0, 0, 1, 0, 0);
    cv.ctx.clearRect(0, 0, cv.el.width, cv.el.height);
    cv.ctx.drawImage(cv.base, 0, 0);
    cv.ctx.setTransform(cv.dpr, 0, 0, cv.dpr, 0, 0);
  }

  // Calls paint(i, x0, x1) for each run of pixel columns [x0, x1) that shows
  // interval i of n sorted, non-overlapping, inclusive cycle intervals
  // (startOf(i)..endOf(i)). A column shows the interval under its centre, or
  // else the first one inside it, so a one-cycle interval stays visible far
  // zoomed out; an interval wider than a column is painted once. `map` is
  // {start, span} over `width` columns. Cost: O(columns * log n).
  function walkColumns(n, startOf, endOf, map, width, paint) {
    const k = map.span / width;    // cycles per column
    let x = 0, i = 0;
    while (x < width) {
      const c0 = map.start + x * k, c1 = c0 + k, mid = c0 + k / 2;
      i = firstEndingAfter(i, n, endOf, c0);
      if (i >= n) return;
      if (startOf(i) >= c1) {       // nothing in this column: jump to interval i
        x = Math.max(x + 1, Math.floor((startOf(i) - map.start) / k));
        continue;
      }
      let j = i;
      if (endOf(j) + 1 <= mid && j + 1 < n && startOf(j + 1) <= mid && endOf(j + 1) + 1 > mid) j++;
      const x1 = Math.min(width, Math.max(x + 1, Math.floor((endOf(j) + 1 - map.start) / k)));
      paint(j, x, x1);
      x = x1;
    }
  }

  // The first interval index >= from whose end lies after cycle c: a
  // galloping search, since the columns visit the intervals in order and the
  // answer is usually near `from`.
  function firstEndingAfter(from, n, endOf, c) {
    if (from >= n || endOf(from) + 1 > c) return from;
    let lo = from, step = 1;
    while (lo + step < n && endOf(lo + step) + 1 <= c) { lo += step; step *= 2; }
    const hi = Math.min(n, lo + step);
    return lo + 1 + lowerBound(hi - lo - 1, (j) => endOf(lo + 1 + j) + 1 > c);
  }

  // Runs of columns [x0, x1) where a run has cycles, for shading the gaps.
  function presentColumns(ranges, map, width) {
    const out = [];
    walkColumns(ranges.length, (i) => ranges[i][0], (i) => ranges[i][1], map, width, (i, x0, x1) => {
      const top = out[out.length - 1];
      if (top && top[1] === x0) top[1] = x1; else out.push([x0, x1]);
    });
    return out;
  }

  let hatch = null;
  // A diagonal hatch for cycles a run did not record.
  function gapPattern(ctx) {
    if (hatch) return hatch;
    const p = document.createElement('canvas');
    p.width = p.height = 8;
    const g = p.getContext('2d');
    g.fillStyle = '#f1f3f5';
    g.fillRect(0, 0, 8, 8);
    g.strokeStyle = '#dfe3e8';
    g.beginPath(); g.moveTo(0, 8); g.lineTo(8, 0); g.stroke();
    hatch = ctx.createPattern(p, 'repeat');
    return hatch;
  }

  // ---------------------------------------------------------------- ruler

  // A "nice" tick step (1, 2, 5 x 10^k cycles) at least minPx apart.
  function tickStep(minPx) {
    const raw = minPx / pxPerCycle();
    let step = 1;
    while (step < raw) {
      const s = String(step)[0];
      step = s === '1' ? step * 2 : s === '2' ? step * 2.5 : step * 2;
    }
    return step;
  }

  function drawRulerBase() {
    const cv = S.canvases.ruler, g = cv.bctx;
    g.fillStyle = '#fff';
    g.fillRect(0, 0, cv.w, cv.h);
    const step = tickStep(80), minor = tickStep(12);
    g.strokeStyle = '#c4cad2';
    g.beginPath();
    for (let c = Math.ceil(S.view.start / minor) * minor; c < S.view.start + S.view.span; c += minor) {
      const x = Math.round(xOf(c + 0.5)) + 0.5;
      const major = c % step === 0;
      g.moveTo(x, cv.h); g.lineTo(x, cv.h - (major ? 9 : 4));
    }
    g.stroke();
    g.fillStyle = '#5f6b7a';
    g.font = '11px ui-monospace, "DejaVu Sans Mono", Menlo, monospace';
    g.textAlign = 'center';
    g.textBaseline = 'top';
    for (let c = Math.ceil(S.view.start / step) * step; c < S.view.start + S.view.span; c += step) {
      const half = g.measureText(String(c)).width / 2 + 2;   // keep edge labels whole
      g.fillText(String(c), clamp(xOf(c + 0.5), half, cv.w - half), 4);
    }
    if (S.difference) drawDiffLine(g, cv.h);
  }

  function drawRulerOverlay() {
    const cv = S.canvases.ruler, g = cv.ctx;
    copyBase(cv);
    const x = xOf(S.cursor + 0.5);
    if (x < -40 || x > cv.w + 40) return;
    drawCursorLine(g, cv.h);
    const label = String(S.cursor);
    g.font = '600 11px ui-monospace, "DejaVu Sans Mono", Menlo, monospace';
    const w = g.measureText(label).width + 10;
    const bx = clamp(x - w / 2, 0, cv.w - w);
    g.fillStyle = CURSOR;
    g.fillRect(bx, 2, w, 16);
    g.fillStyle = '#fff';
    g.textAlign = 'center';
    g.textBaseline = 'middle';
    g.fillText(label, bx + w / 2, 10.5);
  }

  // ---------------------------------------------------------------- lanes

  function buildRows() {
    S.rows = [];
    const two = S.runs.length > 1;
    for (const run of S.runs) {
      if (two) S.rows.push({ kind: 'header', run });
      if (run.tasks.length === 0) S.rows.push({ kind: 'empty', run });
      for (const task of run.tasks) S.rows.push({ kind: 'lane', run, task });
    }
  }

  function buildLaneLabels() {
    const box = $('lane-labels');
    box.textContent = '';
    for (const row of S.rows) box.appendChild(laneLabel(row));
  }

  function laneLabel(row) {
    const two = S.runs.length > 1;
    if (row.kind === 'header') {
      const h = el('div', 'run-header', runLetter(row.run.index) + ': ' + row.run.name);
      h.title = row.run.name + ' (' + row.run.kind + ')';
      return h;
    }
    if (row.kind === 'empty') return el('div', 'empty', 'no tasks in ' + row.run.name);
    const d = el('div', 'lane-label');
    d.dataset.task = row.task.name;
    d.dataset.run = String(row.run.index);
    d.style.paddingLeft = (8 + row.task.depth * 14) + 'px';
    d.title = (two ? runLetter(row.run.index) + ': ' : '') + row.task.name;
    d.textContent = row.task.short;
    row.label = d;
    return d;
  }

  function drawLanesBase() {
    const cv = S.canvases.lanes, g = cv.bctx;
    g.fillStyle = '#fff';
    g.fillRect(0, 0, cv.w, cv.h);
    const gaps = S.runs.map((run) => presentColumns(run.cycles, S.view, cv.w));
    S.rows.forEach((row, r) => drawRow(g, row, r * LANE_H, gaps[row.run.index]));
    if (S.difference) drawDiffLine(g, cv.h);
  }

  function drawRow(g, row, y, present) {
    const w = S.canvases.lanes.w;
    if (row.kind === 'header') {
      g.fillStyle = '#f0f2f5';
      g.fillRect(0, y, w, LANE_H);
      g.fillStyle = '#dde1e6';
      g.fillRect(0, y, w, 1);
      return;
    }
    // Background: hatched where the run has no cycle, plain where it has.
    g.fillStyle = gapPattern(g);
    g.fillRect(0, y, w, LANE_H);
    g.fillStyle = '#fff';
    for (const [x0, x1] of present) g.fillRect(x0, y, x1 - x0, LANE_H);
    g.fillStyle = '#eef0f3';
    g.fillRect(0, y + LANE_H - 1, w, 1);
    if (row.kind === 'lane') drawSegments(g, row.task, y);
  }

  function drawSegments(g, task, y) {
    const segs = task.segments, w = S.canvases.lanes.w;
    const top = y + 3, h = LANE_H - 6;
    g.font = '11px system-ui, sans-serif';
    g.textBaseline = 'middle';
    g.textAlign = 'left';
    const paths = new Map();       // colour -> Path2D of narrow columns
    const narrow = (color, x0, x1) => {
      let p = paths.get(color);
      if (!p) paths.set(color, p = { path: new Path2D(), x0: -1, x1: -1 });
      if (p.x1 === x0) { p.x1 = x1; return; }
      if (p.x1 > p.x0) p.path.rect(p.x0, top, p.x1 - p.x0, h);
      p.x0 = x0; p.x1 = x1;
    };
    walkColumns(segs.length / 5, (i) => segs[5 * i], (i) => segs[5 * i + 1], S.view, w, (i, x0, x1) => {
      const color = stateColorByIndex(segs[5 * i + 2]);
      if (x1 - x0 < 4) { narrow(color, x0, x1); return; }
      g.fillStyle = color;
      g.fillRect(x0, top, x1 - x0, h);
      // A light edge where a segment starts, so that two segments with the
      // same state (say, waiting at another line) stay distinguishable.
      if (Math.floor(xOf(segs[5 * i])) === x0) {
        g.fillStyle = 'rgba(255,255,255,0.85)';
        g.fillRect(x0, top, 1, h);
      }
      if (x1 - x0 >= 44) drawSegmentText(g, segs, i, x0, x1, top, h);
    });
    // Zoomed out, most columns are narrow: one path per colour instead of a
    // rectangle per column keeps a 100,000-cycle lane cheap.
    for (const [color, p] of paths) {
      if (p.x1 > p.x0) p.path.rect(p.x0, top, p.x1 - p.x0, h);
      g.fillStyle = color;
      g.fill(p.path);
    }
  }

  // Colour by string index, cached: looked up once per painted column.
  function stateColorByIndex(i) {
    let c = S.colorByIndex[i];
    if (c === undefined) c = S.colorByIndex[i] = colorOf(str(i));
    return c;
  }

  function drawSegmentText(g, segs, i, x0, x1, top, h) {
    const at = segs[5 * i + 3];
    let text = str(segs[5 * i + 2]);
    if (at >= 0 && x1 - x0 > 160) text += ' \u00b7 ' + str(at);
    g.save();
    g.beginPath();
    g.rect(x0 + 3, top, x1 - x0 - 6, h);
    g.clip();
    g.fillStyle = '#fff';
    g.fillText(text, Math.max(x0, 0) + 5, top + h / 2 + 0.5);
    g.restore();
  }

  function drawDiffLine(g, h) {
    const c = S.difference.cycle;
    const x0 = xOf(c), x1 = xOf(c + 1);
    if (x1 < 0 || x0 > S.width) return;
    if (x1 - x0 >= 3) {
      g.fillStyle = 'rgba(197,34,31,0.10)';
      g.fillRect(x0, 0, x1 - x0, h);
    }
    g.strokeStyle = DIFF;
    g.lineWidth = 1.5;
    g.setLineDash([4, 3]);
    g.beginPath();
    g.moveTo(Math.round(x0) + 0.5, 0);
    g.lineTo(Math.round(x0) + 0.5, h);
    g.stroke();
    g.setLineDash([]);
    g.lineWidth = 1;
  }

  function drawCursorLine(g, h) {
    const x0 = xOf(S.cursor), x1 = xOf(S.cursor + 1);
    if (x1 - x0 >= 3) {
      g.fillStyle = 'rgba(232,113,10,0.16)';
      g.fillRect(x0, 0, x1 - x0, h);
    }
    const x = Math.round((x0 + x1) / 2) + 0.5;
    g.strokeStyle = CURSOR;
    g.lineWidth = 1.5;
    g.beginPath();
    g.moveTo(x, 0);
    g.lineTo(x, h);
    g.stroke();
    g.lineWidth = 1;
  }

  function drawLanesOverlay() {
    const cv = S.canvases.lanes;
    copyBase(cv);
    drawCursorLine(cv.ctx, cv.h);
  }

  // ------------------------------------------------------------ overview

  function overviewMap() { return { start: S.first, span: domainSpan() }; }

  function drawOverviewBase() {
    const cv = S.canvases.overview, g = cv.bctx, map = overviewMap();
    g.fillStyle = '#f6f7f9';
    g.fillRect(0, 0, cv.w, cv.h);
    const bandH = Math.floor((cv.h - 6) / S.runs.length);
    S.runs.forEach((run, r) => {
      g.fillStyle = S.runs.length > 1 ? RUN_COLORS[r] + '66' : '#c4cad2';
      for (const [x0, x1] of presentColumns(run.cycles, map, cv.w)) g.fillRect(x0, 3 + r * bandH, x1 - x0, bandH - 1);
    });
    if (S.difference) {
      const x = Math.round((S.difference.cycle - map.start) * cv.w / map.span) + 0.5;
      g.strokeStyle = DIFF;
      g.beginPath(); g.moveTo(x, 0); g.lineTo(x, cv.h); g.stroke();
    }
  }

  function drawOverviewOverlay() {
    const cv = S.canvases.overview, g = cv.ctx, map = overviewMap();
    copyBase(cv);
    const k = cv.w / map.span;
    const x0 = (S.view.start - map.start) * k;
    const w = Math.max(3, S.view.span * k);
    g.fillStyle = 'rgba(26,115,232,0.14)';
    g.fillRect(x0, 0, w, cv.h);
    g.strokeStyle = '#1a73e8';
    g.strokeRect(Math.round(x0) + 0.5, 0.5, Math.round(w) - 1, cv.h - 1);
    const xc = Math.round((S.cursor + 0.5 - map.start) * k) + 0.5;
    g.strokeStyle = CURSOR;
    g.beginPath(); g.moveTo(xc, 0); g.lineTo(xc, cv.h); g.stroke();
  }

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
      S.runs.forEach((run, r) => {
        const k = el('span', '', runLetter(r));
        const sw = el('i');
        sw.style.background = RUN_COLORS[r];
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
    S.runs.forEach((run, r) => {
      const pd = plotData(run, cv.path);
      if (pd) drawPlotLine(g, cv, pd, S.runs.length > 1 ? RUN_COLORS[r] : RUN_COLORS[0]);
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
      return (S.runs.length > 1 ? runLetter(run.index) + ' ' : '') + formatValue(v);
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

  // ------------------------------------------------------------- rendering

  function layout() {
    const col = document.querySelector('#lanes-row .canvas-col');
    S.width = Math.max(50, col.clientWidth);
    clampView();
    sizeCanvas(S.canvases.ruler, S.width, RULER_H);
    sizeCanvas(S.canvases.lanes, S.width, Math.max(1, S.rows.length) * LANE_H);
    sizeCanvas(S.canvases.overview, S.width, OVERVIEW_H);
    for (const cv of plotCanvases()) sizeCanvas(cv, S.width, PLOT_H);
  }

  function plotCanvases() {
    return Object.keys(S.canvases).filter((k) => k.startsWith('plot:')).map((k) => S.canvases[k]);
  }

  // Marks what needs drawing and draws it on the next animation frame.
  function invalidate(base) {
    S.dirty.overlay = true;
    if (base) S.dirty.base = true;
    if (!S.frame && S.ready) S.frame = requestAnimationFrame(render);
  }

  function render() {
    if (S.frame) cancelAnimationFrame(S.frame);
    S.frame = 0;
    if (S.dirty.base) {
      layout();
      drawRulerBase();
      drawLanesBase();
      drawOverviewBase();
      for (const cv of plotCanvases()) drawPlotBase(cv);
      updateZoomInfo();
    }
    if (S.dirty.base || S.dirty.overlay) {
      drawRulerOverlay();
      drawLanesOverlay();
      drawOverviewOverlay();
      for (const cv of plotCanvases()) drawPlotOverlay(cv);
    }
    S.dirty.base = S.dirty.overlay = false;
  }

  function updateZoomInfo() {
    const ppc = pxPerCycle();
    const text = ppc >= 1 ? ppc.toFixed(ppc >= 10 ? 0 : 1) + ' px/cycle' : (1 / ppc).toFixed(1) + ' cycles/px';
    $('zoom-info').textContent = Math.round(S.view.span) + ' cycles \u00b7 ' + text;
  }

  // ---------------------------------------------------------------- panel

  function updatePanel() {
    updateCycleHeader();
    updateHierarchy();
    updateIO();
  }

  function updateCycleHeader() {
    const box = $('cycle');
    box.textContent = '';
    box.appendChild(el('span', 'num', 'cycle ' + S.cursor));
    S.runs.forEach((run, r) => {
      if (r) box.appendChild(document.createTextNode(', '));
      else box.appendChild(document.createTextNode(' '));
      const name = (S.runs.length > 1 ? runLetter(r) + ': ' : '') + run.name;
      box.appendChild(el('span', isPresent(run, S.cursor) ? 'run' : 'run absent',
        name + (isPresent(run, S.cursor) ? '' : ' (no such cycle)')));
    });
  }

  function updateHierarchy() {
    const box = $('hierarchy');
    box.textContent = '';
    for (const run of S.runs) {
      const wrap = el('div', 'run-tree');
      wrap.dataset.run = String(run.index);
      if (S.runs.length > 1) wrap.appendChild(el('h3', '', runLetter(run.index) + ': ' + run.name));
      wrap.appendChild(runTree(run));
      box.appendChild(wrap);
    }
  }

  // The tree of tasks active at the cursor in one run.
  function runTree(run) {
    const c = S.cursor;
    if (!isPresent(run, c)) return el('div', 'none', 'cycle ' + c + ' is not in this run');
    const children = new Map();   // parent index (-1: root) -> [{i, s}]
    run.tasks.forEach((task, i) => {
      const s = segmentAt(task, c);
      if (s < 0) return;
      const parent = task.segments[5 * s + 4];
      const key = parent >= 0 && parent < run.tasks.length && segmentAt(run.tasks[parent], c) >= 0 ? parent : -1;
      if (!children.has(key)) children.set(key, []);
      children.get(key).push({ i, s });
    });
    if (children.size === 0) return el('div', 'none', 'no task active');
    const otherRun = S.runs.length > 1 ? S.runs[1 - run.index] : null;   // to mark differing fields
    return taskList(run, children, -1, otherRun, new Set());
  }

  function taskList(run, children, parent, otherRun, seen) {
    const ul = el('ul');
    for (const { i, s } of children.get(parent) || []) {
      if (seen.has(i)) continue;          // a malformed parent cycle must not loop
      seen.add(i);
      const li = el('li');
      li.appendChild(taskNode(run, run.tasks[i], s, otherRun));
      if (children.has(i)) li.appendChild(taskList(run, children, i, otherRun, seen));
      ul.appendChild(li);
    }
    return ul;
  }

  function taskNode(run, task, s, otherRun) {
    const segs = task.segments, state = str(segs[5 * s + 2]), at = segs[5 * s + 3];
    const node = el('div', 'task');
    node.dataset.task = task.name;
    node.dataset.run = String(run.index);
    node.title = task.name;
    const head = el('div', 'head');
    const sw = el('span', 'swatch');
    sw.style.background = colorOf(state);
    head.append(sw, el('span', 'text', task.short + ' [' + state + (at >= 0 ? ', ' + str(at) : '') + ']'));
    node.appendChild(head);
    const otherTask = otherRun && otherRun.tasks.find((t) => t.name === task.name);
    for (const f of task.fields) {
      const v = valueAt(f.series, S.cursor);
      const line = el('div', 'field' + (f.param ? ' param' : ''), f.name + ' = ' + formatValue(v));
      if (otherTask && differsFrom(v, otherTask, f.name)) line.classList.add('differs');
      node.appendChild(line);
    }
    return node;
  }

  function fieldValuesAt(task, name) {
    const f = task.fields.find((x) => x.name === name);
    return f ? valueAt(f.series, S.cursor) : undefined;
  }

  function differsFrom(v, otherTask, name) {
    const w = fieldValuesAt(otherTask, name);
    return w !== undefined && formatValue(w) !== formatValue(v);
  }

  function updateIO() {
    const box = $('io');
    box.textContent = '';
    for (const run of S.runs) {
      if (S.runs.length > 1) box.appendChild(el('h3', '', runLetter(run.index) + ': ' + run.name));
      if (run.series.length === 0) {
        const why = run.kind === 'robot log' ? 'a robot log has no input or output' : 'no input or output';
        box.appendChild(el('div', 'none', why));
        continue;
      }
      if (!isPresent(run, S.cursor)) {
        box.appendChild(el('div', 'none', 'cycle ' + S.cursor + ' is not in this run'));
        continue;
      }
      appendLeaves(box, run);
    }
  }

  function appendLeaves(box, run) {
    const other = S.runs.length > 1 ? S.runs[1 - run.index] : null;
    let group = '';
    for (const s of run.series) {
      const top = s.path.split(/[.[]/)[0];
      if (top !== group) { group = top; box.appendChild(el('div', 'group-name', top)); }
      const v = valueAt(s, S.cursor);
      const leaf = el('div', 'leaf', s.path + ' = ' + formatValue(v));
      leaf.dataset.path = s.path;
      leaf.dataset.run = String(run.index);
      if (v === null) leaf.classList.add('v-null');
      const os = other && other.seriesByPath.get(s.path);
      if (other && (!os || formatValue(valueAt(os, S.cursor)) !== formatValue(v))) leaf.classList.add('differs');
      box.appendChild(leaf);
    }
  }

  // --------------------------------------------------------------- tooltip

  function showLaneTooltip(ev) {
    const rect = S.canvases.lanes.el.getBoundingClientRect();
    const row = S.rows[Math.floor((ev.clientY - rect.top) / LANE_H)];
    setHoverLabel(row);
    if (!row || row.kind !== 'lane') { hideTooltip(); return; }
    const c = Math.floor(cycleAtX(ev.clientX - rect.left));
    const tip = $('tooltip');
    tip.textContent = '';
    tip.append(...tooltipLines(row, c));
    tip.hidden = false;
    const x = ev.clientX + 14, y = ev.clientY + 14;
    tip.style.left = Math.min(x, window.innerWidth - tip.offsetWidth - 8) + 'px';
    tip.style.top = (y + tip.offsetHeight > window.innerHeight - 8 ? ev.clientY - tip.offsetHeight - 10 : y) + 'px';
  }

  function tooltipLines(row, c) {
    const task = row.task, run = row.run;
    const line = (cls, text) => el('div', cls, text);
    const out = [line('t-name', task.short), line('t-dim', task.name)];
    out.push(line('', 'cycle ' + c + (S.runs.length > 1 ? ' \u00b7 ' + runLetter(run.index) + ': ' + run.name : '')));
    const s = segmentAt(task, c);
    if (s < 0) { out.push(line('t-dim', isPresent(run, c) ? 'not active' : 'no such cycle in this run')); return out; }
    const segs = task.segments, at = segs[5 * s + 3], parent = segs[5 * s + 4];
    out.push(line('', 'state ' + str(segs[5 * s + 2])));
    out.push(line('', at >= 0 ? 'waits at ' + str(at) : 'finished'));
    if (parent >= 0 && run.tasks[parent]) out.push(line('t-dim', 'parent ' + run.tasks[parent].short));
    out.push(line('t-dim', 'cycles ' + segs[5 * s] + '\u2013' + segs[5 * s + 1]));
    return out;
  }

  function hideTooltip() {
    $('tooltip').hidden = true;
    setHoverLabel(null);
  }

  let hoverLabel = null;
  function setHoverLabel(row) {
    const label = row && row.label ? row.label : null;
    if (label === hoverLabel) return;
    if (hoverLabel) hoverLabel.classList.remove('hover');
    if (label) label.classList.add('hover');
    hoverLabel = label;
  }

  // ----------------------------------------------------------------- mouse

  function cycleAtClientX(canvas, clientX) {
    const rect = canvas.getBoundingClientRect();
    return Math.floor(cycleAtX(clientX - rect.left));
  }

  // Click or drag moves the cursor; with Shift, drag pans. Pointer events
  // carry fractional coordinates, so a click at xForCycle(c) lands on c even
  // at a few pixels per cycle.
  function attachScrub(canvas) {
    canvas.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0) return;
      blurInputs();
      ev.preventDefault();
      canvas.setPointerCapture(ev.pointerId);
      const pan = ev.shiftKey;
      const startX = ev.clientX, startView = S.view.start;
      if (pan) canvas.classList.add('panning'); else setCursor(cycleAtClientX(canvas, ev.clientX), false);
      const move = (e) => {
        if (pan) setView(startView - (e.clientX - startX) * S.view.span / S.width, S.view.span);
        else setCursor(cycleAtClientX(canvas, e.clientX), false);
      };
      const up = () => {
        canvas.classList.remove('panning');
        canvas.removeEventListener('pointermove', move);
        canvas.removeEventListener('pointerup', up);
        canvas.removeEventListener('pointercancel', up);
      };
      canvas.addEventListener('pointermove', move);
      canvas.addEventListener('pointerup', up);
      canvas.addEventListener('pointercancel', up);
    });
    canvas.addEventListener('wheel', onWheel, { passive: false });
  }

  // Wheel zooms around the pointer; Shift+wheel or a sideways wheel pans.
  function onWheel(ev) {
    ev.preventDefault();
    const scale = ev.deltaMode === 1 ? 16 : ev.deltaMode === 2 ? 400 : 1;
    const dx = ev.deltaX * scale, dy = ev.deltaY * scale;
    if (ev.shiftKey || Math.abs(dx) > Math.abs(dy)) {
      panBy((Math.abs(dx) > Math.abs(dy) ? dx : dy) * S.view.span / S.width);
      return;
    }
    const rect = ev.currentTarget.getBoundingClientRect();
    zoomAround(cycleAtX(ev.clientX - rect.left), Math.exp(-dy * 0.002));
  }

  // Dragging the overview moves the view; a press outside the view's box
  // first centres the view there.
  function attachOverview(canvas) {
    canvas.addEventListener('pointerdown', (ev) => {
      if (ev.button !== 0) return;
      blurInputs();
      ev.preventDefault();
      canvas.setPointerCapture(ev.pointerId);
      const map = overviewMap();
      const toCycle = (clientX) => map.start + (clientX - canvas.getBoundingClientRect().left) * map.span / S.width;
      const c = toCycle(ev.clientX);
      if (c < S.view.start || c > S.view.start + S.view.span) setView(c - S.view.span / 2, S.view.span);
      const grab = toCycle(ev.clientX) - S.view.start;
      const move = (e) => setView(toCycle(e.clientX) - grab, S.view.span);
      const up = () => {
        canvas.removeEventListener('pointermove', move);
        canvas.removeEventListener('pointerup', up);
      };
      canvas.addEventListener('pointermove', move);
      canvas.addEventListener('pointerup', up);
    });
    canvas.addEventListener('wheel', onWheel, { passive: false });
  }

  function blurInputs() {
    const a = document.activeElement;
    if (a && a.tagName === 'INPUT' && a.type === 'text') a.blur();
  }

  // -------------------------------------------------------------- keyboard

  function onKey(ev) {
    const t = ev.target;
    if (t && t.tagName === 'INPUT' && t.type === 'text') { onInputKey(ev); return; }
    if (ev.ctrlKey || ev.metaKey || ev.altKey) return;
    const action = keyAction(ev);
    if (!action) return;
    ev.preventDefault();
    action();
  }

  function keyAction(ev) {
    const screen = Math.max(1, Math.round(S.view.span));
    switch (ev.key) {
      case 'ArrowRight': return () => moveCursor(ev.shiftKey ? 10 : 1);
      case 'ArrowLeft': return () => moveCursor(ev.shiftKey ? -10 : -1);
      case 'Home': return () => setCursor(S.first, true);
      case 'End': return () => setCursor(S.last, true);
      case 'PageDown': return () => { panBy(screen); moveCursor(screen); };
      case 'PageUp': return () => { panBy(-screen); moveCursor(-screen); };
      case '+': case '=': case 'w': case 'W': return () => zoomAtCursor(1.6);
      case '-': case '_': case 's': case 'S': return () => zoomAtCursor(1 / 1.6);
      case '0': return fit;
      case 'a': case 'A': return () => panBy(-S.view.span * 0.2);
      case 'd': case 'D': return () => panBy(S.view.span * 0.2);
      case '/': return () => $('search').focus();
      case 'n': return () => runSearch('next');
      case 'N': case 'p': case 'P': return () => runSearch('prev');
      case '?': return toggleHelp;
      default: return null;
    }
  }

  function onInputKey(ev) {
    if (ev.key === 'Escape') { ev.target.blur(); return; }
    if (ev.target.id === 'search' && ev.key === 'Enter') {
      ev.preventDefault();
      runSearch(ev.shiftKey ? 'prev' : 'next');
    }
  }

  function toggleHelp() { $('help').hidden = !$('help').hidden; }

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

  // ------------------------------------------------------------ chrome

  function buildLegend() {
    const box = $('legend');
    box.textContent = '';
    box.appendChild(el('span', 'title', 'States'));
    const item = (color, text, pattern) => {
      const it = el('span', 'item');
      const sw = el('span', 'swatch');
      sw.style.background = color;
      if (pattern) sw.style.border = '1px solid #c4cad2';
      it.append(sw, el('span', '', text));
      box.appendChild(it);
    };
    const states = legendStates();
    if (states.length === 0) box.appendChild(el('span', 'item', 'no tasks'));
    for (const s of states) item(colorOf(s), s);
    item(CURSOR, 'cursor');
    if (S.difference) item(DIFF, 'first difference');
    if (S.runs.some((r) => r.cycles.length > 1)) {
      item('repeating-linear-gradient(135deg,#dfe3e8 0 1px,#f1f3f5 1px 5px)', 'no cycle recorded', true);
    }
    box.appendChild(el('span', 'hint', 'click/drag lanes: cursor \u00b7 wheel: zoom \u00b7 shift+drag: pan \u00b7 ? keys'));
  }

  function buildDifference() {
    const box = $('difference');
    const d = S.difference;
    if (!d) { box.hidden = true; return; }
    box.textContent = '';
    box.appendChild(el('strong', '', 'The runs first differ at cycle ' + d.cycle));
    const ul = el('ul');
    for (const note of d.notes || []) ul.appendChild(el('li', '', String(note)));
    box.appendChild(ul);
    const jump = el('button', '', 'go to cycle ' + d.cycle);
    jump.id = 'difference-jump';
    jump.addEventListener('click', () => setCursor(d.cycle, true));
    box.appendChild(jump);
    box.hidden = false;
  }

  function wireButtons() {
    $('zoom-in').addEventListener('click', () => zoomAtCursor(1.6));
    $('zoom-out').addEventListener('click', () => zoomAtCursor(1 / 1.6));
    $('fit').addEventListener('click', fit);
    $('help-toggle').addEventListener('click', toggleHelp);
    $('search-first').addEventListener('click', () => runSearch('first'));
    $('search-next').addEventListener('click', () => runSearch('next'));
    $('search-prev').addEventListener('click', () => runSearch('prev'));
    $('search').addEventListener('input', () => setSearchStatus('', ''));
    document.addEventListener('keydown', onKey);
    const lanes = $('lanes');
    attachScrub(lanes);
    attachScrub($('ruler'));
    attachOverview($('overview'));
    lanes.addEventListener('pointermove', (ev) => { if (!ev.buttons) showLaneTooltip(ev); else hideTooltip(); });
    lanes.addEventListener('pointerleave', hideTooltip);
    // The lanes' column narrows when the timeline gets a vertical scrollbar,
    // not only when the window is resized: watch the column itself.
    new ResizeObserver(() => { if (S.ready) invalidate(true); }).observe(document.querySelector('#lanes-row .canvas-col'));
  }

  // ----------------------------------------------------------- test API

  function runByKey(key) {
    if (typeof key === 'number') return S.runs[key];
    if (key === 'A' || key === 'B') return S.runs[key === 'A' ? 0 : 1];
    return S.runs.find((r) => r.name === key) || S.runs[Number(key)];
  }

  // The clientY of a lane's centre; scrolls the timeline first if the lane is
  // out of sight, so that the returned point can be clicked.
  function yForLane(runKey, taskName) {
    const run = runByKey(runKey === undefined ? 0 : runKey);
    const r = S.rows.findIndex((row) => row.kind === 'lane' && row.run === run &&
      (row.task.name === taskName || row.task.short === taskName));
    if (r < 0) return null;
    const scroller = $('timeline'), top = $('lanes-row').offsetTop + r * LANE_H;
    const minTop = scroller.scrollTop + RULER_H, maxTop = scroller.scrollTop + scroller.clientHeight - LANE_H;
    if (top < minTop || top > maxTop) scroller.scrollTop = top - scroller.clientHeight / 2;
    return S.canvases.lanes.el.getBoundingClientRect().top + r * LANE_H + LANE_H / 2;
  }

  // The clientX of a cycle's centre. If the cycle is outside the view, the
  // view is scrolled (not zoomed) to it first, so that it can be clicked.
  function xForCycle(c) {
    if (c < S.view.start || c + 1 > S.view.start + S.view.span) { ensureVisible(c); render(); }
    return S.canvases.lanes.el.getBoundingClientRect().left + xOf(c + 0.5);
  }

  function exposeApi() {
    window.bscTimeline = {
      cursor: () => S.cursor,
      setCursor: (c) => { setCursor(Number(c), true); render(); },
      xForCycle,
      yForLane,
      lanes: () => {
        const top = S.canvases.lanes.el.getBoundingClientRect().top;
        return S.rows.map((row, r) => ({ row, r })).filter(({ row }) => row.kind === 'lane')
          .map(({ row, r }) => ({ run: row.run.index, task: row.task.name, y: top + r * LANE_H + LANE_H / 2 }));
      },
      firstRenderMs: null,
    };
  }

  // ----------------------------------------------------------------- start

  function showError(message) {
    const box = $('error');
    box.textContent = 'bsc timeline: ' + message;
    box.hidden = false;
    if (!S.ready) { $('content').hidden = true; $('legend').hidden = true; }
    document.body.dataset.ready = '1';
  }

  function init(data) {
    S.strings = Array.isArray(data.strings) ? data.strings : [];
    S.difference = data.difference && typeof data.difference.cycle === 'number' ? data.difference : null;
    S.runs = data.runs.map(prepareRun);
    computeDomain();
    assignStateColors();
    document.title = document.title || S.runs.map((r) => r.name).join(' vs ');
    const names = S.runs.map((r, i) => (S.runs.length > 1 ? runLetter(i) + ': ' : '') + r.name);
    $('title-text').textContent = names.join('  \u00b7  ');
    buildRows();
    buildLaneLabels();
    buildLegend();
    buildDifference();
    buildFieldChooser();
    setupCanvas('ruler', $('ruler'));
    setupCanvas('lanes', $('lanes'));
    setupCanvas('overview', $('overview'));
    buildPlots();
    exposeApi();
    wireButtons();
    S.cursor = S.present.length ? S.present[0][0] : S.first;
    layout();
    S.view = { start: S.first, span: domainSpan() };
    updatePanel();
    S.dirty.base = true;
    render();
    S.ready = true;
    window.bscTimeline.firstRenderMs = performance.now();
    document.body.dataset.ready = '1';
  }

  function main() {
    window.addEventListener('error', (e) => showError('internal error: ' + e.message));
    let data;
    try {
      data = readData();
    } catch (e) {
      showError('cannot read the timeline data: ' + e.message);
      return;
    }
    try {
      init(data);
    } catch (e) {
      showError('cannot show the timeline: ' + (e && e.message ? e.message : e) + (e && e.stack ? '\n' + e.stack : ''));
    }
  }

  if (document.readyState === 'loading') document.addEventListener('DOMContentLoaded', main);
  else main();
})();

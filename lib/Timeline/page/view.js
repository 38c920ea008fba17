// bsc timeline page, view.js: the view (which cycles the canvases show,
// zoom and pan), the cursor, canvas helpers (sizing, per-column walks, the
// gap hatch) and scheduling the drawing of everything.

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

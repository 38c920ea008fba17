// bsc timeline page, lanes.js: drawing the ruler, the task lanes and the
// overview, and the lanes' hover (tooltip and label highlight).

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
    const h = el('div', 'run-header', runLabel(row.run));
    h.title = row.run.name + ' (' + row.run.kind + ')';
    return h;
  }
  if (row.kind === 'empty') return el('div', 'empty', 'no tasks in ' + row.run.name);
  const d = el('div', 'lane-label');
  d.dataset.task = row.task.name;
  d.dataset.run = String(row.run.index);
  d.style.paddingLeft = (8 + row.task.depth * 14) + 'px';
  d.title = (two ? runLabel(row.run) + ': ' : '') + row.task.name;
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
    g.fillStyle = S.runs.length > 1 ? runColor(run) + '66' : '#c4cad2';
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
  out.push(line('', 'cycle ' + c + (S.runs.length > 1 ? ' \u00b7 ' + runLabel(run) : '')));
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

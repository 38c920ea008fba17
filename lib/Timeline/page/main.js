// bsc timeline page, main.js: mouse and keyboard handling, wiring the
// controls, the window.bscTimeline test API and startup.

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

// ---------------------------------------------------------------- wiring

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
  if (key === 'A' || key === 'B') return S.runs.find((r) => r.record === (key === 'A' ? 0 : 1));
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
  S.records = S.runs.some((r) => r.record === 1) ? 2 : 1;
  computeDomain();
  assignStateColors();
  // The files drawn: a team's is one, whatever its robots.
  const files = S.runs.filter((r, i) => i === 0 || r.record !== S.runs[i - 1].record);
  document.title = document.title || files.map((r) => r.name).join(' vs ');
  const robots = (r) => S.runs.filter((o) => o.record === r.record).length;
  const names = files.map((r) => (S.records > 1 ? runLetter(r.record) + ': ' : '') + r.name +
    (r.robot !== null ? ' (' + robots(r) + (robots(r) === 1 ? ' robot)' : ' robots)') : ''));
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

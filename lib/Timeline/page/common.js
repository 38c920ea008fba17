// bsc timeline: the page's script. Plain ES2020, no modules, no dependencies.
//
// The script is split by job into the files of lib/Timeline/page, which
// EmbedPage.cmake concatenates in a fixed order (see PAGE_JS in
// lib/Timeline/CMakeLists.txt) into one strict-mode function: they share
// one scope of plain function declarations and top-level consts.
//
// The data (format 1: docs/repl.md, "The timeline's data") is read from the
// JSON script element.
// Everything drawn over cycles goes onto canvases, painted per pixel column
// with a binary search to the interval under the column, so drawing costs
// O(pixels * log n) whatever the number of cycles. Each canvas keeps a "base"
// image (lanes, ticks, plot lines) that changes only when the view changes;
// moving the cursor just copies the base and draws the cursor on top.
//
// common.js: constants, the page's mutable state S, small utilities.

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
// A run's colour in plots and the overview: A and B of two runs, or each
// robot of a team.
const RUN_COLORS = ['#1a73e8', '#e37400', '#0b8043', '#8e24aa', '#c2185b',
  '#00838f', '#6d4c41', '#546e7a'];
const CURSOR = '#e8710a';
const DIFF = '#c5221f';

const $ = (id) => document.getElementById(id);

// All mutable state of the page.
const S = {
  runs: [],            // prepared runs (see prepareRun): a team's file is one per robot
  records: 1,          // the files drawn: 1, or 2 to compare
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

// How a run is named where several are drawn: its file's letter when two
// files compare, its name, and its robot in a team's file.
function runLabel(run) {
  return (S.records > 1 ? runLetter(run.record) + ': ' : '') + run.name +
    (run.robot !== null ? ', robot ' + run.robot : '');
}

// A short form beside plotted values: `A`, `robot 1`, `B robot 1`.
function runTag(run) {
  const parts = [];
  if (S.records > 1) parts.push(runLetter(run.record));
  if (run.robot !== null) parts.push('robot ' + run.robot);
  return parts.join(' ');
}

// The run a run compares with: the same robot in the other file.
function partnerOf(run) {
  if (S.records < 2) return null;
  return S.runs.find((o) => o.record !== run.record && o.robot === run.robot) || null;
}

function runColor(run) { return RUN_COLORS[run.index % RUN_COLORS.length]; }

// bsc timeline page, panel.js: the side panel at the cursor (cycle, task
// hierarchy, inputs and outputs), the legend and the first-difference box.

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
    const name = S.runs.length > 1 ? runLabel(run) : run.name;
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
    if (S.runs.length > 1) wrap.appendChild(el('h3', '', runLabel(run)));
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
  const otherRun = partnerOf(run);   // to mark differing fields
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
    if (S.runs.length > 1) box.appendChild(el('h3', '', runLabel(run)));
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
  const other = partnerOf(run);
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

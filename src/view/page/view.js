// goal view: rebuilds the world and every agent's mind from the run's trace lines
// (docs/trace-format.md) and draws them. The same code serves a replay (all lines at once)
// and a live run (the lines so far, then a stream of server-sent events).
'use strict';

// A full copy of the state every KEY ticks: moving the timeline restores the copy before the
// tick and applies at most KEY ticks of records.
const KEY = 50;
const MAX_LIST = 400; // lines shown per list (beliefs, messages, ...)
const params = new URLSearchParams(location.search);
const $ = (id) => document.getElementById(id);
const SVG = 'http://www.w3.org/2000/svg';

// ---------------------------------------------------------------- the model: records to state

// An attention set: the goals of the top-level base (module null) or of a module with a focus.
function newSet(module, focus, goals) { return { module, focus, goals: new Set(goals) }; }

// `attention` is the agent's attention stack, the top-level goal base first.
function newMind() {
  return { beliefs: new Set(), attention: [newSet(null, null)], percepts: new Set(), mail: new Set(),
    stack: [], module: null, rule: null, actions: [], errors: [], stopped: null };
}

function copyMind(m) {
  return { beliefs: new Set(m.beliefs), attention: m.attention.map((a) => newSet(a.module, a.focus, a.goals)),
    percepts: new Set(m.percepts), mail: new Set(m.mail), stack: m.stack.slice(), module: m.module, rule: m.rule,
    actions: m.actions.slice(), errors: m.errors.slice(), stopped: m.stopped };
}

// The goals of attention set `i` (absent in the trace: the top-level base, 0).
function goalsOf(m, i) {
  i = i || 0;
  while (m.attention.length <= i) m.attention.push(newSet('?', '?'));
  return m.attention[i].goals;
}

function newState() { return { world: new Map(), minds: new Map(), tick: 0 }; }

function copyState(s) {
  const minds = new Map();
  for (const [k, m] of s.minds) minds.set(k, copyMind(m));
  return { world: new Map(s.world), minds, tick: s.tick };
}

function mindOf(s, name) {
  let m = s.minds.get(name);
  if (!m) { m = newMind(); s.minds.set(name, m); }
  return m;
}

function keepLast(list, item, n) { list.push(item); if (list.length > n) list.shift(); }

// One cycle event into an agent's mind.
function applyEvent(m, e, tick) {
  switch (e.event) {
    case 'belief_inserted': m.beliefs.add(e.fact); break;
    case 'belief_deleted': m.beliefs.delete(e.fact); break;
    case 'goal_adopted': goalsOf(m, e.attention).add(e.goal); break;
    case 'goal_dropped': case 'goal_achieved': goalsOf(m, e.attention).delete(e.goal); break;
    case 'attention_pushed':
      m.attention.length = Math.max(1, Math.min(m.attention.length, e.attention));
      m.attention.push(newSet(e.module, e.focus, e.goals));
      break;
    case 'attention_popped': m.attention.length = Math.max(1, Math.min(m.attention.length, e.attention)); break;
    case 'percept_added': m.percepts.add(e.percept); break;
    case 'percept_removed': m.percepts.delete(e.percept); break;
    case 'mail_added': m.mail.add(e.fact); break;
    case 'mail_deleted': m.mail.delete(e.fact); break;
    case 'module_entered': m.stack.push(e.module); m.module = e.module; break;
    case 'module_exited': {
      const i = m.stack.lastIndexOf(e.module);
      if (i >= 0) m.stack.length = i;
      break;
    }
    case 'rule_fired': m.rule = { rule: e.rule, bindings: e.bindings, tick }; break;
    case 'action_performed': keepLast(m.actions, tick + ': ' + e.action, 30); break;
    case 'action_failed': keepLast(m.errors, tick + ': ' + e.action + ' failed: ' + e.reason, 30); break;
    case 'error': keepLast(m.errors, tick + ': ' + e.message, 30); break;
    case 'warning': keepLast(m.errors, tick + ': warning: ' + e.message, 30); break;
    case 'stopped': m.stopped = e.reason; break;
  }
}

// One record into the state.
function applyRecord(s, r) {
  if (r.tick !== undefined) s.tick = r.tick;
  switch (r.type) {
    case 'world':
      for (const k in r.set) s.world.set(k, r.set[k]);
      for (const k of r.unset) s.world.delete(k);
      break;
    case 'cycle': {
      const m = mindOf(s, r.agent);
      for (const e of r.events) applyEvent(m, e, r.tick);
      break;
    }
    case 'action':
      if (r.result !== 'ok') keepLast(mindOf(s, r.agent).errors, r.tick + ': ' + r.action + ' failed: ' + r.reason, 30);
      break;
    case 'warning': keepLast(mindOf(s, r.agent).errors, r.tick + ': ' + r.message, 30); break;
  }
}

class Model {
  constructor() {
    this.recs = [];
    this.header = null; this.layout = null; this.end = null;
    this.start = [];        // start[t]: index of the first record of tick >= t
    this.head = newState(); // the state after every record so far
    this.keys = [];         // keys[k]: { idx, state } before the first record of tick >= k*KEY
    this.messages = [];     // message records in order
    this.marks = new Map(); // agent -> { message: [ticks], delivery: [...], error: [...] }
    this.agentOf = new Map(); // entity -> agent
    this.maxTick = 0;
  }

  mark(agent, kind, tick) {
    if (!agent) return;
    let m = this.marks.get(agent);
    if (!m) { m = { message: [], delivery: [], error: [] }; this.marks.set(agent, m); }
    const l = m[kind];
    if (l[l.length - 1] !== tick) l.push(tick);
  }

  add(r) {
    switch (r.type) {
      case 'header':
        this.header = r;
        for (const a of r.agents || []) { mindOf(this.head, a.name); if (a.entity) this.agentOf.set(a.entity, a.name); }
        return;
      case 'map': this.layout = r.layout; return;
      case 'end':
        // Idle ticks at the end leave no records: the run's length is in the end record.
        this.end = r;
        if (r.ticks > this.maxTick) this.maxTick = r.ticks;
        return;
    }
    const t = r.tick;
    while (this.keys.length * KEY <= t) this.keys.push({ idx: this.recs.length, state: copyState(this.head) });
    while (this.start.length <= t) this.start.push(this.recs.length);
    if (t > this.maxTick) this.maxTick = t;
    this.noteMarks(r);
    this.recs.push(r);
    applyRecord(this.head, r);
  }

  noteMarks(r) {
    if (r.type === 'message') {
      this.messages.push(r);
      this.mark(r.from, 'message', r.tick); this.mark(r.to, 'message', r.tick);
    } else if (r.type === 'cycle') {
      for (const e of r.events) if (e.event === 'error' || e.event === 'action_failed') this.mark(r.agent, 'error', r.tick);
    } else if ((r.type === 'action' && r.result !== 'ok') || r.type === 'warning') {
      this.mark(r.agent, 'error', r.tick);
    } else if (r.type === 'world' && 'sequence_index' in r.set) {
      // The robot whose held blocks changed when the sequence advanced delivered.
      for (const k in r.set) {
        const p = k.split('/');
        if (p[0] === 'robots' && p[2] === 'holding') this.mark(this.agentOf.get(p[1]) || p[1], 'delivery', r.tick);
      }
    }
  }

  // The state at the end of tick t (every record of ticks <= t).
  at(t) {
    if (t >= this.maxTick) return this.head;
    const k = this.keys[Math.min(Math.floor(t / KEY), this.keys.length - 1)];
    const end = t + 1 < this.start.length ? this.start[t + 1] : this.recs.length;
    const s = copyState(k.state);
    for (let i = k.idx; i < end; i++) applyRecord(s, this.recs[i]);
    s.tick = t;
    return s;
  }

  // The first tick after t where `agent` has a mark of `kind`, or null.
  next(agent, kind, t) {
    const m = this.marks.get(agent);
    if (!m) return null;
    const l = m[kind];
    let lo = 0, hi = l.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (l[mid] <= t) lo = mid + 1; else hi = mid; }
    return lo < l.length ? l[lo] : null;
  }

  // Messages sent up to tick t (the last `n`, optionally only to or from `agent`).
  messagesUpTo(t, n, agent) {
    let lo = 0, hi = this.messages.length;
    while (lo < hi) { const mid = (lo + hi) >> 1; if (this.messages[mid].tick <= t) lo = mid + 1; else hi = mid; }
    const out = [];
    for (let i = lo - 1; i >= 0 && out.length < n; i--) {
      const m = this.messages[i];
      if (!agent || m.from === agent || m.to === agent) out.push(m);
    }
    return out;
  }
}

// Parses JSON lines into the model; a broken line is reported, not fatal.
function addLines(model, text) {
  let bad = 0;
  for (const line of text.split('\n')) {
    if (!line) continue;
    try { model.add(JSON.parse(line)); } catch (e) { bad++; }
  }
  if (bad) status(bad + ' unreadable trace line(s) skipped');
}

// ---------------------------------------------------------------- drawing

function el(name, attrs, parent) {
  const e = document.createElementNS(SVG, name);
  for (const k in attrs) e.setAttribute(k, attrs[k]);
  if (parent) parent.appendChild(e);
  return e;
}

const COLORS = { Red: '#e33', Blue: '#36f', Green: '#3b3', Yellow: '#fd2', White: '#fff', Pink: '#f9c',
  Orange: '#f92', Cyan: '#3dd', Magenta: '#d3d', DarkGray: '#555' };
const colour = (c) => COLORS[c] || '#999';

function drawLayout(layout) {
  const g = $('static');
  g.textContent = '';
  // An SVG element has no `hidden` property: the attribute hides it (view.css).
  if (!layout) { $('world').setAttribute('hidden', ''); $('nomap').hidden = false; return; }
  const [x0, y0, x1, y1] = layout.bounds;
  $('world').setAttribute('viewBox', [x0 - 1, y0 - 1, x1 - x0 + 2, y1 - y0 + 2].join(' '));
  for (const z of layout.zones) {
    const [a, b, c, d] = z.rect;
    el('rect', { x: a, y: b, width: c - a, height: d - b, class: 'zone ' + z.kind, 'data-name': z.name }, g);
    for (const [p, q, r, s] of z.doors) {
      el('rect', { x: p, y: q, width: r - p, height: s - q, class: 'door', 'data-room': z.name }, g);
    }
    if (z.kind !== 'corridor') el('text', { x: a + .4, y: b + 1.6, class: 'zlabel' }, g).textContent = z.name;
  }
  view.doors = Array.from(g.querySelectorAll('.door'));
  const seq = $('sequence');
  seq.textContent = '';
  seq.dataset.total = layout.sequence.length;
  for (const c of layout.sequence) {
    const d = document.createElement('span');
    d.className = 'c'; d.title = c; d.style.background = colour(c); d.dataset.color = c;
    seq.appendChild(d);
  }
  const p = document.createElement('span');
  p.id = 'progress'; seq.appendChild(p);
}

// The flat world (path -> value) as nested objects.
function nest(world) {
  const o = {};
  for (const [k, v] of world) {
    const p = k.split('/');
    let t = o;
    for (let i = 0; i < p.length - 1; i++) t = t[p[i]] || (t[p[i]] = {});
    t[p[p.length - 1]] = v;
  }
  return o;
}

// The blocks lying about (not held), as rectangles kept from one drawing to the next: most
// blocks do not move between two ticks, so only the ones that did are touched.
function drawBlocks(blocks) {
  const g = $('blocks');
  const drawn = view.blocks;
  for (const [id, e] of drawn) {
    const b = blocks[id];
    if (!b || b.holder) { e.remove(); drawn.delete(id); }
  }
  for (const id in blocks) {
    const b = blocks[id];
    if (b.holder) continue;
    const x = b.pos[0] - .5, y = b.pos[1] - .5, fill = colour(b.color);
    let e = drawn.get(id);
    if (!e) {
      e = el('rect', { width: 1, height: 1, class: 'block', 'data-id': id }, g);
      drawn.set(id, e);
    }
    if (e.dataset.x !== String(x) || e.dataset.y !== String(y)) {
      e.setAttribute('x', x); e.setAttribute('y', y); e.dataset.x = x; e.dataset.y = y;
    }
    if (e.dataset.color !== b.color) { e.setAttribute('fill', fill); e.dataset.color = b.color; }
  }
}

function drawWorld(s) {
  if (!view.model.layout) return;
  const w = nest(s.world);
  const occupied = new Set(w.occupied || []);
  for (const d of view.doors) d.classList.toggle('occupied', occupied.has(d.dataset.room));
  const blocks = w.blocks || {};
  drawBlocks(blocks);
  const g = $('dynamic');
  g.textContent = '';
  const robots = w.robots || {};
  for (const name in robots) {
    const r = robots[name];
    const agent = view.model.agentOf.get(name) || name;
    if (r.path && r.path.length) {
      el('polyline', { class: 'path', points: [r.pos].concat(r.path).map((p) => p.join(',')).join(' ') }, g);
    }
    const sel = agent === view.selected ? ' selected' : '';
    const rg = el('g', { class: 'robot' + sel, 'data-name': name, 'data-agent': agent, 'data-x': r.pos[0], 'data-y': r.pos[1],
      transform: 'translate(' + r.pos[0] + ',' + r.pos[1] + ')' }, g);
    el('rect', { x: -1, y: -1, width: 2, height: 2, rx: .3 }, rg);
    const a = (r.heading || 0) * Math.PI / 180;
    el('line', { class: 'nose', x1: 0, y1: 0, x2: Math.cos(a) * 1.3, y2: Math.sin(a) * 1.3 }, rg);
    (r.holding || []).forEach((id, i) => {
      const b = blocks[id];
      el('rect', { x: -.45 + i * .5, y: -.45, width: .9, height: .9, fill: colour(b && b.color), class: 'block held',
        'data-id': id, 'data-color': b ? b.color : '' }, rg);
    });
    if (r.battery !== undefined) {
      el('rect', { x: -1, y: 1.2, width: 2 * r.battery / 100, height: .3, class: 'battery' }, rg);
      rg.dataset.battery = r.battery;
    }
    el('text', { x: -1, y: -1.3 }, rg).textContent = name;
    // On press, not click: the robot is drawn anew each tick, so in a live run its release
    // often lands on a new element and the click would be lost.
    rg.addEventListener('pointerdown', () => select(agent));
  }
  const done = w.sequence_index || 0;
  const seq = $('sequence');
  seq.dataset.done = done;
  seq.querySelectorAll('.c').forEach((c, i) => c.classList.toggle('done', i < done));
  const p = $('progress');
  if (p) p.textContent = done + ' of ' + seq.dataset.total + ' delivered';
}

// Shows `items` in the list `id` (or the element itself), changing only the entries that differ
// from what it shows (moving the timeline a tick changes a few beliefs, not the hundreds shown).
function fillList(id, items, countId) {
  const ul = typeof id === 'string' ? $(id) : id;
  const all = Array.from(items);
  const shown = all.slice(0, MAX_LIST);
  if (all.length > MAX_LIST) shown.push('… ' + (all.length - MAX_LIST) + ' more');
  const lis = ul.children;
  for (let i = 0; i < shown.length; i++) {
    if (i < lis.length) {
      if (lis[i].textContent !== shown[i]) lis[i].textContent = shown[i];
    } else {
      const li = document.createElement('li'); li.textContent = shown[i]; ul.appendChild(li);
    }
  }
  while (lis.length > shown.length) ul.removeChild(ul.lastChild);
  if (countId) $(countId).textContent = '(' + all.length + ')';
}

// True when `e` already shows what `sig` describes; otherwise remembers `sig`. A list redrawn
// although nothing changed would replace the element under the mouse, and a click whose press and
// release land on different elements is lost (in a live run the page draws every tick).
function unchanged(e, sig) {
  if (e.dataset.sig === sig) return true;
  e.dataset.sig = sig;
  return false;
}

function drawAgents(s) {
  const ul = $('agents');
  const shown = Array.from(s.minds, ([name, m]) => [name, name === view.selected, m.stopped || '']);
  if (unchanged(ul, JSON.stringify(shown))) return;
  ul.textContent = '';
  for (const [name, m] of s.minds) {
    const li = document.createElement('li');
    li.textContent = name; li.dataset.name = name;
    if (name === view.selected) li.classList.add('selected');
    if (m.stopped) { li.classList.add('stopped'); li.title = m.stopped; }
    li.addEventListener('click', () => select(name));
    ul.appendChild(li);
  }
}

function drawMind(s) {
  const name = view.selected;
  const m = name && s.minds.get(name);
  $('mind').hidden = !m;
  if (!m) return;
  $('mindname').textContent = name;
  const a = (view.model.header.agents || []).find((x) => x.name === name) || {};
  const facts = [['entity', a.entity || 'none'], ['file', a.file || ''],
    ['modules', m.stack.join(' › ') || '(between cycles)'], ['last module', m.module || '-'],
    ['last rule fired', m.rule ? m.rule.rule + (m.rule.bindings ? ' with ' + m.rule.bindings : '') + ' (tick ' + m.rule.tick + ')' : '-'],
    ['status', m.stopped || 'running']];
  const dl = $('facts');
  dl.textContent = '';
  for (const [k, v] of facts) {
    const dt = document.createElement('dt'); dt.textContent = k;
    const dd = document.createElement('dd'); dd.textContent = v; dd.dataset.key = k;
    dl.append(dt, dd);
  }
  fillList('beliefs', Array.from(m.beliefs).sort(), 'nbeliefs');
  drawGoals(m);
  fillList('percepts', Array.from(m.percepts).sort(), 'npercepts');
  fillList('mail', m.mail, 'nmail');
  fillList('actions', m.actions.slice().reverse());
  fillList('errors', m.errors.slice().reverse());
}

// The goals per attention set, the current set (top of the stack) first and highlighted, each
// labelled with the module that owns it: the top-level base with the bottom module.
function drawGoals(m) {
  const box = $('goals');
  const sets = m.attention.slice().reverse();
  while (box.children.length > sets.length) box.removeChild(box.lastChild);
  let total = 0;
  sets.forEach((a, i) => {
    let sec = box.children[i];
    if (!sec) {
      sec = document.createElement('section');
      const h = document.createElement('h4');
      const n = document.createElement('span'); n.className = 'n';
      h.append(document.createElement('span'), ' ', n);
      const ul = document.createElement('ul'); ul.className = 'terms';
      sec.append(h, ul);
      box.appendChild(sec);
    }
    const depth = sets.length - 1 - i;
    const label = depth === 0 ? (m.stack[0] || 'top level') + ' (base)' : a.module + ' [focus=' + a.focus + ']';
    sec.className = 'goalset' + (i === 0 ? ' current' : '');
    sec.dataset.attention = depth;
    sec.firstChild.firstChild.textContent = label;
    sec.firstChild.lastChild.textContent = '(' + a.goals.size + ')';
    fillList(sec.lastChild, a.goals);
    total += a.goals.size;
  });
  $('ngoals').textContent = '(' + total + ')';
}

// The messages up to tick t, newest first; entries are reused from the last drawing and
// rewritten only where the message at their place changed.
function drawMessages(t) {
  const ol = $('messages');
  const only = $('onlyagent').checked ? view.selected : null;
  const list = view.model.messagesUpTo(t, 100, only);
  const lis = ol.children;
  list.forEach((m, i) => {
    let li = lis[i];
    if (!li) { li = document.createElement('li'); ol.appendChild(li); }
    if (li.message === m) return;
    li.message = m;
    li.textContent = '';
    const act = document.createElement('span'); act.className = 'act'; act.textContent = m.act;
    li.append(m.tick + ' ' + m.from + ' → ' + m.to + ' ', act, ' ' + (m.english ? '“' + m.english + '” ' : '') + m.content);
    li.classList.toggle('lost', !m.delivered);
  });
  while (lis.length > list.length) ol.removeChild(ol.lastChild);
}

function render() {
  const t = view.tick;
  const s = view.model.at(t);
  drawWorld(s);
  drawAgents(s);
  drawMind(s);
  drawMessages(t);
  $('timeline').max = view.model.maxTick;
  $('timeline').value = t;
  $('tick').value = t;
  $('of').textContent = 'of ' + view.model.maxTick + (view.model.end ? ' (' + view.model.end.end + ')' : '');
  document.body.dataset.tick = t;
  // Other panels (player.js) draw their part of the same state.
  document.dispatchEvent(new CustomEvent('goal:render', { detail: s }));
}

// ---------------------------------------------------------------- why / why not

function showWhy(v) {
  const box = $('why');
  box.textContent = '';
  if (v.error) { const p = document.createElement('p'); p.className = 'unavailable'; p.textContent = v.error; box.appendChild(p); return; }
  const p = document.createElement('p');
  p.textContent = v.agent + ' at tick ' + v.tick + ', cycle ' + v.cycle + ', module ' + v.module + ':';
  box.appendChild(p);
  const table = document.createElement('table');
  table.innerHTML = '<tr><th>rule</th><th>outcome</th><th>bindings</th><th>failed</th></tr>';
  for (const r of v.rules || []) {
    const tr = document.createElement('tr');
    tr.className = 'rule ' + r.outcome;
    tr.title = r.text;
    for (const c of [r.rule, r.outcome.replace('_', ' '), r.bindings || '', r.failed_literal || r.failed_action || '']) {
      const td = document.createElement('td'); td.textContent = c; tr.appendChild(td);
    }
    table.appendChild(tr);
  }
  box.appendChild(table);
}

function askWhy(sync) {
  if (!view.selected) return;
  if (!view.info.why) {
    showWhy({ error: 'The why answer is unavailable for this run (this view cannot rerun the system).' });
    return;
  }
  const url = '/api/why?agent=' + encodeURIComponent(view.selected) + '&tick=' + view.tick;
  $('why').textContent = 'asking…';
  const x = new XMLHttpRequest();
  x.open('GET', url, !sync);
  x.onload = () => { try { showWhy(JSON.parse(x.responseText)); } catch (e) { showWhy({ error: 'unreadable answer: ' + e }); } };
  x.onerror = () => showWhy({ error: 'the view server did not answer' });
  x.send();
}

// ---------------------------------------------------------------- controls

const view = { model: new Model(), tick: 0, selected: null, playing: false, follow: false, info: {}, speed: 100,
  doors: [], blocks: new Map() };
let pending = false;

function status(text) { $('status').textContent = text; }

function seek(t) {
  view.tick = Math.max(0, Math.min(view.model.maxTick, t | 0));
  if (!pending) { pending = true; requestAnimationFrame(() => { pending = false; render(); }); }
}

function select(name) { view.selected = name; $('why').textContent = ''; render(); }

function control(cmd) {
  const x = new XMLHttpRequest();
  x.open('POST', '/api/control?' + cmd);
  x.onload = () => { try { liveState(JSON.parse(x.responseText)); } catch (e) { /* shown by the next state */ } };
  x.send();
}

function liveState(c) {
  if (!c || c.error) return;
  view.playing = !c.paused;
  $('play').textContent = c.paused ? '▶' : '❚❚';
  status(c.ended ? 'run ended' : c.paused ? 'paused' : '');
}

let lastFrame = null, carry = 0;
function playFrame(now) {
  if (!view.playing || view.info.mode === 'live') { lastFrame = null; return; }
  if (lastFrame !== null) {
    carry += (now - lastFrame) / 1000 * view.speed;
    const n = Math.floor(carry);
    if (n > 0) { carry -= n; seek(view.tick + n); }
    if (view.tick >= view.model.maxTick) { view.playing = false; $('play').textContent = '▶'; }
  }
  lastFrame = now;
  requestAnimationFrame(playFrame);
}

function wire() {
  $('timeline').addEventListener('input', (e) => { view.follow = false; seek(+e.target.value); });
  $('tick').addEventListener('change', (e) => { view.follow = false; seek(+e.target.value); });
  $('speed').addEventListener('change', (e) => {
    view.speed = +e.target.value;
    if (view.info.mode === 'live') control('speed=' + view.speed);
  });
  $('play').addEventListener('click', () => {
    if (view.info.mode === 'live') { control(view.playing ? 'pause' : 'play'); return; }
    view.playing = !view.playing;
    $('play').textContent = view.playing ? '❚❚' : '▶';
    if (view.playing) { if (view.tick >= view.model.maxTick) seek(0); requestAnimationFrame(playFrame); }
  });
  $('step').addEventListener('click', () => {
    if (view.info.mode === 'live') { view.follow = true; control('step'); } else seek(view.tick + 1);
  });
  $('live').addEventListener('click', () => { view.follow = true; seek(view.model.maxTick); });
  $('onlyagent').addEventListener('change', render);
  $('askwhy').addEventListener('click', () => askWhy(false));
  for (const b of document.querySelectorAll('#jumps button')) {
    b.addEventListener('click', () => {
      const t = view.model.next(view.selected, b.dataset.kind, view.tick);
      if (t === null) status('no later ' + b.dataset.kind + ' of ' + view.selected); else { view.follow = false; status(''); seek(t); }
    });
  }
  document.addEventListener('keydown', (e) => {
    if (e.target.tagName === 'INPUT' || e.target.tagName === 'SELECT') return;
    if (e.key === ' ') { e.preventDefault(); $('play').click(); }
    if (e.key === 'ArrowRight') seek(view.tick + 1);
    if (e.key === 'ArrowLeft') seek(view.tick - 1);
  });
}

// A live run: new lines arrive as server-sent events; the view follows the newest tick unless
// the user moved the timeline.
function stream(from) {
  const es = new EventSource('/api/stream?from=' + from);
  let queued = [];
  es.onmessage = (e) => {
    queued.push(e.data);
    if (queued.length === 1) {
      requestAnimationFrame(() => {
        addLines(view.model, queued.join('\n'));
        queued = [];
        if (view.follow) view.tick = view.model.maxTick;
        render();
      });
    }
  };
  es.addEventListener('end', () => { es.close(); status('run ended'); render(); });
  es.onerror = () => status('connection to the run lost');
  setInterval(() => { const x = new XMLHttpRequest(); x.open('GET', '/api/info'); x.onload = () => { try { liveState(JSON.parse(x.responseText).control); } catch (e) { /* next time */ } }; x.send(); }, 1000);
}

// Loads the trace so far. Synchronous on purpose: the first drawing is complete when the page's
// load event fires (what a headless browser dumps), and nothing else can happen before it.
function load() {
  const info = new XMLHttpRequest();
  info.open('GET', '/api/info', false);
  info.send();
  view.info = JSON.parse(info.responseText);
  const x = new XMLHttpRequest();
  x.open('GET', '/api/trace', false);
  x.send();
  if (x.status !== 200) { status('cannot load the trace: ' + x.status); return; }
  addLines(view.model, x.responseText);
  const lines = +x.getResponseHeader('X-Trace-Lines');
  document.title = 'goal view: ' + view.info.title;
  $('title').textContent = view.info.title;
  $('mode').textContent = view.info.mode === 'live' ? 'live run' : 'replay';
  drawLayout(view.model.layout);
  const agents = view.model.header ? view.model.header.agents : [];
  view.selected = params.get('agent') || (agents.length ? agents[0].name : null);
  if (view.info.mode === 'live') {
    $('step').title = 'pause and run one more round';
    liveState(view.info.control);
    view.speed = view.info.control ? view.info.control.speed : 100;
  } else {
    $('live').hidden = true;
  }
  view.follow = view.info.mode === 'live' && !params.has('tick');
  view.tick = params.has('tick') ? Math.min(+params.get('tick'), view.model.maxTick) : view.follow ? view.model.maxTick : 0;
  render();
  // Milliseconds from the start of navigation until the run is drawn.
  if (params.has('measure')) measure(performance.now());
  if (params.has('why')) askWhy(true);
  document.body.dataset.ready = '1';
  if (view.info.mode === 'live' && !view.info.complete) stream(lines);
}

// ?measure: the load time (navigation start to the first drawing of the run) and the time to
// move the timeline to 200 spread ticks and lay the page out again, written into #measure (read
// in the headless browser).
function measure(loaded) {
  const n = 200, times = [], model = [];
  for (let i = 0; i < n; i++) {
    const t = Math.floor((i * 7919) % (view.model.maxTick + 1));
    let a = performance.now();
    view.model.at(t);
    model.push(performance.now() - a);
    a = performance.now();
    view.tick = t; render();
    void document.body.offsetHeight; // the style and layout the change costs, too
    times.push(performance.now() - a);
  }
  times.sort((a, b) => a - b);
  model.sort((a, b) => a - b);
  const out = $('measure');
  out.dataset.loadMs = loaded.toFixed(0);
  out.dataset.pageMs = performance.now().toFixed(0);
  out.dataset.seekMedianMs = times[n >> 1].toFixed(1);
  out.dataset.seekP95Ms = times[Math.floor(n * .95)].toFixed(1);
  out.dataset.seekMaxMs = times[n - 1].toFixed(1);
  out.dataset.stateMaxMs = model[n - 1].toFixed(1); // of which the model's state at the tick
  out.dataset.ticks = view.model.maxTick;
  out.textContent = JSON.stringify(out.dataset);
}

wire();
try { load(); } catch (e) { status('cannot show this run: ' + e); }

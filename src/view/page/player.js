// goal view, player panel: a person plays a HumanBot of a live run. They take a free robot
// (one per browser), click a room or the drop zone to go there, a block to go to it, and pick
// up, put down or send a message from the BW4T message list. Each choice is the HumanBot
// request percept of the BW4T interface (goTo('RoomA1'), goToBlock(3), pickUp(3), putDown,
// sendMessage(all, Content), ...), POSTed to the server; the run takes it at its next tick
// boundary and the page shows whether it was applied or refused. In a replay the panel lists
// the requests the run took. It also shows the humans, e-partners and who holds which.
'use strict';

// The panel's markup (inside <section id="player"> of the page).
const PANEL = `
<div id="playlive" hidden>
  <h2>Play a HumanBot</h2>
  <ul id="humans"></ul>
  <div id="playcontrols" hidden>
    <p>You play <strong id="me"></strong>: click a room or the drop zone to go there, a block to
      go to it. <button id="leave">leave</button></p>
    <p><button id="pickup" disabled>pick up</button> <button id="putdown">put down</button>
      <button id="eppick">pick up e-partner</button> <button id="epdrop">drop e-partner</button></p>
    <p id="msgbox"><label>message <select id="msgpattern"></select></label> <span id="msgslots"></span>
      <label>to <select id="msgto"><option value="all">all</option></select></label>
      <button id="sendmsg">send</button></p>
    <h3>Your requests (latest first)</h3><ol id="myrequests"></ol>
  </div>
  <p id="playnote" role="status"></p>
</div>
<div id="peoplebox" hidden><h3>Humans and e-partners</h3><ul id="people"></ul></div>
<div id="inputsbox" hidden><h3>Requests people made (latest first)</h3><ol id="inputs"></ol></div>`;

const play = { token: null, mine: null, block: null, state: null, vocab: null, inputs: [], scanned: 0 };
const TOKEN_KEY = 'goal-view-player';

function pel(tag, attrs, text) {
  const e = document.createElement(tag);
  for (const k in attrs || {}) e.setAttribute(k, attrs[k]);
  if (text !== undefined) e.textContent = text;
  return e;
}

// An atom as Prolog reads it back (always quoted: names like RoomA1 start with a capital).
function atom(name) { return "'" + String(name).replace(/\\/g, '\\\\').replace(/'/g, "\\'") + "'"; }

function playSay(text, bad) {
  const p = $('playnote');
  p.textContent = text;
  p.className = bad ? 'refused' : '';
}

function ask(method, path, body, done) {
  const x = new XMLHttpRequest();
  x.open(method, path);
  if (body) x.setRequestHeader('Content-Type', 'application/json');
  x.onload = () => {
    let v = null;
    try { v = JSON.parse(x.responseText); } catch (e) { v = { error: 'unreadable answer (' + x.status + ')' }; }
    done(x.status, v);
  };
  x.onerror = () => done(0, { error: 'the view server did not answer' });
  x.send(body ? JSON.stringify(body) : null);
}

// ---------------------------------------------------------------- taking a robot, requests

function takeRobot(entity) {
  ask('POST', '/api/play/take', { robot: entity, token: play.token }, (status, v) => {
    if (status !== 200) { playSay(v.error, true); return; }
    play.token = v.token;
    try { localStorage.setItem(TOKEN_KEY, v.token); } catch (e) { /* private mode: this tab only */ }
    playSay('You play ' + v.robot + ': click a room or the drop zone to go there, a block to go to it.');
    poll();
  });
}

function leaveRobot() {
  if (!play.token) return;
  ask('POST', '/api/play/leave', { token: play.token }, () => poll());
}

function send(request) {
  if (!play.mine) { playSay('Take a free HumanBot first.', true); return; }
  ask('POST', '/api/play/request', { token: play.token, request }, (status, v) => {
    if (status !== 202) playSay(request + ': ' + v.error, true);
    else playSay(request + ': sent, taken at the next tick');
    poll();
  });
}

// What a click on the map means: the topmost free block or zone under the pointer (a robot
// drawn over a room or a block does not stand in the way).
function mapTarget(e) {
  const under = document.elementsFromPoint ? document.elementsFromPoint(e.clientX, e.clientY) : [e.target];
  return under.find((t) => t.classList && ((t.classList.contains('block') && !t.classList.contains('held'))
    || (t.classList.contains('zone') && t.dataset.name)));
}

// Clicks on the map: a zone (room, drop zone, corridor) is goTo, a free block goToBlock.
function onMapClick(e) {
  if (!play.mine || view.info.mode !== 'live') return;
  const t = mapTarget(e);
  if (!t) return;
  if (t.classList.contains('block')) {
    play.block = t.dataset.id;
    drawPlayer();
    send('goToBlock(' + Number(t.dataset.id) + ')');
  } else if (t.classList.contains('zone') && t.dataset.name) {
    send('goTo(' + atom(t.dataset.name) + ')');
  }
}

// ---------------------------------------------------------------- messages

// The slots of a message pattern (`Me`, `Player`, `Room`, `Place`, `Color`, `Block`, `N`).
function slotsOf(pattern) { return Array.from(new Set(pattern.match(/\b[A-Z][A-Za-z]*\b/g) || [])); }

function optionsFor(slot) {
  const layout = view.model.layout;
  const zones = layout ? layout.zones : [];
  switch (slot) {
    case 'Player': return (view.model.header ? view.model.header.agents : []).map((a) => a.name);
    case 'Room': return zones.filter((z) => z.kind === 'room' || z.kind === 'dropzone').map((z) => z.name);
    case 'Place': return zones.map((z) => z.name);
    case 'Color': return play.vocab ? play.vocab.colors : [];
    default: return null; // a number
  }
}

function drawMessageSlots() {
  const box = $('msgslots');
  box.textContent = '';
  const pattern = $('msgpattern').value;
  for (const slot of slotsOf(pattern)) {
    if (slot === 'Me') continue;
    const opts = optionsFor(slot);
    let input;
    if (opts) {
      input = pel('select', { 'data-slot': slot, 'aria-label': slot });
      for (const o of opts) input.appendChild(pel('option', { value: o }, o));
    } else {
      input = pel('input', { 'data-slot': slot, type: 'number', min: '0', value: '1', 'aria-label': slot });
    }
    box.append(pel('span', {}, slot.toLowerCase() + ' '), input, ' ');
  }
}

// The content of the chosen message: the pattern with its slots filled in.
function messageContent() {
  const me = agentOfEntity(play.mine);
  const values = { Me: atom(me) };
  for (const i of $('msgslots').querySelectorAll('[data-slot]')) {
    values[i.dataset.slot] = i.tagName === 'SELECT' ? atom(i.value) : String(Math.max(0, Math.floor(+i.value || 0)));
  }
  return $('msgpattern').value.replace(/\b[A-Z][A-Za-z]*\b/g, (s) => values[s] || s);
}

function loadVocabulary() {
  ask('GET', '/api/play/messages', null, (status, v) => {
    if (status !== 200) return;
    play.vocab = v;
    const sel = $('msgpattern');
    sel.textContent = '';
    for (const m of v.messages) {
      sel.appendChild(pel('option', { value: m.pattern, title: m.act }, m.sentence.replace(/\{([A-Za-z]+)\}/g, (_, slot) => '[' + slot.toLowerCase() + ']')));
    }
    drawMessageSlots();
  });
}

function agentOfEntity(entity) {
  const a = (view.model.header ? view.model.header.agents : []).find((x) => x.entity === entity);
  return a ? a.name : entity;
}

// ---------------------------------------------------------------- drawing the panel

function drawRobots() {
  const ul = $('humans');
  const st = play.state;
  const shown = st && [st.announced, st.robots.map((r) => [r.entity, r.mine, r.taken])];
  if (unchanged(ul, JSON.stringify(shown))) return;
  ul.textContent = '';
  if (!st || !st.robots.length) {
    ul.appendChild(pel('li', {}, st && st.announced ? 'This run has no HumanBots (goal run --humans 1 adds one).' : 'Waiting for the run…'));
    return;
  }
  for (const r of st.robots) {
    const cls = r.mine ? 'mine' : r.taken ? 'taken' : 'free';
    const li = pel('li', { class: cls, 'data-entity': r.entity });
    const b = pel('button', { 'data-entity': r.entity, class: 'take' }, r.entity);
    b.disabled = r.taken && !r.mine;
    b.addEventListener('click', () => takeRobot(r.entity));
    li.append(b, ' ', pel('span', { class: 'who' }, r.mine ? 'you' : r.taken ? 'taken' : 'free'));
    ul.appendChild(li);
  }
}

function drawRequests() {
  const ol = $('myrequests');
  ol.textContent = '';
  for (const q of (play.state && play.state.requests) || []) {
    const li = pel('li', { class: q.state, 'data-id': q.id });
    li.textContent = q.request + ': ' + q.state + (q.tick !== null ? ' at tick ' + q.tick : '') + (q.reason ? ' (' + q.reason + ')' : '');
    ol.appendChild(li);
  }
  const last = ((play.state && play.state.requests) || [])[0];
  if (last && last.state === 'refused') playSay(last.request + ' refused: ' + last.reason, true);
}

function drawPlayer() {
  const live = view.info.mode === 'live';
  $('playlive').hidden = !live;
  $('playcontrols').hidden = !play.mine;
  $('me').textContent = play.mine || '';
  const pick = $('pickup');
  pick.disabled = play.block === null;
  pick.textContent = play.block === null ? 'pick up (click a block first)' : 'pick up block ' + play.block;
  drawRobots();
  drawRequests();
}

// Humans, e-partners and who holds which, from the world at the shown tick.
function drawPeople(s) {
  const ul = $('people');
  ul.textContent = '';
  const w = nest(s.world);
  const robots = w.robots || {};
  const eps = w.epartners || {};
  for (const name in robots) {
    const r = robots[name];
    if (r.kind !== 'human') continue;
    const li = pel('li', { class: 'human', 'data-name': name });
    li.textContent = name + ' (human, agent ' + agentOfEntity(name) + ')' + (r.epartner ? ' carries e-partner ' + r.epartner : '');
    ul.appendChild(li);
  }
  for (const name in eps) {
    const e = eps[name];
    const li = pel('li', { class: 'epartner', 'data-name': name, 'data-holder': e.holder || '' });
    li.textContent = name + ' (e-partner: ' + (e.functionalities || []).join(', ') + ') ' + (e.holder ? 'held by ' + e.holder : 'lying free');
    ul.appendChild(li);
  }
  $('peoplebox').hidden = !ul.children.length;
  markMap(robots, eps);
}

// Humans and e-partners on the map: humans get their own look, e-partners a small marker.
function markMap(robots, eps) {
  for (const g of document.querySelectorAll('#dynamic .robot')) {
    const r = robots[g.dataset.name];
    g.classList.toggle('human', !!(r && r.kind === 'human'));
    g.classList.toggle('played', g.dataset.name === play.mine);
  }
  const dyn = $('dynamic');
  if (!dyn) return;
  for (const name in eps) {
    const e = eps[name];
    const p = e.holder && robots[e.holder] ? robots[e.holder].pos : e.pos;
    if (!p) continue;
    const c = el('circle', { cx: p[0] + (e.holder ? 1 : 0), cy: p[1] + (e.holder ? 1 : 0), r: .45, class: 'epartner-mark', 'data-name': name }, dyn);
    el('title', {}, c).textContent = name + (e.holder ? ' held by ' + e.holder : '');
  }
}

// The requests the run took up to the shown tick (input records; a replay shows them too).
function drawInputs(t) {
  const recs = view.model.recs;
  if (recs.length < play.scanned) { play.inputs = []; play.scanned = 0; }
  for (let i = play.scanned; i < recs.length; i++) if (recs[i].type === 'input') play.inputs.push(recs[i]);
  play.scanned = recs.length;
  const ol = $('inputs');
  ol.textContent = '';
  const shown = play.inputs.filter((r) => r.tick <= t).slice(-30).reverse();
  for (const r of shown) {
    const li = pel('li', { class: r.result });
    li.textContent = r.tick + ' ' + r.entity + ': ' + r.request + (r.result === 'ok' ? '' : ' refused: ' + r.reason);
    ol.appendChild(li);
  }
  $('inputsbox').hidden = !play.inputs.length;
}

function poll() {
  if (view.info.mode !== 'live') return;
  const q = play.token ? '?token=' + encodeURIComponent(play.token) : '';
  ask('GET', '/api/play' + q, null, (status, v) => {
    if (status !== 200) return;
    play.state = v;
    if (v.you !== play.mine) play.block = null;
    play.mine = v.you;
    drawPlayer();
  });
}

function wirePlayer() {
  $('player').innerHTML = PANEL;
  try { play.token = localStorage.getItem(TOKEN_KEY); } catch (e) { play.token = null; }
  $('world').addEventListener('click', onMapClick);
  $('pickup').addEventListener('click', () => { if (play.block !== null) send('pickUp(' + Number(play.block) + ')'); });
  $('putdown').addEventListener('click', () => send('putDown'));
  $('eppick').addEventListener('click', () => send('pickUpEPartner'));
  $('epdrop').addEventListener('click', () => send('dropEPartner'));
  $('leave').addEventListener('click', leaveRobot);
  $('msgpattern').addEventListener('change', drawMessageSlots);
  $('sendmsg').addEventListener('click', () => {
    const to = $('msgto').value;
    send('sendMessage(' + (to === 'all' ? 'all' : atom(to)) + ', ' + messageContent() + ')');
  });
  document.addEventListener('goal:render', (e) => { drawPeople(e.detail); drawInputs(view.tick); });
  if (view.info.mode === 'live') {
    const to = $('msgto');
    for (const a of (view.model.header ? view.model.header.agents : [])) to.appendChild(pel('option', { value: a.name }, a.name));
    loadVocabulary();
    poll();
    setInterval(poll, 1000);
  }
  drawPlayer();
  drawPeople(view.model.at(view.tick));
  drawInputs(view.tick);
}

wirePlayer();

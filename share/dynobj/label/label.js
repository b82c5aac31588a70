// SPDX-License-Identifier: BSD-3-Clause
// dynobj-label's page: shows one sweep at a time (intensity image, rows scaled up, and a top-down
// view), sends clicks to the server for region growing, and keeps only the candidate region and
// the undo list itself: every label lives in the server (saved every few seconds).
'use strict';

const $ = (id) => document.getElementById(id);
const S = {
  info: null, k: 0, n: 0, rows: 0, cols: 0, xs: 1, ys: 1,
  data: null,      // {inten, ground, x, y, z} of the sweep shown
  labels: null,    // {reviewed, objects: [{id, state, pixels}]}
  cand: null,      // Set of candidate pixels (not yet accepted)
  current: 0,      // current object id (0 = none: Accept makes a new one)
  undo: [], busy: 0, tool: 'grow', painting: false, loadSeq: 0,
};
window.dynobjLabel = S;  // for the browser test and the curious

// ---- server calls -------------------------------------------------------------------------------
function setBusy(d) { S.busy += d; document.body.dataset.busy = String(S.busy); }

async function api(path, body) {
  setBusy(+1);
  try {
    let res;
    try {
      res = await fetch(path, body === undefined ? {} : {
        method: 'POST', headers: {'Content-Type': 'application/json'}, body: JSON.stringify(body)});
    } catch (e) {
      throw new Error('dynobj-label is not answering (' + e.message + '). Start it again with the ' +
                      'same command: it resumes from the last save.');
    }
    if (!res.ok) {
      let msg = res.status + ' ' + res.statusText;
      try { msg = (await res.json()).error || msg; } catch (e) { /* not JSON */ }
      throw new Error(msg);
    }
    return path.startsWith('/api/sweep-data') ? res.arrayBuffer() : res.json();
  } finally { setBusy(-1); }
}

function showError(e) {
  $('error-text').textContent = (e && e.message) ? e.message : String(e);
  $('error').hidden = false;
}
function notice(text) { $('notice').textContent = text; }
async function guarded(fn) { try { await fn(); } catch (e) { showError(e); } }

// ---- loading ------------------------------------------------------------------------------------
async function refreshInfo() {
  S.info = await api('/api/info');
  $('nreviewed').textContent = S.info.reviewed;
  $('nlabelled').textContent = S.info.labelled;
  $('nobjects').textContent = S.info.objects.length;
  const st = $('save-state');
  if (S.info.save_error) {
    st.className = 'save fail';
    st.textContent = 'SAVE FAILED: ' + S.info.save_error + ' (labels kept in dynobj-label)';
  } else if (S.info.revision !== S.info.saved_revision) {
    st.className = 'save dirty'; st.textContent = 'unsaved changes (autosave)';
  } else {
    st.className = 'save ok';
    st.textContent = S.info.saved_at ? 'saved ' + S.info.saved_at : 'nothing to save';
  }
}

async function loadSweep(k) {
  k = Math.max(0, Math.min(S.n - 1, k));
  const seq = ++S.loadSeq;
  const [labels, buf] = await Promise.all([api('/api/sweep?k=' + k), api('/api/sweep-data?k=' + k)]);
  if (seq !== S.loadSeq) return;  // a later request won
  const n = S.rows * S.cols;
  S.data = {inten: new Uint8Array(buf, 0, n), ground: new Uint8Array(buf, n, n),
            x: new Float32Array(buf, 2 * n, n), y: new Float32Array(buf, 6 * n, n),
            z: new Float32Array(buf, 10 * n, n)};
  if (k !== S.k) S.cand = null;
  S.k = k; S.labels = labels;
  $('sweep').value = k; $('k').textContent = k + 1;
  history.replaceState(null, '', '#k=' + k);
  document.body.dataset.k = String(k);
  draw();
}

async function reloadLabels() {
  S.labels = await api('/api/sweep?k=' + S.k);
  await refreshInfo();
  draw();
}

// ---- drawing ------------------------------------------------------------------------------------
function colour(id) {  // a stable, distinct colour per object id
  const h = (id * 137.508) % 360, s = 0.75, l = 0.55;
  const f = (n) => { const k = (n + h / 30) % 12;
    return Math.round(255 * (l - s * Math.min(l, 1 - l) * Math.max(-1, Math.min(k - 3, 9 - k, 1)))); };
  return [f(0), f(8), f(4)];
}

function draw() {
  if (!S.data) return;
  const W = S.cols, H = S.rows, d = S.data;
  const img = new ImageData(W, H);
  const px = img.data;
  for (let i = 0; i < W * H; i++) {
    const v = d.inten[i];
    px[4 * i] = v; px[4 * i + 1] = v; px[4 * i + 2] = v; px[4 * i + 3] = 255;
    if (d.ground[i]) { px[4 * i] = v * 0.75; px[4 * i + 1] = v * 0.75 + 30; px[4 * i + 2] = v * 0.7; }
  }
  const paint = (i, c, a) => {
    px[4 * i] = px[4 * i] * (1 - a) + c[0] * a;
    px[4 * i + 1] = px[4 * i + 1] * (1 - a) + c[1] * a;
    px[4 * i + 2] = px[4 * i + 2] * (1 - a) + c[2] * a;
  };
  const rowsHere = [];
  for (const o of S.labels.objects) {
    const c = colour(o.id), solid = o.state === 'confirmed';
    for (const i of o.pixels) {
      const hatch = ((Math.floor(i / W) + i % W) & 1) === 0;
      if (solid) paint(i, c, 0.75); else if (hatch) paint(i, c, 0.9); else paint(i, [90, 90, 90], 0.5);
    }
    rowsHere.push(o);
  }
  if (S.cand) for (const i of S.cand) paint(i, [0, 229, 255], 0.8);
  const off = document.createElement('canvas');
  off.width = W; off.height = H;
  off.getContext('2d').putImageData(img, 0, 0);
  const cv = $('image');
  cv.width = W * S.xs; cv.height = H * S.ys;
  const g = cv.getContext('2d');
  g.imageSmoothingEnabled = false;
  g.drawImage(off, 0, 0, cv.width, cv.height);
  drawTopDown();
  drawObjects();
  const rev = S.labels.reviewed;
  $('review-badge').textContent = rev ? 'reviewed' : 'not reviewed';
  $('review-badge').className = 'badge' + (rev ? ' ok' : '');
}

function drawTopDown() {
  const cv = $('topdown'), g = cv.getContext('2d'), d = S.data, W = S.cols, H = S.rows;
  g.fillStyle = '#000'; g.fillRect(0, 0, cv.width, cv.height);
  // Centred on the current object when it is in this sweep (8 m across), else on the sensor with
  // the 95th percentile of the horizontal distances at the edge.
  const cur = S.labels.objects.find((o) => o.id === S.current);
  const focus = S.cand && S.cand.size ? [...S.cand] : (cur ? cur.pixels : []);
  let ox = 0, oy = 0, R;
  if (focus.length) {
    for (const i of focus) { ox += d.x[i]; oy += d.y[i]; }
    ox /= focus.length; oy /= focus.length; R = 4;
  } else {
    const dist = [];
    for (let i = 0; i < W * H; i += 7) if (d.x[i] || d.y[i]) dist.push(Math.hypot(d.x[i], d.y[i]));
    dist.sort((a, b) => a - b);
    R = Math.max(5, dist.length ? dist[Math.floor(dist.length * 0.95)] : 20);
  }
  const s = cv.width / 2 / R, cx = cv.width / 2, cy = cv.height / 2;
  const owner = new Int32Array(W * H);
  for (const o of S.labels.objects) for (const i of o.pixels) owner[i] = o.id;
  const size = focus.length ? 3 : 1;
  const dot = (i, style, sz) => {
    g.fillStyle = style;  // +x up, +y left
    g.fillRect(cx - (d.y[i] - oy) * s - sz / 2, cy - (d.x[i] - ox) * s - sz / 2, sz, sz);
  };
  for (let i = 0; i < W * H; i++) {
    if (!(d.x[i] || d.y[i] || d.z[i]) || owner[i]) continue;
    dot(i, d.ground[i] ? '#2c4020' : '#8a8a8a', size);
  }
  for (let i = 0; i < W * H; i++) if (owner[i]) { const c = colour(owner[i]); dot(i, `rgb(${c})`, size + 2); }
  if (S.cand) for (const i of S.cand) dot(i, '#00e5ff', size + 2);
  const sx = cx + oy * s, sy = cy + ox * s;  // the sensor
  g.fillStyle = '#fff'; g.beginPath(); g.moveTo(sx, sy - 7); g.lineTo(sx - 4, sy + 4); g.lineTo(sx + 4, sy + 4); g.fill();
  g.fillStyle = '#999';
  g.fillText(focus.length ? `top view around the ${S.cand && S.cand.size ? 'candidate' : 'object ' + cur.id}, ${2 * R} m across, +x up` :
                   `top view, ${R.toFixed(0)} m to the edge, +x up`, 6, cv.height - 6);
}

function drawObjects() {
  const tb = $('objects').querySelector('tbody');
  tb.innerHTML = '';
  const here = new Map(S.labels.objects.map((o) => [o.id, o]));
  for (const info of (S.info ? S.info.objects : [])) {
    const o = here.get(info.id);
    const tr = document.createElement('tr');
    if (info.id === S.current) tr.className = 'current';
    const c = colour(info.id);
    tr.innerHTML = `<td><span class="sw" style="background:rgb(${c})"></span> ${info.id}</td>` +
      `<td>${escapeHtml(info.class)}${info.moving ? '' : ' (static)'}</td>` +
      `<td>${o ? o.pixels.length + ' px, ' + o.state : '–'}</td>`;
    tr.onclick = () => selectObject(info.id);
    tb.appendChild(tr);
  }
}

function escapeHtml(s) {
  return s.replace(/[&<>"]/g, (c) => ({'&': '&amp;', '<': '&lt;', '>': '&gt;', '"': '&quot;'}[c]));
}

function selectObject(id) {
  S.current = id;
  const info = S.info && S.info.objects.find((o) => o.id === id);
  if (info) { $('class').value = info.class; $('moving').checked = info.moving; }
  notice(id ? `current object: ${id}` : 'new object: Accept gives it an id');
  draw();
}

// ---- editing ------------------------------------------------------------------------------------
function pixelAt(ev) {
  const r = $('image').getBoundingClientRect();
  const col = Math.floor((ev.clientX - r.left) / S.xs), row = Math.floor((ev.clientY - r.top) / S.ys);
  if (row < 0 || row >= S.rows || col < 0 || col >= S.cols) return null;
  return {row, col};
}

function pushCandUndo() { S.undo.push({kind: 'cand', k: S.k, cand: S.cand ? new Set(S.cand) : null}); }

async function growAt(p, add) {
  const res = await api('/api/grow', {k: S.k, row: p.row, col: p.col, id: S.current || -1,
    distance: +$('distance').value, max_extent: +$('extent').value});
  pushCandUndo();
  if (!add || !S.cand) S.cand = new Set();
  for (const i of res.pixels) S.cand.add(i);
  notice(`grown: ${res.pixels.length} pixels from row ${p.row}, column ${p.col}` +
         ' — A accepts, brushes edit, Esc drops');
  draw();
}

function brushAt(p, add) {
  if (!S.cand) {
    const o = S.labels.objects.find((x) => x.id === S.current);
    S.cand = new Set(o ? o.pixels : []);
  }
  const b = Math.max(0, +$('brush').value | 0);
  for (let r = p.row - b; r <= p.row + b; r++) {
    if (r < 0 || r >= S.rows) continue;
    for (let c = p.col - b; c <= p.col + b; c++) {
      const i = r * S.cols + ((c + S.cols) % S.cols);
      if (!add) S.cand.delete(i);
      else if (S.data.x[i] || S.data.y[i] || S.data.z[i]) S.cand.add(i);  // only real returns
    }
  }
  draw();
}

async function accept() {
  if (!S.cand || S.cand.size === 0) { notice('nothing to accept: click an object first'); return; }
  const prev = S.labels.objects.find((o) => o.id === S.current);
  const res = await api('/api/object', {k: S.k, id: S.current, pixels: [...S.cand].sort((a, b) => a - b),
                                        class: $('class').value || 'object'});
  if (!S.current) {
    await api('/api/object-info', {id: res.id, class: $('class').value || 'object', moving: $('moving').checked});
  }
  S.undo.push({kind: 'object', k: S.k, id: res.id, pixels: prev ? prev.pixels : [],
               state: prev ? prev.state : 'confirmed'});
  S.current = res.id;
  S.cand = null;
  notice(`object ${res.id}: ${prev ? 'updated' : 'added'} in sweep ${S.k + 1}`);
  await reloadLabels();
}

async function undo() {
  const u = S.undo.pop();
  if (!u) { notice('nothing to undo'); return; }
  if (u.kind === 'cand') {
    if (u.k !== S.k) await loadSweep(u.k);
    S.cand = u.cand; draw(); notice('undone: candidate edit'); return;
  }
  await api('/api/object', {k: u.k, id: u.id, pixels: u.pixels, state: u.state});
  if (u.k !== S.k) await loadSweep(u.k); else await reloadLabels();
  await refreshInfo();
  notice(`undone: object ${u.id} in sweep ${u.k + 1}`);
}

async function removeObject() {
  const o = S.labels.objects.find((x) => x.id === S.current);
  if (!o) { notice('the current object has no label in this sweep'); return; }
  await api('/api/object', {k: S.k, id: o.id, pixels: []});
  S.undo.push({kind: 'object', k: S.k, id: o.id, pixels: o.pixels, state: o.state});
  await reloadLabels();
}

async function propagate(steps) {
  if (!S.current || !S.labels.objects.find((o) => o.id === S.current)) {
    notice('select an object labelled in this sweep first'); return;
  }
  if (S.k + 1 >= S.n) { notice('this is the last sweep'); return; }
  const res = await api('/api/propagate', {k: S.k, id: S.current, steps});
  const ok = res.steps.filter((s) => s.found);
  const last = res.steps[res.steps.length - 1];
  let text = `object ${S.current}: proposed in ${ok.length} sweep(s)`;
  if (ok.length) text += ` (${ok[0].to + 1}–${ok[ok.length - 1].to + 1}, ego-motion: ${ok[0].ego_motion})`;
  if (last && !last.found) text += `; not found in sweep ${last.to + 1} (occluded or gone?)`;
  notice(text + ' — check each and press Enter');
  await refreshInfo();
  if (ok.length) await loadSweep(S.k + 1); else draw();
}

async function review(reviewed) {
  const k = S.k;
  const res = await api('/api/review', {k, reviewed, propagate: reviewed && $('autoprop').checked});
  await refreshInfo();
  if (reviewed && k + 1 < S.n) {
    const lost = res.propagated.filter((p) => !p.found).map((p) => p.id);
    notice(`sweep ${k + 1} reviewed` + (lost.length ? `; not found in the next sweep: ${lost.join(', ')}` : ''));
    await loadSweep(k + 1);
  } else {
    notice(`sweep ${k + 1} ${reviewed ? 'reviewed' : 'marked not reviewed'}`);
    await reloadLabels();
  }
}

async function save() {
  try {
    const res = await api('/api/save', {});
    notice('saved: ' + res.files.join(', '));
  } finally { await refreshInfo(); }
}

async function newObject() {
  S.current = 0; S.cand = null;
  notice('new object: click it, then Accept');
  draw();
}

async function updateObjectInfo() {
  if (!S.current) return;
  await api('/api/object-info', {id: S.current, class: $('class').value || 'object', moving: $('moving').checked});
  await refreshInfo(); draw();
}

function cycleObject(d) {
  const ids = (S.info ? S.info.objects : []).map((o) => o.id);
  if (!ids.length) return;
  const i = ids.indexOf(S.current);
  selectObject(ids[(i + d + ids.length) % ids.length]);
}

// ---- wiring -------------------------------------------------------------------------------------
function wire() {
  const cv = $('image');
  cv.addEventListener('mousedown', (ev) => guarded(async () => {
    const p = pixelAt(ev);
    if (!p) return;
    if (S.tool === 'grow') { await growAt(p, ev.shiftKey); return; }
    pushCandUndo(); S.painting = true; brushAt(p, S.tool === 'add');
  }));
  cv.addEventListener('mousemove', (ev) => {
    const p = pixelAt(ev);
    if (!p || !S.data) return;
    const i = p.row * S.cols + p.col, d = S.data;
    const rng = Math.hypot(d.x[i], d.y[i], d.z[i]);
    const owner = S.labels.objects.find((o) => o.pixels.includes(i));
    $('hover').textContent = `row ${p.row}, column ${p.col}: ` +
      (rng > 0 ? `range ${rng.toFixed(2)} m, z ${d.z[i].toFixed(2)} m${d.ground[i] ? ', ground' : ''}` : 'no return') +
      (owner ? `, object ${owner.id} (${owner.state})` : '');
    if (S.painting) brushAt(p, S.tool === 'add');
  });
  window.addEventListener('mouseup', () => { S.painting = false; });
  $('sweep').addEventListener('input', () => guarded(() => loadSweep(+$('sweep').value)));
  $('prev').onclick = () => guarded(() => loadSweep(S.k - 1));
  $('next').onclick = () => guarded(() => loadSweep(S.k + 1));
  for (const r of document.querySelectorAll('input[name=tool]')) r.onchange = () => { S.tool = r.value; };
  const showVal = () => {
    $('distance-value').textContent = (+$('distance').value).toFixed(2);
    $('extent-value').textContent = (+$('extent').value).toFixed(1);
  };
  $('distance').oninput = showVal; $('extent').oninput = showVal;
  $('accept').onclick = () => guarded(accept);
  $('cancel').onclick = () => { S.cand = null; draw(); };
  $('undo').onclick = () => guarded(undo);
  $('delete').onclick = () => guarded(removeObject);
  $('propagate').onclick = () => guarded(() => propagate(1));
  $('propagate10').onclick = () => guarded(() => propagate(10));
  $('review').onclick = () => guarded(() => review(true));
  $('unreview').onclick = () => guarded(() => review(false));
  $('save').onclick = () => guarded(save);
  $('new-object').onclick = () => guarded(newObject);
  $('class').onchange = () => guarded(updateObjectInfo);
  $('moving').onchange = () => guarded(updateObjectInfo);
  $('error-close').onclick = () => { $('error').hidden = true; };
  const setTool = (t) => { S.tool = t; document.querySelector(`input[name=tool][value=${t}]`).checked = true; };
  document.addEventListener('keydown', (ev) => {
    if (ev.target.tagName === 'INPUT' && ev.target.type === 'text') return;
    const k = ev.key;
    const act = {
      ArrowLeft: () => loadSweep(S.k - 1), ArrowRight: () => loadSweep(S.k + 1),
      a: accept, Escape: async () => { S.cand = null; draw(); }, z: undo, Delete: removeObject,
      p: () => propagate(1), Enter: () => review(true), u: () => review(false), s: save,
      n: newObject, '[': async () => cycleObject(-1), ']': async () => cycleObject(1),
      g: async () => setTool('grow'), b: async () => setTool('add'), e: async () => setTool('erase'),
    }[k.length === 1 ? k.toLowerCase() : k];
    if (!act || ev.altKey || (ev.ctrlKey && k !== 'z' && k !== 's')) return;
    ev.preventDefault();
    guarded(act);
  });
  // Leaving the page: ask the server to save now (it also saves every few seconds by itself).
  window.addEventListener('pagehide', () =>
    navigator.sendBeacon('/api/save', new Blob(['{}'], {type: 'application/json'})));
  window.addEventListener('beforeunload', (ev) => { if (S.cand && S.cand.size) { ev.preventDefault(); ev.returnValue = ''; } });
  showVal();
}

async function start() {
  wire();
  await refreshInfo();
  S.n = S.info.sweeps; S.rows = S.info.rows; S.cols = S.info.cols;
  $('n').textContent = S.n;
  $('file').textContent = S.info.input + ' → ' + S.info.output + '.labels';
  $('sweep').max = S.n - 1;
  $('distance').value = S.info.distance; $('extent').value = S.info.max_extent;
  // Columns: at least 1 px, as wide as the window allows; rows stretched so the image is readable.
  S.xs = Math.max(1, Math.floor((window.innerWidth - 40) / S.cols));
  S.ys = Math.max(S.xs, Math.round(320 / S.rows));
  const m = /k=(\d+)/.exec(location.hash);
  await loadSweep(m ? +m[1] : 0);
  setInterval(() => guarded(refreshInfo), 3000);
  document.body.dataset.ready = '1';
}

guarded(start);

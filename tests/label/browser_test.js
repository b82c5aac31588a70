// SPDX-License-Identifier: BSD-3-Clause
// Drives dynobj-label's real page in headless Chromium through the DevTools protocol (over
// --remote-debugging-pipe: Node's own modules only, no npm package) on the committed sample:
// opens a sweep, clicks on a walking person, accepts the grown region, propagates it over 10
// sweeps, reviews them, saves; then compares the saved labels with the sample's ground truth for
// that person (IoU >= 0.8 per sweep) and has dynobj-eval read the file.
// Usage: node browser_test.js --bin <build/apps> --sample <rawlogs/hall-small/hall-small>
//          --work <dir> --object <gt id> --sweep <first sweep> [--screenshots <dir>]
//          [--chromium <browser binary, default chromium>]
'use strict';
const {spawn, spawnSync} = require('child_process');
const fs = require('fs');
const path = require('path');

const args = {};
for (let i = 2; i < process.argv.length; i += 2) args[process.argv[i].replace(/^--/, '')] = process.argv[i + 1];
for (const k of ['bin', 'sample', 'work', 'object', 'sweep'])
  if (!args[k]) { console.error(`missing --${k}`); process.exit(2); }
const OBJECT = +args.object, K0 = +args.sweep, STEPS = 10;
const shots = args.screenshots || args.work;
fs.mkdirSync(args.work, {recursive: true});
fs.mkdirSync(shots, {recursive: true});
const base = path.join(args.work, 'hall-small.person');
const children = [];
// Chromium runs in a process group of its own: its zygote and renderer processes outlive the
// browser process for a moment and write into the profile, so stopBrowser() kills the whole group
// and waits until none of it runs before it removes the profile (at the end and on failure).
const browser = {pgid: 0, profile: null};
function browserRunning() {
  for (const pid of fs.readdirSync('/proc').filter((p) => /^\d+$/.test(p))) {
    let stat;
    try { stat = fs.readFileSync(`/proc/${pid}/stat`, 'utf8'); } catch (e) { continue; }  // gone
    const [state, , pgrp] = stat.slice(stat.lastIndexOf(')') + 2).split(' ');
    if (+pgrp === browser.pgid && state !== 'Z') return true;
  }
  return false;
}
function stopBrowser() {
  if (browser.pgid) {
    try { process.kill(-browser.pgid, 'SIGKILL'); } catch (e) { /* gone */ }
    const t0 = Date.now(), tick = new Int32Array(new SharedArrayBuffer(4));
    while (browserRunning()) {
      if (Date.now() - t0 > 10000) { console.error(`Chromium (process group ${browser.pgid}) still runs 10 s after SIGKILL`); break; }
      Atomics.wait(tick, 0, 0, 20);
    }
    browser.pgid = 0;
  }
  if (browser.profile) fs.rmSync(browser.profile, {recursive: true, force: true});
  browser.profile = null;
}
function fail(msg) {
  console.error('FAIL: ' + msg);
  for (const c of children) try { c.kill('SIGKILL'); } catch (e) { /* gone */ }
  stopBrowser();
  process.exit(1);
}
const sleep = (ms) => new Promise((r) => setTimeout(r, ms));

// ---- label files ----------------------------------------------------------------------------------
function readLabels(file) {
  const lines = fs.readFileSync(file, 'utf8').split('\n').filter((l) => l.length);
  const head = /rows=(\d+) cols=(\d+)/.exec(lines[0]);
  let reviewed = null;
  const sweeps = [];
  for (const l of lines.slice(1)) {
    if (l.startsWith('# reviewed ')) { reviewed = l.slice(11); continue; }
    const t = l.split(' ');
    const px = t.slice(2).map((e) => { const [i, id] = e.split(':'); return {i: +i, id: id === undefined ? 0 : +id}; });
    sweeps.push({ts: t[0], px});
  }
  return {rows: +head[1], cols: +head[2], sweeps, reviewed};
}

// ---- the DevTools protocol over a pipe -------------------------------------------------------------
class Cdp {
  constructor(proc) {
    this.proc = proc; this.id = 0; this.pending = new Map(); this.buf = '';
    proc.stdio[4].on('data', (d) => {
      this.buf += d.toString('utf8');
      let z;
      while ((z = this.buf.indexOf('\0')) >= 0) {
        const msg = JSON.parse(this.buf.slice(0, z));
        this.buf = this.buf.slice(z + 1);
        const p = this.pending.get(msg.id);
        if (p) { this.pending.delete(msg.id); msg.error ? p.reject(new Error(JSON.stringify(msg.error))) : p.resolve(msg.result); }
      }
    });
  }
  send(method, params = {}, sessionId) {
    const id = ++this.id;
    const msg = {id, method, params};
    if (sessionId) msg.sessionId = sessionId;
    this.proc.stdio[3].write(JSON.stringify(msg) + '\0');
    return new Promise((resolve, reject) => this.pending.set(id, {resolve, reject}));
  }
}

async function main() {
  const truth = readLabels(args.sample + '.gt.instances');
  const objectPixels = (k) => truth.sweeps[k].px.filter((p) => p.id === OBJECT).map((p) => p.i);
  const W = truth.cols;
  const first = objectPixels(K0);
  if (first.length < 5) fail(`ground-truth object ${OBJECT} has ${first.length} pixels in sweep ${K0}`);
  // Click the person's pixel nearest its median row / column (where a person would click).
  const rs = first.map((i) => Math.floor(i / W)).sort((a, b) => a - b), cs = first.map((i) => i % W).sort((a, b) => a - b);
  const mr = rs[rs.length >> 1], mc = cs[cs.length >> 1];
  const click = first.reduce((b, i) => {
    const d = (Math.floor(i / W) - mr) ** 2 + (i % W - mc) ** 2;
    return d < b.d ? {i, d} : b;
  }, {i: -1, d: 1e9}).i;

  // ---- dynobj-label ----
  const app = spawn(path.join(args.bin, 'dynobj-label'),
                    ['-i', args.sample + '.rawlog', '-o', base, '--port', '0', '-w'],
                    {stdio: ['ignore', 'pipe', 'inherit']});
  children.push(app);
  const url = await new Promise((resolve, reject) => {
    let out = '';
    app.stdout.on('data', (d) => { out += d; const m = /(http:\/\/127\.0\.0\.1:\d+\/)/.exec(out); if (m) resolve(m[1]); });
    app.on('exit', (c) => reject(new Error('dynobj-label exited with ' + c)));
    setTimeout(() => reject(new Error('dynobj-label did not start within 120 s')), 120000);
  }).catch((e) => fail(e.message));
  console.log('dynobj-label serves ' + url);

  // ---- Chromium ----
  // Under /tmp, not TMPDIR (build/tests/tmp in scripts/test.sh): Chromium puts its SingletonSocket
  // in <TMPDIR>/org.chromium.Chromium.XXXXXX/, and a Unix socket path has at most 107 characters,
  // which a checkout a little deeper than usual exceeds (Chromium then exits at once). The name
  // starts with dynobj so that scripts/test.sh reports it if it is left behind.
  browser.profile = fs.mkdtempSync('/tmp/dynobj-chromium-');
  const chromium = args.chromium || 'chromium';
  const chrome = spawn(chromium,
    ['--headless', '--no-sandbox', '--disable-gpu', '--remote-debugging-pipe', '--no-first-run',
     '--disable-background-networking', '--disable-component-update', '--disable-sync',
     '--user-data-dir=' + browser.profile, 'about:blank'],
    // Chromium's own temporary files go into the profile, removed at the end.
    {stdio: ['ignore', 'ignore', 'pipe', 'pipe', 'pipe'], env: {...process.env, TMPDIR: browser.profile},
     detached: true});
  browser.pgid = chrome.pid || 0;
  // Chromium gone before the test is done (it does not start, crashes, is killed): fail at once,
  // with the end of its stderr, rather than wait for DevTools answers that never come.
  let chromeErr = '';
  chrome.stderr.on('data', (d) => { chromeErr = (chromeErr + d).slice(-8000); });
  const chromeGone = (what) => {
    const report = () => {
      const tail = chromeErr.trim().split('\n').slice(-8).join('\n');
      fail(`${chromium} ${what} before the test was done` + (tail ? '; the end of its output:\n' + tail : ' (no output)'));
    };
    if (chrome.stderr.readableEnded) return report();
    chrome.stderr.once('end', report);  // all of its output, or what came within 1 s
    setTimeout(report, 1000);
  };
  chrome.on('error', (e) => fail(`cannot start ${chromium}: ${e.message}`));
  const onChromeExit = (code, signal) => chromeGone(signal ? `was killed by ${signal}` : `exited with ${code}`);
  chrome.on('exit', onChromeExit);
  // A broken pipe means Chromium is exiting: its exit status, reported above, says more.
  for (const fd of [3, 4])
    chrome.stdio[fd].on('error', (e) => setTimeout(() => chromeGone(`closed its DevTools pipe (${e.message})`), 2000));
  const cdp = new Cdp(chrome);
  const {targetInfos} = await cdp.send('Target.getTargets');
  const page = targetInfos.find((t) => t.type === 'page');
  if (!page) fail('Chromium has no page');
  const {sessionId} = await cdp.send('Target.attachToTarget', {targetId: page.targetId, flatten: true});
  const cmd = (m, p) => cdp.send(m, p, sessionId);
  const evaluate = async (expr) => {
    const r = await cmd('Runtime.evaluate', {expression: expr, returnByValue: true, awaitPromise: true});
    if (r.exceptionDetails) throw new Error(expr + ': ' + JSON.stringify(r.exceptionDetails));
    return r.result.value;
  };
  const waitFor = async (expr, what, ms = 60000) => {
    const t0 = Date.now();
    for (;;) {
      const err = await evaluate("(() => { const e = document.getElementById('error'); return e && !e.hidden ? document.getElementById('error-text').textContent : ''; })()");
      if (err) fail(`the page shows an error while waiting for ${what}: ${err}`);
      if (await evaluate(`(() => { try { return !!(${expr}); } catch (e) { return false; } })()`)) return;  // the page may be (re)loading
      if (Date.now() - t0 > ms) {  // what the page showed, to tell a lost click from a slow server
        const state = await evaluate(`(() => 'sweep ' + (Number(document.body.dataset.k) + 1) + ', busy ' + document.body.dataset.busy +
          ', notice "' + document.getElementById('notice').textContent + '"')()`);
        fail(`timed out waiting for ${what} (the page: ${state})`);
      }
      await sleep(50);
    }
  };
  const idle = (k) => waitFor(`document.body.dataset.busy === '0'` + (k === undefined ? '' : ` && document.body.dataset.k === '${k}'`),
                              k === undefined ? 'the page' : `sweep ${k + 1}`);
  const key = async (keyName, code, vk, text) => {
    await cmd('Input.dispatchKeyEvent', {type: 'keyDown', key: keyName, code, windowsVirtualKeyCode: vk, text});
    await cmd('Input.dispatchKeyEvent', {type: 'keyUp', key: keyName, code, windowsVirtualKeyCode: vk});
  };
  const mouseClick = async (x, y) => {
    for (const type of ['mousePressed', 'mouseReleased'])
      await cmd('Input.dispatchMouseEvent', {type, x, y, button: 'left', clickCount: 1});
  };
  // Clicks the middle of an element once it is enabled, topmost there and has kept its place for
  // one poll (a notice shown a moment earlier may still move it: a click read before the move
  // lands beside the button, and nothing happens).
  const clickElement = async (id) => {
    let last = '';
    const t0 = Date.now();
    for (;;) {
      const r = await evaluate(`(() => { const e = document.getElementById('${id}'); const b = e.getBoundingClientRect();
        const x = b.left + b.width / 2, y = b.top + b.height / 2;
        const top = document.elementFromPoint(x, y);
        return [x, y, !e.disabled && (top === e || e.contains(top))]; })()`);
      const here = `${r[0]},${r[1]}`;
      if (r[2] && here === last) {
        await mouseClick(r[0], r[1]);
        return;
      }
      if (Date.now() - t0 > 10000) fail(`the button '${id}' was not clickable within 10 s`);
      last = here;
      await sleep(50);
    }
  };
  const screenshot = async (name) => {
    const {data} = await cmd('Page.captureScreenshot', {format: 'png'});
    fs.writeFileSync(path.join(shots, name), Buffer.from(data, 'base64'));
    console.log('screenshot ' + path.join(shots, name));
  };

  await cmd('Page.enable');
  await cmd('Emulation.setDeviceMetricsOverride', {width: 1640, height: 1000, deviceScaleFactor: 1, mobile: false});
  await cmd('Page.navigate', {url: url + '#k=' + K0});
  await waitFor(`document.body.dataset.ready === '1'`, 'the page to load');
  await idle(K0);

  // Click on the person.
  const row = Math.floor(click / W), col = click % W;
  const pos = await evaluate(`(() => { const b = document.getElementById('image').getBoundingClientRect();
    const S = window.dynobjLabel; return [b.left + (${col} + 0.5) * S.xs, b.top + (${row} + 0.5) * S.ys]; })()`);
  await mouseClick(pos[0], pos[1]);
  await waitFor(`window.dynobjLabel.cand !== null && document.body.dataset.busy === '0'`, 'the grown region');
  const grown = await evaluate('window.dynobjLabel.cand.size');
  console.log(`clicked row ${row}, column ${col} of sweep ${K0 + 1}: grown ${grown} pixels (truth ${first.length})`);
  await screenshot('label-grown.png');

  await key('a', 'KeyA', 65, 'a');  // accept
  await waitFor(`window.dynobjLabel.current > 0 && window.dynobjLabel.cand === null && document.body.dataset.busy === '0'`, 'the accepted object');
  const id = await evaluate('window.dynobjLabel.current');
  await clickElement('propagate10');
  await idle(K0 + 1);
  console.log('propagated: ' + await evaluate(`document.getElementById('notice').textContent`));
  await screenshot('label-propagated.png');

  // Reloading the page loses nothing: the labels live in dynobj-label.
  await cmd('Page.reload');
  await waitFor(`document.body.dataset.ready === '1'`, 'the reloaded page');
  await idle(K0 + 1);
  const after = await evaluate(`window.dynobjLabel.labels.objects.map((o) => o.id + ':' + o.state).join(',')`);
  if (after !== `${id}:proposed`) fail(`after a reload sweep ${K0 + 2} holds '${after}', expected '${id}:proposed'`);
  await key(']', 'BracketRight', 221, ']');  // select the object again (the page forgot it)
  await waitFor(`window.dynobjLabel.current === ${id}`, 'the object selected');

  // Review sweep K0 .. K0 + 10: back to the first, then Enter on each (the page moves on).
  await key('ArrowLeft', 'ArrowLeft', 37);
  await idle(K0);
  for (let k = K0; k <= K0 + STEPS; k++) {
    await key('Enter', 'Enter', 13, '\r');
    if (k + 1 < truth.sweeps.length) await idle(k + 1);
    else await waitFor(`document.body.dataset.busy === '0' && window.dynobjLabel.labels.reviewed`, 'the last sweep reviewed');
    if (k === K0 + 5) await screenshot('label-review.png');
  }
  await key('s', 'KeyS', 83, 's');
  await waitFor(`document.getElementById('notice').textContent.startsWith('saved')`, 'the save');
  await idle();
  await screenshot('label-saved.png');
  chrome.removeListener('exit', onChromeExit);
  stopBrowser();
  app.kill('SIGINT');
  const code = await new Promise((r) => app.on('exit', r));
  if (code !== 0) fail('dynobj-label exited with ' + code);

  // Started again on the same output, it resumes the session.
  const again = spawn(path.join(args.bin, 'dynobj-label'), ['-i', args.sample + '.rawlog', '-o', base, '--port', '0'],
                      {stdio: ['ignore', 'pipe', 'pipe']});
  children.push(again);
  let againErr = '';
  again.stderr.on('data', (d) => { againErr += d; });
  const url2 = await new Promise((resolve) => {
    let out = '';
    again.stdout.on('data', (d) => { out += d; const m = /(http:\/\/127\.0\.0\.1:\d+\/)/.exec(out); if (m) resolve(m[1]); });
    again.on('exit', () => resolve(null));
  });
  if (!url2) fail('dynobj-label did not start again: ' + againErr);
  const info = await fetch(url2 + 'api/info').then((r) => r.json());
  again.kill('SIGINT');
  await new Promise((r) => again.on('exit', r));
  if (info.reviewed !== STEPS + 1) fail(`resumed session has ${info.reviewed} reviewed sweeps, expected ${STEPS + 1}`);
  console.log('resumed: ' + againErr.split('\n').find((l) => l.includes('resumed')));

  // ---- the saved labels against the ground truth ----
  const saved = readLabels(base + '.instances');
  if (saved.rows !== truth.rows || saved.cols !== truth.cols) fail('saved labels have another size');
  if (saved.reviewed !== `${K0}-${K0 + STEPS}`) fail(`saved '# reviewed ${saved.reviewed}', expected ${K0}-${K0 + STEPS}`);
  let worst = 1;
  console.log('sweep  saved  truth  IoU');
  for (let k = K0; k <= K0 + STEPS; k++) {
    const a = new Set(saved.sweeps[k].px.filter((p) => p.id === id).map((p) => p.i));
    const b = new Set(objectPixels(k));
    let inter = 0;
    for (const i of a) if (b.has(i)) inter++;
    const iou = inter / (a.size + b.size - inter);
    worst = Math.min(worst, iou);
    console.log(`${String(k).padStart(5)}  ${String(a.size).padStart(5)}  ${String(b.size).padStart(5)}  ${iou.toFixed(3)}`);
  }
  console.log(`worst IoU over ${STEPS + 1} sweeps: ${worst.toFixed(3)}`);
  if (!(worst >= 0.8)) fail('IoU below 0.8');

  // ---- dynobj-eval reads the file: refuses the unreviewed sweeps unless asked ----
  const det = path.join(args.work, 'detect.labels');
  const d = spawnSync(path.join(args.bin, 'dynobj-detect'), ['-i', args.sample + '.rawlog', '-o', det, '-w'], {encoding: 'utf8'});
  if (d.status !== 0) fail('dynobj-detect failed: ' + d.stderr);
  const evalArgs = ['--gt', base + '.labels', '--pred', det, '-o', path.join(args.work, 'eval'), '-w'];
  const refused = spawnSync(path.join(args.bin, 'dynobj-eval'), evalArgs, {encoding: 'utf8'});
  if (refused.status === 0 || !/not reviewed/.test(refused.stderr)) fail('dynobj-eval accepted unreviewed sweeps: ' + refused.stderr);
  console.log('dynobj-eval without --unreviewed: ' + refused.stderr.trim());
  const ok = spawnSync(path.join(args.bin, 'dynobj-eval'), evalArgs.concat(['--unreviewed', 'skip', '-q']), {encoding: 'utf8'});
  if (ok.status !== 0) fail('dynobj-eval --unreviewed skip failed: ' + ok.stderr);
  const summary = JSON.parse(fs.readFileSync(path.join(args.work, 'eval', 'summary.json'), 'utf8'));
  if (summary.runs[0].sweeps !== STEPS + 1) fail(`dynobj-eval scored ${summary.runs[0].sweeps} sweeps, expected ${STEPS + 1}`);
  console.log(ok.stdout.trim());
  console.log(`browser test passed: object ${id}, ${STEPS + 1} sweeps, worst IoU ${worst.toFixed(3)}`);
  process.exit(0);
}

main().catch((e) => fail(e.stack || String(e)));

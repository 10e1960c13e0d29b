// What every browser suite shares: the tiny test runner, the console and request watch,
// and the page helpers (open, idle, statistics, canvas hashes, screenshots, clicks).
import { mkdirSync, existsSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import path from 'node:path';
import { ROOT, WWW } from './serve.mjs';

export const OUT = path.join(ROOT, 'test-output', 'browser');
export const BAD = path.join(ROOT, 'tests', 'data', 'bad');
export const DATA = path.join(ROOT, 'tests', 'data');
export const HARDENING = path.join(DATA, 'hardening');
export const TIMEOUT = 60_000;
/** Mesquite's meshes, read in place beside the repository (not copied into it): absent on
 * a developer's machine their test says so and passes; absent under CI=true it fails. */
export const MESQUITE = path.join(ROOT, '..', 'shared', 'meshes', 'mesquite');
export const CI = Boolean(process.env.CI) && !['false', '0'].includes(process.env.CI);

mkdirSync(OUT, { recursive: true });
if (!existsSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'))) {
  console.error('www/pkg/smoothlab_bg.wasm is missing: run `make site` first');
  process.exit(1);
}

// ---- a tiny test runner ---------------------------------------------------------------
export const results = [];
/** ONLY=regex runs the tests whose names match (and the last, which checks the console). */
export const ONLY = process.env.ONLY ? new RegExp(process.env.ONLY) : null;
export async function test(name, fn) {
  if (ONLY && !ONLY.test(name) && !/^no request left/.test(name)) return;
  const t0 = Date.now();
  try {
    await fn();
    results.push({ name, ok: true });
    console.log(`ok   ${name} (${Date.now() - t0} ms)`);
  } catch (e) {
    results.push({ name, ok: false, error: e });
    console.log(`FAIL ${name}\n     ${String(e && e.stack ? e.stack : e).split('\n').slice(0, process.env.ONLY ? 30 : 4).join('\n     ')}`);
  }
}
export function check(cond, msg) {
  if (!cond) throw new Error(msg);
}

// ---- page helpers ---------------------------------------------------------------------
export const externalRequests = [];
export const consoleErrors = [];
/** Substrings of console errors a test provokes on purpose (set with allowErrors). */
let allowedErrors = [];
export function allowErrors(list) {
  allowedErrors = list;
}

export function watch(page, label) {
  page.on('request', (req) => {
    const u = new URL(req.url());
    if (!['data:', 'blob:', 'file:'].includes(u.protocol) && u.hostname !== '127.0.0.1') externalRequests.push(req.url());
  });
  page.on('console', (msg) => {
    if (msg.type() === 'error' && !allowedErrors.some((a) => msg.text().includes(a))) consoleErrors.push(`${label}: ${msg.text()}`);
  });
  page.on('pageerror', (err) => consoleErrors.push(`${label}: uncaught ${err.message}`));
  page.on('worker', (w) => {
    w.on('console', (msg) => {
      if (msg.type() === 'error' && !allowedErrors.some((a) => msg.text().includes(a))) consoleErrors.push(`${label} worker: ${msg.text()}`);
    });
  });
}

/** Opens the side column's folded disclosures (Compare, Perturb) as a user would, by
 * their summaries, so their controls can be used. */
export async function unfold(page) {
  for (const id of ['compare-box', 'perturb-box']) {
    if (await page.evaluate((id) => !document.getElementById(id).open, id)) await page.click(`#${id} > summary`);
  }
}
export async function idle(page) {
  await page.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
}
/** Opens `url` and waits until the page has opened its address: a URL that differs only
 * in its hash reloads nothing, and the page handles the hash after `goto` returns. */
export async function open(page, url) {
  await page.goto(url);
  await page.waitForFunction(() => document.body.dataset.hash === location.hash, null, { timeout: TIMEOUT });
  await idle(page);
}
export async function stats(page, side) {
  return page.evaluate((side) => {
    const out = {};
    for (const tr of document.querySelectorAll(`#stats-${side} tr`)) out[tr.dataset.stat] = tr.querySelector('td').textContent;
    return out;
  }, side);
}
/** Distinct colours and a hash of a canvas's pixels. */
export async function canvasInfo(page, id) {
  return page.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    const colours = new Set();
    let h = 2166136261;
    for (let i = 0; i < d.length; i += 4) {
      const v = (d[i] << 24) | (d[i + 1] << 16) | (d[i + 2] << 8) | d[i + 3];
      colours.add(v);
      h = Math.imul(h ^ v, 16777619);
    }
    return { colours: colours.size, hash: h >>> 0, w: c.width, h: c.height };
  }, id);
}
export async function shot(page, name, fullPage = true) {
  await page.screenshot({ path: path.join(OUT, `${name}.png`), fullPage });
}
export async function chooseSample(page, value) {
  await page.selectOption('#sample', value);
  await page.waitForFunction((v) => document.getElementById('sample').value === v && document.body.dataset.busy === '0', value, { timeout: TIMEOUT });
  await idle(page);
}
/** Clicks near points of the mesh canvas until a node is chosen (as a user aims at a node). */
export async function clickSomeNode(page, canvasId, fractions) {
  await page.locator(`#${canvasId}`).scrollIntoViewIfNeeded();
  const box = await page.locator(`#${canvasId}`).boundingBox();
  for (const [fx, fy] of fractions) {
    await page.mouse.click(box.x + fx * box.width, box.y + fy * box.height);
    await idle(page);
    const v = await page.inputValue('#node');
    if (v !== '') return { node: Number(v), x: box.x + fx * box.width, y: box.y + fy * box.height };
  }
  throw new Error('no click near the mesh chose a node');
}
export function ringPoints() {
  // points in the plate's ring between the hole (r = 0.4) and the square (half-width 1)
  const pts = [];
  for (let k = 0; k < 24; k++) {
    const a = (k / 24) * 2 * Math.PI;
    for (const r of [0.36, 0.3]) pts.push([0.5 + r * Math.cos(a), 0.5 + r * Math.sin(a)]);
  }
  return pts;
}

/** A new page of `context` at width × height, watched (console errors, requests) as `label`. */
export async function freshPage(context, width, height, label) {
  const p = await context.newPage();
  await p.setViewportSize({ width, height });
  p.setDefaultTimeout(TIMEOUT);
  watch(p, label);
  return p;
}

/** Puts `src` (an http URL of the site) in page `p` as an iframe of w × h, as a course page,
 * a sidebar or a slide holds it, optionally under `transform: scale(scale)`; returns the
 * frame once the page inside is ready (and has opened its figure, when `figure`). */
export async function hostFrame(p, src, w, h, { scale = 1, figure = false, timeout = TIMEOUT } = {}) {
  await p.setContent(`<!doctype html><body style="margin:0">
    <div id="wrap" style="transform: scale(${scale}); transform-origin: 0 0; width: ${w}px">
    <iframe id="f" src="${src}" style="width:${w}px;height:${h}px;border:0"></iframe></div></body>`);
  const frame = await (await p.$('#f')).contentFrame();
  await frame.waitForFunction((figure) => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' && (!figure || Boolean(document.body.dataset.figure)), figure, { timeout });
  return frame;
}

/** How far the visible content of `where` (a page or a frame) reaches right (`r`) and down
 * (`b`), its window's size (`vw`, `vh`) and its document's scroll size (`sw`, `sh`). */
export function reach(where) {
  return where.evaluate(() => {
    let r = 0;
    let b = 0;
    for (const el of document.body.querySelectorAll('*')) {
      if (el.getClientRects().length === 0) continue;
      const q = el.getBoundingClientRect();
      if (q.width === 0 || q.height === 0) continue;
      r = Math.max(r, q.right);
      b = Math.max(b, q.bottom);
    }
    const d = document.documentElement;
    return { r, b, vw: window.innerWidth, vh: window.innerHeight, sw: d.scrollWidth, sh: d.scrollHeight };
  });
}

/** Runs the command-line tool of this checkout, `smoothlab ARGS` (built by cargo as needed). */
export const cli = (args) => spawnSync('cargo', ['run', '--quiet', '--bin', 'smoothlab', '--', ...args], { cwd: ROOT, encoding: 'utf8' });

/** The node lines of a .msh 2.2 text: `[x, y, z]` of each node, as numbers. */
export function mshNodes(text) {
  return text.split('$Nodes')[1].split('$EndNodes')[0].trim().split('\n').slice(1)
    .map((l) => l.trim().split(/\s+/).slice(1).map(Number));
}

/** Clicks Step and waits for the pass to be done and the page idle. */
export async function step(p) {
  await p.click('#step');
  await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
  await idle(p);
}

// The playground page at scale, measured in headless Chromium (Debian's) as a user uses
// it, for the "In the page" section of docs/performance.md (`make performance`):
//  0. the first visit: from the navigation to the first mesh drawn (the page opens on a
//     sample generated in wasm), in fresh pages, and when the engine (worker + wasm) was ready;
//  1. the 100k-node sample: its load, then "Step" (one pass on both sides and the redraw
//     of both meshes and tables) for the page's default settings, laplace and smart —
//     the time from the click to the redrawn meshes, and where it went (the page's own
//     measurements, window.smoothlab.metrics);
//  2. the 1M-node sample: its load, "Run" of 3 passes (time per pass, progress updates
//     during each pass), "Stop" during a pass (how long until the page is idle again),
//     the longest gap between animation frames and the lateness of a 50 ms interval on
//     the main thread all along, and the wasm memory; then, with the page's default
//     settings (rules, priority order), Stop right after a click (while the smoother
//     orders the nodes, in slices) and one whole Step (about a minute).
// Prints JSON on stdout. A benchmark, not a test: slow (minutes), not part of `make test`.
//   node tests/browser/page_bench.mjs [--reps 3] [--million-strategy smart] [--no-million] [--no-million-default]
//     [--startup-only] [--default-only] (only the first visit; only the default settings at 100k)
// Needs www/pkg from `make site` and playwright-core in tests/browser/node_modules.
import { existsSync, readFileSync } from 'node:fs';
import { gzipSync } from 'node:zlib';
import os from 'node:os';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { WWW, CHROMIUM, CHROMIUM_ARGS as ARGS, startServer } from './serve.mjs';

function arg(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 && process.argv[i + 1] ? process.argv[i + 1] : fallback;
}
const reps = Math.max(1, Number(arg('reps', '3')));
const millionStrategy = arg('million-strategy', 'smart');
const skipMillion = process.argv.includes('--no-million');
const skipMillionDefault = process.argv.includes('--no-million-default');
const startupOnly = process.argv.includes('--startup-only');
const defaultOnly = process.argv.includes('--default-only');
const log = (s) => process.stderr.write(`page bench: ${s}\n`);

if (!existsSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'))) {
  console.error('page bench: www/pkg/smoothlab_bg.wasm is missing: run `make site` first');
  process.exit(1);
}

const HOUR = 60 * 60_000;

async function idle(page, timeout = 10 * 60_000) {
  await page.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' &&
    document.getElementById('run').textContent === 'Run', null, { timeout, polling: 50 });
}

/** Starts watching the main thread: gaps between animation frames and how late a
 * 50 ms interval fires. */
async function watchMainThread(page) {
  await page.evaluate(() => {
    const w = { gaps: [], late: [], on: true };
    let last = performance.now();
    const f = (t) => {
      w.gaps.push(t - last);
      last = t;
      if (w.on) requestAnimationFrame(f);
    };
    requestAnimationFrame(f);
    let due = performance.now() + 50;
    w.timer = setInterval(() => {
      const t = performance.now();
      w.late.push(t - due);
      due = t + 50;
    }, 50);
    window.mainThreadWatch = w;
  });
}
async function stopWatching(page) {
  return page.evaluate(() => {
    const w = window.mainThreadWatch;
    w.on = false;
    clearInterval(w.timer);
    const max = (v) => (v.length ? Math.max(...v) : 0);
    return { longest_frame_gap_ms: max(w.gaps), frames: w.gaps.length, worst_interval_lateness_ms: max(w.late) };
  });
}

async function choose(page, value) {
  await page.selectOption('#sample', value);
  await page.waitForFunction((v) => document.getElementById('sample').value === v, value, { timeout: HOUR });
  await idle(page, HOUR);
}

async function setControls(page, strategy, order) {
  await page.selectOption('#strategy', strategy);
  await page.selectOption('#order', order);
  await idle(page);
}

function median(v) {
  const s = [...v].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}
/** The median of each numeric field (and of each element of numeric arrays) over runs. */
function medianOf(runs) {
  const out = {};
  for (const k of Object.keys(runs[0])) {
    const vals = runs.map((r) => r[k]);
    if (typeof vals[0] === 'number') out[k] = median(vals);
    else if (Array.isArray(vals[0]) && typeof vals[0][0] === 'number') out[k] = vals[0].map((_, i) => median(vals.map((v) => v[i])));
    else out[k] = vals[0];
  }
  return out;
}

const SETTINGS_100K = [
  { name: 'default (rules, priority order)', strategy: 'rules', order: 'priority' },
  { name: 'laplace (input order)', strategy: 'laplace', order: 'input' },
  { name: 'smart (input order)', strategy: 'smart', order: 'input' },
];

const server = await startServer();
let browser;
let code = 0;
try {
  browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS });
  const context = await browser.newContext({ viewport: { width: 1280, height: 900 } });
  const result = {
    browser: `Chromium ${browser.version()} (headless)`,
    viewport: [1280, 900],
    slice_ms: 50,
  };
  // other work on the same cores slows every figure: the load average at the start
  result.load_average = os.loadavg().map((x) => Number(x.toFixed(2)));
  // the module the page loads, as served and gzipped (zlib level 9, as gzip -9)
  const wasm = readFileSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'));
  result.wasm = { bytes: wasm.length, gzip_bytes: gzipSync(wasm, { level: 9 }).length };

  // ---- 0. the first visit: navigation → first mesh drawn, in fresh pages ----------------
  {
    const runs = [];
    for (let r = 0; r < Math.max(reps, 5); r++) {
      const fresh = await browser.newContext({ viewport: { width: 1280, height: 900 } });
      const p = await fresh.newPage();
      p.on('pageerror', (e) => log(`page error: ${e}`));
      await p.goto(server.base);
      await idle(p);
      const m = await p.evaluate(() => ({ ...window.smoothlab.metrics.startup, load: window.smoothlab.metrics.lastLoad }));
      runs.push({ first_mesh_ms: m.first_mesh_ms, engine_ready_ms: m.engine_ready_ms, menus_ms: m.menus_ms, first_frame_ms: m.first_frame_ms, first_render_ms: m.first_render_ms,
        sample: m.load.label, sample_build_ms: m.load.build_ms, sample_draw_ms: m.load.draw_ms });
      await fresh.close();
    }
    const m = medianOf(runs);
    result.startup = { runs: runs.length, median: m, all: runs };
    log(`first visit: first mesh drawn ${m.first_mesh_ms.toFixed(0)} ms after the navigation (engine ready ${m.engine_ready_ms.toFixed(0)} ms; ${runs.map((x) => x.first_mesh_ms.toFixed(0)).join(', ')})`);
  }
  if (startupOnly) {
    console.log(JSON.stringify(result, null, 2));
    throw Object.assign(new Error('done'), { done: true });
  }

  const page = await context.newPage();
  page.on('pageerror', (e) => log(`page error: ${e}`));
  await page.goto(server.base);
  await idle(page);

  // ---- 1. the 100k sample: one pass + redraw -------------------------------------------
  log('loading the 100k sample');
  await watchMainThread(page);
  await choose(page, 'sample:rand2d-large');
  const load100k = await page.evaluate(() => window.smoothlab.metrics.lastLoad);
  const main100k = await stopWatching(page);
  const table = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#stats-b tr')].map((tr) => [tr.dataset.stat, tr.querySelector('td').textContent])));
  result.hundred_k = { nodes: Number(table.nodes), elements: Number(table.elements), load: { ...load100k, ...main100k }, steps: [] };
  // the page splits each pass of a mesh this size between two workers once the second one
  // has loaded it (in the background, after the load): the Steps are timed from then
  const t2 = Date.now();
  const two = await page.waitForFunction(() => window.smoothlab.twoWorkers(), null, { timeout: 120_000, polling: 20 }).then(() => true, () => false);
  result.hundred_k.second_worker_ready_ms = two ? Date.now() - t2 : null;
  log(two ? `the second worker was ready ${Date.now() - t2} ms after the load` : 'no second worker: passes in one worker');
  for (const s of defaultOnly ? SETTINGS_100K.slice(0, 1) : SETTINGS_100K) {
    await setControls(page, s.strategy, s.order);
    const runs = [];
    for (let r = 0; r < reps; r++) {
      await page.click('#reset');
      await idle(page);
      await watchMainThread(page);
      await page.click('#step');
      await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: HOUR, polling: 20 });
      await idle(page);
      const step = await page.evaluate(() => window.smoothlab.metrics.lastStep);
      runs.push({ ...step, ...(await stopWatching(page)) });
    }
    const m = medianOf(runs);
    log(`100k ${s.name}: ${m.wall_ms.toFixed(0)} ms to the redrawn meshes (${runs.map((x) => x.wall_ms.toFixed(0)).join(', ')})`);
    result.hundred_k.steps.push({ ...s, reps, median: m, runs });
  }

  // ---- 2. the 1M sample: load, 3 passes with progress, Stop ------------------------------
  if (!skipMillion) {
    await page.fill('#passes', '3');
    await page.dispatchEvent('#passes', 'change');
    await setControls(page, 'laplace', 'input'); // no smoothing starts before the run
    log('loading the 1M sample');
    await watchMainThread(page);
    await choose(page, 'sample:rand2d-million');
    const load = await page.evaluate(() => window.smoothlab.metrics.lastLoad);
    const mainLoad = await stopWatching(page);
    const tableM = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#stats-b tr')].map((tr) => [tr.dataset.stat, tr.querySelector('td').textContent])));
    await page.screenshot({ path: path.join(process.cwd(), 'target', 'perf', 'page-1m-loaded.png') }).catch(() => {});
    const million = { nodes: Number(tableM.nodes), elements: Number(tableM.elements), strategy: `${millionStrategy} (input order)`, load: { ...load, ...mainLoad } };

    await setControls(page, millionStrategy, 'input');
    log(`1M: Run 3 passes of ${millionStrategy}`);
    // progress values seen during each pass (strictly between its start and end)
    await page.evaluate(() => {
      window.progressSeen = [];
      const p = document.getElementById('progress');
      window.progressObserver = new MutationObserver(() => window.progressSeen.push([performance.now(), Number(p.value)]));
      window.progressObserver.observe(p, { attributes: true, attributeFilter: ['value'] });
    });
    await watchMainThread(page);
    await page.click('#run');
    await page.waitForFunction(() => /passes done/.test(document.getElementById('status').textContent), null, { timeout: 2 * HOUR, polling: 200 });
    await idle(page, HOUR);
    const run = await page.evaluate(() => window.smoothlab.metrics.run);
    const mainRun = await stopWatching(page);
    const seen = await page.evaluate(() => { window.progressObserver.disconnect(); return window.progressSeen; });
    const within = [0, 1, 2].map((i) => seen.filter(([, v]) => v > i && v < i + 1).length);
    million.run = {
      total_ms: run.total_ms,
      charts_ms: run.charts_ms,
      passes: run.passes.map((p) => ({ pass: p.pass, wall_ms: p.wall_ms, pass_ms: p.pass_ms, slices: p.slices, sweep_ms: p.sweep_ms, stats_ms: p.stats_ms, render_ms: p.render_ms, paint_ms: p.paint_ms })),
      progress_updates_within_pass: within,
      ...mainRun,
    };
    await page.screenshot({ path: path.join(process.cwd(), 'target', 'perf', 'page-1m-after-3-passes.png') }).catch(() => {});

    log('1M: Stop during a pass');
    await watchMainThread(page);
    await page.click('#run');
    await page.waitForFunction(() => document.getElementById('progress').value >= 0.25, null, { timeout: HOUR, polling: 20 });
    const t0 = Date.now();
    await page.click('#run'); // Stop
    await page.waitForFunction(() => /Stopped after/.test(document.getElementById('status').textContent), null, { timeout: HOUR, polling: 20 });
    const stopToStatus = Date.now() - t0;
    await idle(page, HOUR);
    const stopToIdle = Date.now() - t0;
    million.stop = { to_status_ms: stopToStatus, to_idle_ms: stopToIdle, ...(await stopWatching(page)) };

    log('1M: the default settings: Stop while the nodes are ordered, then one Step');
    await setControls(page, 'rules', 'priority');
    await page.click('#step');
    await page.waitForTimeout(50);
    const t1 = Date.now();
    await page.click('#run'); // Stop
    await page.waitForFunction(() => /Stopped after/.test(document.getElementById('status').textContent), null, { timeout: HOUR, polling: 20 });
    million.stop_while_ordering = { to_status_ms: Date.now() - t1 };
    await idle(page, HOUR);
    if (!skipMillionDefault) {
      await watchMainThread(page);
      await page.click('#step');
      await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: 2 * HOUR, polling: 500 });
      await idle(page, HOUR);
      const step = await page.evaluate(() => window.smoothlab.metrics.lastStep);
      million.default_step = { ...step, ...(await stopWatching(page)) };
      log(`1M: default Step ${(step.wall_ms / 1000).toFixed(1)} s`);
    }
    million.memory = await page.evaluate(() => window.smoothlab.memory());
    result.million = million;
    log(`1M: loaded in ${(load.ms / 1000).toFixed(1)} s, 3 passes in ${(run.total_ms / 1000).toFixed(1)} s, stop ${stopToStatus} ms, memory peak ${(million.memory.peak_bytes / 2 ** 20).toFixed(0)} MiB`);
  }
  console.log(JSON.stringify(result, null, 2));
} catch (e) {
  if (!e.done) {
    console.error(`page bench: ${e}`);
    code = 1;
  }
} finally {
  if (browser) await browser.close();
  server.proc.kill();
}
process.exit(code);

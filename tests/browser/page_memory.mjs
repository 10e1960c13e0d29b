// The wasm memory of the playground page with the 1M-node sample, in headless Chromium
// (Debian's), for the memory section of docs/performance.md (`make performance`): the
// size of the worker's wasm memory (`memory.buffer.byteLength`, which never shrinks)
// after the sample is loaded and drawn, and after one Step (one pass on both sides) with
// the page's default settings (rules, priority order).
// Prints JSON on stdout. A benchmark, not a test: slow (a minute or two).
//   node tests/browser/page_memory.mjs
// Needs www/pkg from `make site` and playwright-core in tests/browser/node_modules.
import { existsSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { WWW, CHROMIUM, CHROMIUM_ARGS as ARGS, startServer } from './serve.mjs';

const log = (s) => process.stderr.write(`page memory: ${s}\n`);
if (!existsSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'))) {
  console.error('page memory: www/pkg/smoothlab_bg.wasm is missing: run `make site` first');
  process.exit(1);
}
const HOUR = 60 * 60_000;

async function idle(page, timeout = HOUR) {
  await page.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' &&
    document.getElementById('run').textContent === 'Run', null, { timeout, polling: 100 });
}
const memory = (page) => page.evaluate(() => window.smoothlab.memory());

const server = await startServer();
let browser;
let code = 0;
try {
  browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS });
  const page = await (await browser.newContext({ viewport: { width: 1280, height: 900 } })).newPage();
  page.on('pageerror', (e) => log(`page error: ${e}`));
  await page.goto(server.base);
  await idle(page);
  const result = { browser: `Chromium ${browser.version()} (headless)`, at_start: await memory(page) };
  log('loading the 1M sample');
  await page.selectOption('#sample', 'sample:rand2d-million');
  await page.waitForFunction(() => document.getElementById('sample').value === 'sample:rand2d-million', null, { timeout: HOUR });
  await idle(page);
  const table = await page.evaluate(() => Object.fromEntries([...document.querySelectorAll('#stats-b tr')].map((tr) => [tr.dataset.stat, tr.querySelector('td').textContent])));
  result.nodes = Number(table.nodes);
  result.elements = Number(table.elements);
  result.loaded = await memory(page);
  log(`loaded: ${(result.loaded.bytes / 2 ** 20).toFixed(0)} MiB (peak ${(result.loaded.peak_bytes / 2 ** 20).toFixed(0)} MiB)`);
  await page.selectOption('#strategy', 'rules');
  await page.selectOption('#order', 'priority');
  await idle(page);
  log('one Step with the default settings');
  await page.click('#step');
  await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: 2 * HOUR, polling: 500 });
  await idle(page);
  result.smoothed = await memory(page);
  log(`after one Step: ${(result.smoothed.bytes / 2 ** 20).toFixed(0)} MiB (peak ${(result.smoothed.peak_bytes / 2 ** 20).toFixed(0)} MiB)`);
  console.log(JSON.stringify(result, null, 2));
} catch (e) {
  console.error(`page memory: ${e}`);
  code = 1;
} finally {
  if (browser) await browser.close();
  server.proc.kill();
}
process.exit(code);

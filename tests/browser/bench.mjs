// Runs the wasm benchmark page (www/bench.html) in headless Chromium (Debian's) and prints
// its result as JSON on stdout, for the perf program (`make performance`).
//   node tests/browser/bench.mjs [--nodes 100000] [--reps 3]
// Needs www/pkg from `make site` and playwright-core in tests/browser/node_modules.
import { existsSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { WWW, CHROMIUM, CHROMIUM_ARGS as ARGS, startServer } from './serve.mjs';

function arg(name, fallback) {
  const i = process.argv.indexOf(`--${name}`);
  return i > 0 && process.argv[i + 1] ? process.argv[i + 1] : fallback;
}
const nodes = Number(arg('nodes', '100000'));
const reps = Number(arg('reps', '3'));

if (!existsSync(path.join(WWW, 'pkg', 'smoothlab_bg.wasm'))) {
  console.error('bench: www/pkg/smoothlab_bg.wasm is missing: run `make site` first');
  process.exit(1);
}

const server = await startServer();
const base = server.base;
let browser;
let code = 0;
try {
  browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS });
  const page = await browser.newPage();
  page.on('pageerror', (e) => console.error(`bench page error: ${e}`));
  await page.goto(`${base}bench.html?auto=1&nodes=${nodes}&reps=${reps}`);
  await page.waitForFunction(() => window.benchResult !== undefined, null, { timeout: 20 * 60_000, polling: 500 });
  const result = await page.evaluate(() => window.benchResult);
  if (result.error) throw new Error(result.error);
  result.browser = `Chromium ${browser.version()} (headless)`;
  console.log(JSON.stringify(result, null, 2));
} catch (e) {
  console.error(`bench: ${e}`);
  code = 1;
} finally {
  if (browser) await browser.close();
  server.proc.kill();
}
process.exit(code);

// Runs the wasm benchmark page (www/bench.html) in headless Chromium (Debian's) and prints
// its result as JSON on stdout, for examples/perf.rs (`make performance`).
//   node tests/browser/bench.mjs [--nodes 100000] [--reps 3]
// Needs www/pkg from `make site` and playwright-core in tests/browser/node_modules.
import { spawn } from 'node:child_process';
import { existsSync } from 'node:fs';
import { createServer } from 'node:net';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { chromium } from 'playwright-core';

const ROOT = path.resolve(path.dirname(fileURLToPath(import.meta.url)), '../..');
const WWW = path.join(ROOT, 'www');
const CHROMIUM = process.env.CHROMIUM || '/usr/bin/chromium';
const ARGS = ['--headless', '--no-sandbox', '--disable-gpu', '--disable-quic', '--no-first-run',
  '--disable-background-networking', '--disable-component-update', '--disable-sync'];

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

function freePort() {
  return new Promise((resolve, reject) => {
    const s = createServer();
    s.once('error', reject);
    s.listen(0, '127.0.0.1', () => {
      const { port } = s.address();
      s.close(() => resolve(port));
    });
  });
}

const port = await freePort();
const server = spawn('python3', ['-m', 'http.server', String(port), '--bind', '127.0.0.1', '--directory', WWW], {
  stdio: ['ignore', 'ignore', 'ignore'],
});
const base = `http://127.0.0.1:${port}/`;
let browser;
let code = 0;
try {
  for (let i = 0; ; i++) {
    try {
      if ((await fetch(base)).ok) break;
    } catch { /* not up yet */ }
    if (i > 100) throw new Error('the bench server did not start');
    await new Promise((r) => setTimeout(r, 100));
  }
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
  server.kill();
}
process.exit(code);

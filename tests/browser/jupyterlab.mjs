// The notebook widget in a real JupyterLab (make lab-test), driven in Debian's Chromium:
// a notebook of four widgets is run cell by cell, one is stepped in its frame and read
// back in Python, one is given another sample after it is shown, the notebook is saved
// with its widgets' state (measured: under 3.5 MB for the four, the page held once) and
// opened again with no kernel behind it, where every widget shows its page again, as saved.
//   node tests/browser/jupyterlab.mjs LAB_VENV
// LAB_VENV: a virtual environment with JupyterLab and the wheel (scripts/ensure-tools.sh
// --lab makes it). JupyterLab runs on a free 127.0.0.1 port with its settings, runtime
// files and notebook under test-output/jupyterlab/, so nothing of the user's is read or
// written. Screenshots go there too. Prints "N passed, M failed"; exits 1 on failure.
import { spawn } from 'node:child_process';
import { mkdirSync, readFileSync, rmSync, statSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { ROOT, CHROMIUM, CHROMIUM_ARGS, freePort } from './serve.mjs';
import { results, test, check } from './lib.mjs';

const VENV = path.resolve(process.argv[2] || path.join(ROOT, 'tools', 'lab'));
const OUT = path.join(ROOT, 'test-output', 'jupyterlab');
const NOTEBOOK = path.join(OUT, 'work', 'widgets.ipynb');
const TIMEOUT = Number(process.env.LAB_TIMEOUT || 120_000);
const LIMIT = 3.5 * 1024 * 1024; // the bound for a notebook of four widgets

const SAMPLES = ['plate-tri-tangled', 'rand2d', 'plate-quad-tangled', 'hex-tangled'];
const CELLS = [
  `import smoothlab\nws = [smoothlab.Playground(sample=s, height=460) for s in ${JSON.stringify(SAMPLES)}]`,
  'ws[0]', 'ws[1]', 'ws[2]', 'ws[3]',
  'print("read back:", ws[0].stats["b"]["passes"], ws[0].mesh_b.points.shape, int(ws[0].stats["b"]["inverted"]))',
  'ws[1].sample = "plate-quad-tangled-hard"',
];


function writeNotebook() {
  const cell = (source) => ({ cell_type: 'code', execution_count: null, metadata: {}, outputs: [], source });
  const nb = {
    cells: CELLS.map(cell), nbformat: 4, nbformat_minor: 5,
    metadata: { kernelspec: { name: 'python3', display_name: 'Python 3 (ipykernel)', language: 'python' } },
  };
  mkdirSync(path.dirname(NOTEBOOK), { recursive: true });
  writeFileSync(NOTEBOOK, JSON.stringify(nb, null, 1));
}

/** JupyterLab on a free port, its settings (widget state saved with the notebook, no news)
 * and runtime files under OUT. */
async function startLab() {
  const settings = path.join(OUT, 'settings');
  const put = (name, value) => {
    const file = path.join(settings, name);
    mkdirSync(path.dirname(file), { recursive: true });
    writeFileSync(file, JSON.stringify(value));
  };
  put('@jupyter-widgets/jupyterlab-manager/plugin.jupyterlab-settings', { saveState: true });
  put('@jupyterlab/apputils-extension/notification.jupyterlab-settings', { fetchNews: 'false', checkForUpdates: false });
  const port = await freePort();
  const env = {
    ...process.env,
    JUPYTERLAB_SETTINGS_DIR: settings,
    JUPYTERLAB_WORKSPACES_DIR: path.join(OUT, 'workspaces'),
    JUPYTER_CONFIG_DIR: path.join(OUT, 'config'),
    JUPYTER_RUNTIME_DIR: path.join(OUT, 'runtime'),
    JUPYTER_PLATFORM_DIRS: '1',
  };
  const proc = spawn(path.join(VENV, 'bin', 'jupyter'), [
    'lab', '--no-browser', `--ServerApp.port=${port}`, '--ServerApp.ip=127.0.0.1', '--ServerApp.port_retries=0',
    '--IdentityProvider.token=', '--ServerApp.password=', `--ServerApp.root_dir=${path.dirname(NOTEBOOK)}`,
    '--LabApp.news_url=', '--ServerApp.disable_check_xsrf=True', '--ServerApp.allow_root=True',
  ], { env, stdio: ['ignore', 'ignore', 'pipe'] });
  let log = '';
  proc.stderr.on('data', (d) => { log += d; });
  const base = `http://127.0.0.1:${port}/`;
  for (let i = 0; i < 600 && proc.exitCode === null; i++) {
    try {
      const r = await fetch(`${base}api/status`);
      if (r.ok) return { proc, base, log: () => log };
    } catch { /* not up yet */ }
    await new Promise((r) => setTimeout(r, 100));
  }
  proc.kill();
  throw new Error(`JupyterLab did not start:\n${log}`);
}

/** Opens the notebook and waits for its cells (and, if it has one, an idle kernel). */
async function openNotebook(page, base) {
  await page.goto(`${base}lab/tree/widgets.ipynb`);
  await page.waitForSelector('.jp-NotebookPanel .jp-Cell', { timeout: TIMEOUT });
  // the kernel started and connected: the status bar says so (a cell run before is dropped)
  await page.waitForFunction(() => /\| Idle/.test(document.querySelector('.jp-StatusBar-Widget') ? document.querySelector('#jp-main-statusbar').textContent : ''), null, { timeout: TIMEOUT });
}

/** Runs cell i (0-based) as a user does (select it, Shift+Enter) and waits till it ran. */
async function runCell(page, i) {
  const cell = page.locator('.jp-NotebookPanel .jp-Cell').nth(i);
  await cell.locator('.jp-InputPrompt').click();
  await page.keyboard.press('Shift+Enter');
  await page.waitForFunction((i) => {
    const c = document.querySelectorAll('.jp-NotebookPanel .jp-Cell')[i];
    const p = c && c.querySelector('.jp-InputPrompt');
    return p && /\[\d+\]/.test(p.textContent);
  }, i, { timeout: TIMEOUT });
}

/** The widgets' frames in the notebook, in order, once each page is ready. */
async function widgetFrames(page, n) {
  await page.waitForFunction((n) => document.querySelectorAll('.jp-OutputArea-output iframe').length >= n, n, { timeout: TIMEOUT });
  const frames = [];
  for (const el of await page.$$('.jp-OutputArea-output iframe')) {
    await el.scrollIntoViewIfNeeded();
    const f = await el.contentFrame();
    await f.waitForFunction(() => document.body && document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
    frames.push(f);
  }
  return frames;
}

mkdirSync(OUT, { recursive: true });
rmSync(path.join(OUT, 'work'), { recursive: true, force: true });
writeNotebook();
const server = await startLab();
const browser = await chromium.launch({ executablePath: CHROMIUM, args: CHROMIUM_ARGS });
const context = await browser.newContext({ viewport: { width: 1280, height: 1000 } });
const page = await context.newPage();
page.setDefaultTimeout(TIMEOUT);
const errors = [];
page.on('pageerror', (e) => errors.push(e.message));

try {
  await test('JupyterLab: four widgets render the page with its controls beside the meshes', async () => {
    await openNotebook(page, server.base);
    try {
      for (let i = 0; i < 5; i++) await runCell(page, i);
    } finally {
      await page.screenshot({ path: path.join(OUT, 'lab-ran.png') });
    }
    const frames = await widgetFrames(page, 4);
    check(frames.length === 4, `${frames.length} widgets shown`);
    for (const [i, f] of frames.entries()) {
      check((await f.inputValue('#sample')) === `sample:${SAMPLES[i]}`, `widget ${i} opened ${await f.inputValue('#sample')}`);
      check(await f.locator('#strategy').isVisible() && await f.locator('#objective-b').isVisible(), `widget ${i}: the settings column is hidden`);
    }
    check(await frames[3].locator('#cut-at').isVisible(), 'the volume widget shows its cut plane');
    await page.locator('.jp-OutputArea-output iframe').first().scrollIntoViewIfNeeded();
    await page.screenshot({ path: path.join(OUT, 'lab-rendered.png') });
  });

  await test('JupyterLab: Step in a widget, then Python reads the stepped side back', async () => {
    const [f] = await widgetFrames(page, 4);
    const before = await f.evaluate(() => document.querySelector('#stats-b [data-stat="inverted"] td').textContent);
    await f.click('#step');
    await f.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await page.waitForTimeout(500); // the page's state reaches the kernel
    await runCell(page, 5);
    const out = await page.locator('.jp-NotebookPanel .jp-Cell').nth(5).locator('.jp-OutputArea-output').innerText();
    const m = /read back: (\d+) \((\d+), 2\) (\d+)/.exec(out);
    check(m && m[1] === '1', `Python read: ${out}`);
    const after = await f.evaluate(() => document.querySelector('#stats-b [data-stat="inverted"] td').textContent);
    check(m && m[3] === after.trim(), `Python's inverted count ${m && m[3]} is the page's ${after} (before the step ${before})`);
  });

  await test('JupyterLab: a sample assigned after display opens in the shown widget', async () => {
    await runCell(page, 6);
    const el = (await page.$$('.jp-OutputArea-output iframe'))[1];
    let value = '';
    for (let i = 0; i < 200 && value !== 'sample:plate-quad-tangled-hard'; i++) {
      const f = await el.contentFrame();
      value = await f.evaluate(() => document.body.dataset.ready === '1' && document.getElementById('sample').value).catch(() => '');
      if (value !== 'sample:plate-quad-tangled-hard') await page.waitForTimeout(100);
    }
    check(value === 'sample:plate-quad-tangled-hard', `the widget shows ${value}`);
  });

  let saved = null;
  await test('JupyterLab: the notebook saved with its four widgets\' state is under 3.5 MB and holds the page once', async () => {
    const before = statSync(NOTEBOOK).mtimeMs;
    await page.locator('.jp-NotebookPanel .jp-Cell').first().locator('.jp-InputPrompt').click();
    await page.keyboard.press('Control+s');
    for (let i = 0; i < 300 && statSync(NOTEBOOK).mtimeMs === before; i++) await page.waitForTimeout(100);
    await page.waitForTimeout(500);
    const bytes = statSync(NOTEBOOK).size;
    saved = JSON.parse(readFileSync(NOTEBOOK, 'utf8'));
    const widgets = saved.metadata.widgets && saved.metadata.widgets['application/vnd.jupyter.widget-state+json'];
    check(widgets, 'no widget state saved');
    const models = Object.values(widgets.state);
    const pages = models.filter((m) => m.state && m.state.page !== undefined);
    const playgrounds = models.filter((m) => m.state && m.state._page !== undefined);
    const size = (m) => JSON.stringify(m).length;
    console.log(`     saved: ${(bytes / 1048576).toFixed(2)} MB; ${models.length} models, the page model ${(size(pages[0] || {}) / 1048576).toFixed(2)} MB, the widgets ${playgrounds.map((m) => (size(m) / 1024).toFixed(0)).join(', ')} kB`);
    check(playgrounds.length === 4 && pages.length === 1, `${playgrounds.length} widgets, ${pages.length} page models`);
    check(bytes < LIMIT, `the notebook is ${bytes} bytes`);
    const stepped = playgrounds.find((m) => m.state.sample === SAMPLES[0]);
    check(stepped && stepped.state.stats.b.passes === 1, 'the stepped widget\'s state is saved as stepped');
  });

  await test('JupyterLab: the saved notebook opened again, its kernel shut down, shows the four widgets as saved', async () => {
    check(saved, 'not saved');
    // shut the kernel down: what shows is the saved state alone
    const sessions = await (await fetch(`${server.base}api/sessions`)).json();
    for (const s of sessions) await fetch(`${server.base}api/sessions/${s.id}`, { method: 'DELETE' });
    const again = await context.newPage();
    again.on('pageerror', (e) => errors.push(e.message));
    try {
      await again.goto(`${server.base}lab/tree/widgets.ipynb`);
      const frames = await widgetFrames(again, 4);
      const shown = [];
      for (const f of frames) shown.push(await f.inputValue('#sample'));
      check(JSON.stringify(shown) === JSON.stringify(['sample:plate-tri-tangled', 'sample:plate-quad-tangled-hard', 'sample:plate-quad-tangled', 'sample:hex-tangled']), `reopened: ${shown.join(', ')}`);
      // the stepped widget opens stepped: its pass run again, its sides as saved
      const stepped = Object.values(saved.metadata.widgets['application/vnd.jupyter.widget-state+json'].state).find((m) => m.state.sample === SAMPLES[0]);
      const inverted = await frames[0].evaluate(() => document.querySelector('#stats-b [data-stat="inverted"] td').textContent.trim());
      const status = await frames[0].textContent('#status');
      check(/One pass done/.test(status) && inverted === String(stepped.state.stats.b.inverted), `reopened: '${status}', ${inverted} inverted, saved ${stepped.state.stats.b.inverted}`);
      check(!(await frames[0].locator('#message').isVisible()), `a message: ${await frames[0].textContent('#message')}`);
      await again.locator('.jp-OutputArea-output iframe').first().scrollIntoViewIfNeeded();
      await again.screenshot({ path: path.join(OUT, 'lab-reopened.png') });
    } finally {
      await again.close();
    }
  });

  await test('JupyterLab: no error on the page', async () => {
    check(errors.length === 0, `errors:\n${errors.join('\n')}`);
  });
} finally {
  await browser.close();
  server.proc.kill();
}

const failed = results.filter((r) => !r.ok).length;
console.log(`${results.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);

// Browser tests of the playground page, in real Chromium (Debian's), as a user would:
// open the page, pick samples, smooth, click and drag nodes, load bad files, export,
// open the permalink and the embed view. Serves www/ itself on a free 127.0.0.1 port.
// Screenshots go to test-output/browser/. Prints "N passed, M failed"; exits 1 on failure.
// The suites in suites/ (one file a part of the page) run after these, on the same browser.
import { readFileSync, readdirSync, existsSync, mkdirSync } from 'node:fs';
import { spawnSync } from 'node:child_process';
import path from 'node:path';
import { chromium } from 'playwright-core';
import { ROOT, WWW, CHROMIUM, CHROMIUM_ARGS as ARGS, startServer } from './serve.mjs';
import {
  OUT, BAD, DATA, HARDENING, TIMEOUT, MESQUITE, CI, results, test, check, unfold, externalRequests, consoleErrors, allowErrors, watch, idle, open, stats, canvasInfo, shot, chooseSample, clickSomeNode, ringPoints,
} from './lib.mjs';

// ---- the tests ------------------------------------------------------------------------
const server = await startServer();
const browser = await chromium.launch({ executablePath: CHROMIUM, args: ARGS });
const context = await browser.newContext({ viewport: { width: 1280, height: 900 }, acceptDownloads: true });
const page = await context.newPage();
page.setDefaultTimeout(TIMEOUT);
watch(page, 'page');

try {
  await test('the page opens on the heavily tangled quad plate and draws both meshes', async () => {
    await page.goto(server.base);
    await idle(page);
    check((await page.title()).includes('smoothlab'), 'title');
    check((await page.inputValue('#sample')) === 'sample:plate-quad-tangled-hard', `the opening sample: ${await page.inputValue('#sample')}`);
    const s = await stats(page, 'b');
    check(Number(s.nodes) > 0, `nodes: ${JSON.stringify(s)}`);
    for (const id of ['mesh-a', 'mesh-b']) {
      const c = await canvasInfo(page, id);
      check(c.colours > 8, `${id} looks blank (${c.colours} colours)`);
    }
    await shot(page, '01-opened');
  });

  await test('Step once on the opening sample: the old side leaves elements inverted, the new none, and the line above the meshes says so with the tables\' numbers', async () => {
    const p = await context.newPage();
    watch(p, 'opening step');
    try {
      await open(p, server.base);
      const lesson = async () => p.evaluate(() => ({ text: document.getElementById('lesson').textContent, passes: document.getElementById('lesson').dataset.passes }));
      const loaded = [await stats(p, 'a'), await stats(p, 'b')];
      const before = await lesson();
      check(before.passes === '0' && before.text.includes(`${loaded[0].inverted} of ${loaded[0].elements} elements are inverted`) && /Press Step/.test(before.text), `before a pass: ${before.text}`);
      await p.click('#step');
      await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      const [a, b] = [await stats(p, 'a'), await stats(p, 'b')];
      check(a.passes === '1' && b.passes === '1', `passes: ${a.passes}/${b.passes}`);
      check(Number(a.inverted) > 0, `the old side untangled the opening sample in one Step: ${a.inverted}`);
      check(b.inverted === '0', `the new side left ${b.inverted} inverted`);
      const after = await lesson();
      const want = `After 1 pass: A (old) leaves ${a.inverted} of ${a.elements} elements inverted; B (new) leaves no element inverted.`;
      check(after.passes === '1' && after.text === want, `the line: '${after.text}', want '${want}'`);
      const line = await p.locator('#lesson').boundingBox();
      check(line && line.y + line.height <= 768 && line.y >= 0, `the line is not on the first screen: ${JSON.stringify(line)}`);
      console.log(`     ${after.text}`);
    } finally {
      await p.close();
    }
  });

  await test('the link of the page\'s former opening sample still opens it', async () => {
    const p = await context.newPage();
    watch(p, 'former opening');
    try {
      await open(p, `${server.base}#sample=plate-quad-tangled`);
      check((await p.inputValue('#sample')) === 'sample:plate-quad-tangled', `sample: ${await p.inputValue('#sample')}`);
      check(await p.locator('#message').isHidden(), `a message: ${await p.textContent('#message')}`);
      const s = await stats(p, 'b');
      check(Number(s.inverted) > 0 && s.elements === '400', `the tangled quad plate: ${JSON.stringify(s)}`);
    } finally {
      await p.close();
    }
  });

  await test('Run 3 passes on the opening sample (the heavily tangled quad plate): the new side has no inverted element and beats the old', async () => {
    await chooseSample(page, 'sample:plate-quad-tangled-hard');
    const before = [await stats(page, 'a'), await stats(page, 'b')];
    check(Number(before[0].inverted) > 0 && Number(before[1].inverted) > 0, `the sample is not tangled: ${before[1].inverted}`);
    await page.fill('#passes', '3');
    await page.click('#run');
    await page.waitForFunction(() => document.getElementById('run').textContent === 'Run' && document.getElementById('progress').value === 3, null, { timeout: TIMEOUT });
    await idle(page);
    const after = [await stats(page, 'a'), await stats(page, 'b')];
    check(after[1].inverted === '0', `new side still has ${after[1].inverted} inverted elements`);
    check(after[0].passes === '3' && after[1].passes === '3', `passes: ${after[0].passes}/${after[1].passes}`);
    // the page's default sample (issue 11): the new objective ends with the larger smallest
    // angle, the smaller largest angle and the better worst and mean quality (the same
    // numbers as the lab's unit test: the sample is the same mesh natively and here)
    const num = (side, key) => parseFloat(after[side][key]);
    check(num(1, 'min_angle') > num(0, 'min_angle'), `min angle: new ${after[1].min_angle}, old ${after[0].min_angle}`);
    check(num(1, 'max_angle') < num(0, 'max_angle') - 1, `max angle: new ${after[1].max_angle} is not below old ${after[0].max_angle}`);
    check(num(1, 'min_quality') > num(0, 'min_quality'), `min quality: new ${after[1].min_quality}, old ${after[0].min_quality}`);
    check(num(1, 'mean_quality') > num(0, 'mean_quality'), `mean quality: new ${after[1].mean_quality}, old ${after[0].mean_quality}`);
    console.log(`     inverted old ${before[0].inverted} → ${after[0].inverted}, new ${before[1].inverted} → ${after[1].inverted}; ` +
      `min angle old ${after[0].min_angle}, new ${after[1].min_angle}; max angle old ${after[0].max_angle}, new ${after[1].max_angle}`);
    await shot(page, '02-after-3-passes');
  });

  await test('Stop ends a long Run after the pass in progress', async () => {
    await chooseSample(page, 'sample:rand2d-tangled');
    await page.fill('#passes', '40');
    await page.click('#run');
    await page.waitForFunction(() => document.getElementById('progress').value >= 1, null, { timeout: TIMEOUT });
    await page.click('#run'); // now labelled Stop
    await page.waitForFunction(() => document.getElementById('run').textContent === 'Run', null, { timeout: TIMEOUT });
    await idle(page);
    const s = await stats(page, 'b');
    check(Number(s.passes) >= 1 && Number(s.passes) < 40, `passes after Stop: ${s.passes}`);
    check(/Stopped after/.test(await page.textContent('#status')), await page.textContent('#status'));
    await page.fill('#passes', '3');
    await chooseSample(page, 'sample:plate-tri-tangled');
    await page.click('#run');
    await page.waitForFunction(() => document.getElementById('run').textContent === 'Run' && document.getElementById('progress').value === 3, null, { timeout: TIMEOUT });
    await idle(page);
  });

  await test('clicking a node draws both level sets, the path and the solve history', async () => {
    const blank = await canvasInfo(page, 'level-b');
    const before = [await stats(page, 'a'), await stats(page, 'b')];
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    const after = [await stats(page, 'a'), await stats(page, 'b')];
    check(JSON.stringify(after) === JSON.stringify(before), 'clicking (not dragging) moved a node');
    for (const id of ['level-a', 'level-b', 'solve-chart']) {
      const c = await canvasInfo(page, id);
      check(c.colours > 100 && c.hash !== blank.hash, `${id} looks blank (${c.colours} colours)`);
      console.log(`     ${id}: ${c.colours} colours`);
    }
    check((await page.textContent('#node-hint')).includes(String(hit.node)), 'the summary names the node');
    await page.locator('.node-view').screenshot({ path: path.join(OUT, '03-node-view.png') });
  });

  await test('charts per pass and angle histograms are drawn', async () => {
    for (const id of ['pass-chart', 'hist-a', 'hist-b']) {
      const c = await canvasInfo(page, id);
      check(c.colours > 8, `${id} looks blank (${c.colours} colours)`);
    }
    await page.locator('.pass-view').screenshot({ path: path.join(OUT, '04-pass-view.png') });
  });

  await test('every file of the malformed corpus shows an error and leaves the mesh on screen', async () => {
    // each file of tests/data/bad/ alone, and its Triangle .node + .ele pairs selected together
    const names = readdirSync(BAD).sort();
    // the non-planar files are refused by the planar readers, but the page (as the
    // command-line tool) reads them as surfaces in 3D: see the issue 16 test
    const singles = names.filter((f) => !/\.(node|ele)$/.test(f) && !/^non_planar/.test(f)).map((f) => [path.join(BAD, f)]);
    const pairs = names.filter((f) => f.endsWith('.node'))
      .map((f) => [path.join(BAD, f), path.join(BAD, f.replace(/\.node$/, '.ele'))]);
    const files = [...singles, ...pairs];
    check(files.length >= 40, `the corpus has only ${files.length} cases`);
    for (const set of files) for (const f of set) check(existsSync(f), `missing test file ${f}`);
    const before = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
    check(Number(before.s.nodes) > 0 && before.c.colours > 8, 'a mesh is shown before');
    for (const set of files) {
      const f = set[0];
      // clear the box so the message read below is this file's, not the previous one's
      await page.evaluate(() => { const m = document.getElementById('message'); m.textContent = ''; m.hidden = true; });
      await page.setInputFiles('#file', set);
      await page.waitForFunction(() => !document.getElementById('message').hidden, null, { timeout: TIMEOUT });
      await idle(page);
      const msg = await page.textContent('#message');
      check(msg.length > 10, `empty message for ${path.basename(f)}`);
      console.log(`     ${set.map((x) => path.basename(x)).join(' + ')}: ${msg}`);
      const after = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
      check(JSON.stringify(after.s) === JSON.stringify(before.s), 'the statistics changed');
      check(after.c.hash === before.c.hash, 'the mesh canvas changed');
    }
    check((await page.getAttribute('#message', 'role')) === 'alert', 'the message is an alert');
    await shot(page, '05-bad-file', false);
  });

  await test('a Triangle .node + .ele pair loads when selected together', async () => {
    await page.setInputFiles('#file', [path.join(DATA, 'square_o2.node'), path.join(DATA, 'square_o2.ele')]);
    await page.waitForFunction(() => document.getElementById('message').hidden && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
    const s = await stats(page, 'a');
    check(Number(s.nodes) > 0, `nodes ${s.nodes}`);
  });

  await test('issue 16 inputs: the page says what the command-line tool says, and reads BOM files as it does', async () => {
    // the command-line tool's own words ("smoothlab: FILE: message"), by the binary cargo builds
    const cli = (args) => spawnSync('cargo', ['run', '--quiet', '--bin', 'smoothlab', '--', ...args], { cwd: ROOT, encoding: 'utf8' });
    const refused = ['cr_only_bad_number.msh', 'cr_only_inf_coordinate.vtk',
      'cr_only_nan_coordinate.obj', 'cr_only_index_out_of_range.off', 'fixed_node_twice.msh', 'two_fixed_views.msh',
      'two_fixed_arrays.vtk', 'huge_coordinate.vtk'];
    for (const name of refused) {
      const file = path.join(BAD, name);
      const r = cli(['stats', file]);
      check(r.status === 1, `${name}: the command-line tool did not refuse it (${r.status}): ${r.stderr}`);
      const said = r.stderr.trim().split('\n').pop();
      await page.evaluate(() => { const m = document.getElementById('message'); m.textContent = ''; m.hidden = true; });
      await page.setInputFiles('#file', [file]);
      await page.waitForFunction(() => !document.getElementById('message').hidden, null, { timeout: TIMEOUT });
      await idle(page);
      const msg = await page.textContent('#message');
      check(said === `smoothlab: ${file}: ${msg}`, `${name}: the page says\n       ${msg}\n     the command-line tool\n       ${said}`);
      check(!/NaN/.test(msg), `${name}: NaN in ${msg}`);
    }
    // points off a plane: the command-line tool and the page both read a surface in 3D
    for (const name of ['non_planar.vtk', 'non_planar_outlier.obj']) {
      const file = path.join(BAD, name);
      const r = cli(['stats', '--json', file]);
      check(r.status === 0, `${name}: ${r.stderr}`);
      const said = JSON.parse(r.stdout);
      check(said.surface === true, `${name}: the command-line tool reads a surface: ${r.stdout}`);
      await page.setInputFiles('#file', [file]);
      await page.waitForFunction((n) => document.getElementById('status').textContent.includes(`Loaded ${n}`), name, { timeout: TIMEOUT });
      await idle(page);
      check(await page.evaluate(() => document.body.classList.contains('surface')), `${name}: the page reads a surface`);
      const s = await stats(page, 'a');
      check(Number(s.nodes) === said.nodes && Number(s.elements) === said.elements, `${name}: the page has ${JSON.stringify(s)}, the command-line tool ${r.stdout}`);
      // and both say why: the node farthest off the plane, and how far
      const note = r.stderr.trim().split('\n').find((l) => l.includes('read as a surface in 3D: ')) ?? '';
      const why = await page.textContent('#surface-why');
      check(note.endsWith(why.replace(/^Read as a surface in 3D: /, '').replace(/\.$/, '')) && why.includes('off the plane'),
        `${name}: the page says\n       ${why}\n     the command-line tool\n       ${note}`);
    }
    // files with a byte-order mark load, with the node counts the command-line tool reads
    for (const set of [['bom.obj'], ['bom.off'], ['bom.msh'], ['bom.vtk'], ['bom.node', 'bom.ele']]) {
      const files = set.map((f) => path.join(HARDENING, f));
      const r = cli(['stats', '--json', files[0]]);
      check(r.status === 0, `${set[0]}: ${r.stderr}`);
      const nodes = JSON.parse(r.stdout).nodes;
      await page.setInputFiles('#file', files);
      await page.waitForFunction(() => document.getElementById('message').hidden && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
      await idle(page);
      const s = await stats(page, 'a');
      check(Number(s.nodes) === nodes, `${set.join(' + ')}: the page has ${s.nodes} nodes, the command-line tool ${nodes}`);
    }
  });

  await test('a Gmsh sample file is fetched from the site and smoothed by Step', async () => {
    await chooseSample(page, 'gmsh:bracket_quad.msh');
    const s0 = await stats(page, 'b');
    check(s0.nodes === '347', `bracket nodes ${s0.nodes}`);
    await page.focus('#step');
    await page.keyboard.press('Enter'); // keyboard works
    await page.waitForFunction(() => document.querySelector('#stats-b tr[data-stat="passes"] td')?.textContent === '1', null, { timeout: TIMEOUT });
    await idle(page);
  });

  await test('the sample menu offers exactly the Gmsh files the site ships, and a link opens one by its name', async () => {
    const shipped = readdirSync(path.join(WWW, 'samples')).filter((f) => f.endsWith('.msh')).sort();
    const offered = await page.evaluate(() => [...document.querySelectorAll('#sample option')]
      .filter((o) => o.value.startsWith('gmsh:')).map((o) => o.value.slice('gmsh:'.length)));
    check(JSON.stringify([...offered].sort()) === JSON.stringify(shipped), `the menu offers ${offered}, the site ships ${shipped}`);
    check(shipped.length >= 3, `only ${shipped.length} Gmsh files`);
    // the core's name for a file (gmsh-, no .msh, _ as -) opens that file
    const p3 = await context.newPage();
    watch(p3, 'gmsh link');
    await p3.goto(`${server.base}#sample=gmsh-disk-tri6&passes=2`);
    await idle(p3);
    check((await p3.inputValue('#sample')) === 'gmsh:disk_tri6.msh', `the link opened ${await p3.inputValue('#sample')}`);
    const s = await stats(p3, 'b');
    check(Number(s.nodes) > 0, `disk nodes ${s.nodes}`);
    await p3.close();
  });

  await test('a file over the page\'s limit (256 MB, the core\'s) is refused by its size, before it is read', async () => {
    const before = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
    await page.evaluate(() => { const m = document.getElementById('message'); m.textContent = ''; m.hidden = true; });
    // a real file one byte over the limit, dropped on the page: its parts are one small
    // blob over and over, so the browser need not hold 256 MB to make it
    const size = await page.evaluate(() => {
      const mib = new Blob([new Uint8Array(1 << 20)]);
      const file = new File([...Array(256).fill(mib), new Blob([new Uint8Array(1)])], 'huge.msh');
      const dt = new DataTransfer();
      dt.items.add(file);
      document.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
      return file.size;
    });
    check(size === 256 * 1048576 + 1, `the file is ${size} bytes`);
    await page.waitForFunction(() => !document.getElementById('message').hidden, null, { timeout: TIMEOUT });
    await idle(page);
    const msg = await page.textContent('#message');
    check(msg === 'huge.msh is too large (256 MB); the page reads files up to 256 MB.', `message: ${msg}`);
    const after = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
    check(JSON.stringify(after.s) === JSON.stringify(before.s) && after.c.hash === before.c.hash, 'the mesh on screen changed');
  });

  await test('dragging a node moves it on both meshes', async () => {
    await chooseSample(page, 'sample:plate-quad');
    const before = [await canvasInfo(page, 'mesh-a'), await canvasInfo(page, 'mesh-b')];
    const hit = await clickSomeNode(page, 'mesh-a', ringPoints());
    await page.mouse.move(hit.x, hit.y);
    await page.mouse.down();
    await page.mouse.move(hit.x + 15, hit.y + 10, { steps: 5 });
    await page.mouse.up();
    await idle(page);
    const after = [await canvasInfo(page, 'mesh-a'), await canvasInfo(page, 'mesh-b')];
    check(after[0].hash !== before[0].hash && after[1].hash !== before[1].hash, 'a mesh did not change');
    const s = [await stats(page, 'a'), await stats(page, 'b')];
    check(s[0].min_angle === s[1].min_angle, `both sides moved alike: ${s[0].min_angle} vs ${s[1].min_angle}`);
  });

  await test('Perturb tangles the mesh and Reset restores it', async () => {
    const s0 = await stats(page, 'b');
    await unfold(page);
    await page.fill('#seed', '7');
    await unfold(page);
    await page.locator('#amount').fill('1');
    await unfold(page);
    await page.click('#perturb');
    await idle(page);
    const s1 = await stats(page, 'b');
    check(Number(s1.inverted) > 0, `perturb by 1 gave ${s1.inverted} inverted elements`);
    await page.click('#reset');
    await idle(page);
    const s2 = await stats(page, 'b');
    check(s2.min_angle === s1.min_angle, 'reset goes back to the perturbed mesh as the new original');
    check(s0.nodes === s2.nodes, 'node count');
  });

  await test('export the smoothed mesh as .msh and .vtk and a view as PNG', async () => {
    const get = async (sel) => {
      const [dl] = await Promise.all([page.waitForEvent('download'), page.click(sel)]);
      return { name: dl.suggestedFilename(), bytes: readFileSync(await dl.path()) };
    };
    const msh = await get('button[data-export="msh"][data-side="b"]');
    check(msh.name.endsWith('_b.msh') && msh.bytes.toString().startsWith('$MeshFormat'), `msh: ${msh.name}`);
    const vtk = await get('button[data-export="vtk"][data-side="a"]');
    check(vtk.bytes.toString().startsWith('# vtk DataFile'), `vtk: ${vtk.bytes.toString().slice(0, 30)}`);
    const png = await get('button[data-png="mesh-b"]');
    check(png.bytes.subarray(1, 4).toString() === 'PNG', 'png magic');
  });

  await test('a mesh saved from a panel reads back with the same statistics (drop a file)', async () => {
    await chooseSample(page, 'sample:plate-tri-tangled');
    await page.click('#step');
    await page.waitForFunction(() => document.querySelector('#stats-b tr[data-stat="passes"] td')?.textContent === '1', null, { timeout: TIMEOUT });
    await idle(page);
    const smoothed = await stats(page, 'b');
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('button[data-export="msh"][data-side="b"]')]);
    const text = readFileSync(await dl.path(), 'utf8');
    // drop it on the page as a user drags a file from the desktop
    await page.evaluate(([name, body]) => {
      const dt = new DataTransfer();
      dt.items.add(new File([body], name));
      document.body.dispatchEvent(new DragEvent('drop', { dataTransfer: dt, bubbles: true, cancelable: true }));
    }, [dl.suggestedFilename(), text]);
    await page.waitForFunction(() => /Loaded .*_b\.msh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const back = await stats(page, 'a');
    for (const k of ['nodes', 'elements', 'inverted', 'min_angle', 'max_angle', 'min_quality']) {
      check(back[k] === smoothed[k], `${k}: ${back[k]} read back, ${smoothed[k]} saved`);
    }
    check(back.passes === '0', 'a loaded file starts with no passes');
  });

  await test('a node chosen from the keyboard; a fixed node is refused with a message', async () => {
    await chooseSample(page, 'sample:star-regular');
    await page.fill('#node', '0');
    await page.press('#node', 'Enter');
    await page.waitForFunction(() => !document.getElementById('message').hidden, null, { timeout: TIMEOUT });
    check(/Node 0 cannot be chosen: node 0 is fixed/.test(await page.textContent('#message')), await page.textContent('#message'));
    await page.fill('#node', '6');
    await page.press('#node', 'Tab');
    await page.waitForFunction(() => document.getElementById('message').hidden, null, { timeout: TIMEOUT });
    await idle(page);
    const c = await canvasInfo(page, 'level-b');
    check(c.colours > 100, `level sets of node 6: ${c.colours} colours`);
    check((await page.textContent('#node-hint')).startsWith('Node 6:'), 'summary');
  });

  await test('the 100k-node sample loads in the worker while the page keeps drawing frames', async () => {
    await page.evaluate(() => {
      window.gaps = [];
      let last = performance.now();
      window.keep = true;
      const f = (t) => { window.gaps.push(t - last); last = t; if (window.keep) requestAnimationFrame(f); };
      requestAnimationFrame(f);
    });
    const t0 = Date.now();
    await chooseSample(page, 'sample:rand2d-large');
    const ms = Date.now() - t0;
    const gap = await page.evaluate(() => { window.keep = false; return Math.max(...window.gaps); });
    const s = await stats(page, 'b');
    check(Number(s.nodes) >= 100000, `nodes ${s.nodes}`);
    check(gap < 250, `the main thread stalled for ${gap.toFixed(0)} ms`);
    console.log(`     ${s.nodes} nodes, ${s.elements} elements loaded and drawn in ${ms} ms; longest frame gap ${gap.toFixed(0)} ms`);
  });

  await test('a pass split between two workers gives the meshes one worker gives, bit for bit', async () => {
    // the 100k sample is loaded: the second worker loads it too, in the background
    await page.waitForFunction(() => window.smoothlab.twoWorkers(), null, { timeout: TIMEOUT, polling: 100 });
    const onePass = async (p) => {
      await p.selectOption('#strategy', 'rules');
      await p.selectOption('#order', 'priority');
      await idle(p);
      await p.click('#step');
      await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      const meshes = [];
      for (const side of ['a', 'b']) {
        const [dl] = await Promise.all([p.waitForEvent('download'), p.click(`button[data-export="msh"][data-side="${side}"]`)]);
        meshes.push(readFileSync(await dl.path()).toString());
      }
      const step = await p.evaluate(() => window.smoothlab.metrics.lastStep);
      return { meshes, step, a: await stats(p, 'a'), b: await stats(p, 'b') };
    };
    const two = await onePass(page);
    check(two.step.workers === 2, `the pass ran in ${two.step.workers} worker(s)`);
    const other = await context.newPage();
    other.setDefaultTimeout(TIMEOUT);
    watch(other, 'one worker');
    try {
      await other.goto(`${server.base}?workers=1`);
      await idle(other);
      await chooseSample(other, 'sample:rand2d-large');
      const one = await onePass(other);
      check(one.step.workers === 1, `?workers=1 ran the pass in ${one.step.workers} workers`);
      for (const [i, side] of ['a', 'b'].entries()) {
        check(two.meshes[i] === one.meshes[i], `the ${side} side differs between two workers and one`);
        for (const row of ['inverted', 'min_angle', 'max_angle', 'min_quality', 'laplacian_moves', 'optimization_calls', 'passes']) {
          check(two[side][row] === one[side][row], `${side} ${row}: ${two[side][row]} with two workers, ${one[side][row]} with one`);
        }
      }
      console.log(`     one default Step: ${two.step.wall_ms.toFixed(0)} ms in two workers, ${one.step.wall_ms.toFixed(0)} ms in one; the same meshes (${two.meshes[1].length} bytes of .msh a side)`);
    } finally {
      await other.close();
    }
    await page.click('#reset');
    await idle(page);
  });

  await test('the 1M sample is listed; a pass on 100k nodes shows progress as it goes, and Stop undoes it within a second', async () => {
    const title = await page.$eval('#sample option[value="sample:rand2d-million"]', (o) => o.textContent);
    check(/1M/.test(title) && /slow/i.test(title), `the 1M sample's title: ${title}`);
    check((await stats(page, 'b')).nodes === '100000', 'the 100k sample is loaded');
    await page.selectOption('#strategy', 'smart');
    await page.selectOption('#order', 'input');
    await idle(page);
    await page.evaluate(() => {
      const p = document.getElementById('progress');
      window.seen = [];
      window.watcher = new MutationObserver(() => window.seen.push(Number(p.value)));
      window.watcher.observe(p, { attributes: true, attributeFilter: ['value'] });
    });
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const seen = await page.evaluate(() => { window.watcher.disconnect(); return window.seen; });
    const during = seen.filter((v) => v > 0 && v < 1);
    const step = await page.evaluate(() => window.smoothlab.metrics.lastStep);
    // every slice but the last moves the bar (a pass that fits in two slices has little to show)
    check(step.slices < 3 || during.length >= step.slices - 1, `${step.slices} slices, progress during the pass: ${JSON.stringify(seen)}`);
    check(during.every((v, i) => i === 0 || v >= during[i - 1]), `progress went back: ${JSON.stringify(during)}`);
    console.log(`     smart pass + redraw: ${step.wall_ms.toFixed(0)} ms in ${step.slices} slices, progress ${during.map((v) => v.toFixed(2)).join(' ')}`);
    // a long pass (Chen's rules, priority order, about 10 s here), stopped early
    await page.selectOption('#strategy', 'rules');
    await page.selectOption('#order', 'priority');
    await idle(page);
    const before = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
    await page.evaluate(() => { window.seen = []; window.watcher.observe(document.getElementById('progress'), { attributes: true, attributeFilter: ['value'] }); });
    await page.click('#run');
    await page.waitForFunction(() => window.seen.filter((v) => v % 1 > 0).length >= 3, null, { timeout: TIMEOUT, polling: 10 });
    const t0 = Date.now();
    await page.click('#run'); // Stop
    await page.waitForFunction(() => /Stopped after \d+ of/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT, polling: 10 });
    const stopMs = Date.now() - t0;
    await idle(page);
    check(stopMs < 1500, `Stop took ${stopMs} ms`);
    const done = Number(/Stopped after (\d+) of/.exec(await page.textContent('#status'))[1]);
    const after = { s: await stats(page, 'b'), c: await canvasInfo(page, 'mesh-b') };
    check(Number(after.s.passes) === Number(before.s.passes) + done, `passes ${before.s.passes} + ${done} whole ones, but ${after.s.passes}`);
    if (done === 0) {
      // (a faster smoother may finish a pass before the click: then whole passes are kept)
      check(JSON.stringify(after.s) === JSON.stringify(before.s), `the stopped pass left a trace: ${JSON.stringify(after.s)}`);
      check(after.c.hash === before.c.hash, 'the stopped pass changed the picture');
    }
    await page.evaluate(() => window.watcher.disconnect());
    console.log(`     Stop during a rules pass: idle again after ${stopMs} ms, ${done} whole passes kept, the pass in progress undone`);
    await chooseSample(page, 'sample:plate-tri');
  });

  await test('a panic in the engine is reported and the page keeps working', async () => {
    allowErrors(['deliberate panic']);
    const before = await stats(page, 'b');
    await page.evaluate(() => window.smoothlab.panicForTest());
    await page.waitForFunction(() => /Internal error/.test(document.getElementById('message').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    await page.waitForFunction(() => document.querySelector('#stats-b tr[data-stat="nodes"]') !== null, null, { timeout: TIMEOUT });
    const after = await stats(page, 'b');
    check(after.nodes === before.nodes, 'the mesh was reloaded');
    await page.click('#step');
    await page.waitForFunction(() => document.querySelector('#stats-b tr[data-stat="passes"] td')?.textContent === '1', null, { timeout: TIMEOUT });
    await shot(page, '06-after-panic', false);
    allowErrors([]);
  });

  await test('the permalink restores the sample and the settings', async () => {
    await chooseSample(page, 'sample:star-chen');
    await page.selectOption('#strategy', 'c2');
    await page.selectOption('#threshold', '10');
    await page.fill('#passes', '5');
    await page.dispatchEvent('#passes', 'change');
    await idle(page); // the link is written by the engine's encoder
    const href = await page.getAttribute('#permalink', 'href');
    check(href.includes('sample=star-chen') && href.includes('strategy=c2'), `permalink ${href}`);
    const p2 = await context.newPage();
    watch(p2, 'permalink');
    await p2.goto(new URL(href, server.base).toString());
    await idle(p2);
    check((await p2.inputValue('#sample')) === 'sample:star-chen', 'sample');
    check((await p2.inputValue('#strategy')) === 'c2', 'strategy');
    check((await p2.inputValue('#threshold')) === '10', 'threshold');
    check((await p2.inputValue('#passes')) === '5', 'passes');
    // a hash with junk is ignored, not injected
    await p2.goto(`${server.base}#sample=%3Cimg%20src%3Dx%3E&strategy=evil&passes=1e9`);
    await p2.reload();
    await idle(p2);
    check((await p2.inputValue('#strategy')) === 'rules', 'junk strategy ignored');
    check((await p2.locator('img').count()) === 0, 'no element built from the URL');
    await p2.close();
  });

  await test('a permalink with a malformed value says why and loads the defaults', async () => {
    const p4 = await context.newPage();
    watch(p4, 'bad permalink');
    await p4.goto(`${server.base}#sample=star-quad&passes=abc&strategy=c1`);
    await idle(p4);
    const msg = await p4.textContent('#message');
    check(await p4.isVisible('#message'), 'the message is shown');
    check(msg.includes("'passes'") && msg.includes("'abc'") && msg.includes('1 to 100'), `message: ${msg}`);
    check((await p4.getAttribute('#message', 'role')) === 'alert', 'the message is an alert');
    check((await p4.inputValue('#sample')) === 'sample:plate-quad-tangled-hard', `the default sample, not ${await p4.inputValue('#sample')}`);
    check((await p4.inputValue('#passes')) === '3' && (await p4.inputValue('#strategy')) === 'rules', 'defaults kept');
    check((await stats(p4, 'b')).nodes !== undefined, 'the default mesh is loaded');
    await p4.close();
  });

  await test('a permalink copied from the page reproduces its sample and controls', async () => {
    await chooseSample(page, 'gmsh:bracket_quad.msh');
    await page.selectOption('#strategy', 'c3');
    await page.selectOption('#threshold', '15');
    await page.selectOption('#order', 'input');
    for (const [id, v] of [['passes', '7'], ['maxiter', '9'], ['seed', '42']]) {
      await page.fill(`#${id}`, v);
      await page.dispatchEvent(`#${id}`, 'change');
    }
    await unfold(page);
    await page.locator('#amount').fill('0.75');
    await page.dispatchEvent('#amount', 'change');
    await idle(page);
    const ids = ['sample', 'strategy', 'threshold', 'order', 'passes', 'maxiter', 'seed', 'amount'];
    const controls = (pg) => pg.evaluate((ids) => ids.map((id) => document.getElementById(id).value), ids);
    const want = await controls(page);
    const href = await page.getAttribute('#permalink', 'href');
    check(href.includes('#sample=gmsh-bracket-quad&') && href.includes('maxiter=9'), `permalink ${href}`);
    check(new URL(href, server.base).hash === new URL(page.url()).hash, 'the address bar holds the same hash');
    const p5 = await context.newPage();
    watch(p5, 'copied permalink');
    await p5.goto(new URL(href, server.base).toString());
    await idle(p5);
    const got = await controls(p5);
    check(JSON.stringify(got) === JSON.stringify(want), `controls ${JSON.stringify(got)} != ${JSON.stringify(want)}`);
    check(await p5.isHidden('#message'), `message: ${await p5.textContent('#message')}`);
    check((await p5.getAttribute('#permalink', 'href')) === href, 'the reopened page writes the same link');
    await p5.close();
  });

  await test('the embed view is compact and fits a narrow iframe', async () => {
    const p3 = await context.newPage();
    watch(p3, 'embed');
    await p3.setViewportSize({ width: 480, height: 800 });
    await p3.goto(`${server.base}?embed=1#sample=plate-mixed-tangled`);
    await idle(p3);
    check(!(await p3.isVisible('.node-view')) && !(await p3.isVisible('.pass-view')), 'embed hides the extra views');
    check(await p3.isVisible('#mesh-a') && await p3.isVisible('#mesh-b'), 'both meshes shown');
    check(await p3.isVisible('#open-full'), 'link to the full page');
    const overflow = () => p3.evaluate(() => document.documentElement.scrollWidth - window.innerWidth);
    const boxes = async () => [await p3.locator('#panel-a').boundingBox(), await p3.locator('#panel-b').boundingBox()];
    check((await overflow()) <= 0, `horizontal overflow ${await overflow()}px`);
    const fits = () => p3.evaluate(() => document.documentElement.scrollHeight <= window.innerHeight);
    check(await fits(), 'at 480 × 800 the embed scrolls');
    await shot(p3, '07-embed-480');
    await p3.setViewportSize({ width: 360, height: 800 });
    await p3.waitForTimeout(400);
    await idle(p3);
    // side by side or stacked, whichever gives the larger pictures: both whole in the frame
    const [a, b] = await boxes();
    check(a.y + a.height <= 800 && b.y + b.height <= 800 && a.x + a.width <= 360 && b.x + b.width <= 360, `at 360 × 800 a panel is cut off: ${JSON.stringify([a, b])}`);
    check((await overflow()) <= 0 && (await fits()), `overflow at 360 px: ${await overflow()}px`);
    // the full page on a phone-sized screen shows one panel at a time, with its A/B switch
    await p3.goto(`${server.base}#sample=star-quad`);
    await idle(p3);
    check(await p3.isVisible('#mesh-a') && !(await p3.isVisible('#mesh-b')) && (await p3.isVisible('#show-b')), 'the full page at 360 px: A, and a switch to B');
    check((await overflow()) <= 0, 'the full page scrolls sideways at 360 px');
    await shot(p3, '08-full-360');
    await p3.close();
  });

  // ---- the page as a lecturer uses it -----------------------------------------------
  await test('a permalink reproduces Perturb (amount, seed) and the chosen node; Copy link copies it', async () => {
    await chooseSample(page, 'sample:plate-tri');
    await unfold(page);
    await page.fill('#seed', '5');
    await unfold(page);
    await page.locator('#amount').fill('0.8');
    await idle(page);
    await unfold(page);
    await page.click('#perturb');
    await idle(page);
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    await idle(page);
    const want = [await stats(page, 'a'), await stats(page, 'b')];
    check(Number(want[0].inverted) > 0, `the perturbed plate has ${want[0].inverted} inverted elements`);
    const href = await page.getAttribute('#permalink', 'href');
    for (const part of ['sample=plate-tri&', 'tangle=0.8', 'seed=5', 'perturbed=1', `node=${hit.node}`]) {
      check(href.includes(part), `the link ${href} lacks ${part}`);
    }
    await context.grantPermissions(['clipboard-read', 'clipboard-write'], { origin: server.base.replace(/\/$/, '') });
    await page.click('#copy-link');
    await page.waitForFunction(() => document.getElementById('copy-link').dataset.copied, null, { timeout: TIMEOUT });
    const copied = await page.getAttribute('#copy-link', 'data-copied');
    check(copied === new URL(href, server.base).toString(), `copied ${copied}`);
    check((await page.textContent('#status')).includes(copied), `status: ${await page.textContent('#status')}`);
    const clip = await page.evaluate(() => navigator.clipboard.readText().catch(() => null));
    check(clip === null || clip === copied, `clipboard holds ${clip}`);
    const p6 = await context.newPage();
    watch(p6, 'perturbed permalink');
    await p6.goto(copied);
    await idle(p6);
    const got = [await stats(p6, 'a'), await stats(p6, 'b')];
    check(JSON.stringify(got) === JSON.stringify(want), `reopened ${JSON.stringify(got)} != ${JSON.stringify(want)}`);
    check((await p6.inputValue('#node')) === String(hit.node), `node ${await p6.inputValue('#node')}`);
    check((await canvasInfo(p6, 'level-b')).colours > 100, 'the level sets of the node are drawn');
    check((await p6.getAttribute('#permalink', 'href')) === href, 'the reopened page writes the same link');
    await p6.close();
  });

  await test('with the user\'s own file loaded, the link says it cannot carry the file', async () => {
    await page.setInputFiles('#file', [path.join(DATA, 'square_o2.node'), path.join(DATA, 'square_o2.ele')]);
    await page.waitForFunction(() => /Loaded square_o2/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const note = await page.textContent('#permalink-note');
    check(/Your own file \(square_o2\.node \+ square_o2\.ele\) cannot travel in a link/.test(note), `note: ${note}`);
    check(await page.isVisible('#permalink-note'), 'the note is visible');
    await chooseSample(page, 'sample:star-chen');
    check((await page.textContent('#permalink-note')) === '', 'a sample clears the note');
  });

  await test('editing the hash or going Back shows what the address names', async () => {
    const p7 = await context.newPage();
    watch(p7, 'hash edits');
    await p7.goto(`${server.base}#sample=star-quad&passes=2`);
    await idle(p7);
    check((await p7.inputValue('#sample')) === 'sample:star-quad', 'opened on star-quad');
    await p7.evaluate(() => { location.hash = '#sample=star-regular&strategy=c2&passes=4&node=6'; });
    await p7.waitForFunction(() => document.getElementById('sample').value === 'sample:star-regular' && document.getElementById('node').value === '6', null, { timeout: TIMEOUT });
    await idle(p7);
    check((await p7.inputValue('#strategy')) === 'c2' && (await p7.inputValue('#passes')) === '4', 'settings of the edited hash');
    await p7.goBack();
    await p7.waitForFunction(() => document.getElementById('sample').value === 'sample:star-quad', null, { timeout: TIMEOUT });
    await idle(p7);
    check((await p7.inputValue('#passes')) === '2' && (await p7.inputValue('#node')) === '', 'Back restores the settings and no node');
    await p7.close();
  });

  await test('typed controls are checked as they are edited, with the range in words, from one source', async () => {
    await chooseSample(page, 'sample:star-chen');
    const html = readFileSync(path.join(WWW, 'index.html'), 'utf8');
    check(!/id="(passes|maxiter|seed|amount)"[^>]*\b(min|max|value)=/.test(html), 'the HTML writes no range of its own');
    const attrs = await page.evaluate(() => ['passes', 'maxiter'].map((id) => [document.getElementById(id).min, document.getElementById(id).max]));
    check(JSON.stringify(attrs) === '[["1","100"],["1","50"]]', `ranges from the core: ${JSON.stringify(attrs)}`);
    const before = await stats(page, 'b');
    await page.fill('#passes', '2.5');
    await page.waitForFunction(() => document.getElementById('passes-error').textContent !== '', null, { timeout: TIMEOUT });
    check((await page.textContent('#passes-error')) === "Passes must be a whole number from 1 to 100; '2.5' is not.", await page.textContent('#passes-error'));
    check((await page.getAttribute('#passes', 'aria-invalid')) === 'true', 'aria-invalid');
    await page.click('#run');
    await idle(page);
    const msg = await page.textContent('#message');
    check(/Passes must be .* Correct it first\./.test(msg) && !/invalid type|u32|Error:/.test(msg), `message: ${msg}`);
    check(JSON.stringify(await stats(page, 'b')) === JSON.stringify(before), 'nothing ran');
    await page.fill('#passes', '500');
    await page.waitForFunction(() => /'500' is not/.test(document.getElementById('passes-error').textContent), null, { timeout: TIMEOUT });
    await page.fill('#passes', '2');
    await page.waitForFunction(() => document.getElementById('passes-error').textContent === '', null, { timeout: TIMEOUT });
    await idle(page);
    check(await page.isHidden('#message'), 'the refusal goes once the value is fixed');
    check((await page.getAttribute('#permalink', 'href')).includes('passes=2'), 'the link follows the fixed value');
    await unfold(page);
    await page.fill('#seed', '-3');
    await page.waitForFunction(() => document.getElementById('seed-error').textContent !== '', null, { timeout: TIMEOUT });
    check(/^Seed must be a whole number from 0 to 18446744073709551615; '-3' is not\.$/.test(await page.textContent('#seed-error')), await page.textContent('#seed-error'));
    await unfold(page);
    await page.click('#perturb');
    await idle(page);
    check(/Seed must be/.test(await page.textContent('#message')), 'Perturb refuses a negative seed');
    await unfold(page);
    await page.fill('#seed', '18446744073709551615');
    await page.waitForFunction(() => document.getElementById('seed-error').textContent === '', null, { timeout: TIMEOUT });
    await unfold(page);
    await page.locator('#amount').fill('1');
    await idle(page);
    await unfold(page);
    await page.click('#perturb');
    await idle(page);
    const status = await page.textContent('#status');
    check(status.includes('by 1 mean edge length (seed 18446744073709551615)'), `status: ${status}`);
    await page.click('#run');
    await page.waitForFunction(() => /2 passes done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    await page.fill('#node', '6');
    await page.press('#node', 'Enter');
    await idle(page);
    const summary = await page.textContent('#node-hint');
    check(!/MaxIter|LineSearchFailed|SmallStep|Optimal\b|NotFinite/.test(summary), `summary: ${summary}`);
    await chooseSample(page, 'sample:plate-tri-tangled');
    check(!/plate-tri-tangled/.test(await page.textContent('#status')), `status: ${await page.textContent('#status')}`);
  });

  await test('Perturb, Reset or a new sample during a run say what happened, not the run', async () => {
    await page.selectOption('#strategy', 'rules');
    for (const [action, want] of [['#perturb', /^Perturbed .* The run in progress was stopped\.$/], ['#reset', /^Both sides reset .* The run in progress was stopped\.$/], ['sample', /^Loaded .* The run in progress was stopped\.$/]]) {
      await chooseSample(page, 'sample:rand2d-tangled');
      await page.fill('#passes', '40');
      await idle(page);
      await page.click('#run');
      await page.waitForFunction(() => document.getElementById('progress').value >= 1, null, { timeout: TIMEOUT });
      if (action === 'sample') await page.selectOption('#sample', 'sample:plate-quad');
      else await page.click(action);
      await page.waitForFunction(() => document.getElementById('run').textContent === 'Run', null, { timeout: TIMEOUT });
      await idle(page);
      const status = await page.textContent('#status');
      check(want.test(status), `${action}: status ${status}`);
      const s = await stats(page, 'b');
      check(s.passes === '0', `${action}: ${s.passes} passes shown after it`);
    }
    await page.fill('#passes', '3');
    await idle(page);
  });

  await test('controls the strategy does not use are disabled, saying why', async () => {
    const look = () => page.evaluate(() => ({
      threshold: document.getElementById('threshold').disabled,
      thresholdWhy: document.getElementById('threshold-why').textContent,
      maxiter: document.getElementById('maxiter').disabled,
      maxiterWhy: document.getElementById('maxiter-why').textContent,
    }));
    await page.selectOption('#strategy', 'rules');
    let c = await look();
    check(c.threshold && /Chen's rules decide by their own tests/.test(c.thresholdWhy) && !c.maxiter, JSON.stringify(c));
    await page.selectOption('#strategy', 'c2');
    c = await look();
    check(!c.threshold && c.thresholdWhy === '' && !c.maxiter, JSON.stringify(c));
    await page.selectOption('#strategy', 'laplace');
    c = await look();
    check(c.threshold && c.maxiter && /never calls the solver/.test(c.maxiterWhy), JSON.stringify(c));
    await page.selectOption('#strategy', 'rules');
    await idle(page);
  });

  await test('a press near a node: chosen within reach, else a note says why; hover shows the node number', async () => {
    await chooseSample(page, 'sample:plate-quadratic');
    // the meshes as large as the settings leave them: with a node's level sets in front
    // they are drawn smaller, and a quadratic plate's nodes lie a few pixels apart
    await page.click('#tabbtn-settings');
    await idle(page);
    const box = await page.locator('#mesh-b').boundingBox();
    // the hover label names nodes as the mouse passes over them
    const seen = { free: null, fixed: null, mid: null };
    for (let i = 0; i < 60 && !(seen.free && seen.fixed && seen.mid); i++) {
      for (let j = 0; j < 60 && !(seen.free && seen.fixed && seen.mid); j += 1) {
        let x = box.x + ((i + 0.5) / 60) * box.width;
        let y = box.y + ((j + 0.5) / 60) * box.height;
        if ((i + j) % 3) continue;
        await page.mouse.move(x, y);
        await page.waitForFunction(() => true);
        await page.waitForTimeout(5);
        const hovered = await page.evaluate(() => {
          const l = document.querySelector('#panel-b .hover-label');
          return l.hidden ? null : { label: l.textContent, left: parseFloat(l.style.left), top: parseFloat(l.style.top) };
        });
        if (!hovered) continue;
        // where the label was asked for (it may lag the mouse by a move): left = x + 12, top = y − 8
        const label = hovered.label;
        x = box.x + hovered.left - 12;
        y = box.y + hovered.top + 8;
        if (/\(mid-side\)$/.test(label)) seen.mid ??= { x, y, label };
        else if (/\(fixed\)$/.test(label)) seen.fixed ??= { x, y, label };
        else if (/^node \d+$/.test(label)) seen.free ??= { x, y, label };
      }
    }
    check(seen.free && seen.fixed && seen.mid, `hover labels seen: ${JSON.stringify(seen)}`);
    await page.mouse.click(seen.mid.x, seen.mid.y);
    await idle(page);
    await page.waitForFunction(() => !document.getElementById('pick-note').hidden, null, { timeout: TIMEOUT });
    const note = await page.textContent('#pick-note');
    check(/is a mid-side node of a quadratic element/.test(note), `note: ${note}`);
    await page.mouse.click(seen.fixed.x, seen.fixed.y);
    await idle(page);
    check(/is fixed: it is on the boundary/.test(await page.textContent('#pick-note')), await page.textContent('#pick-note'));
    await page.mouse.click(seen.free.x, seen.free.y);
    await idle(page);
    check(await page.isHidden('#pick-note'), 'choosing a node clears the note');
    check(`node ${await page.inputValue('#node')}` === seen.free.label, `chose ${await page.inputValue('#node')} under ${seen.free.label}`);
    // a typed mid-side node is refused, saying it is one
    const mid = /node (\d+)/.exec(seen.mid.label)[1];
    await page.fill('#node', mid);
    await page.press('#node', 'Enter');
    await page.waitForFunction(() => !document.getElementById('message').hidden, null, { timeout: TIMEOUT });
    check(/mid-side node/.test(await page.textContent('#message')), await page.textContent('#message'));
    // a tap reaches farther than a mouse click: every tap within 20 px of a free node takes it
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    const radius = await page.evaluate(() => window.smoothlab.pickRadius({ pointerType: 'touch' }));
    check(radius >= 20, `touch radius ${radius}`);
    console.log(`     hover: ${seen.free.label}, ${seen.fixed.label}, ${seen.mid.label}; chose node ${hit.node}`);
  });

  await test('the old solver\'s path shows at nodes 200 and 320 of the default sample', async () => {
    await chooseSample(page, 'sample:plate-tri-tangled');
    for (const node of ['200', '320']) {
      await page.fill('#node', node);
      await page.press('#node', 'Enter');
      await page.waitForFunction((n) => document.getElementById('node-hint').textContent.startsWith(`Node ${n}:`), node, { timeout: TIMEOUT });
      await idle(page);
      const ink = await page.evaluate(() => {
        const c = document.getElementById('level-a');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let n = 0;
        for (let i = 0; i < d.length; i += 4) if (d[i] === 204 && d[i + 1] === 0 && d[i + 2] === 153) n++;
        return { n, w: c.width };
      });
      // the path is drawn (the bug this guards against drew none): a path of a few steps,
      // 2 px wide, in a picture whose plot shares its room with the legend's band
      check(ink.n >= 15, `node ${node}: ${ink.n} pixels of the old solver's path in a ${ink.w}-px picture`);
    }
    await page.locator('#level-a').screenshot({ path: path.join(OUT, '09-old-path-node-320.png') });
  });

  await test('on a phone (390×844) the first screen shows a mesh, the charts have height, the legend is whole', async () => {
    const phone = await browser.newContext({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 3, isMobile: true, hasTouch: true });
    const p8 = await phone.newPage();
    watch(p8, 'phone');
    await p8.goto(`${server.base}#sample=plate-tri-tangled&passes=2`);
    await idle(p8);
    const box = await p8.locator('#mesh-a').boundingBox();
    check(box.y + box.height / 2 < 844, `the old mesh starts at ${box.y} px, below the first screen`);
    check(!/left|right/.test(await p8.textContent('.lede')), 'the intro says left/right');
    await shot(p8, '10-phone-first-screen', false);
    await p8.click('#run');
    await p8.waitForFunction(() => /2 passes done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(p8);
    for (const id of ['pass-chart', 'hist-a', 'hist-b']) {
      const b = await p8.locator(`#${id}`).boundingBox();
      check(b.height >= 250, `${id} is ${b.height} px high`);
    }
    // nothing inked in the canvas's last pixel columns: the legend ends inside it
    const edge = await p8.evaluate(() => {
      const c = document.getElementById('mesh-a');
      const d = c.getContext('2d').getImageData(c.width - 4, 0, 4, c.height).data;
      let dark = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 200 || d[i + 1] < 200 || d[i + 2] < 200) dark++;
      return dark;
    });
    check(edge === 0, `${edge} dark pixels at the right edge of the mesh canvas`);
    await shot(p8, '10-phone-after-run', false);
    await p8.locator('.pass-view').screenshot({ path: path.join(OUT, '11-phone-charts.png') });
    // a tap reaches a node a finger covers
    const t = await p8.evaluate(() => window.smoothlab.pickRadius({ pointerType: 'touch' }));
    check(t >= 20, `touch reach ${t}`);
    await phone.close();
  });

  await test('the README\'s 520×760 iframe holds the whole embed, without scrolling', async () => {
    const host = await context.newPage();
    watch(host, 'iframe host');
    await host.setViewportSize({ width: 1280, height: 900 });
    await host.setContent(`<iframe id="f" src="${server.base}?embed=1#sample=plate-tri-tangled&strategy=rules&order=priority&passes=3" width="520" height="760" style="border:0"></iframe>`);
    const frame = await (await host.$('#f')).contentFrame();
    await frame.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
    const fit = await frame.evaluate(() => ({ h: document.documentElement.scrollHeight, inner: window.innerHeight, w: document.documentElement.scrollWidth, iw: window.innerWidth }));
    check(fit.h <= fit.inner && fit.w <= fit.iw, `the embed is ${fit.w}×${fit.h} in a ${fit.iw}×${fit.inner} frame`);
    check((await frame.locator('#mesh-b').boundingBox()).height > 150, 'the meshes are still of a useful size');
    await host.locator('#f').screenshot({ path: path.join(OUT, '12-embed-iframe-520.png') });
    await host.close();
  });

  await test('the tables compare what the papers judge by, the better side marked', async () => {
    await open(page, `${server.base}#sample=plate-tri-tangled&passes=3`);
    await page.click('#run');
    await page.waitForFunction(() => /3 passes done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const rows = ['inverted', 'min_angle', 'max_angle', 'min_quality', 'mean_quality', 'small_angles', 'max_condition'];
    const dirs = { inverted: 'lower', min_angle: 'higher', max_angle: 'lower', min_quality: 'higher', mean_quality: 'higher', small_angles: 'lower', max_condition: 'lower' };
    const cells = await page.evaluate((rows) => {
      const out = {};
      for (const key of rows) {
        out[key] = ['a', 'b'].map((side) => {
          const td = document.querySelector(`#stats-${side} tr[data-stat="${key}"] td`);
          return td && { text: td.textContent, value: td.dataset.value, better: td.classList.contains('better') };
        });
      }
      return out;
    }, rows);
    let marked = 0;
    for (const key of rows) {
      const [a, b] = cells[key];
      check(a && b && a.value !== undefined && b.value !== undefined, `row ${key} is missing: ${JSON.stringify(cells[key])}`);
      const [va, vb] = [Number(a.value), Number(b.value)];
      const want = va === vb ? null : (dirs[key] === 'higher') === va > vb ? 0 : 1;
      check(a.better === (want === 0) && b.better === (want === 1), `row ${key}: A ${va}, B ${vb}, marks ${a.better}/${b.better}`);
      marked += want === null ? 0 : 1;
    }
    check(marked >= 4, `only ${marked} rows mark a better side`);
    // after 3 passes on the tangled plate, B (new) has no inverted element and the better mean quality
    check(cells.inverted[1].value === '0', `B inverted ${cells.inverted[1].value}`);
    check(cells.mean_quality[1].better, 'B has the better mean quality');
    check(/%$/.test(cells.small_angles[0].text), cells.small_angles[0].text);
    check(/better/.test(await page.getAttribute('#stats-b tr[data-stat="mean_quality"] td', 'aria-label')), 'the mark is said to screen readers');
    await page.locator('main.panels').screenshot({ path: path.join(OUT, '13-tables-compared.png') });
  });

  await test('one colour per side in every chart; histograms share a scale, with a log option; the angle chart is broken', async () => {
    const ink = (id) => page.evaluate(({ id, rgb }) => {
      const c = document.getElementById(id);
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      const n = rgb.map(() => 0);
      for (let i = 0; i < d.length; i += 4) {
        rgb.forEach(([r, g, b], k) => {
          if (d[i] === r && d[i + 1] === g && d[i + 2] === b) n[k] += 1;
        });
      }
      return n;
    }, { id, rgb: sideRgb });
    const sideRgb = await page.evaluate(() => ['--side-a', '--side-b'].map((v) => getComputedStyle(document.documentElement).getPropertyValue(v).match(/\d+/g).map(Number)));
    check(JSON.stringify(sideRgb[0]) !== JSON.stringify(sideRgb[1]), `the sides share a colour ${JSON.stringify(sideRgb)}`);
    const [ho, hn, pc] = [await ink('hist-a'), await ink('hist-b'), await ink('pass-chart')];
    check(ho[0] > 50 && ho[1] === 0, `A's histogram in A's colour only: ${ho}`);
    check(hn[1] > 50 && hn[0] === 0, `B's histogram in B's colour only: ${hn}`);
    check(pc[0] > 50 && pc[1] > 50, `the pass chart shows both colours: ${pc}`);
    // the panel headings carry the same colours
    const border = await page.evaluate(() => ['title-a', 'title-b'].map((id) => getComputedStyle(document.getElementById(id)).borderLeftColor));
    check(border[0] === `rgb(${sideRgb[0].join(', ')})` && border[1] === `rgb(${sideRgb[1].join(', ')})`, `headings ${border}`);
    // both histograms are drawn on one scale: the same y-axis labels, so the same pixels
    // left of the plot; the log option redraws both
    const axis = (id) => page.evaluate((id) => {
      const c = document.getElementById(id);
      const k = c.width / c.clientWidth;
      return Array.from(c.getContext('2d').getImageData(0, 0, Math.round(56 * k), c.height).data).join(',');
    }, id);
    check((await axis('hist-a')) === (await axis('hist-b')), 'the two histograms have different y axes');
    const before = await canvasInfo(page, 'hist-a');
    await page.check('#hist-log');
    await idle(page);
    check((await canvasInfo(page, 'hist-a')).hash !== before.hash, 'the log scale changed nothing');
    check((await axis('hist-a')) === (await axis('hist-b')), 'on the log scale the axes differ');
    await page.locator('.pass-view').screenshot({ path: path.join(OUT, '14-charts-log-broken-axis.png') });
    await page.uncheck('#hist-log');
    await idle(page);
  });

  await test('compare A with B: any objective on either side, a penalty for new, carried in the link', async () => {
    await open(page, `${server.base}#sample=plate-tri-tangled&passes=1`);
    const menu = await page.evaluate(() => [...document.getElementById('objective-a').options].map((o) => o.value));
    for (const name of ['old', 'sine', 'new', 'condition', 'untangle']) check(menu.includes(name), `A offers no ${name}: ${menu}`);
    check(await page.isDisabled('#penalty-a'), 'A runs old by default: no penalty');
    check(/only the new objective/.test(await page.textContent('#penalty-a-why')), 'the reason is said');
    check(!(await page.isDisabled('#penalty-b')), 'B runs new: its penalty is chosen');
    await unfold(page);
    await page.selectOption('#objective-a', 'sine');
    await idle(page);
    await unfold(page);
    await page.selectOption('#penalty-b', 'angle');
    await idle(page);
    check(/^A: sine/.test(await page.textContent('#title-a')), await page.textContent('#title-a'));
    check(/angle penalty/.test(await page.textContent('#title-b')), await page.textContent('#title-b'));
    const hash = await page.evaluate(() => location.hash);
    check(hash.includes('a=sine') && hash.includes('b=new&b-penalty=angle') && !hash.includes('a-penalty'), hash);
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    // the panels smoothed differently from old vs new-barrier: compare with that run
    const sineAngle = [await stats(page, 'a'), await stats(page, 'b')];
    await open(page, `${server.base}#sample=plate-tri-tangled&passes=1`);
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const oldNew = [await stats(page, 'a'), await stats(page, 'b')];
    check(sineAngle[0].min_angle !== oldNew[0].min_angle || sineAngle[0].min_quality !== oldNew[0].min_quality, 'A ran the same objective');
    check(sineAngle[1].min_angle !== oldNew[1].min_angle || sineAngle[1].mean_quality !== oldNew[1].mean_quality, 'B ran the same penalty');
    // the link reopens the comparison
    await open(page, `${server.base}${hash}`);
    check((await page.inputValue('#objective-a')) === 'sine' && (await page.inputValue('#penalty-b')) === 'angle', 'the link lost the comparison');
    check(/^A: sine/.test(await page.textContent('#title-a')), 'the heading after the link');
    // an old link naming 'objective' still opens, as B's
    await open(page, `${server.base}#sample=plate-tri&objective=condition`);
    check((await page.inputValue('#objective-b')) === 'condition', 'objective= is read as B');
    // a penalty for a side that has none is refused, saying why
    await open(page, `${server.base}#sample=plate-tri&a=old&a-penalty=angle`);
    check(/only when 'a' is new/.test(await page.textContent('#message')), await page.textContent('#message'));
    await open(page, `${server.base}#sample=plate-tri-tangled&passes=3`);
  });

  await test('a mesh from a tilted 3D plane is exported in its own plane, not flattened', async () => {
    // a 4 × 4 grid in the plane through (1, -2, 3) along (0.6, 0, 0.8) and (0, 1, 0.3)
    const v = [];
    const f = [];
    for (let j = 0; j < 4; j++) {
      for (let i = 0; i < 4; i++) {
        const t = i > 0 && i < 3 && j > 0 && j < 3 ? 0.2 : 0;
        const [a, b] = [i + t, j - t];
        v.push([1 + 0.6 * a, -2 + b, 3 + 0.8 * a + 0.3 * b]);
      }
    }
    for (let j = 0; j < 3; j++) for (let i = 0; i < 3; i++) {
      const k = j * 4 + i + 1;
      f.push(`f ${k} ${k + 1} ${k + 5}`, `f ${k} ${k + 5} ${k + 4}`);
    }
    const obj = `${v.map((p) => `v ${p.join(' ')}`).join('\n')}\n${f.join('\n')}\n`;
    await page.setInputFiles('#file', { name: 'tilted.obj', mimeType: 'text/plain', buffer: Buffer.from(obj) });
    await page.waitForFunction(() => /Loaded tilted\.obj/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('button[data-export="vtk"][data-side="b"]')]);
    const lines = readFileSync(await dl.path(), 'utf8').split('\n');
    const at = lines.findIndex((l) => l.startsWith('POINTS'));
    const pts = lines.slice(at + 1, at + 17).map((l) => l.trim().split(/\s+/).map(Number));
    // every point lies in the plane: its normal (0.6, 0, 0.8) × (0, 1, 0.3) through (1, -2, 3)
    const n = [0 * 0.3 - 0.8 * 1, 0.8 * 0 - 0.6 * 0.3, 0.6 * 1 - 0];
    const len = Math.hypot(...n);
    for (const p of pts) {
      const d = ((p[0] - 1) * n[0] + (p[1] + 2) * n[1] + (p[2] - 3) * n[2]) / len;
      check(Math.abs(d) < 1e-9, `a point ${p} is ${d} off the plane`);
    }
    check(pts.some((p) => Math.abs(p[2]) > 1), 'the points were flattened to z = 0');
    // the fixed corners are where they were
    for (const k of [0, 3, 12, 15]) check(Math.hypot(...pts[k].map((c, i) => c - v[k][i])) < 1e-9, `corner ${k} moved: ${pts[k]}`);
  });

  // ---- for teaching material ------------------------------------------------------------
  /** A host page with the embed in an iframe of `w × h`; returns the host and the frame. */
  async function embedIn(query, hash, w, h) {
    const host = await context.newPage();
    watch(host, `iframe ${query}`);
    await host.setContent(`<iframe id="f" src="${server.base}?${query}${hash}" width="${w}" height="${h}" style="border:0"></iframe>`);
    const frame = await (await host.$('#f')).contentFrame();
    await frame.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
    return { host, frame };
  }
  /** The README's embedded views: each in a 520-px iframe of the height the README gives. */
  const EMBED_VIEWS = [
    ['mesh', 300, ['mesh-a', 'mesh-b']],
    ['levelset', 380, ['level-a', 'level-b']],
    ['compare', 540, ['mesh-a', 'mesh-b']],
    ['history', 420, ['pass-chart']],
    ['histogram', 280, ['hist-a', 'hist-b']],
  ];

  await test('embed=1&view=…: each view alone fills its 520-px frame, with the settings of the hash', async () => {
    const hash = '#sample=plate-tri-tangled&strategy=rules&order=priority&passes=3';
    for (const [view, h, canvases] of EMBED_VIEWS) {
      const { host, frame } = await embedIn(`embed=1&view=${view}`, hash, 520, h);
      const fit = await frame.evaluate(() => ({ h: document.documentElement.scrollHeight, inner: window.innerHeight, w: document.documentElement.scrollWidth, iw: window.innerWidth }));
      check(fit.h <= fit.inner && fit.w <= fit.iw, `${view}: ${fit.w}×${fit.h} in a ${fit.iw}×${fit.inner} frame`);
      for (const id of canvases) {
        const box = await frame.locator(`#${id}`).boundingBox();
        check(box && box.height >= 100 && box.width >= 200, `${view}: #${id} is ${JSON.stringify(box)}`);
        if (view !== 'compare') check(box.y + box.height >= h - 30, `${view}: #${id} ends at ${box.y + box.height} of ${h}: the view does not fill its frame`);
        check((await canvasInfo(frame, id)).colours > 8, `${view}: #${id} looks blank`);
      }
      for (const sel of ['.controls', '.load', '.foot']) check(!(await frame.isVisible(sel)), `${view}: ${sel} is shown`);
      const others = ['mesh-b', 'level-b', 'pass-chart', 'hist-b', 'solve-chart'].filter((id) => !canvases.includes(id));
      for (const id of others) check(!(await frame.isVisible(`#${id}`)), `${view}: #${id} is shown too`);
      const run = await frame.evaluate(() => window.smoothlab.metrics.run);
      if (['compare', 'history', 'histogram'].includes(view)) check(run && run.done === 3, `${view}: ran ${JSON.stringify(run && run.done)} of the hash's 3 passes`);
      else check(run === null, `${view}: ran passes the view does not show`);
      if (view === 'levelset') check(/^\d+$/.test(await frame.inputValue('#node')), 'the level sets of a node (the worst one when the hash names none)');
      if (view === 'compare') {
        const t = await frame.locator('#stats-b').boundingBox();
        check(t && t.y + t.height >= h - 40, `the compare view keeps its tables, down to the frame's foot: ${JSON.stringify(t)}`);
      }
      await host.locator('#f').screenshot({ path: path.join(OUT, `20-embed-${view}-520.png`) });
      await host.close();
    }
    // the hash's node, and a view it does not know said in words
    const { host, frame } = await embedIn('embed=1&view=levelset', '#sample=plate-tri&node=40', 520, 300);
    check((await frame.inputValue('#node')) === '40', 'the hash\'s node');
    await host.close();
    const bad = await embedIn('embed=1&view=mesh3d', '#sample=plate-tri', 520, 760);
    check(/view=mesh3d: an embed shows one of the views mesh, levelset, compare, history, histogram/.test(await bad.frame.textContent('#message')), 'an unknown view is named');
    await bad.host.close();
  });

  await test('zoom and pan: wheel, drag on empty space and a pinch on the meshes and the level sets; double-click fits again', async () => {
    await open(page, `${server.base}#sample=plate-tri`);
    // the meshes at the size the settings leave them (a chosen node widens its column)
    await page.click('#tabbtn-settings');
    await idle(page);
    await page.locator('#mesh-b').scrollIntoViewIfNeeded();
    const fitted = await canvasInfo(page, 'mesh-b');
    const box = await page.locator('#mesh-b').boundingBox();
    await page.mouse.move(box.x + box.width * 0.3, box.y + box.height * 0.3);
    await page.mouse.wheel(0, -600);
    await idle(page);
    const zoomed = await canvasInfo(page, 'mesh-b');
    check(zoomed.hash !== fitted.hash, 'the wheel changed nothing');
    check((await canvasInfo(page, 'mesh-a')).hash !== fitted.hash, 'both meshes zoom');
    // a drag from the hole (no node there) pans, choosing no node
    const hole = { x: box.x + box.width * 0.5, y: box.y + box.height * 0.5 };
    // the hole's centre, (0.5, 0.5) fitted, is at 0.3 + 0.2 × the zoom after the wheel
    const z = Math.exp(600 * 0.0015);
    const inHole = { x: box.x + box.width * (0.3 + 0.2 * z), y: box.y + box.height * (0.3 + 0.2 * z) };
    await page.mouse.move(inHole.x, inHole.y);
    await page.mouse.down();
    await page.mouse.move(inHole.x - 60, inHole.y - 40, { steps: 6 });
    await page.mouse.up();
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash !== zoomed.hash, 'a drag on empty space did not pan');
    check((await page.inputValue('#node')) === '', 'a pan chose a node');
    check(await page.isHidden('#pick-note'), 'a pan is not a missed press');
    // nodes are still chosen and dragged through the zoomed view
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    check(hit.node >= 0, 'a node chosen on the zoomed mesh');
    await page.click('#tabbtn-settings');
    await idle(page);
    await page.mouse.dblclick(hole.x, hole.y);
    await idle(page);
    const refit = await canvasInfo(page, 'mesh-b');
    // the chosen node is highlighted now: compare with that picture fitted
    await page.fill('#node', '');
    await page.dispatchEvent('#node', 'change');
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash === fitted.hash, 'a double-click fits the meshes again exactly');
    check(refit.hash !== zoomed.hash, 'double-click');
    // the level sets
    await page.fill('#node', String(hit.node));
    await page.dispatchEvent('#node', 'change');
    await idle(page);
    await page.locator('#level-b').scrollIntoViewIfNeeded();
    const lv = [await canvasInfo(page, 'level-a'), await canvasInfo(page, 'level-b')];
    const lb = await page.locator('#level-b').boundingBox();
    await page.mouse.move(lb.x + lb.width / 2, lb.y + lb.height * 0.6);
    await page.mouse.wheel(0, -500);
    await idle(page);
    const lz = [await canvasInfo(page, 'level-a'), await canvasInfo(page, 'level-b')];
    check(lz[0].hash !== lv[0].hash && lz[1].hash !== lv[1].hash, 'both level sets zoom');
    await page.mouse.move(lb.x + lb.width / 2, lb.y + lb.height * 0.6);
    await page.mouse.down();
    await page.mouse.move(lb.x + lb.width / 2 + 40, lb.y + lb.height * 0.6 + 20, { steps: 4 });
    await page.mouse.up();
    await idle(page);
    check((await canvasInfo(page, 'level-b')).hash !== lz[1].hash, 'a drag pans the level sets');
    await page.mouse.dblclick(lb.x + lb.width / 2, lb.y + lb.height / 2);
    await idle(page);
    check((await canvasInfo(page, 'level-b')).hash === lv[1].hash, 'a double-click fits the level sets again');
    await shot(page, '21-zoom-level-sets');
    // a pinch of two fingers on a touch screen zooms the meshes
    const phone = await browser.newContext({ viewport: { width: 390, height: 844 }, deviceScaleFactor: 2, isMobile: true, hasTouch: true });
    const p = await phone.newPage();
    watch(p, 'pinch');
    await p.goto(`${server.base}#sample=plate-tri`);
    await idle(p);
    const before = await canvasInfo(p, 'mesh-a');
    const b = await p.locator('#mesh-a').boundingBox();
    const cdp = await phone.newCDPSession(p);
    const cx = b.x + b.width / 2;
    const cy = b.y + b.height / 2;
    const fingers = (d) => [{ x: cx - d, y: cy, id: 1 }, { x: cx + d, y: cy, id: 2 }];
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchStart', touchPoints: fingers(20) });
    for (const d of [30, 45, 60, 80]) await cdp.send('Input.dispatchTouchEvent', { type: 'touchMove', touchPoints: fingers(d) });
    await cdp.send('Input.dispatchTouchEvent', { type: 'touchEnd', touchPoints: [] });
    await idle(p);
    check((await canvasInfo(p, 'mesh-a')).hash !== before.hash, 'a pinch did not zoom');
    check((await p.inputValue('#node')) === '', 'a pinch chose a node');
    await shot(p, '24-phone-pinched-390', false);
    await phone.close();
  });

  await test('undo takes back a drag, by the button and by Ctrl+Z', async () => {
    await open(page, `${server.base}#sample=plate-quad`);
    check(await page.isDisabled('#undo'), 'nothing to undo at first');
    const hit = await clickSomeNode(page, 'mesh-a', ringPoints());
    await idle(page);
    const before = [await canvasInfo(page, 'mesh-a'), await canvasInfo(page, 'mesh-b'), await stats(page, 'b')];
    let at = { x: hit.x, y: hit.y };
    const drag = async (dx, dy) => {
      await page.mouse.move(at.x, at.y);
      await page.mouse.down();
      await page.mouse.move(at.x + dx, at.y + dy, { steps: 6 });
      await page.mouse.up();
      await idle(page);
      at = { x: at.x + dx, y: at.y + dy };
    };
    await drag(18, 12);
    check((await canvasInfo(page, 'mesh-b')).hash !== before[1].hash, 'the drag moved nothing');
    check(!(await page.isDisabled('#undo')), 'Undo is offered');
    check(new RegExp(`node ${hit.node}`).test(await page.textContent('#undo')), await page.textContent('#undo'));
    await page.click('#undo');
    await idle(page);
    check((await canvasInfo(page, 'mesh-a')).hash === before[0].hash && (await canvasInfo(page, 'mesh-b')).hash === before[1].hash, 'the button put the node back exactly');
    check(JSON.stringify(await stats(page, 'b')) === JSON.stringify(before[2]), 'the table as before');
    check(await page.isDisabled('#undo'), 'nothing left to undo');
    at = { x: hit.x, y: hit.y };
    await drag(-14, 9);
    await drag(10, -16);
    await page.locator('#mesh-b').focus();
    await page.keyboard.press('Control+z');
    await idle(page);
    await page.keyboard.press('Control+z');
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash === before[1].hash, 'Ctrl+Z twice took back both drags');
    await drag(12, 12);
    await page.click('#step');
    await idle(page);
    check(await page.isDisabled('#undo'), 'a pass ends what undo can take back');
  });

  await test('Smooth this node: one solver call on the chosen node, its history shown, undoable', async () => {
    await open(page, `${server.base}#sample=plate-tri&perturbed=1&tangle=0.4&seed=3`);
    check(await page.isDisabled('#smooth-node'), 'no node, nothing to smooth');
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    await idle(page);
    const before = await canvasInfo(page, 'mesh-b');
    const summary = await page.textContent('#node-hint');
    await page.click('#smooth-node');
    await idle(page);
    const hint = await page.textContent('#node-hint');
    check(new RegExp(`One solver call on each side moved node ${hit.node}`).test(hint), hint);
    check(hint.includes(summary), `the history shown is the call's: ${hint} vs ${summary}`);
    check((await canvasInfo(page, 'mesh-b')).hash !== before.hash, 'the node did not move');
    // from where it is now, the solve has little left to do
    const m = /B, .* \(\w+ is better\): (-?[\d.]+) → (-?[\d.]+)/.exec(hint);
    check(m, hint);
    await page.fill('#node', String(hit.node));
    await page.dispatchEvent('#node', 'change');
    await idle(page);
    const again = /B, .* \(\w+ is better\): (-?[\d.]+) →/.exec(await page.textContent('#node-hint'));
    check(Math.abs(Number(again[1]) - Number(m[2])) < 1e-3, `B starts where the call ended: ${again[1]} vs ${m[2]}`);
    await page.click('#undo');
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash === before.hash, 'undo puts the node back');
    await shot(page, '22-smooth-this-node');
    await page.locator('.node-view').scrollIntoViewIfNeeded();
    await shot(page, '22-smooth-this-node-1280', false);
  });

  await test('Save figure: A | B with titles, colour bar and statistics at the chosen size and pixel ratio', async () => {
    await open(page, `${server.base}#sample=plate-tri-tangled&passes=2`);
    await page.click('#run');
    await page.waitForFunction(() => /2 passes done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    await page.fill('#figure-w', '800');
    await page.fill('#figure-h', '450');
    await page.selectOption('#figure-dpr', '2');
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('#save-figure')]);
    const bytes = readFileSync(await dl.path());
    check(bytes.subarray(1, 4).toString() === 'PNG', 'a PNG');
    const [w, h] = [bytes.readUInt32BE(16), bytes.readUInt32BE(20)];
    check(w === 1600 && h === 900, `the figure is ${w}×${h}`);
    check(/_figure_800x450@2x\.png$/.test(dl.suggestedFilename()), dl.suggestedFilename());
    check(/1600 × 900 pixels/.test(await page.textContent('#figure-note')), await page.textContent('#figure-note'));
    // drawn by the core (the picture the command-line tool's compare view draws): shown here to be looked at
    const info = await page.evaluate(async (b64) => {
      const img = new Image();
      img.src = `data:image/png;base64,${b64}`;
      await img.decode();
      const c = document.createElement('canvas');
      c.width = img.width;
      c.height = img.height;
      const g = c.getContext('2d');
      g.drawImage(img, 0, 0);
      const half = (x0) => {
        const d = g.getImageData(x0, 60, img.width / 2 - 80, img.height - 200).data;
        const s = new Set();
        for (let i = 0; i < d.length; i += 16) s.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
        return s.size;
      };
      return { left: half(0), right: half(img.width / 2) };
    }, bytes.toString('base64'));
    check(info.left > 20 && info.right > 20, `both meshes drawn: ${JSON.stringify(info)}`);
    await page.fill('#figure-w', 'wide');
    await page.click('#save-figure');
    await idle(page);
    check(/Figure: give its width and height in whole pixels/.test(await page.textContent('#message')), await page.textContent('#message'));
    await page.fill('#figure-w', '3000');
    await page.click('#save-figure');
    await idle(page);
    check(/give 1 to 4096 on each side/.test(await page.textContent('#message')), await page.textContent('#message'));
  });

  await test('help panel and tooltips; canvases focusable; arrow keys move the chosen node; every Save PNG has its own name', async () => {
    await open(page, `${server.base}#sample=plate-tri`);
    await page.click('#help summary');
    const help = await page.textContent('#help');
    for (const term of ['α', 'β', 'κ', 'Inverted element', 'C1, C2, C3', "Chen's rules", 'Priority order', 'Level set']) check(help.includes(term), `the help says nothing of ${term}`);
    const papers = await page.$$eval('#help a', (as) => as.map((a) => a.textContent));
    check(papers.length === 3 && /Chen/.test(papers[0]) && /Freitag/.test(papers[1]) && /Knupp/.test(papers[2]), `papers: ${papers}`);
    await page.locator('#help').screenshot({ path: path.join(OUT, '23-help.png') });
    await page.click('#help summary');
    // tooltips on the terms where they are used
    for (const sel of ['#stats-b tr[data-stat="inverted"] th', '#stats-b tr[data-stat="max_condition"] th', '#stats-b tr[data-stat="min_quality"] th', '#strategy option[value="c1"]', '#strategy option[value="rules"]', '#order option[value="priority"]']) {
      const title = await page.getAttribute(sel, 'title');
      check(title && title.length > 20, `${sel} has no tooltip`);
    }
    // every canvas is reached by Tab
    const canvases = await page.$$eval('canvas', (cs) => cs.map((c) => [c.id, c.tabIndex]));
    check(canvases.every(([, t]) => t === 0), `canvases not focusable: ${JSON.stringify(canvases)}`);
    // the buttons that save something each have a name of their own
    const names = await page.$$eval('button[data-png], button[data-export]', (bs) => bs.map((b) => b.getAttribute('aria-label') || b.textContent));
    check(new Set(names).size === names.length && names.every((n) => /Save/.test(n)), `names: ${names.join(' | ')}`);
    check((await page.locator('button[data-png="hist-b"]').getAttribute('aria-label')) === "Save PNG of B's angle histogram", 'the histogram B button');
    // arrow keys: nothing chosen says so; a chosen node moves, and Ctrl+Z takes it back
    await page.locator('#mesh-b').focus();
    await page.keyboard.press('ArrowRight');
    check(/arrow keys move the chosen node/.test(await page.textContent('#pick-note')), await page.textContent('#pick-note'));
    const hit = await clickSomeNode(page, 'mesh-b', ringPoints());
    const before = await canvasInfo(page, 'mesh-b');
    await page.locator('#mesh-b').focus();
    const scroll = await page.evaluate(() => window.scrollY);
    await page.keyboard.press('Shift+ArrowUp');
    await idle(page);
    await page.keyboard.press('ArrowLeft');
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash !== before.hash, 'the arrow keys moved nothing');
    check(await page.evaluate(() => window.scrollY) === scroll, 'the page scrolled under the arrow keys');
    check(new RegExp(`Node ${hit.node} moved 1 px left`).test(await page.textContent('#status')), await page.textContent('#status'));
    await page.keyboard.press('Control+z');
    await idle(page);
    await page.keyboard.press('Control+z');
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash === before.hash, 'Ctrl+Z took back the two key moves');
  });

  // the figures tour (issue 13): every figure opens by its link, in its state, with its views drawn
  const FIGURES = ['chen-2', 'chen-6', 'chen-9', 'chen-10', 'chen-11', 'chen-13', 'chen-16', 'chen-20', 'freitag-t1', 'freitag-3', 'knupp-1'];
  /** Opens `#figure=NAME` (a fresh load) and waits until its passes ran and its table filled. */
  async function openFigure(p, name, query = '') {
    await p.goto(`${server.base}${query || `?open=${name}`}#figure=${name}`);
    await p.waitForFunction((n) => document.body.dataset.figure === n && document.body.dataset.busy === '0', name, { timeout: 4 * TIMEOUT });
    await idle(p);
    return p.evaluate(() => window.smoothlab.figure());
  }
  for (const name of FIGURES) {
    await test(`#figure=${name} opens its state, its picture and its view`, async () => {
      const card = await openFigure(page, name);
      check(card && card.name === name, `card: ${JSON.stringify(card)}`);
      check(page.url().endsWith(`#figure=${name}`), `the address keeps the figure: ${page.url()}`);
      const text = await page.textContent('#tour-text');
      check(/\d/.test(await page.textContent('#tour-measured')) && text.length > 200, `text: ${text}`);
      check((await page.textContent('#tour-title')).includes(card.source), 'title');
      check((await page.textContent('#tour-caption')).length > 10, 'caption');
      if (card.rows) {
        // a table figure shows its table once: the live table, not also a picture of it
        check(await page.locator('#tour-picture').isHidden(), 'the table is shown twice');
      } else {
        const pic = await canvasInfo(page, 'tour-picture');
        check(pic.colours > 50 && pic.w > 400, `the figure's picture looks blank (${pic.colours} colours, ${pic.w} px)`);
      }
      const hash = new URLSearchParams(card.hash);
      check((await page.inputValue('#sample')) === `sample:${hash.get('sample')}`, `sample ${await page.inputValue('#sample')}`);
      for (const [key, id] of [['strategy', 'strategy'], ['a', 'objective-a'], ['b', 'objective-b']]) {
        if (hash.has(key)) check((await page.inputValue(`#${id}`)) === hash.get(key), `${id}: ${await page.inputValue(`#${id}`)}`);
      }
      if (hash.has('node')) {
        check((await page.inputValue('#node')) === hash.get('node'), `node selected: '${await page.inputValue('#node')}'`);
        for (const id of ['level-a', 'level-b', 'solve-chart']) {
          const c = await canvasInfo(page, id);
          check(c.colours > 100, `${id} looks blank (${c.colours} colours)`);
        }
      }
      const s = [await stats(page, 'a'), await stats(page, 'b')];
      const passes = card.run ? hash.get('passes') || '3' : '0';
      check(s[0].passes === passes && s[1].passes === passes, `passes run: ${s[0].passes}/${s[1].passes}, want ${passes}`);
      for (const id of ['mesh-a', 'mesh-b', 'pass-chart', 'hist-a', 'hist-b']) {
        const c = await canvasInfo(page, id);
        check(c.colours > 8, `${id} looks blank (${c.colours} colours)`);
      }
      if (card.rows) {
        const rows = await page.$$eval('#tour-rows tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
        check(rows.length === card.rows, `table rows: ${rows.length} of ${card.rows}`);
        check(rows.every((r) => r.length === 8 && /\d/.test(r[1]) && /\[/.test(r[5])), `rows: ${JSON.stringify(rows)}`);
        check(rows.some((r) => /18\.20/.test(r[7])), 'Freitag\'s numbers beside ours');
      }
      if (name === 'chen-13' || name === 'knupp-1') check(s[1].inverted === '0', `the new side is untangled: ${s[1].inverted}`);
      await page.locator('#tour').screenshot({ path: path.join(OUT, `figure-${name}.png`) });
      const view = { levelset: '.node-view', compare: '.panels', history: '.pass-view', histogram: '.pass-view' }[card.view];
      await page.locator(view).screenshot({ path: path.join(OUT, `figure-${name}-view.png`) });
    });
  }

  await test('the tour: Next and Previous walk it, the menu jumps, Back returns, the header links it', async () => {
    await openFigure(page, 'chen-10');
    await page.click('#tour-next');
    await page.waitForFunction(() => document.body.dataset.figure === 'chen-11', null, { timeout: 2 * TIMEOUT });
    check(page.url().endsWith('#figure=chen-11'), page.url());
    await page.click('#tour-prev');
    await page.waitForFunction(() => document.body.dataset.figure === 'chen-10', null, { timeout: 2 * TIMEOUT });
    await page.selectOption('#tour-menu', 'knupp-hex');
    await page.waitForFunction(() => document.body.dataset.figure === 'knupp-hex', null, { timeout: 4 * TIMEOUT });
    await idle(page);
    check((await page.getAttribute('#tour-next', 'data-figure')) === 'chen-2', 'the tour wraps round');
    await page.goBack();
    await page.waitForFunction(() => document.body.dataset.figure === 'chen-10', null, { timeout: 2 * TIMEOUT });
    await idle(page);
    check((await page.getAttribute('#tour-open', 'href')) === '#figure=chen-2', 'the header links the tour');
    // an unknown figure: the page opens anyway and says which figures there are
    await page.goto(`${server.base}?open=none#figure=chen-99`);
    await idle(page);
    check(/no figure named 'chen-99'.*chen-2/.test(await page.textContent('#message')), await page.textContent('#message'));
    check((await canvasInfo(page, 'mesh-b')).colours > 8, 'the default mesh is drawn');
    await openFigure(page, 'chen-2');
    await page.click('#tour-close');
    await idle(page);
    check(await page.locator('#tour').isHidden(), 'the tour closes');
    check(!page.url().includes('figure='), `closed, the address is the playground's: ${page.url()}`);
  });

  await test('?embed=1#figure=NAME embeds one figure: its words and its picture in a 520-px frame, Live view its view', async () => {
    const frame = await context.newPage();
    watch(frame, 'embed-figure');
    await frame.setViewportSize({ width: 520, height: 760 });
    for (const [name, canvases] of [['chen-10', ['level-a', 'level-b']], ['freitag-3', ['hist-a', 'hist-b']], ['knupp-1', ['mesh-a', 'mesh-b']]]) {
      await openFigure(frame, name, '?embed=1');
      check(await frame.evaluate(() => document.body.classList.contains('embed') && document.body.classList.contains('view')), 'an embedded view');
      check(await frame.locator('#tour').isVisible(), 'the figure is shown');
      check((await canvasInfo(frame, 'tour-picture')).colours > 50, 'its picture');
      for (const id of canvases) check(!(await frame.locator(`#${id}`).isVisible()), `${id} is shown before Live view`);
      await frame.screenshot({ path: path.join(OUT, `figure-embed-${name}-520.png`) });
      // Live view: the view the figure was made from, in its place
      await frame.click('#figure-live');
      await idle(frame);
      check(!(await frame.locator('#tour-picture').isVisible()), 'the picture stays beside the live view');
      for (const id of canvases) {
        check(await frame.locator(`#${id}`).isVisible(), `${id} is shown`);
        check((await canvasInfo(frame, id)).colours > 8, `${id} looks blank`);
      }
      check(await frame.evaluate(() => document.documentElement.scrollHeight <= window.innerHeight), `${name}: the live view scrolls`);
      await frame.screenshot({ path: path.join(OUT, `figure-embed-${name}-520-live.png`) });
      await frame.click('#figure-live');
      await idle(frame);
    }
    await frame.close();
  });

  // ---- surfaces in 3D ------------------------------------------------------------------
  /** Waits until a canvas's pixels differ from `before` (the engine draws in a worker). */
  async function changed(page, id, before) {
    for (let i = 0; i < 100; i++) {
      await idle(page);
      const now = await canvasInfo(page, id);
      if (now.hash !== before.hash) return now;
      await page.waitForTimeout(50);
    }
    throw new Error(`${id} did not change`);
  }
  /** A 1280 × 900 screenshot of the first screen: the two views, the run bar and, in the
   * side column, the 3D note (a surface's, or the tetrahedra's with its cut). */
  async function panelsShot(page, name) {
    await page.evaluate(() => window.scrollTo(0, 0));
    await shot(page, name, false);
  }
  /** Steps until B has no inverted element (at most `max` passes); returns the passes taken. */
  async function stepUntilUntangled(page, max) {
    for (let i = 1; i <= max; i++) {
      await page.click('#step');
      await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(page);
      if ((await stats(page, 'b')).inverted === '0') return i;
    }
    throw new Error(`B is still tangled after ${max} passes: ${JSON.stringify(await stats(page, 'b'))}`);
  }

  await test('a tangled surface sample: 3D views turned by a drag and zoomed by the wheel, Step untangles, the export reads back as a surface', async () => {
    await open(page, server.base);
    await chooseSample(page, 'sample:sphere-tangled');
    check(await page.evaluate(() => document.body.classList.contains('surface')), 'the page is in its surface mode');
    check(await page.locator('#surface-note').isVisible(), 'the surface note is shown');
    const s0 = await stats(page, 'b');
    check(Number(s0.inverted) > 0, `the sample is tangled: ${JSON.stringify(s0)}`);
    check(Number(s0.surface_distance) < 1e-9, `its nodes are on the sphere: ${s0.surface_distance}`);
    check(/^\d\.\d\de[-+]\d+$/.test(s0.surface_distance), `the distance row: ${s0.surface_distance}`);
    for (const id of ['node', 'save-figure', 'hist-log']) {
      check(await page.locator(`#${id}`).isEnabled(), `#${id} works for a surface`);
      check(!/^Not for/.test(await page.getAttribute(`#${id}`, 'title') ?? ''), `#${id} says it waits`);
    }
    check(await page.locator('#smooth-node').isDisabled() && await page.locator('#undo').isDisabled(), 'Smooth this node waits for a node, Undo for a move');
    check(/tangent plane/.test(await page.textContent('#node-hint')), 'the node view says where the level sets are drawn');
    check((await page.textContent('#permalink-note')) === '' && (await page.getAttribute('#permalink', 'href')).includes('#sample=sphere-tangled&'), 'the link carries the surface sample');
    const a0 = await canvasInfo(page, 'mesh-a');
    const b0 = await canvasInfo(page, 'mesh-b');
    check(a0.colours > 50 && b0.colours > 50, 'both sides are drawn shaded');
    await panelsShot(page, 'surface-sphere-loaded');

    // a drag on B turns both views (one camera), and chooses no node
    await page.locator('#mesh-b').scrollIntoViewIfNeeded();
    const box = await page.locator('#mesh-b').boundingBox();
    const [cx, cy] = [box.x + box.width / 2, box.y + box.height / 2];
    await page.mouse.move(cx, cy);
    await page.mouse.down();
    for (let k = 1; k <= 8; k++) await page.mouse.move(cx + 12 * k, cy + 4 * k);
    await page.mouse.up();
    const b1 = await changed(page, 'mesh-b', b0);
    const a1 = await changed(page, 'mesh-a', a0);
    check(await page.inputValue('#node') === '', 'a drag on a surface moves no node');
    // the wheel zooms in: the surface covers more of the canvas
    const ink = (id) => page.evaluate((id) => {
      const c = document.getElementById(id);
      const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
      let n = 0;
      for (let i = 0; i < d.length; i += 4) if (d[i] < 250 || d[i + 1] < 250 || d[i + 2] < 250) n++;
      return n;
    }, id);
    const before = await ink('mesh-a');
    await page.mouse.move(cx, cy);
    await page.mouse.wheel(0, -300);
    await changed(page, 'mesh-a', a1);
    await changed(page, 'mesh-b', b1);
    const after = await ink('mesh-a');
    check(after > 1.3 * before, `the wheel zooms in: ${before} → ${after} inked pixels`);
    // a double-click fits again: the first view's picture comes back exactly
    await page.dblclick('#mesh-a');
    await idle(page);
    await page.waitForTimeout(100);
    await idle(page);
    check((await canvasInfo(page, 'mesh-b')).hash === b0.hash, 'a double-click shows the starting view again');

    const passes = await stepUntilUntangled(page, 3);
    const s1 = await stats(page, 'b');
    check(s1.passes === String(passes) && Number(s1.surface_distance) < 1e-9, `after ${passes} passes: ${JSON.stringify(s1)}`);
    check(Number.parseFloat(s1.min_angle) > Number.parseFloat(s0.min_angle), `the smallest angle grows: ${s0.min_angle} → ${s1.min_angle}`);
    await panelsShot(page, 'surface-sphere-smoothed');
    await shot(page, 'surface-sphere-page');

    // the export is B's surface, in 3D, and the page reads it back as a surface
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('button[data-export="vtk"][data-side="b"]')]);
    const text = readFileSync(await dl.path(), 'utf8');
    const lines = text.split('\n');
    const at = lines.findIndex((l) => l.startsWith('POINTS'));
    const n = Number(lines[at].split(/\s+/)[1]);
    check(n === Number(s1.nodes), `${n} points, ${s1.nodes} nodes`);
    const pts = lines.slice(at + 1, at + 1 + n).map((l) => l.trim().split(/\s+/).map(Number));
    check(pts.every((p) => Math.abs(Math.hypot(...p) - 1) < 1e-9), 'every exported point is on the unit sphere');
    check(pts.filter((p) => Math.abs(p[2]) > 0.5).length > n / 4, 'the points keep their z');
    await page.setInputFiles('#file', { name: 'sphere_b.vtk', mimeType: 'text/plain', buffer: Buffer.from(text) });
    await page.waitForFunction(() => /Loaded sphere_b\.vtk/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const back = await stats(page, 'a');
    check(await page.evaluate(() => document.body.classList.contains('surface')), 'the export reads back as a surface');
    check(back.nodes === s1.nodes && back.inverted === '0' && back.min_angle === s1.min_angle, `read back: ${JSON.stringify(back)} vs ${JSON.stringify(s1)}`);

    // the other surface samples draw; a planar sample brings the planar page back
    for (const name of ['torus-tangled', 'cylinder-capped']) {
      await chooseSample(page, `sample:${name}`);
      check((await canvasInfo(page, 'mesh-a')).colours > 50, `${name} is drawn`);
      check(Number((await stats(page, 'a')).inverted) > 0, `${name} is tangled`);
      await panelsShot(page, `surface-${name}`);
    }
    await stepUntilUntangled(page, 3);
    await chooseSample(page, 'sample:plate-tri');
    check(!(await page.evaluate(() => document.body.classList.contains('surface'))), 'a planar sample leaves the surface mode');
    check(await page.locator('#surface-note').isHidden(), 'the surface note is hidden');
    check(!(await page.locator('#node').isDisabled()) && !(await page.locator('#save-figure').isDisabled()), 'the planar controls are back');
    check(!('surface_distance' in (await stats(page, 'a'))), 'a planar table has no distance from a surface');
  });

  await test('issue 32: a tangled surface file (a sphere tangled by 1.5 edges) untangles on the page as in the command-line tool', async () => {
    // the file as a user has it: generated, tangled and smoothed by the command-line tool
    const cli = (args) => spawnSync('cargo', ['run', '--quiet', '--bin', 'smoothlab', '--', ...args], { cwd: ROOT, encoding: 'utf8' });
    const dir = path.join(OUT, 'tangled-sphere');
    mkdirSync(dir, { recursive: true });
    const [sphere, tangled, smoothed] = ['sphere.vtk', 'sphere-tangled.vtk', 'sphere-smoothed.vtk'].map((f) => path.join(dir, f));
    for (const args of [['generate', 'sphere', '--kind', 'tri', '--resolution', '8', '-o', sphere],
      ['generate', 'perturb', sphere, '--amount', '1.5', '--seed', '2', '-o', tangled]]) {
      const r = cli(args);
      check(r.status === 0, `${args.join(' ')}: ${r.stderr}`);
    }
    const before = JSON.parse(cli(['stats', '--json', tangled]).stdout);
    // the page steps the passes; the tool's finish (max-min after them) is not a Step
    const r = cli(['smooth', tangled, '-o', smoothed, '--passes', '3', '--finish', '0', '--json']);
    check(r.status === 0, r.stderr);
    const report = JSON.parse(r.stdout);
    check(before.inverted > 100 && report.final.inverted === 0, `the command-line tool: ${before.inverted} → ${report.final.inverted}`);
    // the page reads the same file with the same fitted reference and the same counts
    await open(page, server.base);
    await page.setInputFiles('#file', tangled);
    await page.waitForFunction(() => /Loaded sphere-tangled\.vtk/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const s0 = await stats(page, 'b');
    check(Number(s0.inverted) === before.inverted, `inverted as loaded: the page ${s0.inverted}, the command-line tool ${before.inverted}`);
    // B is the command-line tool's defaults (new + rules, priority order): pass for pass the same
    for (const pass of report.passes) {
      await page.click('#step');
      await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(page);
      const s = await stats(page, 'b');
      const want = { inverted: String(pass.inverted), min_angle: `${pass.min_angle_deg.toFixed(2)}°`, max_angle: `${pass.max_angle_deg.toFixed(2)}°` };
      for (const key of Object.keys(want)) check(s[key] === want[key], `pass ${pass.pass}, ${key}: the page ${s[key]}, the command-line tool ${want[key]}`);
    }
    await panelsShot(page, 'surface-tangled-file-untangled');
  });

  await test("a Mesquite surface file (quads on a sphere) loads, turns, smooths and exports", async () => {
    const file = path.join(MESQUITE, 'quads', 'untangled', 'quads_on_sphere_529.vtk');
    if (!existsSync(file)) {
      check(!CI, `CI is set but the external Mesquite meshes (${MESQUITE}) are missing`);
      console.log('     external Mesquite meshes (../shared/meshes/mesquite) not found: skipped');
      return;
    }
    await page.setInputFiles('#file', file);
    await page.waitForFunction(() => /Loaded quads_on_sphere_529\.vtk/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    check(await page.evaluate(() => document.body.classList.contains('surface')), 'the file is a surface');
    const s0 = await stats(page, 'a');
    check(s0.elements === '529' && s0.inverted === '0', `529 quads, none inverted: ${JSON.stringify(s0)}`);
    const a0 = await canvasInfo(page, 'mesh-a');
    check(a0.colours > 50, 'the surface is drawn');
    await page.locator('#mesh-a').scrollIntoViewIfNeeded();
    const box = await page.locator('#mesh-a').boundingBox();
    await page.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
    await page.mouse.down();
    for (let k = 1; k <= 6; k++) await page.mouse.move(box.x + box.width / 2 - 10 * k, box.y + box.height / 2 - 6 * k);
    await page.mouse.up();
    await changed(page, 'mesh-a', a0);
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const s1 = await stats(page, 'b');
    check(s1.passes === '1' && s1.inverted === '0', `a pass: ${JSON.stringify(s1)}`);
    check(Number(s1.surface_distance) < 1e-6, `the nodes stay on the surface: ${s1.surface_distance}`);
    await panelsShot(page, 'surface-mesquite-quads-on-sphere');
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('button[data-export="msh"][data-side="b"]')]);
    const text = readFileSync(await dl.path(), 'utf8');
    check(/\$Nodes/.test(text) && /\$Elements/.test(text), 'a .msh file');
    const nodes = text.split('$Nodes')[1].split('$EndNodes')[0].trim().split('\n').slice(1).map((l) => l.trim().split(/\s+/).map(Number));
    check(nodes.length === Number(s0.nodes) && nodes.some((p) => Math.abs(p[3]) > 0.1), 'the nodes keep their z');
    // Perturb moves the nodes in their tangent planes, on the surface, and starts both sides again
    const b1 = await canvasInfo(page, 'mesh-b');
    await unfold(page);
    await page.click('#perturb');
    await page.waitForFunction(() => /^Perturbed/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const s2 = await stats(page, 'b');
    check(s2.passes === '0' && s2.min_angle !== s1.min_angle, `perturbed: ${JSON.stringify(s2)}`);
    check(Number(s2.surface_distance) < 1e-6, `the perturbed nodes are on the surface: ${s2.surface_distance}`);
    check((await canvasInfo(page, 'mesh-b')).hash !== b1.hash, 'the perturbed surface is drawn');
  });

  await test("Freitag's rand3D: tetrahedra cut by a plane, smoothed old vs new, their dihedral histograms, exported and read back", async () => {
    await chooseSample(page, 'sample:rand3d');
    check(await page.evaluate(() => document.body.classList.contains('surface')), 'tetrahedra use the 3D view');
    check(await page.locator('#volume-note').isVisible() && await page.locator('#surface-note').isHidden(), 'the tetrahedra note, not the surface one');
    const s0 = await stats(page, 'b');
    check(s0.nodes === '1086' && Number(s0.elements) > 5000 && s0.inverted === '0', `rand3D: ${JSON.stringify(s0)}`);
    check(await page.evaluate(() => [...document.querySelectorAll('#stats-b th')].some((th) => th.textContent === 'Min dihedral angle')), 'the table names dihedral angles');
    for (const id of ['node', 'save-figure']) {
      check(await page.locator(`#${id}`).isEnabled(), `#${id} works for tetrahedra`);
    }
    const a0 = await canvasInfo(page, 'mesh-a');
    check(a0.colours > 50, 'the cut is drawn coloured');
    const h0 = await canvasInfo(page, 'hist-b');
    check(h0.colours > 3, 'the dihedral histogram is drawn');
    await panelsShot(page, 'volume-rand3d-loaded');
    // the cut plane moves: across x at 0.3, both views change
    await page.selectOption('#cut-axis', '0');
    await page.locator('#cut-at').fill('0.3');
    const a1 = await changed(page, 'mesh-a', a0);
    check(await page.textContent('#cut-at-out') === '0.30', 'the slider shows where the plane is');
    // one pass: the smallest dihedral angle grows on both sides, nothing is inverted
    await page.click('#step');
    await page.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const [o1, n1] = [await stats(page, 'a'), await stats(page, 'b')];
    for (const s of [o1, n1]) {
      check(s.passes === '1' && s.inverted === '0', `a pass: ${JSON.stringify(s)}`);
      check(Number.parseFloat(s.min_angle) > Number.parseFloat(s0.min_angle), `the smallest dihedral angle grows: ${s0.min_angle} → ${s.min_angle}`);
    }
    await changed(page, 'mesh-a', a1);
    await changed(page, 'hist-b', h0);
    await panelsShot(page, 'volume-rand3d-smoothed');
    await shot(page, 'volume-rand3d-page');
    // B's mesh exported as .vtk (cell type 10) reads back as tetrahedra
    const [dl] = await Promise.all([page.waitForEvent('download'), page.click('button[data-export="vtk"][data-side="b"]')]);
    const text = readFileSync(await dl.path(), 'utf8');
    check(/CELL_TYPES/.test(text) && text.split('CELL_TYPES')[1].trim().split(/\s+/)[1] === '10', 'a .vtk of tetrahedra');
    await page.setInputFiles('#file', { name: 'rand3d_b.vtk', mimeType: 'text/plain', buffer: Buffer.from(text) });
    await page.waitForFunction(() => /Loaded rand3d_b\.vtk/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
    await idle(page);
    const back = await stats(page, 'a');
    check(back.nodes === '1086' && back.min_angle === n1.min_angle, `read back: ${JSON.stringify(back)} vs ${JSON.stringify(n1)}`);
    // a planar sample brings the planar page back
    await chooseSample(page, 'sample:plate-tri');
    check(await page.locator('#volume-note').isHidden(), 'the tetrahedra note is hidden for a planar mesh');
    check(!(await page.locator('#node').isDisabled()), 'the planar controls are back');
  });

  // the suites of suites/, in name order, each given the shared browser, context and page
  const dir = path.join(path.dirname(new URL(import.meta.url).pathname), 'suites');
  for (const f of existsSync(dir) ? readdirSync(dir).filter((n) => n.endsWith('.mjs')).sort() : []) {
    const suite = await import(path.join(dir, f));
    await suite.default({ server, browser, context, page });
  }

  await test('no request left 127.0.0.1 and the console has no errors', async () => {
    check(externalRequests.length === 0, `external requests: ${externalRequests.join(', ')}`);
    check(consoleErrors.length === 0, `console errors:\n${consoleErrors.join('\n')}`);
  });
} finally {
  await browser.close();
  server.proc.kill();
}

const failed = results.filter((r) => !r.ok).length;
console.log(`${results.length - failed} passed, ${failed} failed`);
process.exit(failed ? 1 : 0);

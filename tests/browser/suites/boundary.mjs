// Issue 58, boundaries that slide, on the page: the Boundary menu says in a sentence what
// each rule does, a run with `slide` is the command-line tool's
// `smoothlab smooth --boundary slide --finish 0` on the same file (its counts, pass for
// pass and to the bit), the pictures mark the feature curves and the corners, the link
// carries the rule, a surface's curves slide, a planar mesh's boundary slides too (held
// while it is tangled), and a quadratic planar mesh's along its curved edges, in one
// worker and split between two. Screenshots of the sliding block at 1366×768, of the
// sliding plate at 1366×768 and 390×844 and of the sliding quadratic plate at 1366×768 go
// to test-output/browser/.
import path from 'node:path';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { OUT, TIMEOUT, test, check, idle, open, stats, canvasInfo, chooseSample, freshPage, cli, mshNodes, step } from '../lib.mjs';

/** How many pixels of a canvas are the sliding boundary's reddish purple (MARK_LINE_RGB). */
async function purplePixels(p, id) {
  return p.evaluate((id) => {
    const c = document.getElementById(id);
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    let n = 0;
    for (let i = 0; i < d.length; i += 4) if (d[i] === 204 && d[i + 1] === 121 && d[i + 2] === 167) n += 1;
    return n;
  }, id);
}

/** Saves a side's mesh as .msh to `file`; its nodes. */
async function saveMsh(p, side, file) {
  const [dl] = await Promise.all([p.waitForEvent('download'), p.click(`button[data-export="msh"][data-side="${side}"]`)]);
  const text = readFileSync(await dl.path(), 'utf8');
  writeFileSync(file, text);
  return mshNodes(text);
}

/** The tool's run on `file` with the boundary sliding and no finish: its report and its
 * mesh's nodes. */
function smoothSliding(file, passes) {
  const out = file.replace(/\.msh$/, '-slid.msh');
  const r = cli(['smooth', file, '-o', out, '--boundary', 'slide', '--passes', String(passes), '--finish', '0', '--json']);
  check(r.status === 0, r.stderr);
  return { report: JSON.parse(r.stdout), nodes: mshNodes(readFileSync(out, 'utf8')) };
}

/** Whether two lists of nodes are the same to the bit. */
const sameNodes = (got, want) => got.length === want.length && got.every((q, i) => q.every((v, k) => v === want[i][k]));

/** Sets the boundary menu and waits for the page to have taken it. */
async function chooseBoundary(p, rule) {
  await p.selectOption('#boundary', rule);
  await p.waitForFunction((rule) => document.body.dataset.busy === '0' && document.getElementById('status').textContent.startsWith('Boundary: ')
    && (rule === 'slide') === /boundary=slide/.test(location.hash), rule, { timeout: TIMEOUT });
  await idle(p);
}

export default async function ({ server, context }) {
  await test('issue 58: the boundary menu slides a volume\'s boundary as `smoothlab smooth --boundary slide` does, marks its curves and corners, and travels in the link', async () => {
    // a file as a user has it: a block of hexahedra bent by 60° (curved faces, twelve
    // feature curves), its interior tangled, written as a mesher that fixes no node
    // writes it (smoothlab's own .mesh says which nodes it fixed: the boundary), then
    // smoothed by the command-line tool with the boundary sliding (and fixed, to see
    // that the rule matters)
    const dir = path.join(OUT, 'boundary');
    mkdirSync(dir, { recursive: true });
    const [block, flagged, file, slid, fixed] = ['block.mesh', 'block-flagged.mesh', 'block-tangled.mesh', 'slide.msh', 'fixed.msh'].map((f) => path.join(dir, f));
    for (const args of [['generate', 'hexgrid', '--cells', '5', '--bend', '60', '-o', block],
      ['generate', 'perturb', block, '--amount', '0.6', '--seed', '3', '-o', flagged]]) {
      const r = cli(args);
      check(r.status === 0, `${args.join(' ')}: ${r.stderr}`);
    }
    const text = readFileSync(flagged, 'utf8');
    check(/\nRequiredVertices\n/.test(text), 'the .mesh names its fixed nodes');
    writeFileSync(file, text.replace(/\nRequiredVertices\n[\s\S]*?(?=\nEnd\b)/, ''));
    const smooth = (rule, out) => {
      const r = cli(['smooth', file, '-o', out, '--boundary', rule, '--passes', '3', '--finish', '0', '--json']);
      check(r.status === 0, r.stderr);
      return JSON.parse(r.stdout);
    };
    const report = smooth('slide', slid);
    smooth('fixed', fixed);
    const b = report.boundary;
    check(b && b.curves === 12 && b.corners === 8 && b.surface_nodes > 0 && b.curve_nodes > 0, `the tool's boundary report: ${JSON.stringify(b)}`);
    check(report.passes[0].inverted > 0 || report.passes.some((q) => q.moves > 0), 'the tool moves nodes');
    const [want, other] = [slid, fixed].map((f) => mshNodes(readFileSync(f, 'utf8')));
    check(JSON.stringify(want) !== JSON.stringify(other), 'sliding and fixed give the same mesh: the file cannot tell them apart');

    const p = await freshPage(context, 1366, 768, 'boundary');
    try {
      await open(p, server.base);
      // a linear planar mesh (the default sample): fixed, and free to choose
      check(!(await p.locator('#boundary').isDisabled()) && (await p.textContent('#boundary-why')) === '', 'a planar mesh\'s boundary slides');
      check(await p.inputValue('#boundary') === 'fixed', `the menu shows ${await p.inputValue('#boundary')}`);
      check(/as in the papers/.test(await p.textContent('#boundary-words')), await p.textContent('#boundary-words'));

      await p.setInputFiles('#file', file);
      await p.waitForFunction(() => /Loaded block-tangled\.mesh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      check(!(await p.locator('#boundary').isDisabled()) && (await p.textContent('#boundary-why')) === '', 'a linear volume mesh\'s boundary slides');
      check(await p.locator('#boundary-key').isHidden(), 'no key of marks while the boundary is fixed');
      const fixedPicture = await canvasInfo(p, 'mesh-b');
      await chooseBoundary(p, 'slide');
      const words = await p.textContent('#boundary-words');
      check(/feature curves/.test(words) && /corners where curves meet stay/.test(words), `the slide's sentence: ${words}`);
      // the status counts the nodes as the tool's report does
      const status = await p.textContent('#status');
      const counts = `${b.surface_nodes} nodes slide on the boundary, ${b.curve_nodes} along ${b.curves} feature curves; ${b.corners} corners stay.`;
      check(status.includes(counts), `status: ${status}; the tool: ${counts}`);
      check(await p.locator('#boundary-key').isVisible(), 'the key of the marks is shown');
      check(/feature curves/.test(await p.textContent('#boundary-key')), await p.textContent('#boundary-key'));
      const sliding = await canvasInfo(p, 'mesh-b');
      check(sliding.hash !== fixedPicture.hash, 'the picture marks the sliding boundary');
      const s0 = await stats(p, 'b');
      check(s0.boundary_sliding === String(b.surface_nodes + b.curve_nodes) && s0.passes === '0', `the table: ${JSON.stringify(s0)}`);
      await p.screenshot({ path: path.join(OUT, 'boundary-slide-1366x768.png') });
      // B is the tool's defaults (new + rules, priority order): pass for pass the same
      for (const pass of report.passes) {
        await step(p);
        const s = await stats(p, 'b');
        const w = { inverted: String(pass.inverted), min_angle: `${pass.min_angle_deg.toFixed(2)}°`, max_angle: `${pass.max_angle_deg.toFixed(2)}°` };
        for (const key of Object.keys(w)) check(s[key] === w[key], `pass ${pass.pass}, ${key}: the page ${s[key]}, the command-line tool ${w[key]}`);
      }
      const s3 = await stats(p, 'b');
      check(s3.boundary_distance === b.max_distance.toExponential(2), `the largest distance from the boundary: the page ${s3.boundary_distance}, the tool ${b.max_distance.toExponential(2)}`);
      // …and to the bit: B's mesh exported is the tool's output
      const [dl] = await Promise.all([p.waitForEvent('download'), p.click('button[data-export="msh"][data-side="b"]')]);
      const got = mshNodes(readFileSync(await dl.path(), 'utf8'));
      check(got.length === want.length && got.every((q, i) => q.every((v, k) => v === want[i][k])), 'B after 3 passes is not the command-line tool\'s mesh');
      console.log(`     3 passes sliding: min angle ${report.final.min_angle_deg.toFixed(2)}°, ${b.surface_nodes + b.curve_nodes} boundary nodes slid, the page's B the tool's output node for node`);

      // back to fixed: both sides start again, no marks, no key; the link drops the rule
      await chooseBoundary(p, 'fixed');
      check((await stats(p, 'b')).passes === '0' && (await stats(p, 'b')).boundary_sliding === undefined, 'fixed again: a fresh start without the boundary rows');
      check(await p.locator('#boundary-key').isHidden(), 'the key goes with the rule');
      check((await canvasInfo(p, 'mesh-b')).hash === fixedPicture.hash, 'the picture is the fixed boundary\'s again');

      // the link: a volume sample opens sliding, and writes the rule back
      await open(p, `${server.base}#sample=hex-tangled&boundary=slide`);
      check(await p.inputValue('#boundary') === 'slide' && !(await p.locator('#boundary').isDisabled()), 'the link sets the rule');
      check(/&maxiter=3&boundary=slide(&|$)/.test(await p.evaluate(() => location.hash)), `the link is written back: ${await p.evaluate(() => location.hash)}`);
      check(await p.locator('#boundary-key').isVisible(), 'the key follows the link');
      const hex = await stats(p, 'b');
      check(hex.boundary_sliding === String(6 * 25 + 12 * 5) && Number(hex.boundary_distance) < 1e-12, `the cube of 6³ cells: 150 nodes on its faces, 60 on its edges, all on it: ${JSON.stringify(hex)}`);
      // a quadratic planar sample in the same link: it slides too, the link keeps it
      await open(p, `${server.base}#sample=plate-quadratic&boundary=slide`);
      check(await p.isHidden('#message'), `no refusal: ${await p.textContent('#message')}`);
      check(!(await p.locator('#boundary').isDisabled()) && await p.inputValue('#boundary') === 'slide' && (await p.textContent('#boundary-why')) === '', 'a quadratic planar sample slides');
      check(await p.locator('#boundary-key').isVisible(), 'the key of the marks is shown for a quadratic plate');
      check(/&boundary=slide(&|$)/.test(await p.evaluate(() => location.hash)), `the link keeps it: ${await p.evaluate(() => location.hash)}`);
      // a surface: its curves (the capped cylinder's two rims) slide, said in its own words
      await chooseSample(p, 'sample:cylinder-capped');
      await idle(p);
      check(await p.inputValue('#boundary') === 'slide' && !(await p.locator('#boundary').isDisabled()) && (await p.textContent('#boundary-why')) === '', 'a surface\'s curves slide');
      const surfaceWords = await p.textContent('#boundary-words');
      check(/open edges and feature curves/.test(surfaceWords) && /slide along them/.test(surfaceWords), `the surface's sentence: ${surfaceWords}`);
      check(await p.locator('#boundary-key').isVisible(), 'the key of the marks is shown for a surface');
      const rims = await stats(p, 'b');
      check(Number(rims.boundary_sliding) > 20 && rims.passes === '0', `the rims' nodes slide: ${JSON.stringify(rims)}`);
      await step(p);
      const slid = await stats(p, 'b');
      check(slid.passes === '1' && Number(slid.boundary_distance) < 1e-12, `after a Step every rim node is on its circle: ${JSON.stringify(slid)}`);
      await chooseSample(p, 'sample:hex-tangled');
      check(await p.inputValue('#boundary') === 'slide' && !(await p.locator('#boundary').isDisabled()), 'the choice comes back with a volume mesh');
      check(/boundary=slide/.test(await p.evaluate(() => location.hash)), `and the link carries it: ${await p.evaluate(() => location.hash)}`);
      const msg = await p.evaluate(() => document.getElementById('message').hidden ? '' : document.getElementById('message').textContent);
      check(msg === '', `no message: ${msg}`);
      // a rule the link does not know is refused, naming it
      await open(p, `${server.base}#sample=hex-tangled&boundary=sliding`);
      const bad = await p.textContent('#message');
      check(/'boundary' must be one of fixed, slide, found 'sliding'/.test(bad), `the refusal: ${bad}`);
    } finally {
      await p.close();
    }
  });

  await test('issue 58: a planar mesh\'s boundary slides on the page as `smoothlab smooth --boundary slide` slides it, and a tangled one\'s once a pass leaves it valid', async () => {
    const dir = path.join(OUT, 'boundary');
    mkdirSync(dir, { recursive: true });
    const p = await freshPage(context, 1366, 768, 'planar boundary');
    try {
      // the plate with a hole in triangles, valid: its boundary slides from the first pass
      await open(p, `${server.base}#sample=plate-tri`);
      const plate = path.join(dir, 'plate-tri.msh');
      await saveMsh(p, 'b', plate);
      const tool = smoothSliding(plate, 2);
      const b = tool.report.boundary;
      check(b && b.corners === 4 && b.curve_nodes > 20, `the tool's boundary report: ${JSON.stringify(b)}`);
      check(await purplePixels(p, 'mesh-b') === 0, 'a fixed boundary is not marked');
      await chooseBoundary(p, 'slide');
      const words = await p.textContent('#boundary-words');
      check(/slide along the boundary as loaded/.test(words) && /turns by more than 60°/.test(words) && /tangled/.test(words), `the planar sentence: ${words}`);
      const status = await p.textContent('#status');
      const counts = `${b.curve_nodes} nodes slide along the boundary; ${b.corners} corners stay.`;
      check(status.includes(counts), `status: ${status}; the tool: ${counts}`);
      check(await p.locator('#boundary-key').isVisible() && /the boundary: its nodes slide along it/.test(await p.textContent('#boundary-key')), await p.textContent('#boundary-key'));
      for (const id of ['mesh-a', 'mesh-b']) {
        const purple = await purplePixels(p, id);
        check(purple > 200, `${id}: the sliding boundary is drawn (${purple} pixels)`);
      }
      check((await stats(p, 'b')).boundary_sliding === String(b.curve_nodes), `the table: ${JSON.stringify(await stats(p, 'b'))}`);
      check(/&boundary=slide(&|$)/.test(await p.evaluate(() => location.hash)), `the link: ${await p.evaluate(() => location.hash)}`);
      for (const pass of tool.report.passes) {
        await step(p);
        const s = await stats(p, 'b');
        check(s.min_angle === `${pass.min_angle_deg.toFixed(2)}°` && s.inverted === String(pass.inverted), `pass ${pass.pass}: the page ${s.min_angle}, the tool ${pass.min_angle_deg.toFixed(2)}°`);
      }
      await p.evaluate(() => window.scrollTo(0, 0));
      await p.screenshot({ path: path.join(OUT, 'boundary-planar-1366x768.png') });
      const s2 = await stats(p, 'b');
      check(s2.boundary_distance === b.max_distance.toExponential(2), `the largest distance from the boundary: the page ${s2.boundary_distance}, the tool ${b.max_distance.toExponential(2)}`);
      check(sameNodes(await saveMsh(p, 'b', path.join(dir, 'plate-tri-page.msh')), tool.nodes), 'B after 2 passes is not the command-line tool\'s mesh');
      console.log(`     plate-tri, 2 passes sliding: min angle ${tool.report.final.min_angle_deg.toFixed(2)}°, ${b.curve_nodes} boundary nodes slid, the page's B the tool's output node for node`);
      // Reset keeps the boundary where it was loaded
      await p.click('#reset');
      await idle(p);
      check((await stats(p, 'b')).passes === '0' && Number((await stats(p, 'b')).boundary_distance) === 0, `reset: ${JSON.stringify(await stats(p, 'b'))}`);

      // the opening sample, tangled: the boundary is held until a pass leaves a side valid
      await chooseSample(p, 'sample:plate-quad-tangled-hard');
      check(await p.inputValue('#boundary') === 'slide' && !(await p.locator('#boundary').isDisabled()), 'the rule stays with another planar sample');
      const tangled = path.join(dir, 'plate-quad-tangled-hard.msh');
      await saveMsh(p, 'b', tangled);
      const held = smoothSliding(tangled, 2);
      check(held.report.passes[0].inverted === 0 && held.report.boundary, `the tool untangles it in a pass, then slides: ${JSON.stringify(held.report.passes)}`);
      check((await stats(p, 'b')).boundary_sliding === undefined && await purplePixels(p, 'mesh-b') === 0, 'held while tangled: no boundary rows, no marks');
      await step(p);
      const [a1, b1] = [await stats(p, 'a'), await stats(p, 'b')];
      check(b1.inverted === '0' && b1.boundary_sliding === String(held.report.boundary.curve_nodes), `B is valid after a pass, and slides from the next: ${JSON.stringify(b1)}`);
      check(Number(a1.inverted) > 0 && a1.boundary_sliding === undefined, `A is still tangled, its boundary held: ${JSON.stringify(a1)}`);
      check(await purplePixels(p, 'mesh-b') > 200 && await purplePixels(p, 'mesh-a') === 0, 'the marks on the side that slides only');
      await step(p);
      const b2 = await stats(p, 'b');
      check(b2.boundary_distance === held.report.boundary.max_distance.toExponential(2), `the distance: the page ${b2.boundary_distance}, the tool ${held.report.boundary.max_distance.toExponential(2)}`);
      check(sameNodes(await saveMsh(p, 'b', path.join(dir, 'plate-quad-tangled-hard-page.msh')), held.nodes), 'the tangled plate\'s B after 2 passes is not the command-line tool\'s mesh');
      await p.evaluate(() => window.scrollTo(0, 0));
      await p.screenshot({ path: path.join(OUT, 'boundary-planar-tangled-1366x768.png') });
      // fixed again: both sides start again, held
      await chooseBoundary(p, 'fixed');
      check((await stats(p, 'b')).boundary_sliding === undefined && await p.locator('#boundary-key').isHidden(), 'fixed again');
    } finally {
      await p.close();
    }
    // a phone: the sliding plate after a Step, marks and key in view
    const phone = await freshPage(context, 390, 844, 'planar boundary phone');
    try {
      await open(phone, `${server.base}#sample=plate-tri&boundary=slide`);
      await step(phone);
      check(await purplePixels(phone, 'mesh-a') > 100, 'the phone draws the marks');
      await phone.evaluate(() => window.scrollTo(0, 0));
      await phone.screenshot({ path: path.join(OUT, 'boundary-planar-390x844.png') });
    } finally {
      await phone.close();
    }
  });

  await test('issue 58: a quadratic planar mesh\'s boundary slides along its curved edges on the page as `smoothlab smooth --boundary slide` slides it, in one worker and in two', async () => {
    const dir = path.join(OUT, 'boundary');
    mkdirSync(dir, { recursive: true });
    const differ = (got, was) => got.filter((q, i) => q.some((v, k) => v !== was[i][k])).length;
    const p = await freshPage(context, 1366, 768, 'quadratic boundary');
    try {
      // the plate with 6-node triangles, its hole curved: each boundary edge is the
      // quadratic through its corners and mid-side node, and a sliding corner carries the
      // mid-side nodes of its edges
      await open(p, `${server.base}#sample=plate-quadratic`);
      const plate = path.join(dir, 'plate-quadratic.msh');
      const loaded = await saveMsh(p, 'b', plate);
      const tool = smoothSliding(plate, 2);
      const b = tool.report.boundary;
      check(b && b.corners === 4 && b.curve_nodes > 20 && b.max_distance < 1e-9, `the tool's boundary report: ${JSON.stringify(b)}`);
      check(!(await p.locator('#boundary').isDisabled()) && (await p.textContent('#boundary-why')) === '', 'a quadratic planar mesh\'s boundary is free to slide');
      await chooseBoundary(p, 'slide');
      const words = await p.textContent('#boundary-words');
      check(/slide along the boundary as loaded/.test(words) && /quadratic mesh's boundary is its curved edges/.test(words) && /mid-side nodes/.test(words), `the planar sentence: ${words}`);
      const status = await p.textContent('#status');
      const counts = `${b.curve_nodes} nodes slide along the boundary; ${b.corners} corners stay.`;
      check(status.includes(counts), `status: ${status}; the tool: ${counts}`);
      check(await p.isHidden('#message') || (await p.textContent('#message')) === '', `no message: ${await p.textContent('#message')}`);
      for (const id of ['mesh-a', 'mesh-b']) {
        const purple = await purplePixels(p, id);
        check(purple > 200, `${id}: the sliding curved boundary is drawn (${purple} pixels)`);
      }
      check((await stats(p, 'b')).boundary_sliding === String(b.curve_nodes), `the table: ${JSON.stringify(await stats(p, 'b'))}`);
      for (const pass of tool.report.passes) {
        await step(p);
        const s = await stats(p, 'b');
        check(s.min_angle === `${pass.min_angle_deg.toFixed(2)}°` && s.inverted === String(pass.inverted), `pass ${pass.pass}: the page ${s.min_angle}, the tool ${pass.min_angle_deg.toFixed(2)}°`);
      }
      await p.evaluate(() => window.scrollTo(0, 0));
      await p.screenshot({ path: path.join(OUT, 'boundary-quadratic-1366x768.png') });
      const s2 = await stats(p, 'b');
      check(s2.boundary_distance === b.max_distance.toExponential(2), `the largest distance from the boundary: the page ${s2.boundary_distance}, the tool ${b.max_distance.toExponential(2)}`);
      const got = await saveMsh(p, 'b', path.join(dir, 'plate-quadratic-page.msh'));
      check(sameNodes(got, tool.nodes), 'the quadratic plate\'s B after 2 passes is not the command-line tool\'s mesh');
      const moved = differ(got, loaded);
      console.log(`     plate-quadratic, 2 passes sliding: min angle ${tool.report.final.min_angle_deg.toFixed(2)}°, ${b.curve_nodes} boundary nodes sliding, ${moved} nodes moved, the page's B the tool's output node for node`);
      // Reset puts the boundary back as loaded (on its curves, to the rounding of the
      // nearest points on them)
      await p.click('#reset');
      await idle(p);
      const r = await stats(p, 'b');
      check(r.passes === '0' && Number(r.boundary_distance) < 1e-12 && r.min_angle === (await stats(p, 'a')).min_angle, `reset: ${JSON.stringify(r)}`);
    } finally {
      await p.close();
    }

    // a larger quadratic plate, tangled: its passes are split between two workers; the
    // first holds the boundary, the second slides it, the boundary's segments and
    // parameters handed to the second worker with the sweep
    const big = path.join(dir, 'plate-quadratic-big.msh');
    const perturbed = path.join(dir, 'plate-quadratic-big-perturbed.msh');
    for (const args of [['generate', 'plate', '--kind', 'tri', '--order', '2', '--resolution', '20', '-o', big],
      ['generate', 'perturb', big, '--amount', '0.3', '--seed', '3', '-o', perturbed]]) {
      const r = cli(args);
      check(r.status === 0, `${args.join(' ')}: ${r.stderr}`);
    }
    const bigTool = smoothSliding(perturbed, 2);
    const firstPass = bigTool.report.passes[0];
    check(firstPass.inverted === 0 && bigTool.report.boundary && bigTool.report.boundary.curve_nodes > 100, `the tool untangles it in a pass, then slides: ${JSON.stringify(bigTool.report.passes)}, ${JSON.stringify(bigTool.report.boundary)}`);
    const q = await freshPage(context, 1366, 768, 'quadratic boundary, two workers');
    try {
      await open(q, `${server.base}#boundary=slide`);
      await q.setInputFiles('#file', perturbed);
      await q.waitForFunction(() => /Loaded plate-quadratic-big-perturbed\.msh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(q);
      check(await q.inputValue('#boundary') === 'slide', 'the file slides as the link said');
      await q.waitForFunction(() => window.smoothlab.twoWorkers(), null, { timeout: TIMEOUT, polling: 100 });
      for (const pass of bigTool.report.passes) {
        await step(q);
        const last = await q.evaluate(() => window.smoothlab.metrics.lastStep);
        check(last.workers === 2, `pass ${pass.pass} ran in ${last.workers} worker(s)`);
      }
      const nodes = await saveMsh(q, 'b', path.join(dir, 'plate-quadratic-big-page-b.msh'));
      check(sameNodes(nodes, bigTool.nodes), 'the big quadratic plate\'s B after 2 split passes is not the command-line tool\'s mesh');
      // side A (old) was swept by the second worker: the tool's run with old's objective
      const aOut = perturbed.replace(/\.msh$/, '-old.msh');
      const r = cli(['smooth', perturbed, '-o', aOut, '--boundary', 'slide', '--passes', '2', '--finish', '0', '--objective', 'old']);
      check(r.status === 0, r.stderr);
      const aNodes = await saveMsh(q, 'a', path.join(dir, 'plate-quadratic-big-page-a.msh'));
      check(sameNodes(aNodes, mshNodes(readFileSync(aOut, 'utf8'))), 'the big quadratic plate\'s A after 2 split passes is not the command-line tool\'s mesh with old');
      console.log(`     plate-quadratic at ${nodes.length} nodes, 2 passes split between two workers: both sides the tool's output node for node`);
    } finally {
      await q.close();
    }
  });
}

// Issue 58, boundaries that slide, on the page: the Boundary menu says in a sentence what
// each rule does, a run with `slide` is the command-line tool's
// `smoothlab smooth --boundary slide --finish 0` on the same file (its counts, pass for
// pass and to the bit), the pictures mark the feature curves and the corners, the link
// carries the rule, a surface's curves slide, and a planar sample shows the boundary
// fixed, disabled, saying why. A screenshot of the sliding block at 1366×768 goes to test-output/browser/.
import path from 'node:path';
import { mkdirSync, readFileSync, writeFileSync } from 'node:fs';
import { OUT, TIMEOUT, test, check, idle, open, stats, canvasInfo, chooseSample, freshPage, cli, mshNodes, step } from '../lib.mjs';

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
      // a planar mesh (the default sample): fixed, disabled, and why
      check(await p.locator('#boundary').isDisabled(), 'a planar mesh\'s boundary cannot slide');
      check(await p.inputValue('#boundary') === 'fixed', `the menu shows ${await p.inputValue('#boundary')}`);
      const why = await p.textContent('#boundary-why');
      check(/^Fixed here: the page slides the boundaries of volume meshes and surfaces; this mesh is planar \(the command line and Python slide it\)\.$/.test(why), `why: ${why}`);
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
      // a planar sample in the same link: fixed, disabled, the choice kept for a volume
      await open(p, `${server.base}#sample=plate-tri&boundary=slide`);
      check(await p.isHidden('#message'), `no refusal: ${await p.textContent('#message')}`);
      check(await p.locator('#boundary').isDisabled() && await p.inputValue('#boundary') === 'fixed', 'a planar sample shows the boundary fixed');
      check(/this mesh is planar/.test(await p.textContent('#boundary-why')), await p.textContent('#boundary-why'));
      check(!/boundary=/.test(await p.evaluate(() => location.hash)), `the link drops it: ${await p.evaluate(() => location.hash)}`);
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
}

// Issue 57, the target on the page: its menu says in a sentence what each target means,
// takes only the ideal with a strategy that takes Laplacian steps (saying why), travels in
// the link, and a run against the input is the command-line tool's
// `smoothlab smooth --target input --finish 0` on the same file, pass for pass and to the
// bit, in one worker or split between two. A screenshot of the page with the menu at
// 1366×768 goes to test-output/browser/.
import path from 'node:path';
import { mkdirSync, readFileSync } from 'node:fs';
import { OUT, TIMEOUT, test, check, idle, open, stats, freshPage, cli, mshNodes, step } from '../lib.mjs';

export default async function ({ server, context }) {
  await test('issue 57: the target menu says what it means, takes only the ideal with a Laplacian strategy, and steps as `smoothlab smooth --target input`', async () => {
    // a file as a user has it: a grid of 3:1 quads, tangled (8 quads inverted), then
    // smoothed by the command-line tool against itself: the inverted corners aim at the
    // square, the others keep their shape (and against the ideal, to see that it matters)
    const dir = path.join(OUT, 'target');
    mkdirSync(dir, { recursive: true });
    const [grid, file, input, ideal] = ['grid.msh', 'grid-perturbed.msh', 'input.msh', 'ideal.msh'].map((f) => path.join(dir, f));
    for (const args of [['generate', 'grid', '--nx', '12', '--ny', '4', '--kind', 'quad', '-o', grid],
      ['generate', 'perturb', grid, '--amount', '0.6', '--seed', '2', '-o', file]]) {
      const r = cli(args);
      check(r.status === 0, `${args.join(' ')}: ${r.stderr}`);
    }
    const smooth = (target, out) => {
      const r = cli(['smooth', file, '-o', out, '--strategy', 'rules', '--target', target, '--passes', '3', '--finish', '0', '--json']);
      check(r.status === 0, r.stderr);
      return JSON.parse(r.stdout);
    };
    const report = smooth('input', input);
    check(report.passes.every((q) => q.moves > 0), `every pass of the tool moves nodes: ${report.passes.map((q) => q.moves)}`);
    smooth('ideal', ideal);
    check(report.target === 'input', `the tool's report names its target: ${report.target}`);
    const [want, other] = [input, ideal].map((f) => mshNodes(readFileSync(f, 'utf8')));
    check(JSON.stringify(want) !== JSON.stringify(other), 'the two targets give the same mesh: the file cannot tell them apart');

    const p = await freshPage(context, 1366, 768, 'target');
    try {
      await open(p, server.base);
      await p.setInputFiles('#file', file);
      await p.waitForFunction(() => /Loaded grid-perturbed\.msh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      check(Number((await stats(p, 'b')).inverted) > 0, 'the file is tangled');
      // the menu starts on the ideal, its sentence beside it
      check(await p.inputValue('#target') === 'ideal', `the target starts on ${await p.inputValue('#target')}`);
      check(await p.locator('#target-words').isVisible(), 'the sentence is shown');
      const idealWords = await p.textContent('#target-words');
      check(/equilateral triangle, the square/.test(idealWords), `the ideal's sentence: ${idealWords}`);
      // a strategy of Laplacian steps: the ideal only, disabled, and why
      await p.selectOption('#strategy', 'c2');
      check(await p.locator('#target').isDisabled(), 'C2 takes no target but the ideal');
      const why = await p.textContent('#target-why');
      check(/^Only the ideal here: only optimization and Chen's rules measure corners against a target other than the ideal; Freitag's C2 takes Laplacian steps/.test(why), `why: ${why}`);
      await p.selectOption('#strategy', 'rules');
      check(!(await p.locator('#target').isDisabled()) && (await p.textContent('#target-why')) === '', 'Chen\'s rules take a target');
      // the input: its sentence, and the link carries it
      await p.selectOption('#target', 'input');
      await p.waitForFunction(() => /target=input/.test(location.hash) && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
      const inputWords = await p.textContent('#target-words');
      check(/as loaded/.test(inputWords) && /inverted or flat aims at the ideal/.test(inputWords), `the input's sentence: ${inputWords}`);
      check(/^Target: the mesh as loaded\./.test(await p.textContent('#status')), await p.textContent('#status'));
      await p.screenshot({ path: path.join(OUT, 'target-control-1366x768.png') });
      // with C2 and back, the user's choice comes back with a strategy that takes it
      await p.selectOption('#strategy', 'c2');
      check(await p.inputValue('#target') === 'ideal', 'C2 shows the ideal');
      await p.selectOption('#strategy', 'rules');
      check(await p.inputValue('#target') === 'input', 'the input is chosen again with the rules');
      // B is the tool's defaults (new + rules, priority order): pass for pass the same
      for (const pass of report.passes) {
        await step(p);
        const s = await stats(p, 'b');
        const w = { inverted: String(pass.inverted), min_angle: `${pass.min_angle_deg.toFixed(2)}°`, max_angle: `${pass.max_angle_deg.toFixed(2)}°` };
        for (const key of Object.keys(w)) check(s[key] === w[key], `pass ${pass.pass}, ${key}: the page ${s[key]}, the command-line tool ${w[key]}`);
      }
      // …and to the bit: B's mesh exported is the tool's output
      const [dl] = await Promise.all([p.waitForEvent('download'), p.click('button[data-export="msh"][data-side="b"]')]);
      const got = mshNodes(readFileSync(await dl.path(), 'utf8'));
      check(got.length === want.length && got.every((q, i) => q.every((v, k) => v === want[i][k])), 'B after 3 passes is not the command-line tool\'s mesh');
      console.log(`     3 passes against the input: min angle ${report.final.min_angle_deg.toFixed(2)}°, the page's B the tool's output node for node`);
      // the link opens the target again; a link with a strategy that takes none is refused
      await open(p, `${server.base}#sample=plate-quad&strategy=opt&target=input`);
      check(await p.inputValue('#target') === 'input' && await p.inputValue('#strategy') === 'opt', 'the link sets the target and the strategy');
      check(/as loaded/.test(await p.textContent('#target-words')), 'the sentence follows the link');
      check(/&target=input$/.test(await p.evaluate(() => location.hash)), `the link is written back: ${await p.evaluate(() => location.hash)}`);
      await open(p, `${server.base}#sample=plate-quad&strategy=c3&target=input`);
      const msg = await p.textContent('#message');
      check(/'target' must be ideal unless 'strategy' is opt or rules \(it is c3\), found 'input'/.test(msg), `the refusal: ${msg}`);
    } finally {
      await p.close();
    }
  });

  await test('issue 57: a pass against the input split between two workers is one worker\'s, bit for bit, on a perturbed mesh the second worker loaded unperturbed', async () => {
    // the second worker holds the sample as loaded; the first perturbed it, so the target
    // (the mesh as perturbed) travels with the sweep
    const hash = '#sample=rand2d-large&tangle=0.3&seed=3&perturbed=1&strategy=rules&target=input';
    const onePass = async (workers) => {
      const p = await freshPage(context, 1280, 900, `target, ${workers} worker(s)`);
      try {
        await open(p, `${server.base}${workers === 1 ? '?workers=1' : ''}${hash}`);
        check(await p.inputValue('#target') === 'input', 'the link chose the input');
        if (workers === 2) await p.waitForFunction(() => window.smoothlab.twoWorkers(), null, { timeout: TIMEOUT, polling: 100 });
        await step(p);
        const meshes = [];
        for (const side of ['a', 'b']) {
          const [dl] = await Promise.all([p.waitForEvent('download'), p.click(`button[data-export="msh"][data-side="${side}"]`)]);
          meshes.push(readFileSync(await dl.path()).toString());
        }
        const last = await p.evaluate(() => window.smoothlab.metrics.lastStep);
        return { meshes, workers: last.workers, wall_ms: last.wall_ms, a: await stats(p, 'a'), b: await stats(p, 'b') };
      } finally {
        await p.close();
      }
    };
    const two = await onePass(2);
    const one = await onePass(1);
    check(two.workers === 2 && one.workers === 1, `workers: ${two.workers} and ${one.workers}`);
    for (const [i, side] of ['a', 'b'].entries()) {
      check(two.meshes[i] === one.meshes[i], `the ${side} side differs between two workers and one`);
      for (const row of ['inverted', 'min_angle', 'max_angle', 'optimization_calls']) {
        check(two[side][row] === one[side][row], `${side} ${row}: ${two[side][row]} with two workers, ${one[side][row]} with one`);
      }
    }
    console.log(`     one Step against the input: ${two.wall_ms.toFixed(0)} ms in two workers, ${one.wall_ms.toFixed(0)} ms in one; the same meshes`);
  });
}

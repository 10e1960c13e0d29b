// The tour's figures of issue 28, part B: chen-13 (priority against input order, pass by
// pass), freitag-t1 (Table 1 shown once, filling row by row at a pace one can follow),
// freitag-t2 (Table 2 on rand3D, filling live, with the cut view) and chen-18 (a tangled
// quadratic surface, old against new, in 3D) and knupp-hex (Knupp's tangled block of
// hexahedra pass by pass, old against new, cut). Each opens by its link and embeds in frames
// of 800×450 and 520×520 without scrolling. The numbers checked are the core's: the card's
// text is computed by the same functions as the picture (crates/smoothlab-page/src/lab/tour/pictures.rs).
import path from 'node:path';
import { OUT, TIMEOUT, test, check, idle, canvasInfo, stats, freshPage, hostFrame } from '../lib.mjs';

/** Opens `#figure=NAME` in a fresh load and waits until it is open (passes run, table filled). */
async function openFigure(p, base, name, query = '') {
  await p.goto(`${base}${query || `?open=${name}`}#figure=${name}`);
  await p.waitForFunction((n) => document.body.dataset.figure === n && document.body.dataset.busy === '0', name, { timeout: 4 * TIMEOUT });
  await idle(p);
  return p.evaluate(() => window.smoothlab.figure());
}

/** The numbers of "a → b → c" lists in a text, each list as an array. */
function arrowLists(text) {
  return [...text.matchAll(/\d+(?: → \d+)+/g)].map((m) => m[0].split(' → ').map(Number));
}

const MINE = ['chen-13', 'chen-18', 'freitag-t1', 'freitag-t2', 'knupp-hex'];

export default async function ({ server, context }) {
  const base = server.base;

  await test('chen-13: both orders pass by pass, priority untangles in fewer passes than input order (the computed counts)', async () => {
    const p = await freshPage(context, 1366, 900, 'chen-13');
    try {
      const card = await openFigure(p, base, 'chen-13');
      check(p.url().endsWith('#figure=chen-13'), p.url());
      const text = await p.textContent('#tour-measured');
      check(text === card.measured, 'the page shows the core\'s text');
      // the first two arrow lists: priority's counts, then input order's, as computed
      const [prio, input] = arrowLists(text);
      check(prio && input && prio[0] === input[0] && prio[0] > 100, `counts: ${JSON.stringify([prio, input])} in "${text}"`);
      const zero = (v) => v.indexOf(0);
      check(zero(prio) > 0 && zero(input) > 0 && zero(prio) < zero(input), `priority ${prio} against input ${input}`);
      check(new RegExp(`— ${zero(prio)} pass(es)? against ${zero(input)};`).test(text), `the passes in words: ${text}`);
      const pic = await canvasInfo(p, 'tour-picture');
      check(pic.colours > 50 && pic.w > 400, `the picture looks blank (${pic.colours} colours)`);
      await p.locator('#tour').screenshot({ path: path.join(OUT, 'figure-b-chen-13.png') });
    } finally {
      await p.close();
    }
  });

  /** One number for one run (issue 59): the live meshes A and B, run by the page with the
   * figure's settings, read the smallest angle the table's rows of their methods read. */
  const oneRun = (rows, s, name) => {
    for (const [i, method] of [[0, 'opt, sine'], [1, 'opt, new']]) {
      const row = rows.find((r) => r[0] === method);
      check(row && row[1] === s[i].min_angle, `${name}: the table's ${method} says ${row && row[1]}, side ${'AB'[i]} ${s[i].min_angle}`);
    }
  };

  await test('freitag-t1: Table 1 shown once (no picture of it beside the table), its rows coming one at a time at a pace one can follow', async () => {
    const p = await freshPage(context, 1366, 900, 'freitag-t1');
    try {
      await p.goto(`${base}?open=freitag-t1#figure=freitag-t1`);
      await p.waitForFunction(() => document.body.dataset.figureRows === '1', null, { timeout: 4 * TIMEOUT });
      // watch the rows come: record when each count is first seen
      const seen = await p.evaluate(() => new Promise((done) => {
        const t0 = performance.now();
        const times = [[1, 0]];
        const id = setInterval(() => {
          const n = Number(document.body.dataset.figureRows);
          const rows = document.querySelectorAll('#tour-rows tr').length;
          if (n !== times[times.length - 1][0] || rows !== n) times.push([n, performance.now() - t0, rows]);
          if (document.body.dataset.figure === 'freitag-t1') {
            clearInterval(id);
            done(times);
          }
        }, 20);
      }));
      const card = await p.evaluate(() => window.smoothlab.figure());
      const counts = seen.map(([n]) => n);
      check(counts.every((n, i) => i === 0 || n === counts[i - 1] + 1), `rows did not come one at a time: ${JSON.stringify(seen)}`);
      check(counts[counts.length - 1] === card.rows, `${counts[counts.length - 1]} of ${card.rows} rows`);
      const gaps = seen.slice(1).map(([, t], i) => t - seen[i][1]);
      check(gaps.every((g) => g >= 600), `a row came sooner than 0.6 s after the last: ${JSON.stringify(gaps.map(Math.round))}`);
      // shown once: the table, not the picture of it; no heading cut off
      check(await p.locator('#tour-picture').isHidden(), 'the picture of the table is shown beside the table');
      check((await p.$$eval('#tour-table', (t) => t.length)) === 1 && (await p.locator('#tour-table').isVisible()), 'the table is shown');
      const heads = await p.$$eval('#tour-head th', (ths) => ths.map((th) => [th.textContent, th.scrollWidth <= th.clientWidth + 1]));
      check(heads.length === 8 && heads.every(([, whole]) => whole), `headings: ${JSON.stringify(heads)}`);
      check(heads[7][0].startsWith('Freitag'), `the last heading: ${heads[7][0]}`);
      const rows = await p.$$eval('#tour-rows tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
      check(rows.length === card.rows && rows.every((r) => r.length === 8), `rows: ${JSON.stringify(rows)}`);
      check(rows.some((r) => /18\.20/.test(r[7])), 'Freitag\'s numbers beside ours');
      oneRun(rows, [await stats(p, 'a'), await stats(p, 'b')], 'freitag-t1');
      await p.locator('#tour').screenshot({ path: path.join(OUT, 'figure-b-freitag-t1.png') });
    } finally {
      await p.close();
    }
  });

  await test('freitag-t2: Table 2 on rand3D fills live beside Freitag\'s numbers, its cut view drawn on both sides', async () => {
    const p = await freshPage(context, 1366, 900, 'freitag-t2');
    try {
      const card = await openFigure(p, base, 'freitag-t2');
      check(card.gallery === 'rand3d' && (await p.inputValue('#sample')) === 'sample:rand3d', `sample: ${await p.inputValue('#sample')}`);
      check(await p.evaluate(() => document.body.classList.contains('surface')), 'the 3D view is not on');
      const rows = await p.$$eval('#tour-rows tr', (trs) => trs.map((tr) => [...tr.children].map((c) => c.textContent)));
      check(rows.length === card.rows && card.rows >= 8, `rows: ${rows.length} of ${card.rows}`);
      check(rows.every((r) => r.length === 8 && /°$/.test(r[1]) && /\[/.test(r[5])), `rows: ${JSON.stringify(rows)}`);
      check(rows.some((r) => r[0] === 'opt, sine' && /^7\.88 \//.test(r[7])), 'Freitag\'s optimization row beside ours');
      check(/only/.test(await p.textContent('#tour-table-caption')), 'the caption says which rows are read, not run');
      check(/dihedral/.test((await p.$$eval('#tour-head th', (t) => t.map((x) => x.textContent))).join(' ')), 'dihedral headings');
      const s = [await stats(p, 'a'), await stats(p, 'b')];
      check(s[0].passes === '3' && s[1].passes === '3', `passes run: ${s[0].passes}/${s[1].passes}`);
      oneRun(rows, s, 'freitag-t2');
      for (const id of ['mesh-a', 'mesh-b']) {
        const c = await canvasInfo(p, id);
        check(c.colours > 50, `${id}, the cut view, looks blank (${c.colours} colours)`);
      }
      check(/§10/.test(await p.textContent('#tour-measured')), 'the text cites the reproduction');
      await p.locator('#tour').screenshot({ path: path.join(OUT, 'figure-b-freitag-t2.png') });
    } finally {
      await p.close();
    }
  });

  await test('chen-18: the tangled quadratic torus after the passes, old and new in 3D, the text\'s counts the computed ones', async () => {
    const p = await freshPage(context, 1366, 900, 'chen-18');
    try {
      const card = await openFigure(p, base, 'chen-18');
      check(card.gallery === 'torus-quadratic-tangled' && (await p.inputValue('#sample')) === `sample:${card.gallery}`, 'sample');
      const pic = await canvasInfo(p, 'tour-picture');
      check(pic.colours > 50 && pic.w > 400, `the picture looks blank (${pic.colours} colours)`);
      const text = await p.textContent('#tour-measured');
      const [old, nw] = arrowLists(text);
      check(old && nw && old[0] === nw[0] && old[0] > 0, `counts: ${text}`);
      check(nw[nw.length - 1] === 0 && old[old.length - 1] > 0, `the new side untangles, the old does not: ${old} / ${nw}`);
      // the live panels ran the same passes from the same mesh: their counts are the text's
      const s = [await stats(p, 'a'), await stats(p, 'b')];
      check(s[0].passes === String(old.length - 1), `passes: ${s[0].passes}`);
      check(s[0].inverted === String(old[old.length - 1]) && s[1].inverted === String(nw[nw.length - 1]), `live counts ${s[0].inverted}/${s[1].inverted} against ${old} / ${nw}`);
      for (const id of ['mesh-a', 'mesh-b']) check((await canvasInfo(p, id)).colours > 50, `${id} looks blank`);
      check(/§9/.test(text), 'the text cites the reproduction\'s §9');
      await p.locator('#tour').screenshot({ path: path.join(OUT, 'figure-b-chen-18.png') });
    } finally {
      await p.close();
    }
  });

  await test('knupp-hex: the tangled hexahedra pass by pass, old and new cut on both sides, the text\'s counts the computed ones and the live tables', async () => {
    const p = await freshPage(context, 1366, 900, 'knupp-hex');
    try {
      const card = await openFigure(p, base, 'knupp-hex');
      check(card.gallery === 'hex-tangled' && (await p.inputValue('#sample')) === `sample:${card.gallery}`, `sample: ${await p.inputValue('#sample')}`);
      check(await p.evaluate(() => document.body.classList.contains('surface')), 'the 3D view is not on');
      const pic = await canvasInfo(p, 'tour-picture');
      check(pic.colours > 50 && pic.w > 400, `the picture looks blank (${pic.colours} colours)`);
      const text = await p.textContent('#tour-measured');
      check(text === card.measured, 'the page shows the core\'s text');
      const [old, nw] = arrowLists(text);
      check(old && nw && old[0] === nw[0] && old[0] > 0 && old.length === 4, `counts: ${text}`);
      check(nw[1] === 0 && old[old.length - 1] > 0, `the new side untangles in a pass, the old does not: ${old} / ${nw}`);
      check(/inverted inside only, all eight corner Jacobians positive/.test(text), `the text says what a corner check misses: ${text}`);
      check(/Bernstein/.test(await p.textContent('#tour-text')), 'the words say how validity is decided');
      // the live panels ran the same passes from the same mesh: their counts are the text's
      const s = [await stats(p, 'a'), await stats(p, 'b')];
      check(s[0].passes === String(old.length - 1) && s[1].passes === s[0].passes, `passes: ${s[0].passes}/${s[1].passes}`);
      check(s[0].elements === '216' && s[0].inverted === String(old[old.length - 1]) && s[1].inverted === String(nw[nw.length - 1]), `live ${JSON.stringify(s)} against ${old} / ${nw}`);
      for (const id of ['mesh-a', 'mesh-b']) check((await canvasInfo(p, id)).colours > 50, `${id} looks blank`);
      await p.locator('#tour').screenshot({ path: path.join(OUT, 'figure-b-knupp-hex.png') });
      await p.locator('.panels').screenshot({ path: path.join(OUT, 'figure-b-knupp-hex-view.png') });
    } finally {
      await p.close();
    }
  });

  await test('chen-13, chen-18, freitag-t1, freitag-t2, knupp-hex embed (?embed=1) in frames of 800×450 and 520×520 without scrolling, the picture whole', async () => {
    const p = await freshPage(context, 1400, 900, 'embeds-b');
    try {
      for (const name of MINE) {
        for (const [w, h] of [[800, 450], [520, 520]]) {
          const frame = await hostFrame(p, `${base}?embed=1#figure=${name}`, w, h, { figure: true, timeout: 4 * TIMEOUT });
          check((await frame.evaluate(() => document.body.dataset.figure)) === name, `${name} did not open`);
          const r = await frame.evaluate(() => ({ sw: document.documentElement.scrollWidth, sh: document.documentElement.scrollHeight, vw: innerWidth, vh: innerHeight }));
          check(r.sw <= w && r.sh <= h, `${name} at ${w}×${h}: scrolls (${r.sw}×${r.sh})`);
          const b = await frame.evaluate(() => {
            const q = document.getElementById('tour-picture').getBoundingClientRect();
            return { x: q.left, y: q.top, r: q.right, b: q.bottom, w: q.width, h: q.height };
          });
          check(b.w > 0 && b.x >= -0.5 && b.y >= -0.5 && b.r <= w + 0.5 && b.b <= h + 0.5, `${name} at ${w}×${h}: the picture is not whole: ${JSON.stringify(b)}`);
          check(Math.max(b.w, b.h) >= 0.4 * Math.min(w, h), `${name} at ${w}×${h}: the picture is small: ${JSON.stringify(b)}`);
          check((await canvasInfo(frame, 'tour-picture')).colours > 50, `${name} at ${w}×${h}: the picture looks blank`);
          await p.locator('#f').screenshot({ path: path.join(OUT, `embed-b-${name}-${w}x${h}.png`) });
        }
      }
    } finally {
      await p.close();
    }
  });
}

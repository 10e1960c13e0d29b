// The gallery's volume samples beyond tetrahedra: Knupp's tangled block of hexahedra and the
// mixed block (hexahedra, wedges, pyramids, tetrahedra), each opened by its link, drawn cut
// by the plane on both sides, its counts in the tables, and a Step that untangles.
import { TIMEOUT, test, check, open, stats, canvasInfo, shot, freshPage, idle } from '../lib.mjs';

// the counts by hand: 6³ cells, 7³ nodes; the mixed block of 4³ cells with its wedge
// column (4 cells of 2 wedges), its pyramid row (4 cells, 10 boundary bases as 20
// tetrahedra, 14 pyramids) and the 56 hexahedra left; 5³ lattice nodes and 4 centres
const SAMPLES = [
  { name: 'hex-tangled', nodes: '343', elements: '216' },
  { name: 'mixed-tangled', nodes: '129', elements: String(56 + 8 + 14 + 20) },
];

export default async function ({ server, context }) {
  for (const want of SAMPLES) {
    await test(`#sample=${want.name}: the volume sample drawn cut on both sides, its counts in the tables, tangled, and a Step untangles`, async () => {
      const p = await freshPage(context, 1280, 900, want.name);
      try {
        await open(p, `${server.base}#sample=${want.name}`);
        check((await p.inputValue('#sample')) === `sample:${want.name}`, `the menu shows ${await p.inputValue('#sample')}`);
        check(await p.isHidden('#message'), `message: ${await p.textContent('#message')}`);
        check(await p.evaluate(() => document.body.classList.contains('surface')), 'the 3D view is on');
        check(await p.locator('#volume-note').isVisible(), 'the volume note (with the cut) is shown');
        const s0 = [await stats(p, 'a'), await stats(p, 'b')];
        for (const s of s0) {
          check(s.nodes === want.nodes && s.elements === want.elements, `${want.name}: ${JSON.stringify(s)}`);
          check(Number(s.inverted) > 0 && s.passes === '0', `${want.name} starts tangled: ${JSON.stringify(s)}`);
        }
        check(s0[0].inverted === s0[1].inverted, 'both sides start from one mesh');
        const before = [];
        for (const id of ['mesh-a', 'mesh-b']) {
          const c = await canvasInfo(p, id);
          check(c.colours > 50, `${want.name}: ${id}, the cut view, looks blank (${c.colours} colours)`);
          before.push(c);
        }
        await shot(p, `volume-${want.name}-loaded`, false);
        await p.click('#step');
        await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
        await idle(p);
        const s1 = [await stats(p, 'a'), await stats(p, 'b')];
        for (const [i, s] of s1.entries()) {
          check(s.passes === '1', `a pass: ${JSON.stringify(s)}`);
          check(Number(s.inverted) < Number(s0[i].inverted), `${want.name}: Step leaves ${s.inverted} of ${s0[i].inverted} inverted on side ${'ab'[i]}`);
        }
        check(s1[1].inverted === '0', `${want.name}: the new objective untangles in one pass: ${s1[1].inverted}`);
        for (const [i, id] of ['mesh-a', 'mesh-b'].entries()) {
          check((await canvasInfo(p, id)).hash !== before[i].hash, `${id} is drawn again after the pass`);
        }
        await shot(p, `volume-${want.name}-step`, false);
      } finally {
        await p.close();
      }
    });
  }
}

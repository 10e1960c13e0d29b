// The lesson at a glance (issue 59): the status line after a drag says what it did, a new
// file forgets the previous file's node, and on a phone a figure's picture is on the
// first screen.
import path from 'node:path';
import { DATA, OUT, TIMEOUT, test, check, open, idle, stats, canvasInfo, clickSomeNode, ringPoints, freshPage } from '../lib.mjs';

export default async function ({ server, context }) {
  const base = server.base;

  await test('after a drag the status line says what the drag did, with the tables\' counts', async () => {
    const p = await freshPage(context, 1280, 900, 'drag status');
    try {
      await open(p, `${base}#sample=plate-tri-tangled`);
      const { node, x, y } = await clickSomeNode(p, 'mesh-a', ringPoints());
      // back to the settings: the meshes are where they were when the node was clicked
      await p.click('#tabbtn-settings');
      await idle(p);
      check(/^Loaded /.test(await p.textContent('#status')), `the status before: ${await p.textContent('#status')}`);
      const before = [(await stats(p, 'a')).inverted, (await stats(p, 'b')).inverted];
      await p.mouse.move(x, y);
      await p.mouse.down();
      await p.mouse.move(x + 30, y + 20, { steps: 6 });
      await p.mouse.up();
      await idle(p);
      await p.waitForFunction(() => /^Dragged node/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      const after = [(await stats(p, 'a')).inverted, (await stats(p, 'b')).inverted];
      const status = await p.textContent('#status');
      const count = (i) => (before[i] === after[i] ? after[i] : `${before[i]} → ${after[i]}`);
      const want = `Dragged node ${node} on both sides: inverted elements A ${count(0)}, B ${count(1)} (Ctrl+Z takes it back).`;
      check(status === want, `the status: '${status}', want '${want}'`);
      console.log(`     ${status}`);
    } finally {
      await p.close();
    }
  });

  await test('a new file forgets the node chosen on the previous mesh: the Node tab, its field and its pictures', async () => {
    const p = await freshPage(context, 1366, 768, 'node reset');
    try {
      await open(p, `${base}#sample=plate-tri-tangled`);
      const { node } = await clickSomeNode(p, 'mesh-a', ringPoints());
      check((await p.textContent('#node-badge')) === String(node), 'the Node tab names the node');
      const drawn = await canvasInfo(p, 'level-a');
      await p.setInputFiles('#file', path.join(DATA, 'grid_lines.msh'));
      await p.waitForFunction(() => /^Loaded grid_lines\.msh/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      check((await p.textContent('#node-badge')) === '', `the Node tab still says '${await p.textContent('#node-badge')}'`);
      check((await p.inputValue('#node')) === '', `the node field still says '${await p.inputValue('#node')}'`);
      check(!/#.*node=/.test(p.url()), `the address keeps a node: ${p.url()}`);
      check((await canvasInfo(p, 'level-a')).hash !== drawn.hash, 'the level sets of the previous mesh are still drawn');
      check(await p.locator('#smooth-node').isDisabled(), 'Smooth this node waits for a node');
    } finally {
      await p.close();
    }
  });

  await test('on a phone (390×844) a figure of the tour shows its picture on the first screen, its words under it', async () => {
    const p = await freshPage(context, 390, 844, 'phone figure first');
    try {
      for (const name of ['chen-2', 'chen-10', 'knupp-1', 'knupp-hex']) {
        await open(p, `${base}#figure=${name}`);
        await p.waitForFunction((n) => document.body.dataset.figure === n, name, { timeout: TIMEOUT });
        await idle(p);
        const [pic, words] = await p.evaluate(() => ['tour-picture', 'tour-text'].map((id) => {
          const r = document.getElementById(id).getBoundingClientRect();
          return { top: r.top + window.scrollY, bottom: r.bottom + window.scrollY, h: r.height };
        }));
        check(pic.h > 100, `${name}: the picture is ${pic.h} px high`);
        check(pic.bottom <= 844 + 0.5, `${name}: the picture ends at ${Math.round(pic.bottom)} px, below the first screen (844)`);
        check(words.top >= pic.bottom - 0.5, `${name}: the words are not under the picture`);
        console.log(`     ${name}: the picture from ${Math.round(pic.top)} to ${Math.round(pic.bottom)} px`);
        if (name === 'chen-10') await p.screenshot({ path: path.join(OUT, 'phone-390x844-figure.png') });
      }
    } finally {
      await p.close();
    }
  });
}

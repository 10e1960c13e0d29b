// Meshes in 3D are first-class on the page: a click on a surface or on a cut of
// tetrahedra picks the nearest node of the face there (a drag still turns the view), its
// level sets are drawn over its plane (a surface's tangent plane, the cut plane moved to
// the node), Smooth this node moves it and Undo puts it back, the per-pass chart and the
// histograms are drawn, the figure for slides is saved, and a link keeps the node, the
// camera and the cut. Screenshots of the laptop, the phone and an 800 × 450 embed with a
// node picked go to test-output/browser/.
import path from 'node:path';
import { readFileSync } from 'node:fs';
import { OUT, TIMEOUT, test, check, idle, open, stats, canvasInfo, freshPage, hostFrame, reach } from '../lib.mjs';

/** Where node `node` of side `side` is drawn, in the page's CSS pixels, and how far behind
 * the front of its mesh it is (CSS pixels; 0 for the nearest). */
async function screenOf(p, side, node) {
  const at = await p.evaluate(([s, n]) => window.smoothlab.nodeOnScreen(s, n), [side, node]);
  check(at, `node ${node} is not on side ${side}`);
  const box = await p.locator(`#mesh-${side}`).boundingBox();
  const css = await p.evaluate((id) => {
    const c = document.getElementById(id);
    const dpr = Math.min(window.devicePixelRatio || 1, 2);
    return { w: c.width / dpr, h: c.height / dpr };
  }, `mesh-${side}`);
  return { x: box.x + (at.x * box.width) / css.w, y: box.y + (at.y * box.height) / css.h, behind: at.behind };
}

/** Clicks (a press and a release, no motion) at `(x, y)` and waits for the page to settle. */
async function clickAt(p, x, y) {
  await p.mouse.move(x, y);
  await p.mouse.down();
  await p.mouse.up();
  await idle(p);
  await p.waitForTimeout(50);
  await idle(p);
}

/** Clicks near the middle of side `side`'s view (then a little around it) until a node is
 * chosen; returns it and where the click was, as a share of the view's width and height
 * (a chosen node widens the column beside the views, and they are drawn smaller). */
async function pickNear(p, side, offsets = [[0, 0.04], [0.05, 0], [-0.05, 0.06], [0.02, -0.08], [-0.1, -0.05]]) {
  await p.locator(`#mesh-${side}`).scrollIntoViewIfNeeded();
  const box = await p.locator(`#mesh-${side}`).boundingBox();
  for (const [fx, fy] of offsets) {
    const [x, y] = [box.x + (0.5 + fx) * box.width, box.y + (0.5 + fy) * box.height];
    await clickAt(p, x, y);
    const v = await p.inputValue('#node');
    if (v !== '') return { node: Number(v), fx: 0.5 + fx, fy: 0.5 + fy };
  }
  throw new Error(`no click on side ${side} chose a node: ${await p.textContent('#pick-note')}`);
}

/** Where a click at shares `(fx, fy)` of side `side`'s view is now, CSS px. */
async function nowAt(p, side, fx, fy) {
  const box = await p.locator(`#mesh-${side}`).boundingBox();
  return { x: box.x + fx * box.width, y: box.y + fy * box.height };
}

/** Waits until a canvas's pixels differ from `before`. */
async function changed(p, id, before) {
  for (let i = 0; i < 100; i++) {
    await idle(p);
    const now = await canvasInfo(p, id);
    if (now.hash !== before.hash) return now;
    await p.waitForTimeout(50);
  }
  throw new Error(`${id} did not change`);
}

/** The node view's three canvases are drawn (many colours: bands, lines, a chart). */
async function nodeViewDrawn(p, what) {
  for (const id of ['level-a', 'level-b', 'solve-chart']) {
    const c = await canvasInfo(p, id);
    check(c.colours > 40, `${what}: #${id} is not drawn (${c.colours} colours)`);
  }
}

/** A saved PNG's width and height, from its header. */
function pngSize(file) {
  const b = readFileSync(file);
  check(b.toString('latin1', 1, 4) === 'PNG', 'not a PNG');
  return [b.readUInt32BE(16), b.readUInt32BE(20)];
}

const distance = (a, b) => Math.hypot(a.x - b.x, a.y - b.y);

export default async function ({ server, context }) {
  const base = server.base;

  await test('a surface: a click picks the nearest node of the face there, its level sets in its tangent plane; Smooth this node moves it on the surface, Undo puts it back', async () => {
    const p = await freshPage(context, 1366, 768, 'space surface');
    try {
      await open(p, `${base}#sample=sphere-tangled`);
      for (const id of ['node', 'save-figure', 'hist-log']) check(await p.locator(`#${id}`).isEnabled(), `#${id} works for a surface`);
      check(await p.locator('#smooth-node').isDisabled(), 'Smooth this node waits for a node');
      check(/tangent plane/.test(await p.textContent('#node-hint')), `the node hint: ${await p.textContent('#node-hint')}`);
      const a0 = await canvasInfo(p, 'mesh-a');
      const { node, fx, fy } = await pickNear(p, 'b');
      const { x, y } = await nowAt(p, 'b', fx, fy);
      // the node picked is a node of the face clicked: drawn near the click, on the near side
      const at = await screenOf(p, 'b', node);
      check(distance(at, { x, y }) < 40, `node ${node} is drawn at ${Math.round(at.x)},${Math.round(at.y)}, the click was at ${Math.round(x)},${Math.round(y)}`);
      check(at.behind < 0.5 * (await p.locator('#mesh-b').boundingBox()).width, `node ${node} is on the far side (${at.behind} px behind)`);
      // it is marked on both sides, and its level sets and solve are drawn
      await changed(p, 'mesh-a', a0);
      await nodeViewDrawn(p, 'a surface');
      const hint = await p.textContent('#node-hint');
      check(hint.startsWith(`Node ${node}: A, old`) && /tangent plane/.test(hint), `the summary: ${hint}`);
      check(await p.locator('#smooth-node').isEnabled(), 'Smooth this node is ready');
      check((await p.textContent('#node-badge')).includes(String(node)), 'the Node tab names the node');
      // a drag still turns the view and chooses nothing
      const b1 = await canvasInfo(p, 'mesh-b');
      const box = await p.locator('#mesh-b').boundingBox();
      await p.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await p.mouse.down();
      for (let k = 1; k <= 6; k++) await p.mouse.move(box.x + box.width / 2 + 10 * k, box.y + box.height / 2 + 3 * k);
      await p.mouse.up();
      await changed(p, 'mesh-b', b1);
      check((await p.inputValue('#node')) === String(node), 'a drag chose another node');
      // a click right on another node picks that node
      const other = await p.evaluate(async (n) => {
        for (let m = 0; m < 2000; m++) {
          if (m === n) continue;
          const s = await window.smoothlab.nodeOnScreen('b', m);
          if (s && s.behind < 5) return m;
        }
        return null;
      }, node);
      check(other !== null, 'a node at the front');
      const o = await screenOf(p, 'b', other);
      await clickAt(p, o.x, o.y);
      check((await p.inputValue('#node')) === String(other), `a click on node ${other} chose ${await p.inputValue('#node')}`);
      await p.fill('#node', String(node));
      await p.dispatchEvent('#node', 'change');
      await idle(p);
      await p.locator('#title-node').scrollIntoViewIfNeeded();
      await p.screenshot({ path: path.join(OUT, 'space-surface-node-1366x768.png') });

      // Smooth this node: one solver call on each side moves the node, on the sphere
      const before = await p.evaluate((n) => Promise.all([window.smoothlab.nodePoint('a', n), window.smoothlab.nodePoint('b', n)]), node);
      const m0 = await canvasInfo(p, 'mesh-b');
      await p.click('#smooth-node');
      await p.waitForFunction(() => /smoothed by one solver call/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      const after = await p.evaluate((n) => Promise.all([window.smoothlab.nodePoint('a', n), window.smoothlab.nodePoint('b', n)]), node);
      for (const k of [0, 1]) {
        check(after[k].some((v, i) => v !== before[k][i]), `side ${'ab'[k]} did not move node ${node}`);
        check(Math.abs(Math.hypot(...after[k]) - 1) < 1e-9, `the node left the unit sphere: ${after[k]}`);
      }
      check(/put back on the surface/.test(await p.textContent('#node-hint')), await p.textContent('#node-hint'));
      await changed(p, 'mesh-b', m0);
      check(await p.locator('#undo').isEnabled() && (await p.textContent('#undo')) === `Undo move of node ${node}`, `the Undo button: ${await p.textContent('#undo')}`);
      await p.click('#undo');
      await p.waitForFunction(() => /is back where it was/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      const back = await p.evaluate((n) => Promise.all([window.smoothlab.nodePoint('a', n), window.smoothlab.nodePoint('b', n)]), node);
      check(JSON.stringify(back) === JSON.stringify(before), `Undo: ${JSON.stringify(back)} is not ${JSON.stringify(before)}`);
      check(await p.locator('#undo').isDisabled(), 'nothing more to undo');
    } finally {
      await p.close();
    }
  });

  await test('a surface: the per-pass chart and the corner-angle histograms are drawn, and the figure for slides is saved', async () => {
    const p = await freshPage(context, 1366, 768, 'space charts');
    try {
      await open(p, `${base}#sample=torus-tangled`);
      const pass0 = await canvasInfo(p, 'pass-chart');
      const hist0 = await canvasInfo(p, 'hist-b');
      check(pass0.colours > 20 && hist0.colours > 20, `charts drawn: ${pass0.colours}, ${hist0.colours} colours`);
      check(/Corner angles, B/.test(await p.textContent('#hist-b + figcaption')), await p.textContent('#hist-b + figcaption'));
      await p.click('#step');
      await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      await changed(p, 'pass-chart', pass0);
      await changed(p, 'hist-b', hist0);
      // the side colours are in the pass chart (A orange, B blue)
      const sides = await p.evaluate(() => {
        const c = document.getElementById('pass-chart');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let orange = 0;
        let blue = 0;
        for (let i = 0; i < d.length; i += 4) {
          if (d[i] > 200 && d[i + 1] > 130 && d[i + 1] < 180 && d[i + 2] < 60) orange++;
          if (d[i] < 40 && d[i + 1] > 90 && d[i + 1] < 140 && d[i + 2] > 160) blue++;
        }
        return { orange, blue };
      });
      check(sides.orange > 20 && sides.blue > 20, `the pass chart's sides: ${JSON.stringify(sides)}`);
      await p.locator('.pass-view').scrollIntoViewIfNeeded();
      await p.screenshot({ path: path.join(OUT, 'space-surface-charts.png') });
      const [dl] = await Promise.all([p.waitForEvent('download'), p.click('#save-figure')]);
      const file = await dl.path();
      const [w, h] = pngSize(file);
      check(w === 2800 && h === 1560, `the figure is ${w} × ${h}`);
      check(/Saved a figure of 2800 × 1560 pixels/.test(await p.textContent('#figure-note')), await p.textContent('#figure-note'));
      await dl.saveAs(path.join(OUT, 'space-surface-figure.png'));
    } finally {
      await p.close();
    }
  });

  await test('a surface: the link keeps the node and the camera, and opens them again; an older link opens the starting camera', async () => {
    const p = await freshPage(context, 1366, 768, 'space link');
    try {
      await open(p, `${base}#sample=cylinder-capped`);
      const box = await p.locator('#mesh-a').boundingBox();
      await p.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await p.mouse.down();
      for (let k = 1; k <= 5; k++) await p.mouse.move(box.x + box.width / 2 - 9 * k, box.y + box.height / 2 + 5 * k);
      await p.mouse.up();
      await idle(p);
      await p.mouse.move(box.x + box.width / 2, box.y + box.height / 2);
      await p.mouse.wheel(0, -200);
      await idle(p);
      await p.waitForTimeout(100);
      await idle(p);
      const { node } = await pickNear(p, 'a');
      const camera = await p.evaluate(() => window.smoothlab.camera());
      check(camera.yaw !== 30 && camera.zoom > 1, `the camera turned and zoomed: ${JSON.stringify(camera)}`);
      const href = await p.getAttribute('#permalink', 'href');
      check(new RegExp(`&node=${node}&yaw=[0-9.e-]+&pitch=[-0-9.e]+&zoom=[0-9.e-]+`).test(href) && !/cut=/.test(href), `the link: ${href}`);
      const mesh = await canvasInfo(p, 'mesh-b');
      const level = await canvasInfo(p, 'level-b');
      // the link in a fresh page: the same node, camera and pictures
      const q = await freshPage(context, 1366, 768, 'space link opened');
      try {
        await open(q, new URL(href, base).toString());
        check((await q.inputValue('#node')) === String(node), `the link's node: ${await q.inputValue('#node')}`);
        const cam = await q.evaluate(() => window.smoothlab.camera());
        check(JSON.stringify(cam) === JSON.stringify(camera), `the link's camera ${JSON.stringify(cam)} is not ${JSON.stringify(camera)}`);
        check((await canvasInfo(q, 'mesh-b')).hash === mesh.hash, 'the view opened from the link differs');
        check((await canvasInfo(q, 'level-b')).hash === level.hash, 'the level sets opened from the link differ');
        // an older link (no camera keys): the camera as it starts, the node chosen
        await open(q, `${base}#sample=sphere-tangled&node=12`);
        check(JSON.stringify(await q.evaluate(() => window.smoothlab.camera())) === JSON.stringify({ yaw: 30, pitch: 25, zoom: 1 }), 'an older link opens the starting camera');
        check((await q.inputValue('#node')) === '12', 'and its node');
        await nodeViewDrawn(q, 'an older link');
      } finally {
        await q.close();
      }
    } finally {
      await p.close();
    }
  });

  await test('tetrahedra: a click on the cut picks a node of its face, its level sets over the cut plane moved to it; the cut axis turns that plane; Smooth this node and Undo; the link keeps node, camera and cut', async () => {
    const p = await freshPage(context, 1366, 768, 'space volume');
    try {
      await open(p, `${base}#sample=rand3d`);
      for (const id of ['node', 'save-figure', 'hist-log']) check(await p.locator(`#${id}`).isEnabled(), `#${id} works for tetrahedra`);
      const pass0 = await canvasInfo(p, 'pass-chart');
      check(pass0.colours > 20, `the per-pass chart is drawn (${pass0.colours} colours)`);
      check(/Dihedral angles, A/.test(await p.textContent('#hist-a + figcaption')), await p.textContent('#hist-a + figcaption'));
      // beside the mesh: no face, said in the tetrahedra's words
      const box = await p.locator('#mesh-a').boundingBox();
      await clickAt(p, box.x + 4, box.y + box.height / 2);
      check((await p.inputValue('#node')) === '' && /No face of a volume mesh there/.test(await p.textContent('#pick-note')), `beside the mesh: ${await p.textContent('#pick-note')}`);
      const { node, fx, fy } = await pickNear(p, 'a');
      const { x, y } = await nowAt(p, 'a', fx, fy);
      const at = await screenOf(p, 'a', node);
      check(distance(at, { x, y }) < 40, `node ${node} is drawn at ${Math.round(at.x)},${Math.round(at.y)}, the click was at ${Math.round(x)},${Math.round(y)}`);
      await nodeViewDrawn(p, 'tetrahedra');
      const hint = await p.textContent('#node-hint');
      check(hint.startsWith(`Node ${node}: A, old`) && /plane across z through the node/.test(hint) && !/surface|tangent/.test(hint), `the summary: ${hint}`);
      await p.screenshot({ path: path.join(OUT, 'space-volume-node-1366x768.png') });
      // across x: the level sets are drawn over the plane across x through the node
      const l0 = await canvasInfo(p, 'level-a');
      await p.selectOption('#cut-axis', '0');
      await changed(p, 'level-a', l0);
      check(/plane across x through the node/.test(await p.textContent('#node-hint')), await p.textContent('#node-hint'));
      await p.locator('#cut-at').fill('0.35');
      await idle(p);
      await p.waitForTimeout(100);
      await idle(p);
      // Smooth this node moves it in space; Undo puts it back
      const before = await p.evaluate((n) => window.smoothlab.nodePoint('b', n), node);
      await p.click('#smooth-node');
      await p.waitForFunction(() => /smoothed by one solver call/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      const after = await p.evaluate((n) => window.smoothlab.nodePoint('b', n), node);
      check(after.some((v, i) => v !== before[i]), `node ${node} did not move: ${after}`);
      await p.click('#undo');
      await p.waitForFunction(() => /is back where it was/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      check(JSON.stringify(await p.evaluate((n) => window.smoothlab.nodePoint('b', n), node)) === JSON.stringify(before), 'Undo put the node back');
      // a Step: the per-pass chart and the dihedral histograms follow
      const hist0 = await canvasInfo(p, 'hist-b');
      await p.click('#step');
      await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      await idle(p);
      await changed(p, 'pass-chart', pass0);
      await changed(p, 'hist-b', hist0);
      // the link keeps the node, the camera and the cut
      const href = await p.getAttribute('#permalink', 'href');
      check(new RegExp(`&node=${node}&yaw=30&pitch=25&zoom=1&cut=x&cut-at=0\\.35`).test(href), `the link: ${href}`);
      const mesh = await canvasInfo(p, 'mesh-a');
      const q = await freshPage(context, 1366, 768, 'space volume link');
      try {
        await open(q, new URL(href, base).toString());
        check((await q.inputValue('#node')) === String(node), 'the link\'s node');
        check((await q.inputValue('#cut-axis')) === '0' && (await q.inputValue('#cut-at')) === '0.35', `the link's cut: ${await q.inputValue('#cut-axis')} ${await q.inputValue('#cut-at')}`);
        check(/plane across x/.test(await q.textContent('#node-hint')), 'the level sets across x');
        // the link opens the mesh as loaded (passes are not run): the same cut view as before the Step
        await q.click('#step');
        await q.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
        await idle(q);
        check((await canvasInfo(q, 'mesh-a')).hash === mesh.hash, 'the view after one pass, opened from the link, differs');
      } finally {
        await q.close();
      }
      const [dl] = await Promise.all([p.waitForEvent('download'), p.click('#save-figure')]);
      const [w, h] = pngSize(await dl.path());
      check(w === 2800 && h === 1560, `the figure is ${w} × ${h}`);
      await dl.saveAs(path.join(OUT, 'space-volume-figure.png'));
    } finally {
      await p.close();
    }
  });

  await test('3D with a node picked on a phone (390×844) and in an 800×450 embed: drawn whole, no scrolling sideways', async () => {
    for (const [name, hash] of [['surface', '#sample=sphere-tangled&node=40'], ['volume', '#sample=rand3d&node=431&cut=z&cut-at=0.5']]) {
      const p = await freshPage(context, 390, 844, `space phone ${name}`);
      try {
        await open(p, `${base}${hash}`);
        const picked = await p.inputValue('#node');
        check(picked !== '', `${name}: the link's node on a phone`);
        const r = await reach(p);
        check(r.sw <= r.vw + 1, `${name}: the phone scrolls sideways (${r.sw} > ${r.vw})`);
        check((await canvasInfo(p, 'mesh-a')).colours > 50, `${name}: the view is drawn`);
        await p.screenshot({ path: path.join(OUT, `space-${name}-phone-390x844.png`) });
        await p.locator('#title-node').scrollIntoViewIfNeeded();
        await nodeViewDrawn(p, `${name} on a phone`);
        await p.screenshot({ path: path.join(OUT, `space-${name}-phone-390x844-node.png`) });
      } finally {
        await p.close();
      }
      const host = await freshPage(context, 840, 500, `space embed ${name}`);
      try {
        for (const [kind, view] of [['compact', ''], ['levelset', '&view=levelset']]) {
          const frame = await hostFrame(host, `${base}?embed=1${view}${hash}`, 800, 450);
          const r = await reach(frame);
          check(r.sh <= r.vh + 1 && r.sw <= r.vw + 1, `${name} ${kind}: the embed scrolls (${r.sw}×${r.sh} in ${r.vw}×${r.vh})`);
          for (const id of kind === 'levelset' ? ['level-a', 'level-b'] : ['mesh-a', 'mesh-b']) {
            const c = await canvasInfo(frame, id);
            check(c.colours > 40, `${name} ${kind}: #${id} is blank (${c.colours} colours)`);
          }
          await host.screenshot({ path: path.join(OUT, `space-${name}-embed-${kind}-800x450.png`) });
        }
      } finally {
        await host.close();
      }
    }
  });

  await test('an embedded level-set view of tetrahedra without a node opens on the worst node', async () => {
    const host = await freshPage(context, 840, 500, 'space embed worst');
    try {
      const frame = await hostFrame(host, `${base}?embed=1&view=levelset#sample=rand3d`, 800, 450);
      check((await frame.inputValue('#node')) !== '', 'no node was chosen');
      check((await canvasInfo(frame, 'level-b')).colours > 40, 'the level sets are blank');
      const statsB = await stats(frame, 'b');
      check(statsB.nodes === '1086', `rand3D: ${JSON.stringify(statsB)}`);
    } finally {
      await host.close();
    }
  });
}

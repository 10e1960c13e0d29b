// The picture first (issue 27): the two meshes on the first screen at every desktop size,
// one mesh with Step on a phone, a chosen node's level sets beside the meshes, embeds that
// fill every frame (also under a CSS transform), the presenter's keys, fullscreen and the
// dark theme the pictures follow. Screenshots go to test-output/browser/ (the README's).
import path from 'node:path';
import { OUT, TIMEOUT, test, check, watch, idle, open, canvasInfo, clickSomeNode, ringPoints, freshPage, hostFrame, reach } from '../lib.mjs';

/** The CSS-pixel box of an element of `where` (a page or a frame), or null if not shown. */
function box(where, selector) {
  return where.evaluate((sel) => {
    const el = document.querySelector(sel);
    if (!el || el.getClientRects().length === 0) return null;
    const r = el.getBoundingClientRect();
    if (r.width === 0 || r.height === 0) return null;
    return { x: r.left, y: r.top, w: r.width, h: r.height, r: r.right, b: r.bottom };
  }, selector);
}
function inView(b, vw, vh) {
  return b !== null && b.x >= -0.5 && b.y >= -0.5 && b.r <= vw + 0.5 && b.b <= vh + 0.5;
}
const say = (b) => (b ? `${Math.round(b.x)},${Math.round(b.y)} ${Math.round(b.w)}×${Math.round(b.h)}` : 'not shown');

/** Resizes the host's iframe and waits until the page inside has fitted itself again. */
async function resizeFrame(p, frame, w, h) {
  await p.evaluate(([w, h]) => {
    const f = document.getElementById('f');
    f.style.width = `${w}px`;
    f.style.height = `${h}px`;
    document.getElementById('wrap').style.width = `${w}px`;
  }, [w, h]);
  await frame.waitForFunction(([w, h]) => window.innerWidth === w && window.innerHeight === h, [w, h], { timeout: TIMEOUT });
  await new Promise((r) => setTimeout(r, 250)); // the page's resize waits 150 ms
  await frame.waitForFunction(() => document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
}

const FRAMES = [[520, 520], [520, 760], [800, 450], [1280, 720], [390, 844]];
/** Each embed, and the canvases that are its picture. */
const EMBEDS = [
  ['compact', '?embed=1#sample=plate-tri-tangled&passes=3', ['#mesh-a', '#mesh-b']],
  // the opening sample, whose longer name made the status wrap after the frame was fitted
  ['compact-opening', '?embed=1', ['#mesh-a', '#mesh-b']],
  ['mesh', '?embed=1&view=mesh#sample=plate-tri-tangled', ['#mesh-a', '#mesh-b']],
  ['compare', '?embed=1&view=compare#sample=plate-tri-tangled&passes=1', ['#mesh-a', '#mesh-b']],
  ['levelset', '?embed=1&view=levelset#sample=plate-tri-tangled&node=200', ['#level-a', '#level-b']],
  ['history', '?embed=1&view=history#sample=plate-tri-tangled&passes=2', ['#pass-chart']],
  ['histogram', '?embed=1&view=histogram#sample=plate-tri-tangled&passes=2', ['#hist-a', '#hist-b']],
  ['chen-10', '?embed=1#figure=chen-10', ['#tour-picture']],
  ['freitag-t1', '?embed=1#figure=freitag-t1', ['#tour-picture']],
];

export default async function ({ server, context }) {
  await test('the first screen: both meshes whole, side by side, equal and ≥ 300 px, Step/Run/Reset and the status in view (1366×768, 1920×1080, 1024×768)', async () => {
    for (const [w, h] of [[1366, 768], [1920, 1080], [1024, 768]]) {
      const p = await freshPage(context, w, h, `first-screen ${w}`);
      try {
        await open(p, `${server.base}#sample=plate-tri-tangled`);
        const a = await box(p, '#mesh-a');
        const b = await box(p, '#mesh-b');
        check(inView(a, w, h) && inView(b, w, h), `${w}×${h}: meshes not whole on the first screen: A ${say(a)}, B ${say(b)}`);
        check(a.w >= 300 && a.h >= 300 && Math.abs(a.w - b.w) < 1 && Math.abs(a.h - b.h) < 1, `${w}×${h}: sizes A ${say(a)}, B ${say(b)}`);
        check(Math.abs(a.y - b.y) < 1 && b.x >= a.r, `${w}×${h}: A and B not side by side at one height: A ${say(a)}, B ${say(b)}`);
        const pa = await box(p, '#panel-a');
        const pb = await box(p, '#panel-b');
        check(Math.abs(pa.h - pb.h) < 1, `${w}×${h}: panel heights ${pa.h} and ${pb.h}`);
        for (const id of ['#step', '#run', '#reset', '#status', '#progress', '#sample']) {
          check(inView(await box(p, id), w, h), `${w}×${h}: ${id} is not in view: ${say(await box(p, id))}`);
        }
        // Run becomes Stop while running: the same button, in view
        await p.screenshot({ path: path.join(OUT, `first-screen-${w}x${h}.png`) });
        const before = await canvasInfo(p, 'mesh-b');
        await p.click('#step');
        await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
        await idle(p);
        check((await canvasInfo(p, 'mesh-b')).hash !== before.hash, 'Step changed nothing in view');
        check((await p.evaluate(() => window.scrollY)) === 0, 'the page scrolled');
      } finally {
        await p.close();
      }
    }
  });

  await test('a chosen node: its two level sets open side by side beside the meshes, each at least 300 px wide, all in view', async () => {
    const p = await freshPage(context, 1366, 768, 'node beside');
    try {
      await open(p, `${server.base}#sample=plate-tri-tangled`);
      const { node } = await clickSomeNode(p, 'mesh-a', ringPoints());
      await idle(p);
      check((await p.textContent('#node-badge')) === String(node), 'the Node button shows the node');
      await p.waitForTimeout(100);
      const [la, lb] = [await box(p, '#level-a'), await box(p, '#level-b')];
      for (const [name, lv] of [['A', la], ['B', lb]]) {
        check(inView(lv, 1366, 768), `${name}'s level sets are not in view: ${say(lv)}`);
        check(lv.w >= 300, `${name}'s level sets are ${Math.round(lv.w)} px wide`);
      }
      check(Math.abs(la.y - lb.y) < 1 && lb.x >= la.r, `not side by side: A ${say(la)}, B ${say(lb)}`);
      check(la.x >= (await box(p, '#mesh-b')).r, 'the level sets are not beside the meshes');
      check(inView(await box(p, '#mesh-a'), 1366, 768) && inView(await box(p, '#mesh-b'), 1366, 768), 'the meshes left the screen');
      for (const id of ['level-a', 'level-b']) check((await canvasInfo(p, id)).colours > 20, `${id} is not drawn`);
      // drawn at the size they are shown, as the meshes are after the column widened
      const sized = await p.evaluate(() => ['level-a', 'mesh-a'].map((id) => {
        const c = document.getElementById(id);
        return Math.abs(c.width / Math.min(window.devicePixelRatio || 1, 2) - c.clientWidth) <= 1;
      }));
      check(sized.every(Boolean), `a canvas is not drawn at its size: ${sized}`);
      check((await p.getAttribute('#tabbtn-node', 'aria-current')) === 'true', 'the Node button is not marked');
      await p.screenshot({ path: path.join(OUT, 'first-screen-node-1366x768.png') });
      const narrow = await box(p, '#mesh-a');
      await p.click('#tabbtn-settings');
      await idle(p);
      check(inView(await box(p, '#strategy'), 1366, 768), 'Settings brings the controls back');
      const wide = await box(p, '#mesh-a');
      check(wide.w > narrow.w + 50, `the meshes do not take the room back: ${say(narrow)} → ${say(wide)}`);
    } finally {
      await p.close();
    }
  });

  await test('on a phone (390×844): one mesh at a time with Step on the same screen, an A/B switch, no sideways scrolling', async () => {
    const p = await freshPage(context, 390, 844, 'phone');
    try {
      await open(p, `${server.base}#sample=plate-tri-tangled`);
      const a = await box(p, '#mesh-a');
      check(inView(a, 390, 844) && a.w >= 340, `A: ${say(a)}`);
      check((await box(p, '#mesh-b')) === null, 'B shows beside A on a phone');
      for (const id of ['#step', '#run', '#reset', '#show-b']) check(inView(await box(p, id), 390, 844), `${id} is not on A's screen: ${say(await box(p, id))}`);
      const r = await reach(p);
      check(r.sw <= 390, `the page scrolls sideways: ${r.sw} px wide`);
      await p.screenshot({ path: path.join(OUT, 'phone-390x844-a.png') });
      await p.click('#show-b');
      await idle(p);
      const b = await box(p, '#mesh-b');
      check(inView(b, 390, 844) && (await box(p, '#mesh-a')) === null, `B: ${say(b)}`);
      check((await canvasInfo(p, 'mesh-b')).colours > 20, 'B is not drawn');
      check(inView(await box(p, '#step'), 390, 844), 'Step is not on B\'s screen');
      await p.click('#step');
      await p.waitForFunction(() => /One pass done/.test(document.getElementById('status').textContent), null, { timeout: TIMEOUT });
      check(inView(await box(p, '#status'), 390, 844), 'the status is not on the screen');
      await p.screenshot({ path: path.join(OUT, 'phone-390x844-b.png') });
    } finally {
      await p.close();
    }
  });

  await test('on a phone (390×844): a figure\'s picture fits its card, its panels chosen for the width (none shrunk, none scrolled sideways)', async () => {
    const p = await freshPage(context, 390, 844, 'phone-figure');
    try {
      await open(p, `${server.base}#figure=chen-2`);
      await p.waitForFunction(() => document.body.dataset.figure === 'chen-2', null, { timeout: TIMEOUT });
      await idle(p);
      const pic = await box(p, '#tour-picture');
      check(pic !== null && pic.w > 300 && pic.x >= 0 && pic.x + pic.w <= 390, `the picture: ${say(pic)}`);
      check((await canvasInfo(p, 'tour-picture')).colours > 5, 'the picture is not drawn');
      const fig = await p.evaluate(() => {
        const f = document.querySelector('.tour-figure');
        return { sw: f.scrollWidth, cw: f.clientWidth };
      });
      check(fig.sw <= fig.cw + 1, `the figure scrolls sideways in its card: ${fig.sw} in ${fig.cw}`);
      const r = await reach(p);
      check(r.sw <= 390, `the page scrolls sideways: ${r.sw} px wide`);
      await p.screenshot({ path: path.join(OUT, 'phone-390x844-figure.png') });
    } finally {
      await p.close();
    }
  });

  await test('every embed fills frames of 520×520, 520×760, 800×450, 1280×720 and 390×844 without scrolling, its picture ≥ 40 % of the short side', async () => {
    const p = await freshPage(context, 1400, 900, 'embeds');
    try {
      for (const [name, query, pictures] of EMBEDS) {
        const [w0, h0] = FRAMES[0];
        const frame = await hostFrame(p, `${server.base}${query}`, w0, h0);
        for (const [w, h] of FRAMES) {
          await resizeFrame(p, frame, w, h);
          const r = await reach(frame);
          check(r.r <= w + 0.5 && r.b <= h + 0.5 && r.sw <= w && r.sh <= h, `${name} at ${w}×${h}: content reaches ${Math.round(r.r)}×${Math.round(r.b)} (scroll ${r.sw}×${r.sh})`);
          const short = Math.min(w, h);
          for (const sel of pictures) {
            const b = await box(frame, sel);
            check(b !== null && inView(b, w, h), `${name} at ${w}×${h}: ${sel} not whole in the frame: ${say(b)}`);
            // a picture's extent along its long side, against the frame's short side
            check(Math.max(b.w, b.h) >= 0.4 * short && Math.min(b.w, b.h) >= 0.25 * short, `${name} at ${w}×${h}: ${sel} is ${say(b)}, under 40 % of ${short}`);
          }
          if ([[800, 450], [520, 520], [390, 844]].some(([x, y]) => x === w && y === h)) {
            await p.locator('#f').screenshot({ path: path.join(OUT, `embed-${name}-${w}x${h}.png`) });
          }
        }
      }
    } finally {
      await p.close();
    }
  });

  await test('an embed without its caption (&caption=0) gives the picture the room; the meshes never shrink to a dot', async () => {
    const p = await freshPage(context, 1400, 900, 'caption=0');
    try {
      let frame = await hostFrame(p, `${server.base}?embed=1&view=mesh#sample=plate-tri-tangled`, 800, 450);
      const withCaption = await box(frame, '#mesh-a');
      check((await box(frame, '#title-a')) !== null, 'the caption is shown by default');
      frame = await hostFrame(p, `${server.base}?embed=1&view=mesh&caption=0#sample=plate-tri-tangled`, 800, 450);
      const without = await box(frame, '#mesh-a');
      check((await box(frame, '#title-a')) === null, 'caption=0 still shows the titles');
      check(without.h > withCaption.h, `no room given back: ${say(withCaption)} → ${say(without)}`);
      check((await canvasInfo(frame, 'mesh-a')).colours > 20, 'the mesh is not drawn');
    } finally {
      await p.close();
    }
  });

  await test('an embed under a CSS transform (0.75 and 1.5, as reveal.js scales a slide): whole, and a click chooses a node', async () => {
    const p = await freshPage(context, 1400, 900, 'transform');
    try {
      for (const scale of [0.75, 1.5]) {
        const frame = await hostFrame(p, `${server.base}?embed=1#sample=plate-tri-tangled`, 800, 450, { scale });
        const r = await reach(frame);
        check(r.r <= 800.5 && r.b <= 450.5, `scale ${scale}: content reaches ${r.r}×${r.b}`);
        // a click where the user sees the mesh: the iframe's transformed box on the screen,
        // and the point in it scaled as the frame is
        const fb = await p.evaluate(() => {
          const r = document.getElementById('f').getBoundingClientRect();
          return { x: r.left, y: r.top };
        });
        const b = await box(frame, '#mesh-a');
        let chosen = '';
        for (const [fx, fy] of ringPoints()) {
          await p.mouse.click(fb.x + (b.x + fx * b.w) * scale, fb.y + (b.y + fy * b.h) * scale);
          await frame.waitForFunction(() => document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
          chosen = await frame.inputValue('#node');
          if (chosen !== '') break;
        }
        check(chosen !== '', `scale ${scale}: no click chose a node`);
        await p.screenshot({ path: path.join(OUT, `embed-transform-${scale}.png`) });
      }
    } finally {
      await p.close();
    }
  });

  await test('presenting: →, PageDown and Space go on, ← and PageUp back, Home to the first; not while typing; F fullscreen, Esc leaves', async () => {
    const p = await freshPage(context, 1366, 768, 'keys');
    try {
      await open(p, `${server.base}#figure=chen-2`);
      const names = await p.evaluate(() => [...document.getElementById('tour-menu').options].map((o) => o.value));
      const at = () => p.evaluate(() => window.smoothlab.figure() && window.smoothlab.figure().name);
      const press = async (key, want) => {
        await p.keyboard.press(key);
        await p.waitForFunction((n) => document.body.dataset.figure === n && document.body.dataset.busy === '0', want, { timeout: TIMEOUT });
        check((await at()) === want, `${key}: at ${await at()}, not ${want}`);
      };
      await p.locator('body').click({ position: { x: 5, y: 5 } });
      await press('ArrowRight', names[1]);
      await press('PageDown', names[2]);
      await press('Space', names[3]);
      await press('ArrowLeft', names[2]);
      await press('PageUp', names[1]);
      await press('Home', names[0]);
      // typing in a field keeps its keys
      await p.focus('#passes');
      await p.keyboard.press('ArrowRight');
      await p.keyboard.press('Space');
      await p.waitForTimeout(200);
      check((await at()) === names[0], 'a key typed in a field moved the tour');
      await p.locator('body').click({ position: { x: 5, y: 5 } });
      await p.keyboard.press('f');
      await p.waitForFunction(() => document.fullscreenElement !== null, null, { timeout: 5000 });
      await p.waitForFunction(() => document.getElementById('fullscreen').getAttribute('aria-pressed') === 'true', null, { timeout: 5000 });
      await p.keyboard.press('Escape');
      await p.waitForFunction(() => document.fullscreenElement === null, null, { timeout: 5000 });
      await p.click('#fullscreen');
      await p.waitForFunction(() => document.fullscreenElement !== null, null, { timeout: 5000 });
      await p.click('#fullscreen');
      await p.waitForFunction(() => document.fullscreenElement === null, null, { timeout: 5000 });
      // Esc, not in fullscreen, closes the tour
      await p.keyboard.press('Escape');
      await p.waitForFunction(() => document.getElementById('tour').hidden, null, { timeout: 5000 });
    } finally {
      await p.close();
    }
  });

  await test('the dark projector theme: the toggle, the system\'s preference and ?theme= choose it, and the pictures follow', async () => {
    const p = await freshPage(context, 1366, 768, 'theme');
    const corner = (id) => p.evaluate((id) => [...document.getElementById(id).getContext('2d').getImageData(2, 2, 1, 1).data].slice(0, 3), id);
    const lum = ([r, g, b]) => 0.2126 * r + 0.7152 * g + 0.0722 * b;
    try {
      await open(p, `${server.base}#sample=plate-tri-tangled`);
      check((await p.evaluate(() => document.documentElement.dataset.theme)) === 'light', 'light by default');
      check(lum(await corner('mesh-a')) > 200, `a light picture: ${await corner('mesh-a')}`);
      await p.click('#theme-toggle');
      await idle(p);
      check((await p.evaluate(() => document.documentElement.dataset.theme)) === 'dark', 'the toggle chose dark');
      check(lum(await corner('mesh-a')) < 60 && lum(await corner('mesh-b')) < 60, `the pictures did not follow: ${await corner('mesh-a')}`);
      const bg = await p.evaluate(() => getComputedStyle(document.documentElement).backgroundColor);
      check(/rgb\((\d+), (\d+), (\d+)\)/.test(bg) && lum(bg.match(/\d+/g).map(Number)) < 60, `the page is not dark: ${bg}`);
      await p.screenshot({ path: path.join(OUT, 'dark-1366x768.png') });
      // the choice is kept for the next visit; ?theme=light overrides it
      await p.reload();
      await idle(p);
      check((await p.evaluate(() => document.documentElement.dataset.theme)) === 'dark', 'the choice was not kept');
      await p.evaluate(() => localStorage.clear());
      await open(p, `${server.base}?theme=light#sample=plate-tri`);
      check(lum(await corner('mesh-a')) > 200, '?theme=light is not light');
    } finally {
      await p.close();
    }
    const q = await context.browser().newContext({ viewport: { width: 1366, height: 768 }, colorScheme: 'dark' });
    try {
      const p2 = await q.newPage();
      watch(p2, 'system dark');
      await open(p2, `${server.base}#sample=plate-tri`);
      check((await p2.evaluate(() => document.documentElement.dataset.theme)) === 'dark', 'prefers-color-scheme: dark is not followed');
    } finally {
      await q.close();
    }
  });
}

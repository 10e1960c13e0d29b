// Slides: the page in a reveal.js deck, as docs/teaching.md shows it (`<iframe data-src=...>`).
// A deck of three slides (a title, the figure chen-10, the tangled plate set for 3 passes),
// loading reveal.js from this folder's node_modules (a dev dependency, no CDN), is served
// from a second 127.0.0.1 port (the course page's host; the page's is another) and shown at
// 1280×720: the frames stay empty away from their slides, the figure's embed draws and fills
// its frame under reveal.js's scale, and once reveal.js has unloaded a frame (its slide
// left) and loaded it again, the page inside is a new document with the same state.
import { cpSync, existsSync, mkdtempSync, rmSync, writeFileSync } from 'node:fs';
import { tmpdir } from 'node:os';
import path from 'node:path';
import { fileURLToPath } from 'node:url';
import { startServer } from '../serve.mjs';
import { OUT, TIMEOUT, test, check, watch, canvasInfo, stats, reach } from '../lib.mjs';

const DIST = path.join(path.dirname(fileURLToPath(import.meta.url)), '..', 'node_modules', 'reveal.js', 'dist');

function deck(base) {
  return `<!doctype html>
<html><head><meta charset="utf-8"><title>smoothlab in reveal.js</title>
<link rel="stylesheet" href="dist/reset.css"><link rel="stylesheet" href="dist/reveal.css">
<link rel="stylesheet" href="dist/theme/white.css"><link rel="icon" href="data:,"></head>
<body><div class="reveal"><div class="slides">
  <section><h2>Mesh smoothing</h2><p>max-min against smooth objectives</p></section>
  <section><iframe id="fig" data-src="${base}?embed=1#figure=chen-10" title="smoothlab: Chen et al. (2003), Fig. 10, live"
    width="800" height="450" style="border:0"></iframe></section>
  <section><iframe id="plate" data-src="${base}?embed=1#sample=plate-tri-tangled&passes=3" title="smoothlab: the tangled plate"
    width="800" height="450" style="border:0"></iframe></section>
</div></div>
<script src="dist/reveal.js"></script>
<script>Reveal.initialize({ transition: 'none' }).then(() => { document.body.dataset.deck = 'ready'; });</script>
</body></html>`;
}

/** The iframe `id` of the deck: its attributes, its document's address, and whether it is
 * a frame playwright sees (null when reveal.js has not loaded it). */
async function frameOf(p, id) {
  const el = await p.$(`#${id}`);
  return { src: await el.getAttribute('src'), dataSrc: await el.getAttribute('data-src'), frame: await el.contentFrame() };
}

/** Waits until iframe `id` holds the page (an address of `base`: the page writes its whole
 * state into its hash once open) drawn (`until` true in it), and returns its frame. */
async function drawn(p, id, base, until) {
  const t0 = Date.now();
  for (;;) {
    const { frame } = await frameOf(p, id);
    if (frame && frame.url().startsWith(`${base}?embed=1#`)) {
      await frame.waitForFunction(until, null, { timeout: TIMEOUT });
      return frame;
    }
    check(Date.now() - t0 < TIMEOUT, `#${id} never loaded the page (it is at ${frame ? frame.url() : 'no frame'})`);
    await p.waitForTimeout(100);
  }
}

/** Goes to slide `h` by reveal.js's API and waits until it is the present one. */
async function slide(p, h) {
  await p.evaluate((h) => Reveal.slide(h), h);
  await p.waitForFunction((h) => Reveal.getIndices().h === h, h, { timeout: TIMEOUT });
}

export default async function ({ server, browser }) {
  const dir = mkdtempSync(path.join(tmpdir(), 'smoothlab-deck-'));
  let host = null;
  let context = null;
  const FIG = `${server.base}?embed=1#figure=chen-10`;
  const PLATE = `${server.base}?embed=1#sample=plate-tri-tangled&passes=3`;
  const figureDrawn = () => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' && document.body.dataset.figure === 'chen-10';
  const plateDrawn = () => document.body.dataset.ready === '1' && document.body.dataset.busy === '0' &&
    document.body.dataset.hash === location.hash && document.querySelectorAll('#stats-b tr[data-stat]').length > 0;
  // the plate's state as the page shows it: the sample, the passes, the statistics of B
  const plateState = async (f) => ({ sample: await f.inputValue('#sample'), passes: await f.inputValue('#passes'), stats: await stats(f, 'b') });
  try {
    let p = null;
    // the page's documents the deck asked for: the embeds' own requests to the page's server
    const loads = [];
    let before = null;
    await test('slides: a reveal.js deck (the npm package, no CDN) holds the page by data-src, not loaded away from its slide', async () => {
      check(existsSync(path.join(DIST, 'reveal.js')), `reveal.js is not installed: run \`npm ci\` in tests/browser (${DIST})`);
      cpSync(DIST, path.join(dir, 'dist'), { recursive: true });
      host = await startServer(dir);
      writeFileSync(path.join(dir, 'index.html'), deck(server.base));
      context = await browser.newContext({ viewport: { width: 1280, height: 720 } });
      p = await context.newPage();
      p.setDefaultTimeout(TIMEOUT);
      watch(p, 'slides');
      p.on('request', (r) => { if (r.url().startsWith(`${server.base}?embed=1`)) loads.push(r.url()); });
      await p.goto(host.base);
      await p.waitForFunction(() => document.body.dataset.deck === 'ready', null, { timeout: TIMEOUT });
      check((await p.evaluate(() => Reveal.getIndices().h)) === 0, 'the deck opens on its title');
      await p.waitForTimeout(1000); // time for a frame that would load to ask for the page
      for (const [id, want] of [['fig', FIG], ['plate', PLATE]]) {
        const f = await frameOf(p, id);
        check(f.src === null && f.dataSrc === want, `#${id} on the title slide: src ${f.src}, data-src ${f.dataSrc}`);
        check(!f.frame || ['about:blank', ''].includes(f.frame.url()), `#${id} holds ${f.frame && f.frame.url()} on the title slide`);
      }
      check(loads.length === 0, `the page was asked for from the title slide: ${loads.join(', ')}`);
    });

    await test('slides: on its slide (→) the figure\'s embed draws and fills its 800×450 frame under reveal.js\'s scale', async () => {
      check(p !== null, 'no deck');
      await p.locator('.reveal').click({ position: { x: 5, y: 5 } }); // the deck has the keys
      await p.keyboard.press('ArrowRight');
      await p.waitForFunction(() => Reveal.getIndices().h === 1, null, { timeout: TIMEOUT });
      const frame = await drawn(p, 'fig', server.base, figureDrawn);
      // the next slide is within reveal.js's viewDistance (3), but a frame without
      // data-preload loads only when its slide is shown
      check((await frameOf(p, 'plate')).src === null, 'the next slide\'s frame loaded early');
      const c = await canvasInfo(frame, 'tour-picture');
      check(c.colours > 100, `the figure looks blank (${c.colours} colours)`);
      // reveal.js scales the slide (960×700 into 1280×720): the frame is 800×450 CSS pixels
      // inside and 800×450 times the scale on the screen
      const scale = await p.evaluate(() => Reveal.getScale());
      const tr = await p.evaluate(() => document.querySelector('.reveal .slides').style.transform);
      check(scale !== 1 && tr.includes(`scale(${scale})`), `reveal.js's transform: ${tr} (scale ${scale})`);
      const onScreen = await p.locator('#fig').boundingBox();
      check(Math.abs(onScreen.width - 800 * scale) < 1.5 && Math.abs(onScreen.height - 450 * scale) < 1.5, `the frame on the screen: ${onScreen.width}×${onScreen.height} at scale ${scale}`);
      check(onScreen.x >= 0 && onScreen.y >= 0 && onScreen.x + onScreen.width <= 1280 && onScreen.y + onScreen.height <= 720, `the frame is off the screen: ${JSON.stringify(onScreen)}`);
      const r = await reach(frame);
      check(r.vw === 800 && r.vh === 450, `the page's window in the frame: ${r.vw}×${r.vh}`);
      check(r.r <= 800.5 && r.b <= 450.5 && r.sw <= 800 && r.sh <= 450, `the embed overflows its frame: reaches ${Math.round(r.r)}×${Math.round(r.b)}, scrolls ${r.sw}×${r.sh}`);
      check(r.r >= 0.9 * 800 && r.b >= 0.9 * 450, `the embed leaves its frame empty: reaches ${Math.round(r.r)}×${Math.round(r.b)} of 800×450`);
      const pic = await frame.evaluate(() => {
        const q = document.getElementById('tour-picture').getBoundingClientRect();
        return { x: q.left, y: q.top, r: q.right, b: q.bottom, w: q.width, h: q.height };
      });
      check(pic.x >= -0.5 && pic.y >= -0.5 && pic.r <= 800.5 && pic.b <= 450.5 && Math.max(pic.w, pic.h) >= 0.4 * 450, `the figure's picture in the frame: ${JSON.stringify(pic)}`);
      await p.screenshot({ path: path.join(OUT, 'slides-chen-10-1280x720.png') });
      before = { hash: c.hash, url: frame.url(), text: await frame.evaluate(() => document.body.innerText) };
      await frame.evaluate(() => { window.smoothlabDeckMark = 1; }); // gone once the document is new
      check(loads.length === 1, `the page was asked for ${loads.length} times: ${loads.join(', ')}`);
    });

    await test('slides: left, reveal.js unloads the figure\'s frame; back, the page is loaded again and drawn as it was (its address)', async () => {
      check(before !== null, 'the figure was not drawn');
      await slide(p, 2);
      const gone = await frameOf(p, 'fig');
      check(gone.src === null && gone.dataSrc === FIG, `the figure's frame after its slide was left: src ${gone.src}, data-src ${gone.dataSrc}`);
      check(!gone.frame || ['about:blank', ''].includes(gone.frame.url()), `the figure's frame still holds ${gone.frame && gone.frame.url()}`);
      // the next slide's frame, the tangled plate set for 3 passes, is loaded and drawn meanwhile
      const plate = await drawn(p, 'plate', server.base, plateDrawn);
      const s = await plateState(plate);
      check(s.sample === 'sample:plate-tri-tangled' && s.passes === '3' && Number(s.stats.inverted) > 0, `the plate: ${JSON.stringify(s)}`);
      check((await canvasInfo(plate, 'mesh-b')).colours > 20, 'the plate is not drawn');
      const plateUrl = plate.url();
      await plate.evaluate(() => { window.smoothlabDeckMark = 1; });
      await slide(p, 0);
      check((await frameOf(p, 'plate')).src === null, 'the plate\'s frame was not unloaded');
      await slide(p, 1);
      const frame = await drawn(p, 'fig', server.base, figureDrawn);
      check((await frame.evaluate(() => window.smoothlabDeckMark)) === undefined, 'the frame was not loaded again (the old document is still there)');
      check(frame.url() === before.url, `the page's address: ${frame.url()}, was ${before.url}`);
      const c = await canvasInfo(frame, 'tour-picture');
      check(c.colours > 100 && c.hash === before.hash, `the figure is not drawn as it was: ${c.colours} colours, hash ${c.hash} vs ${before.hash}`);
      check((await frame.evaluate(() => document.body.innerText)) === before.text, 'the figure\'s words changed');
      // the plate comes back with the same statistics too
      await slide(p, 2);
      const again = await drawn(p, 'plate', server.base, plateDrawn);
      check((await again.evaluate(() => window.smoothlabDeckMark)) === undefined, 'the plate\'s frame was not loaded again');
      check(again.url() === plateUrl, `the plate's address: ${again.url()}, was ${plateUrl}`);
      const s2 = await plateState(again);
      check(JSON.stringify(s2) === JSON.stringify(s), `the plate: ${JSON.stringify(s2)}, was ${JSON.stringify(s)}`);
      check(loads.length === 4, `the page was asked for ${loads.length} times (4 loads of the two frames): ${loads.join(', ')}`);
    });
  } finally {
    if (context) await context.close();
    if (host) host.proc.kill();
    rmSync(dir, { recursive: true, force: true });
  }
}

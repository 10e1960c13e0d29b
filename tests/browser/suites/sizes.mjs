// Every figure of the tour keeps its claim at every size (issue 59): in ?embed=1 iframes of
// 800×450, 520×520 and 1280×720 and on the page on a 390×844 phone, the claim and the
// measured text's key sentence (its first, with the key numbers) are on the first screen, whole (not clipped by a box, not
// scrolled away, not cut by a line clamp), and the picture is whole with every text in it
// at least the page's smallest label, none cut to "…" and none running off the picture —
// read from the boxes the core records as it draws each text (tourPictureLayout), checked
// against the canvas's pixels. A title too wide for its panel keeps its leading clauses
// only where the clauses left out hold no digit (Theme::fit_title), else it is cut to "…":
// so no text cut means no number of a title lost.
import path from 'node:path';
import { OUT, TIMEOUT, test, check, idle, open, freshPage, hostFrame } from '../lib.mjs';

/** The page's smallest label, CSS px (present.js: LABEL_PX). */
const LABEL_PX = 14;
/** The sizes: three iframes as course pages and slides hold them, and a phone's page. */
const SIZES = [
  { name: '800×450', w: 800, h: 450, embed: true },
  { name: '520×520', w: 520, h: 520, embed: true },
  { name: '1280×720', w: 1280, h: 720, embed: true },
  { name: 'phone 390×844', w: 390, h: 844, embed: false },
];

/** Calls the core's wasm export `fn` with `args` in `where` (the page's own module). */
function core(where, fn, ...args) {
  return where.evaluate(async ([fn, args]) => {
    const m = await import('/pkg/smoothlab.js');
    if (!window.__coreReady) window.__coreReady = m.default();
    await window.__coreReady;
    return m[fn](...args);
  }, [fn, args]);
}

/** Where the words `want` are seen in `where`'s window: the line boxes of the first text
 * of the tour's words (#tour-text) that holds them, and the first box (an ancestor, or a
 * line clamp) that clips them, with the window's scroll and the words' font size. */
function wordsSeen(where, want) {
  return where.evaluate((want) => {
    const root = document.getElementById('tour-text');
    const walk = document.createTreeWalker(root, NodeFilter.SHOW_TEXT);
    let node = null;
    let at = -1;
    while (walk.nextNode()) {
      at = walk.currentNode.data.indexOf(want);
      if (at >= 0) {
        node = walk.currentNode;
        break;
      }
    }
    if (!node) return { missing: true };
    const range = document.createRange();
    range.setStart(node, at);
    range.setEnd(node, at + want.length);
    const rects = [...range.getClientRects()].filter((r) => r.width > 0 && r.height > 0).map((r) => ({ x: r.left, y: r.top, r: r.right, b: r.bottom }));
    let clipped = null;
    for (let a = node.parentElement; a && a !== document.documentElement; a = a.parentElement) {
      const cs = getComputedStyle(a);
      if (cs.visibility === 'hidden' || cs.display === 'none') clipped = `${a.id || a.className || a.tagName} is hidden`;
      const clamp = cs.webkitLineClamp && cs.webkitLineClamp !== 'none';
      const clips = cs.overflowX !== 'visible' || cs.overflowY !== 'visible' || clamp;
      if (!clips || clipped) continue;
      const q = a.getBoundingClientRect();
      // the box clips what lies outside it, and a clamp what lies past its lines
      const inside = rects.every((r) => r.x >= q.left - 0.5 && r.r <= q.right + 0.5 && r.y >= q.top - 0.5 && r.b <= q.bottom + 0.5);
      if (!inside || (clamp && a.scrollHeight > a.clientHeight + 1)) clipped = `${a.id || a.className || a.tagName} clips it`;
    }
    return { rects, clipped, font: parseFloat(getComputedStyle(node.parentElement).fontSize), vw: window.innerWidth, vh: window.innerHeight, scrollY: window.scrollY };
  }, want);
}

/** The tour's canvas: its CSS and device size, its box and the pixel ratio and theme the
 * page drew it with (tour.js: the window's ratio up to 2), and its pixels. */
function picture(where) {
  return where.evaluate(() => {
    const c = document.getElementById('tour-picture');
    const r = c.getBoundingClientRect();
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    return {
      shown: c.getClientRects().length > 0, w: c.width, h: c.height, cssW: parseFloat(c.style.width), cssH: parseFloat(c.style.height),
      dpr: Math.min(window.devicePixelRatio || 1, 2), dark: document.documentElement.dataset.theme === 'dark',
      box: { x: r.left, y: r.top, r: r.right, b: r.bottom }, vw: window.innerWidth, vh: window.innerHeight, data: Array.from(d),
    };
  });
}

/** Pixels in rectangle `r` that differ from the paper (the picture's bottom-left pixel). */
function inked(pic, r) {
  const at = (x, y) => { const i = 4 * (Math.round(y) * pic.w + Math.round(x)); return [pic.data[i], pic.data[i + 1], pic.data[i + 2]]; };
  const paper = at(1, pic.h - 2);
  let ink = 0;
  for (let y = Math.max(0, Math.ceil(r.y)); y < Math.min(pic.h, r.y + r.h); y++) {
    for (let x = Math.max(0, Math.ceil(r.x)); x < Math.min(pic.w, r.x + r.w); x++) if (at(x, y).some((v, k) => Math.abs(v - paper[k]) > 24)) ink++;
  }
  return ink;
}

/** A table figure on the page shows its live table instead of its picture: its shown
 * cells at least LABEL_PX, the table within the window's width, no heading cut. */
async function checkTable(where, at) {
  const t = await where.evaluate(() => {
    const cells = [...document.querySelectorAll('#tour-table th, #tour-table td')].filter((c) => c.getClientRects().length > 0);
    const r = document.getElementById('tour-table').getBoundingClientRect();
    return {
      cells: cells.length, r: r.right, vw: window.innerWidth,
      smallest: Math.min(...cells.map((c) => parseFloat(getComputedStyle(c).fontSize))),
      cutHeads: [...document.querySelectorAll('#tour-head th')].filter((c) => c.getClientRects().length > 0 && c.scrollWidth > c.clientWidth + 1).map((c) => c.textContent),
    };
  });
  check(t.cells > 0, `${at}: the table shows no cell`);
  check(t.r <= t.vw + 0.5, `${at}: the table reaches ${Math.round(t.r)} px in a ${t.vw} px window`);
  check(t.smallest >= LABEL_PX - 0.01, `${at}: a cell of the table is ${t.smallest} px`);
  check(t.cutHeads.length === 0, `${at}: headings cut: ${t.cutHeads}`);
  return { texts: t.cells, smallest: t.smallest };
}

/** The checks of one figure at one size, in `where` (the iframe or the phone's page). */
async function checkFigure(where, card, size) {
  const at = `${card.name} at ${size.name}`;
  // the claim and the key sentence of the measured text: whole on the first screen
  for (const [what, want] of [['the claim', card.claim], ['the key numbers', card.key]]) {
    const s = await wordsSeen(where, want);
    check(!s.missing, `${at}: ${what} is not among the tour's words`);
    if (s.missing) continue;
    check(s.rects.length > 0, `${at}: ${what} is not shown`);
    check(!s.clipped, `${at}: ${what}: ${s.clipped}`);
    check(s.scrollY === 0, `${at}: the window is scrolled by ${s.scrollY} px`);
    for (const r of s.rects) {
      check(r.x >= -0.5 && r.r <= s.vw + 0.5 && r.y >= -0.5 && r.b <= s.vh + 0.5, `${at}: a line of ${what} lies at ${Math.round(r.x)},${Math.round(r.y)}–${Math.round(r.r)},${Math.round(r.b)}, outside the ${s.vw}×${s.vh} window`);
    }
    check(s.font >= LABEL_PX - 0.01, `${at}: ${what} is ${s.font} px`);
  }
  // the picture: whole in the window, every text it draws at least LABEL_PX, none cut
  const pic = await picture(where);
  if (!pic.shown && card.rows > 0 && !size.embed) return checkTable(where, at);
  check(pic.shown, `${at}: the picture is not shown`);
  const b = pic.box;
  check(b.x >= -0.5 && b.y >= -0.5 && b.r <= pic.vw + 0.5 && b.b <= pic.vh + 0.5, `${at}: the picture is not whole on the first screen: ${JSON.stringify(b)}`);
  const lay = await core(where, 'tourPictureLayout', card.name, pic.cssW, pic.cssH, pic.dpr, pic.dark, LABEL_PX);
  check(lay.w === pic.w && lay.h === pic.h, `${at}: the core's picture is ${lay.w}×${lay.h}, the page's ${pic.w}×${pic.h}`);
  const texts = lay.regions.filter((r) => r.kind === 'text');
  check(texts.length >= 2, `${at}: the core recorded ${texts.length} texts in the picture (its title and a panel's at least)`);
  const small = texts.filter((r) => r.size < LABEL_PX * pic.dpr - 0.01);
  check(small.length === 0, `${at}: ${small.length} of ${texts.length} texts under ${LABEL_PX} px, the smallest ${Math.min(...small.map((r) => r.size / pic.dpr)).toFixed(1)} px`);
  const cut = texts.filter((r) => r.cut);
  check(cut.length === 0, `${at}: ${cut.length} texts cut to "…", at ${cut.slice(0, 3).map((r) => `${Math.round(r.x)},${Math.round(r.y)}`).join('; ')}`);
  const off = texts.filter((r) => r.x < -1 || r.y < -1 || r.x + r.w > pic.w + 1 || r.y + r.h > pic.h + 1);
  check(off.length === 0, `${at}: ${off.length} texts run off the picture: ${JSON.stringify(off.slice(0, 2))}`);
  // the boxes are believed only where the canvas has ink in them
  const blank = texts.filter((r) => r.w > 4 && inked(pic, r) === 0);
  check(blank.length <= texts.length / 10, `${at}: ${blank.length} of ${texts.length} recorded texts have no ink on the canvas`);
  return { texts: texts.length, smallest: Math.min(...texts.map((r) => r.size / pic.dpr)) };
}

export default async function ({ server, context }) {
  const p = await freshPage(context, 1366, 900, 'sizes');
  let names;
  try {
    await p.goto(server.base);
    await idle(p);
    names = (await core(p, 'tourFigures')).map((e) => e.name);
  } finally {
    await p.close();
  }
  for (const name of names) {
    for (const size of SIZES) {
      await test(`#figure=${name} at ${size.name}: the claim and its key numbers whole on the first screen, the picture whole, its texts ≥ ${LABEL_PX} px and none cut`, async () => {
        const h = await freshPage(context, size.embed ? size.w + 40 : size.w, size.embed ? size.h + 40 : size.h, `${name} ${size.name}`);
        try {
          let where;
          if (size.embed) {
            where = await hostFrame(h, `${server.base}?embed=1#figure=${name}`, size.w, size.h, { figure: true, timeout: 4 * TIMEOUT });
          } else {
            await open(h, `${server.base}#figure=${name}`);
            await h.waitForFunction((n) => document.body.dataset.figure === n && document.body.dataset.busy === '0', name, { timeout: 4 * TIMEOUT });
            await idle(h);
            await h.evaluate(() => window.scrollTo(0, 0));
            where = h;
          }
          const card = await core(where, 'tourCard', name);
          const r = await checkFigure(where, card, size);
          console.log(`     ${r.texts} texts in the picture, the smallest ${r.smallest.toFixed(1)} px`);
          const file = path.join(OUT, `sizes-${name}-${size.w}x${size.h}.png`);
          if (size.embed) await h.locator('#f').screenshot({ path: file });
          else await h.screenshot({ path: file });
        } finally {
          await h.close();
        }
      });
    }
  }
}

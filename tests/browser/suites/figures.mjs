// The tour's figures (issue 28): each opens by #figure=NAME with the words and the picture
// the core computes — the marks its text promises drawn, no legend over the data, the
// numbers of the text those of the computation — and each fits an embed of 800×450 and
// 520×520 without scrolling. Where a picture put its plots, legends and marks comes from
// the core (tourPictureLayout: recorded as the picture is drawn), and is checked against
// the canvas's own pixels before it is believed.
import path from 'node:path';
import { OUT, TIMEOUT, test, check, idle, open, stats, freshPage, hostFrame, reach } from '../lib.mjs';

/** The figures of the tour when this suite was written: each must still be there. */
const FIGURES = ['chen-2', 'chen-6', 'chen-9', 'chen-10', 'chen-11', 'chen-13', 'chen-16', 'chen-20', 'freitag-t1', 'freitag-3', 'knupp-1'];
/** Figures another part of the work owns: only the checks every figure shares run on them. */
const ELSEWHERE = new Set(['chen-13', 'freitag-t1', 'freitag-3']);
/** The page's smallest label, CSS px (present.js: LABEL_PX). */
const LABEL_PX = 14;
/** The colours of the steps' marks (render::PathKind): g, c, n, as the level sets draw them. */
const STEP_RGB = { g: [86, 180, 233], c: [230, 159, 0], n: [213, 94, 0] };
/** Fig. 9's end tangents and the optimum found by search (lab::tour::solves). */
const TANGENT_RGB = [0, 114, 178];
const OPTIMUM_RGB = [240, 228, 66];

/** Calls the core's wasm export `fn` with `args` in the page (the page's own module). */
function core(p, fn, ...args) {
  return p.evaluate(async ([fn, args]) => {
    const m = await import('/pkg/smoothlab.js');
    if (!window.__coreReady) window.__coreReady = m.default();
    await window.__coreReady;
    return m[fn](...args);
  }, [fn, args]);
}

/** Opens `#figure=NAME` and waits until its picture (and its run, if any) is done. */
async function openFigure(p, base, name) {
  await open(p, `${base}#figure=${name}`);
  await p.waitForFunction((n) => document.body.dataset.figure === n, name, { timeout: TIMEOUT });
  await idle(p);
}

/** The tour's canvas: its pixels (RGBA, device px), the CSS size and pixel ratio the page
 * asked the core for (tour.js: the canvas's style size, the window's ratio up to 2), the theme. */
function picture(where) {
  return where.evaluate(() => {
    const c = document.getElementById('tour-picture');
    const r = c.getBoundingClientRect();
    const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
    return { shown: c.getClientRects().length > 0, dpr: Math.min(window.devicePixelRatio || 1, 2), w: c.width, h: c.height, cssW: parseFloat(c.style.width), cssH: parseFloat(c.style.height), box: { x: r.left, y: r.top, r: r.right, b: r.bottom }, dark: document.documentElement.dataset.theme === 'dark', data: Array.from(d) };
  });
}

/** The layout of the picture `pic` of figure `name`, as the core draws it at that size. */
async function layoutOf(p, name, pic) {
  const lay = await core(p, 'tourPictureLayout', name, pic.cssW, pic.cssH, pic.dpr, pic.dark, LABEL_PX);
  check(lay.w === pic.w && lay.h === pic.h, `${name}: the core's picture is ${lay.w}×${lay.h}, the page's ${pic.w}×${pic.h}`);
  return lay.regions;
}

const px = (pic, x, y) => {
  const i = 4 * (Math.round(y) * pic.w + Math.round(x));
  return [pic.data[i], pic.data[i + 1], pic.data[i + 2]];
};
const near = (a, b, tol = 10) => a.every((v, k) => Math.abs(v - b[k]) <= tol);
const overlaps = (a, b) => a.x < b.x + b.w && b.x < a.x + a.w && a.y < b.y + b.h && b.y < a.y + a.h;

/** The pixels of rectangle `r` that differ from the paper. */
function inked(pic, r) {
  const paper = px(pic, 1, pic.h - 2);
  let ink = 0;
  for (let y = Math.ceil(r.y + 1); y < r.y + r.h - 1; y++) {
    for (let x = Math.ceil(r.x + 1); x < r.x + r.w - 1; x++) if (!near(px(pic, x, y), paper, 6)) ink++;
  }
  return ink;
}

/** The legend rule, with the layout checked against the pixels: every plot and legend has
 * something drawn in it, every mark is of its colour, and no legend meets a plot. */
function checkLayout(name, pic, regions) {
  const plots = regions.filter((r) => r.kind === 'plot');
  const legends = regions.filter((r) => r.kind === 'legend');
  const marks = regions.filter((r) => r.kind === 'mark');
  // a picture with a legend has data it explains (Freitag's table has neither)
  check(plots.length > 0 || legends.length === 0, `${name}: the core noted legends and no plot`);
  for (const r of [...plots, ...legends]) {
    check(r.x >= -0.5 && r.y >= -0.5 && r.x + r.w <= pic.w + 0.5 && r.y + r.h <= pic.h + 0.5, `${name}: ${r.kind} ${JSON.stringify(r)} is outside the ${pic.w}×${pic.h} picture`);
    if (r.w > 20 && r.h > 12) check(inked(pic, r) > 40, `${name}: nothing drawn in the ${r.kind} at ${Math.round(r.x)},${Math.round(r.y)} ${Math.round(r.w)}×${Math.round(r.h)}`);
  }
  for (const l of legends) {
    for (const q of plots) check(!overlaps(l, q), `${name}: a legend (${JSON.stringify(l)}) lies over a plot (${JSON.stringify(q)})`);
  }
  // a mark is seen in its colour, or covered by another mark drawn at the same point (two
  // series through one value: chen-13's orders both start at 285 and end at 0)
  const seen = (m) => near(px(pic, m.x, m.y), m.rgb, 12);
  const right = marks.filter((m) => seen(m) || marks.some((o) => o !== m && Math.hypot(o.x - m.x, o.y - m.y) < 3 && seen(o))).length;
  check(right >= 0.8 * marks.length, `${name}: ${marks.length - right} of ${marks.length} marks are not of their colour on the canvas`);
  return { plots, legends, marks };
}

/** Step marks ("…: g 0.0050, c 1.6e-6, …") in a text, counted by letter. */
function stepsInText(text) {
  const out = { g: 0, c: 0, n: 0 };
  for (const m of text.matchAll(/[,:;] ([gcn]) (\d+(?:\.\d+)?(?:e[+-]?\d+)?)\b/g)) out[m[1]]++;
  return out;
}

/** What a figure's own test checks beyond the shared ones; `pic` its canvas, `lay` its layout. */
const OWN = {
  'chen-9': async (p, card, pic, lay) => {
    const text = card.measured;
    const num = (re) => {
      const m = text.match(re);
      check(m, `chen-9: "${re}" not in the text: ${text}`);
      return Number(m[1]);
    };
    const meet = num(/meet at y = (-?\d+\.\d+)/);
    const newEnd = num(/solver ends at y = (-?\d+\.\d+)/);
    const oldBest = num(/optimum lies at y = (-?\d+\.\d+)/);
    check(newEnd < meet && oldBest < meet && /below the meeting point/.test(text) && /below it too/.test(text), `chen-9: the text's optima are not below ${meet}: ${text}`);
    // the picture agrees: in each panel the optimum's star lies below the dashed lines' meeting point
    const half = pic.w / 2;
    for (const [side, inSide] of [['A', (m) => m.x < half], ['B', (m) => m.x >= half]]) {
      const marks = lay.marks.filter(inSide);
      const meetMark = marks.find((m) => near(m.rgb, TANGENT_RGB, 0));
      const star = marks.find((m) => near(m.rgb, OPTIMUM_RGB, 0));
      check(meetMark && star, `chen-9 ${side}: the meeting point or the optimum is not drawn (${JSON.stringify(marks)})`);
      check(star.y > meetMark.y + 5, `chen-9 ${side}: the optimum (y ${star.y}) is not below the meeting point (y ${meetMark.y})`);
    }
    // max-min α cannot leave the start: the text says why, with the solver's own count
    const iters = num(/ascent stays at the start \((\d+) iterations/);
    check(iters === 0 && /tie at α = [0-9.]+, a kink/.test(text), `chen-9: the kink is not explained: ${text}`);
    const tangentPixels = countColour(pic, TANGENT_RGB, 0, half) + countColour(pic, TANGENT_RGB, half, pic.w);
    check(tangentPixels > 200, `chen-9: the end tangents are not drawn (${tangentPixels} pixels)`);
  },
  'chen-10': async (p, card, pic, lay) => {
    check(lay.plots.length === 2, `chen-10: ${lay.plots.length} plots`);
    // levels inside the feasible region: each plot shows many distinct band colours
    for (const q of lay.plots) {
      const colours = new Set();
      for (let y = q.y + q.h * 0.2; y < q.y + q.h * 0.8; y += 2) {
        for (let x = q.x + q.w * 0.2; x < q.x + q.w * 0.8; x += 2) colours.add(px(pic, x, y).join());
      }
      check(colours.size > 40, `chen-10: only ${colours.size} colours inside a plot`);
    }
  },
  'chen-11': async (p, card, pic, lay) => {
    const said = stepsInText(card.measured);
    check(said.g > 0 && said.c > 0 && said.n > 0, `chen-11: the text marks no g, c or n step: ${card.measured}`);
    // the chart (the right half) marks every step the text lists, in the path's colours
    const chart = lay.marks.filter((m) => m.x >= pic.w / 2);
    for (const k of ['g', 'c', 'n']) {
      const drawn = chart.filter((m) => near(m.rgb, STEP_RGB[k], 0)).length;
      check(drawn === said[k], `chen-11: ${drawn} ${k} marks drawn, the text lists ${said[k]}`);
      check(countColour(pic, STEP_RGB[k], pic.w / 2, pic.w) > 4 * drawn, `chen-11: the ${k} marks' colour is not on the canvas`);
    }
    const iters = [...card.measured.matchAll(/(\d+) iterations/g)].map((m) => Number(m[1]));
    check(iters.length >= 2 && iters[0] === said.g + said.c && iters[1] === said.n, `chen-11: the counts ${iters} are not the steps listed ${JSON.stringify(said)}`);
  },
  'chen-16': async (p, card) => {
    // the text's optimization numbers are the compare view's tables (one pass each)
    const [a, b] = [await stats(p, 'a'), await stats(p, 'b')];
    const m = card.measured.match(/min angle \(([0-9.]+)° vs ([0-9.]+)°\)/);
    check(m, `chen-16: the text compares no min angles: ${card.measured}`);
    const [oldA, newA] = [parseFloat(a.min_angle), parseFloat(b.min_angle)];
    const winner = /old objective wins/.test(card.measured) ? 'old' : 'new';
    const [first, second] = winner === 'old' ? [oldA, newA] : [newA, oldA];
    check(Math.abs(Number(m[1]) - first) < 0.01 && Math.abs(Number(m[2]) - second) < 0.01, `chen-16: text ${m[1]}° vs ${m[2]}°, tables old ${a.min_angle} new ${b.min_angle}`);
    check((winner === 'old') === (oldA > newA), `chen-16: the text says ${winner} wins on min angle, the tables old ${oldA} new ${newA}`);
  },
};

/** Pixels of colour `rgb` (± tol) in the columns `x0..x1` of the canvas. */
function countColour(pic, rgb, x0, x1, tol = 0) {
  let n = 0;
  for (let y = 0; y < pic.h; y++) {
    for (let x = Math.floor(x0); x < Math.min(pic.w, x1); x++) if (near(px(pic, x, y), rgb, tol)) n++;
  }
  return n;
}

export default async function ({ server, context }) {
  const p = await freshPage(context, 1366, 900, 'figures');
  try {
    await p.goto(server.base);
    await idle(p);
    const names = (await core(p, 'tourFigures')).map((e) => e.name);
    await test('the tour has every figure this suite checks', async () => {
      for (const n of FIGURES) check(names.includes(n), `the tour lost ${n}: ${names}`);
    });
    for (const name of names) {
      await test(`#figure=${name}: the words are the core's, no legend over the data${OWN[name] && !ELSEWHERE.has(name) ? ', its own marks and numbers' : ''}`, async () => {
        await openFigure(p, server.base, name);
        const card = await core(p, 'tourCard', name);
        for (const [id, key] of [['tour-look', 'look'], ['tour-claim', 'claim'], ['tour-measured', 'measured']]) {
          check((await p.textContent(`#${id}`)) === card[key], `${name}: #${id} is not the core's ${key}`);
        }
        check(/\d/.test(card.measured), `${name}: the measured text has no number`);
        const pic = await picture(p);
        // a table figure is shown once on the page, as its live table: its picture is the
        // embed's (checked there)
        if (!pic.shown) {
          check(card.rows > 0, `${name}: the page hides the picture of a figure that is no table`);
          return;
        }
        const lay = checkLayout(name, pic, await layoutOf(p, name, pic));
        if (OWN[name] && !ELSEWHERE.has(name)) await OWN[name](p, card, pic, lay);
        await p.locator('#tour-picture').screenshot({ path: path.join(OUT, `figure-${name}.png`) });
      });
    }
    await test('every figure opens in an ?embed=1 iframe of 800×450 and 520×520: no scrolling, the picture whole, its legends off the data', async () => {
      const h = await freshPage(context, 1400, 900, 'figure embeds');
      try {
        for (const name of names) {
          for (const [w, hh] of [[800, 450], [520, 520]]) {
            const frame = await hostFrame(h, `${server.base}?embed=1#figure=${name}`, w, hh, { figure: true });
            const r = await reach(frame);
            check(r.sw <= w && r.sh <= hh && r.r <= w + 0.5 && r.b <= hh + 0.5, `${name} at ${w}×${hh}: content reaches ${Math.round(r.r)}×${Math.round(r.b)} (scroll ${r.sw}×${r.sh})`);
            const pic = await picture(frame);
            check(pic.box.x >= -0.5 && pic.box.y >= -0.5 && pic.box.r <= w + 0.5 && pic.box.b <= hh + 0.5, `${name} at ${w}×${hh}: the picture is not whole: ${JSON.stringify(pic.box)}`);
            checkLayout(`${name} at ${w}×${hh}`, pic, await layoutOf(frame, name, pic));
            await h.locator('#f').screenshot({ path: path.join(OUT, `figure-embed-${name}-${w}x${hh}.png`) });
          }
        }
      } finally {
        await h.close();
      }
    });
  } finally {
    await p.close();
  }
}

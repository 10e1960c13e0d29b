// Drawing: the engine's pixels on the canvases, sized to the layout (and to an embed's frame).
import { $, EMBED, HOSTED, engine, metrics, now, pageEvents, state, view } from './state.js';
import { nodeHint } from './loading.js';
import { fillTables } from './tables.js';
import { refreshUndo } from './undo.js';

/** Device-pixel size of a canvas as laid out, and the ratio used (at most 2). */
export function canvasPixels(canvas) {
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const w = Math.max(64, Math.min(2048, Math.round(canvas.clientWidth * dpr)));
  const h = Math.max(64, Math.min(2048, Math.round(canvas.clientHeight * dpr)));
  return { w, h, dpr };
}
/** Puts RGBA pixels (moved here from the worker, not copied) on a canvas; returns the ms it took. */
export function paint(canvas, pixels, w, h) {
  const t0 = now();
  if (canvas.width !== w) canvas.width = w;
  if (canvas.height !== h) canvas.height = h;
  const img = new ImageData(new Uint8ClampedArray(pixels.buffer, pixels.byteOffset, pixels.byteLength), w, h);
  canvas.getContext('2d').putImageData(img, 0, 0);
  return now() - t0;
}

/** The part of the page an embed fills its frame with: the box whose height the frame
 * leaves (a flex item of the embed's column) and the canvases in it. */
function embedTarget() {
  if (state.figure && !document.body.classList.contains('live')) return null; // the tour's picture: tour.js
  if (view.spec && view.spec.draws === 'charts') return { box: document.querySelector('.pass-view'), canvases: view.spec.canvases.map($) };
  if (view.spec) return { box: document.querySelector('.stage'), canvases: view.spec.canvases.map($) };
  return { box: document.querySelector('.stage'), canvases: [$('mesh-a'), $('mesh-b')] };
}

/** Sizes the canvases to the layout; returns whether a size changed. On the full page the
 * meshes are as large as their column and the height the window leaves below the bars
 * (so both are whole on the first screen); in an embed, see fitFrame. */
export function fitEmbed() {
  if (!EMBED) {
    capMeshes();
    return false;
  }
  return fitFrame();
}

/** The full page: the meshes no taller than the window leaves under the bars above them. */
function capMeshes() {
  const root = document.documentElement;
  if (window.innerWidth <= 600) {
    root.style.removeProperty('--mesh-max');
    return;
  }
  const wrap = $('mesh-a').parentElement;
  // with the tour open the meshes are below it: as large as the window under the run bar
  const top = state.figure
    ? document.querySelector('.runbar').offsetHeight + $('title-a').offsetHeight + 24
    : wrap.getBoundingClientRect().top + window.scrollY;
  const cap = Math.max(300, Math.floor(window.innerHeight - top - 12));
  root.style.setProperty('--mesh-max', `${cap}px`);
  // the side column ends at the window's foot (it scrolls inside), from where it starts
  // (from the stage's top: the column itself is sticky, its box moves as the page scrolls)
  const sideTop = document.querySelector('.stage').getBoundingClientRect().top + window.scrollY;
  root.style.setProperty('--side-max', `${Math.max(320, Math.floor(window.innerHeight - Math.min(sideTop, window.innerHeight / 2) - 8))}px`);
}

/** How tall the content of a box is (not the box: a flex item is as tall as it is given). */
export function contentHeight(box) {
  const top = box.getBoundingClientRect().top;
  let bottom = top;
  for (const el of box.children) {
    // out of the flow (a notebook widget's settings column beside the meshes): not content
    if (el.getClientRects().length === 0 || getComputedStyle(el).position === 'absolute') continue;
    bottom = Math.max(bottom, el.getBoundingClientRect().bottom + parseFloat(getComputedStyle(el).marginBottom || '0'));
  }
  return bottom - top + parseFloat(getComputedStyle(box).paddingBottom || '0') + parseFloat(getComputedStyle(box).borderBottomWidth || '0');
}

/** An embed fills its frame without scrolling: its canvases take the whole room the rest
 * of the column leaves (the core draws a mesh, level sets or a chart into any rectangle),
 * side by side or stacked, whichever makes the smaller side of each larger; the tables
 * give their room up ('tight') when the pictures would otherwise be under 40 % of the
 * frame's short side. */
function fitFrame() {
  const t = embedTarget();
  if (!t) return false;
  const { box, canvases } = t;
  const body = document.body;
  const before = canvases.map((c) => `${c.style.width}x${c.style.height}`);
  const probe = 40;
  const n = canvases.length;
  const measure = (stacked, tight) => {
    body.classList.toggle('stacked', stacked);
    body.classList.toggle('tight', tight);
    for (const c of canvases) {
      c.style.width = `${probe}px`;
      c.style.height = `${probe}px`;
    }
    const rows = stacked ? n : 1;
    const extra = contentHeight(box) - probe * rows; // titles, tables, captions, padding
    const w = canvases[0].parentElement.clientWidth;
    const h = Math.floor((box.clientHeight - extra) / rows) - 1;
    return { w, h, stacked, tight };
  };
  const short = Math.min(window.innerWidth, window.innerHeight);
  const side = (s) => Math.min(s.w, s.h);
  // with the boundary's key under the meshes, the quality's key is counted as shown
  // whether or not it is: it shows only on canvases too small for the colour bar, so a fit
  // that left it out would grow the canvases, hide it, and the next fit shrink them again
  const colourKey = $('colour-key');
  const countKey = !$('boundary-key').hidden && colourKey.hidden;
  if (countKey) colourKey.hidden = false;
  let best = null;
  for (const tight of [false, true]) {
    for (const stacked of n > 1 ? [false, true] : [false]) {
      const s = measure(stacked, tight);
      if (!best || side(s) > side(best)) best = s;
    }
    if (side(best) >= 0.4 * short) break;
  }
  if (countKey) colourKey.hidden = true;
  body.classList.toggle('stacked', best.stacked);
  body.classList.toggle('tight', best.tight);
  for (const c of canvases) {
    c.style.width = `${Math.max(60, best.w)}px`;
    c.style.height = `${Math.max(60, best.h)}px`;
  }
  return canvases.some((c, i) => `${c.style.width}x${c.style.height}` !== before[i]);
}

/** The quality scale in HTML, shown when the canvases were too small for the core to draw
 * its colour bar (the key's words name the measure the meshes are coloured by). */
function showColourKey(on) {
  const key = $('colour-key');
  if (key.hidden === !on) return false;
  key.hidden = !on;
  $('colour-key-text').textContent = state.volume
    ? 'mean ratio of the cut faces: 0 (poor) to 1 (ideal)'
    : 'quality (α for triangles, β for quads): 0 (poor) to 1 (ideal)';
  return true;
}

/** The key of a sliding boundary's marks, in words, shown while the boundary slides (the
 * pictures draw its curves, corners and sliding nodes; a surface's dots are its curves'
 * nodes, a planar mesh's curve is its boundary). */
function showBoundaryKey() {
  const on = state.boundary !== 'fixed' && !state.slideRefused;
  const key = $('boundary-key');
  key.hidden = !on;
  key.firstElementChild.lastChild.textContent = state.surface ? ' feature curves: their nodes slide along them;' : ' the boundary: its nodes slide along it;';
  key.lastElementChild.lastChild.textContent = state.volume ? ' nodes slide on the boundary' : state.surface ? ' nodes slide along the curves' : ' nodes slide along the boundary';
}

/** `refits`: how many times more the canvases may be fitted again to what the tables and
 * the colour key took (each fit only shrinks them or leaves them, so this ends). */
export async function redrawMeshes(refits = 2) {
  showBoundaryKey();
  fitEmbed();
  const t0 = now();
  // a phone shows one panel at a time: the size is the shown one's (both are drawn alike)
  const shown = $('mesh-a').clientWidth ? $('mesh-a') : $('mesh-b');
  const { w, h, dpr } = canvasPixels(shown);
  const { result: f, timing } = await engine.timed('frame', w, h, dpr, false);
  const paint_ms = [0, 0];
  if (f.a) paint_ms[0] = paint($('mesh-a'), f.a, w, h);
  if (f.b) paint_ms[1] = paint($('mesh-b'), f.b, w, h);
  if (f.a || f.b) pageEvents.dispatchEvent(new Event('meshes'));
  if (metrics.startup && !metrics.startup.first_mesh_ms && (f.a || f.b)) {
    Object.assign(metrics.startup, { first_mesh_ms: now(), first_frame_ms: now() - t0, first_render_ms: f.render_ms });
  }
  state.frame = { w, h, dpr };
  const keyChanged = showColourKey(f.colour_bar === false);
  const t1 = now();
  fillTables(f.stats);
  // the tables or the colour key took room: the canvases shrink (a bounded number of times)
  if (refits > 0 && (refits === 2 || keyChanged) && fitEmbed()) return redrawMeshes(refits - 1);
  await refreshUndo();
  return {
    frame_ms: t1 - t0,
    render_ms: f.render_ms,
    copy_ms: f.copy_ms,
    transfer_ms: timing.received - timing.worker.end,
    paint_ms,
    sent: [Boolean(f.a), Boolean(f.b)],
    canvas: [w, h],
    table_ms: now() - t1,
  };
}

export async function redrawCharts() {
  if (EMBED && !(view.spec && view.spec.draws === 'charts')) return;
  fitEmbed();
  const c = canvasPixels($('pass-chart'));
  const hc = canvasPixels($('hist-a'));
  const r = await engine.call('charts', c.w, c.h, hc.w, hc.h, c.dpr, $('hist-log').checked);
  paint($('pass-chart'), r.pass, c.w, c.h);
  paint($('hist-a'), r.hist_a, hc.w, hc.h);
  paint($('hist-b'), r.hist_b, hc.w, hc.h);
  showHistograms(r.histograms, hc);
  fillTables(r.stats); // the detail rows of a large mesh are measured by now
}

/** The histograms' captions in the words of the mesh on screen, and the histograms after
 * the first (a kind of mesh in 3D lists one entry a measure: `{ title, a, b }`), each pair
 * in figures of its own after the first pair. */
function showHistograms(list, hc) {
  const what = list && list.length ? list[0].title.replace(/ \(6° bins\)$/, '') : 'Angles';
  for (const [id, letter] of [['hist-a', 'A'], ['hist-b', 'B']]) {
    $(id).parentElement.querySelector('figcaption').textContent = `${what}, ${letter} (both histograms on one scale)`;
  }
  const pair = $('hist-b').closest('.pair');
  for (const old of pair.querySelectorAll('figure.more-histogram')) old.remove();
  for (const [i, h] of (list || []).entries()) {
    if (i === 0) continue;
    for (const [side, letter] of [['a', 'A'], ['b', 'B']]) {
      const fig = document.createElement('figure');
      fig.className = 'more-histogram';
      const canvas = document.createElement('canvas');
      canvas.id = `hist-${side}-${i}`;
      canvas.tabIndex = 0;
      canvas.setAttribute('aria-label', `${h.title}, panel ${letter}`);
      const cap = document.createElement('figcaption');
      cap.textContent = `${h.title}, ${letter}`;
      fig.append(canvas, cap);
      pair.append(fig);
      paint(canvas, h[side], hc.w, hc.h);
    }
  }
}

export const NODE_HINT = 'Click a free (interior) node on either mesh, or type its number. Drag a node to move it on both meshes.';

/** A canvas with a line of text in the middle (drawn, not HTML). */
export function placeholder(canvas, text) {
  const { w, h } = canvasPixels(canvas);
  canvas.width = w;
  canvas.height = h;
  const g = canvas.getContext('2d');
  g.fillStyle = '#ffffff';
  g.fillRect(0, 0, w, h);
  g.fillStyle = '#5b6470';
  g.font = `${Math.round(14 * (w / canvas.clientWidth || 1))}px system-ui, sans-serif`;
  g.textAlign = 'center';
  g.textBaseline = 'middle';
  g.fillText(text, w / 2, h / 2);
}

export async function redrawNode() {
  // an embed draws a node's level sets in its level-set view; a notebook's widget in its column
  if (EMBED && !HOSTED && !(view.spec && view.spec.draws === 'node')) return;
  fitEmbed();
  const lv = canvasPixels($('level-a'));
  const ch = canvasPixels($('solve-chart'));
  $('smooth-node').disabled = state.node === null || state.running;
  if (state.node === null) {
    const ask = state.surface ? 'Click a node on either view' : 'Click a free node on a mesh';
    for (const id of ['level-a', 'level-b', 'solve-chart']) placeholder($(id), ask);
    $('node-hint').textContent = nodeHint();
    return;
  }
  const r = await engine.call('nodeView', lv.w, lv.h, ch.w, ch.h, lv.dpr);
  state.level = lv;
  paint($('level-a'), r.level_a, lv.w, lv.h);
  paint($('level-b'), r.level_b, lv.w, lv.h);
  paint($('solve-chart'), r.chart, ch.w, ch.h);
  $('node-hint').textContent = r.summary;
}

export async function redrawAll() {
  await redrawMeshes();
  await redrawCharts();
  await redrawNode();
}

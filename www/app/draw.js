// Drawing: the engine's pixels on the canvases, sized to the layout (and to an embed's frame).
import { $, EMBED, engine, metrics, now, state, view } from './state.js';
import { planarOnlyWhy } from './loading.js';
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

/** Draws both meshes (a panel whose picture would not change is not sent again) and
 * their statistics tables; returns where the time went. */
/** In an embed the page must fit its frame without scrolling: the mesh canvases shrink
 * (staying square) by what the page is taller than the frame. */
export function fitEmbed() {
  if (!EMBED) return false;
  if (view.spec) return fitView();
  const canvases = [$('mesh-old'), $('mesh-new')];
  const over = document.documentElement.scrollHeight - window.innerHeight;
  if (over <= 0) return false;
  const side = Math.max(120, canvases[0].clientWidth - over - 2);
  if (side >= canvases[0].clientWidth) return false;
  for (const c of canvases) c.style.width = `${side}px`;
  return true;
}

/** An embedded view fills its frame: its canvases take the height the rest leaves, side
 * by side (stacked, one above the other, in a frame narrower than 480 px). Returns
 * whether their size changed. */
export function fitView() {
  const cs = view.spec.canvases.map($);
  const stacked = window.innerWidth < 480 && cs.length > 1;
  document.body.classList.toggle('stacked', stacked);
  const before = cs.map((c) => c.style.height);
  const probe = 40;
  for (const c of cs) c.style.height = `${probe}px`;
  const rest = document.body.getBoundingClientRect().height - probe * (stacked ? cs.length : 1);
  const avail = window.innerHeight - rest - 1;
  const h = Math.max(100, Math.floor(stacked ? avail / cs.length : avail));
  for (const c of cs) c.style.height = `${h}px`;
  return cs.some((c, i) => c.style.height !== before[i]);
}

export async function redrawMeshes() {
  fitEmbed();
  const t0 = now();
  const { w, h, dpr } = canvasPixels($('mesh-old'));
  const { result: f, timing } = await engine.timed('frame', w, h, dpr, false);
  const paint_ms = [0, 0];
  if (f.old) paint_ms[0] = paint($('mesh-old'), f.old, w, h);
  if (f.new) paint_ms[1] = paint($('mesh-new'), f.new, w, h);
  if (metrics.startup && !metrics.startup.first_mesh_ms && (f.old || f.new)) {
    Object.assign(metrics.startup, { first_mesh_ms: now(), first_frame_ms: now() - t0, first_render_ms: f.render_ms });
  }
  state.frame = { w, h, dpr };
  const t1 = now();
  fillTables(f.stats);
  if (fitEmbed()) return redrawMeshes(); // the tables took room: the canvases shrink, once more at most
  await refreshUndo();
  return {
    frame_ms: t1 - t0,
    render_ms: f.render_ms,
    copy_ms: f.copy_ms,
    transfer_ms: timing.received - timing.worker.end,
    paint_ms,
    sent: [Boolean(f.old), Boolean(f.new)],
    canvas: [w, h],
    table_ms: now() - t1,
  };
}

export async function redrawCharts() {
  if (EMBED && !(view.spec && view.spec.draws === 'charts')) return;
  if (view.spec) fitView();
  if (state.volume) {
    placeholder($('pass-chart'), 'Drawn for planar meshes; the tables follow the tetrahedra pass by pass');
    const hc = canvasPixels($('hist-old'));
    const r = await engine.call('volumeHistograms', hc.w, hc.h, hc.dpr, $('hist-log').checked);
    paint($('hist-old'), r.old, hc.w, hc.h);
    paint($('hist-new'), r.new, hc.w, hc.h);
    return;
  }
  if (state.surface) {
    for (const id of ['pass-chart', 'hist-old', 'hist-new']) placeholder($(id), 'Drawn for planar meshes; this is a surface in 3D');
    return;
  }
  const c = canvasPixels($('pass-chart'));
  const hc = canvasPixels($('hist-old'));
  const r = await engine.call('charts', c.w, c.h, hc.w, hc.h, c.dpr, $('hist-log').checked);
  paint($('pass-chart'), r.pass, c.w, c.h);
  paint($('hist-old'), r.hist_old, hc.w, hc.h);
  paint($('hist-new'), r.hist_new, hc.w, hc.h);
  fillTables(r.stats); // the detail rows of a large mesh are measured by now
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
  if (EMBED && !(view.spec && view.spec.draws === 'node')) return;
  if (view.spec) fitView();
  const lv = canvasPixels($('level-old'));
  const ch = canvasPixels($('solve-chart'));
  $('smooth-node').disabled = state.node === null || state.running || state.surface;
  if (state.surface) {
    const what = state.volume ? 'these are tetrahedra' : 'this is a surface in 3D';
    for (const id of ['level-old', 'level-new', 'solve-chart']) placeholder($(id), `Drawn for planar meshes; ${what}`);
    $('node-hint').textContent = planarOnlyWhy('node');
    return;
  }
  if (state.node === null) {
    for (const id of ['level-old', 'level-new', 'solve-chart']) placeholder($(id), 'Click a free node on a mesh');
    $('node-hint').textContent = NODE_HINT;
    return;
  }
  const r = await engine.call('nodeView', lv.w, lv.h, ch.w, ch.h, lv.dpr);
  state.level = lv;
  paint($('level-old'), r.level_old, lv.w, lv.h);
  paint($('level-new'), r.level_new, lv.w, lv.h);
  paint($('solve-chart'), r.chart, ch.w, ch.h);
  $('node-hint').textContent = r.summary;
}

export async function redrawAll() {
  await redrawMeshes();
  await redrawCharts();
  await redrawNode();
}

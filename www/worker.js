// The playground's engine: a module worker that owns the wasm module and the one
// Playground handle, so smoothing a large mesh never freezes the page. The main thread
// sends {id, cmd, args}; the worker answers {id, ok, result} or {id, ok: false, error,
// panic}. `panic: true` means the Rust code panicked: the handle may be broken, and the
// main thread replaces this worker with a fresh one. Every answer also carries `t`, the
// worker's start and end of the command (ms since the epoch, performance.timeOrigin +
// now, so the page can compare them with its own clock), and `memory`, the size of the
// wasm memory in bytes.
import init, * as wasm from './pkg/smoothlab.js';

// the one-file page's worker carries the module's bytes (scripts/single.mjs puts them in
// `self.SMOOTHLAB_WASM` before this runs); the site's fetches pkg/smoothlab_bg.wasm
const ready = self.SMOOTHLAB_WASM ? init({ module_or_path: self.SMOOTHLAB_WASM }) : init();
let exports = null;
let pg = null;

function need() {
  if (!pg) throw new Error('no mesh is loaded yet');
  return pg;
}

// The handle is a Playground (a planar mesh) or a Lab3d (a mesh in 3D: a surface, or
// tetrahedra drawn cut by a plane; its kind() says which). Both answer the page's views of
// one node, the charts, undo and the figure by the same names.
let kind = null;
const isVolume = () => kind === 'volume';
const isSpace = () => kind !== null;

/** The handle of a planar mesh: what only a planar mesh has (passes in slices, two
 * workers, dragging a node, panning). */
function planar() {
  if (need() && isSpace()) {
    throw new Error(`this takes planar meshes only; this mesh is ${isVolume() ? 'made of tetrahedra' : 'a surface in 3D'}`);
  }
  return pg;
}

/** The handle of tetrahedra: what only they have (the cut plane). */
function volume() {
  if (!(need() && isVolume())) throw new Error('the cut plane takes tetrahedral meshes only');
  return pg;
}

/** The handle of a mesh in 3D: what only the 3D view has (its camera). */
function space() {
  if (!(need() && isSpace())) throw new Error('the 3D view takes surfaces and tetrahedra only; this mesh is planar');
  return pg;
}

// The page's theme for every picture (dark or light, the smallest label in CSS px): kept
// here, so each new handle and the tour's pictures draw in it.
let theme = { dark: false, labelPx: 0 };
function applyTheme() {
  if (pg) pg.setTheme(theme.dark, theme.labelPx);
}

// Replace the handle only once the new one is built: a failed load keeps the old mesh.
// Says which kind of handle it is.
function replace(next) {
  if (pg) pg.free();
  pg = next;
  kind = pg instanceof wasm.Lab3d ? pg.kind() : null;
  applyTheme();
  return {
    surface: isSpace(),
    volume: isVolume(),
    notPlanar: isSpace() ? pg.notPlanar() ?? null : null,
    fileNote: isSpace() ? pg.fileNote() ?? null : null,
    // a planar mesh's boundary always slides (a quadratic one's along its curved edges)
    slideRefused: isSpace() ? pg.slideRefused() ?? null : null,
    nodes: isSpace() ? null : pg.nodeCount(),
  };
}

const handlers = {
  samples: () => wasm.samples(),
  // the theme of every later picture: dark (projector) or light, labels >= labelPx CSS px
  theme: (dark, labelPx) => {
    theme = { dark: Boolean(dark), labelPx: Number(labelPx) };
    applyTheme();
    return null;
  },
  controls: () => wasm.controls(),
  checkControl: (key, text) => wasm.checkControl(key, text),
  loadSample: (name) => replace(wasm.openSample(name)),
  loadFile: (name, bytes) => replace(wasm.openBytes(new Uint8Array(bytes), name)),
  loadTriangle: (node, ele) => replace(wasm.Playground.fromTriangle(node, ele)),
  settings: (s) => need().setSettings(s),
  reset: () => need().reset(),
  step: () => need().step(),
  beginPass: () => planar().beginPass(),
  // settings, beginPass and the first slice in one message (a short pass is one round trip);
  // a pass in 3D runs whole
  pass: (settings, budgetMs) => {
    const p = need();
    p.setSettings(settings);
    if (isSpace()) return { done: true, fraction: 1, records: p.step() };
    p.beginPass();
    return p.continuePass(budgetMs);
  },
  continuePass: (budgetMs) => planar().continuePass(budgetMs),
  // a pass split between two workers (lab::pass): this one smooths side B and measures
  // both, the other sweeps side A from this one's positions and hands them back
  splitPass: (settings, budgetMs) => {
    const p = planar();
    p.setSettings(settings);
    p.beginSplitPass();
    return p.continuePass(budgetMs);
  },
  positions: (side) => planar().panelPositions(side),
  // the positions corners are measured against with these settings (null: the ideal)
  targetPositions: (settings) => {
    const p = planar();
    p.setSettings(settings);
    return p.targetPositions() ?? null;
  },
  // where the runs begin (the mesh as loaded or last perturbed): the grading they keep,
  // whether it was valid and whether the run's first pass is to come (it fits the mesh to
  // its targets first), which the sweep takes as this worker's
  runStart: () => Array.from(planar().runStart()),
  // where a side's sliding boundary stands ({ from, segments, params }; null while it is held),
  // which the sweep takes as this worker's
  slideState: (side) => planar().slideState(side),
  adoptSweep: (nodes, sweep, segments, params) => planar().adoptSweep(nodes, sweep, segments ?? undefined, params ?? undefined),
  // the other worker's part: side A's sweep, its result taken with the last slice
  sweep: (settings, side, nodes, target, start, slide, budgetMs) => {
    const p = planar();
    p.setSettings(settings);
    p.beginSweep(side, nodes, target ?? undefined, start[0], start[1], start[2], slide?.from, slide?.segments, slide?.params);
    return sweepSlice(p, budgetMs);
  },
  continueSweep: (budgetMs) => sweepSlice(planar(), budgetMs),
  abortPass: () => (isSpace() ? null : need().abortPass()),
  perturb: (amount, seed) => need().perturb(amount, seed),
  // the pictures of both meshes and their statistics tables, in one message
  frame: (w, h, dpr, force) => {
    const p = need();
    const f = isSpace() ? p.frame(w, h, dpr) : p.frame(w, h, dpr, Boolean(force));
    f.stats = { a: p.stats('a'), b: p.stats('b') };
    return f;
  },
  forgetFrames: () => (isSpace() ? null : need().forgetFrames()),
  // a planar mesh: the nearest node; in 3D: the nearest node of the face drawn there
  pick: (panel, x, y, radius) => need().pickNode(panel, x, y, radius),
  drag: (node, x, y) => planar().dragNode(node, x, y),
  select: (node) => need().selectNode(node === null ? undefined : node),
  nodeView: (w, h, cw, ch, dpr) => need().nodeView(w, h, cw, ch, dpr),
  charts: (w, h, hw, hh, dpr, logY) => need().charts(w, h, hw, hh, dpr, Boolean(logY)),
  exportMesh: (side, format) => need().exportMesh(side, format),
  // a side's mesh as arrays, for the page's host (app/host.js)
  meshArrays: (side) => need().meshArrays(side),
  stats: (side) => need().stats(side),
  worstNode: () => need().worstFreeNode() ?? null,
  // the wheel: the 3D camera zooms about the centre of its view
  zoomMeshes: (x, y, factor) => (isSpace() ? need().zoom(factor) : need().zoomMeshes(x, y, factor)),
  panMeshes: (dx, dy) => planar().panMeshes(dx, dy),
  orbit: (dx, dy) => space().orbit(dx, dy),
  camera: () => space().camera(),
  setCamera: (yaw, pitch, zoom) => space().setCamera(yaw, pitch, zoom),
  setCut: (axis, at) => volume().setCut(axis, at),
  // where a node is drawn in 3D, and where it is: for the browser tests
  nodeOnScreen: (panel, node) => space().nodeOnScreen(panel, node) ?? null,
  nodePoint: (panel, node) => space().nodePoint(panel, node) ?? null,
  zoomLevelSets: (panel, x, y, factor) => need().zoomLevelSets(panel, x, y, factor),
  panLevelSets: (panel, dx, dy) => need().panLevelSets(panel, dx, dy),
  resetZoom: () => need().resetZoom(),
  rememberBeforeMove: (node) => planar().rememberBeforeMove(node),
  undo: () => need().undo(),
  nudge: (panel, dx, dy) => planar().nudgeNode(panel, dx, dy),
  undoSummary: () => need().undoSummary(),
  smoothNode: (w, h, cw, ch, dpr) => need().smoothNode(w, h, cw, ch, dpr),
  figure: (w, h, dpr) => need().figure(w, h, dpr),
  panicForTest: () => wasm.panicForTest(),
  tourFigures: () => wasm.tourFigures(),
  tourCard: (name) => wasm.tourCard(name),
  // the tour's pictures in the page's theme too
  tourPicture: (name, w, h, dpr) => wasm.tourPicture(name, w, h, dpr, theme.dark, theme.labelPx),
  tourPictureSize: (name) => wasm.tourPictureSize(name),
  tourRow: (i) => wasm.tourRow(i),
  tourTableRow: (name, i) => wasm.tourTableRow(name, i),
  decodePermalink: (hash) => wasm.decodePermalink(hash),
  encodePermalink: (fields) => wasm.encodePermalink(fields),
};

/** A slice of a sweep for the other worker; the sweep's positions and record once done. */
function sweepSlice(p, budgetMs) {
  const progress = p.continuePass(budgetMs);
  if (progress.done) progress.result = p.takeSweep();
  return progress;
}

// Buffers of typed arrays in a result, moved (not copied) to the main thread, each once
// (a picture may be named twice: the 3D charts' first histogram is also hist_a, hist_b).
// (never the wasm memory itself: results are copies out of it)
function transferables(value, out = []) {
  if (ArrayBuffer.isView(value)) {
    if (!(exports && value.buffer === exports.memory.buffer) && !out.includes(value.buffer)) out.push(value.buffer);
  }
  else if (value && typeof value === 'object') for (const v of Object.values(value)) transferables(v, out);
  return out;
}

const clock = () => performance.timeOrigin + performance.now();
function memoryBytes() {
  try {
    return exports ? exports.memory.buffer.byteLength : 0;
  } catch {
    return 0;
  }
}

self.onmessage = async (ev) => {
  const { id, cmd, args } = ev.data;
  let start = clock();
  try {
    exports = await ready;
    start = clock();
    const handler = handlers[cmd];
    if (!handler) throw new Error(`unknown command ${cmd}`);
    const result = handler(...(args || []));
    const t = { start, end: clock() };
    self.postMessage({ id, ok: true, result, t, memory: memoryBytes() }, transferables(result));
  } catch (e) {
    const panic = wasm.takePanicMessage ? safeTakePanic() : null;
    const error = panic || (e && e.message) || String(e);
    self.postMessage({ id, ok: false, error, panic: Boolean(panic), t: { start, end: clock() }, memory: memoryBytes() });
  }
};

function safeTakePanic() {
  try {
    return wasm.takePanicMessage() || null;
  } catch {
    return null;
  }
}

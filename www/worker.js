// The playground's engine: a module worker that owns the wasm module and the one
// Playground handle, so smoothing a large mesh never freezes the page. The main thread
// sends {id, cmd, args}; the worker answers {id, ok, result} or {id, ok: false, error,
// panic}. `panic: true` means the Rust code panicked: the handle may be broken, and the
// main thread replaces this worker with a fresh one. Every answer also carries `t`, the
// worker's start and end of the command (ms since the epoch, performance.timeOrigin +
// now, so the page can compare them with its own clock), and `memory`, the size of the
// wasm memory in bytes.
import init, * as wasm from './pkg/smoothlab.js';

const ready = init();
let exports = null;
let pg = null;

function need() {
  if (!pg) throw new Error('no mesh is loaded yet');
  return pg;
}

// Replace the handle only once the new one is built: a failed load keeps the old mesh.
function replace(next) {
  if (pg) pg.free();
  pg = next;
  return null;
}

const handlers = {
  samples: () => wasm.samples(),
  controls: () => wasm.controls(),
  checkControl: (key, text) => wasm.checkControl(key, text),
  loadSample: (name) => replace(wasm.Playground.fromSample(name)),
  loadFile: (name, bytes) => replace(wasm.Playground.fromBytes(new Uint8Array(bytes), name)),
  loadTriangle: (node, ele) => replace(wasm.Playground.fromTriangle(node, ele)),
  settings: (s) => need().setSettings(s),
  reset: () => need().reset(),
  step: () => need().step(),
  beginPass: () => need().beginPass(),
  // settings, beginPass and the first slice in one message (a short pass is one round trip)
  pass: (settings, budgetMs) => {
    const p = need();
    p.setSettings(settings);
    p.beginPass();
    return p.continuePass(budgetMs);
  },
  continuePass: (budgetMs) => need().continuePass(budgetMs),
  abortPass: () => need().abortPass(),
  perturb: (amount, seed) => need().perturb(amount, seed),
  // the pictures of both meshes and their statistics tables, in one message
  frame: (w, h, dpr, force) => {
    const p = need();
    const f = p.frame(w, h, dpr, Boolean(force));
    f.stats = { old: p.stats('old'), new: p.stats('new') };
    return f;
  },
  forgetFrames: () => need().forgetFrames(),
  pick: (panel, x, y, radius) => need().pickNode(panel, x, y, radius),
  drag: (node, x, y) => need().dragNode(node, x, y),
  select: (node) => need().selectNode(node === null ? undefined : node),
  nodeView: (w, h, cw, ch, dpr) => need().nodeView(w, h, cw, ch, dpr),
  charts: (w, h, hw, hh, dpr, logY) => need().charts(w, h, hw, hh, dpr, Boolean(logY)),
  exportMesh: (side, format) => need().exportMesh(side, format),
  worstNode: () => need().worstFreeNode() ?? null,
  zoomMeshes: (x, y, factor) => need().zoomMeshes(x, y, factor),
  panMeshes: (dx, dy) => need().panMeshes(dx, dy),
  zoomLevelSets: (panel, x, y, factor) => need().zoomLevelSets(panel, x, y, factor),
  panLevelSets: (panel, dx, dy) => need().panLevelSets(panel, dx, dy),
  resetZoom: () => need().resetZoom(),
  rememberBeforeMove: (node) => need().rememberBeforeMove(node),
  undo: () => need().undo(),
  nudge: (panel, dx, dy) => need().nudgeNode(panel, dx, dy),
  undoState: () => need().undoState(),
  smoothNode: (w, h, cw, ch, dpr) => need().smoothNode(w, h, cw, ch, dpr),
  figure: (w, h, dpr) => need().figure(w, h, dpr),
  panicForTest: () => wasm.panicForTest(),
  tourFigures: () => wasm.tourFigures(),
  tourCard: (name) => wasm.tourCard(name),
  tourPicture: (name, w, h, dpr) => wasm.tourPicture(name, w, h, dpr),
  tourPictureSize: (name) => wasm.tourPictureSize(name),
  tourRow: (i) => wasm.tourRow(i),
  decodePermalink: (hash) => wasm.decodePermalink(hash),
  encodePermalink: (fields) => wasm.encodePermalink(fields),
};

// Buffers of typed arrays in a result, moved (not copied) to the main thread.
function transferables(value, out = []) {
  if (value instanceof Uint8Array) out.push(value.buffer);
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

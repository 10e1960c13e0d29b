// The page's shared ground: the element lookup, the constants read from the address, the
// page's state, the engine (a worker running the Rust core as wasm), the serial queue that
// runs one engine operation at a time, and the message line. Every other module imports it.
// Nothing in the page builds HTML from file content or from the URL: text goes in with
// textContent only.
import { Engine } from '../engine.js';
import { loadSource } from './loading.js';
import { redrawAll } from './draw.js';

export const $ = (id) => document.getElementById(id);

/** The sample the page opens on: the first of the engine's gallery (`Sample::DEFAULT`). */
export const gallery = { defaultSample: null };
export const SETTINGS = ['strategy', 'target', 'boundary', 'threshold', 'order', 'passes', 'maxiter', 'amount', 'seed', 'objective-a', 'penalty-a', 'objective-b', 'penalty-b'];
/** The compare menus of the left (A) and right (B) panel. */
export const COMPARE = [['objective-a', 'penalty-a'], ['objective-b', 'penalty-b']];
export const PARAMS = new URLSearchParams(location.search);
/** The page inside a host that drives it (a notebook's widget, python/): the host writes
 * `data-host` on the page's <html>, where a document without an address of its own (a
 * blob) has no query to say it; the host's bridge is app/host.js. */
export const HOSTED = document.documentElement.dataset.host === 'widget';
export const EMBED = PARAMS.get('embed') === '1' || HOSTED;
/** The views `?embed=1&view=…` embeds alone, filling the frame: the canvases each shows,
 * which drawing fills them, and whether the embed first runs the hash's passes (as
 * `smoothlab render` does for the same views). */
export const VIEWS = {
  mesh: { canvases: ['mesh-a', 'mesh-b'], draws: 'meshes', passes: false },
  levelset: { canvases: ['level-a', 'level-b'], draws: 'node', passes: false },
  compare: { canvases: ['mesh-a', 'mesh-b'], draws: 'meshes', passes: true },
  history: { canvases: ['pass-chart'], draws: 'charts', passes: true },
  histogram: { canvases: ['hist-a', 'hist-b'], draws: 'charts', passes: true },
};
/** The embedded view (`?embed=1&view=NAME`): its name, and its entry of VIEWS when it names one;
 * a figure's own view replaces them (tour). */
export const view = { name: EMBED ? PARAMS.get('view') : null, spec: null };
view.spec = view.name !== null && Object.hasOwn(VIEWS, view.name) ? VIEWS[view.name] : null;
/** `#figure=NAME`: a figure of the papers' tour (crates/smoothlab-page/src/lab/tour), opened in its state. */
export const FIGURE_HASH = /^#figure=([a-z0-9-]{1,40})$/;
/** Milliseconds of smoothing per call to the worker during a pass: the progress bar
 * moves and Stop is heard at least this often. */
export const SLICE_MS = 50;

/** What the page tells its parts that may listen (app/host.js): `meshes`, a mesh picture
 * changed (a load, a pass, a move, a reset). */
export const pageEvents = new EventTarget();

export const now = () => performance.now();
export const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r()));

/** What the page measured of itself, for the curious and the page benchmark
 * (tests/browser/page_bench.mjs): see `window.smoothlab` at the end. */
export const metrics = { lastLoad: null, lastStep: null, run: null, startup: null };

export const state = {
  controls: null, // the core's control sheet (crates/smoothlab-page/src/lab/controls.rs): ranges, defaults, per-strategy reasons, menus, the Gmsh samples, the file limit
  invalid: new Map(), // control id → its message, while what is typed there is not valid
  perturbed: null, // {amount, seed} when the mesh on screen is the loaded one perturbed
  generation: 0, // counts what replaces the meshes (load, Perturb, Reset): a run's last words are for its own
  lastHash: null, // the hash this page last wrote or applied
  source: null, // what is loaded: {kind: 'sample'|'gmsh', name} or {kind: 'file'|'triangle', ...}
  lastGood: null, // the last source that loaded: reloaded after a panic
  node: null, // the node whose level sets are shown
  compare: null, // what the engine smooths each side with (as the compare menus said when last sent)
  boundary: 'fixed', // what the engine's boundary nodes do (as the boundary menu said when last sent)
  slideRefused: null, // why the mesh on screen's boundary cannot slide (a quadratic volume), or null
  running: false,
  cancel: false,
  frame: { w: 0, h: 0, dpr: 1 }, // the last mesh frame (pointer positions map through it)
  figure: null, // the tour's figure on show (its card from the core), or null
  viewOfFigure: false, // an embed shows the view its figure chose (not one named by view=)
  level: null, // the canvas the level sets were last drawn on (likewise)
  surface: false, // the mesh is a surface in 3D: its views orbit, and the planar-only views wait
  volume: false, // the mesh is made of tetrahedra (a 3D view too), drawn cut by a plane
};

export const engine = new Engine((err) => recoverFromPanic(err));

// ---- serial queue: one engine operation at a time, in order ---------------------------
export let chain = Promise.resolve();
export let queued = 0;
export function serial(fn) {
  queued += 1;
  document.body.dataset.busy = '1';
  const p = chain.then(fn);
  chain = p.catch(() => {}).finally(() => {
    queued -= 1;
    if (queued === 0) document.body.dataset.busy = '0';
  });
  return p;
}

// ---- messages ------------------------------------------------------------------------
export function showError(text) {
  const m = $('message');
  delete m.dataset.control;
  m.textContent = text;
  m.hidden = false;
}
export function clearError() {
  $('message').hidden = true;
  $('message').textContent = '';
  delete $('message').dataset.control;
}
export function setStatus(text) {
  $('status').textContent = text;
}
export function report(err) {
  if (err && err.panic) return; // recoverFromPanic shows it
  showError(err && err.message ? err.message : String(err));
}

export function recoverFromPanic(err) {
  showError(`Internal error in the smoothing engine (a bug; please report it): ${err.message}. ` +
    'The engine was restarted and the mesh reloaded from its source.');
  state.cancel = true;
  const src = state.lastGood;
  engine
    .restart(async (call) => {
      if (src) await loadSource(src, call);
    })
    .then(() => serial(redrawAll))
    .catch((e) => showError(`${$('message').textContent} Reloading failed too: ${e.message}`));
}

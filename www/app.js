// The playground page: wires the controls to the engine (a worker running the Rust core
// as wasm) and paints the pixels it returns. Nothing here builds HTML from file content
// or from the URL: text goes in with textContent only.
import { Engine } from './engine.js';

const $ = (id) => document.getElementById(id);

/** Gmsh meshes shipped with the site (www/samples/), fetched from the site itself. */
const GMSH_SAMPLES = [
  ['plate_hole_tri.msh', 'Gmsh: plate with a hole, triangles'],
  ['bracket_quad.msh', 'Gmsh: L-bracket, quads'],
  ['disk_tri6.msh', 'Gmsh: disk, 6-node triangles (curved)'],
];
/** The sample the page opens on: the first of the engine's gallery (`Sample::DEFAULT`). */
let defaultSample = null;
const MAX_FILE_BYTES = 256 * 1024 * 1024;
const SETTINGS = ['strategy', 'threshold', 'order', 'passes', 'maxiter', 'amount', 'seed', 'objective-a', 'penalty-a', 'objective-b', 'penalty-b'];
/** The compare menus of the left (A) and right (B) panel. */
const COMPARE = [['objective-a', 'penalty-a'], ['objective-b', 'penalty-b']];
const PARAMS = new URLSearchParams(location.search);
const EMBED = PARAMS.get('embed') === '1';
/** The views `?embed=1&view=…` embeds alone, filling the frame: the canvases each shows,
 * which drawing fills them, and whether the embed first runs the hash's passes (as
 * `smoothlab render` does for the same views). */
const VIEWS = {
  mesh: { canvases: ['mesh-old', 'mesh-new'], draws: 'meshes', passes: false },
  levelset: { canvases: ['level-old', 'level-new'], draws: 'node', passes: false },
  compare: { canvases: ['mesh-old', 'mesh-new'], draws: 'meshes', passes: true },
  history: { canvases: ['pass-chart'], draws: 'charts', passes: true },
  histogram: { canvases: ['hist-old', 'hist-new'], draws: 'charts', passes: true },
};
let VIEW_NAME = EMBED ? PARAMS.get('view') : null;
let VIEW = VIEW_NAME !== null && Object.hasOwn(VIEWS, VIEW_NAME) ? VIEWS[VIEW_NAME] : null;
/** `#figure=NAME`: a figure of the papers' tour (src/lab/tour), opened in its state. */
const FIGURE_HASH = /^#figure=([a-z0-9-]{1,40})$/;
/** Milliseconds of smoothing per call to the worker during a pass: the progress bar
 * moves and Stop is heard at least this often. */
const SLICE_MS = 50;
/** Generated samples a permalink cannot name (filled from the engine's gallery). */
const UNLINKABLE = new Set();

const now = () => performance.now();
const nextFrame = () => new Promise((r) => requestAnimationFrame(() => r()));

/** What the page measured of itself, for the curious and the page benchmark
 * (tests/browser/page_bench.mjs): see `window.smoothlab` at the end. */
const metrics = { lastLoad: null, lastStep: null, run: null, startup: null };

const state = {
  controls: null, // ranges, defaults and per-strategy reasons, from the core (limits.rs)
  invalid: new Map(), // control id → its message, while what is typed there is not valid
  perturbed: null, // {amount, seed} when the mesh on screen is the loaded one perturbed
  generation: 0, // counts what replaces the meshes (load, Perturb, Reset): a run's last words are for its own
  lastHash: null, // the hash this page last wrote or applied
  source: null, // what is loaded: {kind: 'sample'|'gmsh', name} or {kind: 'file'|'triangle', ...}
  lastGood: null, // the last source that loaded: reloaded after a panic
  node: null, // the node whose level sets are shown
  compare: null, // what the engine smooths each side with (as the compare menus said when last sent)
  running: false,
  cancel: false,
  frame: { w: 0, h: 0, dpr: 1 }, // the last mesh frame (pointer positions map through it)
  figure: null, // the tour's figure on show (its card from the core), or null
  viewOfFigure: false, // an embed shows the view its figure chose (not one named by view=)
  level: null, // the canvas the level sets were last drawn on (likewise)
  surface: false, // the mesh is a surface in 3D: its views orbit, and the planar-only views wait
  volume: false, // the mesh is made of tetrahedra (a 3D view too), drawn cut by a plane
};

const engine = new Engine((err) => recoverFromPanic(err));

// ---- serial queue: one engine operation at a time, in order ---------------------------
let chain = Promise.resolve();
let queued = 0;
function serial(fn) {
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
function showError(text) {
  const m = $('message');
  delete m.dataset.control;
  m.textContent = text;
  m.hidden = false;
}
function clearError() {
  $('message').hidden = true;
  $('message').textContent = '';
  delete $('message').dataset.control;
}
function setStatus(text) {
  $('status').textContent = text;
}
function report(err) {
  if (err && err.panic) return; // recoverFromPanic shows it
  showError(err && err.message ? err.message : String(err));
}

function recoverFromPanic(err) {
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

// ---- settings and permalink -----------------------------------------------------------
function readSettings() {
  return {
    strategy: $('strategy').value,
    threshold_deg: Number($('threshold').value),
    order: $('order').value,
    max_iter: Number($('maxiter').value),
    compare: COMPARE.map((_, i) => readChoice(i)),
  };
}
/** What side `i` (0 = A, 1 = B) smooths with; a penalty only for `new` (else the default design). */
function readChoice(i) {
  const [obj, pen] = COMPARE[i];
  const objective = $(obj).value;
  return { objective, penalty: $(pen).disabled ? state.controls.penalties[0].name : $(pen).value };
}

// ---- controls: built from the core's ranges, checked where they are edited ------------
/** The permalink key by which the core checks each typed control. */
const CHECKED = { passes: 'passes', maxiter: 'maxiter', seed: 'seed', amount: 'tangle' };

/** Sets the inputs' ranges and defaults from the core (the one place they are written). */
function buildControls(c) {
  state.controls = c;
  for (const id of ['passes', 'maxiter']) {
    const el = $(id);
    el.min = c[id].min;
    el.max = c[id].max;
    el.step = '1';
    el.value = c[id].default;
    el.title = `${c[id].label}: ${c[id].words}`;
    el.dataset.help = el.title;
  }
  $('seed').value = c.seed.default;
  $('seed').title = `Seed: ${c.seed.words}`;
  const a = $('amount');
  a.min = String(c.amount.min);
  a.max = String(c.amount.max);
  a.step = String(c.amount.step);
  a.value = String(c.amount.default);
  a.title = `Perturb amount: ${c.amount.words}`;
  $('amount-out').textContent = a.value;
  const t = $('threshold');
  t.replaceChildren();
  for (const v of c.threshold.options) {
    const o = document.createElement('option');
    o.value = String(v);
    o.textContent = `${v}°`;
    t.append(o);
  }
  t.value = String(c.threshold.default);
  $('file').accept = c.file_extensions.join(',');
  $('drop-hint').textContent = `…or drop a ${c.file_extensions_words} file (a .node and .ele pair together) anywhere on the page.`;
  fillMenu($('strategy'), c.strategies.map((s) => [s.name, s.label, s.title]), c.settings.strategy);
  fillMenu($('order'), c.orders.map((o) => [o.name, o.label, o.title]), c.settings.order);
  showStrategyReasons();
  // compare: every objective and penalty design the core offers, by its names
  for (const [i, [obj, pen]] of COMPARE.entries()) {
    const panel = c.panels[i];
    fillMenu($(obj), c.objectives.map((o) => [o.name, `${o.name}: ${o.words}`]), panel.objective);
    fillMenu($(pen), c.penalties.map((p) => [p.name, `${p.name}: ${p.words}`]), panel.penalty);
    document.documentElement.style.setProperty(`--side-${panel.side}`, `rgb(${panel.rgb.join(',')})`);
  }
  showPenaltyReasons();
}
/** Fills a menu with `[value, text, tooltip]` entries (the tooltip may be absent). */
function fillMenu(select, entries, value) {
  select.replaceChildren();
  for (const [v, text, title] of entries) {
    const o = document.createElement('option');
    o.value = v;
    o.textContent = text;
    if (title) o.title = title;
    select.append(o);
  }
  select.value = value;
}
/** A penalty is a design of `new`: its menu is disabled, saying so, for another objective. */
function showPenaltyReasons() {
  for (const [obj, pen] of COMPARE) {
    const other = $(obj).value !== 'new';
    $(pen).disabled = other;
    const why = other ? `Not used: only the new objective has a penalty (this side runs ${$(obj).value}).` : '';
    $(`${pen}-why`).textContent = why;
    $(pen).title = why;
  }
}
/** A side now runs something else: both sides start again from the mesh as loaded. */
function changeCompare() {
  showPenaltyReasons();
  const stopped = endRun();
  return serial(async () => {
    await engine.call('settings', readSettings());
    state.compare = COMPARE.map((_, i) => readChoice(i));
    await engine.call('reset');
    await redrawAll();
    clearError();
    const [a, b] = [readChoice(0), readChoice(1)];
    const name = (c) => (c.objective === 'new' ? `new (${c.penalty} penalty)` : c.objective);
    setStatus(`Comparing A, ${name(a)}, with B, ${name(b)}: both sides start again from the mesh as loaded.${stopped}`);
    await writePermalink();
  }).catch(report);
}

/** Disables the controls the chosen strategy does not use, saying why (as the CLI refuses them). */
function showStrategyReasons() {
  const info = state.controls.strategies.find((s) => s.name === $('strategy').value);
  for (const [id, why] of [['threshold', info && info.threshold_unused], ['maxiter', info && info.max_iter_unused]]) {
    $(id).disabled = Boolean(why);
    $(`${id}-why`).textContent = why ? `Not used: ${why}.` : '';
    $(id).title = why ? `Not used: ${why}.` : $(id).dataset.help || '';
  }
}

/** Checks one typed control with the core's rules; shows or clears its message. */
async function checkControl(id) {
  const text = $(id).value;
  const msg = await engine.call('checkControl', CHECKED[id], text);
  if ($(id).value !== text) return; // typed on meanwhile: that check will answer
  if (msg) state.invalid.set(id, msg);
  else state.invalid.delete(id);
  $(id).setAttribute('aria-invalid', msg ? 'true' : 'false');
  $(`${id}-error`).textContent = msg || '';
  // a refusal that named this control is stale once it is valid
  if (!msg && $('message').dataset.control === id) clearError();
}
/** The first message of a control that is not valid (ignoring controls not in use). */
function invalidMessage(ids) {
  for (const id of ids) if (state.invalid.has(id) && !$(id).disabled) return state.invalid.get(id);
  return null;
}
/** The permalink name of a Gmsh file: `gmsh-`, the name without `.msh`, `_` as `-`
 * (the rule of `gmsh_sample_name` in src/permalink.rs, which tests this list). */
function gmshSampleName(file) {
  return `gmsh-${file.replace(/\.msh$/, '').replaceAll('_', '-')}`;
}
/** The permalink sample name of what is loaded, or null (a user's file has none). */
function sourceSample() {
  const s = state.lastGood;
  if (!s) return null;
  if (s.kind === 'sample') return UNLINKABLE.has(s.name) ? null : s.name;
  if (s.kind === 'gmsh') return gmshSampleName(s.name);
  return null;
}
/** The hash of the loaded sample and the controls, written by the Rust encoder. */
function permalinkHash() {
  return engine.call('encodePermalink', {
    sample: sourceSample(),
    seed: state.perturbed ? BigInt(state.perturbed.seed) : BigInt($('seed').value.trim()),
    amount: state.perturbed ? state.perturbed.amount : Number($('amount').value),
    perturbed: Boolean(state.perturbed),
    node: state.node,
    settings: readSettings(),
    passes: Number($('passes').value),
  });
}
/** Keeps the URL and the permalink link current; a setting the link cannot carry is said
 * in the message box (the link then keeps its last good value). */
let permalinkSeq = 0;
async function writePermalink() {
  const seq = ++permalinkSeq;
  // a control being edited is not valid yet: the link keeps its last good value, and the
  // control itself says what it wants
  if (invalidMessage(Object.keys(CHECKED))) return;
  let hash;
  try {
    hash = await permalinkHash();
  } catch (e) {
    if (seq === permalinkSeq) showError(`The link cannot hold these settings: ${e.message.replace(/^permalink: /, '')}`);
    return;
  }
  if (seq !== permalinkSeq) return; // a later change wrote it
  state.lastHash = hash;
  history.replaceState(null, '', `${location.pathname}${location.search}${hash}`);
  $('permalink').href = `${location.pathname}${hash}`;
  const s = state.lastGood;
  let note = '';
  if (s && s.kind === 'sample' && UNLINKABLE.has(s.name) && state.surface) {
    note = 'A surface sample cannot be opened from a link yet: the link keeps the settings only, with the default sample.';
  } else if (s && s.kind === 'sample' && UNLINKABLE.has(s.name)) {
    note = 'This sample is too large to open from a link: the link keeps the settings only, with the default sample.';
  } else if (s && (s.kind === 'file' || s.kind === 'triangle')) {
    note = `Your own file (${s.name}) cannot travel in a link: the link opens these settings on the default sample.`;
  }
  $('permalink').title = note;
  $('permalink-note').textContent = note;
  if (EMBED) $('open-full').href = `${location.pathname}${hash}`;
}
/** The page's address with the current hash, for the Copy link button. */
async function copyLink() {
  await serial(writePermalink);
  const url = new URL($('permalink').getAttribute('href'), location.href).toString();
  try {
    await navigator.clipboard.writeText(url);
    setStatus(`Link copied: ${url}`);
  } catch {
    setStatus(`Copy this link: ${url}`);
  }
  $('copy-link').dataset.copied = url;
}
function updatePermalink() {
  return serial(writePermalink).catch(report);
}
/** Reads the URL hash through the Rust decoder and applies it to the controls (a value a
 * control does not offer is ignored). Returns the source to load and, when the hash could
 * not be read, the decoder's message (the defaults are then kept). */
async function applyHash(hash = location.hash) {
  const fallback = { kind: 'sample', name: defaultSample };
  let p;
  try {
    p = await engine.call('decodePermalink', hash);
  } catch (e) {
    return { src: fallback, error: e.message };
  }
  const c = p.settings;
  const values = {
    strategy: c.strategy,
    threshold: c.threshold_deg,
    order: c.order,
    passes: p.passes,
    maxiter: c.max_iter,
    amount: p.amount,
    seed: p.seed,
    'objective-a': c.compare[0].objective,
    'penalty-a': c.compare[0].penalty,
    'objective-b': c.compare[1].objective,
    'penalty-b': c.compare[1].penalty,
  };
  for (const id of SETTINGS) {
    const v = String(values[id]);
    const el = $(id);
    if (el.tagName === 'SELECT') {
      if ([...el.options].some((o) => o.value === v)) el.value = v;
    } else {
      el.value = v; // the decoder checked it against the same ranges
    }
  }
  for (const id of Object.keys(CHECKED)) {
    state.invalid.delete(id);
    $(id).setAttribute('aria-invalid', 'false');
    $(`${id}-error`).textContent = '';
  }
  $('amount-out').textContent = $('amount').value;
  showStrategyReasons();
  showPenaltyReasons();
  const extra = { perturbed: p.perturbed ? { amount: p.amount, seed: String(p.seed) } : null, node: p.node };
  if (p.sample === null) return { src: fallback, ...extra };
  const gmsh = GMSH_SAMPLES.find(([f]) => gmshSampleName(f) === p.sample);
  if (gmsh) return { src: { kind: 'gmsh', name: gmsh[0] }, ...extra };
  if ([...$('sample').options].some((o) => o.value === `sample:${p.sample}`)) return { src: { kind: 'sample', name: p.sample }, ...extra };
  return { src: fallback, ...extra };
}

/** The label of a source as the sample menu shows it (not its internal name). */
function labelOf(src) {
  const o = [...$('sample').options].find((x) => x.value === selectValueOf(src));
  return o ? o.textContent : src.name;
}

/** Opens what a hash names: its sample (unless it is already loaded and unperturbed),
 * its perturbation and its node. The controls were set by applyHash. */
async function openHash({ src, error, perturbed, node }, { keepLink = false } = {}) {
  const same = state.lastGood && selectValueOf(state.lastGood) === selectValueOf(src) && selectValueOf(src) !== '';
  if (!same || state.perturbed || perturbed) await load(src, labelOf(src), { keepHash: true });
  else if (!sameCompare()) await changeCompare();
  if (perturbed) await perturbWith(perturbed.amount, perturbed.seed, { keepHash: true });
  if (node !== null && node !== undefined) await selectNode(node, { keepHash: true });
  else if (state.node !== null) await selectNode(null, { keepHash: true });
  if (error) showError(`This link's settings could not be read, so the defaults are shown: ${error.replace(/^permalink: /, '')}`);
  if (!keepLink) await serial(writePermalink).catch(report);
}

/** An embedded view shows what `smoothlab render` shows for it: the level sets of the
 * hash's node (else of the free node with the worst star), the other views after the
 * hash's passes. */
async function openView() {
  if (!VIEW) return;
  if (VIEW_NAME === 'levelset' && state.node === null) {
    const worst = await serial(() => engine.call('worstNode'));
    if (worst !== null) await selectNode(worst, { keepHash: true });
  }
  if (VIEW.passes) await smooth(Number($('passes').value));
}

/** Whether the engine smooths each side with what the menus say. */
function sameCompare() {
  return JSON.stringify(state.compare) === JSON.stringify(COMPARE.map((_, i) => readChoice(i)));
}

/** The user edited the hash or went Back or Forward: show what the address now names. */
async function onAddressChange() {
  try {
    await openAddress();
  } finally {
    markAddressHandled();
  }
}
/** Says on the body which address the page has opened (`data-hash`), for tests and tools:
 * a link that changes only the hash reloads nothing, so its handling starts after the
 * navigation has ended. */
function markAddressHandled() {
  document.body.dataset.hash = location.hash;
}
async function openAddress() {
  if (location.hash === state.lastHash) return; // this page wrote it
  state.lastHash = location.hash;
  const fig = FIGURE_HASH.exec(location.hash);
  if (fig) return openFigure(fig[1]);
  if (state.figure) {
    state.figure = null;
    $('tour').hidden = true;
    delete document.body.dataset.figure;
  }
  await openHash(await applyHash());
}

// ---- the figures tour ---------------------------------------------------------------
/** Opens a figure of the tour: its words, the playground in its state (sample, settings,
 * node; its passes run when the figure says so), its picture and, for Freitag's table,
 * the rows smoothed one by one. The address stays `#figure=NAME`. */
async function openFigure(name) {
  let card;
  try {
    card = await engine.call('tourCard', name);
  } catch (e) {
    // an unknown name: the playground as it is (or the defaults, on a first load), and why
    if (!state.lastGood) await openHash(await applyHash('#'));
    showError(`This link names no figure of the tour: ${e.message}`);
    return;
  }
  state.figure = card;
  document.body.dataset.figure = '';
  document.body.dataset.figureRows = '0';
  // an embedded figure shows its own view, unless the address names one (`view=`)
  if (EMBED && (!VIEW || state.viewOfFigure) && Object.hasOwn(VIEWS, card.view)) {
    if (VIEW_NAME) document.body.classList.remove(`view-${VIEW_NAME}`);
    VIEW_NAME = card.view;
    VIEW = VIEWS[card.view];
    state.viewOfFigure = true;
    document.body.classList.add('view', `view-${VIEW_NAME}`);
  }
  showCard(card);
  await openHash(await applyHash(`#${card.hash}`), { keepLink: true });
  const link = `#figure=${card.name}`;
  state.lastHash = link;
  history.replaceState(null, '', `${location.pathname}${location.search}${link}`);
  $('permalink').href = `${location.pathname}${link}`;
  if (EMBED) $('open-full').href = `${location.pathname}${link}`;
  await drawFigurePicture();
  if (card.run) await smooth(Number($('passes').value));
  if (card.rows) await fillTourTable(card);
  if (state.figure === card) document.body.dataset.figure = card.name;
}

function showCard(card) {
  $('tour').hidden = false;
  $('tour-title').textContent = `${card.index + 1} of ${card.count}: ${card.source}`;
  $('tour-caption').textContent = card.caption;
  $('tour-look').textContent = card.look;
  $('tour-claim').textContent = card.claim;
  $('tour-measured').textContent = card.measured;
  $('tour-menu').value = card.name;
  $('tour-prev').dataset.figure = card.prev;
  $('tour-next').dataset.figure = card.next;
  $('tour-link').href = `#figure=${card.name}`;
  $('tour-link').textContent = `Link to this figure (#figure=${card.name})`;
  $('tour-table').hidden = !card.rows;
  $('tour-rows').replaceChildren();
}

/** The figure's own picture (the core draws it: `smoothlab render --figure NAME`), as
 * wide as the panel and in the picture's proportions. */
async function drawFigurePicture() {
  const card = state.figure;
  if (!card) return;
  const canvas = $('tour-picture');
  const [w0, h0] = await engine.call('tourPictureSize', card.name);
  const w = Math.max(200, Math.min(w0, Math.round(canvas.parentElement.clientWidth - 4)));
  const h = Math.round((w * h0) / w0);
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const r = await engine.call('tourPicture', card.name, w, h, dpr);
  if (state.figure !== card) return;
  canvas.style.aspectRatio = `${w} / ${h}`;
  canvas.style.maxWidth = `${w}px`;
  paint(canvas, r.pixels, r.w, r.h);
}

/** Freitag's Table 1: each row smoothed now in the worker (3 passes on seed 1), then shown. */
async function fillTourTable(card) {
  const body = $('tour-rows');
  for (let i = 0; i < card.rows; i++) {
    const r = await engine.call('tourRow', i);
    if (state.figure !== card) return;
    const tr = document.createElement('tr');
    const cells = [
      r.method.replaceAll('`', ''),
      `${r.min_angle_deg.toFixed(2)}°`,
      `${r.max_angle_deg.toFixed(1)}°`,
      String(r.laplacian_moves),
      String(r.optimization_calls),
      r.reproduction_min,
      r.reproduction_max,
      r.paper,
    ];
    for (const [k, text] of cells.entries()) {
      const td = document.createElement(k === 0 ? 'th' : 'td');
      if (k === 0) td.scope = 'row';
      td.textContent = text;
      tr.append(td);
    }
    body.append(tr);
    document.body.dataset.figureRows = String(i + 1);
  }
}

function goFigure(name) {
  if (!name) return;
  location.hash = `figure=${name}`; // hashchange opens it, and Back returns
}

function closeTour() {
  state.figure = null;
  $('tour').hidden = true;
  delete document.body.dataset.figure;
  updatePermalink();
}

async function fillTourMenu() {
  const list = await engine.call('tourFigures');
  for (const f of list) {
    const o = document.createElement('option');
    o.value = f.name;
    o.textContent = `${f.source} (${f.name})`;
    $('tour-menu').append(o);
  }
}

// ---- loading -------------------------------------------------------------------------
async function loadSource(src, call = (...a) => engine.call(...a)) {
  const loaded = await sendSource(src, call);
  await call('settings', readSettings());
  state.compare = COMPARE.map((_, i) => readChoice(i));
  state.lastGood = src;
  state.node = null;
  state.perturbed = null;
  $('node').value = '';
  showSurfaceMode(loaded.surface, loaded.notPlanar, Boolean(loaded.volume));
  return loaded;
}

/** Has a worker load a source; says what it loaded (`{ surface, volume, notPlanar, nodes }`). */
async function sendSource(src, call) {
  let loaded = { surface: false };
  switch (src.kind) {
    case 'sample':
      loaded = await call('loadSample', src.name);
      break;
    case 'gmsh': {
      const res = await fetch(`samples/${encodeURIComponent(src.name)}`);
      if (!res.ok) throw new Error(`could not fetch the sample ${src.name} (HTTP ${res.status})`);
      const bytes = await res.arrayBuffer();
      loaded = await call('loadFile', src.name, bytes);
      break;
    }
    case 'file':
      loaded = await call('loadFile', src.name, src.bytes.slice(0));
      break;
    case 'triangle':
      loaded = await call('loadTriangle', src.node, src.ele);
      break;
    default:
      throw new Error('unknown mesh source');
  }
  return loaded;
}

// ---- the second worker ---------------------------------------------------------------
/** A planar mesh of SPLIT_MIN_NODES to SPLIT_MAX_NODES nodes is also loaded into a second
 * worker, which sweeps the old side (A) of each pass while the first worker smooths the
 * new side (B): the two sides are independent, so on two cores a pass takes about the
 * longer side's time rather than both sides' (the same result, bit for bit: the core's
 * split pass, lab::pass). A smaller mesh is not worth a second copy of it; a larger one
 * would take the two workers' memory together past the page's 400 MiB
 * (docs/performance.md). `?workers=1` keeps one worker. */
const SPLIT_MIN_NODES = 20000;
const SPLIT_MAX_NODES = 500000;
const helper = { engine: null, src: null, ok: false };

/** Loads `src` (just loaded, with `nodes` nodes) into the second worker, in the background;
 * passes use it once it is ready. Any other mesh stops it. */
function startHelper(src, nodes) {
  stopHelper();
  if (!(nodes >= SPLIT_MIN_NODES && nodes <= SPLIT_MAX_NODES) || PARAMS.get('workers') === '1') return;
  const e = new Engine(() => stopHelper()); // a panic there: passes go on in one worker
  Object.assign(helper, { engine: e, src, ok: false });
  sendSource(src, (...a) => e.call(...a))
    .then(() => {
      if (helper.engine === e) helper.ok = true;
    })
    .catch(() => {
      if (helper.engine === e) stopHelper();
    });
}

function stopHelper() {
  if (helper.engine) helper.engine.worker.terminate();
  Object.assign(helper, { engine: null, src: null, ok: false });
}

/** The second worker, when it holds the mesh on screen. */
function readyHelper() {
  return helper.ok && helper.src === state.lastGood && !state.surface ? helper.engine : null;
}

/** What a surface does not have (yet) on the page, and why: these controls wait,
 * saying so, while a surface is loaded (as a strategy's unused controls do). */
const PLANAR_ONLY = {
  node: 'a node of a surface moves in its tangent plane: the level sets are drawn for planar meshes',
  'smooth-node': 'the level sets and one-node smoothing are for planar meshes',
  undo: 'nodes of a surface are not dragged (a drag turns the view)',
  'hist-log': 'the per-pass chart and the angle histograms are drawn for planar meshes',
  'save-figure': 'the figure for slides is drawn for planar meshes; save each 3D view as a PNG',
};

/** Puts the page in the surface mode (or back in the planar one); `why` says why a file
 * read as a surface (the node farthest off the plane it would lie in: a mistyped
 * coordinate shows here, as the command-line tool says it). */
function showSurfaceMode(on, why = null, volume = false) {
  state.surface = on;
  state.volume = on && volume;
  showPickNote(null); // it spoke of the mesh before
  document.body.classList.toggle('surface', on);
  $('surface-note').hidden = !on || state.volume;
  $('volume-note').hidden = !state.volume;
  if (state.volume) {
    $('cut-axis').value = '2';
    $('cut-at').value = '0.5';
    $('cut-at-out').textContent = '0.50';
  }
  $('surface-why').hidden = !(on && why);
  $('surface-why').textContent = on && why ? `Read as a surface in 3D: ${why}.` : '';
  for (const [id, why] of Object.entries(PLANAR_ONLY)) {
    const el = $(id);
    if (on) {
      el.disabled = true;
      el.title = state.volume ? `Not for tetrahedra: ${why.replace(/a surface/g, 'a 3D mesh')}.` : `Not for a surface: ${why}.`;
    } else {
      el.disabled = id === 'smooth-node' ? state.node === null : id === 'undo' ? el.disabled : false;
      el.title = el.dataset.help || '';
    }
  }
  for (const id of ['mesh-old', 'mesh-new']) {
    const letter = id === 'mesh-old' ? 'A' : 'B';
    $(id).setAttribute('aria-label', on
      ? (state.volume
        ? `Tetrahedra of panel ${letter}, cut by a plane, coloured by mean ratio; drag to turn, wheel to zoom`
        : `Surface of panel ${letter} in 3D, coloured by quality; drag to turn, wheel to zoom`)
      : `Mesh of panel ${letter}, coloured by quality; arrow keys move the chosen node`);
  }
}

function selectValueOf(src) {
  if (src.kind === 'sample') return `sample:${src.name}`;
  if (src.kind === 'gmsh') return `gmsh:${src.name}`;
  return '';
}

/** Loads a source; on failure the previous mesh stays on screen and the message says why. */
function load(src, label, { keepHash = false } = {}) {
  const stopped = endRun();
  return serial(async () => {
    setStatus(`Loading ${label}…`);
    const t0 = now();
    $('progress').removeAttribute('value'); // indeterminate while the worker builds it
    let loaded;
    try {
      loaded = await loadSource(src);
    } catch (e) {
      setStatus('');
      $('sample').value = state.lastGood ? selectValueOf(state.lastGood) : '';
      throw e;
    } finally {
      $('progress').max = 1;
      $('progress').value = 0;
    }
    const t1 = now();
    clearError();
    $('sample').value = selectValueOf(src);
    await redrawAll();
    const ms = now() - t0;
    metrics.lastLoad = { label, ms, build_ms: t1 - t0, draw_ms: now() - t1, memory_bytes: engine.memory };
    startHelper(src, loaded.nodes);
    setStatus(`Loaded ${label} in ${Math.round(ms)} ms.${stopped}`);
    if (!keepHash) await writePermalink();
  }).catch(report);
}

/** Something replaces the meshes: a run in progress stops, and says nothing more (what
 * replaced them says what happened). Returns the words to add to that. */
function endRun() {
  state.generation += 1;
  if (!state.running) return '';
  state.cancel = true;
  return ' The run in progress was stopped.';
}

async function readFiles(files) {
  const list = [...files];
  if (list.length === 0) return;
  for (const f of list) {
    if (f.size > MAX_FILE_BYTES) {
      showError(`${f.name} is too large (${(f.size / 1048576).toFixed(0)} MB); the page reads files up to ${MAX_FILE_BYTES / 1048576} MB.`);
      return;
    }
  }
  const ext = (f) => f.name.toLowerCase().split('.').pop();
  const node = list.find((f) => ext(f) === 'node');
  const ele = list.find((f) => ext(f) === 'ele');
  if (node || ele) {
    if (!(node && ele)) {
      showError(`A Triangle mesh needs its .node and .ele files together: select or drop both (got only ${(node || ele).name}).`);
      return;
    }
    const [nt, et] = await Promise.all([node.text(), ele.text()]);
    await load({ kind: 'triangle', node: nt, ele: et, name: `${node.name} + ${ele.name}` }, `${node.name} + ${ele.name}`);
    return;
  }
  if (list.length > 1) {
    showError(`Drop one mesh file at a time (or a .node and .ele pair); got ${list.length} files.`);
    return;
  }
  const f = list[0];
  const bytes = await f.arrayBuffer();
  await load({ kind: 'file', name: f.name, bytes }, f.name);
}

// ---- drawing -------------------------------------------------------------------------
/** Device-pixel size of a canvas as laid out, and the ratio used (at most 2). */
function canvasPixels(canvas) {
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const w = Math.max(64, Math.min(2048, Math.round(canvas.clientWidth * dpr)));
  const h = Math.max(64, Math.min(2048, Math.round(canvas.clientHeight * dpr)));
  return { w, h, dpr };
}
/** Puts RGBA pixels (moved here from the worker, not copied) on a canvas; returns the ms it took. */
function paint(canvas, pixels, w, h) {
  const t0 = now();
  if (canvas.width !== w) canvas.width = w;
  if (canvas.height !== h) canvas.height = h;
  const img = new ImageData(new Uint8ClampedArray(pixels.buffer, pixels.byteOffset, pixels.byteLength), w, h);
  canvas.getContext('2d').putImageData(img, 0, 0);
  return now() - t0;
}

/** The table's rows: key, label, value, and which way is better (`higher`, `lower`, or
 * none): the better of the two sides is marked. `detail` rows need every corner measured
 * (large meshes: after the run). */
const STAT_ROWS = [
  ['nodes', 'Nodes', (s) => s.nodes],
  ['elements', 'Elements', (s) => s.elements],
  ['inverted', 'Inverted elements', (s) => s.inverted, 'lower'],
  ['min_angle', 'Min angle', (s) => s.min_angle_deg, 'higher', deg],
  ['max_angle', 'Max angle', (s) => s.max_angle_deg, 'lower', deg],
  ['min_quality', 'Min quality (α/β)', (s) => s.min_quality, 'higher', num],
  ['mean_quality', 'Mean quality (α/β)', (s) => s.detail && s.detail.mean_quality, 'higher', num, true],
  ['small_angles', 'Angles under 18°', (s) => s.detail && s.detail.small_angle_share, 'lower', pct, true],
  ['max_condition', 'Worst κ (condition number)', (s) => s.detail && (s.detail.max_condition ?? Infinity), 'lower', kappa, true],
  ['surface_distance', 'Largest distance from the surface', (s) => s.max_distance_from_surface, 'lower', (v) => v.toExponential(2), false, true],
  ['laplacian_moves', 'Laplacian moves', (s) => s.laplacian_moves],
  ['optimization_calls', 'Optimization calls', (s) => s.optimization_calls],
  ['passes', 'Passes', (s) => s.passes],
  ['time', 'Smoothing time', (s) => s.time_ms, null, (v) => `${num(v, 1)} ms`],
];
/** A tetrahedral mesh's names for the rows whose meaning changes in 3D. */
const VOLUME_LABELS = {
  elements: 'Tetrahedra',
  inverted: 'Inverted tetrahedra',
  min_angle: 'Min dihedral angle',
  max_angle: 'Max dihedral angle',
  min_quality: 'Min mean ratio',
  mean_quality: 'Mean of the mean ratio',
  small_angles: 'Dihedral angles under 18°',
};
/** What a table row means, as its tooltip. */
const ROW_HELP = {
  inverted: 'Elements whose corners run the wrong way round (negative area): a tangled mesh. Fewer is better.',
  min_angle: 'The smallest corner angle of any element (negative in an inverted element). Larger is better.',
  max_angle: 'The largest corner angle of any element. Smaller is better.',
  min_quality: "The worst element quality: Lo's α for triangles, Canann's β for quads (1 ideal, below 0 inverted).",
  mean_quality: 'The mean element quality (α for triangles, β for quads).',
  small_angles: "The share of corner angles under 18° (Freitag's Fig. 3 view).",
  max_condition: "The worst condition number κ = ‖A‖‖A⁻¹‖ of an element's Jacobian (Knupp): 1 ideal, ∞ inverted.",
  surface_distance: 'A surface only: how far the node farthest from the surface it lies on is from it, in the mesh\'s units (nodes are moved in their tangent plane, then put back on the surface).',
  laplacian_moves: 'Nodes moved by a (plain or smart) Laplacian step, over the passes.',
  optimization_calls: 'Calls to the solver, over the passes.',
};
function deg(v) {
  return Number.isFinite(v) ? `${v.toFixed(2)}°` : '—';
}
function num(v, digits = 4) {
  return typeof v === 'number' && Number.isFinite(v) ? v.toFixed(digits) : '—';
}
function pct(v) {
  return `${(100 * v).toFixed(v > 0 && v < 0.001 ? 3 : 1)}%`;
}
function kappa(v) {
  return v === Infinity ? '∞ (inverted)' : num(v, 3);
}
/** Which side's value is better (0 = A, 1 = B), or null for a tie or no direction. */
function betterSide(dir, a, b) {
  if (!dir || typeof a !== 'number' || typeof b !== 'number' || Number.isNaN(a) || Number.isNaN(b) || a === b) return null;
  return (dir === 'higher') === (a > b) ? 0 : 1;
}
/** Fills both tables side by side, marking the better value of each row. */
function fillTables(stats) {
  const pair = [stats.old, stats.new];
  for (const [i, side] of ['old', 'new'].entries()) {
    const s = pair[i];
    $(`title-${side}`).textContent = EMBED ? s.label : s.title;
    const body = $(`stats-${side}`).tBodies[0];
    body.replaceChildren();
    for (const [key, label, get, dir, fmt = String, detail, surfaceOnly] of STAT_ROWS) {
      const v = get(s);
      if (surfaceOnly && (v === null || v === undefined)) continue;
      const tr = document.createElement('tr');
      tr.dataset.stat = key;
      const th = document.createElement('th');
      th.scope = 'row';
      th.textContent = (state.volume && VOLUME_LABELS[key]) || label;
      if (ROW_HELP[key]) th.title = ROW_HELP[key];
      const td = document.createElement('td');
      if (detail && !s.detail) {
        td.textContent = 'after the run';
        td.classList.add('pending');
        td.title = 'This mesh is large: this row is measured when the charts are drawn, after a run.';
      } else {
        td.textContent = fmt(v);
        td.dataset.value = String(v);
        if (betterSide(dir, get(pair[0]), get(pair[1])) === i) {
          td.classList.add('better'); // marked ✓ by the style sheet
          td.setAttribute('aria-label', `${td.textContent}, the better of the two`);
          td.title = 'the better of the two sides';
        }
      }
      tr.append(th, td);
      body.append(tr);
    }
  }
}

/** Draws both meshes (a panel whose picture would not change is not sent again) and
 * their statistics tables; returns where the time went. */
/** In an embed the page must fit its frame without scrolling: the mesh canvases shrink
 * (staying square) by what the page is taller than the frame. */
function fitEmbed() {
  if (!EMBED) return false;
  if (VIEW) return fitView();
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
function fitView() {
  const cs = VIEW.canvases.map($);
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

async function redrawMeshes() {
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

async function redrawCharts() {
  if (EMBED && !(VIEW && VIEW.draws === 'charts')) return;
  if (VIEW) fitView();
  if (state.volume) {
    placeholder($('pass-chart'), 'Drawn for planar meshes; the tables follow the tetrahedra pass by pass');
    const hc = canvasPixels($('hist-old'));
    const r = await engine.call('volumeHistograms', hc.w, hc.h, hc.dpr);
    paint($('hist-old'), r.old, hc.w, hc.h);
    paint($('hist-new'), r.new, hc.w, hc.h);
    return;
  }
  if (state.surface) {
    for (const id of ['pass-chart', 'hist-old', 'hist-new']) placeholder($(id), 'Drawn for planar meshes; this is a surface');
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

const NODE_HINT = 'Click a free (interior) node on either mesh, or type its number. Drag a node to move it on both meshes.';

/** A canvas with a line of text in the middle (drawn, not HTML). */
function placeholder(canvas, text) {
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

async function redrawNode() {
  if (EMBED && !(VIEW && VIEW.draws === 'node')) return;
  if (VIEW) fitView();
  const lv = canvasPixels($('level-old'));
  const ch = canvasPixels($('solve-chart'));
  $('smooth-node').disabled = state.node === null || state.running || state.surface;
  if (state.surface) {
    for (const id of ['level-old', 'level-new', 'solve-chart']) placeholder($(id), 'Drawn for planar meshes; this is a surface');
    $('node-hint').textContent = `Not for a surface: ${PLANAR_ONLY.node}.`;
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

async function redrawAll() {
  await redrawMeshes();
  await redrawCharts();
  await redrawNode();
}

// ---- smoothing -----------------------------------------------------------------------
const SIDE_NAME = { old: 'A', new: 'B' };
const STAGE_NAME = { plan: 'ordering the nodes', smooth: 'smoothing', measure: 'measuring', wait: 'waiting for the other worker' };

/**
 * One pass on both sides, in slices of SLICE_MS in the worker so the progress bar moves
 * during the pass and Stop is heard within a slice. Returns the pass records, or null
 * when stopped (the worker then puts both meshes back as they were before the pass).
 * `i` and `n` place the pass in its run for the progress bar.
 */
async function smoothPass(i, n) {
  // the worker's time in its commands, and the round trips' time beyond it
  const cost = { worker_ms: 0, messaging_ms: 0 };
  const call = async (cmd, ...args) => {
    const { result, timing: t } = await engine.timed(cmd, ...args);
    const w = t.worker.end - t.worker.start;
    cost.worker_ms += w;
    cost.messaging_ms += t.received - t.sent - w;
    return result;
  };
  const second = readyHelper();
  if (second) {
    const r = await splitPass(i, n, call, cost, second);
    if (r !== undefined) return r;
  }
  let slices = 0;
  if ($('order').value === 'priority') {
    setStatus(`Pass ${i + 1} of ${n}: ordering the nodes of the old side, worst first…`);
  }
  for (;;) {
    if (state.cancel) {
      await call('abortPass');
      return null;
    }
    const p = await (slices === 0 ? call('pass', readSettings(), SLICE_MS) : call('continuePass', SLICE_MS));
    slices += 1;
    $('progress').value = i + p.fraction;
    if (p.done) return { records: p.records, slices, workers: 1, ...cost };
    if (state.cancel) continue; // "Stopping…" stays on screen
    const pct = Math.floor(p.fraction * 100);
    setStatus(`Pass ${i + 1} of ${n}: ${SIDE_NAME[p.side]} side, ${STAGE_NAME[p.stage] || p.stage}… ${pct}% (Stop undoes this pass)`);
  }
}

/**
 * One pass split between the two workers (see SPLIT_MIN_NODES): the second sweeps the old
 * side from this worker's positions while this one smooths the new side, then takes the
 * old side's sweep over and measures it. As smoothPass; `undefined` when the second worker
 * failed (it is dropped, the pass undone, and the caller runs it in one worker).
 */
async function splitPass(i, n, call, cost, second) {
  const settings = readSettings();
  const nodes = await call('positions', 'old');
  let swept = null; // the second worker's result, once it has it
  let failed = null;
  let oldFraction = 0;
  // settles when the second worker is done, stopped or failed (never rejects)
  const sweeping = (async () => {
    let p = await second.call('sweep', settings, 'old', nodes, SLICE_MS);
    while (!p.done) {
      oldFraction = p.fraction;
      if (state.cancel) {
        await second.call('abortPass');
        return;
      }
      p = await second.call('continueSweep', SLICE_MS);
    }
    oldFraction = 1;
    swept = p.result;
  })().catch((e) => {
    failed = e;
  });
  let slices = 1;
  let p = await call('splitPass', settings, SLICE_MS);
  let adopted = false;
  for (;;) {
    if (failed) {
      await call('abortPass');
      stopHelper();
      return undefined;
    }
    if (state.cancel) {
      await call('abortPass');
      await sweeping;
      return null;
    }
    if (!adopted && swept) {
      await call('adoptSweep', swept.nodes, swept.sweep);
      adopted = true;
    }
    // the new side is the first half of this worker's pass, the old side's statistics the
    // last twentieth of its second half; the old side's sweep is the second worker's
    const newPart = Math.min(1, 2 * p.fraction);
    const oldPart = 0.9 * oldFraction + Math.max(0, 2 * p.fraction - 1.9);
    $('progress').value = i + (p.done ? 1 : Math.min(1, (newPart + oldPart) / 2));
    if (p.done) return { records: p.records, slices, workers: 2, ...cost };
    setStatus(`Pass ${i + 1} of ${n}, in two workers: A side ${Math.floor(100 * oldFraction)}%, B side ${Math.floor(100 * newPart)}%… (Stop undoes this pass)`);
    if (p.stage === 'wait' && !adopted) {
      // this worker is done with the new side: wait for the old side's sweep, a slice at a time
      await Promise.race([sweeping, new Promise((r) => setTimeout(r, SLICE_MS))]);
      continue;
    }
    p = await call('continuePass', SLICE_MS);
    slices += 1;
  }
}

function setRunning(on) {
  state.running = on;
  $('run').textContent = on ? 'Stop' : 'Run';
  $('run').setAttribute('aria-pressed', on ? 'true' : 'false');
  $('step').disabled = on;
  $('smooth-node').disabled = on || state.node === null || state.surface;
  if (on) $('undo').disabled = true;
}

/** Runs `n` passes, redrawing the meshes after each; the Run button stops it. */
/** Asks the run in progress to stop, and says so at once. */
function requestStop() {
  state.cancel = true;
  setStatus('Stopping: the pass in progress is being undone…');
}

async function smooth(n) {
  if (state.running) {
    requestStop();
    return;
  }
  const t0 = now();
  const generation = state.generation;
  setRunning(true);
  state.cancel = false;
  $('progress').max = n;
  $('progress').value = 0;
  let done = 0;
  const passes = [];
  try {
    for (let i = 0; i < n && !state.cancel; i++) {
      setStatus(`Pass ${i + 1} of ${n}…`);
      const p0 = now();
      const r = await serial(async () => {
        const pass = await smoothPass(i, n);
        if (!pass) return null;
        const p1 = now();
        const draw = await redrawMeshes();
        return { ...pass, pass_ms: p1 - p0, draw, meshes_ms: now() - p0 };
      });
      if (!r) break;
      done = i + 1;
      $('progress').value = done;
      const [ro, rn] = r.records;
      passes.push({
        pass: ro.pass,
        wall_ms: r.meshes_ms,
        pass_ms: r.pass_ms,
        slices: r.slices,
        workers: r.workers,
        worker_ms: r.worker_ms,
        messaging_ms: r.messaging_ms,
        sweep_ms: [ro.elapsed_ms, rn.elapsed_ms],
        stats_ms: [ro.stats_ms, rn.stats_ms],
        visits: [ro.visits, rn.visits],
        ...r.draw,
      });
      await nextFrame();
    }
    const c0 = now();
    if (!state.cancel && generation === state.generation) setStatus('Drawing the charts…');
    await serial(async () => {
      await redrawCharts();
      await redrawNode();
    });
    const charts_ms = now() - c0;
    const total = now() - t0;
    const stopped = state.cancel && done < n;
    if (generation !== state.generation) {
      // a load, Perturb or Reset replaced the meshes and said so: its words stay
    } else if (stopped) {
      setStatus(`Stopped after ${done} of ${n} passes (the pass in progress was undone).`);
    } else if (n === 1) {
      setStatus(`One pass done on both sides in ${Math.round(total)} ms.`);
    } else {
      setStatus(`${n} passes done on both sides in ${(total / 1000).toFixed(1)} s.`);
    }
    const record = { n, done, stopped, total_ms: total, charts_ms, passes, memory_bytes: engine.memory };
    if (n === 1 && passes.length === 1) metrics.lastStep = { ...passes[0], charts_ms, all_ms: total };
    metrics.run = record;
    clearError();
  } catch (e) {
    if (generation === state.generation) report(e);
  } finally {
    setRunning(false);
    state.cancel = false;
  }
}

/** Refuses to start while a control it needs is not valid, saying which and why. */
function refuseInvalid(ids) {
  const id = ids.find((i) => state.invalid.has(i) && !$(i).disabled);
  if (!id) return false;
  showError(`${state.invalid.get(id)} Correct it first.`);
  $('message').dataset.control = id;
  return true;
}

function step() {
  if (!state.running && refuseInvalid(['maxiter'])) return;
  return smooth(1);
}

function run() {
  if (state.running) {
    requestStop();
    return;
  }
  if (refuseInvalid(['passes', 'maxiter'])) return;
  return smooth(Number($('passes').value));
}

function reset() {
  const stopped = endRun();
  return serial(async () => {
    await engine.call('reset');
    await redrawAll();
    clearError();
    const what = state.perturbed ? 'the mesh as loaded and perturbed' : 'the mesh as loaded';
    setStatus(`Both sides reset to ${what}.${stopped}`);
  }).catch(report);
}

/** "1 mean edge length", "0.5 mean edge lengths". */
function edgeLengths(amount) {
  return `${amount} mean edge length${amount === 1 ? '' : 's'}`;
}

function perturbWith(amount, seed, { keepHash = false } = {}) {
  const stopped = endRun();
  return serial(async () => {
    await engine.call('perturb', amount, seed);
    state.perturbed = { amount, seed };
    await redrawAll();
    clearError();
    setStatus(`Perturbed the mesh as loaded by ${edgeLengths(amount)} (seed ${seed}); both sides start again from it.${stopped}`);
    if (!keepHash) await writePermalink();
  }).catch(report);
}

function perturb() {
  if (refuseInvalid(['amount', 'seed'])) return;
  return perturbWith(Number($('amount').value), $('seed').value.trim());
}

// ---- picking and dragging ------------------------------------------------------------
/** The pointer in CSS pixels of the last frame drawn (what the engine's view maps). */
function toFrame(canvas, ev) {
  const r = canvas.getBoundingClientRect();
  const { w, h, dpr } = state.frame;
  return {
    x: ((ev.clientX - r.left) / r.width) * (w / dpr),
    y: ((ev.clientY - r.top) / r.height) * (h / dpr),
  };
}

/** Chooses the node whose star is highlighted and whose level sets are drawn. */
function selectNode(node, { keepHash = false } = {}) {
  return serial(async () => {
    try {
      await engine.call('select', node);
    } catch (e) {
      $('node').value = state.node === null ? '' : String(state.node);
      throw e;
    }
    state.node = node;
    $('node').value = node === null ? '' : String(node);
    clearError();
    showPickNote(null);
    await redrawMeshes();
    await redrawNode();
    if (!keepHash) await writePermalink();
  }).catch(report);
}

/** Says why a press chose no node (or clears that). */
function showPickNote(text) {
  $('pick-note').hidden = !text;
  $('pick-note').textContent = text || '';
}

/** How far from a node a press still takes it, CSS pixels: a finger is wider than a mouse pointer. */
function pickRadius(ev) {
  return ev.pointerType === 'touch' || ev.pointerType === 'pen' ? 24 : 14;
}

function attachPointer(canvas) {
  // One gesture per press. The pick is asynchronous (the engine is in a worker), so the
  // button may be released, or the pointer moved, before it answers: the gesture keeps
  // what happened and finishes when both the pick and the release are in.
  let gesture = null;
  const finish = (g) => {
    if (g.node === null && g.moved) pumpPan(g);
    if (g.node === null || g.node === undefined) return;
    if (g.moved) pumpDrag(g, true);
    else selectNode(g.node);
  };
  const zoom = zoomer((at, f) => engine.call('zoomMeshes', at.x, at.y, f), redrawMeshes);
  const touches = attachZoom(canvas, () => toFrame.bind(null, canvas), zoom, () => {
    if (gesture) gesture.cancelled = true; // a second finger: the press becomes a pinch
    gesture = null;
  });
  canvas.addEventListener('pointerdown', (ev) => {
    if (state.running || ev.button !== 0 || !state.frame.w || touches.size > 1) return;
    if (state.surface) {
      gesture = { orbit: true, start: { x: ev.clientX, y: ev.clientY }, last: { x: ev.clientX, y: ev.clientY }, moved: false };
      canvas.setPointerCapture(ev.pointerId);
      return;
    }
    const p = toFrame(canvas, ev);
    const g = { node: undefined, start: p, moved: false, up: false, busy: false, latest: null, final: false };
    gesture = g;
    canvas.setPointerCapture(ev.pointerId);
    serial(() => engine.call('pick', canvas.dataset.side, p.x, p.y, pickRadius(ev)))
      .then((pick) => {
        if (g.cancelled) return;
        g.node = pick.node === undefined ? null : pick.node;
        if (g.node === null && !g.moved) showPickNote(pick.message);
        if (g.up) finish(g);
        else if (g.moved && g.node !== null) pumpDrag(g);
        else if (g.moved) pumpPan(g);
      })
      .catch(report);
  });
  canvas.addEventListener('pointermove', (ev) => {
    const g = gesture;
    if (!g) {
      if (ev.pointerType === 'mouse' && !state.surface) hover(canvas, ev);
      return;
    }
    if (g.orbit) {
      // CSS pixels of the drag, as the camera takes them
      if (!g.moved && Math.hypot(ev.clientX - g.start.x, ev.clientY - g.start.y) < 3) return;
      g.moved = true;
      orbitBy(ev.clientX - g.last.x, ev.clientY - g.last.y);
      g.last = { x: ev.clientX, y: ev.clientY };
      return;
    }
    const p = toFrame(canvas, ev);
    if (!g.moved && Math.hypot(p.x - g.start.x, p.y - g.start.y) < 4) return;
    g.moved = true;
    g.latest = p;
    if (g.node === null) pumpPan(g);
    else if (g.node !== undefined) pumpDrag(g);
  });
  const end = (ev) => {
    const g = gesture;
    if (!g) return;
    gesture = null;
    g.up = true;
    if (canvas.hasPointerCapture(ev.pointerId)) canvas.releasePointerCapture(ev.pointerId);
    if (g.orbit) {
      if (!g.moved && ev.type === 'pointerup') sayNode(canvas, ev);
      return;
    }
    if (g.moved) g.latest = toFrame(canvas, ev);
    if (g.node !== undefined) finish(g);
  };
  canvas.addEventListener('keydown', (ev) => {
    const step = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[ev.key];
    if (!step || ev.ctrlKey || ev.metaKey || ev.altKey || state.surface) return;
    ev.preventDefault(); // the page does not scroll under a moving node
    if (state.node === null || state.running) {
      showPickNote(state.node === null ? 'Choose a free node first (click it): the arrow keys move the chosen node.' : null);
      return;
    }
    const k = ev.shiftKey ? 10 : 1;
    const node = state.node;
    serial(async () => {
      await engine.call('nudge', canvas.dataset.side, step[0] * k, step[1] * k);
      await redrawMeshes();
      await redrawNode();
      setStatus(`Node ${node} moved ${k} px ${ev.key.replace('Arrow', '').toLowerCase()} on both sides (Ctrl+Z takes it back).`);
    }).catch(report);
  });
  canvas.addEventListener('pointerleave', () => {
    canvas.parentElement.querySelector('.hover-label').hidden = true;
  });
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
}

/** Turns both surface views by a drag of `(dx, dy)` CSS pixels; turns that arrive while
 * the engine draws are added up and sent as one. */
const orbitPump = { dx: 0, dy: 0, busy: false };
function orbitBy(dx, dy) {
  orbitPump.dx += dx;
  orbitPump.dy += dy;
  if (orbitPump.busy || (orbitPump.dx === 0 && orbitPump.dy === 0)) return;
  const [x, y] = [orbitPump.dx, orbitPump.dy];
  orbitPump.dx = 0;
  orbitPump.dy = 0;
  orbitPump.busy = true;
  serial(async () => {
    await engine.call('orbit', x, y);
    await redrawMeshes();
  })
    .catch(report)
    .finally(() => {
      orbitPump.busy = false;
      orbitBy(0, 0);
    });
}

/** A click on a surface view says which node is there (the near side of the surface). */
function sayNode(canvas, ev) {
  const p = toFrame(canvas, ev);
  serial(() => engine.call('pickSurface', canvas.dataset.side, p.x, p.y, pickRadius(ev)))
    .then((node) => showPickNote(node === null ? 'No node there: drag to turn the surface, wheel to zoom.' : `Node ${node} of the surface.`))
    .catch(report);
}

/**
 * Zooms by the mouse wheel, by a pinch of two fingers, and fits again on a double-click,
 * on `canvas` whose pointer positions `point()(ev)` gives in the engine's CSS pixels.
 * `onPinch` is told when a second finger lands. Returns the map of pointers down.
 */
function attachZoom(canvas, point, zoom, onPinch = () => {}) {
  const down = new Map();
  let pinch = 0;
  const spread = () => {
    const [a, b] = [...down.values()];
    return { d: Math.hypot(a.x - b.x, a.y - b.y), mid: { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 } };
  };
  canvas.addEventListener('wheel', (ev) => {
    if (state.running) return;
    ev.preventDefault();
    zoom(point()(ev), Math.exp(-ev.deltaY * (ev.deltaMode === 1 ? 0.05 : 0.0015)));
  }, { passive: false });
  canvas.addEventListener('pointerdown', (ev) => {
    down.set(ev.pointerId, point()(ev));
    if (down.size === 2) {
      onPinch();
      pinch = spread().d;
    }
  });
  canvas.addEventListener('pointermove', (ev) => {
    if (!down.has(ev.pointerId)) return;
    down.set(ev.pointerId, point()(ev));
    if (down.size !== 2 || !pinch || state.running) return;
    const { d, mid } = spread();
    if (d > 0 && Math.abs(d / pinch - 1) > 0.02) {
      zoom(mid, d / pinch);
      pinch = d;
    }
  });
  const up = (ev) => {
    down.delete(ev.pointerId);
    if (down.size < 2) pinch = 0;
  };
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('pointercancel', up);
  canvas.addEventListener('dblclick', () => {
    if (state.running) return;
    serial(async () => {
      await engine.call('resetZoom');
      await redrawMeshes();
      await redrawNode();
    }).catch(report);
  });
  return down;
}

/** A zoom that asks the engine once at a time: factors that arrive meanwhile multiply. */
function zoomer(call, redraw) {
  const acc = { factor: 1, at: null, busy: false };
  const go = (at, factor) => {
    acc.factor *= factor;
    acc.at = at;
    if (acc.busy) return;
    const f = acc.factor;
    acc.factor = 1;
    acc.busy = true;
    serial(async () => {
      await call(at, f);
      await redraw();
    })
      .catch(report)
      .finally(() => {
        acc.busy = false;
        if (acc.factor !== 1) go(acc.at, 1);
      });
  };
  return go;
}

/** Moves a picture by the pointer's way since the last move sent (`call(dx, dy)`);
 * moves that arrive meanwhile are coalesced. */
function panner(call, redraw) {
  const go = (g) => {
    if (g.panBusy || !g.latest || g.latest === g.panFrom) return;
    const from = g.panFrom || g.start;
    const to = g.latest;
    g.panFrom = to;
    g.panBusy = true;
    showPickNote(null);
    serial(async () => {
      await call(to.x - from.x, to.y - from.y);
      await redraw();
    })
      .catch(report)
      .finally(() => {
        g.panBusy = false;
        go(g);
      });
  };
  return go;
}
const pumpPan = panner((dx, dy) => engine.call('panMeshes', dx, dy), redrawMeshes);

/** Zoom and pan on a level-set canvas (`panel` old or new); both level sets follow. */
function attachLevelZoom(canvas, panel) {
  const point = () => (ev) => {
    const r = canvas.getBoundingClientRect();
    const { w, h, dpr } = state.level || { w: r.width, h: r.height, dpr: 1 };
    return { x: ((ev.clientX - r.left) / r.width) * (w / dpr), y: ((ev.clientY - r.top) / r.height) * (h / dpr) };
  };
  let g = null;
  const ready = () => state.node !== null && state.level && !state.running;
  const zoom = zoomer((at, f) => engine.call('zoomLevelSets', panel, at.x, at.y, f), redrawNode);
  const touches = attachZoom(canvas, point, (at, f) => ready() && zoom(at, f), () => {
    g = null;
  });
  const pan = panner((dx, dy) => engine.call('panLevelSets', panel, dx, dy), redrawNode);
  canvas.addEventListener('pointerdown', (ev) => {
    if (!ready() || ev.button !== 0 || touches.size > 1) return;
    canvas.setPointerCapture(ev.pointerId);
    g = { start: point()(ev), latest: null };
  });
  canvas.addEventListener('pointermove', (ev) => {
    if (!g) return;
    g.latest = point()(ev);
    pan(g);
  });
  const end = () => {
    g = null;
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
}

/** Shows the number of the node under the mouse (one question to the engine at a time;
 * none while it is busy). */
let hovering = false;
function hover(canvas, ev) {
  const label = canvas.parentElement.querySelector('.hover-label');
  if (hovering || queued > 0 || state.running || !state.frame.w) return;
  hovering = true;
  const p = toFrame(canvas, ev);
  const r = canvas.getBoundingClientRect();
  const at = { x: ev.clientX - r.left, y: ev.clientY - r.top };
  engine
    .call('pick', canvas.dataset.side, p.x, p.y, pickRadius(ev))
    .then((pick) => {
      if (pick.nearest === null || pick.nearest === undefined) {
        label.hidden = true;
        return;
      }
      label.textContent = pick.node !== null && pick.node !== undefined ? `node ${pick.nearest}` : `node ${pick.nearest} (${pick.message.includes('mid-side') ? 'mid-side' : 'fixed'})`;
      label.style.left = `${Math.round(at.x + 12)}px`;
      label.style.top = `${Math.round(at.y - 8)}px`;
      label.hidden = false;
    })
    .catch(() => {})
    .finally(() => {
      hovering = false;
    });
}

/** Sends the latest drag position; positions that arrive meanwhile are coalesced. */
function pumpDrag(d, final = false) {
  if (d.busy) {
    d.final = d.final || final;
    return;
  }
  const p = d.latest;
  if (!p) return;
  d.latest = null;
  d.busy = true;
  serial(async () => {
    if (!d.remembered) {
      d.remembered = true; // undo takes the whole drag back
      await engine.call('rememberBeforeMove', d.node);
    }
    await engine.call('drag', d.node, p.x, p.y);
    if (final || d.final) {
      await engine.call('select', d.node);
      state.node = d.node;
      $('node').value = String(d.node);
    }
    await redrawMeshes();
    if (final || d.final) {
      await redrawCharts();
      await redrawNode();
      await writePermalink();
    }
  })
    .catch(report)
    .finally(() => {
      d.busy = false;
      if (d.latest) pumpDrag(d, d.final);
    });
}

// ---- undo, one node, the figure --------------------------------------------------------
/** The Undo button says what it would take back, or why it cannot. */
async function refreshUndo() {
  if (state.surface) return; // disabled, saying why (showSurfaceMode)
  const u = await engine.call('undoState');
  const b = $('undo');
  b.disabled = u.depth === 0 || state.running;
  b.textContent = u.depth ? `Undo move of node ${u.next}` : 'Undo move';
  b.title = u.depth
    ? `Put node ${u.next} back where it was before its last move, on both sides (Ctrl+Z); ${u.depth} move${u.depth === 1 ? '' : 's'} can be undone.`
    : 'Nothing to undo: a move (a drag or Smooth this node) can be taken back until the next pass, Reset or Perturb.';
}

function undo() {
  if (state.running || state.surface) return;
  return serial(async () => {
    const u = await engine.call('undo');
    if (u.node === undefined) {
      setStatus('Nothing to undo.');
      return;
    }
    await redrawMeshes();
    await redrawCharts();
    await redrawNode();
    setStatus(`Node ${u.node} is back where it was before its last move, on both sides.`);
  }).catch(report);
}

/** One solver call on the chosen node on each side; the node view shows that call. */
function smoothThisNode() {
  if (state.running || state.node === null) return;
  return serial(async () => {
    const node = state.node;
    const lv = canvasPixels($('level-old'));
    const ch = canvasPixels($('solve-chart'));
    const r = await engine.call('smoothNode', lv.w, lv.h, ch.w, ch.h, lv.dpr);
    state.level = lv;
    paint($('level-old'), r.level_old, lv.w, lv.h);
    paint($('level-new'), r.level_new, lv.w, lv.h);
    paint($('solve-chart'), r.chart, ch.w, ch.h);
    $('node-hint').textContent = `One solver call on each side moved node ${node} to its optimum; the pictures show that call. ${r.summary}`;
    await redrawMeshes();
    await redrawCharts();
    setStatus(`Node ${node} smoothed by one solver call on each side (Undo takes it back).`);
  }).catch(report);
}

/** The figure for slides, drawn by the core at the size and pixel ratio chosen. */
function saveFigure() {
  return serial(async () => {
    const [w, h] = ['figure-w', 'figure-h'].map((id) => $(id).value.trim());
    if (!/^\d+$/.test(w) || !/^\d+$/.test(h) || Number(w) < 1 || Number(h) < 1) {
      throw new Error(`Figure: give its width and height in whole pixels from 1 (got ${w || 'nothing'} × ${h || 'nothing'}).`);
    }
    const dpr = Number($('figure-dpr').value);
    const f = await engine.call('figure', Number(w), Number(h), dpr);
    const c = document.createElement('canvas');
    paint(c, f.pixels, f.w, f.h);
    const blob = await new Promise((resolve) => c.toBlob(resolve, 'image/png'));
    download(blob, `${baseName()}_figure_${w}x${h}@${dpr}x.png`);
    $('figure-note').textContent = `Saved a figure of ${f.w} × ${f.h} pixels (${w} × ${h} at ${dpr}×).`;
    clearError();
  }).catch(report);
}

// ---- export --------------------------------------------------------------------------
function download(blob, name) {
  const a = document.createElement('a');
  a.href = URL.createObjectURL(blob);
  a.download = name;
  document.body.append(a);
  a.click();
  a.remove();
  setTimeout(() => URL.revokeObjectURL(a.href), 10000);
}
function baseName() {
  const s = state.lastGood;
  if (!s) return 'mesh';
  return String(s.name || 'mesh').replace(/\.[^.]*$/, '').replace(/[^A-Za-z0-9_-]+/g, '_').slice(0, 60) || 'mesh';
}
function exportMesh(side, format) {
  return serial(async () => {
    const text = await engine.call('exportMesh', side, format);
    download(new Blob([text], { type: 'text/plain' }), `${baseName()}_${side}.${format}`);
    setStatus(`Saved the ${side} side as .${format}.`);
  }).catch(report);
}
function exportPng(canvasId) {
  $(canvasId).toBlob((blob) => {
    if (blob) download(blob, `${baseName()}_${canvasId}.png`);
  }, 'image/png');
}

// ---- start ---------------------------------------------------------------------------
async function fillGallery() {
  const list = await engine.call('samples');
  defaultSample = list[0].name;
  const sel = $('sample');
  const gen = document.createElement('optgroup');
  gen.label = 'Generated in the browser';
  for (const s of list) {
    const o = document.createElement('option');
    o.value = `sample:${s.name}`;
    o.textContent = s.title;
    if (!s.linkable) UNLINKABLE.add(s.name);
    gen.append(o);
  }
  const files = document.createElement('optgroup');
  files.label = 'Meshed by Gmsh (files)';
  for (const [f, title] of GMSH_SAMPLES) {
    const o = document.createElement('option');
    o.value = `gmsh:${f}`;
    o.textContent = title;
    files.append(o);
  }
  const none = document.createElement('option');
  none.value = '';
  none.textContent = '(your file)';
  none.disabled = true;
  sel.append(gen, files, none);
}

function wire() {
  $('sample').addEventListener('change', () => {
    const v = $('sample').value;
    const i = v.indexOf(':');
    if (i < 0) return;
    const kind = v.slice(0, i);
    const name = v.slice(i + 1);
    const label = $('sample').selectedOptions[0].textContent;
    load({ kind, name }, label);
  });
  $('file').addEventListener('change', async () => {
    const files = $('file').files;
    await readFiles(files);
    $('file').value = '';
  });
  document.addEventListener('dragover', (ev) => {
    ev.preventDefault();
    document.body.classList.add('dropping');
  });
  document.addEventListener('dragleave', (ev) => {
    if (ev.target === document.documentElement || ev.clientX <= 0) document.body.classList.remove('dropping');
  });
  document.addEventListener('drop', (ev) => {
    ev.preventDefault();
    document.body.classList.remove('dropping');
    if (ev.dataTransfer && ev.dataTransfer.files.length) readFiles(ev.dataTransfer.files);
  });
  $('step').addEventListener('click', step);
  $('run').addEventListener('click', run);
  $('reset').addEventListener('click', reset);
  $('perturb').addEventListener('click', perturb);
  $('amount').addEventListener('input', () => {
    $('amount-out').textContent = $('amount').value;
  });
  for (const id of SETTINGS) {
    if (!CHECKED[id] && !id.includes('-')) $(id).addEventListener('change', updatePermalink);
  }
  for (const [obj, pen] of COMPARE) {
    $(obj).addEventListener('change', changeCompare);
    $(pen).addEventListener('change', changeCompare);
  }
  $('hist-log').addEventListener('change', () => serial(redrawCharts).catch(report));
  // the cut plane of tetrahedra: both views follow as the slider moves
  const cut = () => {
    const at = Number($('cut-at').value);
    $('cut-at-out').textContent = at.toFixed(2);
    if (!state.volume) return;
    serial(async () => {
      await engine.call('setCut', Number($('cut-axis').value), at);
      await redrawMeshes();
    }).catch(report);
  };
  $('cut-at').addEventListener('input', cut);
  $('cut-axis').addEventListener('change', cut);
  $('node').addEventListener('change', () => {
    const v = $('node').value.trim();
    if (v !== '' && !/^\d+$/.test(v)) {
      showError(`Node: enter a node number (a whole number from 0), not '${v}'.`);
      return;
    }
    selectNode(v === '' ? null : Number(v));
  });
  $('copy-link').addEventListener('click', () => copyLink().catch(report));
  $('tour-prev').addEventListener('click', () => goFigure($('tour-prev').dataset.figure));
  $('tour-next').addEventListener('click', () => goFigure($('tour-next').dataset.figure));
  $('tour-menu').addEventListener('change', () => goFigure($('tour-menu').value));
  $('tour-close').addEventListener('click', closeTour);
  $('strategy').addEventListener('change', showStrategyReasons);
  for (const id of Object.keys(CHECKED)) {
    $(id).addEventListener('input', () => checkControl(id).then(() => updatePermalink()).catch(report));
  }
  window.addEventListener('hashchange', () => onAddressChange().catch(report));
  window.addEventListener('popstate', () => onAddressChange().catch(report));
  attachPointer($('mesh-old'));
  attachPointer($('mesh-new'));
  attachLevelZoom($('level-old'), 'old');
  attachLevelZoom($('level-new'), 'new');
  $('undo').addEventListener('click', undo);
  document.addEventListener('keydown', (ev) => {
    const typing = ev.target instanceof HTMLElement && ev.target.matches('input, select, textarea');
    if ((ev.ctrlKey || ev.metaKey) && !ev.shiftKey && !ev.altKey && ev.key.toLowerCase() === 'z' && !typing) {
      ev.preventDefault();
      undo();
    }
  });
  $('smooth-node').addEventListener('click', smoothThisNode);
  $('save-figure').addEventListener('click', saveFigure);
  for (const b of document.querySelectorAll('button[data-export]')) {
    b.addEventListener('click', () => exportMesh(b.dataset.side, b.dataset.export));
  }
  for (const b of document.querySelectorAll('button[data-png]')) {
    b.addEventListener('click', () => exportPng(b.dataset.png));
  }
  let resizeTimer = 0;
  window.addEventListener('resize', () => {
    clearTimeout(resizeTimer);
    resizeTimer = setTimeout(() => {
      if (EMBED) for (const id of ['mesh-old', 'mesh-new']) $(id).style.width = '';
      serial(redrawAll).catch(report);
      serial(drawFigurePicture).catch(report);
    }, 150);
  });
}

function setupEmbed() {
  if (!EMBED) return;
  document.body.classList.add('embed');
  if (VIEW) document.body.classList.add('view', `view-${VIEW_NAME}`);
  const a = document.createElement('a');
  a.id = 'open-full';
  a.target = '_blank';
  a.rel = 'noopener';
  a.textContent = 'Open the full playground';
  $('message').before(a);
}

async function main() {
  document.body.dataset.busy = '1';
  setupEmbed();
  wire();
  try {
    // the first answer waits for the worker to start and the wasm module to be compiled
    const { result: controls, timing } = await engine.timed('controls');
    metrics.startup = { engine_ready_ms: timing.worker.start - performance.timeOrigin, first_mesh_ms: 0 };
    buildControls(controls);
    await fillGallery();
    await fillTourMenu();
    metrics.startup.menus_ms = now();
  } catch (e) {
    report(e);
    document.body.dataset.busy = '0';
    return;
  }
  state.lastHash = location.hash;
  const fig = FIGURE_HASH.exec(location.hash);
  if (fig) {
    await openFigure(fig[1]);
    markAddressHandled();
    document.body.dataset.ready = '1';
    return;
  }
  await openHash(await applyHash());
  if (VIEW_NAME !== null && !VIEW) {
    showError(`view=${VIEW_NAME}: an embed shows one of the views ${Object.keys(VIEWS).join(', ')}; this is the compact page.`);
  }
  await openView();
  markAddressHandled();
  document.body.dataset.ready = '1';
}

// A hook for the browser tests (and the curious): make the engine panic on purpose.
// The page's own measurements: the last load and the last Step (where the time of "one
// pass + redraw" went), the last run (per pass), and the wasm memory.
window.smoothlab = {
  panicForTest: () => serial(() => engine.call('panicForTest')).catch(report),
  metrics,
  pickRadius,
  memory: () => ({ bytes: engine.memory, peak_bytes: engine.peakMemory }),
  // whether passes are split between two workers now (see SPLIT_MIN_NODES)
  twoWorkers: () => readyHelper() !== null,
  figure: () => state.figure,
};

main();

// The address: the permalink written and read by the core's encoder (crates/smoothlab-page/src/lab/permalink.rs),
// what a hash opens, the embedded views, Back and Forward.
import { $, COMPARE, EMBED, FIGURE_HASH, SETTINGS, engine, gallery, report, serial, setStatus, showError, state, view } from './state.js';
import { CHECKED, changeBoundary, changeCompare, invalidMessage, readChoice, readSettings, sameBoundary, showBoundaryReasons, showPenaltyReasons, showStrategyReasons } from './controls.js';
import { openFigure } from './tour.js';
import { labelOf, load, selectValueOf } from './loading.js';
import { perturbWith, smooth } from './run.js';
import { selectNode } from './pointer.js';
import { redrawMeshes } from './draw.js';

/** The permalink sample name of what is loaded, or null (a user's file has none). Every
 * sample of the gallery has one (crates/smoothlab-page/src/lab/permalink.rs, SAMPLES), surfaces and tetrahedra
 * too; a Gmsh file the name the core gives it in the control sheet. */
export function sourceSample() {
  const s = state.lastGood;
  if (!s) return null;
  if (s.kind === 'sample') return s.name;
  if (s.kind === 'gmsh') return state.controls.gmsh_samples.find((g) => g.file === s.name)?.name ?? null;
  return null;
}
/** The hash of the loaded sample and the controls, written by the Rust encoder. */
export async function permalinkHash() {
  return engine.call('encodePermalink', {
    sample: sourceSample(),
    seed: state.perturbed ? BigInt(state.perturbed.seed) : BigInt($('seed').value.trim()),
    amount: state.perturbed ? state.perturbed.amount : Number($('amount').value),
    perturbed: Boolean(state.perturbed),
    node: state.node,
    settings: readSettings(),
    passes: Number($('passes').value),
    // a mesh in 3D: the camera, and the cut of tetrahedra
    camera: state.surface ? await engine.call('camera') : null,
    cut: state.volume ? readCut() : null,
  });
}
/** The cut plane the controls hold: `{ axis, at }`. */
export function readCut() {
  return { axis: Number($('cut-axis').value), at: Number($('cut-at').value) };
}
/** Keeps the URL and the permalink link current; a setting the link cannot carry is said
 * in the message box (the link then keeps its last good value). */
export let permalinkSeq = 0;
export async function writePermalink() {
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
  // the hash alone: a page without a path of its own (a blob, in a notebook) takes it too
  history.replaceState(null, '', hash);
  $('permalink').href = `${location.pathname}${hash}`;
  const s = state.lastGood;
  let note = '';
  if (s && (s.kind === 'file' || s.kind === 'triangle')) {
    note = `Your own file (${s.name}) cannot travel in a link: the link opens these settings on the default sample.`;
  }
  $('permalink').title = note;
  $('permalink-note').textContent = note;
  if (EMBED) $('open-full').href = `${location.pathname}${hash}`;
}
/** The page's address with the current hash, for the Copy link button. */
export async function copyLink() {
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
export function updatePermalink() {
  return serial(writePermalink).catch(report);
}
/** Reads the URL hash through the Rust decoder and applies it to the controls (a value a
 * control does not offer is ignored). Returns the source to load and, when the hash could
 * not be read, the decoder's message (the defaults are then kept). */
export async function applyHash(hash = location.hash) {
  const fallback = { kind: 'sample', name: gallery.defaultSample };
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
    target: c.target,
    boundary: c.boundary,
    passes: p.passes,
    maxiter: c.max_iter,
    amount: p.amount,
    seed: p.seed,
    'objective-a': c.compare[0].objective,
    'penalty-a': c.compare[0].penalty,
    'objective-b': c.compare[1].objective,
    'penalty-b': c.compare[1].penalty,
  };
  // the target's menu is enabled again, so that the hash's target is what it shows (the
  // strategy's reasons, below, disable it where the strategy takes no target)
  $('target').disabled = false;
  // so is the boundary's (the mesh's reasons, below and at its load, disable it again)
  $('boundary').disabled = false;
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
  showBoundaryReasons(state.slideRefused);
  const extra = { perturbed: p.perturbed ? { amount: p.amount, seed: String(p.seed) } : null, node: p.node, camera: p.camera, cut: p.cut };
  if (p.sample === null) return { src: fallback, ...extra };
  const gmsh = state.controls.gmsh_samples.find((g) => g.name === p.sample);
  if (gmsh) return { src: { kind: 'gmsh', name: gmsh.file }, ...extra };
  if ([...$('sample').options].some((o) => o.value === `sample:${p.sample}`)) return { src: { kind: 'sample', name: p.sample }, ...extra };
  return { src: fallback, ...extra };
}

/** Opens what a hash names: its sample (unless it is already loaded and unperturbed),
 * its perturbation, a 3D view's camera and cut, and its node. The controls were set by
 * applyHash. */
export async function openHash({ src, error, perturbed, node, camera, cut }, { keepLink = false } = {}) {
  const same = state.lastGood && selectValueOf(state.lastGood) === selectValueOf(src) && selectValueOf(src) !== '';
  if (!same || state.perturbed || perturbed) await load(src, labelOf(src), { keepHash: true });
  else if (!sameCompare()) await changeCompare();
  else if (!sameBoundary()) await changeBoundary({ keepHash: true });
  if (perturbed) await perturbWith(perturbed.amount, perturbed.seed, { keepHash: true });
  if (state.surface) await openView3d(camera, cut);
  if (node !== null && node !== undefined) await selectNode(node, { keepHash: true });
  else if (state.node !== null) await selectNode(null, { keepHash: true });
  if (error) showError(`This link's settings could not be read, so the defaults are shown: ${error.replace(/^permalink: /, '')}`);
  if (!keepLink) await serial(writePermalink).catch(report);
}

/** A 3D view as a link names it: its camera (or the camera as it starts) and, for
 * tetrahedra, its cut (or half way up z). */
export function openView3d(camera, cut) {
  return serial(async () => {
    if (camera) await engine.call('setCamera', camera.yaw, camera.pitch, camera.zoom);
    else await engine.call('resetZoom');
    if (state.volume) {
      const c = cut ?? { axis: 2, at: 0.5 };
      $('cut-axis').value = String(c.axis);
      $('cut-at').value = String(c.at);
      const at = Number($('cut-at').value); // as the slider holds it (its steps)
      $('cut-at-out').textContent = at.toFixed(2);
      await engine.call('setCut', c.axis, at);
    }
    await redrawMeshes();
  }).catch(report);
}

/** An embedded view shows what `smoothlab render` shows for it: the level sets of the
 * hash's node (else of the free node with the worst star), the other views after the
 * hash's passes. */
export async function openView() {
  if (!view.spec) return;
  if (view.name === 'levelset' && state.node === null) {
    const worst = await serial(() => engine.call('worstNode'));
    if (worst !== null) await selectNode(worst, { keepHash: true });
  }
  if (view.spec.passes) await smooth(Number($('passes').value));
}

/** Whether the engine smooths each side with what the menus say. */
export function sameCompare() {
  return JSON.stringify(state.compare) === JSON.stringify(COMPARE.map((_, i) => readChoice(i)));
}

/** The user edited the hash or went Back or Forward: show what the address now names. */
export async function onAddressChange() {
  try {
    await openAddress();
  } finally {
    markAddressHandled();
  }
}
/** Says on the body which address the page has opened (`data-hash`), for tests and tools:
 * a link that changes only the hash reloads nothing, so its handling starts after the
 * navigation has ended. */
export function markAddressHandled() {
  document.body.dataset.hash = location.hash;
}
export async function openAddress() {
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

// The controls: the settings they make, their ranges and defaults from the core
// (crates/smoothlab-page/src/lab/controls.rs, written once), the compare menus, what a strategy does not use,
// typed values checked.
import { $, COMPARE, clearError, engine, report, serial, setStatus, state } from './state.js';
import { writePermalink } from './permalink.js';
import { endRun } from './loading.js';
import { redrawAll, redrawNode } from './draw.js';

export function readSettings() {
  return {
    strategy: $('strategy').value,
    threshold_deg: Number($('threshold').value),
    order: $('order').value,
    max_iter: Number($('maxiter').value),
    target: $('target').value,
    boundary: $('boundary').value,
    compare: COMPARE.map((_, i) => readChoice(i)),
  };
}
/** What side `i` (0 = A, 1 = B) smooths with; a penalty only for `new` (else the default design). */
export function readChoice(i) {
  const [obj, pen] = COMPARE[i];
  const objective = $(obj).value;
  return { objective, penalty: $(pen).disabled ? state.controls.penalties[0].name : $(pen).value };
}

// ---- controls: built from the core's ranges, checked where they are edited ------------
/** The permalink key by which the core checks each typed control. */
export const CHECKED = { passes: 'passes', maxiter: 'maxiter', seed: 'seed', amount: 'tangle' };

/** Sets the inputs' ranges and defaults from the core (the one place they are written). */
export function buildControls(c) {
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
  fillMenu($('target'), c.targets.map((t) => [t.name, t.label, t.words]), c.settings.target);
  fillMenu($('boundary'), c.boundaries.map((b) => [b.name, b.label, b.words]), c.settings.boundary);
  showBoundaryReasons(state.slideRefused);
  showStrategyReasons();
  // compare: every objective and penalty design the core offers, by its names
  for (const [i, [obj, pen]] of COMPARE.entries()) {
    const panel = c.panels[i];
    fillMenu($(obj), c.objectives.map((o) => [o.name, `${o.name}: ${o.words}`]), panel.objective);
    fillMenu($(pen), c.penalties.map((p) => [p.name, `${p.name}: ${p.words}`]), panel.penalty);
    document.documentElement.style.setProperty(`--side-${panel.side}-light`, `rgb(${panel.rgb.join(',')})`);
    document.documentElement.style.setProperty(`--side-${panel.side}-dark`, `rgb(${panel.rgb_dark.join(',')})`);
  }
  const ramp = c.quality_ramp.map((rgb, i) => `rgb(${rgb.join(',')}) ${((100 * i) / (c.quality_ramp.length - 1)).toFixed(1)}%`);
  document.documentElement.style.setProperty('--quality-ramp', `linear-gradient(to right, ${ramp.join(', ')})`);
  showPenaltyReasons();
}
/** Fills a menu with `[value, text, tooltip]` entries (the tooltip may be absent). */
export function fillMenu(select, entries, value) {
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
/** The Compare disclosure's summary: what each side runs, so it says so folded. */
function showCompareSummary() {
  const name = (i) => {
    const c = readChoice(i);
    return c.objective === 'new' ? `new (${c.penalty})` : c.objective;
  };
  $('compare-summary').textContent = `A ${name(0)}, B ${name(1)}`;
}

/** A penalty is a design of `new`: its menu is disabled, saying so, for another objective. */
export function showPenaltyReasons() {
  for (const [obj, pen] of COMPARE) {
    const other = $(obj).value !== 'new';
    $(pen).disabled = other;
    const why = other ? `Not used: only the new objective has a penalty (this side runs ${$(obj).value}).` : '';
    $(`${pen}-why`).textContent = why;
    $(pen).title = why;
  }
  showCompareSummary();
}
/** A side now runs something else: both sides start again from the mesh as loaded. */
export function changeCompare() {
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
export function showStrategyReasons() {
  const info = state.controls.strategies.find((s) => s.name === $('strategy').value);
  for (const [id, why] of [['threshold', info && info.threshold_unused], ['maxiter', info && info.max_iter_unused]]) {
    $(id).disabled = Boolean(why);
    $(`${id}-why`).textContent = why ? `Not used: ${why}.` : '';
    $(id).title = why ? `Not used: ${why}.` : $(id).dataset.help || '';
  }
  // a strategy that takes Laplacian steps measures against the ideal only: the menu shows
  // the ideal, disabled, and gets the user's choice back with a strategy that takes it
  const t = $('target');
  const refused = info && info.target_refused;
  const ideal = state.controls.targets[0].name;
  if (refused && !t.disabled) {
    t.dataset.chosen = t.value;
    t.value = ideal;
  } else if (!refused && t.disabled) {
    t.value = t.dataset.chosen || ideal;
  }
  t.disabled = Boolean(refused);
  $('target-why').textContent = refused ? `Only the ideal here: ${refused}.` : '';
  showTargetWords();
}

/** What the chosen target means, in a sentence beside its menu (the core's words). */
export function showTargetWords() {
  const t = state.controls.targets.find((x) => x.name === $('target').value);
  $('target-words').textContent = t ? t.words : '';
  $('target').title = $('target-why').textContent || (t ? t.words : '');
}

/** A new target: the engine measures against it from the next pass (the input is the
 * mesh as loaded or as last perturbed, whatever was smoothed since), and the chosen
 * node's level sets are drawn against it at once. */
export function changeTarget() {
  showTargetWords();
  return serial(async () => {
    await engine.call('settings', readSettings());
    await redrawNode();
    await writePermalink();
    const t = state.controls.targets.find((x) => x.name === $('target').value);
    setStatus(`Target: ${t.label.toLowerCase()}. ${t.words}`);
  }).catch(report);
}

/** Where the mesh's boundary cannot slide (`refused`, the core's reason: a quadratic
 * volume mesh), the boundary menu shows fixed, disabled, saying why, and gets the
 * user's choice back with a mesh whose boundary slides (as the target menu with a
 * strategy that takes no target). */
export function showBoundaryReasons(refused) {
  state.slideRefused = refused ?? null;
  const b = $('boundary');
  const fixed = state.controls.boundaries[0].name;
  if (refused && !b.disabled) {
    b.dataset.chosen = b.value;
    b.value = fixed;
  } else if (!refused && b.disabled) {
    b.value = b.dataset.chosen || fixed;
  }
  b.disabled = Boolean(refused);
  $('boundary-why').textContent = refused ? `Fixed here: ${refused}.` : '';
  showBoundaryWords();
}

/** What the chosen boundary rule does, in a sentence beside its menu (the core's words),
 * in the words of the mesh's kind. */
export function showBoundaryWords() {
  const r = state.controls.boundaries.find((x) => x.name === $('boundary').value);
  // a surface's boundary is its curves, a planar mesh's its edges, and the sentence says so
  const words = !r ? '' : state.volume ? r.words : state.surface ? r.surface_words : r.planar_words;
  $('boundary-words').textContent = words;
  $('boundary').title = $('boundary-why').textContent || words;
}

/** "96 nodes slide on the boundary, 36 along 12 feature curves; 8 corners stay": what a
 * side's boundary report (the command-line tool's) counts. */
export function boundaryCounts(b) {
  const held = b.held ? `, ${b.held} fixed by the file` : '';
  if (!state.surface) {
    // a planar mesh's boundary is one curve a loop: "56 nodes slide along the boundary; 4 corners stay"
    return `${b.curve_nodes} nodes slide along the boundary; ${b.corners} corner${b.corners === 1 ? '' : 's'} stay${b.corners === 1 ? 's' : ''}${held}`;
  }
  if (!state.volume) {
    // a surface's boundary is its curves: "36 nodes slide along 4 curves; 4 corners stay"
    return `${b.curve_nodes} nodes slide along ${b.curves} curve${b.curves === 1 ? '' : 's'}; ${b.corners} corner${b.corners === 1 ? '' : 's'} stay${b.corners === 1 ? 's' : ''}${held}`;
  }
  return `${b.surface_nodes} nodes slide on the boundary, ${b.curve_nodes} along ${b.curves} feature curve${b.curves === 1 ? '' : 's'}; ${b.corners} corner${b.corners === 1 ? '' : 's'} stay${b.corners === 1 ? 's' : ''}${held}`;
}

/** A new boundary rule: the engine takes it on the mesh as loaded (or as last perturbed),
 * whose boundary sliding nodes stay on, and both sides start again from that mesh. */
export function changeBoundary({ keepHash = false } = {}) {
  showBoundaryWords();
  const stopped = endRun();
  return serial(async () => {
    const settings = readSettings();
    await engine.call('settings', settings);
    state.boundary = settings.boundary;
    await redrawAll();
    clearError();
    const r = state.controls.boundaries.find((x) => x.name === settings.boundary);
    let counts = '';
    if (settings.boundary !== 'fixed') {
      const t = await engine.call('stats', 'b');
      if (t.boundary) counts = ` ${boundaryCounts(t.boundary)}.`;
      // a tangled planar mesh's boundary is held until a pass leaves a side valid
      else if (!state.surface) counts = ' The mesh is tangled: its boundary stays until a pass leaves a side valid, then slides there.';
    }
    setStatus(`Boundary: ${r.label.toLowerCase()}.${counts} Both sides start again from the mesh as loaded.${stopped}`);
    if (!keepHash) await writePermalink();
  }).catch(report);
}

/** Whether the engine's boundary rule is what the menu says. */
export function sameBoundary() {
  return state.boundary === $('boundary').value;
}

/** Checks one typed control with the core's rules; shows or clears its message. */
export async function checkControl(id) {
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
export function invalidMessage(ids) {
  for (const id of ids) if (state.invalid.has(id) && !$(id).disabled) return state.invalid.get(id);
  return null;
}

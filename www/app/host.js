// The bridge to a host that drives the page: a notebook's widget (python/smoothlab, whose
// module puts the one-file page in a frame with `data-host="widget"` on its <html>). They
// talk by messages `{ smoothlab: KIND, … }`: the page says `hello` once its controls are
// built; the host answers `open` (the mesh file it brings, if any, the settings it sets,
// the 3D view, and the passes of a saved state to run again); the page then sends `state`
// (its settings, both sides' meshes as arrays, their tables, the 3D view, and what went
// wrong, if anything) after every change of a mesh or a setting, and takes `settings` and
// `view` (a 3D view's camera and cut) from the host at any time. The page's own controls
// do the work: a setting is put in its control and the control's own change handler
// runs, a file is loaded by the page's loader, so the host sees the page's checks and
// messages.
import { $, engine, pageEvents, serial, state } from './state.js';
import { CHECKED, checkControl } from './controls.js';
import { load } from './loading.js';
import { smooth } from './run.js';
import { openView3d, readCut } from './permalink.js';

/** The host's names of the settings (the Python widget's traits) and the controls they set. */
export const SETTING_CONTROLS = {
  strategy: 'strategy',
  threshold: 'threshold',
  order: 'order',
  passes: 'passes',
  max_iter: 'maxiter',
  objective_a: 'objective-a',
  penalty_a: 'penalty-a',
  objective_b: 'objective-b',
  penalty_b: 'penalty-b',
};
const NUMERIC = new Set(['threshold', 'passes', 'max_iter']);

const host = { window: null, error: null, sent: { a: null, b: null }, timer: 0, replay: null, view: null };
const AXES = ['x', 'y', 'z'];

/** The 3D view as the host names it: `camera` [yaw, pitch, zoom] (degrees), `cut` [axis
 * ('x', 'y' or 'z'), fraction of the extent]; null for a planar mesh (or no cut). */
async function readView() {
  if (!state.surface) return { camera: null, cut: null };
  const c = await engine.call('camera');
  const cut = state.volume ? readCut() : null;
  return { camera: [c.yaw, c.pitch, c.zoom], cut: cut ? [AXES[cut.axis], cut.at] : null };
}

/** Sees the mesh in 3D by the host's camera and cut (`{ camera, cut }`, either null). */
async function applyView(v) {
  if (!state.surface || !v || (!v.camera && !v.cut)) return;
  const camera = v.camera ? { yaw: v.camera[0], pitch: v.camera[1], zoom: v.camera[2] ?? 1 } : await engine.call('camera');
  const cut = v.cut ? { axis: AXES.indexOf(v.cut[0]), at: v.cut[1] } : state.volume ? readCut() : null;
  await openView3d(camera, cut);
}

function post(message) {
  host.window.postMessage({ smoothlab: message.kind, ...message }, '*');
}

/** The settings as the controls hold them, by the host's names. */
function readSettings() {
  const out = {};
  for (const [name, id] of Object.entries(SETTING_CONTROLS)) {
    const v = $(id).value;
    out[name] = NUMERIC.has(name) ? Number(v) : v;
  }
  return out;
}

/** Puts the host's settings in the controls and runs their handlers; returns the first
 * refusal in words (a value a menu does not offer, a typed value out of its range). */
async function applySettings(settings) {
  const refusals = [];
  for (const [name, value] of Object.entries(settings || {})) {
    if (value === null || value === undefined) continue;
    const id = SETTING_CONTROLS[name];
    if (!id) {
      refusals.push(`no setting named '${name}': the settings are ${Object.keys(SETTING_CONTROLS).join(', ')}`);
      continue;
    }
    const el = $(id);
    const text = String(value);
    if (el.tagName === 'SELECT') {
      const offered = [...el.options].map((o) => o.value);
      if (!offered.includes(text)) {
        refusals.push(`${name}: '${text}' is not offered; choose one of ${offered.join(', ')}`);
        continue;
      }
      if (el.value === text) continue;
      el.value = text;
      el.dispatchEvent(new Event('change'));
    } else {
      if (el.value === text) continue;
      el.value = text;
      if (Object.hasOwn(CHECKED, id)) {
        await checkControl(id);
        if (state.invalid.has(id)) {
          refusals.push(`${name}: ${state.invalid.get(id)}`);
          continue;
        }
      }
      el.dispatchEvent(new Event('change'));
    }
  }
  return refusals.length ? refusals.join('; ') : null;
}

/** A hash of a typed array's bytes: a side is sent again only when its mesh changed. */
function digest(arrays) {
  let h = 2166136261;
  const mix = (view) => {
    const bytes = new Uint8Array(view.buffer, view.byteOffset, view.byteLength);
    for (let i = 0; i < bytes.length; i += 1) h = Math.imul(h ^ bytes[i], 16777619);
  };
  mix(arrays.points);
  mix(arrays.fixed);
  for (const c of arrays.cells) mix(c.nodes);
  return `${h >>> 0}:${arrays.points.length}:${arrays.cells.length}`;
}

/** Sends the page's state: the settings always, a side's mesh when it changed since sent. */
async function sendState() {
  const meshes = {};
  if (state.lastGood) {
    for (const side of ['a', 'b']) {
      const arrays = await engine.call('meshArrays', side);
      const d = digest(arrays);
      if (d !== host.sent[side]) {
        meshes[side] = arrays;
        host.sent[side] = d;
      }
    }
  }
  const stats = state.lastGood ? { a: await engine.call('stats', 'a'), b: await engine.call('stats', 'b') } : null;
  post({ kind: 'state', settings: readSettings(), meshes, stats, error: host.error, view: await readView() });
}

/** Sends the state once the page is idle (a run's passes are not each sent). */
function scheduleState() {
  if (!host.window) return;
  clearTimeout(host.timer);
  host.timer = setTimeout(() => {
    if (state.running) {
      scheduleState();
      return;
    }
    serial(sendState).catch((e) => post({ kind: 'state', settings: readSettings(), meshes: {}, stats: null, error: e.message }));
  }, 60);
}

/** Waits for the host's `open`, after saying `hello`; returns what it brings: `{ file,
 * settings }`, `file` `{ name, bytes }` or null (then the page opens its address). */
export function connect() {
  return new Promise((resolve) => {
    window.addEventListener('message', (ev) => {
      const m = ev.data;
      if (ev.source !== window.parent || !m || typeof m.smoothlab !== 'string') return;
      if (m.smoothlab === 'open' && !host.window) {
        host.window = ev.source;
        host.replay = m.replay || null;
        host.view = m.view || null;
        resolve({ file: m.file || null, settings: m.settings || {} });
      } else if (m.smoothlab === 'view' && host.window) {
        applyView(m).then(scheduleState);
      } else if (m.smoothlab === 'settings' && host.window) {
        applySettings(m.settings).then((why) => {
          host.error = why;
          scheduleState();
        });
      }
    });
    pageEvents.addEventListener('meshes', scheduleState);
    window.parent.postMessage({ smoothlab: 'hello' }, '*');
  });
}

/** Opens what the host brought: its settings, then its file (a load the core refuses
 * leaves its message for the host). Resolves whether the page should go on to open its
 * address (no file was brought). */
export async function openFromHost({ file, settings }) {
  host.error = await applySettings(settings);
  if (!file) return true;
  const src = { kind: 'file', name: file.name, bytes: file.bytes };
  await load(src, file.name, { keepHash: true });
  if (state.lastGood !== src) host.error = $('message').textContent || `${file.name} could not be opened`;
  scheduleState();
  return false;
}

/** The host's 3D view (`open`'s `view`), then the passes the host's saved state records (`open`'s `replay`: `{ passes, points: { a, b } }`,
 * a notebook opened again from its saved widget state), run again on the mesh just
 * opened: the page is deterministic, so both sides come back as they were saved, which is
 * checked against the saved points; a side that differs (a node moved by hand, a
 * perturbation) is said in the host's error. */
export async function replayFromHost() {
  await applyView(host.view);
  host.view = null;
  const r = host.replay;
  host.replay = null;
  if (!r || !state.lastGood || !(r.passes > 0)) return;
  await smooth(r.passes);
  for (const side of ['a', 'b']) {
    const want = r.points && r.points[side] ? new Uint8Array(r.points[side]) : null;
    if (!want) continue;
    const p = (await engine.call('meshArrays', side)).points;
    const got = new Uint8Array(p.buffer, p.byteOffset, p.byteLength);
    if (got.length !== want.length || got.some((v, i) => v !== want[i])) {
      host.error = `side ${side.toUpperCase()} as saved was not made by its ${r.passes} passes alone (a node moved by hand, or a perturbation): it shows those passes run again on the mesh as opened`;
      break;
    }
  }
  scheduleState();
}

// Loading: a sample, a Gmsh file of the site or the user's file into the engine; the page's
// planar, surface or volume mode; the previous mesh kept when a load fails.
import { $, COMPARE, clearError, engine, metrics, now, report, serial, setStatus, showError, state } from './state.js';
import { readChoice, readSettings, showBoundaryReasons, showBoundaryWords } from './controls.js';
import { writePermalink } from './permalink.js';
import { startHelper } from './workers.js';
import { NODE_HINT, redrawAll } from './draw.js';
import { showPickNote } from './pointer.js';
import { showNodeBadge } from './present.js';


export async function loadSource(src, call = (...a) => engine.call(...a)) {
  const loaded = await sendSource(src, call);
  // the boundary menu for this mesh first: fixed where its boundary cannot slide
  showBoundaryReasons(loaded.slideRefused ?? null);
  const settings = readSettings();
  await call('settings', settings);
  state.boundary = settings.boundary;
  state.compare = COMPARE.map((_, i) => readChoice(i));
  state.lastGood = src;
  state.node = null;
  state.perturbed = null;
  $('node').value = '';
  showNodeBadge(); // the Node tab named the previous mesh's node
  const why = loaded.notPlanar ? `Read as a surface in 3D: ${loaded.notPlanar}.` : loaded.fileNote ? `${loaded.fileNote}.` : null;
  showSurfaceMode(loaded.surface, why, Boolean(loaded.volume));
  showBoundaryWords(); // in the words of the mesh's kind (a surface's boundary is its curves)
  return loaded;
}

/** Has a worker load a source; says what it loaded (`{ surface, volume, notPlanar, fileNote, nodes }`). */
export async function sendSource(src, call) {
  let loaded = { surface: false };
  switch (src.kind) {
    case 'sample':
      loaded = await call('loadSample', src.name);
      break;
    case 'gmsh':
      loaded = await call('loadFile', src.name, await gmshSample(src.name));
      break;
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

/** The bytes of a Gmsh file the site ships (www/samples/): fetched, or, in the one-file
 * page (`make single`), read from the page, where it is inlined as a script element of
 * type text/plain named by `data-sample`. */
async function gmshSample(name) {
  for (const el of document.querySelectorAll('script[data-sample]')) {
    if (el.dataset.sample === name) return new TextEncoder().encode(el.textContent).buffer;
  }
  const res = await fetch(`samples/${encodeURIComponent(name)}`);
  if (!res.ok) throw new Error(`could not fetch the sample ${name} (HTTP ${res.status})`);
  return res.arrayBuffer();
}

/** What the log-scale box scales for the mesh on screen, as its tooltip. */
export const HIST_LOG_HELP = {
  planar: 'The corner-angle histograms of both sides on a logarithmic scale: the few very poor angles show.',
  volume: 'The dihedral-angle histograms of both sides on a logarithmic scale: the few very poor angles show.',
};

/** Puts the page in the 3D mode (a surface, or tetrahedra when `volume`) or back in the
 * planar one; `why` says why a file read as a surface (the node farthest off the plane
 * it would lie in: a mistyped coordinate shows here, as the command-line tool says it).
 * Every view works in 3D; what differs is said in the notes: a drag turns the view
 * (nodes are not dragged), and tetrahedra are cut by a plane. */
export function showSurfaceMode(on, why = null, volume = false) {
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
  $('surface-why').textContent = on && why ? why : '';
  $('hist-log').title = HIST_LOG_HELP[state.volume ? 'volume' : 'planar'];
  $('smooth-node').disabled = state.node === null;
  $('node-hint').textContent = nodeHint();
  for (const id of ['mesh-a', 'mesh-b']) {
    const letter = id === 'mesh-a' ? 'A' : 'B';
    $(id).setAttribute('aria-label', on
      ? (state.volume
        ? `Volume mesh of panel ${letter}, cut by a plane, coloured by mean ratio; click a face to choose its nearest node, drag to turn, wheel to zoom`
        : `Surface of panel ${letter} in 3D, coloured by quality; click to choose a node, drag to turn, wheel to zoom`)
      : `Mesh of panel ${letter}, coloured by quality; arrow keys move the chosen node`);
  }
}

/** What the node view asks for, in the words of the mesh on screen. */
export function nodeHint() {
  if (state.volume) {
    return 'Click a face of the cut (or of the boundary) to choose its nearest node, or type its number: its level sets are drawn over the cut plane moved to pass through it.';
  }
  if (state.surface) {
    return 'Click the surface to choose the nearest node of the face there, or type its number: its level sets are drawn in its tangent plane.';
  }
  return NODE_HINT;
}

export function selectValueOf(src) {
  if (src.kind === 'sample') return `sample:${src.name}`;
  if (src.kind === 'gmsh') return `gmsh:${src.name}`;
  return '';
}

/** The label of a source as the sample menu shows it (not its internal name); a user's
 * file by its name. */
export function labelOf(src) {
  if (src.kind === 'file' || src.kind === 'triangle') return `your file ${src.name}`;
  const o = [...$('sample').options].find((x) => x.value === selectValueOf(src));
  return o ? o.textContent : src.name;
}

/** The sample menu shows the mesh on screen: a sample by its entry, a user's file as
 * "(your file: NAME)". */
export function showSource(src) {
  const mine = [...$('sample').options].find((o) => o.value === '');
  const file = src && (src.kind === 'file' || src.kind === 'triangle');
  if (mine) mine.textContent = file ? `(your file: ${src.name})` : '(your file)';
  $('sample').value = src ? selectValueOf(src) : '';
}

/** A load that failed: the message box says why (the core's words, as the command-line
 * tool says them), the status line says it too, with the mesh still on screen, and the
 * sample menu names that mesh. */
export function refuseLoad(name, reason) {
  const prev = state.lastGood;
  showSource(prev);
  const still = prev ? ` Still showing ${labelOf(prev)}.` : '';
  setStatus(`Could not open ${name}: ${String(reason).replace(/[.\s]+$/, '')}.${still}`);
}

/** Loads a source; on failure the previous mesh stays on screen and the message says why. */
export function load(src, label, { keepHash = false } = {}) {
  const stopped = endRun();
  return serial(async () => {
    setStatus(`Loading ${label}…`);
    const t0 = now();
    $('progress').removeAttribute('value'); // indeterminate while the worker builds it
    let loaded;
    try {
      loaded = await loadSource(src);
    } catch (e) {
      if (!e.panic) refuseLoad(label, e && e.message ? e.message : String(e));
      throw e;
    } finally {
      $('progress').max = 1;
      $('progress').value = 0;
    }
    const t1 = now();
    clearError();
    showSource(src);
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
export function endRun() {
  state.generation += 1;
  if (!state.running) return '';
  state.cancel = true;
  return ' The run in progress was stopped.';
}

export async function readFiles(files) {
  const list = [...files];
  if (list.length === 0) return;
  // the page's own limit, from the core's control sheet (asked for here if a file comes
  // before the page has built its controls)
  const limit = (state.controls ?? (await engine.call('controls'))).max_file_bytes;
  for (const f of list) {
    if (f.size > limit) {
      const why = `${f.name} is too large (${(f.size / 1048576).toFixed(0)} MB); the page reads files up to ${limit / 1048576} MB.`;
      showError(why);
      refuseLoad(f.name, why);
      return;
    }
  }
  const ext = (f) => f.name.toLowerCase().split('.').pop();
  const node = list.find((f) => ext(f) === 'node');
  const ele = list.find((f) => ext(f) === 'ele');
  if (node || ele) {
    if (!(node && ele)) {
      const why = `A Triangle mesh needs its .node and .ele files together: select or drop both (got only ${(node || ele).name}).`;
      showError(why);
      refuseLoad((node || ele).name, why);
      return;
    }
    const [nt, et] = await Promise.all([node.text(), ele.text()]);
    await load({ kind: 'triangle', node: nt, ele: et, name: `${node.name} + ${ele.name}` }, `${node.name} + ${ele.name}`);
    return;
  }
  if (list.length > 1) {
    const why = `Drop one mesh file at a time (or a .node and .ele pair); got ${list.length} files.`;
    showError(why);
    refuseLoad(list.map((f) => f.name).join(', '), why);
    return;
  }
  const f = list[0];
  const bytes = await f.arrayBuffer();
  await load({ kind: 'file', name: f.name, bytes }, f.name);
}

// The playground page's entry: wires the controls, fills the menus and opens the address.
import { $, COMPARE, EMBED, HOSTED, PARAMS, FIGURE_HASH, SETTINGS, VIEWS, engine, gallery, metrics, now, report, serial, showError, state, view } from './state.js';
import { CHECKED, buildControls, changeBoundary, changeCompare, changeTarget, checkControl, showStrategyReasons } from './controls.js';
import { applyHash, copyLink, markAddressHandled, onAddressChange, openHash, openView, updatePermalink, writePermalink } from './permalink.js';
import { closeTour, drawFigurePicture, fillTourMenu, goFigure, openFigure } from './tour.js';
import { load, readFiles } from './loading.js';
import { readyHelper } from './workers.js';
import { redrawAll, redrawCharts, redrawMeshes, redrawNode } from './draw.js';
import { perturb, reset, run, step } from './run.js';
import { attachLevelZoom, attachPointer, pickRadius, selectNode } from './pointer.js';
import { saveFigure, smoothThisNode, undo } from './undo.js';
import { exportMesh, exportPng } from './export.js';
import { sendTheme, startTheme, wirePresentation } from './present.js';
import { connect, openFromHost, replayFromHost } from './host.js';

export async function fillGallery() {
  const list = await engine.call('samples');
  gallery.defaultSample = list[0].name;
  const sel = $('sample');
  const gen = document.createElement('optgroup');
  gen.label = 'Generated in the browser';
  for (const s of list) {
    const o = document.createElement('option');
    o.value = `sample:${s.name}`;
    o.textContent = s.title;
    gen.append(o);
  }
  const files = document.createElement('optgroup');
  files.label = 'Meshed by Gmsh (files)';
  // the Gmsh files the site ships (www/samples/), as the core lists them
  for (const { file, title } of state.controls.gmsh_samples) {
    const o = document.createElement('option');
    o.value = `gmsh:${file}`;
    o.textContent = title;
    files.append(o);
  }
  const none = document.createElement('option');
  none.value = '';
  none.textContent = '(your file)';
  none.disabled = true;
  sel.append(gen, files, none);
}

export function wire() {
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
  // the cut plane of tetrahedra: both views follow as the slider moves, the chosen node's
  // level sets (over the cut plane moved to it) follow its axis, and the link keeps it
  const cut = () => {
    const at = Number($('cut-at').value);
    $('cut-at-out').textContent = at.toFixed(2);
    if (!state.volume) return;
    serial(async () => {
      await engine.call('setCut', Number($('cut-axis').value), at);
      await redrawMeshes();
      await redrawNode();
      await writePermalink();
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
  $('target').addEventListener('change', changeTarget);
  $('boundary').addEventListener('change', () => changeBoundary());
  for (const id of Object.keys(CHECKED)) {
    $(id).addEventListener('input', () => checkControl(id).then(() => updatePermalink()).catch(report));
  }
  window.addEventListener('hashchange', () => onAddressChange().catch(report));
  window.addEventListener('popstate', () => onAddressChange().catch(report));
  attachPointer($('mesh-a'));
  attachPointer($('mesh-b'));
  attachLevelZoom($('level-a'), 'a');
  attachLevelZoom($('level-b'), 'b');
  $('undo').addEventListener('click', undo);
  document.addEventListener('keydown', (ev) => {
    const typing = ev.target instanceof HTMLElement && ev.target.matches('input, select, textarea');
    if ((ev.ctrlKey || ev.metaKey) && !ev.shiftKey && !ev.altKey && ev.key.toLowerCase() === 'z' && !typing) {
      ev.preventDefault();
      undo();
    }
  });
  wirePresentation({ closeTour });
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
      serial(redrawAll).catch(report);
      serial(drawFigurePicture).catch(report);
    }, 150);
  });
}

/** `?embed=1`: the compact page that fills its frame; `&caption=0` leaves the words out. A
 * link opens the full playground in the same state (in the header bar, or in the tour's
 * bar for a figure); an embedded figure shows its picture, and "Live view" the view it
 * was made from. */
export function setupEmbed() {
  if (!EMBED) return;
  document.body.classList.add('embed');
  if (view.spec) document.body.classList.add('view', `view-${view.name}`);
  if (PARAMS.get('caption') === '0') document.body.classList.add('nocaption');
  // a notebook's widget shows the settings column: what each side runs, unfolded
  if (HOSTED) $('compare-box').open = true;
  const a = document.createElement('a');
  a.id = 'open-full';
  a.target = '_blank';
  a.rel = 'noopener';
  a.textContent = 'Open the full playground';
  $('theme-toggle').before(a);
  const live = document.createElement('button');
  live.type = 'button';
  live.id = 'figure-live';
  live.className = 'quiet';
  live.setAttribute('aria-pressed', 'false');
  live.textContent = 'Live view';
  live.title = 'The playground in the state this figure was made from (Step and Run smooth it)';
  live.addEventListener('click', () => {
    const on = document.body.classList.toggle('live');
    live.setAttribute('aria-pressed', on ? 'true' : 'false');
    serial(redrawAll).catch(report);
    serial(drawFigurePicture).catch(report);
  });
  $('tour-link').before(live);
  // a figure's own bar links the full page too (its header is hidden)
  const b = a.cloneNode(true);
  b.id = 'open-full-figure';
  $('tour-bar-end').append(b);
}

export async function main() {
  document.body.dataset.busy = '1';
  startTheme();
  setupEmbed();
  wire();
  try {
    // the first answer waits for the worker to start and the wasm module to be compiled
    const { result: controls, timing } = await engine.timed('controls');
    metrics.startup = { engine_ready_ms: timing.worker.start - performance.timeOrigin, first_mesh_ms: 0 };
    buildControls(controls);
    await sendTheme();
    await fillGallery();
    await fillTourMenu();
    metrics.startup.menus_ms = now();
  } catch (e) {
    report(e);
    document.body.dataset.busy = '0';
    return;
  }
  state.lastHash = location.hash;
  // in a notebook's widget: the host's settings, and its mesh instead of the address's
  if (HOSTED && !(await openFromHost(await connect()))) {
    markAddressHandled();
    await replayFromHost();
    document.body.dataset.ready = '1';
    return;
  }
  const fig = FIGURE_HASH.exec(location.hash);
  if (fig) {
    await openFigure(fig[1]);
    markAddressHandled();
    document.body.dataset.ready = '1';
    return;
  }
  await openHash(await applyHash());
  if (view.name !== null && !view.spec) {
    showError(`view=${view.name}: an embed shows one of the views ${Object.keys(VIEWS).join(', ')}; this is the compact page.`);
  }
  await openView();
  markAddressHandled();
  if (HOSTED) await replayFromHost();
  document.body.dataset.ready = '1';
}

/** Offline after the first visit: the site's service worker (sw.js) keeps its files, on a
 * page served over HTTP (not opened from a file, nor in a notebook's widget, which
 * carries the page itself). Registered once the page has opened, so it costs the first
 * screen nothing. */
function keepOffline() {
  if (HOSTED || !/^https?:$/.test(location.protocol) || !('serviceWorker' in navigator)) return;
  navigator.serviceWorker.register(new URL('sw.js', location.href), { updateViaCache: 'none' }).catch((e) => {
    console.warn(`the page will not work offline: ${e.message}`);
  });
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
  // in 3D: where node `node` of side `side` is drawn on its canvas (CSS pixels of the
  // canvas, and how far behind the front of the mesh it is), and where it is in space
  nodeOnScreen: (side, node) => serial(() => engine.call('nodeOnScreen', side, node)),
  nodePoint: (side, node) => serial(() => engine.call('nodePoint', side, node)),
  camera: () => serial(() => engine.call('camera')),
};

main().then(keepOffline);

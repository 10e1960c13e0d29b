// The notebook widget's view (anywidget: `render({ model, el })`): the playground page
// itself, the same engine and controls, in a frame sized for a notebook cell, and the
// bridge between the page (www/app/host.js) and the widget's model. The page (the one-file
// page of scripts/single.mjs, wasm inside) is not in this module, nor in any widget's
// state: it is the `page` (gzipped, base64) of one model every widget of the kernel shares
// (`_page`, a reference "IPY_MODEL_<id>"), so a notebook saved with its widgets' state
// holds it once, however many widgets it shows.
//
// The model's traits (python/smoothlab/widget.py): `_file` and `_file_name`, the mesh the
// page opens (a .vtk text the Python side wrote); `sample` or `figure`, what it opens
// instead; the settings (`strategy`, `threshold`, `order`, `passes`, `max_iter`,
// `objective_a`, `penalty_a`, `objective_b`, `penalty_b`; null: the page's default),
// which flow both ways; `_mesh_a`, `_mesh_b` (each side's mesh as arrays, set here after
// every change), `stats` and `error`, set here; `camera` and `cut`, a 3D view's, which
// flow both ways; `height`, the frame's height in pixels.
// A model that holds a stepped mesh (a notebook's saved state) opens stepped: the page
// runs its passes again and checks the sides against the saved points.

/** The traits the page's settings are synced with (app/host.js's SETTING_CONTROLS). */
const SETTINGS = ['strategy', 'threshold', 'order', 'passes', 'max_iter', 'objective_a', 'penalty_a', 'objective_b', 'penalty_b'];

/** The page's text from its gzipped base64 (1.8 MB, not 3.3: its wasm is base64 inside). */
async function unzipPage(text) {
  if (typeof text !== 'string' || !text) throw new Error('smoothlab: no page came with the widget');
  const bytes = Uint8Array.from(atob(text), (c) => c.charCodeAt(0));
  const stream = new Blob([bytes]).stream().pipeThrough(new DecompressionStream('gzip'));
  const page = await new Response(stream).text();
  if (!page.includes('<html lang="en">')) throw new Error('smoothlab: what came as the page is not the page');
  return page;
}

/** The page, asked of the kernel by a message (a front end whose models cannot reach the
 * shared one: no `widget_manager.get_model`); the answer is not kept in any state. */
function pageFromKernel(model) {
  return new Promise((resolve, reject) => {
    const timer = setTimeout(() => {
      model.off('msg:custom', onMessage);
      reject(new Error('smoothlab: the kernel did not send the page (is it running?)'));
    }, 60_000);
    function onMessage(m) {
      if (!m || m.smoothlab !== 'page') return;
      clearTimeout(timer);
      model.off('msg:custom', onMessage);
      resolve(m.page);
    }
    model.on('msg:custom', onMessage);
    model.send({ smoothlab: 'page?' });
  });
}

/** The one-file page: the `page` of the model all widgets share (`_page`), unzipped once
 * however many widgets ask; where the front end cannot reach that model, the kernel sends it. */
async function pageText(model) {
  const ref = model.get('_page');
  const id = typeof ref === 'string' && ref.startsWith('IPY_MODEL_') ? ref.slice('IPY_MODEL_'.length) : null;
  if (!id) throw new Error('smoothlab: the widget has no page model (_page): build the wheel again (make wheel)');
  const pages = (globalThis.smoothlabPages ||= new Map());
  if (!pages.has(id)) {
    pages.set(id, (async () => {
      let text = null;
      if (model.widget_manager && typeof model.widget_manager.get_model === 'function') {
        const shared = await model.widget_manager.get_model(id).catch(() => null);
        text = shared ? shared.get('page') : null;
      }
      return unzipPage(text || (await pageFromKernel(model)));
    })());
  }
  try {
    return await pages.get(id);
  } catch (e) {
    pages.delete(id); // a later widget asks again
    throw e;
  }
}

/** The page's document: the one-file page marked as hosted (app/state.js, HOSTED). */
function pageURL(model, page) {
  const html = page.replace('<html lang="en">', '<html lang="en" data-host="widget">');
  const url = URL.createObjectURL(new Blob([html], { type: 'text/html' }));
  const figure = model.get('figure');
  const sample = model.get('sample');
  const hash = figure ? `#figure=${encodeURIComponent(figure)}` : sample ? `#sample=${encodeURIComponent(sample)}` : '';
  return { url, address: url + hash };
}

/** The bytes a binary trait holds (a DataView, an ArrayBuffer or a typed array), copied. */
function bytesOf(value) {
  if (!value) return null;
  if (value instanceof ArrayBuffer) return value.slice(0);
  if (ArrayBuffer.isView(value)) return value.buffer.slice(value.byteOffset, value.byteOffset + value.byteLength);
  return null;
}

/** A side's mesh for the model: its arrays as DataViews (sent to the kernel as binary
 * buffers, not as lists of numbers). */
function meshTrait(arrays) {
  const view = (a) => new DataView(a.buffer, a.byteOffset, a.byteLength);
  return {
    dim: arrays.dim,
    points: view(arrays.points),
    cells: arrays.cells.map((c) => ({ vtk_type: c.vtk_type, per_cell: c.per_cell, nodes: view(c.nodes) })),
    fixed: view(arrays.fixed),
  };
}

/** The passes a stepped model records, for the page to run again once it has opened the
 * mesh (a notebook opened again from its saved widget state, or the widget shown once
 * more): `{ passes, points: { a, b } }` (the sides' points as saved, which the page checks
 * its replay against), or null when the model holds no stepped mesh. */
function savedRun(model) {
  const stats = model.get('stats');
  const passes = stats && stats.b ? Number(stats.b.passes) : 0;
  const a = model.get('_mesh_a');
  const b = model.get('_mesh_b');
  if (!(passes > 0) || !a || !a.points || !b || !b.points) return null;
  return { passes, points: { a: bytesOf(a.points), b: bytesOf(b.points) } };
}

/** The traits of the 3D view: `camera` [yaw, pitch, zoom], `cut` [axis, fraction]. */
const VIEW = ['camera', 'cut'];

function viewOf(model) {
  return { camera: model.get('camera') ?? null, cut: model.get('cut') ?? null };
}

function settingsOf(model) {
  const out = {};
  for (const name of SETTINGS) out[name] = model.get(name);
  return out;
}

async function render({ model, el }) {
  let page;
  try {
    page = await pageText(model);
  } catch (e) {
    const p = document.createElement('p');
    p.textContent = e.message;
    p.style.cssText = 'color: #8a1c1c; font-family: system-ui, sans-serif;';
    el.append(p);
    return () => {};
  }
  const frame = document.createElement('iframe');
  frame.title = 'smoothlab: two smoothing objectives side by side';
  frame.style.cssText = 'width: 100%; border: 0; display: block;';
  const size = () => {
    frame.style.height = `${model.get('height')}px`;
  };
  size();
  let applying = false; // the page's own state going into the model: not sent back
  const onMessage = (ev) => {
    const m = ev.data;
    if (ev.source !== frame.contentWindow || !m || typeof m.smoothlab !== 'string') return;
    if (m.smoothlab === 'hello') {
      const bytes = bytesOf(model.get('_file'));
      const file = bytes && bytes.byteLength ? { name: model.get('_file_name') || 'mesh.vtk', bytes } : null;
      const replay = model.get('figure') ? null : savedRun(model);
      frame.contentWindow.postMessage({ smoothlab: 'open', file, settings: settingsOf(model), view: viewOf(model), replay }, '*', file ? [file.bytes] : []);
    } else if (m.smoothlab === 'state') {
      applying = true;
      try {
        for (const name of SETTINGS) {
          if (m.settings && m.settings[name] !== undefined && model.get(name) !== m.settings[name]) model.set(name, m.settings[name]);
        }
        if (m.meshes && m.meshes.a) model.set('_mesh_a', meshTrait(m.meshes.a));
        if (m.meshes && m.meshes.b) model.set('_mesh_b', meshTrait(m.meshes.b));
        if (m.stats) model.set('stats', m.stats);
        for (const name of VIEW) {
          const v = m.view ? m.view[name] ?? null : null;
          if (JSON.stringify(v) !== JSON.stringify(model.get(name) ?? null)) model.set(name, v);
        }
        model.set('error', m.error ?? null);
        model.save_changes();
      } finally {
        applying = false;
      }
    }
  };
  window.addEventListener('message', onMessage);
  const onSettings = () => {
    if (applying || !frame.contentWindow) return;
    frame.contentWindow.postMessage({ smoothlab: 'settings', settings: settingsOf(model) }, '*');
  };
  for (const name of SETTINGS) model.on(`change:${name}`, onSettings);
  const onView = () => {
    if (applying || !frame.contentWindow) return;
    frame.contentWindow.postMessage({ smoothlab: 'view', ...viewOf(model) }, '*');
  };
  for (const name of VIEW) model.on(`change:${name}`, onView);
  model.on('change:height', size);
  let at = pageURL(model, page);
  frame.src = at.address;
  // `sample`, `figure` or the mesh assigned after display: the page opens it anew (one
  // reload for the traits the kernel changes together)
  let reloading = false;
  const reopen = () => {
    if (reloading) return;
    reloading = true;
    setTimeout(() => {
      reloading = false;
      URL.revokeObjectURL(at.url);
      at = pageURL(model, page);
      frame.src = at.address;
    }, 0);
  };
  const OPENERS = ['sample', 'figure', '_file'];
  for (const name of OPENERS) model.on(`change:${name}`, reopen);
  el.append(frame);
  return () => {
    window.removeEventListener('message', onMessage);
    for (const name of SETTINGS) model.off(`change:${name}`, onSettings);
    for (const name of VIEW) model.off(`change:${name}`, onView);
    for (const name of OPENERS) model.off(`change:${name}`, reopen);
    model.off('change:height', size);
    URL.revokeObjectURL(at.url);
  };
}

export default { render };

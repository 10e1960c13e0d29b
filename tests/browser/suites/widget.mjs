// The notebook widget's ES module (python/smoothlab/static/widget.js, made by `make python`)
// loaded as anywidget loads it (a dynamic import of a blob of its text) into a page laid
// out like a notebook's cell, and rendered with a stand-in model that keeps the anywidget
// contract (get, set, on, off, save_changes, widget_manager.get_model for the shared
// model that holds the page, page.html.gz in base64): the mesh the Python side wrote goes in, the
// page draws it, a Step sends both sides' smoothed meshes back to the model as arrays, the
// model's settings reach the page's controls, and what the page refuses comes back in
// words. The model's final state is written to test-output/widget/state.json, which the
// Python tests read back through the package (python/tests/test_from_page.py).
import { readFileSync, mkdirSync, writeFileSync } from 'node:fs';
import path from 'node:path';
import { ROOT } from '../serve.mjs';
import { OUT, TIMEOUT, test, check, freshPage } from '../lib.mjs';

const MODULE = path.join(ROOT, 'python', 'smoothlab', 'static', 'widget.js');
const PAGE = path.join(ROOT, 'python', 'smoothlab', 'static', 'page.html.gz');
const STATE = path.join(ROOT, 'test-output', 'widget', 'state.json');

/** A tangled grid of n × n quads as the Python side writes it (`mesh.vtk_text`): its
 * inner points moved by up to 0.6 of a cell, so a pass moves them. */
function tangledGrid(n) {
  const pts = [];
  let s = 7;
  const rnd = () => {
    s = (s * 16807) % 2147483647;
    return s / 2147483647 - 0.5;
  };
  for (let j = 0; j <= n; j++) {
    for (let i = 0; i <= n; i++) {
      const inner = i > 0 && j > 0 && i < n && j < n;
      pts.push([i + (inner ? 1.2 * rnd() : 0), j + (inner ? 1.2 * rnd() : 0)]);
    }
  }
  const cells = [];
  for (let j = 0; j < n; j++) for (let i = 0; i < n; i++) {
    const a = j * (n + 1) + i;
    cells.push([a, a + 1, a + n + 2, a + n + 1]);
  }
  return '# vtk DataFile Version 3.0\nsmoothlab widget mesh\nASCII\nDATASET UNSTRUCTURED_GRID\n' +
    `POINTS ${pts.length} double\n${pts.map(([x, y]) => `${x} ${y} 0`).join('\n')}\n` +
    `CELLS ${cells.length} ${cells.length * 5}\n${cells.map((c) => `4 ${c.join(' ')}`).join('\n')}\n` +
    `CELL_TYPES ${cells.length}\n${cells.map(() => '9').join('\n')}\n`;
}

/** A notebook's cell (900 px wide) at an http address, with the widget's module imported
 * as anywidget does and a stand-in model; `window.cellModel` is the model. */
async function renderWidget(p, server, state, { kernelPage = false } = {}) {
  // the notebook at the site's origin (a notebook server's pages are its own)
  await p.route('**/notebook', (r) => r.fulfill({
    contentType: 'text/html',
    body: '<!doctype html><link rel="icon" href="data:,"><body style="margin:0;background:#eee"><div id="cell" style="width:900px;margin:16px;background:#fff"></div></body>',
  }));
  await p.goto(`${server.base}notebook`);
  await p.evaluate(async ({ source, page, state, kernelPage }) => {
    const listeners = {};
    // the model every widget shares, which holds the page (gzipped), as the kernel's manager gives it
    const pageModel = { get: (name) => (name === 'page' ? page : undefined) };
    const model = {
      state: { _page: 'IPY_MODEL_page', ...state },
      saves: 0,
      widget_manager: {
        async get_model(id) {
          if (id !== 'page') throw new Error(`no model ${id}`);
          return pageModel;
        },
      },
      get(name) {
        return this.state[name];
      },
      set(name, value) {
        const before = this.state[name];
        this.state[name] = value;
        if (before !== value) for (const f of listeners[`change:${name}`] || []) f();
      },
      on(event, f) {
        (listeners[event] ||= []).push(f);
      },
      off(event, f) {
        listeners[event] = (listeners[event] || []).filter((g) => g !== f);
      },
      save_changes() {
        this.saves += 1;
      },
      asked: 0,
      send(content) {
        // the kernel's answer to the view's message (Playground._on_message)
        if (content && content.smoothlab === 'page?') {
          this.asked += 1;
          setTimeout(() => { for (const f of listeners['msg:custom'] || []) f({ smoothlab: 'page', page }, []); }, 0);
        }
      },
    };
    if (kernelPage) delete model.widget_manager; // a front end without get_model
    if (state._file !== null) model.state._file = new DataView(new TextEncoder().encode(state._file).buffer);
    window.cellModel = model;
    const url = URL.createObjectURL(new Blob([source], { type: 'text/javascript' }));
    window.widgetURL = url;
    const widget = (await import(url)).default;
    window.cellCleanup = widget.render({ model, el: document.getElementById('cell') });
    window.cellCleanup = await window.cellCleanup;
  }, { source: readFileSync(MODULE, 'utf8'), page: readFileSync(PAGE).toString('base64'), state, kernelPage });
  const frame = await (await p.$('#cell iframe')).contentFrame();
  await frame.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
  return frame;
}

/** The model's state as the test reads it: a side's arrays summed up, the rest as it is. */
function modelSide(p, side) {
  return p.evaluate((side) => {
    const m = window.cellModel.state[side];
    if (!m) return null;
    const points = new Float64Array(m.points.buffer, m.points.byteOffset, m.points.byteLength / 8);
    return {
      dim: m.dim,
      points: [...points],
      cells: m.cells.map((c) => ({ vtk_type: c.vtk_type, per_cell: c.per_cell, count: c.nodes.byteLength / 4 / c.per_cell })),
      free: new Uint8Array(m.fixed.buffer, m.fixed.byteOffset, m.fixed.byteLength).filter((f) => f === 0).length,
    };
  }, side);
}

const EMPTY = {
  _file: null, _file_name: '', sample: null, figure: null, height: 540,
  strategy: null, threshold: null, order: null, passes: null, max_iter: null,
  objective_a: null, penalty_a: null, objective_b: null, penalty_b: null,
  camera: null, cut: null, _mesh_a: {}, _mesh_b: {}, stats: {}, error: null,
};

export default async function ({ server, browser }) {
  // a notebook's own origin: no service worker of the site's (the other suites' pages
  // register it on this address) between the cell and its requests
  const context = await browser.newContext({ serviceWorkers: 'block' });
  try {
    await widgetTests(server, context);
  } finally {
    await context.close();
  }
}

async function widgetTests(server, context) {
  await test('the notebook widget: a mesh from Python drawn on both sides, a Step sends the smoothed meshes back to the model as arrays', async () => {
    const p = await freshPage(context, 940, 640, 'widget');
    try {
      const frame = await renderWidget(p, server, { ...EMPTY, _file: tangledGrid(8), _file_name: 'notebook.vtk', passes: 2 });
      await p.waitForFunction(() => window.cellModel.state._mesh_b.dim !== undefined, null, { timeout: TIMEOUT });
      const a0 = await modelSide(p, '_mesh_a');
      const b0 = await modelSide(p, '_mesh_b');
      check(a0.dim === 2 && a0.points.length === 81 * 2, `side A as loaded: ${a0.dim}D, ${a0.points.length / 2} points`);
      check(b0.cells.length === 1 && b0.cells[0].vtk_type === 9 && b0.cells[0].count === 64, `B's cells: ${JSON.stringify(b0.cells)}`);
      check(b0.free === 49, `the 7 × 7 inner points are free: ${b0.free}`);
      check(JSON.stringify(a0.points) === JSON.stringify(b0.points), 'both sides start from the mesh given');
      // the page's defaults came back as the model's settings, the model's passes went in
      const st = await p.evaluate(() => window.cellModel.state);
      check(st.strategy && st.objective_a === 'old' && st.objective_b === 'new', `settings from the page: ${st.strategy}, ${st.objective_a}, ${st.objective_b}`);
      check(st.passes === 2 && (await frame.inputValue('#passes')) === '2', `passes: model ${st.passes}, page ${await frame.inputValue('#passes')}`);
      check(Number(st.stats.b.inverted) > 0, `the grid starts tangled: ${JSON.stringify(st.stats.b)}`);
      check(st.error === null, `no error: ${st.error}`);
      await p.screenshot({ path: path.join(OUT, 'widget-cell-loaded.png') });
      // Step in the page: both sides' smoothed meshes reach the model
      const saves = await p.evaluate(() => window.cellModel.saves);
      await frame.click('#step');
      await p.waitForFunction((n) => window.cellModel.saves > n && window.cellModel.state.stats.b.passes === 1, saves, { timeout: TIMEOUT });
      const a1 = await modelSide(p, '_mesh_a');
      const b1 = await modelSide(p, '_mesh_b');
      check(b1.points.length === b0.points.length && JSON.stringify(b1.points) !== JSON.stringify(b0.points), 'B\'s points moved');
      check(JSON.stringify(a1.points) !== JSON.stringify(b1.points), 'the two objectives moved them differently');
      // the boundary stays where it was (point 0 is a corner, 8 the other end of the bottom)
      check(b1.points[0] === 0 && b1.points[1] === 0 && b1.points[16] === 8, `the boundary is fixed: ${b1.points.slice(0, 2)}, ${b1.points[16]}`);
      const stats = await p.evaluate(() => window.cellModel.state.stats);
      check(Number(stats.b.inverted) < Number(st.stats.b.inverted), `B untangles: ${st.stats.b.inverted} → ${stats.b.inverted}`);
      await p.screenshot({ path: path.join(OUT, 'widget-cell-stepped.png') });
      // the page's controls are in the cell, beside the meshes: the settings column with
      // what each side runs, the Node tab with a node's level sets and their Save PNG
      for (const id of ['strategy', 'target', 'boundary', 'threshold', 'order', 'passes', 'maxiter', 'objective-a', 'penalty-a', 'objective-b', 'penalty-b', 'perturb-box']) {
        check(await frame.locator(`#${id}`).isVisible(), `#${id} is not shown in the widget`);
      }
      const cell = await p.locator('#cell iframe').boundingBox();
      const column = await frame.locator('aside.side').boundingBox();
      const meshB = await frame.locator('#mesh-b').boundingBox();
      check(column.x >= meshB.x + meshB.width && column.x + column.width <= cell.x + cell.width + 1, `the column is beside the meshes, in the cell: ${JSON.stringify({ column, meshB, cell })}`);
      check(meshB.width >= 240, `the meshes keep their room: ${meshB.width} px`);
      await frame.click('#tabbtn-node');
      await frame.fill('#node', '40');
      await frame.press('#node', 'Enter');
      await frame.waitForFunction(() => /^40$/.test(document.getElementById('node-badge').textContent), null, { timeout: TIMEOUT });
      await frame.waitForFunction(() => document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
      check(await frame.locator('#level-b').isVisible() && !(await frame.locator('#strategy').isVisible()), 'the Node tab shows the level sets in place of the settings');
      const level = await frame.evaluate(() => {
        const c = document.getElementById('level-b');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        const seen = new Set();
        for (let i = 0; i < d.length; i += 16) seen.add((d[i] << 16) | (d[i + 1] << 8) | d[i + 2]);
        return { w: c.width, colours: seen.size };
      });
      check(level.w >= 150 && level.colours > 20, `B's level sets are drawn in the column: ${JSON.stringify(level)}`);
      check(await frame.locator('button[data-png="level-b"]').isVisible(), 'Save PNG of the level sets is shown');
      await p.screenshot({ path: path.join(OUT, 'widget-cell-node.png') });
      await frame.click('#tabbtn-settings');
      mkdirSync(path.dirname(STATE), { recursive: true });
      writeFileSync(STATE, JSON.stringify(await p.evaluate(() => {
        const b64 = (v) => btoa(String.fromCharCode(...new Uint8Array(v.buffer, v.byteOffset, v.byteLength)));
        const side = (m) => ({ dim: m.dim, points: b64(m.points), fixed: b64(m.fixed), cells: m.cells.map((c) => ({ vtk_type: c.vtk_type, per_cell: c.per_cell, nodes: b64(c.nodes) })) });
        const s = window.cellModel.state;
        return { _mesh_a: side(s._mesh_a), _mesh_b: side(s._mesh_b), stats: s.stats, strategy: s.strategy, passes: s.passes };
      })));
      // the same model shown again, as a notebook reopened from its saved state shows it:
      // the page opens the mesh as given, runs the saved pass again, and both sides are
      // the saved ones (checked by the page: no error)
      const savedA = await modelSide(p, '_mesh_a');
      await p.evaluate(async () => {
        window.cellCleanup();
        document.getElementById('cell').replaceChildren();
        const widget = (await import(window.widgetURL)).default;
        window.cellCleanup = await widget.render({ model: window.cellModel, el: document.getElementById('cell') });
      });
      const again = await (await p.$('#cell iframe')).contentFrame();
      await again.waitForFunction(() => document.body.dataset.ready === '1' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
      await p.waitForTimeout(300);
      const replayed = await p.evaluate(() => ({ passes: window.cellModel.state.stats.b.passes, error: window.cellModel.state.error }));
      check(replayed.passes === 1 && replayed.error === null, `shown again: ${JSON.stringify(replayed)}`);
      check(JSON.stringify(await modelSide(p, '_mesh_b')) === JSON.stringify(b1) && JSON.stringify(await modelSide(p, '_mesh_a')) === JSON.stringify(savedA), 'shown again, the sides are as stepped');
      check(/One pass done/.test(await again.textContent('#status')), `the page says: ${await again.textContent('#status')}`);
      const frame2 = again;
      // a setting from the model reaches the page's control; one the page refuses comes back in words
      await p.evaluate(() => window.cellModel.set('objective_a', 'condition'));
      await frame2.waitForFunction(() => document.getElementById('objective-a').value === 'condition', null, { timeout: TIMEOUT });
      await p.evaluate(() => window.cellModel.set('passes', 100000));
      await p.waitForFunction(() => window.cellModel.state.error !== null, null, { timeout: TIMEOUT });
      const error = await p.evaluate(() => window.cellModel.state.error);
      check(/^passes: /.test(error) && /Passes/.test(error), `the page's words for passes out of range: ${error}`);
      await p.evaluate(() => window.cellCleanup());
    } finally {
      await p.close();
    }
  });

  await test('the notebook widget: a mesh the core refuses says why in the model\'s error, in the core\'s words', async () => {
    const p = await freshPage(context, 940, 640, 'widget-bad');
    try {
      // a pentagon: VTK polygons of 5 vertices are refused by the reader, naming the element
      const bad = '# vtk DataFile Version 3.0\nt\nASCII\nDATASET UNSTRUCTURED_GRID\nPOINTS 5 double\n0 0 0\n1 0 0\n1.5 1 0\n0.5 1.5 0\n-0.5 1 0\nCELLS 1 6\n5 0 1 2 3 4\nCELL_TYPES 1\n7\n';
      // …in a front end whose models cannot reach the shared page model: the kernel sends the page
      await renderWidget(p, server, { ...EMPTY, _file: bad, _file_name: 'notebook.vtk', _page: 'IPY_MODEL_other' }, { kernelPage: true });
      check((await p.evaluate(() => window.cellModel.asked)) === 1, 'the page was not asked of the kernel once');
      await p.waitForFunction(() => window.cellModel.state.error !== null, null, { timeout: TIMEOUT });
      const error = await p.evaluate(() => window.cellModel.state.error);
      check(/polygons are not supported/.test(error) && /element 0/.test(error), `the reader's message: ${error}`);
    } finally {
      await p.close();
    }
  });

  await test('the notebook widget: figure=chen-10 opens the tour\'s figure, and samples by their names (planar, volume)', async () => {
    const p = await freshPage(context, 940, 640, 'widget-figure');
    try {
      const frame = await renderWidget(p, server, { ...EMPTY, figure: 'chen-10' });
      await frame.waitForFunction(() => document.body.dataset.figure === 'chen-10', null, { timeout: TIMEOUT });
      check(/Fig\. 10/.test(await frame.textContent('#tour-title')), `title: ${await frame.textContent('#tour-title')}`);
      await p.screenshot({ path: path.join(OUT, 'widget-cell-figure.png') });
      await p.evaluate(() => window.cellCleanup());
      const f2 = await renderWidget(p, server, { ...EMPTY, sample: 'plate-tri-tangled' });
      check((await f2.inputValue('#sample')) === 'sample:plate-tri-tangled', `the sample menu: ${await f2.inputValue('#sample')}`);
      await p.waitForFunction(() => window.cellModel.state._mesh_a.dim === 2, null, { timeout: TIMEOUT });
      await p.evaluate(() => window.cellCleanup());
      // a volume sample: its hexahedra come back with three coordinates a point
      await renderWidget(p, server, { ...EMPTY, sample: 'hex-tangled' });
      await p.waitForFunction(() => window.cellModel.state._mesh_b.dim === 3, null, { timeout: TIMEOUT });
      const hex = await modelSide(p, '_mesh_b');
      check(hex.points.length === 343 * 3 && hex.cells[0].vtk_type === 12 && hex.cells[0].count === 216, `the hexahedra: ${JSON.stringify(hex.cells)}`);
      // the cut plane is in the column, and moving it redraws the volume
      const f3 = await (await p.$('#cell iframe')).contentFrame();
      check(await f3.locator('#cut-at').isVisible() && await f3.locator('#cut-axis').isVisible(), 'the cut plane\'s controls are shown');
      const pixels = () => f3.evaluate(() => {
        const c = document.getElementById('mesh-b');
        const d = c.getContext('2d').getImageData(0, 0, c.width, c.height).data;
        let h = 0;
        for (let i = 0; i < d.length; i += 4) h = (Math.imul(h, 31) + d[i] + d[i + 1] + d[i + 2]) | 0;
        return h;
      });
      const before = await pixels();
      await f3.locator('#cut-at').fill('0.8');
      await f3.waitForFunction(() => document.getElementById('cut-at-out').textContent === '0.80' && document.body.dataset.busy === '0', null, { timeout: TIMEOUT });
      await f3.waitForTimeout(300);
      check((await pixels()) !== before, 'moving the cut plane redrew the volume');
      await p.screenshot({ path: path.join(OUT, 'widget-cell-volume.png') });
      // the view as the page turned it comes back to the model
      await p.waitForFunction(() => JSON.stringify(window.cellModel.state.cut) === '["z",0.8]', null, { timeout: TIMEOUT });
      const cam = await p.evaluate(() => window.cellModel.state.camera);
      check(Array.isArray(cam) && cam.length === 3 && cam.every(Number.isFinite), `the camera: ${JSON.stringify(cam)}`);
      await p.evaluate(() => window.cellCleanup());
      // the initial view, and a view the model is given after display
      const f4 = await renderWidget(p, server, { ...EMPTY, sample: 'hex-tangled', camera: [60, 10, 1.5], cut: ['x', 0.3] });
      await f4.waitForFunction(() => document.getElementById('cut-axis').value === '0' && document.getElementById('cut-at-out').textContent === '0.30', null, { timeout: TIMEOUT });
      await p.waitForFunction(() => JSON.stringify(window.cellModel.state.camera) === '[60,10,1.5]', null, { timeout: TIMEOUT });
      const first = await f4.evaluate(() => document.getElementById('mesh-b').toDataURL());
      await p.evaluate(() => window.cellModel.set('camera', [200, 40, 1]));
      await f4.waitForFunction((first) => document.body.dataset.busy === '0' && document.getElementById('mesh-b').toDataURL() !== first, first, { timeout: TIMEOUT });
      await p.waitForFunction(() => JSON.stringify(window.cellModel.state.camera) === '[200,40,1]', null, { timeout: TIMEOUT });
    } finally {
      await p.close();
    }
  });
}

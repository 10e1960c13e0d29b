// The in-browser benchmark: generates a rand2d mesh in wasm and times one smoothing pass
// per strategy with performance.now(). The result is shown in the table and published as
// window.benchResult (JSON-ready) for tests/browser/bench.mjs. `?auto=1&nodes=…&reps=…`
// runs at once.
import init, { BenchMesh } from './pkg/smoothlab.js';

const SEED = 2003; // as in examples/perf.rs
const PASSES = [
  ['laplace', 'laplace', 'new'],
  ['smart', 'smart', 'new'],
  ['opt+new', 'opt', 'new'],
  ['opt+old', 'opt', 'old'],
  ['rules+new', 'rules', 'new'],
];

const $ = (id) => document.getElementById(id);
const status = (s) => { $('status').textContent = s; };
const frame = () => new Promise((r) => setTimeout(r, 0));

function median(v) {
  const s = [...v].sort((a, b) => a - b);
  return s[Math.floor(s.length / 2)];
}

function addRow(r) {
  const tr = document.createElement('tr');
  for (const v of [r.name, r.hilbert ? 'Hilbert' : 'file', r.ns_per_visit.toFixed(1), r.visits]) {
    const td = document.createElement('td');
    td.textContent = String(v);
    tr.appendChild(td);
  }
  $('results').querySelector('tbody').appendChild(tr);
  $('results').hidden = false;
}

async function run(nodes, reps) {
  $('run').disabled = true;
  $('results').querySelector('tbody').replaceChildren();
  const result = { nodes, seed: SEED, reps, browser: navigator.userAgent, passes: [] };
  try {
    for (const hilbert of [false, true]) {
      status(`generating ${nodes} nodes (${hilbert ? 'Hilbert order' : 'file order'})…`);
      await frame();
      const mesh = new BenchMesh(nodes, SEED, hilbert);
      result.nodes = mesh.nodeCount();
      for (const [name, strategy, objective] of PASSES) {
        status(`${name}, ${hilbert ? 'Hilbert order' : 'file order'}…`);
        await frame();
        const times = [];
        let visits = 0;
        for (let i = 0; i < reps; i++) {
          mesh.reset();
          const t0 = performance.now();
          visits = mesh.sweep(strategy, objective);
          const t1 = performance.now();
          times.push(((t1 - t0) * 1e6) / Math.max(visits, 1));
        }
        const row = { name, hilbert, ns_per_visit: median(times), visits };
        result.passes.push(row);
        addRow(row);
      }
      mesh.free();
    }
    status('done');
    window.benchResult = result;
  } catch (e) {
    status(`failed: ${e}`);
    window.benchResult = { error: String(e) };
  } finally {
    $('run').disabled = false;
  }
}

await init();
const params = new URLSearchParams(location.search);
if (params.has('nodes')) $('nodes').value = params.get('nodes');
if (params.has('reps')) $('reps').value = params.get('reps');
$('run').addEventListener('click', () => run(Number($('nodes').value), Number($('reps').value)));
status('ready');
if (params.get('auto') === '1') run(Number($('nodes').value), Number($('reps').value));

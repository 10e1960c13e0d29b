// Smoothing: Step, Run and Stop in slices the page can interrupt; Reset and Perturb.
import { $, SLICE_MS, clearError, engine, metrics, nextFrame, now, report, serial, setStatus, showError, state } from './state.js';
import { readSettings } from './controls.js';
import { writePermalink } from './permalink.js';
import { endRun } from './loading.js';
import { readyHelper, stopHelper } from './workers.js';
import { redrawAll, redrawCharts, redrawMeshes, redrawNode } from './draw.js';

export const SIDE_NAME = { a: 'A', b: 'B' };
export const STAGE_NAME = { plan: 'ordering the nodes', smooth: 'smoothing', measure: 'measuring', wait: 'waiting for the other worker' };

/**
 * One pass on both sides, in slices of SLICE_MS in the worker so the progress bar moves
 * during the pass and Stop is heard within a slice. Returns the pass records, or null
 * when stopped (the worker then puts both meshes back as they were before the pass).
 * `i` and `n` place the pass in its run for the progress bar.
 */
export async function smoothPass(i, n) {
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
    setStatus(`Pass ${i + 1} of ${n}: ordering the nodes of side A, worst first…`);
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
 * One pass split between the two workers (see SPLIT_MIN_NODES): the second sweeps side
 * A from this worker's positions while this one smooths side B, then takes
 * side A's sweep over and measures it. As smoothPass; `undefined` when the second worker
 * failed (it is dropped, the pass undone, and the caller runs it in one worker).
 */
export async function splitPass(i, n, call, cost, second) {
  const settings = readSettings();
  const nodes = await call('positions', 'a');
  // measured against the input: the mesh as this worker holds it (perturbed, maybe), not
  // as the second worker loaded it
  const target = settings.target === 'ideal' ? null : await call('targetPositions', settings);
  // …and judged as this worker's run, from where it began, side A's boundary sliding as
  // it slides here (null while it is held)
  const start = await call('runStart');
  const slide = await call('slideState', 'a');
  let swept = null; // the second worker's result, once it has it
  let failed = null;
  let aFraction = 0;
  // settles when the second worker is done, stopped or failed (never rejects)
  const sweeping = (async () => {
    let p = await second.call('sweep', settings, 'a', nodes, target, start, slide, SLICE_MS);
    while (!p.done) {
      aFraction = p.fraction;
      if (state.cancel) {
        await second.call('abortPass');
        return;
      }
      p = await second.call('continueSweep', SLICE_MS);
    }
    aFraction = 1;
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
      await call('adoptSweep', swept.nodes, swept.sweep, swept.segments, swept.params);
      adopted = true;
    }
    // side B is the first half of this worker's pass, side A's statistics the
    // last twentieth of its second half; side A's sweep is the second worker's
    const bPart = Math.min(1, 2 * p.fraction);
    const aPart = 0.9 * aFraction + Math.max(0, 2 * p.fraction - 1.9);
    $('progress').value = i + (p.done ? 1 : Math.min(1, (bPart + aPart) / 2));
    if (p.done) return { records: p.records, slices, workers: 2, ...cost };
    setStatus(`Pass ${i + 1} of ${n}, in two workers: A side ${Math.floor(100 * aFraction)}%, B side ${Math.floor(100 * bPart)}%… (Stop undoes this pass)`);
    if (p.stage === 'wait' && !adopted) {
      // this worker is done with side B: wait for side A's sweep, a slice at a time
      await Promise.race([sweeping, new Promise((r) => setTimeout(r, SLICE_MS))]);
      continue;
    }
    p = await call('continuePass', SLICE_MS);
    slices += 1;
  }
}

export function setRunning(on) {
  state.running = on;
  $('run').textContent = on ? 'Stop' : 'Run';
  $('run').setAttribute('aria-pressed', on ? 'true' : 'false');
  $('step').disabled = on;
  $('smooth-node').disabled = on || state.node === null;
  if (on) $('undo').disabled = true;
}

/** Runs `n` passes, redrawing the meshes after each; the Run button stops it. */
/** Asks the run in progress to stop, and says so at once. */
export function requestStop() {
  state.cancel = true;
  setStatus('Stopping: the pass in progress is being undone…');
}

export async function smooth(n) {
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
export function refuseInvalid(ids) {
  const id = ids.find((i) => state.invalid.has(i) && !$(i).disabled);
  if (!id) return false;
  showError(`${state.invalid.get(id)} Correct it first.`);
  $('message').dataset.control = id;
  return true;
}

export function step() {
  if (!state.running && refuseInvalid(['maxiter'])) return;
  return smooth(1);
}

export function run() {
  if (state.running) {
    requestStop();
    return;
  }
  if (refuseInvalid(['passes', 'maxiter'])) return;
  return smooth(Number($('passes').value));
}

export function reset() {
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
export function edgeLengths(amount) {
  return `${amount} mean edge length${amount === 1 ? '' : 's'}`;
}

export function perturbWith(amount, seed, { keepHash = false } = {}) {
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

export function perturb() {
  if (refuseInvalid(['amount', 'seed'])) return;
  return perturbWith(Number($('amount').value), $('seed').value.trim());
}

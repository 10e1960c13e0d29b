// Undo of a node's move, Smooth this node, and the figure for slides.
import { $, clearError, engine, report, serial, setStatus, state } from './state.js';
import { canvasPixels, paint, redrawCharts, redrawMeshes, redrawNode } from './draw.js';
import { baseName, download } from './export.js';

/** The Undo button says what it would take back, or why it cannot. */
export async function refreshUndo() {
  const u = await engine.call('undoSummary');
  const b = $('undo');
  b.disabled = u.depth === 0 || state.running;
  b.textContent = u.depth ? `Undo move of node ${u.next}` : 'Undo move';
  b.title = u.depth
    ? `Put node ${u.next} back where it was before its last move, on both sides (Ctrl+Z); ${u.depth} move${u.depth === 1 ? '' : 's'} can be undone.`
    : state.surface
      ? 'Nothing to undo: a move (Smooth this node) can be taken back until the next pass, Reset or Perturb.'
      : 'Nothing to undo: a move (a drag or Smooth this node) can be taken back until the next pass, Reset or Perturb.';
}

export function undo() {
  if (state.running) return;
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
export function smoothThisNode() {
  if (state.running || state.node === null) return;
  return serial(async () => {
    const node = state.node;
    const lv = canvasPixels($('level-a'));
    const ch = canvasPixels($('solve-chart'));
    const r = await engine.call('smoothNode', lv.w, lv.h, ch.w, ch.h, lv.dpr);
    state.level = lv;
    paint($('level-a'), r.level_a, lv.w, lv.h);
    paint($('level-b'), r.level_b, lv.w, lv.h);
    paint($('solve-chart'), r.chart, ch.w, ch.h);
    const placed = state.volume ? '' : state.surface ? ' (put back on the surface)' : '';
    $('node-hint').textContent = `One solver call on each side moved node ${node} to its optimum${placed}; the pictures show that call. ${r.summary}`;
    await redrawMeshes();
    await redrawCharts();
    setStatus(`Node ${node} smoothed by one solver call on each side (Undo takes it back).`);
  }).catch(report);
}

/** The figure for slides, drawn by the core at the size and pixel ratio chosen. */
export function saveFigure() {
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

// The second worker, which sweeps one side of a pass of a large planar mesh.
import { Engine } from '../engine.js';
import { PARAMS, state } from './state.js';
import { sendSource } from './loading.js';

/** A planar mesh of SPLIT_MIN_NODES to SPLIT_MAX_NODES nodes is also loaded into a second
 * worker, which sweeps side A of each pass while the first worker smooths side B:
 * the two sides are independent, so on two cores a pass takes about the
 * longer side's time rather than both sides' (the same result, bit for bit: the core's
 * split pass, lab::pass). A smaller mesh is not worth a second copy of it; a larger one
 * would take the two workers' memory together past the page's 400 MiB
 * (docs/performance.md). `?workers=1` keeps one worker. */
export const SPLIT_MIN_NODES = 20000;
export const SPLIT_MAX_NODES = 500000;
export const helper = { engine: null, src: null, ok: false };

/** Loads `src` (just loaded, with `nodes` nodes) into the second worker, in the background;
 * passes use it once it is ready. Any other mesh stops it. */
export function startHelper(src, nodes) {
  stopHelper();
  if (!(nodes >= SPLIT_MIN_NODES && nodes <= SPLIT_MAX_NODES) || PARAMS.get('workers') === '1') return;
  const e = new Engine(() => stopHelper()); // a panic there: passes go on in one worker
  Object.assign(helper, { engine: e, src, ok: false });
  sendSource(src, (...a) => e.call(...a))
    .then(() => {
      if (helper.engine === e) helper.ok = true;
    })
    .catch(() => {
      if (helper.engine === e) stopHelper();
    });
}

export function stopHelper() {
  if (helper.engine) helper.engine.worker.terminate();
  Object.assign(helper, { engine: null, src: null, ok: false });
}

/** The second worker, when it holds the mesh on screen. */
export function readyHelper() {
  return helper.ok && helper.src === state.lastGood && !state.surface ? helper.engine : null;
}

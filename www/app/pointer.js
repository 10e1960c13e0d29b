// The pointer on the canvases: picking, dragging and nudging a node, zoom and pan, turning
// a 3D view (a click there picks a node, a drag turns it), the hover label.
import { $, EMBED, HOSTED, clearError, engine, queued, report, serial, setStatus, state } from './state.js';
import { writePermalink } from './permalink.js';
import { showNodeBadge, showTab } from './present.js';
import { redrawCharts, redrawMeshes, redrawNode } from './draw.js';
import { shownInverted } from './tables.js';


/** The pointer in CSS pixels of the last frame drawn (what the engine's view maps). */
export function toFrame(canvas, ev) {
  const r = canvas.getBoundingClientRect();
  const { w, h, dpr } = state.frame;
  return {
    x: ((ev.clientX - r.left) / r.width) * (w / dpr),
    y: ((ev.clientY - r.top) / r.height) * (h / dpr),
  };
}

/** Chooses the node whose star is highlighted and whose level sets are drawn. */
export function selectNode(node, { keepHash = false } = {}) {
  return serial(async () => {
    try {
      await engine.call('select', node);
    } catch (e) {
      $('node').value = state.node === null ? '' : String(state.node);
      throw e;
    }
    state.node = node;
    $('node').value = node === null ? '' : String(node);
    showNodeBadge();
    clearError();
    showPickNote(null);
    // the node's level sets are in the side column's Node tab, next to the meshes (in a
    // notebook's widget too)
    if (node !== null && (!EMBED || HOSTED)) showTab('node', { cue: true });
    await redrawMeshes();
    await redrawNode();
    if (!keepHash) await writePermalink();
  }).catch(report);
}

/** Says why a press chose no node (or clears that). */
export function showPickNote(text) {
  $('pick-note').hidden = !text;
  $('pick-note').textContent = text || '';
}

/** How far from a node a press still takes it, CSS pixels: a finger is wider than a mouse pointer. */
export function pickRadius(ev) {
  return ev.pointerType === 'touch' || ev.pointerType === 'pen' ? 24 : 14;
}

export function attachPointer(canvas) {
  // One gesture per press. The pick is asynchronous (the engine is in a worker), so the
  // button may be released, or the pointer moved, before it answers: the gesture keeps
  // what happened and finishes when both the pick and the release are in.
  let gesture = null;
  const finish = (g) => {
    if (g.node === null && g.moved) pumpPan(g);
    if (g.node === null || g.node === undefined) return;
    if (g.moved) pumpDrag(g, true);
    else selectNode(g.node);
  };
  const zoom = zoomer((at, f) => engine.call('zoomMeshes', at.x, at.y, f), redrawMeshesAndView);
  const touches = attachZoom(canvas, () => toFrame.bind(null, canvas), zoom, () => {
    if (gesture) gesture.cancelled = true; // a second finger: the press becomes a pinch
    gesture = null;
  });
  canvas.addEventListener('pointerdown', (ev) => {
    if (state.running || ev.button !== 0 || !state.frame.w || touches.size > 1) return;
    if (state.surface) {
      // a press soon after a click makes a double-click (fit the view), not two picks
      const second = clickPending.token !== null;
      clickPending.token = null;
      gesture = { orbit: true, second, start: { x: ev.clientX, y: ev.clientY }, last: { x: ev.clientX, y: ev.clientY }, moved: false };
      canvas.setPointerCapture(ev.pointerId);
      return;
    }
    const p = toFrame(canvas, ev);
    const g = { node: undefined, start: p, moved: false, up: false, busy: false, latest: null, final: false };
    gesture = g;
    canvas.setPointerCapture(ev.pointerId);
    serial(() => engine.call('pick', canvas.dataset.side, p.x, p.y, pickRadius(ev)))
      .then((pick) => {
        if (g.cancelled) return;
        g.node = pick.node === undefined ? null : pick.node;
        if (g.node === null && !g.moved) showPickNote(pick.message);
        if (g.up) finish(g);
        else if (g.moved && g.node !== null) pumpDrag(g);
        else if (g.moved) pumpPan(g);
      })
      .catch(report);
  });
  canvas.addEventListener('pointermove', (ev) => {
    const g = gesture;
    if (!g) {
      if (ev.pointerType === 'mouse' && !state.surface) hover(canvas, ev);
      return;
    }
    if (g.orbit) {
      // CSS pixels of the drag, as the camera takes them
      if (!g.moved && Math.hypot(ev.clientX - g.start.x, ev.clientY - g.start.y) < 3) return;
      g.moved = true;
      orbitBy(ev.clientX - g.last.x, ev.clientY - g.last.y);
      g.last = { x: ev.clientX, y: ev.clientY };
      return;
    }
    const p = toFrame(canvas, ev);
    if (!g.moved && Math.hypot(p.x - g.start.x, p.y - g.start.y) < 4) return;
    g.moved = true;
    g.latest = p;
    if (g.node === null) pumpPan(g);
    else if (g.node !== undefined) pumpDrag(g);
  });
  const end = (ev) => {
    const g = gesture;
    if (!g) return;
    gesture = null;
    g.up = true;
    if (canvas.hasPointerCapture(ev.pointerId)) canvas.releasePointerCapture(ev.pointerId);
    if (g.orbit) {
      // a press and release without motion is a click: it picks a node, as on a planar mesh
      if (!g.moved && !g.second && ev.type === 'pointerup') pickIn3d(canvas, ev);
      return;
    }
    if (g.moved) g.latest = toFrame(canvas, ev);
    if (g.node !== undefined) finish(g);
  };
  canvas.addEventListener('keydown', (ev) => {
    const step = { ArrowLeft: [-1, 0], ArrowRight: [1, 0], ArrowUp: [0, -1], ArrowDown: [0, 1] }[ev.key];
    if (!step || ev.ctrlKey || ev.metaKey || ev.altKey || state.surface) return;
    if (state.node === null && state.figure) return; // the tour's keys: the next figure
    ev.preventDefault(); // the page does not scroll under a moving node
    if (state.node === null || state.running) {
      showPickNote(state.node === null ? 'Choose a free node first (click it): the arrow keys move the chosen node.' : null);
      return;
    }
    const k = ev.shiftKey ? 10 : 1;
    const node = state.node;
    serial(async () => {
      await engine.call('nudge', canvas.dataset.side, step[0] * k, step[1] * k);
      await redrawMeshes();
      await redrawNode();
      setStatus(`Node ${node} moved ${k} px ${ev.key.replace('Arrow', '').toLowerCase()} on both sides (Ctrl+Z takes it back).`);
    }).catch(report);
  });
  canvas.addEventListener('pointerleave', () => {
    canvas.parentElement.querySelector('.hover-label').hidden = true;
  });
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
}

/** Turns both 3D views by a drag of `(dx, dy)` CSS pixels; turns that arrive while
 * the engine draws are added up and sent as one. The link keeps the camera. */
export const orbitPump = { dx: 0, dy: 0, busy: false };
export function orbitBy(dx, dy) {
  orbitPump.dx += dx;
  orbitPump.dy += dy;
  if (orbitPump.busy || (orbitPump.dx === 0 && orbitPump.dy === 0)) return;
  const [x, y] = [orbitPump.dx, orbitPump.dy];
  orbitPump.dx = 0;
  orbitPump.dy = 0;
  orbitPump.busy = true;
  serial(async () => {
    await engine.call('orbit', x, y);
    await redrawMeshesAndView();
  })
    .catch(report)
    .finally(() => {
      orbitPump.busy = false;
      orbitBy(0, 0);
    });
}

/** The meshes drawn again after the view changed; in 3D the link keeps the camera. */
async function redrawMeshesAndView() {
  await redrawMeshes();
  if (state.surface) await writePermalink();
}

/** A click on a 3D view waiting to be picked: it waits out a double-click's interval
 * (a second press, a double-click, fits the view instead). */
const clickPending = { token: null };
const DOUBLE_CLICK_MS = 250;

/** A click on a 3D view chooses the nearest node of the face drawn there (a surface's,
 * or a face of the cut or of the boundary of tetrahedra), or says why it chose none. */
export function pickIn3d(canvas, ev) {
  const p = toFrame(canvas, ev);
  const token = {};
  clickPending.token = token;
  serial(async () => {
    await new Promise((r) => setTimeout(r, DOUBLE_CLICK_MS));
    if (clickPending.token !== token) return null; // a double-click
    clickPending.token = null;
    return engine.call('pick', canvas.dataset.side, p.x, p.y, pickRadius(ev));
  })
    .then((pick) => {
      if (!pick) return;
      if (pick.node === null || pick.node === undefined) showPickNote(pick.message);
      else selectNode(pick.node);
    })
    .catch(report);
}

/**
 * Whether the wheel zooms. In a notebook (the widget) a wheel over a mesh scrolls the
 * notebook, as every cell's output does, until the widget is clicked (armed till the
 * pointer leaves it or the frame loses focus); with Ctrl or ⌘ held (a trackpad's pinch
 * sends Ctrl) it zooms at once. On the page it always zooms.
 */
let wheelArmed = null;
function armWheel() {
  if (wheelArmed !== null) return; // wired once, when the first view is wired (not as this
  wheelArmed = !HOSTED; //           module loads: state.js has not finished then)
  if (HOSTED) {
    document.addEventListener('pointerdown', () => { wheelArmed = true; }, true);
    document.documentElement.addEventListener('pointerleave', () => { wheelArmed = false; });
    window.addEventListener('blur', () => { wheelArmed = false; });
  }
}

/**
 * Zooms by the mouse wheel, by a pinch of two fingers, and fits again on a double-click,
 * on `canvas` whose pointer positions `point()(ev)` gives in the engine's CSS pixels.
 * `onPinch` is told when a second finger lands. Returns the map of pointers down.
 */
export function attachZoom(canvas, point, zoom, onPinch = () => {}) {
  armWheel();
  const down = new Map();
  let pinch = 0;
  const spread = () => {
    const [a, b] = [...down.values()];
    return { d: Math.hypot(a.x - b.x, a.y - b.y), mid: { x: (a.x + b.x) / 2, y: (a.y + b.y) / 2 } };
  };
  canvas.addEventListener('wheel', (ev) => {
    if (!wheelArmed && !ev.ctrlKey && !ev.metaKey) return; // the notebook scrolls
    if (state.running) return;
    ev.preventDefault();
    zoom(point()(ev), Math.exp(-ev.deltaY * (ev.deltaMode === 1 ? 0.05 : 0.0015)));
  }, { passive: false });
  canvas.addEventListener('pointerdown', (ev) => {
    down.set(ev.pointerId, point()(ev));
    if (down.size === 2) {
      onPinch();
      pinch = spread().d;
    }
  });
  canvas.addEventListener('pointermove', (ev) => {
    if (!down.has(ev.pointerId)) return;
    down.set(ev.pointerId, point()(ev));
    if (down.size !== 2 || !pinch || state.running) return;
    const { d, mid } = spread();
    if (d > 0 && Math.abs(d / pinch - 1) > 0.02) {
      zoom(mid, d / pinch);
      pinch = d;
    }
  });
  const up = (ev) => {
    down.delete(ev.pointerId);
    if (down.size < 2) pinch = 0;
  };
  canvas.addEventListener('pointerup', up);
  canvas.addEventListener('pointercancel', up);
  canvas.addEventListener('dblclick', () => {
    if (state.running) return;
    serial(async () => {
      await engine.call('resetZoom');
      await redrawMeshes();
      await redrawNode();
      if (state.surface) await writePermalink();
    }).catch(report);
  });
  return down;
}

/** A zoom that asks the engine once at a time: factors that arrive meanwhile multiply. */
export function zoomer(call, redraw) {
  const acc = { factor: 1, at: null, busy: false };
  const go = (at, factor) => {
    acc.factor *= factor;
    acc.at = at;
    if (acc.busy) return;
    const f = acc.factor;
    acc.factor = 1;
    acc.busy = true;
    serial(async () => {
      await call(at, f);
      await redraw();
    })
      .catch(report)
      .finally(() => {
        acc.busy = false;
        if (acc.factor !== 1) go(acc.at, 1);
      });
  };
  return go;
}

/** Moves a picture by the pointer's way since the last move sent (`call(dx, dy)`);
 * moves that arrive meanwhile are coalesced. */
export function panner(call, redraw) {
  const go = (g) => {
    if (g.panBusy || !g.latest || g.latest === g.panFrom) return;
    const from = g.panFrom || g.start;
    const to = g.latest;
    g.panFrom = to;
    g.panBusy = true;
    showPickNote(null);
    serial(async () => {
      await call(to.x - from.x, to.y - from.y);
      await redraw();
    })
      .catch(report)
      .finally(() => {
        g.panBusy = false;
        go(g);
      });
  };
  return go;
}
export const pumpPan = panner((dx, dy) => engine.call('panMeshes', dx, dy), redrawMeshes);

/** Zoom and pan on a level-set canvas (`panel` a or b); both level sets follow. */
export function attachLevelZoom(canvas, panel) {
  const point = () => (ev) => {
    const r = canvas.getBoundingClientRect();
    const { w, h, dpr } = state.level || { w: r.width, h: r.height, dpr: 1 };
    return { x: ((ev.clientX - r.left) / r.width) * (w / dpr), y: ((ev.clientY - r.top) / r.height) * (h / dpr) };
  };
  let g = null;
  const ready = () => state.node !== null && state.level && !state.running;
  const zoom = zoomer((at, f) => engine.call('zoomLevelSets', panel, at.x, at.y, f), redrawNode);
  const touches = attachZoom(canvas, point, (at, f) => ready() && zoom(at, f), () => {
    g = null;
  });
  const pan = panner((dx, dy) => engine.call('panLevelSets', panel, dx, dy), redrawNode);
  canvas.addEventListener('pointerdown', (ev) => {
    if (!ready() || ev.button !== 0 || touches.size > 1) return;
    canvas.setPointerCapture(ev.pointerId);
    g = { start: point()(ev), latest: null };
  });
  canvas.addEventListener('pointermove', (ev) => {
    if (!g) return;
    g.latest = point()(ev);
    pan(g);
  });
  const end = () => {
    g = null;
  };
  canvas.addEventListener('pointerup', end);
  canvas.addEventListener('pointercancel', end);
}

/** Shows the number of the node under the mouse (one question to the engine at a time;
 * none while it is busy). */
export let hovering = false;
export function hover(canvas, ev) {
  const label = canvas.parentElement.querySelector('.hover-label');
  if (hovering || queued > 0 || state.running || !state.frame.w) return;
  hovering = true;
  const p = toFrame(canvas, ev);
  const r = canvas.getBoundingClientRect();
  const at = { x: ev.clientX - r.left, y: ev.clientY - r.top };
  engine
    .call('pick', canvas.dataset.side, p.x, p.y, pickRadius(ev))
    .then((pick) => {
      if (pick.nearest === null || pick.nearest === undefined) {
        label.hidden = true;
        return;
      }
      label.textContent = pick.node !== null && pick.node !== undefined ? `node ${pick.nearest}` : `node ${pick.nearest} (${pick.message.includes('mid-side') ? 'mid-side' : 'fixed'})`;
      label.style.left = `${Math.round(at.x + 12)}px`;
      label.style.top = `${Math.round(at.y - 8)}px`;
      label.hidden = false;
    })
    .catch(() => {})
    .finally(() => {
      hovering = false;
    });
}

/** Sends the latest drag position; positions that arrive meanwhile are coalesced. */
/** What a drag did, from the tables before and after it: the node moved and each side's
 * inverted elements. */
function dragWords(node, before, after) {
  const side = (i) => (before[i] === after[i] ? `${after[i]}` : `${before[i]} → ${after[i]}`);
  return `Dragged node ${node} on both sides: inverted elements A ${side(0)}, B ${side(1)} (Ctrl+Z takes it back).`;
}

export function pumpDrag(d, final = false) {
  if (d.busy) {
    d.final = d.final || final;
    return;
  }
  const p = d.latest;
  if (!p) return;
  d.latest = null;
  d.busy = true;
  serial(async () => {
    if (!d.remembered) {
      d.remembered = true; // undo takes the whole drag back
      d.invertedBefore = ['a', 'b'].map(shownInverted);
      await engine.call('rememberBeforeMove', d.node);
    }
    await engine.call('drag', d.node, p.x, p.y);
    if (final || d.final) {
      await engine.call('select', d.node);
      state.node = d.node;
      $('node').value = String(d.node);
    }
    await redrawMeshes();
    if (final || d.final) {
      await redrawCharts();
      await redrawNode();
      await writePermalink();
      setStatus(dragWords(d.node, d.invertedBefore, ['a', 'b'].map(shownInverted)));
    }
  })
    .catch(report)
    .finally(() => {
      d.busy = false;
      if (d.latest) pumpDrag(d, d.final);
    });
}

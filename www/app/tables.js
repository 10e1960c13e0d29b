// The statistics tables of the two panels, the better side of each row marked.
import { $, EMBED, state } from './state.js';

/** The table's rows: key, label, value, and which way is better (`higher`, `lower`, or
 * none): the better of the two sides is marked. `detail` rows need every corner measured
 * (large meshes: after the run). */
export const STAT_ROWS = [
  ['nodes', 'Nodes', (s) => s.nodes],
  ['elements', 'Elements', (s) => s.elements],
  ['inverted', 'Inverted elements', (s) => s.inverted, 'lower'],
  ['min_angle', 'Min angle', (s) => s.min_angle_deg, 'higher', deg],
  ['max_angle', 'Max angle', (s) => s.max_angle_deg, 'lower', deg],
  ['min_quality', 'Min quality (α/β)', (s) => s.min_quality, 'higher', num],
  ['mean_quality', 'Mean quality (α/β)', (s) => s.detail && s.detail.mean_quality, 'higher', num, true],
  ['small_angles', 'Angles under 18°', (s) => s.detail && s.detail.small_angle_share, 'lower', pct, true],
  ['max_condition', 'Worst κ (condition number)', (s) => s.detail && (s.detail.max_condition ?? Infinity), 'lower', kappa, true],
  ['surface_distance', 'Largest distance from the surface', (s) => s.max_distance_from_surface, 'lower', (v) => v.toExponential(2), false, true],
  ['boundary_sliding', 'Boundary nodes sliding', (s) => s.boundary && s.boundary.surface_nodes + s.boundary.curve_nodes, null, String, false, true],
  ['boundary_distance', 'Largest distance from the boundary', (s) => s.boundary && s.boundary.max_distance, 'lower', (v) => v.toExponential(2), false, true],
  ['laplacian_moves', 'Laplacian moves', (s) => s.laplacian_moves],
  ['optimization_calls', 'Optimization calls', (s) => s.optimization_calls],
  ['passes', 'Passes', (s) => s.passes],
  ['time', 'Smoothing time', (s) => s.time_ms, null, (v) => `${num(v, 1)} ms`],
];
/** A volume mesh's tooltips for the rows whose meaning changes in 3D (tetrahedra,
 * hexahedra, wedges and pyramids alike: each measured at its corners, Knupp's view). */
export const VOLUME_HELP = {
  inverted: 'Elements inverted somewhere: a tetrahedron of negative volume; a hexahedron, wedge or pyramid whose Jacobian determinant is zero or negative anywhere inside, decided for certain (a hexahedron can be inverted inside with its eight corners positive). A tangled mesh. Fewer is better.',
  min_angle: 'The smallest dihedral angle (the angle between two faces) of any tetrahedron, or at the edges of any corner of the other kinds. Larger is better.',
  max_angle: 'The largest dihedral angle, as the smallest. Smaller is better.',
  min_quality: "The worst mean ratio of an element (a tetrahedron's, the mean over the corners of the other kinds; 1 for the regular tetrahedron or the cube, below 0 inverted). Larger is better.",
  mean_quality: 'The mean of the mean ratio over the elements.',
  small_angles: "The share of dihedral angles under 18° (Freitag's Fig. 3 view).",
  max_condition: "The worst condition number κ = ‖T‖‖T⁻¹‖ (Frobenius norms) of an element's corner Jacobian T, weighted by its kind's ideal corner (Knupp; the regular tetrahedron's, the cube's): 3 at best, growing without bound as the element degenerates, ∞ when it is inverted. Smaller is better.",
};
/** A volume mesh's names for the rows whose meaning changes in 3D. */
export const VOLUME_LABELS = {
  min_angle: 'Min dihedral angle',
  max_angle: 'Max dihedral angle',
  min_quality: 'Min mean ratio',
  mean_quality: 'Mean of the mean ratio',
  small_angles: 'Dihedral angles under 18°',
};
/** A volume mesh's rows whose value can stay positive while elements are inverted, as
 * labelled and explained where it does: an element's mean ratio is the mean of its
 * corners', so a hexahedron, wedge or pyramid with a corner or its inside inverted can
 * keep a positive one (the inverted row's count is the certain test). */
export const VOLUME_BESIDE_INVERTED = {
  min_quality: [
    'Min mean ratio (corners averaged)',
    "Positive though elements are inverted: an element's mean ratio is the mean over its corners (a tetrahedron's its own), so a hexahedron, wedge or pyramid with an inverted corner among good ones, or inverted inside with every corner positive, keeps a positive one. The inverted row counts them for certain. Larger is better.",
  ],
};
/** What a table row means, as its tooltip. */
export const ROW_HELP = {
  inverted: 'Elements whose corners run the wrong way round (negative area): a tangled mesh. Fewer is better.',
  min_angle: 'The smallest corner angle of any element (negative in an inverted element). Larger is better.',
  max_angle: 'The largest corner angle of any element. Smaller is better.',
  min_quality: "The worst element quality: Lo's α for triangles, Canann's β for quads (1 ideal, below 0 inverted).",
  mean_quality: 'The mean element quality (α for triangles, β for quads).',
  small_angles: "The share of corner angles under 18° (Freitag's Fig. 3 view).",
  max_condition: "The worst condition number κ = ‖T‖‖T⁻¹‖ (Frobenius norms) of an element's corner Jacobian T, weighted by the ideal element (Knupp): 2 at best (a corner of an equilateral triangle or a square), growing without bound as the element degenerates, ∞ when it is inverted. Smaller is better.",
  boundary_sliding: 'A mesh whose boundary slides: its boundary nodes that slide, along a feature curve (a surface\'s open edges too) or on a volume\'s boundary between the curves (the corners where curves meet stay).',
  boundary_distance: "A mesh whose boundary slides: how far the sliding node farthest from the boundary as loaded is from it, in the mesh's units (a node moves in its tangent plane or along its curve, then is put back on the boundary).",
  surface_distance: 'A surface only: how far the node farthest from the surface it lies on is from it, in the mesh\'s units (nodes are moved in their tangent plane, then put back on the surface).',
  laplacian_moves: 'Nodes moved by a (plain or smart) Laplacian step, over the passes.',
  optimization_calls: 'Calls to the solver, over the passes.',
};
export function deg(v) {
  return Number.isFinite(v) ? `${v.toFixed(2)}°` : '—';
}
export function num(v, digits = 4) {
  return typeof v === 'number' && Number.isFinite(v) ? v.toFixed(digits) : '—';
}
export function pct(v) {
  return `${(100 * v).toFixed(v > 0 && v < 0.001 ? 3 : 1)}%`;
}
export function kappa(v) {
  return v === Infinity ? '∞ (inverted)' : num(v, 3);
}
/** Which side's value is better (0 = A, 1 = B), or null for a tie or no direction. */
export function betterSide(dir, a, b) {
  if (!dir || typeof a !== 'number' || typeof b !== 'number' || Number.isNaN(a) || Number.isNaN(b) || a === b) return null;
  return (dir === 'higher') === (a > b) ? 0 : 1;
}
/** Fills both tables side by side, marking the better value of each row where the two
 * values as shown differ (90.00° beside 90.00° is a tie to the reader, whatever the
 * digits not shown). */
export function fillTables(stats) {
  const pair = [stats.a, stats.b];
  fillLesson(pair);
  for (const [i, side] of ['a', 'b'].entries()) {
    const s = pair[i];
    $(`title-${side}`).textContent = EMBED ? s.label : s.title;
    const body = $(`stats-${side}`).tBodies[0];
    body.replaceChildren();
    for (const [key, label, get, dir, fmt = String, detail, surfaceOnly] of STAT_ROWS) {
      const v = get(s);
      if (surfaceOnly && (v === null || v === undefined)) continue;
      const tr = document.createElement('tr');
      tr.dataset.stat = key;
      const th = document.createElement('th');
      th.scope = 'row';
      th.textContent = (state.volume && VOLUME_LABELS[key]) || label;
      let help = (state.volume && VOLUME_HELP[key]) || ROW_HELP[key];
      // a value that stays positive beside inverted elements says why
      const beside = state.volume && VOLUME_BESIDE_INVERTED[key];
      if (beside && s.inverted > 0 && !(detail && !s.detail) && v > 0) [th.textContent, help] = beside;
      if (help) th.title = help;
      const td = document.createElement('td');
      if (detail && !s.detail) {
        td.textContent = 'after the run';
        td.classList.add('pending');
        td.title = 'This mesh is large: this row is measured when the charts are drawn, after a run.';
      } else {
        td.textContent = fmt(v);
        td.dataset.value = String(v);
        // a row of one side only (a planar mesh's boundary slides on the side a pass left
        // valid first) marks neither
        const alone = surfaceOnly && pair.some((p) => get(p) === null || get(p) === undefined);
        const shown = pair.map((p) => (detail && !p.detail) || alone ? null : fmt(get(p)));
        if (!alone && shown[0] !== shown[1] && betterSide(dir, get(pair[0]), get(pair[1])) === i) {
          td.classList.add('better'); // marked ✓ by the style sheet
          td.setAttribute('aria-label', `${td.textContent}, the better of the two`);
          td.title = 'the better of the two sides';
        }
      }
      tr.append(th, td);
      body.append(tr);
    }
  }
}

/** The count of inverted elements side `side` ('a' or 'b') shows in its table, or null. */
export function shownInverted(side) {
  const td = document.querySelector(`#stats-${side} tr[data-stat="inverted"] td`);
  return td && td.dataset.value !== undefined ? Number(td.dataset.value) : null;
}

/** How many of a side's elements are inverted, in words. */
function invertedWords(s) {
  return s.inverted === 0 ? 'no element' : `${s.inverted} of ${s.elements} elements`;
}
/** The line above the meshes: what the passes so far did on each side, from the tables'
 * own numbers (before a pass: how tangled the mesh is, and what Step does). */
function fillLesson([a, b]) {
  const line = $('lesson');
  const passes = a.passes === b.passes ? a.passes : null;
  line.dataset.passes = String(Math.max(a.passes, b.passes));
  if (passes === 0 && a.inverted === b.inverted) {
    const now = a.inverted > 0 ? `${a.inverted} of ${a.elements} elements are inverted on both sides.` : 'No element is inverted.';
    line.textContent = `${now} Press Step: one pass on both sides, A and B.`;
    return;
  }
  // each side by its objective's name, the first word of its label ("A: old (max-min α/β)")
  const name = (s) => s.label.replace(/^[AB]: /, '').split(/[ ,(]/)[0];
  const when = passes === 0 ? 'Before any pass' : passes === null ? 'After the passes' : `After ${passes} ${passes === 1 ? 'pass' : 'passes'}`;
  const verb = passes === 0 ? 'has' : 'leaves';
  line.textContent = `${when}: A (${name(a)}) ${verb} ${invertedWords(a)} inverted; B (${name(b)}) ${verb} ${invertedWords(b)} inverted.`;
}

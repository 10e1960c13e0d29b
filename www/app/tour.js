// The figures tour: one figure of the papers at a time, with its words and picture, and
// the playground in the figure's state.
import { $, EMBED, VIEWS, engine, now, showError, state, view } from './state.js';
import { applyHash, openHash, updatePermalink } from './permalink.js';
import { contentHeight, paint } from './draw.js';
import { smooth } from './run.js';

/** Opens a figure of the tour: its words, the playground in its state (sample, settings,
 * node; its passes run when the figure says so), its picture and, for Freitag's table,
 * the rows smoothed one by one. The address stays `#figure=NAME`. */
export async function openFigure(name) {
  let card;
  try {
    card = await engine.call('tourCard', name);
  } catch (e) {
    // an unknown name: the playground as it is (or the defaults, on a first load), and why
    if (!state.lastGood) await openHash(await applyHash('#'));
    showError(`This link names no figure of the tour: ${e.message}`);
    return;
  }
  state.figure = card;
  document.body.dataset.figure = '';
  document.body.dataset.figureRows = '0';
  // an embedded figure shows its own view, unless the address names one (`view=`)
  if (EMBED && (!view.spec || state.viewOfFigure) && Object.hasOwn(VIEWS, card.view)) {
    if (view.name) document.body.classList.remove(`view-${view.name}`);
    view.name = card.view;
    view.spec = VIEWS[card.view];
    state.viewOfFigure = true;
    document.body.classList.add('view', `view-${view.name}`);
  }
  showCard(card);
  const opened = await applyHash(`#${card.hash}`);
  // a surface or tetrahedra: the hash holds the settings, the card names the gallery's mesh
  if (card.gallery) opened.src = { kind: 'sample', name: card.gallery };
  await openHash(opened, { keepLink: true });
  const link = `#figure=${card.name}`;
  state.lastHash = link;
  history.replaceState(null, '', link);
  $('permalink').href = `${location.pathname}${link}`;
  if (EMBED) $('open-full').href = `${location.pathname}${link}`;
  await drawFigurePicture();
  if (card.run) await smooth(Number($('passes').value));
  if (card.rows) await fillTourTable(card);
  if (state.figure === card) document.body.dataset.figure = card.name;
}

export function showCard(card) {
  $('tour').hidden = false;
  $('tour-title').textContent = `${card.index + 1} of ${card.count}: ${card.source}`;
  $('tour-caption').textContent = card.caption;
  $('tour-look').textContent = card.look;
  $('tour-claim').textContent = card.claim;
  // the measured text's first sentence, its key numbers, stays where words give way
  $('tour-key').textContent = card.key;
  $('tour-rest').textContent = card.measured.slice(card.key.length);
  $('tour-menu').value = card.name;
  $('tour-prev').dataset.figure = card.prev;
  $('tour-next').dataset.figure = card.next;
  $('tour-link').href = `#figure=${card.name}`;
  $('tour-link').textContent = `Link to this figure (#figure=${card.name})`;
  $('tour-table').hidden = !card.rows;
  $('tour-rows').replaceChildren();
  // a table figure shows its table once: on the page the table filling live, in an embed
  // (where the table gives way) the picture the core draws of it
  $('tour-picture').hidden = Boolean(card.rows) && !EMBED;
  $('tour-table-caption').textContent = card.table_caption;
  $('tour-head').replaceChildren(...card.columns.map((text) => {
    const th = document.createElement('th');
    th.scope = 'col';
    th.textContent = text;
    return th;
  }));
}

/** The narrowest card a figure's picture is drawn in its own proportions, CSS pixels:
 * in a narrower one (a phone) the picture takes the card's width and the core keeps the
 * panels that fit there at full label size (lab::tour::pictures::arrangement). */
export const MIN_PAGE_PICTURE_W = 600;

/** The figure's own picture (the core draws it: `smoothlab render --figure NAME`). On the
 * page, in the picture's proportions, as wide as the tour's card (at most its own width)
 * and whole in the window under the bars; on a narrow card and in an embed, the room there
 * is (under the figure's words, in an embed), the core choosing the panels that fit (its
 * view shows instead once "Live view" is pressed). */
export async function drawFigurePicture() {
  const card = state.figure;
  if (!card) return;
  const canvas = $('tour-picture');
  if (canvas.hidden) return; // a table figure on the page: the table is its picture
  const [w0, h0] = await engine.call('tourPictureSize', card.name);
  if (state.figure !== card) return;
  const tour = $('tour');
  const inEmbed = EMBED && !document.body.classList.contains('live');
  if (EMBED && !inEmbed) return; // hidden behind the live view
  const probe = 40;
  canvas.style.width = `${probe}px`;
  canvas.style.height = `${probe}px`;
  const availW = Math.max(120, canvas.parentElement.clientWidth - 4);
  // the page: whole in the window below where it starts (the tour's bar and title above it)
  const top = canvas.getBoundingClientRect().top + window.scrollY;
  const availH = inEmbed
    ? Math.max(80, tour.clientHeight - (contentHeight(tour) - probe) - 2)
    : Math.max(240, window.innerHeight - Math.min(top, 200) - 16);
  let w;
  let h;
  if (inEmbed) {
    [w, h] = [Math.round(availW), Math.round(availH)];
  } else if (availW < Math.min(w0, MIN_PAGE_PICTURE_W)) {
    // a phone: the card's width, as high as leaves the claim and its key numbers (under
    // the picture, now probe high) on the first screen, at least 220 px
    const keyBottom = $('tour-key').getBoundingClientRect().bottom;
    const room = window.innerHeight - 8 - keyBottom + probe;
    [w, h] = [Math.round(availW), Math.round(Math.max(220, Math.min(availW * 1.2, room)))];
  } else {
    const scale = Math.min(availW / w0, availH / h0, 1);
    [w, h] = [Math.max(120, Math.round(w0 * scale)), Math.max(60, Math.round(h0 * scale))];
  }
  canvas.style.width = `${w}px`;
  canvas.style.height = `${h}px`;
  const dpr = Math.min(window.devicePixelRatio || 1, 2);
  const r = await engine.call('tourPicture', card.name, w, h, dpr);
  if (state.figure !== card) return;
  paint(canvas, r.pixels, r.w, r.h);
}

/** The pace of a live table, milliseconds a row: slow enough to follow each row as it
 * comes (a row whose smoothing takes longer comes when it is done). */
export const ROW_MS = 800;

/** Freitag's Tables 1 and 2: each row smoothed now in the worker (3 passes on seed 1),
 * then shown, one row at most every ROW_MS. An embed shows the picture instead. */
export async function fillTourTable(card) {
  if (EMBED) return;
  const body = $('tour-rows');
  let shown = -Infinity;
  for (let i = 0; i < card.rows; i++) {
    const r = await engine.call('tourTableRow', card.name, i);
    if (state.figure !== card) return;
    const wait = shown + ROW_MS - now();
    if (wait > 0) await new Promise((done) => setTimeout(done, wait));
    if (state.figure !== card) return;
    const tr = document.createElement('tr');
    for (const [k, text] of r.cells.entries()) {
      const td = document.createElement(k === 0 ? 'th' : 'td');
      if (k === 0) td.scope = 'row';
      td.textContent = text;
      tr.append(td);
    }
    body.append(tr);
    shown = now();
    document.body.dataset.figureRows = String(i + 1);
  }
}

export function goFigure(name) {
  if (!name) return;
  location.hash = `figure=${name}`; // hashchange opens it, and Back returns
}

export function closeTour() {
  state.figure = null;
  $('tour').hidden = true;
  delete document.body.dataset.figure;
  updatePermalink();
}

export async function fillTourMenu() {
  const list = await engine.call('tourFigures');
  for (const f of list) {
    const o = document.createElement('option');
    o.value = f.name;
    o.textContent = `${f.source} (${f.name})`;
    $('tour-menu').append(o);
  }
}

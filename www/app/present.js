// Presenting: the dark projector theme (the canvases' pictures follow it), fullscreen, the
// tour's keys, the side column's two parts (settings / one node) and, on a phone, the A/B
// switch.
import { $, EMBED, HOSTED, PARAMS, engine, report, serial, state } from './state.js';
import { redrawAll } from './draw.js';
import { drawFigurePicture, goFigure } from './tour.js';

/** The smallest label in a picture, in CSS px: readable from the back of a lecture hall. */
export const LABEL_PX = 14;
const THEME_KEY = 'smoothlab-theme';

/** The theme asked for: `?theme=` first, then the toggle's last choice, then the system's. */
function wantedTheme() {
  const asked = PARAMS.get('theme');
  if (asked === 'dark' || asked === 'light') return asked;
  let saved = null;
  try {
    saved = localStorage.getItem(THEME_KEY);
  } catch {
    /* storage may be refused in a sandboxed iframe */
  }
  if (saved === 'dark' || saved === 'light') return saved;
  return window.matchMedia('(prefers-color-scheme: dark)').matches ? 'dark' : 'light';
}

/** Whether the page is in the dark theme now. */
export function isDark() {
  return document.documentElement.dataset.theme === 'dark';
}

/** Sets the page's theme (CSS) and the engine's (the pictures); redraws unless told not to. */
export function setTheme(theme, { redraw = true, remember = false } = {}) {
  document.documentElement.dataset.theme = theme;
  const b = $('theme-toggle');
  b.setAttribute('aria-pressed', theme === 'dark' ? 'true' : 'false');
  b.textContent = theme === 'dark' ? 'Light' : 'Dark';
  b.title = theme === 'dark' ? 'Back to the light theme' : 'Dark projector theme (the pictures follow)';
  if (remember) {
    try {
      localStorage.setItem(THEME_KEY, theme);
    } catch {
      /* not kept: the toggle still works for this visit */
    }
  }
  state.theme = theme;
  if (!redraw) return Promise.resolve();
  return serial(async () => {
    await sendTheme();
    if (state.lastGood) await redrawAll();
  })
    .then(() => serial(drawFigurePicture))
    .catch(report);
}

/** Tells the engine the theme (it keeps it for every later picture, and across loads). */
export function sendTheme() {
  return engine.call('theme', isDark(), LABEL_PX);
}

/** The first theme, before anything is drawn. */
export function startTheme() {
  setTheme(wantedTheme(), { redraw: false });
  // the system's preference changing follows, unless the address or the toggle chose
  window.matchMedia('(prefers-color-scheme: dark)').addEventListener('change', (e) => {
    if (PARAMS.get('theme')) return;
    try {
      if (localStorage.getItem(THEME_KEY)) return;
    } catch {
      /* no storage: follow the system */
    }
    setTheme(e.matches ? 'dark' : 'light');
  });
}

// ---- fullscreen ------------------------------------------------------------------------
function toggleFullscreen() {
  if (document.fullscreenElement) return document.exitFullscreen().catch(() => {});
  const el = document.documentElement;
  if (!el.requestFullscreen) return Promise.resolve();
  return el.requestFullscreen().catch((e) => report(new Error(`Fullscreen was refused: ${e.message}`)));
}
function showFullscreen() {
  const on = Boolean(document.fullscreenElement);
  $('fullscreen').setAttribute('aria-pressed', on ? 'true' : 'false');
  $('fullscreen').textContent = on ? 'Leave fullscreen' : 'Fullscreen';
  document.body.classList.toggle('presenting', on);
}

// ---- the side column: settings, then one node ----------------------------------------------
/** Scrolls the side column to its part `name` ('settings' or 'node') and marks its button;
 * `cue` makes the part blink (a node was chosen on a mesh: its level sets are there). Only
 * the column scrolls: the meshes stay where they are, drawn smaller when the column widened
 * (returns whether it changed width: the caller redraws). */
export function showTab(name, { cue = false } = {}) {
  for (const t of ['settings', 'node']) $(`tabbtn-${t}`).setAttribute('aria-current', t === name ? 'true' : 'false');
  // the style sheet widens the column for a node's level sets, side by side
  const widthBefore = document.querySelector('.side').clientWidth;
  document.body.dataset.tab = name;
  const resized = document.querySelector('.side').clientWidth !== widthBefore;
  const side = document.querySelector('.side');
  const part = $(`tab-${name}`);
  if (side.scrollHeight > side.clientHeight) {
    const top = part.getBoundingClientRect().top - side.getBoundingClientRect().top + side.scrollTop - 40;
    side.scrollTo({ top: name === 'settings' ? 0 : Math.max(0, top), behavior: 'instant' });
  }
  if (cue) {
    for (const el of [part, $(`tabbtn-${name}`)]) {
      el.classList.remove('cue');
      void el.offsetWidth; // restart the animation
      el.classList.add('cue');
    }
  }
  return resized;
}

/** The badge on the Node tab: the chosen node's number. */
export function showNodeBadge() {
  $('node-badge').textContent = state.node === null ? '' : `${state.node}`;
}

// ---- the phone's A/B switch ------------------------------------------------------------------
function showPanel(letter) {
  document.body.dataset.show = letter;
  $('show-a').setAttribute('aria-pressed', letter === 'a' ? 'true' : 'false');
  $('show-b').setAttribute('aria-pressed', letter === 'b' ? 'true' : 'false');
}

// ---- keys -------------------------------------------------------------------------------------
/** Whether a key press belongs to what has the focus (typing in a field, a menu, a button's
 * Space), not to the page. */
function ownedByFocus(ev) {
  const t = ev.target;
  if (!(t instanceof HTMLElement)) return false;
  if (t.isContentEditable || t.matches('input, select, textarea')) return true;
  return ev.key === ' ' && t.matches('button, summary, a');
}

/** The presenter's keys: in the tour →, PageDown and Space go to the next figure, ←
 * and PageUp to the previous, Home to the first; F toggles fullscreen; Esc leaves it (or,
 * not in fullscreen, closes the tour). Ignored while typing in a field. */
function onKey(ev, closeTour) {
  if (ev.defaultPrevented || ev.ctrlKey || ev.metaKey || ev.altKey || ownedByFocus(ev)) return;
  const card = state.figure;
  const go = (name) => {
    ev.preventDefault();
    goFigure(name);
  };
  if (card) {
    if (['ArrowRight', 'PageDown', ' '].includes(ev.key)) return go(card.next);
    if (['ArrowLeft', 'PageUp'].includes(ev.key)) return go(card.prev);
    if (ev.key === 'Home') return go($('tour-menu').options[0].value);
  }
  if ((ev.key === 'f' || ev.key === 'F') && !ev.shiftKey && !EMBED) {
    ev.preventDefault();
    toggleFullscreen();
    return;
  }
  if (ev.key === 'Escape' && document.fullscreenElement) {
    // a browser leaves fullscreen on Esc by itself; where it passes the key on, so do we
    ev.preventDefault();
    document.exitFullscreen().catch(() => {});
  } else if (ev.key === 'Escape' && card && !EMBED) {
    closeTour();
  }
}

/** Wires the theme toggle, fullscreen, the tabs, the A/B switch and the keys. */
export function wirePresentation({ closeTour }) {
  $('theme-toggle').addEventListener('click', () => setTheme(isDark() ? 'light' : 'dark', { remember: true }));
  $('fullscreen').addEventListener('click', toggleFullscreen);
  document.addEventListener('fullscreenchange', showFullscreen);
  for (const t of ['settings', 'node']) {
    $(`tabbtn-${t}`).addEventListener('click', () => {
      // a notebook's widget shows one part of its column at a time: the one shown is drawn
      if (showTab(t) || HOSTED) serial(redrawAll).catch(report);
    });
  }
  showPanel('a');
  $('show-a').addEventListener('click', () => showPanel('a'));
  $('show-b').addEventListener('click', () => {
    const first = document.body.dataset.shownB !== '1';
    showPanel('b');
    document.body.dataset.shownB = '1';
    // B's canvas had no size while hidden: draw it at its size now
    if (first) serial(redrawAll).catch(report);
  });
  document.addEventListener('keydown', (ev) => onKey(ev, closeTour));
}

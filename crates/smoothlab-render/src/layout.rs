//! Where a picture put its plots, its legends and its marks, as the renderers drew them:
//! for a test (and the page's tests through the wasm layer) to check that no legend lies
//! over the data it explains, and that a mark a caption promises is drawn — from what was
//! drawn, not from a second computation of the layout.
//!
//! Recording is off unless a caller asks for it with [`record`]; the renderers then
//! `note` each plot rectangle, legend band and chart marker in device pixels of the
//! pixmap they draw into. A note carries the address of that pixmap's pixels, so a
//! picture made of several pixmaps ([`render_titled`](super::render_titled)) can tell
//! which part each note belongs to ([`Notes::of`]).

use std::cell::RefCell;

use serde::Serialize;
use tiny_skia::{Color, Pixmap};

/// What a rectangle or point of a picture is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum RegionKind {
    /// Where data is drawn: a chart's or histogram's axes box, a level set's field, a
    /// mesh's area (above its colour bar).
    Plot,
    /// A legend band or a colour bar.
    Legend,
    /// A chart marker (a one-pixel rectangle at its centre), with its colour.
    Mark,
    /// The box of a chart's label: a tick's value, or a value written beside a point.
    Label,
    /// The box of any text drawn upright, with its size and whether it was cut.
    Text,
}

/// One note: a rectangle of device pixels `x, y, w, h` of one pixmap.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Region {
    pub kind: RegionKind,
    pub x: f32,
    pub y: f32,
    pub w: f32,
    pub h: f32,
    /// A mark's colour, `[r, g, b]`; `None` for a rectangle.
    pub rgb: Option<[u8; 3]>,
    /// A text's font size, device pixels; `None` for anything else.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub size: Option<f32>,
    /// A text cut to its leading words and "…" to fit its room.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub cut: bool,
    #[serde(skip)]
    key: usize,
}

impl Region {
    /// Whether the insides of two rectangles meet (touching edges do not).
    pub fn overlaps(&self, o: &Region) -> bool {
        self.x < o.x + o.w && o.x < self.x + self.w && self.y < o.y + o.h && o.y < self.y + self.h
    }

    /// The region moved by `(dx, dy)` device pixels.
    pub fn shifted(mut self, dx: f32, dy: f32) -> Region {
        self.x += dx;
        self.y += dy;
        self
    }
}

/// The notes taken while [`record`] ran.
#[derive(Clone, Debug, Default)]
pub struct Notes(Vec<Region>);

impl Notes {
    /// The notes about `pixmap`, in the order they were taken.
    pub fn of(&self, pixmap: &Pixmap) -> Vec<Region> {
        let key = key(pixmap);
        self.0.iter().filter(|r| r.key == key).copied().collect()
    }
}

thread_local! {
    static NOTES: RefCell<Option<Vec<Region>>> = const { RefCell::new(None) };
}

fn key(pixmap: &Pixmap) -> usize {
    pixmap.data().as_ptr() as usize
}

/// Runs `f` with recording on and returns its result with the notes taken meanwhile
/// (recordings nest: an inner one takes its own notes, and the outer one gets them too).
pub fn record<T>(f: impl FnOnce() -> T) -> (T, Notes) {
    let outer = NOTES.with(|n| n.borrow_mut().replace(Vec::new()));
    let out = f();
    let mine = NOTES.with(|n| n.borrow_mut().take()).unwrap_or_default();
    if let Some(mut o) = outer {
        o.extend(mine.iter().copied());
        NOTES.with(|n| *n.borrow_mut() = Some(o));
    }
    (out, Notes(mine))
}

/// Notes a rectangle of `pixmap` (device pixels), when recording.
pub(crate) fn note(pixmap: &Pixmap, kind: RegionKind, x: f32, y: f32, w: f32, h: f32) {
    NOTES.with(|n| {
        if let Some(v) = n.borrow_mut().as_mut() {
            v.push(Region { kind, x, y, w, h, rgb: None, size: None, cut: false, key: key(pixmap) });
        }
    });
}

/// Notes again, for `to`, every note about `from` moved by `(dx, dy)` device pixels (a
/// part drawn into a larger picture), when recording.
pub(crate) fn adopt(from: &Pixmap, to: &Pixmap, dx: f32, dy: f32) {
    let (kf, kt) = (key(from), key(to));
    NOTES.with(|n| {
        if let Some(v) = n.borrow_mut().as_mut() {
            let moved: Vec<Region> = v.iter().filter(|r| r.key == kf).map(|r| Region { key: kt, ..r.shifted(dx, dy) }).collect();
            v.extend(moved);
        }
    });
}

/// Drops the notes about `pixmap` (a new picture at the address of one freed), when
/// recording.
pub fn forget(pixmap: &Pixmap) {
    let k = key(pixmap);
    NOTES.with(|n| {
        if let Some(v) = n.borrow_mut().as_mut() {
            v.retain(|r| r.key != k);
        }
    });
}

/// Notes the box of `text` drawn with `style` at `(x, y)` of `pixmap`, when recording.
pub(crate) fn note_label(pixmap: &Pixmap, text: &str, x: f32, y: f32, style: &super::text::TextStyle) {
    let [bx, by, w, h] = super::text::text_box(text, x, y, style);
    note(pixmap, RegionKind::Label, bx, by, w, h);
}

/// Notes the box of a text drawn upright with `style` at `(x, y)` of `pixmap`: its size,
/// and whether it ends in "…" (cut to fit), when recording.
pub(crate) fn note_text(pixmap: &Pixmap, text: &str, x: f32, y: f32, style: &super::text::TextStyle) {
    NOTES.with(|n| {
        if let Some(v) = n.borrow_mut().as_mut() {
            let [bx, by, w, h] = super::text::text_box(text, x, y, style);
            let cut = text.trim_end().ends_with('…');
            v.push(Region { kind: RegionKind::Text, x: bx, y: by, w, h, rgb: None, size: Some(style.size), cut, key: key(pixmap) });
        }
    });
}

/// Notes a marker of colour `c` centred at `(x, y)` of `pixmap` (device pixels), when
/// recording.
pub(crate) fn note_mark(pixmap: &Pixmap, x: f32, y: f32, c: Color) {
    NOTES.with(|n| {
        if let Some(v) = n.borrow_mut().as_mut() {
            let u = c.to_color_u8();
            v.push(Region { kind: RegionKind::Mark, x, y, w: 1.0, h: 1.0, rgb: Some([u.red(), u.green(), u.blue()]), size: None, cut: false, key: key(pixmap) });
        }
    });
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn notes_are_taken_only_while_recording_and_kept_per_pixmap() {
        let (a, b) = (Pixmap::new(4, 4).unwrap(), Pixmap::new(4, 4).unwrap());
        note(&a, RegionKind::Plot, 0.0, 0.0, 1.0, 1.0);
        let ((), notes) = record(|| {
            note(&a, RegionKind::Plot, 0.0, 0.0, 2.0, 2.0);
            let ((), inner) = record(|| note_mark(&b, 1.0, 1.0, Color::BLACK));
            assert_eq!(inner.of(&b).len(), 1);
            note(&b, RegionKind::Legend, 1.0, 1.0, 1.0, 1.0);
        });
        assert_eq!(notes.of(&a).len(), 1, "the note before recording is not kept");
        assert_eq!(notes.of(&b).iter().map(|r| r.kind).collect::<Vec<_>>(), [RegionKind::Mark, RegionKind::Legend]);
        let r = notes.of(&a)[0];
        assert!(r.overlaps(&r.shifted(1.0, 1.0)) && !r.overlaps(&r.shifted(2.0, 0.0)));
    }
}

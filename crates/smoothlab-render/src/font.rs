//! The labels' font: DejaVu Sans cut down to the characters the pictures label with
//! (`assets/fonts/README.md`), as tables that `build.rs` takes from the font file with
//! `ab_glyph`'s own reader. The crate carries these tables rather than the file and a
//! parser for it (in the wasm module, some 44 KB of `ttf-parser`'s code besides the file's
//! 25 KB); `ab_glyph` still scales and rasterizes the outlines, so the labels' pixels are
//! the same. A unit test compares every table with the font as `ab_glyph` reads it.
//!
//! The tables (`font-tables.rs` in the build's output), in font units:
//! - `ASCENT`, `DESCENT`: the font's ascender and descender;
//! - `CHARS`: (character, glyph) pairs in character order; a character not listed is
//!   glyph 0, the missing-glyph box;
//! - `ADVANCES[g]`: glyph `g`'s horizontal advance;
//! - `KERNING`: (`first << 16 | second`, the pair's kerning) in order, the pairs whose
//!   kerning is not 0;
//! - `BOUNDS[g]`: x min, y min, x max, y max of glyph `g`'s outline, all 0 where it has none;
//! - `CURVES[CURVE_STARTS[g]..CURVE_STARTS[g + 1]]`: the outline's curves in `ab_glyph`'s
//!   order, each a tag byte (0 a line, 1 a quadratic, 2 a cubic; plus 4 where its first
//!   point is written, as it does not start at the last point written, 0, 0 before the
//!   glyph's first) and its points (`Reader`).

use ab_glyph::{point, Glyph, GlyphId, Outline, OutlineCurve, OutlinedGlyph, Point, PxScaleFactor, Rect};

include!(concat!(env!("OUT_DIR"), "/font-tables.rs"));

/// The glyph of `c` (0, the missing-glyph box, for a character the font lacks).
pub(super) fn glyph_id(c: char) -> GlyphId {
    GlyphId(CHARS.binary_search_by_key(&c, |&(k, _)| k).map_or(0, |i| CHARS[i].1))
}

/// The font at `size` device pixels, as `ab_glyph::PxScaleFont` scales it: `size` is the
/// height from descender to ascender.
#[derive(Clone, Copy, Debug)]
pub(super) struct Scaled {
    factor: f32,
}

impl Scaled {
    pub(super) fn new(size: f32) -> Self {
        Scaled { factor: size / (ASCENT - DESCENT) }
    }
    pub(super) fn ascent(self) -> f32 {
        self.factor * ASCENT
    }
    pub(super) fn descent(self) -> f32 {
        self.factor * DESCENT
    }
    pub(super) fn h_advance(self, id: GlyphId) -> f32 {
        self.factor * ADVANCES.get(usize::from(id.0)).map_or(0.0, |&a| f32::from(a))
    }
    pub(super) fn kern(self, first: GlyphId, second: GlyphId) -> f32 {
        let pair = u32::from(first.0) << 16 | u32::from(second.0);
        self.factor * KERNING.binary_search_by_key(&pair, |&(p, _)| p).map_or(0.0, |i| f32::from(KERNING[i].1))
    }
}

/// `glyph`'s outline at its scale and position, ready to draw (`None` for a glyph
/// without one, such as the space).
pub(super) fn outline_glyph(glyph: Glyph) -> Option<OutlinedGlyph> {
    let outline = outline(glyph.id)?;
    let s = Scaled::new(glyph.scale.x);
    let v = Scaled::new(glyph.scale.y);
    Some(OutlinedGlyph::new(glyph, outline, PxScaleFactor { horizontal: s.factor, vertical: v.factor }))
}

/// Glyph `id`'s outline in font units, as `ab_glyph` reads it from the font file.
fn outline(id: GlyphId) -> Option<Outline> {
    let g = usize::from(id.0);
    let &[x_min, y_min, x_max, y_max] = BOUNDS.get(g)?;
    if x_min >= x_max || y_min >= y_max {
        return None;
    }
    let bounds = Rect { min: point(x_min.into(), y_max.into()), max: point(x_max.into(), y_min.into()) };
    let mut read = Reader { bytes: &CURVES[CURVE_STARTS[g] as usize..CURVE_STARTS[g + 1] as usize], last: [0; 2] };
    let mut curves = Vec::new();
    while let Some(tag) = read.byte() {
        // a curve not written from its start begins at the last point read (0, 0 before the
        // first)
        let start = if tag & 4 != 0 { read.point() } else { read.last_point() };
        curves.push(match tag & 3 {
            0 => OutlineCurve::Line(start, read.point()),
            1 => OutlineCurve::Quad(start, read.point(), read.point()),
            _ => OutlineCurve::Cubic(start, read.point(), read.point(), read.point()),
        });
    }
    Some(Outline { bounds, curves })
}

/// Reads one glyph's curves: tags, and points as the differences from the point before (the
/// glyph's first from 0, 0) in half font units, each zigzag-coded in groups of 7 bits
/// (`push_number` in `build.rs`).
struct Reader {
    bytes: &'static [u8],
    last: [i32; 2],
}

impl Reader {
    fn byte(&mut self) -> Option<u8> {
        let (&b, rest) = self.bytes.split_first()?;
        self.bytes = rest;
        Some(b)
    }

    fn number(&mut self) -> i32 {
        let (mut z, mut shift) = (0u32, 0);
        while let Some(b) = self.byte() {
            z |= u32::from(b & 0x7f) << shift;
            shift += 7;
            if b & 0x80 == 0 || shift > 28 {
                break;
            }
        }
        (z >> 1) as i32 ^ -((z & 1) as i32)
    }

    fn point(&mut self) -> Point {
        self.last[0] += self.number();
        self.last[1] += self.number();
        self.last_point()
    }

    fn last_point(&self) -> Point {
        point(self.last[0] as f32 * 0.5, self.last[1] as f32 * 0.5)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use ab_glyph::{Font, FontRef, PxScale, ScaleFont};

    /// The font file the tables were built from, read by `ab_glyph` as the labels read it
    /// before the tables.
    fn file() -> FontRef<'static> {
        FontRef::try_from_slice(include_bytes!("../../../assets/fonts/DejaVuSans-subset.ttf")).unwrap()
    }

    fn bits(p: Point) -> (u32, u32) {
        (p.x.to_bits(), p.y.to_bits())
    }

    fn curve_bits(c: &OutlineCurve) -> Vec<(u32, u32)> {
        match c {
            OutlineCurve::Line(a, b) => vec![bits(*a), bits(*b)],
            OutlineCurve::Quad(a, b, c) => vec![(0, 1), bits(*a), bits(*b), bits(*c)],
            OutlineCurve::Cubic(a, b, c, d) => vec![(0, 2), bits(*a), bits(*b), bits(*c), bits(*d)],
        }
    }

    #[test]
    fn the_tables_are_the_font_as_ab_glyph_reads_it() {
        let f = file();
        assert_eq!(ASCENT.to_bits(), f.ascent_unscaled().to_bits());
        assert_eq!(DESCENT.to_bits(), f.descent_unscaled().to_bits());
        // every character up to the last the font maps, and some beyond
        for c in ('\0'..='\u{3000}').chain(['\u{1F600}', '\u{10FFFF}']) {
            assert_eq!(glyph_id(c), f.glyph_id(c), "{c:?}");
        }
        let n = f.glyph_count();
        assert_eq!(ADVANCES.len(), n);
        for g in 0..n as u16 {
            let id = GlyphId(g);
            assert_eq!(f32::from(ADVANCES[g as usize]).to_bits(), f.h_advance_unscaled(id).to_bits(), "glyph {g}");
            let (ours, theirs) = (outline(id), f.outline(id));
            assert_eq!(ours.is_some(), theirs.is_some(), "glyph {g}");
            if let (Some(o), Some(t)) = (ours, theirs) {
                assert_eq!((bits(o.bounds.min), bits(o.bounds.max)), (bits(t.bounds.min), bits(t.bounds.max)), "glyph {g}");
                let cb = |v: &[OutlineCurve]| v.iter().map(curve_bits).collect::<Vec<_>>();
                assert_eq!(cb(&o.curves), cb(&t.curves), "glyph {g}");
            }
        }
        let scaled = Scaled::new(1.0);
        let theirs = f.as_scaled(PxScale::from(1.0));
        for a in 0..n as u16 {
            for b in 0..n as u16 {
                let (a, b) = (GlyphId(a), GlyphId(b));
                assert_eq!(scaled.kern(a, b).to_bits(), theirs.kern(a, b).to_bits(), "{a:?} {b:?}");
            }
        }
        assert!(KERNING.windows(2).all(|w| w[0].0 < w[1].0));
        assert!(CHARS.windows(2).all(|w| w[0].0 < w[1].0));
    }

    #[test]
    fn scaled_and_drawn_as_ab_glyph_does() {
        let f = file();
        for size in [0.0, 7.5, 12.0, 13.37, 40.0] {
            let (ours, theirs) = (Scaled::new(size), f.as_scaled(PxScale::from(size)));
            assert_eq!(ours.ascent().to_bits(), theirs.ascent().to_bits());
            assert_eq!(ours.descent().to_bits(), theirs.descent().to_bits());
            let mut caret = 0.3;
            for c in "Hg αβ≤∞→ Wa AV To é".chars() {
                let id = glyph_id(c);
                assert_eq!(ours.h_advance(id).to_bits(), theirs.h_advance(id).to_bits(), "{c:?} at {size}");
                let glyph = id.with_scale_and_position(size, point(caret, 17.25));
                caret += ours.h_advance(id);
                let (o, t) = (outline_glyph(glyph.clone()), f.outline_glyph(glyph));
                assert_eq!(o.is_some(), t.is_some(), "{c:?} at {size}");
                if let (Some(o), Some(t)) = (o, t) {
                    assert_eq!(o.px_bounds(), t.px_bounds(), "{c:?} at {size}");
                    let cover = |g: &OutlinedGlyph| {
                        let mut v = Vec::new();
                        g.draw(|x, y, c| v.push((x, y, c.to_bits())));
                        v
                    };
                    assert_eq!(cover(&o), cover(&t), "{c:?} at {size}");
                }
            }
        }
    }
}

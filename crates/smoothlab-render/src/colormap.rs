//! Colour maps for scalar fields, and the qualitative palette for series.
//!
//! Viridis (van der Walt & Smith, matplotlib 1.5) is perceptually uniform: its CIE
//! lightness L* rises monotonically from the dark end to the bright end, so the order of
//! values reads the same in colour, in grey and for most colour-blind readers.

use tiny_skia::Color;

/// A colour map from `t ∈ [0, 1]` to a colour.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Colormap {
    /// Viridis: dark purple (0) → blue → green → yellow (1). The default.
    #[default]
    Viridis,
    /// Linear grey ramp from dark grey (0) to near white (1), for print.
    Grey,
}

/// Viridis at `t = 0, 1/8, …, 1` (matplotlib's table sampled at nine points, 8-bit sRGB);
/// between anchors the map interpolates linearly in sRGB, which keeps L* monotone.
pub const VIRIDIS: [[u8; 3]; 9] = [
    [68, 1, 84],
    [71, 44, 122],
    [59, 81, 139],
    [44, 113, 142],
    [33, 144, 141],
    [39, 173, 129],
    [92, 200, 99],
    [170, 220, 50],
    [253, 231, 37],
];

impl Colormap {
    /// The colour at `t`, clamped to [0, 1]; a NaN `t` gives the low end.
    pub fn rgb(self, t: f64) -> [u8; 3] {
        let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
        match self {
            Colormap::Viridis => {
                let x = t * (VIRIDIS.len() - 1) as f64;
                let i = (x.floor() as usize).min(VIRIDIS.len() - 2);
                let f = x - i as f64;
                let (a, b) = (VIRIDIS[i], VIRIDIS[i + 1]);
                let mix = |k: usize| (a[k] as f64 + f * (b[k] as f64 - a[k] as f64)).round() as u8;
                [mix(0), mix(1), mix(2)]
            }
            Colormap::Grey => {
                let v = (40.0 + t * 205.0).round() as u8;
                [v, v, v]
            }
        }
    }
    /// The colour at `t` as an opaque tiny-skia colour.
    pub fn color(self, t: f64) -> Color {
        let [r, g, b] = self.rgb(t);
        Color::from_rgba8(r, g, b, 255)
    }
}

/// How many colours the mesh views use: a quality map is drawn in this many flat colours
/// (the page's fast raster and the CLI's vector renderer alike), `BUCKETS − 1` steps
/// from the bottom of the colour map to its top.
pub const BUCKETS: usize = 64;

/// The colour bucket of a value at `t` of the colour map's range (0 bottom, 1 top):
/// `round(clamp(t, 0, 1) × (BUCKETS − 1))`, and 0 for NaN. The one definition both mesh
/// renderers use.
#[inline]
pub fn bucket(t: f64) -> usize {
    // + 0.5 and a cast: `round` for these non-negative values, without a call
    let t = if t > 0.0 { t.min(1.0) } else { 0.0 };
    (t * (BUCKETS - 1) as f64 + 0.5) as usize
}

/// The colour map's colour for bucket `b` (see [`bucket`]).
pub fn bucket_color(colormap: Colormap, b: usize) -> tiny_skia::Color {
    colormap.color(b as f64 / (BUCKETS - 1) as f64)
}

/// CIE L* (0 = black, 100 = white) of an 8-bit sRGB colour, D65 white.
pub fn lightness(rgb: [u8; 3]) -> f64 {
    let lin = |c: u8| {
        let c = c as f64 / 255.0;
        if c <= 0.040_45 {
            c / 12.92
        } else {
            ((c + 0.055) / 1.055).powf(2.4)
        }
    };
    let y = 0.2126 * lin(rgb[0]) + 0.7152 * lin(rgb[1]) + 0.0722 * lin(rgb[2]);
    if y > 216.0 / 24389.0 {
        116.0 * y.cbrt() - 16.0
    } else {
        y * 24389.0 / 27.0
    }
}

/// The Okabe–Ito palette (colour-blind safe), in the order series take it.
pub const SERIES: [[u8; 3]; 7] = [
    [0, 0, 0],       // black
    [230, 159, 0],   // orange
    [0, 114, 178],   // blue
    [0, 158, 115],   // bluish green
    [213, 94, 0],    // vermillion
    [86, 180, 233],  // sky blue
    [204, 121, 167], // reddish purple
];

/// The colour of series `i` (cycling through [`SERIES`]).
pub fn series_color(i: usize) -> Color {
    let [r, g, b] = SERIES[i % SERIES.len()];
    Color::from_rgba8(r, g, b, 255)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn viridis_endpoints_and_middle() {
        assert_eq!(Colormap::Viridis.rgb(0.0), [68, 1, 84]);
        assert_eq!(Colormap::Viridis.rgb(1.0), [253, 231, 37]);
        assert_eq!(Colormap::Viridis.rgb(0.5), [33, 144, 141]);
        assert_eq!(Colormap::Viridis.rgb(-3.0), Colormap::Viridis.rgb(0.0));
        assert_eq!(Colormap::Viridis.rgb(7.0), Colormap::Viridis.rgb(1.0));
        assert_eq!(Colormap::Viridis.rgb(f64::NAN), Colormap::Viridis.rgb(0.0));
    }

    #[test]
    fn lightness_is_monotone() {
        for map in [Colormap::Viridis, Colormap::Grey] {
            let mut last = -1.0;
            for k in 0..=256 {
                let l = lightness(map.rgb(k as f64 / 256.0));
                assert!(l > last - 0.3, "{map:?}: L* falls at {k}: {l} after {last}");
                last = last.max(l);
            }
            let (lo, hi) = (lightness(map.rgb(0.0)), lightness(map.rgb(1.0)));
            assert!(hi - lo > 60.0, "{map:?} spans L* {lo}..{hi}");
        }
        assert!((lightness([255, 255, 255]) - 100.0).abs() < 1e-6);
        assert!(lightness([0, 0, 0]).abs() < 1e-9);
    }
}

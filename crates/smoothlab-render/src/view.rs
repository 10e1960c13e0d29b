//! From model coordinates to pixels and back: fit a box to a frame with a margin, then
//! zoom and pan, at a device-pixel ratio.
//!
//! Three coordinate systems appear: *world* (the mesh's own, y up), *CSS pixels* (what a
//! page's pointer events report, y down, origin at the pixmap's top left) and *device
//! pixels* (the pixmap's own, `CSS × dpr`). Frames, margins, zoom and pan are in CSS
//! pixels so a picture looks the same on every screen and is sharp on HiDPI ones.

use glam::DVec2;
use tiny_skia::Pixmap;

/// A rectangle in CSS pixels.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Frame {
    pub x: f32,
    pub y: f32,
    pub w: f32,
    pub h: f32,
}

impl Frame {
    pub fn new(x: f32, y: f32, w: f32, h: f32) -> Self {
        Frame { x, y, w: w.max(0.0), h: h.max(0.0) }
    }
    /// The whole pixmap, in CSS pixels at device-pixel ratio `dpr`.
    pub fn of_pixmap(pixmap: &Pixmap, dpr: f32) -> Self {
        let d = sane_dpr(dpr);
        Frame::new(0.0, 0.0, pixmap.width() as f32 / d, pixmap.height() as f32 / d)
    }
    /// The frame less `left`, `top`, `right`, `bottom` CSS pixels.
    pub fn inset(self, left: f32, top: f32, right: f32, bottom: f32) -> Self {
        Frame::new(self.x + left, self.y + top, self.w - left - right, self.h - top - bottom)
    }
    /// Column `i` of `n` equal columns separated by `gap`.
    pub fn column(self, i: usize, n: usize, gap: f32) -> Self {
        let n = n.max(1);
        let w = (self.w - gap * (n - 1) as f32) / n as f32;
        Frame::new(self.x + i as f32 * (w + gap), self.y, w, self.h)
    }
    /// Row `i` of `n` equal rows separated by `gap`.
    pub fn row(self, i: usize, n: usize, gap: f32) -> Self {
        let n = n.max(1);
        let h = (self.h - gap * (n - 1) as f32) / n as f32;
        Frame::new(self.x, self.y + i as f32 * (h + gap), self.w, h)
    }
    pub fn right(&self) -> f32 {
        self.x + self.w
    }
    pub fn bottom(&self) -> f32 {
        self.y + self.h
    }
    pub fn centre(&self) -> DVec2 {
        DVec2::new((self.x + 0.5 * self.w) as f64, (self.y + 0.5 * self.h) as f64)
    }
}

/// A device-pixel ratio that can be used: finite and within [0.25, 8], else 1.
pub fn sane_dpr(dpr: f32) -> f32 {
    if dpr.is_finite() && dpr > 0.0 {
        dpr.clamp(0.25, 8.0)
    } else {
        1.0
    }
}

/// The user's zoom and pan on top of the fitted view. Default: no zoom, no pan.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZoomPan {
    /// Magnification over the fitted scale (1 = fitted). Default 1.
    pub zoom: f64,
    /// Shift of the picture in CSS pixels (x right, y down). Default 0.
    pub pan: DVec2,
}

impl Default for ZoomPan {
    fn default() -> Self {
        ZoomPan { zoom: 1.0, pan: DVec2::ZERO }
    }
}

impl ZoomPan {
    /// Moved by `delta` CSS pixels (a drag).
    pub fn panned(self, delta: DVec2) -> Self {
        ZoomPan { pan: self.pan + delta, ..self }
    }
}

/// A fitted view: world ↔ CSS ↔ device pixels. Build it with [`View::fit`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct View {
    /// Centre of the fitted frame in CSS pixels.
    frame_centre: DVec2,
    /// World point drawn at the frame centre before panning.
    world_centre: DVec2,
    /// CSS pixels per world unit after the zoom.
    scale: f64,
    zoom_pan: ZoomPan,
    dpr: f64,
}

impl View {
    /// Fits the world box `lo..hi` into `frame` less `margin` CSS pixels on every side,
    /// keeping the aspect ratio, then applies `zoom_pan`. A degenerate or non-finite box
    /// is widened so the view is always usable.
    pub fn fit(lo: DVec2, hi: DVec2, frame: Frame, margin: f32, zoom_pan: ZoomPan, dpr: f32) -> View {
        let (mut lo, mut hi) = (lo.min(hi), lo.max(hi));
        if !lo.is_finite() || !hi.is_finite() {
            lo = DVec2::ZERO;
            hi = DVec2::ONE;
        }
        let mut size = hi - lo;
        let big = size.max_element();
        let pad = if big > 0.0 { big } else { lo.abs().max_element().max(1.0) };
        for k in 0..2 {
            if size[k] <= 1e-12 * pad {
                size[k] = pad;
            }
        }
        let avail_w = (frame.w - 2.0 * margin).max(1.0) as f64;
        let avail_h = (frame.h - 2.0 * margin).max(1.0) as f64;
        let fit = (avail_w / size.x).min(avail_h / size.y);
        let zoom = if zoom_pan.zoom.is_finite() && zoom_pan.zoom > 0.0 { zoom_pan.zoom.clamp(1e-6, 1e9) } else { 1.0 };
        let pan = if zoom_pan.pan.is_finite() { zoom_pan.pan } else { DVec2::ZERO };
        View {
            frame_centre: frame.centre(),
            world_centre: 0.5 * (lo + hi),
            scale: fit * zoom,
            zoom_pan: ZoomPan { zoom, pan },
            dpr: sane_dpr(dpr) as f64,
        }
    }
    /// CSS pixels per world unit.
    pub fn scale(&self) -> f64 {
        self.scale
    }
    /// Device pixels per world unit.
    pub fn device_scale(&self) -> f64 {
        self.scale * self.dpr
    }
    pub fn dpr(&self) -> f64 {
        self.dpr
    }
    pub fn zoom_pan(&self) -> ZoomPan {
        self.zoom_pan
    }
    /// World point → CSS pixel.
    pub fn to_css(&self, p: DVec2) -> DVec2 {
        let d = (p - self.world_centre) * self.scale;
        self.frame_centre + DVec2::new(d.x, -d.y) + self.zoom_pan.pan
    }
    /// World point → device pixel.
    pub fn to_device(&self, p: DVec2) -> DVec2 {
        self.to_css(p) * self.dpr
    }
    /// World point → device pixel as `f32`, for path building.
    pub fn device_xy(&self, p: DVec2) -> (f32, f32) {
        let d = self.to_device(p);
        (d.x as f32, d.y as f32)
    }
    /// CSS pixel → world point (the inverse of [`to_css`](Self::to_css)).
    pub fn css_to_world(&self, css: DVec2) -> DVec2 {
        let d = css - self.frame_centre - self.zoom_pan.pan;
        self.world_centre + DVec2::new(d.x, -d.y) / self.scale
    }
    /// Device pixel → world point.
    pub fn device_to_world(&self, px: DVec2) -> DVec2 {
        self.css_to_world(px / self.dpr)
    }
    /// The zoom and pan that magnify by `factor` while keeping the world point under the
    /// CSS pixel `cursor` where it is (mouse-wheel zoom). Non-positive factors are ignored.
    pub fn zoomed_at(&self, cursor: DVec2, factor: f64) -> ZoomPan {
        if !(factor.is_finite() && factor > 0.0 && cursor.is_finite()) {
            return self.zoom_pan;
        }
        let c = cursor - self.frame_centre;
        ZoomPan { zoom: self.zoom_pan.zoom * factor, pan: (1.0 - factor) * c + factor * self.zoom_pan.pan }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    #[test]
    fn fits_with_margin_and_flips_y() {
        let frame = Frame::new(0.0, 0.0, 200.0, 100.0);
        let v = View::fit(DVec2::new(0.0, 0.0), DVec2::new(4.0, 1.0), frame, 10.0, ZoomPan::default(), 2.0);
        // width-limited: 180 px / 4 units
        assert!((v.scale() - 45.0).abs() < 1e-12);
        let a = v.to_css(DVec2::new(0.0, 0.0));
        let b = v.to_css(DVec2::new(4.0, 1.0));
        assert!((a.x - 10.0).abs() < 1e-9 && (b.x - 190.0).abs() < 1e-9);
        assert!(b.y < a.y, "y is up in the world and down on screen");
        assert!((v.to_device(DVec2::new(4.0, 1.0)) - 2.0 * b).length() < 1e-9);
        // degenerate boxes still give a finite view
        let p = View::fit(DVec2::ONE, DVec2::ONE, frame, 10.0, ZoomPan::default(), 1.0);
        assert!(p.scale().is_finite() && p.scale() > 0.0);
        let q = View::fit(DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY), frame, 10.0, ZoomPan::default(), f32::NAN);
        assert!(q.scale().is_finite() && q.dpr() == 1.0);
    }

    #[test]
    fn zoom_keeps_the_point_under_the_cursor() {
        let frame = Frame::new(5.0, 7.0, 300.0, 200.0);
        let v = View::fit(DVec2::new(-1.0, -2.0), DVec2::new(3.0, 1.0), frame, 12.0, ZoomPan::default(), 1.5);
        let cursor = DVec2::new(40.0, 180.0);
        let w = v.css_to_world(cursor);
        let zp = v.zoomed_at(cursor, 2.5);
        let v2 = View::fit(DVec2::new(-1.0, -2.0), DVec2::new(3.0, 1.0), frame, 12.0, zp, 1.5);
        assert!((v2.css_to_world(cursor) - w).length() < 1e-9);
        assert!((v2.scale() / v.scale() - 2.5).abs() < 1e-12);
        let v3 = View::fit(DVec2::new(-1.0, -2.0), DVec2::new(3.0, 1.0), frame, 12.0, zp.panned(DVec2::new(10.0, 0.0)), 1.5);
        assert!((v3.to_css(w) - cursor - DVec2::new(10.0, 0.0)).length() < 1e-9);
    }

    proptest! {
        #[test]
        fn world_pixel_round_trip(
            x in -1e6f64..1e6, y in -1e6f64..1e6,
            lox in -1e3f64..1e3, loy in -1e3f64..1e3, sx in 1e-6f64..1e4, sy in 1e-6f64..1e4,
            zoom in 0.01f64..100.0, panx in -500f64..500.0, dpr in 0.5f32..4.0,
        ) {
            let frame = Frame::new(3.0, 4.0, 640.0, 480.0);
            let lo = DVec2::new(lox, loy);
            let v = View::fit(lo, lo + DVec2::new(sx, sy), frame, 16.0, ZoomPan { zoom, pan: DVec2::new(panx, -panx) }, dpr);
            let p = DVec2::new(x, y);
            let back = v.device_to_world(v.to_device(p));
            prop_assert!((back - p).length() <= 1e-9 * (1.0 + p.length() + lo.length()));
            let px = DVec2::new(x * 1e-3, y * 1e-3);
            let back = v.to_css(v.css_to_world(px));
            prop_assert!((back - px).length() <= 1e-6 * (1.0 + px.length()));
        }
    }
}

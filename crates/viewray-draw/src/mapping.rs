//! From world units (y up) to figure pixels (y down).

use glam::Vec2;

use crate::Rect;

/// A uniform-scale map from a world-space rectangle (y up) onto a canvas rectangle
/// (figure pixels, y down), so figure code can draw in world units.
///
/// The scale is the largest that fits the whole world rectangle inside the canvas
/// rectangle; the world rectangle is centred, so the canvas may show a margin of extra
/// world on two sides. Circles stay circles and angles stay angles.
///
/// ```text
/// s = min(canvas.width / world.width, canvas.height / world.height)
/// x_px = canvas.center.x + s (x - world.center.x)
/// y_px = canvas.center.y - s (y - world.center.y)
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Mapping {
    scale: f32,
    world_center: Vec2,
    canvas_center: Vec2,
}

impl Mapping {
    /// The map that fits `world` (y up) inside `canvas` (figure pixels), centred.
    ///
    /// Returns `None` when either rectangle has a width or height that is not positive
    /// and finite.
    pub fn fit(world: Rect, canvas: Rect) -> Option<Mapping> {
        let usable = |r: &Rect| {
            r.width().is_finite() && r.height().is_finite() && r.width() > 0.0 && r.height() > 0.0
        };
        if !usable(&world) || !usable(&canvas) {
            return None;
        }
        let scale = (canvas.width() / world.width()).min(canvas.height() / world.height());
        Some(Mapping {
            scale,
            world_center: world.center(),
            canvas_center: canvas.center(),
        })
    }

    /// Pixels per world unit.
    pub fn scale(&self) -> f32 {
        self.scale
    }

    /// The figure point (pixels, y down) of world point `p` (y up).
    pub fn to_canvas(&self, p: Vec2) -> Vec2 {
        let d = (p - self.world_center) * self.scale;
        self.canvas_center + Vec2::new(d.x, -d.y)
    }

    /// The world point (y up) shown at figure point `p` (pixels, y down).
    pub fn to_world(&self, p: Vec2) -> Vec2 {
        let d = (p - self.canvas_center) / self.scale;
        self.world_center + Vec2::new(d.x, -d.y)
    }

    /// A world-space length in pixels.
    pub fn length_to_canvas(&self, length: f32) -> f32 {
        length * self.scale
    }

    /// The figure rectangle covered by world rectangle `r`.
    pub fn rect_to_canvas(&self, r: Rect) -> Rect {
        Rect::from_corners(self.to_canvas(r.min), self.to_canvas(r.max))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[track_caller]
    fn check(world: Rect, canvas: Rect, cases: &[(Vec2, Vec2)]) {
        let m = Mapping::fit(world, canvas).expect("valid rectangles");
        for &(w, px) in cases {
            let got = m.to_canvas(w);
            assert!(got.abs_diff_eq(px, 1e-3), "{w} -> {got}, expected {px}");
            assert!(m.to_world(px).abs_diff_eq(w, 1e-4), "round trip of {w}");
        }
    }

    #[test]
    fn maps_world_to_canvas_with_y_flipped() {
        // A 2 x 1 world exactly fills a 1600 x 800 canvas: 800 px per unit.
        let world = Rect::from_corners(Vec2::new(-1.0, 0.0), Vec2::new(1.0, 1.0));
        let canvas = Rect::from_xywh(0.0, 50.0, 1600.0, 800.0);
        check(
            world,
            canvas,
            &[
                (Vec2::new(-1.0, 0.0), Vec2::new(0.0, 850.0)),
                (Vec2::new(1.0, 1.0), Vec2::new(1600.0, 50.0)),
                (Vec2::new(0.0, 0.5), Vec2::new(800.0, 450.0)),
            ],
        );
    }

    #[test]
    fn preserves_aspect_ratio_and_centres() {
        // A square world on a wide canvas: height limits the scale, x gets margins.
        let world = Rect::from_corners(Vec2::ZERO, Vec2::new(2.0, 2.0));
        let canvas = Rect::from_xywh(0.0, 0.0, 1600.0, 900.0);
        let m = Mapping::fit(world, canvas).expect("valid rectangles");
        assert_eq!(m.scale(), 450.0);
        assert_eq!(m.length_to_canvas(0.5), 225.0);
        check(
            world,
            canvas,
            &[
                (Vec2::ZERO, Vec2::new(350.0, 900.0)),
                (Vec2::new(2.0, 2.0), Vec2::new(1250.0, 0.0)),
            ],
        );
        let r = m.rect_to_canvas(world);
        assert_eq!(r, Rect::from_xywh(350.0, 0.0, 900.0, 900.0));
    }

    #[test]
    fn rejects_empty_rectangles() {
        let good = Rect::from_xywh(0.0, 0.0, 10.0, 10.0);
        let flat = Rect::from_xywh(0.0, 0.0, 10.0, 0.0);
        let infinite = Rect::from_xywh(0.0, 0.0, f32::INFINITY, 1.0);
        assert_eq!(Mapping::fit(flat, good), None);
        assert_eq!(Mapping::fit(good, flat), None);
        assert_eq!(Mapping::fit(infinite, good), None);
        assert!(Mapping::fit(good, good).is_some());
    }
}

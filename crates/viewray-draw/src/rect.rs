//! Axis-aligned rectangles.

use glam::Vec2;

/// An axis-aligned rectangle from `min` to `max`.
///
/// In figure space (y down) `min` is the top-left corner; in world space (y up, see
/// [`Mapping`](crate::Mapping)) it is the bottom-left one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Rect {
    /// The corner with the smallest coordinates.
    pub min: Vec2,
    /// The corner with the largest coordinates.
    pub max: Vec2,
}

impl Rect {
    /// The rectangle spanned by two opposite corners, in either order.
    pub fn from_corners(a: Vec2, b: Vec2) -> Rect {
        Rect {
            min: a.min(b),
            max: a.max(b),
        }
    }

    /// The rectangle with top-left corner `(x, y)` (in figure space) and the given size.
    pub fn from_xywh(x: f32, y: f32, width: f32, height: f32) -> Rect {
        Rect::from_corners(Vec2::new(x, y), Vec2::new(x + width, y + height))
    }

    /// `max.x - min.x`.
    pub fn width(&self) -> f32 {
        self.max.x - self.min.x
    }

    /// `max.y - min.y`.
    pub fn height(&self) -> f32 {
        self.max.y - self.min.y
    }

    /// The centre point.
    pub fn center(&self) -> Vec2 {
        (self.min + self.max) * 0.5
    }

    /// Whether `p` lies inside or on the boundary.
    pub fn contains(&self, p: Vec2) -> bool {
        p.cmpge(self.min).all() && p.cmple(self.max).all()
    }

    /// Whether `other` lies entirely inside (or on the boundary of) this rectangle.
    pub fn contains_rect(&self, other: &Rect) -> bool {
        self.contains(other.min) && self.contains(other.max)
    }

    /// Whether the two rectangles overlap in an area (touching edges do not count).
    pub fn intersects(&self, other: &Rect) -> bool {
        self.min.cmplt(other.max).all() && other.min.cmplt(self.max).all()
    }

    /// The smallest rectangle holding both.
    pub fn union(&self, other: &Rect) -> Rect {
        Rect {
            min: self.min.min(other.min),
            max: self.max.max(other.max),
        }
    }

    /// The rectangle grown by `margin` on every side (shrunk for a negative margin).
    pub fn expand(&self, margin: f32) -> Rect {
        Rect {
            min: self.min - Vec2::splat(margin),
            max: self.max + Vec2::splat(margin),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn rect_relations() {
        let r = Rect::from_xywh(10.0, 20.0, 100.0, 50.0);
        assert_eq!(r.center(), Vec2::new(60.0, 45.0));
        assert!(r.contains(Vec2::new(10.0, 70.0)));
        assert!(!r.contains(Vec2::new(9.9, 30.0)));
        let touching = Rect::from_xywh(110.0, 20.0, 5.0, 5.0);
        assert!(!r.intersects(&touching));
        assert!(r.intersects(&touching.expand(1.0)));
        assert!(r.contains_rect(&Rect::from_xywh(20.0, 30.0, 10.0, 10.0)));
        assert_eq!(Rect::from_corners(r.max, r.min), r);
    }
}

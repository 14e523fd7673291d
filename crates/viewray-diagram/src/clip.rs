//! Clipping polygons and segments in figure space (Sutherland–Hodgman, half-plane by
//! half-plane), so pictures drawn through a camera stay inside their image.

use glam::Vec2;

use viewray_draw::Rect;

/// A half-plane `normal . p + offset >= 0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct HalfPlane {
    pub(crate) normal: Vec2,
    pub(crate) offset: f32,
}

impl HalfPlane {
    /// The signed distance-like value of `p`: positive inside.
    fn value(&self, p: Vec2) -> f32 {
        self.normal.dot(p) + self.offset
    }

    /// The four half-planes whose intersection is `rect`.
    pub(crate) fn of_rect(rect: Rect) -> [HalfPlane; 4] {
        [
            HalfPlane {
                normal: Vec2::X,
                offset: -rect.min.x,
            },
            HalfPlane {
                normal: Vec2::NEG_X,
                offset: rect.max.x,
            },
            HalfPlane {
                normal: Vec2::Y,
                offset: -rect.min.y,
            },
            HalfPlane {
                normal: Vec2::NEG_Y,
                offset: rect.max.y,
            },
        ]
    }
}

/// The part of the convex or concave polygon `points` inside every half-plane of
/// `planes`; fewer than three points when nothing is left.
pub(crate) fn clip_polygon(points: &[Vec2], planes: &[HalfPlane]) -> Vec<Vec2> {
    let mut polygon = points.to_vec();
    for plane in planes {
        if polygon.is_empty() {
            break;
        }
        let mut out = Vec::with_capacity(polygon.len() + 2);
        for (i, &a) in polygon.iter().enumerate() {
            let b = polygon[(i + 1) % polygon.len()];
            let (va, vb) = (plane.value(a), plane.value(b));
            if va >= 0.0 {
                out.push(a);
            }
            if (va >= 0.0) != (vb >= 0.0) {
                out.push(a + (b - a) * (va / (va - vb)));
            }
        }
        polygon = out;
    }
    polygon
}

/// The part of the segment `a`-`b` inside every half-plane of `planes`, if any.
pub(crate) fn clip_segment(a: Vec2, b: Vec2, planes: &[HalfPlane]) -> Option<(Vec2, Vec2)> {
    let (mut t0, mut t1) = (0.0f32, 1.0f32);
    for plane in planes {
        let (va, vb) = (plane.value(a), plane.value(b));
        if va < 0.0 && vb < 0.0 {
            return None;
        }
        if va < 0.0 {
            t0 = t0.max(va / (va - vb));
        } else if vb < 0.0 {
            t1 = t1.min(va / (va - vb));
        }
    }
    (t0 < t1).then(|| (a + (b - a) * t0, a + (b - a) * t1))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_square_overlapping_a_corner_keeps_the_overlap() {
        let rect = Rect::from_xywh(0.0, 0.0, 10.0, 10.0);
        let square = [
            Vec2::new(5.0, 5.0),
            Vec2::new(15.0, 5.0),
            Vec2::new(15.0, 15.0),
            Vec2::new(5.0, 15.0),
        ];
        let clipped = clip_polygon(&square, &HalfPlane::of_rect(rect));
        assert_eq!(clipped.len(), 4);
        for p in &clipped {
            assert!(rect.contains(*p), "{p}");
        }
        let area: f32 = (0..clipped.len())
            .map(|i| clipped[i].perp_dot(clipped[(i + 1) % clipped.len()]))
            .sum::<f32>()
            / 2.0;
        assert!((area.abs() - 25.0).abs() < 1e-3, "{area}");
    }

    #[test]
    fn segments_are_cut_at_the_edges_or_dropped() {
        let planes = HalfPlane::of_rect(Rect::from_xywh(0.0, 0.0, 10.0, 10.0));
        assert_eq!(
            clip_segment(Vec2::new(-5.0, 5.0), Vec2::new(5.0, 5.0), &planes),
            Some((Vec2::new(0.0, 5.0), Vec2::new(5.0, 5.0)))
        );
        assert_eq!(
            clip_segment(Vec2::new(-5.0, -5.0), Vec2::new(-1.0, 20.0), &planes),
            None
        );
    }
}

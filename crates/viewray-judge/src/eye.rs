//! A moved eye, found and checked: when neither the right camera nor any entry of the
//! catalogue explains a picture, the scene is labelled from eyes moved right, up or
//! forward (the view kept, or turned to keep looking at the same point) and the one whose
//! map explains the picture is named, never guessed: only a map that explains the
//! picture clearly better than the right camera's is.
//!
//! The moves tried are the image's measure: an eye moved by `D vw / (d W)` to the side
//! moves a point at depth `D` by one pixel (`vw / W` for a parallel camera); one moved
//! forward by `D (1 - 1 / (1 + 2 p / W))` grows the picture by `p` pixels at its edges,
//! `D` the median depth of what the right camera sees. The move the image judgement
//! measured (a shift of the picture, when it found one) is tried too, and the best move
//! is refined along its axis.

use glam::DVec3;
use viewray_camera::{Camera, Frame, Projection};
use viewray_compare::{
    CANDIDATE_MARGIN, CameraCandidates, Fit, GeometryJudgement, LabelMap, PictureEdges,
};
use viewray_render::object_labels;
use viewray_scene::Scene;

/// The pixel moves the search tries first, along each axis and each way.
const PIXEL_MOVES: [f64; 4] = [1.5, 4.0, 10.0, 25.0];

/// How the camera's basis follows a moved eye.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Aim {
    /// The view direction is kept: the camera moved as a whole.
    Kept,
    /// The camera turns to keep looking at the point it looked at (a `look_at` camera
    /// whose eye was typed wrong).
    AtTarget,
}

/// An eye found moved: by how much, in the camera's axes, and how well its map explains
/// the picture.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct MovedEye {
    /// Along u (right), v (up) and -w (forward).
    pub(crate) offset: [f64; 3],
    /// Where the eye is.
    pub(crate) eye: DVec3,
    /// Its map's fit.
    pub(crate) fit: Fit,
}

/// What the search needs of the scene, worked out once.
#[derive(Clone, Debug)]
pub(crate) struct EyeSearch {
    /// The median depth (along -w) of what the right camera sees; 1 when it sees nothing.
    depth: f64,
    /// The size of one pixel's move, in scene units, for an eye moved to the side: along
    /// u and along v.
    pixel: [f64; 2],
}

impl EyeSearch {
    /// Prepares the search for `scene`'s camera.
    pub(crate) fn new(scene: &Scene) -> EyeSearch {
        let camera = scene.camera();
        let depth = median_depth(scene, camera).unwrap_or(1.0);
        let (width, height) = (f64::from(camera.width()), f64::from(camera.height()));
        let projection = camera.projection();
        let viewport = projection.viewport().unwrap_or(glam::DVec2::ONE);
        let per_pixel = [viewport.x / width, viewport.y / height];
        let pixel = match projection {
            Projection::Perspective(p) => per_pixel.map(|k| k * depth / p.distance.abs()),
            Projection::ThinLens(p) => per_pixel.map(|k| k * depth / p.distance.abs()),
            _ => per_pixel,
        };
        EyeSearch { depth, pixel }
    }

    /// The moved eye whose map explains `edges` clearly better than the right camera
    /// (`judged` is the candidates' judgement of them), if one does. `measured` is the
    /// picture's move in pixels (x right, y down) as the image judgement measured it.
    pub(crate) fn search(
        &self,
        scene: &Scene,
        candidates: &CameraCandidates,
        edges: &PictureEdges,
        judged: &GeometryJudgement,
        measured: Option<(f64, f64)>,
    ) -> Option<MovedEye> {
        let camera = scene.camera();
        let width = f64::from(camera.width());
        let parallel = camera.projection().is_parallel();
        let score = |offset: [f64; 3], aim: Aim| -> Option<MovedEye> {
            let (moved, eye) = moved_camera(camera, offset, aim, self.depth)?;
            let labels = object_labels(scene, &moved);
            let map = LabelMap::new(camera.width(), camera.height(), labels)?;
            let fit = candidates.fit_other(edges, judged, &map)?;
            Some(MovedEye { offset, eye, fit })
        };
        let better = |a: Option<MovedEye>, b: Option<MovedEye>| match (a, b) {
            (Some(a), Some(b)) => Some(if b.fit.score > a.fit.score { b } else { a }),
            (a, b) => a.or(b),
        };
        // The tries: each axis, each way, each pixel move; both aims for a perspective
        // camera's sideways moves.
        let mut tries: Vec<([f64; 3], Aim)> = Vec::new();
        let aims: &[Aim] = if parallel {
            &[Aim::Kept]
        } else {
            &[Aim::Kept, Aim::AtTarget]
        };
        for &p in &PIXEL_MOVES {
            for sign in [1.0, -1.0] {
                for &aim in aims {
                    tries.push(([sign * p * self.pixel[0], 0.0, 0.0], aim));
                    tries.push(([0.0, sign * p * self.pixel[1], 0.0], aim));
                }
                if !parallel {
                    let forward = self.depth * (1.0 - 1.0 / (1.0 + 2.0 * p / width));
                    tries.push(([0.0, 0.0, sign * forward], Aim::Kept));
                }
            }
        }
        // The picture moved right by tx shows an eye moved left: u = -tx px, v = +ty px.
        if let Some((tx, ty)) = measured {
            tries.push(([-tx * self.pixel[0], ty * self.pixel[1], 0.0], Aim::Kept));
        }
        let mut best: Option<(MovedEye, Aim)> = None;
        for (offset, aim) in tries {
            if let Some(found) = score(offset, aim)
                && best.is_none_or(|(b, _)| found.fit.score > b.fit.score)
            {
                best = Some((found, aim));
            }
        }
        let (found, aim) = best?;
        // Refine the amount along the found move's direction: a golden-section search of
        // the score over a third to three times it.
        let direction = found.offset;
        let at = |k: f64| score(direction.map(|c| c * k), aim);
        let (mut lo, mut hi) = (1.0_f64 / 3.0, 3.0_f64);
        let ratio = 0.5 * (5.0_f64.sqrt() - 1.0);
        let mut a = hi - ratio * (hi - lo);
        let mut b = lo + ratio * (hi - lo);
        let (mut fa, mut fb) = (at(a), at(b));
        let mut refined = Some(found);
        for _ in 0..10 {
            refined = better(better(refined, fa), fb);
            let sa = fa.map_or(0.0, |m| m.fit.score);
            let sb = fb.map_or(0.0, |m| m.fit.score);
            if sa >= sb {
                hi = b;
                b = a;
                fb = fa;
                a = hi - ratio * (hi - lo);
                fa = at(a);
            } else {
                lo = a;
                a = b;
                fa = fb;
                b = lo + ratio * (hi - lo);
                fb = at(b);
            }
        }
        let refined = better(better(refined, fa), fb)?;
        (refined.fit.explains() && refined.fit.score > judged.right.score + CANDIDATE_MARGIN)
            .then_some(refined)
    }
}

/// `camera` with its eye moved by `offset` (along u, v and -w), its basis kept or turned
/// to look at the point `depth` ahead; `None` where no camera can be made so.
fn moved_camera(
    camera: &Camera,
    offset: [f64; 3],
    aim: Aim,
    depth: f64,
) -> Option<(Camera, DVec3)> {
    let frame = camera.frame();
    let [right, up, forward] = offset;
    let eye = frame.e() + right * frame.u() + up * frame.v() - forward * frame.w();
    let moved = match aim {
        Aim::Kept => frame.with_eye(eye).ok()?,
        Aim::AtTarget => {
            let target = frame.e() - depth * frame.w();
            Frame::from_eye_look_at_up(eye, target, frame.up()).ok()?
        }
    };
    let camera = Camera::new(moved, *camera.projection(), camera.width(), camera.height()).ok()?;
    Some((camera, eye))
}

/// The median depth, along -w from the eye, of what `camera`'s centre rays hit in
/// `scene`; `None` when they hit nothing.
fn median_depth(scene: &Scene, camera: &Camera) -> Option<f64> {
    let frame = camera.frame();
    let mut depths = Vec::new();
    // Every fourth pixel each way is plenty for a median.
    for row in (0..camera.height()).step_by(4) {
        for col in (0..camera.width()).step_by(4) {
            let Some(ray) = camera.generate_ray(row, col, viewray_camera::CameraSample::CENTER)
            else {
                continue;
            };
            let Some(hit) = scene
                .world()
                .closest_object(&ray.as_ray(), f32::MIN_POSITIVE..f32::INFINITY)
            else {
                continue;
            };
            let point = ray.origin + f64::from(hit.t) * ray.direction;
            let depth = (point - frame.e()).dot(-frame.w());
            if depth.is_finite() && depth > 0.0 {
                depths.push(depth);
            }
        }
    }
    if depths.is_empty() {
        return None;
    }
    let middle = depths.len() / 2;
    let (_, m, _) = depths.select_nth_unstable_by(middle, f64::total_cmp);
    Some(*m)
}

/// The sentence naming a moved eye: `the eye is about 0.6 to the right of where it
/// should be (e is about (0.6, 1.5, 6), not (0, 1.5, 6))`.
pub(crate) fn sentence(moved: &MovedEye, right_eye: DVec3) -> String {
    let [r, u, f] = moved.offset;
    let largest = r.abs().max(u.abs()).max(f.abs());
    let mut parts = Vec::new();
    for (value, positive, negative) in [
        (r, "to the right of", "to the left of"),
        (u, "above", "below"),
        (f, "in front of", "behind"),
    ] {
        if value.abs() >= 0.3 * largest {
            let way = if value > 0.0 { positive } else { negative };
            parts.push(format!("{} {way}", about(value.abs())));
        }
    }
    let point = |p: DVec3| {
        format!(
            "({}, {}, {})",
            coordinate(p.x),
            coordinate(p.y),
            coordinate(p.z)
        )
    };
    format!(
        "the eye is about {} where it should be (e is about {}, not {})",
        parts.join(" and "),
        point(moved.eye),
        point(right_eye)
    )
}

/// A moved distance as the sentence says it: one significant digit below 1 (0.58 is
/// 0.6), one decimal above.
fn about(value: f64) -> String {
    if value < 1.0 {
        let digits = (-value.log10().floor()) as i32;
        let scale = 10f64.powi(digits);
        trimmed((value * scale).round() / scale, 4)
    } else {
        trimmed(value, 1)
    }
}

/// A coordinate of a point, to two decimals.
fn coordinate(value: f64) -> String {
    trimmed(value, 2)
}

/// `value` to `decimals` decimals, without trailing zeros (and never `-0`).
fn trimmed(value: f64, decimals: usize) -> String {
    let text = format!("{value:.decimals$}");
    let text = if text.contains('.') {
        text.trim_end_matches('0').trim_end_matches('.').to_owned()
    } else {
        text
    };
    if text == "-0" { "0".to_owned() } else { text }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn moved(offset: [f64; 3]) -> MovedEye {
        MovedEye {
            offset,
            eye: DVec3::new(0.58, 1.5, 6.0) + DVec3::new(0.0, offset[1], -offset[2]),
            fit: Fit {
                agreement: 1.0,
                coverage: 1.0,
                score: 1.0,
            },
        }
    }

    #[test]
    fn the_sentence_names_each_clear_part_of_the_move() {
        let right = DVec3::new(0.0, 1.5, 6.0);
        assert_eq!(
            sentence(&moved([0.58, 0.01, 0.0]), right),
            "the eye is about 0.6 to the right of where it should be (e is about (0.58, \
             1.51, 6), not (0, 1.5, 6))"
        );
        assert_eq!(
            sentence(&moved([-0.4, 0.3, 0.0]), right),
            "the eye is about 0.4 to the left of and 0.3 above where it should be (e is \
             about (0.58, 1.8, 6), not (0, 1.5, 6))"
        );
        assert_eq!(
            sentence(&moved([0.0, 0.0, -1.26]), right),
            "the eye is about 1.3 behind where it should be (e is about (0.58, 1.5, 7.26), \
             not (0, 1.5, 6))"
        );
        assert_eq!(about(0.048), "0.05");
        assert_eq!(trimmed(-0.001, 2), "0");
    }
}

//! A moved eye, found and checked: when the right camera does not explain a picture, the
//! scene is labelled from moved eyes (the view kept, or turned to keep looking at a point
//! ahead, as a `look_at` camera whose eye was typed wrong turns) and the eye whose map
//! explains the picture is named, never guessed: only a map that explains the picture
//! clearly better than the right camera's is, and only for a move of a few pixels or more.
//!
//! The agreement of a map with a picture is a needle (high within about a pixel of the
//! right move, as low a few pixels off as far away), so the search first descends the
//! chamfer distance between the map's boundaries and the picture's edges
//! ([`PictureEdges::distance`]), which falls steadily as they approach, from the best of
//! a few starts; near its lowest point (when the agreement there says some eye's picture
//! could be it) the agreement is looked at on a grid and descended. A move is measured in
//! the image's pixels: an eye moved by `D vw / (d W)` to the side moves a point at depth
//! `D` by one pixel (`vw / W` for a parallel camera), one moved forward by `2 D / W` grows
//! the picture by about a pixel at its edges, `D` the median depth of what the right
//! camera sees; where the point `D` ahead shows is the view's turn (see [`Move`]).

use glam::DVec3;
use viewray_camera::{Camera, Frame, Projection};
use viewray_compare::{
    CANDIDATE_MARGIN, CameraCandidates, Fit, GeometryJudgement, LabelMap, PictureEdges,
};
use viewray_render::object_labels;
use viewray_scene::Scene;

/// The pixel moves the search starts from, along each axis and each way.
const PIXEL_MOVES: [f64; 4] = [2.0, 5.0, 12.0, 30.0];

/// The smallest move of an eye that is named, in pixels.
const SMALLEST_MOVE: f64 = 4.0;

/// The first step of the descent, in pixels along each of its axes.
const FIRST_STEP: f64 = 4.0;

/// The descent stops when its pixel steps are below this.
const FINEST_STEP: f64 = 0.2;

/// The agreement below which the lowest point of the distance is no moved eye's picture:
/// the agreement is not searched near it.
const HOPELESS: f64 = 0.7;

/// How many of the best starts the distance is descended from.
const DESCENTS: usize = 2;

/// The most cameras each descent of the distance labels the scene through.
const DESCENT_BUDGET: usize = 60;

/// The first step of the agreement's descent, in pixels: the distance's lowest point is
/// within a pixel or two of the best move.
const POLISH_STEP: f64 = 1.0;

/// The most cameras the agreement's descent labels the scene through.
const POLISH_BUDGET: usize = 50;

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
    /// u and along v; and forward.
    pixel: [f64; 3],
}

/// A picture the search explains: its edges and their judgement by the right camera's
/// and the catalogue's maps, and its move in pixels (x right, y down) as the image
/// judgement measured it, when it did.
#[derive(Clone, Copy)]
pub(crate) struct Seen<'a> {
    /// The right camera's and the catalogue's maps.
    pub(crate) candidates: &'a CameraCandidates,
    /// The picture's edges.
    pub(crate) edges: &'a PictureEdges,
    /// Their judgement by `candidates`.
    pub(crate) judged: &'a GeometryJudgement,
    /// The picture's measured move.
    pub(crate) measured: Option<(f64, f64)>,
}

/// A move the search tries, in pixels (see the module's docs): the eye's right, up and
/// forward, and where the point `D` ahead of the right eye shows, right and up of where
/// it shows in the right picture. The view is kept when the point moves with the eye
/// (`[a, b, _, a, b]`), aimed at the point when it stays (`[a, b, _, 0, 0]`). Splitting
/// the picture's move so (a shift of what lies at depth `D`, and the parallax the eye's
/// own move adds) gives the descent axes along which the picture changes apart, where a
/// move and a turn of the view would trade one for the other.
type Move = [f64; 5];

impl EyeSearch {
    /// Prepares the search for `scene`'s camera.
    pub(crate) fn new(scene: &Scene) -> EyeSearch {
        let camera = scene.camera();
        let depth = median_depth(scene, camera).unwrap_or(1.0);
        let (width, height) = (f64::from(camera.width()), f64::from(camera.height()));
        let projection = camera.projection();
        let viewport = projection.viewport().unwrap_or(glam::DVec2::ONE);
        let per_pixel = [viewport.x / width, viewport.y / height];
        let [right, up] = match projection {
            Projection::Perspective(p) => per_pixel.map(|k| k * depth / p.distance.abs()),
            Projection::ThinLens(p) => per_pixel.map(|k| k * depth / p.distance.abs()),
            _ => per_pixel,
        };
        // Forward moves change nothing in a parallel camera's picture.
        let forward = if projection.is_parallel() {
            0.0
        } else {
            2.0 * depth / width
        };
        EyeSearch {
            depth,
            pixel: [right, up, forward],
        }
    }

    /// The moved eye whose map explains the `seen` picture clearly better than the right
    /// camera, if one does.
    pub(crate) fn search(&self, scene: &Scene, seen: &Seen<'_>) -> Option<MovedEye> {
        let Seen {
            candidates,
            edges,
            judged,
            measured,
        } = *seen;
        let camera = scene.camera();
        let map = |step: Move| -> Option<LabelMap> {
            let (moved, _) = self.moved_camera(camera, step)?;
            LabelMap::new(
                camera.width(),
                camera.height(),
                object_labels(scene, &moved),
            )
        };
        let cost = |step: Move| -> f64 {
            map(step)
                .and_then(|m| edges.distance(&m))
                .unwrap_or(f64::INFINITY)
        };
        // The starts: each axis, each way, each pixel move, the view kept or aimed at the
        // point D ahead for the sideways moves; and the move the image judgement measured.
        let parallel = camera.projection().is_parallel();
        let mut starts: Vec<Move> = Vec::new();
        for &p in &PIXEL_MOVES {
            for sign in [1.0, -1.0] {
                let p = sign * p;
                starts.extend([
                    [p, 0.0, 0.0, p, 0.0],
                    [p, 0.0, 0.0, 0.0, 0.0],
                    [0.0, p, 0.0, 0.0, p],
                    [0.0, p, 0.0, 0.0, 0.0],
                ]);
                if !parallel {
                    starts.push([0.0, 0.0, p, 0.0, 0.0]);
                }
            }
        }
        // The picture moved right by tx shows an eye moved left: -tx px right, ty px up.
        if let Some((tx, ty)) = measured {
            starts.push([-tx, ty, 0.0, -tx, ty]);
        }
        // Descend the distance from the best few starts, far enough apart to fall into
        // different hollows; then the agreement, a needle, from the lowest point found.
        let mut scored: Vec<(f64, Move)> = starts.into_iter().map(|m| (cost(m), m)).collect();
        scored.sort_by(|a, b| a.0.total_cmp(&b.0));
        let axes: &[usize] = if parallel {
            &[0, 1, 3, 4]
        } else {
            &[0, 1, 2, 3, 4]
        };
        let (mut best, mut best_cost) = ([0.0; 5], f64::INFINITY);
        for &(start_cost, start) in scored.iter().take(DESCENTS) {
            let (end, end_cost) = descend(
                start,
                start_cost,
                (FIRST_STEP, FINEST_STEP),
                axes,
                DESCENT_BUDGET,
                &cost,
            );
            if end_cost < best_cost {
                (best, best_cost) = (end, end_cost);
            }
        }
        let disagreement = |step: Move| -> f64 {
            map(step)
                .and_then(|m| candidates.fit_other(edges, judged, &m))
                .map_or(f64::INFINITY, |fit| -fit.agreement)
        };
        // Along the parallax of the larger sideways move the distance is nearly flat and
        // the agreement a ridge one pixel wide across the shift: the agreement is looked
        // at on a grid of both before its descent.
        let (parallax, shift) = if best[1].abs() > best[0].abs() {
            (1, 4)
        } else {
            (0, 3)
        };
        let mut grid = (best, disagreement(best));
        // Far from any eye's picture, the agreement is not looked at further.
        if -grid.1 < HOPELESS {
            return None;
        }
        for i in -4_i32..=4 {
            for j in -3_i32..=3 {
                let mut next = best;
                next[parallax] += 2.0 * f64::from(i);
                next[shift] += 0.5 * f64::from(j);
                let c = disagreement(next);
                if c < grid.1 {
                    grid = (next, c);
                }
            }
        }
        let (best, _) = descend(
            grid.0,
            grid.1,
            (POLISH_STEP, FINEST_STEP),
            axes,
            POLISH_BUDGET,
            &disagreement,
        );
        let (_, eye) = self.moved_camera(camera, best)?;
        let fit = candidates.fit_other(edges, judged, &map(best)?)?;
        let found = MovedEye {
            offset: self.offset(best),
            eye,
            fit,
        };
        // A move of a pixel or so is what the pixel formulas' mistakes and anti-aliasing
        // do to a picture: no eye is named for it.
        let visible = best[..3].iter().any(|p| p.abs() >= SMALLEST_MOVE);
        (visible && fit.explains() && fit.score > judged.right.score + CANDIDATE_MARGIN)
            .then_some(found)
    }

    /// A move's offset in scene units along u, v and -w.
    fn offset(&self, step: Move) -> [f64; 3] {
        [
            step[0] * self.pixel[0],
            step[1] * self.pixel[1],
            step[2] * self.pixel[2],
        ]
    }

    /// `camera` with its eye moved by `step`, and where its eye is; `None` where no
    /// camera can be made so.
    fn moved_camera(&self, camera: &Camera, step: Move) -> Option<(Camera, DVec3)> {
        let frame = camera.frame();
        let [right, up, forward] = self.offset(step);
        let moved = right * frame.u() + up * frame.v() - forward * frame.w();
        let eye = frame.e() + moved;
        // The point D ahead of the right eye, moved as the picture of it moves.
        let target = frame.e() - self.depth * frame.w()
            + step[3] * self.pixel[0] * frame.u()
            + step[4] * self.pixel[1] * frame.v();
        let moved_frame = if step[0] == step[3] && step[1] == step[4] {
            frame.with_eye(eye).ok()?
        } else {
            Frame::from_eye_look_at_up(eye, target, frame.up()).ok()?
        };
        let camera = Camera::new(
            moved_frame,
            *camera.projection(),
            camera.width(),
            camera.height(),
        )
        .ok()?;
        Some((camera, eye))
    }
}

/// The move near `start` (whose cost is `start_cost`) where `cost` is lowest, found by
/// stepping along each of `axes` each way, taking the best step, and halving the step when
/// none is better, from `steps.0` until it is below `steps.1` or `budget` moves are
/// tried; with its cost.
fn descend(
    start: Move,
    start_cost: f64,
    (mut step, finest): (f64, f64),
    axes: &[usize],
    budget: usize,
    cost: &dyn Fn(Move) -> f64,
) -> (Move, f64) {
    let (mut best, mut best_cost) = (start, start_cost);
    let mut tried = 0;
    // Every point costed so far: each cost is a render, and the walk comes back to
    // points it has seen (the one it just left, and the coarser steps' points after a
    // halving). A point's cost is always the same, so the walk takes the same path.
    let mut known = vec![(start, start_cost)];
    while step >= finest && tried < budget {
        let mut moved = None;
        for &axis in axes {
            for sign in [1.0, -1.0] {
                let mut next = best;
                next[axis] += sign * step;
                let c = match known.iter().find(|(point, _)| *point == next) {
                    Some(&(_, c)) => c,
                    None => {
                        let c = cost(next);
                        known.push((next, c));
                        c
                    }
                };
                tried += 1;
                if c < best_cost {
                    (best_cost, moved) = (c, Some(next));
                }
            }
        }
        match moved {
            Some(next) => best = next,
            None => step *= 0.5,
        }
    }
    (best, best_cost)
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
    fn the_descent_finds_the_bottom_of_a_bowl_within_its_finest_step() {
        let bottom = [7.3, -2.6, 0.0, 1.1, 0.4];
        let bowl = |m: Move| -> f64 { m.iter().zip(bottom).map(|(a, b)| (a - b).powi(2)).sum() };
        let start = [0.0; 5];
        let (found, cost) = descend(
            start,
            bowl(start),
            (4.0, FINEST_STEP),
            &[0, 1, 3, 4],
            1000,
            &bowl,
        );
        for axis in [0, 1, 3, 4] {
            assert!(
                (found[axis] - bottom[axis]).abs() <= FINEST_STEP,
                "{found:?}"
            );
        }
        assert_eq!(found[2], 0.0, "an axis not given is not moved");
        assert!(cost < bowl(start));
        // The budget stops it early, having moved downhill.
        let (early, _) = descend(
            start,
            bowl(start),
            (4.0, FINEST_STEP),
            &[0, 1, 3, 4],
            8,
            &bowl,
        );
        assert!(bowl(early) < bowl(start) && bowl(early) > cost, "{early:?}");
    }

    #[test]
    fn the_descent_never_renders_a_point_twice() {
        // Each cost is a render: stepping back to the point just left (or to the
        // start) would pay for one whose cost is known.
        let bottom = [2.5, -1.25, 0.0, 0.75, 0.0];
        let seen = std::cell::RefCell::new(vec![[0.0; 5]]);
        let bowl = |m: Move| -> f64 {
            let mut seen = seen.borrow_mut();
            assert!(!seen.contains(&m), "{m:?} costed twice");
            seen.push(m);
            m.iter().zip(bottom).map(|(a, b)| (a - b).powi(2)).sum()
        };
        let start = [0.0; 5];
        let (found, _) = descend(start, 8.375, (1.0, 0.25), &[0, 1, 3], 1000, &bowl);
        assert_eq!(found, bottom);
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

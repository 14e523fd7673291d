//! The search: the coarsest level's candidates scored by masked NCC over a grid of
//! mirrors, turns and scales ([`search`]), ranked again by the edges they cover, refined
//! down the pyramid, and checked against the other repeats of a repeating pattern
//! ([`estimate_search`]); and a move the scene predicts, checked on the sharp images
//! ([`verify_move`]).

use crate::raster::FloatImage;

use super::correlation::Correlator;
use super::fit::{Fit, Free, contrast_floor, evaluate, refine, texture, textured};
use super::model::Model;
use super::pyramid::Pyramid;
use super::selection::{Estimate, Tolerances, select};
use super::{FINE_BUDGET, MIN_OVERLAP};

/// A candidate of the search: a model and its score there (higher is better).
#[derive(Clone, Copy, Debug)]
struct Candidate {
    score: f64,
    model: Model,
}

/// The luminance-like mean of the channels.
fn grey(p: [f32; 3]) -> f32 {
    (p[0] + p[1] + p[2]) / 3.0
}

/// The search's grid: rotations (degrees) at scale 1, and scales at no rotation.
fn search_grid() -> Vec<(f64, f64)> {
    let mut grid = vec![(0.0, 1.0)];
    for step in 1..=6 {
        let degrees = 5.0 * f64::from(step);
        grid.push((degrees, 1.0));
        grid.push((-degrees, 1.0));
    }
    // 0.68x to 1.47x, 8% apart.
    for step in -5..=5 {
        if step != 0 {
            grid.push((0.0, 1.08f64.powi(step)));
        }
    }
    grid
}

/// Searches the coarsest level for the best starts: for every mirror, rotation and scale
/// of the grid, the best moves by masked NCC. Returns them best first.
fn search(pyramid: &Pyramid) -> Vec<Candidate> {
    let level = pyramid.top();
    let l = &pyramid.levels[level];
    let (w, h) = (l.actual.width, l.actual.height);
    let centre = pyramid.centre();
    let margin = pyramid.margin(level);
    let [full_w, full_h] = pyramid.size;
    let inside = |p: [f64; 2]| {
        p[0] >= margin && p[0] <= full_w - margin && p[1] >= margin && p[1] <= full_h - margin
    };
    let actual: Vec<f32> = l.actual.pixels.iter().map(|&p| grey(p)).collect();
    let actual_mask: Vec<f32> = (0..w * h)
        .map(|i| {
            let x = [
                ((i % w) as f64 + 0.5) * l.factor,
                ((i / w) as f64 + 0.5) * l.factor,
            ];
            if inside(x) { 1.0 } else { 0.0 }
        })
        .collect();
    let expected: Vec<f32> = l.expected.pixels.iter().map(|&p| grey(p)).collect();
    let mut correlator = Correlator::new(&actual, &actual_mask, w, h);
    let inside_count: f32 = actual_mask.iter().sum();
    let min_count = MIN_OVERLAP * f64::from(inside_count);
    let mut candidates = Vec::new();
    let mut warped = vec![0.0f32; w * h];
    let mut mask = vec![0.0f32; w * h];
    for mirror in [[false, false], [true, false], [false, true], [true, true]] {
        for (degrees, scale) in search_grid() {
            let model = Model {
                mirror,
                rotation: f64::to_radians(degrees),
                log_scale: [scale.ln(); 2],
                about: centre,
                shift: [0.0; 2],
            };
            let inverse = model.inverse_matrix();
            for row in 0..h {
                for col in 0..w {
                    let x = [(col as f64 + 0.5) * l.factor, (row as f64 + 0.5) * l.factor];
                    let e = model.preimage(&inverse, x);
                    let i = row * w + col;
                    if inside(e) {
                        let ex = ((e[0] / l.factor - 0.5).clamp(0.0, (w - 1) as f64)) as f32;
                        let ey = ((e[1] / l.factor - 0.5).clamp(0.0, (h - 1) as f64)) as f32;
                        let (x0, y0) = (ex.floor() as usize, ey.floor() as usize);
                        let (x1, y1) = ((x0 + 1).min(w - 1), (y0 + 1).min(h - 1));
                        let (tx, ty) = (ex - x0 as f32, ey - y0 as f32);
                        let top = expected[y0 * w + x0] * (1.0 - tx) + expected[y0 * w + x1] * tx;
                        let bottom =
                            expected[y1 * w + x0] * (1.0 - tx) + expected[y1 * w + x1] * tx;
                        warped[i] = top * (1.0 - ty) + bottom * ty;
                        mask[i] = 1.0;
                    } else {
                        warped[i] = 0.0;
                        mask[i] = 0.0;
                    }
                }
            }
            // The two best moves of this warp, at least two level pixels apart.
            let mut best: [Option<([i64; 2], f64)>; 2] = [None, None];
            correlator.correlate(&warped, &mask, min_count, |u, ncc, _| {
                let beats = |slot: &Option<([i64; 2], f64)>| slot.is_none_or(|(_, s)| ncc > s);
                if beats(&best[0]) {
                    let near = best[0]
                        .is_some_and(|(v, _)| (v[0] - u[0]).abs() <= 2 && (v[1] - u[1]).abs() <= 2);
                    if !near {
                        best[1] = best[0];
                    }
                    best[0] = Some((u, ncc));
                } else if beats(&best[1]) {
                    let near = best[0]
                        .is_some_and(|(v, _)| (v[0] - u[0]).abs() <= 2 && (v[1] - u[1]).abs() <= 2);
                    if !near {
                        best[1] = Some((u, ncc));
                    }
                }
            });
            for (u, ncc) in best.into_iter().flatten() {
                candidates.push(Candidate {
                    score: ncc,
                    model: Model {
                        shift: [u[0] as f64 * l.factor, u[1] as f64 * l.factor],
                        ..model
                    },
                });
            }
        }
    }
    candidates.sort_by(|a, b| b.score.total_cmp(&a.score));
    candidates
}

/// How many of the search's best candidates are ranked again by their coverage.
const CANDIDATES: usize = 24;

/// How much of the picture's edges a match covers, from 0 to 1: its overlap's share of
/// the picture times the edges there along the poorer axis (see [`texture`]).
fn coverage(texture: [f64; 2], overlap: f64) -> f64 {
    (texture[0].min(texture[1]) * overlap).min(1.0)
}

/// The rank of a refined match (lower is better): its normalized residual (see
/// [`Fit::normalized`]), plus a hundredth for what of the picture's edges it leaves
/// uncovered. Two right answers differ in the residual; a right answer and a strip that
/// matches itself slid sideways, in the coverage.
fn rank(fit: &Fit, texture: [f64; 2], floor: f64) -> f64 {
    fit.normalized(floor) + 0.01 * (1.0 - coverage(texture, fit.overlap()))
}

/// Two matches are as good as each other when the worse one's normalized residual is at
/// most `AMBIGUITY` times the better one's plus `AMBIGUITY_FLOOR`: a repeat of a tiled
/// wall leaves twice what the right move leaves (the sampling differs), a wrong repeat
/// where the overlap also holds the ground or an edge thirty times as much.
const AMBIGUITY: f64 = 3.0;
const AMBIGUITY_FLOOR: f64 = 0.0005;

/// How much lower the best mirrored candidate's normalized residual must be than the best
/// unmirrored one's to be believed: a nearly symmetric picture looks much the same
/// mirrored, and then the simpler answer stands.
const MIRROR_ADVANTAGE: f64 = 0.5;

/// Estimates the transform by the full search (see the module doc), then selects the
/// components the evidence supports. `anchors` are the points a scale, rotation or mirror
/// may be about without a move (the image centre, and the principal point when known);
/// `extra` are starts to refine besides the search's (the moves a scene predicts).
pub(crate) fn estimate_search(
    pyramid: &Pyramid,
    anchors: &[[f64; 2]],
    extra: &[Model],
    tolerances: &Tolerances,
) -> Estimate {
    let top = pyramid.top();
    let mut candidates = search(pyramid);
    let floor = contrast_floor(pyramid);
    // The best by correlation, ranked again by how much of the picture's edges they
    // match: a strip of sky and ground slid sideways correlates as well as the right
    // move, but covers little.
    candidates.truncate(CANDIDATES);
    let mut ranked: Vec<(f64, Candidate)> = candidates
        .into_iter()
        .map(|c| {
            let fit = evaluate(pyramid, top, &c.model, 1);
            let cover = coverage(texture(pyramid, top, &c.model, 1), fit.overlap());
            (c.score - 0.1 * (1.0 - cover), c)
        })
        .collect();
    ranked.sort_by(|a, b| b.0.total_cmp(&a.0));
    // Refine the best few of each mirror class at the search level.
    let mut refined: Vec<(f64, Model)> = Vec::new();
    let mut taken = [0usize; 4];
    let class = |m: &Model| usize::from(m.mirror[0]) + 2 * usize::from(m.mirror[1]);
    let mut starts: Vec<Model> = vec![Model::identity(pyramid.centre())];
    starts.extend_from_slice(extra);
    for (_, candidate) in &ranked {
        let c = class(&candidate.model);
        let limit = if c == 0 { 4 } else { 1 };
        if taken[c] < limit && textured(texture(pyramid, top, &candidate.model, 1)) {
            taken[c] += 1;
            starts.push(candidate.model);
        }
    }
    for start in starts {
        let model = refine(pyramid, top, start, Free::ALL, 1, 12);
        let fit = evaluate(pyramid, top, &model, 1);
        let texture = texture(pyramid, top, &model, 1);
        if fit.overlap() >= MIN_OVERLAP && textured(texture) {
            refined.push((rank(&fit, texture, floor), model));
        }
    }
    refined.sort_by(|a, b| a.0.total_cmp(&b.0));
    // Carry down the pyramid the best unmirrored start, the runner-up when it comes near
    // (within twice the residual), and the best mirrored one when it could still win.
    let plain: Vec<(f64, Model)> = refined
        .iter()
        .copied()
        .filter(|(_, m)| class(m) == 0)
        .collect();
    let mirrored = refined.iter().copied().find(|(_, m)| class(m) != 0);
    let mut carried: Vec<Model> = Vec::new();
    if let Some(&(first, model)) = plain.first() {
        carried.push(model);
        if let Some(&(second, model)) = plain.get(1)
            && second < 2.0 * first
        {
            carried.push(model);
        }
    }
    if let Some((score, model)) = mirrored
        && plain.first().is_none_or(|&(first, _)| score < first)
    {
        carried.push(model);
    }
    if carried.is_empty() {
        carried.push(Model::identity(pyramid.centre()));
    }
    let mut best_plain: Option<(f64, Model)> = None;
    let mut best_mirrored: Option<(f64, Model)> = None;
    for start in carried {
        let mut model = start;
        for level in (0..top).rev() {
            let budget = if level == 0 {
                FINE_BUDGET
            } else {
                FINE_BUDGET / 2
            };
            model = refine(
                pyramid,
                level,
                model,
                Free::ALL,
                pyramid.stride(level, budget),
                5,
            );
        }
        let stride = pyramid.stride(0, FINE_BUDGET);
        let fit = evaluate(pyramid, 0, &model, stride);
        let texture = texture(pyramid, 0, &model, stride);
        if fit.overlap() < MIN_OVERLAP || !textured(texture) {
            continue;
        }
        let score = rank(&fit, texture, floor);
        let slot = if class(&model) == 0 {
            &mut best_plain
        } else {
            &mut best_mirrored
        };
        if slot.is_none_or(|(s, _)| score < s) {
            *slot = Some((score, model));
        }
    }
    let mut best = best_plain;
    if let Some((mirrored_score, _)) = best_mirrored
        && best_plain.is_none_or(|(plain, _)| mirrored_score < MIRROR_ADVANTAGE * plain)
    {
        best = best_mirrored;
    }
    // Another repeat of a repeating pattern may match better (take it) or as well (then
    // the move is not determined).
    let mut ambiguous = false;
    if let Some((_, model)) = best
        && let Some((other_score, other)) = other_move(pyramid, &model)
    {
        let score = evaluate(pyramid, 0, &model, pyramid.stride(0, FINE_BUDGET)).normalized(floor);
        if other_score < 0.5 * score {
            let again = other_move(pyramid, &other);
            ambiguous = again.is_some_and(|(s, _)| s < AMBIGUITY * other_score + AMBIGUITY_FLOOR);
            best = Some((other_score, other));
        } else {
            ambiguous = other_score < AMBIGUITY * score + AMBIGUITY_FLOOR;
        }
    }
    let best = best.map_or(Model::identity(pyramid.centre()), |(_, m)| m);
    let mut estimate = select(pyramid, best, anchors, tolerances);
    estimate.ambiguous = ambiguous;
    estimate
}

/// The best other move near `model`'s: a repeating pattern (a tiled wall filling what
/// is left in common) matches itself moved by its period, and a search on a blurred
/// level may have taken the wrong repeat. Along x and along y, from 3 search-level pixels
/// up to a quarter of the picture away, the dips of the squared difference that come
/// near `model`'s at the search level (the repeats) are refined, the move alone, down to
/// full resolution. Returns the best one's normalized residual there (see
/// [`Fit::normalized`]) and its model.
fn other_move(pyramid: &Pyramid, model: &Model) -> Option<(f64, Model)> {
    let top = pyramid.top();
    let l = &pyramid.levels[top];
    let floor = contrast_floor(pyramid);
    let moves_only = Free {
        rotation: false,
        scale: false,
        aspect: false,
        shift: true,
    };
    let here = evaluate(pyramid, top, model, 1).normalized(floor);
    let mut best: Option<(f64, Model)> = None;
    for (axis, size) in [l.actual.width, l.actual.height].into_iter().enumerate() {
        let reach = (size / 4).max(3) as i64;
        let moved = |k: i64| {
            let mut m = *model;
            m.shift[axis] += k as f64 * l.factor;
            m
        };
        let scores: Vec<(i64, f64)> = (-reach - 1..=reach + 1)
            .map(|k| {
                let fit = evaluate(pyramid, top, &moved(k), 1);
                let score = if fit.overlap() >= MIN_OVERLAP {
                    fit.normalized(floor)
                } else {
                    f64::INFINITY
                };
                (k, score)
            })
            .collect();
        let mut dips: Vec<(i64, f64)> = scores
            .windows(3)
            .filter(|w| w[1].0.abs() >= 3 && w[1].1 <= w[0].1 && w[1].1 <= w[2].1)
            .map(|w| w[1])
            .filter(|&(_, score)| score < 4.0 * here + 0.002)
            .collect();
        dips.sort_by(|a, b| a.1.total_cmp(&b.1));
        for &(k, _) in dips.iter().take(3) {
            // Refined at the search level first: only a repeat that still comes near is
            // followed down to full resolution.
            let mut other = refine(pyramid, top, moved(k), moves_only, 1, 6);
            if evaluate(pyramid, top, &other, 1).normalized(floor) > 3.0 * here + 0.002 {
                continue;
            }
            for level in (0..top).rev() {
                let stride = pyramid.stride(level, FINE_BUDGET);
                other = refine(pyramid, level, other, moves_only, stride, 6);
            }
            let apart = (other.shift[axis] - model.shift[axis]).abs() >= 2.0 * l.factor;
            let stride = pyramid.stride(0, FINE_BUDGET);
            let fit = evaluate(pyramid, 0, &other, stride);
            if apart && fit.overlap() >= MIN_OVERLAP {
                let score = fit.normalized(floor);
                if best.is_none_or(|(b, _)| score < b) {
                    best = Some((score, other));
                }
            }
        }
    }
    best
}

/// A move the scene predicts, checked on the sharp (unblurred) images where the search
/// cannot see it: when so little is left in common that the blur's margins would leave
/// nothing. The move is measured to half a pixel within 3 pixels of the prediction; it
/// stands when the images agree there and clearly disagree 2 pixels further in any
/// direction (the part in common has structure, and it is where the scene says).
/// Returns the measured move, the fraction of the picture in common and the fraction of
/// the difference there that the move explains.
pub(crate) fn verify_move(
    expected: &FloatImage,
    actual: &FloatImage,
    predicted: [f64; 2],
) -> Option<([f64; 2], f64, f64)> {
    let (w, h) = (expected.width as f64, expected.height as f64);
    // The mean squared difference over the pixels whose preimage lies inside the expected
    // image (or, with `identity`, of the same pixels unmoved), and their count.
    let residual = |t: [f64; 2], identity: bool| -> (f64, usize) {
        let mut sum = 0.0;
        let mut count = 0;
        for row in 0..actual.height {
            let y = row as f64 + 0.5;
            let ey = y - t[1];
            if !(0.5..=h - 0.5).contains(&ey) {
                continue;
            }
            for col in 0..actual.width {
                let x = col as f64 + 0.5;
                let ex = x - t[0];
                if !(0.5..=w - 0.5).contains(&ex) {
                    continue;
                }
                let e = if identity {
                    expected.at(row, col)
                } else {
                    expected.sample_bilinear(ex, ey)
                };
                let a = actual.at(row, col);
                for c in 0..3 {
                    let d = f64::from(e[c] - a[c]);
                    sum += d * d;
                }
                count += 1;
            }
        }
        (
            if count == 0 {
                f64::INFINITY
            } else {
                sum / (3 * count) as f64
            },
            count,
        )
    };
    let mut best = (f64::INFINITY, predicted);
    for dy in -6..=6 {
        for dx in -6..=6 {
            let t = [
                predicted[0] + 0.5 * f64::from(dx),
                predicted[1] + 0.5 * f64::from(dy),
            ];
            let (r, count) = residual(t, false);
            if count > 0 && r < best.0 {
                best = (r, t);
            }
        }
    }
    let (r0, t) = best;
    let (_, count) = residual(t, false);
    let fraction = count as f64 / (w * h);
    // At least a sliver of the picture: 2% of it, and 200 pixels.
    if fraction < 0.02 || count < 200 {
        return None;
    }
    let ring = [
        [2.0, 0.0],
        [-2.0, 0.0],
        [0.0, 2.0],
        [0.0, -2.0],
        [2.0, 2.0],
        [-2.0, -2.0],
        [2.0, -2.0],
        [-2.0, 2.0],
    ];
    let nearest_other = ring
        .iter()
        .map(|d| residual([t[0] + d[0], t[1] + d[1]], false).0)
        .fold(f64::INFINITY, f64::min);
    // The identity on the same pixels of the actual image.
    let identity = residual(t, true).0;
    let explained = 1.0 - r0 / identity;
    (r0 < 0.25 * nearest_other && explained >= 0.8).then_some((t, fraction, explained))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::pyramid::ExpectedPyramid;
    use crate::estimate::test_images::{pattern, picture, transformed};

    const SIZE: (usize, usize) = (160, 120);

    /// The tolerances `viewray compare` uses by default.
    const TOLERANCES: Tolerances = Tolerances {
        shift: 0.25,
        scale: 0.02,
        rotation: 0.5 * std::f64::consts::PI / 180.0,
    };

    /// The search's candidates, best first, for the pattern taken by `truth`.
    fn candidates(truth: &Model) -> Vec<Candidate> {
        let expected = ExpectedPyramid::new(&picture(SIZE.0, SIZE.1, pattern));
        let actual = transformed(SIZE.0, SIZE.1, truth);
        search(&Pyramid::new(&expected, &actual, 2.0, usize::MAX))
    }

    #[test]
    fn the_grid_holds_the_identity_and_turns_and_scales_alone() {
        let grid = search_grid();
        assert_eq!(grid[0], (0.0, 1.0));
        assert_eq!(grid.len(), 1 + 12 + 10);
        assert!(
            grid.iter()
                .all(|&(degrees, scale)| degrees == 0.0 || scale == 1.0)
        );
        let turns = grid.iter().map(|g| g.0.abs()).fold(0.0, f64::max);
        let scales = grid.iter().map(|g| g.1);
        assert_eq!(turns, 30.0);
        assert!((scales.clone().fold(f64::MAX, f64::min) - 0.6806).abs() < 1e-4);
        assert!((scales.fold(0.0, f64::max) - 1.4693).abs() < 1e-4);
    }

    #[test]
    fn the_fft_search_finds_a_planted_whole_pixel_move() {
        // 160 x 120 has three levels: the search level has 4 pixels per pixel, and the
        // move is (3, -2) of them.
        let truth = Model {
            shift: [12.0, -8.0],
            ..Model::identity([80.0, 60.0])
        };
        let candidates = candidates(&truth);
        let best = candidates[0];
        assert_eq!(best.model, truth, "{candidates:?}");
        assert!(best.score > 0.99, "{}", best.score);
        // Best first.
        assert!(candidates.windows(2).all(|w| w[0].score >= w[1].score));
    }

    #[test]
    fn the_fft_search_sees_a_mirror() {
        let truth = Model {
            mirror: [true, false],
            ..Model::identity([80.0, 60.0])
        };
        let best = candidates(&truth)[0];
        assert_eq!(best.model.mirror, [true, false]);
        assert_eq!((best.model.rotation, best.model.log_scale), (0.0, [0.0; 2]));
        assert_eq!(best.model.shift, [0.0; 2]);
    }

    #[test]
    fn the_full_search_measures_a_move_and_names_nothing_else() {
        let truth = Model {
            shift: [13.5, -7.25],
            ..Model::identity([80.0, 60.0])
        };
        let expected = ExpectedPyramid::new(&picture(SIZE.0, SIZE.1, pattern));
        let actual = transformed(SIZE.0, SIZE.1, &truth);
        let pyramid = Pyramid::new(&expected, &actual, 2.0, usize::MAX);
        let estimate = estimate_search(&pyramid, &[pyramid.centre()], &[], &TOLERANCES);
        let model = estimate.model;
        assert_eq!(model.mirror, [false, false]);
        assert_eq!((model.rotation, model.log_scale), (0.0, [0.0; 2]));
        assert!((model.shift[0] - 13.5).abs() < 0.02, "{model:?}");
        assert!((model.shift[1] + 7.25).abs() < 0.02, "{model:?}");
        assert_eq!(
            estimate.kept,
            Free {
                rotation: false,
                scale: false,
                aspect: false,
                shift: true,
            }
        );
        assert!(!estimate.ambiguous);
        assert!(estimate.normalized < 1e-3 && estimate.fit.mean() < 1e-3 * estimate.identity_mean);
    }

    #[test]
    fn a_predicted_move_is_measured_to_half_a_pixel_on_the_sharp_pictures() {
        let expected = picture(SIZE.0, SIZE.1, pattern);
        let truth = Model {
            shift: [40.0, 0.0],
            ..Model::identity([80.0, 60.0])
        };
        let actual = transformed(SIZE.0, SIZE.1, &truth);
        let (shift, fraction, explained) = verify_move(&expected, &actual, [41.0, 0.5]).unwrap();
        assert_eq!(shift, [40.0, 0.0]);
        // The 120 of 160 columns the two pictures share.
        assert!((fraction - 0.75).abs() < 1e-12, "{fraction}");
        assert!(explained > 0.999, "{explained}");
        // Further than 3 pixels from the prediction, the move is not found.
        assert_eq!(verify_move(&expected, &actual, [45.0, 0.0]), None);
        // Nor in a picture the move does not explain.
        let mirrored = transformed(
            SIZE.0,
            SIZE.1,
            &Model {
                mirror: [true, true],
                ..truth
            },
        );
        assert_eq!(verify_move(&expected, &mirrored, [40.0, 0.0]), None);
    }
}

//! Model selection: the simplest transform the evidence supports ([`select`]), and the
//! estimate without a search for images that already look alike ([`estimate_local`]).

use super::FINE_BUDGET;
use super::fit::{
    Fit, Free, contrast_floor, cost, evaluate, for_each_overlap, refine, sample, texture,
};
use super::model::Model;
use super::pyramid::Pyramid;

/// The outcome of estimating the transform.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Estimate {
    /// The transform with only the components the evidence supports (see [`select`]).
    pub(crate) model: Model,
    /// Which components it keeps.
    pub(crate) kept: Free,
    /// Its fit on its overlap at full resolution.
    pub(crate) fit: Fit,
    /// The identity's fit on the same pixels.
    pub(crate) identity_mean: f64,
    /// The normalized residual of the model (see [`Fit::normalized`]).
    pub(crate) normalized: f64,
    /// The edges in its overlap (see [`texture`]).
    pub(crate) texture: [f64; 2],
    /// Whether the picture repeats, so that another move explains it about as well
    /// (see [`estimate_search`](super::search::estimate_search)).
    pub(crate) ambiguous: bool,
}

/// Estimates a small transform without a search, for images that already look alike:
/// refines from the identity at the finer levels, then selects the components.
pub(crate) fn estimate_local(
    pyramid: &Pyramid,
    anchors: &[[f64; 2]],
    tolerances: &Tolerances,
) -> Estimate {
    let mut model = Model::identity(pyramid.centre());
    let start = 1.min(pyramid.top());
    for level in (0..=start).rev() {
        let stride = pyramid.stride(level, FINE_BUDGET);
        model = refine(pyramid, level, model, Free::ALL, stride, 10);
    }
    select(pyramid, model, anchors, tolerances)
}

/// How much a component must raise the mean squared difference on the overlap, when it
/// is removed, to be kept: by half, and by more than an RMS of a third of an 8-bit code.
fn clearly_worse(reduced: f64, full: f64) -> bool {
    reduced > 1.5 * full + (0.33f64 / 255.0).powi(2)
}

/// The sizes below which a component is measurement noise, whatever the residual says.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Tolerances {
    /// Pixels of move along x or y.
    pub(crate) shift: f64,
    /// Relative scale error along x or y.
    pub(crate) scale: f64,
    /// Radians of turn.
    pub(crate) rotation: f64,
}

/// How a reduced model treats the move: free, or none about an anchor.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Move {
    Free,
    About([f64; 2]),
}

/// How a reduced model scales.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Scaling {
    None,
    Uniform,
    PerAxis,
}

/// Model selection: every reduction of `model` (the turn kept or dropped; the scale per
/// axis, uniform or none; the move free or none about one of the `anchors`) is refitted,
/// and the simplest whose residual on the overlap is not clearly worse than the full
/// model's wins (the lowest residual among equally simple ones). Components within their
/// tolerance are dropped without a test: they would not be named, and the others are
/// refitted without them.
pub(super) fn select(
    pyramid: &Pyramid,
    model: Model,
    anchors: &[[f64; 2]],
    tolerances: &Tolerances,
) -> Estimate {
    let stride = pyramid.stride(0, FINE_BUDGET);
    let model = model.about_point(pyramid.centre());
    let full = cost(pyramid, 0, &model, stride);
    let [sx, sy] = model.scale();
    let turned = model.rotation.abs() >= tolerances.rotation;
    let per_axis = (sx / sy - 1.0).abs() >= tolerances.scale;
    let scaled = per_axis || (sx - 1.0).abs().max((sy - 1.0).abs()) >= tolerances.scale;
    let moved = |anchor: [f64; 2]| {
        let t = model.about_point(anchor).shift;
        t[0].abs().max(t[1].abs()) >= tolerances.shift
    };
    let mut moves: Vec<Move> = anchors.iter().map(|&a| Move::About(a)).collect();
    if anchors.iter().all(|&a| moved(a)) {
        moves.push(Move::Free);
    }
    let scalings: &[Scaling] = match (scaled, per_axis) {
        (_, true) => &[Scaling::PerAxis, Scaling::Uniform, Scaling::None],
        (true, false) => &[Scaling::Uniform, Scaling::None],
        (false, false) => &[Scaling::None],
    };
    let turns: &[bool] = if turned { &[true, false] } else { &[false] };
    // (parameters, cost, what stays free, the refitted model)
    let mut best: Option<(usize, f64, Free, Model)> = None;
    for &turn in turns {
        for &scaling in scalings {
            for &how in &moves {
                let mut start = model;
                if !turn {
                    start.rotation = 0.0;
                }
                match scaling {
                    Scaling::None => start.log_scale = [0.0; 2],
                    Scaling::Uniform => {
                        let mean = 0.5 * (start.log_scale[0] + start.log_scale[1]);
                        start.log_scale = [mean; 2];
                    }
                    Scaling::PerAxis => {}
                }
                if let Move::About(anchor) = how {
                    start = start.about_point(anchor);
                    start.shift = [0.0; 2];
                }
                let free = Free {
                    rotation: turn,
                    scale: scaling != Scaling::None,
                    aspect: scaling == Scaling::PerAxis,
                    shift: how == Move::Free,
                };
                let refit = refine(pyramid, 0, start, free, stride, 8);
                let c = cost(pyramid, 0, &refit, stride);
                if clearly_worse(c, full) {
                    continue;
                }
                // A scale per axis counts as much as a uniform scale about a point of its
                // own: when the two fit alike, the lower residual decides.
                let parameters = usize::from(turn)
                    + match scaling {
                        Scaling::None => 0,
                        Scaling::Uniform => 1,
                        Scaling::PerAxis => 3,
                    }
                    + if how == Move::Free { 2 } else { 0 };
                if best.is_none_or(|(p, bc, _, _)| (parameters, c) < (p, bc)) {
                    best = Some((parameters, c, free, refit));
                }
            }
        }
    }
    // The full model itself, when every reduction is clearly worse.
    let (kept, model) = best.map_or(
        (
            Free {
                rotation: turned,
                scale: scaled,
                aspect: per_axis,
                shift: true,
            },
            model,
        ),
        |(_, _, free, refit)| (free, refit),
    );
    let fit = evaluate(pyramid, 0, &model, stride);
    // The identity's squared difference on the model's overlap.
    let l = &pyramid.levels[0];
    let mut identity_fit = Fit::default();
    for_each_overlap(pyramid, 0, &model, stride, |[row, col], x, _| {
        let e = sample(l.expected, x[0], x[1]);
        let a = l.actual.at(row, col);
        identity_fit.count += 1;
        for c in 0..3 {
            let d = f64::from(e[c] - a[c]);
            identity_fit.sum_sq += d * d;
        }
    });
    Estimate {
        model,
        kept,
        fit,
        identity_mean: identity_fit.mean(),
        normalized: fit.normalized(contrast_floor(pyramid)),
        texture: texture(pyramid, 0, &model, stride),
        ambiguous: false,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::pyramid::ExpectedPyramid;
    use crate::estimate::test_images::{pattern, picture, transformed};

    const SIZE: (usize, usize) = (160, 120);

    /// Tolerances small enough that every component of the tests' starts is tested by
    /// the residual, not dropped as noise.
    const FINE: Tolerances = Tolerances {
        shift: 0.05,
        scale: 0.002,
        rotation: 0.05 * std::f64::consts::PI / 180.0,
    };

    const MOVE_ONLY: Free = Free {
        rotation: false,
        scale: false,
        aspect: false,
        shift: true,
    };

    /// The selection from `start`, for the pattern taken by `truth`, about the centre.
    fn selected(truth: &Model, start: &Model, tolerances: &Tolerances) -> Estimate {
        let expected = ExpectedPyramid::new(&picture(SIZE.0, SIZE.1, pattern));
        let actual = transformed(SIZE.0, SIZE.1, truth);
        let pyramid = Pyramid::new(&expected, &actual, 2.0, usize::MAX);
        select(&pyramid, *start, &[pyramid.centre()], tolerances)
    }

    #[test]
    fn a_component_stays_when_removing_it_raises_the_residual_clearly() {
        let full = 1e-4;
        let code = (0.33f64 / 255.0).powi(2);
        assert!(!clearly_worse(1.5 * full, full));
        assert!(clearly_worse(1.5 * full + 1.01 * code, full));
        // On a perfect fit, a third of an 8-bit code of RMS is within the noise.
        assert!(!clearly_worse(0.99 * code, 0.0));
    }

    #[test]
    fn selection_prefers_the_simpler_model_when_the_residual_does_not_need_more() {
        let truth = Model {
            shift: [2.5, -1.5],
            ..Model::identity([80.0, 60.0])
        };
        // A start with a spurious turn and scale, each above the tolerances.
        let start = Model {
            rotation: 0.6f64.to_radians(),
            log_scale: [0.01, 0.012],
            ..truth
        };
        let estimate = selected(&truth, &start, &FINE);
        assert_eq!(estimate.kept, MOVE_ONLY);
        let model = estimate.model;
        assert_eq!((model.rotation, model.log_scale), (0.0, [0.0; 2]));
        assert!((model.shift[0] - 2.5).abs() < 0.02 && (model.shift[1] + 1.5).abs() < 0.02);
        let explained = 1.0 - estimate.fit.mean() / estimate.identity_mean;
        assert!(explained > 0.999, "{explained}");
    }

    #[test]
    fn selection_keeps_a_scale_the_residual_needs_and_drops_the_move_it_does_not() {
        // Scaled 1.08x about the centre: no move about the anchor.
        let truth = Model {
            log_scale: [1.08f64.ln(); 2],
            ..Model::identity([80.0, 60.0])
        };
        let start = Model {
            rotation: 0.3f64.to_radians(),
            log_scale: [1.07f64.ln(), 1.09f64.ln()],
            shift: [0.4, -0.3],
            ..truth
        };
        let estimate = selected(&truth, &start, &FINE);
        assert_eq!(
            estimate.kept,
            Free {
                rotation: false,
                scale: true,
                aspect: false,
                shift: false,
            }
        );
        let model = estimate.model;
        assert_eq!(model.about, [80.0, 60.0]);
        assert_eq!((model.rotation, model.shift), (0.0, [0.0; 2]));
        assert_eq!(model.log_scale[0], model.log_scale[1]);
        assert!((model.scale()[0] - 1.08).abs() < 5e-4, "{model:?}");
    }

    #[test]
    fn a_component_within_its_tolerance_is_never_named() {
        // A turn of 0.3 degrees that the residual needs, under a tolerance of half a
        // degree: every reduction without it is clearly worse, so the full model stands,
        // but the turn is not among what it keeps.
        let truth = Model {
            rotation: 0.3f64.to_radians(),
            shift: [3.0, 0.0],
            ..Model::identity([80.0, 60.0])
        };
        let tolerances = Tolerances {
            rotation: 0.5f64.to_radians(),
            ..FINE
        };
        let estimate = selected(&truth, &truth, &tolerances);
        assert_eq!(estimate.kept, MOVE_ONLY);
        assert_eq!(estimate.model, truth);
    }

    #[test]
    fn the_local_estimate_finds_a_small_move_from_the_identity() {
        let truth = Model {
            shift: [0.5, 0.5],
            ..Model::identity([80.0, 60.0])
        };
        let expected = ExpectedPyramid::new(&picture(SIZE.0, SIZE.1, pattern));
        let actual = transformed(SIZE.0, SIZE.1, &truth);
        let pyramid = Pyramid::new(&expected, &actual, 2.0, 2);
        let tolerances = Tolerances {
            shift: 0.25,
            scale: 0.02,
            rotation: 0.5f64.to_radians(),
        };
        let estimate = estimate_local(&pyramid, &[pyramid.centre()], &tolerances);
        assert_eq!(estimate.kept, MOVE_ONLY);
        assert!((estimate.model.shift[0] - 0.5).abs() < 0.01, "{estimate:?}");
        assert!((estimate.model.shift[1] - 0.5).abs() < 0.01, "{estimate:?}");
        assert!(!estimate.ambiguous);
    }
}

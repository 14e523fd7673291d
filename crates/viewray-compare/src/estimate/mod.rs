//! Estimating the camera transform between an expected and an actual image.
//!
//! The model: the actual picture is the expected one mirrored (left-right, upside down, or
//! both), scaled (per axis) and rotated about a point `p`, then moved by `t`. In
//! continuous image coordinates (x right, y down, pixel (row, col) covering
//! [col, col + 1) x [row, row + 1)), what the expected image shows at `X_e` the actual one
//! shows at
//!
//! ```text
//! X_a = p + R(theta) S M (X_e - p) + t      M = diag(+-1, +-1), S = diag(sx, sy)
//! ```
//!
//! with `R(theta)` turning clockwise as seen (x towards y). Only the overlap counts: the
//! actual pixels whose preimage lies inside the expected image (both away from the
//! borders, where the blur saw beyond the picture). What enters the picture at an edge
//! (a lens shift slides the window over the image plane) is no evidence either way.
//!
//! 1. Search (the coarsest pyramid level, 16 to 31 pixels on the shorter side):
//!    for every mirror and each of a grid of rotations (up to 30 degrees) and of scales
//!    (0.68x to 1.47x), the expected image is warped about the centre and its masked
//!    normalized cross-correlation with the actual image is computed for every whole-pixel
//!    move at once with FFTs (Padfield's masked NCC, so that the score counts the overlap
//!    only). Moves of up to the whole image are seen; a candidate needs an overlap of
//!    [`MIN_OVERLAP`] of the picture.
//! 2. Refinement: the best candidates are refined by Levenberg-Marquardt on the sum of
//!    squared differences over the overlap (rotation, per-axis scale and move), level by
//!    level down to full resolution, sampling the expected image bilinearly.
//! 3. Model selection ([`selection::select`]): each component (rotation, aspect ratio, scale, the
//!    move) is removed in turn and the rest refitted; a component stays only if removing
//!    it clearly raises the residual on the overlap.
//!
//! The modules follow those steps: [`model`] is the transform, [`pyramid`] the two images
//! at every level, [`fit`] the sums over the overlap and the Levenberg-Marquardt
//! refinement, [`correlation`] the masked NCC over FFTs, [`search`] the first step and
//! the carrying of its best candidates down the pyramid ([`estimate_search`]), and
//! [`selection`] the last step ([`selection::select`]) and [`estimate_local`], which skips the
//! search. Start reading at [`estimate_search`].

mod correlation;
mod fit;
mod model;
mod pyramid;
mod search;
mod selection;

pub(crate) use fit::textured;
pub(crate) use model::Model;
pub(crate) use pyramid::{ExpectedPyramid, Pyramid};
pub(crate) use search::{estimate_search, verify_move};
pub(crate) use selection::{Estimate, Tolerances, estimate_local};

/// The smallest overlap, as a fraction of the picture, on which a transform found by the
/// search is judged: a move of half the picture in x and y at once leaves a quarter.
pub(crate) const MIN_OVERLAP: f64 = 0.2;

/// The pixels to evaluate at full resolution.
const FINE_BUDGET: usize = 6_000;

#[cfg(test)]
mod test_images;

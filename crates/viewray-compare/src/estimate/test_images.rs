//! Synthetic pictures for the estimate's tests: a smooth pattern of coloured blobs,
//! defined everywhere, so that a picture moved, turned or scaled by a known transform is
//! the pattern sampled through that transform, without any resampling of pixels.

use crate::raster::FloatImage;

use super::model::Model;

/// The pattern's blobs: centre, standard deviation (pixels) and colour.
const BLOBS: [([f64; 2], f64, [f64; 3]); 5] = [
    ([50.0, 40.0], 14.0, [0.9, 0.3, 0.1]),
    ([110.0, 75.0], 18.0, [0.2, 0.7, 0.4]),
    ([80.0, 20.0], 10.0, [0.1, 0.2, 0.9]),
    ([30.0, 95.0], 12.0, [0.8, 0.8, 0.2]),
    ([135.0, 30.0], 9.0, [0.6, 0.1, 0.7]),
];

/// The pattern's colour at continuous image coordinates `p`: coloured Gaussian blobs
/// over a faint ramp, no two alike, so that no move, turn or mirror matches it but the
/// identity.
pub(super) fn pattern(p: [f64; 2]) -> [f32; 3] {
    let mut colour = [0.1 + 0.001 * p[0]; 3];
    for (centre, sigma, tint) in BLOBS {
        let d2 = (p[0] - centre[0]).powi(2) + (p[1] - centre[1]).powi(2);
        let weight = (-d2 / (2.0 * sigma * sigma)).exp();
        for c in 0..3 {
            colour[c] += weight * tint[c];
        }
    }
    colour.map(|v| v as f32)
}

/// A `width` x `height` picture of `colour`, sampled at the pixel centres.
pub(super) fn picture(
    width: usize,
    height: usize,
    colour: impl Fn([f64; 2]) -> [f32; 3],
) -> FloatImage {
    let mut image = FloatImage::new(width, height);
    for row in 0..height {
        for col in 0..width {
            image.pixels[row * width + col] = colour([col as f64 + 0.5, row as f64 + 0.5]);
        }
    }
    image
}

/// The pattern as the actual picture shows it when `model` takes the expected picture
/// (the pattern itself) to the actual one: each pixel shows the pattern at its preimage.
pub(super) fn transformed(width: usize, height: usize, model: &Model) -> FloatImage {
    let inverse = model.inverse_matrix();
    picture(width, height, |x| pattern(model.preimage(&inverse, x)))
}

/// Where `model` takes the point `x` of the expected picture: `p + A (x - p) + t`.
pub(super) fn forward(model: &Model, x: [f64; 2]) -> [f64; 2] {
    let a = model.matrix();
    let d = [x[0] - model.about[0], x[1] - model.about[1]];
    [
        model.about[0] + a[0][0] * d[0] + a[0][1] * d[1] + model.shift[0],
        model.about[1] + a[1][0] * d[0] + a[1][1] * d[1] + model.shift[1],
    ]
}

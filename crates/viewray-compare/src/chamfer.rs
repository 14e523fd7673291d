//! How far apart two sets of edges lie, in pixels: the chamfer distance that a search for
//! a camera descends.
//!
//! The agreement of a label map with a picture ([`crate::CameraCandidates`]) is a needle:
//! it is high only where the map's boundaries fall on the picture's edges within about a
//! pixel, and as low a few pixels off as far away. Searching for a camera (a moved eye)
//! needs a measure that falls steadily as the boundaries approach the edges: the mean
//! distance from each boundary pixel to the nearest edge pixel and from each edge pixel to
//! the nearest boundary pixel, each distance capped at [`CAP`] pixels so that what one
//! side has and the other lacks (a shadow's edge, an object out of view) costs alike
//! wherever the rest lies.

/// The largest distance counted, in pixels.
pub(crate) const CAP: f64 = 16.0;

/// One pixel's step in the chamfer's integer units (a diagonal step is [`DIAGONAL`]):
/// the 3-4 chamfer, within 8% of the Euclidean distance.
const STEP: u16 = 3;
const DIAGONAL: u16 = 4;

/// The capped distance, in chamfer units, from each pixel of a `width x height` image to
/// the nearest marked pixel (row by row; all at the cap when none is marked).
pub(crate) fn distances(marked: &[bool], width: usize, height: usize) -> Vec<u16> {
    let cap = cap_units();
    let mut d: Vec<u16> = marked.iter().map(|&m| if m { 0 } else { cap }).collect();
    // Forward: from the pixels above and to the left.
    for row in 0..height {
        for col in 0..width {
            let p = row * width + col;
            let mut best = d[p];
            if col > 0 {
                best = best.min(d[p - 1] + STEP);
            }
            if row > 0 {
                let up = p - width;
                best = best.min(d[up] + STEP);
                if col > 0 {
                    best = best.min(d[up - 1] + DIAGONAL);
                }
                if col + 1 < width {
                    best = best.min(d[up + 1] + DIAGONAL);
                }
            }
            d[p] = best.min(cap);
        }
    }
    // Backward: from the pixels below and to the right.
    for row in (0..height).rev() {
        for col in (0..width).rev() {
            let p = row * width + col;
            let mut best = d[p];
            if col + 1 < width {
                best = best.min(d[p + 1] + STEP);
            }
            if row + 1 < height {
                let down = p + width;
                best = best.min(d[down] + STEP);
                if col + 1 < width {
                    best = best.min(d[down + 1] + DIAGONAL);
                }
                if col > 0 {
                    best = best.min(d[down - 1] + DIAGONAL);
                }
            }
            d[p] = best.min(cap);
        }
    }
    d
}

/// The mean distance, in pixels, from the `marked` pixels to what `distances` measures
/// from; [`CAP`] when none is marked.
pub(crate) fn mean_distance(distances: &[u16], marked: &[bool]) -> f64 {
    let (mut sum, mut n) = (0_u64, 0_u64);
    for (&d, &m) in distances.iter().zip(marked) {
        if m {
            sum += u64::from(d);
            n += 1;
        }
    }
    if n == 0 {
        return CAP;
    }
    crate::geometry::count(sum) / crate::geometry::count(n) / f64::from(STEP)
}

/// [`CAP`] in chamfer units.
fn cap_units() -> u16 {
    // CAP is a small whole number of pixels.
    (CAP as u16) * STEP
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn distances_grow_by_a_step_a_pixel_and_stop_at_the_cap() {
        let (w, h) = (40, 5);
        let mut marked = vec![false; w * h];
        marked[2 * w + 3] = true;
        let d = distances(&marked, w, h);
        assert_eq!(d[2 * w + 3], 0);
        assert_eq!(d[2 * w + 4], STEP);
        assert_eq!(d[3 * w + 4], DIAGONAL);
        assert_eq!(d[2 * w + 39], cap_units());
        assert!((mean_distance(&d, &marked)).abs() < 1e-12);
        let mut other = vec![false; w * h];
        other[2 * w + 5] = true;
        assert!((mean_distance(&d, &other) - 2.0).abs() < 1e-12);
        assert!((mean_distance(&d, &vec![false; w * h]) - CAP).abs() < 1e-12);
    }
}

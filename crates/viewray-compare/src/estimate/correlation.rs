//! Padfield's masked normalized cross-correlation ("Masked object registration in the
//! Fourier domain", 2012): the correlation of an image with a moved one, over the pixels
//! both hold, for every whole-pixel move at once, with FFTs. The search scores its warps
//! with it.

use std::sync::Arc;

use rustfft::num_complex::Complex32;
use rustfft::{Fft, FftPlanner};

/// The masked normalized cross-correlation of the actual image with warped expected
/// images, for every whole-pixel move at once (Padfield, "Masked object registration in
/// the Fourier domain", 2012).
pub(super) struct Correlator {
    width: usize,
    height: usize,
    padded: [usize; 2],
    row_forward: Arc<dyn Fft<f32>>,
    column_forward: Arc<dyn Fft<f32>>,
    row_inverse: Arc<dyn Fft<f32>>,
    column_inverse: Arc<dyn Fft<f32>>,
    scratch: Vec<Complex32>,
    transposed: Vec<Complex32>,
    /// Spectra of the actual image's mask m_f, of m_f f and of m_f f^2.
    mask_spectrum: Vec<Complex32>,
    value_spectrum: Vec<Complex32>,
    square_spectrum: Vec<Complex32>,
    /// The floor on either side's variance over an overlap, per pixel: a flat overlap
    /// correlates with nothing.
    variance_floor: f64,
}

impl Correlator {
    /// Prepares the actual image `actual` of `width` x `height`, valid where `mask` is 1.
    pub(super) fn new(actual: &[f32], mask: &[f32], width: usize, height: usize) -> Self {
        let padded = [2 * width, 2 * height];
        let mut planner = FftPlanner::new();
        let row_forward = planner.plan_fft_forward(padded[0]);
        let column_forward = planner.plan_fft_forward(padded[1]);
        let row_inverse = planner.plan_fft_inverse(padded[0]);
        let column_inverse = planner.plan_fft_inverse(padded[1]);
        let scratch_len = [&row_forward, &column_forward, &row_inverse, &column_inverse]
            .iter()
            .map(|f| f.get_inplace_scratch_len())
            .max()
            .unwrap_or(0);
        let mut correlator = Self {
            width,
            height,
            padded,
            row_forward,
            column_forward,
            row_inverse,
            column_inverse,
            scratch: vec![Complex32::default(); scratch_len],
            transposed: vec![Complex32::default(); padded[0] * padded[1]],
            mask_spectrum: Vec::new(),
            value_spectrum: Vec::new(),
            square_spectrum: Vec::new(),
            variance_floor: 0.0,
        };
        let (count, sum, sum_sq) =
            actual
                .iter()
                .zip(mask)
                .fold((0.0f64, 0.0f64, 0.0f64), |(n, s, q), (&v, &m)| {
                    let (v, m) = (f64::from(v), f64::from(m));
                    (n + m, s + m * v, q + m * v * v)
                });
        let variance = if count > 0.0 {
            (sum_sq / count - (sum / count).powi(2)).max(0.0)
        } else {
            0.0
        };
        correlator.variance_floor = 0.02 * variance + 1e-6;
        correlator.mask_spectrum = correlator.spectrum(mask, None);
        correlator.value_spectrum = correlator.spectrum(actual, Some(mask));
        let squares: Vec<f32> = actual.iter().map(|v| v * v).collect();
        correlator.square_spectrum = correlator.spectrum(&squares, Some(mask));
        correlator
    }

    /// The 2D FFT of `values` (times `mask`), zero-padded.
    fn spectrum(&mut self, values: &[f32], mask: Option<&[f32]>) -> Vec<Complex32> {
        let mut data = self.pad(|i| values[i] * mask.map_or(1.0, |m| m[i]), |_| 0.0);
        self.fft2(&mut data, false);
        data
    }

    /// The zero-padded complex image with real part `re(i)` and imaginary part `im(i)` at
    /// pixel index `i`.
    fn pad(&self, re: impl Fn(usize) -> f32, im: impl Fn(usize) -> f32) -> Vec<Complex32> {
        let [pw, ph] = self.padded;
        let mut data = vec![Complex32::default(); pw * ph];
        for row in 0..self.height {
            for col in 0..self.width {
                let i = row * self.width + col;
                data[row * pw + col] = Complex32::new(re(i), im(i));
            }
        }
        data
    }

    /// The 2D FFT (or its unnormalized inverse) of the padded `data`, in place.
    fn fft2(&mut self, data: &mut [Complex32], inverse: bool) {
        let [pw, ph] = self.padded;
        let (rows, columns) = if inverse {
            (&self.row_inverse, &self.column_inverse)
        } else {
            (&self.row_forward, &self.column_forward)
        };
        rows.process_with_scratch(data, &mut self.scratch);
        transpose(data, &mut self.transposed, pw, ph);
        columns.process_with_scratch(&mut self.transposed, &mut self.scratch);
        transpose(&self.transposed, data, ph, pw);
    }

    /// The masked NCC of the actual image with the moving image `g` (valid where `mask`
    /// is 1) for every move u: actual(x) against g(x - u). Calls `visit(u, ncc, overlap
    /// pixels)` for every move whose overlap has at least `min_count` pixels.
    pub(super) fn correlate(
        &mut self,
        g: &[f32],
        mask: &[f32],
        min_count: f64,
        mut visit: impl FnMut([i64; 2], f64, f64),
    ) {
        let [pw, ph] = self.padded;
        let size = pw * ph;
        // One complex FFT carries two real images: m_g + i m_g g, then m_g g^2.
        let mut pair = self.pad(|i| mask[i], |i| mask[i] * g[i]);
        self.fft2(&mut pair, false);
        let mut squares = self.pad(|i| mask[i] * g[i] * g[i], |_| 0.0);
        self.fft2(&mut squares, false);
        let mirror_index = |k: usize| {
            let (row, col) = (k / pw, k % pw);
            ((ph - row) % ph) * pw + (pw - col) % pw
        };
        // Products whose inverses are real, packed two to a complex inverse FFT.
        let mut first = vec![Complex32::default(); size];
        let mut second = vec![Complex32::default(); size];
        let mut third = vec![Complex32::default(); size];
        let i = Complex32::new(0.0, 1.0);
        for k in 0..size {
            let z = pair[k];
            let zc = pair[mirror_index(k)].conj();
            let mask_g = (z + zc) * 0.5;
            let value_g = (z - zc) * (-0.5 * i);
            let (mask_g, value_g, square_g) = (mask_g.conj(), value_g.conj(), squares[k].conj());
            let (mf, ff, f2) = (
                self.mask_spectrum[k],
                self.value_spectrum[k],
                self.square_spectrum[k],
            );
            // n + i S_f
            first[k] = mf * mask_g + i * (ff * mask_g);
            // S_g + i S_ff
            second[k] = mf * value_g + i * (f2 * mask_g);
            // S_gg + i S_fg
            third[k] = mf * square_g + i * (ff * value_g);
        }
        self.fft2(&mut first, true);
        self.fft2(&mut second, true);
        self.fft2(&mut third, true);
        let scale = 1.0 / size as f64;
        let floor = self.variance_floor;
        for uy in -(self.height as i64 - 1)..self.height as i64 {
            for ux in -(self.width as i64 - 1)..self.width as i64 {
                let k =
                    (uy.rem_euclid(ph as i64) as usize) * pw + ux.rem_euclid(pw as i64) as usize;
                let n = f64::from(first[k].re) * scale;
                if n < min_count {
                    continue;
                }
                let s_f = f64::from(first[k].im) * scale;
                let s_g = f64::from(second[k].re) * scale;
                let s_ff = f64::from(second[k].im) * scale;
                let s_gg = f64::from(third[k].re) * scale;
                let s_fg = f64::from(third[k].im) * scale;
                let var_f = (s_ff - s_f * s_f / n).max(floor * n);
                let var_g = (s_gg - s_g * s_g / n).max(floor * n);
                let ncc = (s_fg - s_f * s_g / n) / (var_f * var_g).sqrt();
                visit([ux, uy], ncc, n);
            }
        }
    }
}

/// Writes the `width` x `height` array `input` transposed into `output`.
fn transpose(input: &[Complex32], output: &mut [Complex32], width: usize, height: usize) {
    for row in 0..height {
        for col in 0..width {
            output[col * height + row] = input[row * width + col];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Deterministic pseudo-random values in [0, 1).
    fn noise(count: usize, seed: u32) -> Vec<f32> {
        let mut state = seed.wrapping_mul(2_654_435_761) | 1;
        (0..count)
            .map(|_| {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                (state >> 8) as f32 / (1u32 << 24) as f32
            })
            .collect()
    }

    /// Every move's NCC and overlap, by move.
    fn all_moves(
        correlator: &mut Correlator,
        g: &[f32],
        mask: &[f32],
    ) -> Vec<([i64; 2], f64, f64)> {
        let mut moves = Vec::new();
        correlator.correlate(g, mask, 0.5, |u, ncc, n| moves.push((u, ncc, n)));
        moves
    }

    #[test]
    fn the_correlation_peaks_at_one_at_the_planted_move() {
        let (w, h) = (24usize, 20usize);
        let g = noise(w * h, 3);
        let planted = [5i64, -3i64];
        // actual(x) = g(x - planted) where that lies in g; nothing elsewhere.
        let mut actual = vec![0.0f32; w * h];
        let mut mask = vec![0.0f32; w * h];
        for row in 0..h as i64 {
            for col in 0..w as i64 {
                let (source_row, source_col) = (row - planted[1], col - planted[0]);
                if (0..h as i64).contains(&source_row) && (0..w as i64).contains(&source_col) {
                    let i = (row as usize) * w + col as usize;
                    actual[i] = g[source_row as usize * w + source_col as usize];
                    mask[i] = 1.0;
                }
            }
        }
        let mut correlator = Correlator::new(&actual, &mask, w, h);
        let moves = all_moves(&mut correlator, &g, &vec![1.0; w * h]);
        // Among the moves with an overlap of a hundred pixels or more (a few pixels in
        // common correlate by chance).
        let (best, ncc, n) = moves
            .iter()
            .copied()
            .filter(|m| m.2 >= 100.0)
            .max_by(|a, b| a.1.total_cmp(&b.1))
            .unwrap();
        assert_eq!(best, planted);
        assert!((ncc - 1.0).abs() < 1e-3, "{ncc}");
        // The overlap: the 19 x 17 pixels the two have in common.
        assert!((n - 19.0 * 17.0).abs() < 0.01, "{n}");
        // Elsewhere, unrelated noise correlates weakly.
        let runner_up = moves
            .iter()
            .filter(|m| m.0 != planted && m.2 >= 100.0)
            .map(|m| m.1)
            .fold(f64::MIN, f64::max);
        assert!(runner_up < 0.5, "{runner_up}");
    }

    #[test]
    fn every_move_counts_the_pixels_both_images_hold() {
        let (w, h) = (16usize, 12usize);
        let ones = vec![1.0f32; w * h];
        let mut correlator = Correlator::new(&noise(w * h, 5), &ones, w, h);
        let moves = all_moves(&mut correlator, &noise(w * h, 6), &ones);
        // Every move with an overlap, each once.
        assert_eq!(moves.len(), (2 * w - 1) * (2 * h - 1));
        for (u, _, n) in moves {
            let want = (w as i64 - u[0].abs()) * (h as i64 - u[1].abs());
            assert!((n - want as f64).abs() < 0.01, "{u:?} {n}");
        }
        // A floor on the overlap leaves out the moves with less.
        let mut seen = 0;
        correlator.correlate(&noise(w * h, 6), &ones, 100.0, |_, _, n| {
            assert!(n >= 100.0);
            seen += 1;
        });
        assert!(seen > 0 && seen < (2 * w - 1) * (2 * h - 1));
    }
}

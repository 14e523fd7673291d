//! Float RGB images and the few operations the comparisons need: sRGB decoding and
//! encoding (viewray-output's transfer function), Gaussian blur, 2x downsampling, bilinear
//! sampling and gradients.
//!
//! Pixel (row, col) covers [col, col + 1) x [row, row + 1) in continuous image coordinates,
//! so its centre is (col + 0.5, row + 0.5), as in the camera crate's convention.

use image::RgbaImage;
use viewray_output::{linear_to_srgb, srgb_to_linear, unit_to_u8};

/// An RGB image of `f32` channels, row by row from the top-left.
#[derive(Clone, Debug)]
pub(crate) struct FloatImage {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) pixels: Vec<[f32; 3]>,
}

impl FloatImage {
    /// An image of `width` x `height` black pixels.
    pub(crate) fn new(width: usize, height: usize) -> Self {
        Self {
            width,
            height,
            pixels: vec![[0.0; 3]; width * height],
        }
    }

    /// The linear-light colours of an sRGB-encoded RGBA8 image, composited over black
    /// (renders are opaque; a transparent pixel counts as black background).
    pub(crate) fn linear_from_rgba8(image: &RgbaImage) -> Self {
        let table: Vec<f32> = (0..=255u8)
            .map(|code| srgb_to_linear(f32::from(code) / 255.0))
            .collect();
        let pixels = image
            .pixels()
            .map(|p| {
                let alpha = f32::from(p[3]) / 255.0;
                [0, 1, 2].map(|c| table[usize::from(p[c])] * alpha)
            })
            .collect();
        Self {
            width: image.width() as usize,
            height: image.height() as usize,
            pixels,
        }
    }

    /// This linear-light image encoded as sRGB, channels still in [0, 1].
    pub(crate) fn encoded_as_srgb(&self) -> Self {
        Self {
            width: self.width,
            height: self.height,
            pixels: self
                .pixels
                .iter()
                .map(|p| p.map(|c| linear_to_srgb(c.clamp(0.0, 1.0))))
                .collect(),
        }
    }

    /// [`FloatImage::encoded_as_srgb`], taking each channel that is the same bit for bit
    /// as `linear_reference`'s (an image of the same size) from `encoded_reference`, its
    /// encoding, instead of computing it again: the same result, cheaper where two images
    /// agree (a flat background).
    pub(crate) fn encoded_as_srgb_reusing(
        &self,
        linear_reference: &FloatImage,
        encoded_reference: &FloatImage,
    ) -> Self {
        debug_assert_eq!(self.pixels.len(), linear_reference.pixels.len());
        let pixels = self
            .pixels
            .iter()
            .zip(&linear_reference.pixels)
            .zip(&encoded_reference.pixels)
            .map(|((p, reference), encoded)| {
                std::array::from_fn(|c| {
                    if p[c].to_bits() == reference[c].to_bits() {
                        encoded[c]
                    } else {
                        linear_to_srgb(p[c].clamp(0.0, 1.0))
                    }
                })
            })
            .collect();
        Self {
            width: self.width,
            height: self.height,
            pixels,
        }
    }

    /// The channels quantized to 8 bits, RGB interleaved (channels taken as already
    /// encoded).
    pub(crate) fn to_rgb8_bytes(&self) -> Vec<u8> {
        self.pixels.iter().flat_map(|p| p.map(unit_to_u8)).collect()
    }

    /// The pixel at (`row`, `col`).
    pub(crate) fn at(&self, row: usize, col: usize) -> [f32; 3] {
        self.pixels[row * self.width + col]
    }

    /// The pixel at (`row`, `col`) with indices clamped to the image (edge pixels extend
    /// outwards).
    fn at_clamped(&self, row: isize, col: isize) -> [f32; 3] {
        let row = row.clamp(0, self.height as isize - 1) as usize;
        let col = col.clamp(0, self.width as isize - 1) as usize;
        self.at(row, col)
    }

    /// A separable Gaussian blur with standard deviation `sigma` pixels (kernel radius
    /// 3 sigma), edge pixels extended. `sigma <= 0` returns a copy.
    pub(crate) fn gaussian_blur(&self, sigma: f32) -> Self {
        if sigma <= 0.0 {
            return self.clone();
        }
        let radius = (3.0 * sigma).ceil() as isize;
        let mut kernel: Vec<f32> = (-radius..=radius)
            .map(|i| (-(i * i) as f32 / (2.0 * sigma * sigma)).exp())
            .collect();
        let sum: f32 = kernel.iter().sum();
        kernel.iter_mut().for_each(|k| *k /= sum);
        let horizontal = self.convolve(&kernel, radius, true);
        horizontal.convolve(&kernel, radius, false)
    }

    /// Convolves rows (`along_rows`) or columns with a symmetric `kernel` of `radius`,
    /// edge pixels extended. Each output channel is the sum over the kernel's taps, in
    /// order, of `weight * input`, starting from 0; the loops run over whole rows (taps
    /// outside, pixels inside) so that they vectorize without changing that order.
    fn convolve(&self, kernel: &[f32], radius: isize, along_rows: bool) -> Self {
        let (w, h) = (self.width, self.height);
        let mut out = Self::new(w, h);
        let r = radius as usize;
        if along_rows {
            // Each row padded with its edge pixels, then every tap over the whole row.
            let mut padded = vec![[0.0f32; 3]; w + 2 * r];
            for row in 0..h {
                let line = &self.pixels[row * w..(row + 1) * w];
                for (i, slot) in padded.iter_mut().enumerate() {
                    *slot = line[i.saturating_sub(r).min(w - 1)];
                }
                let out_line = out.pixels[row * w..(row + 1) * w].as_flattened_mut();
                for (k, &weight) in kernel.iter().enumerate() {
                    let source = padded[k..k + w].as_flattened();
                    for (o, &p) in out_line.iter_mut().zip(source) {
                        *o += weight * p;
                    }
                }
            }
        } else {
            // Each output row is the weighted sum of whole input rows.
            for row in 0..h {
                let out_line = out.pixels[row * w..(row + 1) * w].as_flattened_mut();
                for (k, weight) in (-radius..=radius).zip(kernel) {
                    let source = (row as isize + k).clamp(0, h as isize - 1) as usize;
                    let line = self.pixels[source * w..(source + 1) * w].as_flattened();
                    for (o, &p) in out_line.iter_mut().zip(line) {
                        *o += weight * p;
                    }
                }
            }
        }
        out
    }

    /// Half the size: each pixel the mean of a 2 x 2 block (an odd last row or column is
    /// dropped), so coarse pixel (r, c) covers fine pixels [2c, 2c + 2) x [2r, 2r + 2).
    pub(crate) fn downsample_2x(&self) -> Self {
        let (width, height) = (self.width / 2, self.height / 2);
        let mut out = Self::new(width, height);
        for row in 0..height {
            for col in 0..width {
                let mut sum = [0.0f32; 3];
                for (dr, dc) in [(0, 0), (0, 1), (1, 0), (1, 1)] {
                    let p = self.at(2 * row + dr, 2 * col + dc);
                    for c in 0..3 {
                        sum[c] += 0.25 * p[c];
                    }
                }
                out.pixels[row * width + col] = sum;
            }
        }
        out
    }

    /// The bilinear interpolation at continuous image coordinates (`x`, `y`) (pixel
    /// centres at half-integers), edge pixels extended.
    pub(crate) fn sample_bilinear(&self, x: f64, y: f64) -> [f32; 3] {
        let fx = (x - 0.5).clamp(0.0, (self.width - 1) as f64);
        let fy = (y - 0.5).clamp(0.0, (self.height - 1) as f64);
        let (x0, y0) = (fx.floor() as usize, fy.floor() as usize);
        let (x1, y1) = ((x0 + 1).min(self.width - 1), (y0 + 1).min(self.height - 1));
        let (tx, ty) = ((fx - x0 as f64) as f32, (fy - y0 as f64) as f32);
        let p00 = self.at(y0, x0);
        let p01 = self.at(y0, x1);
        let p10 = self.at(y1, x0);
        let p11 = self.at(y1, x1);
        [0, 1, 2].map(|c| {
            let top = p00[c] + tx * (p01[c] - p00[c]);
            let bottom = p10[c] + tx * (p11[c] - p10[c]);
            top + ty * (bottom - top)
        })
    }

    /// The horizontal and vertical derivatives by central differences (one-sided at the
    /// edges), per pixel, in channel units per pixel.
    pub(crate) fn gradients(&self) -> (Self, Self) {
        let mut dx = Self::new(self.width, self.height);
        let mut dy = Self::new(self.width, self.height);
        for row in 0..self.height as isize {
            for col in 0..self.width as isize {
                let left = self.at_clamped(row, col - 1);
                let right = self.at_clamped(row, col + 1);
                let up = self.at_clamped(row - 1, col);
                let down = self.at_clamped(row + 1, col);
                let span_x = (col + 1).min(self.width as isize - 1) - (col - 1).max(0);
                let span_y = (row + 1).min(self.height as isize - 1) - (row - 1).max(0);
                let i = row as usize * self.width + col as usize;
                dx.pixels[i] = [0, 1, 2].map(|c| (right[c] - left[c]) / span_x.max(1) as f32);
                dy.pixels[i] = [0, 1, 2].map(|c| (down[c] - up[c]) / span_y.max(1) as f32);
            }
        }
        (dx, dy)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bilinear_sampling_reproduces_pixel_centres_and_interpolates_between() {
        let mut image = FloatImage::new(2, 1);
        image.pixels = vec![[0.0; 3], [1.0; 3]];
        assert_eq!(image.sample_bilinear(0.5, 0.5), [0.0; 3]);
        assert_eq!(image.sample_bilinear(1.5, 0.5), [1.0; 3]);
        assert_eq!(image.sample_bilinear(1.0, 0.5), [0.5; 3]);
        assert_eq!(image.sample_bilinear(1.25, 0.5), [0.75; 3]);
        // Outside, edge pixels extend.
        assert_eq!(image.sample_bilinear(-3.0, 7.0), [0.0; 3]);
        assert_eq!(image.sample_bilinear(9.0, -2.0), [1.0; 3]);
    }

    #[test]
    fn blur_spreads_an_impulse_as_the_gaussian_and_extends_the_edges() {
        let sigma = 1.0f32;
        let g = |d: f32| (-d * d / (2.0 * sigma * sigma)).exp();
        let norm: f32 = (-3..=3).map(|i| g(i as f32)).sum();
        let mut image = FloatImage::new(9, 9);
        image.pixels[4 * 9 + 4] = [1.0, 0.5, 0.0];
        let blurred = image.gaussian_blur(sigma);
        for (row, col) in [(4, 4), (4, 6), (2, 5), (7, 4)] {
            let want = g(row as f32 - 4.0) * g(col as f32 - 4.0) / (norm * norm);
            let got = blurred.at(row, col);
            assert!((got[0] - want).abs() < 1e-6 && (got[1] - 0.5 * want).abs() < 1e-6);
        }
        // A bright left column, extended beyond the edge, stays as bright at the edge.
        let mut edge = FloatImage::new(9, 3);
        for row in 0..3 {
            edge.pixels[row * 9] = [1.0; 3];
        }
        let blurred = edge.gaussian_blur(sigma);
        let want: f32 = (-3..=0).map(|i| g(i as f32)).sum::<f32>() / norm;
        assert!((blurred.at(1, 0)[0] - want).abs() < 1e-6);
    }

    /// A deterministic image of pseudo-random channels in [0, 1.2).
    fn noise(width: usize, height: usize, seed: u32) -> FloatImage {
        let mut state = seed.wrapping_mul(2_654_435_761) | 1;
        let mut image = FloatImage::new(width, height);
        for pixel in &mut image.pixels {
            *pixel = [0, 1, 2].map(|_| {
                state ^= state << 13;
                state ^= state >> 17;
                state ^= state << 5;
                (state >> 8) as f32 / (1u32 << 24) as f32 * 1.2
            });
        }
        image
    }

    #[test]
    fn blur_sums_each_pixel_as_the_direct_convolution_does_bit_for_bit() {
        // The direct form: each output the sum over the taps, in order, from 0, of the
        // edge-extended input, rows first.
        let direct = |image: &FloatImage, sigma: f32| -> FloatImage {
            let radius = (3.0 * sigma).ceil() as isize;
            let mut kernel: Vec<f32> = (-radius..=radius)
                .map(|i| (-(i * i) as f32 / (2.0 * sigma * sigma)).exp())
                .collect();
            let sum: f32 = kernel.iter().sum();
            kernel.iter_mut().for_each(|k| *k /= sum);
            let pass = |image: &FloatImage, along_rows: bool| {
                let mut out = FloatImage::new(image.width, image.height);
                for row in 0..image.height as isize {
                    for col in 0..image.width as isize {
                        let mut acc = [0.0f32; 3];
                        for (k, weight) in (-radius..=radius).zip(&kernel) {
                            let p = if along_rows {
                                image.at_clamped(row, col + k)
                            } else {
                                image.at_clamped(row + k, col)
                            };
                            for c in 0..3 {
                                acc[c] += weight * p[c];
                            }
                        }
                        out.pixels[row as usize * image.width + col as usize] = acc;
                    }
                }
                out
            };
            pass(&pass(image, true), false)
        };
        for (width, height, sigma) in [(37, 23, 2.0), (5, 40, 2.0), (64, 48, 1.0), (1, 1, 2.0)] {
            let image = noise(width, height, width as u32);
            let (fast, slow) = (image.gaussian_blur(sigma), direct(&image, sigma));
            assert!(
                fast.pixels
                    .iter()
                    .zip(&slow.pixels)
                    .all(|(a, b)| (0..3).all(|c| a[c].to_bits() == b[c].to_bits())),
                "{width}x{height}"
            );
        }
    }

    #[test]
    fn encoding_that_reuses_a_references_channels_is_the_same_bit_for_bit() {
        let reference = noise(40, 30, 7);
        let encoded_reference = reference.encoded_as_srgb();
        // Half the pixels the reference's, the rest other values (some out of [0, 1]).
        let mut image = noise(40, 30, 8);
        for (i, pixel) in image.pixels.iter_mut().enumerate() {
            if i % 2 == 0 {
                *pixel = reference.pixels[i];
            }
        }
        let reused = image.encoded_as_srgb_reusing(&reference, &encoded_reference);
        let plain = image.encoded_as_srgb();
        assert!(
            reused
                .pixels
                .iter()
                .zip(&plain.pixels)
                .all(|(a, b)| (0..3).all(|c| a[c].to_bits() == b[c].to_bits()))
        );
    }

    #[test]
    fn blur_keeps_the_mean_of_a_uniform_image_and_downsampling_averages_blocks() {
        let mut image = FloatImage::new(4, 2);
        image.pixels = vec![[0.25; 3]; 8];
        assert!(
            image
                .gaussian_blur(1.5)
                .pixels
                .iter()
                .all(|p| (p[0] - 0.25).abs() < 1e-6)
        );
        image.pixels[0] = [1.0; 3];
        let half = image.downsample_2x();
        assert_eq!((half.width, half.height), (2, 1));
        assert!((half.pixels[0][0] - (1.0 + 3.0 * 0.25) / 4.0).abs() < 1e-6);
    }
}

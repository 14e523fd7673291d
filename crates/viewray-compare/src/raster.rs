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

/// Where a continuous coordinate falls between pixel centres along one axis: the two
/// neighbouring indices (clamped to the image) and the weight of the higher one.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct AxisSample {
    pub(crate) low: usize,
    pub(crate) high: usize,
    pub(crate) t: f32,
}

impl AxisSample {
    /// The neighbours of continuous coordinate `x` (pixel centres at half-integers) on an
    /// axis of `size` pixels, edge pixels extended.
    pub(crate) fn new(x: f64, size: usize) -> Self {
        let f = x - 0.5;
        let floor = f.floor();
        let last = size as f64 - 1.0;
        Self {
            low: floor.clamp(0.0, last) as usize,
            high: (floor + 1.0).clamp(0.0, last) as usize,
            t: (f - floor) as f32,
        }
    }
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

    /// Convolves rows (`along_rows`) or columns with a symmetric `kernel` of `radius`.
    fn convolve(&self, kernel: &[f32], radius: isize, along_rows: bool) -> Self {
        let mut out = Self::new(self.width, self.height);
        for row in 0..self.height as isize {
            for col in 0..self.width as isize {
                let mut sum = [0.0f32; 3];
                for (k, weight) in (-radius..=radius).zip(kernel) {
                    let p = if along_rows {
                        self.at_clamped(row, col + k)
                    } else {
                        self.at_clamped(row + k, col)
                    };
                    for c in 0..3 {
                        sum[c] += weight * p[c];
                    }
                }
                out.pixels[row as usize * self.width + col as usize] = sum;
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
    #[cfg(test)]
    pub(crate) fn sample_bilinear(&self, x: f32, y: f32) -> [f32; 3] {
        let (fx, fy) = (x - 0.5, y - 0.5);
        let (x0, y0) = (fx.floor(), fy.floor());
        let (tx, ty) = (fx - x0, fy - y0);
        let (c0, r0) = (x0 as isize, y0 as isize);
        let p00 = self.at_clamped(r0, c0);
        let p01 = self.at_clamped(r0, c0 + 1);
        let p10 = self.at_clamped(r0 + 1, c0);
        let p11 = self.at_clamped(r0 + 1, c0 + 1);
        [0, 1, 2].map(|c| {
            let top = p00[c] + tx * (p01[c] - p00[c]);
            let bottom = p10[c] + tx * (p11[c] - p10[c]);
            top + ty * (bottom - top)
        })
    }

    /// The bilinear interpolation at a point given by its weights along each axis (see
    /// [`AxisSample`]): the same value as `FloatImage::sample_bilinear`, much cheaper when
    /// a whole row of points shares `y` and a whole column shares `x`.
    pub(crate) fn sample_separable(&self, y: AxisSample, x: AxisSample) -> [f32; 3] {
        let p00 = self.at(y.low, x.low);
        let p01 = self.at(y.low, x.high);
        let p10 = self.at(y.high, x.low);
        let p11 = self.at(y.high, x.high);
        [0, 1, 2].map(|c| {
            let top = p00[c] + x.t * (p01[c] - p00[c]);
            let bottom = p10[c] + x.t * (p11[c] - p10[c]);
            top + y.t * (bottom - top)
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
        // Outside, edge pixels extend.
        assert_eq!(image.sample_bilinear(-3.0, 7.0), [0.0; 3]);
        for x in [-1.0, 0.2, 0.75, 1.0, 1.3, 2.5, 9.0] {
            let separable = image.sample_separable(AxisSample::new(0.5, 1), AxisSample::new(x, 2));
            let direct = image.sample_bilinear(x as f32, 0.5);
            assert!((separable[0] - direct[0]).abs() < 1e-6, "{x}");
        }
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

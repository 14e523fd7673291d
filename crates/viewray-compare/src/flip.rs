//! NVIDIA's FLIP (LDR-FLIP) through the `nv-flip` bindings to the reference C++ code, and
//! the statistics this crate reads from its error map.

use image::RgbImage;

/// A per-pixel FLIP error map: values in [0, 1], 0 where a viewer sees no difference.
#[derive(Clone, Debug)]
pub(crate) struct ErrorMap {
    pub(crate) width: usize,
    pub(crate) height: usize,
    pub(crate) values: Vec<f32>,
}

/// The side of the square window over which [`ErrorMap::peak`] averages: 3 x 3 pixels.
///
/// A lone pixel that differs (one sample that grazed an edge differently on another
/// machine) contributes at most a ninth of its error; an edge moved by a pixel fills the
/// window along its length and keeps most of its error.
pub(crate) const PEAK_WINDOW: usize = 3;

/// Runs LDR-FLIP on two sRGB-encoded RGB8 images of `width` x `height` at FLIP's default
/// 67 pixels per degree (a 0.7 m viewing distance from a 24-inch 4K monitor).
pub(crate) fn flip(
    reference_rgb8: &[u8],
    test_rgb8: &[u8],
    width: usize,
    height: usize,
) -> ErrorMap {
    let (w, h) = (width as u32, height as u32);
    let reference = nv_flip::FlipImageRgb8::with_data(w, h, reference_rgb8);
    let test = nv_flip::FlipImageRgb8::with_data(w, h, test_rgb8);
    let map = nv_flip::flip(reference, test, nv_flip::DEFAULT_PIXELS_PER_DEGREE);
    ErrorMap {
        width,
        height,
        values: map.to_vec(),
    }
}

impl ErrorMap {
    /// The mean error over all pixels (the single number FLIP's authors recommend).
    pub(crate) fn mean(&self) -> f32 {
        let sum: f64 = self.values.iter().map(|&v| f64::from(v)).sum();
        (sum / self.values.len().max(1) as f64) as f32
    }

    /// The largest mean error over any `window` x `window` block of pixels (windows
    /// clipped at the image's edges still divide by the full window area).
    pub(crate) fn peak(&self, window: usize) -> f32 {
        let (w, h) = (self.width, self.height);
        // A summed-area table: table[(r) * (w + 1) + c] sums rows < r, columns < c.
        let mut table = vec![0.0f64; (w + 1) * (h + 1)];
        for r in 0..h {
            let mut row_sum = 0.0;
            for c in 0..w {
                row_sum += f64::from(self.values[r * w + c]);
                table[(r + 1) * (w + 1) + c + 1] = table[r * (w + 1) + c + 1] + row_sum;
            }
        }
        let area = (window * window) as f64;
        let mut peak = 0.0f64;
        let (win_w, win_h) = (window.min(w), window.min(h));
        for r in 0..=(h - win_h) {
            for c in 0..=(w - win_w) {
                let (r1, c1) = (r + win_h, c + win_w);
                let sum =
                    table[r1 * (w + 1) + c1] - table[r * (w + 1) + c1] - table[r1 * (w + 1) + c]
                        + table[r * (w + 1) + c];
                peak = peak.max(sum / area);
            }
        }
        peak as f32
    }

    /// The error map through FLIP's magma colour map: black where nothing differs, through
    /// purple and orange to pale yellow at the largest error.
    pub(crate) fn heatmap(&self) -> RgbImage {
        let (w, h) = (self.width as u32, self.height as u32);
        let map = nv_flip::FlipImageFloat::with_data(w, h, &self.values);
        let colored = map.apply_color_lut(&nv_flip::magma_lut());
        RgbImage::from_raw(w, h, colored.to_vec()).expect("the colour map keeps the image size")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_images_have_zero_error_and_a_black_heatmap() {
        let pixels: Vec<u8> = (0..16 * 8 * 3).map(|i| (i * 7 % 256) as u8).collect();
        let map = flip(&pixels, &pixels, 16, 8);
        assert_eq!(map.mean(), 0.0);
        assert_eq!(map.peak(PEAK_WINDOW), 0.0);
        let heatmap = map.heatmap();
        assert_eq!(heatmap.dimensions(), (16, 8));
        assert!(heatmap.pixels().all(|p| p.0 == heatmap.get_pixel(0, 0).0));
    }

    #[test]
    fn the_peak_window_averages_a_lone_pixel_away_but_not_a_block() {
        let mut map = ErrorMap {
            width: 10,
            height: 10,
            values: vec![0.0; 100],
        };
        map.values[55] = 0.9;
        assert!((map.peak(3) - 0.1).abs() < 1e-6);
        for r in 2..5 {
            for c in 2..5 {
                map.values[r * 10 + c] = 0.6;
            }
        }
        assert!((map.peak(3) - 0.6).abs() < 1e-6);
        assert!((map.mean() - (0.9 + 9.0 * 0.6) / 100.0).abs() < 1e-6);
    }
}

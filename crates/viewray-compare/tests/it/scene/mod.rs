//! A small analytic scene rendered through the lecture's pixel -> image-plane mapping, with
//! the classic camera mistakes as switches and several antialiasing patterns: test images
//! whose right answer is known exactly.
//!
//! The image plane spans vw x vh = 4 x 3 units; pixel (row, col) with sample offset
//! (sx, sy) looks at
//!
//! ```text
//! u =  ((col + sx) / W - 1/2) * vw
//! v = -((row + sy) / H - 1/2) * vh
//! ```
//!
//! Each sample's linear colour is averaged over the pixel, then encoded as sRGB 8-bit, as
//! a renderer does.

#![allow(dead_code, unreachable_pub)]

use image::{Rgba, RgbaImage};

/// How the student's camera differs from the right one.
#[derive(Clone, Copy, Debug)]
pub struct Mistake {
    /// u = -u: the picture mirrored left-right (u = w x up instead of up x w).
    pub mirror_x: bool,
    /// v = -v: the picture upside down.
    pub mirror_y: bool,
    /// The viewport divided by this: the content appears `scale` times larger.
    pub scale: f64,
    /// The content moved by this many pixels (x right, y down): (0.5, 0.5) is the
    /// missing pixel-centre offset.
    pub shift: (f64, f64),
}

impl Mistake {
    /// The right camera.
    pub const NONE: Mistake = Mistake {
        mirror_x: false,
        mirror_y: false,
        scale: 1.0,
        shift: (0.0, 0.0),
    };
}

/// Where the samples of a pixel lie.
#[derive(Clone, Copy, Debug)]
pub enum Pattern {
    /// One sample at the pixel centre.
    Center,
    /// An n x n grid of samples at the centres of the cells.
    Grid(u32),
    /// n x n stratified samples, each jittered in its cell (seeded).
    Jittered(u32, u64),
    /// n uniform random samples (seeded).
    Random(u32, u64),
}

const VW: f64 = 4.0;
const VH: f64 = 3.0;

/// The scene's colours and shapes; `red` is the colour of the big disc, so a test can
/// change it.
#[derive(Clone, Copy, Debug)]
pub struct Scene {
    /// The big disc's linear colour.
    pub red: [f64; 3],
    /// Moves the triangle by this much in (u, v) units.
    pub triangle_offset: (f64, f64),
    /// Whether the small white disc is drawn.
    pub white_disc: bool,
}

impl Default for Scene {
    fn default() -> Self {
        Self {
            red: [0.8, 0.1, 0.1],
            triangle_offset: (0.0, 0.0),
            white_disc: true,
        }
    }
}

impl Scene {
    /// The linear colour seen at image-plane point (u, v).
    pub fn color_at(&self, u: f64, v: f64) -> [f64; 3] {
        let mut color = [0.02, 0.03, 0.05];
        // A thin blue bar near the top.
        if (-0.3..1.6).contains(&u) && (1.05..1.2).contains(&v) {
            color = [0.1, 0.2, 0.9];
        }
        // A shaded disc, like a lit sphere.
        let (du, dv) = (u + 0.7, v - 0.3);
        let r2 = (du * du + dv * dv) / (0.5 * 0.5);
        if r2 < 1.0 {
            let nz = (1.0 - r2).sqrt();
            let light = 0.25 + 0.75 * (0.4 * (-du / 0.5) + 0.4 * (dv / 0.5) + 0.8 * nz).max(0.0);
            color = self.red.map(|c| c * light);
        }
        let (tu, tv) = self.triangle_offset;
        if inside(
            &[
                (0.3 + tu, -0.2 + tv),
                (1.4 + tu, -0.1 + tv),
                (0.8 + tu, 0.9 + tv),
            ],
            u,
            v,
        ) {
            color = [0.1, 0.7, 0.2];
        }
        if inside(
            &[(-1.5, -1.2), (-0.2, -0.9), (-0.35, -0.4), (-1.6, -0.7)],
            u,
            v,
        ) {
            color = [0.9, 0.8, 0.1];
        }
        let (wu, wv) = (u - 1.2, v + 0.9);
        if self.white_disc && wu * wu + wv * wv < 0.15 * 0.15 {
            color = [0.9, 0.9, 0.9];
        }
        color
    }

    /// Renders a `width` x `height` image with `pattern`, through the camera with
    /// `mistake`.
    pub fn render(&self, width: u32, height: u32, mistake: Mistake, pattern: Pattern) -> RgbaImage {
        RgbaImage::from_fn(width, height, |col, row| {
            let samples = samples(pattern, row, col);
            let mut sum = [0.0; 3];
            for &(sx, sy) in &samples {
                let x = f64::from(col) + sx - mistake.shift.0;
                let y = f64::from(row) + sy - mistake.shift.1;
                // The image plane seen around the centre, magnified by `scale`.
                let mut u = (x / f64::from(width) - 0.5) * VW / mistake.scale;
                let mut v = -(y / f64::from(height) - 0.5) * VH / mistake.scale;
                if mistake.mirror_x {
                    u = -u;
                }
                if mistake.mirror_y {
                    v = -v;
                }
                let c = self.color_at(u, v);
                for k in 0..3 {
                    sum[k] += c[k];
                }
            }
            let n = samples.len() as f64;
            let encode = |linear: f64| viewray_output::linear_to_srgb8((linear / n) as f32);
            Rgba([encode(sum[0]), encode(sum[1]), encode(sum[2]), 255])
        })
    }
}

/// The right render with `pattern`, no mistake.
pub fn render(width: u32, height: u32, mistake: Mistake, pattern: Pattern) -> RgbaImage {
    Scene::default().render(width, height, mistake, pattern)
}

fn inside(polygon: &[(f64, f64)], u: f64, v: f64) -> bool {
    // Even-odd rule.
    let mut inside = false;
    let mut j = polygon.len() - 1;
    for i in 0..polygon.len() {
        let (ui, vi) = polygon[i];
        let (uj, vj) = polygon[j];
        if (vi > v) != (vj > v) && u < (uj - ui) * (v - vi) / (vj - vi) + ui {
            inside = !inside;
        }
        j = i;
    }
    inside
}

/// A random number in [0, 1) from (seed, row, col, index) alone: splitmix64.
fn random(seed: u64, row: u32, col: u32, index: u32) -> f64 {
    let mut z = seed
        ^ (u64::from(row) << 40)
        ^ (u64::from(col) << 20)
        ^ u64::from(index).wrapping_mul(0x9e37_79b9_7f4a_7c15);
    z = z.wrapping_add(0x9e37_79b9_7f4a_7c15);
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^= z >> 31;
    (z >> 11) as f64 / (1u64 << 53) as f64
}

fn samples(pattern: Pattern, row: u32, col: u32) -> Vec<(f64, f64)> {
    match pattern {
        Pattern::Center => vec![(0.5, 0.5)],
        Pattern::Grid(n) => (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                (
                    (f64::from(i) + 0.5) / f64::from(n),
                    (f64::from(j) + 0.5) / f64::from(n),
                )
            })
            .collect(),
        Pattern::Jittered(n, seed) => (0..n * n)
            .map(|k| {
                let (i, j) = (k % n, k / n);
                (
                    (f64::from(i) + random(seed, row, col, 2 * k)) / f64::from(n),
                    (f64::from(j) + random(seed, row, col, 2 * k + 1)) / f64::from(n),
                )
            })
            .collect(),
        Pattern::Random(n, seed) => (0..n)
            .map(|k| {
                (
                    random(seed, row, col, 2 * k),
                    random(seed, row, col, 2 * k + 1),
                )
            })
            .collect(),
    }
}

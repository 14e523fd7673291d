//! Small synthetic renders for compare's and grade's tests: shapes sampled as a camera
//! would, mirrored or moved on request, so that a test knows the mistake it planted.

use image::{Rgba, RgbaImage};

/// A small picture: a red disc, a green triangle and a yellow bar on a dark background,
/// seen through a camera whose image may be mirrored left-right, moved by `shift_x`
/// pixels, and sampled `n` x `n` times per pixel.
pub(crate) fn picture(width: u32, height: u32, n: u32, mirrored: bool, shift_x: f64) -> RgbaImage {
    let color_at = |x: f64, y: f64| -> [f64; 3] {
        let (u, v) = (x / f64::from(width), y / f64::from(height));
        let u = if mirrored { 1.0 - u } else { u };
        let (du, dv) = ((u - 0.3) * 4.0 / 3.0, v - 0.4);
        if du * du + dv * dv < 0.18 * 0.18 {
            return [0.8, 0.1, 0.1];
        }
        // A triangle with vertices (0.6, 0.2), (0.9, 0.7), (0.55, 0.75).
        let edge = |(ax, ay): (f64, f64), (bx, by): (f64, f64)| {
            (bx - ax) * (v - ay) - (by - ay) * (u - ax)
        };
        let (a, b, c) = ((0.6, 0.2), (0.9, 0.7), (0.55, 0.75));
        if edge(a, b) > 0.0 && edge(b, c) > 0.0 && edge(c, a) > 0.0 {
            return [0.1, 0.7, 0.2];
        }
        if (0.1..0.45).contains(&u) && (0.78..0.86).contains(&v) {
            return [0.9, 0.8, 0.1];
        }
        [0.02, 0.03, 0.05]
    };
    RgbaImage::from_fn(width, height, |col, row| {
        let mut sum = [0.0; 3];
        for k in 0..n * n {
            let sx = (f64::from(k % n) + 0.5) / f64::from(n);
            let sy = (f64::from(k / n) + 0.5) / f64::from(n);
            let c = color_at(f64::from(col) + sx - shift_x, f64::from(row) + sy);
            for i in 0..3 {
                sum[i] += c[i] / f64::from(n * n);
            }
        }
        let encode = |l: f64| viewray_output::linear_to_srgb8(l as f32);
        Rgba([encode(sum[0]), encode(sum[1]), encode(sum[2]), 255])
    })
}

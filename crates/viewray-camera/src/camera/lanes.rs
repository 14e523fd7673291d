//! A round, untilted thin lens's viewing rays four pixels at a time, in the lanes of AVX2
//! registers: the thin-lens rule of [`Camera::generate_ray`](super::Camera::generate_ray)
//! with the same operations in the same order in every lane, so every ray is the one a
//! pixel gets alone, bit for bit. One at a time, a sample's image-plane point, iris point
//! and two frame transforms had been about 120 instructions.

use std::arch::x86_64::{
    _mm256_add_pd, _mm256_div_pd, _mm256_mul_pd, _mm256_set_pd, _mm256_set1_pd, _mm256_sub_pd,
    _mm256_xor_pd,
};

use glam::{DVec2, DVec3};
use viewray_geometry::DRay;

use super::CameraSample;
use crate::sampling::{F64x4, load, sample_unit_disk_concentric_avx2, store};
use crate::{Frame, ThinLens};

/// How many pixels' rays go through the lanes together.
pub(super) const LANES: usize = 4;

/// What the rays of a round, untilted thin lens share: the camera's numbers and the
/// terms of its rule that are the same for every ray.
#[derive(Clone, Copy, Debug)]
pub(super) struct RoundLens {
    /// The image size `(W, H)`.
    size: DVec2,
    /// The viewport `(vw, vh)`.
    viewport: DVec2,
    /// The viewport shift `(sx, sy)`.
    shift: DVec2,
    /// The aperture's radius.
    aperture: f64,
    /// `f / d`.
    focus_over_distance: f64,
    /// The eye `e`.
    eye: DVec3,
    /// The frame's `U`.
    u: DVec3,
    /// The frame's `V`.
    v: DVec3,
    /// `0 W`: the last term of every lens point's frame transform (the lens point's
    /// camera `z` is 0).
    origin_w: DVec3,
    /// `((f / d) (-d)) W`: the last term of every direction's frame transform.
    direction_w: DVec3,
}

impl RoundLens {
    /// The shared terms of `lens`'s rays on an image of `size` pixels seen from `frame`.
    #[inline]
    pub(super) fn new(lens: &ThinLens, size: DVec2, frame: &Frame) -> Self {
        let focus_over_distance = lens.focus / lens.distance;
        // The camera `z` of `f / d (u + sx, v + sy, -d) - (ax, ay, 0)`.
        // (`- 0` leaves every number as it is, `-0` included).
        let direction_z = focus_over_distance * -lens.distance;
        Self {
            size,
            viewport: lens.viewport,
            shift: lens.shift,
            aperture: lens.aperture,
            focus_over_distance,
            eye: frame.e(),
            u: frame.u(),
            v: frame.v(),
            origin_w: 0.0 * frame.w(),
            direction_w: direction_z * frame.w(),
        }
    }

    /// The rays of the first `filled` of the four pixels `(row, col + k)` through their
    /// samples `samples[k]`, handed to `ray` pixel by pixel.
    ///
    /// Per lane, `camera_space_ray`'s thin-lens rule: the image point
    /// `(col + k + film x, row + film y)` (`col + k` exact in `f64`), the image-plane
    /// point `u = (x / W - 1/2) vw`, `v = -(y / H - 1/2) vh` (`image_to_image_plane`), the
    /// lens point `a = aperture * disk(p_lens)`, the direction
    /// `c = f / d (u + sx, v + sy, -d) - (ax, ay, 0)`; then `Frame`'s transforms, the
    /// origin `e + ((ax U + ay V) + 0 W)` and the direction `(cx U + cy V) + cz W`.
    #[target_feature(enable = "avx2")]
    #[inline]
    pub(super) fn rays_avx2(
        &self,
        (row, col): (u32, u32),
        samples: &[CameraSample; LANES],
        filled: usize,
        ray: &mut impl FnMut(u32, u32, Option<DRay>),
    ) {
        let (add, mul, sub) = (_mm256_add_pd, _mm256_mul_pd, _mm256_sub_pd);
        let splat = |value| _mm256_set1_pd(value);
        let columns = add(splat(f64::from(col)), _mm256_set_pd(3.0, 2.0, 1.0, 0.0));
        let x = add(columns, gather(samples, |s| s.p_film.x));
        let y = add(splat(f64::from(row)), gather(samples, |s| s.p_film.y));
        let half = splat(0.5);
        let u = mul(
            sub(_mm256_div_pd(x, splat(self.size.x)), half),
            splat(self.viewport.x),
        );
        let v_up = sub(_mm256_div_pd(y, splat(self.size.y)), half);
        // `-(y / H - 1/2)`: the sign bit flipped, as `f64`'s negation.
        let v = mul(_mm256_xor_pd(v_up, splat(-0.0)), splat(self.viewport.y));
        let (disk_x, disk_y) = sample_unit_disk_concentric_avx2(
            gather(samples, |s| s.p_lens.x),
            gather(samples, |s| s.p_lens.y),
        );
        let aperture = splat(self.aperture);
        let (lens_x, lens_y) = (mul(aperture, disk_x), mul(aperture, disk_y));
        let fd = splat(self.focus_over_distance);
        let camera_x = sub(mul(fd, add(u, splat(self.shift.x))), lens_x);
        let camera_y = sub(mul(fd, add(v, splat(self.shift.y))), lens_y);
        // `Frame::world_from_camera_xy`, coordinate by coordinate: `x U + y V + last`.
        let transform = |x: F64x4, y: F64x4, last: DVec3, axis: usize| {
            let across = mul(x, splat(self.u[axis]));
            add(add(across, mul(y, splat(self.v[axis]))), splat(last[axis]))
        };
        let origin = [0, 1, 2].map(|axis| {
            let offset = transform(lens_x, lens_y, self.origin_w, axis);
            store(add(splat(self.eye[axis]), offset))
        });
        let direction =
            [0, 1, 2].map(|axis| store(transform(camera_x, camera_y, self.direction_w, axis)));
        for (lane, col) in (col..).take(filled).enumerate() {
            let origin = DVec3::new(origin[0][lane], origin[1][lane], origin[2][lane]);
            let direction = DVec3::new(direction[0][lane], direction[1][lane], direction[2][lane]);
            ray(row, col, Some(DRay::new(origin, direction)));
        }
    }
}

/// One coordinate of four samples in the lanes of a register.
#[target_feature(enable = "avx2")]
#[inline]
fn gather(samples: &[CameraSample; LANES], coordinate: impl Fn(&CameraSample) -> f64) -> F64x4 {
    load(&samples.each_ref().map(coordinate))
}

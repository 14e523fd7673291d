//! Viewing rays a block of pixels at a time: what a block's rays share is worked out
//! once, and every ray is still bit for bit the one [`Camera::generate_ray`] makes.

use std::ops::Range;

use glam::{DVec2, DVec3};
use viewray_geometry::DRay;

#[cfg(target_arch = "x86_64")]
use super::lanes::{LANES, RoundLens};
use super::{Camera, CameraSample, image_to_image_plane, image_x_to_u, image_y_to_v};
use crate::{Perspective, Projection, ThinLens};

/// What every ray of a block shares, by family: [`Camera::generate_sampled_block_rays`]'s
/// shortcuts, each the family's rule of [`Camera::generate_ray`] with its shared numbers
/// taken out (the same operations in the same order, so the same bits).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Shortcut {
    /// A perspective camera with its shared terms ([`super::Pinhole`]): the direction
    /// `(u + sx) U + (v + sy) V + (-d w)` from the eye.
    Pinhole {
        /// The camera's perspective projection (viewport and shift).
        projection: Perspective,
        /// The eye (or what a mistake puts in its place).
        origin: DVec3,
        /// `-d w`.
        depth: DVec3,
    },
    /// An orthographic camera without a lens, or an oblique one, without mistakes: every
    /// ray has the same direction and starts at `e + ((u U + v V) + 0 W)`.
    Parallel {
        /// The viewport `(vw, vh)`.
        viewport: DVec2,
        /// `0 W`: the last term of the frame transform of every origin `(u, v, 0)` (not
        /// left out: it turns a coordinate `-0` into `+0`).
        flat: DVec3,
        /// The world direction every ray shares.
        direction: DVec3,
    },
    /// An untilted thin lens with a round aperture, without mistakes: as
    /// [`Shortcut::ThinLens`], and four rays at a time in AVX2 lanes
    /// ([`Camera::generate_sampled_block_rays_avx2`]).
    RoundLens(ThinLens),
    /// An untilted thin lens with blades, without mistakes: its checks taken once,
    /// `f / d` divided once.
    ThinLens(ThinLens),
    /// Every other camera: ray by ray.
    General,
}

impl Camera {
    /// The viewing rays through the same point `sample` of every pixel of the block
    /// `rows x cols`, row by row: `ray(row, col, r)` is called with exactly what
    /// [`Camera::generate_ray`]`(row, col, sample)` returns, bit for bit.
    ///
    /// A renderer taking one sample per pixel (or a depth pass through the pixel
    /// centres) asks for a block of rays at a time. For a perspective camera the
    /// direction `u U + v V - d w` is separable: `u` depends on the column alone and `v`
    /// on the row alone, so a block of at most 16 columns works out each column's `u U`
    /// and each row's `v V` once, and every ray is their sum (the same operations in the
    /// same order as one ray at a time). Other blocks and families go ray by ray.
    #[inline]
    pub fn generate_block_rays(
        &self,
        rows: Range<u32>,
        cols: Range<u32>,
        sample: CameraSample,
        mut ray: impl FnMut(u32, u32, Option<DRay>),
    ) {
        /// The widest block whose column terms fit in the array below.
        const MAX_COLUMNS: usize = 16;
        if let (Projection::Perspective(p), Some(pinhole)) = (&self.projection, &self.pinhole)
            && cols.len() <= MAX_COLUMNS
        {
            let size = self.size();
            // The first term of `world_from_camera_xy` for each column, the second for
            // each row: `direction(uv) = (u + sx, v + sy, -d)`.
            let mut across = [DVec3::ZERO; MAX_COLUMNS];
            for (term, col) in across.iter_mut().zip(cols.clone()) {
                let u = image_x_to_u(f64::from(col) + sample.p_film.x, size.x, p.viewport.x);
                *term = (u + p.shift.x) * self.frame.u();
            }
            for row in rows {
                let v = image_y_to_v(f64::from(row) + sample.p_film.y, size.y, p.viewport.y);
                let down = (v + p.shift.y) * self.frame.v();
                for (col, term) in cols.clone().zip(&across) {
                    let direction = *term + down + pinhole.depth;
                    ray(row, col, Some(DRay::new(pinhole.origin, direction)));
                }
            }
            return;
        }
        for row in rows {
            for col in cols.clone() {
                ray(row, col, self.generate_ray(row, col, sample));
            }
        }
    }

    /// The viewing rays of the block `rows x cols`, row by row, each through its own
    /// sample: `ray(row, col, r)` is called with exactly what
    /// [`Camera::generate_ray`]`(row, col, sample(row, col))` returns, bit for bit.
    ///
    /// A renderer taking several samples per pixel asks for a block of rays at a time.
    /// What every ray of the block shares is worked out once: the family's match and
    /// checks, the image size, the frame's axes and, by family, the eye and `-d w` of a
    /// perspective camera, the one direction of a parallel camera (orthographic without
    /// a lens, oblique) and `f / d` of an untilted thin lens. Each ray is then its
    /// image-plane point and the frame transform, the same operations in the same order
    /// as one ray at a time. Other cameras (fisheyes, tilted or mistaken lenses,
    /// mistaken parallel cameras) go ray by ray.
    #[inline]
    pub fn generate_sampled_block_rays(
        &self,
        rows: Range<u32>,
        cols: Range<u32>,
        mut sample: impl FnMut(u32, u32) -> CameraSample,
        mut ray: impl FnMut(u32, u32, Option<DRay>),
    ) {
        let (size, frame) = (self.size(), &self.frame);
        let (u_axis, v_axis) = (frame.u(), frame.v());
        match self.shortcut() {
            Shortcut::Pinhole {
                projection: p,
                origin,
                depth,
            } => {
                // `generate_ray_through`'s perspective rule.
                for row in rows {
                    let y = f64::from(row);
                    for col in cols.clone() {
                        let p_film = sample(row, col).p_film;
                        let u = image_x_to_u(f64::from(col) + p_film.x, size.x, p.viewport.x);
                        let v = image_y_to_v(y + p_film.y, size.y, p.viewport.y);
                        let direction = (u + p.shift.x) * u_axis + (v + p.shift.y) * v_axis + depth;
                        ray(row, col, Some(DRay::new(origin, direction)));
                    }
                }
            }
            Shortcut::Parallel {
                viewport,
                flat,
                direction,
            } => {
                // `camera_space_ray`'s orthographic and oblique origin `(u, v, 0)`, then
                // `world_from_camera_point`.
                let eye = frame.e();
                for row in rows {
                    let y = f64::from(row);
                    for col in cols.clone() {
                        let p_film = sample(row, col).p_film;
                        let u = image_x_to_u(f64::from(col) + p_film.x, size.x, viewport.x);
                        let v = image_y_to_v(y + p_film.y, size.y, viewport.y);
                        let origin = eye + (u * u_axis + v * v_axis + flat);
                        ray(row, col, Some(DRay::new(origin, direction)));
                    }
                }
            }
            Shortcut::RoundLens(lens) | Shortcut::ThinLens(lens) => {
                // `camera_space_ray`'s thin-lens rule.
                let (iris, pinhole) = (lens.iris, lens.pinhole());
                let focus_over_distance = lens.focus / lens.distance;
                for row in rows {
                    for col in cols.clone() {
                        let CameraSample { p_film, p_lens } = sample(row, col);
                        let image = DVec2::new(f64::from(col), f64::from(row)) + p_film;
                        let uv = image_to_image_plane(image, size, pinhole.viewport);
                        let lens_offset = (lens.aperture * iris.sample(p_lens)).extend(0.0);
                        let direction = focus_over_distance * pinhole.direction(uv) - lens_offset;
                        ray(
                            row,
                            col,
                            Some(DRay::new(
                                frame.world_from_camera_point(lens_offset),
                                frame.world_from_camera_vector(direction),
                            )),
                        );
                    }
                }
            }
            Shortcut::General => {
                for row in rows {
                    for col in cols.clone() {
                        ray(row, col, self.generate_ray(row, col, sample(row, col)));
                    }
                }
            }
        }
    }

    /// [`Camera::generate_sampled_block_rays`] compiled for AVX2, with the block's
    /// samples given row by row (pixel `(row, col)`'s at
    /// `(row - rows.start) * cols.len() + (col - cols.start)`): the same rays in the same
    /// order. A round, untilted thin lens without mistakes takes each row's pixels four
    /// at a time in the lanes of AVX2 registers (their image-plane points, iris points
    /// and frame transforms, the same operations in the same order in every lane); every
    /// other camera goes as [`Camera::generate_sampled_block_rays`].
    ///
    /// # Safety
    ///
    /// The processor must run AVX2 (which is why code not compiled for AVX2 calls this
    /// in `unsafe`): a renderer asks `is_x86_feature_detected!("avx2")` once.
    ///
    /// # Panics
    /// If `samples` holds fewer than the block's pixels.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    #[inline]
    pub fn generate_sampled_block_rays_avx2(
        &self,
        rows: Range<u32>,
        cols: Range<u32>,
        samples: &[CameraSample],
        mut ray: impl FnMut(u32, u32, Option<DRay>),
    ) {
        let width = cols.len();
        let Shortcut::RoundLens(lens) = self.shortcut() else {
            let (top, left) = (rows.start, cols.start);
            let sample =
                |row: u32, col: u32| samples[(row - top) as usize * width + (col - left) as usize];
            self.generate_sampled_block_rays(rows, cols, sample, ray);
            return;
        };
        assert!(samples.len() >= rows.len() * width, "a sample per pixel");
        if width == 0 {
            return;
        }
        let round = RoundLens::new(&lens, self.size(), &self.frame);
        // Row by row, four pixels at a time; a short last group of a row padded with lens
        // centres, whose rays are not handed on.
        for (row, line) in rows.zip(samples.chunks(width)) {
            let mut quads = line.chunks_exact(LANES);
            let mut col = cols.start;
            for quad in &mut quads {
                let quad = quad.try_into().expect("chunks of LANES");
                round.rays_avx2((row, col), quad, LANES, &mut ray);
                col += LANES as u32;
            }
            let rest = quads.remainder();
            if !rest.is_empty() {
                let mut padded = [CameraSample::CENTER; LANES];
                padded[..rest.len()].copy_from_slice(rest);
                round.rays_avx2((row, col), &padded, rest.len(), &mut ray);
            }
        }
    }

    /// The shortcut this camera's sampled blocks take.
    fn shortcut(&self) -> Shortcut {
        let frame = &self.frame;
        let plain = self.mistakes.is_empty();
        match (&self.projection, &self.pinhole) {
            (Projection::Perspective(p), Some(pinhole)) => Shortcut::Pinhole {
                projection: *p,
                origin: pinhole.origin,
                depth: pinhole.depth,
            },
            (Projection::Orthographic(o), _) if plain && o.lens.is_none() => Shortcut::Parallel {
                viewport: o.viewport,
                flat: 0.0 * frame.w(),
                direction: frame.world_from_camera_vector(DVec3::NEG_Z),
            },
            (Projection::Oblique(o), _) if plain => Shortcut::Parallel {
                viewport: o.viewport,
                flat: 0.0 * frame.w(),
                direction: frame.world_from_camera_vector(o.direction()),
            },
            (Projection::ThinLens(lens), _) if plain && !lens.is_tilted() => {
                if lens.iris.is_round() {
                    Shortcut::RoundLens(*lens)
                } else {
                    Shortcut::ThinLens(*lens)
                }
            }
            _ => Shortcut::General,
        }
    }
}

#[cfg(test)]
mod tests {
    use glam::DVec3;
    use proptest::prelude::*;

    use super::super::tests::coordinate;
    use super::*;
    use crate::{Frame, Mistake, Mistakes};

    /// A block's rays, `(row, col, ray)`, are `expected`'s bit for bit, in order.
    fn same_rays(
        got: Vec<(u32, u32, Option<DRay>)>,
        expected: Vec<(u32, u32, Option<DRay>)>,
    ) -> Result<(), TestCaseError> {
        let bits = |r: Option<DRay>| {
            r.map(|r| {
                (
                    r.origin.to_array().map(f64::to_bits),
                    r.direction.to_array().map(f64::to_bits),
                )
            })
        };
        prop_assert_eq!(got.len(), expected.len());
        for (g, e) in got.into_iter().zip(expected) {
            prop_assert_eq!((g.0, g.1, bits(g.2)), (e.0, e.1, bits(e.2)));
        }
        Ok(())
    }

    /// A camera of family `family` (0 to 12): thin lenses round and with blades, tilted
    /// and mistaken; perspective cameras right and mistaken (with and without the
    /// pinhole's terms); orthographic cameras with and without a lens, right and
    /// mistaken; oblique cameras right and mistaken; a fisheye. `None` where the numbers
    /// make no camera.
    #[allow(clippy::too_many_arguments)]
    fn family_camera(
        family: usize,
        eye: (f64, f64, f64),
        view: (f64, f64, f64),
        viewport: (f64, f64),
        shift: (f64, f64),
        lens: (f64, f64, f64),
        slant: (f64, f64),
        size: (u32, u32),
    ) -> Option<Camera> {
        let frame = Frame::from_eye_view_up(eye.into(), view.into(), DVec3::Y).ok()?;
        let (aperture, focus, distance) = lens;
        let pinhole = Perspective {
            distance,
            viewport: viewport.into(),
            shift: shift.into(),
        };
        let thin = crate::ThinLens::new(pinhole, aperture, focus);
        let orthographic = crate::Orthographic {
            viewport: viewport.into(),
            lens: None,
        };
        let oblique = crate::Oblique {
            viewport: viewport.into(),
            ratio: slant.0,
            angle: slant.1,
        };
        let (projection, mistakes) = match family {
            0 => (Projection::ThinLens(thin), Mistakes::NONE),
            1 => (
                Projection::ThinLens(crate::ThinLens {
                    iris: crate::Iris::new(6, 0.3).unwrap(),
                    ..thin
                }),
                Mistakes::NONE,
            ),
            2 => (
                Projection::ThinLens(crate::ThinLens {
                    tilt: 0.2,
                    focus: focus.max(distance * 2.0),
                    ..thin
                }),
                Mistakes::NONE,
            ),
            3 => (
                Projection::ThinLens(thin),
                Mistakes::one(Mistake::PixelCorner),
            ),
            4 => (Projection::Perspective(pinhole), Mistakes::NONE),
            5 => (
                Projection::Perspective(pinhole),
                Mistakes::one(Mistake::PixelCorner),
            ),
            6 => (
                Projection::Perspective(pinhole),
                Mistakes::one(Mistake::EyeMissing),
            ),
            7 => (Projection::Orthographic(orthographic), Mistakes::NONE),
            8 => (
                Projection::Orthographic(crate::Orthographic {
                    lens: Some(crate::Lens { aperture, focus }),
                    ..orthographic
                }),
                Mistakes::NONE,
            ),
            9 => (
                Projection::Orthographic(orthographic),
                Mistakes::one(Mistake::EyeMissing),
            ),
            10 => (Projection::Oblique(oblique), Mistakes::NONE),
            11 => (
                Projection::Oblique(oblique),
                Mistakes::one(Mistake::EyeMissing),
            ),
            _ => (
                Projection::Fisheye(crate::Fisheye { fov: 3.0 }),
                Mistakes::NONE,
            ),
        };
        Camera::new(frame, projection, size.0, size.1)
            .ok()?
            .with_mistakes(mistakes)
            .ok()
    }

    proptest! {
        /// A block's rays through a sample per pixel are the rays of its pixels one at a
        /// time, bit for bit, for every shortcut and the general rule: thin lenses round
        /// and with blades, tilted and mistaken; perspective cameras right and mistaken
        /// (with and without the pinhole's terms); orthographic cameras with and without
        /// a lens, right and mistaken; oblique cameras right and mistaken; a fisheye.
        #[test]
        fn sampled_block_rays_are_the_single_rays_bit_for_bit(
            eye in (coordinate(), coordinate(), coordinate()),
            view in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            family in 0usize..13,
            viewport in (0.1..10.0f64, 0.1..10.0f64),
            shift in (-1.0..1.0f64, -1.0..1.0f64),
            lens in (0.001..1.0f64, 0.5..20.0f64, 0.2..3.0f64),
            slant in (0.0..2.0f64, -4.0..4.0f64),
            size in (1u32..2000, 1u32..2000),
            start in (0u32..2000, 0u32..2000),
            len in (0u32..10, 0u32..10),
            seed in any::<u64>(),
        ) {
            let camera = family_camera(family, eye, view, viewport, shift, lens, slant, size);
            prop_assume!(camera.is_some());
            let camera = camera.unwrap();
            // Each pixel's own sample, from its row and column.
            let sample = |row: u32, col: u32| {
                let mut z = seed ^ (u64::from(row) << 32 | u64::from(col));
                let mut next = || {
                    z = z.wrapping_mul(6364136223846793005).wrapping_add(1442695040888963407);
                    (z >> 11) as f64 / (1u64 << 53) as f64
                };
                let (p_film, t) = (DVec2::new(next(), next()), next());
                // Some lens points at the lens centre, on a diagonal and on an axis.
                let p_lens = match (row + col) % 5 {
                    0 => DVec2::splat(0.5),
                    1 => DVec2::splat(t),
                    2 => DVec2::new(0.5, t),
                    _ => DVec2::new(t, next()),
                };
                CameraSample { p_film, p_lens }
            };
            let (rows, cols) = (start.0..start.0 + len.0, start.1..start.1 + len.1);
            let mut expected = Vec::new();
            for row in rows.clone() {
                for col in cols.clone() {
                    expected.push((row, col, camera.generate_ray(row, col, sample(row, col))));
                }
            }
            let mut got = Vec::new();
            camera.generate_sampled_block_rays(rows.clone(), cols.clone(), sample, |row, col, ray| {
                got.push((row, col, ray));
            });
            same_rays(got, expected.clone())?;
            #[cfg(target_arch = "x86_64")]
            if std::arch::is_x86_feature_detected!("avx2") {
                let mut lanes = Vec::new();
                let take = |row, col, ray| lanes.push((row, col, ray));
                let samples: Vec<_> = rows
                    .clone()
                    .flat_map(|row| cols.clone().map(move |col| sample(row, col)))
                    .collect();
                // SAFETY: the processor runs AVX2 (asked above), all the call needs.
                #[allow(unsafe_code)]
                unsafe {
                    camera.generate_sampled_block_rays_avx2(rows, cols, &samples, take);
                }
                same_rays(lanes, expected)?;
            }
        }

        /// The box of a block's rays holds every ray of its pixels, through any film
        /// point and any lens point, for every family whose rays are affine; the others
        /// (a tilted lens, mistakes, a fisheye) have none.
        #[test]
        fn ray_bounds_hold_every_ray_of_the_region(
            eye in (coordinate(), coordinate(), coordinate()),
            view in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            family in 0usize..13,
            viewport in (0.1..10.0f64, 0.1..10.0f64),
            shift in (-1.0..1.0f64, -1.0..1.0f64),
            lens in (0.001..1.0f64, 0.5..20.0f64, 0.2..3.0f64),
            slant in (0.0..2.0f64, -4.0..4.0f64),
            size in (1u32..2000, 1u32..2000),
            start in (0u32..2000, 0u32..2000),
            len in (1u32..10, 1u32..10),
            samples in prop::collection::vec(
                (0u32..10, 0u32..10, 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64),
                16,
            ),
        ) {
            let camera = family_camera(family, eye, view, viewport, shift, lens, slant, size);
            prop_assume!(camera.is_some());
            let camera = camera.unwrap();
            let corners = [
                DVec2::new(f64::from(start.1), f64::from(start.0)),
                DVec2::new(f64::from(start.1 + len.1), f64::from(start.0 + len.0)),
            ];
            let bounds = camera.ray_bounds(corners);
            let affine = matches!(family, 0 | 1 | 4 | 7 | 8 | 10);
            prop_assert_eq!(bounds.is_some(), affine);
            let Some(bounds) = bounds else { return Ok(()) };
            // Within the box but for the rounding of the corners' own arithmetic.
            let inside = |v: DVec3, [low, high]: [DVec3; 2]| {
                let margin = 1e-12 * (1.0 + low.abs().max(high.abs()).max_element());
                v.cmpge(low - margin).all() && v.cmple(high + margin).all()
            };
            // Samples anywhere in the block's pixels, lens points at the edge of the
            // square and inside it.
            for (k, &(row, col, fx, fy, lx, ly)) in samples.iter().enumerate() {
                let (row, col) = (start.0 + row % len.0, start.1 + col % len.1);
                let p_lens = if k % 2 == 0 { DVec2::new(lx.round(), ly) } else { DVec2::new(lx, ly) };
                let sample = CameraSample { p_film: DVec2::new(fx, fy), p_lens };
                let ray = camera.generate_ray(row, col, sample).unwrap();
                prop_assert!(inside(ray.origin, bounds.origin), "{ray:?} {bounds:?}");
                prop_assert!(inside(ray.direction, bounds.direction), "{ray:?} {bounds:?}");
            }
        }

        /// A block's rays are the rays of its pixels one at a time, bit for bit, for
        /// every family (the perspective shortcut and the rest), through any sample,
        /// for blocks narrower and wider than the shortcut's 16 columns.
        #[test]
        fn block_rays_are_the_single_rays_bit_for_bit(
            eye in (coordinate(), coordinate(), coordinate()),
            view in (-1.0..1.0f64, -1.0..1.0f64, -1.0..1.0f64),
            family in 0usize..4,
            viewport in (0.1..10.0f64, 0.1..10.0f64),
            shift in (-1.0..1.0f64, -1.0..1.0f64),
            size in (1u32..2000, 1u32..2000),
            start in (0u32..2000, 0u32..2000),
            len in (0u32..20, 0u32..20),
            sample in (0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64, 0.0..1.0f64),
        ) {
            let frame = Frame::from_eye_view_up(eye.into(), view.into(), DVec3::Y);
            prop_assume!(frame.is_ok());
            let viewport = DVec2::from(viewport);
            let projection = match family {
                0 => Projection::Perspective(Perspective {
                    distance: 1.5,
                    viewport,
                    shift: shift.into(),
                }),
                1 => Projection::Orthographic(crate::Orthographic { viewport, lens: None }),
                2 => Projection::ThinLens(crate::ThinLens::new(
                    Perspective { distance: 1.0, viewport, shift: shift.into() },
                    0.2,
                    3.0,
                )),
                _ => Projection::Fisheye(crate::Fisheye { fov: 3.0 }),
            };
            let camera = Camera::new(frame.unwrap(), projection, size.0, size.1).unwrap();
            let sample = CameraSample {
                p_film: DVec2::new(sample.0, sample.1),
                p_lens: DVec2::new(sample.2, sample.3),
            };
            let (rows, cols) = (start.0..start.0 + len.0, start.1..start.1 + len.1);
            let mut expected = Vec::new();
            for row in rows.clone() {
                for col in cols.clone() {
                    expected.push((row, col, camera.generate_ray(row, col, sample)));
                }
            }
            let mut got = Vec::new();
            camera.generate_block_rays(rows, cols, sample, |row, col, ray| {
                got.push((row, col, ray));
            });
            same_rays(got, expected)?;
        }
    }
    /// Which shortcut each camera's sampled blocks take: every family that has one takes
    /// it (or its rays would be right but slow), every camera that does not goes ray by
    /// ray (or its rays would be wrong).
    #[test]
    fn each_camera_takes_its_shortcut() {
        let frame = Frame::from_eye_view_up(DVec3::ONE, DVec3::NEG_Z, DVec3::Y).unwrap();
        let viewport = DVec2::new(2.0, 1.5);
        let pinhole = Perspective {
            distance: 1.0,
            viewport,
            shift: DVec2::ZERO,
        };
        let thin = ThinLens::new(pinhole, 0.1, 4.0);
        let orthographic = crate::Orthographic {
            viewport,
            lens: None,
        };
        let lens = Some(crate::Lens {
            aperture: 0.1,
            focus: 4.0,
        });
        let oblique = crate::Oblique {
            viewport,
            ratio: 0.5,
            angle: 0.7,
        };
        let shortcut = |projection, mistakes: &[Mistake]| {
            let mistakes = mistakes.iter().fold(Mistakes::NONE, |set, &m| set.with(m));
            let camera = Camera::new(frame, projection, 64, 48).unwrap();
            match camera.with_mistakes(mistakes).unwrap().shortcut() {
                Shortcut::Pinhole { .. } => "pinhole",
                Shortcut::Parallel { .. } => "parallel",
                Shortcut::RoundLens(_) => "round lens",
                Shortcut::ThinLens(_) => "thin lens",
                Shortcut::General => "general",
            }
        };
        let tilted = ThinLens { tilt: 0.1, ..thin };
        let bladed = ThinLens {
            iris: crate::Iris::new(5, 0.2).unwrap(),
            ..thin
        };
        for (projection, mistakes, expected) in [
            (Projection::Perspective(pinhole), &[][..], "pinhole"),
            (
                Projection::Perspective(pinhole),
                &[Mistake::EyeMissing],
                "pinhole",
            ),
            (
                Projection::Perspective(pinhole),
                &[Mistake::PixelCorner],
                "general",
            ),
            (Projection::Orthographic(orthographic), &[], "parallel"),
            (
                Projection::Orthographic(orthographic),
                &[Mistake::EyeMissing],
                "general",
            ),
            (
                Projection::Orthographic(crate::Orthographic {
                    lens,
                    ..orthographic
                }),
                &[],
                "general",
            ),
            (Projection::Oblique(oblique), &[], "parallel"),
            (
                Projection::Oblique(oblique),
                &[Mistake::EyeMissing],
                "general",
            ),
            (Projection::ThinLens(thin), &[], "round lens"),
            (Projection::ThinLens(bladed), &[], "thin lens"),
            (
                Projection::ThinLens(thin),
                &[Mistake::PixelCorner],
                "general",
            ),
            (Projection::ThinLens(tilted), &[], "general"),
            (Projection::Equirectangular, &[], "general"),
        ] {
            assert_eq!(
                shortcut(projection, mistakes),
                expected,
                "{projection:?} {mistakes:?}"
            );
        }
    }

    /// A round lens's rays in lanes keep the frame transforms' last terms: with an
    /// axis-aligned frame, whose axes hold zeros, and an eye at `-0`, each ray (through
    /// the lens centre and off it, in every lane and a short last group) is the single
    /// ray to the bit, signed zeros included; a term left out, or divided instead of
    /// multiplied (`0 / 0`), would not be.
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn round_lens_lanes_keep_the_signed_zero() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let eye = DVec3::splat(-0.0);
        let frame = Frame::from_eye_view_up(eye, DVec3::NEG_Z, DVec3::Y).unwrap();
        let pinhole = Perspective {
            distance: 1.0,
            viewport: DVec2::new(2.0, 1.5),
            shift: DVec2::ZERO,
        };
        let camera = Camera::new(
            frame,
            Projection::ThinLens(ThinLens::new(pinhole, 0.5, 3.0)),
            4,
            4,
        )
        .unwrap();
        let sample = |row: u32, col: u32| CameraSample {
            p_film: DVec2::splat(0.5),
            p_lens: if (row + col).is_multiple_of(2) {
                DVec2::splat(0.5)
            } else {
                DVec2::new(0.25, 0.5)
            },
        };
        let bits = |v: DVec3| v.to_array().map(f64::to_bits);
        let mut rays = 0;
        let check = |row, col, ray: Option<DRay>| {
            let (ray, single) = (
                ray.unwrap(),
                camera.generate_ray(row, col, sample(row, col)),
            );
            let single = single.unwrap();
            assert_eq!(bits(ray.origin), bits(single.origin), "{row} {col}");
            assert_eq!(bits(ray.direction), bits(single.direction), "{row} {col}");
            rays += 1;
        };
        // Three rows of six pixels: a group of four and a short group each.
        let samples: Vec<_> = (0..3)
            .flat_map(|row| (0..6).map(move |col| sample(row, col)))
            .collect();
        // SAFETY: the processor runs AVX2 (asked above), all the call needs.
        #[allow(unsafe_code)]
        unsafe {
            camera.generate_sampled_block_rays_avx2(0..3, 0..6, &samples, check);
        }
        assert_eq!(rays, 18);
    }

    /// A round lens's block in lanes asks for a sample per pixel: a slice one short
    /// panics before any ray (its last row would otherwise go one pixel short).
    #[cfg(target_arch = "x86_64")]
    #[test]
    fn round_lens_lanes_want_a_sample_per_pixel() {
        if !std::arch::is_x86_feature_detected!("avx2") {
            return;
        }
        let frame = Frame::from_eye_view_up(DVec3::ZERO, DVec3::NEG_Z, DVec3::Y).unwrap();
        let pinhole = Perspective {
            distance: 1.0,
            viewport: DVec2::new(2.0, 1.5),
            shift: DVec2::ZERO,
        };
        let lens = Projection::ThinLens(ThinLens::new(pinhole, 0.5, 3.0));
        let camera = Camera::new(frame, lens, 8, 8).unwrap();
        for (len, panics) in [(8, false), (7, true)] {
            let samples = vec![CameraSample::CENTER; len];
            let mut rays = 0;
            let block = std::panic::AssertUnwindSafe(|| {
                // SAFETY: the processor runs AVX2 (asked above), all the call needs.
                #[allow(unsafe_code)]
                unsafe {
                    camera.generate_sampled_block_rays_avx2(0..2, 0..4, &samples, |_, _, _| {
                        rays += 1;
                    });
                }
            });
            assert_eq!(std::panic::catch_unwind(block).is_err(), panics, "{len}");
            assert_eq!(rays, if panics { 0 } else { 8 }, "{len}");
        }
    }

    /// A parallel camera's origin keeps the frame transform's last term `0 W`: with an
    /// axis-aligned frame and an eye at `-0`, `e + ((u U + v V) + 0 W)` has a `+0` where
    /// leaving the term out (or subtracting it) leaves a `-0`; and the axes' zeros make
    /// any other term (`0 / W`) a NaN.
    #[test]
    fn parallel_origins_keep_the_signed_zero() {
        let eye = DVec3::splat(-0.0);
        let frame = Frame::from_eye_view_up(eye, DVec3::NEG_Z, DVec3::Y).unwrap();
        let viewport = DVec2::new(2.0, 1.5);
        for projection in [
            Projection::Orthographic(crate::Orthographic {
                viewport,
                lens: None,
            }),
            Projection::Oblique(crate::Oblique {
                viewport,
                ratio: 0.5,
                angle: 0.7,
            }),
        ] {
            let camera = Camera::new(frame, projection, 4, 4).unwrap();
            let sample = |_, _| CameraSample::CENTER;
            // The bottom-left pixel: u < 0 and v < 0, so `u U + v V` is `-0` along W.
            let single = camera.generate_ray(3, 0, CameraSample::CENTER).unwrap();
            assert_eq!(
                single.origin.z.to_bits(),
                0.0f64.to_bits(),
                "{projection:?}"
            );
            let bits = |v: DVec3| v.to_array().map(f64::to_bits);
            camera.generate_sampled_block_rays(3..4, 0..1, sample, |_, _, ray| {
                let ray = ray.unwrap();
                assert_eq!(bits(ray.origin), bits(single.origin), "{projection:?}");
                assert_eq!(
                    bits(ray.direction),
                    bits(single.direction),
                    "{projection:?}"
                );
            });
        }
    }
}

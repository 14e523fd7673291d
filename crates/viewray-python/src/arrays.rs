//! The numbers the module hands to NumPy, as flat row-major buffers of `f64` (or `u8`)
//! with their shapes: every pixel's viewing ray, projected points and rendered pixels.
//!
//! Each value comes from the library that owns its rule (viewray-camera's rays and
//! projection, viewray-render's image and its 8-bit encoding); this module only lays
//! the values out as `(H, W, 3)` or `(N, 2)` arrays, with NaN where the camera has no
//! value.

use std::collections::TryReserveError;

use glam::DVec3;
use viewray_camera::{Camera, CameraSample};
use viewray_judge::{Answer, CheckOptions, Checker, Report};
use viewray_render::{RenderError, RenderSettings, View, render_view};
use viewray_scene::Scene;

/// The viewing ray of every pixel's centre through the lens's centre, as `viewray rays`
/// prints them: two `(H, W, 3)` buffers, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct PixelRays {
    /// `H * W * 3` origins; NaN for a pixel with no ray (outside a fisheye's circle).
    pub origins: Vec<f64>,
    /// `H * W * 3` directions, not normalized (the lecture's formulas exactly); NaN where
    /// the pixel has no ray.
    pub directions: Vec<f64>,
}

/// The rays of every pixel of `camera` (see [`PixelRays`]).
///
/// # Errors
/// When the two buffers cannot be allocated (a very large image).
pub fn pixel_rays(camera: &Camera) -> Result<PixelRays, TryReserveError> {
    let (width, height) = (camera.width(), camera.height());
    let len = 3 * width as usize * height as usize;
    let mut origins = Vec::new();
    origins.try_reserve_exact(len)?;
    let mut directions = Vec::new();
    directions.try_reserve_exact(len)?;
    for row in 0..height {
        for col in 0..width {
            let (origin, direction) = match camera.generate_ray(row, col, CameraSample::CENTER) {
                Some(ray) => (ray.origin, ray.direction),
                None => (DVec3::NAN, DVec3::NAN),
            };
            origins.extend_from_slice(&origin.to_array());
            directions.extend_from_slice(&direction.to_array());
        }
    }
    Ok(PixelRays {
        origins,
        directions,
    })
}

/// A student's rays judged as `viewray check` judges printed ones: the ray of pixel
/// `(row, col)` is `origins[row, col]` and `directions[row, col]` (row-major `(H, W, 3)`
/// buffers of `camera`'s image), each judged against the camera (directions up to a
/// positive factor unless `options` say otherwise) and the wrong ones explained by the
/// lecture's catalogue.
pub fn check_rays(
    camera: &Camera,
    origins: &[f64],
    directions: &[f64],
    options: CheckOptions,
) -> Report {
    let width = camera.width() as usize;
    let mut checker = Checker::new(camera, options);
    let rays = origins.chunks_exact(3).zip(directions.chunks_exact(3));
    for (k, (origin, direction)) in rays.enumerate() {
        let (row, col) = (k / width, k % width);
        let answer = Answer::Ray {
            row: i64::try_from(row).unwrap_or(i64::MAX),
            col: i64::try_from(col).unwrap_or(i64::MAX),
            one_based: false,
            uv: None,
            origin: DVec3::from_slice(origin),
            direction: DVec3::from_slice(direction),
        };
        // Every index is inside the image: the arrays are the image's shape.
        let line = u64::try_from(k + 1).unwrap_or(u64::MAX);
        checker
            .check(line, &answer)
            .expect("an array's pixels are the image's");
    }
    checker.finish()
}

/// The continuous image coordinates `(x, y)` of each point, in pixels from the image's
/// top-left corner (`Camera::project`), as an `(N, 2)` buffer; `(NaN, NaN)` where the
/// camera does not see the point.
pub fn project_points(camera: &Camera, points: impl IntoIterator<Item = DVec3>) -> Vec<f64> {
    points
        .into_iter()
        .flat_map(|point| {
            camera
                .project(point)
                .map_or([f64::NAN; 2], |xy| xy.to_array())
        })
        .collect()
}

/// Renders `scene` as `viewray render --samples N` does (`samples: None` keeps the
/// scene's own), on rayon's global pool, and returns its pixels as a PNG stores them:
/// `H * W * 3` bytes, row by row from the top.
///
/// # Errors
/// viewray-render's error (only for a thread pool of its own, which this never asks for).
pub fn render_rgb8(scene: &Scene, samples: Option<u32>) -> Result<Vec<u8>, RenderError> {
    let own = View::of(scene);
    let view = View {
        samples: samples.unwrap_or(own.samples),
        ..own
    };
    let rendered = render_view(scene, &view, &RenderSettings::default(), |_, _| {})?;
    Ok(rendered.image.to_rgb8())
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use glam::DVec2;
    use viewray_camera::{Fisheye, Frame, Perspective, Projection};

    use super::*;

    /// The lecture's canonical camera: e at the origin, d = 1, vw = vh = 1.
    fn canonical(width: u32, height: u32) -> Camera {
        let projection = Projection::Perspective(Perspective {
            distance: 1.0,
            viewport: DVec2::ONE,
            shift: DVec2::ZERO,
        });
        Camera::new(Frame::CANONICAL, projection, width, height).unwrap()
    }

    #[test]
    fn rays_are_the_lectures_formula_row_by_row() {
        // u = ((j - 1/2)/W - 1/2) vw, v = -((i - 1/2)/H - 1/2) vh, d = (u, v, -1).
        let rays = pixel_rays(&canonical(2, 2)).unwrap();
        assert_eq!(rays.origins, vec![0.0; 12]);
        #[rustfmt::skip]
        let expected = vec![
            -0.25, 0.25, -1.0,   0.25, 0.25, -1.0,
            -0.25, -0.25, -1.0,  0.25, -0.25, -1.0,
        ];
        assert_eq!(rays.directions, expected);

        // Three columns, one row: the middle column looks straight ahead.
        let rays = pixel_rays(&canonical(3, 1)).unwrap();
        assert_eq!(rays.directions[3..6], [0.0, 0.0, -1.0]);
        assert_eq!(rays.directions[0], (0.5 / 3.0 - 0.5));
    }

    #[test]
    fn a_pixel_without_a_ray_is_nan() {
        // A fisheye's circle touches the image's left and right edges: a tall image's
        // top and bottom rows are outside it.
        let projection = Projection::Fisheye(Fisheye {
            fov: std::f64::consts::PI,
        });
        let camera = Camera::new(Frame::CANONICAL, projection, 2, 8).unwrap();
        let rays = pixel_rays(&camera).unwrap();
        assert_eq!(rays.origins.len(), 2 * 8 * 3);
        // (row 0, col 0): a = -1/2, b = (1 - 1/8) 8/2 = 7/2, outside the circle;
        // (row 3, col 0): a = -1/2, b = 1/2, inside it.
        assert!(rays.origins[..3].iter().all(|x| x.is_nan()));
        assert!(rays.directions[..3].iter().all(|x| x.is_nan()));
        assert_eq!(rays.origins[18..21], [0.0; 3]);
        assert!(rays.directions[18..21].iter().all(|x| x.is_finite()));
    }

    #[test]
    fn points_project_to_image_coordinates_or_nan() {
        let camera = canonical(2, 2);
        let xy = project_points(
            &camera,
            [
                // Straight ahead: the image's centre.
                DVec3::new(0.0, 0.0, -1.0),
                // The top-right pixel's centre ray, twice as far.
                DVec3::new(0.5, 0.5, -2.0),
                // Behind the eye: not seen.
                DVec3::new(0.0, 0.0, 1.0),
            ],
        );
        assert_eq!(xy[..4], [1.0, 1.0, 1.5, 0.5]);
        assert!(xy[4].is_nan() && xy[5].is_nan());
        assert!(project_points(&camera, []).is_empty());
    }

    #[test]
    fn a_render_is_the_pngs_pixels_and_samples_override_the_scenes() {
        let text = "(image: (width: 4, height: 3, samples: 1), \
                    camera: (eye: (0.0, 0.0, 3.0), look_at: (0.0, 0.0, 0.0), \
                    projection: Perspective(fov_y: 60.0)), \
                    objects: [Sphere(center: (0.0, 0.0, 0.0), radius: 1.0)])";
        let scene = viewray_scene::SceneLoader::text(text, Path::new("<test>"))
            .load()
            .unwrap()
            .scene;
        let pixels = render_rgb8(&scene, None).unwrap();
        let rendered = viewray_render::render(&scene, &RenderSettings::default(), |_, _| {})
            .unwrap()
            .image;
        assert_eq!(pixels, rendered.to_rgb8());
        assert_eq!(pixels.len(), 4 * 3 * 3);

        let options = viewray_scene::LoadOptions {
            samples: Some(4),
            ..Default::default()
        };
        let four = viewray_scene::SceneLoader::text(text, Path::new("<test>"))
            .options(options)
            .load()
            .unwrap()
            .scene;
        let four_samples = viewray_render::render(&four, &RenderSettings::default(), |_, _| {})
            .unwrap()
            .image;
        assert_eq!(
            render_rgb8(&scene, Some(4)).unwrap(),
            four_samples.to_rgb8()
        );
        assert_ne!(
            four_samples.to_rgb8(),
            pixels,
            "4 samples antialias the edge"
        );
    }

    /// The arrays a student with v without its minus sign computes, in NumPy terms:
    /// the check names the mistake, and the right arrays pass.
    #[test]
    fn a_students_arrays_are_checked_and_explained() {
        let text = "(image: (width: 4, height: 3), \
                    camera: (eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0), \
                    projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))";
        let scene = viewray_scene::SceneLoader::text(text, Path::new("<test>"))
            .load()
            .unwrap()
            .scene;
        let camera = scene.camera();
        let right = pixel_rays(camera).unwrap();
        let options = CheckOptions::default();
        let report = check_rays(camera, &right.origins, &right.directions, options);
        assert!(report.passed(), "{report}");
        assert_eq!(report.answers, 12);
        let mut flipped = right.directions.clone();
        for row in 0..3 {
            for col in 0..4 {
                let v = -((f64::from(row) + 0.5) / 3.0 - 0.5);
                flipped[3 * (4 * row as usize + col) + 1] = -v;
            }
        }
        let report = check_rays(camera, &right.origins, &flipped, options);
        assert!(!report.passed());
        let ids: Vec<String> = report
            .diagnosis
            .unwrap()
            .alternatives
            .iter()
            .map(ToString::to_string)
            .collect();
        assert!(ids.contains(&"v-sign".to_owned()), "{ids:?}");
    }
}

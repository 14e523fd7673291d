//! How far the scene lies in front of a camera: what the page needs to switch the
//! projection kind without losing the picture (a thin lens focused on what is in front of
//! it, a parallel view as tall as the perspective one there).

use glam::DVec2;
use serde_json::{Value, json};
use viewray_camera::Camera;
use viewray_scene::Scene;

/// The depth of the scene at the middle of `camera`'s picture: the distance along the view
/// (`-w`, the axis a focus distance is measured on) from the eye to what the ray through
/// the image's centre hits; where it hits nothing in front of the eye, to the middle of
/// the objects' bounds (planes aside); `None` when neither lies in front of the eye.
///
/// ```text
/// depth = (p - e) . (-w),   p = ray(centre).at(t_hit), else the objects' centre
/// ```
pub(crate) fn scene_depth(scene: &Scene, camera: &Camera) -> Option<(f64, &'static str)> {
    let frame = camera.frame();
    let along_view = |p: glam::DVec3| (p - frame.e()).dot(-frame.w());
    let centre = DVec2::new(f64::from(camera.width()), f64::from(camera.height())) / 2.0;
    let hit = camera
        .generate_ray_through(centre, DVec2::splat(0.5))
        .and_then(|ray| {
            let hit = scene
                .world()
                .closest_hit(&ray.as_ray(), f32::MIN_POSITIVE..f32::INFINITY)?;
            Some(along_view(ray.at(f64::from(hit.t))))
        })
        .filter(|depth| depth.is_finite() && *depth > 0.0);
    if let Some(depth) = hit {
        return Some((depth, "hit"));
    }
    let mut bounds: Option<(glam::DVec3, glam::DVec3)> = None;
    for object in scene.world().objects() {
        if let Some(aabb) = object.bounds() {
            let (min, max) = (aabb.min.as_dvec3(), aabb.max.as_dvec3());
            if min.is_finite() && max.is_finite() {
                bounds = Some(bounds.map_or((min, max), |(a, b)| (a.min(min), b.max(max))));
            }
        }
    }
    bounds
        .map(|(min, max)| along_view((min + max) / 2.0))
        .filter(|depth| depth.is_finite() && *depth > 0.0)
        .map(|depth| (depth, "objects"))
}

/// The JSON of `/api/depth`: `{"depth": D, "from": "hit" | "objects"}`, or
/// `{"depth": null, "from": null}`.
pub(crate) fn depth_json(depth: Option<(f64, &'static str)>) -> Value {
    match depth {
        Some((depth, from)) => json!({ "depth": depth, "from": from }),
        None => json!({ "depth": null, "from": null }),
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use viewray_scene::{Scene, SceneLoader, parse_camera};

    use super::*;

    /// A unit sphere at `(0, 1, -3)` over the ground.
    fn scene() -> Scene {
        SceneLoader::text(
            "(camera: (eye: (0.0, 1.0, 5.0), look_at: (0.0, 1.0, 0.0), \
             projection: Perspective(fov_y: 40.0)), \
             image: (width: 64, height: 36), \
             materials: { \"grey\": (color: (0.5, 0.5, 0.5)) }, \
             objects: [Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: \"grey\"), \
                       Sphere(center: (0.0, 1.0, -3.0), radius: 1.0, material: \"grey\")])",
            Path::new("scene.ron"),
        )
        .load()
        .unwrap()
        .scene
    }

    fn camera(text: &str) -> Camera {
        parse_camera(text, Path::new("camera"), 64, 36).unwrap()
    }

    #[test]
    fn the_depth_is_where_the_centre_ray_hits_measured_along_the_view() {
        let scene = scene();
        // Straight at the sphere from z = 5: its front at z = -2, 7 along the view.
        let (depth, from) = scene_depth(&scene, &camera("(eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 40.0))")).unwrap();
        assert_eq!(from, "hit");
        assert!((depth - 7.0).abs() < 1e-5, "{depth}");
        // A view direction that is not a unit vector measures the same.
        let (depth, _) = scene_depth(&scene, &camera("(eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -9.0), projection: Perspective(fov_y: 40.0))")).unwrap();
        assert!((depth - 7.0).abs() < 1e-5, "{depth}");
        // Looking down at the ground from 2 up, 45 degrees: it meets the ground 2 along x
        // and 2 down, 2 sqrt(2) along the view.
        let (depth, from) = scene_depth(&scene, &camera("(eye: (0.0, 2.0, 5.0), view: (1.0, -1.0, 0.0), projection: Perspective(fov_y: 40.0))")).unwrap();
        assert_eq!(from, "hit");
        assert!((depth - 2.0 * 2f64.sqrt()).abs() < 1e-5, "{depth}");
        // A parallel camera: from the eye's plane.
        let (depth, _) = scene_depth(&scene, &camera("(eye: (0.0, 1.0, 10.0), view: (0.0, 0.0, -1.0), projection: Orthographic(height: 4.0))")).unwrap();
        assert!((depth - 12.0).abs() < 1e-5, "{depth}");
    }

    #[test]
    fn a_centre_ray_into_the_sky_measures_to_the_objects_middle() {
        let scene = scene();
        // Looking up and over the sphere: the sphere's centre (0, 1, -3) is 8 along -z.
        let (depth, from) = scene_depth(&scene, &camera("(eye: (0.0, 1.0, 5.0), view: (0.0, 0.0, -1.0), projection: Perspective(fov_y: 20.0, shift: (0.0, 2.0)))")).unwrap();
        assert_eq!(from, "objects");
        assert!((depth - 8.0).abs() < 1e-9, "{depth}");
        // Looking away from everything.
        assert_eq!(
            scene_depth(
                &scene,
                &camera(
                    "(eye: (0.0, 1.0, 5.0), view: (0.0, 1.0, 1.0), projection: Perspective(fov_y: 40.0))"
                )
            ),
            None
        );
    }
}

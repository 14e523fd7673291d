//! What each pixel sees, as a label: the geometry of a picture without its shading.
//!
//! A student's ray tracer shades in its own way (its lights, its gamma, its samples), but
//! if its camera is right its objects' silhouettes and occlusion edges fall where the
//! right camera's labels change. A label map is what a judge of the camera compares
//! a student's picture with, one per candidate camera (the right one and each of the
//! catalogue's mistakes).

use rayon::prelude::*;
use viewray_camera::{Camera, CameraSample};
use viewray_scene::Scene;

/// The label of a pixel whose centre ray meets nothing (or has no ray).
pub const BACKGROUND_LABEL: u32 = 0;

/// The label of every pixel of `camera`'s image, row by row: [`BACKGROUND_LABEL`] where
/// the pixel's centre ray (through the lens centre) meets nothing, else a number that
/// is the same exactly where the first surface met belongs to the same object and has
/// the same material (a mesh's faces of two materials are two labels).
///
/// The camera may make the catalogue's mistakes ([`Camera::with_mistakes`]): its
/// labels are then those of the mistaken picture. Runs on the current rayon pool; the
/// labels depend on nothing else.
pub fn object_labels(scene: &Scene, camera: &Camera) -> Vec<u32> {
    let (width, height) = (camera.width(), camera.height());
    let materials = u32::try_from(scene.materials().len()).unwrap_or(u32::MAX);
    let mut labels = vec![BACKGROUND_LABEL; width as usize * height as usize];
    labels
        .par_chunks_mut(width as usize)
        .enumerate()
        .for_each(|(row, line)| {
            let row = u32::try_from(row).expect("an image has at most u32::MAX rows");
            for (col, label) in (0..width).zip(line.iter_mut()) {
                let Some(ray) = camera.generate_ray(row, col, CameraSample::CENTER) else {
                    continue;
                };
                let Some(hit) = scene
                    .world()
                    .closest_object(&ray.as_ray(), f32::MIN_POSITIVE..f32::INFINITY)
                else {
                    continue;
                };
                let material = scene.material_of(hit.object, hit.primitive);
                let index = scene
                    .materials()
                    .iter()
                    .position(|m| std::ptr::eq(m, material))
                    .map_or(0, |i| u32::try_from(i).unwrap_or(u32::MAX));
                *label = 1 + hit.object.wrapping_mul(materials.saturating_add(1)) + index;
            }
        });
    labels
}

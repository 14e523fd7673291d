//! One pixel's trace: the lecture's pseudocode (generate a viewing ray, find the closest
//! object it intersects, determine its colour) with every number the renderer computed
//! on the way, for `viewray trace`.
//!
//! [`trace_pixel`] renders the pixel with the renderer's own code, not a copy of it: the
//! block of pixels it belongs to is traced and shaded exactly as a one-sample
//! [`render_view`](crate::render_view) traces and shades it (the same packets, the same
//! Lit batches and lanes), while a recorder the shading code calls at each step (module
//! `shade::record`) keeps the numbers of the one sample followed. So the trace's value
//! is the image's, bit for bit, and its steps are the numbers that value was made of.
//!
//! What the renderer does not compute is added for the reader, with the geometry's own
//! functions: each object's test against a ray (the renderer's BVH skips most of them),
//! the surface details Flat and Depth shading do without, and which object blocks a
//! shadow ray. The types of the steps are in `steps`; the recorder in `recorder`.

mod recorder;
mod steps;

use viewray_geometry::{Hit, Object};
use viewray_scene::{Scene, Shading};

pub use self::steps::{
    BlinnPhong, ClosestHit, DepthValue, GridLines, HeadlightTerms, LightSource, LightTerms,
    LitSurface, LitTerm, PixelTrace, ShadowRay, Shape, Specular, Step, StepKind,
};
use crate::render::trace_pixel_with;
use crate::{PixelKind, RenderSettings, View};

/// Why a pixel cannot be traced.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("pixel {row},{col} is outside the {width} x {height} image")]
pub struct PixelOutside {
    /// The pixel's row, 0-based.
    pub row: u32,
    /// The pixel's column, 0-based.
    pub col: u32,
    /// The image's width.
    pub width: u32,
    /// The image's height.
    pub height: u32,
}

/// Traces pixel `(row, col)` (0-based from the top-left) of `view`'s image with one
/// sample per pixel, whatever `view.samples` says: the lecture's viewing ray through the
/// pixel's centre (and the lens centre), the closest object it meets, and its colour,
/// with every number on the way.
///
/// The trace's [`PixelTrace::value`] and [`PixelTrace::rgb8`] are the pixel's value in
/// the image [`render_view`](crate::render_view) makes of `view` with one sample per
/// pixel and the same `settings`, and its 8-bit value in that image's PNG, bit for bit:
/// both come from the same code (see the module docs). Depth shading first finds the
/// image's range of depths, one ray per pixel, as a render does.
///
/// # Errors
/// [`PixelOutside`] for a pixel outside the image.
pub fn trace_pixel(
    scene: &Scene,
    view: &View,
    settings: &RenderSettings,
    row: u32,
    col: u32,
) -> Result<PixelTrace, PixelOutside> {
    let camera = &view.camera;
    let (width, height) = (camera.width(), camera.height());
    if row >= height || col >= width {
        return Err(PixelOutside {
            row,
            col,
            width,
            height,
        });
    }
    let mut recorder = recorder::TraceRecorder::new(scene, (row, col));
    let start = |recorder: &mut recorder::TraceRecorder<'_>, ray, background| {
        recorder.viewing_ray(ray, background);
    };
    let value = trace_pixel_with(scene, view, settings, (row, col), (&mut recorder, start));
    let kind = match view.shading {
        Shading::Flat | Shading::Lit => PixelKind::Color,
        Shading::Normals | Shading::Depth => PixelKind::Data,
    };
    Ok(PixelTrace {
        row,
        col,
        steps: recorder.into_steps(),
        value,
        kind,
        rgb8: kind.to_rgb8(value),
    })
}

/// The index in the scene's materials of the material `hit` is on.
pub(crate) fn material_index(scene: &Scene, hit: &Hit) -> usize {
    let material = scene.material(hit);
    scene
        .materials()
        .iter()
        .position(|m| std::ptr::eq(m, material))
        .unwrap_or_default()
}

/// What kind of object `object` is.
fn shape(object: &Object) -> Shape {
    match object {
        Object::Sphere(_) => Shape::Sphere,
        Object::Plane(_) => Shape::Plane,
        Object::Triangle(_) => Shape::Triangle,
        Object::Box(_) => Shape::Box,
        Object::Instance(_) => Shape::Mesh,
    }
}

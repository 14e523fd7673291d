//! viewray's renderer: for each pixel, generate viewing rays, find the closest object
//! each meets, and determine its colour.
//!
//! This crate owns shading (the four [`Shading`](viewray_scene::Shading) modes, lights,
//! shadows, mirrors, grid lines), sampling (where each sample falls in a pixel and on the
//! lens), the parallel tile loop, and the [`Image`] with its PNG and EXR encoders. It
//! takes a loaded [`Scene`](viewray_scene::Scene) and knows no file format but image
//! output: no RON, no OBJ, no command line.
//!
//! Where to start reading: module `render` ([`render()`], [`render_view`]) splits the image
//! into tiles and traces each tile block by block; `sampling` says where each sample
//! falls; `shade` is what a ray sees (its module doc is the map: the block driver, Lit
//! batches with their lights and mirrors, grid lines, depth); `lanes` holds four
//! samples' vectors side by side for Lit shading (surface colours, lighting); `image` is the [`Image`] and its
//! encoders; `trace` is [`trace_pixel`], one pixel's trace with every number the
//! shading computed (for `viewray trace`), read through hooks in the shading code.
//!
//! # Shading
//!
//! Colours are linear RGB throughout; see the camera crate's
//! [conventions](viewray_camera#conventions) for pixels and rays.
//!
//! - **Flat**: the material's colour as is, so a render of pure colours is a coverage
//!   mask. Grid lines are part of a material's colour pattern, so they are drawn too.
//! - **Normals**: the shading normal (facing the ray) mapped from `[-1, 1]` to `[0, 1]`,
//!   `n / 2 + 1/2`.
//! - **Depth**: near white, far dark: distance along the view direction `-w` (from the
//!   eye for panoramic cameras) mapped linearly from the nearest hit to the farthest hit
//!   on a bounded object, both found by a pre-pass of one centre ray per pixel, so the
//!   rule does not depend on threads or tiles. Infinite planes fade on to black beyond
//!   the farthest object.
//! - **Lit**: Blinn-Phong, summed over the lights, for unit vectors `n` (shading normal),
//!   `l` (to the light), `v` (to the eye), `h = (l + v) / |l + v|`:
//!
//!   ```text
//!   ambient:      color * I
//!   point:        (I / r^2) (color max(0, n.l) + specular max(0, n.h)^shininess)
//!   directional:  I (color max(0, n.l) + specular max(0, n.h)^shininess)
//!   mirror:       (1 - mirror) local + mirror * (colour along the reflected ray)
//!   ```
//!
//!   Point and directional lights cast hard shadows: a shadow ray from the hit point,
//!   moved off the surface along the geometric normal (by 1e-4 of the size of its
//!   coordinates plus 1e-5 of the distance the ray travelled), asks
//!   [`World::any_hit`](viewray_geometry::World::any_hit) whether anything lies before
//!   the light. Reflections follow
//!   [`RenderSettings::max_reflection_depth`] bounces (default
//!   [`MAX_REFLECTION_DEPTH`]). A scene with no lights at all gets a headlight (a light
//!   at the eye plus a little ambient), so a camera-only scene is visible.
//!
//! Grid materials draw lines of constant world coordinate every `spacing` along the two
//! world axes closest to the surface's plane (x and z on a ground plane), `line_width`
//! wide. Each sample averages the lines over its footprint on the surface (from the
//! neighbouring samples' rays, as ray differentials do), so grids stay smooth to the
//! horizon instead of turning into moire.
//!
//! # Sampling and determinism
//!
//! One sample per pixel is the pixel centre through the lens centre: exactly the
//! lecture's viewing ray. `n > 1` samples are stratified: the pixel is split into `n`
//! cells of equal area (`round(sqrt n)` rows of `n / rows` or one more cells; 16 gives
//! a 4 x 4 grid) and each sample is jittered in its cell. Lens samples, for cameras with
//! a lens, are stratified the same way with their cells shuffled per pixel. The random
//! numbers come from a SplitMix64 generator seeded by (row, col, sample index) alone, so
//! an image is byte-identical on any number of threads. Pixels average their samples (a
//! box filter). A tile hashes each pixel's part of the seed once; a block's samples are
//! drawn together before its rays (four pixels at a time where the processor has AVX2,
//! the same bits as one at a time; a round thin lens's rays too, four at a time).
//!
//! Tiles of 16 x 16 pixels are rendered in parallel. Within a tile, each sample index
//! is traced block by block: the viewing rays of 8 x 8 neighbouring pixels go to
//! [`World::closest_objects`](viewray_geometry::World::closest_objects) as one packet
//! (same hits as ray by ray, a fraction of the work), and each pixel still adds its
//! samples in index order. Before a tile traces anything, it asks of each block what
//! any of its rays may meet, whatever its samples
//! ([`Camera::ray_bounds`](viewray_camera::Camera::ray_bounds),
//! [`World::reach`](viewray_geometry::World::reach)): a block that surely meets nothing
//! (the sky) makes no rays, its pixels getting the background once per sample as its
//! misses would; one that meets planes at most (the open ground), or planes and one
//! sphere or triangle (the ground around a ball), traces its rays against those alone.
//! Flat shading of a plain colour and Depth shading need no normals, so they skip the
//! surface details. Lit shading works on the block's hits together: their shadow rays
//! toward each light go to
//! [`World::any_hits`](viewray_geometry::World::any_hits) as one batch, their reflected
//! rays to `closest_objects`, and the reflected hits are shaded as a batch one bounce
//! deeper. The lighting itself is worked out four samples at a time, light by light,
//! in SIMD lanes (structure of arrays) that do glam's operations in glam's order, `powf`
//! lane by lane; each sample still sums its lights in order with the same numbers, so
//! the image is the same, bit for bit, as sample by sample.
//!
//! [`trace_pixel`] traces one pixel of a one-sample render through that same code (its
//! whole block and batches, as the render does) and keeps the numbers of its sample
//! at each step, so a trace's value is always the image's.
//!
//! # Unsafe code
//!
//! The workspace denies `unsafe_code`; this crate opts in at two sites, each with a
//! `SAFETY` comment, both in `sampling.rs` and both where the processor was found to run
//! AVX2: the call of its AVX2 build of the block's sample drawing, and, for a camera with
//! a lens, the call of the camera's AVX2 build of a block's rays
//! (`Camera::generate_sampled_block_rays_avx2`). Neither function holds an unsafe
//! operation.
//!
//! # Output
//!
//! [`Image`] holds linear `f32` RGB. PNG output is 8-bit with the sRGB transfer function
//! ([`viewray_output::linear_to_srgb`], not a 2.2 gamma) for colour renders; Normals and Depth renders
//! are data and are stored as `round(255 x)` ([`PixelKind`]). EXR output holds the
//! linear floats as rendered.
//!
//! ```
//! use std::path::Path;
//! use viewray_render::{render, RenderSettings};
//! use viewray_scene::SceneLoader;
//!
//! let scene = SceneLoader::text(
//!     "(image: (width: 8, height: 6), shading: Flat,
//!       camera: (eye: (0.0, 0.0, 0.0), look_at: (0.0, 0.0, -1.0),
//!                projection: Perspective(distance: 1.0, viewport: (1.0, 0.75))),
//!       materials: { \"red\": (color: (1.0, 0.0, 0.0)) },
//!       objects: [Sphere(center: (0.0, 0.0, -5.0), radius: 1.0, material: \"red\")])",
//!     Path::new("example.ron"),
//! )
//! .load()?
//! .scene;
//! let rendered = render(&scene, &RenderSettings::default(), |_, _| {})?;
//! assert_eq!(rendered.image.pixel(3, 4), glam::Vec3::new(1.0, 0.0, 0.0));
//! assert_eq!(rendered.stats.rays, 8 * 6);
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod image;
mod labels;
mod lanes;
mod render;
mod sampling;
mod shade;
#[cfg(test)]
mod test_numbers;
mod trace;

pub use crate::image::{Image, ImageError, ImageFormat, PixelKind};
pub use crate::labels::{BACKGROUND_LABEL, object_labels};
pub use crate::render::{
    MAX_REFLECTION_DEPTH, RenderError, RenderSettings, RenderStats, Rendered, TILE_SIZE, View,
    render, render_view, render_view_cancellable,
};
pub use crate::trace::{
    BlinnPhong, ClosestHit, DepthValue, GridLines, HeadlightTerms, LightSource, LightTerms,
    LitSurface, LitTerm, PixelOutside, PixelTrace, ShadowRay, Shape, Specular, Step, StepKind,
    trace_pixel,
};

//! What a ray sees: the four shading modes, grid lines, lights, shadows and mirrors.
//!
//! A [`Shader`] holds what every tile shares (the scene, the camera, the mode, the depth
//! range, the background); each part of its work is a module:
//!
//! - [`primary`]: the block driver. A block's viewing rays are traced together
//!   ([`Shader::trace_primary`]) and shaded together ([`Shader::shade_primaries`]):
//!   Flat, Normals and Depth sample by sample, Lit as one batch.
//! - [`lit`]: Lit shading of a batch, four samples at a time: the surface details of
//!   each group of four, then `lit::lights` (the headlight, ambient, point and
//!   directional lights, their shadow rays traced together, Blinn-Phong in lanes), then
//!   `lit::mirrors` (the reflected rays traced together and shaded as a batch one
//!   bounce deeper).
//! - [`grid`]: a material's colour with its grid lines, box-filtered over the sample's
//!   [`footprint`] on the surface, which the pixel's ray differentials give; for Lit
//!   batches four samples at a time, bit for bit as one alone.
//! - [`depth`]: the rule that turns hit points into Depth values, and the pre-pass that
//!   finds its range.
//! - [`record`]: the hooks through which each step tells a [`Recorder`] the numbers of
//!   the one sample it follows (`viewray trace`); the renderer's recorder records
//!   nothing and its hooks compile away.
//!
//! Every step does the same arithmetic, in the same order, as one sample shaded alone,
//! so batching, lanes and tiles never change a pixel.

mod depth;
mod footprint;
mod grid;
mod lit;
mod primary;
mod record;

use glam::Vec3;
use viewray_camera::Camera;
use viewray_output::linear_to_srgb;
use viewray_scene::{Scene, Shading};

use crate::View;

pub(crate) use self::depth::{DepthMap, DepthRange};
pub(crate) use self::footprint::{FilmPixel, FilmPoint};
pub(crate) use self::lit::LitScratch;
pub(crate) use self::primary::T_MIN;
pub(crate) use self::record::{NoRecorder, Recorder};

/// Everything shading needs, shared read-only by every tile.
pub(crate) struct Shader<'a> {
    scene: &'a Scene,
    /// The camera (for ray differentials) and the shading, which may not be the scene's.
    camera: &'a Camera,
    shading: Shading,
    max_depth: u32,
    depth_map: DepthMap,
    /// The background as stored in the image: the colour itself for colour images,
    /// its sRGB encoding for data images (so it looks the same in a PNG).
    background: Vec3,
}

impl<'a> Shader<'a> {
    pub(crate) fn new(
        scene: &'a Scene,
        view: &'a View,
        max_depth: u32,
        depth_map: DepthMap,
    ) -> Self {
        let background = match view.shading {
            Shading::Flat | Shading::Lit => scene.background(),
            Shading::Normals | Shading::Depth => scene.background().map(linear_to_srgb),
        };
        Self {
            scene,
            camera: &view.camera,
            shading: view.shading,
            max_depth,
            depth_map,
            background,
        }
    }
}

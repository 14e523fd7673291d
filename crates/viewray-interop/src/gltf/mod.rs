//! glTF 2.0: `.gltf` (JSON, buffers embedded as base64) and `.glb` (binary).
//!
//! # Conventions
//!
//! - **Axes.** Right-handed, `+y` up, metres. A camera looks down its node's local `-z`
//!   with `+x` right and `+y` up: viewray's `U`, `V`, `W`, so the node's `matrix`
//!   (column-major) has the columns `U`, `V`, `W`, `e`.
//! - **Field of view.** `perspective.yfov` is *vertical*, in radians: `vh = 2 d tan(yfov
//!   / 2)`. `aspectRatio = vw / vh` when given; without it the renderer's viewport
//!   decides (an imported camera then gets a 640 x 480 image and `fov_y`).
//! - **Orthographic.** `xmag` and `ymag` are *half* the viewport: `vw = 2 xmag`,
//!   `vh = 2 ymag`. viewray writes `znear = 0`, `zfar = 10^6`.
//! - **Image size** is not part of glTF: viewray keeps it in the camera's `extras`
//!   (`{"viewray": {"width", "height", "samples"}}`) and reads it back from there.
//! - **Geometry.** glTF has only triangle meshes: spheres become 64 x 32 UV spheres,
//!   infinite planes squares 2 x 10^4 across. Colours are linear `baseColorFactor`s;
//!   lights use `KHR_lights_punctual` (intensities times pi, as for three.js); the
//!   background and ambient light have no glTF counterpart.
//! - **Cannot be expressed**: a shift (glTF's frustum is symmetric), a lens, oblique and
//!   panoramic cameras.
//!
//! # Where to read
//!
//! [`export`](fn@export) (`export.rs`) writes a scene, [`import`](fn@import) (`import.rs`)
//! reads one by walking the default scene's nodes; `glb.rs` is the binary container both go
//! through.

mod export;
mod glb;
mod import;

pub use export::export;
pub use import::import;

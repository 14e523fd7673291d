//! pbrt-v4 scene files.
//!
//! # Conventions
//!
//! - **Handedness.** pbrt's camera space is left-handed: `+x` right in the image, `+y`
//!   up, `+z` forward. `LookAt pos look up` builds `right = up x dir`, which in a
//!   right-handed world is the image's *left*: a right-handed scene seen through a plain
//!   `LookAt` comes out mirrored. viewray writes `Scale -1 1 1` before `LookAt e, e - W,
//!   V`, so that camera `x = U`, `y = V`, `z = -W` (what Blender's pbrt exporter does).
//!   On import, a perspective or orthographic camera whose frame is right-handed in the
//!   world (a plain `LookAt`) is made exact by mirroring the whole scene in `x`, and a
//!   comment says so.
//! - **Field of view.** `fov` (degrees, default 90) spans the *shorter* image side: the
//!   screen window is `[-a, a] x [-1, 1]` for `a = W / H > 1`, else `[-1, 1] x
//!   [-1/a, 1/a]`, and a screen point `(x, y)` is the camera-space point
//!   `(x t, y t, 1)` with `t = tan(fov / 2)`.
//! - **Shift and non-square pixels.** An explicit `screenwindow [x0 x1 y0 y1]` is the
//!   viewport at distance 1 in units of `t`: viewray writes
//!   `[(sx - vw/2)/(d t), (sx + vw/2)/(d t), (sy - vh/2)/(d t), (sy + vh/2)/(d t)]` when
//!   there is a shift or the pixels are not square.
//! - **Orthographic.** The screen window is the viewport itself, in scene units (default
//!   `[-a, a] x [-1, 1]`); viewray always writes it. pbrt's orthographic camera takes a
//!   lens too (`lensradius`, `focaldistance`), as viewray's does.
//! - **Thin lens.** `lensradius` is `r`, `focaldistance` is `f` (along the view axis).
//! - **Panorama.** `Camera "spherical" "string mapping" "equirectangular"`: the image's
//!   centre looks along camera `-x`, its top along `+y`, its left edge along `+x`; viewray
//!   writes `LookAt e, e - U, V` (no mirroring) so that `x = W`, `y = V`, `z = -U`.
//!   pbrt-v4 has no equidistant fisheye.
//! - **Units of light**: as Mitsuba's (`I` and `L` are written times pi); the background
//!   is an `infinite` light; viewray's ambient light has no counterpart.
//! - **Cannot be expressed**: an oblique camera (pbrt warns that a camera transform with
//!   shear or scale breaks its assumptions), the fisheye, a tilted or swung lens,
//!   aperture blades.
//!
//! # Where to read
//!
//! [`export`](fn@export) (`export.rs`) writes a scene. [`import`](fn@import) (`import.rs`)
//! reads one with an `Importer` that keeps pbrt's graphics state and has one method per
//! directive (the camera's in `import/camera.rs`, the world's in `import/world.rs`); the
//! tokens and `"type name" value` parameters it reads come from `parse.rs`.

mod export;
mod import;
mod parse;

pub use export::export;
pub use import::import;

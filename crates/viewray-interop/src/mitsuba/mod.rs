//! Mitsuba 3 XML scenes (`mitsuba.load_file`).
//!
//! # Conventions
//!
//! - **Axes.** World space is right-handed, as viewray's. A sensor's local frame has `+z`
//!   forward, `+y` up and `+x` to the image's **left**: `<lookat origin target up>`
//!   builds the columns `left = normalize(up x dir)`, `up' = dir x left`, `dir`. So
//!   `U = -x`, `V = y`, `W = -z`, `e` = the translation, and viewray writes the lookat
//!   `origin = e`, `target = e - W`, `up = V`.
//! - **Field of view.** `fov` (degrees) spans the axis `fov_axis` names: `x` (the
//!   default), `y`, `diagonal`, `smaller`, `larger`, of the film (pixels are square:
//!   `vw / vh = W / H`). Without `fov`, `focal_length` ("50mm", the default) is a 35 mm
//!   equivalent: a diagonal field of view `2 atan(sqrt(36^2 + 24^2) / (2 f))`. viewray
//!   writes `fov` on the `x` axis, `2 atan(vw / (2 d))`.
//! - **Shift.** `principal_point_offset_x = sx / vw`, `principal_point_offset_y =
//!   -sy / vh`: fractions of the film, `y` measured downwards (a positive `y` offset
//!   moves the picture up). The `thinlens` sensor has no principal point.
//! - **Orthographic scale.** The `orthographic` sensor sees `[-1, 1]` across `x` and
//!   `[-1/a, 1/a]` across `y` (`a = W / H`) before `to_world`; a `to_world` scale of
//!   `(sx, sy)` makes `vw = 2 sx`, `vh = 2 sy / a`.
//! - **Thin lens.** `aperture_radius` is `r`, `focus_distance` is `f` (measured along the
//!   view axis, as viewray's).
//! - **Clipping.** Rays start at `near_clip` (default 0.01) along the view axis, not at
//!   the eye: nearer objects are not seen.
//! - **Units of light.** Mitsuba's diffuse BSDF is `albedo / pi`, viewray's Lit shading
//!   `albedo`: a point light of viewray intensity `I` is written as `intensity = pi I`,
//!   a directional one as `irradiance = pi E`; the background is a `constant` emitter.
//!   viewray's ambient light has no counterpart (a comment says so).
//! - **Cannot be expressed**: an oblique camera, an orthographic camera with a lens, a
//!   shifted, tilted or swung thin lens, aperture blades, non-square pixels in
//!   perspective, the panoramic cameras.
//! - Meshes are written as OBJ files beside the XML (`<stem>-mesh<N>.obj`), one per
//!
//! # Where to read
//!
//! [`export`](fn@export) (`export.rs`) writes the XML and the meshes' OBJ files;
//! [`import`](fn@import) (`import.rs`) reads a scene's sensor, emitters, materials and
//! shapes through a `Reader` whose XML values (properties, `$name` defaults, transforms)
//! are in `xml.rs`.

mod export;
mod import;
mod xml;

pub use export::export;
pub use import::import;

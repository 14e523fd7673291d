//! three.js JSON objects (`THREE.ObjectLoader().parse`, `object.toJSON()`).
//!
//! # Conventions
//!
//! - **Axes.** Right-handed, `+y` up; a camera looks down its local `-z` with `+x` right
//!   and `+y` up, exactly viewray's `U`, `V`, `W`: the camera's `matrix` (column-major,
//!   16 numbers) has the columns `U`, `V`, `W`, `e`.
//! - **Field of view.** `PerspectiveCamera.fov` is *vertical*, in degrees, divided by
//!   `zoom`: `vh = 2 d tan(fov / 2) / zoom`, `vw = aspect vh`. `aspect` is a number of
//!   its own, not the canvas's: viewray writes `aspect = vw / vh`.
//! - **Shift.** `setViewOffset(fullWidth, fullHeight, x, y, width, height)` (the JSON's
//!   `view`) moves the window by `x` pixels right and `y` pixels *down* of a
//!   `fullWidth x fullHeight` image: `sx = x vw / fullWidth`, `sy = -y vh / fullHeight`.
//!   `filmOffset` (mm on a `filmGauge` of 35 mm across the smaller side) shifts
//!   horizontally too: `sx = d filmOffset / (filmGauge min(aspect, 1))` at zoom 1.
//!   viewray always writes a `view` of the image's own size, so the image size comes
//!   back on import; without a `view` an imported camera gets a 480-row image of its
//!   aspect ratio.
//! - **Orthographic.** `left`, `right`, `top`, `bottom` (divided by `zoom` about their
//!   centre) are the viewport in scene units; viewray writes `±vw/2`, `±vh/2` with
//!   `near = 0`. On import an off-centre window or a `near` plane moves the eye (viewray's
//!   parallel rays start on the image plane).
//! - **Colours** are sRGB-encoded `0xRRGGBB` integers (three.js's colour management);
//!   lights are `intensity` times a colour, and three.js's Lambert BRDF has the `1 / pi`
//!   viewray's shading lacks, so intensities are written times pi.
//! - **Cannot be expressed**: a lens (three.js cameras are pinholes; `focus` is for
//!   stereo), oblique and panoramic cameras.
//!
//! # Where to read
//!
//! [`export`](fn@export) (`export.rs`) writes a scene as one `Scene` object;
//! [`import`](fn@import) (`import.rs`) walks an object's children and reads its first
//! camera.

mod export;
mod import;

pub use export::export;
pub use import::import;

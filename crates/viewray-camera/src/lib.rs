//! The lecture's cameras, made exact: camera frames, every projection family, the
//! pixel -> viewing ray rule and its inverse, point -> pixel.
//!
//! # What it owns
//!
//! - [`Frame`] (`e`, `u`, `v`, `w` from eye, view and up; `frame`), the [`Projection`]
//!   families and their parameters (`projection`; fields of view and physical lenses in
//!   `lens`), [`Camera`] (a frame, a projection and an image size: [`Camera::generate_ray`]
//!   and its block and differential forms, [`Camera::project`]; `camera`), the taxonomy
//!   [`Preset`]s (`presets`) and the lens's sample points (`sampling`).
//! - The thin lens's movements and iris: a tilted or swung lens's plane of focus, its
//!   Scheimpflug and hinge lines ([`TiltedFocus`], [`Camera::focus_plane`]; `scheimpflug`)
//!   and the aperture's blades ([`Iris`]; `iris`), with the ray through a chosen lens
//!   point ([`Camera::generate_ray_at_lens`]).
//! - The lecture's catalogue of mistakes ([`Mistake`], [`Mistakes`]; `mistakes`).
//! - viewray's image limits: the largest image and the most samples per pixel, and the
//!   one check of a size and a sample count against them ([`ImageLimits`],
//!   [`ImageLimitError`]; `image_limits`), which scene files, the command line and the
//!   live playground call.
//! - The conventions below, written once for every crate.
//!
//! # Invariant
//!
//! This crate is pure: it does no I/O and never panics on user input. Invalid parameters
//! are rejected where a value is built ([`Frame::from_eye_view_up`], [`Camera::new`]),
//! so a [`Camera`] that exists always produces finite rays, and [`Camera::project`]
//! inverts [`Camera::generate_ray`] for every family.
//!
//! # Conventions
//!
//! These hold everywhere in viewray; other docs link here. The repository's
//! `docs/cameras.md` explains them for students, with worked examples.
//!
//! - **World space** is right-handed. Presets and the default scenes take `+y` as up.
//! - **The camera frame** `(e; u, v, w)` is orthonormal and right-handed: `u` points right
//!   in the image, `v` up, `w` back; the camera looks along `-w` (the lecture's canonical
//!   camera looks down `-z`). In formulas, `U`, `V`, `W` are the basis vectors and `u`, `v`
//!   the image-plane coordinates.
//! - **Pixels**: an image is `W` columns by `H` rows. Indices are 0-based, `row` from the
//!   top and `col` from the left. The lecture's `(i, j)` are 1-based: `i = row + 1`,
//!   `j = col + 1`.
//! - **Continuous image coordinates** `(x, y)`: `x` from the left edge, `y` from the top,
//!   in pixels. Pixel `(row, col)` covers `[col, col + 1) x [row, row + 1)` and its centre
//!   is `(col + 1/2, row + 1/2)`. An offset in the pixel `(ox, oy)` in `[0, 1)^2` (the
//!   `p_film` of a [`CameraSample`]) picks the point `(col + ox, row + oy)`. Not to be
//!   confused with the lens shift `(sx, sy)` of the table below, which moves the window
//!   on the image plane.
//! - **The image plane**: `u = (x / W - 1/2) vw`, `v = -(y / H - 1/2) vh` (see
//!   [`pixel_to_image_plane`]).
//! - **Viewing rays** are `origin + t direction` with `t > 0`, and their directions are
//!   *not* normalized: they are exactly the lecture's, so `(u, v, -d)` for the canonical
//!   camera, and a printed ray can be checked against a homework answer.
//! - **Angles** are radians in this API and degrees in scene files.
//! - **Fields of view** are full angles across one extent of the viewport ([`FovAxis`]:
//!   x, y, diagonal, the smaller or the larger side); **physical cameras** give a focal
//!   length and a sensor in millimetres, fitted as Blender's `sensor_fit` ([`SensorFit`]),
//!   with scene units of metres: see [`Perspective::from_fov`] and
//!   [`Perspective::from_focal_length`].
//! - Everything is computed in `f64`; [`viewray_geometry::DRay::as_ray`] rounds a ray for
//!   the tracer.
//!
//! # Boundaries
//!
//! What happens exactly on an edge, decided once and tested with hand-worked values:
//!
//! - **Pixel edges**: pixel `(row, col)` holds its left and top edges but not its right
//!   and bottom ones. A point exactly on the image's right edge (`x = W`) or bottom edge
//!   (`y = H`) is in no pixel: [`Camera::pixel_at`] returns `None`, while
//!   [`Camera::project`] still gives its coordinates (`x = W`). The image is
//!   `[0, W) x [0, H)`.
//! - **Behind the eye**: a perspective or thin-lens camera sees a point only strictly in
//!   front of the eye (depth `> 0`); a point in the eye's own plane is not seen. A
//!   parallel camera's rays start on the image plane at `t = 0`, which is excluded, so a
//!   point on the image plane itself is not seen; one just in front of it is.
//! - **Fields of view** of a perspective camera lie strictly between 0 and 180 degrees: at
//!   180 the viewport would be infinite.
//! - **Fisheye**: the field of view `F` lies in `(0, 360]` degrees, so 180 and 360 are
//!   both valid. A point exactly on the image circle (`r = 1`) has a ray (at `theta =
//!   F/2`; sideways for 180 degrees, straight back for 360); only `r > 1` has none. A
//!   world point exactly at `theta = F/2` projects onto the circle. Straight back, which
//!   only a 360-degree fisheye sees, is the whole circle: [`Camera::project`] names its
//!   rightmost point `(W, H/2)`.
//! - **Equirectangular**: the left edge `x = 0` and the right edge `x = W` are both
//!   longitude `pi`, straight back; [`Camera::project`] puts straight back on `x = 0` so
//!   that every point lands in `[0, W)`. `y = 0` looks straight up and `y = H` straight
//!   down.
//! - **The eye itself** has no direction: panoramic cameras do not project it.
//! - **Lens tilt and swing** lie strictly between -90 and 90 degrees (at 90 the lens
//!   would stand edge-on to the sensor); a tilted lens focuses strictly beyond its focal
//!   length (`f > d`). A pixel whose centre ray meets the plane of focus behind the eye
//!   or runs parallel to it has no sharp point in front of the lens: its rays spread
//!   from the virtual one (see the module `scheimpflug`).
//! - **Blades**: 0 (round) or 3 to 64; a rotation is any angle, wrapped into
//!   `[-180, 180)` degrees. A lens point on the aperture's edge is on the aperture
//!   ([`Iris::contains`]); the unit square's edges map exactly onto the polygon's edges.
//!
//! # Families
//!
//! `(sx, sy)` is the lens shift of the perspective families (zero unless a scene sets
//! one), `d` the distance to the image plane, `r` the lens radius, `f` the focus
//! distance, `(lx, ly)` the lens point in unit-disk coordinates (the lens sample mapped
//! to the aperture, an [`Iris`]: the unit disk, or a polygon of blades inscribed in it),
//! `L` and `phi` the oblique ratio and angle, `c` the pinhole direction
//! `(u+sx) U + (v+sy) V - d W`.
//!
//! | family | origin | direction |
//! |---|---|---|
//! | [`Perspective`] | `e` | `(u+sx) U + (v+sy) V - d W` |
//! | [`ThinLens`] | `e + r(lx U + ly V)` | `(f/d)((u+sx) U + (v+sy) V - d W) - r(lx U + ly V)` |
//! | [`ThinLens`], tilted | `e + r(lx U + ly V)` | `(F / m.c) c - r(lx U + ly V)`: through the point where `c` meets the plane of focus `m.P = F` |
//! | [`Orthographic`] | `e + u U + v V` | `-W` |
//! | [`Oblique`] | `e + u U + v V` | `-W - L (cos phi U + sin phi V)` |
//! | [`Projection::Equirectangular`] | `e` | longitude and latitude from `(x, y)` |
//! | [`Fisheye`] | `e` | equidistant: angle from `-W` proportional to the radius |
//!
//! The classical taxonomy (multiview, axonometric, oblique, one/two/three-point
//! perspective) is a set of [`Preset`]s over these rules.
//!
//! A tilted or swung thin lens (a view camera's movements, `F = d` its focal length)
//! focuses on a plane through its Scheimpflug and hinge lines, `m = n + (1 - F/f) W`
//! with `n` the lens's axis; the module `scheimpflug` derives it and writes the rule
//! for the centre ray's meeting point behind the eye or at infinity.
//!
//! # Where to start reading
//!
//! `camera` (the pixel -> ray rule and its inverse: the pixel mapping, the frame
//! transform, `project`), then `projection` (each family's formula, the table above) and
//! `frame`, which builds the basis; `lens` the fields of view and physical cameras,
//! `presets` the taxonomy, `mistakes` the lecture's catalogue of wrong formulas. The
//! lens: `sampling` maps lens samples to the unit disk or a polygon, `iris` is the
//! aperture's shape, `scheimpflug` the tilted lens's plane of focus and rays.

mod camera;
mod error;
mod frame;
mod image_limits;
mod iris;
mod lens;
mod mistakes;
mod presets;
mod projection;
mod sampling;
mod scheimpflug;

pub use camera::{Camera, CameraSample, RayDifferential, pixel_to_image_plane};
pub(crate) use camera::{image_plane_to_image, image_to_image_plane};
pub use error::CameraError;
pub use frame::Frame;
pub use image_limits::{
    ImageLimitError, ImageLimits, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES,
};
pub use iris::Iris;
pub use lens::{FovAxis, MILLIMETRES_PER_UNIT, SensorFit, aperture_from_f_number};
pub use mistakes::{Entry, Mistake, Mistakes};
pub use presets::{PARALLEL_EYE_DISTANCE, PRESET_FOV_Y_DEGREES, Preset};
pub use projection::{
    Fisheye, FisheyePoint, Lens, Oblique, Orthographic, Perspective, Projection, ThinLens,
    equirectangular_angles,
};
pub use sampling::{sample_regular_polygon, sample_unit_disk_concentric};
pub use scheimpflug::{Line3, Plane3, TiltedFocus};

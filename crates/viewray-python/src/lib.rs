//! The `viewray` Python module: a scene's viewing rays, frame, projections and renders
//! as NumPy arrays, with the same numbers and pixels as the `viewray` command.
//!
//! ```python
//! import viewray
//! scene = viewray.Scene.load("scene.ron")   # or viewray.Scene.parse(text)
//! o, d = scene.rays()                       # float64 (H, W, 3) each
//! f = scene.frame()                         # {"e", "u", "v", "w"}: float64 (3,)
//! xy = scene.project(points)                # (N, 3) -> (N, 2); NaN where not seen
//! img = scene.render(samples=4)             # uint8 (H, W, 3), as `viewray render`
//! report = viewray.check(scene, origins=o2, directions=d2)   # a student's arrays
//! report.ok, report.mistakes                # False, ["v-sign"]
//! ```
//!
//! Like the command, this crate is a thin layer over the libraries: viewray-scene loads
//! (its `SceneError` becomes `viewray.SceneError` with `path`, `line` and `column`),
//! viewray-camera makes the rays and projections, viewray-render renders. It owns only
//! what Python sees: the array layouts, what an argument must be, and the boundary.
//!
//! Where to start reading:
//! - `arrays`: each value laid out as a flat row-major buffer, computed without the
//!   interpreter ([`pixel_rays`], [`project_points`], [`render_rgb8`]);
//! - `shapes`: what an array argument or a sample count must be, and the sentence when
//!   it is not ([`ArraySpec`]);
//! - `guard`: every call runs inside [`catch_panic`], so a bug is a `RuntimeError`,
//!   never a panic in the interpreter;
//! - `module` (feature `python`): the PyO3 classes and functions over those. The GIL is
//!   released while rays are computed and while a scene loads or renders.
//!
//! **Invariant:** the module computes nothing the libraries do not: its rays are
//! `Camera::generate_ray` at the pixel's centre and the lens's centre (what `viewray
//! rays` prints), its pixels `Image::to_rgb8` of `viewray_render::render_view` (what
//! `viewray render` writes to a PNG).
//!
//! # Building
//!
//! `cargo xtask wheel` builds the wheel with maturin, which turns on the `python`
//! feature (PyO3 with the stable ABI from CPython 3.9, and the `numpy` crate). Without
//! the feature the crate is its array rules alone, so the workspace's `cargo build` and
//! `cargo test` need no Python and compile no PyO3; the module itself is tested from
//! Python by `cargo xtask wheel --test` (`tests/test_module.py`).
//!
//! # Checking a student's arrays
//!
//! `viewray.check(scene, origins=..., directions=...)` judges a student's rays, as
//! `viewray check` judges printed ones ([`check_rays`], on viewray-judge): each pixel's
//! ray against the scene's camera, and the wrong ones explained by the lecture's
//! catalogue. Its report (`ok`, `mistakes`, `alternatives`, `wrong`, and `str()` in the
//! command's words) is `viewray.Report`.

mod arrays;
mod guard;
#[cfg(feature = "python")]
mod module;
mod shapes;

pub use arrays::{PixelRays, check_rays, pixel_rays, project_points, render_rgb8};
pub use guard::{Panic, catch_panic};
pub use shapes::{ArraySpec, Axis, FLOAT64, samples};

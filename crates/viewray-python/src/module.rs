//! The PyO3 layer: the `viewray` module, its `Scene` class and `SceneError`, and the
//! conversions between Python's values and the crate's buffers. Every method body runs
//! inside [`guarded`], so no panic reaches the interpreter; long computations release
//! the GIL.

use std::path::{Path, PathBuf};

use glam::DVec3;
use numpy::{PyArray1, PyArray2, PyArrayMethods, PyUntypedArray, PyUntypedArrayMethods};
use pyo3::create_exception;
use pyo3::exceptions::{PyException, PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use pyo3::types::PyDict;
use viewray_scene::{Scene, SceneLoader};

use crate::arrays::{check_rays, pixel_rays, project_points, render_rgb8};
use crate::guard::catch_panic;
use crate::shapes::{self, ArraySpec};

create_exception!(
    viewray,
    SceneError,
    PyException,
    "A scene that could not be loaded. `str(error)` is `path:line:column: message`, as \
     `viewray` prints it; the attributes `path`, `line`, `column` (None where the \
     position is unknown) and `message` hold its parts."
);

/// The name a scene given as text goes by in errors (its meshes are found from the
/// current folder).
const TEXT_NAME: &str = "<string>";

/// Runs a method's body, turning a panic into a `RuntimeError` naming it.
fn guarded<T>(body: impl FnOnce() -> PyResult<T>) -> PyResult<T> {
    catch_panic(body).unwrap_or_else(|panic| Err(PyRuntimeError::new_err(panic.sentence())))
}

/// The `SceneError` of a scene that did not load, with its parts as attributes.
fn scene_error(py: Python<'_>, error: &viewray_scene::SceneError) -> PyErr {
    let raised = SceneError::new_err(error.to_string());
    let value = raised.value(py);
    let position = error.position();
    let attributes = value
        .setattr("path", error.path().display().to_string())
        .and_then(|()| value.setattr("message", error.message()))
        .and_then(|()| value.setattr("line", position.map(|p| p.line)))
        .and_then(|()| value.setattr("column", position.map(|p| p.column)));
    match attributes {
        Ok(()) => raised,
        Err(failed) => failed,
    }
}

/// A loaded scene: its camera, image size, samples, objects, materials and lights, with
/// its BVHs built. Made by `Scene.load(path)` or `Scene.parse(text)`.
#[pyclass(name = "Scene", module = "viewray", frozen)]
struct PyScene {
    scene: Scene,
    /// The file it was loaded from, or `<string>`.
    path: PathBuf,
}

#[pymethods]
impl PyScene {
    /// Loads the scene file at `path` (a `str` or `os.PathLike`), as `viewray render
    /// path` does; meshes are found relative to the file.
    ///
    /// Raises `SceneError` (with `path`, `line`, `column`) when the file cannot be read
    /// or is not a valid scene.
    #[staticmethod]
    fn load(py: Python<'_>, path: PathBuf) -> PyResult<Self> {
        guarded(|| {
            let scene = py
                .detach(|| SceneLoader::file(&path).load().map(|loaded| loaded.scene))
                .map_err(|error| scene_error(py, &error))?;
            Ok(Self { scene, path })
        })
    }

    /// Parses scene text (the format of a scene file); meshes are found relative to the
    /// current folder, and errors name the text `<string>`.
    ///
    /// Raises `SceneError` (with `path`, `line`, `column`) when the text is not a valid
    /// scene.
    #[staticmethod]
    fn parse(py: Python<'_>, text: &str) -> PyResult<Self> {
        guarded(|| {
            let path = Path::new(TEXT_NAME);
            let scene = py
                .detach(|| {
                    SceneLoader::text(text, path)
                        .load()
                        .map(|loaded| loaded.scene)
                })
                .map_err(|error| scene_error(py, &error))?;
            Ok(Self {
                scene,
                path: path.to_path_buf(),
            })
        })
    }

    /// The image's width W, in pixels.
    #[getter]
    fn width(&self) -> u32 {
        self.scene.camera().width()
    }

    /// The image's height H, in pixels.
    #[getter]
    fn height(&self) -> u32 {
        self.scene.camera().height()
    }

    /// Samples per pixel of `render()` unless it is given others.
    #[getter]
    fn samples(&self) -> u32 {
        self.scene.samples()
    }

    fn __repr__(&self) -> String {
        let samples = self.samples();
        format!(
            "<viewray.Scene {}: {} x {}, {samples} sample{}>",
            self.path.display(),
            self.width(),
            self.height(),
            if samples == 1 { "" } else { "s" }
        )
    }

    /// The viewing rays of every pixel, as `viewray rays` prints them: `(origins,
    /// directions)`, two float64 arrays of shape (H, W, 3), row 0 at the top. Each is the
    /// ray through the pixel's centre and the lens's centre; directions are not
    /// normalized (the lecture's formulas exactly). NaN where a pixel has no ray
    /// (outside a fisheye's circle).
    fn rays<'py>(&self, py: Python<'py>) -> PyResult<(Bound<'py, PyAny>, Bound<'py, PyAny>)> {
        guarded(|| {
            let camera = *self.scene.camera();
            let rays = py.detach(|| pixel_rays(&camera)).map_err(|_| {
                PyMemoryError::new_err(format!(
                    "not enough memory for the rays of a {} x {} image",
                    camera.width(),
                    camera.height()
                ))
            })?;
            let shape = [camera.height() as usize, camera.width() as usize, 3];
            let origins = PyArray1::from_vec(py, rays.origins).reshape(shape)?;
            let directions = PyArray1::from_vec(py, rays.directions).reshape(shape)?;
            Ok((origins.into_any(), directions.into_any()))
        })
    }

    /// The camera frame: a dict of float64 arrays of shape (3,), `e` (the eye) and the
    /// orthonormal basis `u` (right), `v` (up), `w` (back; the camera looks along -w).
    fn frame<'py>(&self, py: Python<'py>) -> PyResult<Bound<'py, PyDict>> {
        guarded(|| {
            let frame = self.scene.camera().frame();
            let dict = PyDict::new(py);
            for (name, vector) in [
                ("e", frame.e()),
                ("u", frame.u()),
                ("v", frame.v()),
                ("w", frame.w()),
            ] {
                dict.set_item(name, PyArray1::from_slice(py, &vector.to_array()))?;
            }
            Ok(dict)
        })
    }

    /// Where world points appear in the image: `points`, a float64 array of shape (N, 3),
    /// gives a float64 array of shape (N, 2) of continuous image coordinates (x, y), in
    /// pixels from the image's top-left corner (pixel (row, col) covers [col, col + 1) x
    /// [row, row + 1)); NaN where the camera does not see the point.
    ///
    /// Raises `ValueError` for anything but a float64 array of shape (N, 3).
    fn project<'py>(
        &self,
        py: Python<'py>,
        points: &Bound<'py, PyAny>,
    ) -> PyResult<Bound<'py, PyAny>> {
        guarded(|| {
            let points = float64_array(points, &ArraySpec::points())?;
            let points = points.cast::<PyArray2<f64>>()?.readonly();
            let points: Vec<DVec3> = points
                .as_array()
                .rows()
                .into_iter()
                .map(|row| DVec3::new(row[0], row[1], row[2]))
                .collect();
            let rows = points.len();
            let camera = *self.scene.camera();
            let xy = py.detach(|| project_points(&camera, points));
            Ok(PyArray1::from_vec(py, xy).reshape([rows, 2])?.into_any())
        })
    }

    /// Renders the scene as `viewray render` does and returns its pixels as the PNG
    /// holds them: a uint8 array of shape (H, W, 3), sRGB, row 0 at the top. `samples`
    /// (1 to 65536) replaces the scene's samples per pixel, as `--samples` does. The GIL
    /// is released while it renders, on all the machine's cores.
    ///
    /// Raises `ValueError` for a number of samples out of range.
    #[pyo3(signature = (samples = None))]
    fn render<'py>(&self, py: Python<'py>, samples: Option<i64>) -> PyResult<Bound<'py, PyAny>> {
        guarded(|| {
            let samples = samples
                .map(shapes::samples)
                .transpose()
                .map_err(PyValueError::new_err)?;
            let pixels = py
                .detach(|| render_rgb8(&self.scene, samples))
                .map_err(|error| PyRuntimeError::new_err(error.to_string()))?;
            let camera = self.scene.camera();
            let shape = [camera.height() as usize, camera.width() as usize, 3];
            Ok(PyArray1::from_vec(py, pixels).reshape(shape)?.into_any())
        })
    }
}

/// What `viewray.check` found: whether every ray is right, and the catalogue's
/// explanation of the wrong ones. `str(report)` is the summary `viewray check` prints.
#[pyclass(name = "Report", module = "viewray", frozen)]
struct PyReport {
    report: viewray_judge::Report,
}

#[pymethods]
impl PyReport {
    /// Whether every ray is right.
    #[getter]
    fn ok(&self) -> bool {
        self.report.passed()
    }

    /// How many rays are wrong.
    #[getter]
    fn wrong(&self) -> u64 {
        self.report.wrong
    }

    /// The catalogue ids that explain the wrong rays (`["v-sign"]`; two ids for two
    /// mistakes made together; entries that make the same rays for this camera are all
    /// listed); empty when every ray is right or no entry explains them.
    #[getter]
    fn mistakes(&self) -> Vec<&'static str> {
        let mut ids = Vec::new();
        for set in self.alternative_sets() {
            for mistake in set.iter() {
                if !ids.contains(&mistake.id()) {
                    ids.push(mistake.id());
                }
            }
        }
        ids
    }

    /// Each explanation on its own: a list of lists of ids (`[["v-sign"],
    /// ["v-cross-order"]]` when either makes these rays).
    #[getter]
    fn alternatives(&self) -> Vec<Vec<&'static str>> {
        self.alternative_sets()
            .iter()
            .map(|set| set.iter().map(|m| m.id()).collect())
            .collect()
    }

    fn __str__(&self) -> String {
        self.report.to_string()
    }

    fn __repr__(&self) -> String {
        format!(
            "<viewray.Report: {} rays, {} wrong{}>",
            self.report.answers,
            self.report.wrong,
            match self.mistakes().as_slice() {
                [] => String::new(),
                ids => format!(": {}", ids.join(", ")),
            }
        )
    }
}

impl PyReport {
    fn alternative_sets(&self) -> &[viewray_camera::Mistakes] {
        self.report
            .diagnosis
            .as_ref()
            .map_or(&[], |d| d.alternatives.as_slice())
    }
}

/// Judges a student's rays, as `viewray check` judges printed ones: `origins` and
/// `directions` are float64 arrays of shape (H, W, 3) for the scene's image (row 0 at
/// the top; what `Scene.rays()` returns for the right camera). Directions are right up
/// to a positive factor unless `exact_direction`; every comparison is relative, within
/// `tolerance`. Returns a `Report`: `ok`, `mistakes` (the catalogue ids that explain the
/// wrong rays) and, as text, the command's words with the formula to fix.
///
/// Raises `ValueError` for arrays of another dtype or shape, or a tolerance that is not
/// a positive number.
#[pyfunction]
#[pyo3(signature = (scene, origins, directions, *, tolerance = 1e-6, exact_direction = false))]
fn check(
    py: Python<'_>,
    scene: &PyScene,
    origins: &Bound<'_, PyAny>,
    directions: &Bound<'_, PyAny>,
    tolerance: f64,
    exact_direction: bool,
) -> PyResult<PyReport> {
    guarded(|| {
        if !(tolerance.is_finite() && tolerance > 0.0) {
            return Err(PyValueError::new_err(format!(
                "tolerance: expected a positive number such as 1e-6, found {tolerance}"
            )));
        }
        let camera = *scene.scene.camera();
        let (width, height) = (camera.width(), camera.height());
        let buffer = |value: &Bound<'_, PyAny>, name: &'static str| -> PyResult<Vec<f64>> {
            let array = float64_array(value, &ArraySpec::per_pixel(name, width, height))?;
            let array = array.cast::<numpy::PyArrayDyn<f64>>()?.readonly();
            Ok(array.as_array().iter().copied().collect())
        };
        let (origins, directions) = (
            buffer(origins, "origins")?,
            buffer(directions, "directions")?,
        );
        let options = viewray_judge::CheckOptions {
            one_based: false,
            tolerance,
            exact_direction,
        };
        let report = py.detach(|| check_rays(&camera, &origins, &directions, options));
        Ok(PyReport { report })
    })
}

/// `value` as a NumPy array that `spec` accepts.
///
/// # Errors
/// `ValueError` naming what was expected and what was found.
fn float64_array<'py>(
    value: &Bound<'py, PyAny>,
    spec: &ArraySpec,
) -> PyResult<Bound<'py, PyUntypedArray>> {
    let Ok(array) = value.cast::<PyUntypedArray>() else {
        let found = value.get_type().name()?;
        return Err(PyValueError::new_err(spec.not_an_array(&found.to_cow()?)));
    };
    let dtype = array.dtype().str()?;
    spec.check(&dtype.to_cow()?, array.shape())
        .map_err(PyValueError::new_err)?;
    Ok(array.clone())
}

/// The `viewray` module: scenes, their viewing rays, frames, projections and renders as
/// NumPy arrays, with the same numbers and pixels as the `viewray` command.
#[pymodule(name = "viewray")]
fn viewray_module(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("SceneError", m.py().get_type::<SceneError>())?;
    m.add_class::<PyScene>()?;
    m.add_class::<PyReport>()?;
    m.add_function(wrap_pyfunction!(check, m)?)?;
    Ok(())
}

//! What the module accepts from Python, checked before anything is computed: an array
//! argument's element type and shape, and a number of samples. Each refusal is a
//! sentence naming the argument, what was expected and what was found, which the PyO3
//! layer raises as a `ValueError`.

use viewray_scene::MAX_SAMPLES;

/// One axis of an expected array shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Axis {
    /// Any length, named for the message (`N`).
    Any(&'static str),
    /// Exactly this length.
    Exactly(usize),
}

/// What an array argument must be: `float64`, of a given shape.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ArraySpec {
    /// The argument's name, as the Python signature spells it (`points`).
    pub name: &'static str,
    /// The shape, axis by axis.
    pub shape: Vec<Axis>,
    /// What the exact axes are, for the message (`the scene's height and width`), or
    /// empty.
    pub why: &'static str,
}

/// The element type every array argument has: NumPy's name for `f64`.
pub const FLOAT64: &str = "float64";

impl ArraySpec {
    /// `points` of `project`: `(N, 3)`, one point a row.
    pub fn points() -> Self {
        Self {
            name: "points",
            shape: vec![Axis::Any("N"), Axis::Exactly(3)],
            why: "",
        }
    }

    /// An `(H, W, 3)` array of one vector per pixel for an image of `width x height`
    /// (a student's ray origins or directions), named `name`.
    pub fn per_pixel(name: &'static str, width: u32, height: u32) -> Self {
        Self {
            name,
            shape: vec![
                Axis::Exactly(height as usize),
                Axis::Exactly(width as usize),
                Axis::Exactly(3),
            ],
            why: " (the scene's height, width, 3)",
        }
    }

    /// The shape as Python prints one: `(N, 3)`, `(2,)`.
    fn shape_text(&self) -> String {
        let axes: Vec<String> = self
            .shape
            .iter()
            .map(|axis| match axis {
                Axis::Any(name) => (*name).to_owned(),
                Axis::Exactly(n) => n.to_string(),
            })
            .collect();
        tuple(&axes)
    }

    /// The sentence for an argument that is not a NumPy array at all.
    pub fn not_an_array(&self, found_type: &str) -> String {
        format!(
            "{}: expected a {FLOAT64} numpy array of shape {}{}, found {found_type} \
             (numpy.asarray({}, dtype=numpy.float64) makes one)",
            self.name,
            self.shape_text(),
            self.why,
            self.name
        )
    }

    /// Checks an array of element type `dtype` (NumPy's name for it) and shape `shape`.
    ///
    /// # Errors
    /// The sentence naming what was expected and what was found.
    pub fn check(&self, dtype: &str, shape: &[usize]) -> Result<(), String> {
        let fits = shape.len() == self.shape.len()
            && shape.iter().zip(&self.shape).all(|(&n, axis)| match axis {
                Axis::Any(_) => true,
                Axis::Exactly(m) => n == *m,
            });
        if dtype == FLOAT64 && fits {
            return Ok(());
        }
        let found: Vec<String> = shape.iter().map(usize::to_string).collect();
        Err(format!(
            "{}: expected a {FLOAT64} array of shape {}{}, found {} {dtype} array of shape {}",
            self.name,
            self.shape_text(),
            self.why,
            article(dtype),
            tuple(&found)
        ))
    }
}

/// `a` or `an`, as `word` is said (`an int64`, `a uint8`).
fn article(word: &str) -> &'static str {
    if word.starts_with(['a', 'e', 'i', 'o']) {
        "an"
    } else {
        "a"
    }
}

/// `(a, b)`, or `(a,)` for one item, as Python writes a tuple.
fn tuple(items: &[String]) -> String {
    match items {
        [one] => format!("({one},)"),
        _ => format!("({})", items.join(", ")),
    }
}

/// Checks `samples` of `render`: a whole number from 1 to [`MAX_SAMPLES`], as `viewray
/// render --samples` takes.
///
/// # Errors
/// The sentence naming the range.
pub fn samples(samples: i64) -> Result<u32, String> {
    u32::try_from(samples)
        .ok()
        .filter(|s| (1..=MAX_SAMPLES).contains(s))
        .ok_or_else(|| {
            format!(
                "samples: expected a whole number of samples from 1 to {MAX_SAMPLES}, found \
                 {samples}"
            )
        })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn points_are_float64_n_by_3() {
        let spec = ArraySpec::points();
        assert_eq!(spec.check("float64", &[5, 3]), Ok(()));
        assert_eq!(spec.check("float64", &[0, 3]), Ok(()));
        assert_eq!(
            spec.check("float64", &[3]),
            Err(
                "points: expected a float64 array of shape (N, 3), found a float64 array of \
                 shape (3,)"
                    .to_owned()
            )
        );
        assert_eq!(
            spec.check("int64", &[2, 3]),
            Err(
                "points: expected a float64 array of shape (N, 3), found an int64 array of \
                 shape (2, 3)"
                    .to_owned()
            )
        );
        assert!(
            spec.check("uint8", &[2, 3])
                .unwrap_err()
                .contains("found a uint8 array")
        );
        assert!(spec.check("float32", &[2, 3]).is_err());
        assert!(spec.check("float64", &[2, 4]).is_err());
        assert!(spec.check("float64", &[2, 3, 1]).is_err());
        assert_eq!(
            spec.not_an_array("list"),
            "points: expected a float64 numpy array of shape (N, 3), found list \
             (numpy.asarray(points, dtype=numpy.float64) makes one)"
        );
    }

    #[test]
    fn per_pixel_arrays_are_the_images_height_and_width() {
        let spec = ArraySpec::per_pixel("directions", 320, 240);
        assert_eq!(spec.check("float64", &[240, 320, 3]), Ok(()));
        assert_eq!(
            spec.check("float64", &[320, 240, 3]),
            Err(
                "directions: expected a float64 array of shape (240, 320, 3) (the scene's \
                 height, width, 3), found a float64 array of shape (320, 240, 3)"
                    .to_owned()
            )
        );
        assert!(spec.check("float64", &[240, 320]).is_err());
        assert!(spec.check("float64", &[]).is_err());
    }

    #[test]
    fn samples_run_from_one_to_the_scene_formats_limit() {
        assert_eq!(samples(1), Ok(1));
        assert_eq!(samples(i64::from(MAX_SAMPLES)), Ok(MAX_SAMPLES));
        for bad in [0, -1, i64::from(MAX_SAMPLES) + 1, i64::MAX, i64::MIN] {
            let error = samples(bad).unwrap_err();
            assert_eq!(
                error,
                format!(
                    "samples: expected a whole number of samples from 1 to {MAX_SAMPLES}, \
                     found {bad}"
                )
            );
        }
    }
}

//! A student's numbers, checked: each answer against the right camera, and the wrong ones
//! explained by the catalogue entry (or pair of entries) that reproduces every answer.
//!
//! A [`Checker`] takes the answers one at a time and holds no more than a few hundred
//! hypotheses, whatever the number of answers: each hypothesis is a set of the
//! catalogue's mistakes (one entry, or two made together) and stays alive while it
//! reproduces every answer seen. At the end, the smallest sets still alive that
//! reproduce the wrong answers are the explanation; entries that make the same numbers
//! for this camera are named together. When none is alive, what the wrong answers have
//! in common (a sign, a scale, a constant offset) is said instead.
//!
//! Directions are compared up to a positive factor unless asked otherwise (a student may
//! normalize them); every comparison is relative: `|found - expected| <= tolerance *
//! max(1, |expected|)`. Projections are judged against the right camera only: the
//! catalogue's entries are mistakes in making rays, not in projecting points.

use std::fmt;

use glam::{DVec2, DVec3};
use viewray_camera::{Camera, CameraSample, Mistake, Mistakes};
use viewray_output::number::round_trip;

use crate::answers::{Answer, AnswerError};

/// How answers are compared.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CheckOptions {
    /// The plain lines' and `row`/`col` keys' indices are the lecture's 1-based `i`, `j`.
    pub one_based: bool,
    /// The relative tolerance of every comparison.
    pub tolerance: f64,
    /// Directions must be equal, not only equal up to a positive factor.
    pub exact_direction: bool,
}

impl Default for CheckOptions {
    /// 0-based indices, a tolerance of `1e-6`, directions up to a positive factor.
    fn default() -> Self {
        CheckOptions {
            one_based: false,
            tolerance: 1e-6,
            exact_direction: false,
        }
    }
}

/// The right camera's value for an answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Expected {
    /// The frame `(e, u, v, w)`.
    Frame([DVec3; 4]),
    /// The 0-based pixel, its image-plane point `(u, v)` (for the planar families) and
    /// its ray (none outside a fisheye's circle).
    Ray {
        /// The 0-based `(row, col)`.
        pixel: (u32, u32),
        /// `(u, v)`, for the planar families.
        uv: Option<DVec2>,
        /// `(origin, direction)`.
        ray: Option<(DVec3, DVec3)>,
    },
    /// Where the point appears, if it is seen.
    Project(Option<DVec2>),
}

/// One answer judged.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Judged {
    /// The answer's line in the file (from 1).
    pub line: u64,
    /// The answer as read.
    pub found: Answer,
    /// The right camera's value.
    pub expected: Expected,
    /// Whether the answer is right.
    pub right: bool,
}

/// The catalogue's explanation of a student's wrong answers.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Diagnosis {
    /// The sets of mistakes that reproduce every answer, smallest first; several when
    /// they make the same numbers for this camera (any of them is the student's).
    pub alternatives: Vec<Mistakes>,
}

/// The answers' index convention, when the other one would make them right.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum IndexHint {
    /// The answers are right with 1-based indices: use `--one-based`.
    OneBased,
    /// The answers are right with 0-based indices: leave out `--one-based`.
    ZeroBased,
}

/// What a whole answers file came to.
#[derive(Clone, Debug, PartialEq)]
pub struct Report {
    /// How many answers were read.
    pub answers: u64,
    /// How many are right.
    pub right: u64,
    /// How many are wrong.
    pub wrong: u64,
    /// The index convention the answers use, when it is not the one asked for.
    pub index_hint: Option<IndexHint>,
    /// The catalogue's explanation of the wrong answers, if an entry reproduces them.
    pub diagnosis: Option<Diagnosis>,
    /// What the wrong answers have in common, when the catalogue does not explain them.
    pub pattern: Option<String>,
}

impl Report {
    /// Whether every answer is right.
    pub fn passed(&self) -> bool {
        self.wrong == 0
    }
}

/// A set of mistakes and an index convention, alive while it reproduces every answer.
#[derive(Clone, Debug)]
struct Hypothesis {
    mistakes: Mistakes,
    camera: Camera,
    /// The index convention is the other one than asked for.
    other_indices: bool,
    alive: bool,
}

/// Checks a student's answers against a camera, one at a time (see the module's doc).
#[derive(Clone, Debug)]
pub struct Checker {
    camera: Camera,
    options: CheckOptions,
    hypotheses: Vec<Hypothesis>,
    answers: u64,
    right: u64,
    /// Wrong answers that a catalogue entry could reproduce (frames and rays).
    wrong_explainable: u64,
    pattern: Pattern,
}

impl Checker {
    /// A checker of answers about `camera` (the scene's camera: its frame, rays and
    /// projections), with every single catalogue entry that fits it and every pair.
    pub fn new(camera: &Camera, options: CheckOptions) -> Checker {
        let fitting: Vec<Mistake> = Mistake::ALL
            .into_iter()
            .filter(|m| camera.with_mistakes(Mistakes::one(*m)).is_ok())
            .collect();
        let mut sets = vec![Mistakes::NONE];
        sets.extend(fitting.iter().map(|&m| Mistakes::one(m)));
        for (k, &a) in fitting.iter().enumerate() {
            for &b in &fitting[k + 1..] {
                sets.push(Mistakes::one(a).with(b));
            }
        }
        let mut hypotheses: Vec<Hypothesis> = sets
            .into_iter()
            .filter_map(|mistakes| {
                Some(Hypothesis {
                    mistakes,
                    camera: camera.with_mistakes(mistakes).ok()?,
                    other_indices: false,
                    alive: true,
                })
            })
            .collect();
        // The right camera with the other index convention (for the hint); the right
        // camera itself is judged apart.
        hypotheses[0].other_indices = true;
        Checker {
            camera: *camera,
            options,
            hypotheses,
            answers: 0,
            right: 0,
            wrong_explainable: 0,
            pattern: Pattern::default(),
        }
    }

    /// Judges `answer`, read from line `line`.
    ///
    /// # Errors
    /// For a ray of a pixel outside the image: the line, the pixel and the image's
    /// ranges (with a hint when the indices look like the other convention's).
    pub fn check(&mut self, line: u64, answer: &Answer) -> Result<Judged, AnswerError> {
        let expected = self.expected(line, answer)?;
        let right = matches_with(self.options, answer, &expected);
        self.answers += 1;
        if right {
            self.right += 1;
        } else {
            if !matches!(answer, Answer::Project { .. }) {
                self.wrong_explainable += 1;
            }
            self.pattern.add(answer, &expected);
        }
        let options = self.options;
        for hypothesis in self.hypotheses.iter_mut().filter(|h| h.alive) {
            if matches!(answer, Answer::Project { .. }) && !hypothesis.mistakes.is_empty() {
                continue;
            }
            hypothesis.alive = expected_for(
                &hypothesis.camera,
                answer,
                options,
                hypothesis.other_indices,
            )
            .is_some_and(|theirs| matches_with(options, answer, &theirs));
        }
        Ok(Judged {
            line,
            found: *answer,
            expected,
            right,
        })
    }

    /// What the answers came to.
    pub fn finish(self) -> Report {
        let wrong = self.answers - self.right;
        let index_hint =
            (wrong > 0 && self.hypotheses[0].alive).then_some(if self.options.one_based {
                IndexHint::ZeroBased
            } else {
                IndexHint::OneBased
            });
        let diagnosis = if wrong == 0 || index_hint.is_some() || self.wrong_explainable < wrong {
            None
        } else {
            let alive: Vec<Mistakes> = self
                .hypotheses
                .iter()
                .filter(|h| h.alive && !h.other_indices && !h.mistakes.is_empty())
                .map(|h| h.mistakes)
                .collect();
            let smallest = alive.iter().map(|m| m.len()).min();
            smallest.map(|n| Diagnosis {
                alternatives: alive.into_iter().filter(|m| m.len() == n).collect(),
            })
        };
        let pattern = if wrong > 0 && diagnosis.is_none() && index_hint.is_none() {
            self.pattern.describe()
        } else {
            None
        };
        Report {
            answers: self.answers,
            right: self.right,
            wrong,
            index_hint,
            diagnosis,
            pattern,
        }
    }

    /// The right camera's value for `answer`.
    fn expected(&self, line: u64, answer: &Answer) -> Result<Expected, AnswerError> {
        let size = (self.camera.width(), self.camera.height());
        if let Some(Err(())) = answer_pixel(answer, self.options, false, size) {
            let Answer::Ray { row, col, .. } = *answer else {
                unreachable!("only rays name pixels")
            };
            let one_based = self.one_based(answer);
            let hint = match answer_pixel(answer, self.options, true, size) {
                Some(Ok(_)) if one_based => " (your rows look 0-based: leave out --one-based)",
                Some(Ok(_)) => " (your rows look 1-based: use --one-based)",
                _ => "",
            };
            let (first, [row_name, col_name]) = if one_based {
                (1, ["i", "j"])
            } else {
                (0, ["row", "col"])
            };
            let (w, h) = (i64::from(size.0), i64::from(size.1));
            return Err(AnswerError {
                line,
                message: format!(
                    "pixel {row},{col} is outside the {w} x {h} image: expected {row_name} in \
                     {first}..={} and {col_name} in {first}..={}{hint}",
                    h - 1 + first,
                    w - 1 + first
                ),
            });
        }
        Ok(expected_for(&self.camera, answer, self.options, false)
            .expect("a pixel inside the image has an expected value"))
    }

    fn one_based(&self, answer: &Answer) -> bool {
        matches!(
            answer,
            Answer::Ray {
                one_based: true,
                ..
            }
        ) || self.options.one_based
    }
}

/// The 0-based pixel of a ray answer (`None` for the other answers), or `Err` when it is
/// outside the image; `other` reads the indices in the other convention than asked.
fn answer_pixel(
    answer: &Answer,
    options: CheckOptions,
    other: bool,
    (width, height): (u32, u32),
) -> Option<Result<(u32, u32), ()>> {
    let Answer::Ray {
        row,
        col,
        one_based,
        ..
    } = *answer
    else {
        return None;
    };
    let one_based = (one_based || options.one_based) != other;
    let base = i64::from(one_based);
    let index = |i: i64, size: u32| u32::try_from(i - base).ok().filter(|&i| i < size);
    Some(match (index(row, height), index(col, width)) {
        (Some(r), Some(c)) => Ok((r, c)),
        _ => Err(()),
    })
}

/// `camera`'s value for `answer` (`None` for a ray of a pixel outside the image).
fn expected_for(
    camera: &Camera,
    answer: &Answer,
    options: CheckOptions,
    other: bool,
) -> Option<Expected> {
    let size = (camera.width(), camera.height());
    Some(match answer {
        Answer::Frame { .. } => {
            let f = camera.frame();
            Expected::Frame([f.e(), f.u(), f.v(), f.w()])
        }
        Answer::Ray { .. } => {
            let (row, col) = answer_pixel(answer, options, other, size)?.ok()?;
            let uv = camera.image_plane_point(row, col, CameraSample::CENTER.p_film);
            let ray = camera
                .generate_ray(row, col, CameraSample::CENTER)
                .map(|r| (r.origin, r.direction));
            Expected::Ray {
                pixel: (row, col),
                uv,
                ray,
            }
        }
        Answer::Project { point, .. } => Expected::Project(camera.project(*point)),
    })
}

/// Whether `found` is `expected` within the tolerance, relative to the expected value.
fn close(found: DVec3, expected: DVec3, tolerance: f64) -> bool {
    (found - expected).length() <= tolerance * expected.length().max(1.0)
}

fn close2(found: DVec2, expected: DVec2, tolerance: f64) -> bool {
    (found - expected).length() <= tolerance * expected.length().max(1.0)
}

/// Whether a direction is the expected one (up to a positive factor unless exact).
fn same_direction(found: DVec3, expected: DVec3, options: CheckOptions) -> bool {
    if options.exact_direction {
        return close(found, expected, options.tolerance);
    }
    match (found.try_normalize(), expected.try_normalize()) {
        (Some(f), Some(e)) => close(f, e, options.tolerance),
        (None, None) => true,
        _ => false,
    }
}

fn matches_with(options: CheckOptions, answer: &Answer, expected: &Expected) -> bool {
    let tolerance = options.tolerance;
    match (answer, expected) {
        (Answer::Frame { e, u, v, w }, Expected::Frame(right)) => [*e, *u, *v, *w]
            .iter()
            .zip(right)
            .all(|(f, r)| close(*f, *r, tolerance)),
        (
            Answer::Ray {
                uv,
                origin,
                direction,
                ..
            },
            Expected::Ray {
                uv: right_uv,
                ray: Some((right_origin, right_direction)),
                ..
            },
        ) => {
            let uv_right = match (uv, right_uv) {
                (Some(found), Some(right)) => {
                    close2(DVec2::new(found.0, found.1), *right, tolerance)
                }
                _ => true,
            };
            uv_right
                && close(*origin, *right_origin, tolerance)
                && same_direction(*direction, *right_direction, options)
        }
        (Answer::Project { xy, .. }, Expected::Project(right)) => match (xy, right) {
            (None, None) => true,
            (Some(found), Some(right)) => close2(DVec2::new(found.0, found.1), *right, tolerance),
            _ => false,
        },
        _ => false,
    }
}

/// What the wrong rays have in common, kept as the first wrong ray's relations and
/// checked against every later one (constant memory).
#[derive(Clone, Debug, Default)]
struct Pattern {
    /// The first wrong ray's `found - expected` direction, and whether every later one
    /// has the same difference.
    offset: Option<(DVec3, bool)>,
    /// The first wrong ray's components whose sign is flipped (and nothing else), and
    /// whether every later one flips the same.
    signs: Option<([bool; 3], bool)>,
    /// The first wrong ray's `found = k expected` factor, and whether it holds for all.
    scale: Option<(f64, bool)>,
    /// The first wrong ray's origin offset, and whether every later one is the same.
    origin: Option<(DVec3, bool)>,
    rays: u64,
}

impl Pattern {
    fn add(&mut self, answer: &Answer, expected: &Expected) {
        let (
            Answer::Ray {
                origin, direction, ..
            },
            Expected::Ray {
                ray: Some((right_origin, right_direction)),
                ..
            },
        ) = (answer, expected)
        else {
            return;
        };
        self.rays += 1;
        let tolerance = 1e-6;
        let offset = *direction - *right_direction;
        track(&mut self.offset, offset, |a, b| close(*a, *b, tolerance));
        let flips = std::array::from_fn(|k| {
            let (f, e) = (direction[k], right_direction[k]);
            e.abs() > 1e-12 && (f + e).abs() <= tolerance * e.abs().max(1.0)
        });
        let rest_same = (0..3).all(|k| {
            flips[k]
                || (direction[k] - right_direction[k]).abs()
                    <= tolerance * right_direction[k].abs().max(1.0)
        });
        if rest_same && flips.iter().any(|&f| f) {
            track(&mut self.signs, flips, |a, b| a == b);
        } else {
            self.signs = Some(([false; 3], false));
        }
        let k = direction.dot(*right_direction) / right_direction.length_squared().max(1e-300);
        if close(*direction, k * *right_direction, tolerance) {
            track(&mut self.scale, k, |a, b| {
                (a - b).abs() <= tolerance * b.abs().max(1.0)
            });
        } else {
            self.scale = Some((0.0, false));
        }
        track(&mut self.origin, *origin - *right_origin, |a, b| {
            close(*a, *b, tolerance)
        });
    }

    fn describe(&self) -> Option<String> {
        if self.rays == 0 {
            return None;
        }
        let vector = |v: DVec3| {
            format!(
                "({}, {}, {})",
                round_trip(v.x),
                round_trip(v.y),
                round_trip(v.z)
            )
        };
        let all = if self.rays == 1 {
            "the wrong ray's"
        } else {
            "every wrong ray's"
        };
        if let Some((flips, true)) = self.signs {
            let names: Vec<&str> = ["x", "y", "z"]
                .into_iter()
                .zip(flips)
                .filter_map(|(n, f)| f.then_some(n))
                .collect();
            return Some(format!(
                "{all} direction has the wrong sign in {}",
                names.join(" and ")
            ));
        }
        if let Some((k, true)) = self.scale
            && k != 0.0
        {
            return Some(format!(
                "{all} direction is {} times the right one",
                round_trip(k)
            ));
        }
        if let Some((origin, true)) = self.origin
            && origin.length() > 1e-9
        {
            return Some(format!(
                "{all} origin is off by the same {}: check e",
                vector(origin)
            ));
        }
        if let Some((offset, true)) = self.offset {
            return Some(format!(
                "{all} direction is off by the same {} from the right one",
                vector(offset)
            ));
        }
        Some("the wrong rays have nothing in common that viewray can name".to_owned())
    }
}

/// Keeps the first value, and whether every later one is the same as it.
fn track<T: Copy>(slot: &mut Option<(T, bool)>, value: T, same: impl Fn(&T, &T) -> bool) {
    match slot {
        None => *slot = Some((value, true)),
        Some((first, all)) => *all = *all && same(&value, first),
    }
}

impl fmt::Display for Judged {
    /// `line 4: ray 0 1: right`, or `wrong` with what was found and what was expected.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let vector = |v: DVec3| {
            format!(
                "({}, {}, {})",
                round_trip(v.x),
                round_trip(v.y),
                round_trip(v.z)
            )
        };
        let pair = |(x, y): (f64, f64)| format!("({}, {})", round_trip(x), round_trip(y));
        let what = match self.found {
            Answer::Frame { .. } => "frame".to_owned(),
            Answer::Ray { row, col, .. } => format!("ray {row} {col}"),
            Answer::Project { point, .. } => format!("project {}", vector(point)),
        };
        write!(f, "line {}: {what}: ", self.line)?;
        if self.right {
            return f.write_str("right");
        }
        f.write_str("wrong")?;
        match (self.found, self.expected) {
            (Answer::Frame { e, u, v, w }, Expected::Frame(right)) => {
                for (name, (found, right)) in ["e", "u", "v", "w"]
                    .into_iter()
                    .zip([e, u, v, w].into_iter().zip(right))
                {
                    if (found - right).length() > 0.0 {
                        write!(f, "; {name} {} (expected {})", vector(found), vector(right))?;
                    }
                }
                Ok(())
            }
            (
                Answer::Ray {
                    uv,
                    origin,
                    direction,
                    ..
                },
                Expected::Ray {
                    uv: right_uv, ray, ..
                },
            ) => {
                let Some((right_origin, right_direction)) = ray else {
                    return f.write_str(": this pixel has no ray (outside the image circle)");
                };
                let options = CheckOptions::default();
                let mut parts = Vec::new();
                if let (Some(found), Some(right)) = (uv, right_uv)
                    && !close2(DVec2::new(found.0, found.1), right, options.tolerance)
                {
                    parts.push(format!(
                        "(u, v) {}, expected {}",
                        pair(found),
                        pair((right.x, right.y))
                    ));
                }
                if !close(origin, right_origin, options.tolerance) {
                    parts.push(format!(
                        "origin {}, expected {}",
                        vector(origin),
                        vector(right_origin)
                    ));
                }
                if parts.is_empty() || !same_direction(direction, right_direction, options) {
                    parts.push(format!(
                        "direction {}, expected {}",
                        vector(direction),
                        vector(right_direction)
                    ));
                }
                write!(f, ": {}", parts.join("; "))
            }
            (Answer::Project { xy, .. }, Expected::Project(right)) => {
                let show = |xy: Option<(f64, f64)>| xy.map_or("not seen".to_owned(), pair);
                write!(
                    f,
                    ": {}, expected {}",
                    show(xy),
                    show(right.map(|r| (r.x, r.y)))
                )
            }
            _ => Ok(()),
        }
    }
}

impl fmt::Display for Report {
    /// The summary, then the explanation in the lecture's words with the formula to fix,
    /// or what the wrong answers have in common.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "{} answer{}: {} right, {} wrong",
            self.answers,
            if self.answers == 1 { "" } else { "s" },
            self.right,
            self.wrong
        )?;
        if let Some(hint) = self.index_hint {
            f.write_str(match hint {
                IndexHint::OneBased => {
                    "\nyour rows and columns look 1-based (the lecture's i, j): use --one-based"
                }
                IndexHint::ZeroBased => {
                    "\nyour rows and columns look 0-based: leave out --one-based"
                }
            })?;
        }
        if let Some(diagnosis) = &self.diagnosis {
            let them = if self.wrong == 1 { "it" } else { "them" };
            let names: Vec<String> = diagnosis
                .alternatives
                .iter()
                .map(ToString::to_string)
                .collect();
            write!(f, "\nthe catalogue explains {them}: {}", names.join(" or "))?;
            if let [set] = diagnosis.alternatives.as_slice()
                && set.len() == 1
            {
                let mistake = set.iter().next().expect("a set of one");
                write!(f, " ({})", mistake.entry().summary)?;
            } else if diagnosis.alternatives.len() > 1 {
                f.write_str(" (the same numbers for this camera)")?;
            }
            let mut shown = Mistakes::NONE;
            for mistake in diagnosis.alternatives.iter().flat_map(|set| set.iter()) {
                if shown.contains(mistake) {
                    continue;
                }
                shown = shown.with(mistake);
                let entry = mistake.entry();
                if diagnosis.alternatives.len() > 1 || diagnosis.alternatives[0].len() > 1 {
                    write!(f, "\n  {}: {}", entry.id, entry.summary)?;
                }
                write!(f, "\n    you wrote:        {}", entry.mistaken)?;
                write!(f, "\n    the lecture says: {}", entry.fix)?;
                write!(f, "\n    in the picture:   {}", entry.picture)?;
            }
        } else if let Some(pattern) = &self.pattern {
            write!(
                f,
                "\nno entry of the catalogue explains {}; {pattern}",
                if self.wrong == 1 { "it" } else { "them" }
            )?;
        }
        Ok(())
    }
}

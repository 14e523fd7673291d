//! What a student's program prints for `viewray check`: frames, rays and projections, in
//! each spelling the command accepts (viewray's own JSON lines, plain whitespace lines,
//! comma-separated lines) and with the variations students' programs have (1-based
//! indices, normalized directions, CRLF line ends, extra spaces, `#` comments, rounded
//! or exponent numbers).

use super::camera::{CameraSpec, Frame, image_plane, project, ray};
use super::mistakes::Mistake;
use super::vec3::Vec3;

/// One printed answer.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Answer {
    /// The camera frame, `frame ex ey ez ux uy uz vx vy vz wx wy wz`.
    Frame(Frame),
    /// A pixel's viewing ray (0-based `row`, `col`), `ray ROW COL ox oy oz dx dy dz`.
    Ray {
        /// The pixel's row, 0-based.
        row: u32,
        /// The pixel's column, 0-based.
        col: u32,
        /// The ray's origin.
        origin: Vec3,
        /// The ray's direction.
        direction: Vec3,
    },
    /// Where a point appears, `project px py pz x y`.
    Project {
        /// The point.
        point: Vec3,
        /// Its continuous image coordinates, `None` where it is not seen.
        image: Option<(f64, f64)>,
        /// The pixel `(row, col)` holding it, 0-based, `None` outside the image.
        pixel: Option<(u32, u32)>,
    },
}

impl Answer {
    /// The frame a student with `mistakes` prints.
    pub(crate) fn frame(camera: &CameraSpec, mistakes: &[Mistake]) -> Self {
        Answer::Frame(super::camera::frame(camera, mistakes))
    }

    /// The centre ray of pixel `(row, col)` a student with `mistakes` prints, in an image
    /// of `size = (W, H)`.
    pub(crate) fn ray(
        camera: &CameraSpec,
        mistakes: &[Mistake],
        size: (u32, u32),
        (row, col): (u32, u32),
    ) -> Self {
        let r = ray(camera, mistakes, size, (row, col), (0.5, 0.5));
        Answer::Ray {
            row,
            col,
            origin: r.origin,
            direction: r.direction,
        }
    }

    /// Where `point` appears in the correct camera's image of `size = (W, H)`.
    pub(crate) fn project(camera: &CameraSpec, size: (u32, u32), point: Vec3) -> Self {
        let image = project(camera, size, point);
        let pixel = image.and_then(|(x, y)| {
            let inside =
                (0.0..f64::from(size.0)).contains(&x) && (0.0..f64::from(size.1)).contains(&y);
            inside.then(|| (y.floor() as u32, x.floor() as u32))
        });
        Answer::Project {
            point,
            image,
            pixel,
        }
    }
}

/// The image-plane point `(u, v)` a student prints beside a ray (not part of an answer
/// line; for tests that look at it).
pub(crate) fn uv(
    camera: &CameraSpec,
    mistakes: &[Mistake],
    size: (u32, u32),
    pixel: (u32, u32),
) -> (f64, f64) {
    image_plane(camera, mistakes, size, pixel, (0.5, 0.5))
}

/// How the lines are spelled.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Syntax {
    /// viewray's own JSON lines: the keys of `frame`, `rays` and `project`.
    Json,
    /// `ray ROW COL ox oy oz dx dy dz`, fields apart by whitespace.
    Words,
    /// The same fields apart by commas.
    Csv,
}

/// How a number is printed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Number {
    /// The shortest text that reads back as the same f64 (JSON: `1.0`; words: `1`).
    Shortest,
    /// This many digits after the point, as C's `%.Nf`.
    Fixed(usize),
    /// Exponent notation, as Rust's `{:e}` (`2.5e-1`).
    Exponent,
}

/// The variations of a student's printout.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) struct AnswerStyle {
    /// The spelling.
    pub(crate) syntax: Syntax,
    /// Pixels as the lecture's 1-based `i, j` (JSON keys `i`, `j`).
    pub(crate) one_based: bool,
    /// Ray directions divided by their length.
    pub(crate) normalized: bool,
    /// Lines end with `\r\n`.
    pub(crate) crlf: bool,
    /// Spaces (and, in words, tabs) before, between and after the fields.
    pub(crate) extra_spaces: bool,
    /// A `#` comment line at the top and before each kind of answer.
    pub(crate) comments: bool,
    /// How numbers are printed.
    pub(crate) number: Number,
}

impl Default for AnswerStyle {
    /// viewray's JSON lines, 0-based, as computed, `\n`, no extra spaces or comments.
    fn default() -> Self {
        Self {
            syntax: Syntax::Json,
            one_based: false,
            normalized: false,
            crlf: false,
            extra_spaces: false,
            comments: false,
            number: Number::Shortest,
        }
    }
}

/// The printout of `answers` in `style`, one line each (and comments if asked).
pub(crate) fn write_answers(answers: &[Answer], style: &AnswerStyle) -> String {
    let end = if style.crlf { "\r\n" } else { "\n" };
    let mut text = String::new();
    if style.comments {
        text.push_str("# the camera homework's answers, printed by my ray tracer");
        text.push_str(end);
    }
    let mut last_kind = None;
    for answer in answers {
        let kind = std::mem::discriminant(answer);
        if style.comments && last_kind != Some(kind) {
            text.push_str(match answer {
                Answer::Frame(_) => "# the frame e, u, v, w",
                Answer::Ray { .. } => "#   viewing rays",
                Answer::Project { .. } => "# where points appear",
            });
            text.push_str(end);
        }
        last_kind = Some(kind);
        text.push_str(&line(answer, style));
        text.push_str(end);
    }
    text
}

/// One answer's line, without its end.
fn line(answer: &Answer, style: &AnswerStyle) -> String {
    let num = |x: f64| number(x, style);
    let (first, second) = if style.one_based {
        ("i", "j")
    } else {
        ("row", "col")
    };
    let index = |k: u32| if style.one_based { k + 1 } else { k };
    match style.syntax {
        Syntax::Json => {
            let (colon, comma) = if style.extra_spaces {
                (": ", ", ")
            } else {
                (":", ",")
            };
            let array = |a: Vec3| format!("[{}]", a.to_array().map(num).join(comma));
            let fields: Vec<(&str, String)> = match *answer {
                Answer::Frame(f) => vec![
                    ("e", array(f.e)),
                    ("u", array(f.u)),
                    ("v", array(f.v)),
                    ("w", array(f.w)),
                ],
                Answer::Ray {
                    row,
                    col,
                    origin,
                    direction,
                } => vec![
                    (first, index(row).to_string()),
                    (second, index(col).to_string()),
                    ("origin", array(origin)),
                    ("direction", array(direction_of(direction, style))),
                ],
                Answer::Project {
                    point,
                    image,
                    pixel,
                } => {
                    let or_null = |x: Option<String>| x.unwrap_or_else(|| "null".to_owned());
                    vec![
                        ("point", array(point)),
                        ("x", or_null(image.map(|(x, _)| num(x)))),
                        ("y", or_null(image.map(|(_, y)| num(y)))),
                        (first, or_null(pixel.map(|(r, _)| index(r).to_string()))),
                        (second, or_null(pixel.map(|(_, c)| index(c).to_string()))),
                    ]
                }
            };
            let body: Vec<String> = fields
                .into_iter()
                .map(|(key, value)| format!("\"{key}\"{colon}{value}"))
                .collect();
            let lead = if style.extra_spaces { "  " } else { "" };
            format!("{lead}{{{}}}", body.join(comma))
        }
        Syntax::Words | Syntax::Csv => {
            let mut fields: Vec<String> = Vec::new();
            let push_vec = |fields: &mut Vec<String>, a: Vec3| {
                fields.extend(a.to_array().map(num));
            };
            match *answer {
                Answer::Frame(f) => {
                    fields.push("frame".to_owned());
                    for a in [f.e, f.u, f.v, f.w] {
                        push_vec(&mut fields, a);
                    }
                }
                Answer::Ray {
                    row,
                    col,
                    origin,
                    direction,
                } => {
                    fields.push("ray".to_owned());
                    fields.push(index(row).to_string());
                    fields.push(index(col).to_string());
                    push_vec(&mut fields, origin);
                    push_vec(&mut fields, direction_of(direction, style));
                }
                Answer::Project { point, image, .. } => {
                    fields.push("project".to_owned());
                    push_vec(&mut fields, point);
                    match image {
                        Some((x, y)) => fields.extend([num(x), num(y)]),
                        None => fields.extend(["null".to_owned(), "null".to_owned()]),
                    }
                }
            }
            let separator = match (style.syntax, style.extra_spaces) {
                (Syntax::Csv, false) => ",",
                (Syntax::Csv, true) => ", ",
                (_, false) => " ",
                (_, true) => " \t  ",
            };
            let joined = fields.join(separator);
            if style.extra_spaces {
                format!("   {joined}  ")
            } else {
                joined
            }
        }
    }
}

fn direction_of(direction: Vec3, style: &AnswerStyle) -> Vec3 {
    if style.normalized {
        direction.normalized()
    } else {
        direction
    }
}

fn number(x: f64, style: &AnswerStyle) -> String {
    match style.number {
        Number::Shortest if style.syntax == Syntax::Json => format!("{x:?}"),
        Number::Shortest => format!("{x}"),
        Number::Fixed(digits) => format!("{x:.digits$}"),
        Number::Exponent => format!("{x:e}"),
    }
}

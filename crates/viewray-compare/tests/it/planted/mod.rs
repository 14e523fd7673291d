//! Planted camera mistakes: the test matrix of the instructor's diagnoses.
//!
//! Each [`Case`] is a reference scene (the instructor's), a student's version of it with
//! one planted mistake (or none), an image size, the student's samples per pixel, and the
//! exact diagnosis each must give: in pixels without the scene, in the lecture's terms
//! with it. [`Case::render`] renders both with viewray itself, in-process;
//! [`Case::reference_scene`] and [`Case::student_scene`] give the scene files' text, so a
//! test of the `viewray` command can write them beside the images (`--scene`).
//!
//! Shared by `tests/it/matrix.rs` and `benches/judge.rs` of viewray-compare, and meant for the
//! `viewray` command's tests as well (include it there with
//! `#[path = "../../../viewray-compare/tests/it/planted/mod.rs"] mod planted;`): one table of
//! mistakes for `viewray compare` and `viewray grade`.
//!
//! The expected moves, scales and angles are computed here from the lecture's formulas,
//! never from the estimator: a lens shift (sx, sy) moves the picture by sx W / vw pixels
//! right and sy H / vh pixels up when it is left out; the principal point sits at
//! x = W (1/2 - sx/vw), y = H (1/2 + sy/vh); a distance d k times too long (or a viewport
//! k times too small) shows the picture k times larger about the principal point (the
//! image centre); rolling up by a degrees about the view direction turns the picture a
//! degrees counterclockwise.

#![allow(dead_code, unreachable_pub)]

use std::fmt::Write as _;
use std::path::{Path, PathBuf};

use image::RgbaImage;
use viewray_render::RenderSettings;
use viewray_scene::{LoadOptions, SceneLoader};

/// The samples per pixel of every reference render.
pub const REFERENCE_SAMPLES: u32 = 16;

/// A reference scene the mistakes are planted in.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Base {
    /// A lit ground grid with two boxes, viewport 1.2 x 0.9 with a lens shift of (0, 0.2):
    /// the scene of the issue that asked for these diagnoses (native 192 x 144).
    Boxes,
    /// `fixtures/scenes/perspective_general.ron`: no shift (native 240 x 180).
    General,
    /// `perspective_general.ron` with a shift of (0, 0.17).
    GeneralShifted,
    /// `fixtures/scenes/distortion_shifted.ron`: a tower seen through a lens shifted up
    /// by 0.4352 (native 180 x 240, portrait).
    Tower,
    /// `fixtures/scenes/orthographic.ron`: a parallel projection 5 units high.
    Orthographic,
}

/// The camera of a base scene, as far as the mistakes need it.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Lens {
    Perspective {
        distance: f64,
        viewport: (f64, f64),
        shift: (f64, f64),
    },
    Orthographic {
        height: f64,
    },
}

const BOXES: &str = r#"// A lit ground grid with two boxes, seen through a lens shifted up.
(
    image: (width: 192, height: 144, samples: 16),
    camera: (
        eye: (0.0, 1.5, 6.0),
        look_at: (0.0, 1.0, 0.0),
        up: (0.0, 1.0, 0.0),
        projection: Perspective(distance: 1.0, viewport: (1.2, 0.9), shift: (0.0, 0.2)),
    ),
    background: (0.55, 0.70, 0.90),
    shading: Lit,
    materials: {
        "ground": (color: (0.62, 0.62, 0.60), grid: (spacing: 1.0, width: 0.03, color: (0.25, 0.25, 0.25))),
        "red": (color: (0.80, 0.12, 0.08), specular: 0.3, shininess: 40.0),
        "blue": (color: (0.10, 0.25, 0.80), specular: 0.3, shininess: 40.0),
    },
    lights: [
        Directional(direction: (-0.4, -1.0, -0.6), intensity: (0.85, 0.85, 0.80)),
        Ambient(intensity: (0.22, 0.23, 0.26)),
    ],
    objects: [
        Plane(point: (0.0, 0.0, 0.0), normal: (0.0, 1.0, 0.0), material: "ground"),
        Box(min: (-1.5, 0.0, -0.5), max: (-0.5, 2.0, 0.5), material: "red"),
        Box(min: (0.5, 0.0, -1.0), max: (1.5, 1.0, 0.0), material: "blue"),
    ],
)
"#;

/// The fixtures folder, from this crate's or the `viewray` crate's manifest folder.
pub fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

impl Base {
    /// A short name, for case names and file names.
    pub fn name(self) -> &'static str {
        match self {
            Base::Boxes => "boxes",
            Base::General => "general",
            Base::GeneralShifted => "general_shifted",
            Base::Tower => "tower",
            Base::Orthographic => "orthographic",
        }
    }

    fn fixture(self) -> Option<&'static str> {
        match self {
            Base::Boxes => None,
            Base::General | Base::GeneralShifted => Some("perspective_general.ron"),
            Base::Tower => Some("distortion_shifted.ron"),
            Base::Orthographic => Some("orthographic.ron"),
        }
    }

    fn lens(self) -> Lens {
        match self {
            Base::Boxes => Lens::Perspective {
                distance: 1.0,
                viewport: (1.2, 0.9),
                shift: (0.0, 0.2),
            },
            Base::General => Lens::Perspective {
                distance: 1.0,
                viewport: (0.8, 0.6),
                shift: (0.0, 0.0),
            },
            Base::GeneralShifted => Lens::Perspective {
                distance: 1.0,
                viewport: (0.8, 0.6),
                shift: (0.0, 0.17),
            },
            Base::Tower => Lens::Perspective {
                distance: 1.0,
                viewport: (0.675, 0.9),
                shift: (0.0, 0.4352),
            },
            Base::Orthographic => Lens::Orthographic { height: 5.0 },
        }
    }

    /// The eye and the view direction.
    fn pose(self) -> ([f64; 3], [f64; 3]) {
        match self {
            Base::Boxes => ([0.0, 1.5, 6.0], [0.0, -0.5, -6.0]),
            Base::General | Base::GeneralShifted | Base::Orthographic => {
                ([5.0, 3.5, 6.0], [-5.0, -2.7, -6.0])
            }
            Base::Tower => ([0.8, 1.2, 5.5], [-0.4, 0.0, -5.5]),
        }
    }

    /// An object line to remove (a missing object) and a material colour to change (a
    /// wrong colour), as they are spelled in the scene's text.
    fn object_and_colour(self) -> (&'static str, &'static str) {
        match self {
            Base::Boxes => (
                "Box(min: (0.5, 0.0, -1.0), max: (1.5, 1.0, 0.0), material: \"blue\"),",
                "\"blue\": (color: (0.10, 0.25, 0.80)",
            ),
            Base::General | Base::GeneralShifted | Base::Orthographic => (
                "Sphere(center: (2.2, 0.6, -0.5), radius: 0.6, material: \"ivory\"),",
                "\"ivory\": (color: (0.80, 0.75, 0.62)",
            ),
            Base::Tower => (
                "Box(min: (1.5, 0.0, -0.5), max: (2.5, 3.0, 0.5), material: \"tower\"),",
                "\"tower\": (color: (0.70, 0.68, 0.64)",
            ),
        }
    }

    /// The path the scene is parsed as (meshes are found relative to its folder).
    fn path(self) -> PathBuf {
        let scenes = fixtures().join("scenes");
        scenes.join(self.fixture().unwrap_or("planted_boxes.ron"))
    }

    /// The reference scene's text, with mesh paths made absolute so that it can be
    /// written anywhere.
    fn text(self) -> String {
        let text = match self.fixture() {
            None => BOXES.to_owned(),
            Some(file) => std::fs::read_to_string(self.path())
                .unwrap_or_else(|e| panic!("cannot read the fixture {file}: {e}")),
        };
        let meshes = fixtures().join("meshes");
        let text = text.replace("\"../meshes/", &format!("\"{}/", meshes.display()));
        let lens = self.lens();
        replace_line(&text, "projection:", &projection_line(lens))
    }

    /// The lens shift (sx, sy), zero for a parallel projection.
    pub fn shift(self) -> (f64, f64) {
        match self.lens() {
            Lens::Perspective { shift, .. } => shift,
            Lens::Orthographic { .. } => (0.0, 0.0),
        }
    }

    /// The viewport (vw, vh) at `size` (an orthographic height follows the aspect ratio).
    fn viewport(self, size: (u32, u32)) -> (f64, f64) {
        match self.lens() {
            Lens::Perspective { viewport, .. } => viewport,
            Lens::Orthographic { height } => {
                (height * f64::from(size.0) / f64::from(size.1), height)
            }
        }
    }

    /// How far the picture moves, in pixels (x right, y down), when the shift is left
    /// out: (sx W / vw, -sy H / vh).
    pub fn missing_shift_move(self, size: (u32, u32)) -> (f64, f64) {
        let (sx, sy) = self.shift();
        let (vw, vh) = self.viewport(size);
        (sx * f64::from(size.0) / vw, -sy * f64::from(size.1) / vh)
    }

    /// The principal point in pixels: x = W (1/2 - sx/vw), y = H (1/2 + sy/vh).
    pub fn principal_point(self, size: (u32, u32)) -> (f64, f64) {
        let (sx, sy) = self.shift();
        let (vw, vh) = self.viewport(size);
        (
            f64::from(size.0) * (0.5 - sx / vw),
            f64::from(size.1) * (0.5 + sy / vh),
        )
    }
}

fn projection_line(lens: Lens) -> String {
    match lens {
        Lens::Perspective {
            distance,
            viewport: (vw, vh),
            shift: (sx, sy),
        } => format!(
            "projection: Perspective(distance: {distance:?}, viewport: ({vw:?}, {vh:?}), \
             shift: ({sx:?}, {sy:?})),"
        ),
        Lens::Orthographic { height } => format!("projection: Orthographic(height: {height:?}),"),
    }
}

/// `text` with the line that starts (after its indent) with `prefix` replaced by
/// `replacement`, indented as it was.
fn replace_line(text: &str, prefix: &str, replacement: &str) -> String {
    let mut out = String::new();
    let mut found = false;
    for line in text.lines() {
        let trimmed = line.trim_start();
        if trimmed.starts_with(prefix) {
            let indent = &line[..line.len() - trimmed.len()];
            writeln!(out, "{indent}{replacement}").unwrap();
            found = true;
        } else {
            writeln!(out, "{line}").unwrap();
        }
    }
    assert!(found, "no line starts with {prefix:?}");
    out
}

/// `text` with `from` replaced by `to`, which must occur.
fn replace_once(text: &str, from: &str, to: &str) -> String {
    assert!(text.contains(from), "the scene has no {from:?}");
    text.replacen(from, to, 1)
}

/// The student's mistake.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Mistake {
    /// None: the render is right (only its samples per pixel differ).
    None,
    /// The shift's sign is flipped: (-sx, -sy).
    ShiftFlipped,
    /// The shift is left out.
    ShiftMissing,
    /// u = (j/W - 1/2) vw and v = -(i/H - 1/2) vh: the pixel corner, not its centre (the
    /// picture moves half a pixel left and up).
    PixelCorner,
    /// d k times too long: the picture k times larger about the principal point.
    Distance(f64),
    /// vw and vh k times too small: the picture k times larger about the image centre.
    Viewport(f64),
    /// The picture mirrored left-right and/or upside down (about its centre).
    Mirror {
        /// Mirrored left-right.
        left_right: bool,
        /// Upside down.
        upside_down: bool,
    },
    /// The up vector rolled by this many degrees about the view direction.
    Roll(f64),
    /// The shift changed so that the picture moves by (dx, dy) pixels (x right, y down).
    Move(f64, f64),
    /// Mirrored left-right, and the shift left out.
    MirrorAndShiftMissing,
    /// One object left out of the scene.
    MissingObject,
    /// One material's colour changed.
    WrongColour,
}

/// One entry of the matrix.
#[derive(Clone, Debug)]
pub struct Case {
    /// A unique name: base, mistake, size (a valid file stem).
    pub name: String,
    /// The reference scene.
    pub base: Base,
    /// The image size of both renders.
    pub size: (u32, u32),
    /// The student's samples per pixel.
    pub samples: u32,
    /// The planted mistake.
    pub mistake: Mistake,
    /// Whether the student's render must pass.
    pub passes: bool,
    /// The diagnosis without the scene, messages joined by "; " (empty: none).
    pub without_scene: String,
    /// The diagnosis with the reference's scene.
    pub with_scene: String,
}

impl Case {
    /// The reference scene's text (RON), at its native size.
    pub fn reference_scene(&self) -> String {
        self.base.text()
    }

    /// The student's scene's text: the reference with the mistake planted in the camera
    /// or the objects (a mirror is applied to the image, see [`Case::render`]).
    pub fn student_scene(&self) -> String {
        let base = self.base;
        let text = base.text();
        let lens = base.lens();
        let with_lens = |lens: Lens| replace_line(&text, "projection:", &projection_line(lens));
        let shifted = |change: &dyn Fn((f64, f64)) -> (f64, f64)| match lens {
            Lens::Perspective {
                distance,
                viewport,
                shift,
            } => with_lens(Lens::Perspective {
                distance,
                viewport,
                shift: change(shift),
            }),
            Lens::Orthographic { .. } => {
                panic!("{}: a parallel projection has no shift", self.name)
            }
        };
        let (w, h) = (f64::from(self.size.0), f64::from(self.size.1));
        let (vw, vh) = base.viewport(self.size);
        match self.mistake {
            Mistake::None | Mistake::Mirror { .. } => text,
            Mistake::ShiftFlipped => shifted(&|(sx, sy)| (-sx, -sy)),
            Mistake::ShiftMissing | Mistake::MirrorAndShiftMissing => shifted(&|_| (0.0, 0.0)),
            // u larger by vw / 2W, v smaller by vh / 2H.
            Mistake::PixelCorner => shifted(&|(sx, sy)| (sx + 0.5 * vw / w, sy - 0.5 * vh / h)),
            // A larger u shows what lay to the right (the picture moves left); a larger v
            // what lay above (the picture moves down).
            Mistake::Move(dx, dy) => shifted(&|(sx, sy)| (sx - dx * vw / w, sy + dy * vh / h)),
            Mistake::Distance(k) => match lens {
                Lens::Perspective {
                    distance,
                    viewport,
                    shift,
                } => with_lens(Lens::Perspective {
                    distance: distance * k,
                    viewport,
                    shift,
                }),
                Lens::Orthographic { .. } => {
                    panic!("{}: a parallel projection has no d", self.name)
                }
            },
            Mistake::Viewport(k) => match lens {
                Lens::Perspective {
                    distance,
                    viewport: (vw, vh),
                    shift,
                } => with_lens(Lens::Perspective {
                    distance,
                    viewport: (vw / k, vh / k),
                    shift,
                }),
                Lens::Orthographic { height } => {
                    with_lens(Lens::Orthographic { height: height / k })
                }
            },
            Mistake::Roll(degrees) => {
                let (_, view) = base.pose();
                let up = rolled_up(view, degrees);
                replace_line(
                    &text,
                    "up:",
                    &format!("up: ({:?}, {:?}, {:?}),", up[0], up[1], up[2]),
                )
            }
            Mistake::MissingObject => replace_once(&text, base.object_and_colour().0, ""),
            Mistake::WrongColour => replace_once(
                &text,
                base.object_and_colour().1,
                &format!(
                    "{}(color: (0.20, 0.55, 0.30)",
                    base.object_and_colour()
                        .1
                        .split("(color")
                        .next()
                        .expect("a material entry")
                ),
            ),
        }
    }

    /// Renders the reference ([`REFERENCE_SAMPLES`] per pixel) and the student's image
    /// (`samples` per pixel, the mistake planted) at `size`.
    pub fn render(&self) -> (RgbaImage, RgbaImage) {
        (self.render_reference(), self.render_student())
    }

    /// The reference render: the same for every case of one base and size.
    pub fn render_reference(&self) -> RgbaImage {
        render_text(
            &self.reference_scene(),
            self.base.path(),
            self.size,
            REFERENCE_SAMPLES,
        )
    }

    /// The student's render, the mistake planted (a mirror is applied to the image).
    pub fn render_student(&self) -> RgbaImage {
        let mut student = render_text(
            &self.student_scene(),
            self.base.path(),
            self.size,
            self.samples,
        );
        let (left_right, upside_down) = match self.mistake {
            Mistake::Mirror {
                left_right,
                upside_down,
            } => (left_right, upside_down),
            Mistake::MirrorAndShiftMissing => (true, false),
            _ => (false, false),
        };
        if left_right {
            image::imageops::flip_horizontal_in_place(&mut student);
        }
        if upside_down {
            image::imageops::flip_vertical_in_place(&mut student);
        }
        student
    }
}

/// Parses and renders a scene's text at `size` with `samples` per pixel.
pub fn render_text(text: &str, path: PathBuf, size: (u32, u32), samples: u32) -> RgbaImage {
    let options = LoadOptions {
        size: Some(size),
        samples: Some(samples),
    };
    let scene = SceneLoader::text(text, &path)
        .options(options)
        .load()
        .map(|loaded| loaded.scene)
        .unwrap_or_else(|e| panic!("a planted scene does not parse: {e}"));
    let rendered = viewray_render::render(&scene, &RenderSettings::default(), |_, _| {})
        .expect("the planted scene renders");
    let rgb = image::RgbImage::from_raw(size.0, size.1, rendered.image.to_rgb8())
        .expect("the render has the requested size");
    image::DynamicImage::ImageRgb8(rgb).to_rgba8()
}

/// The up vector (0, 1, 0) rotated by `degrees` about `view` (right-handed: about the
/// direction the camera looks, so the camera rolls clockwise as the viewer sees it and
/// the picture turns counterclockwise).
fn rolled_up(view: [f64; 3], degrees: f64) -> [f64; 3] {
    let length = view.iter().map(|c| c * c).sum::<f64>().sqrt();
    let k = view.map(|c| c / length);
    let up = [0.0, 1.0, 0.0];
    let (sin, cos) = degrees.to_radians().sin_cos();
    let cross = [
        k[1] * up[2] - k[2] * up[1],
        k[2] * up[0] - k[0] * up[2],
        k[0] * up[1] - k[1] * up[0],
    ];
    let dot: f64 = k.iter().zip(up).map(|(a, b)| a * b).sum();
    std::array::from_fn(|i| up[i] * cos + cross[i] * sin + k[i] * dot * (1.0 - cos))
}

/// A number of pixels or degrees as the diagnoses print it: whole from 2 up, else with one
/// decimal.
fn amount(value: f64) -> String {
    if value.abs() >= 2.0 {
        format!("{:.0}", value.abs())
    } else {
        format!("{:.1}", value.abs())
    }
}

/// A move in the diagnoses' words: `64 px up`, `25 px down and 40 px left`.
fn move_words(dx: f64, dy: f64) -> String {
    let mut parts = Vec::new();
    if dy.abs() > 0.25 {
        let way = if dy < 0.0 { "up" } else { "down" };
        parts.push(format!("{} px {way}", amount(dy)));
    }
    if dx.abs() > 0.25 {
        let way = if dx < 0.0 { "left" } else { "right" };
        parts.push(format!("{} px {way}", amount(dx)));
    }
    parts.join(" and ")
}

/// A scene parameter as the diagnoses print it.
fn parameter(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

const UNEXPLAINED_LOCAL: &str =
    "no camera transform explains the difference: an object or a colour differs";
const UNEXPLAINED_VIEW: &str = "no camera transform explains the difference: the whole view \
                                differs (check e, the view direction and the shift)";
const PIXEL_CORNER: &str =
    "shifted -0.5 px in x and y: check the pixel-centre offset (j - 1/2, i - 1/2)";

impl Case {
    /// A case with its expected diagnoses worked out from the lecture's formulas.
    pub fn new(base: Base, size: (u32, u32), samples: u32, mistake: Mistake) -> Self {
        let (w, h) = (f64::from(size.0), f64::from(size.1));
        let centre = (w / 2.0, h / 2.0);
        let pp = base.principal_point(size);
        let off_centre = (pp.0 - centre.0).abs() > 0.5 || (pp.1 - centre.1).abs() > 0.5;
        let about = |point: (f64, f64), named: bool| {
            if named {
                format!(" about ({:.0}, {:.0})", point.0, point.1)
            } else {
                String::new()
            }
        };
        let (sx, sy) = base.shift();
        let scene_shift = format!(
            "the scene's shift (sx, sy) is ({}, {})",
            parameter(sx),
            parameter(sy)
        );
        let parallel = matches!(base.lens(), Lens::Orthographic { .. });
        let field_of_view = |k: f64| {
            let (times, how) = if k > 1.0 {
                (k, "narrow")
            } else {
                (1.0 / k, "wide")
            };
            if parallel {
                format!("scaled {k:.2}x: check vw and vh: your view is {times:.2} times too {how}")
            } else {
                format!(
                    "scaled {k:.2}x: check vw, vh or d: your field of view is {times:.2} times \
                     too {how}"
                )
            }
        };
        let (m_x, m_y) = base.missing_shift_move(size);
        let mirror_words = |left_right: bool, upside_down: bool| match (left_right, upside_down) {
            (true, true) => {
                "rotated 180 degrees (mirrored left-right and upside down): check the sign of up"
            }
            (true, false) => "mirrored left-right: check u = up x w",
            (false, true) => {
                "upside down: check v = w x u and the minus sign in v = -((i - 1/2)/H - 1/2) vh"
            }
            (false, false) => "",
        };
        let (passes, without_scene, with_scene) = match mistake {
            Mistake::None => (true, String::new(), String::new()),
            Mistake::ShiftFlipped | Mistake::ShiftMissing => {
                let (k, cause) = if mistake == Mistake::ShiftFlipped {
                    (2.0, "the sign of the shift is flipped")
                } else {
                    (1.0, "the shift is missing")
                };
                let words = move_words(k * m_x, k * m_y);
                // Beyond half the picture less than a fifth of it is left in common: no
                // search can tell that from another view; the scene's prediction can.
                let common = (1.0 - (k * m_x).abs() / w) * (1.0 - (k * m_y).abs() / h);
                let without = if common < 0.2 {
                    UNEXPLAINED_VIEW.to_owned()
                } else {
                    format!("shifted {words}: check the shift (sx, sy)")
                };
                (
                    false,
                    without,
                    format!("shifted {words}: {cause} ({scene_shift})"),
                )
            }
            Mistake::PixelCorner => (false, PIXEL_CORNER.to_owned(), PIXEL_CORNER.to_owned()),
            Mistake::Distance(k) => (
                false,
                format!("scaled {k:.2}x{}: check vw, vh or d", about(pp, off_centre)),
                field_of_view(k),
            ),
            Mistake::Viewport(k) => (
                false,
                format!("scaled {k:.2}x: check vw, vh or d"),
                field_of_view(k),
            ),
            Mistake::Mirror {
                left_right,
                upside_down,
            } => {
                let words = mirror_words(left_right, upside_down).to_owned();
                (false, words.clone(), words)
            }
            Mistake::Roll(degrees) => {
                let way = if degrees > 0.0 {
                    "counterclockwise"
                } else {
                    "clockwise"
                };
                let turn = |named| {
                    format!(
                        "rotated {} degrees {way}{}: check the up vector",
                        amount(degrees),
                        about(pp, named)
                    )
                };
                (false, turn(off_centre), turn(false))
            }
            Mistake::Move(dx, dy) => {
                let words = move_words(dx, dy);
                let with = if parallel {
                    format!("shifted {words}: check e (the eye moved across the view)")
                } else if sx != 0.0 || sy != 0.0 {
                    format!(
                        "shifted {words}: check sx and sy ({scene_shift}) and the view direction"
                    )
                } else {
                    format!(
                        "shifted {words}: check sx and sy (the scene has no shift) and the view \
                         direction"
                    )
                };
                (
                    false,
                    format!("shifted {words}: check the shift (sx, sy)"),
                    with,
                )
            }
            Mistake::MirrorAndShiftMissing => {
                let words = move_words(m_x, m_y);
                let mirrored = mirror_words(true, false);
                (
                    false,
                    format!("{mirrored}; shifted {words}: check the shift (sx, sy)"),
                    format!("{mirrored}; shifted {words}: the shift is missing ({scene_shift})"),
                )
            }
            Mistake::MissingObject | Mistake::WrongColour => (
                false,
                UNEXPLAINED_LOCAL.to_owned(),
                UNEXPLAINED_LOCAL.to_owned(),
            ),
        };
        let label = match mistake {
            Mistake::None => format!("correct_{samples}spp"),
            Mistake::ShiftFlipped => "shift_flipped".to_owned(),
            Mistake::ShiftMissing => "shift_missing".to_owned(),
            Mistake::PixelCorner => "pixel_corner".to_owned(),
            Mistake::Distance(k) => format!("distance_{:.0}", k * 100.0),
            Mistake::Viewport(k) => format!("viewport_{:.0}", k * 100.0),
            Mistake::Mirror {
                left_right,
                upside_down,
            } => match (left_right, upside_down) {
                (true, true) => "mirror_both".to_owned(),
                (true, false) => "mirror_left_right".to_owned(),
                _ => "upside_down".to_owned(),
            },
            Mistake::Roll(degrees) => format!("roll_{degrees:.0}").replace('-', "minus"),
            Mistake::Move(dx, dy) => format!("move_{dx:.0}_{dy:.0}").replace('-', "minus"),
            Mistake::MirrorAndShiftMissing => "mirror_and_shift_missing".to_owned(),
            Mistake::MissingObject => "missing_object".to_owned(),
            Mistake::WrongColour => "wrong_colour".to_owned(),
        };
        Case {
            name: format!("{}_{label}_{}x{}", base.name(), size.0, size.1),
            base,
            size,
            samples,
            mistake,
            passes,
            without_scene,
            with_scene,
        }
    }
}

/// The matrix: every kind of mistake, on scenes with and without a lens shift, at
/// several sizes.
pub fn cases() -> Vec<Case> {
    use Mistake::*;
    let mirror = |left_right, upside_down| Mirror {
        left_right,
        upside_down,
    };
    let mut cases = Vec::new();
    let mut add = |base: Base, size: (u32, u32), samples: u32, mistakes: &[Mistake]| {
        for &mistake in mistakes {
            cases.push(Case::new(base, size, samples, mistake));
        }
    };
    // The issue's scene: a lens shift of (0, 0.2), 192 x 144.
    add(Base::Boxes, (192, 144), 1, &[None, PixelCorner]);
    add(
        Base::Boxes,
        (192, 144),
        4,
        &[
            None,
            ShiftFlipped,
            ShiftMissing,
            Distance(0.7),
            Distance(1.4),
            Viewport(0.85),
            Viewport(1.2),
            mirror(true, false),
            mirror(false, true),
            mirror(true, true),
            Roll(3.0),
            Roll(-8.0),
            Roll(30.0),
            Move(3.0, 0.0),
            Move(-90.0, 0.0),
            Move(40.0, -30.0),
            MirrorAndShiftMissing,
            MissingObject,
            WrongColour,
        ],
    );
    add(Base::Boxes, (192, 144), 16, &[None]);
    add(
        Base::Boxes,
        (128, 96),
        4,
        &[ShiftFlipped, Distance(1.2), Roll(10.0), mirror(true, false)],
    );
    // No shift.
    add(Base::General, (160, 120), 1, &[None, PixelCorner]);
    add(
        Base::General,
        (160, 120),
        4,
        &[
            Viewport(0.7),
            Viewport(1.4),
            Distance(1.1),
            Roll(8.0),
            Roll(-20.0),
            mirror(true, false),
            Move(0.0, 2.0),
            Move(-70.0, 50.0),
            MissingObject,
            WrongColour,
        ],
    );
    add(Base::General, (240, 180), 16, &[None]);
    add(
        Base::General,
        (240, 180),
        4,
        &[Roll(8.0), mirror(false, true)],
    );
    // The issue's other shifted scenes.
    add(
        Base::GeneralShifted,
        (240, 180),
        4,
        &[ShiftFlipped, ShiftMissing, Distance(1.25)],
    );
    add(
        Base::Tower,
        (180, 240),
        4,
        &[None, ShiftFlipped, ShiftMissing],
    );
    // A parallel projection.
    add(
        Base::Orthographic,
        (160, 120),
        4,
        &[None, Viewport(1.25), Roll(10.0)],
    );
    cases
}

/// Whether the diagnosis `got` says what `want` says: the same words, and the same
/// numbers up to one unit of their last printed digit (or 2%, for the coordinates of a
/// fixed point): the estimate is measured, the expectation computed.
pub fn same_message(got: &str, want: &str) -> bool {
    let split = |s: &str| -> Vec<String> {
        let mut parts = Vec::new();
        let mut current = String::new();
        let mut numeric = false;
        for ch in s.chars() {
            let is_num = ch.is_ascii_digit() || (ch == '.' && numeric);
            if is_num != numeric && !current.is_empty() {
                parts.push(std::mem::take(&mut current));
            }
            numeric = is_num;
            current.push(ch);
        }
        parts.push(current);
        parts
    };
    let (a, b) = (split(got), split(want));
    a.len() == b.len()
        && a.iter().zip(&b).all(|(x, y)| {
            if x == y {
                return true;
            }
            match (x.parse::<f64>(), y.parse::<f64>()) {
                (Ok(u), Ok(v)) => {
                    let decimals = y.split('.').nth(1).map_or(0, str::len);
                    let unit = 10f64.powi(-(decimals as i32));
                    (u - v).abs() <= unit * 1.001 || (u - v).abs() <= 0.02 * v.abs()
                }
                _ => false,
            }
        })
}

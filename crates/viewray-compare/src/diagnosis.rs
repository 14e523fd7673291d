//! What a failed render's difference says about the student's camera, and the words for
//! it: in pixels, or in the lecture's terms when the reference's scene is known.
//!
//! Each classic camera mistake is a transform of the picture (see [`CameraMistake`]):
//! u = w x up instead of up x w mirrors it left-right; a wrong v turns it upside down; a
//! missing pixel-centre offset (j instead of j - 1/2) moves it by half a pixel; a wrong
//! vw, vh or d scales it about the principal point; a wrong up vector rolls the camera and
//! turns it; a lens shift left out moves it by the shift (sx W / vw pixels along x, sy H /
//! vh along y), and one with the wrong sign by twice that. With [`Expectations`] (the
//! scene's principal point and shift, as plain numbers) the messages name the parameter
//! ("the sign of the shift is flipped", "your field of view is 1.25 times too wide").

use std::fmt;

/// What the reference's scene says a camera mistake would look like: the facts the
/// messages are worded with. Plain numbers, so that this crate needs no scene.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Expectations {
    /// Where the principal point (the foot of the perpendicular from the eye to the image
    /// plane) sits in the picture, as fractions of its width and height from the top-left:
    /// `(1/2 - sx/vw, 1/2 + sy/vh)` for a perspective camera with a lens shift (sx, sy),
    /// `(0.5, 0.5)` without one. A wrong d or field of view scales the picture about it;
    /// a roll turns it about it.
    pub principal_point: (f64, f64),
    /// The scene's lens shift (sx, sy), in image-plane units (zero without one).
    pub shift: (f64, f64),
    /// The kind of projection, which decides what sets the field of view.
    pub camera: CameraKind,
}

/// What kind of projection made the reference, as far as the wording needs it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum CameraKind {
    /// Rays from the eye (perspective, thin lens): the field of view is set by vw, vh and
    /// d; a lens shift moves the picture.
    Perspective,
    /// Parallel rays (orthographic, oblique): the view is set by vw and vh; moving e
    /// across the view moves the picture.
    Parallel,
}

impl Expectations {
    /// The principal point in pixels of a `width` x `height` picture.
    pub fn principal_point_pixels(&self, width: u32, height: u32) -> (f64, f64) {
        (
            self.principal_point.0 * f64::from(width),
            self.principal_point.1 * f64::from(height),
        )
    }

    /// How far the picture moves, in pixels (x right, y down), when the shift is left
    /// out: from the principal point to the centre, `(sx W / vw, -sy H / vh)`.
    pub fn missing_shift_move(&self, width: u32, height: u32) -> (f64, f64) {
        (
            (0.5 - self.principal_point.0) * f64::from(width),
            (0.5 - self.principal_point.1) * f64::from(height),
        )
    }
}

/// What the instructor's judgement found about a render that differs.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Diagnosis {
    /// The actual picture is the expected one transformed: a camera mistake.
    Camera(CameraMistake),
    /// The render failed, and no camera transform explains the difference.
    Unexplained {
        /// Most of the picture differs (a different view altogether, or a transform beyond
        /// what can be measured); otherwise the difference is local: an object or a
        /// colour.
        whole_view: bool,
    },
}

/// A camera mistake: how the actual picture is transformed from the expected one.
///
/// In continuous image coordinates (x right, y down), what the expected picture shows at
/// `X` the actual one shows at `about + R S M (X - about) + shift`, where `M` mirrors,
/// `S` scales and `R` turns by `rotation`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct CameraMistake {
    /// Mirrored left-right (about the vertical line through `about`).
    pub mirrored_left_right: bool,
    /// Upside down (mirrored about the horizontal line through `about`).
    pub upside_down: bool,
    /// How far the picture is turned, in degrees, counterclockwise as seen.
    pub rotation: f64,
    /// How many times larger the content appears in the actual image, along x and y:
    /// 1.1 when vw and vh are 1.1 times too small.
    pub scale: (f64, f64),
    /// The point the mirrors, the turn and the scale are about, in pixels.
    pub about: (f64, f64),
    /// How far the content moved besides, in pixels: x right, y down.
    pub shift: (f64, f64),
    /// Which parts are beyond the tolerances (the others are measurement noise and are
    /// not reported).
    pub significant: Significant,
    /// The fraction of the mean squared difference between the (blurred) images, on the
    /// part both show, that the transform explains: 1 when undoing it leaves no
    /// difference.
    pub explained: f64,
    /// The fraction of the actual picture that shows part of the expected one through
    /// the transform (the rest is new content, entered at an edge).
    pub overlap: f64,
    /// The width and height of the pictures.
    pub size: (u32, u32),
    /// The scene's facts the messages are worded with, when it is known.
    pub expectations: Option<Expectations>,
}

/// Which parts of a [`CameraMistake`] are beyond the tolerances.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub struct Significant {
    /// The picture is turned.
    pub rotation: bool,
    /// The scale along x differs from 1.
    pub scale_x: bool,
    /// The scale along y differs from 1.
    pub scale_y: bool,
    /// The move along x differs from 0.
    pub shift_x: bool,
    /// The move along y differs from 0.
    pub shift_y: bool,
    /// The turn or scale is about a point that is neither the image centre nor the
    /// principal point (so it is named).
    pub about: bool,
}

impl Diagnosis {
    /// One message per finding, each saying what is seen and what to check, e.g.
    /// `shifted -0.5 px in x and y: check the pixel-centre offset (j - 1/2, i - 1/2)` or
    /// `mirrored left-right: check u = up x w`.
    pub fn messages(&self) -> Vec<String> {
        match self {
            Diagnosis::Camera(mistake) => mistake.messages(),
            Diagnosis::Unexplained { whole_view: false } => vec![
                "no camera transform explains the difference: an object or a colour differs"
                    .to_owned(),
            ],
            Diagnosis::Unexplained { whole_view: true } => vec![
                "no camera transform explains the difference: the whole view differs (check e, \
                 the view direction and the shift)"
                    .to_owned(),
            ],
        }
    }

    /// The camera mistake, if the diagnosis is one.
    pub fn camera_mistake(&self) -> Option<&CameraMistake> {
        match self {
            Diagnosis::Camera(mistake) => Some(mistake),
            Diagnosis::Unexplained { .. } => None,
        }
    }
}

impl fmt::Display for Diagnosis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.messages().join("; "))
    }
}

impl fmt::Display for CameraMistake {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.messages().join("; "))
    }
}

/// A number of pixels or degrees as the messages print it: whole from 2 up, else with
/// one decimal.
fn amount(value: f64) -> String {
    if value.abs() >= 2.0 {
        format!("{:.0}", value.abs())
    } else {
        format!("{:.1}", value.abs())
    }
}

/// A scene parameter as the messages print it: up to four decimals, no trailing zeros.
fn parameter(value: f64) -> String {
    let text = format!("{value:.4}");
    let text = text.trim_end_matches('0').trim_end_matches('.');
    if text == "-0" {
        "0".to_owned()
    } else {
        text.to_owned()
    }
}

/// A move in words, e.g. `64 px up` or `25 px down and 40 px left`.
fn move_words(shift: (f64, f64), moved: (bool, bool)) -> String {
    let (tx, ty) = shift;
    let mut parts = Vec::new();
    if moved.1 {
        parts.push(format!(
            "{} px {}",
            amount(ty),
            if ty < 0.0 { "up" } else { "down" }
        ));
    }
    if moved.0 {
        parts.push(format!(
            "{} px {}",
            amount(tx),
            if tx < 0.0 { "left" } else { "right" }
        ));
    }
    parts.join(" and ")
}

/// How close a measured move must be to a predicted one: a third of a pixel, and 2% of
/// a large move (where new content enters at the border).
fn matches(measured: f64, predicted: f64) -> bool {
    (measured - predicted).abs() <= 0.35 + 0.02 * predicted.abs()
}

impl CameraMistake {
    /// One message per mistake, each saying what is seen and what to check.
    pub fn messages(&self) -> Vec<String> {
        let mut messages = Vec::new();
        match (self.mirrored_left_right, self.upside_down) {
            (true, true) => messages.push(
                "rotated 180 degrees (mirrored left-right and upside down): check the sign of up"
                    .to_owned(),
            ),
            (true, false) => messages.push("mirrored left-right: check u = up x w".to_owned()),
            (false, true) => messages.push(
                "upside down: check v = w x u and the minus sign in v = -((i - 1/2)/H - 1/2) vh"
                    .to_owned(),
            ),
            (false, false) => {}
        }
        let about = if self.significant.about {
            format!(" about ({:.0}, {:.0})", self.about.0, self.about.1)
        } else {
            String::new()
        };
        if self.significant.rotation {
            messages.push(format!(
                "rotated {} degrees {}{about}: check the up vector",
                amount(self.rotation),
                if self.rotation > 0.0 {
                    "counterclockwise"
                } else {
                    "clockwise"
                }
            ));
        }
        if let Some(message) = self.scale_message(&about) {
            messages.push(message);
        }
        if let Some(message) = self.shift_message() {
            messages.push(message);
        }
        messages
    }

    /// What was measured, in plain words and without advice: `mirrored left-right, rotated
    /// 1.1 degrees clockwise, scaled 0.95x, moved 12 px left` (only what is significant;
    /// `neither moved, scaled nor turned` when nothing is).
    pub fn measured_words(&self) -> String {
        let mut parts = Vec::new();
        match (self.mirrored_left_right, self.upside_down) {
            (true, true) => parts.push("turned 180 degrees".to_owned()),
            (true, false) => parts.push("mirrored left-right".to_owned()),
            (false, true) => parts.push("upside down".to_owned()),
            (false, false) => {}
        }
        if self.significant.rotation {
            parts.push(format!(
                "rotated {} degrees {}",
                amount(self.rotation),
                if self.rotation > 0.0 {
                    "counterclockwise"
                } else {
                    "clockwise"
                }
            ));
        }
        let (sx, sy) = self.scale;
        match (self.significant.scale_x, self.significant.scale_y) {
            (true, true) if (sx - sy).abs() < 0.01 => {
                parts.push(format!("scaled {:.2}x", 0.5 * (sx + sy)));
            }
            (true, true) => parts.push(format!("scaled {sx:.2}x in x and {sy:.2}x in y")),
            (true, false) => parts.push(format!("scaled {sx:.2}x in x")),
            (false, true) => parts.push(format!("scaled {sy:.2}x in y")),
            (false, false) => {}
        }
        let moved = (self.significant.shift_x, self.significant.shift_y);
        if moved.0 || moved.1 {
            parts.push(format!("moved {}", move_words(self.shift, moved)));
        }
        if parts.is_empty() {
            "neither moved, scaled nor turned".to_owned()
        } else {
            parts.join(", ")
        }
    }

    fn scale_message(&self, about: &str) -> Option<String> {
        let (sx, sy) = self.scale;
        let parallel = self
            .expectations
            .is_some_and(|e| e.camera == CameraKind::Parallel);
        let view = |s: f64, axis: &str| -> String {
            let Some(expectations) = self.expectations else {
                return String::new();
            };
            let what = match expectations.camera {
                CameraKind::Perspective => "your field of view",
                CameraKind::Parallel => "your view",
            };
            let (times, how) = if s > 1.0 {
                (s, "narrow")
            } else {
                (1.0 / s, "wide")
            };
            let how = match (axis, how) {
                ("y", "narrow") => "short",
                ("y", "wide") => "tall",
                _ => how,
            };
            format!(": {what} is {times:.2} times too {how}")
        };
        let message = match (self.significant.scale_x, self.significant.scale_y) {
            (true, true) if (sx - sy).abs() < 0.01 => {
                let s = 0.5 * (sx + sy);
                let names = if parallel { "vw and vh" } else { "vw, vh or d" };
                format!("scaled {s:.2}x{about}: check {names}{}", view(s, ""))
            }
            (true, true) => format!(
                "scaled {sx:.2}x in x and {sy:.2}x in y{about}: check vw and vh (the aspect ratio)"
            ),
            (true, false) => format!(
                "scaled {sx:.2}x in x only{about}: check vw{}",
                view(sx, "x")
            ),
            (false, true) => format!(
                "scaled {sy:.2}x in y only{about}: check vh{}",
                view(sy, "y")
            ),
            (false, false) => return None,
        };
        Some(message)
    }

    /// The message about the move, if it is significant.
    fn shift_message(&self) -> Option<String> {
        let moved = (self.significant.shift_x, self.significant.shift_y);
        if !moved.0 && !moved.1 {
            return None;
        }
        let (tx, ty) = self.shift;
        let words = move_words(self.shift, moved);
        let Some(expectations) = self.expectations else {
            return Some(
                half_pixel_message(self.shift, moved)
                    .unwrap_or_else(|| format!("shifted {words}: check the shift (sx, sy)")),
            );
        };
        let (w, h) = self.size;
        let (mx, my) = expectations.missing_shift_move(w, h);
        let has_shift = mx.abs() > 0.5 || my.abs() > 0.5;
        let (sx, sy) = expectations.shift;
        let scene_shift = format!(
            "the scene's shift (sx, sy) is ({}, {})",
            parameter(sx),
            parameter(sy)
        );
        // The move as twice or once the shift, plus perhaps half a pixel.
        if has_shift {
            for (k, cause) in [
                (2.0, "the sign of the shift is flipped"),
                (1.0, "the shift is missing"),
            ] {
                let (px, py) = (k * mx, k * my);
                if matches(tx, px) && matches(ty, py) {
                    return Some(format!("shifted {words}: {cause} ({scene_shift})"));
                }
                let rest = (tx - px, ty - py);
                let rest_moved = (rest.0.abs() > 0.25, rest.1.abs() > 0.25);
                let is_half = |t: f64, on: bool| !on || (t.abs() - 0.5).abs() < 0.2;
                if (rest_moved.0 || rest_moved.1)
                    && is_half(rest.0, rest_moved.0)
                    && is_half(rest.1, rest_moved.1)
                    && let Some(half) = half_pixel_message(rest, rest_moved)
                {
                    return Some(format!(
                        "shifted {words}: {cause} ({scene_shift}); and {half}"
                    ));
                }
            }
        }
        if let Some(message) = half_pixel_message(self.shift, moved) {
            return Some(message);
        }
        Some(match expectations.camera {
            CameraKind::Parallel => {
                format!("shifted {words}: check e (the eye moved across the view)")
            }
            CameraKind::Perspective if has_shift => {
                format!("shifted {words}: check sx and sy ({scene_shift}) and the view direction")
            }
            CameraKind::Perspective => format!(
                "shifted {words}: check sx and sy (the scene has no shift) and the view direction"
            ),
        })
    }
}

/// The message for a move of half a pixel (within a fifth of a pixel) on each moved axis:
/// the samples are taken at a pixel corner instead of its centre.
fn half_pixel_message(shift: (f64, f64), moved: (bool, bool)) -> Option<String> {
    let (tx, ty) = shift;
    let half = |t: f64| (t.abs() - 0.5).abs() < 0.2;
    if (moved.0 && !half(tx)) || (moved.1 && !half(ty)) {
        return None;
    }
    let (axes, terms) = match moved {
        (true, true) if tx.signum() == ty.signum() => (
            format!("{:+.1} px in x and y", 0.5 * tx.signum()),
            "j - 1/2, i - 1/2",
        ),
        (true, true) => (
            format!(
                "{:+.1} px in x and {:+.1} px in y",
                0.5 * tx.signum(),
                0.5 * ty.signum()
            ),
            "j - 1/2, i - 1/2",
        ),
        (true, false) => (format!("{:+.1} px in x", 0.5 * tx.signum()), "j - 1/2"),
        (false, true) => (format!("{:+.1} px in y", 0.5 * ty.signum()), "i - 1/2"),
        (false, false) => return None,
    };
    Some(format!(
        "shifted {axes}: check the pixel-centre offset ({terms})"
    ))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mistake(shift: (f64, f64), scale: (f64, f64), significant: Significant) -> CameraMistake {
        CameraMistake {
            mirrored_left_right: false,
            upside_down: false,
            rotation: 0.0,
            scale,
            about: (96.0, 72.0),
            shift,
            significant,
            explained: 0.9,
            overlap: 1.0,
            size: (192, 144),
            expectations: None,
        }
    }

    const BOTH: Significant = Significant {
        shift_x: true,
        shift_y: true,
        rotation: false,
        scale_x: false,
        scale_y: false,
        about: false,
    };
    const ONLY_Y: Significant = Significant {
        shift_x: false,
        ..BOTH
    };
    const ONLY_X: Significant = Significant {
        shift_y: false,
        ..BOTH
    };
    const SCALED: Significant = Significant {
        scale_x: true,
        scale_y: true,
        shift_x: false,
        shift_y: false,
        ..BOTH
    };

    /// The boxes scene of the tests: viewport 1.2 x 0.9, shift (0, 0.2), 192 x 144: the
    /// principal point is at y = 144 (1/2 + 0.2/0.9) = 104, a missing shift moves the
    /// picture 32 px up.
    const BOXES: Expectations = Expectations {
        principal_point: (0.5, 0.5 + 0.2 / 0.9),
        shift: (0.0, 0.2),
        camera: CameraKind::Perspective,
    };

    #[test]
    fn messages_in_pixels_name_the_classic_mistakes() {
        let cases = [
            (
                mistake((-0.48, -0.53), (1.0, 1.0), BOTH),
                "shifted -0.5 px in x and y: check the pixel-centre offset (j - 1/2, i - 1/2)",
            ),
            (
                mistake((0.02, -12.2), (1.0, 1.0), ONLY_Y),
                "shifted 12 px up: check the shift (sx, sy)",
            ),
            (
                mistake((3.0, 1.2), (1.0, 1.0), BOTH),
                "shifted 1.2 px down and 3 px right: check the shift (sx, sy)",
            ),
            (
                mistake((0.0, 0.0), (1.098, 1.101), SCALED),
                "scaled 1.10x: check vw, vh or d",
            ),
            (
                CameraMistake {
                    mirrored_left_right: true,
                    ..mistake((0.0, 0.0), (1.0, 1.0), Significant::default())
                },
                "mirrored left-right: check u = up x w",
            ),
            (
                CameraMistake {
                    rotation: -8.04,
                    significant: Significant {
                        rotation: true,
                        about: true,
                        ..Significant::default()
                    },
                    ..mistake((0.0, 0.0), (1.0, 1.0), Significant::default())
                },
                "rotated 8 degrees clockwise about (96, 72): check the up vector",
            ),
        ];
        for (mistake, expected) in cases {
            assert_eq!(mistake.to_string(), expected);
        }
    }

    #[test]
    fn messages_with_the_scene_speak_the_lectures_terms() {
        let with = |m: CameraMistake| CameraMistake {
            expectations: Some(BOXES),
            ..m
        };
        let cases = [
            (
                mistake((0.1, -64.2), (1.0, 1.0), ONLY_Y),
                "shifted 64 px up: the sign of the shift is flipped (the scene's shift (sx, sy) \
                 is (0, 0.2))",
            ),
            (
                mistake((0.0, -31.9), (1.0, 1.0), ONLY_Y),
                "shifted 32 px up: the shift is missing (the scene's shift (sx, sy) is (0, 0.2))",
            ),
            (
                mistake((-0.5, -32.4), (1.0, 1.0), BOTH),
                "shifted 32 px up and 0.5 px left: the shift is missing (the scene's shift (sx, \
                 sy) is (0, 0.2)); and shifted -0.5 px in x and y: check the pixel-centre \
                 offset (j - 1/2, i - 1/2)",
            ),
            (
                mistake((12.0, 0.0), (1.0, 1.0), ONLY_X),
                "shifted 12 px right: check sx and sy (the scene's shift (sx, sy) is (0, 0.2)) \
                 and the view direction",
            ),
            (
                mistake((0.0, 0.0), (0.8, 0.8), SCALED),
                "scaled 0.80x: check vw, vh or d: your field of view is 1.25 times too wide",
            ),
            (
                mistake((0.0, 0.0), (1.25, 1.25), SCALED),
                "scaled 1.25x: check vw, vh or d: your field of view is 1.25 times too narrow",
            ),
        ];
        for (mistake, expected) in cases {
            assert_eq!(with(mistake).to_string(), expected);
        }
    }

    #[test]
    fn the_missing_shift_moves_the_picture_from_the_principal_point_to_the_centre() {
        // sy = 0.2 on vh = 0.9 and H = 144: 0.2 * 144 / 0.9 = 32 px up.
        let (mx, my) = BOXES.missing_shift_move(192, 144);
        assert!(mx.abs() < 1e-9 && (my + 32.0).abs() < 1e-9, "{mx} {my}");
        let (px, py) = BOXES.principal_point_pixels(192, 144);
        assert!((px - 96.0).abs() < 1e-9 && (py - 104.0).abs() < 1e-9);
    }
}

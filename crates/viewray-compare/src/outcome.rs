//! What became of one pair of images, and the verdict the terminal, the JSON lines, the
//! gradebook and the reports all give it.

use crate::appearance::Appearance;
use crate::camera::CameraFinding;
use crate::comparison::{Comparison, Failure};

/// What became of one pair of images: compared, or not, and whose failure that is.
///
/// The golden check, `viewray compare` and `viewray grade` all speak of a pair this way;
/// [`crate::Report`]s show it.
#[derive(Clone, Debug)]
pub enum Outcome {
    /// The images were compared.
    Compared(Box<Comparison>),
    /// The actual image could not be compared because it is missing or cannot be read
    /// (the message says which): the render's failure, as `viewray compare` and `viewray
    /// grade` judge folders.
    Failed(String),
    /// The images could not be compared, and it is no one's failure (the message says
    /// why): the golden check's word for a reference it lacks.
    Error(String),
}

impl From<Comparison> for Outcome {
    fn from(comparison: Comparison) -> Self {
        Outcome::Compared(Box::new(comparison))
    }
}

impl Outcome {
    /// The verdict: [`Verdict::Pass`] for a comparison that passed,
    /// [`Verdict::Error`] for [`Outcome::Error`], else [`Verdict::Fail`].
    pub fn verdict(&self) -> Verdict {
        match self {
            Outcome::Compared(c) if c.passed() => Verdict::Pass,
            Outcome::Compared(_) | Outcome::Failed(_) => Verdict::Fail,
            Outcome::Error(_) => Verdict::Error,
        }
    }

    /// Whether the pair passed (an error never does).
    pub fn passed(&self) -> bool {
        self.verdict() == Verdict::Pass
    }

    /// The comparison, when the images were compared.
    pub fn comparison(&self) -> Option<&Comparison> {
        match self {
            Outcome::Compared(c) => Some(c),
            Outcome::Failed(_) | Outcome::Error(_) => None,
        }
    }

    /// The peak FLIP, when the images were compared with FLIP.
    pub fn peak_flip(&self) -> Option<f32> {
        self.comparison()?.metrics.map(|m| m.peak_flip)
    }

    /// What a row says after the figures: the diagnosis, else why it failed, else nothing
    /// ([`Comparison::note`]).
    pub fn note(&self) -> String {
        match self {
            Outcome::Compared(c) => c.note(),
            Outcome::Failed(message) | Outcome::Error(message) => message.clone(),
        }
    }

    /// The camera judgement, when the pair was compared with a scene's camera judge.
    pub fn camera(&self) -> Option<&CameraFinding> {
        self.comparison()?.camera.as_ref()
    }

    /// How the render looks beside the reference, when that was judged.
    pub fn appearance(&self) -> Option<Appearance> {
        self.comparison()?.appearance
    }

    /// Why a pair failed, in the few kinds a class report colours apart; `None` when it
    /// passed.
    pub fn failure_kind(&self) -> Option<FailureKind> {
        match self {
            Outcome::Compared(c) if c.passed() => None,
            Outcome::Compared(c) => Some(
                if c.failures.iter().any(|f| {
                    matches!(
                        f,
                        Failure::WrongCamera { .. }
                            | Failure::CameraMistake
                            | Failure::SizeMismatch { .. }
                    )
                }) {
                    FailureKind::Camera
                } else {
                    FailureKind::Appearance
                },
            ),
            Outcome::Failed(message) | Outcome::Error(message) => {
                Some(if message.starts_with("missing") {
                    FailureKind::Missing
                } else {
                    FailureKind::Unreadable
                })
            }
        }
    }

    /// What a summary counts a failed pair by, in a few words: the camera's catalogue
    /// entry (`mirrored: u-sign`, [`CameraFinding::key`]), the transform measured when no
    /// scene was given (`mirrored left-right`), the appearance (`gamma-missing`),
    /// `missing` or `unreadable`; `None` when it passed.
    pub fn summary_key(&self) -> Option<String> {
        let kind = self.failure_kind()?;
        let Some(c) = self.comparison() else {
            return Some(kind.word().to_owned());
        };
        if let Some(key) = c.camera.as_ref().and_then(CameraFinding::key)
            && kind == FailureKind::Camera
        {
            return Some(key);
        }
        if c.failures
            .iter()
            .any(|f| matches!(f, Failure::SizeMismatch { .. }))
        {
            return Some("wrong size".to_owned());
        }
        if kind == FailureKind::Camera
            && let Some(mistake) = c.diagnosis.as_ref().and_then(|d| d.camera_mistake())
        {
            return Some(mistake.measured_words());
        }
        Some(match c.appearance {
            Some(appearance) if appearance != Appearance::Same => appearance.id().to_owned(),
            _ => "different".to_owned(),
        })
    }

    /// This outcome without what only a report needs (the FLIP error map).
    pub fn without_error_map(self) -> Self {
        match self {
            Outcome::Compared(c) => Outcome::Compared(Box::new(c.without_error_map())),
            other => other,
        }
    }
}

/// How a set of pairs fared: `passed + failed` pairs in all.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Tally {
    /// The pairs that passed.
    pub passed: usize,
    /// The pairs judged different, missing or unreadable (or, for the golden check, not
    /// compared).
    pub failed: usize,
    /// Of those failed, the ones not compared: missing or unreadable.
    pub not_compared: usize,
}

impl Tally {
    /// Counts one more pair.
    pub fn add(&mut self, outcome: &Outcome) {
        match outcome {
            Outcome::Compared(c) if c.passed() => self.passed += 1,
            Outcome::Compared(_) => self.failed += 1,
            Outcome::Failed(_) | Outcome::Error(_) => {
                self.failed += 1;
                self.not_compared += 1;
            }
        }
    }

    /// The pairs counted.
    pub fn total(&self) -> usize {
        self.passed + self.failed
    }

    /// The summary line, e.g. `6 images: 1 passed, 5 failed, 2 of them missing or
    /// unreadable`.
    pub fn summary(&self) -> String {
        let total = self.total();
        let noun = if total == 1 { "image" } else { "images" };
        let mut line = format!(
            "{total} {noun}: {} passed, {} failed",
            self.passed, self.failed
        );
        if self.not_compared > 0 {
            line.push_str(&format!(
                ", {} of them missing or unreadable",
                self.not_compared
            ));
        }
        line
    }
}

/// Why a pair failed, in the kinds a class report colours apart.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum FailureKind {
    /// No render of that name was handed in.
    Missing,
    /// The render could not be read.
    Unreadable,
    /// The camera is wrong: the picture's geometry (or size) is not the reference's.
    Camera,
    /// The camera is right (or was not judged and no transform explains the
    /// difference), but the picture looks different: shading, gamma, an object or a
    /// colour.
    Appearance,
}

impl FailureKind {
    /// `missing`, `unreadable`, `wrong camera` or `wrong appearance`.
    pub fn word(self) -> &'static str {
        match self {
            FailureKind::Missing => "missing",
            FailureKind::Unreadable => "unreadable",
            FailureKind::Camera => "wrong camera",
            FailureKind::Appearance => "wrong appearance",
        }
    }

    /// `missing`, `unreadable`, `camera` or `appearance`: a report's CSS class.
    pub fn class(self) -> &'static str {
        match self {
            FailureKind::Missing => "missing",
            FailureKind::Unreadable => "unreadable",
            FailureKind::Camera => "camera",
            FailureKind::Appearance => "appearance",
        }
    }
}

/// A pair's verdict, in the words the terminal prints: `PASS`, `FAIL` or `ERROR`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Verdict {
    /// Compared, and judged the same picture.
    Pass,
    /// Judged different, or the actual image is missing or unreadable.
    Fail,
    /// Not compared, and no one's failure: the golden check lacks a reference.
    Error,
}

impl Verdict {
    /// `PASS`, `FAIL` or `ERROR`.
    pub fn label(self) -> &'static str {
        match self {
            Verdict::Pass => "PASS",
            Verdict::Fail => "FAIL",
            Verdict::Error => "ERROR",
        }
    }

    /// `pass`, `fail` or `error`: the page's CSS class, and the JSON lines' word.
    pub fn word(self) -> &'static str {
        match self {
            Verdict::Pass => "pass",
            Verdict::Fail => "fail",
            Verdict::Error => "error",
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_tally_counts_each_outcome_once_and_says_so_in_one_line() {
        let mut tally = Tally::default();
        assert_eq!(tally.summary(), "0 images: 0 passed, 0 failed");
        tally.add(&Outcome::Failed("missing".to_owned()));
        assert_eq!(
            tally.summary(),
            "1 image: 0 passed, 1 failed, 1 of them missing or unreadable"
        );
        tally.add(&Outcome::Error("no golden".to_owned()));
        assert_eq!(
            tally,
            Tally {
                passed: 0,
                failed: 2,
                not_compared: 2
            }
        );
        assert_eq!(tally.total(), 2);
    }

    #[test]
    fn an_outcome_that_was_not_compared_has_no_figures_and_says_why() {
        let failed = Outcome::Failed("not a PNG: it does not decode".to_owned());
        assert_eq!(failed.verdict(), Verdict::Fail);
        assert_eq!(
            (failed.peak_flip(), failed.comparison().is_none()),
            (None, true)
        );
        assert_eq!(failed.note(), "not a PNG: it does not decode");
        let error = Outcome::Error("no golden image".to_owned());
        assert_eq!((error.verdict(), error.passed()), (Verdict::Error, false));
        assert_eq!(
            [Verdict::Pass, Verdict::Fail, Verdict::Error].map(|v| (v.label(), v.word())),
            [("PASS", "pass"), ("FAIL", "fail"), ("ERROR", "error")]
        );
    }
}

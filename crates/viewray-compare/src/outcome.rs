//! What became of one pair of images, and the verdict the terminal, the JSON lines, the
//! gradebook and the reports all give it.

use crate::comparison::Comparison;

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

    /// What a row says after the figures: the diagnosis, else why it failed, else nothing.
    pub fn note(&self) -> String {
        match self {
            Outcome::Compared(c) => match c.diagnosis {
                Some(d) => d.to_string(),
                None => c.reasons(),
            },
            Outcome::Failed(message) | Outcome::Error(message) => message.clone(),
        }
    }

    /// This outcome without what only a report needs (the FLIP error map).
    pub fn without_error_map(self) -> Self {
        match self {
            Outcome::Compared(c) => Outcome::Compared(Box::new(c.without_error_map())),
            other => other,
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

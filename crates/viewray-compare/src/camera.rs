//! Judging a picture's camera apart from its shading: what the judgement says, in plain
//! data, and the interface through which a crate that knows the scene judges it.
//!
//! This crate knows no scene and no camera. A [`CameraJudge`] is prepared once per
//! reference by one that does (viewray-judge labels the scene through the right camera
//! and through the lecture's catalogue of mistaken ones): it judges each picture's edges
//! ([`crate::CameraCandidates`]) and answers with a [`CameraFinding`], whose words (the
//! catalogue's entries, a moved eye) it wrote. [`crate::Reference`] calls it beside FLIP,
//! and [`Judge`] says which of the two decides a pair's verdict.

use std::fmt;

use image::RgbaImage;

use crate::diagnosis::CameraMistake;

/// Which judgement decides a pair's verdict (`--judge`).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Judge {
    /// The camera: the picture's edges against the scene's; shading, brightness, gamma
    /// and noise are reported, never failed. Needs a [`CameraJudge`].
    Camera,
    /// The image: FLIP against the reference, and the transform between the pictures.
    #[default]
    Image,
    /// Both must pass.
    Both,
}

impl Judge {
    /// `camera`, `image` or `both`.
    pub fn word(self) -> &'static str {
        match self {
            Judge::Camera => "camera",
            Judge::Image => "image",
            Judge::Both => "both",
        }
    }

    /// Whether the camera judgement takes part in the verdict.
    pub fn camera_decides(self) -> bool {
        matches!(self, Judge::Camera | Judge::Both)
    }

    /// Whether FLIP takes part in the verdict.
    pub fn image_decides(self) -> bool {
        matches!(self, Judge::Image | Judge::Both)
    }
}

/// An entry of the lecture's catalogue of camera mistakes, in the words of the crate that
/// keeps the catalogue.
#[derive(Clone, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct CatalogueEntry {
    /// The id: `u-sign`.
    pub id: String,
    /// What the picture looks like, in a word or two: `mirrored`.
    pub looks: String,
    /// The mistake in a few words: `u with a minus sign`.
    pub summary: String,
    /// The lecture's line to fix: the right formula.
    pub fix: String,
    /// What the mistake does to the picture, as a sentence.
    pub picture: String,
}

/// What the camera judgement found.
#[derive(Clone, Debug, PartialEq)]
pub enum CameraFinding {
    /// The right camera explains the picture's edges.
    Right {
        /// How well (1: every edge of the picture on a boundary).
        agreement: f64,
    },
    /// Entries of the catalogue explain the picture clearly better than the right camera
    /// (several when they make the same picture of this scene).
    Mistaken {
        /// The entries.
        entries: Vec<CatalogueEntry>,
        /// How well their picture agrees with the student's.
        agreement: f64,
        /// How well the right camera's does.
        right: f64,
    },
    /// The eye is elsewhere, and the scene seen from there explains the picture: checked
    /// by labelling it, never guessed.
    EyeMoved {
        /// The move in the camera's axes: along u (right), v (up) and -w (forward).
        offset: [f64; 3],
        /// The sentence: `the eye is about 0.6 to the right of where it should be`.
        sentence: String,
        /// How well the moved eye's picture agrees with the student's.
        agreement: f64,
        /// How well the right camera's does.
        right: f64,
    },
    /// Neither the right camera, nor an entry of the catalogue, nor a moved eye explains
    /// the picture.
    Unexplained {
        /// The move, scale and turn measured between the reference and the picture, when
        /// a transform explains their difference.
        measured: Option<CameraMistake>,
        /// How well the right camera's picture agrees with the student's.
        right: f64,
    },
    /// The picture is not the reference's size.
    WrongSize {
        /// The picture's width and height.
        found: (u32, u32),
        /// The reference's.
        expected: (u32, u32),
    },
    /// The camera cannot be judged from this picture: the right camera does not explain
    /// the reference's own edges (smooth shading, defocus blur, a picture of a few
    /// pixels), so this picture's edges, which it does not explain either, cannot convict
    /// a camera. The image judgement decides instead, and no mistake is named.
    Unjudged,
}

impl CameraFinding {
    /// Whether the camera is right.
    pub fn passed(&self) -> bool {
        matches!(self, CameraFinding::Right { .. })
    }

    /// Whether the camera was judged at all (see [`CameraFinding::Unjudged`]).
    pub fn judged(&self) -> bool {
        !matches!(self, CameraFinding::Unjudged)
    }

    /// `right`, `wrong` or `unjudged`: the gradebook's word.
    pub fn word(&self) -> &'static str {
        match self {
            CameraFinding::Right { .. } => "right",
            CameraFinding::Unjudged => "unjudged",
            _ => "wrong",
        }
    }

    /// The catalogue's ids of a [`CameraFinding::Mistaken`], else none.
    pub fn ids(&self) -> Vec<&str> {
        match self {
            CameraFinding::Mistaken { entries, .. } => {
                entries.iter().map(|e| e.id.as_str()).collect()
            }
            _ => Vec::new(),
        }
    }

    /// What the picture looks like and the catalogue's words for it, the key the class
    /// summary counts by: `mirrored: u-sign`, `upside down: v-sign or v-cross-order`,
    /// `eye moved`, `unexplained camera`, `wrong size`; `None` for a right camera and one
    /// not judged.
    pub fn key(&self) -> Option<String> {
        match self {
            CameraFinding::Right { .. } | CameraFinding::Unjudged => None,
            CameraFinding::Mistaken { entries, .. } => Some(format!(
                "{}: {}",
                looks(entries),
                entries
                    .iter()
                    .map(|e| e.id.as_str())
                    .collect::<Vec<_>>()
                    .join(" or ")
            )),
            CameraFinding::EyeMoved { .. } => Some("eye moved".to_owned()),
            CameraFinding::Unexplained { .. } => Some("unexplained camera".to_owned()),
            CameraFinding::WrongSize { .. } => Some("wrong size".to_owned()),
        }
    }

    /// The diagnosis, as a student reads it: the catalogue's entry with the formula to
    /// fix, the moved eye, or what was measured when nothing explains the picture; empty
    /// for a right camera; for one not judged, why.
    pub fn diagnosis(&self) -> String {
        match self {
            CameraFinding::Right { .. } => String::new(),
            CameraFinding::Unjudged => {
                "the camera cannot be judged from this picture (the scene's \
                                        edges are too weak in its pictures: smooth shading, \
                                        blur or too few pixels): the image judgement decides"
                    .to_owned()
            }
            CameraFinding::Mistaken { entries, .. } => {
                let each: Vec<String> = entries
                    .iter()
                    .map(|e| format!("{} ({}): fix {}", e.id, e.summary, e.fix))
                    .collect();
                format!("{}: {}", looks(entries), each.join("; or "))
            }
            CameraFinding::EyeMoved { sentence, .. } => format!("{sentence}: check e"),
            CameraFinding::Unexplained { measured, .. } => match measured {
                Some(transform) => format!(
                    "no entry of the lecture's catalogue explains the picture: it is {} \
                     (check e, the view direction and up)",
                    transform.measured_words()
                ),
                None => "no entry of the lecture's catalogue explains the picture, nor does a \
                         move, scale or turn of it (check e, the view direction and up)"
                    .to_owned(),
            },
            CameraFinding::WrongSize { found, expected } => format!(
                "the picture is {}x{}, the reference {}x{}: check W and H",
                found.0, found.1, expected.0, expected.1
            ),
        }
    }
}

/// What the pictures of `entries` look like: their words, each once, joined by `or`.
fn looks(entries: &[CatalogueEntry]) -> String {
    let mut words: Vec<&str> = Vec::new();
    for entry in entries {
        if !words.contains(&entry.looks.as_str()) {
            words.push(&entry.looks);
        }
    }
    words.join(" or ")
}

impl fmt::Display for CameraFinding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.diagnosis())
    }
}

/// A picture's camera judge, prepared once per reference by a crate that knows the scene
/// the reference was rendered from (viewray-judge's `SceneJudge`), and shared by every
/// thread that judges pictures against it.
pub trait CameraJudge: Send + Sync + fmt::Debug {
    /// The size of the pictures it judges.
    fn size(&self) -> (u32, u32);

    /// Judges the camera of `picture` (of [`CameraJudge::size`]). `measure` gives the
    /// move, scale and turn between the reference and the picture, when a transform
    /// explains their difference: the judge asks for it only when no camera it knows
    /// explains the picture (to say what was measured), since it costs a search.
    fn judge(
        &self,
        picture: &RgbaImage,
        measure: &dyn Fn() -> Option<CameraMistake>,
    ) -> CameraFinding;

    /// For each pixel (row by row), whether it lies inside one surface of the right
    /// camera's picture, away from every boundary: where appearance is measured.
    fn interior(&self) -> &[bool];
}

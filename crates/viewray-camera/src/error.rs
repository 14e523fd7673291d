//! The one error type of the camera crate.

use crate::ImageLimitError;

/// Why a frame, projection or camera could not be built.
///
/// Cameras are validated where they are built, so every [`crate::Camera`] that exists
/// generates finite rays.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CameraError {
    /// The view direction is the zero vector (for `look_at`: the eye is the target).
    #[error("the view direction is zero (is the look-at point the eye itself?)")]
    ZeroView,
    /// The up vector is the zero vector.
    #[error("the up vector is zero")]
    ZeroUp,
    /// Up is parallel to view, so `u = up x w` is undefined: the camera's roll is ambiguous.
    #[error("the up vector is parallel to the view direction, so the camera's roll is undefined")]
    UpParallelToView,
    /// A number is NaN or infinite.
    #[error("{name} must be finite, found {value}")]
    NotFinite {
        /// The parameter's name in the lecture's notation, e.g. `"d"` or `"eye"`.
        name: &'static str,
        /// The offending value, printed.
        value: String,
    },
    /// A number that must be positive is zero or negative.
    #[error("{name} must be positive, found {value}")]
    NotPositive {
        /// The parameter's name in the lecture's notation, e.g. `"vw"`.
        name: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A number is outside its valid range.
    #[error("{name} must be {expected}, found {value}")]
    OutOfRange {
        /// The parameter's name.
        name: &'static str,
        /// The range it must lie in, in words.
        expected: &'static str,
        /// The offending value.
        value: f64,
    },
    /// A tilted lens focused at or within its focal length: its sensor would lie at
    /// infinity or in front of it.
    #[error(
        "a tilted lens focuses beyond its focal length: focus must be greater than the focal \
         length d = {focal_length}, found {focus}"
    )]
    FocusWithinFocalLength {
        /// `f`.
        focus: f64,
        /// `F = d`.
        focal_length: f64,
    },
    /// The image has no pixels ([`ImageLimitError::Empty`]).
    #[error(transparent)]
    Image(#[from] ImageLimitError),
    /// A catalogue mistake that cannot be made in this camera (see
    /// [`crate::Mistake::fits`]; `size-minus-one` also needs two pixels each way).
    #[error("the mistake {id} cannot be made in this {family} camera{detail}")]
    MistakeDoesNotFit {
        /// The mistake's id.
        id: &'static str,
        /// The camera's family, as scene files spell it.
        family: &'static str,
        /// Why, when the family alone does not say: `" of 1 x 4 pixels"`.
        detail: String,
    },
}

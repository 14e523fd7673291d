//! How large an image viewray renders and how many samples it takes per pixel: the
//! limits, the one check of a size and a sample count against them, and its error.
//!
//! A scene file, the command line and the live playground all check through
//! [`ImageLimits`], so they refuse the same sizes with the same sentences; the playground
//! only tightens the limits.

/// The largest image side viewray renders: 16384 pixels.
pub const MAX_IMAGE_SIDE: u32 = 16_384;
/// The largest number of pixels viewray renders: 2^28 (a 16384 x 16384 image).
pub const MAX_IMAGE_PIXELS: u64 = 1 << 28;
/// The largest number of samples per pixel: 65536.
pub const MAX_SAMPLES: u32 = 65_536;

/// Bounds on an image's size and on its samples per pixel.
///
/// [`ImageLimits::VIEWRAY`] (the default) are viewray's own; a program that renders for
/// others (the live playground) may tighten them, never loosen them
/// ([`ImageLimits::within_viewray`]).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct ImageLimits {
    /// The largest width or height, in pixels.
    pub max_side: u32,
    /// The most pixels, `width x height`.
    pub max_pixels: u64,
    /// The most samples per pixel.
    pub max_samples: u32,
}

impl Default for ImageLimits {
    fn default() -> Self {
        Self::VIEWRAY
    }
}

/// A size or a sample count outside the [`ImageLimits`]. Sizes are kept as given (in
/// `u64`, so that a typed `100000 x 100000` is named as typed).
#[derive(Clone, Copy, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ImageLimitError {
    /// A side is zero.
    #[error("the image must be at least 1 x 1 pixels, found {width} x {height}")]
    Empty {
        /// Columns.
        width: u64,
        /// Rows.
        height: u64,
    },
    /// A side is longer than the limit.
    #[error("{width} x {height} is too large: each side can be at most {max_side} pixels")]
    SideTooLarge {
        /// Columns.
        width: u64,
        /// Rows.
        height: u64,
        /// The limit.
        max_side: u32,
    },
    /// More pixels than the limit, each side within its own.
    #[error(
        "{width} x {height} is too large: at most {max_pixels} pixels{}",
        if *max_pixels == MAX_IMAGE_PIXELS { " (2^28)" } else { "" }
    )]
    TooManyPixels {
        /// Columns.
        width: u64,
        /// Rows.
        height: u64,
        /// The limit (written with its power of two when it is viewray's own).
        max_pixels: u64,
    },
    /// A sample count, as a number, outside `1..=max_samples`.
    #[error("samples must be between 1 and {max_samples}, found {samples}")]
    Samples {
        /// The count given.
        samples: u64,
        /// The limit.
        max_samples: u32,
    },
    /// A sample count, as typed text, that is not a whole number in `1..=max_samples`.
    #[error("expected a whole number of samples from 1 to {max_samples}")]
    SamplesText {
        /// The limit.
        max_samples: u32,
    },
}

impl ImageLimits {
    /// viewray's own limits: [`MAX_IMAGE_SIDE`], [`MAX_IMAGE_PIXELS`] and
    /// [`MAX_SAMPLES`].
    pub const VIEWRAY: ImageLimits = ImageLimits {
        max_side: MAX_IMAGE_SIDE,
        max_pixels: MAX_IMAGE_PIXELS,
        max_samples: MAX_SAMPLES,
    };

    /// These limits, each at most viewray's own.
    pub fn within_viewray(self) -> ImageLimits {
        ImageLimits {
            max_side: self.max_side.min(MAX_IMAGE_SIDE),
            max_pixels: self.max_pixels.min(MAX_IMAGE_PIXELS),
            max_samples: self.max_samples.min(MAX_SAMPLES),
        }
    }

    /// The size `width x height`, checked: both sides at least 1 and at most
    /// `max_side`, and at most `max_pixels` pixels in all, the first of these that fails
    /// being the error.
    ///
    /// # Errors
    /// [`ImageLimitError::Empty`], [`ImageLimitError::SideTooLarge`] or
    /// [`ImageLimitError::TooManyPixels`].
    pub fn check_size(&self, width: u64, height: u64) -> Result<(u32, u32), ImageLimitError> {
        check_not_empty(width, height)?;
        let max_side = u64::from(self.max_side);
        if width > max_side || height > max_side {
            return Err(ImageLimitError::SideTooLarge {
                width,
                height,
                max_side: self.max_side,
            });
        }
        // Both sides are at most a u32's, so the product cannot overflow.
        if width * height > self.max_pixels {
            return Err(ImageLimitError::TooManyPixels {
                width,
                height,
                max_pixels: self.max_pixels,
            });
        }
        // Both sides are at most `max_side`, a u32.
        Ok((
            u32::try_from(width).unwrap_or(u32::MAX),
            u32::try_from(height).unwrap_or(u32::MAX),
        ))
    }

    /// The sample count `samples`, checked: `1..=max_samples`.
    ///
    /// # Errors
    /// [`ImageLimitError::Samples`].
    pub fn check_samples(&self, samples: u64) -> Result<u32, ImageLimitError> {
        u32::try_from(samples)
            .ok()
            .filter(|s| (1..=self.max_samples).contains(s))
            .ok_or(ImageLimitError::Samples {
                samples,
                max_samples: self.max_samples,
            })
    }

    /// The sample count typed as `text` (surrounding spaces allowed), checked as
    /// [`ImageLimits::check_samples`] checks a number.
    ///
    /// # Errors
    /// [`ImageLimitError::SamplesText`] for text that is not a whole number in
    /// `1..=max_samples`.
    pub fn parse_samples(&self, text: &str) -> Result<u32, ImageLimitError> {
        text.trim()
            .parse::<u64>()
            .ok()
            .and_then(|samples| self.check_samples(samples).ok())
            .ok_or(ImageLimitError::SamplesText {
                max_samples: self.max_samples,
            })
    }
}

/// Checks that a `width x height` image has pixels: the one limit every camera obeys
/// (a [`crate::Camera`] of any size above it can be built).
pub(crate) fn check_not_empty(width: u64, height: u64) -> Result<(), ImageLimitError> {
    if width == 0 || height == 0 {
        return Err(ImageLimitError::Empty { width, height });
    }
    Ok(())
}

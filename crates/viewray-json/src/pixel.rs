//! Pixels named in the lecture's 1-based `i`, `j` or in 0-based `row`, `col`, and the
//! sentence for a pixel outside the image.

use std::fmt;

/// How a line names a pixel: 0-based `row`, `col` from the top-left, or the lecture's
/// 1-based `i = row + 1`, `j = col + 1`.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelIndices {
    /// `row`, `col`, from 0.
    #[default]
    ZeroBased,
    /// `i`, `j`, from 1.
    OneBased,
}

impl PixelIndices {
    /// [`PixelIndices::OneBased`] when `one_based`.
    pub fn one_based_if(one_based: bool) -> PixelIndices {
        if one_based {
            PixelIndices::OneBased
        } else {
            PixelIndices::ZeroBased
        }
    }

    /// The JSON keys of the two indices: `["row", "col"]` or `["i", "j"]`.
    pub fn keys(self) -> [&'static str; 2] {
        match self {
            PixelIndices::ZeroBased => ["row", "col"],
            PixelIndices::OneBased => ["i", "j"],
        }
    }

    /// What is added to a 0-based index to print it: 0 or 1.
    pub fn base(self) -> u32 {
        match self {
            PixelIndices::ZeroBased => 0,
            PixelIndices::OneBased => 1,
        }
    }

    /// The 0-based `(row, col)` of the pixel given as `(first, second)` in these
    /// indices, if it lies in a `width x height` image.
    ///
    /// # Errors
    /// [`PixelOutside`] for a pixel outside the image, which names the image and the
    /// valid ranges.
    pub fn pixel(
        self,
        (first, second): (i64, i64),
        width: u32,
        height: u32,
    ) -> Result<(u32, u32), PixelOutside> {
        let base = i64::from(self.base());
        let zero_based = |index: i64, size: u32| {
            index
                .checked_sub(base)
                .and_then(|i| u32::try_from(i).ok())
                .filter(|&i| i < size)
        };
        match (zero_based(first, height), zero_based(second, width)) {
            (Some(row), Some(col)) => Ok((row, col)),
            _ => Err(PixelOutside {
                pixel: (first, second),
                width,
                height,
                indices: self,
            }),
        }
    }
}

/// A pixel outside the image, as [`PixelIndices::pixel`] found it.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct PixelOutside {
    /// The pixel as given, `(row, col)` or `(i, j)` as `indices` says.
    pub pixel: (i64, i64),
    /// The image's columns.
    pub width: u32,
    /// The image's rows.
    pub height: u32,
    /// How the pixel was given.
    pub indices: PixelIndices,
}

impl PixelOutside {
    /// The sentence naming the image and the valid ranges; for a pixel given 0-based,
    /// `to_one_based` says how the reader gives the lecture's `i`, `j` instead (a program
    /// knows its own words for it):
    ///
    /// ```text
    /// pixel 3,9 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 (0-based)
    /// pixel 3,9 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 (0-based; TO_ONE_BASED for the lecture's i, j)
    /// pixel 0,1 is outside the 4 x 3 image: i runs 1..=3 and j 1..=4 (1-based, the lecture's i, j)
    /// ```
    pub fn sentence(&self, to_one_based: Option<&str>) -> String {
        let (first, second) = self.pixel;
        let (width, height) = (self.width, self.height);
        let first_index = u64::from(self.indices.base());
        let last_row = u64::from(height) + first_index - 1;
        let last_col = u64::from(width) + first_index - 1;
        let [row_key, col_key] = self.indices.keys();
        let convention = match (self.indices, to_one_based) {
            (PixelIndices::OneBased, _) => "1-based, the lecture's i, j".to_owned(),
            (PixelIndices::ZeroBased, None) => "0-based".to_owned(),
            (PixelIndices::ZeroBased, Some(switch)) => {
                format!("0-based; {switch} for the lecture's i, j")
            }
        };
        format!(
            "pixel {first},{second} is outside the {width} x {height} image: {row_key} runs \
             {first_index}..={last_row} and {col_key} {first_index}..={last_col} ({convention})"
        )
    }
}

impl fmt::Display for PixelOutside {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(&self.sentence(None))
    }
}

impl std::error::Error for PixelOutside {}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pixels_outside_the_image_are_named_with_the_valid_ranges() {
        let zero = PixelIndices::ZeroBased;
        let one = PixelIndices::OneBased;
        assert_eq!(zero.pixel((2, 3), 4, 3), Ok((2, 3)));
        assert_eq!(one.pixel((3, 4), 4, 3), Ok((2, 3)));
        let outside = zero.pixel((3, 0), 4, 3).unwrap_err();
        assert_eq!(
            outside,
            PixelOutside {
                pixel: (3, 0),
                width: 4,
                height: 3,
                indices: zero
            }
        );
        assert_eq!(
            outside.to_string(),
            "pixel 3,0 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 (0-based)"
        );
        // The reader's own words for the lecture's indices: a flag, a query parameter.
        assert_eq!(
            outside.sentence(Some("--one-based")),
            "pixel 3,0 is outside the 4 x 3 image: row runs 0..=2 and col 0..=3 \
             (0-based; --one-based for the lecture's i, j)"
        );
        let outside = one.pixel((0, 1), 4, 3).unwrap_err();
        assert_eq!(
            outside.sentence(Some("--one-based")),
            "pixel 0,1 is outside the 4 x 3 image: i runs 1..=3 and j 1..=4 \
             (1-based, the lecture's i, j)"
        );
        assert_eq!(outside.sentence(None), outside.to_string());
        assert!(zero.pixel((i64::MIN, 0), 4, 3).is_err());
        assert!(one.pixel((i64::MIN, 1), 4, 3).is_err());
        assert!(zero.pixel((0, i64::MAX), 4, 3).is_err());
        assert!(zero.pixel((i64::MAX, 0), u32::MAX, u32::MAX).is_err());
        assert!(zero.pixel((-1, 0), 4, 3).is_err());
        assert_eq!(
            zero.pixel((i64::from(u32::MAX) - 1, 0), 1, u32::MAX),
            Ok((u32::MAX - 1, 0))
        );
    }
}

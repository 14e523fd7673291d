//! A student's picture: read from untrusted bytes with the decoder's limits, and judged by
//! its camera and its appearance.
//!
//! [`judge_picture`] is the one place this crate judges a picture: the camera with
//! viewray-judge's [`PictureJudge`] (the scene's label maps, the catalogue's entries), the
//! appearance with viewray-compare's FLIP [`Reference`]. When viewray-compare judges
//! both parts itself (camera and a named appearance), this function calls it instead, and
//! nothing else here changes.

use std::io::Cursor;

use image::{ImageFormat, ImageReader, Limits};
use viewray_compare::{Comparison, InstructorThresholds, Reference, RgbaImage};
use viewray_judge::{CameraVerdict, PictureJudge};
use viewray_render::{RenderSettings, render};
use viewray_scene::Scene;

/// The picture formats a student may hand in, as their names say them.
pub const PICTURE_FORMATS: &str =
    "PNG (8 or 16 bits, grey, RGB or RGBA) or PPM/PGM (P2, P3, P5, P6)";
/// The extensions tried, in order, for a picture handed in under another extension.
pub(crate) const PICTURE_EXTENSIONS: [&str; 4] = ["png", "ppm", "pgm", "pnm"];
/// The largest picture file read.
pub const MAX_PICTURE_BYTES: u64 = 64 << 20;

/// Why a student's picture cannot be judged. The message is for the student.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum PictureError {
    /// Neither PNG nor PPM.
    #[error("is not a picture viewray reads: expected {PICTURE_FORMATS}")]
    Format,
    /// Not the scene's size (checked before anything is decoded, so a huge header costs
    /// nothing).
    #[error("is {}x{} pixels, but the scene's image is {}x{}", found.0, found.1, expected.0, expected.1)]
    Size {
        /// The picture's width and height.
        found: (u32, u32),
        /// The scene's.
        expected: (u32, u32),
    },
    /// It does not decode.
    #[error("does not decode: {0}")]
    Decode(String),
}

/// Decodes a student's picture, which must be `expected` (width, height) pixels: its
/// header is read first, and a picture of another size is refused before any pixel is
/// decoded; the decoder may then allocate no more than that size needs.
///
/// # Errors
/// [`PictureError`].
pub fn read_picture(bytes: &[u8], expected: (u32, u32)) -> Result<RgbaImage, PictureError> {
    let format = if bytes.starts_with(b"\x89PNG\r\n\x1a\n") {
        ImageFormat::Png
    } else if bytes.len() >= 2 && bytes[0] == b'P' && matches!(bytes[1], b'2' | b'3' | b'5' | b'6')
    {
        ImageFormat::Pnm
    } else {
        return Err(PictureError::Format);
    };
    let reader = || {
        let mut reader = ImageReader::with_format(Cursor::new(bytes), format);
        let mut limits = Limits::default();
        limits.max_image_width = Some(expected.0);
        limits.max_image_height = Some(expected.1);
        // Sixteen-bit RGBA and its conversion to eight bits, with room to spare.
        limits.max_alloc = Some(u64::from(expected.0) * u64::from(expected.1) * 16 + (1 << 20));
        reader.limits(limits);
        reader
    };
    let found = ImageReader::with_format(Cursor::new(bytes), format)
        .into_dimensions()
        .map_err(|e| PictureError::Decode(e.to_string()))?;
    if found != expected {
        return Err(PictureError::Size { found, expected });
    }
    let image = reader()
        .decode()
        .map_err(|e| PictureError::Decode(e.to_string()))?;
    Ok(image.into_rgba8())
}

/// What a test's pictures are judged against: made once per test, from its scene.
#[derive(Debug)]
pub struct PictureJudges {
    camera: PictureJudge,
    appearance: Reference,
}

impl PictureJudges {
    /// The judges of pictures of `scene`: its cameras (right and mistaken), and its
    /// reference picture, `reference` or else viewray's render of the scene at its own
    /// size and samples.
    ///
    /// # Errors
    /// The render cannot run (its threads cannot start): a sentence.
    pub fn new(scene: &Scene, reference: Option<&RgbaImage>) -> Result<PictureJudges, String> {
        let reference = match reference {
            Some(image) => image.clone(),
            None => render_reference(scene)?,
        };
        Ok(PictureJudges {
            camera: PictureJudge::new(scene),
            appearance: Reference::new(reference, InstructorThresholds::default(), None),
        })
    }

    /// The reference picture.
    pub fn reference(&self) -> &RgbaImage {
        self.appearance.image()
    }
}

/// viewray's picture of `scene`, as `viewray render` makes it.
fn render_reference(scene: &Scene) -> Result<RgbaImage, String> {
    let rendered =
        render(scene, &RenderSettings::default(), |_, _| {}).map_err(|e| e.to_string())?;
    let (width, height) = (rendered.image.width(), rendered.image.height());
    let rgb = rendered.image.to_rgb8();
    let rgba = rgb
        .chunks_exact(3)
        .flat_map(|p| [p[0], p[1], p[2], 255])
        .collect();
    RgbaImage::from_raw(width, height, rgba)
        .ok_or_else(|| "the render has the wrong size".to_owned())
}

/// A picture judged.
#[derive(Clone, Debug)]
pub struct PictureVerdict {
    /// Its camera.
    pub camera: CameraVerdict,
    /// Its appearance against the reference.
    pub appearance: Comparison,
}

/// Judges a student's picture by its camera and its appearance (see the module's doc).
pub fn judge_picture(judges: &PictureJudges, picture: &RgbaImage) -> PictureVerdict {
    PictureVerdict {
        camera: judges.camera.judge(picture),
        appearance: judges.appearance.judge(picture),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn png(width: u32, height: u32) -> Vec<u8> {
        let image = image::RgbImage::from_pixel(width, height, image::Rgb([10, 20, 30]));
        viewray_output::encode_png(&image, viewray_output::Compression::Fast).unwrap()
    }

    /// PNG's CRC-32 (ISO 3309), bit by bit.
    fn crc32(bytes: &[u8]) -> u32 {
        let mut crc = u32::MAX;
        for &byte in bytes {
            crc ^= u32::from(byte);
            for _ in 0..8 {
                crc = if crc & 1 == 1 {
                    (crc >> 1) ^ 0xEDB8_8320
                } else {
                    crc >> 1
                };
            }
        }
        !crc
    }

    #[test]
    fn png_and_ppm_read_the_same_pixels() {
        let from_png = read_picture(&png(3, 2), (3, 2)).unwrap();
        let ppm =
            "P3\n# a comment\n3 2\n255\n10 20 30 10 20 30 10 20 30\n10 20 30 10 20 30 10 20 30\n";
        let from_ppm = read_picture(ppm.as_bytes(), (3, 2)).unwrap();
        assert_eq!(from_png, from_ppm);
        let mut p6 = b"P6 3 2 65535\n".to_vec();
        for _ in 0..6 {
            for v in [10_u16 * 257, 20 * 257, 30 * 257] {
                p6.extend_from_slice(&v.to_be_bytes());
            }
        }
        assert_eq!(read_picture(&p6, (3, 2)).unwrap(), from_png);
    }

    #[test]
    fn a_picture_bomb_is_refused_before_it_is_decoded() {
        // A PNG whose header claims 100 000 x 100 000 pixels (40 GB decoded), its
        // header's checksum right: only the header is read.
        let mut bomb = png(1, 1);
        bomb[16..20].copy_from_slice(&100_000_u32.to_be_bytes());
        bomb[20..24].copy_from_slice(&100_000_u32.to_be_bytes());
        let crc = crc32(&bomb[12..29]);
        bomb[29..33].copy_from_slice(&crc.to_be_bytes());
        assert_eq!(
            read_picture(&bomb, (160, 120)).unwrap_err().to_string(),
            "is 100000x100000 pixels, but the scene's image is 160x120"
        );
        let ppm_bomb = b"P6 200000 200000 255\n";
        assert!(matches!(
            read_picture(ppm_bomb, (160, 120)),
            Err(PictureError::Size { .. })
        ));
    }

    #[test]
    fn other_files_are_named_for_what_is_expected() {
        assert_eq!(
            read_picture(b"GIF89a", (1, 1)).unwrap_err().to_string(),
            "is not a picture viewray reads: expected PNG (8 or 16 bits, grey, RGB or RGBA) or \
             PPM/PGM (P2, P3, P5, P6)"
        );
        let truncated = &png(3, 2)[..40];
        assert!(matches!(
            read_picture(truncated, (3, 2)),
            Err(PictureError::Decode(_))
        ));
    }
}

//! Rendered images: linear RGB in `f32`, encoded to 8-bit sRGB PNG or to linear EXR.

use std::io::{Seek, Write};
use std::path::Path;

use glam::Vec3;
use image::codecs::openexr::OpenExrEncoder;
use image::{ExtendedColorType, ImageEncoder, RgbImage};
use viewray_output::{Compression, linear_to_srgb8, unit_to_u8};

/// What an image's values mean, which decides how 8-bit output stores them.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum PixelKind {
    /// Linear-light colour (Flat and Lit renders): 8-bit output applies the sRGB transfer
    /// function, so linear 0.5 is stored as 188.
    #[default]
    Color,
    /// Data in `[0, 1]` (Normals and Depth renders): 8-bit output stores `value * 255`
    /// as is, so a normal `(0, 0, 1)` is the usual normal-map `(128, 128, 255)`.
    Data,
}

impl PixelKind {
    /// The 8 bits per channel PNG output stores for the value `value`: sRGB-encoded
    /// ([`linear_to_srgb8`]) for [`PixelKind::Color`], `round(255 x)` ([`unit_to_u8`])
    /// for [`PixelKind::Data`], each channel clamped to `[0, 1]` first.
    pub fn to_rgb8(self, value: Vec3) -> [u8; 3] {
        value.to_array().map(self.encoder())
    }

    /// The encoding of one channel.
    fn encoder(self) -> fn(f32) -> u8 {
        match self {
            PixelKind::Color => linear_to_srgb8,
            PixelKind::Data => unit_to_u8,
        }
    }
}

/// The file formats an [`Image`] can be written as.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum ImageFormat {
    /// 8-bit RGB PNG, sRGB-encoded colour (see [`PixelKind`]), written with fixed
    /// encoder settings and no metadata, so the same image always gives the same bytes.
    Png,
    /// OpenEXR with 32-bit float RGB channels: the linear values as rendered, for
    /// post-processing.
    Exr,
}

impl ImageFormat {
    /// The format named by a path's extension (`.png` or `.exr`, any case).
    pub fn from_path(path: &Path) -> Option<ImageFormat> {
        let extension = path.extension()?.to_str()?.to_ascii_lowercase();
        match extension.as_str() {
            "png" => Some(ImageFormat::Png),
            "exr" => Some(ImageFormat::Exr),
            _ => None,
        }
    }
}

/// Why an image could not be written.
#[derive(Debug, thiserror::Error)]
#[error("cannot encode the image: {0}")]
pub struct ImageError(#[from] std::io::Error);

impl From<image::ImageError> for ImageError {
    fn from(error: image::ImageError) -> Self {
        match error {
            image::ImageError::IoError(error) => ImageError(error),
            other => ImageError(std::io::Error::other(other)),
        }
    }
}

/// A rendered image: `width x height` pixels of linear RGB, row by row from the top.
#[derive(Clone, Debug, PartialEq)]
pub struct Image {
    width: u32,
    height: u32,
    pixels: Vec<Vec3>,
    kind: PixelKind,
}

impl Image {
    /// An image of `width x height` pixels, all `fill`.
    pub fn new(width: u32, height: u32, fill: Vec3, kind: PixelKind) -> Self {
        Self {
            width,
            height,
            pixels: vec![fill; width as usize * height as usize],
            kind,
        }
    }

    /// An image from its pixels, row by row from the top.
    ///
    /// # Panics
    /// If `pixels.len()` is not `width * height`.
    pub fn from_pixels(width: u32, height: u32, pixels: Vec<Vec3>, kind: PixelKind) -> Self {
        assert_eq!(
            pixels.len(),
            width as usize * height as usize,
            "an image of {width} x {height} needs that many pixels"
        );
        Self {
            width,
            height,
            pixels,
            kind,
        }
    }

    /// The number of columns.
    pub fn width(&self) -> u32 {
        self.width
    }

    /// The number of rows.
    pub fn height(&self) -> u32 {
        self.height
    }

    /// What the values mean.
    pub fn kind(&self) -> PixelKind {
        self.kind
    }

    /// Every pixel, row by row from the top.
    pub fn pixels(&self) -> &[Vec3] {
        &self.pixels
    }

    /// The pixel at `(row, col)`, 0-based from the top-left.
    ///
    /// # Panics
    /// If the pixel is outside the image.
    pub fn pixel(&self, row: u32, col: u32) -> Vec3 {
        assert!(
            row < self.height && col < self.width,
            "pixel outside the image"
        );
        self.pixels[row as usize * self.width as usize + col as usize]
    }

    /// Every pixel as 8-bit sRGB, `[r, g, b]` row by row, whatever the [`PixelKind`]:
    /// each channel clamped to `[0, 1]` and encoded by
    /// [`linear_to_srgb8`].
    pub fn to_srgb8(&self) -> Vec<u8> {
        self.to_bytes(linear_to_srgb8)
    }

    /// Every pixel as 8 bits per channel, as PNG output stores it: sRGB-encoded for
    /// [`PixelKind::Color`], `round(255 x)` for [`PixelKind::Data`].
    pub fn to_rgb8(&self) -> Vec<u8> {
        self.to_bytes(self.kind.encoder())
    }

    fn to_bytes(&self, encode: fn(f32) -> u8) -> Vec<u8> {
        self.pixels
            .iter()
            .flat_map(|p| p.to_array().map(encode))
            .collect()
    }

    /// The image as 8-bit pixels, as PNG output stores them ([`Image::to_rgb8`]).
    pub fn to_rgb_image(&self) -> RgbImage {
        RgbImage::from_raw(self.width, self.height, self.to_rgb8())
            .expect("an image holds width x height pixels")
    }

    /// Writes the image as a PNG (see [`ImageFormat::Png`]) with viewray's one PNG
    /// encoder ([`viewray_output::write_png`], balanced compression).
    ///
    /// # Errors
    /// An [`ImageError`] if encoding or writing fails.
    pub fn write_png(&self, out: impl Write) -> Result<(), ImageError> {
        self.write_png_compressed(out, Compression::Balanced)
    }

    /// [`Image::write_png`] with the given compression (which changes the file's size,
    /// never its pixels).
    ///
    /// # Errors
    /// An [`ImageError`] if encoding or writing fails.
    pub fn write_png_compressed(
        &self,
        out: impl Write,
        compression: Compression,
    ) -> Result<(), ImageError> {
        viewray_output::write_png(out, &self.to_rgb_image(), compression)?;
        Ok(())
    }

    /// Writes the image as an OpenEXR file of linear float RGB (see [`ImageFormat::Exr`]).
    ///
    /// # Errors
    /// An [`ImageError`] if encoding or writing fails.
    pub fn write_exr(&self, out: impl Write + Seek) -> Result<(), ImageError> {
        let bytes: Vec<u8> = self
            .pixels
            .iter()
            .flat_map(|p| p.to_array())
            .flat_map(f32::to_ne_bytes)
            .collect();
        OpenExrEncoder::new(out).write_image(
            &bytes,
            self.width,
            self.height,
            ExtendedColorType::Rgb32F,
        )?;
        Ok(())
    }

    /// Writes the image in `format`.
    ///
    /// # Errors
    /// An [`ImageError`] if encoding or writing fails.
    pub fn write(&self, out: impl Write + Seek, format: ImageFormat) -> Result<(), ImageError> {
        match format {
            ImageFormat::Png => self.write_png(out),
            ImageFormat::Exr => self.write_exr(out),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn data_images_store_values_as_is() {
        let image = Image::from_pixels(
            2,
            1,
            vec![Vec3::new(0.5, 0.5, 1.0), Vec3::new(0.0, 0.25, 2.0)],
            PixelKind::Data,
        );
        assert_eq!(image.to_rgb8(), [128, 128, 255, 0, 64, 255]);
        assert_eq!(image.to_srgb8()[..3], [188, 188, 255]);
    }

    #[test]
    fn formats_follow_the_extension() {
        assert_eq!(
            ImageFormat::from_path(Path::new("a/b.PNG")),
            Some(ImageFormat::Png)
        );
        assert_eq!(
            ImageFormat::from_path(Path::new("b.exr")),
            Some(ImageFormat::Exr)
        );
        assert_eq!(ImageFormat::from_path(Path::new("b.jpg")), None);
        assert_eq!(ImageFormat::from_path(Path::new("png")), None);
    }

    #[test]
    fn png_and_exr_round_trip() {
        let image = Image::from_pixels(
            3,
            2,
            (0..6).map(|i| Vec3::splat(i as f32 / 5.0)).collect(),
            PixelKind::Color,
        );
        let mut png = Vec::new();
        image.write_png(&mut png).unwrap();
        let decoded = image::load_from_memory(&png).unwrap().to_rgb8();
        assert_eq!(decoded.dimensions(), (3, 2));
        assert_eq!(decoded.into_raw(), image.to_srgb8());

        let mut exr = std::io::Cursor::new(Vec::new());
        image.write_exr(&mut exr).unwrap();
        let decoded = image::load_from_memory(exr.get_ref()).unwrap().to_rgb32f();
        let values: Vec<f32> = decoded.into_raw();
        assert_eq!(values[9..12], [0.6, 0.6, 0.6]);
    }
}

//! The student's picture and the files a student's program writes: PPM (P6, P3, 16-bit),
//! PGM (P5, P2) and PNG (8-bit RGB, 16-bit RGB, grey), as the Netpbm and PNG
//! specifications spell them.

use std::io::Cursor;
use std::path::Path;

/// An image of encoded values in [0, 1], row by row from the top, each row from the left.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Picture {
    /// Columns.
    pub(crate) width: u32,
    /// Rows.
    pub(crate) height: u32,
    /// `width * height` RGB values, already encoded (sRGB, or not, as rendered).
    pub(crate) values: Vec<[f64; 3]>,
}

/// A file format a student may write.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Format {
    /// Binary PPM, 8 bits.
    PpmP6,
    /// ASCII PPM, 8 bits, with a comment line.
    PpmP3,
    /// Binary PPM with maxval 65535 (big-endian 16-bit samples).
    Ppm16,
    /// Binary PGM, 8 bits, grey.
    PgmP5,
    /// ASCII PGM, 8 bits, grey, with a comment line.
    PgmP2,
    /// PNG, 8-bit RGB.
    Png,
    /// PNG, 16-bit RGB.
    Png16,
    /// PNG, 8-bit grey.
    PngGrey,
}

impl Format {
    /// Every format.
    pub(crate) const ALL: [Format; 8] = [
        Format::PpmP6,
        Format::PpmP3,
        Format::Ppm16,
        Format::PgmP5,
        Format::PgmP2,
        Format::Png,
        Format::Png16,
        Format::PngGrey,
    ];

    /// The file name's extension.
    pub(crate) fn extension(self) -> &'static str {
        match self {
            Format::PpmP6 | Format::PpmP3 | Format::Ppm16 => "ppm",
            Format::PgmP5 | Format::PgmP2 => "pgm",
            Format::Png | Format::Png16 | Format::PngGrey => "png",
        }
    }
}

impl Picture {
    /// The 8-bit RGB values, `round(255 x)`, three bytes a pixel.
    pub(crate) fn rgb8(&self) -> Vec<u8> {
        self.values
            .iter()
            .flatten()
            .map(|&x| quantize(x, 255.0) as u8)
            .collect()
    }

    /// The 16-bit RGB values, `round(65535 x)`, three a pixel.
    pub(crate) fn rgb16(&self) -> Vec<u16> {
        self.values
            .iter()
            .flatten()
            .map(|&x| quantize(x, 65535.0) as u16)
            .collect()
    }

    /// The 8-bit grey values (Rec. 709 weights of the encoded values), one a pixel.
    pub(crate) fn grey8(&self) -> Vec<u8> {
        self.values
            .iter()
            .map(|&[r, g, b]| quantize(0.2126 * r + 0.7152 * g + 0.0722 * b, 255.0) as u8)
            .collect()
    }

    /// The 8-bit RGB value of pixel `(row, col)`.
    pub(crate) fn pixel8(&self, row: u32, col: u32) -> [u8; 3] {
        let i = (row * self.width + col) as usize;
        self.values[i].map(|x| quantize(x, 255.0) as u8)
    }

    /// The file's bytes in `format`.
    pub(crate) fn encode(&self, format: Format) -> Vec<u8> {
        let (w, h) = (self.width, self.height);
        match format {
            Format::PpmP6 => {
                let mut bytes = format!("P6\n{w} {h}\n255\n").into_bytes();
                bytes.extend(self.rgb8());
                bytes
            }
            Format::Ppm16 => {
                let mut bytes = format!("P6\n{w} {h}\n65535\n").into_bytes();
                bytes.extend(self.rgb16().iter().flat_map(|s| s.to_be_bytes()));
                bytes
            }
            Format::PgmP5 => {
                let mut bytes = format!("P5\n{w} {h}\n255\n").into_bytes();
                bytes.extend(self.grey8());
                bytes
            }
            Format::PpmP3 => ascii("P3", w, h, &self.rgb8()),
            Format::PgmP2 => ascii("P2", w, h, &self.grey8()),
            Format::Png => png(image::RgbImage::from_raw(w, h, self.rgb8())),
            Format::Png16 => png(image::ImageBuffer::<image::Rgb<u16>, _>::from_raw(
                w,
                h,
                self.rgb16(),
            )),
            Format::PngGrey => png(image::GrayImage::from_raw(w, h, self.grey8())),
        }
    }

    /// Writes the picture to `path` in `format`.
    ///
    /// # Panics
    ///
    /// If the file cannot be written.
    pub(crate) fn write(&self, path: &Path, format: Format) {
        std::fs::write(path, self.encode(format))
            .unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
    }
}

fn quantize(x: f64, max: f64) -> f64 {
    (x.clamp(0.0, 1.0) * max).round()
}

/// A plain (ASCII) Netpbm file: the magic number, a comment, the size, maxval 255, then
/// the samples in lines of at most 70 characters.
fn ascii(magic: &str, width: u32, height: u32, samples: &[u8]) -> Vec<u8> {
    let mut text = format!("{magic}\n# written by a student's ray tracer\n{width} {height}\n255\n");
    let mut line = String::new();
    for sample in samples {
        let word = sample.to_string();
        if !line.is_empty() && line.len() + 1 + word.len() > 70 {
            text.push_str(&line);
            text.push('\n');
            line.clear();
        }
        if !line.is_empty() {
            line.push(' ');
        }
        line.push_str(&word);
    }
    text.push_str(&line);
    text.push('\n');
    text.into_bytes()
}

fn png<P, C>(image: Option<image::ImageBuffer<P, C>>) -> Vec<u8>
where
    P: image::Pixel + image::PixelWithColorType,
    [P::Subpixel]: image::EncodableLayout,
    C: std::ops::Deref<Target = [P::Subpixel]>,
{
    let image = image.expect("the buffer holds width x height pixels");
    let mut bytes = Cursor::new(Vec::new());
    image
        .write_to(&mut bytes, image::ImageFormat::Png)
        .expect("a PNG encodes in memory");
    bytes.into_inner()
}

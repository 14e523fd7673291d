//! Animations: looping GIF and animated PNG (APNG), written frame by frame, deterministic.
//!
//! Both writers take 8-bit sRGB frames of one size in order and stream them out, so an
//! animation never needs more memory than a frame or two, and both loop forever. Like the
//! [PNG encoder](crate::png), they write no time or text: the same frames always give the
//! same bytes.
//!
//! - [`ApngWriter`]: an animated PNG, every frame lossless (RGB, 8 bits a channel), each
//!   shown for exactly `1 / fps` s. Viewers that know only PNG show the first frame.
//! - [`GifWriter`]: a GIF with one global palette of 256 colours for every frame,
//!   computed by NeuQuant ([`GifPalette::from_frames`]) from frames that span the
//!   animation, so a colour does not flicker from frame to frame as it would with a
//!   palette per frame. A colour the palette holds (a flat background, a line) is kept;
//!   any other takes the palette colour nearest to it after an ordered (Bayer) dither,
//!   which breaks smooth shading's bands and, being tied to the pixel, does not shimmer
//!   over a still background as error diffusion would. GIF counts delays in hundredths of a second:
//!   frame `k` is shown `round(100 (k + 1) / fps) - round(100 k / fps)` of them (4 and 5
//!   alternating at 24 fps, exact on average), at least 2, since browsers slow anything
//!   shorter; so a GIF plays at most 50 frames per second.

use std::collections::HashMap;
use std::io::{self, Write};
use std::sync::Arc;

use color_quant::NeuQuant;
use image::RgbImage;

/// An ordered dither: the 4 x 4 Bayer matrix less its mean, in 8-bit steps (-8 to 7),
/// added to each channel before the nearest palette colour is chosen. It depends on the
/// pixel alone, so a still part of the picture dithers the same way in every frame and
/// does not shimmer, while smooth shading no longer breaks into bands.
const BAYER: [[i16; 4]; 4] = [
    [-8, 0, -6, 2],
    [4, -4, 6, -2],
    [-5, 3, -7, 1],
    [7, -1, 5, -3],
];

/// The largest side of a GIF, in pixels (the format stores sides in 16 bits).
pub const MAX_GIF_SIDE: u32 = u16::MAX as u32;

/// The palette every frame of a GIF uses: 256 colours chosen by NeuQuant.
#[derive(Clone)]
pub struct GifPalette {
    quantizer: Arc<NeuQuant>,
}

impl std::fmt::Debug for GifPalette {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("GifPalette")
            .field("colors", &(self.quantizer.color_map_rgb().len() / 3))
            .finish()
    }
}

impl GifPalette {
    /// The palette NeuQuant learns from `frames` (say the first, middle and last of an
    /// animation): every pixel of them, its sampling factor 10 (one pixel in ten, in
    /// NeuQuant's fixed order, so the palette is the same on every run).
    ///
    /// # Panics
    /// If `frames` is empty.
    pub fn from_frames(frames: &[&RgbImage]) -> GifPalette {
        assert!(!frames.is_empty(), "a palette needs at least one frame");
        let rgba: Vec<u8> = frames
            .iter()
            .flat_map(|frame| frame.pixels())
            .flat_map(|p| [p[0], p[1], p[2], 255])
            .collect();
        GifPalette {
            quantizer: Arc::new(NeuQuant::new(10, 256, &rgba)),
        }
    }

    /// The palette's colours as `[r, g, b, r, g, b, ..]`.
    pub fn colors(&self) -> Vec<u8> {
        self.quantizer.color_map_rgb()
    }
}

/// Writes a looping GIF frame by frame: [`GifWriter::new`], [`GifWriter::write_frame`]
/// for each frame in order, [`GifWriter::finish`].
pub struct GifWriter<W: Write> {
    encoder: gif::Encoder<W>,
    quantizer: Quantizer,
    width: u16,
    height: u16,
    fps: u32,
    written: u32,
}

impl<W: Write> GifWriter<W> {
    /// Starts a GIF of `width x height` frames, shown at `fps` frames per second and
    /// looping forever, with `palette` for every frame.
    ///
    /// # Errors
    /// `InvalidInput` for a side of 0 or more than [`MAX_GIF_SIDE`], or `fps` 0; any error
    /// of `out`.
    pub fn new(
        out: W,
        width: u32,
        height: u32,
        fps: u32,
        palette: GifPalette,
    ) -> io::Result<GifWriter<W>> {
        let side = |side: u32| {
            u16::try_from(side).ok().filter(|&s| s > 0).ok_or_else(|| {
                invalid(format!(
                    "a GIF is 1 to {MAX_GIF_SIDE} pixels a side, not {width} x {height}"
                ))
            })
        };
        let (w, h) = (side(width)?, side(height)?);
        if fps == 0 {
            return Err(invalid(
                "a GIF needs at least 1 frame per second".to_owned(),
            ));
        }
        let mut encoder = gif::Encoder::new(out, w, h, &palette.colors()).map_err(gif_error)?;
        encoder
            .set_repeat(gif::Repeat::Infinite)
            .map_err(gif_error)?;
        Ok(GifWriter {
            encoder,
            quantizer: Quantizer {
                palette,
                indices: HashMap::new(),
                exact: HashMap::new(),
            },
            width: w,
            height: h,
            fps,
            written: 0,
        })
    }

    /// How long frame `k` is shown, in hundredths of a second (see the
    /// [module](self)).
    fn delay(&self, k: u32) -> u16 {
        let at = |k: u32| (100 * u64::from(k) + u64::from(self.fps) / 2) / u64::from(self.fps);
        let delay = (at(k + 1) - at(k)).max(2);
        u16::try_from(delay).unwrap_or(u16::MAX)
    }

    /// Appends `frame`, each pixel as the nearest colour of the palette.
    ///
    /// # Errors
    /// `InvalidInput` for a frame of another size; any error of the output.
    pub fn write_frame(&mut self, frame: &RgbImage) -> io::Result<()> {
        if frame.dimensions() != (u32::from(self.width), u32::from(self.height)) {
            return Err(invalid(format!(
                "a frame of {} x {} in a GIF of {} x {}",
                frame.width(),
                frame.height(),
                self.width,
                self.height
            )));
        }
        let indices = self.quantizer.indices(frame);
        let gif_frame = gif::Frame {
            delay: self.delay(self.written),
            width: self.width,
            height: self.height,
            buffer: indices.into(),
            ..gif::Frame::default()
        };
        self.encoder.write_frame(&gif_frame).map_err(gif_error)?;
        self.written += 1;
        Ok(())
    }

    /// Ends the file and returns the output.
    ///
    /// # Errors
    /// `InvalidInput` if no frame was written; any error of the output.
    pub fn finish(self) -> io::Result<W> {
        if self.written == 0 {
            return Err(invalid("a GIF needs at least one frame".to_owned()));
        }
        self.encoder.into_inner().map_err(gif_error)
    }
}

/// Frames to palette indices. Not generic, so that it is compiled (and optimized) here
/// whatever writer the caller's [`GifWriter`] holds.
struct Quantizer {
    palette: GifPalette,
    /// Palette indices already looked up, by (dithered) colour: most colours repeat.
    indices: HashMap<[u8; 3], u8>,
    /// For each colour met, its palette index when the palette holds it (no dither).
    exact: HashMap<[u8; 3], Option<u8>>,
}

impl Quantizer {
    /// The palette index of each pixel of `frame`, row by row.
    fn indices(&mut self, frame: &RgbImage) -> Vec<u8> {
        let quantizer = &self.palette.quantizer;
        let nearest = |rgb: [u8; 3]| {
            let index = quantizer.index_of(&[rgb[0], rgb[1], rgb[2], 255]);
            u8::try_from(index).expect("a palette of 256 colours")
        };
        frame
            .enumerate_pixels()
            .map(|(x, y, p)| {
                // A colour the palette holds (to within 2 steps), as flat backgrounds
                // are, is kept as it is; others are dithered towards their neighbours.
                let exact = *self.exact.entry(p.0).or_insert_with(|| {
                    let index = nearest(p.0);
                    let close = quantizer
                        .lookup(usize::from(index))
                        .is_some_and(|q| (0..3).all(|c| q[c].abs_diff(p.0[c]) <= 2));
                    close.then_some(index)
                });
                exact.unwrap_or_else(|| {
                    let offset = BAYER[(y % 4) as usize][(x % 4) as usize];
                    let rgb = p.0.map(|c| (i16::from(c) + offset).clamp(0, 255) as u8);
                    *self.indices.entry(rgb).or_insert_with(|| nearest(rgb))
                })
            })
            .collect()
    }
}

/// Writes a looping animated PNG frame by frame: [`ApngWriter::new`] with the number of
/// frames, [`ApngWriter::write_frame`] for each in order, [`ApngWriter::finish`].
pub struct ApngWriter<W: Write> {
    writer: png::Writer<W>,
    width: u32,
    height: u32,
    frames: u32,
    written: u32,
}

impl<W: Write> ApngWriter<W> {
    /// Starts an APNG of `frames` frames of `width x height`, each shown `1 / fps` s,
    /// looping forever.
    ///
    /// # Errors
    /// `InvalidInput` for an empty size, no frames, or `fps` outside 1 to 65535; any error
    /// of `out`.
    pub fn new(
        out: W,
        width: u32,
        height: u32,
        frames: u32,
        fps: u32,
    ) -> io::Result<ApngWriter<W>> {
        if width == 0 || height == 0 || frames == 0 {
            return Err(invalid(format!(
                "an animated PNG needs at least one frame of at least 1 x 1 pixels, not {frames} \
                 of {width} x {height}"
            )));
        }
        let fps = u16::try_from(fps)
            .ok()
            .filter(|&f| f > 0)
            .ok_or_else(|| invalid(format!("{fps} frames per second")))?;
        let mut encoder = png::Encoder::new(out, width, height);
        encoder.set_color(png::ColorType::Rgb);
        encoder.set_depth(png::BitDepth::Eight);
        encoder.set_compression(png::Compression::Balanced);
        encoder.set_animated(frames, 0).map_err(png_error)?;
        encoder.set_frame_delay(1, fps).map_err(png_error)?;
        let writer = encoder.write_header().map_err(png_error)?;
        Ok(ApngWriter {
            writer,
            width,
            height,
            frames,
            written: 0,
        })
    }

    /// Appends `frame`.
    ///
    /// # Errors
    /// `InvalidInput` for a frame of another size or one too many; any error of the
    /// output.
    pub fn write_frame(&mut self, frame: &RgbImage) -> io::Result<()> {
        if frame.dimensions() != (self.width, self.height) {
            return Err(invalid(format!(
                "a frame of {} x {} in an animated PNG of {} x {}",
                frame.width(),
                frame.height(),
                self.width,
                self.height
            )));
        }
        if self.written == self.frames {
            return Err(invalid(format!(
                "frame {} of an animated PNG of {} frames",
                self.written + 1,
                self.frames
            )));
        }
        self.writer
            .write_image_data(frame.as_raw())
            .map_err(png_error)?;
        self.written += 1;
        Ok(())
    }

    /// Ends the file.
    ///
    /// # Errors
    /// `InvalidInput` if fewer frames were written than announced; any error of the
    /// output.
    pub fn finish(self) -> io::Result<()> {
        if self.written < self.frames {
            return Err(invalid(format!(
                "an animated PNG of {} frames ended after {}",
                self.frames, self.written
            )));
        }
        self.writer.finish().map_err(png_error)
    }
}

fn invalid(message: String) -> io::Error {
    io::Error::new(io::ErrorKind::InvalidInput, message)
}

fn gif_error(error: gif::EncodingError) -> io::Error {
    match error {
        gif::EncodingError::Io(error) => error,
        other => invalid(other.to_string()),
    }
}

fn png_error(error: png::EncodingError) -> io::Error {
    match error {
        png::EncodingError::IoError(error) => error,
        other => invalid(other.to_string()),
    }
}

#[cfg(test)]
mod tests {
    use image::{AnimationDecoder as _, Rgb};

    use super::*;

    /// Three frames: a red square moving over a sky-blue background.
    fn frames() -> Vec<RgbImage> {
        (0..3)
            .map(|k| {
                RgbImage::from_fn(40, 30, |x, y| {
                    if (10 * k..10 * k + 10).contains(&x) && (10..20).contains(&y) {
                        Rgb([200, 30, 20])
                    } else {
                        Rgb([140, 180, 230])
                    }
                })
            })
            .collect()
    }

    fn gif_bytes(frames: &[RgbImage], fps: u32) -> Vec<u8> {
        let palette = GifPalette::from_frames(&frames.iter().collect::<Vec<_>>());
        let mut writer = GifWriter::new(Vec::new(), 40, 30, fps, palette).unwrap();
        for frame in frames {
            writer.write_frame(frame).unwrap();
        }
        writer.finish().unwrap()
    }

    #[test]
    fn a_gif_holds_every_frame_with_its_colours_and_delays() {
        let frames = frames();
        let bytes = gif_bytes(&frames, 24);
        assert_eq!(
            bytes,
            gif_bytes(&frames, 24),
            "the same frames, the same bytes"
        );
        let mut options = gif::DecodeOptions::new();
        options.set_color_output(gif::ColorOutput::RGBA);
        let mut decoder = options.read_info(io::Cursor::new(&bytes)).unwrap();
        let mut decoded = Vec::new();
        while let Some(frame) = decoder.read_next_frame().unwrap() {
            decoded.push((frame.delay, frame.buffer.to_vec()));
        }
        // 100 / 24 hundredths: 4, 4, 5 (at 0, 4, 8, 13 cumulative).
        let delays: Vec<u16> = decoded.iter().map(|(delay, _)| *delay).collect();
        assert_eq!(delays, [4, 4, 5]);
        // Each pixel within the dither's reach (8 steps) of its colour, and the palette's.
        for ((_, rgba), expected) in decoded.iter().zip(&frames) {
            for (got, want) in rgba.chunks_exact(4).zip(expected.pixels()) {
                for c in 0..3 {
                    assert!(got[c].abs_diff(want[c]) <= 12, "{got:?} vs {want:?}");
                }
            }
        }
        // The loop marker (NETSCAPE2.0 application extension) is there.
        assert!(bytes.windows(11).any(|w| w == b"NETSCAPE2.0"));
    }

    #[test]
    fn gif_delays_average_exactly_and_never_fall_below_two_hundredths() {
        let palette = GifPalette::from_frames(&[&frames()[0]]);
        let writer = GifWriter::new(Vec::new(), 40, 30, 24, palette.clone()).unwrap();
        let total: u32 = (0..24).map(|k| u32::from(writer.delay(k))).sum();
        assert_eq!(total, 100);
        let fast = GifWriter::new(Vec::new(), 40, 30, 100, palette).unwrap();
        assert!((0..10).all(|k| fast.delay(k) == 2));
    }

    #[test]
    fn an_apng_holds_every_frame_exactly() {
        let frames = frames();
        let encode = || {
            let mut bytes = Vec::new();
            let mut writer = ApngWriter::new(&mut bytes, 40, 30, 3, 12).unwrap();
            for frame in &frames {
                writer.write_frame(frame).unwrap();
            }
            writer.finish().unwrap();
            bytes
        };
        let bytes = encode();
        assert_eq!(bytes, encode());
        let decoder = image::codecs::png::PngDecoder::new(io::Cursor::new(&bytes)).unwrap();
        assert!(decoder.is_apng().unwrap());
        let decoded = decoder
            .apng()
            .unwrap()
            .into_frames()
            .collect_frames()
            .unwrap();
        assert_eq!(decoded.len(), 3);
        for (frame, expected) in decoded.iter().zip(&frames) {
            let (numer, denom) = frame.delay().numer_denom_ms();
            assert_eq!(numer * 12, denom * 1000, "1/12 s");
            let rgb = image::DynamicImage::ImageRgba8(frame.buffer().clone()).to_rgb8();
            assert_eq!(&rgb, expected);
        }
    }

    #[test]
    fn wrong_sizes_and_counts_are_refused() {
        let palette = GifPalette::from_frames(&[&frames()[0]]);
        assert!(GifWriter::new(Vec::new(), 70_000, 10, 24, palette.clone()).is_err());
        assert!(GifWriter::new(Vec::new(), 40, 30, 0, palette.clone()).is_err());
        let mut gif = GifWriter::new(Vec::new(), 41, 30, 24, palette.clone()).unwrap();
        assert_eq!(
            gif.write_frame(&frames()[0]).unwrap_err().kind(),
            io::ErrorKind::InvalidInput
        );
        let empty = GifWriter::new(Vec::new(), 40, 30, 24, palette).unwrap();
        assert!(empty.finish().is_err());
        assert!(ApngWriter::new(Vec::new(), 40, 30, 0, 24).is_err());
        let mut apng = ApngWriter::new(Vec::new(), 40, 30, 2, 24).unwrap();
        apng.write_frame(&frames()[0]).unwrap();
        assert!(apng.finish().is_err(), "one frame short");
    }
}

//! A movie's frames rendered in order and handed to viewray-output's encoders, timed;
//! each frame is encoded while the next one renders.

use std::collections::HashMap;
use std::io::{self, Write};
use std::time::{Duration, Instant};

use image::RgbImage;
use viewray_output::{ApngWriter, GifPalette, GifWriter};
use viewray_render::{RenderError, RenderSettings};

use crate::Movie;

/// How long a movie took: rendering (and laying out) its frames, and encoding and
/// writing them. The two overlap (a frame is encoded while the next one renders), so
/// together they may add up to more than the time the movie took.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct Timings {
    /// Rendering the pictures, drawing the side views and laying out the frames.
    pub render: Duration,
    /// Choosing the palette, encoding the frames and writing them out.
    pub encode: Duration,
}

/// Why a movie could not be written.
#[derive(Debug, thiserror::Error)]
pub enum EncodeError {
    /// A frame could not be rendered.
    #[error(transparent)]
    Render(#[from] RenderError),
    /// The encoder or the output failed.
    #[error(transparent)]
    Io(#[from] io::Error),
}

/// Frames rendered in the order they are asked for, a few kept ahead (the GIF palette's),
/// each reported to `on_frame` when rendered.
struct Frames<'a, F: FnMut()> {
    movie: &'a Movie,
    settings: &'a RenderSettings,
    kept: HashMap<u32, RgbImage>,
    timings: Timings,
    on_frame: F,
}

impl<F: FnMut()> Frames<'_, F> {
    fn render(&mut self, k: u32) -> Result<RgbImage, RenderError> {
        let started = Instant::now();
        let frame = self.movie.render_frame(k, self.settings)?;
        self.timings.render += started.elapsed();
        (self.on_frame)();
        Ok(frame)
    }

    /// Frame `k`: the one kept, or rendered now.
    fn take(&mut self, k: u32) -> Result<RgbImage, RenderError> {
        match self.kept.remove(&k) {
            Some(frame) => Ok(frame),
            None => self.render(k),
        }
    }

    /// Runs `encode` on this thread while frame `next` (if any, and not kept) renders on
    /// the thread pool, and returns frame `next`.
    ///
    /// A frame's render leaves threads idle at its end (its last tiles, then laying out
    /// the frame on one thread) and encoding ran on one thread between renders; side by
    /// side, each fills the other's gaps. The frames are the same: a frame's pixels
    /// depend on the scene and its number alone, and they are encoded in order.
    fn encode_while_rendering(
        &mut self,
        next: Option<u32>,
        encode: impl FnOnce() -> io::Result<()>,
    ) -> Result<Option<RgbImage>, EncodeError> {
        let Some(k) = next.filter(|k| !self.kept.contains_key(k)) else {
            self.encoding(encode)?;
            return Ok(next.map(|k| self.take(k)).transpose()?);
        };
        let (movie, settings) = (self.movie, self.settings);
        let mut rendered = None;
        let (encoded, encode_time) = rayon::in_place_scope(|scope| {
            scope.spawn(|_| {
                let started = Instant::now();
                rendered = Some((movie.render_frame(k, settings), started.elapsed()));
            });
            let started = Instant::now();
            (encode(), started.elapsed())
        });
        self.timings.encode += encode_time;
        let (frame, render_time) = rendered.expect("the scope waits for its render");
        self.timings.render += render_time;
        encoded?;
        let frame = frame?;
        (self.on_frame)();
        Ok(Some(frame))
    }

    /// Runs `encode`, adding its time to the encoding's.
    fn encoding<T>(&mut self, encode: impl FnOnce() -> io::Result<T>) -> io::Result<T> {
        let started = Instant::now();
        let result = encode();
        self.timings.encode += started.elapsed();
        result
    }
}

/// Hands the frames of `movie` to `write` in order, frame `k` while frame `k + 1`
/// renders ([`Frames::encode_while_rendering`]).
fn write_in_order<F: FnMut()>(
    frames: &mut Frames<'_, F>,
    mut write: impl FnMut(u32, &RgbImage) -> io::Result<()>,
) -> Result<(), EncodeError> {
    let n = frames.movie.frames();
    let mut frame = frames.take(0)?;
    for k in 0..n {
        let next = (k + 1 < n).then_some(k + 1);
        if let Some(rendered) = frames.encode_while_rendering(next, || write(k, &frame))? {
            frame = rendered;
        }
    }
    Ok(())
}

/// Writes `movie` to `out` as a looping GIF (viewray-output's [`GifWriter`]), its one
/// palette learnt from the first, middle and last frames, which are rendered first;
/// `on_frame` is called after each frame is rendered. Returns the output and the
/// timings.
///
/// # Errors
/// [`EncodeError`] if a frame cannot be rendered or written.
pub fn write_gif<W: Write>(
    movie: &Movie,
    out: W,
    settings: &RenderSettings,
    on_frame: impl FnMut(),
) -> Result<(W, Timings), EncodeError> {
    let mut frames = Frames {
        movie,
        settings,
        kept: HashMap::new(),
        timings: Timings::default(),
        on_frame,
    };
    let n = movie.frames();
    let mut samples = vec![0, n / 2, n - 1];
    samples.dedup();
    for &k in &samples {
        let frame = frames.render(k)?;
        frames.kept.insert(k, frame);
    }
    let (width, height) = movie.frame_size();
    let kept = std::mem::take(&mut frames.kept);
    let mut writer = frames.encoding(|| {
        let sample_frames: Vec<&RgbImage> = samples.iter().map(|k| &kept[k]).collect();
        let palette = GifPalette::from_frames(&sample_frames);
        GifWriter::new(out, width, height, movie.fps(), palette)
    })?;
    frames.kept = kept;
    write_in_order(&mut frames, |_, frame| writer.write_frame(frame))?;
    let out = frames.encoding(|| {
        let mut out = writer.finish()?;
        out.flush()?;
        Ok(out)
    })?;
    Ok((out, frames.timings))
}

/// Writes `movie` to `out` as a looping animated PNG (viewray-output's [`ApngWriter`]),
/// rendering the frames in order; `on_frame` is called after each.
///
/// # Errors
/// [`EncodeError`] if a frame cannot be rendered or written.
pub fn write_apng<W: Write>(
    movie: &Movie,
    out: W,
    settings: &RenderSettings,
    on_frame: impl FnMut(),
) -> Result<Timings, EncodeError> {
    let mut frames = Frames {
        movie,
        settings,
        kept: HashMap::new(),
        timings: Timings::default(),
        on_frame,
    };
    let (width, height) = movie.frame_size();
    let mut writer =
        frames.encoding(|| ApngWriter::new(out, width, height, movie.frames(), movie.fps()))?;
    write_in_order(&mut frames, |_, frame| writer.write_frame(frame))?;
    frames.encoding(|| writer.finish())?;
    Ok(frames.timings)
}

/// Renders the frames of `movie` in order and hands each, with its number, to `write`
/// (numbered PNG files, say), whose time counts as encoding; `on_frame` is called after
/// each frame is rendered.
///
/// # Errors
/// [`EncodeError`] if a frame cannot be rendered, or `write` fails.
pub fn write_frames(
    movie: &Movie,
    settings: &RenderSettings,
    on_frame: impl FnMut(),
    write: impl FnMut(u32, &RgbImage) -> io::Result<()>,
) -> Result<Timings, EncodeError> {
    let mut frames = Frames {
        movie,
        settings,
        kept: HashMap::new(),
        timings: Timings::default(),
        on_frame,
    };
    write_in_order(&mut frames, write)?;
    Ok(frames.timings)
}

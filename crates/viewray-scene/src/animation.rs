//! A scene file's `animation:` section: keyframed whole cameras, and how two of them mix.
//!
//! ```ron
//! animation: (frames: 48, fps: 24, ease: InOut, keys: [
//!     (t: 0.0, camera: (eye: (0.0, 1.0, 3.0), view: (0.0, 0.0, -1.0),
//!                       projection: Perspective(distance: 0.7, viewport: (1.6, 0.9)))),
//!     (t: 1.0, camera: (eye: (0.0, 1.0, 12.0), view: (0.0, 0.0, -1.0),
//!                       projection: Perspective(distance: 2.8, viewport: (1.6, 0.9)))),
//! ])
//! ```
//!
//! Each key holds a camera exactly as the scene's `camera:` value is written (an explicit
//! camera or a preset). Two keys mix field by field, as written: numbers and vectors
//! linearly, `(1 - s) a + s b`, so a mix at `s = 0` is the first key exactly and at
//! `s = 1` the second. Keys must therefore be written alike: the same projection family
//! (or the same preset), the viewport given the same way (`viewport`, `fov_y`, ..), the
//! camera aimed the same way (`look_at` or `view`); [`CameraSpec::mix`] mixes two. This
//! crate parses and checks the section; turning a frame number into a time and a time
//! into a camera is the animation crate's.

use std::path::{Path, PathBuf};

use ron::value::RawValue;

use crate::camera::parse_camera_spec;
use crate::ron_text::{self, LineIndex, Origin};
use crate::schema::{AnimationDef, EaseDef, KeyDef};
use crate::{CameraSpec, Position, SceneError};

/// The most frames an animation may have.
pub const MAX_FRAMES: u32 = 10_000;
/// The most frames per second an animation may play at.
pub const MAX_FPS: u32 = 100;

/// A scene's animation: `frames` frames played at `fps`, the camera moving through the
/// keys.
#[derive(Clone, Debug, PartialEq)]
pub struct Animation {
    /// How many frames, 1 to [`MAX_FRAMES`].
    pub frames: u32,
    /// Frames per second, 1 to [`MAX_FPS`].
    pub fps: u32,
    /// How time runs from the first frame to the last.
    pub ease: Ease,
    /// The keys, at least one, their times strictly increasing in `[0, 1]`; neighbours
    /// mix ([`CameraSpec::mix`]).
    pub keys: Vec<Key>,
    /// The scene file, for errors.
    pub(crate) path: PathBuf,
    /// Where the section starts in the file.
    pub(crate) position: Position,
}

/// How an animation's time runs through its frames.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum Ease {
    /// Evenly: frame `k` of `n` is time `k / (n - 1)`.
    #[default]
    Linear,
    /// Slow out of the first key and into the last, fastest in the middle.
    InOut,
}

/// One key of an animation: a whole camera at a time.
#[derive(Clone, Debug, PartialEq)]
pub struct Key {
    /// When, in `[0, 1]`.
    pub t: f64,
    /// The camera, as written.
    pub camera: CameraSpec,
    /// Where the key starts in the scene file.
    pub position: Position,
}

impl Animation {
    /// An error about key `index`, placed at that key in the scene file.
    pub fn key_error(&self, index: usize, message: impl Into<String>) -> SceneError {
        let position = self.keys.get(index).map_or(self.position, |k| k.position);
        SceneError::at(&self.path, Some(position), message)
    }

    /// An error about the whole animation, placed at its section in the scene file.
    pub fn error(&self, message: impl Into<String>) -> SceneError {
        SceneError::at(&self.path, Some(self.position), message)
    }

    /// The scene file the animation was read from.
    pub fn path(&self) -> &Path {
        &self.path
    }
}

/// Parses and checks the `animation:` section (`raw`, a slice of the file `lines` index): the
/// frame count and rate, the keys' times (in `[0, 1]`, strictly increasing), and their
/// cameras, each valid for a `width x height` image and written like its neighbours so
/// that the two can be mixed.
pub(crate) fn parse_animation(
    raw: &RawValue,
    lines: &LineIndex<'_>,
    path: &Path,
    width: u32,
    height: u32,
) -> Result<Animation, SceneError> {
    let origin = lines.origin_of(raw.get_ron());
    let def: AnimationDef<'_> = ron_text::parse(raw.get_ron(), origin, path)?;
    let error = |at: Origin, message: String| {
        SceneError::at(path, Some(at.position()), format!("animation: {message}"))
    };
    if def.frames == 0 || def.frames > MAX_FRAMES {
        return Err(error(
            origin,
            format!(
                "frames must be between 1 and {MAX_FRAMES}, found {}",
                def.frames
            ),
        ));
    }
    if def.fps == 0 || def.fps > MAX_FPS {
        return Err(error(
            origin,
            format!("fps must be between 1 and {MAX_FPS}, found {}", def.fps),
        ));
    }
    if def.keys.is_empty() {
        return Err(error(
            origin,
            "no keys: give at least one, `keys: [(t: 0.0, camera: (..)), (t: 1.0, camera: \
             (..))]`"
                .to_owned(),
        ));
    }
    let mut keys: Vec<Key> = Vec::with_capacity(def.keys.len());
    for (index, raw_key) in def.keys.iter().enumerate() {
        let at = lines.origin_of(raw_key.get_ron());
        let key: KeyDef<'_> = ron_text::parse(raw_key.get_ron(), at, path)?;
        let camera_origin = lines.origin_of(key.camera.get_ron());
        let number = index + 1;
        if !(0.0..=1.0).contains(&key.t) {
            return Err(error(
                at,
                format!("key {number}: t must be between 0 and 1, found {}", key.t),
            ));
        }
        if let Some(previous) = keys.last()
            && key.t <= previous.t
        {
            return Err(error(
                at,
                format!(
                    "key {number}: times must increase from key to key, but t = {} follows \
                     t = {}",
                    key.t, previous.t
                ),
            ));
        }
        let camera = parse_camera_spec(key.camera, camera_origin, path)?;
        camera
            .camera(width, height)
            .map_err(|m| error(at, format!("key {number}: camera: {m}")))?;
        if let Some(previous) = keys.last() {
            previous
                .camera
                .mix(&camera, 0.5)
                .map_err(|m| error(at, format!("key {number}: {m}")))?;
        }
        keys.push(Key {
            t: key.t,
            camera,
            position: at.position(),
        });
    }
    Ok(Animation {
        frames: def.frames,
        fps: def.fps,
        ease: match def.ease {
            EaseDef::Linear => Ease::Linear,
            EaseDef::InOut => Ease::InOut,
        },
        keys,
        path: path.to_path_buf(),
        position: origin.position(),
    })
}

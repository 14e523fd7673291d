//! Animations for slides: the cameras of every frame, and each frame rendered and laid
//! out, for a scene file's `animation:` section or for one of the lecture's built-in
//! demonstrations.
//!
//! This crate owns time and motion, and knows no command line and no file format:
//!
//! - [`frame_time`] turns a frame number into a time in `[0, 1]` (eased: [`eased`]), and
//!   [`camera_at`] a time into the camera of a scene file's animation, mixing the two
//!   keys around it field by field (the scene crate parses the keys and says how two
//!   mix);
//! - [`all_demos`] lists the lecture's moving demonstrations ([`Demo`]): a built-in scene
//!   and the path its camera takes, where a mix of keys could not say it (the dolly zoom
//!   keeps `d / D` fixed, the path to orthographic runs the eye out a thousandfold, the
//!   tilt and the shift are two cameras side by side);
//! - a [`Movie`] holds a scene and every frame's cameras; [`Movie::render_frame`]
//!   renders one frame (`viewray-render`, its tiles in parallel), with a caption of the
//!   camera's numbers over each picture and, when asked, the side view of the camera
//!   beside it (`viewray-diagram`);
//! - [`write_gif`], [`write_apng`] and [`write_frames`] render a movie's frames in order
//!   and hand them to `viewray-output`'s encoders (or to the caller, for numbered PNGs),
//!   timing the rendering and the encoding apart; where the bytes go is the caller's.
//!
//! A frame's pixels depend only on the scene and its number: its cameras are fixed when
//! the movie is made, renders are deterministic, and the side views share one window.
//!
//! Where to start reading: `timing` (frame to time to camera), `demos` (each demo's
//! path, a function of time), `movie` (a frame rendered, captioned and laid out), then
//! `encode` (the frames in order into an encoder).
//!
//! ```no_run
//! use viewray_animation::{Movie, MovieSettings, demo_by_name};
//! use viewray_render::RenderSettings;
//! use viewray_scene::LoadOptions;
//!
//! let demo = demo_by_name("dolly-zoom")?;
//! let movie = Movie::from_demo(&demo, LoadOptions::default(), MovieSettings::default())?;
//! let first = movie.render_frame(0, &RenderSettings::default())?;
//! assert_eq!(first.dimensions(), movie.frame_size());
//! # Ok::<(), Box<dyn std::error::Error>>(())
//! ```

mod demos;
mod encode;
mod movie;
#[cfg(test)]
mod tests;
mod timing;

pub use demos::{Demo, Shot, UnknownDemo, all_demos, demo_by_name, demo_names};
pub use encode::{EncodeError, Timings, write_apng, write_frames, write_gif};
pub use movie::{MAX_FRAME_PIXELS, Movie, MovieError, MovieSettings};
pub use timing::{camera_at, eased, frame_time};

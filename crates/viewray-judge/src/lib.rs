//! A student's camera, judged against the lecture's catalogue of mistakes.
//!
//! Students write their own ray tracers (in Julia, Python, C++), so their shading, gamma,
//! lights and sample counts differ from viewray's; what the lecture asks of them is the
//! camera. This crate judges it with the scene the reference was rendered from:
//!
//! - [`PictureJudge`]: where a picture's objects meet. The scene is labelled (what each
//!   pixel's centre ray meets, [`viewray_render::object_labels`]) through the right
//!   camera and through the camera of every catalogue entry that fits it
//!   ([`viewray_camera::Mistake`]), once per scene; each picture is then measured
//!   against those maps by viewray-compare's shading-blind geometry judge, and the entry
//!   whose map explains it best is named (with the entries that make the same picture).
//!
//! - [`SceneJudge`]: the same, as the [`viewray_compare::CameraJudge`] that `viewray
//!   compare` and `viewray grade` hand to viewray-compare, one per scene: its answers are
//!   plain data in the catalogue's words ([`catalogue_entry`]), and when the right
//!   camera does not explain a picture it looks for a moved eye, labelling the scene from
//!   there (module `eye`) so that a moved eye is named only when its picture is the
//!   student's (over an entry of the catalogue, only when it explains the picture
//!   clearly better).
//!
//! Where to start reading: [`PictureJudge::new`] and [`PictureJudge::judge`], then
//! [`SceneJudge`].
//!
//! **Invariant:** judge does no I/O and knows no command line: it takes a loaded scene
//! and decoded pixels, and its words are the catalogue's.

mod answers;
mod eye;
mod numbers;
mod picture;
mod scene_judge;

pub use answers::{Answer, AnswerError, read_answers};
pub use numbers::{CheckOptions, Checker, Diagnosis, Expected, IndexHint, Judged, Report};
pub use picture::{CameraVerdict, Explanation, PictureJudge};
pub use scene_judge::{SceneJudge, catalogue_entry};

//! A student's ray tracer, written apart from viewray so that the tests can judge viewray
//! by it and never viewray by itself: it uses no viewray crate (its own [`Vec3`], its own
//! camera, intersections and shading), only the lecture's formulas and the camera contract.
//! It can make any set of the lecture's mistakes (the catalogue's ids), render pictures,
//! write them as a student's program would, and print the numbers `viewray check` judges.
//!
//! Where to start reading:
//! - [`camera`]: the lecture's three steps (pixel to `u, v`; the frame `e, U, V, W`; each
//!   family's ray) with the mistakes made at their step, and `project`;
//! - [`mistakes`]: the [`Mistake`] enum, one variant per catalogue id;
//! - [`scene`]: spheres, boxes, planes, lights, materials, and the scene as viewray's RON;
//! - [`render`]: the student's shading (Lambert, Phong, shadows, gamma choices) into a
//!   [`Picture`], which [`picture`] writes as PPM, PGM or PNG;
//! - [`answers`]: frames, rays and projections printed in every spelling `check` reads.
//!
//! Its own tests are in `tests/` beside this file, compiled only by
//! `tests/student_tracer.rs` (so the other test binaries, which share this module, do not
//! run them again).

// The re-exports are the map; each test module uses a part of them.
#![allow(unused_imports)]

pub(crate) mod answers;
pub(crate) mod camera;
pub(crate) mod mistakes;
pub(crate) mod picture;
pub(crate) mod render;
pub(crate) mod scene;
pub(crate) mod vec3;

pub(crate) use answers::{Answer, AnswerStyle, Number, Syntax, write_answers};
pub(crate) use camera::{
    Aim, CameraSpec, Frame, Projection, Ray, frame, image_plane, project, ray,
};
pub(crate) use mistakes::Mistake;
pub(crate) use picture::{Format, Picture};
pub(crate) use render::{Gamma, LightChange, RenderOptions, render};
pub(crate) use scene::{Light, Material, Object, Scene, Shape, Specular};
pub(crate) use vec3::Vec3;

//! The lecture's moving demonstrations: built-in scenes, and the path each camera takes.
//!
//! A demo's path is a function of the eased time `u` in `[0, 1]` (and the image size,
//! which fixes the aspect ratio): the cameras of one frame, each with a caption giving
//! its numbers in the lecture's notation. Paths are written here, not as keys, where a
//! mix of two keys cannot say what the lecture means: the dolly zoom keeps `d / D`
//! fixed, the path to orthographic runs the eye out to a thousand times its distance,
//! the tilt and the shift are two cameras side by side.

use std::f64::consts::PI;
use std::fmt;
use std::path::Path;

use glam::{DVec2, DVec3};
use viewray_camera::{
    Camera, Frame, Iris, Oblique, Perspective, Projection, SensorFit, ThinLens,
    aperture_from_f_number,
};
use viewray_scene::{Ease, LoadOptions, Scene, SceneError};

/// One camera of a frame, with a caption of its numbers.
#[derive(Clone, Debug, PartialEq)]
pub struct Shot {
    /// The camera, with the image size.
    pub camera: Camera,
    /// What to write over the picture (the lecture's notation), if anything.
    pub caption: Option<String>,
}

/// A built-in demonstration: `viewray animate --demo NAME`.
#[derive(Clone, Copy)]
pub struct Demo {
    /// The name, kebab-case, as `--demo` takes it.
    pub name: &'static str,
    /// One line saying what the class sees.
    pub summary: &'static str,
    /// The frames, unless overridden.
    pub frames: u32,
    /// Frames per second, unless overridden.
    pub fps: u32,
    /// How time runs through the frames.
    pub ease: Ease,
    /// Whether the last frame leads back into the first (a full turn): then frame `k` of
    /// `n` is at `k / n`, so no frame repeats when the animation loops.
    pub looping: bool,
    /// The scene file's name (for errors) and text.
    scene: (&'static str, &'static str),
    /// The cameras at eased time `u`, for `width x height` pictures.
    path: fn(u: f64, width: u32, height: u32) -> Vec<Shot>,
}

impl fmt::Debug for Demo {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.debug_struct("Demo")
            .field("name", &self.name)
            .field("summary", &self.summary)
            .finish_non_exhaustive()
    }
}

impl Demo {
    /// The demo's scene, at `options`' size and samples when given (its own otherwise:
    /// 480 x 270 a picture, or 240 x 270 for side-by-side pictures).
    ///
    /// # Errors
    /// Never for the built-in scenes at a valid size; a [`SceneError`] for an invalid
    /// size or sample count.
    pub fn scene(&self, options: LoadOptions) -> Result<Scene, SceneError> {
        let (name, text) = self.scene;
        viewray_scene::SceneLoader::text(text, Path::new(name))
            .options(options)
            .load()
            .map(|loaded| loaded.scene)
    }

    /// The time of frame `frame` of `frames`: eased, and for a looping demo spread over
    /// `[0, 1)` so the last frame leads back into the first.
    pub fn time(&self, frame: u32, frames: u32) -> f64 {
        if self.looping {
            f64::from(frame) / f64::from(frames.max(1))
        } else {
            crate::frame_time(self.ease, frame, frames)
        }
    }

    /// The cameras of frame `frame` of `frames`, for `width x height` pictures.
    pub fn shots(&self, frame: u32, frames: u32, width: u32, height: u32) -> Vec<Shot> {
        (self.path)(self.time(frame, frames), width, height)
    }
}

/// The error for a demo name that [`demo_by_name`] does not know; its message lists the
/// demos.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("unknown demo `{name}`; the demos are: {}", demo_names().join(", "))]
pub struct UnknownDemo {
    /// The name asked for.
    pub name: String,
}

/// Every demo, in the lecture's order.
pub fn all_demos() -> Vec<Demo> {
    const STREET: (&str, &str) = ("street.ron", include_str!("../scenes/street.ron"));
    const BLOCKS: (&str, &str) = ("blocks.ron", include_str!("../scenes/blocks.ron"));
    const TOWERS: (&str, &str) = ("towers.ron", include_str!("../scenes/towers.ron"));
    const SPHERES: (&str, &str) = ("spheres.ron", include_str!("../scenes/spheres.ron"));
    const CUBE: (&str, &str) = ("cube.ron", include_str!("../scenes/cube.ron"));
    const TABLETOP: (&str, &str) = ("tabletop.ron", include_str!("../scenes/tabletop.ron"));
    const LAMPS: (&str, &str) = ("lamps.ron", include_str!("../scenes/lamps.ron"));
    let demo = |name, summary, scene, path| Demo {
        name,
        summary,
        frames: 48,
        fps: 24,
        ease: Ease::InOut,
        looping: false,
        scene,
        path,
    };
    vec![
        demo(
            "dolly-zoom",
            "the eye backs away as d grows with it: the card keeps its size, the street behind it flattens",
            STREET,
            dolly_zoom,
        ),
        demo(
            "fov",
            "the eye stays, the field of view narrows: everything grows alike, the perspective does not change",
            STREET,
            fov,
        ),
        demo(
            "perspective-to-orthographic",
            "the eye recedes a thousandfold as the view narrows: parallel projection as the limit of perspective",
            BLOCKS,
            perspective_to_orthographic,
        ),
        demo(
            "tilt-vs-shift",
            "side by side, a camera tilting up to 24 degrees (verticals converge) and a level one shifting its lens (verticals stay parallel)",
            TOWERS,
            tilt_vs_shift,
        ),
        demo(
            "aperture",
            "a thin lens opening from r = 0.005 to 0.3, focused on the green sphere: depth of field shrinks",
            SPHERES,
            aperture,
        ),
        demo(
            "focus-pull",
            "a thin lens refocusing from the red sphere (f = 2) to the blue one (f = 8)",
            SPHERES,
            focus_pull,
        ),
        demo(
            "lens-tilt",
            "a 50 mm lens over a tabletop tilting forward from 0 to 11.5 degrees: the plane of focus swings from upright, across the posts, down onto the table",
            TABLETOP,
            lens_tilt,
        ),
        Demo {
            ease: Ease::Linear,
            ..demo(
                "bokeh",
                "the aperture's blades, 5, 6, 7, 8, 10, 12, 16, then round: the out-of-focus lamps take the aperture's shape",
                LAMPS,
                bokeh,
            )
        },
        Demo {
            ease: Ease::Linear,
            looping: true,
            ..demo(
                "oblique-angle",
                "a cabinet projection (L = 1/2) whose receding axis turns once around, angle phi from 0 to 360 degrees",
                CUBE,
                oblique_angle,
            )
        },
    ]
}

/// The demo called `name`.
///
/// # Errors
/// [`UnknownDemo`] naming every demo.
pub fn demo_by_name(name: &str) -> Result<Demo, UnknownDemo> {
    all_demos()
        .into_iter()
        .find(|demo| demo.name == name)
        .ok_or_else(|| UnknownDemo {
            name: name.to_owned(),
        })
}

/// The demos' names, in order.
pub fn demo_names() -> Vec<&'static str> {
    all_demos().iter().map(|demo| demo.name).collect()
}

/// `(1 - u) a + u b`.
fn mix(a: f64, b: f64, u: f64) -> f64 {
    (1.0 - u) * a + u * b
}

fn aspect(width: u32, height: u32) -> f64 {
    f64::from(width) / f64::from(height)
}

/// A camera the demos build from constants: valid by construction.
fn camera(frame: Frame, projection: Projection, width: u32, height: u32) -> Camera {
    Camera::new(frame, projection, width, height).expect("the demos' cameras are valid")
}

fn looking(eye: DVec3, view: DVec3) -> Frame {
    Frame::from_eye_view_up(eye, view, DVec3::Y).expect("the demos' frames are valid")
}

fn shot(camera: Camera, caption: String) -> Shot {
    Shot {
        camera,
        caption: Some(caption),
    }
}

/// The dolly zoom's `d / D`: the card fills `2 d / (D vh) = 0.55` of the image's height.
const DOLLY_RATIO: f64 = 0.275;

/// The dolly zoom: the eye at distance `D` from the card (2.5 to 12), the image plane at
/// `d = 0.275 D`, the viewport 1 unit tall: the card's image height `2 d / D` never
/// changes while the field of view `2 atan(vh / 2d)` falls from 72 to 17 degrees.
fn dolly_zoom(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let depth = mix(2.5, 12.0, u);
    let distance = DOLLY_RATIO * depth;
    let viewport = DVec2::new(aspect(width, height), 1.0);
    let projection = Projection::Perspective(Perspective {
        distance,
        viewport,
        shift: DVec2::ZERO,
    });
    let fov = 2.0 * (viewport.y / (2.0 * distance)).atan();
    vec![shot(
        camera(
            looking(DVec3::new(0.0, 1.0, depth), DVec3::NEG_Z),
            projection,
            width,
            height,
        ),
        format!(
            "eye {depth:.1} from the card,  $d$ = {distance:.2},  fov {:.0}°",
            fov.to_degrees()
        ),
    )]
}

/// The field of view narrowing from 90 to 20 degrees (vertical), the eye fixed 6 units
/// from the card: `d = 1`, `vh = 2 tan(fov_y / 2)`.
fn fov(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let fov_y = mix(90.0, 20.0, u);
    let perspective = Perspective::from_fov_y(fov_y.to_radians(), aspect(width, height))
        .expect("a field of view between 20 and 90 degrees");
    vec![shot(
        camera(
            looking(DVec3::new(0.0, 1.0, 6.0), DVec3::NEG_Z),
            Projection::Perspective(perspective),
            width,
            height,
        ),
        format!(
            "fov_y {fov_y:.0}°,  $d$ = 1,  $vh$ = {:.2}",
            perspective.viewport.y
        ),
    )]
}

/// What the path to orthographic looks at, and from which direction (towards the eye):
/// 30 degrees up, from 30 degrees to the right.
const BLOCKS_TARGET: DVec3 = DVec3::new(0.0, 0.8, -1.5);
/// The height of the view at the target, in world units, for every frame.
pub(crate) const BLOCKS_VIEW_HEIGHT: f64 = 9.0;
/// The eye's first distance from the target, and its last: a thousand times farther.
const BLOCKS_NEAR: f64 = 10.0;
const BLOCKS_FAR: f64 = 10_000.0;

fn blocks_back() -> DVec3 {
    let (elevation, azimuth) = (30f64.to_radians(), 30f64.to_radians());
    DVec3::new(
        azimuth.sin() * elevation.cos(),
        elevation.sin(),
        azimuth.cos() * elevation.cos(),
    )
}

/// Perspective to orthographic: the eye recedes from the target, `1 / D` falling
/// linearly from `1 / 10` to `1 / 10000` (how strongly the picture converges falls
/// evenly), while `vh = 9 / D` (with `d = 1`) keeps the view 9 units tall at the target.
/// The last frame, the eye 10000 units away, is the orthographic picture to within a
/// fraction of a pixel.
fn perspective_to_orthographic(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let depth = 1.0 / mix(1.0 / BLOCKS_NEAR, 1.0 / BLOCKS_FAR, u);
    let vh = BLOCKS_VIEW_HEIGHT / depth;
    let back = blocks_back();
    let projection = Projection::Perspective(Perspective {
        distance: 1.0,
        viewport: DVec2::new(vh * aspect(width, height), vh),
        shift: DVec2::ZERO,
    });
    vec![shot(
        camera(
            looking(BLOCKS_TARGET + back * depth, -back),
            projection,
            width,
            height,
        ),
        format!("eye {depth:.0} from the target,  $d$ = 1,  $vh$ = {vh:.4}"),
    )]
}

/// The orthographic camera the path to orthographic tends to: the same direction, the
/// view 9 units tall at the target (its eye far enough back to see every block).
#[cfg(test)]
pub(crate) fn blocks_orthographic(width: u32, height: u32) -> Camera {
    let back = blocks_back();
    let projection = Projection::Orthographic(viewray_camera::Orthographic {
        viewport: DVec2::new(
            BLOCKS_VIEW_HEIGHT * aspect(width, height),
            BLOCKS_VIEW_HEIGHT,
        ),
        lens: None,
    });
    camera(
        looking(BLOCKS_TARGET + back * 30.0, -back),
        projection,
        width,
        height,
    )
}

/// Tilt against shift: both eyes 1 above the ground, 8.5 units from the tower's axis,
/// `d = 1`, `vh = 1`; on the left the camera tilts up by `theta` (0 to 24 degrees), on
/// the right it stays level and shifts its lens by `sy = d tan(theta)`, which centres the
/// same point.
fn tilt_vs_shift(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let theta = mix(0.0, 24.0, u).to_radians();
    let eye = DVec3::new(0.0, 1.0, 8.5);
    let perspective = Perspective {
        distance: 1.0,
        viewport: DVec2::new(aspect(width, height), 1.0),
        shift: DVec2::ZERO,
    };
    let sy = Perspective::shift_for_elevation(perspective.distance, theta);
    let tilted = camera(
        looking(eye, DVec3::new(0.0, theta.sin(), -theta.cos())),
        Projection::Perspective(perspective),
        width,
        height,
    );
    let shifted = camera(
        looking(eye, DVec3::NEG_Z),
        Projection::Perspective(Perspective {
            shift: DVec2::new(0.0, sy),
            ..perspective
        }),
        width,
        height,
    );
    vec![
        shot(tilted, format!("tilted up {:.0}°", theta.to_degrees())),
        shot(shifted, format!("level, shifted $s_y$ = {sy:.2}")),
    ]
}

/// The thin lens of the spheres: eye 0.6 above the ground looking down `-z`, `d = 1`, the
/// viewport 0.9 tall.
fn thin_lens(aperture: f64, focus: f64, width: u32, height: u32) -> Camera {
    let projection = Projection::ThinLens(ThinLens {
        distance: 1.0,
        viewport: DVec2::new(0.9 * aspect(width, height), 0.9),
        shift: DVec2::ZERO,
        aperture,
        focus,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    });
    camera(
        looking(DVec3::new(0.0, 0.6, 0.0), DVec3::NEG_Z),
        projection,
        width,
        height,
    )
}

/// The aperture opening: lens radius `r` from 0.005 to 0.3, focus fixed at the green
/// sphere, `f = 4.5`.
fn aperture(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let r = mix(0.005, 0.3, u);
    vec![shot(
        thin_lens(r, 4.5, width, height),
        format!("$r$ = {r:.3},  $f$ = 4.5"),
    )]
}

/// The focus pull: `f` from 2 (the red sphere) to 8 (the blue one), `r = 0.15`.
fn focus_pull(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let f = mix(2.0, 8.0, u);
    vec![shot(
        thin_lens(0.15, f, width, height),
        format!("$f$ = {f:.2},  $r$ = 0.15"),
    )]
}

/// The tabletop's eye: 25 cm above the table, looking level down `-z`.
const TABLETOP_EYE: DVec3 = DVec3::new(0.0, 0.25, 0.6);
/// The tabletop lens's focal length, mm, and f-number.
const TABLETOP_LENS: (f64, f64) = (50.0, 2.0);

/// The lens tilt: a 50 mm lens at f/2 (on a 36 mm wide sensor, shifted down a third of
/// the picture to see more table) 25 cm above a table, tilting forward from 0 to
/// asin(50 mm / 25 cm) = 11.54 degrees, the tilt that lays its hinge line on the table,
/// while focused at `f = F / (1 - cos 11.54 deg) = 2.475` m, which then lays the plane of
/// focus on the table. Untilted the plane stands upright 2.475 m away, beyond the posts;
/// as the lens tilts it swings down about a hinge line that comes up toward the table
/// (`J = F / sin(tilt)` below the lens), across the posts, until the table is sharp from
/// front to back and only the posts' tops blur.
fn lens_tilt(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let (focal_length, f_number) = TABLETOP_LENS;
    let (f, h) = (focal_length / 1000.0, TABLETOP_EYE.y);
    let last = (f / h).asin();
    let focus = f / (1.0 - last.cos());
    let tilt = mix(0.0, last, u);
    let mut pinhole = Perspective::from_focal_length(
        focal_length,
        DVec2::new(36.0, 24.0),
        SensorFit::Horizontal,
        aspect(width, height),
    )
    .expect("a valid physical camera");
    pinhole.shift = DVec2::new(0.0, -pinhole.viewport.y / 3.0);
    let aperture = aperture_from_f_number(focal_length, f_number).expect("a valid f-number");
    let projection = Projection::ThinLens(ThinLens {
        tilt,
        ..ThinLens::new(pinhole, aperture, focus)
    });
    let caption = if tilt > 0.0 {
        format!(
            "lens tilt {:.1}°,  hinge line {:.2} m below the lens",
            tilt.to_degrees(),
            f / tilt.sin()
        )
    } else {
        format!("lens tilt 0°,  plane of focus upright {focus:.2} m ahead")
    };
    vec![shot(
        camera(
            looking(TABLETOP_EYE, DVec3::NEG_Z),
            projection,
            width,
            height,
        ),
        caption,
    )]
}

/// The bokeh demo's blades, in order; 0 is round.
const BLADES: [u32; 8] = [5, 6, 7, 8, 10, 12, 16, 0];

/// Bokeh: the lamps' thin lens (`r = 0.15`, focused at 2 on the red ball, 40 degrees
/// tall) with 5, 6, 7, 8, 10, 12 and 16 blades, each for an eighth of the time, then
/// round; the blades turned by 90 degrees, so that an edge lies flat on top. Each lamp
/// far behind the ball pictures the aperture, upright.
fn bokeh(u: f64, width: u32, height: u32) -> Vec<Shot> {
    // Whole steps of an eighth; the last frame (u = 1) is round.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let step = ((u * BLADES.len() as f64) as usize).min(BLADES.len() - 1);
    let blades = BLADES[step];
    let pinhole = Perspective::from_fov_y(40f64.to_radians(), aspect(width, height))
        .expect("a valid field of view");
    let projection = Projection::ThinLens(ThinLens {
        iris: Iris::from_degrees(blades, 90.0).expect("the demo's blades are valid"),
        ..ThinLens::new(pinhole, 0.15, 2.0)
    });
    let caption = if blades == 0 {
        "round aperture".to_owned()
    } else {
        format!("{blades} blades")
    };
    vec![shot(
        camera(
            looking(DVec3::new(0.0, 0.5, 3.0), DVec3::NEG_Z),
            projection,
            width,
            height,
        ),
        caption,
    )]
}

/// The oblique angle: a cabinet projection (`L = 1/2`) of the cube, looking down `-z`,
/// the view 5 units tall, the receding axis at `phi` from 0 to 360 degrees. The image
/// plane stands 4 units in front of the cube's centre, slid along the projectors so that
/// the centre stays in the middle of the picture: a point `D` behind the plane appears
/// moved by `L D` at angle `phi`, so
///
/// ```text
/// e = target + D w + L D (cos phi u + sin phi v),   D = 4
/// ```
fn oblique_angle(u: f64, width: u32, height: u32) -> Vec<Shot> {
    let phi = 2.0 * PI * u;
    let (ratio, depth) = (0.5, 4.0);
    let target = DVec3::new(0.0, 1.0, 0.0);
    let eye = target + DVec3::new(ratio * depth * phi.cos(), ratio * depth * phi.sin(), depth);
    let projection = Projection::Oblique(Oblique {
        viewport: DVec2::new(5.0 * aspect(width, height), 5.0),
        ratio,
        angle: phi,
    });
    vec![shot(
        camera(looking(eye, DVec3::NEG_Z), projection, width, height),
        format!("$L$ = 0.5,  $φ$ = {:.0}°", phi.to_degrees()),
    )]
}

//! The thin lens: a cone of rays per pixel that meets at the focus plane.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Frame, Projection, ThinLens};

use crate::Diagram;
use crate::distortions::draw_side_scene;
use crate::pictures::{PictureScene, Pictures, draw_picture};
use crate::side::draw_image_plane;
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::{CameraView, FigureView, SideView};
use viewray_draw::{Anchor, Baseline, Item, Rect, Stroke};
use viewray_output::number;

/// The eye of the thin-lens figure: 0.6 above the ground, looking down `-z`.
const EYE: DVec3 = DVec3::new(0.0, 0.6, 0.0);
/// The focus distance `f`: the green sphere's depth.
pub(crate) const FOCUS: f64 = 4.5;
/// The lens radius `r` of the side view.
const APERTURE: f64 = 0.35;
/// The two apertures whose pictures the figure compares.
pub(crate) const PICTURE_APERTURES: [f64; 2] = [0.04, 0.25];
/// The pixel whose cone the side view draws, `(row, col)`: the one that sees the green
/// sphere's centre.
pub(crate) const CONE_PIXEL: (u32, u32) = (100, 120);
/// The lens points of the drawn cone: `(lx, ly)` across the lens's vertical diameter.
pub(crate) const LENS_POINTS: [f64; 5] = [-1.0, -0.5, 0.0, 0.5, 1.0];

/// A thin-lens camera of the figure: `d = 1`, a 1.2 x 0.9 viewport, 240 x 180 pixels,
/// focused at [`FOCUS`], with lens radius `aperture`.
pub(crate) fn thin_lens_camera(aperture: f64) -> Camera {
    let frame = Frame::from_eye_view_up(EYE, DVec3::NEG_Z, DVec3::Y).expect("valid");
    let projection = Projection::ThinLens(ThinLens {
        distance: 1.0,
        viewport: DVec2::new(1.2, 0.9),
        shift: DVec2::ZERO,
        aperture,
        focus: FOCUS,
        tilt: 0.0,
        swing: 0.0,
        iris: viewray_camera::Iris::ROUND,
    });
    Camera::new(frame, projection, 240, 180).expect("a valid thin-lens camera")
}

/// The lens sample in the unit square that the concentric mapping sends to `(0, ly)`.
fn lens_sample(ly: f64) -> DVec2 {
    DVec2::new(0.5, (ly + 1.0) / 2.0)
}

/// The thin lens (slide, 1600 x 900): a side view of a thin-lens camera with its lens
/// (radius `r`), image plane and focus plane at `f`, and the rays that one pixel
/// generates through five points of the lens: a cone that meets at the focus plane and
/// spreads before and after it (the blur of the red and blue spheres). Below, the
/// picture at two apertures (rendered when `pictures` has them; else the spheres
/// projected with their circles of confusion).
pub(crate) fn thin_lens(pictures: &dyn Pictures) -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Thin lens: depth of field");
    let camera = thin_lens_camera(APERTURE);
    let view = SideView::fit(
        (-0.75, 9.3),
        (-0.2, 1.75),
        Rect::from_xywh(40.0, 110.0, 1520.0, 400.0),
    );
    let fv = FigureView::Side(view);
    draw_side_scene(&mut sketch, &view, PictureScene::DepthOfField);

    // The focus plane.
    let focus_top = view.to_figure(EYE + DVec3::new(0.0, 1.05, -FOCUS));
    let focus_bottom = view.to_figure(DVec3::new(0.0, -0.15, -FOCUS));
    sketch.line(
        focus_top,
        focus_bottom,
        Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR).dashed(&style::DASH),
    );
    sketch.label_at(
        &format!("focus plane, $f$ = {}", number::label(FOCUS)),
        focus_top + Vec2::new(0.0, -10.0),
        (Anchor::Middle, Baseline::Bottom),
        style::HIGHLIGHT,
        style::SMALL_LABEL_SIZE,
    );

    // The cone of one pixel: a ray from each lens point, through the focus point, on.
    let far = 8.8 / FOCUS;
    for ly in LENS_POINTS {
        let sample = CameraSample {
            p_film: DVec2::splat(0.5),
            p_lens: lens_sample(ly),
        };
        let stroke = Stroke::new(style::RAY, style::LINE_REGULAR);
        sketch.camera_ray(
            &fv,
            CameraRay {
                camera: &camera,
                pixel: CONE_PIXEL,
                sample,
                t: (0.0, far),
            },
            stroke,
            true,
        );
    }
    let focus_point = camera
        .generate_ray(CONE_PIXEL.0, CONE_PIXEL.1, CameraSample::CENTER)
        .expect("a thin-lens ray")
        .at(1.0);
    sketch.dot(
        view.to_figure(focus_point),
        style::DOT_RADIUS,
        style::HIGHLIGHT,
    );

    // The lens, the image plane, the eye.
    let e = view.to_figure(EYE);
    let lens_half = view.length(APERTURE);
    sketch.push(Item::Ellipse {
        center: e,
        radii: Vec2::new(lens_half * 0.18, lens_half),
        rotation: 0.0,
        fill: Some(style::IMAGE_PLANE_FILL),
        stroke: Some(Stroke::new(style::OBJECT, style::LINE_REGULAR)),
    });
    let (_, plane_bottom) = draw_image_plane(&mut sketch, &view, &camera, style::IMAGE_PLANE, 0.0);
    let ground = view.to_figure(DVec3::ZERO).y;
    sketch.label_at(
        "image plane, $d$ = 1",
        Vec2::new(plane_bottom.x, ground + 12.0),
        (Anchor::Middle, Baseline::Top),
        style::ANNOTATION,
        style::SMALL_LABEL_SIZE,
    );
    sketch.dot(e, style::DOT_RADIUS * 0.7, style::EYE);
    let lens_top = e + Vec2::new(0.0, -lens_half);
    sketch.label_at(
        &format!("lens, radius $r$ = {}", number::label(APERTURE)),
        lens_top + Vec2::new(-16.0, -22.0),
        (Anchor::Start, Baseline::Bottom),
        style::TEXT,
        style::SMALL_LABEL_SIZE,
    );
    sketch.label_at(
        "*e*",
        e + Vec2::new(-24.0, 0.0),
        (Anchor::End, Baseline::Middle),
        style::EYE,
        style::LABEL_SIZE,
    );

    // The pictures at two apertures, and the rule.
    let slot = Vec2::new(340.0, 255.0);
    for (k, aperture) in PICTURE_APERTURES.iter().enumerate() {
        let min = Vec2::new(50.0 + k as f32 * (slot.x + 30.0), 590.0);
        let picture = CameraView::new(
            thin_lens_camera(*aperture),
            Rect::from_corners(min, min + slot),
        );
        draw_picture(&mut sketch, &picture, PictureScene::DepthOfField, pictures);
        sketch.label_at(
            &format!("$r$ = {}", number::label(*aperture)),
            Vec2::new(picture.rect.center().x, picture.rect.min.y - 10.0),
            (Anchor::Middle, Baseline::Bottom),
            style::TEXT,
            style::SMALL_LABEL_SIZE,
        );
    }
    let (l, s) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    sketch.text_lines(
        Vec2::new(810.0, 620.0),
        &[
            ("origin *e* + $r$ ($l_x$ *u* + $l_y$ *v*)", style::TEXT, l),
            (
                "direction ($f/d$)($u$ *u* + $v$ *v* − $d$ *w*)",
                style::TEXT,
                l,
            ),
            ("         − $r$ ($l_x$ *u* + $l_y$ *v*)", style::TEXT, l),
            ("", style::TEXT, l),
            (
                "all rays of a pixel meet at $t$ = 1, on the focus",
                style::ANNOTATION,
                s,
            ),
            (
                "plane: sharp there, blurred nearer and farther",
                style::ANNOTATION,
                s,
            ),
        ],
    );
    sketch.finish()
}

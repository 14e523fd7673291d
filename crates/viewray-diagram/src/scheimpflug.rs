//! The Scheimpflug and hinge rules: a tilted lens tilts the plane of sharp focus.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Frame, Iris, Line3, Plane3, Projection, ThinLens};
use viewray_draw::{Anchor, Baseline, Item, Rect, Stroke};
use viewray_output::number;

use crate::Diagram;
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::{FigureView, SideView};

/// The lens centre: 4 above the ground, looking level down `-z`.
const EYE: DVec3 = DVec3::new(0.0, 4.0, 0.0);
/// The lens's tilt `alpha`, degrees: its top toward the scene.
pub(crate) const TILT_DEGREES: f64 = 20.0;
/// The distance `f` the untilted lens focuses, which places the sensor.
pub(crate) const FOCUS: f64 = 4.0;
/// The lens radius `r`.
const APERTURE: f64 = 0.25;
/// The pixels of the middle column whose rays are drawn: each meets on the plane of
/// focus inside the view.
pub(crate) const ROWS: [u32; 3] = [30, 58, 84];
/// The column of those pixels.
pub(crate) const COLUMN: u32 = 60;
/// The lens points of each pixel's rays, `(0, ly)`.
pub(crate) const LENS_POINTS: [f64; 3] = [-1.0, 0.0, 1.0];

/// The figure's camera: a thin lens of focal length `F = d = 1`, a 1.2 x 0.9 viewport,
/// 120 x 90 pixels, focused at [`FOCUS`], tilted by [`TILT_DEGREES`].
pub(crate) fn scheimpflug_camera() -> Camera {
    let frame = Frame::from_eye_view_up(EYE, DVec3::NEG_Z, DVec3::Y).expect("valid");
    let pinhole = viewray_camera::Perspective {
        distance: 1.0,
        viewport: DVec2::new(1.2, 0.9),
        shift: DVec2::ZERO,
    };
    let lens = ThinLens {
        tilt: TILT_DEGREES.to_radians(),
        iris: Iris::ROUND,
        ..ThinLens::new(pinhole, APERTURE, FOCUS)
    };
    Camera::new(frame, Projection::ThinLens(lens), 120, 90).expect("a valid tilted lens")
}

/// The lens sample in the unit square that the concentric mapping sends to `(0, ly)`.
fn lens_sample(ly: f64) -> DVec2 {
    DVec2::new(0.5, (ly + 1.0) / 2.0)
}

/// The trace of `plane` in the side view (the y-z plane): a unit direction along it.
fn along(plane: &Plane3) -> DVec3 {
    DVec3::new(0.0, plane.normal.z, -plane.normal.y).normalize()
}

/// `d` or `-d`, whichever points up.
fn upward(d: DVec3) -> DVec3 {
    if d.y < 0.0 { -d } else { d }
}

/// The side view's point of a line perpendicular to it (the figure's `x`): where it
/// pierces the y-z plane.
fn pierce(line: &Line3) -> DVec3 {
    line.point - line.direction * (line.point.x / line.direction.x)
}

/// The angle (radians, counter-clockwise on the figure) of the world direction `d`
/// from the figure's up, for rotating the lens's ellipse.
fn tilt_on_figure(view: &SideView, d: DVec3) -> f32 {
    let p = view.plane_point(d);
    (-p.x).atan2(p.y) as f32
}

/// The Scheimpflug and hinge rules (slide, 1600 x 900): the side view of a lens tilted by
/// `alpha` with the sensor behind it, the plane through the lens parallel to the sensor,
/// the lens's front focal plane and the plane of sharp focus; sensor, lens and plane of
/// focus meet in the Scheimpflug line, and the plane of focus turns about the hinge line
/// `F / sin(alpha)` below the lens. Three pixels' rays, through three lens points each,
/// meet on the tilted plane. Every plane and line is the camera's
/// ([`Camera::tilted_focus`]); every ray one it generates.
pub(crate) fn scheimpflug() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Scheimpflug: a tilted lens tilts the plane of focus");
    let camera = scheimpflug_camera();
    let tilted = camera.tilted_focus().expect("a tilted lens");
    let view = SideView::fit(
        (-1.6, 8.4),
        (-0.2, 5.4),
        Rect::from_xywh(40.0, 100.0, 1520.0, 780.0),
    );
    let fv = FigureView::Side(view);
    let at = |p: DVec3| view.to_figure(p);
    let thin = Stroke::new(style::ANNOTATION, style::LINE_THIN).dashed(&style::DASH);

    // The ground.
    let (left, right) = (
        view.mapping.to_canvas(view.bounds.min).x,
        view.mapping.to_canvas(view.bounds.max).x,
    );
    let ground = at(DVec3::ZERO).y;
    sketch.line(
        Vec2::new(left, ground),
        Vec2::new(right, ground),
        Stroke::new(style::OBJECT, style::LINE_REGULAR),
    );

    let scheimpflug = pierce(&tilted.scheimpflug_line);
    let hinge = pierce(&tilted.hinge_line);
    let e = camera.frame().e();

    // The plane through the lens parallel to the sensor, down to the hinge line; the
    // front focal plane through the hinge line; the lens plane down to the Scheimpflug
    // line; the sensor plane down to it too.
    sketch.line(at(e + DVec3::Y * 0.6), at(hinge), thin.clone());
    let focal_up = upward(along(&tilted.front_focal));
    let focal_top = hinge + focal_up * (3.6 / focal_up.y);
    sketch.line(at(hinge), at(focal_top), thin.clone());
    let lens_up = upward(along(&tilted.lens));
    let lens_top = e + lens_up * (0.6 / lens_up.y);
    sketch.line(
        at(lens_top),
        at(scheimpflug),
        Stroke::new(style::OBJECT, style::LINE_THIN).dashed(&style::DASH),
    );
    let sensor_centre = tilted.sensor.point;
    sketch.line(
        at(sensor_centre + DVec3::Y * 0.6),
        at(scheimpflug),
        Stroke::new(style::IMAGE_PLANE, style::LINE_THIN).dashed(&style::DASH),
    );

    // The plane of focus, from the Scheimpflug line through the hinge line and on to the
    // edge of the view.
    let focus_along = {
        let d = along(&tilted.focus);
        if d.z > 0.0 { -d } else { d }
    };
    let reach = viewray_geometry::DRay {
        origin: scheimpflug,
        direction: focus_along,
    };
    let (_, far) = view
        .clip_ray(&reach, (0.0, 100.0))
        .expect("the plane of focus crosses the view");
    sketch.line(
        at(scheimpflug),
        at(reach.at(far)),
        Stroke::new(style::HIGHLIGHT, style::LINE_THICK).dashed(&style::DASH),
    );

    // The sensor (its height on the plane z = s: the viewport seen from the lens), and
    // the lens, tilted.
    let projection = match camera.projection() {
        Projection::ThinLens(p) => *p,
        _ => unreachable!("the figure's camera is a thin lens"),
    };
    let s = projection.sensor_distance();
    let sensor_half = projection.viewport.y / 2.0 * s / projection.distance;
    sketch.line(
        at(sensor_centre + DVec3::Y * sensor_half),
        at(sensor_centre - DVec3::Y * sensor_half),
        Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
    );
    let lens_half = view.length(APERTURE);
    sketch.push(Item::Ellipse {
        center: at(e),
        radii: Vec2::new(lens_half * 0.2, lens_half),
        rotation: -tilt_on_figure(&view, lens_up),
        fill: Some(style::IMAGE_PLANE_FILL),
        stroke: Some(Stroke::new(style::OBJECT, style::LINE_REGULAR)),
    });

    // Three pixels: each centre ray's line back to the sensor, and the rays through three
    // lens points from the lens to where they meet, on the plane of focus, and on.
    for row in ROWS {
        let centre = camera
            .generate_ray(row, COLUMN, CameraSample::CENTER)
            .expect("a thin-lens ray");
        // Behind the lens, the centre ray's line (t < 0, no viewing ray) back to the
        // pixel's point on the sensor: a construction line.
        let behind = s / centre.direction.dot(camera.frame().w());
        sketch.line(
            at(centre.at(behind)),
            at(centre.origin),
            Stroke::new(style::ANNOTATION, style::LINE_THIN),
        );
        for ly in LENS_POINTS {
            let sample = CameraSample {
                p_film: DVec2::splat(0.5),
                p_lens: lens_sample(ly),
            };
            sketch.camera_ray(
                &fv,
                CameraRay {
                    camera: &camera,
                    pixel: (row, COLUMN),
                    sample,
                    t: (0.0, 1.15),
                },
                Stroke::new(style::RAY, style::LINE_REGULAR),
                false,
            );
        }
        sketch.dot(at(centre.at(1.0)), style::DOT_RADIUS, style::HIGHLIGHT);
        sketch.dot(
            at(centre.at(behind)),
            style::DOT_RADIUS * 0.7,
            style::ANNOTATION,
        );
    }

    // The two lines, seen end on, and the eye.
    sketch.dot(at(scheimpflug), style::DOT_RADIUS, style::TEXT);
    sketch.dot(at(hinge), style::DOT_RADIUS, style::TEXT);
    sketch.dot(at(e), style::DOT_RADIUS * 0.7, style::EYE);

    // Labels.
    let (size, small) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    let label = |sketch: &mut Sketch, text: &str, p: Vec2, anchor: (Anchor, Baseline), color| {
        sketch.label_at(text, p, anchor, color, small);
    };
    let j = projection.distance / TILT_DEGREES.to_radians().sin();
    label(
        &mut sketch,
        &format!(
            "hinge line: $J$ = $F$ / sin α = {}",
            number::label_significant(j)
        ),
        at(hinge) + Vec2::new(18.0, 6.0),
        (Anchor::Start, Baseline::Top),
        style::TEXT,
    );
    label(
        &mut sketch,
        "Scheimpflug line",
        at(scheimpflug) + Vec2::new(16.0, 6.0),
        (Anchor::Start, Baseline::Top),
        style::TEXT,
    );
    label(
        &mut sketch,
        "sensor",
        at(sensor_centre + DVec3::Y * 0.6) + Vec2::new(0.0, -8.0),
        (Anchor::Middle, Baseline::Bottom),
        style::IMAGE_PLANE,
    );
    label(
        &mut sketch,
        &format!("lens, tilted α = {TILT_DEGREES}°"),
        at(lens_top) + Vec2::new(10.0, -8.0),
        (Anchor::Start, Baseline::Bottom),
        style::TEXT,
    );
    let focus_label = reach.at(far * 0.8);
    label(
        &mut sketch,
        "plane of focus",
        at(focus_label) + Vec2::new(16.0, 14.0),
        (Anchor::Start, Baseline::Top),
        style::HIGHLIGHT,
    );
    sketch.label_at(
        "*e*",
        at(e) + Vec2::new(-24.0, 6.0),
        (Anchor::End, Baseline::Top),
        style::EYE,
        size,
    );
    sketch.text_lines(
        Vec2::new(850.0, 530.0),
        &[
            (
                &format!(
                    "sensor at $s$ = $F f$ / ($f$ − $F$) = {}",
                    number::label_significant(s)
                ),
                style::TEXT,
                small,
            ),
            (
                "(where the untilted lens focuses $f$)",
                style::ANNOTATION,
                small,
            ),
            (
                "plane of focus: (*n* + (1 − $F/f$) *w*) · (*p* − *e*) = $F$",
                style::TEXT,
                small,
            ),
            (
                "*n*: the lens's axis; every pixel's rays",
                style::ANNOTATION,
                small,
            ),
            ("meet on this plane, at $t$ = 1", style::ANNOTATION, small),
            (
                "grey dashes: the front focal plane ($F$ ahead",
                style::ANNOTATION,
                small,
            ),
            (
                "of the lens) and the plane through *e* parallel",
                style::ANNOTATION,
                small,
            ),
            (
                "to the sensor, meeting in the hinge line",
                style::ANNOTATION,
                small,
            ),
        ],
    );
    sketch.finish()
}

//! The canonical camera: eye at the origin, looking down -z, viewport at d = 1.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, pixel_to_image_plane};

use crate::Diagram;
use crate::sketch::{CameraRay, Canvas, Sketch, vector};
use crate::style;
use crate::view::{CameraView, FigureView};
use viewray_draw::{Anchor, Baseline, Item, Rect, Stroke};
use viewray_output::number;

/// The image of the canonical figure: `W x H` pixels.
const SIZE: (u32, u32) = (5, 5);
/// The pixel the figure works through, `(row, col)` 0-based.
const EXAMPLE: (u32, u32) = (1, 3);
/// How far past the image plane the rays are drawn, in units of their direction: just
/// through it, and the worked example further.
const RAY_END: f64 = 1.1;
/// How far the worked example's ray is drawn.
const EXAMPLE_END: f64 = 1.45;

/// The canonical perspective camera (slide, 1600 x 900): the eye **e** at the origin with
/// **u**, **v**, **w** along x, y, z, the 1 x 1 viewport at `d = 1` down `-z`, a 5 x 5
/// pixel grid with its centres, and the viewing ray through every centre, one of them
/// worked out with the lecture's formula for `u` and `v`.
///
/// ```text
/// u = (j - 1/2)/W - 1/2,   v = -((i - 1/2)/H - 1/2),   direction = (u, v, -1)
/// ```
pub(crate) fn canonical_camera() -> Diagram {
    canonical_camera_on(Canvas::Slide)
}

/// [`canonical_camera`] on the square canvas (1080 x 1080): the 3D view on top, the
/// formulas and the worked pixel below.
pub(crate) fn canonical_camera_square() -> Diagram {
    canonical_camera_on(Canvas::Square)
}

fn canonical_camera_on(canvas: Canvas) -> Diagram {
    let camera = Camera::canonical(SIZE.0, SIZE.1).expect("a 5 x 5 canonical camera");
    let mut sketch = Sketch::on(canvas);
    sketch.title("The canonical camera");

    let plane_corner = |x: f64, y: f64| DVec3::new(x, y, -1.0);
    let fit_points = [
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 0.55),
        DVec3::new(0.0, 0.6, 0.0),
        DVec3::new(0.6, 0.0, 0.0),
        plane_corner(-0.5, -0.5),
        plane_corner(0.5, -0.5),
        plane_corner(0.5, 0.5),
        plane_corner(-0.5, 0.5),
        DVec3::new(0.2, 0.2, -1.0) * EXAMPLE_END,
        DVec3::new(0.62, -0.62, -1.0),
        DVec3::new(-0.5, 0.62, 0.0),
    ];
    let view = CameraView::fit_orthographic(
        DVec3::new(1.0, 0.7, 1.05),
        DVec3::Y,
        &fit_points,
        match canvas {
            Canvas::Slide => Rect::from_xywh(40.0, 110.0, 790.0, 770.0),
            Canvas::Square => Rect::from_xywh(40.0, 100.0, 1000.0, 600.0),
        },
        60.0,
    );
    let fv = FigureView::Camera(view);
    let at = |p: DVec3| view.to_figure(p).expect("in front of the figure camera");

    let ray_stroke = Stroke::new(style::RAY, style::LINE_THIN);
    let highlight = Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR);
    let pixels = || (0..SIZE.1).flat_map(|row| (0..SIZE.0).map(move |col| (row, col)));

    // The rays beyond the image plane, behind it as the figure camera sees them.
    for pixel in pixels() {
        let (stroke, end) = if pixel == EXAMPLE {
            (highlight.clone(), EXAMPLE_END)
        } else {
            (ray_stroke.clone(), RAY_END)
        };
        sketch.camera_ray(
            &fv,
            CameraRay {
                camera: &camera,
                pixel,
                sample: CameraSample::CENTER,
                t: (1.0, end),
            },
            stroke,
            true,
        );
    }

    // The image plane with its pixel grid.
    let corners =
        [(-0.5, -0.5), (0.5, -0.5), (0.5, 0.5), (-0.5, 0.5)].map(|(x, y)| at(plane_corner(x, y)));
    sketch.push(Item::Polygon {
        points: corners.to_vec(),
        fill: style::IMAGE_PLANE_FILL,
        stroke: None,
    });
    let grid = Stroke::new(style::IMAGE_PLANE, style::LINE_THIN);
    let viewport = DVec2::ONE;
    let plane_point = |row: u32, col: u32, film: DVec2| {
        let uv = pixel_to_image_plane(row, col, film, SIZE, viewport);
        DVec3::new(uv.x, uv.y, -1.0)
    };
    for col in 1..SIZE.0 {
        let top = plane_point(0, col, DVec2::ZERO);
        let bottom = plane_point(SIZE.1 - 1, col, DVec2::new(0.0, 1.0));
        sketch.line(at(top), at(bottom), grid.clone());
    }
    for row in 1..SIZE.1 {
        let left = plane_point(row, 0, DVec2::ZERO);
        let right = plane_point(row, SIZE.0 - 1, DVec2::new(1.0, 0.0));
        sketch.line(at(left), at(right), grid.clone());
    }
    // The example pixel, tinted.
    let cell: Vec<Vec2> = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        .iter()
        .map(|&(sx, sy)| at(plane_point(EXAMPLE.0, EXAMPLE.1, DVec2::new(sx, sy))))
        .collect();
    sketch.push(Item::Polygon {
        points: cell,
        fill: style::HIGHLIGHT.with_alpha(0.35),
        stroke: None,
    });
    sketch.push(Item::Polyline {
        points: corners.to_vec(),
        closed: true,
        stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
    });

    // The rays from the eye to the pixel centres, in front of the plane.
    for pixel in pixels() {
        let stroke = if pixel == EXAMPLE {
            highlight.clone()
        } else {
            ray_stroke.clone()
        };
        sketch.ray_to_pixel_centre(&fv, &camera, pixel, stroke, pixel == EXAMPLE);
    }

    // The camera frame at the eye: here u, v, w are the world's x, y, z.
    let e = at(DVec3::ZERO);
    let frame = camera.frame();
    let basis = [
        (frame.u(), style::U_AXIS, "*u* = $x$", Vec2::new(44.0, 18.0)),
        (frame.v(), style::V_AXIS, "*v* = $y$", Vec2::new(0.0, -30.0)),
        (
            frame.w(),
            style::W_AXIS,
            "*w* = $z$",
            Vec2::new(-30.0, 34.0),
        ),
    ];
    for (axis, color, text, offset) in basis {
        let tip = at(axis * 0.5);
        sketch.arrow(e, tip, Stroke::new(color, style::LINE_THICK));
        sketch.label(text, tip + offset, color, style::LABEL_SIZE);
    }
    sketch.dot(e, style::DOT_RADIUS, style::EYE);
    sketch.label_at(
        "*e*",
        e + Vec2::new(-20.0, -8.0),
        (Anchor::End, Baseline::Bottom),
        style::EYE,
        style::LABEL_SIZE,
    );

    // Dimensions: d from the eye to the plane, above the camera's left side; vw along
    // the bottom edge, vh along the right one.
    let over = |z: f64| at(DVec3::new(-0.5, 0.62, z));
    sketch.dimension(over(0.0), over(-1.0));
    let extension = Stroke::new(style::GRID, style::LINE_THIN);
    sketch.line(e, over(0.0), extension.clone());
    sketch.line(at(plane_corner(-0.5, 0.5)), over(-1.0), extension);
    sketch.label_at(
        "$d$ = 1",
        (over(0.0) + over(-1.0)) / 2.0 + Vec2::new(-8.0, -14.0),
        (Anchor::End, Baseline::Bottom),
        style::TEXT,
        style::LABEL_SIZE,
    );
    let below = |x: f64| at(DVec3::new(x, -0.62, -1.0));
    sketch.dimension(below(-0.5), below(0.5));
    sketch.label_at(
        "$vw$ = 1",
        (below(-0.5) + below(0.5)) / 2.0 + Vec2::new(-10.0, 16.0),
        (Anchor::End, Baseline::Top),
        style::TEXT,
        style::LABEL_SIZE,
    );
    let right = |y: f64| at(DVec3::new(0.62, y, -1.0));
    sketch.dimension(right(-0.5), right(0.5));
    sketch.label_at(
        "$vh$ = 1",
        (right(-0.5) + right(0.5)) / 2.0 + Vec2::new(22.0, 0.0),
        (Anchor::Start, Baseline::Middle),
        style::TEXT,
        style::LABEL_SIZE,
    );

    // The formula panel, with the example pixel worked out from the camera's own ray.
    let ray = camera
        .generate_ray(EXAMPLE.0, EXAMPLE.1, CameraSample::CENTER)
        .expect("a perspective ray");
    let (i, j) = (EXAMPLE.0 + 1, EXAMPLE.1 + 1);
    let uv = pixel_to_image_plane(EXAMPLE.0, EXAMPLE.1, DVec2::splat(0.5), SIZE, viewport);
    let example_title = format!("Pixel $(i, j)$ = ({i}, {j}):");
    let example_uv = format!(
        "$u$ = {},  $v$ = {}",
        number::label(uv.x),
        number::label(uv.y)
    );
    let example_ray = format!("direction {}", vector(ray.direction));
    let size = format!("$W × H$ = {} × {} pixels", SIZE.0, SIZE.1);
    let (l, s) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    if canvas == Canvas::Square {
        sketch.text_lines(
            Vec2::new(50.0, 780.0),
            &[
                ("$u = (j - ½)/W - ½$", style::TEXT, l),
                ("$v = -((i - ½)/H - ½)$", style::TEXT, l),
                ("origin (0, 0, 0)", style::TEXT, l),
                ("direction ($u$, $v$, −1)", style::TEXT, l),
            ],
        );
        sketch.text_lines(
            Vec2::new(580.0, 780.0),
            &[
                (&size, style::ANNOTATION, s),
                ("", style::TEXT, s),
                (&example_title, style::HIGHLIGHT, l),
                (&example_uv, style::HIGHLIGHT, l),
                (&example_ray, style::HIGHLIGHT, s),
            ],
        );
        return sketch.finish();
    }
    sketch.text_lines(
        Vec2::new(1000.0, 180.0),
        &[
            ("Eye *e* at the origin", style::TEXT, l),
            ("Looking down $-z$", style::TEXT, l),
            ("Viewport at $z$ = −1", style::TEXT, l),
            ("$vw = vh$ = 1,  $d$ = 1", style::TEXT, l),
            ("", style::TEXT, l),
            (&size, style::ANNOTATION, s),
            ("$u = (j - ½)/W - ½$", style::TEXT, l),
            ("$v = -((i - ½)/H - ½)$", style::TEXT, l),
            ("origin (0, 0, 0)", style::TEXT, l),
            ("direction ($u$, $v$, −1)", style::TEXT, l),
            ("", style::TEXT, l),
            (&example_title, style::HIGHLIGHT, l),
            (&example_uv, style::HIGHLIGHT, l),
            (&example_ray, style::HIGHLIGHT, l),
        ],
    );
    sketch.finish()
}

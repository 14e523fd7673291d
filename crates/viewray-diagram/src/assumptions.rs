//! Breaking the canonical camera's assumptions one by one, as the lecture does: d != 1,
//! vw != vh != 1, the eye moved, a general basis.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Frame, Perspective, Projection};

use crate::Diagram;
use crate::side::{draw_column_rays, draw_frustum_edges, draw_image_plane, draw_side_frame};
use crate::sketch::{CameraRay, Sketch};
use crate::style;
use crate::view::{CameraView, FigureView, SideView};
use viewray_draw::{Anchor, Baseline, Item, Label, Mapping, Rect, Stroke};
use viewray_output::number;

/// The left edge of the text panel on every assumption slide.
const PANEL_X: f32 = 1040.0;
/// Where the side views and 3D views are drawn.
const DRAWING: Rect = Rect {
    min: Vec2::new(40.0, 120.0),
    max: Vec2::new(990.0, 870.0),
};

/// The four assumptions of the canonical camera, as kept and as broken.
const ASSUMPTIONS: [(&str, &str); 4] = [
    ("$d$ = 1", "$d$ ≠ 1"),
    ("$vw = vh$ = 1", "any $vw$, $vh$"),
    ("eye at the origin", "eye at *e*"),
    ("looking down $-z$", "any basis *u*, *v*, *w*"),
];

/// The text panel: which assumptions are broken (the first `broken`, the last of them
/// highlighted) and the viewing-ray formula so far, its changed lines highlighted.
fn panel(sketch: &mut Sketch, broken: usize, note: &[&str]) {
    let (l, s) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    let mut lines: Vec<(String, viewray_draw::Color, f32)> =
        vec![("Breaking the assumptions:".to_owned(), style::ANNOTATION, s)];
    for (k, (kept, gone)) in ASSUMPTIONS.iter().enumerate() {
        let line = if k < broken {
            let color = if k + 1 == broken {
                style::HIGHLIGHT
            } else {
                style::TEXT
            };
            (format!("✗  {gone}"), color, s)
        } else {
            (format!("✓  {kept}"), style::ANNOTATION, s)
        };
        lines.push(line);
    }
    lines.push((String::new(), style::TEXT, l));
    let mark = |changed: bool| {
        if changed {
            style::HIGHLIGHT
        } else {
            style::TEXT
        }
    };
    let (u, v) = if broken >= 2 {
        ("$u = ((j - ½)/W - ½) vw$", "$v = -((i - ½)/H - ½) vh$")
    } else {
        ("$u = (j - ½)/W - ½$", "$v = -((i - ½)/H - ½)$")
    };
    lines.push((u.to_owned(), mark(broken == 2), l));
    lines.push((v.to_owned(), mark(broken == 2), l));
    let origin = if broken >= 3 {
        "origin *e*"
    } else {
        "origin (0, 0, 0)"
    };
    lines.push((origin.to_owned(), mark(broken == 3), l));
    let direction = if broken >= 4 {
        "direction $u *u* + v *v* - d *w*$"
    } else {
        "direction $(u, v, -d)$"
    };
    lines.push((direction.to_owned(), mark(broken == 1 || broken == 4), l));
    lines.push((String::new(), style::TEXT, l));
    for line in note {
        lines.push(((*line).to_owned(), style::ANNOTATION, s));
    }
    let borrowed: Vec<(&str, viewray_draw::Color, f32)> = lines
        .iter()
        .map(|(text, color, size)| (text.as_str(), *color, *size))
        .collect();
    sketch.text_lines(Vec2::new(PANEL_X, 190.0), &borrowed);
}

/// A perspective camera of `width x height` pixels at `frame`.
fn perspective(frame: Frame, distance: f64, viewport: DVec2, size: (u32, u32)) -> Camera {
    let projection = Projection::Perspective(Perspective {
        distance,
        viewport,
        shift: DVec2::ZERO,
    });
    Camera::new(frame, projection, size.0, size.1).expect("a valid figure camera")
}

/// `d != 1` (slide, 1600 x 900): a side view of the canonical camera's eye with its
/// 1 x 1 viewport moved from `d = 1` (dashed) to `d = 2`: the rays through the same
/// pixels close in, the field of view narrows.
pub(crate) fn assumption_distance() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Breaking the assumptions: $d$ ≠ 1");
    let canonical = Camera::canonical(5, 5).expect("a canonical camera");
    let camera = perspective(Frame::CANONICAL, 2.0, DVec2::ONE, (5, 5));
    let view = SideView::fit((-0.75, 3.1), (-1.35, 1.35), DRAWING);
    let far = 2.7;

    // The canonical camera's frustum and plane, for comparison.
    let ghost = Stroke::new(style::ANNOTATION, style::LINE_THIN).dashed(&[8.0, 6.0]);
    draw_frustum_edges(&mut sketch, &view, &canonical, (0.0, far), &ghost);
    let (ghost_top, _) = draw_image_plane(&mut sketch, &view, &canonical, style::GRID, 0.0);
    sketch.label_at(
        "$d$ = 1",
        ghost_top + Vec2::new(0.0, -14.0),
        (Anchor::Middle, Baseline::Bottom),
        style::ANNOTATION,
        style::SMALL_LABEL_SIZE,
    );

    // The camera with d = 2: its frustum, rays through the pixel centres, and plane.
    let edges = Stroke::new(style::RAY, style::LINE_THIN).dashed(&[8.0, 6.0]);
    draw_frustum_edges(&mut sketch, &view, &camera, (0.0, far / 2.0), &edges);
    let rays = Stroke::new(style::RAY, style::LINE_REGULAR);
    draw_column_rays(&mut sketch, &view, &camera, 2, (0.0, 1.18), &rays);
    let (top, bottom) = draw_image_plane(&mut sketch, &view, &camera, style::IMAGE_PLANE, 0.0);
    sketch.label_at(
        "$d$ = 2",
        top + Vec2::new(0.0, -14.0),
        (Anchor::Middle, Baseline::Bottom),
        style::TEXT,
        style::SMALL_LABEL_SIZE,
    );
    draw_side_frame(&mut sketch, &view, camera.frame(), 0.5, true);
    let e = view.to_figure(DVec3::ZERO);
    sketch.label_at(
        "*e*",
        e + Vec2::new(-20.0, 20.0),
        (Anchor::End, Baseline::Top),
        style::EYE,
        style::LABEL_SIZE,
    );

    // d below, vh beyond the plane.
    let y = -1.2;
    let (from, to) = (
        view.to_figure(DVec3::new(0.0, y, 0.0)),
        view.to_figure(DVec3::new(0.0, y, -2.0)),
    );
    sketch.dimension(from, to);
    let extension = Stroke::new(style::GRID, style::LINE_THIN);
    sketch.line(e + Vec2::new(0.0, 22.0), from, extension.clone());
    sketch.line(bottom, to, extension);
    sketch.label_at(
        "$d$",
        (from + to) / 2.0 + Vec2::new(0.0, 10.0),
        (Anchor::Middle, Baseline::Top),
        style::TEXT,
        style::LABEL_SIZE,
    );
    let side = view.to_figure(DVec3::new(0.0, 0.0, -2.5)).x;
    sketch.dimension(Vec2::new(side, top.y), Vec2::new(side, bottom.y));
    sketch.label_at(
        "$vh$ = 1",
        Vec2::new(side + 16.0, (top.y + bottom.y) / 2.0),
        (Anchor::Start, Baseline::Middle),
        style::TEXT,
        style::SMALL_LABEL_SIZE,
    );
    panel(
        &mut sketch,
        1,
        &["Same viewport, farther away:", "a narrower view"],
    );
    sketch.finish()
}

/// `vw != vh != 1` (slide, 1600 x 900): the image plane seen face-on, a 2 x 1 viewport of
/// 6 x 3 pixels over the canonical 1 x 1 one (dashed): `u` scales with `vw`, `v` with
/// `vh`.
pub(crate) fn assumption_viewport() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Breaking the assumptions: $vw$ ≠ $vh$ ≠ 1");
    let size = (4, 3);
    let viewport = DVec2::new(2.0, 1.5);
    let (w, h) = size;
    let world = Rect::from_corners(Vec2::new(-1.0, -0.75), Vec2::new(1.0, 0.75));
    let map = Mapping::fit(world, Rect::from_xywh(170.0, 240.0, 600.0, 450.0))
        .expect("a non-empty region");
    let plane = |row: u32, col: u32, film: DVec2, size: (u32, u32), viewport: DVec2| {
        map.to_canvas(
            viewray_camera::pixel_to_image_plane(row, col, film, size, viewport).as_vec2(),
        )
    };
    let corners = |size: (u32, u32), viewport: DVec2| {
        let (w, h) = size;
        [
            plane(0, 0, DVec2::ZERO, size, viewport),
            plane(0, w - 1, DVec2::new(1.0, 0.0), size, viewport),
            plane(h - 1, w - 1, DVec2::ONE, size, viewport),
            plane(h - 1, 0, DVec2::new(0.0, 1.0), size, viewport),
        ]
    };

    let outline = corners(size, viewport);
    sketch.push(Item::Polygon {
        points: outline.to_vec(),
        fill: style::IMAGE_PLANE_FILL,
        stroke: None,
    });
    let grid = Stroke::new(style::IMAGE_PLANE, style::LINE_THIN);
    for col in 1..w {
        sketch.line(
            plane(0, col, DVec2::ZERO, size, viewport),
            plane(h - 1, col, DVec2::new(0.0, 1.0), size, viewport),
            grid.clone(),
        );
    }
    for row in 1..h {
        sketch.line(
            plane(row, 0, DVec2::ZERO, size, viewport),
            plane(row, w - 1, DVec2::new(1.0, 0.0), size, viewport),
            grid.clone(),
        );
    }
    sketch.push(Item::Polyline {
        points: outline.to_vec(),
        closed: true,
        stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
    });

    // Axes and pixel centres, with the centres' u and v along the edges.
    let origin = map.to_canvas(Vec2::ZERO);
    sketch.uv_axes(origin, (outline[0], outline[2]), 80.0, 10.0);
    for row in 0..h {
        for col in 0..w {
            let p = plane(row, col, DVec2::splat(0.5), size, viewport);
            sketch.dot(p, style::DOT_RADIUS, style::RAY);
        }
    }
    let small = style::SMALL_LABEL_SIZE;
    for col in 0..w {
        let uv =
            viewray_camera::pixel_to_image_plane(h - 1, col, DVec2::splat(0.5), size, viewport);
        let x = plane(h - 1, col, DVec2::splat(0.5), size, viewport).x;
        sketch.label_at(
            &number::label(uv.x),
            Vec2::new(x, outline[2].y + 12.0),
            (Anchor::Middle, Baseline::Top),
            style::U_AXIS,
            small,
        );
    }
    for row in 0..h {
        let uv = viewray_camera::pixel_to_image_plane(row, 0, DVec2::splat(0.5), size, viewport);
        let y = plane(row, 0, DVec2::splat(0.5), size, viewport).y;
        sketch.label_at(
            &number::label(uv.y),
            Vec2::new(outline[0].x - 14.0, y),
            (Anchor::End, Baseline::Middle),
            style::V_AXIS,
            small,
        );
    }

    // The canonical viewport, dashed, with a leader to its name.
    let canonical = corners((1, 1), DVec2::ONE);
    sketch.push(Item::Polyline {
        points: canonical.to_vec(),
        closed: true,
        stroke: Stroke::new(style::ANNOTATION, style::LINE_REGULAR).dashed(&style::DASH),
    });
    let name_at = Vec2::new(outline[0].x, outline[0].y - 30.0);
    sketch.line(
        name_at + Vec2::new(120.0, 4.0),
        canonical[0],
        Stroke::new(style::ANNOTATION, style::LINE_THIN),
    );
    sketch.label_at(
        "canonical 1 × 1",
        name_at,
        (Anchor::Start, Baseline::Bottom),
        style::ANNOTATION,
        small,
    );

    // vw and vh.
    let below = outline[2].y + 70.0;
    sketch.dimension(
        Vec2::new(outline[0].x, below),
        Vec2::new(outline[1].x, below),
    );
    sketch.label_at(
        &format!("$vw$ = {}", number::label(viewport.x)),
        Vec2::new(origin.x, below + 12.0),
        (Anchor::Middle, Baseline::Top),
        style::TEXT,
        style::LABEL_SIZE,
    );
    let right = outline[1].x + 40.0;
    sketch.dimension(
        Vec2::new(right, outline[1].y),
        Vec2::new(right, outline[2].y),
    );
    sketch.label_at(
        &format!("$vh$ = {}", number::label(viewport.y)),
        Vec2::new(right + 16.0, (origin.y + outline[2].y) / 2.0),
        (Anchor::Start, Baseline::Middle),
        style::TEXT,
        style::LABEL_SIZE,
    );
    sketch.label_at(
        &format!("{w} × {h} pixels"),
        Vec2::new(outline[1].x, outline[0].y - 30.0),
        (Anchor::End, Baseline::Bottom),
        style::ANNOTATION,
        small,
    );
    panel(&mut sketch, 2, &["$u$ scales with $vw$, $v$ with $vh$"]);
    sketch.finish()
}

/// `e != 0` (slide, 1600 x 900): a side view of the world's y and z axes, the canonical
/// camera at the origin (dashed) and the same camera moved to **e**: its rays start at
/// **e** and run parallel to the canonical ones.
pub(crate) fn assumption_eye() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Breaking the assumptions: eye at *e*");
    let canonical = Camera::canonical(5, 5).expect("a canonical camera");
    let eye = DVec3::new(0.0, 1.3, -0.9);
    let moved = Frame::CANONICAL.with_eye(eye).expect("a finite eye");
    let camera = perspective(moved, 1.0, DVec2::ONE, (5, 5));
    let view = SideView::fit((-1.0, 3.3), (-1.0, 2.4), DRAWING);
    let far = 2.2;

    // World axes through the origin.
    let o = view.to_figure(DVec3::ZERO);
    let axis = Stroke::new(style::ANNOTATION, style::LINE_THIN);
    let y_tip = view.to_figure(DVec3::new(0.0, 2.2, 0.0));
    let z_tip = view.to_figure(DVec3::new(0.0, 0.0, 0.85));
    sketch.arrow(
        view.to_figure(DVec3::new(0.0, -0.8, 0.0)),
        y_tip,
        axis.clone(),
    );
    sketch.arrow(view.to_figure(DVec3::new(0.0, 0.0, -3.1)), z_tip, axis);
    sketch.label_at(
        "$y$",
        y_tip + Vec2::new(12.0, 0.0),
        (Anchor::Start, Baseline::Top),
        style::ANNOTATION,
        style::LABEL_SIZE,
    );
    sketch.label_at(
        "$z$",
        z_tip + Vec2::new(0.0, 10.0),
        (Anchor::Start, Baseline::Top),
        style::ANNOTATION,
        style::LABEL_SIZE,
    );

    // The canonical camera, dashed.
    let ghost = Stroke::new(style::GRID, style::LINE_THIN).dashed(&[8.0, 6.0]);
    draw_column_rays(&mut sketch, &view, &canonical, 2, (0.0, far), &ghost);
    draw_image_plane(&mut sketch, &view, &canonical, style::GRID, 0.0);
    sketch.dot(o, style::DOT_RADIUS * 0.8, style::ANNOTATION);
    sketch.label_at(
        "(0, 0, 0)",
        o + Vec2::new(-14.0, 12.0),
        (Anchor::End, Baseline::Top),
        style::ANNOTATION,
        style::SMALL_LABEL_SIZE,
    );

    // The moved camera.
    let rays = Stroke::new(style::RAY, style::LINE_REGULAR);
    draw_column_rays(&mut sketch, &view, &camera, 2, (0.0, far), &rays);
    draw_image_plane(&mut sketch, &view, &camera, style::IMAGE_PLANE, 0.0);
    let e = view.to_figure(eye);
    sketch.arrow(o, e, Stroke::new(style::EYE, style::LINE_REGULAR));
    draw_side_frame(&mut sketch, &view, camera.frame(), 0.5, true);
    // e's coordinates left of the arrow's middle, their box's nearest corner (the lower
    // right, the arrow rising to the right) a gap from the arrow's line.
    let text = format!(
        "*e* = (0, {}, {})",
        number::label(eye.y),
        number::label(eye.z)
    );
    let middle = (o + e) / 2.0;
    let half_height = Label::new(text.as_str(), Vec2::ZERO)
        .with_size(style::SMALL_LABEL_SIZE)
        .bounds()
        .height()
        / 2.0;
    let rise = e - o;
    // Where the arrow's line is at the height of the label's bottom edge.
    let line_x = middle.x + half_height * rise.x / rise.y;
    let gap = 14.0 * rise.length() / -rise.y;
    sketch.label_at(
        &text,
        Vec2::new(line_x - gap, middle.y),
        (Anchor::End, Baseline::Middle),
        style::EYE,
        style::SMALL_LABEL_SIZE,
    );
    panel(
        &mut sketch,
        3,
        &["Same directions;", "the rays start at *e*"],
    );
    sketch.finish()
}

/// A general basis (slide, 1600 x 900): a camera at **e** with its frame **u**, **v**,
/// **w** turned away from the world axes, drawn in 3D through an orthographic figure
/// camera: its viewport at `d` along `-w`, the rays through its pixel centres, and one
/// ray's direction built up as `u u + v v - d w`.
pub(crate) fn assumption_basis() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("Breaking the assumptions: any basis");
    let eye = DVec3::new(1.2, 1.1, 0.5);
    let frame = Frame::from_eye_look_at_up(eye, DVec3::new(3.0, 0.5, -2.3), DVec3::Y)
        .expect("a valid frame");
    let distance = 1.1;
    let viewport = DVec2::new(1.2, 0.9);
    let size = (4, 3);
    let camera = perspective(frame, distance, viewport, size);
    let example = (0u32, 3u32);
    let far = 1.55;

    let plane_point = |row: u32, col: u32, film: DVec2| {
        camera
            .generate_ray(
                row,
                col,
                CameraSample {
                    p_film: film,
                    p_lens: DVec2::splat(0.5),
                },
            )
            .expect("a perspective ray")
            .at(1.0)
    };
    let (w, h) = size;
    let corners = [
        plane_point(0, 0, DVec2::ZERO),
        plane_point(0, w - 1, DVec2::new(1.0, 0.0)),
        plane_point(h - 1, w - 1, DVec2::ONE),
        plane_point(h - 1, 0, DVec2::new(0.0, 1.0)),
    ];
    let mut fit: Vec<DVec3> = corners.to_vec();
    fit.extend(corners.iter().map(|&c| eye + (c - eye) * far));
    fit.extend([
        DVec3::ZERO,
        DVec3::X * 0.8,
        DVec3::Y * 0.8,
        DVec3::Z * 0.8,
        eye + frame.w() * 0.7,
        eye + frame.v() * 0.7,
        eye + frame.u() * 0.7,
    ]);
    let view =
        CameraView::fit_orthographic(DVec3::new(0.25, 0.45, 1.0), DVec3::Y, &fit, DRAWING, 50.0);
    let fv = FigureView::Camera(view);
    let at = |p: DVec3| view.to_figure(p).expect("in view");

    // World axes at the origin.
    let o = at(DVec3::ZERO);
    for (axis, name) in [(DVec3::X, "$x$"), (DVec3::Y, "$y$"), (DVec3::Z, "$z$")] {
        let tip = at(axis * 0.7);
        sketch.arrow(o, tip, Stroke::new(style::ANNOTATION, style::LINE_THIN));
        let out = (tip - o).normalize_or_zero();
        sketch.label(
            name,
            tip + out * 24.0,
            style::ANNOTATION,
            style::SMALL_LABEL_SIZE,
        );
    }
    sketch.arrow(
        o,
        at(eye),
        Stroke::new(style::ANNOTATION, style::LINE_THIN).dashed(&[8.0, 6.0]),
    );

    // Rays beyond the plane, the plane, then the rays up to it.
    let ray_stroke = Stroke::new(style::RAY, style::LINE_THIN);
    let pixels = || (0..h).flat_map(|row| (0..w).map(move |col| (row, col)));
    for pixel in pixels() {
        sketch.camera_ray(
            &fv,
            CameraRay {
                camera: &camera,
                pixel,
                sample: CameraSample::CENTER,
                t: (1.0, far),
            },
            ray_stroke.clone(),
            true,
        );
    }
    let plane_px: Vec<Vec2> = corners.iter().map(|&c| at(c)).collect();
    sketch.push(Item::Polygon {
        points: plane_px.clone(),
        fill: style::IMAGE_PLANE_FILL,
        stroke: Some(Stroke::new(style::IMAGE_PLANE, style::LINE_THICK)),
    });
    for pixel in pixels() {
        sketch.ray_to_pixel_centre(&fv, &camera, pixel, ray_stroke.clone(), pixel == example);
    }

    // The example ray's direction, leg by leg: -d w, then u u, then v v.
    let uv = viewray_camera::pixel_to_image_plane(
        example.0,
        example.1,
        DVec2::splat(0.5),
        size,
        viewport,
    );
    let legs = [
        (-distance * frame.w(), style::W_AXIS),
        (uv.x * frame.u(), style::U_AXIS),
        (uv.y * frame.v(), style::V_AXIS),
    ];
    let mut p = eye;
    for (leg, color) in legs {
        let next = p + leg;
        sketch.arrow(
            at(p),
            at(next),
            Stroke::new(color, style::LINE_REGULAR).dashed(&[10.0, 6.0]),
        );
        p = next;
    }

    // The frame at the eye.
    let e = at(eye);
    for (axis, color, name) in [
        (frame.u(), style::U_AXIS, "*u*"),
        (frame.v(), style::V_AXIS, "*v*"),
        (frame.w(), style::W_AXIS, "*w*"),
    ] {
        let tip = at(eye + axis * 0.6);
        sketch.arrow(e, tip, Stroke::new(color, style::LINE_THICK));
        let out = (tip - e).normalize_or_zero();
        sketch.label(name, tip + out * 26.0, color, style::LABEL_SIZE);
    }
    sketch.dot(e, style::DOT_RADIUS, style::EYE);
    sketch.label_at(
        "*e*",
        e + Vec2::new(16.0, 12.0),
        (Anchor::Start, Baseline::Top),
        style::EYE,
        style::LABEL_SIZE,
    );
    panel(
        &mut sketch,
        4,
        &["dashed: $-d$ *w*, then $u$ *u*, then $v$ *v*"],
    );
    sketch.finish()
}

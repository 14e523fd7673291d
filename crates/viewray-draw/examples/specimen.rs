//! A specimen figure with every item kind, for looking at the drawing layer.
//!
//! `cargo run -p viewray-draw --example specimen -- /tmp/draw-sample` writes
//! `/tmp/draw-sample.png` and `/tmp/draw-sample.svg`.

use glam::Vec2;
use image::{Rgba, RgbaImage};
use viewray_draw::{
    Anchor, ArrowEnds, Baseline, Figure, Item, Label, Mapping, Rect, Sampling, Stroke,
};

/// The specimen's colours (the Okabe–Ito palette), line weights and sizes.
mod style {
    use viewray_draw::Color;

    pub(crate) const BACKGROUND: Color = Color::WHITE;
    pub(crate) const TEXT: Color = Color::from_hex(0x1A1A1A);
    pub(crate) const U_AXIS: Color = Color::from_hex(0xD55E00);
    pub(crate) const V_AXIS: Color = Color::from_hex(0x009E73);
    pub(crate) const W_AXIS: Color = Color::from_hex(0x0072B2);
    pub(crate) const EYE: Color = Color::BLACK;
    pub(crate) const RAY: Color = Color::from_hex(0xE69F00);
    pub(crate) const IMAGE_PLANE: Color = Color::from_hex(0x56B4E9);
    pub(crate) const IMAGE_PLANE_FILL: Color = Color::rgba(0x56, 0xB4, 0xE9, 0x40);
    pub(crate) const OBJECT: Color = Color::from_hex(0x4D4D4D);
    pub(crate) const OBJECT_FILL: Color = Color::from_hex(0xD9D9D9);
    pub(crate) const HIGHLIGHT: Color = Color::from_hex(0xCC79A7);
    pub(crate) const ANNOTATION: Color = Color::from_hex(0x6B6B6B);
    pub(crate) const GRID: Color = Color::from_hex(0xBFBFBF);
    pub(crate) const LINE_THIN: f32 = 2.0;
    pub(crate) const LINE_REGULAR: f32 = 3.5;
    pub(crate) const LINE_THICK: f32 = 5.0;
    pub(crate) const DASH: [f32; 2] = [14.0, 10.0];
    pub(crate) const DOT_RADIUS: f32 = 7.0;
    pub(crate) const SMALL_LABEL_SIZE: f32 = 30.0;
}

/// A side view of a perspective camera: the eye, its basis, the image plane, rays and a
/// sphere, with a small "render" beside it.
pub(crate) fn specimen() -> Figure {
    let mut figure = Figure::new(1600, 900);
    // World units: the eye at the origin looking along +x (that is, -w), y up.
    let world = Rect::from_corners(Vec2::new(-2.2, -2.8), Vec2::new(9.2, 3.2));
    let canvas = Rect::from_xywh(40.0, 40.0, 1100.0, 820.0);
    let map = Mapping::fit(world, canvas).expect("non-empty rectangles");
    let at = |x: f32, y: f32| map.to_canvas(Vec2::new(x, y));

    let e = at(0.0, 0.0);
    let d = 3.0;
    let half_vh = 1.5;
    let sphere = (Vec2::new(7.0, 0.4), 1.2);

    // The viewing frustum, dashed, behind everything.
    figure.push(Item::Polyline {
        points: vec![e, at(8.6, 8.6 * half_vh / d), at(8.6, -8.6 * half_vh / d)],
        closed: true,
        stroke: Stroke::new(style::ANNOTATION, style::LINE_THIN).dashed(&style::DASH),
    });

    // The sphere, and the image plane seen edge-on with its translucent slab.
    figure.push(Item::Ellipse {
        center: map.to_canvas(sphere.0),
        radii: Vec2::splat(map.length_to_canvas(sphere.1)),
        rotation: 0.0,
        fill: Some(style::OBJECT_FILL),
        stroke: Some(Stroke::new(style::OBJECT, style::LINE_REGULAR)),
    });
    figure.push(Item::Polygon {
        points: vec![
            at(d, -half_vh),
            at(d, half_vh),
            at(d + 0.5, half_vh + 0.35),
            at(d + 0.5, -half_vh + 0.35),
        ],
        fill: style::IMAGE_PLANE_FILL,
        stroke: Some(Stroke::new(style::IMAGE_PLANE, style::LINE_THIN)),
    });
    figure.push(Item::Line {
        from: at(d, -half_vh),
        to: at(d, half_vh),
        stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
    });

    // Viewing rays through three pixel centres on the plane.
    for v in [-1.0, 0.1, 1.0] {
        let through = Vec2::new(d, v);
        let far = through * (8.4 / d);
        figure.push(Item::Arrow {
            from: e,
            to: map.to_canvas(far),
            stroke: Stroke::new(style::RAY, style::LINE_REGULAR),
            ends: ArrowEnds::End,
        });
        figure.push(Item::Dot {
            center: map.to_canvas(through),
            radius: style::DOT_RADIUS * 0.8,
            color: style::RAY,
        });
    }
    let ray = at(8.4 * 1.0 / d, 8.4 * 1.0 / d) - e;
    figure.push(
        Label::new(
            "viewing ray",
            e + ray * 0.62 + ray.perp().normalize() * 24.0,
        )
        .with_size(style::SMALL_LABEL_SIZE)
        .with_color(style::RAY)
        .with_rotation(-ray.y.atan2(ray.x)),
    );

    // The camera basis at the eye: v up, w back, u out of the page.
    let axis = map.length_to_canvas(1.3);
    figure.push(Item::Arrow {
        from: e,
        to: e + Vec2::new(0.0, -axis),
        stroke: Stroke::new(style::V_AXIS, style::LINE_THICK),
        ends: ArrowEnds::End,
    });
    figure.push(Item::Arrow {
        from: e,
        to: e + Vec2::new(-axis, 0.0),
        stroke: Stroke::new(style::W_AXIS, style::LINE_THICK),
        ends: ArrowEnds::End,
    });
    figure.push(Item::Ellipse {
        center: e,
        radii: Vec2::splat(16.0),
        rotation: 0.0,
        fill: Some(style::BACKGROUND),
        stroke: Some(Stroke::new(style::U_AXIS, style::LINE_REGULAR)),
    });
    figure.push(Item::Dot {
        center: e,
        radius: style::DOT_RADIUS * 0.7,
        color: style::U_AXIS,
    });
    figure.push(Label::vector("v", e + Vec2::new(30.0, -axis + 10.0)).with_color(style::V_AXIS));
    figure.push(Label::vector("w", e + Vec2::new(-axis, 34.0)).with_color(style::W_AXIS));
    figure.push(Label::vector("u", e + Vec2::new(-36.0, -36.0)).with_color(style::U_AXIS));
    figure.push(Label::vector("e", e + Vec2::new(-28.0, 38.0)).with_color(style::EYE));

    // Dimensions: d from the eye to the plane, v_h along the plane.
    let below = -half_vh - 0.9;
    figure.push(Item::Arrow {
        from: at(0.0, below),
        to: at(d, below),
        stroke: Stroke::new(style::ANNOTATION, style::LINE_THIN),
        ends: ArrowEnds::Both,
    });
    for x in [0.0, d] {
        figure.push(Item::Line {
            from: at(x, below - 0.25),
            to: at(x, if x == 0.0 { -0.35 } else { -half_vh - 0.1 }),
            stroke: Stroke::new(style::GRID, style::LINE_THIN),
        });
    }
    figure.push(
        Label::math("d", at(d / 2.0, below))
            .with_anchor(Anchor::Middle, Baseline::Bottom)
            .with_color(style::TEXT),
    );
    let side = d - 0.45;
    figure.push(Item::Arrow {
        from: at(side, -half_vh),
        to: at(side, half_vh),
        stroke: Stroke::new(style::ANNOTATION, style::LINE_THIN),
        ends: ArrowEnds::Both,
    });
    figure.push(
        Label::math("v_h", at(side - 0.12, -0.45)).with_anchor(Anchor::End, Baseline::Middle),
    );

    // A hit point on the sphere.
    let hit = at(5.86, 5.86 * 0.1 / d);
    figure.push(Item::Dot {
        center: hit,
        radius: style::DOT_RADIUS,
        color: style::HIGHLIGHT,
    });

    // The "render": a 16 x 9 image of the sphere, shown pixel by pixel, with its width.
    let render = tiny_render(16, 9);
    let picture = Rect::from_xywh(1180.0, 300.0, 384.0, 216.0);
    figure.push(Item::Image {
        pixels: render,
        rect: picture,
        sampling: Sampling::Nearest,
    });
    figure.push(Item::Polyline {
        points: vec![
            picture.min,
            Vec2::new(picture.max.x, picture.min.y),
            picture.max,
            Vec2::new(picture.min.x, picture.max.y),
        ],
        closed: true,
        stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THIN),
    });
    let above = picture.min.y - 30.0;
    figure.push(Item::Arrow {
        from: Vec2::new(picture.min.x, above),
        to: Vec2::new(picture.max.x, above),
        stroke: Stroke::new(style::ANNOTATION, style::LINE_THIN),
        ends: ArrowEnds::Both,
    });
    figure.push(
        Label::math("vw", Vec2::new(picture.center().x, above - 8.0))
            .with_anchor(Anchor::Middle, Baseline::Bottom),
    );
    figure.push(
        Label::new(
            "W × H = 16 × 9 pixels",
            Vec2::new(picture.center().x, picture.max.y + 20.0),
        )
        .with_size(style::SMALL_LABEL_SIZE)
        .with_anchor(Anchor::Middle, Baseline::Top),
    );
    figure.push(
        Label::new("x_{ij}^2, AV, (i, j)", Vec2::new(picture.center().x, 700.0))
            .with_size(style::SMALL_LABEL_SIZE)
            .with_color(style::ANNOTATION),
    );
    figure
}

/// A tiny flat-shaded render of a grey disc on a sky gradient.
fn tiny_render(width: u32, height: u32) -> RgbaImage {
    RgbaImage::from_fn(width, height, |col, row| {
        let u = (col as f32 + 0.5) / width as f32 - 0.5;
        let v = -((row as f32 + 0.5) / height as f32 - 0.5);
        let (du, dv) = (u * 16.0 / 9.0 - 0.25, v - 0.05);
        if du * du + dv * dv < 0.12 {
            Rgba([180, 180, 180, 255])
        } else {
            let t = (v + 0.5).clamp(0.0, 1.0);
            Rgba([
                (230.0 - 120.0 * t) as u8,
                (240.0 - 60.0 * t) as u8,
                255,
                255,
            ])
        }
    })
}

fn main() -> std::io::Result<()> {
    let stem = std::env::args()
        .nth(1)
        .unwrap_or_else(|| "/tmp/diagram-sample".to_owned());
    let figure = specimen();
    viewray_draw::write_png(&figure, format!("{stem}.png"))?;
    viewray_draw::write_svg(&figure, format!("{stem}.svg"))?;
    Ok(())
}

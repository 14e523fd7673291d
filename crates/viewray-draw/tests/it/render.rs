//! Rendering to pixels: each item kind inks where it should and nowhere else.

use glam::Vec2;
use image::{Rgba, RgbaImage};
use viewray_draw::raster::{render, render_scaled};
use viewray_draw::{
    Anchor, ArrowEnds, Baseline, Color, Figure, Item, Label, Rect, Sampling, Stroke, svg,
};

const WHITE: Rgba<u8> = Rgba([255, 255, 255, 255]);
const INK: Color = Color::from_hex(0x202020);
const PINK: Color = Color::from_hex(0xCC79A7);
const SKY_BLUE: Color = Color::from_hex(0x56B4E9);
const GREY: Color = Color::from_hex(0x4D4D4D);
const BLUE: Color = Color::from_hex(0x0072B2);

/// Length of an arrowhead for a line of `width`, as `Item::Arrow` documents it.
fn head_length(width: f32) -> f32 {
    4.0 * width + 10.0
}

/// Half-width of an arrowhead at its barbs, as a fraction of its length (documented).
const HEAD_ASPECT: f32 = 0.42;

fn figure() -> Figure {
    Figure::new(400, 300)
}

fn inked(image: &RgbaImage, x: u32, y: u32) -> bool {
    *image.get_pixel(x, y) != WHITE
}

/// The number of non-background pixels in column `x`.
fn inked_in_column(image: &RgbaImage, x: u32) -> usize {
    (0..image.height()).filter(|&y| inked(image, x, y)).count()
}

/// Every non-background pixel, as (x, y).
fn ink(image: &RgbaImage) -> Vec<(u32, u32)> {
    image
        .enumerate_pixels()
        .filter(|(_, _, p)| **p != WHITE)
        .map(|(x, y, _)| (x, y))
        .collect()
}

#[test]
fn empty_figure_is_background() {
    let image = render(&figure());
    assert_eq!(image.dimensions(), (400, 300));
    assert!(ink(&image).is_empty());
}

#[test]
fn horizontal_line_colours_its_row_and_nothing_far_away() {
    let mut fig = figure();
    fig.push(Item::Line {
        from: Vec2::new(50.0, 100.0),
        to: Vec2::new(350.0, 100.0),
        stroke: Stroke::new(INK, 4.0),
    });
    let image = render(&fig);
    assert_eq!(*image.get_pixel(200, 99), Rgba([0x20, 0x20, 0x20, 255]));
    assert!(inked(&image, 200, 100) && inked(&image, 60, 101));
    // Round caps reach 2 px past the ends, antialiasing one more; nothing beyond.
    for (x, y) in ink(&image) {
        assert!((97..=103).contains(&y), "ink at row {y}");
        assert!((47..=353).contains(&x), "ink at column {x}");
    }
}

#[test]
fn a_scaled_render_draws_the_same_figure_smaller() {
    let mut fig = figure();
    fig.push(Item::Line {
        from: Vec2::new(50.0, 100.0),
        to: Vec2::new(350.0, 100.0),
        stroke: Stroke::new(INK, 4.0),
    });
    let half = render_scaled(&fig, 0.5);
    assert_eq!(half.dimensions(), (200, 150));
    // The 4-wide line at row 100 becomes a 2-wide line at row 50, from x 25 to 175.
    assert!(inked(&half, 100, 49) && inked(&half, 100, 50));
    for (x, y) in ink(&half) {
        assert!((48..=52).contains(&y), "ink at row {y}");
        assert!((23..=177).contains(&x), "ink at column {x}");
    }
}

#[test]
fn dashed_line_has_gaps_where_the_pattern_says() {
    let mut fig = figure();
    fig.push(Item::Line {
        from: Vec2::new(0.0, 50.0),
        to: Vec2::new(400.0, 50.0),
        stroke: Stroke::new(INK, 4.0).dashed(&[20.0, 20.0]),
    });
    let image = render(&fig);
    for x in [10, 50, 90, 370] {
        assert!(inked(&image, x, 50), "dash at x = {x}");
    }
    for x in [30, 70, 110, 390] {
        assert!(!inked(&image, x, 50), "gap at x = {x}");
    }
}

#[test]
fn translucent_colours_blend_with_the_background() {
    let mut fig = figure();
    fig.push(Item::Line {
        from: Vec2::new(0.0, 50.5),
        to: Vec2::new(400.0, 50.5),
        stroke: Stroke::new(Color::BLACK.with_alpha(0.5), 9.0),
    });
    let p = render(&fig).get_pixel(200, 50).0;
    assert!((120..=136).contains(&p[0]), "{p:?}");
    assert_eq!(p[3], 255);
}

#[test]
fn arrowheads_point_at_the_tip() {
    let width = 4.0;
    let head = head_length(width);
    let (tail, tip) = (100.0, 300.0);
    // Columns a little ahead of the notch at the back of a head, and as far from the tail.
    let near_tip = (tip - 0.7 * head) as u32;
    let near_tail = (tail + 0.7 * head) as u32;

    for reversed in [false, true] {
        let (from, to) = if reversed { (tip, tail) } else { (tail, tip) };
        let mut fig = figure();
        fig.push(Item::Arrow {
            from: Vec2::new(from, 150.0),
            to: Vec2::new(to, 150.0),
            stroke: Stroke::new(INK, width),
            ends: ArrowEnds::End,
        });
        let image = render(&fig);
        let (head_column, tail_column) = if reversed {
            (near_tail, near_tip)
        } else {
            (near_tip, near_tail)
        };
        let head_span = inked_in_column(&image, head_column);
        let tail_span = inked_in_column(&image, tail_column);
        assert!(
            head_span as f32 > 1.2 * HEAD_ASPECT * head,
            "reversed {reversed}: head column spans {head_span}"
        );
        assert!(
            tail_span <= 6,
            "reversed {reversed}: shaft column spans {tail_span}"
        );
        // The tip is at the end point, not past it.
        let tip_x = to as u32;
        assert!(inked(
            &image,
            if reversed { tip_x + 2 } else { tip_x - 2 },
            150
        ));
        assert!(!inked(
            &image,
            if reversed { tip_x - 3 } else { tip_x + 3 },
            150
        ));
    }
}

#[test]
fn double_headed_arrow_has_two_heads() {
    let mut fig = figure();
    fig.push(Item::Arrow {
        from: Vec2::new(100.0, 150.0),
        to: Vec2::new(300.0, 150.0),
        stroke: Stroke::new(INK, 3.0),
        ends: ArrowEnds::Both,
    });
    let image = render(&fig);
    let head = head_length(3.0);
    let spans = [
        inked_in_column(&image, (100.0 + 0.7 * head) as u32),
        inked_in_column(&image, 200),
        inked_in_column(&image, (300.0 - 0.7 * head) as u32),
    ];
    assert!(spans[0] > 10 && spans[2] > 10 && spans[1] <= 5, "{spans:?}");
}

#[test]
fn dot_fills_a_disc() {
    let mut fig = figure();
    fig.push(Item::Dot {
        center: Vec2::new(200.5, 150.5),
        radius: 10.0,
        color: PINK,
    });
    let image = render(&fig);
    let c = PINK;
    assert_eq!(*image.get_pixel(200, 150), Rgba([c.r, c.g, c.b, 255]));
    assert!(inked(&image, 208, 150));
    for (x, y) in ink(&image) {
        let d = Vec2::new(x as f32 + 0.5, y as f32 + 0.5).distance(Vec2::new(200.5, 150.5));
        assert!(d < 11.5, "ink at ({x}, {y})");
    }
}

#[test]
fn polygon_fills_inside_and_strokes_its_edges() {
    let mut fig = figure();
    let fill = SKY_BLUE;
    let edge = GREY;
    fig.push(Item::Polygon {
        points: vec![
            Vec2::new(100.0, 250.0),
            Vec2::new(300.0, 250.0),
            Vec2::new(200.0, 50.0),
        ],
        fill,
        stroke: Some(Stroke::new(edge, 4.0)),
    });
    let image = render(&fig);
    assert_eq!(
        *image.get_pixel(200, 180),
        Rgba([fill.r, fill.g, fill.b, 255])
    );
    assert_eq!(
        *image.get_pixel(200, 250),
        Rgba([edge.r, edge.g, edge.b, 255])
    );
    assert!(!inked(&image, 120, 80), "outside the triangle");
}

#[test]
fn open_polyline_lacks_the_closing_edge() {
    let points = vec![
        Vec2::new(100.0, 250.0),
        Vec2::new(300.0, 250.0),
        Vec2::new(200.0, 50.0),
    ];
    let polyline = |closed: bool| {
        let mut fig = figure();
        fig.push(Item::Polyline {
            points: points.clone(),
            closed,
            stroke: Stroke::new(INK, 3.0),
        });
        render(&fig)
    };
    let (open, closed) = (polyline(false), polyline(true));
    // Midpoint of the closing edge from (200, 50) back to (100, 250).
    assert!(!inked(&open, 150, 150));
    assert!(inked(&closed, 150, 150));
    assert!(inked(&open, 250, 150) && inked(&closed, 250, 150));
    assert!(!inked(&closed, 200, 180), "a polyline is not filled");
}

#[test]
fn rotated_ellipse_turns_counter_clockwise() {
    let mut fig = figure();
    // A 100 x 20 ellipse turned 90 degrees stands upright.
    fig.push(Item::Ellipse {
        center: Vec2::new(200.0, 150.0),
        radii: Vec2::new(100.0, 20.0),
        rotation: std::f32::consts::FRAC_PI_2,
        fill: Some(INK),
        stroke: None,
    });
    let image = render(&fig);
    assert!(inked(&image, 200, 70) && inked(&image, 200, 230));
    assert!(!inked(&image, 260, 150) && !inked(&image, 140, 150));

    // Turned 30 degrees counter-clockwise on screen, its right end rises (smaller y).
    let mut fig = figure();
    fig.push(Item::Ellipse {
        center: Vec2::new(200.0, 150.0),
        radii: Vec2::new(100.0, 10.0),
        rotation: 30f32.to_radians(),
        fill: None,
        stroke: Some(Stroke::new(INK, 3.0)),
    });
    let image = render(&fig);
    let end = Vec2::new(200.0, 150.0)
        + 99.0 * Vec2::new(30f32.to_radians().cos(), -30f32.to_radians().sin());
    assert!(
        inked(&image, end.x as u32, end.y as u32),
        "right end at {end}"
    );
    assert!(!inked(&image, 200, 150), "an outlined ellipse is hollow");
}

#[test]
fn label_ink_lies_inside_its_bounds() {
    let cases = [
        Label::math("v_h", Vec2::new(200.0, 150.0)),
        Label::vector("e", Vec2::new(50.0, 40.0)).with_anchor(Anchor::Start, Baseline::Top),
        Label::new("viewing ray", Vec2::new(200.0, 150.0)).with_rotation(0.5),
        Label::math("vw", Vec2::new(390.0, 290.0)).with_anchor(Anchor::End, Baseline::Bottom),
    ];
    for label in cases {
        let mut fig = figure();
        fig.push(label.clone());
        let image = render(&fig);
        let bounds = label.bounds().expand(1.0);
        let pixels = ink(&image);
        assert!(
            pixels.len() > 50,
            "{:?} drew {} pixels",
            label.text,
            pixels.len()
        );
        for (x, y) in pixels {
            let centre = Vec2::new(x as f32 + 0.5, y as f32 + 0.5);
            assert!(
                bounds.contains(centre),
                "{:?}: ink at ({x}, {y}) outside {bounds:?}",
                label.text
            );
        }
    }
}

#[test]
fn label_ink_is_antialiased_and_coloured() {
    let mut fig = figure();
    fig.push(
        Label::vector("w", Vec2::new(200.0, 150.0))
            .with_size(80.0)
            .with_color(BLUE),
    );
    let image = render(&fig);
    let c = BLUE;
    let full = Rgba([c.r, c.g, c.b, 255]);
    let pixels = ink(&image);
    let solid = pixels
        .iter()
        .filter(|&&(x, y)| *image.get_pixel(x, y) == full)
        .count();
    let partial = pixels.len() - solid;
    assert!(solid > 200, "solid glyph interior: {solid}");
    assert!(partial > 50, "antialiased edge pixels: {partial}");
}

#[test]
fn embedded_image_fills_its_rectangle_pixel_by_pixel() {
    let red = Rgba([230, 20, 20, 255]);
    let green = Rgba([20, 200, 20, 255]);
    let blue = Rgba([20, 20, 230, 255]);
    let clear = Rgba([0, 0, 0, 0]);
    let pixels = RgbaImage::from_vec(
        2,
        2,
        [red, green, blue, clear].iter().flat_map(|p| p.0).collect(),
    )
    .expect("2 x 2 RGBA");
    let mut fig = figure();
    fig.push(Item::Image {
        pixels,
        rect: Rect::from_xywh(100.0, 100.0, 200.0, 100.0),
        sampling: Sampling::Nearest,
    });
    let image = render(&fig);
    assert_eq!(*image.get_pixel(110, 110), red);
    assert_eq!(*image.get_pixel(290, 110), green);
    assert_eq!(*image.get_pixel(110, 190), blue);
    assert_eq!(
        *image.get_pixel(290, 190),
        WHITE,
        "transparent pixels show the background"
    );
    assert_eq!(
        *image.get_pixel(199, 110),
        red,
        "nearest sampling keeps edges sharp"
    );
    assert_eq!(*image.get_pixel(201, 110), green);
    assert!(!inked(&image, 95, 150) && !inked(&image, 305, 150) && !inked(&image, 200, 95));
}

/// `figure` written by `write_png`, as bytes.
fn png_bytes(figure: &Figure) -> std::io::Result<Vec<u8>> {
    let dir = tempfile::tempdir().expect("a temporary directory");
    let path = dir.path().join("figure.png");
    viewray_draw::write_png(figure, &path)?;
    Ok(std::fs::read(&path).expect("the PNG just written"))
}

#[test]
fn rendering_is_deterministic() {
    let build = || {
        let mut fig = Figure::new(1600, 900);
        fig.push(Item::Arrow {
            from: Vec2::new(100.0, 100.0),
            to: Vec2::new(900.0, 500.0),
            stroke: Stroke::new(INK, 3.5),
            ends: ArrowEnds::End,
        });
        fig.push(Label::math("v_h", Vec2::new(400.0, 400.0)));
        fig
    };
    let (a, b) = (
        png_bytes(&build()).expect("png"),
        png_bytes(&build()).expect("png"),
    );
    assert_eq!(a, b);
    let document = |fig: &Figure| svg::document(fig, svg::SvgText::Paths);
    assert_eq!(document(&build()), document(&build()));
}

#[test]
fn png_has_no_metadata_chunks() {
    let png = png_bytes(&figure()).expect("png");
    let mut chunks = Vec::new();
    let mut at = 8;
    while at + 8 <= png.len() {
        let length = u32::from_be_bytes(png[at..at + 4].try_into().expect("4 bytes")) as usize;
        chunks.push(String::from_utf8_lossy(&png[at + 4..at + 8]).into_owned());
        at += 12 + length;
    }
    assert_eq!(chunks.first().map(String::as_str), Some("IHDR"));
    assert_eq!(chunks.last().map(String::as_str), Some("IEND"));
    assert!(
        chunks
            .iter()
            .all(|c| c == "IHDR" || c == "IDAT" || c == "IEND"),
        "{chunks:?}"
    );
    let decoded = image::load_from_memory(&png).expect("a PNG").to_rgba8();
    assert_eq!(decoded, render(&figure()));
}

#[test]
fn zero_sized_figure_renders_empty_and_does_not_encode() {
    let fig = Figure::new(0, 10);
    assert_eq!(render(&fig).dimensions(), (0, 10));
    let error = png_bytes(&fig).expect_err("PNG needs a pixel");
    assert_eq!(error.kind(), std::io::ErrorKind::InvalidInput);
}

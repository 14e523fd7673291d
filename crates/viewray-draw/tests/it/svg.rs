//! SVG output: well-formed XML with one element per item, matching the PNG geometry.

use std::collections::BTreeMap;

use base64::Engine as _;
use glam::Vec2;
use image::{Rgba, RgbaImage};
use viewray_draw::svg::{SvgText, document};
use viewray_draw::{ArrowEnds, Color, Figure, Item, Label, Rect, Sampling, Stroke};

/// Okabe–Ito orange.
const ORANGE: Color = Color::from_hex(0xE69F00);
const DASH: [f32; 2] = [14.0, 10.0];
/// Sky blue, and the same a quarter opaque (alpha 0x40).
const SKY_BLUE: Color = Color::from_hex(0x56B4E9);
const SKY_BLUE_FILL: Color = Color::rgba(0x56, 0xB4, 0xE9, 0x40);
const GREY: Color = Color::from_hex(0x4D4D4D);
const LIGHT_GREY: Color = Color::from_hex(0xD9D9D9);

/// One item of every kind.
fn every_kind() -> Figure {
    let mut fig = Figure::new(800, 600);
    let stroke = Stroke::new(ORANGE, 3.0);
    fig.push(Item::Line {
        from: Vec2::new(10.0, 20.0),
        to: Vec2::new(300.0, 20.0),
        stroke: stroke.clone().dashed(&DASH),
    });
    fig.push(Item::Polyline {
        points: vec![
            Vec2::new(10.0, 40.0),
            Vec2::new(50.0, 80.0),
            Vec2::new(90.0, 40.0),
        ],
        closed: false,
        stroke: stroke.clone(),
    });
    fig.push(Item::Arrow {
        from: Vec2::new(100.0, 300.0),
        to: Vec2::new(400.0, 300.0),
        stroke: stroke.clone(),
        ends: ArrowEnds::Both,
    });
    fig.push(Item::Dot {
        center: Vec2::new(50.0, 500.0),
        radius: 7.0,
        color: Color::BLACK,
    });
    fig.push(Item::Polygon {
        points: vec![
            Vec2::new(500.0, 100.0),
            Vec2::new(700.0, 100.0),
            Vec2::new(600.0, 250.0),
        ],
        fill: SKY_BLUE_FILL,
        stroke: Some(Stroke::new(SKY_BLUE, 2.0)),
    });
    fig.push(Item::Ellipse {
        center: Vec2::new(600.0, 450.0),
        radii: Vec2::new(80.0, 40.0),
        rotation: 0.3,
        fill: Some(LIGHT_GREY),
        stroke: Some(Stroke::new(GREY, 3.0)),
    });
    fig.push(Label::math("v_h", Vec2::new(200.0, 400.0)));
    fig.push(Label::new("a < b & \"c\"", Vec2::new(200.0, 550.0)).with_rotation(0.2));
    fig.push(Item::Image {
        pixels: RgbaImage::from_pixel(4, 3, Rgba([10, 20, 30, 255])),
        rect: Rect::from_xywh(300.0, 420.0, 80.0, 60.0),
        sampling: Sampling::Nearest,
    });
    fig
}

/// Element name -> count, over the whole document.
fn element_counts(svg: &str) -> BTreeMap<String, usize> {
    let doc = roxmltree::Document::parse(svg).expect("well-formed SVG");
    let root = doc.root_element();
    assert_eq!(root.tag_name().name(), "svg");
    assert_eq!(
        root.tag_name().namespace(),
        Some("http://www.w3.org/2000/svg")
    );
    let mut counts = BTreeMap::new();
    for node in root.descendants().filter(|n| n.is_element()) {
        *counts.entry(node.tag_name().name().to_owned()).or_insert(0) += 1;
    }
    counts
}

#[track_caller]
fn check_counts(svg: &str, expected: &[(&str, usize)]) {
    let counts = element_counts(svg);
    let expected: BTreeMap<String, usize> = expected
        .iter()
        .map(|(k, v)| ((*k).to_owned(), *v))
        .collect();
    assert_eq!(counts, expected);
}

#[test]
fn paths_mode_has_one_element_per_item() {
    check_counts(
        &document(&every_kind(), SvgText::Paths),
        &[
            ("svg", 1),
            ("rect", 1), // background
            ("line", 2), // the line, the arrow's shaft
            ("polyline", 1),
            ("g", 1),       // the arrow
            ("polygon", 3), // two arrowheads, the filled polygon
            ("circle", 1),
            ("ellipse", 1),
            ("path", 2), // the two labels' glyph outlines
            ("image", 1),
        ],
    );
}

#[test]
fn elements_mode_writes_text_with_script_tspans() {
    let svg = document(&every_kind(), SvgText::Elements);
    check_counts(
        &svg,
        &[
            ("svg", 1),
            ("rect", 1),
            ("line", 2),
            ("polyline", 1),
            ("g", 1),
            ("polygon", 3),
            ("circle", 1),
            ("ellipse", 1),
            ("text", 2),
            ("tspan", 3), // "v", subscript "h", and the plain label
            ("image", 1),
        ],
    );
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let texts: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("text"))
        .collect();
    assert!(
        texts[0]
            .attribute("font-family")
            .expect("family")
            .starts_with("'DejaVu Sans'")
    );
    assert_eq!(texts[0].attribute("font-style"), Some("italic"));
    assert_eq!(texts[0].attribute("text-anchor"), Some("middle"));
    let spans: Vec<_> = texts[0].children().filter(|n| n.is_element()).collect();
    assert_eq!(spans[0].text(), Some("v"));
    assert_eq!(spans[1].text(), Some("h"));
    assert_eq!(spans[1].attribute("dy"), Some("8"), "0.2 em lower at 40 px");
    assert_eq!(spans[1].attribute("font-size"), Some("28"));
    assert_eq!(texts[1].text(), None);
    let plain: String = texts[1]
        .descendants()
        .filter(|n| n.is_text())
        .filter_map(|n| n.text())
        .collect();
    assert_eq!(plain, "a < b & \"c\"");
    assert!(
        texts[1]
            .attribute("transform")
            .expect("rotated")
            .starts_with("rotate(-11.46 ")
    );
}

#[test]
fn attributes_carry_geometry_and_style() {
    let svg = document(&every_kind(), SvgText::Paths);
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    assert_eq!(doc.root_element().attribute("viewBox"), Some("0 0 800 600"));
    let line = doc
        .descendants()
        .find(|n| n.has_tag_name("line"))
        .expect("a line");
    assert_eq!(line.attribute("x1"), Some("10"));
    assert_eq!(line.attribute("x2"), Some("300"));
    assert_eq!(line.attribute("stroke"), Some("#e69f00"));
    assert_eq!(line.attribute("stroke-dasharray"), Some("14 10"));
    let filled = doc
        .descendants()
        .find(|n| n.has_tag_name("polygon") && n.attribute("fill-opacity").is_some())
        .expect("the translucent polygon");
    assert_eq!(filled.attribute("fill-opacity"), Some("0.251"));
    let label = doc
        .descendants()
        .find(|n| n.has_tag_name("path"))
        .expect("a label");
    assert_eq!(label.attribute("aria-label"), Some("v_h"));
    assert!(label.attribute("d").expect("outline").starts_with('M'));
}

#[test]
fn embedded_image_is_a_png_data_uri() {
    let svg = document(&every_kind(), SvgText::Paths);
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let image = doc
        .descendants()
        .find(|n| n.has_tag_name("image"))
        .expect("an image");
    let href = image
        .attribute(("http://www.w3.org/1999/xlink", "href"))
        .expect("xlink:href");
    let data = href
        .strip_prefix("data:image/png;base64,")
        .expect("a PNG data URI");
    let png = base64::engine::general_purpose::STANDARD
        .decode(data)
        .expect("base64");
    let decoded = image::load_from_memory(&png).expect("a PNG").to_rgba8();
    // Nearest sampling embeds the 4 x 3 image enlarged 20 times, in solid blocks.
    assert_eq!(decoded.dimensions(), (80, 60));
    assert!(decoded.pixels().all(|p| *p == Rgba([10, 20, 30, 255])));
    assert_eq!(image.attribute("width"), Some("80"));
}

#[test]
fn transparent_background_writes_no_rect() {
    let mut fig = Figure::new(10, 10);
    fig.background = Color::TRANSPARENT;
    check_counts(&document(&fig, SvgText::Paths), &[("svg", 1)]);
}

#[test]
fn formula_runs_become_tspans_in_their_own_faces() {
    let mut fig = Figure::new(400, 100);
    fig.push(Label::new("$d *w*$", Vec2::new(200.0, 50.0)));
    let svg = document(&fig, SvgText::Elements);
    let doc = roxmltree::Document::parse(&svg).expect("well-formed SVG");
    let spans: Vec<_> = doc
        .descendants()
        .filter(|n| n.has_tag_name("tspan"))
        .map(|n| {
            (
                n.text().unwrap_or_default().to_owned(),
                n.attribute("font-style"),
                n.attribute("font-weight"),
            )
        })
        .collect();
    assert_eq!(
        spans,
        [
            ("d".to_owned(), Some("italic"), Some("normal")),
            (" ".to_owned(), None, None),
            ("w".to_owned(), Some("normal"), Some("bold")),
        ]
    );
}

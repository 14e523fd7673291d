//! "Save as slide": the render, the side view (and the top view) and the numbers on one
//! 1920 x 1080 picture, painted by viewray-draw, for a lecture's slides.

use glam::Vec2;
use image::{DynamicImage, RgbaImage};
use serde_json::Value;
use viewray_camera::{Camera, CameraSample};
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
use viewray_draw::{
    Anchor, Baseline, Color, FontFace, Item, Label, Rect, Sampling, raster, wrap_parts,
};
use viewray_json::{PixelIndices, frame_line, ray_line};
use viewray_output::{Compression, encode_png};
use viewray_render::{RenderSettings, View, render_view};

use crate::ServedScene;
use crate::api::Reply;

/// The slide's size in pixels.
pub(crate) const SLIDE: (u32, u32) = (1920, 1080);
/// Where the render goes: fitted into this box at its aspect ratio, centred.
const PICTURE: Rect = Rect {
    min: Vec2::new(48.0, 96.0),
    max: Vec2::new(1088.0, 681.0),
};
/// The column of the views, right of the render.
const VIEWS_LEFT: f32 = 1136.0;
const VIEWS_WIDTH: f32 = 736.0;
/// Where the numbers' first baseline is, under the render, and their size.
const NUMBERS_AT: Vec2 = Vec2::new(48.0, 740.0);
const NUMBER_SIZE: f32 = 26.0;

const INK: Color = Color::from_hex(0x1A1A1A);
const MUTED: Color = Color::from_hex(0x5C5C5C);
/// The mistake label over the render: its type size, its margin, its accent.
const MISTAKE_SIZE: f32 = 22.0;
const MISTAKE_PADDING: f32 = 14.0;
const MISTAKE_INK: Color = Color::from_hex(0xB3261E);

/// A slide to make: the render at the slide's size, the camera at the image size the
/// numbers are for, the chosen pixel, whether to add the top view.
#[derive(Clone, Debug)]
pub(crate) struct SlideRequest {
    /// The render, its camera at the picture's size on the slide.
    pub(crate) view: View,
    /// The camera at the image size the page shows numbers for.
    pub(crate) camera: Camera,
    /// The chosen pixel of that image, 0-based (row, col).
    pub(crate) pixel: Option<(u32, u32)>,
    /// Whether the top view stands under the side view.
    pub(crate) top: bool,
}

/// The size the render takes on the slide for a `width x height` image: as large as
/// fits the picture's box at the image's aspect ratio.
pub(crate) fn picture_size((width, height): (u32, u32)) -> (u32, u32) {
    let scale = (PICTURE.width() / width as f32).min(PICTURE.height() / height as f32);
    // At most the box's size, which fits a u32.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let size = |side: u32| ((side as f32 * scale).round() as u32).max(1);
    (size(width), size(height))
}

/// Renders the slide and encodes it as a PNG.
pub(crate) fn slide(served: &ServedScene, request: &SlideRequest) -> Reply {
    let rendered = match render_view(
        served.scene(),
        &request.view,
        &RenderSettings::default(),
        |_, _| {},
    ) {
        Ok(rendered) => rendered,
        Err(error) => return Reply::error(500, &error.to_string()),
    };
    let picture = DynamicImage::ImageRgb8(rendered.image.to_rgb_image()).to_rgba8();
    let figure = compose(served, request, picture);
    match encode_png(&raster::render(&figure), Compression::Fast) {
        Ok(png) => Reply::ok("image/png", png),
        Err(error) => Reply::error(500, &format!("cannot encode the slide: {error}")),
    }
}

/// The slide's figure around the rendered `picture`.
fn compose(
    served: &ServedScene,
    request: &SlideRequest,
    picture: RgbaImage,
) -> viewray_draw::Figure {
    let mut figure = viewray_draw::Figure::new(SLIDE.0, SLIDE.1);
    figure.push(
        Label::new(served.name(), Vec2::new(48.0, 64.0))
            .with_size(40.0)
            .with_face(FontFace::Bold)
            .with_color(INK)
            .with_anchor(Anchor::Start, Baseline::Alphabetic),
    );
    // The render, centred in its box.
    let size = Vec2::new(picture.width() as f32, picture.height() as f32);
    let at = PICTURE.min + (Vec2::new(PICTURE.width(), PICTURE.height()) - size) / 2.0;
    figure.push(Item::Image {
        pixels: picture,
        rect: Rect::from_xywh(at.x, at.y, size.x, size.y),
        sampling: Sampling::Nearest,
    });
    push_mistake_label(
        &mut figure,
        &request.camera,
        Rect::from_xywh(at.x, at.y, size.x, size.y),
    );
    // The side view, and the top view under it.
    let scene = served.scene();
    let camera = &request.camera;
    let mut views: Vec<(SideWindow, SideViewCanvas)> = vec![(
        SideWindow::fit(scene, std::slice::from_ref(camera)),
        SideViewCanvas::Panel,
    )];
    if request.top {
        views.push((
            SideWindow::fit_top(scene, std::slice::from_ref(camera)),
            SideViewCanvas::Square,
        ));
    }
    let mut top = PICTURE.min.y;
    let side_height = VIEWS_WIDTH * 600.0 / 1000.0;
    for (window, canvas) in views {
        let view = side_view(scene, camera, &window, canvas, request.pixel);
        let (w, h) = canvas.size();
        // The side view across the column; the square under it as tall as room allows.
        let height = if canvas == SideViewCanvas::Panel {
            side_height
        } else {
            (SLIDE.1 as f32 - 48.0 - top).min(VIEWS_WIDTH)
        };
        let scale = (VIEWS_WIDTH / w as f32).min(height / h as f32);
        let pixels = raster::render_scaled(&view, scale);
        let (pw, ph) = (pixels.width() as f32, pixels.height() as f32);
        let left = VIEWS_LEFT + (VIEWS_WIDTH - pw) / 2.0;
        figure.push(Item::Image {
            pixels,
            rect: Rect::from_xywh(left, top, pw, ph),
            sampling: Sampling::Nearest,
        });
        figure.push(Item::Polyline {
            points: vec![
                Vec2::new(left, top),
                Vec2::new(left + pw, top),
                Vec2::new(left + pw, top + ph),
                Vec2::new(left, top + ph),
            ],
            closed: true,
            stroke: viewray_draw::Stroke::new(Color::from_hex(0xD0D0D0), 2.0),
        });
        top += ph + 24.0;
    }
    // The numbers, as the command line prints them.
    for (k, line) in number_lines(camera, request.pixel).into_iter().enumerate() {
        figure.push(
            Label::new(
                line,
                NUMBERS_AT + Vec2::new(0.0, k as f32 * NUMBER_SIZE * 1.5),
            )
            .with_size(NUMBER_SIZE)
            .with_color(if k == 4 { MUTED } else { INK })
            .with_anchor(Anchor::Start, Baseline::Alphabetic),
        );
    }
    figure
}

/// Over the render's top left corner (`picture`), on a light panel as the page shows
/// it: each mistake the camera makes (the catalogue's id and summary) and the lecture's
/// line it breaks, so that a slide of a mistaken camera says which mistake it shows.
/// Lines wider than the picture are wrapped between words.
fn push_mistake_label(figure: &mut viewray_draw::Figure, camera: &Camera, picture: Rect) {
    let lines = mistake_lines(camera);
    if lines.is_empty() {
        return;
    }
    let left = picture.min.x + MISTAKE_PADDING;
    let room = picture.width() - 4.0 * MISTAKE_PADDING;
    let mut baseline = picture.min.y + MISTAKE_PADDING + MISTAKE_SIZE;
    let mut labels = Vec::new();
    for (name, fix) in lines {
        for (text, face, color, gap) in [
            (name, FontFace::Bold, MISTAKE_INK, 1.3),
            (fix, FontFace::Regular, INK, 1.6),
        ] {
            let label = |line: &str, at: Vec2| {
                Label::new(line, at)
                    .with_size(MISTAKE_SIZE)
                    .with_face(face)
                    .with_color(color)
                    .with_anchor(Anchor::Start, Baseline::Alphabetic)
            };
            let words = text.split(' ').map(|word| (word, " "));
            let wrapped = wrap_parts(words, |line| {
                label(line, Vec2::ZERO).bounds().width() <= room
            });
            let count = wrapped.len();
            for (k, line) in wrapped.iter().enumerate() {
                labels.push(label(line, Vec2::new(left, baseline)));
                baseline += MISTAKE_SIZE * if k + 1 == count { gap } else { 1.25 };
            }
        }
    }
    let text = labels
        .iter()
        .map(Label::bounds)
        .reduce(|a, b| a.union(&b))
        .unwrap_or(Rect::from_xywh(left, picture.min.y, 0.0, 0.0));
    let (min, max) = (
        text.min - Vec2::splat(MISTAKE_PADDING),
        text.max + Vec2::splat(MISTAKE_PADDING),
    );
    figure.push(Item::Polygon {
        points: vec![min, Vec2::new(max.x, min.y), max, Vec2::new(min.x, max.y)],
        fill: Color::from_hex(0xFFFFFF).with_alpha(0.88),
        stroke: Some(viewray_draw::Stroke::new(MISTAKE_INK, 2.0)),
    });
    for label in labels {
        figure.push(label);
    }
}

/// The mistake label's lines: per mistake the camera makes, in the catalogue's order,
/// "id: summary" and "the lecture: fix".
pub(crate) fn mistake_lines(camera: &Camera) -> Vec<(String, String)> {
    camera
        .mistakes()
        .iter()
        .map(|mistake| {
            let entry = mistake.entry();
            (
                format!("{}: {}", entry.id, entry.summary),
                format!("the lecture: {}", entry.fix),
            )
        })
        .collect()
}

/// The slide's lines of numbers: the frame (`viewray frame`'s digits) and, for a chosen
/// pixel, its viewing ray (`viewray rays`').
pub(crate) fn number_lines(camera: &Camera, pixel: Option<(u32, u32)>) -> Vec<String> {
    let frame = frame_line(camera.frame());
    let mut lines: Vec<String> = ["e", "u", "v", "w"]
        .iter()
        .map(|name| format!("*{name}*   {}", tuple(&frame[*name])))
        .collect();
    if let Some((row, col)) = pixel {
        let ray = ray_line(
            camera,
            (row, col),
            CameraSample::CENTER,
            PixelIndices::ZeroBased,
        );
        lines.push(format!(
            "pixel row {row}, col {col}  (the lecture's $i$ = {}, $j$ = {})",
            row + 1,
            col + 1,
        ));
        lines.push(format!(
            "$u$, $v$   {}, {}",
            scalar(&ray["u"]),
            scalar(&ray["v"])
        ));
        lines.push(format!("origin   {}", tuple(&ray["origin"])));
        lines.push(format!("direction   {}", tuple(&ray["direction"])));
    }
    lines
}

/// A JSON array of numbers as `(a, b, c)`, each number as the command line prints it.
fn tuple(value: &Value) -> String {
    match value.as_array() {
        Some(items) => {
            let items: Vec<String> = items.iter().map(Value::to_string).collect();
            format!("({})", items.join(", "))
        }
        None => "none".to_owned(),
    }
}

/// A JSON number as the command line prints it, or "none".
fn scalar(value: &Value) -> String {
    if value.is_null() {
        "none".to_owned()
    } else {
        value.to_string()
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use viewray_camera::{Mistake, Mistakes};
    use viewray_scene::parse_camera;

    use super::*;

    #[test]
    fn the_slides_numbers_are_the_command_lines_digits() {
        let camera = parse_camera(
            "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), projection: Perspective(fov_y: 32.0))",
            Path::new("camera"),
            640,
            360,
        )
        .unwrap();
        let lines = number_lines(&camera, None);
        assert_eq!(lines.len(), 4);
        // `viewray frame` prints {"e":[5.2,1.6,6.0],"u":[...],...}: each array, as written.
        let printed = frame_line(camera.frame()).to_string();
        for (line, name) in lines.iter().zip(["e", "u", "v", "w"]) {
            let start = printed.find(&format!("\"{name}\":[")).unwrap() + name.len() + 4;
            let array = &printed[start..start + printed[start..].find(']').unwrap()];
            assert_eq!(line, &format!("*{name}*   ({})", array.replace(',', ", ")));
        }
        assert_eq!(lines[0], "*e*   (5.2, 1.6, 6.0)");
        let with_pixel = number_lines(&camera, Some((212, 352)));
        assert_eq!(
            with_pixel[4],
            "pixel row 212, col 352  (the lecture's $i$ = 213, $j$ = 353)"
        );
        let ray = ray_line(
            &camera,
            (212, 352),
            CameraSample::CENTER,
            PixelIndices::ZeroBased,
        );
        assert_eq!(
            with_pixel[5],
            format!("$u$, $v$   {}, {}", ray["u"], ray["v"])
        );
        assert!(
            with_pixel[7].starts_with("direction   ("),
            "{}",
            with_pixel[7]
        );
    }

    #[test]
    fn a_mistaken_cameras_slide_names_each_mistake_and_the_lecture_line_it_breaks() {
        let right = parse_camera(
            "(eye: (5.2, 1.6, 6.0), view: (-5.2, 0.0, -6.0), projection: Perspective(fov_y: 32.0))",
            Path::new("camera"),
            640,
            360,
        )
        .unwrap();
        assert!(mistake_lines(&right).is_empty());
        let mistaken = right
            .with_mistakes(Mistakes::one(Mistake::USign).with(Mistake::PixelCorner))
            .unwrap();
        let lines = mistake_lines(&mistaken);
        assert_eq!(lines.len(), 2);
        // In the catalogue's order, whatever order they were given in.
        for ((name, fix), mistake) in lines.iter().zip([Mistake::PixelCorner, Mistake::USign]) {
            let entry = mistake.entry();
            assert_eq!(name, &format!("{}: {}", entry.id, entry.summary));
            assert_eq!(fix, &format!("the lecture: {}", entry.fix));
        }
        // And the label is drawn: the slide of the mistaken camera has more items.
        let items = |camera: &Camera| {
            let mut figure = viewray_draw::Figure::new(SLIDE.0, SLIDE.1);
            push_mistake_label(&mut figure, camera, PICTURE);
            figure.items.len()
        };
        assert_eq!(items(&right), 0);
        assert_eq!(items(&mistaken), 1 + 2 * 2);
        // Every label fits in a 4:3 image's picture (780 pixels wide), wrapped where
        // it must be, and a wrapped line is never wider than the room.
        let narrow = Rect::from_xywh(0.0, 0.0, 780.0, 585.0);
        let kinds = [
            "Perspective(fov_y: 32.0)",
            "Orthographic(height: 5.0)",
            "Oblique(viewport: (6.0, 4.5), ratio: 0.5, angle: 30.0)",
        ]
        .map(|projection| {
            let text =
                format!("(eye: (0.0, 1.0, 6.0), view: (0.0, 0.0, -1.0), projection: {projection})");
            parse_camera(&text, Path::new("camera"), 640, 480).unwrap()
        });
        for mistake in Mistake::ALL {
            let mut figure = viewray_draw::Figure::new(SLIDE.0, SLIDE.1);
            let camera = kinds
                .iter()
                .find_map(|kind| kind.with_mistakes(Mistakes::one(mistake)).ok())
                .unwrap();
            push_mistake_label(&mut figure, &camera, narrow);
            let Some(Item::Polygon { points, .. }) = figure.items.first() else {
                panic!("no panel for {}", mistake.id());
            };
            assert!(
                points[2].x <= narrow.max.x,
                "{}: {:?}",
                mistake.id(),
                points
            );
        }
        let words = |text: &'static str| text.split(' ').map(|word| (word, " "));
        let lines = wrap_parts(words("aaa bbb ccc ddd"), |_| false);
        assert_eq!(lines, ["aaa", "bbb", "ccc", "ddd"]);
        let lines = wrap_parts(words("aaa bbb"), |_| true);
        assert_eq!(lines, ["aaa bbb"]);
    }

    #[test]
    fn the_picture_fills_its_box_at_the_images_aspect_ratio() {
        assert_eq!(picture_size((640, 360)), (1040, 585));
        assert_eq!(picture_size((640, 480)), (780, 585));
        assert_eq!(picture_size((240, 180)), (780, 585));
        assert_eq!(picture_size((200, 1000)), (117, 585));
    }
}

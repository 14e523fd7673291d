//! From a pixel's indices to its point (u, v) on the image plane.

use glam::{DVec2, Vec2};

use crate::Diagram;
use crate::sketch::Sketch;
use crate::style;
use viewray_draw::{Anchor, Baseline, Item, Label, Mapping, Rect, Stroke};
use viewray_output::number;

/// The image: `W x H` pixels.
const SIZE: (u32, u32) = (4, 3);
/// The viewport `(vw, vh)`: square pixels half a unit wide.
const VIEWPORT: DVec2 = DVec2::new(2.0, 1.5);
/// The worked pixel, `(row, col)` 0-based.
const EXAMPLE: (u32, u32) = (0, 2);

/// From pixel indices to the image plane (slide, 1600 x 900): the viewport of a 4 x 3
/// image with every pixel's 0-based `(row, col)` and the lecture's 1-based `(i, j)`,
/// the pixel centres half a pixel in from the pixel edges, the `u` and `v` axes through
/// the viewport's centre, and one pixel worked out.
///
/// ```text
/// u =  ((j - 1/2)/W - 1/2) vw  =  ((col + 1/2)/W - 1/2) vw
/// v = -((i - 1/2)/H - 1/2) vh  = -((row + 1/2)/H - 1/2) vh
/// ```
pub(crate) fn pixel_to_image_plane() -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("From pixel $(i, j)$ to image-plane point $(u, v)$");

    // The viewport in world units (u right, v up) on the left of the slide.
    let half = (VIEWPORT / 2.0).as_vec2();
    let world = Rect::from_corners(-half, half);
    let map = Mapping::fit(world, Rect::from_xywh(300.0, 215.0, 640.0, 480.0))
        .expect("a non-empty viewport");
    let plane = |row: u32, col: u32, film: DVec2| {
        map.to_canvas(
            viewray_camera::pixel_to_image_plane(row, col, film, SIZE, VIEWPORT).as_vec2(),
        )
    };
    let corner = |row: u32, col: u32| plane(row, col, DVec2::ZERO);
    let centre = |row: u32, col: u32| plane(row, col, DVec2::splat(0.5));
    let (w, h) = SIZE;
    let top_left = corner(0, 0);
    let bottom_right = plane(h - 1, w - 1, DVec2::ONE);

    // The pixels.
    let outline = [
        top_left,
        Vec2::new(bottom_right.x, top_left.y),
        bottom_right,
        Vec2::new(top_left.x, bottom_right.y),
    ];
    sketch.push(Item::Polygon {
        points: outline.to_vec(),
        fill: style::IMAGE_PLANE_FILL,
        stroke: None,
    });
    let example_cell = [(0.0, 0.0), (1.0, 0.0), (1.0, 1.0), (0.0, 1.0)]
        .map(|(sx, sy)| plane(EXAMPLE.0, EXAMPLE.1, DVec2::new(sx, sy)));
    sketch.push(Item::Polygon {
        points: example_cell.to_vec(),
        fill: style::HIGHLIGHT.with_alpha(0.3),
        stroke: None,
    });
    let grid = Stroke::new(style::IMAGE_PLANE, style::LINE_THIN);
    for col in 1..w {
        sketch.line(
            corner(0, col),
            plane(h - 1, col, DVec2::new(0.0, 1.0)),
            grid.clone(),
        );
    }
    for row in 1..h {
        sketch.line(
            corner(row, 0),
            plane(row, w - 1, DVec2::new(1.0, 0.0)),
            grid.clone(),
        );
    }
    sketch.push(Item::Polyline {
        points: outline.to_vec(),
        closed: true,
        stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THICK),
    });

    // The u and v axes through the viewport's centre.
    let origin = map.to_canvas(Vec2::ZERO);
    sketch.uv_axes(origin, (top_left, bottom_right), 100.0, 12.0);

    // Pixel centres.
    for row in 0..h {
        for col in 0..w {
            let color = if (row, col) == EXAMPLE {
                style::HIGHLIGHT
            } else {
                style::RAY
            };
            sketch.dot(centre(row, col), style::DOT_RADIUS, color);
        }
    }

    // Indices: the lecture's i, j (1-based) above and left, the library's row, col
    // (0-based) below and further left.
    let small = style::SMALL_LABEL_SIZE;
    let header_above = top_left.y - 34.0;
    let header_below = bottom_right.y + 34.0;
    for col in 0..w {
        let x = centre(0, col).x;
        let j = format!("$j$ = {}", col + 1);
        sketch.label(&j, Vec2::new(x, header_above), style::TEXT, small);
        let col_text = format!("col {col}");
        sketch.label(
            &col_text,
            Vec2::new(x, header_below),
            style::ANNOTATION,
            small,
        );
    }
    for row in 0..h {
        let y = centre(row, 0).y;
        let i = format!("$i$ = {}", row + 1);
        sketch.label_at(
            &i,
            Vec2::new(top_left.x - 20.0, y),
            (Anchor::End, Baseline::Middle),
            style::TEXT,
            small,
        );
        let row_text = format!("row {row}");
        sketch.label_at(
            &row_text,
            Vec2::new(top_left.x - 130.0, y),
            (Anchor::End, Baseline::Middle),
            style::ANNOTATION,
            small,
        );
    }

    // The worked pixel: its centre is half a pixel in from its edges, (j - 1/2) pixels
    // from the left edge of the viewport and (i - 1/2) from the top.
    let example = centre(EXAMPLE.0, EXAMPLE.1);
    let cell_left = plane(EXAMPLE.0, EXAMPLE.1, DVec2::new(0.0, 0.5));
    let cell_top = plane(EXAMPLE.0, EXAMPLE.1, DVec2::new(0.5, 0.0));
    sketch.dimension(cell_left, example);
    sketch.dimension(cell_top, example);
    // The halves above and right of their dimensions, leaving the cell's lower half to
    // the centre's coordinates.
    sketch.label_at(
        "½",
        (cell_left + example) / 2.0 + Vec2::new(0.0, -8.0),
        (Anchor::Middle, Baseline::Bottom),
        style::TEXT,
        small,
    );
    sketch.label_at(
        "½",
        (cell_top + example) / 2.0 + Vec2::new(10.0, 0.0),
        (Anchor::Start, Baseline::Middle),
        style::TEXT,
        small,
    );
    let uv = viewray_camera::pixel_to_image_plane(
        EXAMPLE.0,
        EXAMPLE.1,
        DVec2::splat(0.5),
        SIZE,
        VIEWPORT,
    );
    // The centre's (u, v), under it and inside its cell: a little smaller than the other
    // small labels, so that it keeps clear of the cell's borders.
    sketch.label_at(
        &format!("({}, {})", number::label(uv.x), number::label(uv.y)),
        example + Vec2::new(0.0, 16.0),
        (Anchor::Middle, Baseline::Top),
        style::HIGHLIGHT,
        0.85 * small,
    );

    // vw and vh.
    let below = bottom_right.y + 80.0;
    sketch.dimension(
        Vec2::new(top_left.x, below),
        Vec2::new(bottom_right.x, below),
    );
    sketch.label_at(
        &format!("$vw$ = {}", number::label(VIEWPORT.x)),
        Vec2::new(origin.x, below + 12.0),
        (Anchor::Middle, Baseline::Top),
        style::TEXT,
        style::LABEL_SIZE,
    );
    let left = top_left.x - 230.0;
    sketch.dimension(Vec2::new(left, top_left.y), Vec2::new(left, bottom_right.y));
    sketch.push(
        Label::new(
            format!("$vh$ = {}", number::label(VIEWPORT.y)),
            Vec2::new(left - 14.0, origin.y),
        )
        .with_size(style::LABEL_SIZE)
        .with_color(style::TEXT)
        .with_anchor(Anchor::Middle, Baseline::Bottom)
        .with_rotation(std::f32::consts::FRAC_PI_2),
    );

    // The formulas, and the worked pixel.
    let (i, j) = (EXAMPLE.0 + 1, EXAMPLE.1 + 1);
    let example_title = format!("Pixel $(i, j)$ = ({i}, {j}):");
    let example_u = format!(
        "$u$ = (({j} − ½)/{w} − ½) · {} = {}",
        number::label(VIEWPORT.x),
        number::label(uv.x)
    );
    let example_v = format!(
        "$v$ = −(({i} − ½)/{h} − ½) · {} = {}",
        number::label(VIEWPORT.y),
        number::label(uv.y)
    );
    let size_line = format!(
        "{w} × {h} pixels, viewport {} × {}",
        number::label(VIEWPORT.x),
        number::label(VIEWPORT.y)
    );
    let (l, s) = (style::LABEL_SIZE, style::SMALL_LABEL_SIZE);
    sketch.text_lines(
        Vec2::new(1050.0, 200.0),
        &[
            (&size_line, style::ANNOTATION, s),
            ("$u = ((j - ½)/W - ½) vw$", style::TEXT, l),
            ("$v = -((i - ½)/H - ½) vh$", style::TEXT, l),
            ("", style::TEXT, l),
            ("$i$ = row + 1,  $j$ = col + 1", style::TEXT, l),
            ("", style::TEXT, l),
            (&example_title, style::HIGHLIGHT, l),
            (&example_u, style::HIGHLIGHT, s),
            (&example_v, style::HIGHLIGHT, s),
        ],
    );
    sketch.finish()
}

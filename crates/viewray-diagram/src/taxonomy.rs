//! The classical taxonomy of planar geometric projections, with a picture per preset.

use glam::{DVec3, Vec2};
use viewray_camera::Preset;

use crate::Diagram;
use crate::pictures::{PictureScene, Pictures, draw_picture};
use crate::sketch::Sketch;
use crate::style;
use crate::view::CameraView;
use viewray_draw::{Anchor, Baseline, Label, Rect, Stroke};

/// The thumbnails' image size: the fixtures' 240 x 180.
pub(crate) const THUMBNAIL_IMAGE: (u32, u32) = (240, 180);
/// Where every preset camera aims, and how tall its view is there: the cube
/// `[-1, 1]^3` lifted onto the ground fills half of it.
const TARGET: DVec3 = DVec3::new(0.0, 1.0, 0.0);
/// The view's height at the target, world units.
const VIEW_SIZE: f64 = 4.0;
/// Where the one- and two-point cameras aim, and their view's height there. Their eye
/// sits a quarter of the view above the target: aimed at the cube's middle it would be
/// level with the cube's top, and the top face and its receding edges would vanish into
/// the horizon. Aimed higher, with a wider view, the eye is a unit above the cube, which
/// stands below the horizon with its converging edges in sight and clear of the frame.
const LEVEL_TARGET: DVec3 = DVec3::new(0.0, 1.6, 0.0);
/// The one- and two-point views' height at [`LEVEL_TARGET`], world units.
const LEVEL_VIEW_SIZE: f64 = 5.6;

/// The camera of a taxonomy thumbnail: `preset` aimed at the cube.
pub(crate) fn taxonomy_camera(preset: &Preset) -> viewray_camera::Camera {
    let (target, size) = match preset {
        Preset::OnePoint | Preset::TwoPoint => (LEVEL_TARGET, LEVEL_VIEW_SIZE),
        _ => (TARGET, VIEW_SIZE),
    };
    preset
        .camera(target, size, THUMBNAIL_IMAGE.0, THUMBNAIL_IMAGE.1)
        .expect("a preset camera for a fixed target and size")
}

/// The leaf name of a preset in the tree.
fn leaf_name(preset: &Preset) -> &'static str {
    match preset {
        Preset::Front => "front",
        Preset::Top => "top",
        Preset::Side => "side",
        Preset::Isometric => "isometric",
        Preset::Dimetric => "dimetric",
        Preset::Trimetric => "trimetric",
        Preset::Cavalier { .. } => "cavalier",
        Preset::Cabinet { .. } => "cabinet",
        Preset::OnePoint => "one-point",
        Preset::TwoPoint => "two-point",
        Preset::ThreePoint => "three-point",
    }
}

/// The classical projection taxonomy (slide, 1600 x 900) as a tree: planar geometric ->
/// parallel {orthographic {multiview, axonometric}, oblique} and perspective, each leaf
/// with a picture of the axis-coloured cube taken by that [`Preset`]'s camera (the
/// rendered picture from `pictures`, else the cube's faces projected with the camera).
pub(crate) fn taxonomy(pictures: &dyn Pictures) -> Diagram {
    let mut sketch = Sketch::slide();
    sketch.title("The classical projections");

    // The leaves, a row per group, in Preset::ALL's order.
    let groups: [(&str, &[Preset]); 4] = [
        ("multiview", &Preset::ALL[0..3]),
        ("axonometric", &Preset::ALL[3..6]),
        ("oblique", &Preset::ALL[6..8]),
        ("perspective", &Preset::ALL[8..11]),
    ];
    let thumb = Vec2::new(200.0, 150.0);
    let leaves_x = 880.0;
    let gap = 24.0;
    let row_top = |k: usize| 118.0 + k as f32 * 194.0;
    let row_centre = |k: usize| row_top(k) + thumb.y / 2.0;
    for (k, (_, presets)) in groups.iter().enumerate() {
        for (n, preset) in presets.iter().enumerate() {
            let min = Vec2::new(leaves_x + n as f32 * (thumb.x + gap), row_top(k));
            let rect = Rect::from_corners(min, min + thumb);
            let view = CameraView::new(taxonomy_camera(preset), rect);
            draw_picture(&mut sketch, &view, PictureScene::AxisCube, pictures);
            sketch.label_at(
                leaf_name(preset),
                Vec2::new(rect.center().x, rect.max.y + 8.0),
                (Anchor::Middle, Baseline::Top),
                style::TEXT,
                style::SMALL_LABEL_SIZE,
            );
        }
    }

    // The inner nodes: (name, column x, centre y).
    let column = [40.0, 220.0, 420.0, 650.0];
    let size = style::SMALL_LABEL_SIZE;
    let orthographic_y = (row_centre(0) + row_centre(1)) / 2.0;
    let parallel_y = (orthographic_y + row_centre(2)) / 2.0;
    let root_y = (parallel_y + row_centre(3)) / 2.0;
    let node = |sketch: &mut Sketch, name: &str, x: f32, y: f32| -> (f32, f32) {
        let label = Label::new(name, Vec2::new(x, y))
            .with_size(size)
            .with_color(style::TEXT)
            .with_anchor(Anchor::Start, Baseline::Middle);
        let bounds = label.bounds();
        sketch.push(label);
        (bounds.min.x, bounds.max.x)
    };
    let line = Stroke::new(style::ANNOTATION, style::LINE_THIN);
    // An elbow from a parent's right end to a child's left end.
    let connect = |sketch: &mut Sketch, from: Vec2, to: Vec2| {
        let spine = from.x + 0.5 * (to.x - from.x).min(60.0);
        sketch.push(viewray_draw::Item::Polyline {
            points: vec![from, Vec2::new(spine, from.y), Vec2::new(spine, to.y), to],
            closed: false,
            stroke: line.clone(),
        });
    };
    let pad = 12.0;

    // Root, on two lines.
    let root_top = Label::new("planar", Vec2::new(column[0], root_y - 4.0))
        .with_size(size)
        .with_color(style::TEXT)
        .with_anchor(Anchor::Start, Baseline::Bottom);
    let root_bottom = Label::new("geometric", Vec2::new(column[0], root_y + 4.0))
        .with_size(size)
        .with_color(style::TEXT)
        .with_anchor(Anchor::Start, Baseline::Top);
    let root_right = root_top.bounds().max.x.max(root_bottom.bounds().max.x);
    sketch.push(root_top);
    sketch.push(root_bottom);

    let (parallel_left, parallel_right) = node(&mut sketch, "parallel", column[1], parallel_y);
    let (perspective_left, perspective_right) =
        node(&mut sketch, "perspective", column[1], row_centre(3));
    let (ortho_left, ortho_right) = node(&mut sketch, "orthographic", column[2], orthographic_y);
    let (oblique_left, oblique_right) = node(&mut sketch, "oblique", column[2], row_centre(2));
    let (multi_left, multi_right) = node(&mut sketch, "multiview", column[3], row_centre(0));
    let (axo_left, axo_right) = node(&mut sketch, "axonometric", column[3], row_centre(1));

    let right = |x: f32, y: f32| Vec2::new(x + pad, y);
    let left = |x: f32, y: f32| Vec2::new(x - pad, y);
    connect(
        &mut sketch,
        right(root_right, root_y),
        left(parallel_left, parallel_y),
    );
    connect(
        &mut sketch,
        right(root_right, root_y),
        left(perspective_left, row_centre(3)),
    );
    connect(
        &mut sketch,
        right(parallel_right, parallel_y),
        left(ortho_left, orthographic_y),
    );
    connect(
        &mut sketch,
        right(parallel_right, parallel_y),
        left(oblique_left, row_centre(2)),
    );
    connect(
        &mut sketch,
        right(ortho_right, orthographic_y),
        left(multi_left, row_centre(0)),
    );
    connect(
        &mut sketch,
        right(ortho_right, orthographic_y),
        left(axo_left, row_centre(1)),
    );
    // Each group's node leads into its row of pictures.
    for (k, end) in [multi_right, axo_right, oblique_right, perspective_right]
        .into_iter()
        .enumerate()
    {
        sketch.line(
            right(end, row_centre(k)),
            Vec2::new(leaves_x - pad, row_centre(k)),
            line.clone(),
        );
    }
    sketch.finish()
}

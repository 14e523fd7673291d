//! Pictures inside figures: what a camera sees of a small scene, rendered by the ray
//! tracer ([`RenderedPictures`](crate::rendered::RenderedPictures)) or drawn as flat-shaded
//! polygons projected with the camera ([`Wireframes`]).

use std::f64::consts::TAU;

use glam::{DVec2, DVec3, Vec2};
use image::RgbaImage;
use viewray_camera::Camera;
use viewray_output::{LinearRgb, Srgb8};

use crate::clip::{HalfPlane, clip_polygon, clip_segment};
use crate::sketch::Sketch;
use crate::style;
use crate::view::CameraView;
use viewray_draw::{Color, Item, Sampling, Stroke};

/// The little scenes the lecture figures show pictures of.
///
/// Each is a list of [`SceneObject`]s on a ground plane `y = 0` under a sky, the same
/// objects as the scene files in `fixtures/scenes/` that the comment on each variant
/// names, so a renderer can make the picture from the fixture or from
/// [`PictureScene::objects`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum PictureScene {
    /// The axis-coloured cube `[-1, 1]^3` lifted onto the ground (centre `(0, 1, 0)`),
    /// as in the axonometric and oblique fixtures: faces perpendicular to x
    /// red, to y green, to z blue.
    AxisCube,
    /// A tower 1.5 x 6 x 1.5 with a floor line every unit and a lower block beside it,
    /// as in `distortion_tilted.ron` and `distortion_shifted.ron`.
    Towers,
    /// Four equal posts 0.6 x 2 x 0.6, each 3 units farther and 1 unit further right than
    /// the one before, for foreshortening.
    Posts,
    /// Three spheres on the ground at depths 2, 4.5 and 8 in front of the origin
    /// (red, green, blue), for depth of field.
    DepthOfField,
}

/// A shape of a [`PictureScene`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Shape {
    /// An axis-aligned box.
    Box {
        /// The corner with the smallest coordinates.
        min: DVec3,
        /// The corner with the largest coordinates.
        max: DVec3,
    },
    /// A sphere.
    Sphere {
        /// Its centre.
        center: DVec3,
        /// Its radius.
        radius: f64,
    },
}

/// How a [`SceneObject`] is coloured (linear RGB, as scene files write colours).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum Paint {
    /// The faces perpendicular to x red, to y green, to z blue (`fixtures/meshes/cube.mtl`).
    AxisColours,
    /// One colour, with a horizontal line every `bands` units when given (the scene
    /// files' `grid` material).
    Uniform {
        /// Linear RGB.
        color: DVec3,
        /// Spacing of horizontal lines, if any.
        bands: Option<f64>,
    },
}

/// One object of a [`PictureScene`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SceneObject {
    /// Its geometry, in world units, `+y` up.
    pub(crate) shape: Shape,
    /// Its colour.
    pub(crate) paint: Paint,
}

/// The sky colour of the pictures (linear RGB, the fixtures' `background`).
pub(crate) const SKY: DVec3 = DVec3::new(0.55, 0.70, 0.90);
/// The ground colour of the pictures (linear RGB, the fixtures' `ground` material).
pub(crate) const GROUND: DVec3 = DVec3::new(0.62, 0.62, 0.60);
/// The axis colours of [`Paint::AxisColours`], x, y and z (linear RGB).
pub(crate) const AXIS_COLOURS: [DVec3; 3] = [
    DVec3::new(0.80, 0.12, 0.08),
    DVec3::new(0.12, 0.55, 0.15),
    DVec3::new(0.10, 0.25, 0.80),
];
/// The towers' stone (linear RGB, the fixtures' `tower` material).
const STONE: DVec3 = DVec3::new(0.70, 0.68, 0.64);

impl PictureScene {
    /// The scene's objects (besides the ground plane `y = 0`).
    pub(crate) fn objects(&self) -> Vec<SceneObject> {
        let cube = |center: DVec3, half: f64| SceneObject {
            shape: Shape::Box {
                min: center - DVec3::splat(half),
                max: center + DVec3::splat(half),
            },
            paint: Paint::AxisColours,
        };
        let stone = |min: DVec3, max: DVec3, bands: Option<f64>| SceneObject {
            shape: Shape::Box { min, max },
            paint: Paint::Uniform {
                color: STONE,
                bands,
            },
        };
        let ball = |center: DVec3, radius: f64, color: DVec3| SceneObject {
            shape: Shape::Sphere { center, radius },
            paint: Paint::Uniform { color, bands: None },
        };
        match self {
            PictureScene::AxisCube => vec![cube(DVec3::Y, 1.0)],
            PictureScene::Towers => vec![
                stone(
                    DVec3::new(-0.75, 0.0, -0.75),
                    DVec3::new(0.75, 6.0, 0.75),
                    Some(1.0),
                ),
                stone(
                    DVec3::new(1.5, 0.0, -0.5),
                    DVec3::new(2.5, 3.0, 0.5),
                    Some(1.0),
                ),
            ],
            PictureScene::Posts => (0..4)
                .map(|k| {
                    let z = -2.0 - 3.0 * f64::from(k);
                    let x = -1.5 + f64::from(k);
                    SceneObject {
                        shape: Shape::Box {
                            min: DVec3::new(x - 0.3, 0.0, z - 0.3),
                            max: DVec3::new(x + 0.3, 2.0, z + 0.3),
                        },
                        paint: Paint::Uniform {
                            color: AXIS_COLOURS[(k % 3) as usize],
                            bands: None,
                        },
                    }
                })
                .collect(),
            PictureScene::DepthOfField => vec![
                ball(DVec3::new(-0.9, 0.4, -2.0), 0.4, AXIS_COLOURS[0]),
                ball(DVec3::new(0.0, 0.45, -4.5), 0.45, AXIS_COLOURS[1]),
                ball(DVec3::new(1.3, 0.5, -8.0), 0.5, AXIS_COLOURS[2]),
            ],
        }
    }
}

/// What a figure asks for to fill a picture slot: the scene, the camera that sees it,
/// and the slot's size.
///
/// The picture is the camera's whole image, stretched to the slot. The camera's own
/// image size (`W x H`) is the one the figure computes with (the pixel whose rays it
/// draws, for example); a renderer should make the picture `size` pixels instead, with
/// the same camera at that size ([`Camera::with_image_size`]: the same view, more
/// pixels), so that it lands on the figure pixel for pixel.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PictureRequest {
    /// What is in the picture.
    pub(crate) scene: PictureScene,
    /// The camera that takes it.
    pub(crate) camera: Camera,
    /// The slot's size in figure pixels, `(width, height)`, rounded: the same aspect
    /// ratio as the camera's image.
    pub(crate) size: (u32, u32),
}

/// Where a figure's pictures come from: the ray tracer
/// ([`RenderedPictures`](crate::rendered::RenderedPictures), what users see), or nothing.
///
/// Returning `None` draws the picture as flat-shaded polygons projected with the
/// request's camera ([`Wireframes`] always does: quick, for tests that must not ray
/// trace). The slot's place and size on the figure do not depend on the answer, so the
/// two give the same layout.
pub(crate) trait Pictures {
    /// A rendered picture for `request`, or `None` to draw it from polygons.
    fn picture(&self, request: &PictureRequest) -> Option<RgbaImage>;
}

/// No rendered pictures: every slot is drawn as projected polygons, and nothing is ray
/// traced.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct Wireframes;

impl Pictures for Wireframes {
    fn picture(&self, _request: &PictureRequest) -> Option<RgbaImage> {
        None
    }
}

impl<F> Pictures for F
where
    F: Fn(&PictureRequest) -> Option<RgbaImage>,
{
    fn picture(&self, request: &PictureRequest) -> Option<RgbaImage> {
        self(request)
    }
}

/// The direction towards the light that shades the polygons (the fixtures' sun).
const TOWARDS_LIGHT: DVec3 = DVec3::new(0.4, 1.0, 0.6);

/// Draws what `view`'s camera sees of `scene` inside `view.rect`: the rendered picture
/// from `pictures` if there is one, else sky, ground and the objects as flat-shaded
/// polygons, then a thin frame.
pub(crate) fn draw_picture(
    sketch: &mut Sketch,
    view: &CameraView,
    scene: PictureScene,
    pictures: &dyn Pictures,
) {
    // The slots are a few hundred pixels wide, so the rounded sizes are positive.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let size = (
        view.rect.width().round().max(1.0) as u32,
        view.rect.height().round().max(1.0) as u32,
    );
    let request = PictureRequest {
        scene,
        camera: view.camera,
        size,
    };
    if let Some(pixels) = pictures.picture(&request) {
        sketch.push(Item::Image {
            pixels,
            rect: view.rect,
            sampling: Sampling::Smooth,
        });
    } else {
        draw_polygons(sketch, view, &scene.objects());
    }
    sketch.frame(view.rect, Stroke::new(style::OBJECT, style::LINE_THIN));
}

/// A polygon to paint, with its distance from the camera.
struct Patch {
    depth: f64,
    points: Vec<DVec3>,
    fill: Color,
    /// The radius of the circle of confusion of a thin-lens camera, in image pixels
    /// (zero for a pinhole).
    blur: f64,
    /// Horizontal lines across it, as world segments.
    lines: Vec<(DVec3, DVec3)>,
}

/// Sky, ground and `objects`, far to near, clipped to the view's rectangle.
fn draw_polygons(sketch: &mut Sketch, view: &CameraView, objects: &[SceneObject]) {
    let camera = &view.camera;
    let clip = HalfPlane::of_rect(view.rect);
    let corners = super::sketch::rect_corners(view.rect);
    sketch.push(Item::Polygon {
        points: corners.to_vec(),
        fill: srgb(SKY),
        stroke: None,
    });
    let mut planes = clip.to_vec();
    planes.push(ground_half_plane(view));
    let ground = clip_polygon(&corners, &planes);
    if ground.len() >= 3 {
        sketch.push(Item::Polygon {
            points: ground,
            fill: srgb(GROUND),
            stroke: None,
        });
    }

    let mut patches: Vec<Patch> = Vec::new();
    for object in objects {
        match object.shape {
            Shape::Box { min, max } => box_patches(camera, min, max, object.paint, &mut patches),
            Shape::Sphere { center, radius } => {
                if let Some(patch) = sphere_patch(camera, center, radius, object.paint) {
                    patches.push(patch);
                }
            }
        }
    }
    patches.sort_by(|a, b| b.depth.total_cmp(&a.depth));
    let outline = Stroke::new(style::OBJECT, 1.5);
    for patch in &patches {
        let Some(points) = patch
            .points
            .iter()
            .map(|&p| view.to_figure(p))
            .collect::<Option<Vec<Vec2>>>()
        else {
            continue;
        };
        if patch.blur * f64::from(view.rect.height()) / f64::from(camera.height()) > 0.75 {
            draw_blurred(sketch, view, &points, patch, &clip);
            continue;
        }
        let clipped = clip_polygon(&points, &clip);
        if clipped.len() < 3 {
            continue;
        }
        sketch.push(Item::Polygon {
            points: clipped,
            fill: patch.fill,
            stroke: None,
        });
        for &(a, b) in &patch.lines {
            if let (Some(a), Some(b)) = (view.to_figure(a), view.to_figure(b))
                && let Some((a, b)) = clip_segment(a, b, &clip)
            {
                sketch.line(a, b, Stroke::new(style::OBJECT.with_alpha(0.6), 1.2));
            }
        }
        // The outline edge by edge, so that edges leaving the picture are cut at its
        // border rather than closed along it.
        for (i, &a) in points.iter().enumerate() {
            let b = points[(i + 1) % points.len()];
            if let Some((a, b)) = clip_segment(a, b, &clip) {
                sketch.line(a, b, outline.clone());
            }
        }
    }
}

/// A disc spread by a circle of confusion: the outline grown and shrunk by the blur
/// radius in steps, each layer translucent, so the edge fades over twice the radius as a
/// disc convolved with the lens's disc does. A preview of what a renderer shows.
fn draw_blurred(
    sketch: &mut Sketch,
    view: &CameraView,
    points: &[Vec2],
    patch: &Patch,
    clip: &[HalfPlane],
) {
    const LAYERS: usize = 10;
    let centre = points.iter().sum::<Vec2>() / points.len() as f32;
    let radius = points.iter().map(|p| p.distance(centre)).sum::<f32>() / points.len() as f32;
    let blur =
        (patch.blur * f64::from(view.rect.height()) / f64::from(view.camera.height())) as f32;
    for k in 0..LAYERS {
        let s = -blur + 2.0 * blur * (k as f32 + 0.5) / LAYERS as f32;
        let scale = ((radius + s) / radius).max(0.0);
        let layer: Vec<Vec2> = points
            .iter()
            .map(|&p| centre + (p - centre) * scale)
            .collect();
        let clipped = clip_polygon(&layer, clip);
        if clipped.len() >= 3 {
            sketch.push(Item::Polygon {
                points: clipped,
                fill: patch.fill.with_alpha(0.22),
                stroke: None,
            });
        }
    }
}

/// The image region whose viewing rays reach the ground `y = 0`, as a half-plane of the
/// figure: `ray.at(T).y <= 0` for a far `T` is affine in the image point for every
/// planar camera (the direction, or a parallel ray's origin, is affine in it).
fn ground_half_plane(view: &CameraView) -> HalfPlane {
    let far = 1e4;
    let height_at = |image: DVec2| {
        view.camera
            .generate_ray_through(image, DVec2::splat(0.5))
            .map_or(0.0, |ray| ray.at(far).y)
    };
    let (w, h) = (
        f64::from(view.camera.width()),
        f64::from(view.camera.height()),
    );
    let g0 = height_at(DVec2::ZERO);
    let gx = height_at(DVec2::new(w, 0.0)) - g0;
    let gy = height_at(DVec2::new(0.0, h)) - g0;
    // g(P) = g0 + gx (P.x - min.x) / width + gy (P.y - min.y) / height, in figure pixels.
    let slope = DVec2::new(
        gx / f64::from(view.rect.width()),
        gy / f64::from(view.rect.height()),
    );
    let offset = g0 - slope.dot(view.rect.min.as_dvec2());
    // Scale to keep the numbers near 1: only the sign matters.
    let norm = slope.length().max(offset.abs()).max(1e-12);
    HalfPlane {
        normal: (-slope / norm).as_vec2(),
        offset: (-offset / norm) as f32,
    }
}

/// The visible faces of the box `min`-`max`.
fn box_patches(camera: &Camera, min: DVec3, max: DVec3, paint: Paint, patches: &mut Vec<Patch>) {
    let size = max - min;
    for axis in 0..3 {
        for side in [0.0, 1.0] {
            let mut normal = DVec3::ZERO;
            normal[axis] = if side == 0.0 { -1.0 } else { 1.0 };
            // The face's corners: fix `axis`, walk the other two around.
            let (a, b) = ((axis + 1) % 3, (axis + 2) % 3);
            let corner = |s: f64, t: f64| {
                let mut p = min;
                p[axis] += side * size[axis];
                p[a] += s * size[a];
                p[b] += t * size[b];
                p
            };
            let points = vec![
                corner(0.0, 0.0),
                corner(1.0, 0.0),
                corner(1.0, 1.0),
                corner(0.0, 1.0),
            ];
            let centre = points.iter().sum::<DVec3>() / 4.0;
            let Some(depth) = facing_depth(camera, centre, normal) else {
                continue;
            };
            let (base, bands) = match paint {
                Paint::AxisColours => (AXIS_COLOURS[axis], None),
                Paint::Uniform { color, bands } => (color, bands),
            };
            let mut lines = Vec::new();
            if let Some(spacing) = bands.filter(|_| axis != 1) {
                let mut y = (min.y / spacing).floor() * spacing + spacing;
                while y < max.y - 1e-9 {
                    let mut from = corner(0.0, 0.0);
                    let mut to = corner(1.0, 1.0);
                    from.y = y;
                    to.y = y;
                    lines.push((from, to));
                    y += spacing;
                }
            }
            patches.push(Patch {
                depth,
                points,
                fill: shaded(base, normal),
                blur: 0.0,
                lines,
            });
        }
    }
}

/// The sphere's silhouette as seen by the camera: the circle where the cone of rays
/// from the eye (or the cylinder of parallel rays) touches it.
fn sphere_patch(camera: &Camera, center: DVec3, radius: f64, paint: Paint) -> Option<Patch> {
    let image = camera.project(center)?;
    let ray = camera.generate_ray_through(image, DVec2::splat(0.5))?;
    let (rim_centre, rim_radius, axis) = if camera.projection().is_parallel() {
        (center, radius, ray.direction.normalize())
    } else {
        let to_centre = center - ray.origin;
        let distance = to_centre.length();
        if distance <= radius {
            return None;
        }
        let axis = to_centre / distance;
        let pull = radius * radius / distance;
        (
            center - pull * axis,
            radius * (1.0 - (radius / distance).powi(2)).sqrt(),
            axis,
        )
    };
    let side = axis.any_orthonormal_vector();
    let other = axis.cross(side);
    let points = (0..96)
        .map(|k| {
            let angle = TAU * f64::from(k) / 96.0;
            rim_centre + rim_radius * (angle.cos() * side + angle.sin() * other)
        })
        .collect();
    let color = match paint {
        Paint::AxisColours => AXIS_COLOURS[0],
        Paint::Uniform { color, .. } => color,
    };
    // Shade the disc as the part of the sphere that faces the camera.
    Some(Patch {
        depth: center.distance(ray.origin),
        points,
        fill: shaded(color, -axis),
        blur: circle_of_confusion(camera, center).unwrap_or(0.0),
        lines: Vec::new(),
    })
}

/// The radius, in image pixels, of the disc over which a thin-lens camera spreads the
/// point `p`: the ray through `p`'s image point from the rim of the lens misses `p` at
/// `p`'s depth by `r |1 - D/f|`; seen from the lens centre, that miss is the blur.
/// `None` for cameras without a lens.
fn circle_of_confusion(camera: &Camera, p: DVec3) -> Option<f64> {
    if !camera.projection().has_lens() {
        return None;
    }
    let image = camera.project(p)?;
    let rim = camera.generate_ray_through(image, DVec2::new(1.0, 0.5))?;
    let w = camera.frame().w();
    // The rim ray at p's depth along -w.
    let t = (p - rim.origin).dot(w) / rim.direction.dot(w);
    let miss = rim.at(t);
    Some(camera.project(miss)?.distance(image))
}

/// The distance from the camera to a face at `centre` with outward `normal`, or `None`
/// when the face turns away from the viewing ray through its centre.
fn facing_depth(camera: &Camera, centre: DVec3, normal: DVec3) -> Option<f64> {
    let image = camera.project(centre)?;
    let ray = camera.generate_ray_through(image, DVec2::splat(0.5))?;
    (ray.direction.dot(normal) < 0.0).then(|| centre.distance(ray.origin))
}

/// `base` lit by the sun from [`TOWARDS_LIGHT`] with some ambient light, as sRGB.
fn shaded(base: DVec3, normal: DVec3) -> Color {
    let lambert = normal.normalize().dot(TOWARDS_LIGHT.normalize()).max(0.0);
    srgb(base * (0.45 + 0.75 * lambert))
}

/// The sRGB colour of a linear RGB colour (each channel clamped to [0, 1]), by
/// viewray-output's transfer function, as the renderer stores its pixels.
pub(crate) fn srgb(linear: DVec3) -> Color {
    let Srgb8([r, g, b]) = LinearRgb(linear.as_vec3().to_array()).to_srgb8();
    Color::rgb(r, g, b)
}

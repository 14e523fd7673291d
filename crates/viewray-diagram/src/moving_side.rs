//! The side view of a moving camera: one window on the scene for a whole animation, so
//! that from frame to frame only the camera moves.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, CameraSample, Projection};
use viewray_draw::{Anchor, Baseline, Color, Figure, Item, Label, Mapping, Rect, Stroke};
use viewray_geometry::{Aabb, Object};
use viewray_output::LinearRgb;
use viewray_scene::{ObjectMaterial, Scene};

use crate::side::viewport_edges;
use crate::style;

/// The part of a scene a side view shows, fixed for a whole animation: the vertical
/// plane along the first camera's horizontal view direction (`forward`, drawn to the
/// right; world up drawn up), and the rectangle of it around the scene's objects and the
/// cameras near them. Eyes far beyond the objects (a camera receding to infinity) are
/// left out and drawn as an arrow at the edge.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SideWindow {
    forward: DVec3,
    min: DVec2,
    max: DVec2,
}

/// Where a world point lies in the side view's plane: `(p . forward, p.y)`.
fn in_plane(forward: DVec3, p: DVec3) -> DVec2 {
    DVec2::new(p.dot(forward), p.y)
}

/// The eight corners of `bounds`.
fn corners(bounds: Aabb) -> [DVec3; 8] {
    let (a, b) = (bounds.min.as_dvec3(), bounds.max.as_dvec3());
    std::array::from_fn(|i| {
        DVec3::new(
            if i & 1 == 0 { a.x } else { b.x },
            if i & 2 == 0 { a.y } else { b.y },
            if i & 4 == 0 { a.z } else { b.z },
        )
    })
}

impl SideWindow {
    /// The window for `scene` seen by `cameras` (every frame's): the objects' bounds and
    /// the eyes and image planes of the cameras within three times the objects' size of
    /// them, with a margin, and the ground line `y = 0`.
    pub fn fit(scene: &Scene, cameras: &[Camera]) -> SideWindow {
        let forward = cameras
            .first()
            .and_then(|c| (-c.frame().w * DVec3::new(1.0, 0.0, 1.0)).try_normalize())
            .unwrap_or(DVec3::NEG_Z);
        let mut min = DVec2::splat(f64::INFINITY);
        let mut max = DVec2::splat(f64::NEG_INFINITY);
        for object in scene.world().objects() {
            if let Some(bounds) = object.bounds() {
                for p in corners(bounds) {
                    let q = in_plane(forward, p);
                    min = min.min(q);
                    max = max.max(q);
                }
            }
        }
        if !min.is_finite() {
            (min, max) = (DVec2::new(-1.0, 0.0), DVec2::new(1.0, 1.0));
        }
        min.y = min.y.min(0.0);
        let size = (max - min).max_element().max(1.0);
        let (near_min, near_max) = (
            min - DVec2::splat(3.0 * size),
            max + DVec2::splat(3.0 * size),
        );
        for camera in cameras {
            let mut points = vec![camera.frame().e];
            if camera.projection().viewport().is_some() {
                let (top, bottom) = viewport_edges(camera);
                points.extend([top, bottom]);
            }
            for p in points {
                let q = in_plane(forward, p);
                if q.cmpge(near_min).all() && q.cmple(near_max).all() {
                    min = min.min(q);
                    max = max.max(q);
                }
            }
        }
        let margin = 0.08 * (max - min).max_element();
        SideWindow {
            forward,
            min: min - DVec2::splat(margin),
            max: max + DVec2::splat(margin),
        }
    }

    /// The part `(t0, t1)` of `t` over which the ray `origin + t direction` stays inside
    /// the window, or `None`.
    fn clip(&self, origin: DVec3, direction: DVec3, t: (f64, f64)) -> Option<(f64, f64)> {
        let (o, d) = (
            in_plane(self.forward, origin),
            DVec2::new(direction.dot(self.forward), direction.y),
        );
        let (mut t0, mut t1) = t;
        for axis in 0..2 {
            if d[axis] == 0.0 {
                if o[axis] < self.min[axis] || o[axis] > self.max[axis] {
                    return None;
                }
                continue;
            }
            let (a, b) = (
                (self.min[axis] - o[axis]) / d[axis],
                (self.max[axis] - o[axis]) / d[axis],
            );
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 < t1).then_some((t0, t1))
    }
}

/// The side view of `camera` looking at `scene` in `window`, on a canvas of `size`
/// pixels: the ground and the objects (spheres as circles, the rest as the outline of
/// their bounds, in their materials' colours), the frustum's top and bottom edges, five
/// viewing rays of the middle column (pixel centres, lens centre) each drawn to the first
/// thing it hits, the image plane edge-on, a thin lens's lens and focus plane, and the
/// eye **e** (an arrow at the edge when it lies beyond the window), with the projection's
/// name. Every ray drawn is one `camera` generates.
pub fn side_view(scene: &Scene, camera: &Camera, window: &SideWindow, size: (u32, u32)) -> Figure {
    let mut figure = Figure {
        background: style::BACKGROUND,
        ..Figure::new(size.0, size.1)
    };
    // Sizes are the slides' (900 pixels tall), scaled to this canvas.
    let k = size.1 as f32 / style::SLIDE.1 as f32;
    let world = Rect::from_corners(window.min.as_vec2(), window.max.as_vec2());
    let canvas = Rect::from_xywh(0.0, 0.0, size.0 as f32, size.1 as f32).expand(-12.0 * k);
    let Some(mapping) = Mapping::fit(world, canvas) else {
        return figure;
    };
    let to = |p: DVec3| mapping.to_canvas(in_plane(window.forward, p).as_vec2());
    let left = mapping.to_world(Vec2::ZERO).x;
    let right = mapping.to_world(Vec2::new(size.0 as f32, 0.0)).x;

    // The ground planes, seen edge-on, and the objects.
    for (index, object) in scene.world().objects().iter().enumerate() {
        let color = object_color(scene, index);
        match object {
            Object::Plane(plane) if plane.normal.normalize().y.abs() > 0.999 => {
                let y = plane.point.y;
                let (a, b) = (
                    mapping.to_canvas(Vec2::new(left, y)),
                    mapping.to_canvas(Vec2::new(right, y)),
                );
                figure.push(Item::Polygon {
                    points: vec![
                        a,
                        b,
                        Vec2::new(b.x, size.1 as f32),
                        Vec2::new(a.x, size.1 as f32),
                    ],
                    fill: Color::from_hex(0xEEEEEE),
                    stroke: None,
                });
                figure.push(Item::Line {
                    from: a,
                    to: b,
                    stroke: Stroke::new(style::OBJECT, style::LINE_REGULAR * k),
                });
            }
            Object::Sphere(sphere) => {
                figure.push(Item::Ellipse {
                    center: to(sphere.center.as_dvec3()),
                    radii: Vec2::splat(mapping.length_to_canvas(sphere.radius)),
                    rotation: 0.0,
                    fill: Some(color),
                    stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN * k)),
                });
            }
            Object::Triangle(triangle) => {
                let points = [triangle.a, triangle.b, triangle.c];
                figure.push(Item::Polygon {
                    points: convex_hull(points.iter().map(|p| to(p.as_dvec3())).collect()),
                    fill: color,
                    stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN * k)),
                });
            }
            _ => {
                if let Some(bounds) = object.bounds() {
                    let points: Vec<Vec2> = corners(bounds).iter().map(|&p| to(p)).collect();
                    figure.push(Item::Polygon {
                        points: convex_hull(points),
                        fill: color,
                        stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN * k)),
                    });
                }
            }
        }
    }

    let frame = camera.frame();
    let planar = camera.projection().viewport().is_some();
    let far = 1e3 * (window.max - window.min).max_element();
    // The frustum's top and bottom edges, dashed.
    if planar {
        let x = f64::from(camera.width()) / 2.0;
        for y in [0.0, f64::from(camera.height())] {
            if let Some(ray) = camera.generate_ray_through(DVec2::new(x, y), DVec2::splat(0.5)) {
                let length = far / ray.direction.length();
                if let Some((t0, t1)) = window.clip(ray.origin, ray.direction, (0.0, length)) {
                    figure.push(Item::Line {
                        from: to(ray.at(t0)),
                        to: to(ray.at(t1)),
                        stroke: Stroke::new(style::RAY, style::LINE_THIN * k)
                            .dashed(&style::DASH.map(|d| d * k)),
                    });
                }
            }
        }
    }
    // Five rays of the middle column, each to what it hits.
    let col = camera.width() / 2;
    for n in 0..5u32 {
        let row = ((2 * n + 1) * camera.height() / 10).min(camera.height() - 1);
        let Some(ray) = camera.generate_ray(row, col, CameraSample::CENTER) else {
            continue;
        };
        let length = far / ray.direction.length();
        #[allow(clippy::cast_possible_truncation)]
        let hit = scene
            .world()
            .closest_hit(&ray.as_ray(), f32::MIN_POSITIVE..length as f32)
            .map_or(length, |hit| f64::from(hit.t));
        if let Some((t0, t1)) = window.clip(ray.origin, ray.direction, (0.0, hit)) {
            figure.push(Item::Line {
                from: to(ray.at(t0)),
                to: to(ray.at(t1)),
                stroke: Stroke::new(style::RAY, style::LINE_REGULAR * k),
            });
            if t1 == hit && hit < length {
                figure.push(Item::Dot {
                    center: to(ray.at(t1)),
                    radius: style::DOT_RADIUS * 0.7 * k,
                    color: style::RAY,
                });
            }
        }
    }
    // A lens: its focus plane, dashed, and the lens itself at the eye.
    let lens = match camera.projection() {
        Projection::ThinLens(p) => Some((p.aperture, p.focus)),
        Projection::Orthographic(o) => o.lens.map(|l| (l.aperture, l.focus)),
        _ => None,
    };
    if let Some((aperture, focus)) = lens {
        let centre = frame.e - frame.w * focus;
        let half = 0.5 * (window.max.y - window.min.y);
        figure.push(Item::Line {
            from: to(centre + frame.v * half),
            to: to(centre - frame.v * half),
            stroke: Stroke::new(style::HIGHLIGHT, style::LINE_REGULAR * k)
                .dashed(&style::DASH.map(|d| d * k)),
        });
        let (a, b) = (
            to(frame.e + frame.v * aperture),
            to(frame.e - frame.v * aperture),
        );
        figure.push(Item::Ellipse {
            center: (a + b) / 2.0,
            radii: Vec2::new(
                ((a - b).length() * 0.09).max(2.0 * k),
                (a - b).length() / 2.0,
            ),
            rotation: 0.0,
            fill: Some(style::IMAGE_PLANE_FILL),
            stroke: Some(Stroke::new(style::OBJECT, style::LINE_THIN * k)),
        });
    }
    // The image plane, edge-on.
    if planar {
        let (top, bottom) = viewport_edges(camera);
        figure.push(Item::Line {
            from: to(top),
            to: to(bottom),
            stroke: Stroke::new(style::IMAGE_PLANE, style::LINE_THICK * k),
        });
    }
    // The eye, or an arrow towards it.
    let eye = in_plane(window.forward, frame.e);
    let label_size = style::LABEL_SIZE * k;
    if eye.cmpge(window.min).all() && eye.cmple(window.max).all() {
        let at = to(frame.e);
        figure.push(Item::Dot {
            center: at,
            radius: style::DOT_RADIUS * k,
            color: style::EYE,
        });
        figure.push(
            Label::new("*e*", at + Vec2::new(-10.0 * k, -10.0 * k))
                .with_size(label_size)
                .with_color(style::EYE)
                .with_anchor(Anchor::End, Baseline::Bottom),
        );
    } else {
        let centre = (window.min + window.max) / 2.0;
        let towards = (eye - centre).normalize();
        // Where the line from the centre to the eye leaves the window.
        let half = (window.max - window.min) / 2.0;
        let reach = (half / towards.abs()).min_element();
        let edge = centre + towards * reach * 0.97;
        let tip = mapping.to_canvas(edge.as_vec2());
        let tail = mapping.to_canvas((edge - towards * reach * 0.25).as_vec2());
        figure.push(Item::Arrow {
            from: tail,
            to: tip,
            stroke: Stroke::new(style::EYE, style::LINE_REGULAR * k),
            ends: viewray_draw::ArrowEnds::End,
        });
        let distance = (frame.e - world_centre(window)).length();
        figure.push(
            Label::new(
                format!("*e*, {distance:.0} away"),
                tail + Vec2::new(0.0, -14.0 * k),
            )
            .with_size(style::SMALL_LABEL_SIZE * k)
            .with_color(style::EYE)
            .with_anchor(Anchor::Middle, Baseline::Bottom),
        );
    }
    figure.push(
        Label::new(
            format!("side view: {}", camera.projection().family_name()),
            Vec2::new(14.0 * k, size.1 as f32 - 12.0 * k),
        )
        .with_size(style::SMALL_LABEL_SIZE * k)
        .with_color(style::ANNOTATION)
        .with_anchor(Anchor::Start, Baseline::Bottom),
    );
    figure
}

/// The world point at the window's centre, on the vertical plane through the origin.
fn world_centre(window: &SideWindow) -> DVec3 {
    let c = (window.min + window.max) / 2.0;
    window.forward * c.x + DVec3::Y * c.y
}

/// An object's colour as a figure draws it: its material's (one material for the whole
/// object), light grey otherwise.
fn object_color(scene: &Scene, index: usize) -> Color {
    match scene.object_materials().get(index) {
        Some(ObjectMaterial::Single(material)) => {
            let c = scene.materials()[*material as usize].color;
            let srgb = LinearRgb(c.to_array()).to_srgb8().0;
            Color::rgba(srgb[0], srgb[1], srgb[2], 255)
        }
        _ => style::OBJECT_FILL,
    }
}

/// The convex hull of `points`, counter-clockwise (Andrew's monotone chain).
fn convex_hull(mut points: Vec<Vec2>) -> Vec<Vec2> {
    points.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    points.dedup();
    if points.len() < 3 {
        return points;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::with_capacity(2 * points.len());
    for pass in 0..2 {
        let start = hull.len();
        let ordered: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(points.iter())
        } else {
            Box::new(points.iter().rev())
        };
        for &p in ordered {
            while hull.len() >= start + 2
                && cross(hull[hull.len() - 2], hull[hull.len() - 1], p) <= 0.0
            {
                hull.pop();
            }
            hull.push(p);
        }
        hull.pop();
    }
    hull
}

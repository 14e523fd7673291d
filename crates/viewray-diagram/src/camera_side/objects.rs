//! The scene's objects seen from the side: spheres as circles, boxes and meshes as
//! their outlines, planes seen edge-on as lines over a light fill.

use glam::{DVec2, DVec3, Vec2};
use viewray_draw::{Color, Item, Stroke};
use viewray_geometry::Object;
use viewray_scene::Scene;

use crate::pictures::srgb;
use crate::sketch::Sketch;
use crate::style;
use crate::view::SideView;

/// Meshes with more triangles than this are drawn as the outline of their bounds.
const MAX_DRAWN_TRIANGLES: usize = 4000;

/// The colour of object `object` of the scene: its material's (the first face's for a
/// mesh with per-face materials), as the renderer stores it.
fn object_color(scene: &Scene, object: usize) -> Color {
    // Object indices come from the scene's own world, which holds fewer than 2^32.
    #[allow(clippy::cast_possible_truncation)]
    let material = scene.material_of(object as u32, 0);
    srgb(material.color.as_dvec3())
}

/// Draws the scene's objects projected onto the side view, farthest from the viewer
/// first.
pub(super) fn draw_objects(sketch: &mut Sketch, view: &SideView, scene: &Scene) {
    let outline = Stroke::new(style::OBJECT, style::LINE_THIN);
    let towards_viewer = view.towards_viewer();
    let objects = scene.world().objects();
    // Planes first (they are the ground and walls), then the rest by depth.
    for (index, object) in objects.iter().enumerate() {
        if let Object::Plane(plane) = object {
            draw_plane(
                sketch,
                view,
                plane.point.as_dvec3(),
                plane.normal.as_dvec3(),
                object_color(scene, index),
            );
        }
    }
    let mut order: Vec<(f64, usize)> = objects
        .iter()
        .enumerate()
        .filter_map(|(index, object)| {
            let bounds = object.bounds()?;
            Some((
                ((bounds.min + bounds.max) / 2.0)
                    .as_dvec3()
                    .dot(towards_viewer),
                index,
            ))
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for (_, index) in order {
        let fill = object_color(scene, index).with_alpha(0.85);
        let to_figure = |p: glam::Vec3| view.to_figure(p.as_dvec3());
        match &objects[index] {
            Object::Sphere(sphere) => sketch.push(Item::Ellipse {
                center: to_figure(sphere.center),
                radii: Vec2::splat(view.length(f64::from(sphere.radius))),
                rotation: 0.0,
                fill: Some(fill),
                stroke: Some(outline.clone()),
            }),
            Object::Triangle(triangle) => sketch.push(Item::Polygon {
                points: [triangle.a, triangle.b, triangle.c].map(to_figure).to_vec(),
                fill,
                stroke: Some(outline.clone()),
            }),
            Object::Box(aabb) => sketch.push(Item::Polygon {
                points: convex_hull(&aabb.corners().map(to_figure)),
                fill,
                stroke: Some(outline.clone()),
            }),
            Object::Instance(instance) => {
                let data = instance.mesh().data();
                let transform = instance.world_from_object();
                if data.triangles.len() > MAX_DRAWN_TRIANGLES {
                    sketch.push(Item::Polygon {
                        points: convex_hull(&instance.bounds().corners().map(to_figure)),
                        fill,
                        stroke: Some(outline.clone()),
                    });
                } else {
                    for triangle in &data.triangles {
                        let points = triangle.map(|i| {
                            to_figure(transform.transform_point3(data.positions[i as usize]))
                        });
                        sketch.push(Item::Polygon {
                            points: points.to_vec(),
                            fill,
                            stroke: Some(Stroke::new(fill.with_alpha(1.0), 1.0)),
                        });
                    }
                }
            }
            Object::Plane(_) => {}
        }
    }
}

/// The convex hull of `points` (Andrew's monotone chain), counter-clockwise.
fn convex_hull(points: &[Vec2]) -> Vec<Vec2> {
    let mut sorted = points.to_vec();
    sorted.sort_by(|a, b| a.x.total_cmp(&b.x).then(a.y.total_cmp(&b.y)));
    sorted.dedup();
    if sorted.len() < 3 {
        return sorted;
    }
    let cross = |o: Vec2, a: Vec2, b: Vec2| (a - o).perp_dot(b - o);
    let mut hull: Vec<Vec2> = Vec::with_capacity(sorted.len() * 2);
    for pass in 0..2 {
        let start = hull.len();
        let iter: Box<dyn Iterator<Item = &Vec2>> = if pass == 0 {
            Box::new(sorted.iter())
        } else {
            Box::new(sorted.iter().rev())
        };
        for &p in iter {
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

/// Draws an infinite plane seen edge-on: the line where it cuts the view, and a light
/// fill on its back side. A plane not perpendicular to the figure covers all of it and
/// is not drawn.
fn draw_plane(sketch: &mut Sketch, view: &SideView, point: DVec3, normal: DVec3, color: Color) {
    let n = view.plane_point(normal);
    if normal.dot(view.towards_viewer()).abs() > 1e-9 * normal.length() || n.length() == 0.0 {
        return;
    }
    let c = point.dot(normal);
    // The view's corners, and the part of the rectangle behind the plane (n . p <= c).
    let (lo, hi) = (view.bounds.min.as_dvec2(), view.bounds.max.as_dvec2());
    let corners = [
        DVec2::new(lo.x, lo.y),
        DVec2::new(hi.x, lo.y),
        DVec2::new(hi.x, hi.y),
        DVec2::new(lo.x, hi.y),
    ];
    let side = |p: DVec2| n.dot(p) - c;
    let mut behind = Vec::new();
    let mut line = Vec::new();
    for k in 0..4 {
        let (a, b) = (corners[k], corners[(k + 1) % 4]);
        let (sa, sb) = (side(a), side(b));
        if sa <= 0.0 {
            behind.push(a);
        }
        if (sa < 0.0) != (sb < 0.0) {
            let crossing = a + (b - a) * (sa / (sa - sb));
            behind.push(crossing);
            line.push(crossing);
        }
    }
    let to_canvas = |p: DVec2| view.mapping.to_canvas(p.as_vec2());
    if behind.len() >= 3 {
        sketch.push(Item::Polygon {
            points: behind.into_iter().map(to_canvas).collect(),
            fill: color.with_alpha(0.35),
            stroke: None,
        });
    }
    if let [a, b] = line[..] {
        sketch.line(
            to_canvas(a),
            to_canvas(b),
            Stroke::new(style::OBJECT, style::LINE_REGULAR),
        );
    }
}

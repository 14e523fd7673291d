//! The trace as text for people: the lecture's three steps as headings, each step's
//! numbers under them beside their formulas, indented by mirror bounce.

use glam::{DVec3, Vec3};
use viewray_camera::Camera;
use viewray_output::number::label_significant;
use viewray_render::{
    ClosestHit, DepthValue, GridLines, LitSurface, PixelKind, PixelTrace, Shape, Step, StepKind,
};
use viewray_scene::Shading;

/// The trace `trace` of a pixel of `camera`'s image, shaded by `shading`, as text for
/// people: the lecture's three steps (generate a viewing ray, find the closest object,
/// determine its colour) with each number beside its formula, then the pixel's linear
/// value and its 8-bit value, "as `render` writes it" (`render` names the one-sample
/// render in the reader's program's words, as `viewray render --samples 1` on the
/// command line). Numbers are rounded to three decimals (three significant digits below
/// 0.1); [`trace_lines`](crate::trace_lines) has them exactly.
pub fn trace_text(camera: &Camera, shading: Shading, trace: &PixelTrace, render: &str) -> String {
    let mut text = Text::default();
    let (row, col) = (trace.row, trace.col);
    text.line(
        0,
        format!(
            "pixel row {row}, col {col} (the lecture's i = {}, j = {}) of the {} x {} image, \
             {} shading, 1 sample",
            row + 1,
            col + 1,
            camera.width(),
            camera.height(),
            shading.name()
        ),
    );
    let mut started = None;
    for step in &trace.steps {
        text.step(camera, shading, trace, step, &mut started);
    }
    text.blank();
    match trace.kind {
        PixelKind::Color => {
            text.line(0, format!("linear colour {}", v3(trace.value)));
            text.line(
                0,
                format!("8-bit sRGB, as {render} writes it: {}", bytes(trace.rgb8)),
            );
        }
        PixelKind::Data => {
            text.line(0, format!("value {}", v3(trace.value)));
            text.line(
                0,
                format!(
                    "8-bit round(255 x), as {render} writes it: {}",
                    bytes(trace.rgb8)
                ),
            );
        }
    }
    text.out
}

/// The part of the lecture's pseudocode a step belongs to.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Part {
    Find,
    Colour,
}

/// Lines of text, indented by nesting level (two spaces each), and the surface shaded
/// at each bounce (whose numbers the lighting's lines repeat).
#[derive(Default)]
pub(super) struct Text {
    out: String,
    /// The surface shaded at each bounce so far.
    pub(super) surfaces: Vec<LitSurface>,
}

impl Text {
    pub(super) fn line(&mut self, level: u32, line: impl AsRef<str>) {
        for _ in 0..level {
            self.out.push_str("  ");
        }
        self.out.push_str(line.as_ref());
        self.out.push('\n');
    }

    pub(super) fn blank(&mut self) {
        self.out.push('\n');
    }

    /// Writes `step`, with the heading of its part of the pseudocode where it starts
    /// one (`started`: the bounce and part last headed).
    fn step(
        &mut self,
        camera: &Camera,
        shading: Shading,
        trace: &PixelTrace,
        step: &Step,
        started: &mut Option<(u32, Part)>,
    ) {
        let b = step.bounce;
        // A bounce's headings sit under its mirror's line: two levels deeper each bounce.
        let (heading, item) = (2 * b, 2 * b + 1);
        let part = match step.kind {
            StepKind::ViewingRay { .. } | StepKind::Reflect { .. } | StepKind::Mix { .. } => None,
            StepKind::Test { .. } | StepKind::Closest(_) => Some(Part::Find),
            StepKind::Background { .. } if started.is_none_or(|s| s != (b, Part::Find)) => {
                Some(Part::Find)
            }
            StepKind::Background { .. } => None,
            _ => Some(Part::Colour),
        };
        if let Some(part) = part
            && *started != Some((b, part))
        {
            if b == 0 {
                self.blank();
            }
            let title = match part {
                Part::Find => "find the closest object it intersects".to_owned(),
                Part::Colour => format!("determine the colour of the object ({})", mode(shading)),
            };
            self.line(heading, title);
            *started = Some((b, part));
        }
        match &step.kind {
            StepKind::ViewingRay { ray } => {
                self.blank();
                self.line(0, "generate a viewing ray for the pixel");
                let ray = ray.map(|r| (r.origin, r.direction));
                self.viewing_ray(camera, (trace.row, trace.col), ray);
                if ray.is_none() {
                    // Nothing to find: the background follows.
                    *started = Some((0, Part::Find));
                }
            }
            StepKind::Test { object, shape, t } => {
                let result = t.map_or("miss".to_owned(), |t| format!("hit at t = {}", n(t)));
                self.line(
                    item,
                    format!("object {object} ({}): {result}", shape.name()),
                );
            }
            StepKind::Closest(hit) => self.closest(item, hit),
            StepKind::Background { color } => {
                self.line(item, format!("nothing: the background {}", v3(*color)));
            }
            StepKind::Flat {
                material,
                color,
                grid,
            } => {
                self.line(item, format!("material {material}: color {}", v3(*color)));
                if let Some(grid) = grid {
                    self.grid(item, grid);
                }
            }
            StepKind::Normals { normal, value } => {
                self.line(
                    item,
                    format!("n/2 + 1/2 = {}/2 + 1/2 = {}", v3(*normal), v3(*value)),
                );
            }
            StepKind::Depth(depth) => self.depth(item, depth),
            StepKind::Surface(surface) => {
                self.surfaces.truncate(b as usize);
                self.surfaces.push(*surface);
                self.surface(item, surface);
            }
            StepKind::Headlight(headlight) => {
                self.line(
                    item,
                    "no lights: the headlight, a light at the eye (l = v, no shadow)",
                );
                self.blinn_phong(item + 1, b, &headlight.lit);
                self.line(
                    item + 1,
                    format!(
                        "adds {} color + {} (diffuse + specular) = {}",
                        n(headlight.ambient),
                        n(1.0 - headlight.ambient),
                        v3(headlight.term)
                    ),
                );
                self.line(item, format!("colour so far {}", v3(headlight.color)));
            }
            StepKind::Ambient {
                light,
                intensity,
                term,
                color,
            } => {
                self.line(
                    item,
                    format!(
                        "light {light}, ambient, I = {}: adds color I = {}; colour so far {}",
                        v3(*intensity),
                        v3(*term),
                        v3(*color)
                    ),
                );
            }
            StepKind::Light(terms) => self.light(item, b, terms),
            StepKind::Reflect { mirror, ray } => match ray {
                Some(ray) => {
                    self.line(
                        item,
                        format!(
                            "mirror {}: the reflected ray r = d - 2 (d.n) n, traced the same way",
                            n(*mirror)
                        ),
                    );
                    self.line(
                        item + 1,
                        format!("origin {}, direction {}", v3(ray.origin), v3(ray.direction)),
                    );
                }
                None => self.line(
                    item,
                    format!(
                        "mirror {}: past the last bounce, the reflection is black",
                        n(*mirror)
                    ),
                ),
            },
            StepKind::Mix {
                mirror,
                local,
                reflected,
                color,
            } => {
                self.line(
                    item,
                    format!(
                        "mix (1 - mirror) local + mirror reflected = {} {} + {} {} = {}",
                        n(1.0 - mirror),
                        v3(*local),
                        n(*mirror),
                        v3(*reflected),
                        v3(*color)
                    ),
                );
            }
        }
    }

    fn closest(&mut self, item: u32, hit: &ClosestHit) {
        let face = if hit.primitive > 0 || hit.shape == Shape::Mesh {
            format!(", face {}", hit.primitive)
        } else {
            String::new()
        };
        self.line(
            item,
            format!(
                "closest: object {} ({}{face}, material {}) at t = {}",
                hit.object,
                hit.shape.name(),
                hit.material,
                n(hit.t)
            ),
        );
        self.line(
            item + 1,
            format!("point  p = origin + t direction = {}", v3(hit.point)),
        );
        if hit.shading_normal == hit.normal {
            self.line(item + 1, format!("normal n = {}", v3(hit.normal)));
        } else {
            self.line(
                item + 1,
                format!(
                    "normal {} (the surface's), shading normal n = {} (interpolated)",
                    v3(hit.normal),
                    v3(hit.shading_normal)
                ),
            );
        }
    }

    pub(super) fn grid(&mut self, item: u32, grid: &GridLines) {
        let axis = |a: usize| ["x", "y", "z"].get(a).copied().unwrap_or("?");
        self.line(
            item + 1,
            format!(
                "grid lines along {} and {}: covering {} and {} of the sample's footprint \
                 ({} by {}), together 1 - (1 - a)(1 - b) = {}",
                axis(grid.axes[0]),
                axis(grid.axes[1]),
                n(grid.coverage[0]),
                n(grid.coverage[1]),
                n(grid.footprint[0]),
                n(grid.footprint[1]),
                n(grid.total)
            ),
        );
        self.line(
            item + 1,
            format!(
                "color = {} mixed with the lines' {} by {} = {}",
                v3(grid.base),
                v3(grid.line_color),
                n(grid.total),
                v3(grid.color)
            ),
        );
    }

    fn depth(&mut self, item: u32, depth: &DepthValue) {
        let rule = if depth.panoramic {
            "|p - e|"
        } else {
            "(p - e).(-W)"
        };
        self.line(item, format!("z = {rule} = {}", n(depth.z)));
        match depth.s {
            Some(s) => {
                self.line(
                    item,
                    format!(
                        "s = (z - near)/(far - near) = ({} - {})/({} - {}) = {}   (near and \
                         far: the image's nearest and farthest hits)",
                        n(depth.z),
                        n(depth.near),
                        n(depth.far),
                        n(depth.near),
                        n(s)
                    ),
                );
                let rule = if s <= 1.0 { "1 - 0.9 s" } else { "0.1 / s" };
                self.line(item, format!("value = {rule} = {}", n(depth.value)));
            }
            None => self.line(
                item,
                format!("the image has no range of depths: value {}", n(depth.value)),
            ),
        }
    }
}

/// The shading mode's name and rule, for the heading of the colour step.
fn mode(shading: Shading) -> &'static str {
    match shading {
        Shading::Flat => "Flat: the material's colour",
        Shading::Normals => "Normals: the shading normal n as n/2 + 1/2",
        Shading::Depth => "Depth: near white, far dark",
        Shading::Lit => "Lit: Blinn-Phong, shadows and mirrors",
    }
}

/// A renderer's number (`f32`) for people (see [`m`]).
pub(super) fn n(x: f32) -> String {
    m(f64::from(x))
}

/// A camera's number (`f64`) for people: a label's digits (three decimals, or three
/// significant digits below 0.1), but with the ASCII minus of the formulas beside it,
/// since a terminal is not typeset and a student pastes these numbers into a program.
pub(super) fn m(x: f64) -> String {
    label_significant(x).replace('\u{2212}', "-")
}

/// A vector of the renderer's numbers, `(x, y, z)`.
pub(super) fn v3(v: Vec3) -> String {
    format!("({}, {}, {})", n(v.x), n(v.y), n(v.z))
}

/// A vector of a camera's numbers, `(x, y, z)`.
pub(super) fn d3(v: DVec3) -> String {
    format!("({}, {}, {})", m(v.x), m(v.y), m(v.z))
}

fn bytes(b: [u8; 3]) -> String {
    format!("({}, {}, {})", b[0], b[1], b[2])
}

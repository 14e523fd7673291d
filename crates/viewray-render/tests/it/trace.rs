//! A pixel's trace against the render and against the lecture's formulas: its value is
//! the one-sample image's, bit for bit, in every fixture scene (every camera family) and
//! every shading mode, at pixels that reach every kind of step; and its numbers are the
//! formulas' numbers, worked out here apart from the renderer.

use std::path::{Path, PathBuf};

use glam::{DVec3, Vec3};
use viewray_render::{
    LightSource, PixelKind, PixelTrace, RenderSettings, Shape, StepKind, View, object_labels,
    render_view, trace_pixel,
};
use viewray_scene::{LoadOptions, Scene, SceneLoader, Shading};

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

/// Every scene file of the repository: `fixtures/scenes/*.ron`, the default scene and
/// the homework scenes.
fn fixture_scenes() -> Vec<PathBuf> {
    let mut paths = Vec::new();
    for folder in ["scenes", "homework"] {
        let entries = std::fs::read_dir(fixtures().join(folder)).unwrap();
        paths.extend(
            entries
                .map(|entry| entry.unwrap().path())
                .filter(|path| path.extension().is_some_and(|e| e == "ron")),
        );
    }
    paths.sort();
    paths.push(fixtures().join("default.ron"));
    paths
}

/// The scene at `path` as `viewray render --samples 1` loads it.
fn load(path: &Path) -> Scene {
    let options = LoadOptions {
        samples: Some(1),
        ..LoadOptions::default()
    };
    SceneLoader::file(path)
        .options(options)
        .load()
        .unwrap_or_else(|e| panic!("{e}"))
        .scene
}

/// The pixels to trace in an image of `labels` (what each pixel's centre ray meets,
/// row by row): the corners, the centre, an even spread of `across x across` pixels,
/// and up to `edges` of the pixels where the label changes (an object's outline, or
/// where one object hides another).
fn pixels(
    labels: &[u32],
    (width, height): (u32, u32),
    across: u32,
    edges: usize,
) -> Vec<(u32, u32)> {
    let (w, h) = (width - 1, height - 1);
    let mut pixels = vec![(0, 0), (0, w), (h, 0), (h, w), (h / 2, w / 2)];
    for r in 0..across {
        for c in 0..across {
            pixels.push((
                (2 * r + 1) * height / (2 * across),
                (2 * c + 1) * width / (2 * across),
            ));
        }
    }
    let label = |row: u32, col: u32| labels[(row * width + col) as usize];
    let outline: Vec<(u32, u32)> = (0..height)
        .flat_map(|row| (0..width).map(move |col| (row, col)))
        .filter(|&(row, col)| {
            (col + 1 < width && label(row, col) != label(row, col + 1))
                || (row + 1 < height && label(row, col) != label(row + 1, col))
        })
        .collect();
    let step = outline.len().div_ceil(edges.max(1)).max(1);
    pixels.extend(outline.iter().step_by(step));
    pixels.sort_unstable();
    pixels.dedup();
    pixels
}

/// Which kinds of step the traces reached, so that the test knows it tried them all.
#[derive(Debug, Default)]
struct Reached {
    background: bool,
    no_ray: bool,
    mirror: bool,
    last_bounce: bool,
    reflected_background: bool,
    shadowed: bool,
    lit: bool,
    behind: bool,
    headlight: bool,
    grid_edge: bool,
    mesh: bool,
    depth_beyond_far: bool,
}

impl Reached {
    fn note(&mut self, trace: &PixelTrace) {
        for step in &trace.steps {
            match &step.kind {
                StepKind::ViewingRay { ray: None } => self.no_ray = true,
                StepKind::Background { .. } if step.bounce == 0 => self.background = true,
                StepKind::Background { .. } => self.reflected_background = true,
                StepKind::Reflect { ray: Some(_), .. } => self.mirror = true,
                StepKind::Reflect { ray: None, .. } => self.last_bounce = true,
                StepKind::Light(light) => match light.shadow {
                    Some(shadow) if shadow.blocked => self.shadowed = true,
                    Some(_) => self.lit |= light.lit.is_some(),
                    None => self.behind = true,
                },
                StepKind::Headlight(_) => self.headlight = true,
                StepKind::Flat {
                    grid: Some(grid), ..
                } => self.grid_edge |= grid.total > 0.0 && grid.total < 1.0,
                StepKind::Surface(surface) => {
                    self.grid_edge |= surface.grid.is_some_and(|g| g.total > 0.0 && g.total < 1.0);
                }
                StepKind::Closest(hit) => self.mesh |= hit.shape == Shape::Mesh,
                StepKind::Depth(depth) => self.depth_beyond_far |= depth.s.is_some_and(|s| s > 1.0),
                _ => {}
            }
        }
    }
}

/// A scene no fixture is like: no lights (the headlight shades it), and two mirrors
/// facing each other, between which rays bounce past the last bounce.
const FACING_MIRRORS: &str = "(
    image: (width: 40, height: 30), shading: Lit,
    camera: (eye: (0.0, 0.5, 0.0), look_at: (0.3, 0.0, -4.0),
             projection: Perspective(fov_y: 60.0)),
    materials: {
        \"mirror\": (color: (0.9, 0.9, 0.9), specular: 0.5, shininess: 50.0, mirror: 0.7),
        \"green\": (color: (0.1, 0.7, 0.2), specular: 0.2, shininess: 10.0),
    },
    objects: [
        Plane(point: (0.0, 0.0, -5.0), normal: (0.0, 0.0, 1.0), material: \"mirror\"),
        Plane(point: (0.0, 0.0, 5.0), normal: (0.0, 0.0, -1.0), material: \"mirror\"),
        Sphere(center: (0.5, 0.0, -3.0), radius: 0.6, material: \"green\"),
    ],
)";

#[test]
fn a_trace_is_the_pixel_of_the_one_sample_render_in_every_scene_and_shading() {
    let settings = RenderSettings::default();
    let mut reached = Reached::default();
    let mut traced = 0;
    let facing = SceneLoader::text(FACING_MIRRORS, Path::new("facing_mirrors.ron"))
        .load()
        .unwrap()
        .scene;
    let scenes = fixture_scenes()
        .into_iter()
        .map(|path| (path.display().to_string(), load(&path)))
        .chain([("facing_mirrors.ron".to_owned(), facing)]);
    for (path, scene) in scenes {
        let camera = scene.camera();
        let size = (camera.width(), camera.height());
        let labels = object_labels(&scene, camera);
        for shading in Shading::ALL {
            let view = View {
                shading,
                ..View::of(&scene)
            };
            let image = render_view(&scene, &view, &settings, |_, _| {})
                .unwrap()
                .image;
            let rgb8 = image.to_rgb8();
            // Depth traces find the image's range of depths first, a ray per pixel:
            // fewer of them.
            let (across, edges) = if shading == Shading::Depth {
                (3, 8)
            } else {
                (8, 48)
            };
            for (row, col) in pixels(&labels, size, across, edges) {
                let trace = trace_pixel(&scene, &view, &settings, row, col).unwrap();
                let at = format!("{path} ({}), pixel {row},{col}", shading.name());
                let expected = image.pixel(row, col);
                assert_eq!(
                    trace.value.to_array().map(f32::to_bits),
                    expected.to_array().map(f32::to_bits),
                    "{at}: the trace's value {} against the image's {expected}",
                    trace.value
                );
                let i = 3 * (row * size.0 + col) as usize;
                assert_eq!(trace.rgb8[..], rgb8[i..i + 3], "{at}");
                assert_eq!(trace.kind, image.kind(), "{at}");
                reached.note(&trace);
                traced += 1;
            }
        }
    }
    assert!(traced > 3000, "{traced} pixels traced");
    let Reached {
        background,
        no_ray,
        mirror,
        last_bounce,
        reflected_background,
        shadowed,
        lit,
        behind,
        headlight,
        grid_edge,
        mesh,
        depth_beyond_far,
    } = reached;
    assert!(
        background
            && no_ray
            && mirror
            && last_bounce
            && reflected_background
            && shadowed
            && lit
            && behind
            && headlight
            && grid_edge
            && mesh
            && depth_beyond_far,
        "not every kind of step was reached: {reached:?}",
        reached = Reached {
            background,
            no_ray,
            mirror,
            last_bounce,
            reflected_background,
            shadowed,
            lit,
            behind,
            headlight,
            grid_edge,
            mesh,
            depth_beyond_far,
        }
    );
}

#[test]
fn every_pixel_of_the_homework_scene_is_its_render_under_any_settings() {
    let scene = load(&fixtures().join("homework/lit_4x4.ron"));
    // Tiles and blocks of other sizes, and fewer mirror bounces: still the image's pixels.
    for settings in [
        RenderSettings::default(),
        RenderSettings {
            tile_size: 3,
            max_reflection_depth: 0,
            threads: Some(1),
        },
    ] {
        let view = View::of(&scene);
        let image = render_view(&scene, &view, &settings, |_, _| {})
            .unwrap()
            .image;
        for row in 0..4 {
            for col in 0..4 {
                let trace = trace_pixel(&scene, &view, &settings, row, col).unwrap();
                assert_eq!(trace.value, image.pixel(row, col), "{row},{col}");
            }
        }
    }
    // Outside the image: an error naming the pixel and the image.
    let error =
        trace_pixel(&scene, &View::of(&scene), &RenderSettings::default(), 4, 0).unwrap_err();
    assert_eq!(error.to_string(), "pixel 4,0 is outside the 4 x 4 image");
}

/// `v` in `f64`.
fn d(v: Vec3) -> DVec3 {
    v.as_dvec3()
}

#[track_caller]
fn close(got: Vec3, expected: DVec3) {
    assert!(
        (d(got) - expected).abs().max_element() < 1e-5,
        "got {got}, expected {expected}"
    );
}

#[track_caller]
fn close1(got: f32, expected: f64) {
    assert!(
        (f64::from(got) - expected).abs() < 1e-5,
        "got {got}, expected {expected}"
    );
}

/// Where the ray `o + t d` first meets the sphere of centre `c` and radius `r` (`t > 0`).
fn sphere_t(o: DVec3, dir: DVec3, c: DVec3, r: f64) -> Option<f64> {
    // |o + t d - c|^2 = r^2: a t^2 + 2 b t + k = 0.
    let oc = o - c;
    let (a, b, k) = (dir.dot(dir), oc.dot(dir), oc.dot(oc) - r * r);
    let disc = b * b - a * k;
    (disc >= 0.0)
        .then(|| (-b - disc.sqrt()) / a)
        .filter(|&t| t > 0.0)
}

#[test]
fn a_lit_trace_has_the_lectures_numbers() {
    // fixtures/homework/lit_4x4.ron: the canonical camera, 4 x 4 pixels, a red sphere
    // (centre (0, 0, -3), radius 1, specular 0.5, shininess 20) on a ground y = -1
    // (grey 0.5, mirror 0.25), a point light at (2, 3, 0) of 10 and ambient 0.1.
    let scene = load(&fixtures().join("homework/lit_4x4.ron"));
    let view = View::of(&scene);
    let (red, grey) = (DVec3::new(0.8, 0.1, 0.1), DVec3::splat(0.5));
    let light = DVec3::new(2.0, 3.0, 0.0);
    let centre = DVec3::new(0.0, 0.0, -3.0);

    // Pixel (i, j) = (2, 3): u = ((3 - 1/2)/4 - 1/2) = 1/8, v = -((2 - 1/2)/4 - 1/2) = 1/8.
    let trace = trace_pixel(&scene, &view, &RenderSettings::default(), 1, 2).unwrap();
    let steps: Vec<&StepKind> = trace.steps.iter().map(|s| &s.kind).collect();
    let StepKind::ViewingRay { ray: Some(ray) } = steps[0] else {
        panic!("{:?}", steps[0]);
    };
    let dir = DVec3::new(0.125, 0.125, -1.0);
    assert_eq!((ray.origin, ray.direction), (DVec3::ZERO, dir));
    // Each object tested: the sphere at the quadratic's first root, the ground where
    // y = -1 (never: the ray goes up).
    let t = sphere_t(DVec3::ZERO, dir, centre, 1.0).unwrap();
    let StepKind::Test {
        object: 0,
        shape: Shape::Sphere,
        t: Some(sphere),
    } = *steps[1]
    else {
        panic!("{:?}", steps[1]);
    };
    close1(sphere, t);
    assert!(matches!(
        steps[2],
        StepKind::Test {
            object: 1,
            shape: Shape::Plane,
            t: None
        }
    ));
    let StepKind::Closest(hit) = steps[3] else {
        panic!("{:?}", steps[3]);
    };
    let p = dir * t;
    let n = (p - centre).normalize();
    close1(hit.t, t);
    close(hit.point, p);
    close(hit.normal, n);
    let StepKind::Surface(surface) = steps[4] else {
        panic!("{:?}", steps[4]);
    };
    let v = -dir.normalize();
    close(surface.view, v);
    close(surface.color, red);
    // The point light: l toward it, r^2, diffuse color n.l, specular 0.5 (n.h)^20 with
    // h = (l + v)/|l + v|, all times I / r^2.
    let StepKind::Light(terms) = steps[5] else {
        panic!("{:?}", steps[5]);
    };
    assert_eq!(terms.source, LightSource::Point(light.as_vec3()));
    let start = d(surface.origin);
    assert!((start - p).length() < 1e-3, "the shadow ray starts near p");
    let to_light = light - start;
    let l = to_light.normalize();
    close(terms.l, l);
    close1(terms.distance_squared, to_light.length_squared());
    let shadow = terms.shadow.unwrap();
    assert!(
        !shadow.blocked,
        "nothing lies between the sphere's top and the light"
    );
    close(shadow.ray.direction, to_light);
    let lit = terms.lit.unwrap();
    let n_dot_l = n.dot(l);
    close1(lit.blinn_phong.n_dot_l, n_dot_l);
    close(lit.blinn_phong.diffuse, red * n_dot_l);
    let h = (l + v).normalize();
    let specular = lit.blinn_phong.specular.unwrap();
    close(specular.h, h);
    close(specular.term, DVec3::splat(0.5 * n.dot(h).powf(20.0)));
    let scale = 10.0 / to_light.length_squared();
    let light_term = scale * (red * n_dot_l + DVec3::splat(0.5 * n.dot(h).powf(20.0)));
    close(lit.term, light_term);
    // The ambient light: color I, and the sum is the pixel's value.
    let StepKind::Ambient { term, color, .. } = *steps[6] else {
        panic!("{:?}", steps[6]);
    };
    close(term, red * 0.1);
    close(color, light_term + red * 0.1);
    assert_eq!(steps.len(), 7, "the sphere is no mirror");
    assert_eq!(color, trace.value);
    assert_eq!(trace.kind, PixelKind::Color);

    // Pixel (i, j) = (4, 2): down onto the ground, whose mirror reflects the ray up.
    let trace = trace_pixel(&scene, &view, &RenderSettings::default(), 3, 1).unwrap();
    let dir = DVec3::new(-0.125, -0.375, -1.0);
    let t = 1.0 / 0.375;
    let p = dir * t;
    let closest = trace.steps.iter().find_map(|s| match &s.kind {
        StepKind::Closest(hit) if s.bounce == 0 => Some(hit),
        _ => None,
    });
    let hit = closest.unwrap();
    assert_eq!(hit.shape, Shape::Plane);
    close1(hit.t, t);
    close(hit.point, p);
    // r = d - 2 (d.n) n with the unit d and n = (0, 1, 0): the y component flips.
    let unit = dir.normalize();
    let reflected = trace.steps.iter().find_map(|s| match s.kind {
        StepKind::Reflect {
            mirror,
            ray: Some(ray),
        } => Some((mirror, ray)),
        _ => None,
    });
    let (mirror, ray) = reflected.expect("the ground is a mirror");
    close1(mirror, 0.25);
    close(ray.direction, DVec3::new(unit.x, -unit.y, unit.z));
    // The mix: (1 - 0.25) local + 0.25 reflected is the pixel's value.
    let Some(StepKind::Mix {
        local,
        reflected,
        color,
        ..
    }) = trace.steps.last().map(|s| s.kind.clone())
    else {
        panic!("a mirror's trace ends with its mix");
    };
    close(color, 0.75 * d(local) + 0.25 * d(reflected));
    assert_eq!(color, trace.value);
    // The reflected ray's own steps are one bounce deeper, and its local colour starts
    // from the ground's grey.
    assert!(trace.steps.iter().any(|s| s.bounce == 1));
    let surface = trace.steps.iter().find_map(|s| match &s.kind {
        StepKind::Surface(surface) if s.bounce == 0 => Some(*surface),
        _ => None,
    });
    close(surface.unwrap().color, grey);
}

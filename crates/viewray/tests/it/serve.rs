//! `viewray serve` as a class uses it: the real binary on a free port, every endpoint
//! checked against what the command line prints or writes for the same camera.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use tempfile::TempDir;
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
use viewray_scene::{SceneLoader, camera_text, parse_camera};

use crate::support;
use support::http::{Served, get, request};
use support::{error_line, viewray};

const BINARY: &str = env!("CARGO_BIN_EXE_viewray");

fn fixtures() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures")
}

fn default_text() -> String {
    std::fs::read_to_string(fixtures().join("default.ron")).unwrap()
}

/// `value` URL-encoded for a query string.
fn encode(value: &str) -> String {
    value
        .bytes()
        .map(|b| match b {
            b'A'..=b'Z' | b'a'..=b'z' | b'0'..=b'9' | b'-' | b'_' | b'.' | b'~' => {
                (b as char).to_string()
            }
            _ => format!("%{b:02X}"),
        })
        .collect()
}

/// The scene file `text` with its camera replaced by `camera` and, if given, its shading.
fn with_camera(text: &str, camera: &str, shading: Option<&str>) -> String {
    let old = camera_text(text, Path::new("scene.ron")).unwrap();
    let start = old.as_ptr() as usize - text.as_ptr() as usize;
    let mut scene = format!("{}{camera}{}", &text[..start], &text[start + old.len()..]);
    if let Some(shading) = shading {
        scene = scene.replacen("shading: Lit", &format!("shading: {shading}"), 1);
    }
    scene
}

/// Runs `viewray args`, which must succeed; returns its standard output.
#[track_caller]
fn cli(args: &[&str]) -> String {
    let out = viewray(args);
    assert!(
        out.status.success(),
        "viewray {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    String::from_utf8(out.stdout).unwrap()
}

#[test]
fn the_first_line_is_the_url_on_loopback_and_the_page_is_served() {
    let served = Served::start(BINARY, &[]);
    assert!(
        served.url.starts_with("http://127.0.0.1:"),
        "{}",
        served.url
    );
    assert!(!served.url.ends_with(":0/"), "{}", served.url);
    let page = served.get("/");
    assert_eq!(page.status, 200);
    assert_eq!(
        page.header("content-type"),
        Some("text/html; charset=utf-8")
    );
    let html = page.text();
    // Everything inline: no script, style or image is fetched from anywhere.
    for outside in [
        "src=\"http",
        "href=\"http",
        "<script src",
        "<link rel=\"stylesheet\"",
    ] {
        assert!(!html.contains(outside), "the page loads {outside}");
    }
    assert!(html.contains("the default scene"));
    // The page starts from the served scene's camera, as its RON text.
    let camera = camera_text(&default_text(), Path::new("x"))
        .unwrap()
        .to_owned();
    let state_json = serde_json::to_string(&camera).unwrap();
    assert!(
        html.contains(&state_json),
        "the page's state holds the camera"
    );

    let scene = served.get("/api/scene");
    assert_eq!(scene.status, 200);
    assert_eq!(scene.text(), default_text());
}

#[test]
fn the_lecture_is_served_whole_with_its_steps_in_the_lectures_order() {
    let served = Served::start(BINARY, &[]);
    let page = served.get("/lecture");
    assert_eq!(page.status, 200);
    assert_eq!(
        page.header("content-type"),
        Some("text/html; charset=utf-8")
    );
    let html = page.text();
    for outside in [
        "src=\"http",
        "href=\"http",
        "<script src",
        "<link rel=\"stylesheet\"",
        "cdn",
    ] {
        assert!(!html.contains(outside), "the lecture loads {outside}");
    }
    // Formulas are MathML, typeset by the browser: the script writes <math> elements.
    assert!(html.contains("<math display=\"block\">"));
    // The first step follows its pixel through the served scene by its trace.
    assert!(html.contains("/api/trace?"));
    assert!(html.contains("hit = intersect(ray, scene)"));
    // The steps, in the lecture's order.
    let order = [
        "pseudocode",
        "canonical",
        "distance",
        "viewport",
        "eye",
        "rotated",
        "basis-${which}",
        "thin-lens",
        "taxonomy",
        "parallel",
        "shift",
        "foreshortening",
        "tilt-shift",
    ];
    let at: Vec<usize> = order
        .iter()
        .map(|id| {
            html.find(&format!("id: \"{id}\""))
                .or_else(|| html.find(&format!("id: `{id}`")))
                .unwrap_or_else(|| panic!("no step {id}"))
        })
        .collect();
    assert!(
        at.windows(2).all(|w| w[0] < w[1]),
        "steps out of order: {at:?}"
    );
    // The first step follows the served scene's camera.
    let camera = camera_text(&default_text(), Path::new("x"))
        .unwrap()
        .to_owned();
    assert!(html.contains(&serde_json::to_string(&camera).unwrap()));
}

#[test]
fn renders_are_pixel_for_pixel_what_viewray_render_writes() {
    let dir = TempDir::new().unwrap();
    let served = Served::start(BINARY, &[]);
    let text = default_text();
    let cases = [
        // The served camera at another size and sample count.
        (None, 96, 54, 2, None),
        (
            Some(
                "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.5, 0.0), projection: ThinLens(fov_y: 45.0, aperture: 0.08, focus: 5.0))",
            ),
            80,
            60,
            3,
            Some("Lit"),
        ),
        (
            Some("Cabinet(target: (0.0, 0.5, 0.0), size: 5.0, angle: 30.0)"),
            64,
            48,
            1,
            Some("Depth"),
        ),
        (
            Some("(eye: (0.0, 1.0, 3.0), view: (0.0, 0.0, -1.0), projection: Fisheye(fov: 200.0))"),
            50,
            50,
            1,
            Some("Normals"),
        ),
    ];
    for (k, (camera, width, height, samples, shading)) in cases.into_iter().enumerate() {
        let mut target = format!("/api/render?width={width}&height={height}&samples={samples}");
        if let Some(camera) = camera {
            target.push_str(&format!("&camera={}", encode(camera)));
        }
        if let Some(shading) = shading {
            target.push_str(&format!("&shading={shading}"));
        }
        let response = served.get(&target);
        assert_eq!(
            response.status,
            200,
            "{target}: {}",
            String::from_utf8_lossy(&response.body)
        );
        assert_eq!(response.header("content-type"), Some("image/png"));

        let scene_text = match camera {
            Some(camera) => with_camera(&text, camera, shading),
            None => text.clone(),
        };
        let scene = dir.path().join(format!("scene{k}.ron"));
        std::fs::write(&scene, scene_text).unwrap();
        let out = dir.path().join(format!("cli{k}.png"));
        cli(&[
            "render",
            scene.to_str().unwrap(),
            "-o",
            out.to_str().unwrap(),
            "--size",
            &format!("{width}x{height}"),
            "--samples",
            &samples.to_string(),
        ]);
        let expected = image::open(&out).unwrap().to_rgb8();
        let got = image::load_from_memory(&response.body).unwrap().to_rgb8();
        assert_eq!((got.width(), got.height()), (width, height));
        assert!(
            got == expected,
            "{target}: not the pixels viewray render writes"
        );
    }
}

#[test]
fn frames_rays_and_projections_are_the_command_lines_lines() {
    let dir = TempDir::new().unwrap();
    let served = Served::start(BINARY, &[]);
    let cameras = [
        "(eye: (1.0, 2.0, 3.0), look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), projection: Perspective(distance: 1.5, viewport: (1.2, 0.9), shift: (0.1, -0.2)))",
        "Isometric(target: (0.0, 0.5, 0.0), size: 4.0)",
        "(eye: (0.0, 2.0, 3.0), view: (0.0, -0.5, -1.0), projection: Oblique(height: 3.0, ratio: 0.5, angle: 30.0))",
        "(eye: (0.0, 1.0, 0.0), view: (0.0, 0.0, -1.0), projection: Equirectangular)",
    ];
    for (k, camera) in cameras.into_iter().enumerate() {
        let (width, height) = (7, 5);
        let scene = dir.path().join(format!("camera{k}.ron"));
        std::fs::write(
            &scene,
            format!("(image: (width: {width}, height: {height}), camera: {camera})"),
        )
        .unwrap();
        let scene = scene.to_str().unwrap();
        let query = format!("camera={}&width={width}&height={height}", encode(camera));

        let frame = served.get(&format!("/api/frame?{query}"));
        assert_eq!(frame.status, 200);
        assert_eq!(frame.header("content-type"), Some("application/json"));
        assert_eq!(frame.text(), cli(&["frame", scene]), "{camera}");

        for (row, col) in [(0, 0), (2, 3), (4, 6)] {
            let rays = served.get(&format!("/api/rays?{query}&row={row}&col={col}"));
            assert_eq!(rays.status, 200);
            assert_eq!(
                rays.text(),
                cli(&["rays", scene, "--pixel", &format!("{row},{col}")]),
                "{camera} ({row}, {col})"
            );
            let (i, j) = (row + 1, col + 1);
            let rays = served.get(&format!("/api/rays?{query}&i={i}&j={j}"));
            assert_eq!(
                rays.text(),
                cli(&["rays", scene, "--one-based", "--pixel", &format!("{i},{j}")]),
                "{camera} (i, j) = ({i}, {j})"
            );
        }

        let points = ["0,0,0", "1,0.5,-2", "-3,1,4"];
        let project_query: String = points.iter().map(|p| format!("&point={p}")).collect();
        let projected = served.get(&format!("/api/project?{query}{project_query}"));
        assert_eq!(projected.status, 200);
        let mut args = vec!["project", scene, "--point"];
        args.extend(points);
        assert_eq!(projected.text(), cli(&args), "{camera}");
    }
}

#[test]
fn a_clicked_pixels_trace_is_what_viewray_trace_prints() {
    let dir = TempDir::new().unwrap();
    let path = fixtures().join("homework/lit_4x4.ron");
    let served = Served::start(BINARY, &[path.to_str().unwrap()]);
    let text = std::fs::read_to_string(&path).unwrap();
    let cases = [
        // The served camera and shading.
        (None, None),
        (
            Some(
                "(eye: (0.5, 1.0, 2.0), look_at: (0.0, -0.5, -3.0), projection: Perspective(fov_y: 50.0))",
            ),
            Some("Depth"),
        ),
        (
            Some("Cabinet(target: (0.0, -0.5, -3.0), size: 5.0, angle: 30.0)"),
            Some("Normals"),
        ),
        (
            Some("(eye: (0.0, 0.0, 0.0), view: (0.0, 0.0, -1.0), projection: Fisheye(fov: 200.0))"),
            Some("Flat"),
        ),
    ];
    for (k, (camera, shading)) in cases.into_iter().enumerate() {
        let scene = dir.path().join(format!("traced{k}.ron"));
        let mut query = "width=4&height=4".to_owned();
        let file = match camera {
            Some(camera) => {
                query.push_str(&format!("&camera={}", encode(camera)));
                with_camera(&text, camera, shading)
            }
            None => text.clone(),
        };
        if let Some(shading) = shading {
            query.push_str(&format!("&shading={shading}"));
        }
        std::fs::write(&scene, file).unwrap();
        let scene = scene.to_str().unwrap();
        for (row, col) in [(0, 0), (1, 2), (3, 1), (3, 3)] {
            let pixel = format!("{row},{col}");
            let lines = served.get(&format!("/api/trace?{query}&row={row}&col={col}"));
            assert_eq!(lines.status, 200, "{}", lines.text());
            assert_eq!(lines.header("content-type"), Some("application/x-ndjson"));
            assert_eq!(
                lines.text(),
                cli(&["trace", scene, "--pixel", &pixel, "--json"]),
                "{camera:?} {shading:?} ({pixel})"
            );
            let (i, j) = (row + 1, col + 1);
            let one_based = served.get(&format!("/api/trace?{query}&i={i}&j={j}"));
            assert_eq!(
                one_based.text(),
                cli(&[
                    "trace",
                    scene,
                    "--pixel",
                    &format!("{i},{j}"),
                    "--one-based",
                    "--json"
                ]),
                "{camera:?} {shading:?} (i, j) = ({i}, {j})"
            );
            // The page's panel: the command line's text, which names the render in the
            // playground's words.
            let page = served.get(&format!(
                "/api/trace?{query}&row={row}&col={col}&format=text"
            ));
            assert_eq!(page.status, 200);
            assert_eq!(
                page.header("content-type"),
                Some("text/plain; charset=utf-8")
            );
            let printed = cli(&["trace", scene, "--pixel", &pixel]);
            assert!(printed.contains("as `viewray render --samples 1` writes it"));
            assert_eq!(
                page.text(),
                printed.replace("`viewray render --samples 1`", "a one-sample render"),
                "{camera:?} {shading:?} ({pixel})"
            );
        }
    }
    let check = |target: &str, expected: &str| {
        let response = served.get(target);
        assert_eq!(response.status, 400, "{target}: {}", response.text());
        let body: serde_json::Value = serde_json::from_slice(&response.body).unwrap();
        assert_eq!(body["error"], expected, "{target}");
    };
    check(
        "/api/trace?row=4&col=0",
        "row: pixel 4,0 is outside the 4 x 4 image: row runs 0..=3 and col 0..=3 (0-based; \
         i=I&j=J for the lecture's i, j)",
    );
    check(
        "/api/trace?i=0&j=1",
        "i: pixel 0,1 is outside the 4 x 4 image: i runs 1..=4 and j 1..=4 (1-based, the \
         lecture's i, j)",
    );
    check(
        "/api/trace",
        "row: missing: give the pixel as row=R&col=C (0-based from the top-left) or i=I&j=J \
         (the lecture's, 1-based)",
    );
    check(
        "/api/trace?row=0&col=0&format=pdf",
        "format: expected `json` (one line per step) or `text`, found `pdf`",
    );
    check(
        "/api/trace?row=0&col=0&width=100000&height=100000",
        "width: 100000 x 100000 is too large: each side can be at most 4096 pixels",
    );
}

#[test]
fn the_diagram_is_the_side_view_of_the_camera_over_the_served_scene() {
    let served = Served::start(BINARY, &[]);
    let text = default_text();
    let scene = SceneLoader::text(&text, Path::new("default.ron"))
        .load()
        .unwrap()
        .scene;
    let camera_ron =
        "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.5, 0.0), projection: Perspective(fov_y: 40.0))";
    let response = served.get(&format!(
        "/api/diagram.svg?camera={}&width=320&height=180&row=90&col=100",
        encode(camera_ron)
    ));
    assert_eq!(response.status, 200);
    assert_eq!(response.header("content-type"), Some("image/svg+xml"));
    let camera = parse_camera(camera_ron, Path::new("camera"), 320, 180).unwrap();
    let window = SideWindow::fit(&scene, &[camera]);
    let figure = side_view(
        &scene,
        &camera,
        &window,
        SideViewCanvas::Panel,
        Some((90, 100)),
    );
    let expected = viewray_draw::svg::document(&figure, viewray_draw::svg::SvgText::Paths);
    let got = response.text();
    if got != expected {
        let at = got
            .bytes()
            .zip(expected.bytes())
            .position(|(a, b)| a != b)
            .unwrap_or(got.len().min(expected.len()));
        let context = |s: &str| s[at.saturating_sub(80)..(at + 80).min(s.len())].to_owned();
        panic!(
            "not the library's side view at byte {at}:\n{}\n---\n{}",
            context(&got),
            context(&expected)
        );
    }
    roxmltree::Document::parse(&expected).unwrap();
}

#[test]
fn the_top_view_and_a_panel_of_any_shape_are_the_librarys() {
    let served = Served::start(BINARY, &[]);
    let scene = SceneLoader::text(&default_text(), Path::new("default.ron"))
        .load()
        .unwrap()
        .scene;
    let camera_ron =
        "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.5, 0.0), projection: Perspective(fov_y: 40.0))";
    let camera = parse_camera(camera_ron, Path::new("camera"), 320, 180).unwrap();
    let cases = [
        (
            "&view=top",
            SideWindow::fit_top(&scene, &[camera]),
            SideViewCanvas::Square,
        ),
        (
            "&canvas=1700x540",
            SideWindow::fit(&scene, &[camera]),
            SideViewCanvas::Fitted {
                width: 1700,
                height: 540,
            },
        ),
        (
            "&view=top&canvas=700x540",
            SideWindow::fit_top(&scene, &[camera]),
            SideViewCanvas::Fitted {
                width: 700,
                height: 540,
            },
        ),
    ];
    for (extra, window, canvas) in cases {
        let response = served.get(&format!(
            "/api/diagram.svg?camera={}&width=320&height=180&row=90&col=100{extra}",
            encode(camera_ron)
        ));
        assert_eq!(response.status, 200, "{extra}: {}", response.text());
        let figure = side_view(&scene, &camera, &window, canvas, Some((90, 100)));
        let expected = viewray_draw::svg::document(&figure, viewray_draw::svg::SvgText::Paths);
        assert!(
            response.text() == expected,
            "{extra}: not the library's view"
        );
    }
}

#[test]
fn the_depth_is_how_far_along_the_view_the_middle_of_the_picture_lies() {
    let served = Served::start(BINARY, &[]);
    let depth = |camera: &str| -> serde_json::Value {
        let response = served.get(&format!(
            "/api/depth?camera={}&width=64&height=48",
            encode(camera)
        ));
        assert_eq!(response.status, 200, "{camera}: {}", response.text());
        serde_json::from_slice(&response.body).unwrap()
    };
    // The default scene's cube spans [-0.6, 0.6] x [0, 1.2] x [-0.6, 0.6]: looking down -z
    // from z = 10 at its middle, the centre ray meets its front face 9.4 along the view,
    // whatever the length of `view`.
    for view in ["(0.0, 0.0, -1.0)", "(0.0, 0.0, -7.0)"] {
        let line = depth(&format!(
            "(eye: (0.0, 0.6, 10.0), view: {view}, projection: Perspective(fov_y: 30.0))"
        ));
        assert_eq!(line["from"], "hit");
        let d = line["depth"].as_f64().unwrap();
        assert!((d - 9.4).abs() < 1e-5, "{d}");
    }
    // From 50 above, looking down: the cube's top, 48.8 below.
    let line = depth(
        "(eye: (0.0, 50.0, 0.0), view: (0.0, -1.0, 0.0), up: (0.0, 0.0, -1.0), \
         projection: Orthographic(height: 4.0))",
    );
    assert!(
        (line["depth"].as_f64().unwrap() - 48.8).abs() < 1e-4,
        "{line}"
    );
    // A centre ray into the sky (the window shifted far up): the middle of the objects'
    // bounds, z from -1.2 (the gold sphere) to 3.0 (the white one), so 0.9: 9.1 away.
    let line = depth(
        "(eye: (0.0, 0.6, 10.0), view: (0.0, 0.0, -1.0), \
         projection: Perspective(fov_y: 30.0, shift: (0.0, 3.0)))",
    );
    assert_eq!(line["from"], "objects");
    assert!(
        (line["depth"].as_f64().unwrap() - 9.1).abs() < 1e-6,
        "{line}"
    );
    // Nothing in front: null.
    let line = depth(
        "(eye: (0.0, 0.6, 10.0), view: (0.0, 0.0, 1.0), projection: Perspective(fov_y: 30.0))",
    );
    assert_eq!(line, serde_json::json!({"depth": null, "from": null}));
}

#[test]
fn a_slide_is_a_1920_by_1080_png_of_the_camera() {
    let served = Served::start(BINARY, &[]);
    let camera =
        "(eye: (3.0, 2.0, 4.0), look_at: (0.0, 0.5, 0.0), projection: Perspective(fov_y: 40.0))";
    for extra in ["", "&row=10&col=20&top=1"] {
        let response = served.get(&format!(
            "/api/slide.png?camera={}&width=160&height=90&samples=1{extra}",
            encode(camera)
        ));
        assert_eq!(response.status, 200, "{extra}: {}", response.text());
        assert_eq!(response.header("content-type"), Some("image/png"));
        let image = image::load_from_memory(&response.body).unwrap();
        assert_eq!((image.width(), image.height()), (1920, 1080), "{extra}");
    }
    let check = |target: &str, expected: &str| {
        let response = served.get(target);
        assert_eq!(response.status, 400, "{target}: {}", response.text());
        let body: serde_json::Value = serde_json::from_slice(&response.body).unwrap();
        assert_eq!(body["error"], expected, "{target}");
    };
    check("/api/slide.png?top=2", "top: expected 0 or 1, found `2`");
    check(
        "/api/slide.png?row=480&col=0",
        "row: pixel 480,0 is outside the 640 x 480 image: row runs 0..=479 and col 0..=639 \
         (0-based)",
    );
    check(
        "/api/diagram.svg?view=front",
        "view: expected `side` or `top`, found `front`",
    );
    check(
        "/api/diagram.svg?canvas=100x100",
        "canvas: expected WIDTHxHEIGHT in pixels, each from 300 to 4000, found `100x100`",
    );
}

#[test]
fn a_scene_file_is_served_with_its_meshes() {
    let path = fixtures().join("scenes/mesh_houses.ron");
    let served = Served::start(BINARY, &[path.to_str().unwrap()]);
    assert_eq!(
        served.get("/api/scene").text(),
        std::fs::read_to_string(&path).unwrap()
    );
    let response = served.get("/api/render?width=48&height=36&samples=1");
    assert_eq!(response.status, 200);
    let dir = TempDir::new().unwrap();
    let out = dir.path().join("houses.png");
    cli(&[
        "render",
        path.to_str().unwrap(),
        "-o",
        out.to_str().unwrap(),
        "--size",
        "48x36",
        "--samples",
        "1",
    ]);
    let expected = image::open(&out).unwrap().to_rgb8();
    assert!(image::load_from_memory(&response.body).unwrap().to_rgb8() == expected);
}

#[test]
fn a_camera_with_the_catalogues_mistakes_makes_the_mistaken_rays() {
    let served = Served::start(BINARY, &[]);
    let (width, height) = (8, 6);
    let query = format!("width={width}&height={height}");
    let direction = |target: &str| -> [f64; 3] {
        let response = served.get(target);
        assert_eq!(response.status, 200, "{target}: {}", response.text());
        let line: serde_json::Value = serde_json::from_slice(&response.body).unwrap();
        let d = &line["direction"];
        [0, 1, 2].map(|k| d[k].as_f64().unwrap())
    };
    let close = |a: [f64; 3], b: [f64; 3]| a.iter().zip(b).all(|(x, y)| (x - y).abs() < 1e-12);
    let u = |target: &str| -> f64 {
        let line: serde_json::Value = serde_json::from_slice(&served.get(target).body).unwrap();
        line["u"].as_f64().unwrap()
    };
    for (row, col) in [(0, 0), (2, 5), (5, 7)] {
        // The line prints the mistaken camera's own u: the mirrored column's.
        let mirrored_u = u(&format!(
            "/api/rays?{query}&row={row}&col={}",
            width - 1 - col
        ));
        let u_sign_u = u(&format!(
            "/api/rays?{query}&row={row}&col={col}&mistakes=u-sign"
        ));
        assert!(
            (u_sign_u - mirrored_u).abs() < 1e-12,
            "({row}, {col}): u {u_sign_u} {mirrored_u}"
        );
        // u-sign: u = -((x/W - 1/2) vw), the u of the column mirrored about the middle.
        let mirrored = direction(&format!(
            "/api/rays?{query}&row={row}&col={}",
            width - 1 - col
        ));
        let u_sign = direction(&format!(
            "/api/rays?{query}&row={row}&col={col}&mistakes=u-sign"
        ));
        assert!(
            close(u_sign, mirrored),
            "({row}, {col}): {u_sign:?} {mirrored:?}"
        );
        // v-sign as well: the row mirrored too; an empty entry in the list is none.
        let both = direction(&format!(
            "/api/rays?{query}&row={row}&col={col}&mistakes=u-sign,,v-sign"
        ));
        let opposite = direction(&format!(
            "/api/rays?{query}&row={}&col={}",
            height - 1 - row,
            width - 1 - col
        ));
        assert!(
            close(both, opposite),
            "({row}, {col}): {both:?} {opposite:?}"
        );
    }
    // No mistakes is the right camera, to the byte.
    assert_eq!(
        served.get(&format!("/api/frame?{query}&mistakes=")).text(),
        served.get(&format!("/api/frame?{query}")).text()
    );
    // A mistaken render differs from the right one.
    let right = served.get(&format!("/api/render?{query}&samples=1"));
    let mirrored = served.get(&format!("/api/render?{query}&samples=1&mistakes=u-sign"));
    assert_eq!(mirrored.status, 200);
    assert_ne!(right.body, mirrored.body);
}

/// The `renders` counts of `/api/status`: running, waiting, rendered, superseded, busy.
fn render_counts(address: &str) -> [u64; 5] {
    let status = get(address, "/api/status").expect("answered");
    assert_eq!(status.status, 200, "{}", status.text());
    let status: serde_json::Value = serde_json::from_slice(&status.body).unwrap();
    ["running", "waiting", "rendered", "superseded", "busy"]
        .map(|key| status["renders"][key].as_u64().expect(key))
}

#[test]
fn a_render_superseded_by_its_ticket_stops_and_frees_its_slot() {
    // One render slot, a long wait for it, and limits that let a render run for hours:
    // only the newer render's ticket can end the first.
    let text = default_text();
    let path = fixtures().join("default.ron");
    let served = viewray_serve::ServedScene::parse("default.ron", text, &path).unwrap();
    let options = viewray_serve::ServeOptions {
        limits: viewray_serve::Limits {
            max_frame_samples: u64::MAX,
            ..viewray_serve::Limits::default()
        },
        render_slots: 1,
        slot_wait: Duration::from_secs(600),
        ..viewray_serve::ServeOptions::default()
    };
    let server = viewray_serve::Server::bind(served, "127.0.0.1:0", options).unwrap();
    let address = server.address().to_string();
    let stopper = server.stopper();
    let running = std::thread::spawn(move || server.run());

    // 2048 x 2048 at 1024 samples a pixel, through a thin lens: 4 G samples.
    let lens = encode(
        "(eye: (0.0, 1.5, 5.0), look_at: (0.0, 0.5, 0.0), \
         projection: ThinLens(fov_y: 40.0, aperture: 0.2, focus: 5.0))",
    );
    let slow = format!(
        "/api/render?camera={lens}&width=2048&height=2048&samples=1024&ticket=page-1-render.1"
    );
    let first = {
        let address = address.clone();
        std::thread::spawn(move || get(&address, &slow).expect("answered"))
    };
    // Once it holds the slot, the same view asks for its next picture.
    while render_counts(&address)[0] == 0 {
        std::thread::sleep(Duration::from_millis(10));
    }
    let next = get(
        &address,
        &format!("/api/render?camera={lens}&width=32&height=18&samples=1&ticket=page-1-render.2"),
    )
    .unwrap();
    assert_eq!(next.status, 200, "{}", next.text());
    let first = first.join().unwrap();
    assert_eq!(first.status, 409, "{}", first.text());
    assert_eq!(
        serde_json::from_slice::<serde_json::Value>(&first.body).unwrap()["error"],
        "ticket: superseded by a newer render with the same ticket"
    );
    // Running, waiting, rendered, superseded, busy.
    assert_eq!(render_counts(&address), [0, 0, 1, 1, 0]);

    // Another ticket does not stop it: two views of one page, or two pages.
    let other = get(
        &address,
        "/api/render?width=32&height=18&samples=1&ticket=page-2-render.7",
    )
    .unwrap();
    assert_eq!(other.status, 200);
    assert_eq!(render_counts(&address), [0, 0, 2, 1, 0]);
    for bad in ["a%20b.1", "page", "page.x", ".1"] {
        let reply = get(&address, &format!("/api/render?ticket={bad}")).unwrap();
        assert_eq!(reply.status, 400);
        let error = serde_json::from_slice::<serde_json::Value>(&reply.body).unwrap();
        assert!(
            error["error"]
                .as_str()
                .unwrap()
                .starts_with("ticket: expected NAME.TURN"),
            "{bad}: {error}"
        );
    }
    stopper.stop();
    running.join().unwrap().unwrap();
}

#[test]
fn bad_requests_are_refused_with_the_command_lines_words() {
    let served = Served::start(BINARY, &[]);
    let check = |target: &str, status: u16, expected: &str| {
        let response = served.get(target);
        assert_eq!(response.status, status, "{target}: {}", response.text());
        let body: serde_json::Value = serde_json::from_slice(&response.body).unwrap();
        assert_eq!(body["error"], expected, "{target}");
    };
    // Far too large: refused before anything is allocated (120 GB would not be).
    check(
        "/api/render?width=100000&height=100000",
        400,
        "width: 100000 x 100000 is too large: each side can be at most 4096 pixels",
    );
    check(
        "/api/render?width=0",
        400,
        "width: the image must be at least 1 x 1 pixels, found 0 x 480",
    );
    check(
        "/api/render?samples=0",
        400,
        "samples: expected a whole number of samples from 1 to 1024",
    );
    check(
        "/api/render?width=2048&height=2048&samples=1024",
        400,
        "samples: 2048 x 2048 at 1024 samples per pixel is too much for one frame: at most \
         67108864 samples in all (pixels x samples)",
    );
    check(
        "/api/render?shading=Shiny",
        400,
        "shading: unknown shading `Shiny`, expected one of `Flat`, `Normals`, `Depth` or `Lit`",
    );
    check(
        "/api/render?zoom=2",
        400,
        "unknown parameter `zoom`: this endpoint takes `camera`, `width`, `height`, `samples`, \
         `shading`, `mistakes` or `ticket`",
    );
    check(
        "/api/rays?row=0&col=0&mistakes=u-sign,left",
        400,
        "mistakes: no mistake `left` in the catalogue (it has pixel-corner, pixel-one-based, \
         size-minus-one, v-sign, u-sign, i-j-swapped, viewport-missing, viewport-swapped, \
         distance-missing, distance-sign, eye-missing, basis-missing, w-view, u-cross-order, \
         v-cross-order, u-not-normalized, shift-sign, shift-missing, ortho-origin-fixed, \
         ortho-as-perspective, oblique-sign, oblique-as-ortho)",
    );
    check(
        "/api/rays?row=480&col=0",
        400,
        "row: pixel 480,0 is outside the 640 x 480 image: row runs 0..=479 and col 0..=639 \
         (0-based; i=I&j=J for the lecture's i, j)",
    );
    // The side view takes row and col only: the sentence offers no other indices.
    check(
        "/api/diagram.svg?row=0&col=640",
        400,
        "row: pixel 0,640 is outside the 640 x 480 image: row runs 0..=479 and col 0..=639 \
         (0-based)",
    );
    check(
        "/api/project?point=1,2",
        400,
        "point: expected 3 numbers separated by commas, like 0,1.5,-2",
    );

    // A camera error is the one the command line gives for the same camera in a file,
    // placed in the camera's own text.
    let camera =
        "(eye: (0.0, 1.0, 2.0), look_at: (0.0, 1.0, 2.0), projection: Perspective(fov_y: 40.0))";
    let response = served.get(&format!("/api/render?camera={}", encode(camera)));
    assert_eq!(response.status, 400);
    let body: serde_json::Value = serde_json::from_slice(&response.body).unwrap();
    let server_error = body["error"].as_str().unwrap();
    let dir = TempDir::new().unwrap();
    let scene = dir.path().join("bad.ron");
    std::fs::write(&scene, format!("(camera: {camera})")).unwrap();
    let cli_error = error_line(&["render", scene.to_str().unwrap(), "-o", "x.png"]);
    // What follows the first `:LINE:COLUMN: `.
    let message = |line: &str| -> String {
        let parts: Vec<&str> = line.split(':').collect();
        let k = (1..parts.len() - 1)
            .find(|&k| {
                [parts[k], parts[k + 1]]
                    .iter()
                    .all(|p| !p.is_empty() && p.chars().all(|c| c.is_ascii_digit()))
            })
            .expect("a line and column");
        parts[k + 2..].join(":").trim().to_owned()
    };
    assert!(server_error.starts_with("camera:1:1: "), "{server_error}");
    assert_eq!(message(server_error), message(&cli_error));

    // Unknown paths, other methods, and no way out to the file system.
    for target in [
        "/nope",
        "/index.html",
        "/../../etc/passwd",
        "/api/scene/../../../etc/passwd",
        "/%2e%2e/etc/passwd",
    ] {
        let response = served.get(target);
        assert_eq!(response.status, 404, "{target}");
        assert!(!response.text().contains("root:"), "{target}");
    }
    let post = request(&served.address, "POST", "/api/render").unwrap();
    assert_eq!(post.status, 405);
    assert_eq!(post.header("allow"), Some("GET, HEAD"));
    let head = request(&served.address, "HEAD", "/api/scene").unwrap();
    assert_eq!(head.status, 200);
    assert!(head.body.is_empty());
}

/// The number of threads of process `pid` (Linux).
fn threads(pid: u32) -> Option<usize> {
    let status = std::fs::read_to_string(format!("/proc/{pid}/status")).ok()?;
    let line = status.lines().find(|l| l.starts_with("Threads:"))?;
    line.split_whitespace().nth(1)?.parse().ok()
}

/// Thirty laptops, each asking for four renders and four rays at once; returns the
/// numbers answered (200) and told to retry (503). Any other answer fails.
fn class_of_laptops(address: &str) -> (usize, usize) {
    let (mut answered, mut busy) = (0, 0);
    std::thread::scope(|scope| {
        let laptops: Vec<_> = (0..30)
            .map(|laptop| {
                scope.spawn(move || {
                    let mut statuses = Vec::new();
                    for k in 0..4 {
                        let camera = format!(
                            "(eye: ({}, 1.5, 5.0), look_at: (0.0, 0.5, 0.0), \
                             projection: Perspective(fov_y: 40.0))",
                            f64::from(k) * 0.5
                        );
                        let target = format!(
                            "/api/render?width={}&height=90&samples=1&camera={}",
                            120 + laptop,
                            encode(&camera)
                        );
                        statuses.push(get(address, &target).expect("answered").status);
                        let rays = get(address, "/api/rays?row=1&col=2").expect("answered");
                        statuses.push(rays.status);
                    }
                    statuses
                })
            })
            .collect();
        for laptop in laptops {
            for status in laptop.join().unwrap() {
                match status {
                    200 => answered += 1,
                    503 => busy += 1,
                    other => panic!("status {other}"),
                }
            }
        }
    });
    (answered, busy)
}

/// The most threads a server with the default 16 workers keeps once it is idle: the
/// blocking pool's 16 (each ends seconds after its last request), the runtime's one
/// worker (which also watches the connections: an idle one holds no thread), main, the
/// Ctrl-C handler, and rayon's pool (one thread a core). A leak (a thread a request or a
/// connection) passes this after one class of 240 requests.
fn idle_thread_bound() -> usize {
    let cores = std::thread::available_parallelism().map_or(1, usize::from);
    let cores = std::env::var("RAYON_NUM_THREADS")
        .ok()
        .and_then(|n| n.parse().ok())
        .filter(|&n| n > 0)
        .unwrap_or(cores);
    16 + 3 + cores
}

/// Waits (up to 90 s: idle connection threads end seconds after their last request,
/// later on a busy machine) for the threads of process `pid` to fall to `bound`; returns
/// the last count seen.
fn threads_falling_to(pid: u32, bound: usize) -> Option<usize> {
    let deadline = Instant::now() + Duration::from_secs(90);
    let mut now = threads(pid)?;
    while now > bound && Instant::now() < deadline {
        std::thread::sleep(Duration::from_millis(250));
        now = threads(pid)?;
    }
    Some(now)
}

#[test]
fn a_class_of_laptops_is_answered_or_told_to_retry_and_nothing_leaks() {
    let served = Served::start(BINARY, &[]);
    let pid = served.child.id();
    let bound = idle_thread_bound();
    // Two classes, each of 240 requests: every request is answered (200) or told to
    // retry (503); how many of each depends on how busy the machine is, so only "some
    // were answered" is asserted of the split. After each, the server falls back to its
    // idle threads (where /proc lets us count them).
    for class in ["one class", "two classes"] {
        let (answered, busy) = class_of_laptops(&served.address);
        assert!(
            answered > 0 && answered + busy == 240,
            "{class}: {answered} answered, {busy} busy"
        );
        if let Some(threads) = threads_falling_to(pid, bound) {
            assert!(
                threads <= bound,
                "{threads} threads after {class}, at most {bound} when idle"
            );
        }
    }
    assert_eq!(served.get("/api/render?width=32&height=18").status, 200);
}

#[cfg(unix)]
#[test]
fn ctrl_c_stops_the_server_cleanly() {
    let mut served = Served::start(BINARY, &[]);
    assert_eq!(served.get("/api/frame").status, 200);
    let pid = served.child.id().to_string();
    let status = std::process::Command::new("kill")
        .args(["-INT", &pid])
        .status()
        .unwrap();
    assert!(status.success());
    let deadline = Instant::now() + Duration::from_secs(20);
    let exit = loop {
        if let Some(exit) = served.child.try_wait().unwrap() {
            break exit;
        }
        assert!(Instant::now() < deadline, "still running after Ctrl-C");
        std::thread::sleep(Duration::from_millis(50));
    };
    assert_eq!(exit.code(), Some(0));
    assert!(get(&served.address, "/").is_err(), "still listening");
}

#[test]
fn serve_refuses_a_bad_scene_and_a_port_in_use_with_one_line() {
    let dir = TempDir::new().unwrap();
    let missing = dir.path().join("missing.ron");
    let line = error_line(&["serve", missing.to_str().unwrap(), "--port", "0"]);
    assert!(line.ends_with("missing.ron: no such scene file"), "{line}");
    let served = Served::start(BINARY, &[]);
    let port = served.address.rsplit(':').next().unwrap().to_owned();
    let line = error_line(&["serve", "--port", &port]);
    assert!(
        line.starts_with(&format!("error: cannot listen on 127.0.0.1:{port}: ")),
        "{line}"
    );
}

#[test]
fn connections_that_arrive_together_and_stay_open_are_all_answered() {
    // A browser keeps its connections open after each request and opens several at once
    // (a page's render, views, numbers and trace). Every one must be answered, however
    // many stay open idle: none may wait for another to close.
    use std::io::{Read as _, Write as _};

    let text = default_text();
    let path = fixtures().join("default.ron");
    let served = viewray_serve::ServedScene::parse("default.ron", text, &path).unwrap();
    let server = viewray_serve::Server::bind(
        served,
        "127.0.0.1:0",
        viewray_serve::ServeOptions::default(),
    )
    .unwrap();
    let address = server.address().to_string();
    let stopper = server.stopper();
    let running = std::thread::spawn(move || server.run());

    const CONNECTIONS: usize = 48;
    let start = std::sync::Arc::new(std::sync::Barrier::new(CONNECTIONS));
    let (answered, answers) = std::sync::mpsc::channel();
    let mut kept = Vec::new();
    for _ in 0..CONNECTIONS {
        let (address, start, answered) = (address.clone(), start.clone(), answered.clone());
        kept.push(std::thread::spawn(move || {
            let mut stream = std::net::TcpStream::connect(&address).unwrap();
            // Long enough never to fire on a server that answers; a hung request fails.
            stream
                .set_read_timeout(Some(Duration::from_secs(60)))
                .unwrap();
            start.wait();
            write!(
                stream,
                "GET /api/status HTTP/1.1\r\nHost: {address}\r\nConnection: keep-alive\r\n\r\n"
            )
            .unwrap();
            let mut head = [0_u8; 12];
            let read = stream.read_exact(&mut head);
            answered.send(read.is_ok()).unwrap();
            // Kept open, idle, until every connection has had its answer.
            stream
        }));
    }
    drop(answered);
    let answers: Vec<bool> = answers.iter().collect();
    let unanswered = answers.iter().filter(|&&ok| !ok).count();
    assert_eq!(
        unanswered, 0,
        "{unanswered} of {CONNECTIONS} requests unanswered"
    );
    drop(
        kept.into_iter()
            .map(|t| t.join().unwrap())
            .collect::<Vec<_>>(),
    );
    stopper.stop();
    running.join().unwrap().unwrap();
}

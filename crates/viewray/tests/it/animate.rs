//! `viewray animate` through the real binary: the demos listed, each output format
//! written whole and looping, the same bytes every time, and bad input refused with one
//! line and nothing written.

use std::path::{Path, PathBuf};

use crate::support;
use support::{error_line, error_line_in, repository, viewray, viewray_in};

fn files_in(dir: &Path) -> Vec<String> {
    let mut names: Vec<String> = std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    names
}

/// A small, quick demo: 4 frames of 64 x 36, 1 sample.
fn small(demo: &str, output: &Path) -> Vec<String> {
    [
        "animate",
        "--demo",
        demo,
        "--frames",
        "4",
        "--size",
        "64x36",
        "--samples",
        "1",
        "-o",
        output.to_str().unwrap(),
    ]
    .map(str::to_owned)
    .to_vec()
}

fn run(args: &[String]) -> std::process::Output {
    let args: Vec<&str> = args.iter().map(String::as_str).collect();
    let out = viewray(&args);
    assert!(
        out.status.success(),
        "viewray {args:?}: {}",
        String::from_utf8_lossy(&out.stderr)
    );
    out
}

#[test]
fn list_names_every_demo_on_one_line_each() {
    let out = viewray(&["animate", "--list"]);
    assert!(out.status.success());
    let text = String::from_utf8(out.stdout).unwrap();
    let names: Vec<&str> = text
        .lines()
        .map(|line| line.split_whitespace().next().unwrap())
        .collect();
    assert_eq!(
        names,
        [
            "dolly-zoom",
            "fov",
            "perspective-to-orthographic",
            "tilt-vs-shift",
            "aperture",
            "focus-pull",
            "lens-tilt",
            "bokeh",
            "oblique-angle"
        ]
    );
    assert!(text.lines().all(|line| line.split_whitespace().count() > 4));
}

/// The frames of a GIF, with their delays (hundredths) and the loop count.
fn gif_frames(bytes: &[u8]) -> (Vec<(u16, Vec<u8>)>, Option<gif::Repeat>) {
    let mut options = gif::DecodeOptions::new();
    options.set_color_output(gif::ColorOutput::RGBA);
    let mut decoder = options.read_info(bytes).unwrap();
    let mut frames = Vec::new();
    while let Some(frame) = decoder.read_next_frame().unwrap() {
        frames.push((frame.delay, frame.buffer.to_vec()));
    }
    (frames, Some(decoder.repeat()))
}

#[test]
fn a_gif_loops_over_every_frame_and_is_the_same_every_time() {
    let dir = tempfile::tempdir().unwrap();
    let gif_path = dir.path().join("oblique.gif");
    run(&small("oblique-angle", &gif_path));
    let bytes = std::fs::read(&gif_path).unwrap();
    assert_eq!(&bytes[..6], b"GIF89a");
    let (frames, repeat) = gif_frames(&bytes);
    assert_eq!(frames.len(), 4);
    assert_eq!(repeat, Some(gif::Repeat::Infinite));
    // 24 fps: 4, 4, 5, 4 hundredths (100 k / 24 rounded, differenced).
    let delays: Vec<u16> = frames.iter().map(|(d, _)| *d).collect();
    assert_eq!(delays, [4, 4, 5, 4]);
    assert_ne!(frames[0].1, frames[1].1, "the cube turns");
    assert_eq!(files_in(dir.path()), ["oblique.gif"]);
    // Again: the same bytes.
    run(&small("oblique-angle", &gif_path));
    assert_eq!(std::fs::read(&gif_path).unwrap(), bytes);
}

#[test]
fn an_animated_png_holds_every_frame_losslessly() {
    use image::AnimationDecoder as _;
    let dir = tempfile::tempdir().unwrap();
    let apng = dir.path().join("fov.png");
    let mut args = small("fov", &apng);
    args.extend(["--fps".to_owned(), "12".to_owned()]);
    run(&args);
    let decoder = image::codecs::png::PngDecoder::new(std::io::BufReader::new(
        std::fs::File::open(&apng).unwrap(),
    ))
    .unwrap();
    let frames = decoder
        .apng()
        .unwrap()
        .into_frames()
        .collect_frames()
        .unwrap();
    assert_eq!(frames.len(), 4);
    for frame in &frames {
        assert_eq!(frame.buffer().dimensions(), (64, 36));
        let (numer, denom) = frame.delay().numer_denom_ms();
        assert_eq!(numer * 12, denom * 1000, "1/12 s a frame");
    }
    // The frames are the ones a folder gets, pixel for pixel.
    let folder = dir.path().join("frames");
    run(&small(
        "fov",
        &PathBuf::from(format!("{}/", folder.display())),
    ));
    assert_eq!(
        files_in(&folder),
        [
            "frame_0000.png",
            "frame_0001.png",
            "frame_0002.png",
            "frame_0003.png"
        ]
    );
    for (k, frame) in frames.iter().enumerate() {
        let png = image::open(folder.join(format!("frame_{k:04}.png"))).unwrap();
        assert_eq!(png.to_rgba8(), *frame.buffer(), "frame {k}");
    }
}

#[test]
fn a_folder_is_replaced_whole_keeping_other_files() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("frames");
    std::fs::create_dir(&folder).unwrap();
    std::fs::write(folder.join("notes.txt"), "mine").unwrap();
    std::fs::write(folder.join("frame_0007.png"), "an older, longer animation").unwrap();
    // An existing folder needs no trailing slash.
    run(&small("aperture", &folder));
    assert_eq!(
        files_in(&folder),
        [
            "frame_0000.png",
            "frame_0001.png",
            "frame_0002.png",
            "frame_0003.png",
            "notes.txt"
        ]
    );
    assert_eq!(files_in(dir.path()), ["frames"], "no temporary folder left");
}

#[test]
fn with_diagram_puts_a_side_view_beside_each_picture() {
    let dir = tempfile::tempdir().unwrap();
    let folder = dir.path().join("tilt");
    let mut args = small(
        "tilt-vs-shift",
        &PathBuf::from(format!("{}/", folder.display())),
    );
    args.extend(["--with-diagram".to_owned(), "--stats".to_owned()]);
    args[4] = "2".to_owned();
    args[6] = "90x54".to_owned();
    let out = run(&args);
    // Two pictures of 90 x 54, each with a 96 x 54 side view.
    let frame = image::open(folder.join("frame_0000.png")).unwrap();
    assert_eq!((frame.width(), frame.height()), (2 * (90 + 96), 54));
    let stats: serde_json::Value = serde_json::from_slice(&out.stdout).unwrap();
    assert_eq!(stats["frames"], 2);
    assert_eq!(stats["width"], 372);
    assert!(stats["render_s"].as_f64().unwrap() > 0.0);
    assert!(stats["encode_s"].as_f64().unwrap() >= 0.0);
}

#[test]
fn a_scene_files_animation_is_animated() {
    let root = repository();
    let dir = tempfile::tempdir().unwrap();
    let gif_path = dir.path().join("focus.gif");
    let out = viewray_in(
        &root,
        &[
            "animate",
            "fixtures/animations/focus_pull.ron",
            "--frames",
            "3",
            "--size",
            "48x27",
            "--samples",
            "2",
            "-o",
            gif_path.to_str().unwrap(),
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    assert_eq!(gif_frames(&std::fs::read(&gif_path).unwrap()).0.len(), 3);
}

#[test]
fn bad_animations_and_settings_are_one_line_and_write_nothing() {
    let root = repository();
    let dir = tempfile::tempdir().unwrap();
    let out = |name: &str| dir.path().join(name).to_str().unwrap().to_owned();
    let mut bad: Vec<PathBuf> = std::fs::read_dir(root.join("fixtures/bad"))
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| {
            p.file_name()
                .unwrap()
                .to_string_lossy()
                .starts_with("animation_")
        })
        .collect();
    bad.sort();
    assert!(bad.len() >= 8);
    let mut lines = Vec::new();
    for scene in &bad {
        let relative = scene.strip_prefix(&root).unwrap().to_str().unwrap();
        lines.push(error_line_in(
            &root,
            &["animate", relative, "-o", &out("a.gif")],
        ));
    }
    for args in [
        vec![
            "animate",
            "fixtures/scenes/orthographic.ron",
            "-o",
            &out("b.gif"),
        ],
        vec![
            "animate",
            "--demo",
            "fov",
            "--frames",
            "0",
            "-o",
            &out("c.gif"),
        ],
        vec![
            "animate",
            "--demo",
            "fov",
            "--frames",
            "20000",
            "-o",
            &out("c.gif"),
        ],
        vec!["animate", "--demo", "fov", "-o", &out("d.mp4")],
        vec![
            "animate",
            "--demo",
            "dolly-zoom",
            "--size",
            "4096x4096",
            "--with-diagram",
            "-o",
            &out("e.gif"),
        ],
        vec!["animate", "--demo", "zoom", "-o", &out("f.gif")],
        vec!["animate", "-o", &out("g.gif")],
    ] {
        lines.push(error_line_in(&root, &args));
    }
    assert_eq!(
        files_in(dir.path()),
        Vec::<String>::new(),
        "nothing written"
    );
    let report = lines
        .join("\n")
        .replace(&format!("{}/", dir.path().display()), "");
    insta::assert_snapshot!(report);
    // The still commands refuse a bad animation too: the scene is not valid.
    assert!(
        error_line(&["render", bad[0].to_str().unwrap(), "-o", &out("h.png")])
            .contains("animation")
    );
}

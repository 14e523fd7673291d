//! The planted matrix of the camera-first judgement, through `viewray grade` and `viewray
//! compare`: a class of students whose pictures the independent student ray tracer
//! (`support/student`, its own camera, shading and gamma, PPM files) rendered, one image
//! per camera family and size, judged against the course's reference renders with the
//! scenes.
//!
//! - Every right camera passes, whatever its appearance (brighter, darker, gamma missing
//!   or twice, another light, no shadows, 1 to 64 samples), and its appearance is named.
//! - Every catalogue entry that changes the picture of a camera is named on it (with the
//!   entries that make the same picture); an entry that does not change it passes.
//! - A moved eye is named as such.
//!
//! The test asserts every cell and prints the matrix, with how many cells are right.

use crate::support;

use std::collections::BTreeMap;
use std::path::Path;

use support::student::{
    Aim, CameraSpec, Format, Gamma, LightChange, Mistake, Projection, RenderOptions, Scene, Vec3,
    render,
};
use support::viewray;
use viewray_judge::PictureJudge;

fn v(x: f64, y: f64, z: f64) -> Vec3 {
    Vec3::new(x, y, z)
}

fn s(path: &Path) -> &str {
    path.to_str().unwrap()
}

/// The camera families, each with its image size: the reference images' stems.
fn cameras() -> Vec<(&'static str, CameraSpec, (u32, u32))> {
    let look = |eye, at, projection| CameraSpec {
        eye,
        aim: Aim::LookAt(at),
        up: Vec3::Y,
        projection,
    };
    vec![
        (
            "canonical",
            CameraSpec {
                eye: v(0.3, 0.8, 6.0),
                aim: Aim::View(v(0.0, 0.0, -1.0)),
                up: Vec3::Y,
                projection: Projection::Perspective {
                    d: 1.0,
                    viewport: (0.6, 0.6),
                    shift: (0.0, 0.0),
                },
            },
            (120, 120),
        ),
        (
            "general",
            look(
                v(0.35, 2.0, 6.0),
                v(0.27, 0.5, 0.0),
                Projection::Perspective {
                    d: 1.5,
                    viewport: (1.2, 0.9),
                    shift: (0.0, 0.0),
                },
            ),
            (160, 120),
        ),
        (
            "wide",
            look(
                v(-0.4, 1.4, 7.0),
                v(0.3, 0.6, 0.0),
                Projection::Perspective {
                    d: 2.0,
                    viewport: (2.4, 1.2),
                    shift: (0.0, 0.0),
                },
            ),
            (200, 100),
        ),
        (
            "shifted",
            look(
                v(0.3, 1.0, 6.0),
                v(0.3, 1.0, 0.0),
                Projection::Perspective {
                    d: 1.0,
                    viewport: (0.8, 0.6),
                    shift: (0.0, -0.15),
                },
            ),
            (160, 120),
        ),
        (
            "ortho",
            look(
                v(2.0, 3.0, 6.0),
                v(0.3, 0.5, 0.0),
                Projection::Orthographic {
                    viewport: (5.0, 3.75),
                },
            ),
            (160, 120),
        ),
        (
            "oblique",
            look(
                v(0.3, 0.8, 6.0),
                v(0.3, 0.8, 0.0),
                Projection::Oblique {
                    viewport: (5.0, 3.75),
                    ratio: 0.5,
                    angle_degrees: 30.0,
                },
            ),
            (160, 120),
        ),
    ]
}

/// A right camera's appearance differences: the student's name, how they render, and the
/// appearances the judgement may name (the sample counts: `same` or `noise`).
fn appearances() -> Vec<(&'static str, RenderOptions, &'static [&'static str])> {
    let plain = RenderOptions::default();
    vec![
        ("right-plain", plain, names(&["same", "noise"])),
        (
            "right-brighter",
            RenderOptions {
                ambient: 0.35,
                light_scale: 1.6,
                ..plain
            },
            names(&["brighter"]),
        ),
        (
            "right-darker",
            RenderOptions {
                light_scale: 0.45,
                ambient: 0.04,
                ..plain
            },
            names(&["darker"]),
        ),
        (
            "right-gamma-missing",
            RenderOptions {
                gamma: Gamma::Linear,
                ..plain
            },
            names(&["gamma-missing"]),
        ),
        (
            "right-gamma-twice",
            RenderOptions {
                gamma: Gamma::Twice,
                ..plain
            },
            names(&["gamma-twice"]),
        ),
        (
            "right-moved-light",
            RenderOptions {
                light_change: Some(LightChange::Moved(v(3.0, 0.0, -4.0))),
                ..plain
            },
            names(&["shading"]),
        ),
        (
            "right-no-shadows",
            RenderOptions {
                shadows: false,
                phong: false,
                ..plain
            },
            names(&["shading", "brighter"]),
        ),
        (
            "right-64-samples",
            RenderOptions {
                samples: 64,
                ..plain
            },
            names(&["same", "noise"]),
        ),
    ]
}

/// The appearances a cell may name.
fn names(names: &'static [&'static str]) -> &'static [&'static str] {
    names
}

/// What a cell must say.
#[derive(Clone, Debug)]
enum Want {
    /// The camera is right, and the appearance one of these.
    Right(&'static [&'static str]),
    /// The camera is wrong, named by this catalogue id.
    Entry(&'static str),
    /// The camera is wrong: the eye moved, named as such.
    EyeMoved,
}

/// The gradebook's rows by (student, image): camera, camera_diagnosis, appearance,
/// verdict.
fn gradebook(path: &Path) -> BTreeMap<(String, String), [String; 4]> {
    let mut reader = csv::Reader::from_path(path).unwrap();
    assert_eq!(
        reader.headers().unwrap(),
        vec![
            "student",
            "image",
            "verdict",
            "camera",
            "camera_diagnosis",
            "peak_flip",
            "appearance"
        ]
    );
    reader
        .records()
        .map(|record| {
            let r = record.unwrap();
            (
                (r[0].to_owned(), r[1].to_owned()),
                [
                    r[3].to_owned(),
                    r[4].to_owned(),
                    r[6].to_owned(),
                    r[2].to_owned(),
                ],
            )
        })
        .collect()
}

/// Whether a row says what `want` says; the reason when not.
fn check(want: &Want, row: &[String; 4]) -> Result<(), String> {
    let [camera, diagnosis, appearance, verdict] = row;
    match want {
        Want::Right(names) => {
            if camera != "right" || verdict != "pass" {
                return Err(format!("the camera should be right: {row:?}"));
            }
            if !names.contains(&appearance.as_str()) {
                return Err(format!(
                    "the appearance should be one of {names:?}: {row:?}"
                ));
            }
        }
        Want::Entry(id) => {
            // The diagnosis names the entries as `id (summary): fix ...`.
            let named = diagnosis.contains(&format!("{id} ("));
            if camera != "wrong" || verdict != "fail" || !named {
                return Err(format!("{id} should be named: {row:?}"));
            }
            if !diagnosis.contains(": fix ") {
                return Err(format!("the formula to fix should be given: {row:?}"));
            }
        }
        Want::EyeMoved => {
            // The eye moved 0.6 along x, which is along u (to the right) give or take the
            // camera's turn; the amount is found within a third: about 0.4 to 0.8.
            let amount = diagnosis
                .strip_prefix("the eye is about ")
                .and_then(|rest| rest.split_once(" to the right of where it should be"))
                .and_then(|(amount, _)| amount.parse::<f64>().ok());
            if camera != "wrong" || !amount.is_some_and(|a| (0.4..=0.8).contains(&a)) {
                return Err(format!("the moved eye should be named: {row:?}"));
            }
        }
    }
    Ok(())
}

/// A student's picture: what the student's program renders.
struct Shot<'a> {
    scene: &'a Scene,
    camera: CameraSpec,
    mistakes: &'a [Mistake],
    size: (u32, u32),
    options: RenderOptions,
    /// ASCII PPM (P3), else binary (P6).
    ascii: bool,
}

/// `shot` rendered and written into `folder` as `IMAGE.ppm`, as a student's program
/// writes it.
fn hand_in(folder: &Path, image: &str, shot: &Shot<'_>) {
    std::fs::create_dir_all(folder).unwrap();
    let path = folder.join(format!("{image}.ppm"));
    let format = if shot.ascii {
        Format::PpmP3
    } else {
        Format::PpmP6
    };
    render(
        shot.scene,
        &shot.camera,
        shot.mistakes,
        shot.size,
        &shot.options,
    )
    .write(&path, format);
}

#[test]
fn the_camera_is_judged_first_and_every_planted_cell_is_named() {
    let scene = Scene::example();
    let dir = tempfile::tempdir().unwrap();
    let (reference, scenes, class) = (
        dir.path().join("reference"),
        dir.path().join("scenes"),
        dir.path().join("class"),
    );
    for folder in [&reference, &scenes, &class] {
        std::fs::create_dir_all(folder).unwrap();
    }
    let mut wants: BTreeMap<(String, String), Want> = BTreeMap::new();
    for (index, (name, camera, size)) in cameras().into_iter().enumerate() {
        let image = format!("{name}.png");
        // The course's reference: its own solution's render (16 samples), with the scene.
        let ron = scene.to_ron(&camera, size.0, size.1, 1);
        std::fs::write(scenes.join(format!("{name}.ron")), &ron).unwrap();
        let solution = RenderOptions {
            samples: 16,
            ..RenderOptions::default()
        };
        render(&scene, &camera, &[], size, &solution).write(&reference.join(&image), Format::Png);
        // The entries that change this camera's picture, as viewray's judge groups them.
        let loaded = viewray_scene::SceneLoader::text(&ron, Path::new("student.ron"))
            .load()
            .unwrap()
            .scene;
        let changing: Vec<String> = PictureJudge::new(&loaded)
            .entries()
            .iter()
            .flatten()
            .map(|m| m.id().to_owned())
            .collect();
        let ascii = index % 2 == 1;
        for (student, options, names) in appearances() {
            hand_in(
                &class.join(student),
                name,
                &Shot {
                    scene: &scene,
                    camera,
                    mistakes: &[],
                    size,
                    options,
                    ascii,
                },
            );
            wants.insert((student.to_owned(), image.clone()), Want::Right(names));
        }
        for mistake in Mistake::ALL {
            let student = mistake.id();
            let want = if !mistake.applies_to(&camera.projection) {
                // Not this family's mistake: the student hands in a right picture.
                hand_in(
                    &class.join(student),
                    name,
                    &Shot {
                        scene: &scene,
                        camera,
                        mistakes: &[],
                        size,
                        options: RenderOptions::default(),
                        ascii,
                    },
                );
                Want::Right(&["same", "noise"])
            } else {
                hand_in(
                    &class.join(student),
                    name,
                    &Shot {
                        scene: &scene,
                        camera,
                        mistakes: &[mistake],
                        size,
                        options: RenderOptions::default(),
                        ascii,
                    },
                );
                if changing.iter().any(|id| id == student) {
                    Want::Entry(student)
                } else {
                    // The same picture as the right camera's (a shift left out where
                    // there is none): nothing to see, nothing failed.
                    Want::Right(&["same", "noise"])
                }
            };
            wants.insert((student.to_owned(), image.clone()), want);
        }
        // The eye moved 0.6 to the right (the student typed e wrong), aimed at the same
        // point; in a nested folder, as a zip unpacks (`henry/hw3/general.ppm`).
        let mut moved = camera;
        moved.eye = moved.eye + v(0.6, 0.0, 0.0);
        hand_in(
            &class.join("eye-moved").join("hw3"),
            name,
            &Shot {
                scene: &scene,
                camera: moved,
                mistakes: &[],
                size,
                options: RenderOptions::default(),
                ascii,
            },
        );
        wants.insert(("eye-moved".to_owned(), image.clone()), Want::EyeMoved);
    }

    let csv = dir.path().join("gradebook.csv");
    let out = viewray(&[
        "grade",
        s(&reference),
        s(&class),
        "--scene",
        s(&scenes),
        "--csv",
        s(&csv),
    ]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(1), "{stdout}");
    let rows = gradebook(&csv);
    let mut wrong = Vec::new();
    for (key, want) in &wants {
        let row = rows
            .get(key)
            .unwrap_or_else(|| panic!("no row for {key:?}"));
        match check(want, row) {
            Ok(()) => println!("ok    {} / {}: {row:?}", key.0, key.1),
            Err(why) => {
                println!("WRONG {} / {}: {why}", key.0, key.1);
                wrong.push(format!("{} / {}: {why}", key.0, key.1));
            }
        }
    }
    println!(
        "{} of {} cells of the matrix are right",
        wants.len() - wrong.len(),
        wants.len()
    );
    assert!(
        wrong.is_empty(),
        "{} wrong cells:\n{}",
        wrong.len(),
        wrong.join("\n")
    );
    assert!(
        stdout.contains("failures: ") && stdout.contains("u-sign"),
        "the summary counts the diagnoses: {stdout}"
    );

    // `viewray compare` judges a student's folder the same way, in JSON lines.
    let out = viewray(&[
        "compare",
        s(&reference),
        s(&class.join("u-sign")),
        "--scene",
        s(&scenes),
        "--json",
    ]);
    assert_eq!(out.status.code(), Some(1));
    let lines: Vec<serde_json::Value> = String::from_utf8(out.stdout)
        .unwrap()
        .lines()
        .map(|l| serde_json::from_str(l).unwrap())
        .collect();
    let general = lines.iter().find(|l| l["name"] == "general.png").unwrap();
    assert_eq!(general["judge"], "camera");
    assert_eq!(general["camera"], "wrong");
    assert!(
        general["catalogue"]
            .as_array()
            .unwrap()
            .contains(&"u-sign".into()),
        "{general}"
    );
    let out = viewray(&[
        "compare",
        s(&reference.join("general.png")),
        s(&class.join("right-gamma-missing").join("general.ppm")),
        "--scene",
        s(&scenes.join("general.ron")),
    ]);
    let stdout = String::from_utf8(out.stdout).unwrap();
    assert_eq!(out.status.code(), Some(0), "{stdout}");
    assert!(
        stdout.contains("right") && stdout.contains("gamma-missing"),
        "{stdout}"
    );
    // Judged by the image alone, the same render fails: the appearance decides.
    let out = viewray(&[
        "compare",
        s(&reference.join("general.png")),
        s(&class.join("right-gamma-missing").join("general.ppm")),
        "--scene",
        s(&scenes.join("general.ron")),
        "--judge",
        "both",
    ]);
    assert_eq!(out.status.code(), Some(1));
}

/// Every file a student's program writes (PPM P3 and P6, 8 and 16 bits; PGM P2 and P5;
/// PNG 8 and 16 bits, RGB and grey) reads back as the values it holds, within one 8-bit
/// code for 16 bits; anything else is refused naming the formats.
#[test]
fn every_image_a_student_writes_is_read_as_written() {
    let dir = tempfile::tempdir().unwrap();
    let (_, camera, _) = cameras().remove(1);
    let picture = render(
        &Scene::example(),
        &camera,
        &[],
        (24, 18),
        &RenderOptions::default(),
    );
    let (rgb, grey) = (picture.rgb8(), picture.grey8());
    for format in Format::ALL {
        let path = dir
            .path()
            .join(format!("{format:?}.{}", format.extension()));
        picture.write(&path, format);
        let read = viewray_compare::load_image(&path).unwrap_or_else(|e| panic!("{e}"));
        assert_eq!(read.dimensions(), (24, 18), "{format:?}");
        let grey_format = matches!(format, Format::PgmP5 | Format::PgmP2 | Format::PngGrey);
        for (p, pixel) in read.pixels().enumerate() {
            let want = if grey_format {
                [grey[p]; 3]
            } else {
                [rgb[3 * p], rgb[3 * p + 1], rgb[3 * p + 2]]
            };
            for c in 0..3 {
                let off = (i32::from(pixel[c]) - i32::from(want[c])).abs();
                assert!(off <= 1, "{format:?} pixel {p}: {pixel:?}, want {want:?}");
            }
            assert_eq!(pixel[3], 255, "{format:?}");
        }
    }
    // OpenEXR holds linear light: read back, it is the PNG viewray writes of it.
    let scene = support::repository().join("fixtures/mistakes/perspective.ron");
    let (exr, png) = (dir.path().join("render.exr"), dir.path().join("render.png"));
    for out in [&exr, &png] {
        let done = viewray(&["render", s(&scene), "--size", "24x18", "-o", s(out)]);
        assert!(
            done.status.success(),
            "{}",
            String::from_utf8_lossy(&done.stderr)
        );
    }
    let (from_exr, from_png) = (
        viewray_compare::load_image(&exr).unwrap(),
        viewray_compare::load_image(&png).unwrap(),
    );
    for (a, b) in from_exr.pixels().zip(from_png.pixels()) {
        for c in 0..4 {
            assert!(a[c].abs_diff(b[c]) <= 1, "{a:?} != {b:?}");
        }
    }
    let text = dir.path().join("notes.ppm");
    std::fs::write(&text, "my render is below").unwrap();
    let error = viewray_compare::load_image(&text).unwrap_err().to_string();
    assert!(
        error.ends_with("not an image viewray reads (PNG, PPM/PGM (P2, P3, P5, P6) or OpenEXR)"),
        "{error}"
    );
}

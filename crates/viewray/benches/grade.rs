//! What grading a class costs: `viewray grade` on 200 students x 10 images of 320 x 240,
//! rendered by viewray from fixture scenes at 1, 2 and 4 samples per pixel against 16-sample
//! references, with a few planted camera mistakes (from viewray-compare's test matrix), a
//! missing image and a file that is not a PNG, judged by their cameras with the scenes
//! (`--scene`). The target: under 30 s on 2 cores.
//!
//! `cargo bench -p viewray --bench grade` renders the class into the target folder once
//! (about 50 renders; the students' files are copies of them), then prints one line for
//! the whole class: the wall time and the processor time (user + system) of `viewray
//! grade`, which other work on a shared machine does not inflate; then criterion's
//! estimate for a class of 20 students.

use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::{Duration, Instant};

use criterion::Criterion;
use image::RgbaImage;

#[path = "../../viewray-compare/tests/it/planted/mod.rs"]
mod planted;

use planted::{Base, Case, Mistake};

const BINARY: &str = env!("CARGO_BIN_EXE_viewray");
const SIZE: (u32, u32) = (320, 240);
const STUDENTS: usize = 200;
const SAMPLES: [u32; 3] = [1, 2, 4];

/// An image of the assignment: a planted base scene (mistakes can be planted in it) or a
/// fixture scene file.
#[derive(Clone, Copy)]
enum Assignment {
    Planted(Base),
    Fixture(&'static str),
}

const ASSIGNMENT: [Assignment; 10] = [
    Assignment::Planted(Base::Boxes),
    Assignment::Planted(Base::General),
    Assignment::Planted(Base::Tower),
    Assignment::Planted(Base::Orthographic),
    Assignment::Planted(Base::GeneralShifted),
    Assignment::Fixture("perspective_two_point"),
    Assignment::Fixture("axonometric_isometric"),
    Assignment::Fixture("oblique_cabinet"),
    Assignment::Fixture("mesh_houses"),
    Assignment::Fixture("thin_lens_small_aperture"),
];

/// The planted mistakes, by the index of the image they are planted in.
const MISTAKES: [(usize, Mistake); 6] = [
    (0, Mistake::ShiftFlipped),
    (1, Mistake::Roll(8.0)),
    (
        2,
        Mistake::Mirror {
            left_right: true,
            upside_down: false,
        },
    ),
    (3, Mistake::Viewport(1.25)),
    (4, Mistake::MissingObject),
    (1, Mistake::PixelCorner),
];

impl Assignment {
    fn name(self) -> String {
        match self {
            Assignment::Planted(base) => base.name().to_owned(),
            Assignment::Fixture(name) => name.to_owned(),
        }
    }

    fn render(self, samples: u32, mistake: Mistake) -> RgbaImage {
        match self {
            Assignment::Planted(base) => {
                let case = Case::new(base, SIZE, samples, mistake);
                if samples == planted::REFERENCE_SAMPLES && mistake == Mistake::None {
                    case.render_reference()
                } else {
                    case.render_student()
                }
            }
            Assignment::Fixture(name) => {
                let path = planted::fixtures()
                    .join("scenes")
                    .join(format!("{name}.ron"));
                let text = std::fs::read_to_string(&path).unwrap();
                planted::render_text(&text, path, SIZE, samples)
            }
        }
    }
}

/// Writes the class into `root` (reference/, scenes/, submissions/student_NNN/) unless it
/// is there.
fn class(root: &Path) -> (PathBuf, PathBuf) {
    let (reference, submissions) = (root.join("reference"), root.join("submissions"));
    if root.join("complete").is_file() && root.join("scenes").is_dir() {
        return (reference, submissions);
    }
    let _ = std::fs::remove_dir_all(root);
    let renders = root.join("renders");
    std::fs::create_dir_all(&reference).unwrap();
    std::fs::create_dir_all(&renders).unwrap();
    // The scenes, for the camera judgement; the fixtures' meshes where their scenes find
    // them (`../meshes/`).
    let scenes = root.join("scenes");
    std::fs::create_dir_all(&scenes).unwrap();
    let meshes = root.join("meshes");
    std::fs::create_dir_all(&meshes).unwrap();
    for entry in std::fs::read_dir(planted::fixtures().join("meshes")).unwrap() {
        let entry = entry.unwrap();
        std::fs::copy(entry.path(), meshes.join(entry.file_name())).unwrap();
    }
    for assignment in ASSIGNMENT {
        let name = assignment.name();
        let text = match assignment {
            Assignment::Planted(base) => {
                Case::new(base, SIZE, planted::REFERENCE_SAMPLES, Mistake::None).reference_scene()
            }
            Assignment::Fixture(name) => std::fs::read_to_string(
                planted::fixtures()
                    .join("scenes")
                    .join(format!("{name}.ron")),
            )
            .unwrap(),
        };
        std::fs::write(scenes.join(format!("{name}.ron")), text).unwrap();
    }
    for (index, assignment) in ASSIGNMENT.iter().enumerate() {
        let name = assignment.name();
        assignment
            .render(planted::REFERENCE_SAMPLES, Mistake::None)
            .save(reference.join(format!("{name}.png")))
            .unwrap();
        for samples in SAMPLES {
            assignment
                .render(samples, Mistake::None)
                .save(renders.join(format!("{name}_{samples}.png")))
                .unwrap();
        }
        for (k, &(_, mistake)) in MISTAKES.iter().enumerate().filter(|(_, m)| m.0 == index) {
            let samples = if mistake == Mistake::PixelCorner {
                1
            } else {
                4
            };
            assignment
                .render(samples, mistake)
                .save(renders.join(format!("{name}_mistake_{k}.png")))
                .unwrap();
        }
    }
    for student in 0..STUDENTS {
        let folder = submissions.join(format!("student_{student:03}"));
        std::fs::create_dir_all(&folder).unwrap();
        // Every eighth student plants one mistake, in turn.
        let mistake = (student % 8 == 5).then(|| (student / 8) % MISTAKES.len());
        for (index, assignment) in ASSIGNMENT.iter().enumerate() {
            let name = assignment.name();
            let target = folder.join(format!("{name}.png"));
            let source = match mistake {
                Some(k) if MISTAKES[k].0 == index => {
                    renders.join(format!("{name}_mistake_{k}.png"))
                }
                _ => {
                    let samples = SAMPLES[(student + index) % SAMPLES.len()];
                    renders.join(format!("{name}_{samples}.png"))
                }
            };
            match (student, index) {
                // One student forgot an image, another handed in a JPEG named .png.
                (17, 3) => {}
                (42, 6) => std::fs::write(&target, b"\xff\xd8\xff\xe0 not a PNG").unwrap(),
                _ => {
                    std::fs::copy(&source, &target).unwrap();
                }
            }
        }
    }
    std::fs::write(root.join("complete"), "").unwrap();
    (reference, submissions)
}

/// The processor time (user + system, in seconds) of this process's children that have
/// been waited for, from `/proc/self/stat`, where Linux has it.
fn children_cpu_time() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/self/stat").ok()?;
    // After the command name (in parentheses), cutime and cstime are the 14th and 15th
    // fields, in clock ticks of 1/100 s.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(13)?.parse::<f64>().ok()? + fields.get(14)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// Runs `viewray grade REFERENCE SUBMISSIONS --scene SCENES --csv ...` (the camera
/// judgement, with the scenes); exit code 1 (the planted mistakes fail).
fn grade(reference: &Path, submissions: &Path, csv: &Path) {
    let scenes = reference.with_file_name("scenes");
    let output = Command::new(BINARY)
        .arg("grade")
        .arg(reference)
        .arg(submissions)
        .arg("--scene")
        .arg(scenes)
        .arg("--csv")
        .arg(csv)
        .output()
        .unwrap();
    assert_eq!(
        output.status.code(),
        Some(1),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
}

fn main() {
    let root = Path::new(env!("CARGO_TARGET_TMPDIR")).join("grade-bench");
    let (reference, submissions) = class(&root);
    let csv = root.join("gradebook.csv");

    // The whole class, once.
    let cpu_before = children_cpu_time();
    let started = Instant::now();
    grade(&reference, &submissions, &csv);
    let wall = started.elapsed().as_secs_f64();
    let cpu = children_cpu_time().zip(cpu_before).map(|(a, b)| a - b);
    println!(
        "grade {STUDENTS} students x {} images of {}x{}: {wall:.1} s wall, {} on {} threads \
         (target under 30 s on 2 cores)",
        ASSIGNMENT.len(),
        SIZE.0,
        SIZE.1,
        cpu.map_or_else(
            || "processor time unknown".to_owned(),
            |cpu| format!("{cpu:.1} s processor time")
        ),
        std::thread::available_parallelism().map_or(1, |n| n.get()),
    );

    // A class of 20 students, for criterion.
    let small = root.join("small");
    if !small.join("student_019").is_dir() {
        for student in 0..20 {
            let name = format!("student_{student:03}");
            let (from, to) = (submissions.join(&name), small.join(&name));
            std::fs::create_dir_all(&to).unwrap();
            for entry in std::fs::read_dir(&from).unwrap() {
                let entry = entry.unwrap();
                std::fs::copy(entry.path(), to.join(entry.file_name())).unwrap();
            }
        }
    }
    let mut criterion = Criterion::default()
        .sample_size(10)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(20))
        .configure_from_args();
    criterion.bench_function("grade 20 students x 10 images 320x240", |b| {
        b.iter(|| grade(&reference, &small, &csv))
    });
    criterion.final_summary();
}

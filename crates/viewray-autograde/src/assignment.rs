//! The assignment file: what a submission is graded on, read from RON and checked before
//! any student's work is looked at.
//!
//! ```text
//! (
//!   title: "Homework 3: general perspective cameras",
//!   judge: Camera,                                  // Camera | Image | Both
//!   run: Some((command: "julia raytracer.jl {scene} {output}", timeout_s: 30)),
//!   tests: [
//!     (name: "canonical", scene: "scenes/canonical.ron", image: "canonical.png", points: 2.0),
//!     (name: "general rays", scene: "scenes/general.ron", answers: "general.txt", points: 3.0,
//!      visibility: AfterDueDate),                   // Visible (default) | AfterDueDate | Hidden
//!   ],
//! )
//! ```
//!
//! Paths in the file are relative to it and stay inside its folder; a test's `image` or
//! `answers` is a name in the student's submission folder. A test may also say
//! `partial: Some(0.5)` (the fraction of its points a picture earns when its camera is
//! right and its appearance is not; with `judge: Image` or `Both`), `reference:
//! Some("references/canonical.png")` (the picture to judge appearance against, instead
//! of viewray's render of the scene), `one_based: true` and `tolerance: Some(1e-4)` (how
//! answers are read and compared, as `viewray check` reads them). The assignment may
//! list `files: ["meshes"]`: more files or folders its scenes read, which a kit carries.

use std::collections::HashSet;
use std::fmt;
use std::path::{Component, Path, PathBuf};

use serde::Deserialize;
use viewray_compare::RgbaImage;
use viewray_scene::{Scene, SceneLoader};

/// What decides whether a picture passes.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Judge {
    /// The camera: the picture's edges fall where the scene's camera puts them, whatever
    /// the shading (the default).
    #[default]
    Camera,
    /// The appearance: the picture looks like the reference (FLIP).
    Image,
    /// Both.
    Both,
}

/// When a student may see a test's result (platforms that cannot say so withhold the
/// details of every test that is not [`Visibility::Visible`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Deserialize)]
pub enum Visibility {
    /// Always (the default).
    #[default]
    Visible,
    /// After the due date.
    AfterDueDate,
    /// Never; the instructor sees it.
    Hidden,
}

/// How the student's own program is run, once per test.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// The command, run by `sh -c` in a copy of the submission folder, with `{scene}`
    /// and `{output}` replaced by the test's scene file and the file it must write.
    pub command: String,
    /// The time limit of one test's run, in seconds.
    pub timeout_s: f64,
}

/// What a test's student hands in.
#[derive(Clone, Debug, PartialEq)]
pub enum HandIn {
    /// A picture of the scene, by this name in the submission.
    Image(String),
    /// Numbers about the scene's camera (as `viewray check` reads them), by this name.
    Answers(String),
}

impl HandIn {
    /// The file's name in the submission (or the `{output}` the program writes).
    pub fn name(&self) -> &str {
        match self {
            HandIn::Image(name) | HandIn::Answers(name) => name,
        }
    }
}

/// One test of an assignment, checked: its scene loaded, its reference read.
#[derive(Clone, Debug)]
pub struct Test {
    /// Its name, unique in the assignment.
    pub name: String,
    /// The scene file, as written in the assignment (relative to it).
    pub scene_path: String,
    /// The scene file's path, for the student's program.
    pub scene_file: PathBuf,
    /// The scene, loaded.
    pub scene: Scene,
    /// What is handed in.
    pub hand_in: HandIn,
    /// The test's points.
    pub points: f64,
    /// Who sees the result, when.
    pub visibility: Visibility,
    /// The fraction of the points a picture earns when its camera is right and its
    /// appearance is not.
    pub partial: Option<f64>,
    /// The reference picture, as written and as read, when the assignment gives one.
    pub reference: Option<(String, RgbaImage)>,
    /// Answers' pixels are the lecture's 1-based `(i, j)`.
    pub one_based: bool,
    /// The relative tolerance answers are compared with.
    pub tolerance: f64,
}

/// An assignment, read and checked.
#[derive(Clone, Debug)]
pub struct Assignment {
    /// The assignment file.
    pub path: PathBuf,
    /// Its title.
    pub title: String,
    /// What decides whether a picture passes.
    pub judge: Judge,
    /// The student's program, when the submission is a program rather than its files.
    pub run: Option<Run>,
    /// The tests, in the file's order.
    pub tests: Vec<Test>,
    /// More files and folders the scenes read (relative to the assignment).
    pub files: Vec<String>,
}

impl Assignment {
    /// The folder the assignment's paths are relative to.
    pub fn folder(&self) -> &Path {
        self.path.parent().unwrap_or(Path::new("."))
    }

    /// The greatest score.
    pub fn max_score(&self) -> f64 {
        self.tests.iter().map(|t| t.points).sum()
    }

    /// Every file and folder the assignment reads beside itself, relative to its folder:
    /// the scenes, the references and `files`, each once, in that order.
    pub fn inputs(&self) -> Vec<String> {
        let mut seen = HashSet::new();
        self.tests
            .iter()
            .flat_map(|t| {
                std::iter::once(t.scene_path.clone()).chain(t.reference.iter().map(|r| r.0.clone()))
            })
            .chain(self.files.iter().cloned())
            .filter(|p| seen.insert(p.clone()))
            .collect()
    }
}

/// Why an assignment file cannot be used: the file, the place when known, and what is
/// wrong, in the form `hw3.ron:12:5: ...`.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub struct AssignmentError {
    /// The assignment file.
    pub path: PathBuf,
    /// The 1-based line and column, when the RON parser knows them.
    pub position: Option<(usize, usize)>,
    /// What is wrong.
    pub message: String,
}

impl fmt::Display for AssignmentError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.path.display())?;
        if let Some((line, column)) = self.position {
            write!(f, ":{line}:{column}")?;
        }
        write!(f, ": {}", self.message)
    }
}

/// The largest assignment file read: far more than any course writes.
const MAX_ASSIGNMENT_BYTES: u64 = 1 << 20;
/// The longest time limit a test may set: an hour.
const MAX_TIMEOUT_S: f64 = 3600.0;

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct AssignmentDef {
    title: String,
    #[serde(default)]
    judge: Judge,
    #[serde(default)]
    run: Option<RunDef>,
    tests: Vec<TestDef>,
    #[serde(default)]
    files: Vec<String>,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct RunDef {
    command: String,
    timeout_s: f64,
}

#[derive(Deserialize)]
#[serde(deny_unknown_fields)]
struct TestDef {
    name: String,
    scene: String,
    #[serde(default)]
    image: Option<String>,
    #[serde(default)]
    answers: Option<String>,
    points: f64,
    #[serde(default)]
    visibility: Visibility,
    #[serde(default)]
    partial: Option<f64>,
    #[serde(default)]
    reference: Option<String>,
    #[serde(default)]
    one_based: bool,
    #[serde(default)]
    tolerance: Option<f64>,
}

/// Reads and checks the assignment file at `path`: its RON, every rule above, every
/// scene loaded and every reference read (the scene's size).
///
/// # Errors
/// The first problem found, naming the file, and the line and column where the RON
/// parser knows them.
pub fn load_assignment(path: &Path) -> Result<Assignment, AssignmentError> {
    let fail = |message: String| AssignmentError {
        path: path.to_path_buf(),
        position: None,
        message,
    };
    let metadata = std::fs::metadata(path).map_err(|e| fail(format!("cannot read it: {e}")))?;
    if !metadata.is_file() {
        return Err(fail("is not a file".to_owned()));
    }
    if metadata.len() > MAX_ASSIGNMENT_BYTES {
        return Err(fail(format!(
            "is {} bytes: an assignment file is at most {MAX_ASSIGNMENT_BYTES}",
            metadata.len()
        )));
    }
    let text = std::fs::read_to_string(path).map_err(|e| fail(format!("cannot read it: {e}")))?;
    let options =
        ron::Options::default().with_default_extension(ron::extensions::Extensions::IMPLICIT_SOME);
    let def: AssignmentDef = options.from_str(&text).map_err(|error| AssignmentError {
        path: path.to_path_buf(),
        position: Some((error.span.start.line, error.span.start.col)),
        message: error.code.to_string(),
    })?;
    check(path, def).map_err(fail)
}

/// Checks a parsed assignment and loads what it names.
fn check(path: &Path, def: AssignmentDef) -> Result<Assignment, String> {
    let folder = path.parent().unwrap_or(Path::new("."));
    if def.tests.is_empty() {
        return Err(
            "has no tests: give `tests: [(name: ..., scene: ..., image: ..., points: ...)]`"
                .to_owned(),
        );
    }
    let run = def.run.map(|run| check_run(run, &def.tests)).transpose()?;
    let mut names = HashSet::new();
    let mut tests = Vec::with_capacity(def.tests.len());
    for test in def.tests {
        let name = test.name.trim().to_owned();
        if name.is_empty() {
            return Err("a test has an empty name".to_owned());
        }
        if !names.insert(name.clone()) {
            return Err(format!(
                "two tests are named `{name}`: each name must be unique"
            ));
        }
        tests.push(
            check_test(folder, def.judge, test, &name)
                .map_err(|m| format!("test `{name}`: {m}"))?,
        );
    }
    for file in &def.files {
        inside(file).map_err(|m| format!("`files`: {m}"))?;
        if !folder.join(file).exists() {
            return Err(format!("`files`: `{file}` does not exist"));
        }
    }
    Ok(Assignment {
        path: path.to_path_buf(),
        title: def.title,
        judge: def.judge,
        run,
        tests,
        files: def.files,
    })
}

fn check_run(run: RunDef, tests: &[TestDef]) -> Result<Run, String> {
    if run.command.trim().is_empty() {
        return Err("`run`: the command is empty".to_owned());
    }
    if !(run.timeout_s.is_finite() && run.timeout_s > 0.0 && run.timeout_s <= MAX_TIMEOUT_S) {
        return Err(format!(
            "`run`: timeout_s is {}: expected seconds above 0, at most {MAX_TIMEOUT_S}",
            run.timeout_s
        ));
    }
    if !run.command.contains("{output}") && tests.iter().any(|t| t.image.is_some()) {
        return Err(
            "`run`: the command must pass `{output}`, the picture's path, to the program \
             (only answers may come from its standard output)"
                .to_owned(),
        );
    }
    Ok(Run {
        command: run.command,
        timeout_s: run.timeout_s,
    })
}

fn check_test(folder: &Path, judge: Judge, test: TestDef, name: &str) -> Result<Test, String> {
    let hand_in = match (test.image, test.answers) {
        (Some(image), None) => HandIn::Image(image),
        (None, Some(answers)) => HandIn::Answers(answers),
        (Some(_), Some(_)) => return Err("give `image` or `answers`, not both".to_owned()),
        (None, None) => {
            return Err(
                "give what the student hands in: `image: \"NAME.png\"` or `answers: \"NAME.txt\"`"
                    .to_owned(),
            );
        }
    };
    inside(hand_in.name()).map_err(|m| format!("`{}`: {m}", hand_in_field(&hand_in)))?;
    if !(test.points.is_finite() && test.points >= 0.0) {
        return Err(format!(
            "points is {}: expected a number, 0 or more",
            test.points
        ));
    }
    if let Some(partial) = test.partial {
        if !(0.0..=1.0).contains(&partial) {
            return Err(format!(
                "partial is {partial}: expected a fraction of the points, in [0, 1]"
            ));
        }
        if matches!(hand_in, HandIn::Answers(_)) {
            return Err(
                "partial credit is for pictures (camera right, appearance wrong), not answers"
                    .to_owned(),
            );
        }
        if judge == Judge::Camera {
            return Err(
                "partial credit needs `judge: Both` or `judge: Image`: with `judge: Camera` the \
                 appearance never costs points"
                    .to_owned(),
            );
        }
    }
    let tolerance = test.tolerance.unwrap_or(1e-6);
    if !(tolerance.is_finite() && tolerance > 0.0) {
        return Err(format!(
            "tolerance is {tolerance}: expected a positive number such as 1e-6"
        ));
    }
    inside(&test.scene).map_err(|m| format!("`scene`: {m}"))?;
    let scene_file = folder.join(&test.scene);
    let scene = SceneLoader::file(&scene_file)
        .load()
        .map_err(|e| format!("its scene: {e}"))?
        .scene;
    let size = (scene.camera().width(), scene.camera().height());
    let reference = match test.reference {
        Some(reference) => {
            inside(&reference).map_err(|m| format!("`reference`: {m}"))?;
            let image = viewray_compare::load_png(folder.join(&reference))
                .map_err(|e| format!("its reference: {e}"))?;
            if image.dimensions() != size {
                return Err(format!(
                    "its reference `{reference}` is {}x{} pixels but its scene's image is {}x{}",
                    image.width(),
                    image.height(),
                    size.0,
                    size.1
                ));
            }
            Some((reference, image))
        }
        None => None,
    };
    Ok(Test {
        name: name.to_owned(),
        scene_path: test.scene,
        scene_file,
        scene,
        hand_in,
        points: test.points,
        visibility: test.visibility,
        partial: test.partial,
        reference,
        one_based: test.one_based,
        tolerance,
    })
}

fn hand_in_field(hand_in: &HandIn) -> &'static str {
    match hand_in {
        HandIn::Image(_) => "image",
        HandIn::Answers(_) => "answers",
    }
}

/// Checks that `path` is relative and stays inside its folder: no root, no `..`.
pub(crate) fn inside(path: &str) -> Result<(), String> {
    if path.trim().is_empty() {
        return Err("the path is empty".to_owned());
    }
    for component in Path::new(path).components() {
        match component {
            Component::Normal(_) | Component::CurDir => {}
            Component::ParentDir => {
                return Err(format!(
                    "`{path}` leaves its folder (`..`): paths stay inside it"
                ));
            }
            Component::RootDir | Component::Prefix(_) => {
                return Err(format!(
                    "`{path}` is absolute: paths are relative to the assignment file"
                ));
            }
        }
    }
    Ok(())
}

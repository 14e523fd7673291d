//! Grading one submission: for each test, the student's file (read from the submission,
//! or made by their program in a scratch folder), judged, and turned into points.

use std::io::Cursor;
use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use viewray_judge::{CheckOptions, Checker, Judged, read_answers};

use crate::assignment::{Assignment, HandIn, Judge, Test, load_assignment};
use crate::files::{CopyLimits, ReadError, copy_submission, read_inside};
use crate::picture::{
    MAX_PICTURE_BYTES, PICTURE_EXTENSIONS, PictureJudges, judge_picture, read_picture,
};
use crate::results::{Results, Status, TestResult, points};
use crate::sandbox::{self, Limits, Program, RunAs, ending_words, shell_quote};
use crate::words::{answers_words, appearance_words, camera_words, thumbnail, thumbnail_rgb};

/// How a submission is graded.
#[derive(Clone, Debug, PartialEq)]
pub struct Options {
    /// The limits the student's program runs under (the time limit is the assignment's).
    pub limits: Limits,
    /// How much of the submission is copied for the program to run in.
    pub copy: CopyLimits,
    /// The folder the scratch folder is made in (the system's temporary folder if none).
    pub scratch_in: Option<PathBuf>,
    /// The tests to grade, by name (all when empty).
    pub only: Vec<String>,
    /// The user the student's program runs as, by name, instead of viewray's own (which
    /// must then be root): it owns only the program's folders.
    pub run_as: Option<String>,
}

impl Default for Options {
    fn default() -> Self {
        Options {
            limits: Limits::default(),
            copy: CopyLimits {
                bytes: 256 << 20,
                entries: 10_000,
            },
            scratch_in: None,
            only: Vec::new(),
            run_as: None,
        }
    }
}

/// The most wrong answers listed in a test's output.
const WRONG_ANSWERS_SHOWN: usize = 20;

/// Grades the submission folder `submission` on the assignment file `assignment`. Never
/// fails: an assignment that cannot be read, a submission folder that does not exist or
/// an unknown test name gives [`Results`] that say why ([`Results::problem`]).
pub fn grade(assignment: &Path, submission: &Path, options: &Options) -> Results {
    let started = Instant::now();
    let title = assignment.file_name().map_or_else(
        || assignment.display().to_string(),
        |n| n.to_string_lossy().into_owned(),
    );
    let assignment = match load_assignment(assignment) {
        Ok(assignment) => assignment,
        Err(error) => {
            return Results::problem(
                title,
                format!("the assignment file is broken: {error}"),
                started.elapsed(),
            );
        }
    };
    grade_assignment(&assignment, submission, options)
}

/// Grades the submission folder `submission` on a loaded assignment (see [`grade`]).
pub fn grade_assignment(assignment: &Assignment, submission: &Path, options: &Options) -> Results {
    let started = Instant::now();
    let problem =
        |message: String| Results::problem(assignment.title.clone(), message, started.elapsed());
    if let Some(unknown) = options
        .only
        .iter()
        .find(|n| !assignment.tests.iter().any(|t| &t.name == *n))
    {
        let names: Vec<&str> = assignment.tests.iter().map(|t| t.name.as_str()).collect();
        return problem(format!(
            "the assignment has no test `{unknown}` (its tests: {})",
            names.join(", ")
        ));
    }
    match std::fs::metadata(submission) {
        Ok(m) if m.is_dir() => {}
        Ok(_) => {
            return problem(format!(
                "the submission `{}` is not a folder",
                submission.display()
            ));
        }
        Err(e) => {
            return problem(format!(
                "the submission folder `{}` cannot be read: {e}",
                submission.display()
            ));
        }
    }
    let mut scratch = None;
    let mut notes = Vec::new();
    let mut tests = Vec::new();
    for (index, test) in assignment.tests.iter().enumerate() {
        if !options.only.is_empty() && !options.only.contains(&test.name) {
            continue;
        }
        let test_started = Instant::now();
        let handed = match &assignment.run {
            None => Handed::from_submission(submission, test),
            Some(run) => {
                if scratch.is_none() {
                    match Scratch::new(submission, options) {
                        Ok((made, note)) => {
                            notes.extend(note);
                            scratch = Some(made);
                        }
                        Err(message) => return problem(message),
                    }
                }
                let scratch = scratch.as_ref().expect("made above");
                let limits = Limits {
                    timeout: Duration::from_secs_f64(run.timeout_s),
                    ..options.limits
                };
                scratch.run(&run.command, test, index, &limits)
            }
        };
        let mut result = judge(assignment, test, handed);
        result.duration = test_started.elapsed();
        tests.push(result);
    }
    Results {
        title: assignment.title.clone(),
        tests,
        problem: None,
        notes,
        elapsed: started.elapsed(),
    }
}

/// What a test's student handed in, or why there is nothing to judge.
struct Handed {
    /// The file's bytes, or the sentence saying why there are none.
    bytes: Result<Vec<u8>, String>,
    /// What the program printed, when it ran (for the details).
    printed: Option<String>,
    /// The command that made it, as a student can run it again.
    command: String,
}

impl Handed {
    /// The test's file from the submission folder; a picture may be in any supported
    /// format under the same stem.
    fn from_submission(submission: &Path, test: &Test) -> Handed {
        let name = test.hand_in.name();
        let bytes = match &test.hand_in {
            HandIn::Answers(name) => {
                read_inside(submission, name, sandbox::Limits::default().answers_bytes)
            }
            HandIn::Image(name) => read_picture_file(submission, name),
        };
        Handed {
            bytes: bytes.map_err(|e| format!("{e}")),
            printed: None,
            command: match &test.hand_in {
                HandIn::Answers(_) => check_command(test),
                HandIn::Image(_) => format!(
                    "viewray's judgement of `{name}` against `{}`",
                    test.scene_path
                ),
            },
        }
    }
}

/// `name` in `root`, else the first file with its stem and another picture extension.
fn read_picture_file(root: &Path, name: &str) -> Result<Vec<u8>, ReadError> {
    let first = read_inside(root, name, MAX_PICTURE_BYTES);
    if !matches!(first, Err(ReadError::Missing(_))) {
        return first;
    }
    let path = Path::new(name);
    for extension in PICTURE_EXTENSIONS {
        let other = path.with_extension(extension);
        let other = other.to_string_lossy();
        if other != name && crate::files::exists_inside(root, &other) {
            return read_inside(root, &other, MAX_PICTURE_BYTES);
        }
    }
    first
}

/// `viewray check`'s command line for an answers test.
fn check_command(test: &Test) -> String {
    let mut command = format!("viewray check {} {}", test.scene_path, test.hand_in.name());
    if test.one_based {
        command.push_str(" --one-based");
    }
    if test.tolerance != 1e-6 {
        command.push_str(&format!(" --tolerance {}", test.tolerance));
    }
    command
}

/// The scratch folder a submission's program runs in: `work` (a copy of the
/// submission), `home` (its HOME and TMPDIR), `out` (each test's output folder).
struct Scratch {
    _dir: tempfile::TempDir,
    root: PathBuf,
    /// The user the program runs as, who owns `work`, `home` and `out`.
    run_as: Option<RunAs>,
}

impl Scratch {
    /// Makes the scratch folder and copies the submission into it; the note lists what
    /// the copy left out.
    fn new(submission: &Path, options: &Options) -> Result<(Scratch, Option<String>), String> {
        let run_as = options.run_as.as_deref().map(RunAs::user).transpose()?;
        let parent = options
            .scratch_in
            .clone()
            .unwrap_or_else(std::env::temp_dir);
        let dir = tempfile::Builder::new()
            .prefix("viewray-autograde-")
            .tempdir_in(&parent)
            .map_err(|e| {
                format!(
                    "cannot make a scratch folder in `{}`: {e}",
                    parent.display()
                )
            })?;
        let root = dir.path().to_path_buf();
        for folder in ["home", "out"] {
            std::fs::create_dir(root.join(folder))
                .map_err(|e| format!("cannot make the scratch folder: {e}"))?;
        }
        let copied = copy_submission(submission, &root.join("work"), options.copy)?;
        if let Some(user) = run_as {
            // The scratch folder itself stays viewray's, which the user may only pass
            // through: nothing can be written beside the program's folders.
            use std::os::unix::fs::PermissionsExt as _;
            std::fs::set_permissions(&root, std::fs::Permissions::from_mode(0o711))
                .map_err(|e| format!("cannot open the scratch folder to the program: {e}"))?;
            for folder in ["work", "home", "out"] {
                give_all(&user, &root.join(folder))?;
            }
        }
        let note = (!copied.left_out.is_empty()).then(|| {
            format!(
                "left out of the copy your program runs in (symbolic links and special files are \
                 not followed): {}",
                copied.left_out.join(", ")
            )
        });
        Ok((
            Scratch {
                _dir: dir,
                root,
                run_as,
            },
            note,
        ))
    }

    /// Runs the student's program for test number `index` and takes what it made.
    fn run(&self, command: &str, test: &Test, index: usize, limits: &Limits) -> Handed {
        let out = self.root.join("out").join(index.to_string());
        let name = test.hand_in.name();
        let shown_command = command
            .replace("{scene}", &test.scene_path)
            .replace("{output}", name);
        let fail = |message: String, printed: Option<String>| Handed {
            bytes: Err(message),
            printed,
            command: shown_command.clone(),
        };
        let output = out.join(name);
        if let Err(e) = std::fs::create_dir_all(output.parent().unwrap_or(&out)) {
            return fail(format!("cannot make the output folder: {e}"), None);
        }
        if let Some(user) = self.run_as
            && let Err(message) = give_all(&user, &out)
        {
            return fail(message, None);
        }
        let scene =
            std::path::absolute(&test.scene_file).unwrap_or_else(|_| test.scene_file.clone());
        let substituted = command
            .replace("{scene}", &shell_quote(&scene.to_string_lossy()))
            .replace("{output}", &shell_quote(&output.to_string_lossy()));
        let from_stdout = !command.contains("{output}");
        let stdout_file =
            from_stdout.then(|| self.root.join("out").join(format!("{index}.stdout")));
        let (work, home, outs) = (
            self.root.join("work"),
            self.root.join("home"),
            self.root.join("out"),
        );
        let watched = [work.as_path(), home.as_path(), outs.as_path()];
        let program = Program {
            command: &substituted,
            folder: &work,
            watched: &watched,
            home: &home,
            stdout_file: stdout_file.clone(),
            run_as: self.run_as,
        };
        let finished = match sandbox::run(&program, limits) {
            Ok(finished) => finished,
            Err(message) => return fail(message, None),
        };
        let mut printed = String::new();
        if !from_stdout && !finished.stdout.kept.is_empty() {
            printed.push_str(&format!(
                "your program's standard output:\n{}",
                finished.stdout.text()
            ));
        }
        if !finished.stderr.kept.is_empty() || finished.stderr.total > 0 {
            if !printed.is_empty() && !printed.ends_with('\n') {
                printed.push('\n');
            }
            printed.push_str(&format!(
                "your program's standard error:\n{}",
                finished.stderr.text()
            ));
        }
        let printed = (!printed.is_empty()).then_some(printed);
        if let Some(words) = ending_words(finished.ended, limits) {
            return fail(words, printed);
        }
        if let Some(stray) = self.strays() {
            return fail(
                format!(
                    "your program wrote outside its folder: `../{stray}`; write only the output file `{name}`"
                ),
                printed,
            );
        }
        let bytes = if from_stdout {
            if finished.stdout.total > limits.answers_bytes {
                Err(format!(
                    "your program printed {} bytes: at most {} are read as answers",
                    finished.stdout.total, limits.answers_bytes
                ))
            } else {
                read_inside(
                    &self.root.join("out"),
                    &format!("{index}.stdout"),
                    limits.answers_bytes,
                )
                .map_err(|e| e.to_string())
            }
        } else {
            let limit = match test.hand_in {
                HandIn::Image(_) => MAX_PICTURE_BYTES,
                HandIn::Answers(_) => limits.answers_bytes,
            };
            read_inside(&out, name, limit).map_err(|e| match e {
                ReadError::Missing(_) => {
                    format!("your program ended without writing `{name}` ({{output}})")
                }
                other => other.to_string(),
            })
        };
        Handed {
            bytes,
            printed,
            command: shown_command,
        }
    }

    /// The first thing in the scratch folder that is not one of its own folders (what a
    /// program wrote beside the folder it runs in), removed so the next test starts
    /// clean.
    fn strays(&self) -> Option<String> {
        let mut stray = None;
        for entry in std::fs::read_dir(&self.root).ok()?.filter_map(Result::ok) {
            let name = entry.file_name().to_string_lossy().into_owned();
            if !matches!(name.as_str(), "work" | "home" | "out") {
                let path = entry.path();
                let _ = if path.is_dir() && !path.is_symlink() {
                    std::fs::remove_dir_all(&path)
                } else {
                    std::fs::remove_file(&path)
                };
                stray.get_or_insert(name);
            }
        }
        stray
    }
}

/// Gives `path` and everything in it to `user` (the copy of a submission holds no links).
fn give_all(user: &RunAs, path: &Path) -> Result<(), String> {
    user.give(path)?;
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.is_dir()) {
        let entries = std::fs::read_dir(path)
            .map_err(|e| format!("cannot read `{}`: {e}", path.display()))?;
        for entry in entries.filter_map(Result::ok) {
            give_all(user, &entry.path())?;
        }
    }
    Ok(())
}

/// Judges what was handed in for `test`.
fn judge(assignment: &Assignment, test: &Test, handed: Handed) -> TestResult {
    let mut result = TestResult {
        name: test.name.clone(),
        max_score: test.points,
        score: 0.0,
        status: Status::Failed,
        visibility: test.visibility,
        message: String::new(),
        output: String::new(),
        images: Vec::new(),
        command: handed.command.clone(),
        duration: Duration::ZERO,
    };
    let (message, mut output) = match &test.hand_in {
        HandIn::Image(name) => judge_image(assignment, test, name, handed.bytes, &mut result),
        HandIn::Answers(name) => judge_answers(test, name, handed.bytes, &mut result),
    };
    if let Some(printed) = handed.printed {
        if !output.is_empty() {
            output.push_str("\n\n");
        }
        output.push_str(&printed);
    }
    result.message = message;
    result.output = output;
    result
}

fn judge_image(
    assignment: &Assignment,
    test: &Test,
    name: &str,
    bytes: Result<Vec<u8>, String>,
    result: &mut TestResult,
) -> (String, String) {
    let judges = match PictureJudges::new(&test.scene, test.reference.as_ref().map(|r| &r.1)) {
        Ok(judges) => judges,
        Err(message) => {
            return (
                format!("viewray could not make the reference picture: {message}"),
                String::new(),
            );
        }
    };
    result
        .images
        .extend(thumbnail("expected", judges.reference()));
    let bytes = match bytes {
        Ok(bytes) => bytes,
        Err(message) => return (message, String::new()),
    };
    let size = (test.scene.camera().width(), test.scene.camera().height());
    let picture = match read_picture(&bytes, size) {
        Ok(picture) => picture,
        Err(error) => return (format!("`{name}` {error}"), String::new()),
    };
    let verdict = judge_picture(&judges, &picture);
    result.images.extend(thumbnail("yours", &picture));
    if let Some(heatmap) = verdict.appearance.heatmap() {
        result.images.extend(thumbnail_rgb("difference", &heatmap));
    }
    let camera_right = verdict.camera.passed();
    let appearance_right = verdict.appearance.passed();
    let (camera_headline, camera_details) = camera_words(&verdict.camera);
    let (appearance_headline, appearance_details) = appearance_words(&verdict.appearance);
    let decided = match assignment.judge {
        Judge::Camera => camera_right,
        Judge::Image => appearance_right,
        Judge::Both => camera_right && appearance_right,
    };
    let partial = camera_right && !appearance_right && assignment.judge != Judge::Camera;
    (result.score, result.status) = if decided {
        (test.points, Status::Passed)
    } else if partial {
        (test.points * test.partial.unwrap_or(0.0), Status::Failed)
    } else {
        (0.0, Status::Failed)
    };
    let message = match assignment.judge {
        Judge::Camera => camera_headline,
        Judge::Image if appearance_right => appearance_headline,
        Judge::Image | Judge::Both if !camera_right => camera_headline,
        Judge::Image | Judge::Both if !appearance_right => {
            let mut text = format!("the camera is right, but {appearance_headline}");
            if result.score > 0.0 {
                text.push_str(&format!(
                    ": {} of {} points",
                    points(result.score),
                    points(test.points)
                ));
            }
            text
        }
        Judge::Image | Judge::Both => format!("{camera_headline} and {appearance_headline}"),
    };
    let decides = match assignment.judge {
        Judge::Camera => "this test judges the camera; the appearance is for your information",
        Judge::Image => "this test judges the appearance; the camera is for your information",
        Judge::Both => "this test judges both the camera and the appearance",
    };
    (
        message,
        format!("{camera_details}\n{appearance_details}\n({decides})"),
    )
}

fn judge_answers(
    test: &Test,
    name: &str,
    bytes: Result<Vec<u8>, String>,
    result: &mut TestResult,
) -> (String, String) {
    let bytes = match bytes {
        Ok(bytes) => bytes,
        Err(message) => return (message, String::new()),
    };
    let options = CheckOptions {
        one_based: test.one_based,
        tolerance: test.tolerance,
        exact_direction: false,
    };
    let mut checker = Checker::new(test.scene.camera(), options);
    let mut judged: Vec<Judged> = Vec::new();
    for item in read_answers(Cursor::new(bytes)) {
        let checked = item.and_then(|(line, answer)| checker.check(line, &answer));
        match checked {
            Ok(one) => judged.push(one),
            Err(error) => return (format!("`{name}` cannot be read: {error}"), String::new()),
        }
    }
    let report = checker.finish();
    if report.passed() {
        result.score = test.points;
        result.status = Status::Passed;
    }
    answers_words(&judged, &report, WRONG_ANSWERS_SHOWN)
}

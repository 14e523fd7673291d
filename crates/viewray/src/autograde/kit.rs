//! `viewray autograde kit`: what a platform takes to run `viewray autograde` on every
//! submission.
//!
//! - Gradescope: the autograder zip, laid out as Gradescope unpacks it into
//!   `/autograder/source`: `setup.sh` and `run_autograder` at its root, `bin/viewray`,
//!   `assignment/` (the assignment file with the scenes, references and `files` it names,
//!   in the same layout) and `README.md` for the instructor.
//! - GitHub Classroom: `.github/workflows/classroom.yml` (one step per test running
//!   viewray, which writes the autograding grader's result object, and the autograding
//!   reporter action) and `.viewray/` (viewray, the assignment, a README), to add to the
//!   assignment's template repository.
//!
//! viewray goes onto the platform's machine as itself: the kit carries the very program
//! that made it (or `--viewray FILE`: a program, or the viewray wheel whose command it
//! takes), so nothing is built or downloaded there and every submission is judged by the
//! viewray the instructor tried. The kit is checked before it
//! is written: its assignment is loaded from the kit's own copy (a scene's mesh left out
//! is named), and the glibc the program needs is read from it and stated in the README.

use std::io::Write as _;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, bail};
use clap::{Args, ValueEnum};
use viewray_autograde::files::KIT_FOLDER;
use viewray_autograde::{Assignment, HandIn, Visibility, load_assignment, points};

/// The platforms a kit is made for.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum Platform {
    /// Gradescope's autograder zip.
    Gradescope,
    /// GitHub Classroom's workflow and files.
    Github,
}

#[derive(Args, Debug)]
#[command(
    override_usage = "viewray autograde kit [OPTIONS] --for <PLATFORM> -o <OUT> <ASSIGNMENT>"
)]
pub(crate) struct KitArgs {
    /// The assignment file (RON).
    pub(crate) assignment: PathBuf,
    /// The platform.
    #[arg(long = "for", value_enum, value_name = "PLATFORM")]
    pub(crate) platform: Platform,
    /// Where the kit goes: the zip file (gradescope), or the folder the files are added
    /// to, a template repository's (github).
    #[arg(short = 'o', long = "output", value_name = "OUT")]
    pub(crate) output: PathBuf,
    /// The viewray program the kit carries, for Linux on x86-64 [default: this one], or a
    /// viewray wheel (`.whl`), whose command the kit carries: it runs on any glibc from
    /// 2.17 on, so on every platform image.
    #[arg(long, value_name = "FILE")]
    pub(crate) viewray: Option<PathBuf>,
}

/// A file of a kit: its path inside the kit, its bytes, and whether it is a program.
struct KitFile {
    path: String,
    bytes: Vec<u8>,
    executable: bool,
}

/// The newest glibc a Gradescope image may be expected to lack: Ubuntu 20.04's is 2.31.
const OLDEST_IMAGE_GLIBC: (u32, u32) = (2, 31);

/// Makes the kit.
pub(crate) fn kit(args: &KitArgs) -> Result<()> {
    let assignment = load_assignment(&args.assignment)?;
    let binary_path = match &args.viewray {
        Some(path) => path.clone(),
        None => std::env::current_exe().context("cannot find this viewray program")?,
    };
    let binary = read_viewray(&binary_path)?;
    let glibc = glibc_needed(&binary);
    let name = file_name(&assignment.path);
    let kit_prefix = format!("{KIT_FOLDER}/");
    let (prefix, extra) = match args.platform {
        Platform::Gradescope => ("", gradescope_files(&assignment, &name, glibc)),
        Platform::Github => (kit_prefix.as_str(), github_files(&assignment, &name, glibc)),
    };
    let assets = if args.platform == Platform::Gradescope {
        "assignment/"
    } else {
        prefix
    };
    let mut files = vec![KitFile {
        path: format!("{prefix}bin/viewray"),
        bytes: binary,
        executable: true,
    }];
    files.extend(assignment_files(
        &assignment,
        &format!("{assets}{name}"),
        assets,
    )?);
    files.extend(extra);
    check_copy(&files, &format!("{assets}{name}"))?;
    match args.platform {
        Platform::Gradescope => write_zip(&files, &args.output)?,
        Platform::Github => write_folder(&files, &args.output)?,
    }
    if let Some(glibc) = glibc.filter(|&g| g > OLDEST_IMAGE_GLIBC) {
        crate::style::warning(format_args!(
            "this viewray needs glibc {}.{} or newer: choose a platform image that has it \
             (Ubuntu 22.04 has 2.35), or make the kit with `--viewray` and the viewray wheel \
             (`cargo xtask wheel`; glibc 2.17 and newer)",
            glibc.0, glibc.1
        ));
    }
    println!("wrote {}", args.output.display());
    Ok(())
}

/// The viewray program at `path`: the file itself or, for a wheel (`.whl`, as `cargo
/// xtask wheel` builds it), the command the wheel installs (`*.data/scripts/viewray`).
fn read_viewray(path: &Path) -> Result<Vec<u8>> {
    let shown = path.display();
    if path.extension().is_none_or(|extension| extension != "whl") {
        return std::fs::read(path)
            .with_context(|| format!("cannot read the viewray program {shown}"));
    }
    let file =
        std::fs::File::open(path).with_context(|| format!("cannot read the wheel {shown}"))?;
    let mut wheel =
        zip::ZipArchive::new(file).with_context(|| format!("{shown}: not a wheel (a zip file)"))?;
    let Some(name) = wheel
        .file_names()
        .find(|name| name.ends_with(".data/scripts/viewray"))
        .map(str::to_owned)
    else {
        bail!("{shown}: this wheel holds no viewray command (no *.data/scripts/viewray)");
    };
    let mut bytes = Vec::new();
    std::io::Read::read_to_end(
        &mut wheel
            .by_name(&name)
            .with_context(|| format!("{shown}: cannot read {name}"))?,
        &mut bytes,
    )
    .with_context(|| format!("{shown}: cannot read {name}"))?;
    Ok(bytes)
}

/// The assignment file (as `path` in the kit) and every input it names, under `prefix`.
fn assignment_files(assignment: &Assignment, path: &str, prefix: &str) -> Result<Vec<KitFile>> {
    let read = |from: &Path| {
        std::fs::read(from).with_context(|| format!("cannot read {}", from.display()))
    };
    let mut files = vec![KitFile {
        path: path.to_owned(),
        bytes: read(&assignment.path)?,
        executable: false,
    }];
    for input in assignment.inputs() {
        let mut stack = vec![PathBuf::from(&input)];
        while let Some(relative) = stack.pop() {
            let full = assignment.folder().join(&relative);
            let metadata = std::fs::symlink_metadata(&full)
                .with_context(|| format!("cannot read {}", full.display()))?;
            if metadata.is_dir() {
                let mut entries: Vec<PathBuf> = std::fs::read_dir(&full)
                    .with_context(|| format!("cannot read {}", full.display()))?
                    .filter_map(Result::ok)
                    .map(|e| relative.join(e.file_name()))
                    .collect();
                entries.sort();
                stack.extend(entries.into_iter().rev());
            } else if metadata.is_file() {
                files.push(KitFile {
                    path: format!("{prefix}{}", kit_path(&relative)),
                    bytes: read(&full)?,
                    executable: false,
                });
            }
        }
    }
    Ok(files)
}

/// A relative path with `/` between its parts, `.` parts dropped.
fn kit_path(path: &Path) -> String {
    path.components()
        .filter_map(|c| match c {
            std::path::Component::Normal(part) => Some(part.to_string_lossy().into_owned()),
            _ => None,
        })
        .collect::<Vec<_>>()
        .join("/")
}

/// Loads the kit's own copy of the assignment, so that what a scene reads and the kit
/// lacks is found now, not on the platform.
fn check_copy(files: &[KitFile], assignment: &str) -> Result<()> {
    let dir = tempfile::tempdir().context("cannot make a temporary folder")?;
    for file in files.iter().filter(|f| !f.executable) {
        let path = dir.path().join(&file.path);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)?;
        }
        std::fs::write(&path, &file.bytes)?;
    }
    load_assignment(&dir.path().join(assignment)).map_err(|error| {
        anyhow::anyhow!(
            "the kit's copy of the assignment does not load: {error} (a file a scene reads, \
             such as a mesh, goes in the assignment's `files: [..]`)"
        )
    })?;
    Ok(())
}

/// The newest `GLIBC_2.N` version the program asks for, read from its bytes (the
/// dynamic symbol versions); `None` for a program that asks for none.
fn glibc_needed(binary: &[u8]) -> Option<(u32, u32)> {
    let needle = b"GLIBC_2.";
    let mut newest = None;
    let mut at = 0;
    while let Some(found) = binary[at..].windows(needle.len()).position(|w| w == needle) {
        let start = at + found + needle.len();
        let digits: String = binary[start..]
            .iter()
            .take_while(|b| b.is_ascii_digit())
            .map(|&b| b as char)
            .collect();
        if let Ok(minor) = digits.parse::<u32>() {
            newest = newest.max(Some((2, minor)));
        }
        at = start;
    }
    newest
}

fn glibc_words(glibc: Option<(u32, u32)>) -> String {
    match glibc {
        Some((major, minor)) => format!(
            "It needs Linux on x86-64 with glibc {major}.{minor} or newer (Ubuntu 20.04 has \
             2.31, 22.04 has 2.35, 24.04 has 2.39)."
        ),
        None => "It asks for no particular glibc.".to_owned(),
    }
}

/// Which of the platform's base images the kit's viewray runs on.
fn image_words(glibc: Option<(u32, u32)>) -> String {
    match glibc {
        Some((major, minor)) if (major, minor) > OLDEST_IMAGE_GLIBC => format!(
            "a base image with glibc {major}.{minor} or newer (see below; Ubuntu 22.04 or \
             newer)"
        ),
        _ => "any of its Ubuntu base images (viewray runs on each, see below)".to_owned(),
    }
}

fn file_name(path: &Path) -> String {
    path.file_name().map_or_else(
        || "assignment.ron".to_owned(),
        |n| n.to_string_lossy().into_owned(),
    )
}

/// The scripts and the README of a Gradescope kit.
fn gradescope_files(
    assignment: &Assignment,
    name: &str,
    glibc: Option<(u32, u32)>,
) -> Vec<KitFile> {
    let run = include_str!("gradescope_run_autograder").replace("{{ASSIGNMENT}}", name);
    let setup = include_str!("gradescope_setup.sh");
    let readme = format!(
        "# {title}: the Gradescope autograder\n\n\
         Made by `viewray autograde kit {name} --for gradescope` ({version}).\n\n\
         ## What to upload\n\n\
         1. On Gradescope, create a Programming Assignment worth {max} points.\n\
         2. On its Configure Autograder page, choose {image}, and upload this zip file as \
            it is: \
            `setup.sh` and `run_autograder` must stay at the zip's root (to change a file, \
            unzip it, edit, and zip the files, not their folder).\n\
         3. If the students' programs need what the image lacks (a language, a library), add \
            its installation to `setup.sh`, where its comments say, and upload again.\n\
         4. Test the autograder with a submission of your own: each test shows its points, \
            the verdict on the camera with the formula line to fix, and for pictures the \
            expected picture, the student's and their difference.\n\n\
         ## What students submit\n\n{submission}\n\n\
         ## The tests\n\n{tests}\n\
         Tests that are `after_due_date` or `hidden` are hidden from students by Gradescope \
         until then (or for good); instructors always see them.\n\n\
         ## viewray on Gradescope\n\n\
         The zip carries viewray itself, one program (`bin/viewray`), so nothing is built or \
         downloaded when Gradescope builds the image, and every submission is judged by the \
         viewray that made this kit. {glibc}\n\n\
         ## Limits on students' programs\n\n{limits}\n",
        title = assignment.title,
        version = crate::cli::VERSION,
        max = points(assignment.max_score()),
        submission = submission_words(assignment),
        tests = tests_table(assignment),
        glibc = glibc_words(glibc),
        image = image_words(glibc),
        limits = limits_words(),
    );
    vec![
        KitFile {
            path: "run_autograder".to_owned(),
            bytes: run.into_bytes(),
            executable: true,
        },
        KitFile {
            path: "setup.sh".to_owned(),
            bytes: setup.as_bytes().to_vec(),
            executable: true,
        },
        KitFile {
            path: "README.md".to_owned(),
            bytes: readme.into_bytes(),
            executable: false,
        },
    ]
}

/// The workflow and the README of a GitHub Classroom kit.
fn github_files(assignment: &Assignment, name: &str, glibc: Option<(u32, u32)>) -> Vec<KitFile> {
    let mut steps = String::new();
    let mut env = String::new();
    let mut runners = Vec::new();
    for (k, test) in assignment.tests.iter().enumerate() {
        let id = format!("test{}", k + 1);
        steps.push_str(
            &include_str!("github_step.yml")
                .replace("{{NAME}}", &yaml_string(&test.name))
                .replace("{{ID}}", &id)
                .replace(
                    "{{ASSIGNMENT}}",
                    &viewray_autograde::sandbox::shell_quote(name),
                )
                .replace(
                    "{{TEST}}",
                    &viewray_autograde::sandbox::shell_quote(&test.name),
                ),
        );
        env.push_str(&format!(
            "          {}_RESULTS: \"${{{{steps.{id}.outputs.result}}}}\"\n",
            id.to_uppercase()
        ));
        runners.push(id);
    }
    let workflow = include_str!("github_workflow.yml")
        .replace("{{TITLE}}", &assignment.title.replace('\n', " "))
        .replace("{{STEPS}}", &steps)
        .replace("{{ENV}}", &env)
        .replace("{{RUNNERS}}", &runners.join(","))
        .replace("{{KIT}}", KIT_FOLDER);
    let readme = format!(
        "# {title}: GitHub Classroom autograding\n\n\
         Made by `viewray autograde kit {name} --for github` ({version}).\n\n\
         ## What to do\n\n\
         1. Copy `.github/workflows/classroom.yml` and this `{kit}/` folder into the \
            assignment's template repository, commit and push.\n\
         2. Create the GitHub Classroom assignment from that template repository, with \
            autograding on. The workflow runs on every push: one step per test runs \
            viewray (`{kit}/bin/viewray autograde ... --test NAME --format github`), which \
            writes the result object GitHub Classroom's autograding grader actions write, \
            with the points, partial credit included, and the diagnosis; the autograding \
            reporter action then reports the points, {max} in all, to GitHub Classroom.\n\
         3. Students read each test's verdict in the workflow's log.\n\n\
         ## What students submit\n\n{submission}\n\n\
         ## The tests\n\n{tests}\n\
         GitHub Classroom cannot hide a test: the scenes and references are in the \
         repository, and a test that is `after_due_date` or `hidden` only keeps its details \
         (the diagnosis, the pictures) out of the log; its points count.\n\n\
         ## viewray on GitHub's runners\n\n\
         `{kit}/bin/viewray` is viewray itself, one program, so the workflow builds and \
         downloads nothing. {glibc} GitHub's `ubuntu-latest` runner has 2.39.\n\n\
         ## Limits on students' programs\n\n{limits}\n",
        title = assignment.title,
        kit = KIT_FOLDER,
        version = crate::cli::VERSION,
        max = points(assignment.max_score()),
        submission = submission_words(assignment),
        tests = tests_table(assignment),
        glibc = glibc_words(glibc),
        limits = limits_words(),
    );
    vec![
        KitFile {
            path: ".github/workflows/classroom.yml".to_owned(),
            bytes: workflow.into_bytes(),
            executable: false,
        },
        KitFile {
            path: format!("{KIT_FOLDER}/README.md"),
            bytes: readme.into_bytes(),
            executable: false,
        },
    ]
}

/// A YAML double-quoted string (JSON's string syntax, which YAML reads).
fn yaml_string(text: &str) -> String {
    serde_json::to_string(text).expect("a string always serializes")
}

fn submission_words(assignment: &Assignment) -> String {
    match &assignment.run {
        Some(run) => format!(
            "Their program, which is run once per test as `{}` in a copy of their submission \
             (at most {} s per test), `{{scene}}` being the test's scene file and `{{output}}` \
             the file it must write: the picture (PNG or PPM) or the numbers (as `viewray \
             check` reads them) the test names below. A program that uses every second \
             runs {} s in all, plus viewray's own time: the platform's time limit for the \
             whole autograder must be longer, or the submission gets no results at all.",
            run.command,
            run.timeout_s,
            points(run.timeout_s * assignment.tests.len() as f64)
        ),
        None => {
            "These files, at the top of their submission (a picture may be PNG or PPM, \
                 under the same name with either extension):"
                .to_owned()
                + &assignment
                    .tests
                    .iter()
                    .map(|t| format!("\n- `{}`", t.hand_in.name()))
                    .collect::<String>()
        }
    }
}

fn tests_table(assignment: &Assignment) -> String {
    let mut table =
        "| test | scene | hands in | points | visibility |\n|---|---|---|---|---|\n".to_owned();
    for test in &assignment.tests {
        let hands_in = match &test.hand_in {
            HandIn::Image(name) => format!("picture `{name}`"),
            HandIn::Answers(name) => format!("answers `{name}`"),
        };
        let visibility = match test.visibility {
            Visibility::Visible => "visible",
            Visibility::AfterDueDate => "after_due_date",
            Visibility::Hidden => "hidden",
        };
        let mut points_text = points(test.points);
        if let Some(partial) = test.partial {
            points_text.push_str(&format!(
                " ({} with the camera right)",
                points(test.points * partial)
            ));
        }
        table.push_str(&format!(
            "| {} | `{}` | {hands_in} | {points_text} | {visibility} |\n",
            test.name, test.scene_path
        ));
    }
    table
}

fn limits_words() -> String {
    let limits = viewray_autograde::sandbox::Limits::default();
    format!(
        "Each run is stopped at the assignment's time limit with every process it started; \
         at most {} KiB of its output is kept; no file it writes may exceed {} MB, nor its \
         folders {} MB; it starts with an empty environment and no input. Where viewray \
         runs as root (Gradescope's run_autograder), the program runs as `nobody` \
         (`--run-as nobody`), who owns only the program's folders and can touch neither \
         viewray, the assignment nor the results; elsewhere it runs as viewray's user. The \
         platform's container keeps it from the rest of the machine: a program that leaves \
         its process group on purpose (setsid) outlives the time limit until the container \
         ends.",
        limits.output_bytes >> 10,
        limits.file_bytes >> 20,
        limits.folder_bytes >> 20
    )
}

/// Writes the files as a zip, atomically, programs with mode 755.
fn write_zip(files: &[KitFile], output: &Path) -> Result<()> {
    use zip::write::SimpleFileOptions;
    let mut bytes = std::io::Cursor::new(Vec::new());
    let mut zip = zip::ZipWriter::new(&mut bytes);
    for file in files {
        let options = SimpleFileOptions::default()
            .compression_method(zip::CompressionMethod::Deflated)
            .unix_permissions(if file.executable { 0o755 } else { 0o644 });
        zip.start_file(file.path.as_str(), options)
            .with_context(|| format!("cannot write {}", output.display()))?;
        zip.write_all(&file.bytes)?;
    }
    zip.finish()
        .with_context(|| format!("cannot write {}", output.display()))?;
    viewray_output::write_atomically(output, bytes.get_ref())?;
    Ok(())
}

/// Writes the files into the folder `output` (made if need be), each atomically.
fn write_folder(files: &[KitFile], output: &Path) -> Result<()> {
    if output.exists() && !output.is_dir() {
        bail!(
            "{} is not a folder: a GitHub kit is a folder of files",
            output.display()
        );
    }
    for file in files {
        let path = output.join(&file.path);
        if let Some(parent) = path.parent() {
            std::fs::create_dir_all(parent)
                .with_context(|| format!("cannot make {}", parent.display()))?;
        }
        viewray_output::write_atomically(&path, &file.bytes)?;
        if file.executable {
            use std::os::unix::fs::PermissionsExt;
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(0o755))?;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_readme_asks_for_a_newer_image_only_when_viewray_needs_one() {
        assert!(image_words(Some((2, 17))).starts_with("any of its Ubuntu base images"));
        assert!(image_words(Some((2, 31))).starts_with("any of its Ubuntu base images"));
        assert!(image_words(None).starts_with("any of its Ubuntu base images"));
        assert!(image_words(Some((2, 34))).starts_with("a base image with glibc 2.34 or newer"));
    }

    #[test]
    fn the_newest_glibc_asked_for_is_found() {
        let bytes = b"\0GLIBC_2.2.5\0GLIBC_2.34\0GLIBC_2.17\0GLIBC_PRIVATE\0GLIBC_2.\0";
        assert_eq!(glibc_needed(bytes), Some((2, 34)));
        assert_eq!(glibc_needed(b"#!/bin/sh\n"), None);
    }

    #[test]
    fn test_names_are_quoted_for_yaml() {
        assert_eq!(
            yaml_string("general: rays \"1\""),
            r#""general: rays \"1\"""#
        );
    }
}

//! `viewray autograde kit` as the platforms take it: the Gradescope zip unpacked into a
//! temporary folder laid out as Gradescope lays out /autograder, its setup.sh and
//! run_autograder run there for a student's Python program and for a broken one; and the
//! GitHub Classroom workflow's steps run as the workflow runs them, their results read by
//! the reporter's own decoding.

use std::io::Read as _;
use std::os::unix::fs::PermissionsExt as _;
use std::path::{Path, PathBuf};
use std::process::Command;

use serde_json::Value;

use crate::support;
use support::platforms::{check_gradescope, github_reporter};
use support::{command, repository};

fn homework() -> PathBuf {
    repository().join("fixtures/autograde/homework.ron")
}

/// Unpacks the zip at `zip` into `folder`, keeping each file's mode.
fn unzip(zip: &Path, folder: &Path) -> Vec<String> {
    let mut archive = zip::ZipArchive::new(std::fs::File::open(zip).unwrap()).unwrap();
    let mut names = Vec::new();
    for k in 0..archive.len() {
        let mut file = archive.by_index(k).unwrap();
        let path = folder.join(file.enclosed_name().unwrap());
        std::fs::create_dir_all(path.parent().unwrap()).unwrap();
        let mut bytes = Vec::new();
        file.read_to_end(&mut bytes).unwrap();
        std::fs::write(&path, bytes).unwrap();
        if let Some(mode) = file.unix_mode() {
            std::fs::set_permissions(&path, std::fs::Permissions::from_mode(mode & 0o777)).unwrap();
        }
        names.push(file.name().to_owned());
    }
    names
}

/// Gradescope's run for one submission: `/autograder` as `root`, the kit in `source`,
/// run_autograder copied beside it, the student's files in `submission`; returns
/// run_autograder's exit code and `results/results.json`.
fn gradescope_run(root: &Path, student_files: &[(&str, &str)]) -> (i32, Value) {
    let submission = root.join("submission");
    let _ = std::fs::remove_dir_all(&submission);
    let _ = std::fs::remove_dir_all(root.join("results"));
    std::fs::create_dir_all(&submission).unwrap();
    for (name, text) in student_files {
        std::fs::write(submission.join(name), text).unwrap();
    }
    let run = Command::new(root.join("run_autograder"))
        .current_dir(root)
        .env("AUTOGRADER_ROOT", root)
        .output()
        .unwrap();
    let results = std::fs::read(root.join("results/results.json")).unwrap();
    (
        run.status.code().unwrap(),
        serde_json::from_slice(&results).unwrap(),
    )
}

#[test]
fn gradescopes_run_autograder_grades_a_python_program_and_a_broken_one() {
    let dir = tempfile::tempdir().unwrap();
    let zip = dir.path().join("autograder.zip");
    let output = command()
        .args(["autograde", "kit"])
        .arg(homework())
        .args(["--for", "gradescope", "-o"])
        .arg(&zip)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    // As on Gradescope, where /autograder is open to the user the program runs as.
    std::fs::set_permissions(dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    let root = dir.path().join("autograder");
    let names = unzip(&zip, &root.join("source"));
    for name in [
        "setup.sh",
        "run_autograder",
        "README.md",
        "bin/viewray",
        "assignment/homework.ron",
        "assignment/scenes/shifted.ron",
    ] {
        assert!(
            names.iter().any(|n| n == name),
            "{name} is not in {names:?}"
        );
    }
    let readme = std::fs::read_to_string(root.join("source/README.md")).unwrap();
    assert!(
        readme.contains("create a Programming Assignment worth 14 points"),
        "{readme}"
    );
    assert!(readme.contains("upload this zip file as it is"));
    // Eight tests of at most 60 s each.
    assert!(readme.contains("runs 480 s in all"), "{readme}");

    // Gradescope builds the image: setup.sh, as root, once.
    let setup = Command::new("bash")
        .arg(root.join("source/setup.sh"))
        .env("AUTOGRADER_ROOT", &root)
        .output()
        .unwrap();
    assert!(
        setup.status.success(),
        "{}",
        String::from_utf8_lossy(&setup.stderr)
    );
    assert!(String::from_utf8_lossy(&setup.stdout).starts_with("viewray "));
    std::fs::copy(
        root.join("source/run_autograder"),
        root.join("run_autograder"),
    )
    .unwrap();

    let program =
        std::fs::read_to_string(repository().join("fixtures/autograde/student/raytracer.py"))
            .unwrap();
    let (code, results) = gradescope_run(&root, &[("raytracer.py", &program)]);
    assert_eq!(code, 0);
    check_gradescope(&results).unwrap();
    assert_eq!(results["score"], 14.0);
    let tests = results["tests"].as_array().unwrap();
    assert_eq!(tests.len(), 8);
    assert!(tests.iter().all(|t| t["status"] == "passed"), "{results:#}");

    // A program that does not run: every test fails with Python's own words, and the
    // results are still Gradescope's.
    let broken = program.replacen("def main():", "def main()", 1);
    let (code, results) = gradescope_run(&root, &[("raytracer.py", &broken)]);
    assert_eq!(code, 0, "a failed submission is a graded one");
    check_gradescope(&results).unwrap();
    assert_eq!(results["score"], 0.0);
    for test in results["tests"].as_array().unwrap() {
        assert_eq!(test["status"], "failed");
        if test["visibility"] == "visible" {
            let output = test["output"].as_str().unwrap();
            assert!(
                output.contains("your program exited with code 1"),
                "{output}"
            );
            assert!(output.contains("SyntaxError"), "{output}");
        }
    }

    // Nothing handed in at all.
    let (code, results) = gradescope_run(&root, &[("notes.txt", "I ran out of time")]);
    assert_eq!(code, 0);
    check_gradescope(&results).unwrap();
    assert_eq!(results["score"], 0.0);

    // A program that reaches for the results and the kit: run as root (as Gradescope
    // runs the autograder), run_autograder runs it as `nobody`, who may write neither.
    let cheat = "import os, sys\n\
        root = os.path.abspath(sys.argv[1])\n\
        for _ in range(4):\n    root = os.path.dirname(root)\n\
        for target in ('results/marker', 'source/marker'):\n\
        \x20   try:\n        open(os.path.join(root, target), 'w').write('cheat')\n\
        \x20   except OSError:\n        pass\n";
    let (code, results) = gradescope_run(&root, &[("raytracer.py", cheat)]);
    assert_eq!(code, 0);
    check_gradescope(&results).unwrap();
    assert_eq!(results["score"], 0.0);
    // It ran to its end (no Python error), having written no picture.
    let output = results["tests"][0]["output"].as_str().unwrap();
    assert!(
        output.contains("your program ended without writing `canonical.png`"),
        "{output}"
    );
    if running_as_root() {
        assert!(!root.join("results/marker").exists());
        assert!(!root.join("source/marker").exists());
    }
}

/// Whether the tests run as root (as Gradescope runs run_autograder).
fn running_as_root() -> bool {
    std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("Uid:"))
        .and_then(|ids| ids.split_whitespace().nth(1))
        == Some("0")
}

#[test]
fn the_github_kit_is_a_workflow_whose_steps_the_reporter_reads() {
    let dir = tempfile::tempdir().unwrap();
    let template = dir.path().join("template");
    let output = command()
        .args(["autograde", "kit"])
        .arg(homework())
        .args(["--for", "github", "-o"])
        .arg(&template)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let workflow =
        std::fs::read_to_string(template.join(".github/workflows/classroom.yml")).unwrap();
    assert!(workflow.contains("uses: classroom-resources/autograding-grading-reporter@v1"));
    assert!(workflow.contains("runners: test1,test2,test3,test4,test5,test6,test7,test8"));
    assert!(workflow.contains("TEST8_RESULTS: \"${{steps.test8.outputs.result}}\""));
    let viewray = template.join(".viewray/bin/viewray");
    assert!(std::fs::metadata(&viewray).unwrap().permissions().mode() & 0o111 != 0);
    assert!(template.join(".viewray/homework.ron").is_file());
    assert!(template.join(".viewray/README.md").is_file());

    // The student's repository: the template with their program at its root. Each step
    // runs as the workflow writes it, from the repository's root.
    let repo = template;
    std::fs::copy(
        repository().join("fixtures/autograde/student/raytracer.py"),
        repo.join("raytracer.py"),
    )
    .unwrap();
    let runner_temp = dir.path().join("runner-temp");
    std::fs::create_dir(&runner_temp).unwrap();
    let mut steps = Vec::new();
    for (k, step) in workflow.split("      - name: ").skip(1).enumerate() {
        let Some(run) = step.split("run: |\n").nth(1) else {
            continue;
        };
        let script: String = run
            .lines()
            .take_while(|l| l.starts_with("          "))
            .map(|l| format!("{}\n", l.trim_start()))
            .collect();
        let github_output = dir.path().join(format!("output{k}"));
        let run = Command::new("bash")
            .args(["-e", "-c", &script])
            .current_dir(&repo)
            .env("RUNNER_TEMP", &runner_temp)
            .env("GITHUB_OUTPUT", &github_output)
            .output()
            .unwrap();
        assert!(run.status.success(), "{script}");
        let written = std::fs::read_to_string(&github_output).unwrap();
        let result = written.trim().strip_prefix("result=").unwrap().to_owned();
        steps.push((format!("test{}", steps.len() + 1), result));
    }
    assert_eq!(steps.len(), 8);
    let pairs: Vec<(&str, &str)> = steps
        .iter()
        .map(|(a, b)| (a.as_str(), b.as_str()))
        .collect();
    let reported = github_reporter(&pairs);
    assert_eq!((reported.total_points, reported.max_points), (14.0, 14.0));
    assert_eq!(reported.failed, None);
}

/// A wheel as `cargo xtask wheel` lays one out, holding `command` as its script.
fn wheel_with(path: &Path, command: Option<&[u8]>) {
    use std::io::Write as _;
    use zip::write::SimpleFileOptions;
    let mut wheel = zip::ZipWriter::new(std::fs::File::create(path).unwrap());
    let options = SimpleFileOptions::default();
    wheel.start_file("viewray/__init__.py", options).unwrap();
    wheel.write_all(b"from .viewray import *\n").unwrap();
    if let Some(command) = command {
        wheel
            .start_file("viewray-0.1.0.data/scripts/viewray", options)
            .unwrap();
        wheel.write_all(command).unwrap();
    }
    wheel.finish().unwrap();
}

#[test]
fn a_kit_takes_viewray_from_a_wheel() {
    let dir = tempfile::tempdir().unwrap();
    // The test binary stands for the wheel's command: what matters is that the kit
    // carries exactly the script's bytes.
    let program = std::fs::read(env!("CARGO_BIN_EXE_viewray")).unwrap();
    let wheel = dir
        .path()
        .join("viewray-0.1.0-cp39-abi3-manylinux2014_x86_64.whl");
    wheel_with(&wheel, Some(&program));
    let zip = dir.path().join("autograder.zip");
    let output = command()
        .args(["autograde", "kit"])
        .arg(homework())
        .args(["--for", "gradescope", "--viewray"])
        .arg(&wheel)
        .arg("-o")
        .arg(&zip)
        .output()
        .unwrap();
    assert!(
        output.status.success(),
        "{}",
        String::from_utf8_lossy(&output.stderr)
    );
    let unpacked = dir.path().join("kit");
    unzip(&zip, &unpacked);
    let carried = std::fs::read(unpacked.join("bin/viewray")).unwrap();
    assert!(
        carried == program,
        "the kit's bin/viewray is not the wheel's command"
    );

    // A wheel without the command is refused in one line, and no kit is written.
    let empty = dir.path().join("viewray-module-only.whl");
    wheel_with(&empty, None);
    let refused = dir.path().join("refused.zip");
    let output = command()
        .args(["autograde", "kit"])
        .arg(homework())
        .args(["--for", "gradescope", "--viewray"])
        .arg(&empty)
        .arg("-o")
        .arg(&refused)
        .output()
        .unwrap();
    assert_eq!(output.status.code(), Some(2));
    let stderr = String::from_utf8_lossy(&output.stderr);
    assert_eq!(stderr.lines().count(), 1, "{stderr}");
    assert!(stderr.contains("holds no viewray command"), "{stderr}");
    assert!(!refused.exists());
}

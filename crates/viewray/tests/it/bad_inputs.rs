//! Hostile and broken inputs through the real binary: every file in `fixtures/bad/` gets
//! one `error:` line and exit code 2, never a panic, and no output file; Ctrl-C during a
//! render leaves the previous output as it was.

use std::path::{Path, PathBuf};
use std::process::Command;

use crate::support;
use support::command as viewray;

fn bad_scenes() -> Vec<PathBuf> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("../../fixtures/bad");
    let mut paths: Vec<PathBuf> = std::fs::read_dir(dir)
        .unwrap()
        .map(|entry| entry.unwrap().path())
        .filter(|path| path.extension().is_some_and(|e| e == "ron"))
        .collect();
    paths.sort();
    paths
}

fn files_in(dir: &Path) -> Vec<String> {
    std::fs::read_dir(dir)
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect()
}

#[test]
fn every_bad_scene_fails_with_one_line_and_no_output() {
    let scenes = bad_scenes();
    assert!(scenes.len() >= 30, "expected a bad file per error kind");
    for scene in scenes {
        let out_dir = tempfile::tempdir().unwrap();
        let output = out_dir.path().join("out.png");
        for args in [
            vec![
                "render".as_ref(),
                scene.as_os_str(),
                "-o".as_ref(),
                output.as_os_str(),
            ],
            vec![
                "rays".as_ref(),
                scene.as_os_str(),
                "--pixel".as_ref(),
                "0,0".as_ref(),
            ],
            vec![
                "trace".as_ref(),
                scene.as_os_str(),
                "--pixel".as_ref(),
                "0,0".as_ref(),
            ],
        ] {
            let result = viewray().args(&args).output().unwrap();
            let stderr = String::from_utf8_lossy(&result.stderr);
            let name = scene.file_name().unwrap().to_string_lossy();
            assert_eq!(result.status.code(), Some(2), "{name}: {stderr}");
            assert_eq!(stderr.lines().count(), 1, "{name}: not one line: {stderr}");
            assert!(stderr.starts_with("error: "), "{name}: {stderr}");
            assert!(!stderr.contains("panicked"), "{name}: {stderr}");
            assert!(result.stdout.is_empty(), "{name} printed to stdout");
            assert_eq!(
                files_in(out_dir.path()),
                Vec::<String>::new(),
                "{name} left files"
            );
        }
    }
}

#[cfg(unix)]
#[test]
fn ctrl_c_during_a_render_keeps_the_previous_image() {
    use std::io::Read as _;
    let dir = tempfile::tempdir().unwrap();
    let output = dir.path().join("picture.png");
    std::fs::write(&output, b"the previous picture").unwrap();
    // The default scene, large and with many samples: seconds of work at least.
    let mut child = viewray()
        .args(["render", "-o"])
        .arg(&output)
        .args(["--size", "1600x1200", "--samples", "256"])
        .stderr(std::process::Stdio::piped())
        .spawn()
        .unwrap();
    // The render installs its Ctrl-C handler before it creates its temporary file, so
    // once that file exists an interrupt is handled: no sleep, no race.
    let started = std::time::Instant::now();
    while files_in(dir.path()).len() < 2 {
        assert!(started.elapsed().as_secs() < 60, "the render never started");
        std::thread::sleep(std::time::Duration::from_millis(5));
    }
    let killed = Command::new("kill")
        .args(["-INT", &child.id().to_string()])
        .status()
        .unwrap();
    assert!(killed.success());
    let status = child.wait().unwrap();
    let mut stderr = String::new();
    child
        .stderr
        .take()
        .unwrap()
        .read_to_string(&mut stderr)
        .unwrap();
    assert_eq!(status.code(), Some(130), "{status:?}: {stderr}");
    assert_eq!(
        stderr,
        format!("interrupted: {} was not written\n", output.display())
    );
    assert_eq!(std::fs::read(&output).unwrap(), b"the previous picture");
    assert_eq!(files_in(dir.path()), ["picture.png"]);
}

#[test]
fn an_unwritable_output_is_named_as_given_never_by_its_temporary_file() {
    let dir = tempfile::tempdir().unwrap();
    let file = dir.path().join("file.txt");
    std::fs::write(&file, "").unwrap();
    let output = file.join("out.png");
    let output = output.to_str().unwrap();
    for args in [
        ["render", "-o", output].as_slice(),
        ["figure", "taxonomy", "-o", output].as_slice(),
    ] {
        let line = support::error_line(args);
        assert_eq!(
            line,
            format!("error: cannot write {output}: Not a directory (os error 20)"),
            "{args:?}"
        );
    }
    assert_eq!(files_in(dir.path()), ["file.txt"]);
}

//! Students' programs are untrusted: one test per way a program can misbehave (hang,
//! fork children, print megabytes, write a 10 GB file, write a PNG bomb, write outside
//! its folder, link its output to /etc/passwd, exit non-zero), each failing only its test
//! with a clear message, and the whole submission still graded.

use std::path::{Path, PathBuf};
use std::time::{Duration, Instant};

use viewray_autograde::sandbox::Limits;
use viewray_autograde::{Options, Results, Status, TestResult, grade};

/// The lecture's canonical camera on a 2 x 2 image, d = 1, a 1 x 1 viewport: pixel
/// (0, 0) has u = ((0 + 1/2)/2 - 1/2) 1 = -1/4 and v = 1/4, so its ray is the origin and
/// the direction (-1/4, 1/4, -1).
const CANONICAL: &str = "(image: (width: 2, height: 2), camera: (eye: (0.0, 0.0, 0.0), \
     view: (0.0, 0.0, -1.0), up: (0.0, 1.0, 0.0), \
     projection: Perspective(distance: 1.0, viewport: (1.0, 1.0))))";
/// The right answer for [`CANONICAL`], worked above.
const RIGHT: &str = "ray 0 0  0 0 0  -0.25 0.25 -1";

/// A sphere in front of a canonical camera, 32 x 24 pixels: something for a picture's
/// camera to be judged by.
const SPHERE: &str = "(image: (width: 32, height: 24, samples: 4), camera: (eye: (0.0, 0.0, 3.0), \
     look_at: (0.0, 0.0, 0.0), up: (0.0, 1.0, 0.0), \
     projection: Perspective(distance: 1.0, viewport: (1.0, 0.75))), \
     objects: [Sphere(center: (0.0, 0.0, 0.0), radius: 0.6)])";

/// An assignment folder with the two scenes, a submission folder, and a scratch folder.
struct Course {
    dir: tempfile::TempDir,
}

impl Course {
    fn new() -> Course {
        let dir = tempfile::tempdir().unwrap();
        std::fs::create_dir_all(dir.path().join("assignment/scenes")).unwrap();
        std::fs::create_dir_all(dir.path().join("submission")).unwrap();
        std::fs::create_dir_all(dir.path().join("scratch")).unwrap();
        std::fs::write(
            dir.path().join("assignment/scenes/canonical.ron"),
            CANONICAL,
        )
        .unwrap();
        std::fs::write(dir.path().join("assignment/scenes/sphere.ron"), SPHERE).unwrap();
        Course { dir }
    }

    fn path(&self, name: &str) -> PathBuf {
        self.dir.path().join(name)
    }

    /// An assignment whose one test, `answers` of the canonical camera, is made by
    /// `command` within `timeout_s`, plus a second test the program passes, so that one
    /// test's failure is seen not to spoil the other's.
    fn assignment(&self, command: &str, timeout_s: f64) -> PathBuf {
        let text = format!(
            r#"(
  title: "Untrusted",
  run: Some((command: {command:?}, timeout_s: {timeout_s})),
  tests: [
    (name: "misbehaving", scene: "scenes/canonical.ron", answers: "rays.txt", points: 1.0),
    (name: "after it", scene: "scenes/canonical.ron", answers: "again.txt", points: 2.0),
  ],
)"#
        );
        let path = self.path("assignment/hw.ron");
        std::fs::write(&path, text).unwrap();
        path
    }

    fn options(&self, limits: Limits) -> Options {
        Options {
            limits,
            scratch_in: Some(self.path("scratch")),
            ..Options::default()
        }
    }

    fn grade(&self, assignment: &Path, limits: Limits) -> Results {
        let results = grade(assignment, &self.path("submission"), &self.options(limits));
        assert_eq!(results.problem, None, "{}", results.summary());
        // Whatever the program did, its scratch folder is gone afterwards.
        assert_eq!(std::fs::read_dir(self.path("scratch")).unwrap().count(), 0);
        results
    }
}

/// A command that misbehaves in the first test (its output is `rays.txt`) and answers
/// right in the second: `case "$1"` picks which.
fn program(misbehaviour: &str) -> String {
    format!(
        "case {{output}} in *rays.txt) {misbehaviour} ;; *) echo '{RIGHT}' > {{output}} ;; esac"
    )
}

#[track_caller]
fn failed_with<'a>(results: &'a Results, words: &str) -> &'a TestResult {
    let test = &results.tests[0];
    assert_eq!(test.status, Status::Failed, "{test:#?}");
    assert_eq!(test.score, 0.0);
    assert!(
        test.message.contains(words),
        "{:?} lacks {words:?}",
        test.message
    );
    let after = &results.tests[1];
    assert_eq!(
        after.status,
        Status::Passed,
        "the next test still passes: {after:#?}"
    );
    assert_eq!(results.score(), 2.0);
    test
}

#[test]
fn a_right_program_passes_and_its_printout_is_not_needed() {
    let course = Course::new();
    let assignment = course.assignment(
        &program(&format!("echo hello; echo '{RIGHT}' > {{output}}")),
        10.0,
    );
    let results = course.grade(&assignment, Limits::default());
    assert!(results.all_passed(), "{results:#?}");
    assert_eq!(results.score(), 3.0);
    assert!(
        results.tests[0]
            .output
            .contains("your program's standard output:\nhello")
    );
}

#[test]
fn a_program_that_hangs_is_stopped_at_the_time_limit() {
    let course = Course::new();
    // It sleeps forever: only the time limit ends it. The limit (5 s) is generous for
    // the other test's program, which answers at once.
    let assignment = course.assignment(&program("while :; do sleep 1; done"), 5.0);
    let results = course.grade(&assignment, Limits::default());
    failed_with(
        &results,
        "ran longer than the time limit of 5 s and was stopped, with every process it started",
    );
}

/// Whether process `pid` still runs (a zombie waiting for its parent does not).
fn running(pid: i32) -> bool {
    std::fs::read_to_string(format!("/proc/{pid}/stat")).is_ok_and(|stat| {
        !stat
            .rsplit(')')
            .next()
            .unwrap_or("")
            .trim_start()
            .starts_with('Z')
    })
}

#[test]
fn children_are_killed_with_the_program_at_the_limit_and_when_it_ends() {
    let course = Course::new();
    let pids = course.path("pids");
    std::fs::create_dir(&pids).unwrap();
    // The first test's program forks a child that forks a grandchild, and hangs; the
    // second's leaves a child behind and exits at once.
    let command = format!(
        "case {{output}} in *rays.txt) (sleep 300 & echo $! > {p}/grandchild; sleep 300) & echo $! > {p}/child; sleep 300 ;; \
         *) sleep 300 & echo $! > {p}/left; echo '{RIGHT}' > {{output}} ;; esac",
        p = pids.display()
    );
    let assignment = course.assignment(&command, 5.0);
    let results = course.grade(&assignment, Limits::default());
    failed_with(&results, "ran longer than the time limit");
    for name in ["child", "grandchild", "left"] {
        let pid: i32 = std::fs::read_to_string(pids.join(name))
            .unwrap()
            .trim()
            .parse()
            .unwrap();
        // SIGKILL was sent to the group; a process takes a moment to end once it is
        // scheduled. Left alive, each would sleep 300 s: a minute tells them apart.
        let sent = Instant::now();
        while running(pid) && sent.elapsed() < Duration::from_secs(60) {
            std::thread::sleep(Duration::from_millis(20));
        }
        assert!(!running(pid), "the {name} ({pid}) still runs");
    }
}

#[test]
fn megabytes_of_output_are_capped() {
    let course = Course::new();
    let assignment = course.assignment(
        &program("head -c 50000000 /dev/zero | tr '\\0' x; exit 1"),
        20.0,
    );
    let limits = Limits {
        output_bytes: 1000,
        ..Limits::default()
    };
    let results = course.grade(&assignment, limits);
    let test = failed_with(&results, "your program exited with code 1");
    assert!(test.output.contains(&format!(
        "{}\n[... 49999000 more bytes not kept]",
        "x".repeat(1000)
    )));
    assert!(test.output.len() < 2000, "{}", test.output.len());
}

#[test]
fn a_10_gb_file_is_stopped_at_the_file_size_limit() {
    let course = Course::new();
    let assignment = course.assignment(&program("head -c 10000000000 /dev/zero > big.bin"), 20.0);
    let limits = Limits {
        file_bytes: 1 << 20,
        ..Limits::default()
    };
    let started = Instant::now();
    let results = course.grade(&assignment, limits);
    assert!(started.elapsed() < Duration::from_secs(15));
    failed_with(
        &results,
        "your program wrote a file larger than 1 MB and was stopped (SIGXFSZ)",
    );
}

#[test]
fn many_files_that_fill_its_folder_stop_it() {
    let course = Course::new();
    let assignment = course.assignment(
        &program("i=0; while [ $i -lt 50 ]; do head -c 500000 /dev/zero > f$i; i=$((i+1)); done; sleep 30"),
        20.0,
    );
    let limits = Limits {
        folder_bytes: 4 << 20,
        ..Limits::default()
    };
    let results = course.grade(&assignment, limits);
    failed_with(
        &results,
        "your program's folders grew past 4 MB and it was stopped",
    );
}

#[test]
fn a_program_that_exits_non_zero_fails_its_test_with_what_it_printed() {
    let course = Course::new();
    let assignment = course.assignment(&program("echo 'Traceback: oops' >&2; exit 3"), 10.0);
    let results = course.grade(&assignment, Limits::default());
    let test = failed_with(&results, "your program exited with code 3");
    assert!(
        test.output
            .contains("your program's standard error:\nTraceback: oops"),
        "{}",
        test.output
    );
}

#[test]
fn a_program_that_writes_nothing_is_told_what_was_expected() {
    let course = Course::new();
    let assignment = course.assignment(&program("true"), 10.0);
    let results = course.grade(&assignment, Limits::default());
    failed_with(
        &results,
        "your program ended without writing `rays.txt` ({output})",
    );
}

#[test]
fn a_write_outside_its_folder_fails_and_never_reaches_the_submission() {
    let course = Course::new();
    std::fs::write(course.path("submission/main.sh"), "echo").unwrap();
    let assignment = course.assignment(
        &program(&format!(
            "echo x > ../escaped.txt; echo '{RIGHT}' > {{output}}"
        )),
        10.0,
    );
    let results = course.grade(&assignment, Limits::default());
    failed_with(
        &results,
        "your program wrote outside its folder: `../escaped.txt`",
    );
    let submission: Vec<_> = std::fs::read_dir(course.path("submission"))
        .unwrap()
        .collect();
    assert_eq!(
        submission.len(),
        1,
        "the submission folder is left as it was"
    );
}

#[test]
fn an_output_linked_to_etc_passwd_is_not_followed() {
    let course = Course::new();
    let assignment = course.assignment(&program("ln -s /etc/passwd {output}"), 10.0);
    let results = course.grade(&assignment, Limits::default());
    let test = failed_with(
        &results,
        "`rays.txt` is a symbolic link: links are not followed",
    );
    assert!(!test.output.contains("root:"));
}

#[test]
fn a_handed_in_link_to_etc_passwd_is_not_followed() {
    let course = Course::new();
    std::fs::write(
        course.path("assignment/hw.ron"),
        r#"(title: "Files", tests: [
            (name: "linked", scene: "scenes/canonical.ron", answers: "rays.txt", points: 1.0),
            (name: "after it", scene: "scenes/canonical.ron", answers: "again.txt", points: 2.0),
        ])"#,
    )
    .unwrap();
    std::os::unix::fs::symlink("/etc/passwd", course.path("submission/rays.txt")).unwrap();
    std::fs::write(course.path("submission/again.txt"), RIGHT).unwrap();
    let results = course.grade(&course.path("assignment/hw.ron"), Limits::default());
    failed_with(
        &results,
        "`rays.txt` is a symbolic link: links are not followed (hand in the file itself)",
    );
}

#[test]
fn a_submission_link_is_left_out_of_the_copy_the_program_runs_in() {
    let course = Course::new();
    std::os::unix::fs::symlink("/etc/passwd", course.path("submission/passwd")).unwrap();
    let assignment = course.assignment(&program("cat passwd > {output}"), 10.0);
    let results = course.grade(&assignment, Limits::default());
    failed_with(&results, "your program exited with code 1");
    assert_eq!(
        results.notes,
        [
            "left out of the copy your program runs in (symbolic links and special files are not \
          followed): passwd"
        ]
    );
}

#[test]
fn a_png_bomb_is_refused_unread() {
    let course = Course::new();
    // A PNG that claims 100 000 x 100 000 pixels, 40 GB once decoded (a real bomb's
    // zlib stream of zeros would fit in 40 MB; a few bytes of it do here, since its
    // header is all that is read).
    let mut bomb = b"\x89PNG\r\n\x1a\n".to_vec();
    let mut header = 100_000_u32.to_be_bytes().to_vec();
    header.extend_from_slice(&100_000_u32.to_be_bytes());
    header.extend_from_slice(&[8, 2, 0, 0, 0]);
    chunk(&mut bomb, b"IHDR", &header);
    // zlib: a stored deflate block of 1000 zeros and its Adler-32.
    let mut zlib = vec![0x78, 0x01, 0x01, 0xe8, 0x03, 0x17, 0xfc];
    zlib.extend_from_slice(&[0; 1000]);
    zlib.extend_from_slice(&((1000_u32 << 16) | 1).to_be_bytes());
    chunk(&mut bomb, b"IDAT", &zlib);
    chunk(&mut bomb, b"IEND", &[]);
    std::fs::write(course.path("submission/bomb.png"), &bomb).unwrap();
    std::fs::write(
        course.path("assignment/hw.ron"),
        r#"(title: "Pictures", run: Some((command: "cp bomb.png {output}", timeout_s: 10)), tests: [
            (name: "bomb", scene: "scenes/sphere.ron", image: "sphere.png", points: 1.0),
        ])"#,
    )
    .unwrap();
    let results = course.grade(&course.path("assignment/hw.ron"), Limits::default());
    let test = &results.tests[0];
    assert_eq!(test.status, Status::Failed);
    assert_eq!(
        test.message,
        "`sphere.png` is 100000x100000 pixels, but the scene's image is 32x24"
    );
    // The reference is still shown, so the student sees what was expected.
    assert_eq!(
        test.images
            .iter()
            .map(|i| i.label.as_str())
            .collect::<Vec<_>>(),
        ["expected"]
    );
}

/// Appends a PNG chunk: length, type, data, CRC of type and data.
fn chunk(png: &mut Vec<u8>, kind: &[u8; 4], data: &[u8]) {
    png.extend_from_slice(&(data.len() as u32).to_be_bytes());
    let start = png.len();
    png.extend_from_slice(kind);
    png.extend_from_slice(data);
    let crc = crc32(&png[start..]);
    png.extend_from_slice(&crc.to_be_bytes());
}

/// PNG's CRC-32 (ISO 3309), bit by bit.
fn crc32(bytes: &[u8]) -> u32 {
    let mut crc = u32::MAX;
    for &byte in bytes {
        crc ^= u32::from(byte);
        for _ in 0..8 {
            crc = if crc & 1 == 1 {
                (crc >> 1) ^ 0xEDB8_8320
            } else {
                crc >> 1
            };
        }
    }
    !crc
}

#[test]
fn a_program_run_as_another_user_can_touch_only_its_folders() {
    let course = Course::new();
    // The user must be able to pass through the course's folders to its own.
    use std::os::unix::fs::PermissionsExt as _;
    std::fs::set_permissions(course.dir.path(), std::fs::Permissions::from_mode(0o755)).unwrap();
    let scene = course.path("assignment/scenes/canonical.ron");
    let before = std::fs::read(&scene).unwrap();
    // It answers right only if it is `nobody` and can neither change the assignment nor
    // write beside its folder.
    let command = format!(
        "if [ \"$(id -un)\" = nobody ] && ! touch {{scene}} 2>/dev/null && \
         ! (echo x > ../escaped.txt) 2>/dev/null; then echo '{RIGHT}' > {{output}}; else exit 9; fi"
    );
    let assignment = course.assignment(&command, 10.0);
    let options = Options {
        run_as: Some("nobody".to_owned()),
        ..course.options(Limits::default())
    };
    let results = grade(&assignment, &course.path("submission"), &options);
    if !running_as_root() {
        // Only root may become another user: the submission is not graded, and says why.
        let problem = results.problem.expect("not graded");
        assert!(
            problem.contains("only when viewray runs as root"),
            "{problem}"
        );
        return;
    }
    assert!(results.all_passed(), "{results:#?}");
    assert_eq!(std::fs::read(&scene).unwrap(), before);
    let scratch: Vec<_> = std::fs::read_dir(course.path("scratch")).unwrap().collect();
    assert!(
        scratch.is_empty(),
        "the scratch folder is removed: {scratch:?}"
    );
}

/// Whether these tests run as root (the only user who may run a program as another).
fn running_as_root() -> bool {
    std::fs::read_to_string("/proc/self/status")
        .unwrap()
        .lines()
        .find_map(|l| l.strip_prefix("Uid:"))
        .and_then(|ids| ids.split_whitespace().nth(1))
        == Some("0")
}

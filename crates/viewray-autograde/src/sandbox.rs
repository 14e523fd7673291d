//! Running a student's program with limits, as far as one process can without a container.
//!
//! What is enforced, on Linux and any Unix:
//! - **time**: the program runs in a process group of its own (`setpgid` at spawn, from
//!   std); at the time limit the whole group is killed (`killpg`, `SIGKILL`), children
//!   and grandchildren included, and after the program ends its group is killed too, so
//!   no child it left behind runs on;
//! - **output**: standard output and error are read as they come and at most
//!   [`Limits::output_bytes`] of each are kept (the rest is counted, not stored, and never
//!   blocks the program); answers taken from standard output are kept up to
//!   [`Limits::answers_bytes`];
//! - **file size**: every file the program writes, anywhere, is capped by
//!   `RLIMIT_FSIZE` (`ulimit -f` in the shell that starts it); a write beyond it ends the
//!   program with `SIGXFSZ`;
//! - **its folders**: the folder it runs in and its output folder are measured while it
//!   runs, and it is killed when they hold more than [`Limits::folder_bytes`] or more
//!   than [`Limits::folder_entries`] files;
//! - **environment**: it starts with an empty environment but `PATH`, `HOME` and `TMPDIR`
//!   (both in the scratch folder) and `LANG`, so no token of the platform reaches it,
//!   and with no standard input;
//! - **user**: when viewray runs as root (Gradescope runs its autograder as root), it
//!   can run the program as another user ([`RunAs`], `--run-as nobody`), which owns only
//!   the program's folders: it can then neither write beside them nor touch viewray, the
//!   assignment or the results, nor signal viewray.
//!
//! What is not prevented without a container (which every platform runs a submission
//! in): without [`RunAs`] the program runs as the same user as viewray, so it can read
//! and write whatever that user can (a write outside its folders is not undone, though it
//! is capped in size); it can use the network where the platform allows it; memory is not capped here
//! (interpreters and JITs reserve more address space than they use, so `RLIMIT_AS` would
//! break them: the platform's container caps memory); and a process that leaves its
//! group on purpose (`setsid`) escapes the group's kill, though not the container's end.

use std::io::{Read, Write};
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Stdio};
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};
use std::thread::JoinHandle;
use std::time::{Duration, Instant};

use nix::sys::signal::{Signal, killpg};
use nix::unistd::Pid;

use crate::files::folder_size;

/// The limits a student's program runs under.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Limits {
    /// The time limit of one run.
    pub timeout: Duration,
    /// How much of standard output and of standard error is kept for the results.
    pub output_bytes: u64,
    /// How much standard output is kept when it is the answers.
    pub answers_bytes: u64,
    /// The largest file the program may write (`RLIMIT_FSIZE`).
    pub file_bytes: u64,
    /// The most its folders may hold.
    pub folder_bytes: u64,
    /// The most files and folders its folders may hold.
    pub folder_entries: u64,
}

impl Default for Limits {
    /// 30 s, 64 KiB of output, 64 MiB of answers, files of 256 MiB, folders of 1 GiB
    /// and 20 000 entries.
    fn default() -> Self {
        Limits {
            timeout: Duration::from_secs(30),
            output_bytes: 64 << 10,
            answers_bytes: 64 << 20,
            file_bytes: 256 << 20,
            folder_bytes: 1 << 30,
            folder_entries: 20_000,
        }
    }
}

/// The user a program runs as, instead of viewray's own (which must then be root).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct RunAs {
    /// Its user id.
    pub uid: u32,
    /// Its group id (its only group).
    pub gid: u32,
}

impl RunAs {
    /// The user named `name` in the system's user database, checked usable: viewray is
    /// root, or already that user.
    ///
    /// # Errors
    /// No such user, or viewray may not become it: a sentence.
    pub fn user(name: &str) -> Result<RunAs, String> {
        let user = nix::unistd::User::from_name(name)
            .map_err(|e| format!("cannot look up the user `{name}`: {e}"))?
            .ok_or_else(|| format!("there is no user `{name}` to run the program as"))?;
        let me = nix::unistd::geteuid();
        if !me.is_root() && me != user.uid {
            return Err(format!(
                "the program can run as `{name}` only when viewray runs as root"
            ));
        }
        Ok(RunAs {
            uid: user.uid.as_raw(),
            gid: user.gid.as_raw(),
        })
    }

    /// Gives `path` (not following a link) to this user.
    ///
    /// # Errors
    /// The change of owner fails: a sentence.
    pub fn give(&self, path: &Path) -> Result<(), String> {
        std::os::unix::fs::lchown(path, Some(self.uid), Some(self.gid)).map_err(|e| {
            format!(
                "cannot give `{}` to the program's user: {e}",
                path.display()
            )
        })
    }
}

/// A program to run.
#[derive(Clone, Debug)]
pub struct Program<'a> {
    /// The shell command (the assignment's, with `{scene}` and `{output}` substituted).
    pub command: &'a str,
    /// The folder it runs in (a copy of the submission).
    pub folder: &'a Path,
    /// The folders measured while it runs ([`Limits::folder_bytes`]).
    pub watched: &'a [&'a Path],
    /// Its `HOME` and `TMPDIR`.
    pub home: &'a Path,
    /// Where its standard output goes in full (up to [`Limits::answers_bytes`]), when
    /// it is the answers.
    pub stdout_file: Option<PathBuf>,
    /// The user it runs as, if not viewray's.
    pub run_as: Option<RunAs>,
}

/// How a run ended.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Ended {
    /// It exited with this code.
    Exited(i32),
    /// A signal ended it (`SIGXFSZ`: it wrote a file larger than the limit).
    Signalled(i32),
    /// It ran past the time limit and was killed with its process group.
    TimedOut,
    /// Its folders grew past the limit, and it was killed with its process group.
    FolderTooLarge,
    /// It made more files than the limit, and was killed with its process group.
    TooManyFiles,
}

/// What one stream of the program printed.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Captured {
    /// The first bytes, up to the limit.
    pub kept: Vec<u8>,
    /// How many bytes it printed in all.
    pub total: u64,
}

impl Captured {
    /// The kept text, lossily decoded, with a last line saying how much was left out.
    pub fn text(&self) -> String {
        let mut text = String::from_utf8_lossy(&self.kept).into_owned();
        if self.total > self.kept.len() as u64 {
            if !text.ends_with('\n') {
                text.push('\n');
            }
            text.push_str(&format!(
                "[... {} more bytes not kept]\n",
                self.total - self.kept.len() as u64
            ));
        }
        text
    }
}

/// A finished run.
#[derive(Clone, Debug)]
pub struct Finished {
    /// How it ended.
    pub ended: Ended,
    /// Its standard output (what was kept of it).
    pub stdout: Captured,
    /// Its standard error.
    pub stderr: Captured,
    /// How long it ran.
    pub elapsed: Duration,
}

/// How often the program is looked at.
const POLL: Duration = Duration::from_millis(10);
/// How often its folders are measured.
const MEASURE: Duration = Duration::from_millis(200);
/// How long the output readers are waited for once the group is dead (a process that
/// left the group may still hold the pipes).
const DRAIN: Duration = Duration::from_secs(2);

/// Runs `program` under `limits`.
///
/// # Errors
/// The shell cannot be started, or the output file cannot be made: a sentence.
pub fn run(program: &Program<'_>, limits: &Limits) -> Result<Finished, String> {
    // POSIX `ulimit -f` counts 512-byte blocks; a core dump is never wanted.
    let blocks = limits.file_bytes.div_ceil(512).max(1);
    let script = format!(
        "ulimit -f {blocks} 2>/dev/null; ulimit -c 0 2>/dev/null; {}",
        program.command
    );
    let mut command = Command::new("/bin/sh");
    command
        .arg("-c")
        .arg(script)
        .current_dir(program.folder)
        .env_clear()
        .env(
            "PATH",
            std::env::var_os("PATH").unwrap_or_else(|| "/usr/local/bin:/usr/bin:/bin".into()),
        )
        .env("HOME", program.home)
        .env("TMPDIR", program.home)
        .env("LANG", "C.UTF-8")
        .stdin(Stdio::null())
        .stdout(Stdio::piped())
        .stderr(Stdio::piped());
    std::os::unix::process::CommandExt::process_group(&mut command, 0);
    if let Some(user) = program.run_as {
        // std drops root's supplementary groups too (setgroups) before setuid.
        std::os::unix::process::CommandExt::uid(&mut command, user.uid);
        std::os::unix::process::CommandExt::gid(&mut command, user.gid);
    }
    let stdout_sink = match &program.stdout_file {
        Some(path) => Some(
            std::fs::File::create(path)
                .map_err(|e| format!("cannot make the file for the answers: {e}"))?,
        ),
        None => None,
    };
    let started = Instant::now();
    let mut child = command
        .spawn()
        .map_err(|e| format!("cannot start /bin/sh to run the program: {e}"))?;
    let group = Pid::from_raw(
        i32::try_from(child.id()).map_err(|_| "a process id out of range".to_owned())?,
    );
    let stdout_limit = if stdout_sink.is_some() {
        limits.answers_bytes
    } else {
        limits.output_bytes
    };
    let stdout = reader(child.stdout.take(), stdout_limit, stdout_sink);
    let stderr = reader(child.stderr.take(), limits.output_bytes, None);
    let ended = watch(&mut child, group, program.watched, limits, started);
    // Whatever it left running in its group ends now.
    let _ = killpg(group, Signal::SIGKILL);
    let elapsed = started.elapsed();
    let stdout = stdout.finish();
    let stderr = stderr.finish();
    Ok(Finished {
        ended,
        stdout,
        stderr,
        elapsed,
    })
}

/// Waits for the child, killing its group at a limit.
fn watch(
    child: &mut Child,
    group: Pid,
    watched: &[&Path],
    limits: &Limits,
    started: Instant,
) -> Ended {
    let mut measured = Instant::now();
    loop {
        match child.try_wait() {
            Ok(Some(status)) => return ended(status),
            Ok(None) => {}
            Err(_) => {
                let _ = killpg(group, Signal::SIGKILL);
                return child.wait().map_or(Ended::Signalled(9), ended);
            }
        }
        let over = if started.elapsed() > limits.timeout {
            Some(Ended::TimedOut)
        } else if measured.elapsed() >= MEASURE {
            measured = Instant::now();
            over_folders(watched, limits)
        } else {
            None
        };
        if let Some(over) = over {
            let _ = killpg(group, Signal::SIGKILL);
            let _ = child.wait();
            return over;
        }
        std::thread::sleep(POLL);
    }
}

fn over_folders(watched: &[&Path], limits: &Limits) -> Option<Ended> {
    let mut bytes = 0;
    for folder in watched {
        let (size, too_many) = folder_size(folder, limits.folder_entries);
        if too_many {
            return Some(Ended::TooManyFiles);
        }
        bytes += size;
    }
    (bytes > limits.folder_bytes).then_some(Ended::FolderTooLarge)
}

fn ended(status: std::process::ExitStatus) -> Ended {
    use std::os::unix::process::ExitStatusExt;
    match (status.code(), status.signal()) {
        // The shell reports a command a signal ended as 128 + the signal.
        (Some(code), _) if code > 128 && code < 128 + 65 => Ended::Signalled(code - 128),
        (Some(code), _) => Ended::Exited(code),
        (None, Some(signal)) => Ended::Signalled(signal),
        (None, None) => Ended::Signalled(0),
    }
}

/// A thread reading one stream: keeps the first `limit` bytes (in memory, or in `sink`)
/// and counts the rest.
struct Reader {
    handle: Option<JoinHandle<Captured>>,
    total: Arc<AtomicU64>,
}

fn reader(
    stream: Option<impl Read + Send + 'static>,
    limit: u64,
    mut sink: Option<std::fs::File>,
) -> Reader {
    let total = Arc::new(AtomicU64::new(0));
    let counted = Arc::clone(&total);
    let handle = stream.map(|mut stream| {
        std::thread::spawn(move || {
            let mut captured = Captured::default();
            let mut buffer = [0_u8; 8192];
            while let Ok(n) = stream.read(&mut buffer) {
                if n == 0 {
                    break;
                }
                let room = limit.saturating_sub(captured.total) as usize;
                let keep = &buffer[..n.min(room)];
                match &mut sink {
                    Some(file) => {
                        let _ = file.write_all(keep);
                    }
                    None => captured.kept.extend_from_slice(keep),
                }
                captured.total += n as u64;
                counted.store(captured.total, Ordering::Relaxed);
            }
            captured
        })
    });
    Reader { handle, total }
}

impl Reader {
    /// What the stream gave, once it closes or [`DRAIN`] has passed.
    fn finish(self) -> Captured {
        let Some(handle) = self.handle else {
            return Captured::default();
        };
        let deadline = Instant::now() + DRAIN;
        while !handle.is_finished() && Instant::now() < deadline {
            std::thread::sleep(POLL);
        }
        if handle.is_finished() {
            handle.join().unwrap_or_default()
        } else {
            // A process outside the group holds the pipe: leave the thread to it.
            Captured {
                kept: Vec::new(),
                total: self.total.load(Ordering::Relaxed),
            }
        }
    }
}

/// The words for how a run ended, for the student (`None` for a clean exit).
pub fn ending_words(ended: Ended, limits: &Limits) -> Option<String> {
    Some(match ended {
        Ended::Exited(0) => return None,
        Ended::Exited(code) => format!("your program exited with code {code}"),
        Ended::Signalled(25) => format!(
            "your program wrote a file larger than {} MB and was stopped (SIGXFSZ)",
            limits.file_bytes >> 20
        ),
        Ended::Signalled(9) => "your program was killed (SIGKILL)".to_owned(),
        Ended::Signalled(11) => "your program crashed (segmentation fault, SIGSEGV)".to_owned(),
        Ended::Signalled(6) => "your program aborted (SIGABRT)".to_owned(),
        Ended::Signalled(signal) => format!("your program was ended by signal {signal}"),
        Ended::TimedOut => format!(
            "your program ran longer than the time limit of {} s and was stopped, with every \
             process it started",
            seconds(limits.timeout)
        ),
        Ended::FolderTooLarge => format!(
            "your program's folders grew past {} MB and it was stopped",
            limits.folder_bytes >> 20
        ),
        Ended::TooManyFiles => format!(
            "your program made more than {} files and it was stopped",
            limits.folder_entries
        ),
    })
}

/// A duration as seconds, without needless decimals: `30`, `0.5`.
pub(crate) fn seconds(duration: Duration) -> String {
    let s = duration.as_secs_f64();
    if s.fract() == 0.0 {
        format!("{s:.0}")
    } else {
        format!("{s}")
    }
}

/// A path quoted for `sh`: in single quotes, each single quote closed, escaped and
/// reopened.
pub fn shell_quote(text: &str) -> String {
    format!("'{}'", text.replace('\'', r"'\''"))
}

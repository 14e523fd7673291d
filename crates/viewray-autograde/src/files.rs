//! A submission's files, read without trusting them: no symbolic link is followed, no
//! special file (a FIFO that would block, a device) is opened, and nothing larger than a
//! limit is read; and a submission copied into a scratch folder for its program to run in.

use std::fs::{File, OpenOptions};
use std::io::Read;
use std::os::unix::fs::OpenOptionsExt;
use std::path::{Component, Path, PathBuf};

/// Why a submission's file was not read. The message is for the student.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
pub enum ReadError {
    /// There is no such file.
    #[error("`{0}` is missing")]
    Missing(String),
    /// The path, or a folder on it, is a symbolic link.
    #[error("`{0}` is a symbolic link: links are not followed (hand in the file itself)")]
    Link(String),
    /// The path is a folder, a FIFO, a device or a socket.
    #[error("`{0}` is not a regular file")]
    NotAFile(String),
    /// The file is larger than the limit.
    #[error("`{name}` is {bytes} bytes: at most {limit} are read")]
    TooLarge {
        /// The file.
        name: String,
        /// Its size.
        bytes: u64,
        /// The limit.
        limit: u64,
    },
    /// The system refused to read it.
    #[error("`{name}` cannot be read: {message}")]
    Unreadable {
        /// The file.
        name: String,
        /// The system's reason.
        message: String,
    },
}

/// Reads the file `name` (a relative path) inside `root`, refusing symbolic links on the
/// way and at the end, anything but a regular file, and more than `limit` bytes.
///
/// Each folder on the way and the file itself are looked at without following links, and
/// the file is opened with `O_NOFOLLOW` (a link put there in between is refused too) and
/// `O_NONBLOCK` (a FIFO put there in between cannot block the reader); what was opened is
/// checked to be the regular file that was looked at.
///
/// # Errors
/// [`ReadError`], in words for the student.
pub fn read_inside(root: &Path, name: &str, limit: u64) -> Result<Vec<u8>, ReadError> {
    let path = checked_path(root, name)?;
    let file = OpenOptions::new()
        .read(true)
        .custom_flags(libc::O_NOFOLLOW | libc::O_NONBLOCK)
        .open(&path)
        .map_err(|e| match e.raw_os_error() {
            Some(libc::ELOOP) => ReadError::Link(name.to_owned()),
            _ if e.kind() == std::io::ErrorKind::NotFound => ReadError::Missing(name.to_owned()),
            _ => ReadError::Unreadable {
                name: name.to_owned(),
                message: e.to_string(),
            },
        })?;
    read_opened(file, name, limit)
}

/// Reads an opened file: a regular file of at most `limit` bytes.
fn read_opened(file: File, name: &str, limit: u64) -> Result<Vec<u8>, ReadError> {
    let unreadable = |e: std::io::Error| ReadError::Unreadable {
        name: name.to_owned(),
        message: e.to_string(),
    };
    let metadata = file.metadata().map_err(unreadable)?;
    if !metadata.is_file() {
        return Err(ReadError::NotAFile(name.to_owned()));
    }
    if metadata.len() > limit {
        return Err(ReadError::TooLarge {
            name: name.to_owned(),
            bytes: metadata.len(),
            limit,
        });
    }
    let mut bytes = Vec::new();
    file.take(limit + 1)
        .read_to_end(&mut bytes)
        .map_err(unreadable)?;
    if bytes.len() as u64 > limit {
        return Err(ReadError::TooLarge {
            name: name.to_owned(),
            bytes: bytes.len() as u64,
            limit,
        });
    }
    Ok(bytes)
}

/// `root/name`, once every folder on the way is known to be a real folder (not a link)
/// and the last component not a link, and `name` to stay inside `root`.
fn checked_path(root: &Path, name: &str) -> Result<PathBuf, ReadError> {
    let mut path = root.to_path_buf();
    let components: Vec<Component<'_>> = Path::new(name).components().collect();
    for (k, component) in components.iter().enumerate() {
        match component {
            Component::Normal(part) => path.push(part),
            Component::CurDir => continue,
            _ => return Err(ReadError::Missing(name.to_owned())),
        }
        let metadata =
            std::fs::symlink_metadata(&path).map_err(|_| ReadError::Missing(name.to_owned()))?;
        if metadata.file_type().is_symlink() {
            return Err(ReadError::Link(name.to_owned()));
        }
        let last = k + 1 == components.len();
        if !last && !metadata.is_dir() {
            return Err(ReadError::Missing(name.to_owned()));
        }
        if last && !metadata.is_file() {
            return Err(ReadError::NotAFile(name.to_owned()));
        }
    }
    Ok(path)
}

/// Whether `root/name` exists as anything at all (a link included), without following it.
pub fn exists_inside(root: &Path, name: &str) -> bool {
    std::fs::symlink_metadata(root.join(name)).is_ok()
}

/// How much of a submission a copy takes.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct CopyLimits {
    /// The most bytes in all.
    pub bytes: u64,
    /// The most files and folders.
    pub entries: u64,
}

/// The folder a GitHub Classroom kit adds to the students' repository (viewray and the
/// assignment), which is not the student's work and is not copied for their program.
pub const KIT_FOLDER: &str = ".viewray";

/// What a copy of a submission left out.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Copied {
    /// The files copied.
    pub files: u64,
    /// Their bytes.
    pub bytes: u64,
    /// The symbolic links and special files left out, relative to the submission.
    pub left_out: Vec<String>,
}

/// Copies the submission folder `from` into the new folder `to`: regular files and
/// folders only (symbolic links, FIFOs, devices and sockets are left out and listed;
/// `.git` folders are skipped, and so is the [`KIT_FOLDER`] at its top, viewray and the
/// assignment in a GitHub Classroom repository), at most `limits`.
///
/// # Errors
/// The submission exceeds the limits, or cannot be read or written: a sentence.
pub fn copy_submission(from: &Path, to: &Path, limits: CopyLimits) -> Result<Copied, String> {
    let mut copied = Copied::default();
    let mut entries = 0_u64;
    let mut stack = vec![PathBuf::new()];
    std::fs::create_dir_all(to).map_err(|e| format!("cannot make the folder to run in: {e}"))?;
    while let Some(relative) = stack.pop() {
        let source = from.join(&relative);
        let mut names: Vec<_> = std::fs::read_dir(&source)
            .map_err(|e| {
                format!(
                    "cannot read the submission's folder `{}`: {e}",
                    shown(&relative)
                )
            })?
            .filter_map(Result::ok)
            .map(|entry| entry.file_name())
            .collect();
        names.sort();
        for name in names {
            entries += 1;
            if entries > limits.entries {
                return Err(format!(
                    "the submission holds more than {} files and folders",
                    limits.entries
                ));
            }
            let inner = relative.join(&name);
            let Ok(metadata) = std::fs::symlink_metadata(from.join(&inner)) else {
                continue;
            };
            if metadata.is_dir() {
                if name == ".git" || (relative.as_os_str().is_empty() && name == KIT_FOLDER) {
                    continue;
                }
                std::fs::create_dir(to.join(&inner))
                    .map_err(|e| format!("cannot copy `{}`: {e}", shown(&inner)))?;
                stack.push(inner);
            } else if metadata.is_file() {
                copied.bytes += metadata.len();
                if copied.bytes > limits.bytes {
                    return Err(format!(
                        "the submission is larger than {} bytes",
                        limits.bytes
                    ));
                }
                std::fs::copy(from.join(&inner), to.join(&inner))
                    .map_err(|e| format!("cannot copy `{}`: {e}", shown(&inner)))?;
                copied.files += 1;
            } else {
                copied.left_out.push(shown(&inner));
            }
        }
    }
    copied.left_out.sort();
    Ok(copied)
}

/// The bytes of every regular file under `folder`, not following links, and whether
/// more than `max_entries` entries were seen (the count stops there).
pub fn folder_size(folder: &Path, max_entries: u64) -> (u64, bool) {
    let mut bytes = 0;
    let mut entries = 0;
    let mut stack = vec![folder.to_path_buf()];
    while let Some(dir) = stack.pop() {
        let Ok(read) = std::fs::read_dir(&dir) else {
            continue;
        };
        for entry in read.filter_map(Result::ok) {
            entries += 1;
            if entries > max_entries {
                return (bytes, true);
            }
            let Ok(metadata) = std::fs::symlink_metadata(entry.path()) else {
                continue;
            };
            if metadata.is_dir() {
                stack.push(entry.path());
            } else if metadata.is_file() {
                bytes += metadata.len();
            }
        }
    }
    (bytes, false)
}

fn shown(path: &Path) -> String {
    path.display().to_string()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_link_to_a_file_outside_is_not_followed() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path().join("submission");
        std::fs::create_dir(&root).unwrap();
        std::os::unix::fs::symlink("/etc/passwd", root.join("answers.txt")).unwrap();
        std::fs::create_dir(dir.path().join("outside")).unwrap();
        std::fs::write(dir.path().join("outside/answers.txt"), "secret").unwrap();
        std::os::unix::fs::symlink("../outside", root.join("linked")).unwrap();
        assert_eq!(
            read_inside(&root, "answers.txt", 100),
            Err(ReadError::Link("answers.txt".to_owned()))
        );
        assert_eq!(
            read_inside(&root, "linked/answers.txt", 100),
            Err(ReadError::Link("linked/answers.txt".to_owned()))
        );
    }

    #[test]
    fn regular_files_are_read_and_others_refused() {
        let dir = tempfile::tempdir().unwrap();
        let root = dir.path();
        std::fs::create_dir(root.join("out")).unwrap();
        std::fs::write(root.join("out/a.txt"), "ray 0 0").unwrap();
        assert_eq!(read_inside(root, "out/a.txt", 100).unwrap(), b"ray 0 0");
        assert_eq!(read_inside(root, "./out/a.txt", 100).unwrap(), b"ray 0 0");
        assert_eq!(
            read_inside(root, "b.txt", 100),
            Err(ReadError::Missing("b.txt".to_owned()))
        );
        assert_eq!(
            read_inside(root, "out", 100),
            Err(ReadError::NotAFile("out".to_owned()))
        );
        assert_eq!(
            read_inside(root, "out/a.txt", 3),
            Err(ReadError::TooLarge {
                name: "out/a.txt".to_owned(),
                bytes: 7,
                limit: 3
            })
        );
        let fifo = root.join("fifo");
        assert!(
            std::process::Command::new("mkfifo")
                .arg(&fifo)
                .status()
                .unwrap()
                .success()
        );
        assert_eq!(
            read_inside(root, "fifo", 100),
            Err(ReadError::NotAFile("fifo".to_owned()))
        );
    }

    #[test]
    fn a_copy_leaves_out_links_and_stops_at_its_limits() {
        let dir = tempfile::tempdir().unwrap();
        let from = dir.path().join("from");
        std::fs::create_dir_all(from.join("src/.git")).unwrap();
        std::fs::create_dir_all(from.join(".git")).unwrap();
        std::fs::create_dir_all(from.join(".viewray/bin")).unwrap();
        std::fs::write(from.join(".viewray/bin/viewray"), "a program").unwrap();
        std::fs::write(from.join("src/main.py"), "print(1)").unwrap();
        std::fs::write(from.join(".git/HEAD"), "ref").unwrap();
        std::os::unix::fs::symlink("/etc/passwd", from.join("passwd")).unwrap();
        let limits = CopyLimits {
            bytes: 100,
            entries: 100,
        };
        let copied = copy_submission(&from, &dir.path().join("to"), limits).unwrap();
        assert_eq!(copied.files, 1);
        assert_eq!(copied.left_out, ["passwd"]);
        assert_eq!(
            std::fs::read(dir.path().join("to/src/main.py")).unwrap(),
            b"print(1)"
        );
        assert!(!dir.path().join("to/.git").exists());
        assert!(!dir.path().join("to/.viewray").exists());
        assert!(!dir.path().join("to/passwd").exists());
        let small = CopyLimits {
            bytes: 3,
            entries: 100,
        };
        let error = copy_submission(&from, &dir.path().join("to2"), small).unwrap_err();
        assert_eq!(error, "the submission is larger than 3 bytes");
        let few = CopyLimits {
            bytes: 100,
            entries: 2,
        };
        let error = copy_submission(&from, &dir.path().join("to3"), few).unwrap_err();
        assert_eq!(error, "the submission holds more than 2 files and folders");
    }
}

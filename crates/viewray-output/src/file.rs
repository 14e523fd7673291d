//! Atomic file writes: every file viewray writes appears whole or not at all.
//!
//! A file is written into a temporary file in the target's folder and renamed over the
//! target only when complete, by the `atomic-write-file` crate. The policy, the same for
//! every writer:
//!
//! - Until the rename, the target keeps what it held; a failure, a [`AtomicFile::discard`]
//!   or a drop removes the temporary file.
//! - Before the rename the file's data is flushed to disk (fsync), and the folder after
//!   it: once a write returns, a crash cannot leave an empty or partial file in its place.
//! - A new file gets the permissions `std::fs::File::create` would give it (mode 0o666
//!   less the umask, usually 0o644); a file that is replaced keeps its own (and its owner,
//!   where the process may set it).
//! - Errors name the path the caller gave ([`WriteError`]), never the temporary file's.
//! - A path that is a folder is refused when the file is created, before any work.

use std::io::{self, Seek, SeekFrom, Write};
use std::path::{Path, PathBuf};

use atomic_write_file::AtomicWriteFile;

/// A file could not be written: the path the caller gave, and why.
///
/// Its message is `cannot write PATH`; the cause is its [`source`](std::error::Error::source),
/// so a report of the chain (`anyhow`'s `{:#}`) reads `cannot write out.png: Not a
/// directory (os error 20)`.
#[derive(Debug, thiserror::Error)]
#[error("cannot write {}", path.display())]
pub struct WriteError {
    path: PathBuf,
    #[source]
    source: io::Error,
}

impl WriteError {
    /// The error `source` met while writing `path`.
    pub fn new(path: impl Into<PathBuf>, source: io::Error) -> Self {
        Self {
            path: path.into(),
            source,
        }
    }

    /// The path that could not be written, as the caller gave it.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// The kind of the underlying I/O error.
    pub fn kind(&self) -> io::ErrorKind {
        self.source.kind()
    }
}

impl From<WriteError> for io::Error {
    /// An I/O error of the same kind whose message names the path.
    fn from(error: WriteError) -> Self {
        io::Error::new(error.kind(), error)
    }
}

/// Writes `bytes` to `path` atomically (see the [module](self) for the policy). The
/// folder must exist.
///
/// # Errors
/// A [`WriteError`] naming `path` if the folder is missing or not writable, `path` is a
/// folder, or the disk is full.
pub fn write_atomically(path: impl AsRef<Path>, bytes: &[u8]) -> Result<(), WriteError> {
    let mut file = AtomicFile::create(path)?;
    if let Err(error) = file.write_all(bytes) {
        return Err(file.error(error));
    }
    file.commit()
}

/// A file being written atomically: write into it (it is [`Write`] and [`Seek`]), then
/// [`commit`](AtomicFile::commit) to move it into place. Dropped without a commit, it
/// leaves the target as it was.
#[derive(Debug)]
pub struct AtomicFile {
    path: PathBuf,
    file: AtomicWriteFile,
}

impl AtomicFile {
    /// Creates the temporary file for `path`, in `path`'s folder, which must exist.
    ///
    /// # Errors
    /// A [`WriteError`] naming `path` if `path` is a folder, or its folder is missing or
    /// not writable.
    pub fn create(path: impl AsRef<Path>) -> Result<Self, WriteError> {
        let path = path.as_ref();
        if path.is_dir() {
            return Err(WriteError::new(
                path,
                io::Error::new(io::ErrorKind::IsADirectory, "it is a directory"),
            ));
        }
        let file = AtomicWriteFile::open(path).map_err(|error| WriteError::new(path, error))?;
        Ok(Self {
            path: path.to_owned(),
            file,
        })
    }

    /// The path the file will have once committed.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// `source`, met while writing this file, as an error that names its path.
    pub fn error(&self, source: io::Error) -> WriteError {
        WriteError::new(&self.path, source)
    }

    /// Flushes the contents to disk and renames the file over its path.
    ///
    /// # Errors
    /// A [`WriteError`] naming the path if the flush or the rename fails; the path then
    /// keeps what it held.
    pub fn commit(self) -> Result<(), WriteError> {
        let Self { path, file } = self;
        file.commit().map_err(|error| WriteError::new(path, error))
    }

    /// Deletes the temporary file, leaving the path as it was.
    ///
    /// # Errors
    /// A [`WriteError`] naming the path if the temporary file cannot be removed.
    pub fn discard(self) -> Result<(), WriteError> {
        let Self { path, file } = self;
        file.discard().map_err(|error| WriteError::new(path, error))
    }
}

impl Write for AtomicFile {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.file.write(buf)
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.file.write_all(buf)
    }

    fn flush(&mut self) -> io::Result<()> {
        self.file.flush()
    }
}

impl Seek for AtomicFile {
    fn seek(&mut self, position: SeekFrom) -> io::Result<u64> {
        self.file.seek(position)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn names_in(dir: &Path) -> Vec<String> {
        let mut names: Vec<String> = std::fs::read_dir(dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        names
    }

    #[test]
    fn a_file_appears_whole_and_only_on_commit() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.txt");
        std::fs::write(&path, "old").unwrap();

        let mut file = AtomicFile::create(&path).unwrap();
        file.write_all(b"new contents").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
        file.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "new contents");
        assert_eq!(names_in(dir.path()), ["out.txt"]);

        write_atomically(&path, b"again").unwrap();
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "again");
        assert_eq!(names_in(dir.path()), ["out.txt"]);
    }

    #[test]
    fn a_discarded_or_dropped_file_leaves_the_old_one_and_no_stray_file() {
        let dir = tempfile::tempdir().unwrap();
        let path = dir.path().join("out.png");
        std::fs::write(&path, "old").unwrap();

        let mut file = AtomicFile::create(&path).unwrap();
        file.write_all(b"half").unwrap();
        assert_eq!(
            names_in(dir.path()).len(),
            2,
            "the temporary file is beside it"
        );
        file.discard().unwrap();
        assert_eq!(names_in(dir.path()), ["out.png"]);

        let mut file = AtomicFile::create(&path).unwrap();
        file.write_all(b"half").unwrap();
        drop(file);
        assert_eq!(names_in(dir.path()), ["out.png"]);
        assert_eq!(std::fs::read_to_string(&path).unwrap(), "old");
    }

    #[test]
    fn errors_name_the_path_given_never_the_temporary_file() {
        let dir = tempfile::tempdir().unwrap();
        let not_a_folder = dir.path().join("file.txt");
        std::fs::write(&not_a_folder, "").unwrap();
        let cases = [
            (not_a_folder.join("out.png"), io::ErrorKind::NotADirectory),
            (dir.path().join("missing/out.png"), io::ErrorKind::NotFound),
            (dir.path().to_owned(), io::ErrorKind::IsADirectory),
        ];
        for (path, kind) in cases {
            let error = write_atomically(&path, b"x").unwrap_err();
            assert_eq!(error.path(), path);
            assert_eq!(error.kind(), kind, "{}", path.display());
            assert_eq!(
                error.to_string(),
                format!("cannot write {}", path.display())
            );
            let io: io::Error = error.into();
            assert_eq!(io.kind(), kind);
            assert_eq!(io.to_string(), format!("cannot write {}", path.display()));
            let cause = std::error::Error::source(&io).unwrap().to_string();
            assert!(
                !cause.contains(".tmp") && !cause.contains("out.png."),
                "{cause}"
            );
        }
        assert_eq!(names_in(dir.path()), ["file.txt"]);
    }

    #[cfg(unix)]
    #[test]
    fn a_new_file_has_the_mode_of_file_create_and_a_replaced_file_keeps_its_own() {
        use std::os::unix::fs::PermissionsExt as _;
        let mode = |path: &Path| std::fs::metadata(path).unwrap().permissions().mode() & 0o777;
        let dir = tempfile::tempdir().unwrap();
        let plain = dir.path().join("plain");
        std::fs::File::create(&plain).unwrap();
        let new = dir.path().join("new");
        write_atomically(&new, b"x").unwrap();
        assert_eq!(mode(&new), mode(&plain));

        let private = dir.path().join("private");
        std::fs::write(&private, "old").unwrap();
        std::fs::set_permissions(&private, std::fs::Permissions::from_mode(0o600)).unwrap();
        write_atomically(&private, b"new").unwrap();
        assert_eq!(mode(&private), 0o600);
    }
}

//! Where a command's output goes while it is made: a file or a folder written atomically,
//! and what Ctrl-C does to it.
//!
//! A file is viewray-output's [`AtomicFile`] (a temporary file beside it, renamed into
//! place only when complete); a folder of frames is written into a hidden temporary
//! folder beside it and moved into place only when every frame is there. Until then the
//! path keeps what it held. On Ctrl-C the temporary file or folder is deleted and the
//! command exits with 130 (the shell's code for SIGINT), saying so on stderr. The handler
//! is installed before the temporary output is created, and the output is handed to it
//! under the same lock it takes: once the temporary output exists, Ctrl-C removes it.

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Arc, Mutex, MutexGuard, PoisonError};

use anyhow::{Context, Result, bail};
use viewray_output::AtomicFile;

/// The output being written.
pub(crate) struct Output {
    path: PathBuf,
    state: Arc<Mutex<State>>,
}

/// Where the output stands, as the Ctrl-C handler sees it.
enum State {
    /// The temporary output is being created.
    Opening,
    /// The temporary output exists and the work is under way.
    Pending(Pending),
    /// Written, or given up after an error: nothing left to clean up.
    Finished,
}

/// A temporary output.
enum Pending {
    /// A file beside the target.
    File(AtomicFile),
    /// A hidden folder beside the target folder.
    Folder(PathBuf),
}

impl Pending {
    /// Deletes the temporary output.
    fn discard(self) {
        match self {
            Pending::File(file) => {
                let _ = file.discard();
            }
            Pending::Folder(folder) => {
                let _ = std::fs::remove_dir_all(folder);
            }
        }
    }
}

impl Output {
    /// Installs the Ctrl-C handler, then creates the temporary file for `path`, in its
    /// folder.
    pub(crate) fn file(path: &Path) -> Result<Output> {
        Output::create(path, || Ok(Pending::File(AtomicFile::create(path)?)))
    }

    /// Installs the Ctrl-C handler, then creates a hidden temporary folder beside the
    /// folder `path` (which need not exist), for the files that will make it up.
    pub(crate) fn folder(path: &Path) -> Result<Output> {
        let name = path
            .file_name()
            .with_context(|| format!("cannot write {}: not a folder name", path.display()))?;
        let parent = match path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let temporary = parent.join(format!(
            ".{}.viewray-{}",
            name.to_string_lossy(),
            std::process::id()
        ));
        Output::create(path, || {
            std::fs::create_dir(&temporary)
                .with_context(|| format!("cannot write {}", path.display()))?;
            Ok(Pending::Folder(temporary.clone()))
        })
    }

    fn create(path: &Path, open: impl FnOnce() -> Result<Pending>) -> Result<Output> {
        let state = Arc::new(Mutex::new(State::Opening));
        // Held until the output is in `state`: a Ctrl-C meanwhile waits for it.
        let mut opening = lock(&state);
        remove_on_interrupt(Arc::clone(&state), path);
        *opening = match open() {
            Ok(pending) => State::Pending(pending),
            Err(error) => {
                *opening = State::Finished;
                return Err(error);
            }
        };
        drop(opening);
        Ok(Output {
            path: path.to_owned(),
            state,
        })
    }

    /// Writes the contents of a file output with `write` and moves the finished file
    /// into place. Ctrl-C meanwhile waits until the file is in place (or given up).
    pub(crate) fn write_and_commit(
        self,
        write: impl FnOnce(&mut BufWriter<&mut AtomicFile>) -> Result<()>,
    ) -> Result<()> {
        let cannot = || format!("cannot write {}", self.path.display());
        let mut state = lock(&self.state);
        let State::Pending(Pending::File(mut file)) =
            std::mem::replace(&mut *state, State::Finished)
        else {
            bail!(
                "cannot write {}: the output was not open",
                self.path.display()
            );
        };
        let mut out = BufWriter::new(&mut file);
        write(&mut out).with_context(cannot)?;
        out.flush().with_context(cannot)?;
        drop(out);
        file.commit()?;
        Ok(())
    }

    /// A writer into a file output that takes the lock for each write only, so that a
    /// long piece of work can write as it goes while Ctrl-C stays prompt. Buffer it.
    pub(crate) fn writer(&self) -> OutputWriter {
        OutputWriter {
            state: Arc::clone(&self.state),
        }
    }

    /// The temporary folder of a folder output, to write its files into.
    pub(crate) fn temporary_folder(&self) -> Result<PathBuf> {
        match &*lock(&self.state) {
            State::Pending(Pending::Folder(folder)) => Ok(folder.clone()),
            _ => bail!(
                "cannot write {}: the output was not open",
                self.path.display()
            ),
        }
    }

    /// Moves the finished output into place: the file renamed over its path; the
    /// folder's files, when the folder does not exist, by renaming the whole temporary
    /// folder, else one by one, after which the files named `stale` are removed from it
    /// (an earlier, longer animation's frames).
    pub(crate) fn commit(self, stale: impl Fn(&str) -> bool) -> Result<()> {
        let mut state = lock(&self.state);
        let State::Pending(pending) = std::mem::replace(&mut *state, State::Finished) else {
            bail!(
                "cannot write {}: the output was not open",
                self.path.display()
            );
        };
        let cannot = || format!("cannot write {}", self.path.display());
        match pending {
            Pending::File(file) => file.commit()?,
            Pending::Folder(temporary) => {
                let result = move_folder(&temporary, &self.path, &stale).with_context(cannot);
                let _ = std::fs::remove_dir_all(&temporary);
                result?;
            }
        }
        Ok(())
    }
}

/// Moves the files of `temporary` into `target`: by renaming the folder when `target`
/// does not exist, else file by file, removing the files of `target` that `stale` names
/// and `temporary` does not hold.
fn move_folder(temporary: &Path, target: &Path, stale: &dyn Fn(&str) -> bool) -> io::Result<()> {
    if !target.exists() {
        return std::fs::rename(temporary, target);
    }
    let mut moved = std::collections::BTreeSet::new();
    for entry in std::fs::read_dir(temporary)? {
        let entry = entry?;
        std::fs::rename(entry.path(), target.join(entry.file_name()))?;
        moved.insert(entry.file_name());
    }
    for entry in std::fs::read_dir(target)? {
        let entry = entry?;
        let name = entry.file_name();
        if !moved.contains(&name) && name.to_str().is_some_and(stale) && entry.path().is_file() {
            std::fs::remove_file(entry.path())?;
        }
    }
    Ok(())
}

impl Drop for Output {
    /// An output dropped before it was written (a bad scene, a failed render) deletes its
    /// temporary file or folder: the Ctrl-C handler keeps the state alive, so this cannot
    /// wait for the last reference.
    fn drop(&mut self) {
        let mut state = lock(&self.state);
        if let State::Pending(pending) = std::mem::replace(&mut *state, State::Finished) {
            pending.discard();
        }
    }
}

/// See [`Output::writer`].
pub(crate) struct OutputWriter {
    state: Arc<Mutex<State>>,
}

impl OutputWriter {
    fn with_file<T>(&self, f: impl FnOnce(&mut AtomicFile) -> io::Result<T>) -> io::Result<T> {
        match &mut *lock(&self.state) {
            State::Pending(Pending::File(file)) => f(file),
            _ => Err(io::Error::other("the output is no longer open")),
        }
    }
}

impl Write for OutputWriter {
    fn write(&mut self, buf: &[u8]) -> io::Result<usize> {
        self.with_file(|file| file.write(buf))
    }

    fn write_all(&mut self, buf: &[u8]) -> io::Result<()> {
        self.with_file(|file| file.write_all(buf))
    }

    fn flush(&mut self) -> io::Result<()> {
        self.with_file(Write::flush)
    }
}

/// The state, even if a thread panicked while holding it (the handler must still run).
fn lock(state: &Mutex<State>) -> MutexGuard<'_, State> {
    state.lock().unwrap_or_else(PoisonError::into_inner)
}

/// On Ctrl-C, deletes the unfinished temporary output and exits with 130: the output
/// path keeps what it held, and no stray file is left beside it.
fn remove_on_interrupt(state: Arc<Mutex<State>>, output: &Path) {
    let output = output.to_owned();
    // Only a second handler fails to install, and a process writes one output.
    let _ = ctrlc::set_handler(move || {
        let mut state = lock(&state);
        if let State::Pending(pending) = std::mem::replace(&mut *state, State::Finished) {
            pending.discard();
            eprintln!("interrupted: {} was not written", output.display());
        }
        std::process::exit(130);
    });
}

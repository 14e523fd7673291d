//! Pairing a folder of reference images with a folder of renders, as `diff -r` pairs two
//! trees: by exact file name. What is missing on the render's side, or cannot be read
//! there, is the render's failure; what the render's side has besides is listed, not
//! judged; the reference's side must be sound (its problems are bad input).

use std::ffi::{OsStr, OsString};
use std::io;
use std::path::{Path, PathBuf};

use thiserror::Error;

/// A folder that cannot be graded against: bad input, not anyone's failure.
#[derive(Debug, Error)]
pub enum FolderError {
    /// The folder (given as `role` on the command line) cannot be read.
    #[error("cannot read {role} `{}`", path.display())]
    Unreadable {
        /// What the folder is: `EXPECTED`, `REFERENCE`, `SUBMISSIONS`.
        role: &'static str,
        /// The folder.
        path: PathBuf,
        /// Why.
        #[source]
        source: io::Error,
    },
    /// The reference folder holds no `*.png` file.
    #[error("{role} `{}` holds no *.png file", path.display())]
    NoPng {
        /// What the folder is.
        role: &'static str,
        /// The folder.
        path: PathBuf,
    },
    /// The submissions folder holds no student folder.
    #[error("{role} `{}` holds no folder: it must hold one folder per student", path.display())]
    NoStudent {
        /// What the folder is.
        role: &'static str,
        /// The folder.
        path: PathBuf,
    },
}

/// One reference image: a `*.png` file of the reference folder.
#[derive(Clone, Debug)]
pub struct ReferenceImage {
    /// The file name, as shown (lossy where it is not UTF-8).
    pub name: String,
    /// The file name as the file system holds it: what a render's name must equal.
    file_name: OsString,
    /// Where the file is.
    pub path: PathBuf,
}

impl ReferenceImage {
    /// A reference image at `path`, its name the path's file name.
    pub fn file(path: &Path) -> Self {
        let file_name = path
            .file_name()
            .map_or_else(|| path.as_os_str().to_owned(), OsStr::to_owned);
        Self {
            name: file_name.to_string_lossy().into_owned(),
            file_name,
            path: path.to_owned(),
        }
    }
}

/// What a render folder holds for one reference image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Counterpart {
    /// The file of that name, to be read.
    File(PathBuf),
    /// No file of that name.
    Missing {
        /// A file that looks meant for it: the same name but for the case of its letters,
        /// or the same stem with another extension.
        near: Option<String>,
    },
    /// A file of that name that is not read: a symbolic link to a file outside the folder.
    Outside {
        /// Where the link leads.
        target: PathBuf,
    },
}

impl Counterpart {
    /// Why the render fails, when it cannot be judged: `missing`, with a hint when a file
    /// looks meant for the image, or why the file is not read.
    pub fn problem(&self, name: &str) -> Option<String> {
        match self {
            Counterpart::File(_) => None,
            Counterpart::Missing { near: None } => Some("missing".to_owned()),
            Counterpart::Missing { near: Some(near) } => Some(if near.eq_ignore_ascii_case(name) {
                format!("missing (found `{near}`: names must match exactly, case included)")
            } else {
                format!("missing (found `{near}`: the image must be a PNG named `{name}`)")
            }),
            Counterpart::Outside { target } => Some(format!(
                "not read: a symbolic link out of the folder, to `{}`",
                target.display()
            )),
        }
    }
}

/// A render folder paired with the reference images.
#[derive(Clone, Debug, Default)]
pub struct Pairing {
    /// One counterpart per reference image, in the reference images' order.
    pub counterparts: Vec<Counterpart>,
    /// The folder's other entries (hidden ones aside), sorted, folders ending in `/`: listed,
    /// not judged.
    pub extra: Vec<String>,
}

/// Whether `name` ends in `.png`, in any case.
fn is_png_name(name: &OsStr) -> bool {
    Path::new(name)
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"))
}

/// The reference images of `folder` (given as `role` on the command line): its `*.png`
/// files (the extension in any case; symbolic links followed), sorted by name.
///
/// # Errors
/// Bad usage: the folder cannot be read, or holds no PNG file.
pub fn reference_images(
    folder: &Path,
    role: &'static str,
) -> Result<Vec<ReferenceImage>, FolderError> {
    let unreadable = |source| FolderError::Unreadable {
        role,
        path: folder.to_owned(),
        source,
    };
    let mut images = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(unreadable)? {
        let entry = entry.map_err(unreadable)?;
        let file_name = entry.file_name();
        let path = entry.path();
        if is_png_name(&file_name) && !path.is_dir() {
            images.push(ReferenceImage {
                name: file_name.to_string_lossy().into_owned(),
                file_name,
                path,
            });
        }
    }
    if images.is_empty() {
        return Err(FolderError::NoPng {
            role,
            path: folder.to_owned(),
        });
    }
    images.sort_by(|a, b| a.file_name.cmp(&b.file_name));
    Ok(images)
}

/// Pairs the render folder `folder` with `references` by exact file name.
///
/// # Errors
/// The folder cannot be read.
pub fn pair(folder: &Path, references: &[ReferenceImage]) -> io::Result<Pairing> {
    let mut entries: Vec<(OsString, bool)> = Vec::new();
    for entry in std::fs::read_dir(folder)? {
        let entry = entry?;
        let is_dir = entry.path().is_dir();
        entries.push((entry.file_name(), is_dir));
    }
    entries.sort();
    let canonical = folder.canonicalize()?;
    let mut matched = vec![false; entries.len()];
    let counterparts = references
        .iter()
        .map(|reference| {
            let found =
                entries.binary_search_by(|(name, _)| name.as_os_str().cmp(&reference.file_name));
            match found {
                Ok(index) => {
                    matched[index] = true;
                    let path = folder.join(&reference.file_name);
                    match outside(&path, &canonical) {
                        Some(target) => Counterpart::Outside { target },
                        None => Counterpart::File(path),
                    }
                }
                Err(_) => Counterpart::Missing {
                    near: near_name(&reference.file_name, &entries),
                },
            }
        })
        .collect();
    let extra = entries
        .iter()
        .zip(&matched)
        .filter(|((name, _), matched)| !**matched && !name.to_string_lossy().starts_with('.'))
        .map(|((name, is_dir), _)| {
            let mut shown = name.to_string_lossy().into_owned();
            if *is_dir {
                shown.push('/');
            }
            shown
        })
        .collect();
    Ok(Pairing {
        counterparts,
        extra,
    })
}

/// One student's folder of SUBMISSIONS.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Student {
    /// The folder's name (lossy where it is not UTF-8): the student's name in every
    /// output.
    pub name: String,
    /// The folder.
    pub folder: PathBuf,
}

/// The folders of a class's submissions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Submissions {
    /// One per sub-folder (hidden ones aside; symbolic links to folders followed), sorted
    /// by name.
    pub students: Vec<Student>,
    /// The other entries (files), sorted: listed, not graded.
    pub other: Vec<String>,
}

/// The student folders of `folder` (given as `role` on the command line).
///
/// # Errors
/// Bad usage: the folder cannot be read, or holds no folder.
pub fn submissions(folder: &Path, role: &'static str) -> Result<Submissions, FolderError> {
    let unreadable = |source| FolderError::Unreadable {
        role,
        path: folder.to_owned(),
        source,
    };
    let mut entries = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(unreadable)? {
        let entry = entry.map_err(unreadable)?;
        let name = entry.file_name();
        if name.to_string_lossy().starts_with('.') {
            continue;
        }
        entries.push((name, entry.path()));
    }
    entries.sort();
    let mut submissions = Submissions::default();
    for (name, path) in entries {
        let name = name.to_string_lossy().into_owned();
        if path.is_dir() {
            submissions.students.push(Student { name, folder: path });
        } else {
            submissions.other.push(name);
        }
    }
    if submissions.students.is_empty() {
        return Err(FolderError::NoStudent {
            role,
            path: folder.to_owned(),
        });
    }
    Ok(submissions)
}

/// Where the symbolic link `path` leads, when that is outside the folder `canonical`
/// (a link within the folder, a broken link and a plain file give `None`: they are read,
/// or fail to be, as they are).
fn outside(path: &Path, canonical: &Path) -> Option<PathBuf> {
    let metadata = std::fs::symlink_metadata(path).ok()?;
    if !metadata.file_type().is_symlink() {
        return None;
    }
    let target = path.canonicalize().ok()?;
    (!target.starts_with(canonical)).then_some(target)
}

/// A file of `entries` that looks meant for `name`: the same name in another case, else
/// the same stem (in any case) with another extension.
fn near_name(name: &OsStr, entries: &[(OsString, bool)]) -> Option<String> {
    let lower = name.to_ascii_lowercase();
    let stem = Path::new(name).file_stem()?.to_ascii_lowercase();
    let files = entries.iter().filter(|(_, is_dir)| !is_dir);
    files
        .clone()
        .find(|(entry, _)| entry.to_ascii_lowercase() == lower)
        .or_else(|| {
            files.clone().find(|(entry, _)| {
                Path::new(entry)
                    .file_stem()
                    .is_some_and(|s| s.to_ascii_lowercase() == stem)
            })
        })
        .map(|(entry, _)| entry.to_string_lossy().into_owned())
}

/// `names` for a line of text: all of them when there are few, else the first few and
/// how many more.
pub fn listed(names: &[String]) -> String {
    const SHOWN: usize = 5;
    if names.len() <= SHOWN + 1 {
        names.join(", ")
    } else {
        format!(
            "{}, and {} more",
            names[..SHOWN].join(", "),
            names.len() - SHOWN
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn touch(path: &Path) {
        std::fs::write(path, b"x").unwrap();
    }

    #[test]
    fn pairs_by_exact_name_and_lists_the_rest() {
        let dir = tempfile::tempdir().unwrap();
        let (reference, student) = (dir.path().join("reference"), dir.path().join("student"));
        std::fs::create_dir_all(&reference).unwrap();
        std::fs::create_dir_all(student.join("nested")).unwrap();
        for name in ["a.png", "b.png", "c.png", "d.png", "notes.txt"] {
            touch(&reference.join(name));
        }
        for name in [
            "a.png",
            "B.png",
            "c.jpg",
            "extra.png",
            ".DS_Store",
            "readme.txt",
        ] {
            touch(&student.join(name));
        }
        let references = reference_images(&reference, "REFERENCE").unwrap();
        let names: Vec<&str> = references.iter().map(|r| r.name.as_str()).collect();
        assert_eq!(names, ["a.png", "b.png", "c.png", "d.png"]);
        let pairing = pair(&student, &references).unwrap();
        assert_eq!(
            pairing.counterparts[0],
            Counterpart::File(student.join("a.png"))
        );
        let problems: Vec<Option<String>> = pairing
            .counterparts
            .iter()
            .zip(&references)
            .map(|(c, r)| c.problem(&r.name))
            .collect();
        assert_eq!(
            problems,
            [
                None,
                Some("missing (found `B.png`: names must match exactly, case included)".into()),
                Some("missing (found `c.jpg`: the image must be a PNG named `c.png`)".into()),
                Some("missing".into()),
            ]
        );
        assert_eq!(
            pairing.extra,
            ["B.png", "c.jpg", "extra.png", "nested/", "readme.txt"]
        );
    }

    #[test]
    fn a_link_out_of_the_folder_is_not_read_and_one_within_it_is() {
        let dir = tempfile::tempdir().unwrap();
        let (reference, student) = (dir.path().join("reference"), dir.path().join("student"));
        std::fs::create_dir_all(&reference).unwrap();
        std::fs::create_dir_all(&student).unwrap();
        for name in ["a.png", "b.png"] {
            touch(&reference.join(name));
        }
        touch(&student.join("mine.png"));
        std::os::unix::fs::symlink(reference.join("a.png"), student.join("a.png")).unwrap();
        std::os::unix::fs::symlink("mine.png", student.join("b.png")).unwrap();
        let references = reference_images(&reference, "REFERENCE").unwrap();
        let pairing = pair(&student, &references).unwrap();
        let outside = reference.join("a.png").canonicalize().unwrap();
        assert_eq!(
            pairing.counterparts,
            [
                Counterpart::Outside { target: outside },
                Counterpart::File(student.join("b.png")),
            ]
        );
        assert_eq!(pairing.extra, ["mine.png"]);
    }

    #[test]
    fn a_reference_folder_without_png_files_is_bad_usage() {
        let dir = tempfile::tempdir().unwrap();
        touch(&dir.path().join("scene.ron"));
        let error = reference_images(dir.path(), "REFERENCE").unwrap_err();
        assert!(error.to_string().contains("holds no *.png file"), "{error}");
    }

    #[test]
    fn submissions_are_the_sub_folders_and_the_rest_is_listed() {
        let dir = tempfile::tempdir().unwrap();
        for name in ["bob", "alice", ".git", "carol"] {
            std::fs::create_dir(dir.path().join(name)).unwrap();
        }
        touch(&dir.path().join("grades.xlsx"));
        let found = submissions(dir.path(), "SUBMISSIONS").unwrap();
        let names: Vec<&str> = found.students.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["alice", "bob", "carol"]);
        assert_eq!(found.students[1].folder, dir.path().join("bob"));
        assert_eq!(found.other, ["grades.xlsx"]);
        let empty = tempfile::tempdir().unwrap();
        touch(&empty.path().join("a.png"));
        let error = submissions(empty.path(), "SUBMISSIONS").unwrap_err();
        assert!(error.to_string().contains("holds no folder"), "{error}");
    }

    #[test]
    fn long_lists_are_cut() {
        let names: Vec<String> = (0..3000).map(|i| format!("{i}.png")).collect();
        assert_eq!(listed(&names[..3]), "0.png, 1.png, 2.png");
        assert_eq!(
            listed(&names),
            "0.png, 1.png, 2.png, 3.png, 4.png, and 2995 more"
        );
    }
}

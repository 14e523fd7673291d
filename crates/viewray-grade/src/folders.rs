//! Pairing a folder of reference images with a folder of renders, as `diff -r` pairs two
//! trees: by file name, exactly, or by stem when the render is another image format
//! (`tower.ppm` answers `tower.png`). What is missing on the render's side, or cannot be
//! read there, is the render's failure; what the render's side has besides is listed, not
//! judged; the reference's side must be sound (its problems are bad input). A class comes
//! as one folder per student (a student folder holding a single nested folder is
//! descended into), or flat, as course sites download it (module `flat`).

use std::ffi::{OsStr, OsString};
use std::io;
use std::path::{Path, PathBuf};

use thiserror::Error;
use viewray_compare::{IMAGE_EXTENSIONS, SUPPORTED_IMAGES};

use crate::flat::{self, FlatName};

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
    /// The reference folder holds no image file (`*.png`, `*.ppm`, `*.pgm`, `*.exr`).
    #[error("{role} `{}` holds no image (*.png, *.ppm, *.pgm or *.exr file)", path.display())]
    NoImage {
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
    /// The flat submissions folder holds no file named as a course site names them.
    #[error(
        "{role} `{}` holds no file named as Canvas or Moodle name submissions (`{}` or `{}`){}",
        path.display(), flat::CANVAS_EXAMPLE, flat::MOODLE_EXAMPLE,
        if *has_folders { ": it holds folders, one per student? then leave out --flat" } else { "" }
    )]
    NoFlatSubmission {
        /// What the folder is.
        role: &'static str,
        /// The folder.
        path: PathBuf,
        /// Whether it holds folders (a class in folders, given as flat).
        has_folders: bool,
    },
}

/// One reference image: an image file of the reference folder.
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
                let stem = Path::new(name)
                    .file_stem()
                    .map_or_else(|| name.to_owned(), |s| s.to_string_lossy().into_owned());
                format!(
                    "missing (found `{near}`: the image must be {SUPPORTED_IMAGES}, named \
                     `{stem}` with the extension .png, .ppm, .pgm or .exr)"
                )
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

/// Whether `name` ends in the extension of an image format viewray reads
/// ([`IMAGE_EXTENSIONS`]), in any case.
pub fn is_image_name(name: &OsStr) -> bool {
    Path::new(name).extension().is_some_and(|e| {
        IMAGE_EXTENSIONS
            .iter()
            .any(|known| e.eq_ignore_ascii_case(known))
    })
}

/// The reference images of `folder` (given as `role` on the command line): its image
/// files (`*.png`, `*.ppm`, `*.pgm`, `*.pnm`, `*.exr`, the extension in any case; symbolic
/// links followed), sorted by name.
///
/// # Errors
/// Bad usage: the folder cannot be read, or holds no image.
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
        if is_image_name(&file_name) && !path.is_dir() {
            images.push(ReferenceImage {
                name: file_name.to_string_lossy().into_owned(),
                file_name,
                path,
            });
        }
    }
    if images.is_empty() {
        return Err(FolderError::NoImage {
            role,
            path: folder.to_owned(),
        });
    }
    images.sort_by(|a, b| a.file_name.cmp(&b.file_name));
    Ok(images)
}

/// One entry of a render folder (or one file of a flat class) as pairing sees it.
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord)]
struct Entry {
    /// The name a render is matched by: the file name, or for a flat class the name the
    /// student gave it.
    name: OsString,
    /// Where it is.
    path: PathBuf,
    /// Whether it is a folder.
    is_dir: bool,
}

/// Pairs the render folder `folder` with `references`: each reference image with the file
/// of its name, else with an image file of its stem in another format (`tower.ppm` for
/// `tower.png`). A folder that holds no image and a single folder (a student's `hw3/`) is
/// descended into, as often as that holds.
///
/// # Errors
/// The folder cannot be read.
pub fn pair(folder: &Path, references: &[ReferenceImage]) -> io::Result<Pairing> {
    let (folder, entries) = descend(folder)?;
    let canonical = folder.canonicalize()?;
    Ok(pair_entries(&entries, references, |path| {
        outside(path, &canonical)
    }))
}

/// Pairs a flat class's files of one student (each with the name the student gave it)
/// with `references`, as [`pair`] pairs a folder's files; a resubmission's `-1` before
/// the extension (as Canvas renames it) is left out where that gives a reference's name.
fn pair_flat(files: &[(OsString, PathBuf)], references: &[ReferenceImage]) -> Pairing {
    let mut entries: Vec<Entry> = files
        .iter()
        .map(|(name, path)| Entry {
            name: flat::without_resubmission(name, |n| {
                references
                    .iter()
                    .any(|r| r.file_name == n || same_stem(n, &r.file_name))
            }),
            path: path.clone(),
            is_dir: false,
        })
        .collect();
    entries.sort();
    pair_entries(&entries, references, |_| None)
}

/// The folder to pair (`folder`, or the single folder it holds, as often as that holds)
/// and its entries, sorted.
fn descend(folder: &Path) -> io::Result<(PathBuf, Vec<Entry>)> {
    let mut folder = folder.to_owned();
    loop {
        let mut entries = Vec::new();
        for entry in std::fs::read_dir(&folder)? {
            let entry = entry?;
            entries.push(Entry {
                name: entry.file_name(),
                is_dir: entry.path().is_dir(),
                path: entry.path(),
            });
        }
        entries.sort();
        let shown: Vec<&Entry> = entries.iter().filter(|e| !hidden(&e.name)).collect();
        let folders: Vec<&&Entry> = shown.iter().filter(|e| e.is_dir).collect();
        let images = shown.iter().any(|e| !e.is_dir && is_image_name(&e.name));
        match folders.as_slice() {
            [only] if !images => folder = only.path.clone(),
            _ => return Ok((folder, entries)),
        }
    }
}

/// Whether an entry is hidden from pairing's lists: a dot file, or the `__MACOSX` folder a
/// zip made on a Mac holds.
fn hidden(name: &OsStr) -> bool {
    let name = name.to_string_lossy();
    name.starts_with('.') || name == "__MACOSX"
}

/// Whether `a` and `b` have the same stem and `a` is an image file viewray reads.
fn same_stem(a: &OsStr, b: &OsStr) -> bool {
    is_image_name(a) && Path::new(a).file_stem() == Path::new(b).file_stem()
}

/// Pairs sorted `entries` with `references` (see [`pair`]); `outside` says where a
/// matched file that is a link out of the folder leads.
fn pair_entries(
    entries: &[Entry],
    references: &[ReferenceImage],
    outside: impl Fn(&Path) -> Option<PathBuf>,
) -> Pairing {
    let mut matched = vec![false; entries.len()];
    let counterparts = references
        .iter()
        .map(|reference| {
            let exact = entries
                .iter()
                .position(|e| e.name == reference.file_name)
                .filter(|&i| !matched[i]);
            let found = exact.or_else(|| {
                (0..entries.len()).find(|&i| {
                    !matched[i]
                        && !entries[i].is_dir
                        && same_stem(&entries[i].name, &reference.file_name)
                })
            });
            match found {
                Some(index) => {
                    matched[index] = true;
                    let path = entries[index].path.clone();
                    match outside(&path) {
                        Some(target) => Counterpart::Outside { target },
                        None => Counterpart::File(path),
                    }
                }
                None => Counterpart::Missing {
                    near: near_name(&reference.file_name, entries),
                },
            }
        })
        .collect();
    let extra = entries
        .iter()
        .zip(&matched)
        .filter(|(entry, matched)| !**matched && !hidden(&entry.name))
        .map(|(entry, _)| {
            let mut shown = entry.name.to_string_lossy().into_owned();
            if entry.is_dir {
                shown.push('/');
            }
            shown
        })
        .collect();
    Pairing {
        counterparts,
        extra,
    }
}

/// One student of SUBMISSIONS.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Student {
    /// The student's name in every output (lossy where it is not UTF-8): the folder's
    /// name, or the name a course site gave the files.
    pub name: String,
    /// Where the student's renders are.
    pub handed_in: HandedIn,
}

/// Where a student's renders are.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum HandedIn {
    /// A folder (see [`pair`]).
    Folder(PathBuf),
    /// Files of a flat class, each with the name the student gave it.
    Files(Vec<(OsString, PathBuf)>),
}

impl Student {
    /// The student's renders paired with `references`.
    ///
    /// # Errors
    /// The student's folder cannot be read.
    pub fn pair(&self, references: &[ReferenceImage]) -> io::Result<Pairing> {
        match &self.handed_in {
            HandedIn::Folder(folder) => pair(folder, references),
            HandedIn::Files(files) => Ok(pair_flat(files, references)),
        }
    }
}

/// The students of a class's submissions.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Submissions {
    /// The students, sorted by name.
    pub students: Vec<Student>,
    /// The other entries, sorted: listed, not graded.
    pub other: Vec<String>,
}

/// The student folders of `folder` (given as `role` on the command line): one per
/// sub-folder (hidden ones aside; symbolic links to folders followed), named after it; a
/// folder as Moodle names it (`Ada Lovelace_123_assignsubmission_file_`) is the
/// student's name (`Ada Lovelace`).
///
/// # Errors
/// Bad usage: the folder cannot be read, or holds no folder.
pub fn submissions(folder: &Path, role: &'static str) -> Result<Submissions, FolderError> {
    let entries = visible_entries(folder, role)?;
    let mut submissions = Submissions::default();
    let mut folders = Vec::new();
    for (name, path) in entries {
        if path.is_dir() {
            folders.push((name, path));
        } else {
            submissions.other.push(name);
        }
    }
    let names: Vec<String> = folders
        .iter()
        .map(|(n, _)| flat::student_folder_name(n))
        .collect();
    for (k, (raw, path)) in folders.into_iter().enumerate() {
        // Two folders of one name (two students called alike) keep their own names.
        let unique = names.iter().filter(|n| **n == names[k]).count() == 1;
        submissions.students.push(Student {
            name: if unique { names[k].clone() } else { raw },
            handed_in: HandedIn::Folder(path),
        });
    }
    submissions.students.sort_by(|a, b| a.name.cmp(&b.name));
    if submissions.students.is_empty() {
        return Err(FolderError::NoStudent {
            role,
            path: folder.to_owned(),
        });
    }
    Ok(submissions)
}

/// The students of a flat class (`--flat`): `folder`'s files, named as Canvas or Moodle
/// name the files of a bulk download (see module `flat`), grouped by student; the files
/// named otherwise, and folders, are listed, not graded.
///
/// # Errors
/// Bad usage: the folder cannot be read, or holds no file named so.
pub fn flat_submissions(folder: &Path, role: &'static str) -> Result<Submissions, FolderError> {
    let entries = visible_entries(folder, role)?;
    let mut students: std::collections::BTreeMap<String, Vec<(OsString, PathBuf)>> =
        std::collections::BTreeMap::new();
    let mut submissions = Submissions::default();
    let mut has_folders = false;
    for (name, path) in entries {
        if path.is_dir() {
            has_folders = true;
            submissions.other.push(format!("{name}/"));
            continue;
        }
        match FlatName::parse(&name) {
            Some(parsed) => students
                .entry(parsed.student)
                .or_default()
                .push((OsString::from(parsed.file), path)),
            None => submissions.other.push(name),
        }
    }
    if students.is_empty() {
        return Err(FolderError::NoFlatSubmission {
            role,
            path: folder.to_owned(),
            has_folders,
        });
    }
    submissions.students = students
        .into_iter()
        .map(|(name, files)| Student {
            name,
            handed_in: HandedIn::Files(files),
        })
        .collect();
    Ok(submissions)
}

/// The entries of `folder` but hidden ones, sorted, with their names as shown.
fn visible_entries(
    folder: &Path,
    role: &'static str,
) -> Result<Vec<(String, PathBuf)>, FolderError> {
    let unreadable = |source| FolderError::Unreadable {
        role,
        path: folder.to_owned(),
        source,
    };
    let mut entries = Vec::new();
    for entry in std::fs::read_dir(folder).map_err(unreadable)? {
        let entry = entry.map_err(unreadable)?;
        let name = entry.file_name();
        if hidden(&name) {
            continue;
        }
        entries.push((name, entry.path()));
    }
    entries.sort();
    Ok(entries
        .into_iter()
        .map(|(name, path)| (name.to_string_lossy().into_owned(), path))
        .collect())
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
fn near_name(name: &OsStr, entries: &[Entry]) -> Option<String> {
    let lower = name.to_ascii_lowercase();
    let stem = Path::new(name).file_stem()?.to_ascii_lowercase();
    let files = entries.iter().filter(|e| !e.is_dir);
    files
        .clone()
        .find(|e| e.name.to_ascii_lowercase() == lower)
        .or_else(|| {
            files.clone().find(|e| {
                Path::new(&e.name)
                    .file_stem()
                    .is_some_and(|s| s.to_ascii_lowercase() == stem)
            })
        })
        .map(|e| e.name.to_string_lossy().into_owned())
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
            "d.ppm",
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
                Some(
                    "missing (found `c.jpg`: the image must be PNG, PPM/PGM (P2, P3, P5, P6) \
                     or OpenEXR, named `c` with the extension .png, .ppm, .pgm or .exr)"
                        .into()
                ),
                None,
            ]
        );
        // Another format of the same stem answers the reference.
        assert_eq!(
            pairing.counterparts[3],
            Counterpart::File(student.join("d.ppm"))
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
    fn a_reference_folder_without_images_is_bad_usage() {
        let dir = tempfile::tempdir().unwrap();
        touch(&dir.path().join("scene.ron"));
        let error = reference_images(dir.path(), "REFERENCE").unwrap_err();
        assert!(
            error
                .to_string()
                .contains("holds no image (*.png, *.ppm, *.pgm or *.exr file)"),
            "{error}"
        );
        touch(&dir.path().join("tower.PPM"));
        let found = reference_images(dir.path(), "REFERENCE").unwrap();
        assert_eq!(found[0].name, "tower.PPM");
    }

    #[test]
    fn a_single_nested_folder_is_descended_into() {
        let dir = tempfile::tempdir().unwrap();
        let (reference, henry) = (dir.path().join("reference"), dir.path().join("henry"));
        std::fs::create_dir_all(&reference).unwrap();
        std::fs::create_dir_all(henry.join("hw3/renders")).unwrap();
        std::fs::create_dir_all(henry.join("__MACOSX")).unwrap();
        touch(&reference.join("a.png"));
        touch(&henry.join("readme.txt"));
        touch(&henry.join("hw3/renders/a.png"));
        touch(&henry.join("hw3/renders/notes.txt"));
        let references = reference_images(&reference, "REFERENCE").unwrap();
        let pairing = pair(&henry, &references).unwrap();
        assert_eq!(
            pairing.counterparts,
            [Counterpart::File(henry.join("hw3/renders/a.png"))]
        );
        assert_eq!(pairing.extra, ["notes.txt"]);
        // Two folders, or an image beside the folder: no descent.
        std::fs::create_dir_all(henry.join("hw4")).unwrap();
        let pairing = pair(&henry, &references).unwrap();
        assert_eq!(pairing.extra, ["hw3/", "hw4/", "readme.txt"]);
    }

    #[test]
    fn a_flat_class_is_grouped_by_the_names_course_sites_give() {
        let dir = tempfile::tempdir().unwrap();
        let (reference, class) = (dir.path().join("reference"), dir.path().join("class"));
        std::fs::create_dir_all(&reference).unwrap();
        std::fs::create_dir_all(&class).unwrap();
        for name in ["cube.png", "tower.png"] {
            touch(&reference.join(name));
        }
        for name in [
            "lovelaceada_12_34_tower.ppm",
            "lovelaceada_late_12_35_cube-1.png",
            "Alan Turing_7_assignsubmission_file_tower.png",
            "grades.csv",
        ] {
            touch(&class.join(name));
        }
        let found = flat_submissions(&class, "SUBMISSIONS").unwrap();
        let names: Vec<&str> = found.students.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["Alan Turing", "lovelaceada"]);
        assert_eq!(found.other, ["grades.csv"]);
        let references = reference_images(&reference, "REFERENCE").unwrap();
        let ada = found.students[1].pair(&references).unwrap();
        assert_eq!(
            ada.counterparts,
            [
                Counterpart::File(class.join("lovelaceada_late_12_35_cube-1.png")),
                Counterpart::File(class.join("lovelaceada_12_34_tower.ppm")),
            ]
        );
        let alan = found.students[0].pair(&references).unwrap();
        assert_eq!(alan.counterparts[0], Counterpart::Missing { near: None });
        // Folders given as a flat class: bad usage, with a hint.
        let folders = dir.path().join("folders");
        std::fs::create_dir_all(folders.join("henry")).unwrap();
        let error = flat_submissions(&folders, "SUBMISSIONS").unwrap_err();
        assert!(error.to_string().contains("leave out --flat"), "{error}");
    }

    #[test]
    fn submissions_are_the_sub_folders_and_the_rest_is_listed() {
        let dir = tempfile::tempdir().unwrap();
        for name in [
            "bob",
            "alice",
            ".git",
            "carol",
            "Ada Lovelace_12_assignsubmission_file_",
        ] {
            std::fs::create_dir(dir.path().join(name)).unwrap();
        }
        touch(&dir.path().join("grades.xlsx"));
        let found = submissions(dir.path(), "SUBMISSIONS").unwrap();
        let names: Vec<&str> = found.students.iter().map(|s| s.name.as_str()).collect();
        assert_eq!(names, ["Ada Lovelace", "alice", "bob", "carol"]);
        assert_eq!(
            found.students[2].handed_in,
            HandedIn::Folder(dir.path().join("bob"))
        );
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

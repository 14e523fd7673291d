//! A class as a course site downloads it: the student's name taken from the names Canvas
//! and Moodle give the files of a bulk download ("Download all submissions").
//!
//! - Canvas puts every file in one folder as `lastnamefirstname_USERID_FILEID_NAME`, the
//!   student's name lowercase without spaces, `_late` after it when handed in late, NAME
//!   the file's own name, with `-1`, `-2`, ... before its extension for a resubmission:
//!   `lovelaceada_12345_67890_tower.png`, `lovelaceada_late_12345_67891_tower-1.png`.
//! - Moodle names each file `Full Name_PARTICIPANT_assignsubmission_file_NAME`
//!   (`Ada Lovelace_12345_assignsubmission_file_tower.png`), or with "download submissions
//!   in folders" puts NAME in a folder `Full Name_PARTICIPANT_assignsubmission_file_` (a
//!   class in folders: [`student_folder_name`] is its student).

use std::ffi::{OsStr, OsString};
use std::path::Path;

/// A Canvas file name, as the messages show it.
pub(crate) const CANVAS_EXAMPLE: &str = "lastnamefirstname_12345_67890_tower.png";
/// A Moodle file name, as the messages show it.
pub(crate) const MOODLE_EXAMPLE: &str = "Firstname Lastname_12345_assignsubmission_file_tower.png";

/// What Moodle puts between the participant number and the file's own name.
const MOODLE_MARK: &str = "_assignsubmission_file_";

/// A file name of a flat class, taken apart.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct FlatName {
    /// The student, as the course site names them.
    pub(crate) student: String,
    /// The file's own name, as the student gave it (a Canvas resubmission's `-1` kept).
    pub(crate) file: String,
}

impl FlatName {
    /// `name` taken apart as Moodle or Canvas name a bulk download's files; `None` for a
    /// name of neither form.
    pub(crate) fn parse(name: &str) -> Option<FlatName> {
        Self::moodle(name).or_else(|| Self::canvas(name))
    }

    /// `Full Name_PARTICIPANT_assignsubmission_file_NAME`.
    fn moodle(name: &str) -> Option<FlatName> {
        let (before, file) = name.split_once(MOODLE_MARK)?;
        let (student, participant) = before.rsplit_once('_')?;
        let numbered = !participant.is_empty() && participant.bytes().all(|b| b.is_ascii_digit());
        (numbered && !student.trim().is_empty() && !file.is_empty()).then(|| FlatName {
            student: student.trim().to_owned(),
            file: file.to_owned(),
        })
    }

    /// `name_[late_]USERID_FILEID_NAME`.
    fn canvas(name: &str) -> Option<FlatName> {
        let mut parts = name.splitn(2, '_');
        let student = parts.next()?;
        let mut rest = parts.next()?;
        if let Some(after) = rest
            .strip_prefix("late_")
            .or_else(|| rest.strip_prefix("LATE_"))
        {
            rest = after;
        }
        let number = |text: &str| !text.is_empty() && text.bytes().all(|b| b.is_ascii_digit());
        let mut fields = rest.splitn(3, '_');
        let (user, file_id, file) = (fields.next()?, fields.next()?, fields.next()?);
        let named = !student.is_empty() && !student.bytes().any(|b| b.is_ascii_digit());
        (named && number(user) && number(file_id) && !file.is_empty()).then(|| FlatName {
            student: student.to_owned(),
            file: file.to_owned(),
        })
    }
}

/// `name` without a resubmission's `-N` before its extension (`tower-1.png` is
/// `tower.png`), when `wanted` takes the shorter name; else `name` as it is.
pub(crate) fn without_resubmission(name: &OsStr, wanted: impl Fn(&OsStr) -> bool) -> OsString {
    if wanted(name) {
        return name.to_owned();
    }
    let path = Path::new(name);
    let (Some(stem), Some(extension)) = (
        path.file_stem().and_then(OsStr::to_str),
        path.extension().and_then(OsStr::to_str),
    ) else {
        return name.to_owned();
    };
    match stem.rsplit_once('-') {
        Some((base, number))
            if !base.is_empty()
                && !number.is_empty()
                && number.bytes().all(|b| b.is_ascii_digit()) =>
        {
            let shorter = OsString::from(format!("{base}.{extension}"));
            if wanted(&shorter) {
                shorter
            } else {
                name.to_owned()
            }
        }
        _ => name.to_owned(),
    }
}

/// The student a class's folder stands for: its name, without the participant number and
/// mark Moodle adds to a folder of a download in folders (`Ada
/// Lovelace_12345_assignsubmission_file_` is `Ada Lovelace`).
pub(crate) fn student_folder_name(folder: &str) -> String {
    let trimmed = folder
        .strip_suffix(MOODLE_MARK)
        .or_else(|| folder.strip_suffix(MOODLE_MARK.trim_end_matches('_')));
    trimmed
        .and_then(|before| before.rsplit_once('_'))
        .filter(|(student, participant)| {
            !student.trim().is_empty()
                && !participant.is_empty()
                && participant.bytes().all(|b| b.is_ascii_digit())
        })
        .map_or_else(
            || folder.to_owned(),
            |(student, _)| student.trim().to_owned(),
        )
}

#[cfg(test)]
mod tests {
    use super::*;

    fn parsed(name: &str) -> Option<(String, String)> {
        FlatName::parse(name).map(|f| (f.student, f.file))
    }

    fn pair(student: &str, file: &str) -> Option<(String, String)> {
        Some((student.to_owned(), file.to_owned()))
    }

    #[test]
    fn canvas_and_moodle_names_give_the_student_and_the_file() {
        assert_eq!(
            parsed("lovelaceada_12345_67890_tower.png"),
            pair("lovelaceada", "tower.png")
        );
        assert_eq!(
            parsed("lovelaceada_late_12345_67890_my_tower.ppm"),
            pair("lovelaceada", "my_tower.ppm")
        );
        assert_eq!(
            parsed("lovelaceada_LATE_12345_67890_tower-1.png"),
            pair("lovelaceada", "tower-1.png")
        );
        assert_eq!(
            parsed("Ada Lovelace_12345_assignsubmission_file_tower.png"),
            pair("Ada Lovelace", "tower.png")
        );
        assert_eq!(
            parsed("Jean-Luc Picard_7_assignsubmission_file_cube_2.png"),
            pair("Jean-Luc Picard", "cube_2.png")
        );
        for other in [
            "tower.png",
            "notes_final.txt",
            "ada_12_x_tower.png",
            "lovelaceada_12345_67890_",
            "Ada Lovelace_x_assignsubmission_file_tower.png",
            "Ada_12345_assignsubmission_onlinetext_onlinetext.html",
            "123_456_789_tower.png",
        ] {
            assert_eq!(parsed(other), None, "{other}");
        }
    }

    #[test]
    fn a_resubmission_number_goes_only_where_it_gives_a_wanted_name() {
        let wanted = |n: &OsStr| n == "tower.png" || n == "frame-2.png";
        let shorter = |n: &str| without_resubmission(OsStr::new(n), wanted);
        assert_eq!(shorter("tower-1.png"), "tower.png");
        assert_eq!(shorter("tower-12.png"), "tower.png");
        assert_eq!(shorter("frame-2.png"), "frame-2.png");
        assert_eq!(shorter("cube-1.png"), "cube-1.png");
        assert_eq!(shorter("tower-a.png"), "tower-a.png");
    }

    #[test]
    fn a_moodle_folder_is_its_students_name() {
        assert_eq!(
            student_folder_name("Ada Lovelace_12345_assignsubmission_file_"),
            "Ada Lovelace"
        );
        assert_eq!(
            student_folder_name("Ada Lovelace_12345_assignsubmission_file"),
            "Ada Lovelace"
        );
        assert_eq!(student_folder_name("henry"), "henry");
        assert_eq!(
            student_folder_name("x_assignsubmission_file_"),
            "x_assignsubmission_file_"
        );
    }
}

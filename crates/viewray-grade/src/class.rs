//! Grading a class: every student's folder judged against the assignment's prepared
//! references, students in parallel.

use std::io;

use image::imageops::FilterType;
use viewray_compare::{Comparison, Outcome, Reference, RgbImage, RgbaImage};

use crate::folders::{ReferenceImage, Student};
use crate::judging::{in_order, judge_counterpart};

/// The largest thumbnail of a report, in pixels: images are shrunk to fit, never grown.
pub const THUMBNAIL: (u32, u32) = (240, 180);

/// One image of the assignment: its file in REFERENCE, prepared for judging.
pub struct Task {
    /// The reference image's file.
    pub image: ReferenceImage,
    /// The reference, prepared once for the class.
    pub reference: Reference,
}

/// The assignment: the reference images every student's folder is paired with, in name
/// order.
pub struct Assignment {
    /// The images.
    pub tasks: Vec<Task>,
}

impl Assignment {
    /// The reference images' names, in order.
    pub fn names(&self) -> impl Iterator<Item = &str> {
        self.tasks.iter().map(|t| t.image.name.as_str())
    }
}

/// The pictures a report shows for a failed image: the student's render (when it could be
/// read) and the FLIP heatmap (when the sizes matched), as thumbnails.
#[derive(Clone, Debug, Default)]
pub struct Pictures {
    /// The student's render.
    pub actual: Option<RgbaImage>,
    /// The FLIP heatmap.
    pub heatmap: Option<RgbImage>,
}

/// One image of one student.
#[derive(Clone, Debug)]
pub struct ImageGrade {
    /// What became of it (without the FLIP error map).
    pub outcome: Outcome,
    /// Thumbnails for a report, when asked for and the image failed.
    pub pictures: Option<Pictures>,
}

/// How one student did.
#[derive(Clone, Debug)]
pub struct StudentGrade {
    /// The student's folder name.
    pub name: String,
    /// One grade per image of the assignment, in its order.
    pub images: Vec<ImageGrade>,
    /// The folder's files that no reference image has: listed, not judged.
    pub extra: Vec<String>,
}

impl StudentGrade {
    /// How many images passed.
    pub fn passed(&self) -> usize {
        self.images.iter().filter(|i| i.outcome.passed()).count()
    }

    /// Whether every image passed.
    pub fn passed_everything(&self) -> bool {
        self.passed() == self.images.len()
    }
}

/// `image` shrunk to fit in [`THUMBNAIL`] (kept as it is when it fits).
pub fn thumbnail<P: image::Pixel + 'static>(
    image: &image::ImageBuffer<P, Vec<P::Subpixel>>,
) -> image::ImageBuffer<P, Vec<P::Subpixel>> {
    let (w, h) = image.dimensions();
    let scale = (f64::from(THUMBNAIL.0) / f64::from(w.max(1)))
        .min(f64::from(THUMBNAIL.1) / f64::from(h.max(1)));
    if scale >= 1.0 {
        return image.clone();
    }
    let size = |n: u32| ((f64::from(n) * scale).round() as u32).max(1);
    image::imageops::resize(image, size(w), size(h), FilterType::Triangle)
}

/// Grades one student: each reference image paired with the file of its name in the
/// student's folder, and judged. A folder that cannot be read fails every image. With
/// `pictures`, each failed image keeps its thumbnails.
pub fn grade_student(assignment: &Assignment, student: &Student, pictures: bool) -> StudentGrade {
    let images: Vec<ReferenceImage> = assignment.tasks.iter().map(|t| t.image.clone()).collect();
    let pairing = match student.pair(&images) {
        Ok(pairing) => pairing,
        Err(error) => {
            let message = format!("cannot read the folder: {error}");
            return StudentGrade {
                name: student.name.clone(),
                images: images
                    .iter()
                    .map(|_| ImageGrade {
                        outcome: Outcome::Failed(message.clone()),
                        pictures: pictures.then(Pictures::default),
                    })
                    .collect(),
                extra: Vec::new(),
            };
        }
    };
    let grades = assignment
        .tasks
        .iter()
        .zip(&pairing.counterparts)
        .map(|(task, counterpart)| {
            let (actual, outcome) =
                judge_counterpart(&task.reference, counterpart, &task.image.name);
            let pictures = (pictures && !outcome.passed()).then(|| Pictures {
                actual: actual.as_ref().map(thumbnail),
                heatmap: outcome
                    .comparison()
                    .and_then(Comparison::heatmap)
                    .as_ref()
                    .map(thumbnail),
            });
            ImageGrade {
                outcome: outcome.without_error_map(),
                pictures,
            }
        })
        .collect();
    StudentGrade {
        name: student.name.clone(),
        images: grades,
        extra: pairing.extra,
    }
}

/// Grades every student, in parallel, and hands each grade to `emit` in the students'
/// order as soon as it and those before it are done; returns them all.
///
/// # Errors
/// The first error of `emit` (a closed pipe): the students not yet started are skipped.
pub fn grade_class(
    assignment: &Assignment,
    students: &[Student],
    pictures: bool,
    mut emit: impl FnMut(&StudentGrade) -> io::Result<()>,
) -> io::Result<Vec<StudentGrade>> {
    let mut grades = Vec::with_capacity(students.len());
    in_order(
        students,
        |student| grade_student(assignment, student, pictures),
        |grade| {
            emit(&grade)?;
            grades.push(grade);
            io::Result::Ok(())
        },
    )?;
    Ok(grades)
}

/// How the class did on one image.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ImageTally {
    /// The reference image's name.
    pub name: String,
    /// The students whose render passed.
    pub passed: usize,
    /// The students.
    pub total: usize,
}

impl ImageTally {
    /// The pass rate as the summary prints it ([`percent`]): `29%` for 2 of 7, `99.5%`
    /// for 199 of 200.
    pub fn percent(&self) -> String {
        percent(self.passed, self.total)
    }
}

/// `part` of `whole` in percent, rounded to the nearest whole percent (2 of 7 is `29%`),
/// with as many decimals as it takes (up to three) never to round a part that is not all
/// to `100%`, or one that is not none to `0%` (199 of 200 is `99.5%`, 1 of 1000 `0.1%`);
/// `100%` for none of none.
pub fn percent(part: usize, whole: usize) -> String {
    if whole == 0 || part == whole {
        return "100%".to_owned();
    }
    if part == 0 {
        return "0%".to_owned();
    }
    let exact = part as f64 * 100.0 / whole as f64;
    for decimals in 0..3 {
        let text = format!("{exact:.decimals$}");
        let value: f64 = text.parse().unwrap_or(exact);
        if value > 0.0 && value < 100.0 {
            return format!("{text}%");
        }
    }
    format!("{exact:.3}%")
}

/// How the class did.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct ClassSummary {
    /// The students.
    pub students: usize,
    /// The students who passed every image.
    pub passed_everything: usize,
    /// Each image's tally, in the assignment's order.
    pub images: Vec<ImageTally>,
    /// How many failed images each diagnosis explains ([`Outcome::summary_key`]), the
    /// most frequent first (then by name).
    pub diagnoses: Vec<(String, usize)>,
}

impl ClassSummary {
    /// Tallies `grades`.
    pub fn new(assignment: &Assignment, grades: &[StudentGrade]) -> Self {
        let images = assignment
            .names()
            .enumerate()
            .map(|(index, name)| ImageTally {
                name: name.to_owned(),
                passed: grades
                    .iter()
                    .filter(|g| g.images[index].outcome.passed())
                    .count(),
                total: grades.len(),
            })
            .collect();
        let mut counts: std::collections::BTreeMap<String, usize> = Default::default();
        for key in grades
            .iter()
            .flat_map(|g| &g.images)
            .filter_map(|i| i.outcome.summary_key())
        {
            *counts.entry(key).or_default() += 1;
        }
        let mut diagnoses: Vec<(String, usize)> = counts.into_iter().collect();
        diagnoses.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(&b.0)));
        Self {
            students: grades.len(),
            passed_everything: grades.iter().filter(|g| g.passed_everything()).count(),
            images,
            diagnoses,
        }
    }

    /// The images the fewest students passed (several when they tie), in name order;
    /// none when every student passed every image.
    pub fn hardest(&self) -> Vec<&ImageTally> {
        let failed = self.images.iter().filter(|i| i.passed < i.total);
        let Some(fewest) = failed.clone().map(|i| i.passed).min() else {
            return Vec::new();
        };
        failed.filter(|i| i.passed == fewest).collect()
    }

    /// Whether every student passed every image.
    pub fn all_passed(&self) -> bool {
        self.passed_everything == self.students
    }

    /// The first summary line, e.g. `200 students, 10 images each: 174 passed everything,
    /// 26 failed some`.
    pub fn headline(&self) -> String {
        let plural =
            |n: usize, one: &str, many: &str| format!("{n} {}", if n == 1 { one } else { many });
        format!(
            "{}, {} each: {} passed everything, {} failed some",
            plural(self.students, "student", "students"),
            plural(self.images.len(), "image", "images"),
            self.passed_everything,
            self.students - self.passed_everything
        )
    }

    /// The hardest image as a sentence, e.g. `hardest image: boxes.png, passed by 188 of
    /// 200 (94%)`, or every image tied for it (`hardest images: a.png and b.png, each
    /// passed by 3 of 7 (43%)`); `None` when every student passed every image.
    pub fn hardest_line(&self) -> Option<String> {
        let hardest = self.hardest();
        let first = hardest.first()?;
        let names: Vec<&str> = hardest.iter().map(|i| i.name.as_str()).collect();
        let (noun, each) = if names.len() == 1 {
            ("image", "")
        } else {
            ("images", "each ")
        };
        Some(format!(
            "hardest {noun}: {}, {each}passed by {} of {} ({})",
            joined(&names),
            first.passed,
            first.total,
            first.percent()
        ))
    }

    /// The diagnoses counted, as a sentence: `diagnoses: 12 mirrored: u-sign, 3
    /// missing`; `None` when nothing failed.
    pub fn diagnoses_line(&self) -> Option<String> {
        (!self.diagnoses.is_empty()).then(|| {
            let counted: Vec<String> = self
                .diagnoses
                .iter()
                .map(|(key, count)| format!("{count} {key}"))
                .collect();
            format!("failures: {}", counted.join(", "))
        })
    }
}

/// Names joined as a sentence: `a`, `a and b`, `a, b and c`.
fn joined(names: &[&str]) -> String {
    match names {
        [] => String::new(),
        [one] => (*one).to_owned(),
        [rest @ .., last] => format!("{} and {last}", rest.join(", ")),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn percentages_round_but_never_to_all_or_none() {
        let cases = [
            ((2, 7), "29%"),
            ((1, 3), "33%"),
            ((199, 200), "99.5%"),
            ((1999, 2000), "99.95%"),
            ((1, 200), "0.5%"),
            ((1, 1000), "0.1%"),
            ((0, 5), "0%"),
            ((5, 5), "100%"),
            ((0, 0), "100%"),
            ((1, 2), "50%"),
        ];
        for ((part, whole), want) in cases {
            assert_eq!(percent(part, whole), want, "{part} of {whole}");
        }
    }

    #[test]
    fn tied_hardest_images_are_all_named() {
        let tally = |name: &str, passed| ImageTally {
            name: name.to_owned(),
            passed,
            total: 7,
        };
        let mut summary = ClassSummary {
            students: 7,
            passed_everything: 2,
            images: vec![tally("a.png", 3), tally("b.png", 5), tally("c.png", 3)],
            diagnoses: vec![
                ("mirrored: u-sign".to_owned(), 4),
                ("missing".to_owned(), 2),
            ],
        };
        let names: Vec<&str> = summary.hardest().iter().map(|i| i.name.as_str()).collect();
        assert_eq!(names, ["a.png", "c.png"]);
        assert_eq!(
            summary.hardest_line().unwrap(),
            "hardest images: a.png and c.png, each passed by 3 of 7 (43%)"
        );
        assert_eq!(
            summary.diagnoses_line().unwrap(),
            "failures: 4 mirrored: u-sign, 2 missing"
        );
        summary.images[2].passed = 4;
        assert_eq!(
            summary.hardest_line().unwrap(),
            "hardest image: a.png, passed by 3 of 7 (43%)"
        );
        summary.images = vec![tally("a.png", 7)];
        assert_eq!(summary.hardest_line(), None);
    }
}

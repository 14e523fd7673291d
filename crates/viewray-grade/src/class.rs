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
    /// The pass rate in whole percent, rounded down (so 199 of 200 is 99%, not 100%).
    pub fn percent(&self) -> usize {
        (self.passed * 100).checked_div(self.total).unwrap_or(100)
    }
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
        Self {
            students: grades.len(),
            passed_everything: grades.iter().filter(|g| g.passed_everything()).count(),
            images,
        }
    }

    /// The image the fewest students passed (the first of them in name order), unless
    /// every student passed every image.
    pub fn hardest(&self) -> Option<&ImageTally> {
        self.images
            .iter()
            .filter(|i| i.passed < i.total)
            .min_by_key(|i| i.passed)
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
    /// 200 (94%)`, or `None` when every student passed every image.
    pub fn hardest_line(&self) -> Option<String> {
        self.hardest().map(|i| {
            format!(
                "hardest image: {}, passed by {} of {} ({}%)",
                i.name,
                i.passed,
                i.total,
                i.percent()
            )
        })
    }
}

//! What grading a submission came to: one [`TestResult`] per test, in the assignment's
//! order, which every platform's format writes in its own words.

use std::time::Duration;

use crate::assignment::Visibility;

/// Whether a test passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Status {
    /// Full points.
    Passed,
    /// Fewer than full points (partial credit included).
    Failed,
}

/// A small picture for the student: the reference, theirs, or the difference.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Thumbnail {
    /// What it shows: `expected`, `yours`, `difference`.
    pub label: String,
    /// The PNG file's bytes.
    pub png: Vec<u8>,
}

impl Thumbnail {
    /// The picture as a `data:image/png;base64,...` URI.
    pub fn data_uri(&self) -> String {
        use base64::Engine as _;
        format!(
            "data:image/png;base64,{}",
            base64::engine::general_purpose::STANDARD.encode(&self.png)
        )
    }
}

/// One test, graded.
#[derive(Clone, Debug, PartialEq)]
pub struct TestResult {
    /// The test's name.
    pub name: String,
    /// Its points.
    pub max_score: f64,
    /// The points earned.
    pub score: f64,
    /// Passed or failed.
    pub status: Status,
    /// Who sees it, when.
    pub visibility: Visibility,
    /// One line: the verdict and why.
    pub message: String,
    /// The details: the diagnosis with the formula line to fix, the answers judged, what
    /// the program printed.
    pub output: String,
    /// Expected, yours and the difference, for a picture that was read.
    pub images: Vec<Thumbnail>,
    /// What was run or judged, as a command a student can run again.
    pub command: String,
    /// How long the test took, the program's run included.
    pub duration: Duration,
}

impl TestResult {
    /// What a student sees on a platform that cannot hide a result until later: the
    /// message and output for a visible test, a sentence saying when for the others.
    pub fn shown(&self) -> Shown<'_> {
        match self.visibility {
            Visibility::Visible => Shown {
                message: &self.message,
                output: &self.output,
                images: &self.images,
            },
            Visibility::AfterDueDate => Shown {
                message: "the details of this test are shown after the due date",
                output: "",
                images: &[],
            },
            Visibility::Hidden => Shown {
                message: "the details of this test are hidden",
                output: "",
                images: &[],
            },
        }
    }
}

/// A test as a student may see it now.
#[derive(Clone, Copy, Debug)]
pub struct Shown<'a> {
    /// The message.
    pub message: &'a str,
    /// The details.
    pub output: &'a str,
    /// The pictures.
    pub images: &'a [Thumbnail],
}

/// A submission, graded.
#[derive(Clone, Debug, PartialEq)]
pub struct Results {
    /// The assignment's title (or its file's name when it could not be read).
    pub title: String,
    /// The tests, in the assignment's order.
    pub tests: Vec<TestResult>,
    /// Why the submission could not be graded at all (a broken assignment, a missing
    /// submission folder): then `tests` is empty and the score 0.
    pub problem: Option<String>,
    /// What the whole submission should know (a link left out of the copy, say).
    pub notes: Vec<String>,
    /// How long grading took.
    pub elapsed: Duration,
}

impl Results {
    /// Results that say only why nothing could be graded.
    pub fn problem(
        title: impl Into<String>,
        problem: impl Into<String>,
        elapsed: Duration,
    ) -> Results {
        Results {
            title: title.into(),
            tests: Vec::new(),
            problem: Some(problem.into()),
            notes: Vec::new(),
            elapsed,
        }
    }

    /// The points earned.
    pub fn score(&self) -> f64 {
        self.tests.iter().map(|t| t.score).sum()
    }

    /// The points there were.
    pub fn max_score(&self) -> f64 {
        self.tests.iter().map(|t| t.max_score).sum()
    }

    /// Whether every test passed (and there was no problem).
    pub fn all_passed(&self) -> bool {
        self.problem.is_none() && self.tests.iter().all(|t| t.status == Status::Passed)
    }

    /// One paragraph for the whole submission: the title, the points, what failed, the
    /// notes; or the problem.
    pub fn summary(&self) -> String {
        if let Some(problem) = &self.problem {
            return format!("{}: not graded: {problem}", self.title);
        }
        let passed = self
            .tests
            .iter()
            .filter(|t| t.status == Status::Passed)
            .count();
        let mut text = format!(
            "{}: {} of {} points; {passed} of {} tests passed",
            self.title,
            points(self.score()),
            points(self.max_score()),
            self.tests.len()
        );
        for note in &self.notes {
            text.push('\n');
            text.push_str(note);
        }
        text
    }
}

/// Points as people write them: `2`, `1.5`, `0.25`.
pub fn points(value: f64) -> String {
    let rounded = (value * 1e6).round() / 1e6;
    let text = format!("{rounded}");
    if text == "-0" { "0".to_owned() } else { text }
}

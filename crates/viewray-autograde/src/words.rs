//! The words of a verdict for a student: the camera's (with the catalogue entry's
//! formula line to fix), the appearance's, the answers', and the thumbnails beside them.

use std::fmt::Write as _;

use viewray_camera::{Mistake, Mistakes};
use viewray_compare::{Comparison, RgbImage, RgbaImage};
use viewray_judge::{CameraVerdict, IndexHint, Judged, Report};
use viewray_output::{Compression, encode_png};

use crate::results::Thumbnail;

/// The camera's verdict: a headline, and the details (the entry's formula lines).
pub(crate) fn camera_words(verdict: &CameraVerdict) -> (String, String) {
    match verdict {
        CameraVerdict::Right { agreement } => (
            "the camera is right".to_owned(),
            format!(
                "camera: right (the picture's edges agree with the scene's at {})",
                percent(*agreement)
            ),
        ),
        CameraVerdict::Mistaken { explanation, right } => {
            let mistakes: Vec<Mistake> = explanation.mistakes.clone();
            let ids: Vec<&str> = mistakes.iter().map(|m| m.id()).collect();
            let headline = match mistakes.as_slice() {
                [one] => format!(
                    "the camera is wrong: {} ({})",
                    one.id(),
                    one.entry().summary
                ),
                _ => format!(
                    "the camera is wrong: {} (the same picture of this scene)",
                    ids.join(" or ")
                ),
            };
            let mut details = format!(
                "camera: wrong; the catalogue explains the picture: {} (its edges agree at {}, \
                 the right camera's at {})",
                ids.join(" or "),
                percent(explanation.agreement),
                percent(*right)
            );
            for mistake in &mistakes {
                details.push('\n');
                details.push_str(&entry_lines(*mistake, mistakes.len() > 1));
            }
            (headline, details)
        }
        CameraVerdict::Unexplained { right, closest } => {
            let mut details = format!(
                "camera: wrong; no entry of the catalogue explains the picture (the right \
                 camera's edges agree at {})",
                percent(*right)
            );
            if let Some(closest) = closest {
                let ids: Vec<&str> = closest.mistakes.iter().map(|m| m.id()).collect();
                let _ = write!(
                    details,
                    "; closest: {} at {}",
                    ids.join(" or "),
                    percent(closest.agreement)
                );
            }
            (
                "the camera is wrong, and no entry of the catalogue explains it".to_owned(),
                details,
            )
        }
        CameraVerdict::WrongSize { found, expected } => {
            let text = format!(
                "the picture is {}x{} pixels, but the scene's image is {}x{}",
                found.0, found.1, expected.0, expected.1
            );
            (text.clone(), format!("camera: {text}"))
        }
    }
}

/// An entry's lines: what was written, the lecture's line to fix, what it does.
fn entry_lines(mistake: Mistake, named: bool) -> String {
    let entry = mistake.entry();
    let mut text = String::new();
    if named {
        let _ = writeln!(text, "  {}: {}", entry.id, entry.summary);
    }
    let _ = write!(
        text,
        "    you wrote:        {}\n    the lecture says: {}\n    in the picture:   {}",
        entry.mistaken, entry.fix, entry.picture
    );
    text
}

/// The appearance's verdict: a headline and a line (how far from the reference, not why).
pub(crate) fn appearance_words(comparison: &Comparison) -> (String, String) {
    let peak = comparison
        .metrics
        .map(|m| format!("peak FLIP {:.3}", m.peak_flip))
        .unwrap_or_default();
    if comparison.passed() {
        return (
            "the picture looks like the reference".to_owned(),
            format!("appearance: like the reference ({peak})"),
        );
    }
    // The camera is the camera judge's to name (camera first): compare's own guess at a
    // camera transform, made from the pixels alone, would contradict it when the shading
    // differs, so the appearance says only how far it is from the reference.
    let line = format!(
        "appearance: differs from the reference: {}",
        comparison.reasons()
    );
    (
        "the picture does not look like the reference".to_owned(),
        line,
    )
}

/// A student's answers judged: a headline, and the details (the wrong answers, at most
/// `shown` of them, then the catalogue's explanation).
pub(crate) fn answers_words(judged: &[Judged], report: &Report, shown: usize) -> (String, String) {
    let headline = if report.passed() {
        format!("all {} answers are right", report.answers)
    } else {
        let mut text = format!("{} of {} answers are wrong", report.wrong, report.answers);
        if let Some(diagnosis) = &report.diagnosis {
            let names: Vec<String> = diagnosis
                .alternatives
                .iter()
                .map(Mistakes::to_string)
                .collect();
            let _ = write!(
                text,
                ": the catalogue explains them: {}",
                names.join(" or ")
            );
        }
        text
    };
    let mut details = String::new();
    let wrong: Vec<&Judged> = judged.iter().filter(|j| !j.right).collect();
    for judged in wrong.iter().take(shown) {
        let _ = writeln!(details, "{judged}");
    }
    if wrong.len() > shown {
        let _ = writeln!(
            details,
            "... and {} more wrong answers",
            wrong.len() - shown
        );
    }
    if !details.is_empty() {
        details.push('\n');
    }
    // The report's own hint names a command-line flag; here the test says which
    // indices it takes.
    let without_hint = Report {
        index_hint: None,
        ..report.clone()
    };
    let _ = write!(details, "{without_hint}");
    if let Some(hint) = report.index_hint {
        let _ = write!(
            details,
            "\n{}",
            match hint {
                IndexHint::OneBased =>
                    "your rows and columns look 1-based (the lecture's i, j), but this test numbers \
                     pixels from 0 (row, col from the top-left)",
                IndexHint::ZeroBased =>
                    "your rows and columns look 0-based, but this test takes the lecture's 1-based \
                     i, j",
            }
        );
    }
    (headline, details)
}

/// A fraction as a whole percentage: `97%`.
fn percent(fraction: f64) -> String {
    format!("{:.0}%", (fraction * 100.0).clamp(0.0, 100.0))
}

/// The widest thumbnail, in pixels: pictures wider are shrunk by a whole factor.
const THUMBNAIL_WIDTH: u32 = 200;

/// A thumbnail of an RGBA picture (shown without its alpha).
pub(crate) fn thumbnail(label: &str, image: &RgbaImage) -> Option<Thumbnail> {
    let rgb = RgbImage::from_fn(image.width(), image.height(), |x, y| {
        let p = image.get_pixel(x, y).0;
        image::Rgb([p[0], p[1], p[2]])
    });
    thumbnail_rgb(label, &rgb)
}

/// A thumbnail of an RGB picture: shrunk by box averaging to at most
/// [`THUMBNAIL_WIDTH`] pixels wide.
pub(crate) fn thumbnail_rgb(label: &str, image: &RgbImage) -> Option<Thumbnail> {
    let factor = image.width().div_ceil(THUMBNAIL_WIDTH).max(1);
    let (width, height) = (image.width() / factor, image.height() / factor);
    if width == 0 || height == 0 {
        return None;
    }
    let small = RgbImage::from_fn(width, height, |x, y| {
        let mut sum = [0_u32; 3];
        for dy in 0..factor {
            for dx in 0..factor {
                let p = image.get_pixel(x * factor + dx, y * factor + dy).0;
                for c in 0..3 {
                    sum[c] += u32::from(p[c]);
                }
            }
        }
        let n = factor * factor;
        image::Rgb(sum.map(|s| ((s + n / 2) / n) as u8))
    });
    let png = encode_png(&small, Compression::Smallest).ok()?;
    Some(Thumbnail {
        label: label.to_owned(),
        png,
    })
}

//! The JSON lines of `viewray compare` and `viewray grade`: one line per pair judged (a
//! student's image, for grade), then one summary line.
//!
//! ```text
//! a pair:     {"name":..,"verdict":..,"peak_flip":..,"mean_flip":..,"threshold":..,
//!              "diagnosis":[..],"transform":{..},"reasons":[..],"judge":..,"camera":..,
//!              "camera_diagnosis":..,"catalogue":[..],"appearance":..}
//! an image:   {"student":..,"name":.., the pair's fields}
//! summaries:  {"summary":{"total":..,"passed":..,"failed":..,"missing_or_unreadable":..,"extra":[..]}}
//!             {"summary":{"students":..,"images":..,"passed_everything":..,"per_image":[..],
//!              "hardest":[..],"failures":{..},"not_graded":[..]}}
//! ```
//!
//! FLIP figures, the transform's numbers and the threshold are rounded to 4 decimals; what
//! a pair lacks (figures when it was not compared, a diagnosis when none was found, the
//! camera when no scene judged it) is `null`. `judge` says which judgement decided
//! (`camera`, `image` or `both`), `camera` is `right`, `wrong` or `unjudged` (too weak
//! edges to judge it: the image judgement decided), `catalogue` the ids of
//! the lecture's mistakes that explain a wrong camera, `appearance` how the picture looks
//! beside the reference (`same`, `gamma-missing`, `gamma-twice`, `brighter`, `darker`,
//! `shading`, `noise`).

use serde_json::{Map, Value, json};
use viewray_compare::{Diagnosis, Outcome, Tally};
use viewray_grade::ClassSummary;

/// The line of one pair: its `name`, then what became of it ([`Outcome`]) against the
/// FLIP `threshold` it was judged by.
pub fn pair_line(name: &str, outcome: &Outcome, threshold: f32) -> Value {
    let mut line = Map::new();
    line.insert("name".into(), json!(name));
    outcome_fields(&mut line, outcome, threshold);
    Value::Object(line)
}

/// The line of one image of one student: the `student`'s folder name, the image's
/// `name`, then the fields of [`pair_line`].
pub fn student_image_line(student: &str, name: &str, outcome: &Outcome, threshold: f32) -> Value {
    let mut line = Map::new();
    line.insert("student".into(), json!(student));
    line.insert("name".into(), json!(name));
    outcome_fields(&mut line, outcome, threshold);
    Value::Object(line)
}

/// The summary line of a set of pairs: the [`Tally`], and the `extra` files on the
/// actual side that no reference image has.
pub fn pairs_summary_line(tally: &Tally, extra: &[String]) -> Value {
    json!({"summary": {
        "total": tally.total(),
        "passed": tally.passed,
        "failed": tally.failed,
        "missing_or_unreadable": tally.not_compared,
        "extra": extra,
    }})
}

/// The summary line of a class: the [`ClassSummary`], and the entries of the class's
/// folder that are not a student's folder (`not_graded`).
pub fn class_summary_line(summary: &ClassSummary, not_graded: &[String]) -> Value {
    let per_image: Vec<Value> = summary
        .images
        .iter()
        .map(|i| json!({"name": i.name, "passed": i.passed, "total": i.total}))
        .collect();
    json!({"summary": {
        "students": summary.students,
        "images": summary.images.len(),
        "passed_everything": summary.passed_everything,
        "per_image": per_image,
        "hardest": summary.hardest().iter().map(|i| i.name.clone()).collect::<Vec<_>>(),
        "failures": summary
            .diagnoses
            .iter()
            .map(|(key, count)| (key.clone(), json!(count)))
            .collect::<Map<String, Value>>(),
        "not_graded": not_graded,
    }})
}

/// A figure, rounded to 4 decimals.
fn figure(value: f32) -> Value {
    json!((f64::from(value) * 1e4).round() / 1e4)
}

/// A pair's fields after its name: verdict, figures, diagnosis, transform, reasons.
fn outcome_fields(line: &mut Map<String, Value>, outcome: &Outcome, threshold: f32) {
    let (metrics, diagnosis, reasons) = match outcome {
        Outcome::Compared(c) => (
            c.metrics,
            c.diagnosis,
            c.failures.iter().map(ToString::to_string).collect(),
        ),
        Outcome::Failed(message) | Outcome::Error(message) => (None, None, vec![message.clone()]),
    };
    line.insert("verdict".into(), json!(outcome.verdict().word()));
    line.insert(
        "peak_flip".into(),
        metrics.map_or(Value::Null, |m| figure(m.peak_flip)),
    );
    line.insert(
        "mean_flip".into(),
        metrics.map_or(Value::Null, |m| figure(m.mean_flip)),
    );
    line.insert("threshold".into(), figure(threshold));
    line.insert(
        "diagnosis".into(),
        diagnosis.map_or(Value::Null, |d| json!(d.messages())),
    );
    line.insert(
        "transform".into(),
        diagnosis
            .as_ref()
            .and_then(Diagnosis::camera_mistake)
            .map_or(Value::Null, |m| {
                json!({
                    "mirrored_left_right": m.mirrored_left_right,
                    "upside_down": m.upside_down,
                    "rotation": figure(m.rotation as f32),
                    "scale": [figure(m.scale.0 as f32), figure(m.scale.1 as f32)],
                    "about": [figure(m.about.0 as f32), figure(m.about.1 as f32)],
                    "shift": [figure(m.shift.0 as f32), figure(m.shift.1 as f32)],
                })
            }),
    );
    line.insert("reasons".into(), json!(reasons));
    let comparison = outcome.comparison();
    line.insert(
        "judge".into(),
        comparison.map_or(Value::Null, |c| json!(c.judge.word())),
    );
    let camera = outcome.camera();
    line.insert(
        "camera".into(),
        camera.map_or(Value::Null, |c| json!(c.word())),
    );
    line.insert(
        "camera_diagnosis".into(),
        camera
            .filter(|c| !c.passed())
            .map_or(Value::Null, |c| json!(c.diagnosis())),
    );
    line.insert(
        "catalogue".into(),
        json!(camera.map(|c| c.ids()).unwrap_or_default()),
    );
    line.insert(
        "appearance".into(),
        outcome.appearance().map_or(Value::Null, |a| json!(a.id())),
    );
}

#[cfg(test)]
mod tests {
    use viewray_compare::{InstructorThresholds, RgbaImage, judge};
    use viewray_grade::ImageTally;

    use super::*;

    fn text(value: &Value) -> String {
        serde_json::to_string(value).unwrap()
    }

    #[test]
    fn a_pair_not_compared_has_null_figures_and_its_reason() {
        let outcome = Outcome::Failed("missing".to_owned());
        assert_eq!(
            text(&pair_line("a.png", &outcome, 0.3)),
            r#"{"name":"a.png","verdict":"fail","peak_flip":null,"mean_flip":null,"threshold":0.3,"diagnosis":null,"transform":null,"reasons":["missing"],"judge":null,"camera":null,"camera_diagnosis":null,"catalogue":[],"appearance":null}"#
        );
        assert_eq!(
            text(&student_image_line("alice", "a.png", &outcome, 0.123_456)),
            r#"{"student":"alice","name":"a.png","verdict":"fail","peak_flip":null,"mean_flip":null,"threshold":0.1235,"diagnosis":null,"transform":null,"reasons":["missing"],"judge":null,"camera":null,"camera_diagnosis":null,"catalogue":[],"appearance":null}"#
        );
    }

    #[test]
    fn a_pair_that_passed_has_its_figures_and_no_diagnosis() {
        let pixels = (0..32 * 24 * 4).map(|i| (i * 7 % 251) as u8).collect();
        let image = RgbaImage::from_raw(32, 24, pixels).unwrap();
        let outcome = Outcome::from(judge(&image, &image, &InstructorThresholds::default()));
        assert_eq!(
            text(&pair_line("same.png", &outcome, 0.3)),
            r#"{"name":"same.png","verdict":"pass","peak_flip":0.0,"mean_flip":0.0,"threshold":0.3,"diagnosis":null,"transform":null,"reasons":[],"judge":"image","camera":null,"camera_diagnosis":null,"catalogue":[],"appearance":"same"}"#
        );
    }

    #[test]
    fn the_summaries_count_what_the_lines_said() {
        let tally = Tally {
            passed: 1,
            failed: 2,
            not_compared: 1,
        };
        assert_eq!(
            text(&pairs_summary_line(&tally, &["notes.txt".to_owned()])),
            r#"{"summary":{"total":3,"passed":1,"failed":2,"missing_or_unreadable":1,"extra":["notes.txt"]}}"#
        );
        let tally = |name: &str, passed| ImageTally {
            name: name.to_owned(),
            passed,
            total: 2,
        };
        let class = ClassSummary {
            students: 2,
            passed_everything: 1,
            images: vec![tally("a.png", 2), tally("b.png", 1)],
            diagnoses: vec![("mirrored: u-sign".to_owned(), 1)],
        };
        assert_eq!(
            text(&class_summary_line(&class, &[])),
            r#"{"summary":{"students":2,"images":2,"passed_everything":1,"per_image":[{"name":"a.png","passed":2,"total":2},{"name":"b.png","passed":1,"total":2}],"hardest":["b.png"],"failures":{"mirrored: u-sign":1},"not_graded":[]}}"#
        );
    }
}

//! The printouts for `viewray check`, spelled out by hand for the canonical camera of a
//! 2 x 2 image: its frame, the ray of pixel (0, 0) and where (0.25, 0.25, -1) appears.

use super::v;
use crate::support::student::{
    Answer, AnswerStyle, CameraSpec, Mistake, Number, Syntax, Vec3, write_answers,
};

fn answers() -> Vec<Answer> {
    let camera = CameraSpec::canonical();
    vec![
        Answer::frame(&camera, &[]),
        Answer::ray(&camera, &[], (2, 2), (0, 0)),
        Answer::project(&camera, (2, 2), v(0.25, 0.25, -1.0)),
        Answer::project(&camera, (2, 2), v(-1.0, 0.0, 1.0)),
    ]
}

#[track_caller]
fn check(style: AnswerStyle, expected: &str) {
    assert_eq!(write_answers(&answers(), &style), expected);
}

#[test]
fn viewrays_json_lines() {
    check(
        AnswerStyle::default(),
        concat!(
            r#"{"e":[0.0,0.0,0.0],"u":[1.0,0.0,0.0],"v":[0.0,1.0,0.0],"w":[0.0,0.0,1.0]}"#,
            "\n",
            r#"{"row":0,"col":0,"origin":[0.0,0.0,0.0],"direction":[-0.25,0.25,-1.0]}"#,
            "\n",
            r#"{"point":[0.25,0.25,-1.0],"x":1.5,"y":0.5,"row":0,"col":1}"#,
            "\n",
            r#"{"point":[-1.0,0.0,1.0],"x":null,"y":null,"row":null,"col":null}"#,
            "\n",
        ),
    );
    // Every line is JSON.
    for line in write_answers(&answers(), &AnswerStyle::default()).lines() {
        serde_json::from_str::<serde_json::Value>(line).unwrap();
    }
}

#[test]
fn json_one_based_normalized_spaced_crlf() {
    let style = AnswerStyle {
        one_based: true,
        normalized: true,
        extra_spaces: true,
        crlf: true,
        number: Number::Fixed(3),
        ..AnswerStyle::default()
    };
    let text = write_answers(&answers()[1..3], &style);
    // |(-0.25, 0.25, -1)| = sqrt(1.125) = 1.06066: (-0.2357, 0.2357, -0.9428).
    assert_eq!(
        text,
        concat!(
            r#"  {"i": 1, "j": 1, "origin": [0.000, 0.000, 0.000], "direction": [-0.236, 0.236, -0.943]}"#,
            "\r\n",
            r#"  {"point": [0.250, 0.250, -1.000], "x": 1.500, "y": 0.500, "i": 1, "j": 2}"#,
            "\r\n",
        )
    );
}

#[test]
fn plain_words() {
    check(
        AnswerStyle {
            syntax: Syntax::Words,
            ..AnswerStyle::default()
        },
        "frame 0 0 0 1 0 0 0 1 0 0 0 1\n\
         ray 0 0 0 0 0 -0.25 0.25 -1\n\
         project 0.25 0.25 -1 1.5 0.5\n\
         project -1 0 1 null null\n",
    );
}

#[test]
fn words_with_comments_spaces_and_one_based_indices() {
    let style = AnswerStyle {
        syntax: Syntax::Words,
        one_based: true,
        extra_spaces: true,
        comments: true,
        ..AnswerStyle::default()
    };
    let text = write_answers(&answers()[1..2], &style);
    assert_eq!(
        text,
        "# the camera homework's answers, printed by my ray tracer\n\
         #   viewing rays\n   \
         ray \t  1 \t  1 \t  0 \t  0 \t  0 \t  -0.25 \t  0.25 \t  -1  \n"
    );
}

#[test]
fn comma_separated() {
    let style = AnswerStyle {
        syntax: Syntax::Csv,
        number: Number::Exponent,
        ..AnswerStyle::default()
    };
    assert_eq!(
        write_answers(&answers()[1..3], &style),
        "ray,0,0,0e0,0e0,0e0,-2.5e-1,2.5e-1,-1e0\nproject,2.5e-1,2.5e-1,-1e0,1.5e0,5e-1\n"
    );
    let spaced = AnswerStyle {
        syntax: Syntax::Csv,
        extra_spaces: true,
        crlf: true,
        ..AnswerStyle::default()
    };
    assert_eq!(
        write_answers(&answers()[1..2], &spaced),
        "   ray, 0, 0, 0, 0, 0, -0.25, 0.25, -1  \r\n"
    );
}

/// A mistaken student's printout holds the mistaken numbers: v-sign's ray for pixel (0, 0)
/// of the canonical 2 x 2 image goes down, (-0.25, -0.25, -1).
#[test]
fn a_mistaken_students_answers() {
    let camera = CameraSpec::canonical();
    let answer = Answer::ray(&camera, &[Mistake::VSign], (2, 2), (0, 0));
    let Answer::Ray { direction, .. } = answer else {
        panic!("{answer:?}");
    };
    assert_eq!(direction, Vec3::new(-0.25, -0.25, -1.0));
    let style = AnswerStyle {
        syntax: Syntax::Words,
        ..AnswerStyle::default()
    };
    assert_eq!(
        write_answers(&[answer], &style),
        "ray 0 0 0 0 0 -0.25 -0.25 -1\n"
    );
}

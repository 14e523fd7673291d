//! What a student's program printed: frames, rays and projections, read line by line.
//!
//! Two spellings are read, one per file:
//!
//! - viewray's own JSON lines, with the keys of `viewray frame` (`e`, `u`, `v`, `w`),
//!   `viewray rays` (`row`, `col` or the 1-based `i`, `j`; `origin`, `direction`;
//!   optionally `u`, `v`) and `viewray project` (`point`, `x`, `y`);
//! - plain lines of numbers, separated by white space or commas:
//!   `frame ex ey ez ux uy uz vx vy vz wx wy wz`, `ray ROW COL ox oy oz dx dy dz`,
//!   `project px py pz x y` (`x y` may be `null null` for a point not seen).
//!
//! Blank lines and `#` comments are skipped; line ends may be CRLF. The reader streams: it
//! holds one line at a time, whatever the file's size.

use std::io::BufRead;

use glam::DVec3;
use serde_json::Value;

/// One answer of a student's program.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Answer {
    /// The camera frame (Problem 2).
    Frame {
        /// `e`.
        e: DVec3,
        /// `u`.
        u: DVec3,
        /// `v`.
        v: DVec3,
        /// `w`.
        w: DVec3,
    },
    /// A viewing ray (Problem 1), for a pixel as the file numbers it.
    Ray {
        /// The pixel's row (or `i`), as written.
        row: i64,
        /// The pixel's column (or `j`), as written.
        col: i64,
        /// Whether the line itself says its indices are 1-based (JSON `i`, `j`).
        one_based: bool,
        /// The image-plane point `(u, v)`, if the line gives it.
        uv: Option<(f64, f64)>,
        /// The ray's origin.
        origin: DVec3,
        /// The ray's direction.
        direction: DVec3,
    },
    /// Where a point appears: continuous image coordinates, or not seen.
    Project {
        /// The world point.
        point: DVec3,
        /// `(x, y)`, or `None` for a point the student says is not seen.
        xy: Option<(f64, f64)>,
    },
}

impl Answer {
    /// What the answer is of, as its plain line starts: `frame`, `ray` or `project`.
    pub fn kind(&self) -> &'static str {
        match self {
            Answer::Frame { .. } => "frame",
            Answer::Ray { .. } => "ray",
            Answer::Project { .. } => "project",
        }
    }
}

/// Why an answers file cannot be read: its line (1-based; 0 for the file as a whole)
/// and what was expected there.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{}{message}", if *line == 0 { String::new() } else { format!("line {line}: ") })]
pub struct AnswerError {
    /// The line, from 1; 0 when the file as a whole is wrong (empty, unreadable).
    pub line: u64,
    /// What was expected.
    pub message: String,
}

/// The spelling of an answers file, fixed by its first answer.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Spelling {
    Json,
    Plain,
}

/// Reads answers from `input` one line at a time: each item is the answer and its line
/// number, or the first error (after which the reader stops). An input with no answer
/// at all is an error too.
pub fn read_answers(
    input: impl BufRead,
) -> impl Iterator<Item = Result<(u64, Answer), AnswerError>> {
    let mut lines = input.split(b'\n');
    let mut number = 0_u64;
    let mut spelling = None;
    let mut done = false;
    let mut any = false;
    std::iter::from_fn(move || {
        while !done {
            let Some(line) = lines.next() else {
                done = true;
                return (!any).then(|| {
                    Err(AnswerError {
                        line: 0,
                        message: "no answers: expected lines such as `ray 0 0 ox oy oz dx dy dz` \
                                  or viewray's JSON lines"
                            .to_owned(),
                    })
                });
            };
            number += 1;
            let fail = |message: String| AnswerError {
                line: number,
                message,
            };
            let line = match line {
                Ok(line) => line,
                Err(error) => {
                    done = true;
                    return Some(Err(fail(format!("cannot be read: {error}"))));
                }
            };
            let Ok(text) = std::str::from_utf8(&line) else {
                done = true;
                return Some(Err(fail("is not text (UTF-8)".to_owned())));
            };
            let text = text.trim_end_matches('\r').trim();
            if text.is_empty() || text.starts_with('#') {
                continue;
            }
            let this = if text.starts_with('{') {
                Spelling::Json
            } else {
                Spelling::Plain
            };
            match spelling {
                None => spelling = Some(this),
                Some(first) if first != this => {
                    done = true;
                    let (was, now) = match first {
                        Spelling::Json => ("JSON lines", "a plain line"),
                        Spelling::Plain => ("plain lines", "a JSON line"),
                    };
                    return Some(Err(fail(format!(
                        "{now} in a file of {was}: expected one spelling throughout"
                    ))));
                }
                Some(_) => {}
            }
            let parsed = match this {
                Spelling::Json => json_answer(text),
                Spelling::Plain => plain_answer(text),
            };
            any = true;
            return Some(match parsed {
                Ok(answer) => Ok((number, answer)),
                Err(message) => {
                    done = true;
                    Err(fail(message))
                }
            });
        }
        None
    })
}

/// A plain line: a word, then numbers separated by white space or commas.
fn plain_answer(text: &str) -> Result<Answer, String> {
    let mut words = text
        .split(|c: char| c.is_whitespace() || c == ',')
        .filter(|w| !w.is_empty());
    let kind = words.next().unwrap_or_default();
    let rest: Vec<&str> = words.collect();
    let (expected, count) = match kind {
        "frame" => ("frame ex ey ez ux uy uz vx vy vz wx wy wz", 12),
        "ray" => ("ray ROW COL ox oy oz dx dy dz", 8),
        "project" => ("project px py pz x y", 5),
        other => {
            return Err(format!(
                "expected `frame`, `ray` or `project` first, found `{other}`"
            ));
        }
    };
    if rest.len() != count {
        return Err(format!(
            "expected `{expected}` ({count} numbers after `{kind}`), found {}",
            rest.len()
        ));
    }
    // Each number is named as the expected line names it: `dx` of `ray ROW COL ...`.
    let name = |k: usize| expected.split(' ').nth(k + 1).unwrap_or("a number");
    let number = |k: usize| -> Result<f64, String> {
        let word = rest[k];
        match word.parse::<f64>() {
            Ok(x) if x.is_finite() => Ok(x),
            Ok(_) => Err(format!(
                "`{}` of `{expected}` is `{word}`: expected a finite number",
                name(k)
            )),
            Err(_) => Err(format!(
                "`{}` of `{expected}` is `{word}`: expected a number",
                name(k)
            )),
        }
    };
    let vector = |k: usize| -> Result<DVec3, String> {
        Ok(DVec3::new(number(k)?, number(k + 1)?, number(k + 2)?))
    };
    Ok(match kind {
        "frame" => Answer::Frame {
            e: vector(0)?,
            u: vector(3)?,
            v: vector(6)?,
            w: vector(9)?,
        },
        "ray" => {
            let index = |k: usize| -> Result<i64, String> {
                let word = rest[k];
                word.parse::<i64>().map_err(|_| {
                    format!(
                        "the {} of `{expected}` is `{word}`: expected a whole number",
                        ["row", "column"][k]
                    )
                })
            };
            Answer::Ray {
                row: index(0)?,
                col: index(1)?,
                one_based: false,
                uv: None,
                origin: vector(2)?,
                direction: vector(5)?,
            }
        }
        _ => {
            let xy = if rest[3] == "null" && rest[4] == "null" {
                None
            } else {
                Some((number(3)?, number(4)?))
            };
            Answer::Project {
                point: vector(0)?,
                xy,
            }
        }
    })
}

/// A JSON line with the keys of `viewray frame`, `rays` or `project`.
fn json_answer(text: &str) -> Result<Answer, String> {
    let value: Value =
        serde_json::from_str(text).map_err(|error| format!("is not a JSON object: {error}"))?;
    let object = value
        .as_object()
        .ok_or_else(|| "is not a JSON object".to_owned())?;
    let number = |key: &str, value: &Value| -> Result<f64, String> {
        value
            .as_f64()
            .filter(|x| x.is_finite())
            .ok_or_else(|| format!("`{key}` is {value}: expected a finite number"))
    };
    let vector = |key: &str| -> Result<DVec3, String> {
        let array = object
            .get(key)
            .and_then(Value::as_array)
            .filter(|a| a.len() == 3)
            .ok_or_else(|| format!("expected `{key}` as an array of three numbers"))?;
        Ok(DVec3::new(
            number(key, &array[0])?,
            number(key, &array[1])?,
            number(key, &array[2])?,
        ))
    };
    let has = |key: &str| object.contains_key(key);
    if has("origin") || has("direction") {
        let (keys, one_based) = if has("i") || has("j") {
            (["i", "j"], true)
        } else {
            (["row", "col"], false)
        };
        let index = |key: &str| -> Result<i64, String> {
            object.get(key).and_then(Value::as_i64).ok_or_else(|| {
                format!(
                    "expected `{key}` as a whole number (a ray's pixel is `row`, `col` or `i`, `j`)"
                )
            })
        };
        let uv = match (object.get("u"), object.get("v")) {
            (Some(u), Some(v)) if u.is_number() && v.is_number() => {
                Some((number("u", u)?, number("v", v)?))
            }
            _ => None,
        };
        Ok(Answer::Ray {
            row: index(keys[0])?,
            col: index(keys[1])?,
            one_based,
            uv,
            origin: vector("origin")?,
            direction: vector("direction")?,
        })
    } else if has("point") {
        let xy = match (object.get("x"), object.get("y")) {
            (Some(Value::Null), Some(Value::Null)) => None,
            (Some(x), Some(y)) => Some((number("x", x)?, number("y", y)?)),
            _ => return Err("expected `x` and `y` (numbers, or both null)".to_owned()),
        };
        Ok(Answer::Project {
            point: vector("point")?,
            xy,
        })
    } else if has("e") {
        Ok(Answer::Frame {
            e: vector("e")?,
            u: vector("u")?,
            v: vector("v")?,
            w: vector("w")?,
        })
    } else {
        Err(
            "expected the keys of a frame (`e`, `u`, `v`, `w`), a ray (`row`, `col`, `origin`, \
             `direction`) or a projection (`point`, `x`, `y`)"
                .to_owned(),
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Vec<Result<(u64, Answer), AnswerError>> {
        read_answers(text.as_bytes()).collect()
    }

    #[track_caller]
    fn error(text: &str) -> String {
        let results = read(text);
        results
            .into_iter()
            .find_map(Result::err)
            .expect("an error")
            .to_string()
    }

    #[test]
    fn plain_and_json_lines_read_the_same_answers() {
        let plain = "# my rays\r\nray 0 1 0 0 0 0.25,0.25,-1\r\n\r\nframe 0 0 0 1 0 0 0 1 0 0 0 1\n\
                     project 0 0 -2  1.5 0.5\nproject 0 0 5 null null\n";
        let json = r#"{"row":0,"col":1,"u":0.25,"v":0.25,"origin":[0,0,0],"direction":[0.25,0.25,-1]}
{"e":[0,0,0],"u":[1,0,0],"v":[0,1,0],"w":[0,0,1]}
{"point":[0,0,-2],"x":1.5,"y":0.5,"row":0,"col":1}
{"point":[0,0,5],"x":null,"y":null,"row":null,"col":null}"#;
        let answers =
            |text| -> Vec<Answer> { read(text).into_iter().map(|r| r.unwrap().1).collect() };
        let (p, j) = (answers(plain), answers(json));
        assert_eq!(p.len(), 4);
        assert_eq!(p[1..], j[1..]);
        assert_eq!(
            j[0],
            Answer::Ray {
                row: 0,
                col: 1,
                one_based: false,
                uv: Some((0.25, 0.25)),
                origin: DVec3::ZERO,
                direction: DVec3::new(0.25, 0.25, -1.0)
            }
        );
        assert!(matches!(p[0], Answer::Ray { uv: None, .. }));
        let lines: Vec<u64> = read(plain).into_iter().map(|r| r.unwrap().0).collect();
        assert_eq!(lines, [2, 4, 5, 6]);
        let one_based = r#"{"i":1,"j":2,"origin":[0,0,0],"direction":[0,0,-1]}"#;
        assert!(matches!(
            answers(one_based)[0],
            Answer::Ray {
                row: 1,
                col: 2,
                one_based: true,
                ..
            }
        ));
    }

    #[test]
    fn bad_answers_name_their_line_and_what_was_expected() {
        assert_eq!(
            error(""),
            "no answers: expected lines such as `ray 0 0 ox oy oz dx dy dz` or viewray's JSON lines"
        );
        assert_eq!(error("# only a comment\n\n"), error(""));
        assert_eq!(
            error("ray 0 0 1 2 3\n"),
            "line 1: expected `ray ROW COL ox oy oz dx dy dz` (8 numbers after `ray`), found 5"
        );
        assert_eq!(
            error("ray 0 0 0 0 0 NaN 0 -1\n"),
            "line 1: `dx` of `ray ROW COL ox oy oz dx dy dz` is `NaN`: expected a finite number"
        );
        assert_eq!(
            error("ray 0 x 0 0 0 0 0 -1"),
            "line 1: the column of `ray ROW COL ox oy oz dx dy dz` is `x`: expected a whole number"
        );
        assert_eq!(
            error("ray 0 0 0 0 0 0 0 -1\n{\"e\":[0,0,0]}\n"),
            "line 2: a JSON line in a file of plain lines: expected one spelling throughout"
        );
        assert_eq!(
            error("pixel 0 0\n"),
            "line 1: expected `frame`, `ray` or `project` first, found `pixel`"
        );
        assert_eq!(
            error("{\"row\":0,\"col\":0,\"origin\":[0,0],\"direction\":[0,0,-1]}"),
            "line 1: expected `origin` as an array of three numbers"
        );
        assert!(error("{not json}").starts_with("line 1: is not a JSON object: "));
        assert_eq!(
            error("{\"colour\":1}"),
            "line 1: expected the keys of a frame (`e`, `u`, `v`, `w`), a ray (`row`, `col`, \
             `origin`, `direction`) or a projection (`point`, `x`, `y`)"
        );
        let bytes: &[u8] = b"ray 0 0 0 0 0 0 0 -1\n\xff\xfe\n";
        let results: Vec<_> = read_answers(bytes).collect();
        assert_eq!(
            results[1].as_ref().unwrap_err().to_string(),
            "line 2: is not text (UTF-8)"
        );
    }

    #[test]
    fn reading_stops_at_the_first_error() {
        let results = read("ray 0 0 1\nray 0 0 0 0 0 0 0 -1\n");
        assert_eq!(results.len(), 1);
        assert!(results[0].is_err());
    }
}

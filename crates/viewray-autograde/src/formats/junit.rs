//! JUnit XML, as CI systems read it: `testsuites` > `testsuite` > `testcase`, a failed
//! test's `failure` (its `message` the verdict, its text the diagnosis), the points in
//! each test's `system-out` and in the suite's `properties` (`score`, `max_score`), and
//! an assignment that could not be graded as one test's `error`.

use quick_xml::Writer;
use quick_xml::events::{BytesCData, BytesDecl, BytesEnd, BytesStart, BytesText, Event};

use crate::formats::seconds;
use crate::results::{Results, Status, points};

/// The results as a JUnit XML document.
pub fn junit_xml(results: &Results) -> String {
    let mut writer = Writer::new_with_indent(Vec::new(), b' ', 2);
    let failures = results
        .tests
        .iter()
        .filter(|t| t.status == Status::Failed)
        .count();
    let errors = usize::from(results.problem.is_some());
    let tests = results.tests.len() + errors;
    let time = format!("{:.3}", seconds(results.elapsed));
    let counts = [
        ("tests", tests.to_string()),
        ("failures", failures.to_string()),
        ("errors", errors.to_string()),
        ("skipped", "0".to_owned()),
        ("time", time),
    ];
    let start = |name: &str, attributes: &[(&str, String)]| {
        let mut element = BytesStart::new(name.to_owned());
        for (key, value) in attributes {
            element.push_attribute((*key, clean(value).as_str()));
        }
        element
    };
    let mut events = vec![Event::Decl(BytesDecl::new("1.0", Some("UTF-8"), None))];
    let mut suites = vec![("name", results.title.clone())];
    suites.extend(counts.iter().filter(|(k, _)| *k != "skipped").cloned());
    events.push(Event::Start(start("testsuites", &suites)));
    let mut suite = vec![("name", results.title.clone())];
    suite.extend(counts.iter().cloned());
    events.push(Event::Start(start("testsuite", &suite)));
    events.push(Event::Start(BytesStart::new("properties")));
    for (name, value) in [
        ("score", points(results.score())),
        ("max_score", points(results.max_score())),
    ] {
        events.push(Event::Empty(start(
            "property",
            &[("name", name.to_owned()), ("value", value)],
        )));
    }
    events.push(Event::End(BytesEnd::new("properties")));
    let mut elements: Vec<Vec<Event<'static>>> = Vec::new();
    if let Some(problem) = &results.problem {
        elements.push(testcase(
            "assignment",
            "0.000",
            Some(("error", problem.clone(), results.summary())),
            String::new(),
        ));
    }
    for test in &results.tests {
        let shown = test.shown();
        let failure = (test.status == Status::Failed)
            .then(|| ("failure", shown.message.to_owned(), shown.output.to_owned()));
        let mut out = format!(
            "points: {} of {}\n",
            points(test.score),
            points(test.max_score)
        );
        if test.status == Status::Passed {
            out.push_str(shown.message);
            out.push('\n');
            if !shown.output.is_empty() {
                out.push_str(shown.output);
                out.push('\n');
            }
        }
        out.push_str(&format!("command: {}\n", test.command));
        elements.push(testcase(
            &test.name,
            &format!("{:.3}", seconds(test.duration)),
            failure,
            out,
        ));
    }
    events.extend(elements.into_iter().flatten());
    events.push(Event::End(BytesEnd::new("testsuite")));
    events.push(Event::End(BytesEnd::new("testsuites")));
    for event in events {
        writer
            .write_event(event)
            .expect("writing to memory cannot fail");
    }
    let mut text = String::from_utf8(writer.into_inner()).expect("the writer writes UTF-8");
    text.push('\n');
    text
}

/// A `testcase` element's events.
fn testcase(
    name: &str,
    time: &str,
    failure: Option<(&'static str, String, String)>,
    system_out: String,
) -> Vec<Event<'static>> {
    let mut element = BytesStart::new("testcase");
    element.push_attribute(("name", clean(name).as_str()));
    element.push_attribute(("classname", "viewray.autograde"));
    element.push_attribute(("time", time));
    let mut events = vec![Event::Start(element)];
    if let Some((kind, message, text)) = failure {
        let mut failure = BytesStart::new(kind);
        failure.push_attribute(("message", clean(&message).as_str()));
        failure.push_attribute((
            "type",
            if kind == "error" {
                "not graded"
            } else {
                "wrong"
            },
        ));
        events.push(Event::Start(failure));
        events.extend(text_events(&text));
        events.push(Event::End(BytesEnd::new(kind)));
    }
    if !system_out.is_empty() {
        events.push(Event::Start(BytesStart::new("system-out")));
        events.extend(text_events(&system_out));
        events.push(Event::End(BytesEnd::new("system-out")));
    }
    events.push(Event::End(BytesEnd::new("testcase")));
    events
}

/// `text` without the characters XML 1.0 forbids (control characters a program
/// printed), each replaced by U+FFFD.
fn clean(text: &str) -> String {
    text.chars()
        .map(|c| match c {
            '\t' | '\n' | '\r' => c,
            c if (c as u32) < 0x20 || c == '\u{FFFE}' || c == '\u{FFFF}' => '\u{FFFD}',
            c => c,
        })
        .collect()
}

/// Text as XML, [`clean`]: CDATA when it has no `]]>`, escaped otherwise.
fn text_events(text: &str) -> Vec<Event<'static>> {
    let clean = clean(text);
    if clean.contains("]]>") {
        vec![Event::Text(BytesText::new(&clean).into_owned())]
    } else {
        vec![Event::CData(BytesCData::new(clean))]
    }
}

//! The golden check as a test target: one test per image, named as `cargo xtask golden`
//! names it (`scenes/oblique_cavalier`, `figures/taxonomy`), so plain `cargo test` runs
//! it and `cargo test -p xtask --test golden -- oblique` runs only the images whose name
//! contains `oblique`. A golden with no scene is a failing test of its own. On a failure
//! the report goes to `target/golden/index.html`, as `cargo xtask golden` writes it;
//! accepting a change stays `cargo xtask golden --bless`, on purpose, by a person.

use std::process::ExitCode;
use std::sync::{Arc, Mutex, PoisonError};

use libtest_mimic::{Arguments, Failed, Trial};
use xtask::golden::{self, GoldenArgs, Verdict};

fn main() -> ExitCode {
    let arguments = Arguments::from_args();
    let root = xtask::workspace_root();
    let (cases, orphans) = match golden::cases(&root, &GoldenArgs::default()) {
        Ok(found) => found,
        Err(error) => {
            eprintln!("error: {error:#}");
            return ExitCode::FAILURE;
        }
    };
    // Each failure with its case's place in the list, to report them in that order.
    let failures: Arc<Mutex<Vec<(usize, String, Verdict)>>> = Arc::default();
    let mut trials: Vec<Trial> = cases
        .into_iter()
        .enumerate()
        .map(|(index, case)| {
            let failures = Arc::clone(&failures);
            Trial::test(case.id().to_owned(), move || match case.check() {
                Verdict::Same | Verdict::Passed(..) => Ok(()),
                failed @ Verdict::Failed { .. } => {
                    let Verdict::Failed { reason, .. } = &failed else {
                        unreachable!("matched above")
                    };
                    let message = Failed::from(reason.as_str());
                    failures
                        .lock()
                        .unwrap_or_else(PoisonError::into_inner)
                        .push((index, case.id().to_owned(), failed));
                    Err(message)
                }
            })
        })
        .collect();
    for orphan in &orphans {
        let name = golden::relative(&root, orphan).replacen("golden/", "", 1);
        let name = name.strip_suffix(".png").unwrap_or(&name).to_owned();
        trials.push(Trial::test(
            format!("{name} (a golden with no scene)"),
            || {
                Err(
                    "a golden with no scene or figure: remove it with `cargo xtask golden --bless`"
                        .into(),
                )
            },
        ));
    }
    let conclusion = libtest_mimic::run(&arguments, trials);

    let mut failures =
        std::mem::take(&mut *failures.lock().unwrap_or_else(PoisonError::into_inner));
    if !failures.is_empty() {
        failures.sort_by_key(|(index, ..)| *index);
        let failures: Vec<(String, Verdict)> = failures
            .into_iter()
            .map(|(_, id, verdict)| (id, verdict))
            .collect();
        // Orphans never pass: the images run are those that passed and those that failed.
        let images = conclusion.num_passed as usize + failures.len();
        let orphans_failed = conclusion.num_failed as usize - failures.len();
        let summary = golden::failure_summary(failures.len(), orphans_failed, images);
        match golden::write_failure_report(&root, &failures, &summary) {
            Ok(page) => eprintln!(
                "{summary}\n  report: {}\n  if the change is intended, look at each image, \
                 then run: cargo xtask golden --bless",
                golden::relative(&root, &page)
            ),
            Err(error) => eprintln!("error: {error:#}"),
        }
    }
    conclusion.exit_code()
}

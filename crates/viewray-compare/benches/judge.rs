//! How long the instructor's judgement takes per pair of 320 x 240 renders: a correct
//! one-sample render (a pass, which must need no transform search), and failures with and
//! without a camera mistake to name; each with the reference prepared for the pair
//! (`judge`, as `viewray compare` judges a pair) and prepared beforehand
//! (`Reference::judge`, as `viewray grade` judges a class).
//!
//! `cargo bench -p viewray-compare --features bench`. The renders come from the planted
//! mistakes of `tests/it/planted` (rendered once, before timing). Before criterion's wall
//! clock timings, each case prints the processor time one judgement takes on its thread
//! (from `/proc/thread-self/stat`, where there is one), which other work on a busy
//! machine does not inflate.

use std::hint::black_box;
use std::time::Duration;

use criterion::Criterion;
use viewray_compare::{InstructorThresholds, Reference, judge};

#[path = "../tests/it/planted/mod.rs"]
mod planted;

use planted::{Base, Case, Mistake};

fn case(base: Base, mistake: Mistake, samples: u32) -> Case {
    Case {
        name: String::new(),
        base,
        size: (320, 240),
        samples,
        mistake,
        passes: false,
        without_scene: String::new(),
        with_scene: String::new(),
    }
}

fn main() {
    let pairs = [
        ("pass (1 sample)", case(Base::General, Mistake::None, 1)),
        (
            "fail: fov 1.2x",
            case(Base::General, Mistake::Viewport(1.2), 4),
        ),
        (
            "fail: shift flipped",
            case(Base::Boxes, Mistake::ShiftFlipped, 4),
        ),
        (
            "fail: rolled 8 degrees",
            case(Base::General, Mistake::Roll(8.0), 4),
        ),
        (
            "fail: missing object",
            case(Base::General, Mistake::MissingObject, 4),
        ),
    ];
    let thresholds = InstructorThresholds::default();
    let mut criterion = Criterion::default()
        .sample_size(20)
        .warm_up_time(Duration::from_secs(1))
        .measurement_time(Duration::from_secs(3))
        .configure_from_args();
    let mut group = criterion.benchmark_group("judge 320x240");
    for (name, case) in pairs {
        let (reference, student) = case.render();
        let verdict = judge(&reference, &student, &thresholds);
        println!(
            "{name}: {} {}",
            verdict.verdict(),
            verdict
                .diagnosis
                .map(|d| d.to_string())
                .unwrap_or_else(|| verdict.reasons())
        );
        if let Some(cpu) = cpu_time_per_call(|| {
            black_box(judge(&reference, &student, &thresholds));
        }) {
            println!(
                "{name}: {:.1} ms of processor time per judgement",
                cpu * 1e3
            );
        }
        let prepared = Reference::new(reference.clone(), thresholds, None);
        if let Some(cpu) = cpu_time_per_call(|| {
            black_box(prepared.judge(&student));
        }) {
            println!(
                "{name}: {:.1} ms of processor time per judgement against a prepared reference",
                cpu * 1e3
            );
        }
        group.bench_function(name, |b| {
            b.iter(|| judge(black_box(&reference), black_box(&student), &thresholds))
        });
        group.bench_function(format!("{name}, prepared reference"), |b| {
            b.iter(|| prepared.judge(black_box(&student)))
        });
    }
    group.finish();
    criterion.final_summary();
}

/// The processor time of this thread so far, in seconds, where Linux reports it.
fn thread_cpu_time() -> Option<f64> {
    let stat = std::fs::read_to_string("/proc/thread-self/stat").ok()?;
    // The fields after the command name (in parentheses): utime and stime are the 12th
    // and 13th, in clock ticks of 1/100 s.
    let fields: Vec<&str> = stat.rsplit_once(')')?.1.split_whitespace().collect();
    let ticks: f64 = fields.get(11)?.parse::<f64>().ok()? + fields.get(12)?.parse::<f64>().ok()?;
    Some(ticks / 100.0)
}

/// The mean processor time of `call`, over enough calls for the clock's ticks.
fn cpu_time_per_call(mut call: impl FnMut()) -> Option<f64> {
    let start = thread_cpu_time()?;
    let mut calls = 0u32;
    while thread_cpu_time()? - start < 3.0 {
        call();
        calls += 1;
    }
    Some((thread_cpu_time()? - start) / f64::from(calls))
}

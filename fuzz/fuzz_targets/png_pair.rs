//! Any two byte strings given to `viewray compare` as PNGs decode or fail with a message,
//! and any two that decode compare in both modes, never panicking.
#![no_main]

use libfuzzer_sys::fuzz_target;
use viewray_compare::{InstructorThresholds, Thresholds};

fuzz_target!(|input: &[u8]| {
    // The first two bytes say where the expected file ends and the actual one begins.
    let Some((split, rest)) = input.split_first_chunk::<2>() else { return };
    let split = usize::from(u16::from_le_bytes(*split)).min(rest.len());
    let (expected, actual) = rest.split_at(split);
    let (Ok(expected), Ok(actual)) = (
        viewray_compare::fuzz_decode_png(expected),
        viewray_compare::fuzz_decode_png(actual),
    ) else {
        return;
    };
    // Keep each run quick: large pictures only make the fuzzer slow, not wiser.
    if expected.width() * expected.height() > 64 * 64 || actual.width() * actual.height() > 64 * 64 {
        return;
    }
    let golden = viewray_compare::compare(&expected, &actual, &Thresholds::GOLDEN);
    let _ = golden.reasons();
    let instructor = viewray_compare::judge(&expected, &actual, &InstructorThresholds::default());
    let _ = instructor.reasons();
});

//! Judging one render: what the render side holds for a reference image, loaded and
//! judged against it, or failed without being compared (missing, unreadable, not a PNG);
//! and judging many in parallel with the results in order ([`in_order`]).

use std::collections::BTreeMap;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc;

use rayon::prelude::*;
use viewray_compare::{LoadError, Outcome, Reference, RgbaImage, SUPPORTED_IMAGES, load_image};

use crate::folders::Counterpart;

/// Why a render that is a file could not be read, as its row says it: `cannot read: ...`,
/// `not an image: ...` or `the PNG does not decode: ...` (the file's name is the row's).
pub fn unreadable(error: &LoadError) -> String {
    match error {
        LoadError::Unreadable { source, .. } => format!("cannot read: {source}"),
        LoadError::NotPng { .. } => {
            "not a PNG: it does not start with the PNG signature".to_owned()
        }
        LoadError::NotAnImage { .. } => {
            format!("not an image viewray reads ({SUPPORTED_IMAGES})")
        }
        LoadError::Decode { format, source, .. } => {
            format!("the {format} does not decode: {source}")
        }
    }
}

/// Loads the render `counterpart` holds for the reference image `name`: its pixels, or
/// why it fails without being compared.
pub fn load_counterpart(counterpart: &Counterpart, name: &str) -> Result<RgbaImage, String> {
    match counterpart {
        Counterpart::File(path) => load_image(path).map_err(|e| unreadable(&e)),
        other => Err(other.problem(name).unwrap_or_default()),
    }
}

/// Loads what `counterpart` holds for the reference image `name` and judges it against
/// `reference`: the render (when it could be read) and the outcome, with its FLIP error
/// map.
pub fn judge_counterpart(
    reference: &Reference,
    counterpart: &Counterpart,
    name: &str,
) -> (Option<RgbaImage>, Outcome) {
    match load_counterpart(counterpart, name) {
        Ok(actual) => {
            let comparison = reference.judge(&actual);
            (Some(actual), Outcome::from(comparison))
        }
        Err(message) => (None, Outcome::Failed(message)),
    }
}

/// Runs `work` on every item in parallel (rayon) and hands the results to `emit` in the
/// items' order, each as soon as it and all before it are done. When `emit` fails (a
/// closed pipe), the items not yet started are skipped and its error returned.
///
/// # Errors
/// The first error of `emit`.
pub fn in_order<T: Sync, R: Send, E>(
    items: &[T],
    work: impl Fn(&T) -> R + Sync,
    mut emit: impl FnMut(R) -> Result<(), E>,
) -> Result<(), E> {
    let stop = AtomicBool::new(false);
    let (sender, receiver) = mpsc::channel();
    std::thread::scope(|scope| {
        let (work, stop) = (&work, &stop);
        scope.spawn(move || {
            items
                .par_iter()
                .enumerate()
                .for_each_with(sender, |sender, (index, item)| {
                    if !stop.load(Ordering::Relaxed) {
                        let _ = sender.send((index, work(item)));
                    }
                });
        });
        let mut waiting = BTreeMap::new();
        let mut next = 0;
        for (index, result) in receiver {
            waiting.insert(index, result);
            while let Some(result) = waiting.remove(&next) {
                next += 1;
                if let Err(error) = emit(result) {
                    stop.store(true, Ordering::Relaxed);
                    return Err(error);
                }
            }
        }
        Ok(())
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn results_come_in_order_and_a_failing_emit_stops_the_rest() {
        let items: Vec<u64> = (0..200).collect();
        let mut seen = Vec::new();
        in_order(
            &items,
            |&i| {
                // Later items finish sooner.
                std::thread::sleep(std::time::Duration::from_micros(200 - i));
                i * 2
            },
            |r| {
                seen.push(r);
                Ok::<(), ()>(())
            },
        )
        .unwrap();
        assert_eq!(seen, items.iter().map(|i| i * 2).collect::<Vec<_>>());
        let mut count = 0;
        let result = in_order(
            &items,
            |&i| i,
            |_| {
                count += 1;
                if count == 3 { Err("closed") } else { Ok(()) }
            },
        );
        assert_eq!(result, Err("closed"));
        assert_eq!(count, 3);
    }
}

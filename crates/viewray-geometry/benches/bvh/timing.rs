//! Contenders taking turns, and the table of their timings.

use std::hint::black_box;
use std::time::Instant;

/// Seconds per run: the median, fastest and slowest of a case's runs, and every run
/// in its round's order.
#[derive(Clone, Debug)]
pub(crate) struct Timing {
    median: f64,
    min: f64,
    max: f64,
    rounds: Vec<f64>,
}

impl Timing {
    fn of(rounds: Vec<f64>) -> Self {
        let mut seconds = rounds.clone();
        seconds.sort_by(f64::total_cmp);
        Self {
            median: seconds[seconds.len() / 2],
            min: seconds[0],
            max: seconds[seconds.len() - 1],
            rounds,
        }
    }
}

/// One way of running a case: who runs it, how, and one run that reports its own
/// time in seconds (so that a setup, such as copying the mesh for a build, or the
/// release of a rendered image, is not timed).
pub(crate) struct Contender<'a> {
    who: &'static str,
    how: String,
    run: Box<dyn FnMut() -> f64 + 'a>,
}

impl<'a> Contender<'a> {
    /// A contender whose `run` times itself.
    pub(crate) fn timed(
        who: &'static str,
        how: impl Into<String>,
        run: impl FnMut() -> f64 + 'a,
    ) -> Self {
        Self {
            who,
            how: how.into(),
            run: Box::new(run),
        }
    }

    /// Times `run` on a fresh `setup()` each time.
    pub(crate) fn new<T>(
        who: &'static str,
        how: impl Into<String>,
        mut setup: impl FnMut() -> T + 'a,
        mut run: impl FnMut(T) + 'a,
    ) -> Self {
        Self::timed(who, how, move || {
            let input = setup();
            let start = Instant::now();
            run(input);
            start.elapsed().as_secs_f64()
        })
    }

    /// Times `trace` on `pool`.
    pub(crate) fn traced(
        pool: &'a rayon::ThreadPool,
        who: &'static str,
        how: impl Into<String>,
        trace: impl Fn() -> f32 + Sync + 'a,
    ) -> Self {
        Self::new(
            who,
            how,
            || (),
            move |()| {
                black_box(pool.install(&trace));
            },
        )
    }
}

/// What a case measures: its mesh, its name, its thread count, and how many rays one
/// run traces (`None`: a build, reported in seconds).
pub(crate) struct Case {
    /// The icosphere's triangle count.
    pub(crate) triangles: usize,
    /// What is traced or built, such as "incoherent, together".
    pub(crate) name: String,
    /// The threads of the pool the contenders run on.
    pub(crate) threads: usize,
    /// The rays one run traces; `None` for a build.
    pub(crate) rays: Option<usize>,
}

/// One line of the table: who ran a case, how, and how long it took.
struct Line {
    case: usize,
    who: &'static str,
    how: String,
    timing: Timing,
}

/// The benchmark's results, case by case.
pub(crate) struct Table {
    /// The runs of each contender per case, after a warm-up run.
    pub(crate) runs: usize,
    cases: Vec<Case>,
    lines: Vec<Line>,
}

impl Table {
    /// An empty table of `runs` runs per contender.
    pub(crate) fn new(runs: usize) -> Self {
        Self {
            runs,
            cases: Vec::new(),
            lines: Vec::new(),
        }
    }

    /// Runs a case's contenders in turns: a warm-up run of each, then `runs` rounds in
    /// which each runs once. On a shared machine slow spells last seconds; taking turns
    /// lets a spell fall on every contender of the case rather than on whichever ran
    /// then, so the ratios hold even when the figures move.
    pub(crate) fn race(&mut self, case: Case, mut contenders: Vec<Contender<'_>>) {
        for contender in &mut contenders {
            (contender.run)();
        }
        let mut seconds = vec![Vec::with_capacity(self.runs); contenders.len()];
        for _ in 0..self.runs {
            for (contender, seconds) in contenders.iter_mut().zip(&mut seconds) {
                seconds.push((contender.run)());
            }
        }
        let index = self.cases.len();
        for (contender, rounds) in contenders.into_iter().zip(seconds) {
            let timing = Timing::of(rounds);
            eprintln!(
                "  {} triangles, {}, {} thread(s): {} {}: {:.4} s",
                case.triangles,
                case.name,
                case.threads,
                contender.who,
                contender.how,
                timing.median
            );
            self.lines.push(Line {
                case: index,
                who: contender.who,
                how: contender.how,
                timing,
            });
        }
        self.cases.push(case);
    }

    /// Prints every line with its figure (seconds for builds, Mrays/s for tracing), the
    /// spread of its runs (slowest to fastest), and, on viewray's lines, the ratio of
    /// viewray's speed to the case's first peer's (above 1: viewray is faster): of the
    /// two medians, and the median of each round's ratio (the peer's run against
    /// viewray's in the same round, moments apart: the steadier of the two when the
    /// machine has slow spells).
    pub(crate) fn print(&self) {
        println!();
        println!(
            "median and spread (slowest-fastest) of {} runs per contender",
            self.runs
        );
        println!("ratio: viewray's speed over the case's peer's (above 1.00x: viewray is faster)");
        println!("paired: the median of each round's ratio");
        let name = self.cases.iter().map(|c| c.name.len()).max().unwrap_or(0);
        let how = self.lines.iter().map(|l| l.how.len()).max().unwrap_or(0);
        let header = ("triangles", "case", "thr", "who", "how", "median", "spread");
        println!(
            "{:>9} {:<name$} {:>3} {:<7} {:<how$} {:>14} {:>13} {:>6} {:>6}",
            header.0, header.1, header.2, header.3, header.4, header.5, header.6, "ratio", "paired"
        );
        for (index, case) in self.cases.iter().enumerate() {
            let lines: Vec<&Line> = self.lines.iter().filter(|l| l.case == index).collect();
            let peer = lines.iter().find(|l| l.who != "viewray");
            for line in &lines {
                let (figure, spread) = match case.rays {
                    Some(rays) => {
                        let speed = |s: f64| rays as f64 / s / 1e6;
                        (
                            format!("{:.2} Mrays/s", speed(line.timing.median)),
                            format!(
                                "{:.2}-{:.2}",
                                speed(line.timing.max),
                                speed(line.timing.min)
                            ),
                        )
                    }
                    None => (
                        format!("{:.3} s", line.timing.median),
                        format!("{:.3}-{:.3}", line.timing.max, line.timing.min),
                    ),
                };
                let (ratio, paired) = match peer {
                    Some(peer) if line.who == "viewray" => {
                        let mut rounds: Vec<f64> = (peer.timing.rounds.iter())
                            .zip(&line.timing.rounds)
                            .map(|(theirs, ours)| theirs / ours)
                            .collect();
                        rounds.sort_by(f64::total_cmp);
                        (
                            format!("{:.2}x", peer.timing.median / line.timing.median),
                            format!("{:.2}x", rounds[rounds.len() / 2]),
                        )
                    }
                    _ => (String::new(), String::new()),
                };
                println!(
                    "{:>9} {:<name$} {:>3} {:<7} {:<how$} {:>14} {:>13} {:>6} {:>6}",
                    case.triangles,
                    case.name,
                    case.threads,
                    line.who,
                    line.how,
                    figure,
                    spread,
                    ratio,
                    paired
                );
            }
        }
    }
}

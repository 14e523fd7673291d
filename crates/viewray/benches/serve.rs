//! What a frame of the live playground costs: `GET /api/render` of the default scene at
//! 640 x 360 and 1 sample per pixel, over HTTP from `viewray serve` (PNG encoding and
//! scene reuse included), against the same render's `render_s` from `viewray render
//! --stats` (tracing and shading alone). The target is at most 1.5 times `render_s`.
//!
//! `cargo bench -p viewray --bench serve` prints criterion's estimate, then one summary
//! line: median latency, frames per second, median `render_s` and their ratio.

use std::time::{Duration, Instant};

use criterion::Criterion;

#[path = "../tests/it/support/http.rs"]
#[allow(dead_code)]
mod http;

const BINARY: &str = env!("CARGO_BIN_EXE_viewray");
const FRAME: &str = "/api/render?width=640&height=360&samples=1";
const RUNS: usize = 31;

fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    values[values.len() / 2]
}

/// The median `render_s` of `viewray render --size 640x360 --samples 1 --stats`.
fn median_render_s() -> f64 {
    let dir = std::env::temp_dir().join(format!("viewray-bench-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let out = dir.join("frame.png");
    let times = (0..RUNS)
        .map(|_| {
            let output = std::process::Command::new(BINARY)
                .args([
                    "render",
                    "--size",
                    "640x360",
                    "--samples",
                    "1",
                    "--stats",
                    "-o",
                ])
                .arg(&out)
                .output()
                .unwrap();
            assert!(output.status.success());
            let stats: serde_json::Value = serde_json::from_slice(&output.stdout).unwrap();
            stats["render_s"].as_f64().unwrap()
        })
        .collect();
    let _ = std::fs::remove_dir_all(&dir);
    median(times)
}

fn frame(c: &mut Criterion) {
    let served = http::Served::start(BINARY, &[]);
    let address = served.address.clone();
    let get = || {
        let response = http::get(&address, FRAME).unwrap();
        assert_eq!(response.status, 200);
        response.body.len()
    };
    c.bench_function("GET /api/render 640x360 1spp", |b| b.iter(get));

    // The summary: the same request, timed one by one, beside `render_s`.
    let latencies = (0..RUNS)
        .map(|_| {
            let started = Instant::now();
            get();
            started.elapsed().as_secs_f64()
        })
        .collect();
    let latency = median(latencies);
    let render_s = median_render_s();
    println!(
        "serve: median latency {:.1} ms ({:.1} frames/s); median render_s {:.1} ms; ratio {:.2} \
         (target at most 1.5)",
        latency * 1e3,
        1.0 / latency,
        render_s * 1e3,
        latency / render_s
    );
}

fn main() {
    let mut criterion = Criterion::default()
        .sample_size(30)
        .measurement_time(Duration::from_secs(10))
        .warm_up_time(Duration::from_secs(2))
        .configure_from_args();
    frame(&mut criterion);
    criterion.final_summary();
}

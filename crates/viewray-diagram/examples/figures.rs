//! Writes lecture figures as PNG and SVG, for looking at them.
//!
//! `cargo run -p viewray-diagram --example figures -- /tmp/figures [NAME...]` writes
//! `/tmp/figures/<name>.png` and `.svg` for the named figures (all without names), with
//! rendered pictures; `--wireframe` first draws the pictures as polygons instead.

use std::time::Instant;

use viewray_diagram::figures::{UnknownFigure, all_figures, figure_by_name};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args: Vec<String> = std::env::args().skip(1).collect();
    let wireframe = args.first().is_some_and(|a| a == "--wireframe");
    if wireframe {
        args.remove(0);
    }
    let mut args = args.into_iter();
    let dir = args.next().unwrap_or_else(|| "/tmp/figures".to_owned());
    std::fs::create_dir_all(&dir)?;
    let names: Vec<String> = args.collect();
    let figures = if names.is_empty() {
        all_figures()
    } else {
        names
            .iter()
            .map(|name| figure_by_name(name).ok_or_else(|| UnknownFigure::new(name)))
            .collect::<Result<_, _>>()?
    };
    for named in figures {
        let start = Instant::now();
        let figure = if wireframe {
            named.wireframe()
        } else {
            named.figure()
        };
        let drawn = start.elapsed();
        figure.write_png(format!("{dir}/{}.png", named.name))?;
        figure.write_svg(format!("{dir}/{}.svg", named.name))?;
        println!(
            "{dir}/{}.png  {}x{}  drawn {:.2} s, written {:.2} s",
            named.name,
            figure.width,
            figure.height,
            drawn.as_secs_f64(),
            (start.elapsed() - drawn).as_secs_f64()
        );
    }
    Ok(())
}

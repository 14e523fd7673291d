//! Writes every lecture figure as PNG and SVG, for looking at them.
//!
//! `cargo run -p viewray-diagram --example figures -- /tmp/figures [NAME...]` writes
//! `/tmp/figures/<name>.png` and `.svg` for the named figures (all without names).

use viewray_diagram::figures::{UnknownFigure, all_figures, figure_by_name};

fn main() -> Result<(), Box<dyn std::error::Error>> {
    let mut args = std::env::args().skip(1);
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
        let figure = named.figure();
        figure.write_png(format!("{dir}/{}.png", named.name))?;
        figure.write_svg(format!("{dir}/{}.svg", named.name))?;
        println!(
            "{dir}/{}.png  {}x{}",
            named.name, figure.width, figure.height
        );
    }
    Ok(())
}

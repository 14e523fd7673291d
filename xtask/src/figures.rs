//! `cargo xtask figures`: every lecture figure as PNG and SVG, for slides and the README.
//!
//! The figures are drawn in-process with their pictures rendered by the ray tracer
//! (`viewray_diagram::NamedFigure::figure`), exactly as `viewray figures`
//! draws them and as `golden/figures/` checks them; then every built-in animation as a
//! GIF into `animations/`, as `viewray animate --demo NAME` writes it.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use viewray_diagram::all_figures;

/// The command line of `cargo xtask figures`.
#[derive(Debug, Default, clap::Args)]
pub struct FiguresArgs {
    /// The folder to write into [default: target/figures/].
    #[arg(long, value_name = "DIR")]
    pub out: Option<PathBuf>,
}

/// Writes every figure as `<name>.png` and `<name>.svg`, and every built-in animation as
/// `animations/<demo>.gif`, each atomically.
///
/// # Errors
/// When the folder cannot be created or a file cannot be written.
pub fn figures(root: &Path, args: &FiguresArgs) -> Result<()> {
    let out = match &args.out {
        Some(out) => out.clone(),
        None => crate::target_dir(root)?.join("figures"),
    };
    lecture_figures(&out)?;
    animations(&out.join("animations"))
}

/// Writes every figure into `out` as `<name>.png` and `<name>.svg`.
fn lecture_figures(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let started = Instant::now();
    let figures = all_figures();
    for named in &figures {
        let figure_started = Instant::now();
        let figure = named.figure();
        let png = out.join(format!("{}.png", named.name));
        let svg = out.join(format!("{}.svg", named.name));
        // The errors name the file.
        viewray_draw::write_png(&figure, &png)?;
        viewray_draw::write_svg(&figure, &svg)?;
        eprintln!(
            "  {:<28} {} x {} {:>6} ms",
            named.name,
            figure.width,
            figure.height,
            figure_started.elapsed().as_millis()
        );
    }
    eprintln!(
        "wrote {} figures as PNG and SVG to {} in {:.2} s",
        figures.len(),
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

/// Writes every built-in animation as `<demo>.gif`, as `viewray animate --demo <demo>
/// -o <demo>.gif` does: its own frames, size and samples, each atomically.
fn animations(out: &Path) -> Result<()> {
    std::fs::create_dir_all(out).with_context(|| format!("cannot create {}", out.display()))?;
    let started = Instant::now();
    let demos = viewray_animation::all_demos();
    for demo in &demos {
        let movie = viewray_animation::Movie::from_demo(
            demo,
            viewray_scene::LoadOptions::default(),
            viewray_animation::MovieSettings::default(),
        )?;
        let path = out.join(format!("{}.gif", demo.name));
        let (gif, timings) = viewray_animation::write_gif(
            &movie,
            Vec::new(),
            &viewray_render::RenderSettings::default(),
            || {},
        )?;
        crate::write_atomically(&path, &gif)?;
        let (width, height) = movie.frame_size();
        eprintln!(
            "  {:<28} {} frames of {width} x {height}, {} KiB, rendered in {:.2} s, encoded in \
             {:.2} s",
            demo.name,
            movie.frames(),
            gif.len() / 1024,
            timings.render.as_secs_f64(),
            timings.encode.as_secs_f64()
        );
    }
    eprintln!(
        "wrote {} animations as GIF to {} in {:.2} s",
        demos.len(),
        out.display(),
        started.elapsed().as_secs_f64()
    );
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn writes_a_png_and_an_svg_per_figure() {
        let dir = tempfile::TempDir::new().unwrap();
        let out = dir.path().join("figures");
        // The animations (seven GIFs of 48 frames) are left to `cargo xtask figures`
        // itself: the command's tests write GIFs through the same code.
        lecture_figures(&out).unwrap();
        let mut written: Vec<String> = std::fs::read_dir(&out)
            .unwrap()
            .map(|e| e.unwrap().file_name().into_string().unwrap())
            .collect();
        written.sort();
        let mut expected: Vec<String> = all_figures()
            .iter()
            .flat_map(|f| [format!("{}.png", f.name), format!("{}.svg", f.name)])
            .collect();
        expected.sort();
        assert_eq!(written, expected);
        let taxonomy = image::open(out.join("taxonomy.png")).unwrap();
        assert_eq!((taxonomy.width(), taxonomy.height()), (1600, 900));
    }
}

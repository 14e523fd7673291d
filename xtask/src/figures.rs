//! `cargo xtask figures`: every lecture figure as PNG and SVG, for slides and the README.
//!
//! The figures are drawn in-process with their pictures rendered by the ray tracer
//! (`viewray_diagram::NamedFigure::figure`), exactly as `viewray figures`
//! draws them and as `golden/figures/` checks them.

use std::path::{Path, PathBuf};
use std::time::Instant;

use anyhow::{Context, Result};
use viewray_diagram::all_figures;

/// The command line of `cargo xtask figures`.
#[derive(Debug, Default)]
pub(crate) struct FiguresArgs {
    /// Where to write the figures; `target/figures/` under the workspace root by default.
    pub(crate) out: Option<PathBuf>,
}

impl FiguresArgs {
    pub(crate) fn parse(args: &[String]) -> Result<Self> {
        Ok(Self {
            out: crate::parse_out("figures", args)?,
        })
    }
}

/// Writes every figure as `<name>.png` and `<name>.svg`, each atomically.
pub(crate) fn figures(root: &Path, args: &FiguresArgs) -> Result<()> {
    let out = args
        .out
        .clone()
        .unwrap_or_else(|| root.join("target").join("figures"));
    std::fs::create_dir_all(&out).with_context(|| format!("cannot create {}", out.display()))?;
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

#[cfg(test)]
mod tests {
    use super::*;

    fn parse(args: &[&str]) -> Result<FiguresArgs> {
        FiguresArgs::parse(&args.iter().map(|a| (*a).to_owned()).collect::<Vec<_>>())
    }

    #[test]
    fn out_is_optional_and_takes_one_folder() {
        assert_eq!(parse(&[]).unwrap().out, None);
        assert_eq!(
            parse(&["--out", "slides"]).unwrap().out,
            Some(PathBuf::from("slides"))
        );
        assert_eq!(
            parse(&["--out=a/b"]).unwrap().out,
            Some(PathBuf::from("a/b"))
        );
        for (bad, message) in [
            (&["--out"][..], "--out needs a folder"),
            (&["--bless"][..], "unknown argument `--bless`"),
            (&["slides"][..], "unknown argument `slides`"),
            (&["--out", "a", "--out", "b"][..], "--out given twice"),
        ] {
            let error = parse(bad).unwrap_err().to_string();
            assert!(error.contains(message), "{bad:?}: {error}");
        }
    }

    #[test]
    fn writes_a_png_and_an_svg_per_figure() {
        let dir = tempfile::TempDir::new().unwrap();
        let out = dir.path().join("figures");
        let args = FiguresArgs {
            out: Some(out.clone()),
        };
        figures(dir.path(), &args).unwrap();
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

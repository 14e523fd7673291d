//! `cargo xtask mistakes`: writes docs/mistakes.md, the students' page of the lecture's
//! mistakes, from viewray-camera's catalogue (`Mistake::entry`): each entry's formula,
//! what it does to the picture, its picture (`golden/mistakes/<id>.png`, rendered by the
//! golden check through the mistaken camera) and the lecture's line to fix. The page is
//! never edited by hand: a test holds it equal to what this module writes.

use std::fmt::Write as _;
use std::path::Path;

use anyhow::{Context, Result};
use viewray_camera::Mistake;

/// Where the page goes, from the workspace root.
pub const PAGE: &str = "docs/mistakes.md";

/// The command line of `cargo xtask mistakes` (no options).
#[derive(Debug, Default, clap::Args)]
pub struct MistakesArgs {}

/// Writes [`PAGE`] under `root`.
///
/// # Errors
/// The page cannot be written.
pub fn mistakes(root: &Path, _args: &MistakesArgs) -> Result<()> {
    let path = root.join(PAGE);
    viewray_output::write_atomically(&path, page().as_bytes())
        .with_context(|| format!("cannot write {}", path.display()))?;
    println!("wrote {PAGE}");
    Ok(())
}

/// The right picture an entry's picture is shown beside, by the family its scene is.
fn right_picture(mistake: Mistake) -> &'static str {
    match mistake {
        Mistake::OrthoOriginFixed | Mistake::OrthoAsPerspective => "right-orthographic",
        Mistake::ObliqueSign | Mistake::ObliqueAsOrtho => "right-oblique",
        _ => "right-perspective",
    }
}

/// The page's Markdown.
pub fn page() -> String {
    let mut page = String::from(
        "# If your picture looks like this: the lecture's camera mistakes\n\
         \n\
         <!-- Written by `cargo xtask mistakes` from viewray's catalogue; do not edit. -->\n\
         \n\
         `viewray compare --scene` and `viewray grade --scene` judge your camera apart from your\n\
         shading: a render whose edges are where the scene's are passes, whatever its light,\n\
         gamma or sample count. When they are not, viewray renders the scene with each of the\n\
         mistakes below and names the one whose picture is yours, with the line of the lecture\n\
         to fix. `viewray check` names the same entries from your printed numbers.\n\
         \n\
         Notation as in the lecture: an image of W columns and H rows; `i`, `j` the 1-based\n\
         row and column (`row`, `col` 0-based); the frame `e`, `U`, `V`, `W` (`u`, `v`, `w`);\n\
         the viewport `vw` x `vh` at distance `d`; the shift `(sx, sy)`. Everything a formula\n\
         does not name is as the lecture says. Each picture is the scene of its camera's\n\
         family rendered by viewray with that one mistake (160 x 120): a general perspective\n\
         camera (d = 1.5, a shift; a red ball behind the eye), an orthographic one, an\n\
         oblique one.\n\
         \n\
         | the right pictures | | |\n\
         |---|---|---|\n\
         | ![perspective](../golden/mistakes/right-perspective.png) | \
         ![orthographic](../golden/mistakes/right-orthographic.png) | \
         ![oblique](../golden/mistakes/right-oblique.png) |\n\
         | perspective | orthographic | oblique |\n\
         \n\
         | id | looks | the mistake |\n\
         |---|---|---|\n",
    );
    for mistake in Mistake::ALL {
        let entry = mistake.entry();
        let _ = writeln!(
            page,
            "| [`{}`](#{}) | {} | {} |",
            entry.id, entry.id, entry.looks, entry.summary
        );
    }
    for mistake in Mistake::ALL {
        let entry = mistake.entry();
        let right = right_picture(mistake);
        // A picture of one colour is no picture to show (nor a golden to keep).
        let yours = if mistake == Mistake::OrthoOriginFixed {
            "(one colour)".to_owned()
        } else {
            format!("![{id}](../golden/mistakes/{id}.png)", id = entry.id)
        };
        let _ = write!(
            page,
            "\n## {id}\n\
             \n\
             {summary}: {picture}.\n\
             \n\
             - the mistake: `{mistaken}`\n\
             - the lecture's line: `{fix}`\n\
             \n\
             | yours, with `{id}` | right |\n\
             |---|---|\n\
             | {yours} | ![right](../golden/mistakes/{right}.png) |\n",
            id = entry.id,
            summary = capitalized(entry.summary),
            picture = entry.picture,
            mistaken = entry.mistaken,
            fix = entry.fix,
        );
    }
    page.push_str(
        "\n## Not the camera: how the picture looks\n\
         \n\
         These are named apart and never fail the camera: `gamma-missing` (linear values\n\
         written as if sRGB-encoded: too dark), `gamma-twice` (encoded twice: washed out),\n\
         `brighter` / `darker` (a light's intensity, the ambient light, an exposure),\n\
         `shading` (another light or material model), `noise` (fewer samples per pixel).\n",
    );
    page
}

/// `text` with its first letter upper case.
fn capitalized(text: &str) -> String {
    let mut chars = text.chars();
    chars.next().map_or_else(String::new, |first| {
        first.to_uppercase().chain(chars).collect()
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_committed_page_is_the_catalogues() {
        let root = crate::workspace_root();
        let committed = std::fs::read_to_string(root.join(PAGE)).unwrap_or_default();
        assert!(
            committed == page(),
            "{PAGE} is not what the catalogue says: run `cargo xtask mistakes`"
        );
        for mistake in Mistake::ALL
            .into_iter()
            .filter(|&m| m != Mistake::OrthoOriginFixed)
        {
            let picture = root.join(format!("golden/mistakes/{}.png", mistake.id()));
            assert!(picture.is_file(), "{}", picture.display());
        }
    }
}

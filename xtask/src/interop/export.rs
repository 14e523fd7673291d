//! Every case written for every tool that can hold its camera.

use std::collections::BTreeMap;
use std::path::PathBuf;

use anyhow::Result;
use viewray_interop::Format;

use super::Paths;
use super::cases::Case;

/// The files written into the work folder, by case and format.
pub(super) type Exported = BTreeMap<(String, Format), PathBuf>;

/// Exports every case to every format into the work folder: the files written, and a
/// line for each export refused (a camera the tool cannot express).
///
/// # Errors
/// When a file cannot be written.
pub(super) fn export_all(paths: &Paths, cases: &[Case]) -> Result<(Exported, Vec<String>)> {
    let mut exported = Exported::new();
    let mut refused: Vec<String> = Vec::new();
    for case in cases {
        for format in Format::ALL {
            let extension = match format {
                Format::Mitsuba => "xml",
                Format::Pbrt => "pbrt",
                Format::Blender => "py",
                Format::Three => "json",
                Format::Gltf => "gltf",
            };
            let file = paths.work.join(format!("{}.{extension}", case.name));
            let name = file.file_name().and_then(|n| n.to_str()).unwrap_or("scene");
            match viewray_interop::export(&case.scene, format, name) {
                Ok(export) => {
                    std::fs::write(&file, &export.main)?;
                    for (extra, bytes) in &export.extra_files {
                        std::fs::write(paths.work.join(extra), bytes)?;
                    }
                    exported.insert((case.name.clone(), format), file);
                }
                Err(e) => refused.push(format!("{:<40} {}", case.name, e)),
            }
        }
    }
    Ok((exported, refused))
}

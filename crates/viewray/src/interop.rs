//! `viewray export` and `viewray import`: scenes for and from Mitsuba 3, pbrt-v4,
//! Blender, three.js and glTF (viewray-interop does the work; this is the file I/O).

use std::io::Write;
use std::path::{Path, PathBuf};

use anyhow::{Context, Result, anyhow, bail};
use clap::Args;
use viewray_interop::Format;
use viewray_output::AtomicFile;
use viewray_scene::{FileKind, SceneLoader};

/// The largest file `viewray import` reads: 256 MiB.
const MAX_IMPORT_BYTES: u64 = 256 << 20;

#[derive(Args, Debug)]
pub(crate) struct ExportArgs {
    /// The viewray scene file to export.
    pub(crate) scene: PathBuf,
    /// The tool to write for: mitsuba (XML, meshes as OBJ files beside it), pbrt
    /// (pbrt-v4), blender (a Python script for `blender -b -P`), three (a three.js JSON
    /// object) or gltf (.gltf, or .glb by OUT's extension).
    #[arg(long, value_name = "TOOL", value_parser = parse_format)]
    pub(crate) to: Format,
    /// Where to write the file.
    #[arg(short, long, value_name = "OUT")]
    pub(crate) output: PathBuf,
}

#[derive(Args, Debug)]
pub(crate) struct ImportArgs {
    /// The file to read: Mitsuba 3 XML (.xml), pbrt-v4 (.pbrt), a three.js JSON object
    /// (.json) or glTF 2.0 (.gltf, .glb).
    pub(crate) file: PathBuf,
    /// The file's format, when its extension does not say: mitsuba, pbrt, three or gltf.
    #[arg(long, value_name = "TOOL", value_parser = parse_format)]
    pub(crate) from: Option<Format>,
}

fn parse_format(text: &str) -> Result<Format, String> {
    Format::from_name(text).ok_or_else(|| {
        let names: Vec<&str> = Format::ALL.iter().map(|f| f.name()).collect();
        format!(
            "unknown tool `{text}`, expected one of {}",
            names.join(", ")
        )
    })
}

/// `viewray export`: the scene written for another tool, atomically (nothing is written
/// when the tool cannot express the camera).
pub(crate) fn export(args: &ExportArgs) -> Result<()> {
    let scene = SceneLoader::file(&args.scene)
        .load()
        .map_err(crate::input::scene_error)?
        .scene;
    let file_name = args
        .output
        .file_name()
        .and_then(|n| n.to_str())
        .context("the output needs a file name")?;
    let export = viewray_interop::export(&scene, args.to, file_name).map_err(|e| {
        anyhow!(
            "{}: cannot export to {}, which {}",
            args.scene.display(),
            e.target(),
            e.lacks()
        )
    })?;
    let folder = match args.output.parent() {
        Some(parent) if !parent.as_os_str().is_empty() => parent.to_path_buf(),
        _ => PathBuf::from("."),
    };
    // Every file is complete in a temporary file before any is moved into place.
    let mut files = Vec::with_capacity(export.extra_files.len() + 1);
    let outputs = export
        .extra_files
        .iter()
        .map(|(name, bytes)| (folder.join(name), bytes.as_slice()))
        .chain([(args.output.clone(), export.main.as_slice())]);
    for (path, bytes) in outputs {
        let mut file = AtomicFile::create(&path)?;
        file.write_all(bytes).map_err(|e| file.error(e))?;
        files.push(file);
    }
    for file in files {
        file.commit()?;
    }
    Ok(())
}

/// What `viewray import` reads, for its errors.
const IMPORTS: &str = "Mitsuba 3 XML (.xml), pbrt-v4 (.pbrt), a three.js JSON object (.json) or \
                       glTF (.gltf, .glb)";

/// Why `viewray import` does not read the file `path` of `kind` (`None`: a kind viewray
/// does not know).
fn not_importable(path: &Path, kind: Option<FileKind>) -> anyhow::Error {
    let name = path.display();
    let Some(kind) = kind else {
        return anyhow!(
            "{name}: cannot tell the format: expected {IMPORTS}; say which with --from"
        );
    };
    match kind.not_a_scene() {
        None => anyhow!(
            "{name}: this is a viewray scene file already: `viewray render {name}` renders it"
        ),
        Some(what) => {
            anyhow!("{name}: {what}; `viewray import` reads other tools' scenes: {IMPORTS}")
        }
    }
}

/// `viewray import`: another tool's file as a viewray scene, RON on stdout.
pub(crate) fn import(args: &ImportArgs) -> Result<()> {
    use std::io::Read;
    let path = &args.file;
    let file = std::fs::File::open(path).map_err(|e| match e.kind() {
        std::io::ErrorKind::NotFound => anyhow!("{}: no such file", path.display()),
        _ => anyhow!("{}: cannot read the file: {e}", path.display()),
    })?;
    if file.metadata().is_ok_and(|m| m.is_dir()) {
        bail!("{}: is a directory, not a scene file", path.display());
    }
    let mut bytes = Vec::new();
    file.take(MAX_IMPORT_BYTES + 1)
        .read_to_end(&mut bytes)
        .with_context(|| format!("{}: cannot read the file", path.display()))?;
    if bytes.len() as u64 > MAX_IMPORT_BYTES {
        bail!(
            "{}: is larger than {} MiB: too large to import",
            path.display(),
            MAX_IMPORT_BYTES >> 20
        );
    }
    let format = match args.from {
        Some(format) => format,
        None => Format::detect(path, &bytes)
            .ok_or_else(|| not_importable(path, FileKind::recognise(path, &bytes)))?,
    };
    let document = viewray_interop::import(&bytes, path, format)?;
    let text = document.to_ron();
    // The camera must load in viewray as it is printed: one out of viewray's range (a
    // field of view of 180 degrees, say) is an error here, not a broken file later.
    let camera_only = viewray_scene::SceneDocument {
        objects: Vec::new(),
        ..document
    };
    SceneLoader::text(&camera_only.to_ron(), path)
        .load()
        .map_err(|e| {
            anyhow!(
                "{}: the imported scene is not valid in viewray: {}",
                path.display(),
                e.message()
            )
        })?;
    let mut out = std::io::stdout().lock();
    out.write_all(text.as_bytes())?;
    out.flush()?;
    Ok(())
}

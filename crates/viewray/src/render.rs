//! `viewray render`: load a scene, render it, write the image atomically.

use std::io::{BufWriter, IsTerminal, Write};
use std::path::{Path, PathBuf};
use std::sync::Arc;
use std::time::{Duration, Instant};

use anyhow::{Context, Result, anyhow, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use serde_json::json;
use tempfile::NamedTempFile;
use viewray_geometry::{Mesh, Object, World};
use viewray_render::{ImageFormat, RenderSettings};
use viewray_scene::{LoadOptions, Scene};

use crate::cli::RenderArgs;
use crate::json;

/// The scene rendered when no scene file is given. It uses only analytic shapes, so it
/// needs no other file and works from any directory.
const DEFAULT_SCENE: &str = include_str!("../../../fixtures/default.ron");

/// The name the default scene goes by in error messages.
const DEFAULT_SCENE_PATH: &str = "fixtures/default.ron";

/// `viewray render`: renders a scene (or the default one) to a PNG or EXR.
pub(crate) fn render(args: &RenderArgs) -> Result<()> {
    if args.output.is_dir() {
        bail!("cannot write {}: it is a directory", args.output.display());
    }
    let format = ImageFormat::from_path(&args.output).ok_or_else(|| {
        anyhow!(
            "cannot write {}: the output must be a .png or .exr file",
            args.output.display()
        )
    })?;
    // Open the output's temporary file first, so that an unwritable path fails before
    // a long render rather than after it.
    let mut output = OutputFile::create(&args.output)?;

    // Load the scene (this builds its BVHs too).
    let options = LoadOptions {
        size: args.size,
        samples: args.samples,
    };
    let start = Instant::now();
    let scene = match &args.scene {
        Some(path) => Scene::load_with(path, options)?,
        None => Scene::parse_with(DEFAULT_SCENE, Path::new(DEFAULT_SCENE_PATH), options)?,
    };
    let load_and_build = start.elapsed();
    // The rebuild estimates the build; it cannot have taken longer than the whole load.
    let build = if args.stats {
        time_bvh_build(&scene.world).min(load_and_build)
    } else {
        Duration::ZERO
    };

    // Render, with a progress bar on a terminal.
    let interactive = std::io::stderr().is_terminal();
    let bar = progress_bar(interactive);
    let settings = RenderSettings {
        threads: args.threads,
        ..RenderSettings::default()
    };
    let start = Instant::now();
    let rendered = viewray_render::render(&scene, &settings, |done, total| {
        bar.set_length(total);
        bar.set_position(done);
    })?;
    let render_time = start.elapsed();
    bar.finish_and_clear();

    // Write the image beside the output and move it into place.
    output.write(|out| rendered.image.write(out, format).map_err(Into::into))?;
    output.persist()?;

    if interactive {
        eprintln!(
            "wrote {}: {} x {}, {} samples per pixel, rendered in {:.2} s",
            args.output.display(),
            rendered.image.width(),
            rendered.image.height(),
            scene.samples,
            render_time.as_secs_f64()
        );
    }
    if args.stats {
        let line = json!({
            "triangles": scene.world.triangle_count(),
            "load_s": seconds(load_and_build.saturating_sub(build)),
            "build_s": seconds(build),
            "render_s": seconds(render_time),
            "rays": rendered.stats.rays,
        });
        let mut out = std::io::stdout().lock();
        json::write_line(&mut out, &line)?;
        out.flush()?;
    }
    Ok(())
}

/// A duration in seconds, to the microsecond.
fn seconds(duration: Duration) -> f64 {
    (duration.as_secs_f64() * 1e6).round() / 1e6
}

/// A progress bar on stderr, or a hidden one when stderr is not a terminal.
fn progress_bar(interactive: bool) -> ProgressBar {
    if !interactive {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
    if let Ok(style) =
        ProgressStyle::with_template("rendering {wide_bar} {percent:>3}% {elapsed} (eta {eta})")
    {
        bar.set_style(style);
    }
    bar
}

/// How long building the scene's BVHs takes: each distinct mesh's and the world's.
///
/// The scene crate builds them while loading and does not time them, so this builds
/// them once more from the same data and times that.
fn time_bvh_build(world: &World) -> Duration {
    let mut meshes: Vec<&Arc<Mesh>> = Vec::new();
    for object in world.objects() {
        if let Object::Instance(instance) = object
            && !meshes.iter().any(|m| Arc::ptr_eq(m, instance.mesh()))
        {
            meshes.push(instance.mesh());
        }
    }
    let mut total = Duration::ZERO;
    for mesh in meshes {
        let data = mesh.data().clone();
        let start = Instant::now();
        let rebuilt = Mesh::new(data);
        total += start.elapsed();
        drop(rebuilt);
    }
    let objects = world.objects().to_vec();
    let start = Instant::now();
    let rebuilt = World::new(objects);
    total += start.elapsed();
    drop(rebuilt);
    total
}

/// An output file written atomically: into a temporary file beside it, renamed into
/// place only when complete. Until then the path keeps what it held; a failure deletes
/// the temporary file.
struct OutputFile {
    path: PathBuf,
    temporary: NamedTempFile,
}

impl OutputFile {
    /// Creates the temporary file in the folder of `path`.
    fn create(path: &Path) -> Result<Self> {
        let cannot = || format!("cannot write {}", path.display());
        let folder = match path.parent() {
            Some(parent) if !parent.as_os_str().is_empty() => parent,
            _ => Path::new("."),
        };
        let mut builder = tempfile::Builder::new();
        builder.prefix(".viewray-").suffix(".tmp");
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // An image is an ordinary file (temporary files default to owner-only).
            builder.permissions(std::fs::Permissions::from_mode(0o644));
        }
        let temporary = builder.tempfile_in(folder).with_context(cannot)?;
        Ok(Self {
            path: path.to_owned(),
            temporary,
        })
    }

    /// Writes the contents with `write`.
    fn write(
        &mut self,
        write: impl FnOnce(&mut BufWriter<&mut std::fs::File>) -> Result<()>,
    ) -> Result<()> {
        let cannot = || format!("cannot write {}", self.path.display());
        let mut out = BufWriter::new(self.temporary.as_file_mut());
        write(&mut out).with_context(cannot)?;
        out.flush().with_context(cannot)?;
        drop(out);
        self.temporary.as_file().sync_all().with_context(cannot)?;
        Ok(())
    }

    /// Moves the finished file into place.
    fn persist(self) -> Result<()> {
        let path = self.path;
        self.temporary
            .persist(&path)
            .map_err(|error| anyhow!("cannot write {}: {}", path.display(), error.error))?;
        Ok(())
    }
}

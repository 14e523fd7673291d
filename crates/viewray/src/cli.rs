//! The command line: clap definitions, vector parsing and one-line usage errors.

use std::ffi::OsString;
use std::fmt::Display;
use std::path::{Path, PathBuf};
use std::process::ExitCode;

use clap::{Args, CommandFactory, Parser, Subcommand, ValueEnum};
use glam::{DVec2, DVec3};
use viewray_render::ImageFormat;
use viewray_scene::{MAX_FPS, MAX_FRAMES, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE, MAX_SAMPLES};

/// The conventions, after the help of the commands that print numbers. Each line fits
/// in 80 columns, so that clap does not rewrap it.
pub(crate) const CONVENTIONS: &str = "\
Conventions (the lecture's, made exact; docs/cameras.md in the source explains
them with worked examples):

Pixels: an image is W columns by H rows. Pixels are 0-based (row, col) from
the top-left by default; --one-based takes and prints the lecture's 1-based
(i, j) = (row + 1, col + 1), and the JSON keys say which: row/col or i/j.

Frame: e = eye, w = -view/|view|, u = (up x w)/|up x w|, v = w x u; u points
right, v up, w back (the camera looks along -w).

Image plane, at a pixel's centre:

    u = ((j - 1/2)/W - 1/2) vw,   v = -((i - 1/2)/H - 1/2) vh

Perspective ray: origin e, direction u U + v V - d W, with U, V, W the frame's
vectors; directions are not normalized.

Exit codes: 0 success, 1 a comparison failed, 2 bad input or usage, other
values internal errors.";

/// What `--version` prints: the version, and the commit it was built from when the
/// build could ask git.
pub(crate) const VERSION: &str = env!("VIEWRAY_VERSION");

/// Ray tracing for learning cameras: render scenes, and check camera frames, viewing rays
/// and projections number by number.
#[derive(Parser, Debug)]
#[command(name = "viewray", version = VERSION, after_long_help = CONVENTIONS,
          after_help = CONVENTIONS)]
pub(crate) struct Cli {
    #[command(subcommand)]
    pub(crate) command: Command,
}

#[derive(Subcommand, Debug)]
pub(crate) enum Command {
    /// Render a scene file to a PNG (or, with an .exr output, linear floats).
    ///
    /// For each pixel: generate viewing rays, find the closest object each meets, and
    /// determine its colour. Without SCENE, renders the built-in default scene (`viewray
    /// scene --default` prints it). The image is the same, byte for byte, on any number
    /// of threads. A progress bar is shown on stderr when it is a terminal.
    Render(RenderArgs),
    /// Render an animation to a looping GIF, an animated PNG or numbered PNG frames.
    ///
    /// SCENE is a scene file with an `animation:` section (keyframed cameras, see the
    /// scene format's docs); --demo NAME renders one of the lecture's moving
    /// demonstrations on its built-in scene instead (--list names them). The output's
    /// name says the format: OUT.gif (a looping GIF, one palette for every frame),
    /// OUT.png (a looping animated PNG, lossless) or DIR/ (DIR/frame_0000.png, ...),
    /// written atomically. --with-diagram puts the side view of each frame's camera
    /// (frustum, image plane, a few rays) beside its picture. A frame's pixels depend
    /// only on the scene and its number. A progress bar over the frames is shown on
    /// stderr when it is a terminal.
    Animate(AnimateArgs),
    /// Print the camera frame e, u, v, w of a scene, or of eye, view and up
    ///
    ///     e = eye,  w = -view/|view|,  u = (up x w)/|up x w|,  v = w x u
    ///
    /// with view = look_at - eye for --look-at, and up = (0, 1, 0) unless --up
    /// says otherwise. With SCENE (a file, or - for standard input), the frame of
    /// its camera, presets included. Prints one JSON line:
    ///
    ///     {"e":[..],"u":[..],"v":[..],"w":[..]}
    #[command(verbatim_doc_comment)]
    Frame(FrameArgs),
    /// Print the viewing rays of pixels, with their image-plane points u, v
    ///
    /// Each ray goes through a point of its pixel, the centre unless --sample says
    /// otherwise, and through the lens centre. The pixel's image-plane point is
    ///
    ///     u =  ((col + 1/2)/W - 1/2) vw  =  ((j - 1/2)/W - 1/2) vw
    ///     v = -((row + 1/2)/H - 1/2) vh  = -((i - 1/2)/H - 1/2) vh
    ///
    /// with the 0-based (row, col) or the lecture's 1-based (i, j). A perspective
    /// camera's ray is then origin e, direction (u + sx) U + (v + sy) V - d W, with
    /// (sx, sy) the lens shift (zero unless the scene sets one); directions are not
    /// normalized.
    ///
    /// Prints one JSON line per pixel,
    ///
    ///     {"row":R,"col":C,"u":U,"v":V,"origin":[..],"direction":[..]}
    ///
    /// or with --one-based
    ///
    ///     {"i":I,"j":J,"u":U,"v":V,"origin":[..],"direction":[..]}
    ///
    /// u and v are null for the panoramic cameras (equirectangular, fisheye), which
    /// have no image plane; origin and direction are null outside a fisheye's image
    /// circle. Without --pixel, every pixel, row by row, each printed as computed.
    #[command(verbatim_doc_comment)]
    Rays(RaysArgs),
    /// Print where points appear in a scene's camera image
    ///
    /// x, y are continuous image coordinates in pixels, x from the left edge and y
    /// from the top; they are the same under both pixel conventions. The pixel
    /// (row, col), or the lecture's (i, j), covers
    ///
    ///     col <= x < col + 1,  row <= y < row + 1   (centre col + 1/2, row + 1/2)
    ///     j - 1 <= x < j,      i - 1 <= y < i       (centre j - 1/2, i - 1/2)
    ///
    /// so the point's image-plane coordinates are u = (x/W - 1/2) vw and
    /// v = -(y/H - 1/2) vh, the lecture's formula with x = j - 1/2 at a centre.
    ///
    /// Prints one JSON line per point,
    ///
    ///     {"point":[..],"x":X,"y":Y,"row":R,"col":C}
    ///
    /// or with --one-based
    ///
    ///     {"point":[..],"x":X,"y":Y,"i":I,"j":J}
    ///
    /// The pixel is null outside the image; all four are null where the point is
    /// not visible (behind a perspective eye).
    #[command(verbatim_doc_comment)]
    Project(ProjectArgs),
    /// Print one pixel's trace, step by step, with every number
    ///
    /// For the pixel (ROW,COL, or the lecture's I,J with --one-based):
    ///
    ///   generate a viewing ray for the pixel: u, v (or a panoramic camera's
    ///     angles), each with its formula, and the ray's origin and direction;
    ///   find the closest object it intersects: each object tested (hit at t, or
    ///     miss), then the closest (object, t, point, normal);
    ///   determine the colour of the object: the shading's terms, for Lit the
    ///     ambient light, each light's diffuse and specular with its shadow ray
    ///     (blocked or not), and a mirror's reflected ray traced the same way;
    ///
    /// then the linear colour and the 8-bit value `viewray render --samples 1`
    /// writes for the pixel (always the same: the numbers are the renderer's own).
    /// With --json, one JSON line per step,
    ///
    ///     {"step":"viewing-ray","bounce":0,"row":R,"col":C,..,"origin":[..],..}
    ///     {"step":"test","bounce":0,"object":K,"shape":"Sphere","t":T}
    ///     ...
    ///
    /// and last {"row":R,"col":C,"linear":[r,g,b],"srgb8":[r,g,b]} (with
    /// --one-based, "i" and "j" instead of "row" and "col").
    #[command(verbatim_doc_comment)]
    Trace(crate::trace::TraceArgs),
    /// Judge renders against reference images, as an instructor would.
    ///
    /// EXPECTED and ACTUAL are two PNG files, or two folders: each *.png file of
    /// EXPECTED is paired with the file of the same name in ACTUAL, as diff -r pairs
    /// files (names match exactly, case included). Antialiasing and sample count are not
    /// errors: both images are blurred by 2 px before NVIDIA's FLIP compares them, so a
    /// correct one-sample render passes. Camera mistakes are errors, and are named from
    /// the transform between the images, measured on the part both show: mirrored ("check
    /// u = up x w"), upside down, rotated ("check the up vector"), scaled ("check vw, vh
    /// or d"), shifted by half a pixel ("check the pixel-centre offset") or more ("check
    /// the shift (sx, sy)"); moves are in pixels, x right and y down. When no transform
    /// explains the difference, the diagnosis says so. With --scene, the diagnosis speaks
    /// the lecture's terms: "the sign of the shift is flipped", "the shift is missing",
    /// "your field of view is 1.25 times too wide".
    ///
    /// Prints a table (NAME, VERDICT, PEAK FLIP, DIAGNOSIS), the files only in ACTUAL
    /// (listed, not judged) and a summary line, or with --json one JSON line per pair
    /// ({"name", "verdict": "pass" | "fail", "peak_flip", "mean_flip", "threshold",
    /// "diagnosis", "transform": {"mirrored_left_right", "upside_down", "rotation"
    /// (degrees counterclockwise), "scale", "about", "shift"}, "reasons"}) and a last line
    /// {"summary": {"total", "passed", "failed", "missing_or_unreadable", "extra"}}.
    /// Images of different sizes fail. A reference image with no file of its name in
    /// ACTUAL fails ("missing"), and so does a file that cannot be read or is not a PNG;
    /// every other pair is still judged. A problem on the EXPECTED side, or a file given
    /// directly that cannot be read, is bad input. Exit code 0 when every pair passes, 1
    /// when any fails, 2 on bad input or usage.
    Compare(crate::compare::CompareArgs),
    /// Grade a class's renders against the reference images.
    ///
    /// REFERENCE is a folder of PNG files (the assignment); SUBMISSIONS holds one folder
    /// per student, each judged against REFERENCE as `viewray compare` judges two
    /// folders: the same rules, diagnoses and --threshold; a missing image, or one that
    /// is not a PNG, fails; the student's other files are listed, not judged.
    ///
    /// Prints one row per student (passed of total, then each failure with its
    /// diagnosis) and a summary: the students who passed everything, each image's pass
    /// rate and the hardest image. --csv writes the gradebook (student, image, verdict,
    /// peak_flip, diagnosis; one line per student and image), --report an HTML report
    /// (the class at a glance, failures first; a page per student with the expected
    /// image, the render and the FLIP heatmap of each failure). With --json, one JSON
    /// line per student and image ({"student", "name", and compare's fields}) and a last
    /// line {"summary": {"students", "images", "passed_everything", "per_image",
    /// "hardest", "not_graded"}}. Students are graded in parallel. Exit code 0 when
    /// every student passes everything, 1 when any image fails or is missing, 2 on bad
    /// usage (REFERENCE missing or without PNG files, SUBMISSIONS not a folder or without
    /// student folders).
    Grade(crate::grade::GradeArgs),
    /// Draw one of the lecture's figures to a PNG or SVG.
    ///
    /// Every figure is computed from the camera code: each 3D point is placed by a
    /// camera's projection and each ray drawn is one the camera generates. The pictures
    /// inside figures (the taxonomy's thumbnails, the distortions', the thin lens at two
    /// apertures) are rendered by the ray tracer. Writes a .png or an .svg as OUT's
    /// extension says, atomically. NAME is one of the figures listed below.
    Figure(crate::figures::FigureArgs),
    /// Draw every lecture figure into a folder, as NAME.png and NAME.svg.
    Figures(crate::figures::FiguresArgs),
    /// Draw the side view of a scene's camera to a PNG or SVG.
    ///
    /// The scene seen from the camera's right (the plane of v and w, world up kept up):
    /// its objects, the eye e with v and w, the image plane edge-on, the frustum's top
    /// and bottom edges, and the viewing rays of five pixels of the middle column, each
    /// drawn to the first object it hits; for a thin lens, the lens and the focus plane.
    /// Every ray drawn is one the camera generates. Writes a .png or an .svg as OUT's
    /// extension says, atomically.
    Diagram(crate::diagram::DiagramArgs),
    /// Serve the live playground: the scene's render, the side view of its camera and
    /// the numbers, in a browser, live as the camera changes.
    ///
    /// Loads the scene once (without SCENE, the built-in default scene) and prints the
    /// page's URL, http://HOST:PORT/, as the first line on standard output. The page
    /// has a control for every projection family and parameter and every taxonomy
    /// preset; its URL holds the camera, so a link reopens it exactly. Everything the
    /// page needs is inside viewray: no network, no CDN. Listens on 127.0.0.1 (this
    /// machine only) unless --host says otherwise; Ctrl-C stops it.
    Serve(crate::serve::ServeArgs),
    /// Print a scene file to start from: the built-in default scene.
    ///
    /// `viewray scene --default > scene.ron` writes the scene `viewray render` renders
    /// without a SCENE (a camera with a field of view and a lens shift, three kinds of
    /// light, planes, triangles and spheres, plain, glossy, mirror and grid materials),
    /// ready to edit and render with `viewray render scene.ron`.
    Scene(SceneArgs),
    /// Print the shell completion script for bash, zsh, fish, elvish or powershell.
    ///
    /// For example, in bash: `source <(viewray completions bash)`, or save it where
    /// your shell looks for completions (`viewray completions bash >
    /// ~/.local/share/bash-completion/completions/viewray`).
    Completions(CompletionsArgs),
    /// Print the man page of viewray or of one of its commands (roff, for `man`).
    ///
    /// For example: `viewray man > ~/.local/share/man/man1/viewray.1` and `viewray man
    /// rays > ~/.local/share/man/man1/viewray-rays.1`, then `man viewray`.
    Man(ManArgs),
    /// Write a scene for another tool: Mitsuba 3, pbrt-v4, Blender, three.js or glTF.
    ///
    /// The camera is carried exactly in the tool's own terms (its field-of-view axis, its
    /// shift units, its orthographic scale). A camera the tool cannot express (an oblique
    /// camera in Mitsuba, pbrt or glTF, a shift in glTF, a panorama where the tool has
    /// none) is an error naming what it lacks, and nothing is written. Objects, diffuse
    /// colours, lights, the image size and samples come along as far as the tool allows.
    Export(crate::interop::ExportArgs),
    /// Read another tool's camera and scene and print it as a viewray scene (RON).
    ///
    /// Reads Mitsuba 3 XML, pbrt-v4, three.js JSON (camera.toJSON() or scene.toJSON())
    /// and glTF 2.0 (.gltf with embedded buffers, .glb). The camera comes across exactly;
    /// what viewray cannot hold of the rest is named in comments at the top. A camera
    /// with no image size (three.js, glTF) gets one of its aspect ratio.
    Import(crate::interop::ImportArgs),
}

/// The file format of an image written to standard output, or one whose name has no
/// .png or .exr extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq, ValueEnum)]
pub(crate) enum OutputFormat {
    /// 8-bit sRGB PNG.
    Png,
    /// OpenEXR of linear 32-bit floats.
    Exr,
}

impl From<OutputFormat> for ImageFormat {
    fn from(format: OutputFormat) -> Self {
        match format {
            OutputFormat::Png => ImageFormat::Png,
            OutputFormat::Exr => ImageFormat::Exr,
        }
    }
}

#[derive(Args, Debug)]
pub(crate) struct RenderArgs {
    /// The scene file to render, or - to read it from standard input (mesh paths are
    /// then relative to the current folder); without it, the built-in default scene.
    pub(crate) scene: Option<PathBuf>,
    /// Where to write the image: .png (8-bit sRGB) or .exr (linear 32-bit floats), or -
    /// for standard output (PNG unless --format says otherwise).
    #[arg(short, long, value_name = "OUT.png", default_value = "viewray.png")]
    pub(crate) output: PathBuf,
    /// The image format, when the output's extension does not say (as for -o -).
    #[arg(long, value_name = "FORMAT")]
    pub(crate) format: Option<OutputFormat>,
    /// Samples per pixel, instead of the scene's (1 is the pixel centre, the lecture's
    /// ray).
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub(crate) samples: Option<u32>,
    /// The image size as WIDTHxHEIGHT, instead of the scene's; fields of view and presets
    /// follow the new aspect ratio, an explicit viewport does not (a warning says when
    /// pixels are no longer square).
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// How many threads to load, build and render on (default: one per core).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub(crate) threads: Option<usize>,
    /// Print one JSON line of statistics on stdout:
    /// {"triangles":N,"load_s":..,"build_s":..,"render_s":..,"rays":N}. load_s is reading
    /// and parsing the scene and its meshes; build_s is building the BVHs (timed by
    /// building them once more, since loading builds them); render_s is tracing and
    /// shading; rays counts primary, shadow and reflected rays.
    #[arg(long)]
    pub(crate) stats: bool,
}

#[derive(Args, Debug)]
pub(crate) struct AnimateArgs {
    /// The scene file to animate (it needs an `animation:` section), or - to read it from
    /// standard input.
    #[arg(value_name = "SCENE", conflicts_with_all = ["demo", "list"],
          required_unless_present_any = ["demo", "list"])]
    pub(crate) scene: Option<PathBuf>,
    /// Where to write: OUT.gif (looping GIF), OUT.png (animated PNG) or DIR/ (numbered
    /// PNG frames, DIR/frame_0000.png, ...).
    #[arg(short, long, value_name = "OUT", default_value = "viewray.gif")]
    pub(crate) output: PathBuf,
    /// Animate one of the lecture's demonstrations on its built-in scene.
    #[arg(long, value_name = "NAME", conflicts_with = "list",
          value_parser = clap::builder::PossibleValuesParser::new(viewray_animation::demo_names()))]
    pub(crate) demo: Option<String>,
    /// List the demonstrations, one line each, and exit.
    #[arg(long)]
    pub(crate) list: bool,
    /// How many frames, instead of the animation's (1 to 10000).
    #[arg(long, value_name = "N", value_parser = parse_frames)]
    pub(crate) frames: Option<u32>,
    /// Frames per second, instead of the animation's (1 to 100; a GIF plays at most 50).
    #[arg(long, value_name = "N", value_parser = parse_fps)]
    pub(crate) fps: Option<u32>,
    /// The size of each picture as WIDTHxHEIGHT, instead of the scene's; fields of view
    /// and presets follow the new aspect ratio, as for `render`.
    #[arg(long, value_name = "WxH", value_parser = parse_size)]
    pub(crate) size: Option<(u32, u32)>,
    /// Samples per pixel, instead of the scene's.
    #[arg(long, value_name = "N", value_parser = parse_samples)]
    pub(crate) samples: Option<u32>,
    /// Put the side view of each frame's camera beside its picture.
    #[arg(long)]
    pub(crate) with_diagram: bool,
    /// How many threads to render on (default: one per core).
    #[arg(long, value_name = "N", value_parser = parse_threads)]
    pub(crate) threads: Option<usize>,
    /// Print one JSON line of statistics on stdout:
    /// {"frames":N,"width":W,"height":H,"render_s":..,"encode_s":..}. render_s is
    /// rendering and laying out the frames; encode_s is choosing the palette, encoding
    /// and writing them.
    #[arg(long)]
    pub(crate) stats: bool,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct FrameArgs {
    /// A scene file (or - for standard input) whose camera's frame to print, instead of
    /// --eye, --view or --look-at, and --up.
    #[arg(value_name = "SCENE", conflicts_with_all = ["eye", "view", "look_at", "up"])]
    pub(crate) scene: Option<PathBuf>,
    /// The eye position e.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) eye: Option<DVec3>,
    /// The view direction (or give --look-at).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          conflicts_with = "look_at")]
    pub(crate) view: Option<DVec3>,
    /// A point to look at: view = look_at - eye.
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) look_at: Option<DVec3>,
    /// The up vector; it fixes the camera's roll and need not be perpendicular to view
    /// [default: 0,1,0].
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true)]
    pub(crate) up: Option<DVec3>,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct RaysArgs {
    /// The scene file whose camera and image size to use, or - for standard input.
    pub(crate) scene: PathBuf,
    /// A pixel as ROW,COL, 0-based (or I,J with --one-based); repeat the option, or list
    /// several after it. Without it, every pixel.
    #[arg(long, value_name = "ROW,COL", value_parser = parse_pixel, allow_hyphen_values = true)]
    pub(crate) pixel: Vec<(i64, i64)>,
    /// Pixels are given and printed 1-based, as the lecture's (i, j), with the JSON keys
    /// "i" and "j" instead of "row" and "col".
    #[arg(long)]
    pub(crate) one_based: bool,
    /// The point inside each pixel as OX,OY, each in [0, 1) from the pixel's top-left
    /// corner; 0.5,0.5 is the centre, the lecture's ray.
    #[arg(long, value_name = "OX,OY", value_parser = parse_offset, default_value = "0.5,0.5")]
    pub(crate) sample: DVec2,
}

#[derive(Args, Debug)]
#[command(after_help = CONVENTIONS)]
pub(crate) struct ProjectArgs {
    /// The scene file whose camera and image size to use, or - for standard input.
    pub(crate) scene: PathBuf,
    /// A world point as X,Y,Z (repeat the option, or list several after it).
    #[arg(long, value_name = "X,Y,Z", value_parser = parse_vec3, allow_hyphen_values = true,
          required = true)]
    pub(crate) point: Vec<DVec3>,
    /// Print the pixel 1-based, as the lecture's (i, j), with the JSON keys "i" and "j"
    /// instead of "row" and "col" (x and y do not change).
    #[arg(long)]
    pub(crate) one_based: bool,
}

#[derive(Args, Debug)]
pub(crate) struct SceneArgs {
    /// Print the built-in default scene, the one `viewray render` renders without a
    /// SCENE.
    #[arg(long, required = true)]
    pub(crate) default: bool,
}

#[derive(Args, Debug)]
pub(crate) struct CompletionsArgs {
    /// The shell to complete for.
    #[arg(value_name = "SHELL")]
    pub(crate) shell: clap_complete::Shell,
}

#[derive(Args, Debug)]
pub(crate) struct ManArgs {
    /// The command whose page to print (`viewray-COMMAND`); without it, viewray's own
    /// page, which lists the commands.
    #[arg(value_name = "COMMAND")]
    pub(crate) command: Option<String>,
}

/// The SCENE argument that means standard input.
pub(crate) const STDIN: &str = "-";

/// Whether a SCENE or OUT argument is `-`, standard input or output.
pub(crate) fn is_standard_stream(path: &Path) -> bool {
    path.as_os_str() == STDIN
}

/// Parses `text` as comma-separated finite numbers, exactly `N` of them.
fn parse_numbers<const N: usize>(text: &str, example: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let wrong = || format!("expected {N} numbers separated by commas, like {example}");
    if parts.len() != N {
        return Err(wrong());
    }
    let mut numbers = [0.0; N];
    for (number, part) in numbers.iter_mut().zip(parts) {
        *number = part.parse::<f64>().map_err(|_| wrong())?;
        if !number.is_finite() {
            return Err(format!("`{part}` is not a finite number"));
        }
    }
    Ok(numbers)
}

fn parse_vec3(text: &str) -> Result<DVec3, String> {
    parse_numbers::<3>(text, "0,1.5,-2").map(DVec3::from)
}

/// Parses an offset inside a pixel: two numbers in `[0, 1)`.
fn parse_offset(text: &str) -> Result<DVec2, String> {
    let offset = DVec2::from(parse_numbers::<2>(text, "0.5,0.5")?);
    if !(0.0..1.0).contains(&offset.x) || !(0.0..1.0).contains(&offset.y) {
        return Err(format!(
            "{},{} lies outside the pixel: each offset must be in [0, 1)",
            offset.x, offset.y
        ));
    }
    Ok(offset)
}

pub(crate) fn parse_pixel(text: &str) -> Result<(i64, i64), String> {
    let wrong = || "expected a pixel as two whole numbers ROW,COL, like 2,3".to_owned();
    let (row, col) = text.split_once(',').ok_or_else(wrong)?;
    let row = row.trim().parse().map_err(|_| wrong())?;
    let col = col.trim().parse().map_err(|_| wrong())?;
    Ok((row, col))
}

/// Parses an image size `WIDTHxHEIGHT` within the renderer's limits.
fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let wrong = || "expected the size as WIDTHxHEIGHT in pixels, like 640x480".to_owned();
    let (width, height) = text.split_once(['x', 'X']).ok_or_else(wrong)?;
    let width: u64 = width.trim().parse().map_err(|_| wrong())?;
    let height: u64 = height.trim().parse().map_err(|_| wrong())?;
    if width == 0 || height == 0 {
        return Err(format!(
            "the image must be at least 1 x 1 pixels, found {width} x {height}"
        ));
    }
    let side = u64::from(MAX_IMAGE_SIDE);
    if width > side || height > side {
        return Err(format!(
            "{width} x {height} is too large: each side can be at most {side} pixels"
        ));
    }
    // Both sides are at most MAX_IMAGE_SIDE (2^14), so the product cannot overflow.
    if width * height > MAX_IMAGE_PIXELS {
        return Err(format!(
            "{width} x {height} is too large: at most {MAX_IMAGE_PIXELS} pixels (2^28)"
        ));
    }
    // Both sides are at most MAX_IMAGE_SIDE, so they fit.
    Ok((width as u32, height as u32))
}

/// Parses a number of samples per pixel, 1 to [`MAX_SAMPLES`].
fn parse_samples(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of samples from 1 to {MAX_SAMPLES}");
    let samples: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(samples) {
        Ok(samples) if (1..=MAX_SAMPLES).contains(&samples) => Ok(samples),
        _ => Err(wrong()),
    }
}

/// Parses a number of frames, 1 to [`MAX_FRAMES`].
fn parse_frames(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of frames from 1 to {MAX_FRAMES}");
    let frames: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(frames) {
        Ok(frames) if (1..=MAX_FRAMES).contains(&frames) => Ok(frames),
        _ => Err(wrong()),
    }
}

/// Parses a number of frames per second, 1 to [`MAX_FPS`].
fn parse_fps(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of frames per second from 1 to {MAX_FPS}");
    let fps: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(fps) {
        Ok(fps) if (1..=MAX_FPS).contains(&fps) => Ok(fps),
        _ => Err(wrong()),
    }
}

/// The most render threads `--threads` accepts.
const MAX_THREADS: usize = 1024;

/// Parses a number of threads, 1 to [`MAX_THREADS`].
fn parse_threads(text: &str) -> Result<usize, String> {
    let wrong = || format!("expected a whole number of threads from 1 to {MAX_THREADS}");
    let threads: usize = text.trim().parse().map_err(|_| wrong())?;
    if (1..=MAX_THREADS).contains(&threads) {
        Ok(threads)
    } else {
        Err(wrong())
    }
}

/// Options that take one value each time and may be followed by several:
/// `--point 1,2,3 -4,5,6` means `--point 1,2,3 --point -4,5,6`.
const REPEATABLE: [&str; 2] = ["--point", "--pixel"];

/// Rewrites `--point A B` as `--point A --point B`, so that several values may follow one
/// option while values starting with `-` (negative coordinates) are still values.
pub(crate) fn expand_repeated_values(args: impl IntoIterator<Item = OsString>) -> Vec<OsString> {
    let mut out = Vec::new();
    let mut repeating: Option<OsString> = None;
    let mut just_saw_option = false;
    for arg in args {
        let text = arg.to_str().unwrap_or_default();
        let looks_like_value = !text.is_empty()
            && text.contains(',')
            && text
                .chars()
                .all(|c| c.is_ascii_digit() || ".,-+eE ".contains(c));
        if REPEATABLE.contains(&text) {
            repeating = Some(arg.clone());
            just_saw_option = true;
            out.push(arg);
            continue;
        }
        if let Some(option) = &repeating {
            if looks_like_value {
                if !just_saw_option {
                    out.push(option.clone());
                }
                just_saw_option = false;
                out.push(arg);
                continue;
            }
            repeating = None;
        }
        just_saw_option = false;
        out.push(arg);
    }
    out
}

/// The options whose value is several numbers joined by commas, the format each takes
/// and how many numbers that is.
const NUMBER_LIST_OPTIONS: [(&str, &str, usize); 7] = [
    ("--eye", "X,Y,Z", 3),
    ("--view", "X,Y,Z", 3),
    ("--look-at", "X,Y,Z", 3),
    ("--up", "X,Y,Z", 3),
    ("--point", "X,Y,Z", 3),
    ("--pixel", "ROW,COL", 2),
    ("--sample", "OX,OY", 2),
];

/// The options of `viewray frame` that describe a camera by hand.
const FRAME_OPTIONS: [&str; 4] = ["--eye", "--view", "--look-at", "--up"];

/// The subcommand named in `args` (which start with the program's name), if any.
pub(crate) fn subcommand_in(args: &[OsString]) -> Option<String> {
    let name = args.get(1)?.to_str()?;
    Cli::command()
        .get_subcommands()
        .any(|command| command.get_name() == name)
        .then(|| name.to_owned())
}

/// `(see `viewray COMMAND --help`)`, the pointer every usage error ends with.
pub(crate) fn see_help(command: Option<&str>) -> String {
    match command {
        Some(command) => format!("(see `viewray {command} --help`)"),
        None => "(see `viewray --help`)".to_owned(),
    }
}

/// A usage error of `viewray COMMAND`: the message and where the help is.
pub(crate) fn usage_error(command: &str, message: impl Display) -> anyhow::Error {
    anyhow::anyhow!("{message} {}", see_help(Some(command)))
}

/// Finds numbers separated by spaces where an option wants them joined by commas
/// (`--eye 1 2 3`, `--pixel 1 1`), which clap would report as "unexpected argument
/// '2'". Returns the message that says the format and what to write instead.
pub(crate) fn spaced_number_list(args: &[OsString]) -> Option<String> {
    let texts: Vec<&str> = args.iter().map(|a| a.to_str().unwrap_or("")).collect();
    for (index, &arg) in texts.iter().enumerate() {
        let Some(&(option, format, count)) = NUMBER_LIST_OPTIONS.iter().find(|o| o.0 == arg) else {
            continue;
        };
        // Take the arguments after the option while they are numbers (or pieces of a
        // list, like `1,`) and fewer than the option needs.
        let mut numbers: Vec<&str> = Vec::new();
        let mut taken = 0;
        for next in &texts[index + 1..] {
            let pieces: Vec<&str> = next.split(',').filter(|p| !p.trim().is_empty()).collect();
            let numeric =
                !pieces.is_empty() && pieces.iter().all(|p| p.trim().parse::<f64>().is_ok());
            if !numeric || numbers.len() + pieces.len() > count {
                break;
            }
            numbers.extend(pieces);
            taken += 1;
            if numbers.len() == count {
                break;
            }
        }
        if taken > 1 {
            let typed = texts[index + 1..=index + taken].join(" ");
            return Some(format!(
                "{option} takes {format}, {count} numbers joined by commas without spaces: \
                 write `{option} {}`, not `{option} {typed}`",
                numbers.join(",")
            ));
        }
    }
    None
}

/// Prints a clap error: help and version as clap formats them, usage errors as one line
/// `error: ...` pointing to the subcommand's help, exit code 2.
pub(crate) fn report_usage_error(error: &clap::Error, args: &[OsString]) -> ExitCode {
    use clap::error::{ContextKind, ContextValue, ErrorKind};
    if matches!(
        error.kind(),
        ErrorKind::DisplayHelp
            | ErrorKind::DisplayVersion
            | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand
    ) {
        let _ = error.print();
        return if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
            ExitCode::from(crate::EXIT_BAD_INPUT)
        } else {
            ExitCode::SUCCESS
        };
    }
    let command = subcommand_in(args);
    let help = see_help(command.as_deref());
    let invalid = match error.get(ContextKind::InvalidArg) {
        Some(ContextValue::String(arg)) => Some(arg.as_str()),
        _ => None,
    };
    // `viewray rays --eye ..`: the camera comes from the scene; clap's tip ("use '--
    // --eye'") would send a student the wrong way.
    if error.kind() == ErrorKind::UnknownArgument
        && let (Some(command @ ("rays" | "project" | "trace")), Some(arg)) =
            (command.as_deref(), invalid)
        && let Some(option) = FRAME_OPTIONS.iter().find(|o| arg.starts_with(**o))
    {
        crate::style::error(format_args!(
            "`viewray {command}` takes its camera from a SCENE file, not from {option}; \
             `viewray frame --eye X,Y,Z --look-at X,Y,Z` prints the frame of eye, view and \
             up {help}"
        ));
        return ExitCode::from(crate::EXIT_BAD_INPUT);
    }
    let text = error.render().to_string();
    let line: Vec<&str> = text
        .lines()
        .map(str::trim)
        .take_while(|line| !line.starts_with("Usage:") && !line.starts_with("For more information"))
        // clap suggests `-- --option` to pass an unknown option as a value: never what a
        // viewray user means.
        .filter(|line| !line.is_empty() && !line.starts_with("tip: to pass '"))
        .collect();
    let line = line.join(" ");
    let line = line.strip_prefix("error: ").unwrap_or(&line);
    crate::style::error(format_args!("{line} {help}"));
    ExitCode::from(crate::EXIT_BAD_INPUT)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn os(args: &[&str]) -> Vec<OsString> {
        args.iter().map(OsString::from).collect()
    }

    fn expand(args: &[&str]) -> Vec<String> {
        expand_repeated_values(os(args))
            .into_iter()
            .map(|a| a.into_string().unwrap())
            .collect()
    }

    #[test]
    fn several_values_after_one_option_become_repeated_options() {
        assert_eq!(
            expand(&[
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "-4,5,6",
                "--one-based"
            ]),
            [
                "viewray",
                "project",
                "s.ron",
                "--point",
                "1,2,3",
                "--point",
                "-4,5,6",
                "--one-based"
            ]
        );
        assert_eq!(
            expand(&["viewray", "rays", "--pixel", "0,0", "s.ron"]),
            ["viewray", "rays", "--pixel", "0,0", "s.ron"]
        );
    }

    #[track_caller]
    fn check_spaced(args: &[&str], expected: Option<&str>) {
        assert_eq!(spaced_number_list(&os(args)).as_deref(), expected);
    }

    #[test]
    fn numbers_separated_by_spaces_are_caught_with_the_fix() {
        check_spaced(
            &[
                "viewray", "frame", "--eye", "1", "2", "3", "--view", "0,0,-1",
            ],
            Some(
                "--eye takes X,Y,Z, 3 numbers joined by commas without spaces: write \
                 `--eye 1,2,3`, not `--eye 1 2 3`",
            ),
        );
        check_spaced(
            &["viewray", "rays", "s.ron", "--pixel", "1", "1"],
            Some(
                "--pixel takes ROW,COL, 2 numbers joined by commas without spaces: write \
                 `--pixel 1,1`, not `--pixel 1 1`",
            ),
        );
        check_spaced(
            &["viewray", "frame", "--eye", "1,", "-2,", "3"],
            Some(
                "--eye takes X,Y,Z, 3 numbers joined by commas without spaces: write \
                 `--eye 1,-2,3`, not `--eye 1, -2, 3`",
            ),
        );
        // Correct lists, several values after one option, and a lone wrong value (which
        // the option's own parser explains) are left alone.
        check_spaced(
            &["viewray", "project", "s", "--point", "1,2,3", "4,5,6"],
            None,
        );
        check_spaced(&["viewray", "rays", "s", "--pixel", "1,1", "2,2"], None);
        check_spaced(&["viewray", "frame", "--eye", "1", "--view", "0,0,1"], None);
        check_spaced(&["viewray", "rays", "--pixel", "1", "s.ron"], None);
    }

    #[test]
    fn sizes_samples_threads_and_offsets_are_checked() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("16384X16384"), Ok((16384, 16384)));
        for bad in [
            "0x10",
            "10x0",
            "100000x10",
            "16384x16385",
            "640",
            "640x",
            "axb",
            "-1x5",
            "99999999999999999999x1",
        ] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_samples("16"), Ok(16));
        for bad in ["0", "-1", "65537", "99999999999", "x"] {
            assert!(parse_samples(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_frames("48"), Ok(48));
        for bad in ["0", "10001", "-3", "2.5", "x"] {
            assert!(parse_frames(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_fps("24"), Ok(24));
        for bad in ["0", "101", "24.0"] {
            assert!(parse_fps(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_threads("2"), Ok(2));
        assert!(parse_threads("0").is_err());
        assert_eq!(parse_offset("0,0.999"), Ok(DVec2::new(0.0, 0.999)));
        for bad in ["1,0", "0,-0.1", "0.5", "nan,0"] {
            assert!(parse_offset(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn vectors_parse_with_negative_numbers_and_spaces() {
        assert_eq!(parse_vec3("-1, 0,5.5"), Ok(DVec3::new(-1.0, 0.0, 5.5)));
        assert!(parse_vec3("1,2").is_err());
        assert!(parse_vec3("1,2,x").is_err());
        assert!(parse_vec3("1,2,inf").is_err());
        assert_eq!(parse_pixel("2, 3"), Ok((2, 3)));
        assert_eq!(
            parse_pixel("-9223372036854775808,0"),
            Ok((i64::MIN, 0)),
            "any whole number parses; the command checks it against the image"
        );
        assert!(parse_pixel("2.5,3").is_err());
        assert!(parse_pixel("9223372036854775808,0").is_err());
    }

    #[test]
    fn the_clap_definitions_are_consistent() {
        Cli::command().debug_assert();
    }
}

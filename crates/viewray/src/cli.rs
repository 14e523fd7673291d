//! The command line's shape: [`Cli`] and its [`Command`]s (each variant's doc is the
//! command's help), assembled from each command's arguments, which the commands' modules
//! define; and the two commands that print the command line itself (completions, man).

use std::ffi::OsString;
use std::io::{BufWriter, Write};

use anyhow::Result;
use clap::{Args, CommandFactory, Parser, Subcommand};

use crate::commands::CONVENTIONS;

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
    Render(crate::render::RenderArgs),
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
    Animate(crate::animate::AnimateArgs),
    /// Print the camera frame e, u, v, w of a scene, or of eye, view and up
    ///
    ///     e = eye,  w = -view/|view|,  u = (up x w)/|up x w|,  v = w x u
    ///
    /// with view = look_at - eye for --look-at, and up = (0, 1, 0) unless --up
    /// says otherwise. With SCENE (a file, or - for standard input), the frame of
    /// its camera, presets included. Prints one JSON line:
    ///
    ///     {"e":[..],"u":[..],"v":[..],"w":[..]}
    ///
    /// A scene's camera with a lens adds its plane of sharp focus (its point nearest
    /// the lens centre and its unit normal toward the lens), and a tilted lens its
    /// hinge line (the point nearest the lens centre, the direction w x n):
    ///
    ///     "focus_plane":{"point":[..],"normal":[..]}
    ///     "hinge_line":{"point":[..],"direction":[..]}
    #[command(verbatim_doc_comment)]
    Frame(crate::commands::FrameArgs),
    /// Print the viewing rays of pixels, with their image-plane points u, v
    ///
    /// Each ray goes through a point of its pixel, the centre unless --sample says
    /// otherwise, and through the lens centre unless --lens says otherwise. The pixel's
    /// image-plane point is
    ///
    ///     u =  ((col + 1/2)/W - 1/2) vw  =  ((j - 1/2)/W - 1/2) vw
    ///     v = -((row + 1/2)/H - 1/2) vh  = -((i - 1/2)/H - 1/2) vh
    ///
    /// with the 0-based (row, col) or the lecture's 1-based (i, j). A perspective
    /// camera's ray is then origin e, direction (u + sx) U + (v + sy) V - d W, with
    /// (sx, sy) the lens shift (zero unless the scene sets one); directions are not
    /// normalized. A thin lens's ray starts at the lens point e + r (LX U + LY V) and
    /// goes through the point where the pixel's centre ray meets the plane of focus
    /// (reached at t = 1; `viewray frame SCENE` prints the plane).
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
    Rays(crate::commands::RaysArgs),
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
    Project(crate::commands::ProjectArgs),
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
    // The help text shows JSON, whose brackets rustdoc would take for links.
    #[allow(rustdoc::broken_intra_doc_links)]
    #[command(verbatim_doc_comment)]
    Trace(crate::trace::TraceArgs),
    /// Check a student's numbers: frames, viewing rays and projections, answer by answer.
    ///
    /// ANSWERS is what the student's program printed, in any language: viewray's own
    /// JSON lines (the keys of `frame`, `rays`, `project`), or plain lines, numbers
    /// apart by white space or commas, with # comments:
    ///
    ///     frame ex ey ez ux uy uz vx vy vz wx wy wz
    ///     ray ROW COL ox oy oz dx dy dz
    ///     project px py pz x y          (x y may be null null: not seen)
    ///
    /// Each answer is judged against the scene's camera (relative tolerance; a
    /// direction is right up to a positive factor, so a normalized one is right, unless
    /// --exact-direction), and printed right, or wrong with the expected value. The wrong
    /// ones are then explained by the lecture's catalogue of mistakes: the entry (or two
    /// entries together) that reproduces every answer, with the formula to fix; or, when
    /// none does, what the wrong answers have in common. Pixels 1-based where 0-based
    /// were asked (or the other way round) are named as such.
    ///
    /// Exit code 0 when every answer is right, 1 when any is wrong, 2 on bad input (an
    /// answer that cannot be read, naming its line and what was expected).
    #[command(verbatim_doc_comment)]
    Check(crate::check::CheckArgs),
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
    /// Grade one student's submission for an autograding platform.
    ///
    /// ASSIGNMENT is an assignment file (RON, paths relative to it): its tests, each a
    /// scene and what the student hands in, a picture (judged by its camera, its
    /// appearance or both, as the assignment's `judge` says) or answers (judged as
    /// `viewray check` judges them), with points and visibility; optionally the command
    /// that runs the student's own program once per test (`{scene}` and `{output}`
    /// replaced, in a copy of SUBMISSION, with a time limit). Writes RESULTS in the
    /// platform's format (--format): per-test points and status, the diagnosis with the
    /// formula line to fix and, where the format shows pictures, expected, yours and
    /// difference. A results file is always written: when nothing can be graded (a
    /// broken assignment, a missing submission) it says why. Prints one line per test.
    /// Exit code 0 when every test passes, 1 when any fails, 2 when nothing could be
    /// graded or on bad usage.
    ///
    /// `viewray autograde kit ASSIGNMENT --for gradescope|github -o OUT` writes what the
    /// platform takes: Gradescope's autograder zip, or GitHub Classroom's workflow and
    /// files.
    Autograde(crate::autograde::AutogradeArgs),
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
    Scene(crate::commands::SceneArgs),
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

/// The subcommand named in `args` (which start with the program's name), if any.
pub(crate) fn subcommand_in(args: &[OsString]) -> Option<String> {
    let name = args.get(1)?.to_str()?;
    Cli::command()
        .get_subcommands()
        .any(|command| command.get_name() == name)
        .then(|| name.to_owned())
}

/// `viewray completions SHELL`: the shell's completion script.
pub(crate) fn completions(args: &CompletionsArgs) -> Result<()> {
    // Into memory first: clap_complete panics when its writer fails (as a closed pipe
    // makes it), and a write error here is reported like any other.
    let mut script = Vec::new();
    clap_complete::generate(args.shell, &mut Cli::command(), "viewray", &mut script);
    let mut out = std::io::stdout().lock();
    out.write_all(&script)?;
    out.flush()?;
    Ok(())
}

/// `viewray man [COMMAND]`: a man page, in roff.
pub(crate) fn man(args: &ManArgs) -> Result<()> {
    let mut command = Cli::command();
    // Building names the subcommands `viewray-NAME`, as their pages are called.
    command.build();
    let page = match &args.command {
        None => command,
        Some(name) => match command.find_subcommand(name) {
            Some(subcommand) => subcommand.clone(),
            None => {
                let names: Vec<&str> = command
                    .get_subcommands()
                    .map(clap::Command::get_name)
                    .filter(|n| *n != "help")
                    .collect();
                return Err(crate::usage::usage_error(
                    "man",
                    format!("no command `{name}`: one of {}", names.join(", ")),
                ));
            }
        },
    };
    let mut out = BufWriter::new(std::io::stdout().lock());
    clap_mangen::Man::new(page)
        .source(format!("viewray {}", VERSION))
        .manual("viewray manual")
        .render(&mut out)?;
    out.flush()?;
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_clap_definitions_are_consistent() {
        Cli::command().debug_assert();
    }
}

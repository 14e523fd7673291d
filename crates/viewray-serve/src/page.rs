//! The pages: HTML, CSS (`base.css` shared, then each page's own) and JavaScript written by
//! hand, compiled into the binary, and put together once per served scene with the
//! scene's starting state. The playground's script
//! is in four parts (`ron.js`, `live.js`, `page.js`, `presenter.js`) and `trace.js` (the
//! chosen pixel's trace, a panel of its own), the lecture's in four
//! (`lecture-math.js`: MathML and the command line's digits, `lecture-trace.js`: the first
//! step's pixel through the pseudocode, from its trace, `lecture-steps.js`: the steps in
//! the lecture's order, `lecture.js`: requests, controls, keys).

use serde_json::json;
use viewray_scene::{Scene, Shading};

use crate::Limits;

const HTML: &str = include_str!("../page/index.html");
/// What both pages' styles share (the lecture figures' colours, the type, the body),
/// put before each page's own sheet.
const BASE_CSS: &str = include_str!("../page/base.css");
const CSS: &str = include_str!("../page/page.css");
/// The page's script in its four parts, and the trace's panel, in the order they are put
/// together: the RON reader, the state and requests, the trace (which the requests ask
/// for), the controls, the presenter (which starts the page).
const SCRIPTS: [&str; 5] = [
    include_str!("../page/ron.js"),
    include_str!("../page/live.js"),
    include_str!("../page/trace.js"),
    include_str!("../page/page.js"),
    include_str!("../page/presenter.js"),
];

const LECTURE_HTML: &str = include_str!("../page/lecture.html");
const LECTURE_CSS: &str = include_str!("../page/lecture.css");
/// The lecture's script in its four parts, in the order they are put together.
const LECTURE_SCRIPTS: [&str; 4] = [
    include_str!("../page/lecture-math.js"),
    include_str!("../page/lecture-trace.js"),
    include_str!("../page/lecture-steps.js"),
    include_str!("../page/lecture.js"),
];

/// The lecture (`/lecture`) for the scene called `name` whose camera is `camera_text`:
/// the first step follows one pixel through the served scene's camera; the others make
/// their own cameras, written for the default scene's objects around the origin.
pub(crate) fn lecture(name: &str, camera_text: &str) -> String {
    let state = json!({ "scene": name, "camera": camera_text });
    let state = state.to_string().replace("</", "<\\/");
    LECTURE_HTML
        .replace("/*STYLE*/", &[BASE_CSS, LECTURE_CSS].join("\n"))
        .replace("/*SCRIPT*/", &LECTURE_SCRIPTS.join("\n"))
        .replace("{/*STATE*/}", &state)
        .replace("<!--SCENE-->", &escape_html(name))
}

/// The page for the scene called `name` whose camera is `camera_text`: the served
/// scene's camera, size, samples and shading are the state a page without a URL
/// fragment starts from (and the "reset" button returns to).
pub(crate) fn page(name: &str, camera_text: &str, scene: &Scene) -> String {
    let camera = scene.camera();
    let limits = Limits::default();
    let state = json!({
        "scene": name,
        "camera": camera_text,
        "width": camera.width(),
        "height": camera.height(),
        "samples": scene.samples(),
        "shading": scene.shading().name(),
        "shadings": Shading::ALL.map(Shading::name),
        "limits": {
            "max_side": limits.max_side,
            "max_pixels": limits.max_pixels,
            "max_samples": limits.max_samples,
            "max_frame_samples": limits.max_frame_samples,
        },
    });
    // Inside <script>, "</" could end the element: JSON allows writing it "<\/".
    let state = state.to_string().replace("</", "<\\/");
    HTML.replace("/*STYLE*/", &[BASE_CSS, CSS].join("\n"))
        .replace("/*SCRIPT*/", &SCRIPTS.join("\n"))
        .replace("{/*STATE*/}", &state)
        .replace("<!--SCENE-->", &escape_html(name))
}

/// `text` safe inside HTML text and attribute values.
fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

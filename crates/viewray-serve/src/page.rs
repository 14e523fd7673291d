//! The page: HTML, CSS and JavaScript written by hand (the script in four parts: `ron.js`,
//! `live.js`, `page.js`, `presenter.js`), compiled into the binary, and put together once
//! per served scene with the scene's starting state.

use serde_json::json;
use viewray_scene::{Scene, Shading};

use crate::Limits;

const HTML: &str = include_str!("../page/index.html");
const CSS: &str = include_str!("../page/page.css");
/// The page's script in its four parts, in the order they are put together: the RON
/// reader, the state and requests, the controls, the presenter (which starts the page).
const SCRIPTS: [&str; 4] = [
    include_str!("../page/ron.js"),
    include_str!("../page/live.js"),
    include_str!("../page/page.js"),
    include_str!("../page/presenter.js"),
];

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
    HTML.replace("/*STYLE*/", CSS)
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

//! The pages: HTML, CSS (`base.css` shared, then each page's own) and JavaScript written by
//! hand, compiled into the binary, and put together once per served scene with the
//! scene's starting state (and the catalogue of mistakes). The playground's script
//! is in four parts (`ron.js`, `live.js`, `page.js`, `presenter.js`), `trace.js` (the
//! chosen pixel's trace, a panel of its own) and `mistakes.js` (the catalogue's menu and
//! the label naming the mistakes made), the lecture's in four
//! (`lecture-math.js`: MathML and the command line's digits, `lecture-trace.js`: the first
//! step's pixel through the pseudocode, from its trace, `lecture-steps.js`: the steps in
//! the lecture's order, `lecture.js`: requests, controls, keys).

use std::path::Path;

use serde_json::{Value, json};
use viewray_camera::Mistake;
use viewray_scene::{Scene, Shading, parse_camera};

use crate::Limits;

const HTML: &str = include_str!("../page/index.html");
/// What both pages' styles share (the lecture figures' colours, the type, the body),
/// put before each page's own sheet.
const BASE_CSS: &str = include_str!("../page/base.css");
const CSS: &str = include_str!("../page/page.css");
/// The page's script in its four parts, the trace's panel and the mistakes' menu, in the
/// order they are put together: the RON reader, the state and requests, the trace (which
/// the requests ask for), the controls, the mistakes, the presenter (which starts the
/// page).
const SCRIPTS: [&str; 6] = [
    include_str!("../page/ron.js"),
    include_str!("../page/live.js"),
    include_str!("../page/trace.js"),
    include_str!("../page/page.js"),
    include_str!("../page/mistakes.js"),
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
        "catalogue": catalogue(),
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

/// A camera of each family the page offers, as its RON: the families a mistake fits are
/// those of these cameras [`Mistake::fits`] accepts.
const FAMILIES: [(&str, &str); 6] = [
    ("Perspective", "Perspective(fov_y: 40.0)"),
    (
        "ThinLens",
        "ThinLens(fov_y: 40.0, aperture: 0.1, focus: 5.0)",
    ),
    ("Orthographic", "Orthographic(height: 4.0)"),
    ("Oblique", "Oblique(height: 4.0, ratio: 0.5, angle: 45.0)"),
    ("Fisheye", "Fisheye(fov: 180.0)"),
    ("Equirectangular", "Equirectangular"),
];

/// The mistakes that move the picture left or right (mirror it, turn it, look elsewhere,
/// stretch or shift it across): the page shows the top view beside the side view while
/// one is made, since the side view cannot show what happens across.
const SIDEWAYS: [Mistake; 13] = [
    Mistake::USign,
    Mistake::IJSwapped,
    Mistake::ViewportSwapped,
    Mistake::DistanceSign,
    Mistake::EyeMissing,
    Mistake::BasisMissing,
    Mistake::WView,
    Mistake::UCrossOrder,
    Mistake::UNotNormalized,
    Mistake::ShiftSign,
    Mistake::ShiftMissing,
    Mistake::ObliqueSign,
    Mistake::ObliqueAsOrtho,
];

/// The lecture's catalogue of mistakes for the page, in its order: each entry's words,
/// the families of camera it can be made in, and whether it moves the picture sideways.
fn catalogue() -> Value {
    let families: Vec<(&str, viewray_camera::Projection)> = FAMILIES
        .iter()
        .filter_map(|&(name, projection)| {
            let text =
                format!("(eye: (0.0, 0.0, 5.0), view: (0.0, 0.0, -1.0), projection: {projection})");
            let camera = parse_camera(&text, Path::new("camera"), 4, 3).ok()?;
            Some((name, *camera.projection()))
        })
        .collect();
    Mistake::ALL
        .iter()
        .map(|&mistake| {
            let entry = mistake.entry();
            let fits: Vec<&str> = families
                .iter()
                .filter(|(_, projection)| mistake.fits(projection))
                .map(|&(name, _)| name)
                .collect();
            json!({
                "id": entry.id,
                "summary": entry.summary,
                "looks": entry.looks,
                "mistaken": entry.mistaken,
                "fix": entry.fix,
                "picture": entry.picture,
                "families": fits,
                "sideways": SIDEWAYS.contains(&mistake),
            })
        })
        .collect()
}

/// `text` safe inside HTML text and attribute values.
fn escape_html(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
        .replace('"', "&quot;")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_catalogue_offers_each_mistake_in_the_families_it_fits() {
        let catalogue = catalogue();
        let entries = catalogue.as_array().unwrap();
        assert_eq!(entries.len(), Mistake::ALL.len());
        let families = |id: &str| -> Vec<String> {
            let entry = entries.iter().find(|e| e["id"] == id).unwrap();
            let list = entry["families"].as_array().unwrap();
            list.iter()
                .map(|f| f.as_str().unwrap().to_owned())
                .collect()
        };
        // Every family's camera was made.
        assert_eq!(
            families("u-sign"),
            ["Perspective", "ThinLens", "Orthographic", "Oblique"]
        );
        assert_eq!(families("distance-sign"), ["Perspective"]);
        assert_eq!(families("ortho-origin-fixed"), ["Orthographic"]);
        assert_eq!(families("oblique-sign"), ["Oblique"]);
        let sideways =
            |id: &str| entries.iter().find(|e| e["id"] == id).unwrap()["sideways"] == true;
        assert!(sideways("u-sign") && sideways("i-j-swapped"));
        assert!(!sideways("v-sign") && !sideways("pixel-corner"));
    }
}

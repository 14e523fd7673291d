//! The endpoints: a request path and query in, a status, content type and body out.
//! Nothing here touches the network or the file system; the served scene is in memory.

use std::path::Path;
use std::sync::atomic::AtomicBool;
use std::time::Instant;

use serde_json::json;
use viewray_camera::{Camera, CameraSample, ImageLimits};
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
use viewray_json::{
    PixelIndices, camera_frame_line, project_line, ray_line, trace_lines, trace_text,
};
use viewray_output::Compression;
use viewray_render::{RenderError, RenderSettings, View, render_view_cancellable, trace_pixel};
use viewray_scene::parse_camera;

use crate::depth::{depth_json, scene_depth};
use crate::params::{self, BadRequest, Query};
use crate::slide::{SlideRequest, picture_size};
use crate::{Limits, ServedScene};

/// What to send back.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Reply {
    /// The HTTP status.
    pub(crate) status: u16,
    /// The `Content-Type`.
    pub(crate) content_type: &'static str,
    /// The body.
    pub(crate) body: Vec<u8>,
    /// A `Server-Timing` header's value, for renders.
    pub(crate) timing: Option<String>,
}

impl Reply {
    pub(crate) fn ok(content_type: &'static str, body: impl Into<Vec<u8>>) -> Reply {
        Reply {
            status: 200,
            content_type,
            body: body.into(),
            timing: None,
        }
    }

    /// An error as `{"error": message}` with `status`.
    pub(crate) fn error(status: u16, message: &str) -> Reply {
        let mut body = json!({ "error": message }).to_string();
        body.push('\n');
        Reply {
            status,
            content_type: JSON,
            body: body.into_bytes(),
            timing: None,
        }
    }
}

impl From<BadRequest> for Reply {
    fn from(bad: BadRequest) -> Reply {
        Reply::error(400, &bad.0)
    }
}

const JSON: &str = "application/json";
const JSON_LINES: &str = "application/x-ndjson";

/// A request after its parameters were checked: answered at once, or a render that
/// waits for a free render slot.
pub(crate) enum Route {
    /// The reply, computed.
    Now(Reply),
    /// A render, its parameters valid and within the limits (boxed: a camera with a lens
    /// is a few hundred bytes).
    Render(Box<RenderRequest>),
    /// A slide: a render with the views and numbers around it.
    Slide(Box<SlideRequest>),
}

/// A render to make: the view, and the ticket of the stream of renders it belongs to
/// (a newer render with the same ticket supersedes it).
pub(crate) struct RenderRequest {
    /// What to render.
    pub(crate) view: View,
    /// The ticket it came with, if any.
    pub(crate) ticket: Option<params::Ticket>,
}

/// The parameters of each endpoint.
const RENDER: [&str; 7] = [
    "camera", "width", "height", "samples", "shading", "mistakes", "ticket",
];
const FRAME: [&str; 4] = ["camera", "width", "height", "mistakes"];
const RAYS: [&str; 8] = [
    "camera", "width", "height", "row", "col", "i", "j", "mistakes",
];
const PROJECT: [&str; 4] = ["camera", "width", "height", "point"];
const DIAGRAM: [&str; 8] = [
    "camera", "width", "height", "row", "col", "view", "canvas", "mistakes",
];
const DEPTH: [&str; 3] = ["camera", "width", "height"];
const TRACE: [&str; 9] = [
    "camera", "width", "height", "shading", "row", "col", "i", "j", "format",
];
const SLIDE: [&str; 9] = [
    "camera", "width", "height", "samples", "shading", "row", "col", "top", "mistakes",
];

/// Routes a `GET` of `path` with `query` (the text after `?`, possibly empty).
pub(crate) fn route(served: &ServedScene, limits: &Limits, path: &str, query: &str) -> Route {
    let result = match path {
        "/" => Ok(Route::Now(Reply::ok(
            "text/html; charset=utf-8",
            served.page.as_bytes(),
        ))),
        "/lecture" => Ok(Route::Now(Reply::ok(
            "text/html; charset=utf-8",
            served.lecture.as_bytes(),
        ))),
        "/api/scene" => Ok(Route::Now(Reply::ok(
            "text/plain; charset=utf-8",
            served.text.as_bytes(),
        ))),
        "/api/render" => render_of(served, limits, query).map(|r| Route::Render(Box::new(r))),
        "/api/frame" => frame(served, limits, query).map(Route::Now),
        "/api/rays" => rays(served, limits, query).map(Route::Now),
        "/api/project" => project(served, limits, query).map(Route::Now),
        "/api/diagram.svg" => diagram(served, limits, query).map(Route::Now),
        "/api/depth" => depth(served, limits, query).map(Route::Now),
        "/api/trace" => trace(served, limits, query).map(Route::Now),
        "/api/slide.png" => slide_of(served, limits, query).map(|r| Route::Slide(Box::new(r))),
        _ => {
            return Route::Now(Reply::error(
                404,
                &format!(
                    "no such page: {path} (the playground serves /, /api/render, /api/frame, \
                     /api/rays, /api/project, /api/diagram.svg, /api/depth, /api/slide.png, \
                     /api/trace, /api/scene and /api/status)"
                ),
            ));
        }
    };
    result.unwrap_or_else(|bad| Route::Now(bad.into()))
}

/// The camera of `query` (the served scene's when it has none) for a `width x height`
/// image.
fn camera(
    served: &ServedScene,
    limits: &Limits,
    query: &Query,
    (width, height): (u32, u32),
) -> Result<Camera, BadRequest> {
    let text = query.get("camera").unwrap_or(&served.camera_text);
    if text.len() > limits.max_camera_bytes {
        return Err(BadRequest(format!(
            "camera: {} bytes is too long for a camera (at most {})",
            text.len(),
            limits.max_camera_bytes
        )));
    }
    let camera = parse_camera(text, Path::new("camera"), width, height)
        .map_err(|error| BadRequest(error.to_string()))?;
    let mistakes = params::mistakes(query)?;
    if mistakes.is_empty() {
        return Ok(camera);
    }
    camera
        .with_mistakes(mistakes)
        .map_err(|error| BadRequest(format!("mistakes: {error}")))
}

/// The served scene's image size.
fn scene_size(served: &ServedScene) -> (u32, u32) {
    let camera = served.scene.camera();
    (camera.width(), camera.height())
}

/// The size of a request that renders nothing (rays, frames, projections, diagrams): as
/// large as a scene file may say.
fn geometry_size(served: &ServedScene, query: &Query) -> Result<(u32, u32), BadRequest> {
    params::size(query, scene_size(served), ImageLimits::VIEWRAY)
}

/// `/api/render`: checks everything a render needs, before anything is allocated.
fn render_of(
    served: &ServedScene,
    limits: &Limits,
    query: &str,
) -> Result<RenderRequest, BadRequest> {
    let query = Query::parse(query, &RENDER, &[])?;
    let ticket = params::ticket(&query)?;
    let size = params::size(&query, scene_size(served), limits.image())?;
    let samples = params::samples(&query, served.scene.samples(), size, limits)?;
    let shading = params::shading(&query, served.scene.shading())?;
    let camera = camera(served, limits, &query, size)?;
    Ok(RenderRequest {
        view: View {
            camera,
            samples,
            shading,
        },
        ticket,
    })
}

/// The status of a render given up because a newer one with its ticket came.
pub(crate) const SUPERSEDED: u16 = 409;

/// The answer to a render superseded by a newer one with the same ticket.
pub(crate) fn superseded() -> Reply {
    Reply::error(
        SUPERSEDED,
        "ticket: superseded by a newer render with the same ticket",
    )
}

/// Renders the served scene through `view` and encodes it as a PNG: the bytes `viewray
/// render` writes for the same scene, camera, size, samples and shading; given up (409)
/// as soon as `cancelled` is set.
pub(crate) fn render(served: &ServedScene, view: &View, cancelled: &AtomicBool) -> Reply {
    let started = Instant::now();
    let settings = RenderSettings::default();
    let rendered =
        match render_view_cancellable(&served.scene, view, &settings, |_, _| {}, cancelled) {
            Ok(rendered) => rendered,
            Err(RenderError::Cancelled) => return superseded(),
            Err(error) => return Reply::error(500, &error.to_string()),
        };
    let rendered_at = Instant::now();
    let mut png = Vec::new();
    // The same pixels as `viewray render` writes, encoded for speed rather than size.
    if let Err(error) = rendered
        .image
        .write_png_compressed(&mut png, Compression::Fast)
    {
        return Reply::error(500, &format!("cannot encode the image: {error}"));
    }
    let ms = |from: Instant, to: Instant| (to - from).as_secs_f64() * 1e3;
    Reply {
        timing: Some(format!(
            "render;dur={:.1}, png;dur={:.1}",
            ms(started, rendered_at),
            ms(rendered_at, Instant::now())
        )),
        ..Reply::ok("image/png", png)
    }
}

/// `/api/frame`: the line of `viewray frame SCENE` (with the plane of focus and hinge
/// line of a camera with a lens).
fn frame(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &FRAME, &[])?;
    let size = geometry_size(served, &query)?;
    let camera = camera(served, limits, &query, size)?;
    Ok(json_lines(&[camera_frame_line(&camera)]))
}

/// `/api/rays`: the line of `viewray rays --pixel R,C` (or `--one-based --pixel I,J`).
fn rays(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &RAYS, &[])?;
    let (width, height) = geometry_size(served, &query)?;
    let camera = camera(served, limits, &query, (width, height))?;
    let (pixel, indices) = pixel_of(&query, (width, height))?;
    Ok(json_lines(&[ray_line(
        &camera,
        pixel,
        CameraSample::CENTER,
        indices,
    )]))
}

/// The pixel of `query` (`row&col`, or the lecture's `i&j`) in a `width x height` image,
/// 0-based, and the indices it was given in.
fn pixel_of(
    query: &Query,
    (width, height): (u32, u32),
) -> Result<((u32, u32), PixelIndices), BadRequest> {
    let (first, second, one_based) = params::pixel(query)?;
    let indices = PixelIndices::one_based_if(one_based);
    let pixel = indices
        .pixel((first, second), width, height)
        .map_err(|outside| {
            let name = if one_based { "i" } else { "row" };
            BadRequest(format!("{name}: {}", outside.sentence(Some("i=I&j=J"))))
        })?;
    Ok((pixel, indices))
}

/// `/api/trace`: the pixel's trace in the image of a one-sample render of the served
/// scene through the camera: the lines of `viewray trace --json` (or `--one-based`), or
/// with `format=text` its text.
fn trace(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &TRACE, &[])?;
    // Depth shading finds the image's range of depths first, a ray per pixel: a trace
    // is held to the size of a render.
    let size = params::size(&query, scene_size(served), limits.image())?;
    let shading = params::shading(&query, served.scene.shading())?;
    let text = match query.get("format") {
        None | Some("json") => false,
        Some("text") => true,
        Some(other) => {
            return Err(BadRequest(format!(
                "format: expected `json` (one line per step) or `text`, found `{other}`"
            )));
        }
    };
    let camera = camera(served, limits, &query, size)?;
    let ((row, col), indices) = pixel_of(&query, size)?;
    let view = View {
        camera,
        samples: 1,
        shading,
    };
    let trace = trace_pixel(&served.scene, &view, &RenderSettings::default(), row, col)
        .map_err(|outside| BadRequest(format!("row: {outside}")))?;
    if text {
        let text = trace_text(&camera, shading, &trace, "a one-sample render");
        return Ok(Reply::ok("text/plain; charset=utf-8", text));
    }
    Ok(json_lines(&trace_lines(&camera, &trace, indices)))
}

/// `/api/project`: the lines of `viewray project --point X,Y,Z...`.
fn project(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &PROJECT, &["point"])?;
    let size = geometry_size(served, &query)?;
    let camera = camera(served, limits, &query, size)?;
    let points = query.all("point");
    if points.is_empty() {
        return Err(BadRequest::new(
            "point: missing: give a world point as point=X,Y,Z (repeat it for several)",
        ));
    }
    if points.len() > limits.max_points {
        return Err(BadRequest(format!(
            "point: {} points is too many for one request (at most {})",
            points.len(),
            limits.max_points
        )));
    }
    let lines = points
        .into_iter()
        .map(|text| {
            Ok(project_line(
                &camera,
                params::point(text)?,
                PixelIndices::ZeroBased,
            ))
        })
        .collect::<Result<Vec<_>, BadRequest>>()?;
    Ok(json_lines(&lines))
}

/// The chosen pixel of a diagram or a slide: `row` and `col` (0-based) if given.
fn optional_pixel(
    query: &Query,
    (width, height): (u32, u32),
) -> Result<Option<(u32, u32)>, BadRequest> {
    match (query.get("row"), query.get("col")) {
        (None, None) => Ok(None),
        _ => {
            let (row, col, _) = params::pixel(query)?;
            Ok(Some(
                PixelIndices::ZeroBased
                    .pixel((row, col), width, height)
                    // These endpoints take row and col only: no other indices to offer.
                    .map_err(|outside| BadRequest(format!("row: {outside}")))?,
            ))
        }
    }
}

/// `/api/diagram.svg`: the side view of the camera over the served scene, or with
/// `view=top` its top view, on a 1000 x 600 panel (800 x 800 for the top view) or one of
/// the size `canvas=WxH` says.
fn diagram(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &DIAGRAM, &[])?;
    let (width, height) = geometry_size(served, &query)?;
    let camera = camera(served, limits, &query, (width, height))?;
    let pixel = optional_pixel(&query, (width, height))?;
    let sized = params::canvas(&query)?;
    let (window, canvas) = match query.get("view") {
        None | Some("side") => (
            SideWindow::fit(&served.scene, &[camera]),
            sized.unwrap_or(SideViewCanvas::Panel),
        ),
        Some("top") => (
            SideWindow::fit_top(&served.scene, &[camera]),
            sized.unwrap_or(SideViewCanvas::Square),
        ),
        Some(other) => {
            return Err(BadRequest(format!(
                "view: expected `side` or `top`, found `{other}`"
            )));
        }
    };
    let figure = side_view(&served.scene, &camera, &window, canvas, pixel);
    let svg = viewray_draw::svg::document(&figure, viewray_draw::svg::SvgText::Paths);
    Ok(Reply::ok("image/svg+xml", svg))
}

/// `/api/depth`: how far the scene lies along the camera's view at the picture's middle
/// ([`scene_depth`]).
fn depth(served: &ServedScene, limits: &Limits, query: &str) -> Result<Reply, BadRequest> {
    let query = Query::parse(query, &DEPTH, &[])?;
    let size = geometry_size(served, &query)?;
    let camera = camera(served, limits, &query, size)?;
    Ok(json_lines(&[depth_json(scene_depth(
        &served.scene,
        &camera,
    ))]))
}

/// `/api/slide.png`: checks a slide's parameters (the camera at `width x height`, as
/// `/api/frame` does, samples and shading as a render's, the pixel and `top`); the render
/// is made at the slide's picture size, with the samples asked for or as many as the
/// frame limit allows there.
fn slide_of(
    served: &ServedScene,
    limits: &Limits,
    query: &str,
) -> Result<SlideRequest, BadRequest> {
    let query = Query::parse(query, &SLIDE, &[])?;
    let size = geometry_size(served, &query)?;
    let samples = params::samples_per_pixel(&query, served.scene.samples(), limits)?;
    let shading = params::shading(&query, served.scene.shading())?;
    let camera = camera(served, limits, &query, size)?;
    let pixel = optional_pixel(&query, size)?;
    let top = match query.get("top") {
        None | Some("0") => false,
        Some("1") => true,
        Some(other) => {
            return Err(BadRequest(format!("top: expected 0 or 1, found `{other}`")));
        }
    };
    let (width, height) = picture_size(size);
    let pixels = u64::from(width) * u64::from(height);
    let most = u32::try_from(limits.max_frame_samples / pixels.max(1)).unwrap_or(u32::MAX);
    let picture = self::camera(served, limits, &query, (width, height))?;
    Ok(SlideRequest {
        view: View {
            camera: picture,
            samples: samples.min(most.max(1)),
            shading,
        },
        camera,
        pixel,
        top,
    })
}

/// `lines` as JSON lines, each ended by a newline, as the command line prints them.
fn json_lines(lines: &[serde_json::Value]) -> Reply {
    let mut body = Vec::new();
    for line in lines {
        // Writing to a Vec cannot fail.
        let _ = viewray_json::write_line(&mut body, line);
    }
    let content_type = if lines.len() == 1 { JSON } else { JSON_LINES };
    Reply::ok(content_type, body)
}

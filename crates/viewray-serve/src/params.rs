//! A request's query parameters: decoded, checked against the endpoint's list, and
//! turned into values with the command line's words for what is wrong (the image limits'
//! sentences are viewray-camera's, as the command line's are).
//!
//! Every error message starts with the parameter's name (`width: ...`, and for the
//! camera the position in its text, `camera:1:9: ...`), so the page can show it next
//! to the control that caused it.

use glam::DVec3;
use viewray_camera::{ImageLimitError, ImageLimits, Mistake, Mistakes};
use viewray_diagram::SideViewCanvas;
use viewray_scene::Shading;

use crate::Limits;

/// A request refused for its parameters: HTTP 400 with this sentence.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct BadRequest(pub(crate) String);

impl BadRequest {
    pub(crate) fn new(message: impl Into<String>) -> BadRequest {
        BadRequest(message.into())
    }
}

/// The decoded `name=value` pairs of a query string.
#[derive(Clone, Debug, Default)]
pub(crate) struct Query {
    pairs: Vec<(String, String)>,
}

impl Query {
    /// The pairs of `query` (the part after `?`, percent- and `+`-decoded), checked:
    /// each name is one of `allowed` and appears once, or is in `repeatable`.
    pub(crate) fn parse(
        query: &str,
        allowed: &[&str],
        repeatable: &[&str],
    ) -> Result<Query, BadRequest> {
        let pairs: Vec<(String, String)> = form_urlencoded::parse(query.as_bytes())
            .map(|(name, value)| (name.into_owned(), value.into_owned()))
            .collect();
        for (k, (name, _)) in pairs.iter().enumerate() {
            if !allowed.contains(&name.as_str()) {
                return Err(BadRequest(format!(
                    "unknown parameter `{name}`: this endpoint takes {}",
                    list(allowed)
                )));
            }
            if !repeatable.contains(&name.as_str()) && pairs[..k].iter().any(|(n, _)| n == name) {
                return Err(BadRequest(format!("{name}: given twice")));
            }
        }
        Ok(Query { pairs })
    }

    /// The value of `name`, if given.
    pub(crate) fn get(&self, name: &str) -> Option<&str> {
        self.pairs
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, value)| value.as_str())
    }

    /// Every value of `name`, in order.
    pub(crate) fn all(&self, name: &str) -> Vec<&str> {
        self.pairs
            .iter()
            .filter(|(n, _)| n == name)
            .map(|(_, value)| value.as_str())
            .collect()
    }
}

/// `a`, `b` or `c`.
fn list(names: &[&str]) -> String {
    let quoted: Vec<String> = names.iter().map(|n| format!("`{n}`")).collect();
    match quoted.as_slice() {
        [] => "no parameters".to_owned(),
        [one] => one.clone(),
        [init @ .., last] => format!("{} or {last}", init.join(", ")),
    }
}

/// A whole number parameter, `name`, from `text`.
fn whole(name: &str, text: &str, what: &str) -> Result<u64, BadRequest> {
    text.trim()
        .parse::<u64>()
        .map_err(|_| BadRequest(format!("{name}: expected {what}, found `{text}`")))
}

/// The image size from `width` and `height` (each defaulting to `default`'s), within
/// `limits`, the parameter that is out of range named first.
pub(crate) fn size(
    query: &Query,
    default: (u32, u32),
    limits: ImageLimits,
) -> Result<(u32, u32), BadRequest> {
    let side = |name: &str, default: u32| match query.get(name) {
        None => Ok(u64::from(default)),
        Some(text) => whole(name, text, "a whole number of pixels"),
    };
    let (width, height) = (side("width", default.0)?, side("height", default.1)?);
    limits.check_size(width, height).map_err(|error| {
        // The parameter to blame: the one that is out of range (width when both are).
        let blame_width = match error {
            ImageLimitError::Empty { width, .. } => width == 0,
            ImageLimitError::SideTooLarge {
                width, max_side, ..
            } => width > u64::from(max_side),
            _ => width >= height,
        };
        let name = if blame_width { "width" } else { "height" };
        BadRequest(format!("{name}: {error}"))
    })
}

/// Samples per pixel from `samples` (default `default`), 1 to the limit.
pub(crate) fn samples_per_pixel(
    query: &Query,
    default: u32,
    limits: &Limits,
) -> Result<u32, BadRequest> {
    // The served scene's own samples are held to the request's limit as if asked for.
    let text = query
        .get("samples")
        .map_or_else(|| default.to_string(), str::to_owned);
    limits
        .image()
        .parse_samples(&text)
        .map_err(|error| BadRequest(format!("samples: {error}")))
}

/// Samples per pixel from `samples` (default `default`), 1 to the limit, and at most
/// `limits.max_frame_samples` for the whole `width x height` frame.
pub(crate) fn samples(
    query: &Query,
    default: u32,
    (width, height): (u32, u32),
    limits: &Limits,
) -> Result<u32, BadRequest> {
    let samples = samples_per_pixel(query, default, limits)?;
    let total = u64::from(width) * u64::from(height) * u64::from(samples);
    if total > limits.max_frame_samples {
        return Err(BadRequest(format!(
            "samples: {width} x {height} at {samples} samples per pixel is too much for one \
             frame: at most {} samples in all (pixels x samples)",
            limits.max_frame_samples
        )));
    }
    Ok(samples)
}

/// The smallest and largest side of a diagram's canvas, `canvas=WxH`, in pixels.
const CANVAS_SIDES: (u32, u32) = (300, 4000);

/// The canvas a diagram is drawn on when `canvas=WxH` is given: a panel of that size.
pub(crate) fn canvas(query: &Query) -> Result<Option<SideViewCanvas>, BadRequest> {
    let Some(text) = query.get("canvas") else {
        return Ok(None);
    };
    let (low, high) = CANVAS_SIDES;
    let wrong = || {
        BadRequest(format!(
            "canvas: expected WIDTHxHEIGHT in pixels, each from {low} to {high}, found `{text}`"
        ))
    };
    let (width, height) = text.split_once('x').ok_or_else(wrong)?;
    let side = |t: &str| {
        t.trim()
            .parse::<u32>()
            .ok()
            .filter(|side| (low..=high).contains(side))
            .ok_or_else(wrong)
    };
    Ok(Some(SideViewCanvas::Fitted {
        width: side(width)?,
        height: side(height)?,
    }))
}

/// The shading named by `shading`, or `default`.
pub(crate) fn shading(query: &Query, default: Shading) -> Result<Shading, BadRequest> {
    match query.get("shading") {
        None => Ok(default),
        Some(text) => text
            .parse::<Shading>()
            .map_err(|message| BadRequest(format!("shading: {message}"))),
    }
}

/// The catalogue's mistakes a request's camera makes: `mistakes=u-sign,v-sign` (the
/// catalogue's ids, comma-separated; none when absent or empty).
pub(crate) fn mistakes(query: &Query) -> Result<Mistakes, BadRequest> {
    let Some(text) = query.get("mistakes") else {
        return Ok(Mistakes::NONE);
    };
    let mut mistakes = Mistakes::NONE;
    for id in text.split(',').map(str::trim).filter(|id| !id.is_empty()) {
        let mistake = Mistake::from_id(id).ok_or_else(|| {
            let known: Vec<&str> = Mistake::ALL.iter().map(|m| m.id()).collect();
            BadRequest(format!(
                "mistakes: no mistake `{id}` in the catalogue (it has {})",
                known.join(", ")
            ))
        })?;
        mistakes = mistakes.with(mistake);
    }
    Ok(mistakes)
}

/// The longest name of a ticket.
const MAX_TICKET: usize = 64;

/// A render's ticket, `ticket=NAME.TURN`: the page's name for the stream of renders one
/// of its views asks for, and the render's turn in it (a render supersedes those of its
/// stream with an earlier turn).
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Ticket {
    /// The stream's name: 1 to 64 letters, digits, `-` or `_`.
    pub(crate) name: String,
    /// The render's turn in it.
    pub(crate) turn: u64,
}

/// The ticket of a render, if it has one.
pub(crate) fn ticket(query: &Query) -> Result<Option<Ticket>, BadRequest> {
    let Some(text) = query.get("ticket") else {
        return Ok(None);
    };
    let wrong = || {
        BadRequest(format!(
            "ticket: expected NAME.TURN, a name of 1 to {MAX_TICKET} letters, digits, `-` or \
             `_` and a whole number, found `{text}`"
        ))
    };
    let (name, turn) = text.rsplit_once('.').ok_or_else(wrong)?;
    let fine = |c: char| c.is_ascii_alphanumeric() || c == '-' || c == '_';
    if name.is_empty() || name.len() > MAX_TICKET || !name.chars().all(fine) {
        return Err(wrong());
    }
    let turn = turn.parse::<u64>().map_err(|_| wrong())?;
    Ok(Some(Ticket {
        name: name.to_owned(),
        turn,
    }))
}

/// The pixel of a rays request: `row` and `col` (0-based), or `i` and `j` (1-based, the
/// lecture's); `(first, second, one_based)`.
pub(crate) fn pixel(query: &Query) -> Result<(i64, i64, bool), BadRequest> {
    let index = |name: &str| -> Result<Option<i64>, BadRequest> {
        query
            .get(name)
            .map(|text| {
                text.trim().parse::<i64>().map_err(|_| {
                    BadRequest(format!("{name}: expected a whole number, found `{text}`"))
                })
            })
            .transpose()
    };
    match (index("row")?, index("col")?, index("i")?, index("j")?) {
        (Some(row), Some(col), None, None) => Ok((row, col, false)),
        (None, None, Some(i), Some(j)) => Ok((i, j, true)),
        (None, None, None, None) => Err(BadRequest::new(
            "row: missing: give the pixel as row=R&col=C (0-based from the top-left) or \
             i=I&j=J (the lecture's, 1-based)",
        )),
        (Some(_), None, _, _) | (None, None, Some(_), None) => Err(BadRequest::new(
            "col: missing: give the pixel as row=R&col=C or i=I&j=J",
        )),
        (None, Some(_), _, _) | (None, None, None, Some(_)) => Err(BadRequest::new(
            "row: missing: give the pixel as row=R&col=C or i=I&j=J",
        )),
        _ => Err(BadRequest::new(
            "row: give the pixel as row=R&col=C or as i=I&j=J, not both",
        )),
    }
}

/// A world point `X,Y,Z`, in the command line's words.
pub(crate) fn point(text: &str) -> Result<DVec3, BadRequest> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let wrong = || BadRequest::new("point: expected 3 numbers separated by commas, like 0,1.5,-2");
    if parts.len() != 3 {
        return Err(wrong());
    }
    let mut numbers = [0.0; 3];
    for (number, part) in numbers.iter_mut().zip(parts) {
        *number = part.parse::<f64>().map_err(|_| wrong())?;
        if !number.is_finite() {
            return Err(BadRequest(format!(
                "point: `{part}` is not a finite number"
            )));
        }
    }
    Ok(DVec3::from(numbers))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn query(text: &str) -> Query {
        Query::parse(
            text,
            &[
                "camera", "width", "height", "samples", "shading", "row", "col", "i", "j", "point",
            ],
            &["point"],
        )
        .unwrap()
    }

    #[test]
    fn values_are_decoded_and_names_checked() {
        let q = query("camera=Top(target%3A+(0.0%2C0.0%2C0.0))&point=1,2,3&point=-4,5,6");
        assert_eq!(q.get("camera"), Some("Top(target: (0.0,0.0,0.0))"));
        assert_eq!(q.all("point"), ["1,2,3", "-4,5,6"]);
        let allowed = ["camera", "width"];
        assert_eq!(
            Query::parse("wdth=3", &allowed, &[]).unwrap_err().0,
            "unknown parameter `wdth`: this endpoint takes `camera` or `width`"
        );
        assert_eq!(
            Query::parse("width=3&width=4", &allowed, &[])
                .unwrap_err()
                .0,
            "width: given twice"
        );
    }

    #[test]
    fn sizes_are_checked_before_anything_is_allocated() {
        let limits = Limits::default();
        let check = |text: &str| size(&query(text), (640, 360), limits.image());
        assert_eq!(check(""), Ok((640, 360)));
        assert_eq!(check("width=320&height=180"), Ok((320, 180)));
        assert_eq!(
            check("width=100000&height=100000").unwrap_err().0,
            "width: 100000 x 100000 is too large: each side can be at most 4096 pixels"
        );
        assert_eq!(
            check("height=0").unwrap_err().0,
            "height: the image must be at least 1 x 1 pixels, found 640 x 0"
        );
        assert_eq!(
            check("width=4096&height=4096").unwrap_err().0,
            "width: 4096 x 4096 is too large: at most 4194304 pixels"
        );
        assert_eq!(
            check("width=-3").unwrap_err().0,
            "width: expected a whole number of pixels, found `-3`"
        );
        assert_eq!(
            check("height=99999999999999999999999").unwrap_err().0,
            "height: expected a whole number of pixels, found `99999999999999999999999`"
        );
    }

    #[test]
    fn samples_are_bounded_per_pixel_and_per_frame() {
        let limits = Limits::default();
        let check = |text: &str, size| samples(&query(text), 4, size, &limits);
        assert_eq!(check("", (640, 360)), Ok(4));
        assert_eq!(check("samples=16", (640, 360)), Ok(16));
        assert_eq!(
            check("samples=0", (640, 360)).unwrap_err().0,
            "samples: expected a whole number of samples from 1 to 1024"
        );
        assert_eq!(
            check("samples=1024", (2048, 2048)).unwrap_err().0,
            "samples: 2048 x 2048 at 1024 samples per pixel is too much for one frame: at \
             most 67108864 samples in all (pixels x samples)"
        );
    }

    #[test]
    fn a_diagrams_canvas_is_a_bounded_size() {
        let canvas_of = |text: &str| {
            let query = Query::parse(text, &["canvas"], &[]).unwrap();
            canvas(&query)
        };
        assert_eq!(canvas_of(""), Ok(None));
        assert_eq!(
            canvas_of("canvas=1700x600"),
            Ok(Some(SideViewCanvas::Fitted {
                width: 1700,
                height: 600
            }))
        );
        for bad in [
            "canvas=1700",
            "canvas=299x600",
            "canvas=600x4001",
            "canvas=axb",
        ] {
            assert!(
                canvas_of(bad)
                    .unwrap_err()
                    .0
                    .starts_with("canvas: expected WIDTHxHEIGHT in pixels, each from 300 to 4000"),
                "{bad}"
            );
        }
    }

    #[test]
    fn shadings_pixels_and_points_use_the_command_lines_words() {
        assert_eq!(
            shading(&query("shading=Depth"), Shading::Lit),
            Ok(Shading::Depth)
        );
        assert_eq!(
            shading(&query("shading=depth"), Shading::Lit)
                .unwrap_err()
                .0,
            "shading: unknown shading `depth`, expected one of `Flat`, `Normals`, `Depth` or `Lit`"
        );
        assert_eq!(pixel(&query("row=3&col=4")), Ok((3, 4, false)));
        assert_eq!(pixel(&query("i=3&j=4")), Ok((3, 4, true)));
        assert!(
            pixel(&query("row=3"))
                .unwrap_err()
                .0
                .starts_with("col: missing")
        );
        assert!(pixel(&query("")).unwrap_err().0.starts_with("row: missing"));
        assert!(pixel(&query("row=1&col=2&i=1&j=1")).is_err());
        assert_eq!(
            pixel(&query("row=x&col=1")).unwrap_err().0,
            "row: expected a whole number, found `x`"
        );
        assert_eq!(point("1, -2.5,3"), Ok(DVec3::new(1.0, -2.5, 3.0)));
        assert_eq!(
            point("1,2").unwrap_err().0,
            "point: expected 3 numbers separated by commas, like 0,1.5,-2"
        );
        assert_eq!(
            point("1,2,inf").unwrap_err().0,
            "point: `inf` is not a finite number"
        );
    }
}

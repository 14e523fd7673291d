//! The figures' visual language: named colours, line weights, sizes and canvases.
//!
//! Every lecture figure takes its colours and weights from here, so the camera basis
//! looks the same on every slide: **u** is always vermillion, **v** bluish green,
//! **w** blue, viewing rays orange, the image plane sky blue.
//!
//! The colours are the Okabe–Ito palette (Okabe & Ito, "Color Universal Design", 2008),
//! which stays distinguishable under the common colour-vision deficiencies; the u/v/w
//! axes keep the usual red/green/blue order of x/y/z while remaining tellable apart by
//! a red–green colour-blind student (vermillion and bluish green differ in lightness).
//!
//! Sizes are in pixels of the [`SLIDE`] canvas (1600 x 900), which a projector shows at
//! roughly the size of a slide's body text; the [`SQUARE`] canvas uses the same values.

use viewray_draw::Color;

/// The slide canvas, 16:9: `(width, height)` in pixels.
pub(crate) const SLIDE: (u32, u32) = (1600, 900);
/// The square canvas, for figures that sit beside text on a slide: `(width, height)`.
pub(crate) const SQUARE: (u32, u32) = (1080, 1080);

/// Figure background.
pub(crate) const BACKGROUND: Color = Color::WHITE;
/// Label text and other plain ink.
pub(crate) const TEXT: Color = Color::from_hex(0x1A1A1A);
/// The camera basis vector **u** (right): Okabe–Ito vermillion.
pub(crate) const U_AXIS: Color = Color::from_hex(0xD55E00);
/// The camera basis vector **v** (up): Okabe–Ito bluish green.
pub(crate) const V_AXIS: Color = Color::from_hex(0x009E73);
/// The camera basis vector **w** (back): Okabe–Ito blue.
pub(crate) const W_AXIS: Color = Color::from_hex(0x0072B2);
/// The eye **e** and other camera body marks.
pub(crate) const EYE: Color = Color::from_hex(0x000000);
/// Viewing rays: Okabe–Ito orange.
pub(crate) const RAY: Color = Color::from_hex(0xE69F00);
/// The image plane (viewport) outline; fill it with [`IMAGE_PLANE_FILL`].
pub(crate) const IMAGE_PLANE: Color = Color::from_hex(0x56B4E9);
/// The image plane's translucent fill.
pub(crate) const IMAGE_PLANE_FILL: Color = Color::rgba(0x56, 0xB4, 0xE9, 0x40);
/// Outlines of scene objects (spheres, boxes).
pub(crate) const OBJECT: Color = Color::from_hex(0x4D4D4D);
/// Fill of scene objects.
pub(crate) const OBJECT_FILL: Color = Color::from_hex(0xD9D9D9);
/// Something the figure points out (a chosen pixel, a hit point): reddish purple.
pub(crate) const HIGHLIGHT: Color = Color::from_hex(0xCC79A7);
/// Construction lines, dimension arrows, world axes and other annotations.
pub(crate) const ANNOTATION: Color = Color::from_hex(0x6B6B6B);
/// Light grid lines (pixel grids, world grids).
pub(crate) const GRID: Color = Color::from_hex(0xBFBFBF);

/// Thin lines: grids, construction lines.
pub(crate) const LINE_THIN: f32 = 2.0;
/// The ordinary weight: rays, outlines, dimension arrows.
pub(crate) const LINE_REGULAR: f32 = 3.5;
/// Emphasis: the camera basis vectors, the image plane.
pub(crate) const LINE_THICK: f32 = 5.0;
/// The dash pattern for hidden or construction lines: `[on, off]` in pixels.
pub(crate) const DASH: [f32; 2] = [14.0, 10.0];
/// Radius of a point mark such as the eye or a pixel centre.
pub(crate) const DOT_RADIUS: f32 = 7.0;

/// Font size (pixels per em) of ordinary labels such as **u**, *d* or *vw*.
pub(crate) const LABEL_SIZE: f32 = 40.0;
/// Font size of secondary labels: tick values, coordinates.
pub(crate) const SMALL_LABEL_SIZE: f32 = 30.0;
/// Font size of a figure's caption line, if it has one.
pub(crate) const CAPTION_SIZE: f32 = 34.0;
/// Font size of a slide's title (set bold, top left).
pub(crate) const TITLE_SIZE: f32 = 48.0;

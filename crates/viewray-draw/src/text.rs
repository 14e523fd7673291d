//! Text labels: the bundled DejaVu Sans faces, a small sub/superscript markup, and layout
//! with kerning, which places the glyphs that [`shape`](crate::shape) outlines.

use std::sync::OnceLock;

use ab_glyph::{Font, FontRef, GlyphId};
use glam::{Affine2, Mat2, Vec2};

use crate::color::Color;
use crate::rect::Rect;

/// The room left after a slanted run before an upright one, in ems.
const ITALIC_CORRECTION: f32 = 0.06;
/// Size of sub- and superscripts relative to the label's size.
const SCRIPT_SCALE: f32 = 0.7;
/// How far a subscript's baseline sits below the label's, in ems of the label's size.
const SUBSCRIPT_DROP: f32 = 0.2;
/// How far a superscript's baseline sits above the label's, in ems of the label's size.
const SUPERSCRIPT_RISE: f32 = 0.38;

/// One of the four bundled DejaVu Sans faces.
///
/// Mathematical writing sets vectors in bold (**e**, **u**, **v**, **w**) and scalars in
/// italics (*u*, *v*, *d*, *vw*, *vh*, *i*, *j*); [`Label::vector`] and [`Label::math`]
/// choose those faces.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, Default)]
pub enum FontFace {
    /// DejaVu Sans: ordinary words and numbers.
    #[default]
    Regular,
    /// DejaVu Sans Oblique: scalar symbols such as *d* and *vw*.
    Italic,
    /// DejaVu Sans Bold: vectors such as **u** and points such as **e**.
    Bold,
    /// DejaVu Sans Bold Oblique.
    BoldItalic,
}

/// The four faces, parsed once.
struct Faces {
    regular: FontRef<'static>,
    italic: FontRef<'static>,
    bold: FontRef<'static>,
    bold_italic: FontRef<'static>,
}

impl FontFace {
    /// The parsed font of this face.
    pub(crate) fn font(self) -> &'static FontRef<'static> {
        static FACES: OnceLock<Faces> = OnceLock::new();
        let faces = FACES.get_or_init(|| {
            let load = |bytes: &'static [u8]| {
                FontRef::try_from_slice(bytes).expect("the bundled DejaVu fonts are valid")
            };
            Faces {
                regular: load(dejavu::sans::regular()),
                italic: load(dejavu::sans::oblique()),
                bold: load(dejavu::sans::bold()),
                bold_italic: load(dejavu::sans::bold_oblique()),
            }
        });
        match self {
            FontFace::Regular => &faces.regular,
            FontFace::Italic => &faces.italic,
            FontFace::Bold => &faces.bold,
            FontFace::BoldItalic => &faces.bold_italic,
        }
    }

    /// The bold face of the same slant: the face of `*bold*` markup.
    fn emboldened(self) -> FontFace {
        match self {
            FontFace::Regular | FontFace::Bold => FontFace::Bold,
            FontFace::Italic | FontFace::BoldItalic => FontFace::BoldItalic,
        }
    }

    /// The slanted face of the same weight: the face of a letter in `$math$` markup.
    fn slanted(self) -> FontFace {
        match self {
            FontFace::Regular | FontFace::Italic => FontFace::Italic,
            FontFace::Bold | FontFace::BoldItalic => FontFace::BoldItalic,
        }
    }

    /// Whether the face is oblique.
    fn is_slanted(self) -> bool {
        matches!(self, FontFace::Italic | FontFace::BoldItalic)
    }
}

/// Which point of the text's width a label's `position` marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Anchor {
    /// The start (left end) of the text.
    Start,
    /// The middle of the text's advance width.
    #[default]
    Middle,
    /// The end (right end) of the text.
    End,
}

/// Which height of the text a label's `position` marks.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum Baseline {
    /// The baseline the letters sit on.
    Alphabetic,
    /// Halfway between the top of the text box and its bottom (see [`Label::bounds`]):
    /// the label is centred on its position.
    #[default]
    Middle,
    /// The top of the ascent: the label hangs below its position.
    Top,
    /// The bottom of the descent: the label stands above its position.
    Bottom,
}

/// The size of a line of text, in pixels: its text box.
///
/// The box `width` x (`ascent` + `descent`) uses the font's line metrics rather than the
/// ink of the particular letters, so "u" and "d" measure equally tall and labels line up;
/// [`Label::bounds`] adds any ink that overhangs the box (an italic letter's tail).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct TextExtent {
    /// The advance width, kerning included.
    pub width: f32,
    /// Height above the baseline, raised superscripts included.
    pub ascent: f32,
    /// Depth below the baseline (positive), lowered subscripts included.
    pub descent: f32,
}

/// A text label drawn at `position` in figure pixels.
///
/// `anchor` and `baseline` say which point of the text `position` is (by default its
/// centre); `rotation` turns the text about that point, radians counter-clockwise on
/// screen.
///
/// # Markup
/// A label's text is one line. `_` makes the next character a subscript and `^` a
/// superscript; braces take several: `v_h`, `x_{ij}`, `r^2`. A backslash takes the next
/// character literally: `file\_name`. Scripts are 70 % of the label's size, subscripts
/// lowered by 0.2 em and superscripts raised by 0.38 em.
///
/// Formulas mix faces as mathematical writing does: between dollar signs (`$u = (j - 1/2)/W$`)
/// letters are set in italics and `-` becomes the minus sign `−`, while digits and
/// punctuation stay upright; between asterisks (`*u*`) text is set in bold, so a ray
/// direction reads `$u *u* + v *v* - d *w*$`. Escape either sign with a backslash.
#[derive(Clone, Debug, PartialEq)]
pub struct Label {
    /// The text, one line, with markup.
    pub text: String,
    /// The anchor point in figure pixels.
    pub position: Vec2,
    /// Font size in pixels per em (as CSS and SVG `font-size`).
    pub size: f32,
    /// Text colour.
    pub color: Color,
    /// Which face.
    pub face: FontFace,
    /// Horizontal anchoring.
    pub anchor: Anchor,
    /// Vertical anchoring.
    pub baseline: Baseline,
    /// Rotation about `position`, radians counter-clockwise on screen.
    pub rotation: f32,
}

impl Label {
    /// The font size of a new label, pixels per em: body text on a 1600 pixel wide slide.
    pub const DEFAULT_SIZE: f32 = 40.0;

    /// A black label in the regular face, [`Label::DEFAULT_SIZE`], centred on `position`.
    pub fn new(text: impl Into<String>, position: Vec2) -> Label {
        Label {
            text: text.into(),
            position,
            size: Label::DEFAULT_SIZE,
            color: Color::BLACK,
            face: FontFace::Regular,
            anchor: Anchor::default(),
            baseline: Baseline::default(),
            rotation: 0.0,
        }
    }

    /// A scalar symbol in italics, as mathematics writes *d*, *vw* or *v_h*.
    pub fn math(text: impl Into<String>, position: Vec2) -> Label {
        Label::new(text, position).with_face(FontFace::Italic)
    }

    /// A vector symbol in bold, as mathematics writes **e**, **u**, **v**, **w**.
    pub fn vector(text: impl Into<String>, position: Vec2) -> Label {
        Label::new(text, position).with_face(FontFace::Bold)
    }

    /// The same label at `size` pixels per em.
    pub fn with_size(self, size: f32) -> Label {
        Label { size, ..self }
    }

    /// The same label in `color`.
    pub fn with_color(self, color: Color) -> Label {
        Label { color, ..self }
    }

    /// The same label in `face`.
    pub fn with_face(self, face: FontFace) -> Label {
        Label { face, ..self }
    }

    /// The same label anchored at `anchor` and `baseline`.
    pub fn with_anchor(self, anchor: Anchor, baseline: Baseline) -> Label {
        Label {
            anchor,
            baseline,
            ..self
        }
    }

    /// The same label turned by `rotation` radians, counter-clockwise on screen.
    pub fn with_rotation(self, rotation: f32) -> Label {
        Label { rotation, ..self }
    }

    /// The axis-aligned box in figure pixels that holds the label's text box and all of
    /// its ink, rotation included: what to test against the canvas or other labels.
    ///
    /// The text box is the advance width (kerning included) by the font's ascent and
    /// descent (raised and lowered scripts included), not the ink of the particular
    /// letters, so "u" and "d" are equally tall and labels line up; ink that overhangs it
    /// (an italic letter's tail) is added.
    pub fn bounds(&self) -> Rect {
        let layout = self.layout();
        let e = layout.extent;
        let mut local =
            Rect::from_corners(Vec2::new(0.0, -e.ascent), Vec2::new(e.width, e.descent));
        if let Some(ink) = layout.ink {
            local = local.union(&ink);
        }
        let to_figure = self.local_to_figure(&e);
        let corners = [
            local.min,
            Vec2::new(local.max.x, local.min.y),
            local.max,
            Vec2::new(local.min.x, local.max.y),
        ]
        .map(|p| to_figure.transform_point2(p));
        let first = Rect::from_corners(corners[0], corners[0]);
        corners
            .iter()
            .fold(first, |r, &p| r.union(&Rect::from_corners(p, p)))
    }

    /// Lays the text out in label-local coordinates: pen x from 0, y down, the label's
    /// baseline at y = 0.
    pub(crate) fn layout(&self) -> TextLayout {
        layout_text(&self.text, self.size, self.face)
    }

    /// The map from label-local coordinates to figure pixels.
    ///
    /// ```text
    /// figure = position + R(rotation) (local + (-anchor * width, baseline offset))
    /// ```
    pub(crate) fn local_to_figure(&self, extent: &TextExtent) -> Affine2 {
        let dx = match self.anchor {
            Anchor::Start => 0.0,
            Anchor::Middle => -0.5 * extent.width,
            Anchor::End => -extent.width,
        };
        let dy = match self.baseline {
            Baseline::Alphabetic => 0.0,
            Baseline::Middle => 0.5 * (extent.ascent - extent.descent),
            Baseline::Top => extent.ascent,
            Baseline::Bottom => -extent.descent,
        };
        // Counter-clockwise on screen, where y points down.
        let (sin, cos) = self.rotation.sin_cos();
        let rotation = Mat2::from_cols(Vec2::new(cos, -sin), Vec2::new(sin, cos));
        Affine2::from_translation(self.position)
            * Affine2::from_mat2(rotation)
            * Affine2::from_translation(Vec2::new(dx, dy))
    }
}

/// Whether a run of text is set normally or as a script.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Script {
    Normal,
    Sub,
    Super,
}

/// A run of characters in one script, after markup parsing.
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct Span {
    pub script: Script,
    /// The face of the run (the label's, or another chosen by markup).
    pub face: FontFace,
    pub text: String,
    /// Font size of the run, pixels per em.
    pub size: f32,
    /// Baseline offset of the run, pixels, positive down.
    pub shift: f32,
}

/// A glyph placed in label-local coordinates.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct PlacedGlyph {
    pub id: GlyphId,
    /// The face the glyph comes from.
    pub face: FontFace,
    /// The glyph origin (pen position on its baseline), y down.
    pub origin: Vec2,
    /// Pixels per font unit.
    pub scale: f32,
}

/// A laid-out line of text in label-local coordinates (pen from x = 0, baseline y = 0,
/// y down).
#[derive(Clone, Debug, PartialEq)]
pub(crate) struct TextLayout {
    pub spans: Vec<Span>,
    pub glyphs: Vec<PlacedGlyph>,
    pub extent: TextExtent,
    /// The union of the glyphs' outline boxes, `None` without ink.
    pub ink: Option<Rect>,
}

/// The markup state a character is set in: inside `$math$`, inside `*bold*`.
#[derive(Clone, Copy, Debug, Default)]
struct MarkupStyle {
    math: bool,
    bold: bool,
}

impl MarkupStyle {
    /// The face and the character to set for `c` in a label whose face is `base`.
    fn set(self, c: char, base: FontFace) -> (FontFace, char) {
        let mut face = if self.bold { base.emboldened() } else { base };
        let mut c = c;
        if self.math {
            if c.is_ascii_alphabetic() && !self.bold {
                face = face.slanted();
            } else if c == '-' {
                c = '\u{2212}';
            }
        }
        (face, c)
    }
}

/// Splits `text` into runs of one script and one face, for a label whose face is `base`.
fn parse_markup(text: &str, base: FontFace) -> Vec<(Script, FontFace, String)> {
    let mut runs: Vec<(Script, FontFace, String)> = Vec::new();
    let mut push = |script: Script, (face, c): (FontFace, char)| match runs.last_mut() {
        Some((s, f, run)) if *s == script && *f == face => run.push(c),
        _ => runs.push((script, face, c.to_string())),
    };
    let mut style = MarkupStyle::default();
    let plain = |c: char| (base, c);
    let mut chars = text.chars();
    while let Some(c) = chars.next() {
        let script = match c {
            '_' => Script::Sub,
            '^' => Script::Super,
            '$' => {
                style.math = !style.math;
                continue;
            }
            '*' => {
                style.bold = !style.bold;
                continue;
            }
            '\\' => {
                let literal = chars.next().unwrap_or('\\');
                push(
                    Script::Normal,
                    MarkupStyle {
                        math: false,
                        ..style
                    }
                    .set(literal, base),
                );
                continue;
            }
            _ => {
                push(Script::Normal, style.set(c, base));
                continue;
            }
        };
        match chars.next() {
            None => push(Script::Normal, plain(c)),
            Some('{') => {
                while let Some(inner) = chars.next() {
                    match inner {
                        '}' => break,
                        '$' => style.math = !style.math,
                        '*' => style.bold = !style.bold,
                        '\\' => {
                            let literal = chars.next().unwrap_or('\\');
                            push(
                                script,
                                MarkupStyle {
                                    math: false,
                                    ..style
                                }
                                .set(literal, base),
                            );
                        }
                        _ => push(script, style.set(inner, base)),
                    }
                }
            }
            Some('\\') => {
                let literal = chars.next().unwrap_or('\\');
                push(
                    script,
                    MarkupStyle {
                        math: false,
                        ..style
                    }
                    .set(literal, base),
                );
            }
            Some(next) => push(script, style.set(next, base)),
        }
    }
    runs
}

/// Lays out one line of `text` at `size` pixels per em in `face`, with kerning between
/// neighbouring glyphs of a run.
fn layout_text(text: &str, size: f32, face: FontFace) -> TextLayout {
    let font = face.font();
    let units_per_em = font.units_per_em().unwrap_or(2048.0);
    let mut extent = TextExtent {
        width: 0.0,
        ascent: font.ascent_unscaled() * size / units_per_em,
        descent: -font.descent_unscaled() * size / units_per_em,
    };
    let mut spans = Vec::new();
    let mut glyphs = Vec::new();
    let mut ink: Option<Rect> = None;
    let mut pen = 0.0;
    let mut previous_face: Option<FontFace> = None;
    for (script, run_face, run) in parse_markup(text, face) {
        let font = run_face.font();
        let units_per_em = font.units_per_em().unwrap_or(2048.0);
        let (span_size, shift) = match script {
            Script::Normal => (size, 0.0),
            Script::Sub => (size * SCRIPT_SCALE, size * SUBSCRIPT_DROP),
            Script::Super => (size * SCRIPT_SCALE, -size * SUPERSCRIPT_RISE),
        };
        // An italic correction, as TeX makes one: a slanted letter leans over into an
        // upright character set after it, so leave it a little room.
        if previous_face.is_some_and(FontFace::is_slanted) && !run_face.is_slanted() {
            pen += ITALIC_CORRECTION * size;
        }
        previous_face = Some(run_face);
        let scale = span_size / units_per_em;
        extent.ascent = extent.ascent.max(font.ascent_unscaled() * scale - shift);
        extent.descent = extent.descent.max(-font.descent_unscaled() * scale + shift);
        let mut previous: Option<GlyphId> = None;
        for c in run.chars().filter(|c| !c.is_control()) {
            let id = font.glyph_id(c);
            if let Some(previous) = previous {
                pen += font.kern_unscaled(previous, id) * scale;
            }
            let origin = Vec2::new(pen, shift);
            if let Some(outline) = font.outline(id) {
                let b = outline.bounds;
                let glyph_ink = Rect::from_corners(
                    origin + Vec2::new(b.min.x, -b.min.y) * scale,
                    origin + Vec2::new(b.max.x, -b.max.y) * scale,
                );
                ink = Some(ink.map_or(glyph_ink, |r| r.union(&glyph_ink)));
            }
            glyphs.push(PlacedGlyph {
                id,
                face: run_face,
                origin,
                scale,
            });
            pen += font.h_advance_unscaled(id) * scale;
            previous = Some(id);
        }
        spans.push(Span {
            script,
            face: run_face,
            text: run,
            size: span_size,
            shift,
        });
    }
    extent.width = pen;
    TextLayout {
        spans,
        glyphs,
        extent,
        ink,
    }
}

/// Breaks a paragraph into lines: `parts`, each with the separator written before it
/// when it follows another part on the same line, as many to a line as `fits` allows (a
/// part that does not fit alone stands alone on its line). Where a line breaks, the
/// separator's trailing punctuation stays at its end (`", "` leaves a comma, `" "`
/// nothing).
///
/// ```
/// use viewray_draw::wrap_parts;
///
/// let words = "one two three".split(' ').map(|w| (w, " "));
/// assert_eq!(wrap_parts(words, |line| line.len() <= 7), ["one two", "three"]);
/// let parts = [("d = 1", ",  "), ("shift (0, 1)", ",  ")];
/// assert_eq!(wrap_parts(parts, |line| line.len() <= 12), ["d = 1,", "shift (0, 1)"]);
/// ```
pub fn wrap_parts<'a>(
    parts: impl IntoIterator<Item = (&'a str, &'a str)>,
    fits: impl Fn(&str) -> bool,
) -> Vec<String> {
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for (part, separator) in parts {
        if line.is_empty() {
            part.clone_into(&mut line);
            continue;
        }
        let longer = format!("{line}{separator}{part}");
        if fits(&longer) {
            line = longer;
        } else {
            lines.push(format!("{line}{}", separator.trim_end()));
            part.clone_into(&mut line);
        }
    }
    if !line.is_empty() {
        lines.push(line);
    }
    lines
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The text box of one line of `text` set at `size` pixels per em in `face`.
    fn measure_text(text: &str, size: f32, face: FontFace) -> TextExtent {
        layout_text(text, size, face).extent
    }

    #[track_caller]
    fn check_markup(text: &str, expected: &[(Script, &str)]) {
        let got = parse_markup(text, FontFace::Regular);
        let got: Vec<(Script, &str)> = got.iter().map(|(s, _, t)| (*s, t.as_str())).collect();
        assert_eq!(got, expected, "markup of {text:?}");
    }

    #[track_caller]
    fn check_faces(text: &str, base: FontFace, expected: &[(Script, FontFace, &str)]) {
        let got = parse_markup(text, base);
        let got: Vec<(Script, FontFace, &str)> =
            got.iter().map(|(s, f, t)| (*s, *f, t.as_str())).collect();
        assert_eq!(got, expected, "faces of {text:?}");
    }

    #[test]
    fn math_and_bold_markup_choose_faces() {
        use FontFace::*;
        use Script::*;
        check_faces(
            "$u = j - 1$",
            Regular,
            &[
                (Normal, Italic, "u"),
                (Normal, Regular, " = "),
                (Normal, Italic, "j"),
                (Normal, Regular, " \u{2212} 1"),
            ],
        );
        check_faces(
            "$d *w*$ \\$5-*",
            Regular,
            &[
                (Normal, Italic, "d"),
                (Normal, Regular, " "),
                (Normal, Bold, "w"),
                (Normal, Regular, " $5-"),
            ],
        );
        check_faces(
            "$v_h$ \\*",
            Regular,
            &[
                (Normal, Italic, "v"),
                (Sub, Italic, "h"),
                (Normal, Regular, " *"),
            ],
        );
        check_faces("$e$", Bold, &[(Normal, BoldItalic, "e")]);
    }

    #[test]
    fn italic_correction_separates_slanted_from_upright() {
        let corrected = measure_text("$f$)", 40.0, FontFace::Regular).width;
        let apart = measure_text("f", 40.0, FontFace::Italic).width
            + measure_text(")", 40.0, FontFace::Regular).width;
        assert!(
            (corrected - (apart + ITALIC_CORRECTION * 40.0)).abs() < 1e-3,
            "{corrected} vs {apart}"
        );
    }

    #[test]
    fn markup() {
        use Script::*;
        check_markup("vw", &[(Normal, "vw")]);
        check_markup("v_h", &[(Normal, "v"), (Sub, "h")]);
        check_markup("v_hw", &[(Normal, "v"), (Sub, "h"), (Normal, "w")]);
        check_markup("x_{ij}^2", &[(Normal, "x"), (Sub, "ij"), (Super, "2")]);
        check_markup("file\\_name", &[(Normal, "file_name")]);
        check_markup("a_", &[(Normal, "a_")]);
        check_markup("a_{b", &[(Normal, "a"), (Sub, "b")]);
        check_markup("", &[]);
    }

    #[test]
    fn kerning_tightens_av() {
        // DejaVu Sans kerns "AV": the pair is narrower than its letters apart.
        let size = 100.0;
        let pair = measure_text("AV", size, FontFace::Regular).width;
        let apart = measure_text("A", size, FontFace::Regular).width
            + measure_text("V", size, FontFace::Regular).width;
        assert!(pair < apart - 1.0, "AV {pair} vs A + V {apart}");
    }

    #[test]
    fn scripts_are_smaller_and_extend_the_box() {
        let plain = measure_text("vh", 40.0, FontFace::Italic);
        let sub = measure_text("v_h", 40.0, FontFace::Italic);
        let sup = measure_text("v^h", 40.0, FontFace::Italic);
        assert!(sub.width < plain.width);
        assert!(sub.descent > plain.descent);
        assert_eq!(sub.ascent, plain.ascent);
        assert!(sup.ascent > plain.ascent);
    }

    #[test]
    fn width_scales_with_size() {
        let small = measure_text("vw", 20.0, FontFace::Italic);
        let large = measure_text("vw", 40.0, FontFace::Italic);
        assert!((large.width - 2.0 * small.width).abs() < 1e-3);
        assert!((large.ascent - 2.0 * small.ascent).abs() < 1e-3);
    }

    #[test]
    fn bounds_follow_anchor_baseline_and_rotation() {
        let at = Vec2::new(500.0, 300.0);
        let label = Label::math("d", at).with_anchor(Anchor::Start, Baseline::Alphabetic);
        let b = label.bounds();
        let e = label.layout().extent;
        assert!((b.min.x - at.x).abs() < 2.0, "{b:?}");
        assert!((b.min.y - (at.y - e.ascent)).abs() < 1e-3);
        assert!((b.max.y - (at.y + e.descent)).abs() < 1e-3);

        let centred = Label::math("d", at).bounds();
        assert!(centred.center().abs_diff_eq(at, 2.0), "{centred:?}");

        let wide = Label::new("viewing ray", at);
        let upright = wide.bounds();
        let turned = wide.with_rotation(std::f32::consts::FRAC_PI_2).bounds();
        assert!(upright.width() > upright.height());
        assert!(turned.height() > turned.width());
        assert!((turned.height() - upright.width()).abs() < 1.0);
    }
}

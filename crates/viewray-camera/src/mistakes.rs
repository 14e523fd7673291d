//! The lecture's mistakes: one catalogue of the ways a student's camera goes wrong.
//!
//! Every diagnosis viewray gives (of a student's numbers, of a student's picture, in
//! grading a class) names an entry of this catalogue. Each entry is an exact variant of
//! the camera contract, so [`Camera::with_mistakes`] makes the camera a student with that
//! mistake wrote: it generates the mistaken rays, prints the mistaken frame and renders
//! the mistaken picture through the very code that makes the right ones. Entries
//! combine (`pixel-corner` with `v-sign`); everything an entry does not name stays as the
//! contract says.
//!
//! How the entries are made exact: a mistake in turning `(i, j)` into `(u, v)` is a
//! change of the continuous image point `(x, y)` before the lecture's mapping (with the
//! centre sample, `x = col + 1/2`); a mistake in the projection is a change of its
//! parameters; a mistake in the basis is a change of the frame. A student's camera is
//! those three steps in the lecture's order:
//!
//! ```text
//! (x, y)  -> the pixel mistakes, in this order: i-j-swapped; pixel-corner or
//!            pixel-one-based; size-minus-one; u-sign, v-sign
//! (u, v)  =  ((x / W - 1/2) vw, -(y / H - 1/2) vh), vw and vh after viewport-missing
//!            and viewport-swapped
//! ray     =  the family's rule with d, (sx, sy), L, phi after the projection mistakes
//! world   =  origin and direction through (e; U, V, W) after the basis mistakes, the
//!            origin without e after eye-missing, the camera's coordinates taken as the
//!            world's after basis-missing
//! ```

use std::fmt;

use glam::{DVec2, DVec3};

use crate::{Perspective, Projection};

/// One mistake of the lecture's catalogue. [`Mistake::ALL`] lists them in the order the
/// lecture meets the formulas they break: pixel to image plane, the projection, the
/// basis, then the parallel families.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Mistake {
    /// No half-pixel offset: `u = (col/W - 1/2) vw`, `v = -(row/H - 1/2) vh`.
    PixelCorner,
    /// A 1-based index without the 1/2: `u = ((col+1)/W - 1/2) vw`, `v` likewise.
    PixelOneBased,
    /// Divides by `W - 1` and `H - 1`: `u = (col/(W-1) - 1/2) vw`, `v` likewise.
    SizeMinusOne,
    /// `v` without its minus sign: the picture upside down.
    VSign,
    /// `u` with a minus sign: the picture mirrored.
    USign,
    /// `u` from the row and `v` from the column (with `W` and `H` as written).
    IJSwapped,
    /// `vw = vh = 1`.
    ViewportMissing,
    /// `vw` and `vh` exchanged.
    ViewportSwapped,
    /// `d = 1`.
    DistanceMissing,
    /// The direction `u U + v V + d W`.
    DistanceSign,
    /// The origin at `0` (orthographic: `0 + u U + v V`).
    EyeMissing,
    /// The direction `(u, v, -d)` taken as world coordinates.
    BasisMissing,
    /// `w = +view / |view|` (then `u = up x w`, `v = w x u` as usual).
    WView,
    /// `u = w x up` (`v = w x u` follows).
    UCrossOrder,
    /// `v = u x w`.
    VCrossOrder,
    /// `u = up x w`, not normalized.
    UNotNormalized,
    /// The shift `(-sx, -sy)`.
    ShiftSign,
    /// The shift `(0, 0)`.
    ShiftMissing,
    /// Orthographic: every ray starts at `e`.
    OrthoOriginFixed,
    /// Orthographic: the direction `u U + v V - W` from `e`.
    OrthoAsPerspective,
    /// Oblique: the direction `-W + L (cos phi U + sin phi V)`.
    ObliqueSign,
    /// Oblique: the direction `-W`.
    ObliqueAsOrtho,
}

/// What the catalogue says of one entry: its words for a student.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Entry {
    /// The id, as every judge prints it: `pixel-corner`.
    pub id: &'static str,
    /// What the picture looks like, in a word or two: `mirrored`, `upside down` (the
    /// class summary counts diagnoses by it: "12 mirrored: u-sign").
    pub looks: &'static str,
    /// The mistake in a few words: "no half-pixel offset".
    pub summary: &'static str,
    /// The mistaken formula, in the lecture's notation.
    pub mistaken: &'static str,
    /// The lecture's line to fix: the right formula.
    pub fix: &'static str,
    /// What the mistake does to the picture.
    pub picture: &'static str,
}

impl Mistake {
    /// Every entry, in the catalogue's order.
    pub const ALL: [Mistake; 22] = [
        Mistake::PixelCorner,
        Mistake::PixelOneBased,
        Mistake::SizeMinusOne,
        Mistake::VSign,
        Mistake::USign,
        Mistake::IJSwapped,
        Mistake::ViewportMissing,
        Mistake::ViewportSwapped,
        Mistake::DistanceMissing,
        Mistake::DistanceSign,
        Mistake::EyeMissing,
        Mistake::BasisMissing,
        Mistake::WView,
        Mistake::UCrossOrder,
        Mistake::VCrossOrder,
        Mistake::UNotNormalized,
        Mistake::ShiftSign,
        Mistake::ShiftMissing,
        Mistake::OrthoOriginFixed,
        Mistake::OrthoAsPerspective,
        Mistake::ObliqueSign,
        Mistake::ObliqueAsOrtho,
    ];

    /// The entry's id, e.g. `"pixel-corner"`.
    pub fn id(self) -> &'static str {
        self.entry().id
    }

    /// The entry whose id is `id`.
    pub fn from_id(id: &str) -> Option<Mistake> {
        Mistake::ALL.into_iter().find(|m| m.id() == id)
    }

    /// What the catalogue says of this mistake.
    pub fn entry(self) -> Entry {
        const PIXEL_FIX: &str = "u = ((j - 1/2)/W - 1/2) vw,  v = -((i - 1/2)/H - 1/2) vh";
        const DIRECTION_FIX: &str = "direction = (u + sx) U + (v + sy) V - d W";
        const BASIS_FIX: &str = "w = -view / |view|,  u = (up x w) / |up x w|,  v = w x u";
        const OBLIQUE_FIX: &str = "direction = -W - L (cos phi U + sin phi V)";
        let (id, looks, summary, mistaken, fix, picture) = match self {
            Mistake::PixelCorner => (
                "pixel-corner",
                "moved half a pixel",
                "no half-pixel offset",
                "u = (col/W - 1/2) vw,  v = -(row/H - 1/2) vh",
                PIXEL_FIX,
                "the picture moves half a pixel right and half a pixel down",
            ),
            Mistake::PixelOneBased => (
                "pixel-one-based",
                "moved half a pixel",
                "1-based indices without the 1/2",
                "u = (j/W - 1/2) vw,  v = -(i/H - 1/2) vh",
                PIXEL_FIX,
                "the picture moves half a pixel left and half a pixel up",
            ),
            Mistake::SizeMinusOne => (
                "size-minus-one",
                "a little too small",
                "divides by W - 1 and H - 1",
                "u = (col/(W-1) - 1/2) vw,  v = -(row/(H-1) - 1/2) vh",
                PIXEL_FIX,
                "the picture is a little too small (W - 1 of W): right in the middle, half a \
                 pixel off at the edges",
            ),
            Mistake::VSign => (
                "v-sign",
                "upside down",
                "v without its minus sign",
                "v = ((i - 1/2)/H - 1/2) vh",
                "v = -((i - 1/2)/H - 1/2) vh: rows count down from the top, v points up",
                "the picture is upside down",
            ),
            Mistake::USign => (
                "u-sign",
                "mirrored",
                "u with a minus sign",
                "u = -((j - 1/2)/W - 1/2) vw",
                "u = ((j - 1/2)/W - 1/2) vw: columns and u both count to the right",
                "the picture is mirrored left to right",
            ),
            Mistake::IJSwapped => (
                "i-j-swapped",
                "transposed",
                "i and j swapped",
                "u = ((i - 1/2)/W - 1/2) vw,  v = -((j - 1/2)/H - 1/2) vh",
                "u comes from the column j, v from the row i: u = ((j - 1/2)/W - 1/2) vw",
                "the picture is transposed (mirrored about its diagonal, stretched when W and \
                 H differ)",
            ),
            Mistake::ViewportMissing => (
                "viewport-missing",
                "wrong field of view",
                "the viewport left out (vw = vh = 1)",
                "u = (j - 1/2)/W - 1/2,  v = -((i - 1/2)/H - 1/2)",
                PIXEL_FIX,
                "the field of view is wrong: the picture is scaled by vw across and vh up and \
                 down",
            ),
            Mistake::ViewportSwapped => (
                "viewport-swapped",
                "stretched",
                "vw and vh exchanged",
                "u = ((j - 1/2)/W - 1/2) vh,  v = -((i - 1/2)/H - 1/2) vw",
                PIXEL_FIX,
                "the picture is stretched: vw/vh too wide or too narrow across, the other way \
                 up and down",
            ),
            Mistake::DistanceMissing => (
                "distance-missing",
                "wrong field of view",
                "d left out (d = 1)",
                "direction = (u + sx) U + (v + sy) V - W",
                DIRECTION_FIX,
                "the picture is d times too small (d > 1) or too large (d < 1): the field of \
                 view is wrong",
            ),
            Mistake::DistanceSign => (
                "distance-sign",
                "looking backwards",
                "+d W instead of -d W",
                "direction = (u + sx) U + (v + sy) V + d W",
                "direction = (u + sx) U + (v + sy) V - d W: the camera looks along -w",
                "the camera looks backwards: you see what is behind the eye, mirrored",
            ),
            Mistake::EyeMissing => (
                "eye-missing",
                "seen from the origin",
                "the eye left out",
                "origin = (0, 0, 0)  (orthographic: 0 + u U + v V)",
                "origin = e  (orthographic: e + u U + v V)",
                "the picture is taken from the world's origin instead of the eye",
            ),
            Mistake::BasisMissing => (
                "basis-missing",
                "looking down -z",
                "the basis left out",
                "direction = (u, v, -d) in world coordinates",
                "direction = u U + v V - d W: the camera's own axes, in the world",
                "the camera looks down -z whatever view and up say; only the eye moved",
            ),
            Mistake::WView => (
                "w-view",
                "looking backwards",
                "w along view",
                "w = view / |view|",
                "w = -view / |view|: w points back, the camera looks along -w",
                "the camera looks backwards: you see what is behind the eye, mirrored",
            ),
            Mistake::UCrossOrder => (
                "u-cross-order",
                "turned 180 degrees",
                "u = w x up",
                "u = w x up",
                "u = up x w",
                "the picture is turned 180 degrees (u and v both flipped)",
            ),
            Mistake::VCrossOrder => (
                "v-cross-order",
                "upside down",
                "v = u x w",
                "v = u x w",
                "v = w x u",
                "the picture is upside down (v flipped)",
            ),
            Mistake::UNotNormalized => (
                "u-not-normalized",
                "wrong field of view",
                "u not normalized",
                "u = up x w",
                BASIS_FIX,
                "the field of view is |up x w| times too wide or too narrow (when up is not a \
                 unit vector perpendicular to view)",
            ),
            Mistake::ShiftSign => (
                "shift-sign",
                "shifted the wrong way",
                "the shift's sign",
                "direction = (u - sx) U + (v - sy) V - d W",
                DIRECTION_FIX,
                "the picture moves twice the shift the wrong way",
            ),
            Mistake::ShiftMissing => (
                "shift-missing",
                "not shifted",
                "the shift left out",
                "direction = u U + v V - d W",
                DIRECTION_FIX,
                "the picture is not shifted: the window is centred on the view direction",
            ),
            Mistake::OrthoOriginFixed => (
                "ortho-origin-fixed",
                "one colour",
                "every parallel ray starts at the eye",
                "origin = e",
                "origin = e + u U + v V: parallel rays start from their pixel",
                "every pixel sees the same point: the picture is one colour",
            ),
            Mistake::OrthoAsPerspective => (
                "ortho-as-perspective",
                "in perspective",
                "perspective rays in an orthographic camera",
                "origin = e,  direction = u U + v V - W",
                "origin = e + u U + v V,  direction = -W",
                "perspective instead of parallel: far things shrink, parallel lines converge",
            ),
            Mistake::ObliqueSign => (
                "oblique-sign",
                "slanted the wrong way",
                "the oblique slant's sign",
                "direction = -W + L (cos phi U + sin phi V)",
                OBLIQUE_FIX,
                "depth recedes the opposite way (phi + 180 degrees)",
            ),
            Mistake::ObliqueAsOrtho => (
                "oblique-as-ortho",
                "not slanted",
                "the oblique slant left out",
                "direction = -W",
                OBLIQUE_FIX,
                "no slant: an orthographic view in which depth does not show",
            ),
        };
        Entry {
            id,
            looks,
            summary,
            mistaken,
            fix,
            picture,
        }
    }

    /// Whether this mistake can be made in a camera of `projection`'s family: the
    /// pixel and basis entries in every planar family, the distance and shift entries in
    /// the perspective ones (`distance-sign` in the pinhole only), the `ortho-` and
    /// `oblique-` entries in their own; none in the panoramic cameras.
    pub fn fits(self, projection: &Projection) -> bool {
        let planar = projection.viewport().is_some();
        match self {
            Mistake::DistanceMissing | Mistake::ShiftSign | Mistake::ShiftMissing => {
                matches!(
                    projection,
                    Projection::Perspective(_) | Projection::ThinLens(_)
                )
            }
            Mistake::DistanceSign => matches!(projection, Projection::Perspective(_)),
            Mistake::OrthoOriginFixed | Mistake::OrthoAsPerspective => {
                matches!(projection, Projection::Orthographic(_))
            }
            Mistake::ObliqueSign | Mistake::ObliqueAsOrtho => {
                matches!(projection, Projection::Oblique(_))
            }
            _ => planar,
        }
    }

    /// The bit of this mistake in a [`Mistakes`] set.
    const fn bit(self) -> u32 {
        1 << self as u32
    }
}

impl fmt::Display for Mistake {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.id())
    }
}

/// A set of the catalogue's mistakes, made together.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Mistakes(u32);

impl Mistakes {
    /// No mistake: the camera as the contract says.
    pub const NONE: Mistakes = Mistakes(0);

    /// The set holding only `mistake`.
    pub const fn one(mistake: Mistake) -> Mistakes {
        Mistakes(mistake.bit())
    }

    /// Whether the set holds `mistake`.
    pub const fn contains(self, mistake: Mistake) -> bool {
        self.0 & mistake.bit() != 0
    }

    /// Whether the set holds no mistake.
    pub const fn is_empty(self) -> bool {
        self.0 == 0
    }

    /// How many mistakes the set holds.
    pub const fn len(self) -> usize {
        self.0.count_ones() as usize
    }

    /// The set with `mistake` added.
    #[must_use]
    pub const fn with(self, mistake: Mistake) -> Mistakes {
        Mistakes(self.0 | mistake.bit())
    }

    /// The set's mistakes in the catalogue's order.
    pub fn iter(self) -> impl Iterator<Item = Mistake> {
        Mistake::ALL.into_iter().filter(move |&m| self.contains(m))
    }

    /// Whether any mistake of the set changes where a pixel's ray goes through the image
    /// plane (the pixel entries), so that the shortcuts that compute `(u, v)` directly do
    /// not apply.
    pub(crate) fn moves_pixels(self) -> bool {
        // One mask, not a walk over the catalogue: every thin-lens sample asks (the walk
        // was about 250 instructions a ray).
        const PIXEL_ENTRIES: u32 = Mistake::PixelCorner.bit()
            | Mistake::PixelOneBased.bit()
            | Mistake::SizeMinusOne.bit()
            | Mistake::VSign.bit()
            | Mistake::USign.bit()
            | Mistake::IJSwapped.bit();
        self.0 & PIXEL_ENTRIES != 0
    }

    /// Whether the rays leave out the basis (`basis-missing`): the camera's coordinates
    /// are taken as the world's.
    pub(crate) fn skips_basis(self) -> bool {
        self.contains(Mistake::BasisMissing)
    }

    /// The continuous image point whose correct `(u, v)` the student's formula gives at
    /// `image = (x, y)`, for an image of `size = (W, H)`: the pixel entries in the order
    /// of the module's doc.
    pub(crate) fn image_point(self, image: DVec2, size: DVec2) -> DVec2 {
        let mut p = image;
        if self.contains(Mistake::IJSwapped) {
            p = DVec2::new(p.y, p.x);
        }
        if self.contains(Mistake::PixelCorner) {
            p -= 0.5;
        }
        if self.contains(Mistake::PixelOneBased) {
            p += 0.5;
        }
        if self.contains(Mistake::SizeMinusOne) {
            // u = (col / (W - 1) - 1/2) vw is the lecture's u at x = W col / (W - 1), the
            // index being what is left of x without its half pixel.
            p = (p - 0.5) * size / (size - 1.0);
        }
        if self.contains(Mistake::USign) {
            p.x = size.x - p.x;
        }
        if self.contains(Mistake::VSign) {
            p.y = size.y - p.y;
        }
        p
    }

    /// The projection the student's formulas amount to: `projection` with the viewport,
    /// distance, shift and oblique entries applied (and an orthographic camera turned
    /// perspective or its slant dropped where an entry says so).
    pub(crate) fn projection(self, projection: Projection) -> Projection {
        let viewport = |viewport: DVec2| {
            let mut viewport = viewport;
            if self.contains(Mistake::ViewportMissing) {
                viewport = DVec2::ONE;
            }
            if self.contains(Mistake::ViewportSwapped) {
                viewport = DVec2::new(viewport.y, viewport.x);
            }
            viewport
        };
        let distance = |distance: f64| {
            let mut distance = distance;
            if self.contains(Mistake::DistanceMissing) {
                distance = 1.0;
            }
            if self.contains(Mistake::DistanceSign) {
                // `(u, v, -d)` with d negative is the student's `(u, v, +d)`.
                distance = -distance;
            }
            distance
        };
        let shift = |shift: DVec2| {
            if self.contains(Mistake::ShiftMissing) {
                DVec2::ZERO
            } else if self.contains(Mistake::ShiftSign) {
                -shift
            } else {
                shift
            }
        };
        match projection {
            Projection::Perspective(p) => Projection::Perspective(Perspective {
                distance: distance(p.distance),
                viewport: viewport(p.viewport),
                shift: shift(p.shift),
            }),
            Projection::ThinLens(mut p) => {
                p.distance = distance(p.distance);
                p.viewport = viewport(p.viewport);
                p.shift = shift(p.shift);
                Projection::ThinLens(p)
            }
            Projection::Orthographic(mut p) => {
                p.viewport = viewport(p.viewport);
                if self.contains(Mistake::OrthoAsPerspective) {
                    // From e, direction u U + v V - W: a pinhole with d = 1.
                    Projection::Perspective(Perspective {
                        distance: 1.0,
                        viewport: p.viewport,
                        shift: DVec2::ZERO,
                    })
                } else {
                    Projection::Orthographic(p)
                }
            }
            Projection::Oblique(mut p) => {
                p.viewport = viewport(p.viewport);
                if self.contains(Mistake::ObliqueAsOrtho) {
                    p.ratio = 0.0;
                } else if self.contains(Mistake::ObliqueSign) {
                    // -L (cos(phi + pi) U + sin(phi + pi) V) = +L (cos phi U + sin phi V).
                    p.angle += std::f64::consts::PI;
                }
                Projection::Oblique(p)
            }
            other => other,
        }
    }

    /// The frame `(e; U, V, W)` the student's basis amounts to, from the right frame
    /// and the `up` vector as given; the right basis itself, to the bit, when no basis
    /// entry is in the set.
    /// `eye-missing` and `basis-missing` are not basis entries: the student's frame is
    /// Problem 2 done right, and only the rays leave out `e` or the basis.
    pub(crate) fn frame(self, right: [DVec3; 4], up: DVec3) -> [DVec3; 4] {
        let [e, right_u, right_v, w] = right;
        let rebuilt = [
            Mistake::WView,
            Mistake::UCrossOrder,
            Mistake::VCrossOrder,
            Mistake::UNotNormalized,
        ];
        if !rebuilt.into_iter().any(|m| self.contains(m)) {
            return [e, right_u, right_v, w];
        }
        let w = if self.contains(Mistake::WView) { -w } else { w };
        let u = if self.contains(Mistake::UCrossOrder) {
            w.cross(up)
        } else {
            up.cross(w)
        };
        let u = if self.contains(Mistake::UNotNormalized) {
            u
        } else {
            u.normalize()
        };
        let v = if self.contains(Mistake::VCrossOrder) {
            u.cross(w)
        } else {
            w.cross(u)
        };
        [e, u, v, w]
    }
}

impl FromIterator<Mistake> for Mistakes {
    fn from_iter<I: IntoIterator<Item = Mistake>>(iter: I) -> Self {
        iter.into_iter().fold(Mistakes::NONE, Mistakes::with)
    }
}

impl From<Mistake> for Mistakes {
    fn from(mistake: Mistake) -> Self {
        Mistakes::one(mistake)
    }
}

impl fmt::Display for Mistakes {
    /// The ids joined by ` + `: `pixel-corner + v-sign`; `none` for the empty set.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        if self.is_empty() {
            return f.write_str("none");
        }
        for (k, mistake) in self.iter().enumerate() {
            if k > 0 {
                f.write_str(" + ")?;
            }
            f.write_str(mistake.id())?;
        }
        Ok(())
    }
}

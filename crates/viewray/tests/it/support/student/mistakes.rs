//! The lecture's mistakes, one variant each, under the ids viewray's catalogue gives them.
//! The formulas themselves are written where each mistake happens, in the camera's steps
//! (camera.rs), so that any set of them can be made at once.

use super::camera::Projection;

/// One of the lecture's mistakes (0-based `row, col`; everything not named is as the
/// camera contract says).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub(crate) enum Mistake {
    /// No half-pixel offset: `u = (col/W - 1/2) vw`, `v = -(row/H - 1/2) vh`.
    PixelCorner,
    /// A 1-based index without the 1/2: `u = ((col+1)/W - 1/2) vw`, v likewise.
    PixelOneBased,
    /// Divides by `W - 1` and `H - 1`: `u = (col/(W-1) - 1/2) vw`, v likewise.
    SizeMinusOne,
    /// `v` without its minus sign (upside down).
    VSign,
    /// `u` with a minus sign (mirrored).
    USign,
    /// `u` from the row and `v` from the column, with `W` and `H` as written.
    IJSwapped,
    /// `vw = vh = 1`.
    ViewportMissing,
    /// `vw` and `vh` exchanged.
    ViewportSwapped,
    /// `d = 1`.
    DistanceMissing,
    /// Direction `u U + v V + d W`.
    DistanceSign,
    /// Origin at 0 (orthographic: `0 + u U + v V`).
    EyeMissing,
    /// Direction `(u, v, -d)` taken as world coordinates.
    BasisMissing,
    /// `w = +view/|view|` (`u = up x w`, `v = w x u` as usual).
    WView,
    /// `u = w x up` (`v = w x u` follows).
    UCrossOrder,
    /// `v = u x w`.
    VCrossOrder,
    /// `u = up x w`, not normalized.
    UNotNormalized,
    /// Shift `(-sx, -sy)`.
    ShiftSign,
    /// Shift `(0, 0)`.
    ShiftMissing,
    /// Orthographic: every ray starts at `e`.
    OrthoOriginFixed,
    /// Orthographic: direction `u U + v V - W` from `e`.
    OrthoAsPerspective,
    /// Oblique: direction `-W + L (cos phi U + sin phi V)`.
    ObliqueSign,
    /// Oblique: direction `-W`.
    ObliqueAsOrtho,
}

impl Mistake {
    /// Every mistake, in the catalogue's order.
    pub(crate) const ALL: [Mistake; 22] = [
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

    /// The catalogue's id, e.g. `pixel-corner`.
    pub(crate) fn id(self) -> &'static str {
        match self {
            Mistake::PixelCorner => "pixel-corner",
            Mistake::PixelOneBased => "pixel-one-based",
            Mistake::SizeMinusOne => "size-minus-one",
            Mistake::VSign => "v-sign",
            Mistake::USign => "u-sign",
            Mistake::IJSwapped => "i-j-swapped",
            Mistake::ViewportMissing => "viewport-missing",
            Mistake::ViewportSwapped => "viewport-swapped",
            Mistake::DistanceMissing => "distance-missing",
            Mistake::DistanceSign => "distance-sign",
            Mistake::EyeMissing => "eye-missing",
            Mistake::BasisMissing => "basis-missing",
            Mistake::WView => "w-view",
            Mistake::UCrossOrder => "u-cross-order",
            Mistake::VCrossOrder => "v-cross-order",
            Mistake::UNotNormalized => "u-not-normalized",
            Mistake::ShiftSign => "shift-sign",
            Mistake::ShiftMissing => "shift-missing",
            Mistake::OrthoOriginFixed => "ortho-origin-fixed",
            Mistake::OrthoAsPerspective => "ortho-as-perspective",
            Mistake::ObliqueSign => "oblique-sign",
            Mistake::ObliqueAsOrtho => "oblique-as-ortho",
        }
    }

    /// The mistake with this id, if there is one.
    pub(crate) fn from_id(id: &str) -> Option<Mistake> {
        Mistake::ALL.into_iter().find(|m| m.id() == id)
    }

    /// Whether the mistake can be made with this projection at all: the distance and the
    /// shift belong to perspective cameras, `ortho-*` to orthographic ones, `oblique-*` to
    /// oblique ones; the others to every family. A mistake that cannot be made leaves the
    /// rays as they are.
    pub(crate) fn applies_to(self, projection: &Projection) -> bool {
        match self {
            Mistake::DistanceMissing
            | Mistake::DistanceSign
            | Mistake::ShiftSign
            | Mistake::ShiftMissing => matches!(projection, Projection::Perspective { .. }),
            Mistake::OrthoOriginFixed | Mistake::OrthoAsPerspective => {
                matches!(projection, Projection::Orthographic { .. })
            }
            Mistake::ObliqueSign | Mistake::ObliqueAsOrtho => {
                matches!(projection, Projection::Oblique { .. })
            }
            _ => true,
        }
    }
}

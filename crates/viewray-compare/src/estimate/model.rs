//! The transform the estimate looks for: mirrors, a scale per axis and a turn about a
//! point, then a move (see the parent module's doc for the formula).

/// A mirror-scale-rotation-move transform from expected to actual coordinates (see the
/// module doc).
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct Model {
    /// Mirrored left-right, upside down.
    pub(crate) mirror: [bool; 2],
    /// The turn, in radians, clockwise as seen.
    pub(crate) rotation: f64,
    /// The natural logarithm of the scale along x and y.
    pub(crate) log_scale: [f64; 2],
    /// The point `p` the mirrors, scale and rotation are about, in pixels.
    pub(crate) about: [f64; 2],
    /// The move `t` after them, in pixels.
    pub(crate) shift: [f64; 2],
}

impl Model {
    /// The identity, written about `about`.
    pub(crate) fn identity(about: [f64; 2]) -> Self {
        Self {
            mirror: [false; 2],
            rotation: 0.0,
            log_scale: [0.0; 2],
            about,
            shift: [0.0; 2],
        }
    }

    /// The mirrors as signs: -1 along a mirrored axis, else 1.
    pub(super) fn signs(&self) -> [f64; 2] {
        self.mirror.map(|m| if m { -1.0 } else { 1.0 })
    }

    /// The scales along x and y.
    pub(crate) fn scale(&self) -> [f64; 2] {
        self.log_scale.map(f64::exp)
    }

    /// `A = R(theta) S M`, rows first.
    pub(crate) fn matrix(&self) -> [[f64; 2]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let signs = self.signs();
        let k = [
            self.log_scale[0].exp() * signs[0],
            self.log_scale[1].exp() * signs[1],
        ];
        [[c * k[0], -s * k[1]], [s * k[0], c * k[1]]]
    }

    /// `A^-1 = M S^-1 R(-theta)`, rows first.
    pub(super) fn inverse_matrix(&self) -> [[f64; 2]; 2] {
        let (s, c) = self.rotation.sin_cos();
        let signs = self.signs();
        let k = [
            signs[0] * (-self.log_scale[0]).exp(),
            signs[1] * (-self.log_scale[1]).exp(),
        ];
        [[k[0] * c, k[0] * s], [-k[1] * s, k[1] * c]]
    }

    /// The same transform written about `q`: `t' = t + (A - I)(q - p)`.
    pub(crate) fn about_point(&self, q: [f64; 2]) -> Self {
        let a = self.matrix();
        let d = [q[0] - self.about[0], q[1] - self.about[1]];
        Self {
            about: q,
            shift: [
                self.shift[0] + (a[0][0] - 1.0) * d[0] + a[0][1] * d[1],
                self.shift[1] + a[1][0] * d[0] + (a[1][1] - 1.0) * d[1],
            ],
            ..*self
        }
    }

    /// The point the transform leaves where it is, `p + (I - A)^-1 t`, when `I - A` is
    /// well conditioned (a scale or a rotation; not a pure move, and not a mirror alone).
    pub(crate) fn fixed_point(&self) -> Option<[f64; 2]> {
        let a = self.matrix();
        let m = [[1.0 - a[0][0], -a[0][1]], [-a[1][0], 1.0 - a[1][1]]];
        let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
        // Both singular values of I - A must be clearly away from zero: at least a 2%
        // scale or a turn of a degree.
        let norm = m.iter().flatten().map(|v| v * v).sum::<f64>();
        if det.abs() < 1e-4 || det.abs() < 0.02 * norm.sqrt() * 0.02 {
            return None;
        }
        let t = self.shift;
        Some([
            self.about[0] + (m[1][1] * t[0] - m[0][1] * t[1]) / det,
            self.about[1] + (-m[1][0] * t[0] + m[0][0] * t[1]) / det,
        ])
    }

    /// Where the actual image's point `x` comes from in the expected image.
    pub(super) fn preimage(&self, inverse: &[[f64; 2]; 2], x: [f64; 2]) -> [f64; 2] {
        let y = [
            x[0] - self.about[0] - self.shift[0],
            x[1] - self.about[1] - self.shift[1],
        ];
        [
            self.about[0] + inverse[0][0] * y[0] + inverse[0][1] * y[1],
            self.about[1] + inverse[1][0] * y[0] + inverse[1][1] * y[1],
        ]
    }
}

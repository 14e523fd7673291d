//! The transform the estimate looks for: mirrors, a scale per axis and a turn about a
//! point, then a move, `X_a = p + R(theta) S M (X_e - p) + t` (see [`super`]).

/// A mirror-scale-rotation-move transform from expected to actual coordinates (see
/// [`super`]).
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::estimate::test_images::forward;

    /// Models with every kind of component: mirrors, turns, scales, moves.
    fn models() -> Vec<Model> {
        let mut models = Vec::new();
        for mirror in [[false, false], [true, false], [false, true], [true, true]] {
            for (rotation, log_scale, shift) in [
                (0.0, [0.0, 0.0], [3.0, -2.0]),
                (0.3, [0.0, 0.0], [0.0, 0.0]),
                (-0.1, [0.2, -0.1], [-7.5, 4.25]),
                (0.05, [-0.3, -0.3], [1.0, 1.0]),
            ] {
                models.push(Model {
                    mirror,
                    rotation,
                    log_scale,
                    about: [40.0, 25.0],
                    shift,
                });
            }
        }
        models
    }

    fn close(a: [f64; 2], b: [f64; 2]) -> bool {
        (a[0] - b[0]).abs() < 1e-9 && (a[1] - b[1]).abs() < 1e-9
    }

    #[test]
    fn the_identity_moves_nothing() {
        let identity = Model::identity([10.0, 20.0]);
        assert_eq!(identity.matrix(), [[1.0, 0.0], [0.0, 1.0]]);
        assert_eq!(identity.scale(), [1.0, 1.0]);
        for x in [[0.0, 0.0], [13.5, -4.0], [100.0, 75.0]] {
            assert_eq!(forward(&identity, x), x);
        }
    }

    #[test]
    fn the_matrix_is_a_turn_times_the_scales_times_the_mirrors() {
        // A quarter turn clockwise as seen (x towards y) of a picture mirrored left-right
        // and scaled 2x along x: x -> -2x -> (0, -2x) turned; y -> y -> (-y, 0).
        let model = Model {
            mirror: [true, false],
            rotation: std::f64::consts::FRAC_PI_2,
            log_scale: [2f64.ln(), 0.0],
            about: [0.0, 0.0],
            shift: [0.0, 0.0],
        };
        let a = model.matrix();
        let expected = [[0.0, -1.0], [-2.0, 0.0]];
        for (row, want) in a.iter().zip(expected) {
            assert!(close(*row, want), "{a:?}");
        }
    }

    #[test]
    fn the_inverse_matrix_undoes_the_matrix() {
        for model in models() {
            let (a, b) = (model.matrix(), model.inverse_matrix());
            let product = [0, 1].map(|i| [0, 1].map(|j| a[i][0] * b[0][j] + a[i][1] * b[1][j]));
            for (row, identity) in product.iter().zip([[1.0, 0.0], [0.0, 1.0]]) {
                assert!(close(*row, identity), "{model:?}: {product:?}");
            }
        }
    }

    #[test]
    fn the_preimage_of_a_points_image_is_the_point() {
        for model in models() {
            let inverse = model.inverse_matrix();
            for x in [[0.0, 0.0], [13.5, -4.0], [100.0, 75.0]] {
                assert!(close(model.preimage(&inverse, forward(&model, x)), x));
            }
        }
    }

    #[test]
    fn written_about_another_point_the_transform_moves_every_point_alike() {
        for model in models() {
            let moved = model.about_point([-12.0, 60.0]);
            assert_eq!(moved.about, [-12.0, 60.0]);
            assert_eq!(moved.matrix(), model.matrix());
            for x in [[0.0, 0.0], [13.5, -4.0], [100.0, 75.0]] {
                assert!(close(forward(&moved, x), forward(&model, x)));
            }
        }
    }

    #[test]
    fn a_scale_or_a_turn_has_a_fixed_point_and_a_move_or_a_lone_mirror_has_none() {
        for model in models() {
            let linear = model.rotation.abs() >= 0.05 || model.log_scale != [0.0, 0.0];
            match model.fixed_point() {
                Some(p) => {
                    let image = forward(&model, p);
                    assert!((image[0] - p[0]).abs() < 1e-9, "{model:?}");
                    assert!((image[1] - p[1]).abs() < 1e-9, "{model:?}");
                }
                None => assert!(!linear || model.mirror != [false, false], "{model:?}"),
            }
        }
        let moved = Model {
            shift: [5.0, 0.0],
            ..Model::identity([0.0, 0.0])
        };
        assert_eq!(moved.fixed_point(), None);
        // A mirror alone leaves a whole line where it is: no single point names it.
        let mirrored = Model {
            mirror: [true, false],
            ..Model::identity([30.0, 30.0])
        };
        assert_eq!(mirrored.fixed_point(), None);
        // Half a percent of scale is too little to name a point.
        let barely = Model {
            log_scale: [0.005f64.ln_1p(); 2],
            shift: [1.0, 0.0],
            ..Model::identity([0.0, 0.0])
        };
        assert_eq!(barely.fixed_point(), None);
    }
}

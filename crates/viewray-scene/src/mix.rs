//! How two cameras written in a scene file mix, field by field as written: what makes an
//! animation's keys into the camera between them.

use crate::CameraSpec;
use crate::camera::CameraDef;
use crate::schema::{
    ExplicitCamera, FisheyeDef, ObliqueDef, OrthographicDef, PerspectiveDef, PresetDef,
    ProjectionDef, ThinLensDef, V2, V3,
};

impl CameraSpec {
    /// The camera `s` of the way from `self` to `other`, field by field:
    ///
    /// ```text
    /// field = (1 - s) self.field + s other.field
    /// ```
    ///
    /// exactly `self` at `s = 0` and `other` at `s = 1`.
    ///
    /// # Errors
    /// The two are written differently (another projection family or preset, one
    /// aimed with `look_at` and the other with `view`, a viewport against a field of
    /// view), so they have no fields in common to mix; the message says which.
    pub fn mix(&self, other: &CameraSpec, s: f64) -> Result<CameraSpec, String> {
        Ok(CameraSpec(match (&self.0, &other.0) {
            (CameraDef::Explicit(a), CameraDef::Explicit(b)) => {
                CameraDef::Explicit(Box::new(mix_explicit(a, b, s)?))
            }
            (CameraDef::Preset(a), CameraDef::Preset(b)) => CameraDef::Preset(mix_preset(a, b, s)?),
            (CameraDef::Explicit(_), CameraDef::Preset(b)) => {
                return Err(explicit_and_preset(preset_name(b)));
            }
            (CameraDef::Preset(a), CameraDef::Explicit(_)) => {
                return Err(explicit_and_preset(preset_name(a)));
            }
        }))
    }
}

fn explicit_and_preset(preset: &str) -> String {
    format!(
        "cannot interpolate an explicit camera `(eye: ..)` and the preset `{preset}`: \
         write both keys the same way"
    )
}

/// Values that mix linearly, `(1 - s) a + s b`.
trait Mix: Sized {
    fn mix(&self, other: &Self, s: f64) -> Self;
}

impl Mix for f64 {
    fn mix(&self, other: &f64, s: f64) -> f64 {
        (1.0 - s) * self + s * other
    }
}

impl Mix for V2 {
    fn mix(&self, other: &V2, s: f64) -> V2 {
        (self.0.mix(&other.0, s), self.1.mix(&other.1, s))
    }
}

impl Mix for V3 {
    fn mix(&self, other: &V3, s: f64) -> V3 {
        (
            self.0.mix(&other.0, s),
            self.1.mix(&other.1, s),
            self.2.mix(&other.2, s),
        )
    }
}

/// Mixes an optional field: both given, or both left out.
fn mix_option<T: Mix + Copy>(
    name: &str,
    a: Option<T>,
    b: Option<T>,
    s: f64,
) -> Result<Option<T>, String> {
    match (a, b) {
        (Some(a), Some(b)) => Ok(Some(a.mix(&b, s))),
        (None, None) => Ok(None),
        _ => Err(format!(
            "one key gives `{name}` and the other does not: write the camera the same \
             way in both keys to interpolate it"
        )),
    }
}

/// A field that cannot be mixed (a choice, such as `fit`): the same in both keys.
fn same<T: PartialEq + Copy + std::fmt::Debug>(
    name: &str,
    a: Option<T>,
    b: Option<T>,
) -> Result<Option<T>, String> {
    if a == b {
        Ok(a)
    } else {
        Err(format!(
            "the keys give different `{name}`: it is a choice, not a number, so every key of \
             an animation gives the same"
        ))
    }
}

fn mix_explicit(a: &ExplicitCamera, b: &ExplicitCamera, s: f64) -> Result<ExplicitCamera, String> {
    Ok(ExplicitCamera {
        eye: a.eye.mix(&b.eye, s),
        look_at: mix_option("look_at", a.look_at, b.look_at, s)?,
        view: mix_option("view", a.view, b.view, s)?,
        up: a.up.mix(&b.up, s),
        projection: mix_projection(&a.projection, &b.projection, s)?,
    })
}

fn mix_projection(a: &ProjectionDef, b: &ProjectionDef, s: f64) -> Result<ProjectionDef, String> {
    use ProjectionDef as P;
    Ok(match (a, b) {
        (P::Perspective(a), P::Perspective(b)) => P::Perspective(mix_perspective(a, b, s)?),
        (P::ThinLens(a), P::ThinLens(b)) => P::ThinLens(ThinLensDef {
            perspective: mix_perspective(&a.perspective, &b.perspective, s)?,
            aperture: mix_option("aperture", a.aperture, b.aperture, s)?,
            f_number: mix_option("f_number", a.f_number, b.f_number, s)?,
            focus: a.focus.mix(&b.focus, s),
            lens_tilt: a.lens_tilt.mix(&b.lens_tilt, s),
            lens_swing: a.lens_swing.mix(&b.lens_swing, s),
            blades: same("blades", Some(a.blades), Some(b.blades))?.unwrap_or(a.blades),
            blade_rotation: a.blade_rotation.mix(&b.blade_rotation, s),
        }),
        (P::Orthographic(a), P::Orthographic(b)) => P::Orthographic(OrthographicDef {
            viewport: mix_option("viewport", a.viewport, b.viewport, s)?,
            height: mix_option("height", a.height, b.height, s)?,
            aperture: mix_option("aperture", a.aperture, b.aperture, s)?,
            focus: mix_option("focus", a.focus, b.focus, s)?,
        }),
        (P::Oblique(a), P::Oblique(b)) => P::Oblique(ObliqueDef {
            viewport: mix_option("viewport", a.viewport, b.viewport, s)?,
            height: mix_option("height", a.height, b.height, s)?,
            ratio: a.ratio.mix(&b.ratio, s),
            angle: a.angle.mix(&b.angle, s),
        }),
        (P::Equirectangular, P::Equirectangular) => P::Equirectangular,
        (P::Fisheye(a), P::Fisheye(b)) => P::Fisheye(FisheyeDef {
            fov: a.fov.mix(&b.fov, s),
        }),
        _ => {
            return Err(format!(
                "cannot interpolate between the projection families `{}` and `{}`: the \
                 keys of an animation share one family (`viewray animate --demo \
                 perspective-to-orthographic` shows a path between two)",
                projection_name(a),
                projection_name(b)
            ));
        }
    })
}

/// The perspective window's fields mixed, the first not given alike in both named.
fn mix_perspective(
    a: &PerspectiveDef,
    b: &PerspectiveDef,
    s: f64,
) -> Result<PerspectiveDef, String> {
    Ok(PerspectiveDef {
        distance: mix_option("distance", a.distance, b.distance, s)?,
        viewport: mix_option("viewport", a.viewport, b.viewport, s)?,
        fov_x: mix_option("fov_x", a.fov_x, b.fov_x, s)?,
        fov_y: mix_option("fov_y", a.fov_y, b.fov_y, s)?,
        fov_diagonal: mix_option("fov_diagonal", a.fov_diagonal, b.fov_diagonal, s)?,
        fov_smaller: mix_option("fov_smaller", a.fov_smaller, b.fov_smaller, s)?,
        fov_larger: mix_option("fov_larger", a.fov_larger, b.fov_larger, s)?,
        focal_length: mix_option("focal_length", a.focal_length, b.focal_length, s)?,
        sensor: mix_option("sensor", a.sensor, b.sensor, s)?,
        fit: same("fit", a.fit, b.fit)?,
        shift: a.shift.mix(&b.shift, s),
    })
}

fn projection_name(def: &ProjectionDef) -> &'static str {
    match def {
        ProjectionDef::Perspective { .. } => "Perspective",
        ProjectionDef::ThinLens { .. } => "ThinLens",
        ProjectionDef::Orthographic { .. } => "Orthographic",
        ProjectionDef::Oblique { .. } => "Oblique",
        ProjectionDef::Equirectangular => "Equirectangular",
        ProjectionDef::Fisheye { .. } => "Fisheye",
    }
}

fn mix_preset(a: &PresetDef, b: &PresetDef, s: f64) -> Result<PresetDef, String> {
    use PresetDef as P;
    let target = |t0: &V3, t1: &V3| t0.mix(t1, s);
    Ok(match (a, b) {
        (
            P::Front {
                target: t0,
                size: z0,
            },
            P::Front {
                target: t1,
                size: z1,
            },
        ) => P::Front {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Top {
                target: t0,
                size: z0,
            },
            P::Top {
                target: t1,
                size: z1,
            },
        ) => P::Top {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Side {
                target: t0,
                size: z0,
            },
            P::Side {
                target: t1,
                size: z1,
            },
        ) => P::Side {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Isometric {
                target: t0,
                size: z0,
            },
            P::Isometric {
                target: t1,
                size: z1,
            },
        ) => P::Isometric {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Dimetric {
                target: t0,
                size: z0,
            },
            P::Dimetric {
                target: t1,
                size: z1,
            },
        ) => P::Dimetric {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Trimetric {
                target: t0,
                size: z0,
            },
            P::Trimetric {
                target: t1,
                size: z1,
            },
        ) => P::Trimetric {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::Cavalier {
                target: t0,
                size: z0,
                angle: a0,
            },
            P::Cavalier {
                target: t1,
                size: z1,
                angle: a1,
            },
        ) => P::Cavalier {
            target: target(t0, t1),
            size: z0.mix(z1, s),
            angle: a0.mix(a1, s),
        },
        (
            P::Cabinet {
                target: t0,
                size: z0,
                angle: a0,
            },
            P::Cabinet {
                target: t1,
                size: z1,
                angle: a1,
            },
        ) => P::Cabinet {
            target: target(t0, t1),
            size: z0.mix(z1, s),
            angle: a0.mix(a1, s),
        },
        (
            P::OnePoint {
                target: t0,
                size: z0,
            },
            P::OnePoint {
                target: t1,
                size: z1,
            },
        ) => P::OnePoint {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::TwoPoint {
                target: t0,
                size: z0,
            },
            P::TwoPoint {
                target: t1,
                size: z1,
            },
        ) => P::TwoPoint {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        (
            P::ThreePoint {
                target: t0,
                size: z0,
            },
            P::ThreePoint {
                target: t1,
                size: z1,
            },
        ) => P::ThreePoint {
            target: target(t0, t1),
            size: z0.mix(z1, s),
        },
        _ => {
            return Err(format!(
                "cannot interpolate the preset `{}` and the preset `{}`: the keys of an \
                 animation use one preset",
                preset_name(a),
                preset_name(b)
            ));
        }
    })
}

fn preset_name(def: &PresetDef) -> &'static str {
    match def {
        PresetDef::Front { .. } => "Front",
        PresetDef::Top { .. } => "Top",
        PresetDef::Side { .. } => "Side",
        PresetDef::Isometric { .. } => "Isometric",
        PresetDef::Dimetric { .. } => "Dimetric",
        PresetDef::Trimetric { .. } => "Trimetric",
        PresetDef::Cavalier { .. } => "Cavalier",
        PresetDef::Cabinet { .. } => "Cabinet",
        PresetDef::OnePoint { .. } => "OnePoint",
        PresetDef::TwoPoint { .. } => "TwoPoint",
        PresetDef::ThreePoint { .. } => "ThreePoint",
    }
}

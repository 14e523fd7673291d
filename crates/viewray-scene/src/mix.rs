//! How two cameras written in a scene file mix, field by field as written: what makes an
//! animation's keys into the camera between them.

use crate::CameraSpec;
use crate::camera::CameraDef;
use crate::schema::{ExplicitCamera, PresetDef, ProjectionDef, V2, V3};

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
        (
            P::Perspective {
                distance: d0,
                viewport: vp0,
                fov_x: fx0,
                fov_y: fy0,
                fov_diagonal: fd0,
                fov_smaller: fs0,
                fov_larger: fl0,
                focal_length: fo0,
                sensor: se0,
                fit: fit0,
                shift: s0,
            },
            P::Perspective {
                distance: d1,
                viewport: vp1,
                fov_x: fx1,
                fov_y: fy1,
                fov_diagonal: fd1,
                fov_smaller: fs1,
                fov_larger: fl1,
                focal_length: fo1,
                sensor: se1,
                fit: fit1,
                shift: s1,
            },
        ) => P::Perspective {
            distance: mix_option("distance", *d0, *d1, s)?,
            viewport: mix_option("viewport", *vp0, *vp1, s)?,
            fov_x: mix_option("fov_x", *fx0, *fx1, s)?,
            fov_y: mix_option("fov_y", *fy0, *fy1, s)?,
            fov_diagonal: mix_option("fov_diagonal", *fd0, *fd1, s)?,
            fov_smaller: mix_option("fov_smaller", *fs0, *fs1, s)?,
            fov_larger: mix_option("fov_larger", *fl0, *fl1, s)?,
            focal_length: mix_option("focal_length", *fo0, *fo1, s)?,
            sensor: mix_option("sensor", *se0, *se1, s)?,
            fit: same("fit", *fit0, *fit1)?,
            shift: s0.mix(s1, s),
        },
        (
            P::ThinLens {
                distance: d0,
                viewport: vp0,
                fov_x: fx0,
                fov_y: fy0,
                fov_diagonal: fd0,
                fov_smaller: fs0,
                fov_larger: fl0,
                focal_length: fo0,
                sensor: se0,
                fit: fit0,
                shift: s0,
                aperture: a0,
                f_number: n0,
                focus: f0,
            },
            P::ThinLens {
                distance: d1,
                viewport: vp1,
                fov_x: fx1,
                fov_y: fy1,
                fov_diagonal: fd1,
                fov_smaller: fs1,
                fov_larger: fl1,
                focal_length: fo1,
                sensor: se1,
                fit: fit1,
                shift: s1,
                aperture: a1,
                f_number: n1,
                focus: f1,
            },
        ) => P::ThinLens {
            distance: mix_option("distance", *d0, *d1, s)?,
            viewport: mix_option("viewport", *vp0, *vp1, s)?,
            fov_x: mix_option("fov_x", *fx0, *fx1, s)?,
            fov_y: mix_option("fov_y", *fy0, *fy1, s)?,
            fov_diagonal: mix_option("fov_diagonal", *fd0, *fd1, s)?,
            fov_smaller: mix_option("fov_smaller", *fs0, *fs1, s)?,
            fov_larger: mix_option("fov_larger", *fl0, *fl1, s)?,
            focal_length: mix_option("focal_length", *fo0, *fo1, s)?,
            sensor: mix_option("sensor", *se0, *se1, s)?,
            fit: same("fit", *fit0, *fit1)?,
            shift: s0.mix(s1, s),
            aperture: mix_option("aperture", *a0, *a1, s)?,
            f_number: mix_option("f_number", *n0, *n1, s)?,
            focus: f0.mix(f1, s),
        },
        (
            P::Orthographic {
                viewport: vp0,
                height: h0,
                aperture: a0,
                focus: f0,
            },
            P::Orthographic {
                viewport: vp1,
                height: h1,
                aperture: a1,
                focus: f1,
            },
        ) => P::Orthographic {
            viewport: mix_option("viewport", *vp0, *vp1, s)?,
            height: mix_option("height", *h0, *h1, s)?,
            aperture: mix_option("aperture", *a0, *a1, s)?,
            focus: mix_option("focus", *f0, *f1, s)?,
        },
        (
            P::Oblique {
                viewport: vp0,
                height: h0,
                ratio: r0,
                angle: a0,
            },
            P::Oblique {
                viewport: vp1,
                height: h1,
                ratio: r1,
                angle: a1,
            },
        ) => P::Oblique {
            viewport: mix_option("viewport", *vp0, *vp1, s)?,
            height: mix_option("height", *h0, *h1, s)?,
            ratio: r0.mix(r1, s),
            angle: a0.mix(a1, s),
        },
        (P::Equirectangular, P::Equirectangular) => P::Equirectangular,
        (P::Fisheye { fov: f0 }, P::Fisheye { fov: f1 }) => P::Fisheye { fov: f0.mix(f1, s) },
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

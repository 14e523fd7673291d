//! A scene file's values checked and converted for the renderer: points, directions,
//! positive numbers and colours (each finite as the `f32` the tracer uses), materials,
//! lights, a mesh's transform, and the image's size and samples. Errors are sentences naming the field, which the loader
//! places in the file.

use glam::{Affine3A, Quat, Vec3};
use viewray_camera::{ImageLimitError, ImageLimits};

use crate::schema::{ImageDef, LightDef, MaterialDef, Scale, Specular, TransformDef, V3};
use crate::{Grid, Light, Material};

/// A finite `f64` that stays finite as the `f32` the tracer uses.
fn finite32(name: &str, x: f64) -> Result<f32, String> {
    #[allow(clippy::cast_possible_truncation)]
    let y = x as f32;
    if y.is_finite() {
        Ok(y)
    } else {
        Err(format!("{name} must be a finite number, found {x}"))
    }
}

/// A point or vector `name`, each coordinate finite as an `f32`.
pub(crate) fn point(name: &str, (x, y, z): V3) -> Result<Vec3, String> {
    let v = Vec3::new(finite32(name, x)?, finite32(name, y)?, finite32(name, z)?);
    if v.is_finite() {
        Ok(v)
    } else {
        Err(format!("{name} must be finite, found ({x}, {y}, {z})"))
    }
}

/// A direction `name`, normalized: finite and not zero.
pub(crate) fn direction(name: &str, v: V3) -> Result<Vec3, String> {
    point(name, v)?
        .try_normalize()
        .ok_or_else(|| format!("{name} must not be the zero vector"))
}

/// A number `name` that is positive and finite as an `f32`.
pub(crate) fn positive(name: &str, x: f64) -> Result<f32, String> {
    let y = finite32(name, x)?;
    if y > 0.0 {
        Ok(y)
    } else {
        Err(format!("{name} must be positive, found {x}"))
    }
}

/// A linear RGB colour: finite and not negative.
pub(crate) fn color(v: V3) -> Result<Vec3, String> {
    let c = point("colour", v)?;
    if c.min_element() < 0.0 {
        return Err(format!(
            "colours cannot be negative, found ({}, {}, {})",
            v.0, v.1, v.2
        ));
    }
    Ok(c)
}

/// A material, its optional fields defaulted: no specular, no mirror, no grid.
pub(crate) fn material(def: &MaterialDef) -> Result<Material, String> {
    let specular = match def.specular {
        None => Vec3::ZERO,
        Some(Specular::Grey(g)) => color((g, g, g))?,
        Some(Specular::Color(c)) => color(c)?,
    };
    let shininess = match def.shininess {
        None => Material::default().shininess,
        Some(s) => positive("shininess", s)?,
    };
    let mirror = finite32("mirror", def.mirror)?;
    if !(0.0..=1.0).contains(&mirror) {
        return Err(format!(
            "mirror must be between 0 and 1, found {}",
            def.mirror
        ));
    }
    let grid = match &def.grid {
        None => None,
        Some(grid) => {
            let spacing = positive("grid spacing", grid.spacing)?;
            let line_width = positive("grid width", grid.width)?;
            if line_width >= spacing {
                return Err(format!(
                    "grid width {} must be smaller than its spacing {}",
                    grid.width, grid.spacing
                ));
            }
            Some(Grid {
                spacing,
                line_width,
                color: color(grid.color)?,
            })
        }
    };
    Ok(Material {
        color: color(def.color)?,
        specular,
        shininess,
        mirror,
        grid,
    })
}

/// A light, its position finite, its direction not zero and its intensity a colour.
pub(crate) fn light(def: &LightDef) -> Result<Light, String> {
    Ok(match *def {
        LightDef::Point {
            position,
            intensity,
        } => Light::Point {
            position: point("position", position)?,
            intensity: color(intensity)?,
        },
        LightDef::Directional {
            direction: d,
            intensity,
        } => Light::Directional {
            direction: direction("direction", d)?,
            intensity: color(intensity)?,
        },
        LightDef::Ambient { intensity } => Light::Ambient {
            intensity: color(intensity)?,
        },
    })
}

/// The transform of a mesh: scale, then rotate about x, y and z (degrees), then translate.
pub(crate) fn affine(def: &TransformDef) -> Result<Affine3A, String> {
    let scale = match def.scale {
        Scale::Uniform(s) => {
            let s = finite32("scale", s)?;
            Vec3::splat(s)
        }
        Scale::PerAxis(s) => point("scale", s)?,
    };
    if scale.cmpeq(Vec3::ZERO).any() {
        return Err("scale must not be zero on any axis".to_owned());
    }
    let rotate = point("rotate", def.rotate)?;
    let rotation = Quat::from_rotation_z(rotate.z.to_radians())
        * Quat::from_rotation_y(rotate.y.to_radians())
        * Quat::from_rotation_x(rotate.x.to_radians());
    let translate = point("translate", def.translate)?;
    Ok(Affine3A::from_scale_rotation_translation(
        scale, rotation, translate,
    ))
}

/// The image's size and samples, within viewray's limits ([`ImageLimits::VIEWRAY`]).
pub(crate) fn image(def: &ImageDef) -> Result<(u32, u32, u32), String> {
    let error = |error: ImageLimitError| format!("image: {error}");
    let limits = ImageLimits::VIEWRAY;
    let (width, height) = limits
        .check_size(u64::from(def.width), u64::from(def.height))
        .map_err(error)?;
    let samples = limits
        .check_samples(u64::from(def.samples))
        .map_err(error)?;
    Ok((width, height, samples))
}

//! The directives of the world: materials (`Material`, `MakeNamedMaterial`,
//! `NamedMaterial`), lights (`LightSource`) and shapes (`Shape`).

use glam::{DMat4, DVec3, Vec3};
use viewray_scene::{Material, ObjectDocument};

use super::{At, Importer, ReadLight};
use crate::ImportError;
use crate::common::viewray_intensity;
use crate::pbrt::parse::Params;

impl Importer<'_> {
    /// `Material "type" params`: an unnamed material, current from here on.
    pub(super) fn material(&mut self, at: At) -> Result<(), ImportError> {
        let kind = self.parser.kind("Material", at)?;
        let params = self.parser.params()?;
        let name = format!("material_{}", self.materials.len());
        self.state.material = Some(self.add_material(name, &params, &kind, at));
        Ok(())
    }

    /// `MakeNamedMaterial "name" params`.
    pub(super) fn make_named_material(&mut self, at: At) -> Result<(), ImportError> {
        let name = self.parser.kind("MakeNamedMaterial", at)?;
        let params = self.parser.params()?;
        let kind = params.string("type").unwrap_or("diffuse").to_owned();
        self.add_material(name, &params, &kind, at);
        Ok(())
    }

    /// `NamedMaterial "name"`: a material `MakeNamedMaterial` defined, current from here on.
    pub(super) fn named_material(&mut self, at: At) -> Result<(), ImportError> {
        let name = self.parser.kind("NamedMaterial", at)?;
        if !self.material_index.contains_key(&name) {
            return Err(self.error(
                at,
                format!("no material named \"{name}\" (MakeNamedMaterial defines one)"),
            ));
        }
        self.state.material = Some(name);
        Ok(())
    }

    /// Defines (or redefines) the material `name` from a pbrt material's parameters: its
    /// `rgb reflectance`, or grey with a comment.
    pub(super) fn add_material(
        &mut self,
        name: String,
        params: &Params,
        kind: &str,
        at: At,
    ) -> String {
        let color = match params.numbers("reflectance") {
            Some(([r, g, b], _)) => Vec3::new(*r as f32, *g as f32, *b as f32),
            Some(([g], _)) => Vec3::splat(*g as f32),
            _ => {
                self.comments.push(format!(
                    "line {}: material `{kind}` has no RGB reflectance viewray reads: grey 0.5",
                    at.0
                ));
                Vec3::splat(0.5)
            }
        };
        let material = Material {
            color: color.max(Vec3::ZERO),
            ..Material::default()
        };
        match self.material_index.get(&name) {
            Some(&i) => self.materials[i].1 = material,
            None => {
                self.material_index
                    .insert(name.clone(), self.materials.len());
                self.materials.push((name.clone(), material));
            }
        }
        name
    }

    /// `LightSource "type" params`: point, distant and infinite (constant) lights.
    pub(super) fn light_source(&mut self, at: At) -> Result<(), ImportError> {
        let kind = self.parser.kind("LightSource", at)?;
        let params = self.parser.params()?;
        let scale = params.number("scale").unwrap_or(1.0) as f32;
        let rgb = |name: &str| -> Option<Vec3> {
            match params.numbers(name) {
                Some(([r, g, b], _)) => Some(Vec3::new(*r as f32, *g as f32, *b as f32)),
                _ => None,
            }
        };
        let point3 = |name: &str, default: DVec3| -> DVec3 {
            match params.numbers(name) {
                Some(([x, y, z], _)) => DVec3::new(*x, *y, *z),
                _ => default,
            }
        };
        match kind.as_str() {
            "point" => self.lights.push(ReadLight::Point {
                position: self.state.ctm.transform_point3(point3("from", DVec3::ZERO)),
                intensity: viewray_intensity(rgb("I").unwrap_or(Vec3::ONE) * scale),
            }),
            "distant" => {
                let from = point3("from", DVec3::ZERO);
                let to = point3("to", DVec3::new(0.0, 0.0, 1.0));
                let direction = self.state.ctm.transform_vector3(to - from);
                let direction = direction.try_normalize().ok_or_else(|| {
                    self.error(at, "a distant light with from = to has no direction")
                })?;
                self.lights.push(ReadLight::Directional {
                    direction: direction.as_vec3(),
                    intensity: viewray_intensity(rgb("L").unwrap_or(Vec3::ONE) * scale),
                });
            }
            "infinite" if params.string("filename").is_none() => {
                self.background = rgb("L").unwrap_or(Vec3::ONE) * scale;
            }
            other => self
                .comments
                .push(format!("line {}: light \"{other}\" skipped", at.0)),
        }
        Ok(())
    }

    /// `Shape "type" params`: full spheres, triangle meshes and bilinear patches.
    pub(super) fn shape(&mut self, at: At) -> Result<(), ImportError> {
        let kind = self.parser.kind("Shape", at)?;
        let params = self.parser.params()?;
        if !self.in_world {
            return Err(self.error(at, "a Shape before WorldBegin"));
        }
        match kind.as_str() {
            "sphere" => {
                let radius = params.number("radius").unwrap_or(1.0);
                let partial = ["zmin", "zmax", "phimax"]
                    .iter()
                    .any(|n| params.numbers(n).is_some());
                if partial {
                    self.comments
                        .push(format!("line {}: a partial sphere skipped", at.0));
                } else {
                    self.objects.push((
                        ObjectDocument::Sphere {
                            center: Vec3::ZERO,
                            radius: radius as f32,
                            material: self.state.material.clone(),
                        },
                        self.state.ctm,
                    ));
                }
            }
            "trianglemesh" | "bilinearmesh" => self.mesh(&kind, &params, at)?,
            other => self
                .comments
                .push(format!("line {}: shape \"{other}\" skipped", at.0)),
        }
        Ok(())
    }

    /// A `trianglemesh` or `bilinearmesh` as triangles; a bilinear patch `p00 p10 p01
    /// p11` is two.
    pub(super) fn mesh(&mut self, kind: &str, params: &Params, at: At) -> Result<(), ImportError> {
        let Some((p, p_at)) = params.numbers("P") else {
            return Err(self.error(at, format!("a {kind} needs \"point3 P\"")));
        };
        if !p.len().is_multiple_of(3) {
            return Err(self.error(p_at, "\"point3 P\" needs a multiple of 3 numbers"));
        }
        let points: Vec<DVec3> = p
            .chunks_exact(3)
            .map(|c| DVec3::new(c[0], c[1], c[2]))
            .collect();
        let corners = if kind == "trianglemesh" { 3 } else { 4 };
        let indices: Vec<usize> = match params.numbers("indices") {
            Some((i, i_at)) => {
                if i.len() % corners != 0
                    || i.iter()
                        .any(|&k| k < 0.0 || k.fract() != 0.0 || k as usize >= points.len())
                {
                    return Err(self.error(
                        i_at,
                        format!("\"integer indices\" must be groups of {corners} indices into P"),
                    ));
                }
                i.iter().map(|&k| k as usize).collect()
            }
            None if points.len() == corners => (0..corners).collect(),
            None => {
                return Err(self.error(
                    at,
                    format!("a {kind} of more than {corners} points needs \"integer indices\""),
                ));
            }
        };
        for face in indices.chunks_exact(corners) {
            let triangles: Vec<[usize; 3]> = if corners == 3 {
                vec![[face[0], face[1], face[2]]]
            } else {
                vec![[face[0], face[1], face[3]], [face[0], face[3], face[2]]]
            };
            for t in triangles {
                let corners = t.map(|i| points[i].as_vec3());
                self.objects.push((
                    ObjectDocument::Triangle {
                        corners,
                        material: self.state.material.clone(),
                    },
                    self.state.ctm,
                ));
            }
        }
        Ok(())
    }
}

/// `object` placed by `m`; a sphere under a non-uniform scale is dropped with a comment.
pub(super) fn transform_object(
    object: ObjectDocument,
    m: DMat4,
    comments: &mut Vec<String>,
) -> Option<ObjectDocument> {
    match object {
        ObjectDocument::Sphere {
            center,
            radius,
            material,
        } => {
            let linear = glam::DMat3::from_mat4(m);
            let scale = linear.x_axis.length();
            let uniform = [linear.y_axis, linear.z_axis]
                .iter()
                .all(|a| (a.length() - scale).abs() <= 1e-9 * scale.max(1e-300));
            if !uniform {
                comments.push("a sphere scaled unevenly (an ellipsoid) skipped".to_owned());
                return None;
            }
            Some(ObjectDocument::Sphere {
                center: m.transform_point3(center.as_dvec3()).as_vec3(),
                radius: (f64::from(radius) * scale) as f32,
                material,
            })
        }
        ObjectDocument::Triangle { corners, material } => {
            let corners = corners.map(|c| m.transform_point3(c.as_dvec3()).as_vec3());
            let area = (corners[1] - corners[0]).cross(corners[2] - corners[0]);
            (area != Vec3::ZERO && area.is_finite())
                .then_some(ObjectDocument::Triangle { corners, material })
        }
        other => Some(other),
    }
}

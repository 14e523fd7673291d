//! `projection:`, the one value of a scene file whose variants share fields: a
//! `Perspective(..)` and a `ThinLens(..)` size and shift their window with the same
//! fields ([`PerspectiveDef`]), the thin lens adding its own.
//!
//! serde's derive cannot read one struct's fields inline among a variant's others
//! (`#[serde(flatten)]` buffers the values, which loses their positions and RON's words),
//! so the enum is read by hand: each variant's fields by a derived struct, straight from
//! RON's map of fields, and a thin lens's by [`PerspectiveDef`]'s own derived reader with
//! the lens's own fields taken out on the way. What a scene file's author reads is the
//! same as for a derived enum: the variant named in every error, and the full list of a
//! variant's fields for an unknown one.

use std::fmt;
use std::marker::PhantomData;
use std::sync::OnceLock;

use serde::Deserialize;
use serde::de::value::{MapAccessDeserializer, StrDeserializer};
use serde::de::{self, Deserializer, EnumAccess, MapAccess, VariantAccess, Visitor};

use super::{SensorFitDef, V2};

/// `projection: Perspective(..) | ThinLens(..) | Orthographic(..) | Oblique(..) |
/// Equirectangular | Fisheye(..)`.
#[derive(Clone, Debug, PartialEq)]
pub(crate) enum ProjectionDef {
    Perspective(PerspectiveDef),
    ThinLens(ThinLensDef),
    Orthographic(OrthographicDef),
    Oblique(ObliqueDef),
    Equirectangular,
    Fisheye(FisheyeDef),
}

/// The fields that size and shift a perspective window, written alike in
/// `Perspective(..)` and `ThinLens(..)`: one of `viewport`, a field of view (degrees) and
/// `focal_length` (mm, with `sensor` and `fit`), the `distance` d, and the `shift`.
#[derive(Deserialize, Clone, Copy, Debug, Default, PartialEq)]
#[serde(deny_unknown_fields, default)]
pub(crate) struct PerspectiveDef {
    pub(crate) distance: Option<f64>,
    pub(crate) viewport: Option<V2>,
    pub(crate) fov_x: Option<f64>,
    pub(crate) fov_y: Option<f64>,
    pub(crate) fov_diagonal: Option<f64>,
    pub(crate) fov_smaller: Option<f64>,
    pub(crate) fov_larger: Option<f64>,
    pub(crate) focal_length: Option<f64>,
    pub(crate) sensor: Option<V2>,
    pub(crate) fit: Option<SensorFitDef>,
    pub(crate) shift: V2,
}

/// `ThinLens(..)`: a perspective window and the lens, its radius `aperture` (or an
/// `f_number`) and its `focus` distance, its tilt and swing, and its blades.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct ThinLensDef {
    pub(crate) perspective: PerspectiveDef,
    pub(crate) aperture: Option<f64>,
    pub(crate) f_number: Option<f64>,
    pub(crate) focus: f64,
    /// Degrees, about `u`; a physical camera's only. 0 when not given.
    pub(crate) lens_tilt: f64,
    /// Degrees, about `v`; a physical camera's only. 0 when not given.
    pub(crate) lens_swing: f64,
    /// 0 (round, when not given) or 3 to 64.
    pub(crate) blades: u32,
    /// Degrees, any angle (wrapped). 0 when not given.
    pub(crate) blade_rotation: f64,
}

/// The lens's own fields, which follow the perspective ones in `ThinLens(..)`'s list.
const LENS_FIELDS: [&str; 7] = [
    "aperture",
    "f_number",
    "focus",
    "lens_tilt",
    "lens_swing",
    "blades",
    "blade_rotation",
];

/// `Orthographic(viewport: .. | height: .., aperture: .., focus: ..)`.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct OrthographicDef {
    #[serde(default)]
    pub(crate) viewport: Option<V2>,
    #[serde(default)]
    pub(crate) height: Option<f64>,
    #[serde(default)]
    pub(crate) aperture: Option<f64>,
    #[serde(default)]
    pub(crate) focus: Option<f64>,
}

/// `Oblique(viewport: .. | height: .., ratio: .., angle: ..)`.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct ObliqueDef {
    #[serde(default)]
    pub(crate) viewport: Option<V2>,
    #[serde(default)]
    pub(crate) height: Option<f64>,
    pub(crate) ratio: f64,
    /// Degrees.
    pub(crate) angle: f64,
}

/// `Fisheye(fov: ..)`.
#[derive(Deserialize, Clone, Copy, Debug, PartialEq)]
#[serde(deny_unknown_fields)]
pub(crate) struct FisheyeDef {
    /// Degrees.
    pub(crate) fov: f64,
}

/// The variants' names, as scene files write them.
#[derive(Deserialize)]
#[serde(variant_identifier)]
enum Family {
    Perspective,
    ThinLens,
    Orthographic,
    Oblique,
    Equirectangular,
    Fisheye,
}

const FAMILIES: &[&str] = &[
    "Perspective",
    "ThinLens",
    "Orthographic",
    "Oblique",
    "Equirectangular",
    "Fisheye",
];

impl<'de> Deserialize<'de> for ProjectionDef {
    fn deserialize<D: Deserializer<'de>>(deserializer: D) -> Result<Self, D::Error> {
        deserializer.deserialize_enum("projection", FAMILIES, ProjectionVisitor)
    }
}

struct ProjectionVisitor;

impl<'de> Visitor<'de> for ProjectionVisitor {
    type Value = ProjectionDef;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a projection")
    }

    fn visit_enum<A: EnumAccess<'de>>(self, data: A) -> Result<ProjectionDef, A::Error> {
        // RON reads a struct variant's fields by their names, not from a list given here.
        let (family, variant) = data.variant()?;
        Ok(match family {
            Family::Perspective => {
                ProjectionDef::Perspective(variant.struct_variant(&[], FieldsOf::default())?)
            }
            Family::ThinLens => {
                ProjectionDef::ThinLens(variant.struct_variant(&[], ThinLensVisitor)?)
            }
            Family::Orthographic => {
                ProjectionDef::Orthographic(variant.struct_variant(&[], FieldsOf::default())?)
            }
            Family::Oblique => {
                ProjectionDef::Oblique(variant.struct_variant(&[], FieldsOf::default())?)
            }
            Family::Equirectangular => {
                variant.unit_variant()?;
                ProjectionDef::Equirectangular
            }
            Family::Fisheye => {
                ProjectionDef::Fisheye(variant.struct_variant(&[], FieldsOf::default())?)
            }
        })
    }
}

/// Reads a struct variant's fields as the derived struct `T` reads its own.
struct FieldsOf<T>(PhantomData<T>);

impl<T> Default for FieldsOf<T> {
    fn default() -> Self {
        Self(PhantomData)
    }
}

impl<'de, T: Deserialize<'de>> Visitor<'de> for FieldsOf<T> {
    type Value = T;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a projection's fields")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<T, A::Error> {
        T::deserialize(MapAccessDeserializer::new(map))
    }
}

/// Reads `ThinLens(..)`: the lens's fields taken out of the map, the rest read as a
/// [`PerspectiveDef`].
struct ThinLensVisitor;

impl<'de> Visitor<'de> for ThinLensVisitor {
    type Value = ThinLensDef;

    fn expecting(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str("a thin lens's fields")
    }

    fn visit_map<A: MapAccess<'de>>(self, map: A) -> Result<ThinLensDef, A::Error> {
        let mut fields = LensTakenOut {
            map,
            aperture: None,
            f_number: None,
            focus: None,
            lens_tilt: None,
            lens_swing: None,
            blades: None,
            blade_rotation: None,
        };
        let perspective = PerspectiveDef::deserialize(MapAccessDeserializer::new(&mut fields))?;
        Ok(ThinLensDef {
            perspective,
            aperture: fields.aperture.flatten(),
            f_number: fields.f_number.flatten(),
            focus: fields
                .focus
                .ok_or_else(|| de::Error::missing_field("focus"))?,
            lens_tilt: fields.lens_tilt.unwrap_or(0.0),
            lens_swing: fields.lens_swing.unwrap_or(0.0),
            blades: fields.blades.unwrap_or(0),
            blade_rotation: fields.blade_rotation.unwrap_or(0.0),
        })
    }
}

/// A thin lens's map of fields with the lens's own taken out as they go by (each read
/// once, as a derived struct reads its fields): what is left is a perspective window's.
struct LensTakenOut<A> {
    map: A,
    /// `Some` once given (`Some(None)` for `aperture: None`).
    aperture: Option<Option<f64>>,
    f_number: Option<Option<f64>>,
    focus: Option<f64>,
    lens_tilt: Option<f64>,
    lens_swing: Option<f64>,
    blades: Option<u32>,
    blade_rotation: Option<f64>,
}

impl<'de, A: MapAccess<'de>> MapAccess<'de> for LensTakenOut<A> {
    type Error = A::Error;

    fn next_key_seed<K: de::DeserializeSeed<'de>>(
        &mut self,
        seed: K,
    ) -> Result<Option<K::Value>, A::Error> {
        loop {
            let Some(name) = self.map.next_key::<String>()? else {
                return Ok(None);
            };
            match name.as_str() {
                "aperture" => self.aperture = Some(take(&mut self.map, "aperture", self.aperture)?),
                "f_number" => self.f_number = Some(take(&mut self.map, "f_number", self.f_number)?),
                "focus" => self.focus = Some(take(&mut self.map, "focus", self.focus)?),
                "lens_tilt" => {
                    self.lens_tilt = Some(take(&mut self.map, "lens_tilt", self.lens_tilt)?);
                }
                "lens_swing" => {
                    self.lens_swing = Some(take(&mut self.map, "lens_swing", self.lens_swing)?);
                }
                "blades" => self.blades = Some(take(&mut self.map, "blades", self.blades)?),
                "blade_rotation" => {
                    self.blade_rotation =
                        Some(take(&mut self.map, "blade_rotation", self.blade_rotation)?);
                }
                _ => {
                    return seed
                        .deserialize(StrDeserializer::<FieldName>::new(&name))
                        .map(Some)
                        .map_err(|error| match error {
                            FieldName::Unknown { expected } => {
                                de::Error::unknown_field(&name, thin_lens_fields(expected))
                            }
                            FieldName::Other(message) => de::Error::custom(message),
                        });
                }
            }
        }
    }

    fn next_value_seed<V: de::DeserializeSeed<'de>>(
        &mut self,
        seed: V,
    ) -> Result<V::Value, A::Error> {
        self.map.next_value_seed(seed)
    }
}

/// The value of the lens field `name`, which must not have been given before.
fn take<'de, A: MapAccess<'de>, T: Deserialize<'de>>(
    map: &mut A,
    name: &'static str,
    before: Option<T>,
) -> Result<T, A::Error> {
    if before.is_some() {
        return Err(de::Error::duplicate_field(name));
    }
    map.next_value()
}

/// `ThinLens(..)`'s fields in order: the perspective window's `window` (as its derived
/// reader lists them), then the lens's.
fn thin_lens_fields(window: &'static [&'static str]) -> &'static [&'static str] {
    static FIELDS: OnceLock<Vec<&'static str>> = OnceLock::new();
    FIELDS.get_or_init(|| window.iter().chain(&LENS_FIELDS).copied().collect())
}

/// What a derived struct's field reader says about a field name handed to it: an
/// unknown name comes back with the struct's list of fields.
#[derive(Debug)]
enum FieldName {
    Unknown { expected: &'static [&'static str] },
    Other(String),
}

impl fmt::Display for FieldName {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            FieldName::Unknown { expected } => write!(f, "unknown field, expected {expected:?}"),
            FieldName::Other(message) => f.write_str(message),
        }
    }
}

impl std::error::Error for FieldName {}

impl de::Error for FieldName {
    fn custom<T: fmt::Display>(message: T) -> Self {
        FieldName::Other(message.to_string())
    }

    fn unknown_field(_field: &str, expected: &'static [&'static str]) -> Self {
        FieldName::Unknown { expected }
    }
}

//! Mitsuba's XML values: properties by name, `$name` substituted from `<default>`s,
//! numbers, vectors, colours and `to_world` transforms, with errors at the element.

use glam::{DMat3, DMat4, DVec3, Vec3};

use super::import::Reader;
use crate::ImportError;

/// An element of the document.
pub(super) type Node<'a, 'input> = roxmltree::Node<'a, 'input>;

impl<'a, 'input> Reader<'a, 'input> {
    /// The 1-based line where `node` starts.
    pub(super) fn line(&self, node: Node<'_, '_>) -> u32 {
        self.document.text_pos_at(node.range().start).row
    }

    /// An error at `node`'s line and column.
    pub(super) fn error(&self, node: Node<'_, '_>, message: impl Into<String>) -> ImportError {
        let pos = self.document.text_pos_at(node.range().start);
        ImportError::new(
            self.path,
            Some((pos.row as usize, pos.col as usize)),
            message,
        )
    }

    /// An attribute, with `$name` replaced by its `<default>`.
    pub(super) fn attribute<'s>(
        &'s self,
        node: Node<'s, 's>,
        name: &str,
    ) -> Result<&'s str, ImportError> {
        let value = node.attribute(name).ok_or_else(|| {
            self.error(
                node,
                format!("<{}> needs a `{name}` attribute", node.tag_name().name()),
            )
        })?;
        Ok(self.substitute(value))
    }

    /// `value`, or what its `$name` stands for.
    pub(super) fn substitute<'s>(&'s self, value: &'s str) -> &'s str {
        match value.strip_prefix('$') {
            Some(name) => self.defaults.get(name).map_or(value, String::as_str),
            None => value,
        }
    }

    /// The child property element named `name` (`<float name="fov" ..>`).
    pub(super) fn property(&self, node: Node<'a, 'input>, name: &str) -> Option<Node<'a, 'input>> {
        node.children()
            .filter(Node::is_element)
            .find(|c| c.attribute("name") == Some(name))
    }

    /// The number in `node`'s `value`.
    pub(super) fn float(&self, node: Node<'_, '_>) -> Result<f64, ImportError> {
        let text = self.attribute(node, "value")?;
        parse_number(text)
            .ok_or_else(|| self.error(node, format!("expected a number, found `{text}`")))
    }

    /// The number of the property `name` of `parent`, if it has one.
    pub(super) fn float_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<f64>, ImportError> {
        self.property(parent, name)
            .map(|n| self.float(n))
            .transpose()
    }

    /// The positive whole number of the property `name` of `parent`, if it has one.
    pub(super) fn integer_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<u32>, ImportError> {
        match self.property(parent, name) {
            None => Ok(None),
            Some(node) => {
                let text = self.attribute(node, "value")?;
                text.trim()
                    .parse::<u32>()
                    .ok()
                    .filter(|&v| v > 0)
                    .map(Some)
                    .ok_or_else(|| {
                        self.error(
                            node,
                            format!("expected a positive whole number, found `{text}`"),
                        )
                    })
            }
        }
    }

    /// The `value` of the property `name` of `parent`, if it has one.
    pub(super) fn string_property(
        &self,
        parent: Node<'a, 'input>,
        name: &str,
    ) -> Result<Option<String>, ImportError> {
        self.property(parent, name)
            .map(|n| self.attribute(n, "value").map(str::to_owned))
            .transpose()
    }

    /// `x`, `y`, `z` attributes or `value="x, y, z"` (one number for all three).
    pub(super) fn vector(&self, node: Node<'_, '_>, default: f64) -> Result<DVec3, ImportError> {
        if let Some(value) = node.attribute("value") {
            return self.triple(node, self.substitute(value));
        }
        let mut v = [default; 3];
        for (slot, name) in v.iter_mut().zip(["x", "y", "z"]) {
            if let Some(text) = node.attribute(name) {
                let text = self.substitute(text);
                *slot = parse_number(text).ok_or_else(|| {
                    self.error(
                        node,
                        format!("expected a number for `{name}`, found `{text}`"),
                    )
                })?;
            }
        }
        Ok(DVec3::from_array(v))
    }

    /// One number (for all three) or three, from `text`.
    pub(super) fn triple(&self, node: Node<'_, '_>, text: &str) -> Result<DVec3, ImportError> {
        let numbers = numbers(text)
            .ok_or_else(|| self.error(node, format!("expected numbers, found `{text}`")))?;
        match numbers.as_slice() {
            [x] => Ok(DVec3::splat(*x)),
            [x, y, z] => Ok(DVec3::new(*x, *y, *z)),
            _ => Err(self.error(
                node,
                format!("expected one or three numbers, found {}", numbers.len()),
            )),
        }
    }

    /// An RGB colour from `<rgb value="r, g, b">` or `<float value="g">`.
    pub(super) fn color(&self, node: Node<'_, '_>) -> Result<Option<Vec3>, ImportError> {
        match node.tag_name().name() {
            "rgb" | "float" => {
                let text = self.attribute(node, "value")?;
                Ok(Some(self.triple(node, text)?.as_vec3()))
            }
            _ => Ok(None),
        }
    }

    /// The transform of `<transform name="to_world">` under `parent`; identity if absent.
    pub(super) fn to_world(&self, parent: Node<'_, '_>) -> Result<DMat4, ImportError> {
        let Some(node) = parent
            .children()
            .find(|c| c.has_tag_name("transform") && c.attribute("name") == Some("to_world"))
        else {
            return Ok(DMat4::IDENTITY);
        };
        let mut m = DMat4::IDENTITY;
        for op in node.children().filter(Node::is_element) {
            let step = match op.tag_name().name() {
                "translate" => DMat4::from_translation(self.vector(op, 0.0)?),
                "scale" => DMat4::from_scale(self.vector(op, 1.0)?),
                "rotate" => {
                    let axis = self.vector(op, 0.0)?;
                    let angle = parse_number(self.attribute(op, "angle")?)
                        .ok_or_else(|| self.error(op, "expected a number for `angle`"))?;
                    let axis = axis
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "the rotation axis is zero"))?;
                    DMat4::from_axis_angle(axis, angle.to_radians())
                }
                "matrix" => {
                    let text = self.attribute(op, "value")?;
                    let values = numbers(text).ok_or_else(|| {
                        self.error(op, format!("expected numbers, found `{text}`"))
                    })?;
                    match values.len() {
                        16 => DMat4::from_cols_array(&values.try_into().expect("16")).transpose(),
                        9 => DMat4::from_mat3(
                            DMat3::from_cols_array(&values.try_into().expect("9")).transpose(),
                        ),
                        n => {
                            return Err(self.error(
                                op,
                                format!("a matrix needs 16 (or 9) numbers, found {n}"),
                            ));
                        }
                    }
                }
                "lookat" => {
                    let origin = self.triple(op, self.attribute(op, "origin")?)?;
                    let target = self.triple(op, self.attribute(op, "target")?)?;
                    let up = match op.attribute("up") {
                        Some(up) => self.triple(op, self.substitute(up))?,
                        None => DVec3::Y,
                    };
                    let dir = (target - origin)
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "lookat: the target is the origin"))?;
                    let left = up
                        .cross(dir)
                        .try_normalize()
                        .ok_or_else(|| self.error(op, "lookat: up is parallel to the view"))?;
                    let new_up = dir.cross(left);
                    DMat4::from_cols(
                        left.extend(0.0),
                        new_up.extend(0.0),
                        dir.extend(0.0),
                        origin.extend(1.0),
                    )
                }
                other => {
                    return Err(self.error(
                        op,
                        format!(
                            "unknown transform step <{other}>, expected translate, rotate, \
                             scale, matrix or lookat"
                        ),
                    ));
                }
            };
            m = step * m;
        }
        if !m.is_finite() {
            return Err(self.error(node, "the transform is not finite"));
        }
        Ok(m)
    }
}

/// A number as Mitsuba writes one.
pub(super) fn parse_number(text: &str) -> Option<f64> {
    text.trim().parse::<f64>().ok().filter(|x| x.is_finite())
}

/// Numbers separated by commas and/or whitespace.
pub(super) fn numbers(text: &str) -> Option<Vec<f64>> {
    text.split(|c: char| c == ',' || c.is_whitespace())
        .filter(|s| !s.is_empty())
        .map(parse_number)
        .collect()
}

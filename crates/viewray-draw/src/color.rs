//! Colours: 8-bit sRGB with straight alpha.

/// An sRGB colour with straight (not premultiplied) alpha, 8 bits a channel.
///
/// These are the values written to PNG and SVG as they are; no gamma conversion happens
/// anywhere in the drawing pipeline.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct Color {
    /// Red, 0..=255.
    pub r: u8,
    /// Green, 0..=255.
    pub g: u8,
    /// Blue, 0..=255.
    pub b: u8,
    /// Alpha (opacity), 0 transparent ..= 255 opaque.
    pub a: u8,
}

impl Color {
    /// Opaque black.
    pub const BLACK: Color = Color::rgb(0, 0, 0);
    /// Opaque white.
    pub const WHITE: Color = Color::rgb(255, 255, 255);
    /// Fully transparent black.
    pub const TRANSPARENT: Color = Color::rgba(0, 0, 0, 0);

    /// An opaque colour from its red, green and blue channels.
    pub const fn rgb(r: u8, g: u8, b: u8) -> Color {
        Color { r, g, b, a: 255 }
    }

    /// A colour from its red, green, blue and alpha channels.
    pub const fn rgba(r: u8, g: u8, b: u8, a: u8) -> Color {
        Color { r, g, b, a }
    }

    /// An opaque colour from a `0xRRGGBB` literal, as colours are written in CSS.
    ///
    /// ```
    /// # use viewray_draw::Color;
    /// assert_eq!(Color::from_hex(0xD55E00), Color::rgb(0xD5, 0x5E, 0x00));
    /// ```
    pub const fn from_hex(rgb: u32) -> Color {
        Color::rgb((rgb >> 16) as u8, (rgb >> 8) as u8, rgb as u8)
    }

    /// The same colour with opacity `alpha` in 0..=1 (clamped; NaN counts as 0).
    pub fn with_alpha(self, alpha: f32) -> Color {
        let alpha = if alpha.is_nan() {
            0.0
        } else {
            alpha.clamp(0.0, 1.0)
        };
        Color {
            a: (alpha * 255.0).round() as u8,
            ..self
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn with_alpha_rounds_and_clamps() {
        let c = Color::from_hex(0x0072B2);
        assert_eq!(c.with_alpha(0.5).a, 128);
        assert_eq!(c.with_alpha(2.0).a, 255);
        assert_eq!(c.with_alpha(-1.0).a, 0);
        assert_eq!(c.with_alpha(f32::NAN).a, 0);
        assert_eq!(c.with_alpha(0.5).r, 0x00);
        assert_eq!(c.with_alpha(0.5).b, 0xB2);
    }
}

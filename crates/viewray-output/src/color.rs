//! Colour encodings: linear light, as scene files, the renderer and EXR hold colour, and
//! sRGB, as PNG files, figures and screens store it.
//!
//! The sRGB transfer function (IEC 61966-2-1) is written here once; every crate that
//! turns linear light into stored bytes, or stored bytes back into light, calls it.

/// A linear-light RGB colour: what scene files write and the renderer computes. Channels
/// are nominally in `[0, 1]`; lights and sums of them may exceed 1 before they are stored.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LinearRgb(pub [f32; 3]);

/// An sRGB-encoded colour, 8 bits a channel: what a PNG file stores and a screen shows.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub struct Srgb8(pub [u8; 3]);

impl LinearRgb {
    /// The colour as stored in 8 bits: each channel clamped to `[0, 1]` (NaN to 0),
    /// encoded by [`linear_to_srgb`] and rounded ([`linear_to_srgb8`]).
    pub fn to_srgb8(self) -> Srgb8 {
        Srgb8(self.0.map(linear_to_srgb8))
    }
}

impl Srgb8 {
    /// The linear light this stored colour stands for ([`srgb_to_linear`] of each
    /// channel's `code / 255`).
    pub fn to_linear(self) -> LinearRgb {
        LinearRgb(self.0.map(|code| srgb_to_linear(f32::from(code) / 255.0)))
    }
}

/// The sRGB transfer function (IEC 61966-2-1): a linear-light value to its encoded
/// value, both in `[0, 1]`.
///
/// ```text
/// x <= 0.0031308:  12.92 x
/// otherwise:       1.055 x^(1/2.4) - 0.055
/// ```
///
/// Outside `[0, 1]` the two formulas simply extend; [`linear_to_srgb8`] clamps first.
pub fn linear_to_srgb(x: f32) -> f32 {
    if x <= 0.003_130_8 {
        12.92 * x
    } else {
        1.055 * x.powf(1.0 / 2.4) - 0.055
    }
}

/// The inverse of [`linear_to_srgb`]: an sRGB-encoded value in `[0, 1]` to linear light.
///
/// ```text
/// s <= 0.04045:  s / 12.92
/// otherwise:     ((s + 0.055) / 1.055)^2.4
/// ```
pub fn srgb_to_linear(s: f32) -> f32 {
    if s <= 0.040_45 {
        s / 12.92
    } else {
        ((s + 0.055) / 1.055).powf(2.4)
    }
}

/// A linear channel value as an 8-bit sRGB code: clamped to `[0, 1]` (NaN to 0),
/// encoded by [`linear_to_srgb`] and stored by [`unit_to_u8`]. Linear 0.5 is 188,
/// linear 0.2140 is 128.
///
/// Looked up rather than computed: the code never decreases as `x` grows, so it is the
/// number of codes whose least value `x` reaches, and those 255 least values are found
/// once, by bisection with the formula itself. The result is the
/// formula's, to the bit, on every machine (the least values come from its `powf`);
/// an image's worth of `powf` had been a frame's PNG encoding's largest part.
#[inline]
pub fn linear_to_srgb8(x: f32) -> u8 {
    SrgbCodes::get().code(x)
}

/// [`linear_to_srgb8`] by the formula, value by value.
fn linear_to_srgb8_by_formula(x: f32) -> u8 {
    unit_to_u8(linear_to_srgb(clamp_unit(x)))
}

/// The 8-bit sRGB codes of linear values as a table: the least value of each code, and
/// a first guess for each bucket of values by their bits (the exponent and the top
/// [`SrgbCodes::MANTISSA_BITS`] of the mantissa), which holds at most a code or two.
struct SrgbCodes {
    /// `least[k]`: the least value whose code is `k`, for `k` in `1..=255` (`least[0]`
    /// is 0 and never read).
    least: [f32; 256],
    /// The bits of the first bucket's first value (`least[1]`'s bucket).
    first: u32,
    /// The code of each bucket's first value, from `first` to `least[255]`'s bucket.
    start: Vec<u8>,
}

impl SrgbCodes {
    /// How many of the mantissa's top bits a bucket shares: buckets 2^-8 of their
    /// values wide, where the codes near 1 are 2^-6.8 apart.
    const MANTISSA_BITS: u32 = 8;
    const SHIFT: u32 = f32::MANTISSA_DIGITS - 1 - Self::MANTISSA_BITS;

    /// The table, made on first use (255 bisections and a few thousand buckets, some
    /// ten thousand evaluations of the formula).
    fn get() -> &'static SrgbCodes {
        static CODES: std::sync::OnceLock<SrgbCodes> = std::sync::OnceLock::new();
        CODES.get_or_init(SrgbCodes::new)
    }

    fn new() -> Self {
        let mut least = [0.0_f32; 256];
        for (k, least) in least.iter_mut().enumerate().skip(1) {
            // The least bits of `[0, 1]` (ordered as their values) whose code reaches `k`.
            let (mut low, mut high) = (0_u32, 1.0_f32.to_bits());
            while low < high {
                let middle = low + (high - low) / 2;
                if usize::from(linear_to_srgb8_by_formula(f32::from_bits(middle))) >= k {
                    high = middle;
                } else {
                    low = middle + 1;
                }
            }
            *least = f32::from_bits(low);
        }
        let first = least[1].to_bits() >> Self::SHIFT << Self::SHIFT;
        let buckets = ((least[255].to_bits() - first) >> Self::SHIFT) as usize + 1;
        let start = (0..buckets)
            .map(|bucket| {
                let value = f32::from_bits(first + ((bucket as u32) << Self::SHIFT));
                // The number of codes whose least value it reaches.
                least[1..].partition_point(|&l| l <= value) as u8
            })
            .collect();
        Self {
            least,
            first,
            start,
        }
    }

    /// The code of `x`.
    #[inline]
    fn code(&self, x: f32) -> u8 {
        // Below the first code's least value: negative, tiny or NaN, code 0.
        if x < self.least[1] || x.is_nan() {
            return 0;
        }
        if x >= self.least[255] {
            return 255;
        }
        let bucket = ((x.to_bits() - self.first) >> Self::SHIFT) as usize;
        let mut code = self.start[bucket];
        while x >= self.least[usize::from(code) + 1] {
            code += 1;
        }
        code
    }
}

/// A value in `[0, 1]` as the 8-bit code `round(255 x)`, as an 8-bit image stores an
/// already-encoded channel (or data, such as a normal map): clamped to `[0, 1]` first,
/// NaN to 0.
pub fn unit_to_u8(x: f32) -> u8 {
    // In 0.5..=255.5 after clamping, and the sum is exact in f32: the cast only drops
    // the fraction, rounding halves up.
    #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
    let code = (clamp_unit(x) * 255.0 + 0.5) as u8;
    code
}

/// `x` clamped to `[0, 1]`, NaN to 0.
fn clamp_unit(x: f32) -> f32 {
    if x.is_nan() { 0.0 } else { x.clamp(0.0, 1.0) }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn looked_up_codes_are_the_formulas() {
        let codes = SrgbCodes::get();
        let check = |bits: u32| {
            let x = f32::from_bits(bits);
            assert_eq!(
                linear_to_srgb8(x),
                linear_to_srgb8_by_formula(x),
                "linear {x:e} (bits {bits:#x})"
            );
        };
        // Every value within 4096 ulps of each code's least value, where a code changes.
        for &least in &codes.least[1..] {
            let bits = least.to_bits();
            (bits - 4096..=bits + 4096).for_each(check);
        }
        // And values all over: zero to beyond 1, negatives, infinities and NaN.
        (0..=1.5_f32.to_bits()).step_by(1009).for_each(check);
        (0..=1.5_f32.to_bits())
            .step_by(1009)
            .for_each(|bits| check(bits | 1 << 31));
        [
            f32::INFINITY,
            f32::NEG_INFINITY,
            f32::NAN,
            f32::MIN_POSITIVE,
            1.0,
            0.0,
            -0.0,
        ]
        .map(f32::to_bits)
        .into_iter()
        .for_each(check);
        // Each code has a least value, above the one before, inside `[0, 1]`.
        assert!(codes.least[1] > 0.0 && codes.least[255] <= 1.0);
        assert!(codes.least[1..].windows(2).all(|pair| pair[0] < pair[1]));
    }

    #[test]
    fn srgb_codes_of_known_values() {
        for (linear, code) in [
            (0.0, 0),
            (1.0, 255),
            (0.5, 188),
            (0.214_041_14, 128),
            (0.001, 3),
            (0.18, 118),
            (-1.0, 0),
            (7.0, 255),
            (f32::NAN, 0),
        ] {
            assert_eq!(linear_to_srgb8(linear), code, "linear {linear}");
        }
    }

    #[test]
    fn the_two_pieces_of_the_transfer_function_meet() {
        // Both sides of each breakpoint agree to within the standard's rounding.
        let below = 12.92 * 0.003_130_8_f32;
        let above = 1.055 * 0.003_130_8_f32.powf(1.0 / 2.4) - 0.055;
        assert!((below - above).abs() < 1e-6, "{below} {above}");
        assert!((srgb_to_linear(0.040_45) - 0.040_45 / 12.92).abs() < 1e-7);
        assert!((srgb_to_linear(0.5) - 0.214_041).abs() < 1e-6);
    }

    #[test]
    fn every_8_bit_code_survives_a_round_trip_through_linear_light() {
        for code in 0..=255u8 {
            let stored = Srgb8([code, 0, 255]);
            assert_eq!(stored.to_linear().to_srgb8(), stored, "code {code}");
            let encoded = f32::from(code) / 255.0;
            assert!((linear_to_srgb(srgb_to_linear(encoded)) - encoded).abs() < 1e-5);
        }
    }

    #[test]
    fn unit_values_round_to_the_nearest_code() {
        for (value, code) in [
            (0.0, 0),
            (0.5, 128),
            (0.25, 64),
            (1.0, 255),
            (1.5, 255),
            (-0.2, 0),
            (f32::NAN, 0),
            (0.5 / 255.0, 1),
        ] {
            assert_eq!(unit_to_u8(value), code, "{value}");
        }
    }
}

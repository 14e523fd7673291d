//! Random numbers for tests, from a fixed seed (xorshift32): every test that feeds the
//! lanes and the scalar rules the same random inputs draws them here.

use glam::Vec3;

/// A xorshift32 generator; its state is the seed.
pub(crate) struct Numbers(pub(crate) u32);

impl Numbers {
    /// The next 32 random bits.
    pub(crate) fn bits(&mut self) -> u32 {
        self.0 ^= self.0 << 13;
        self.0 ^= self.0 >> 17;
        self.0 ^= self.0 << 5;
        self.0
    }

    /// Uniform in `[0, 1)`.
    pub(crate) fn uniform(&mut self) -> f32 {
        (self.bits() >> 8) as f32 / (1 << 24) as f32
    }

    /// One of `n` choices.
    pub(crate) fn pick(&mut self, n: u32) -> u32 {
        self.bits() % n
    }

    /// Each coordinate uniform in `[0, 1)`: a colour.
    pub(crate) fn color(&mut self) -> Vec3 {
        Vec3::new(self.uniform(), self.uniform(), self.uniform())
    }

    /// Each coordinate uniform in `[-1, 1)`.
    pub(crate) fn vector(&mut self) -> Vec3 {
        self.color() * 2.0 - 1.0
    }

    /// A unit vector (of [`Numbers::vector`]'s directions; `y` for the zero vector).
    pub(crate) fn unit(&mut self) -> Vec3 {
        self.vector().normalize_or(Vec3::Y)
    }

    /// `x` moved by up to four ulps either way in magnitude (zero to the smallest
    /// subnormals), the infinities kept.
    pub(crate) fn nudge(&mut self, x: f32) -> f32 {
        let ulps = self.pick(9);
        if x.is_infinite() {
            return x;
        }
        let magnitude = x.abs().to_bits().saturating_add(ulps).saturating_sub(4);
        f32::from_bits(magnitude).copysign(x)
    }
}

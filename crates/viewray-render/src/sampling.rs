//! Where in a pixel (and on the lens) each sample goes: stratified jitter from a hash of
//! (row, col, sample index), so an image never depends on thread scheduling.

use std::ops::Range;

use glam::DVec2;
use viewray_camera::{Camera, CameraSample};
use viewray_geometry::DRay;

/// SplitMix64's output function: a fast, well-mixing bijection on `u64`.
#[inline]
fn mix64(mut z: u64) -> u64 {
    z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
    z ^ (z >> 31)
}

/// The golden-ratio increment of SplitMix64.
const GOLDEN: u64 = 0x9e37_79b9_7f4a_7c15;

/// A small random number generator (SplitMix64) whose whole state comes from the pixel
/// and the sample index, never from a thread or a shared stream.
#[derive(Clone, Copy, Debug)]
pub(crate) struct SampleRng {
    state: u64,
}

impl SampleRng {
    /// The generator of sample `sample` of pixel `(row, col)`.
    #[cfg(test)]
    fn new(row: u32, col: u32, sample: u32) -> Self {
        Self::of_pixel(
            PixelSeed::new(row, col),
            u64::from(sample).wrapping_mul(GOLDEN),
        )
    }

    /// The generator of the sample whose index times [`GOLDEN`] is `salt` in the pixel
    /// of `seed`.
    #[inline]
    fn of_pixel(seed: PixelSeed, salt: u64) -> Self {
        Self {
            state: mix64(seed.film ^ salt),
        }
    }

    /// The next 64 random bits.
    #[inline]
    pub(crate) fn next_u64(&mut self) -> u64 {
        self.state = self.state.wrapping_add(GOLDEN);
        mix64(self.state)
    }

    /// A uniform number in `[0, 1)` with 53 random bits.
    #[inline]
    pub(crate) fn next_f64(&mut self) -> f64 {
        (self.next_u64() >> 11) as f64 * UNIT
    }
}

/// What every sample of one pixel draws from: the hashes of its row and column, worked
/// out once a pixel rather than once a sample (a render takes its samples index by
/// index over a tile, so a tile keeps its pixels' seeds).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub(crate) struct PixelSeed {
    /// The pixel's part of each sample's [`SampleRng`] state.
    film: u64,
    /// The seed of the pixel's [`permute`] of the lens strata.
    lens: u32,
}

impl PixelSeed {
    /// The seed of pixel `(row, col)`.
    #[inline]
    pub(crate) fn new(row: u32, col: u32) -> Self {
        let pixel = u64::from(row) << 32 | u64::from(col);
        Self {
            film: mix64(pixel.wrapping_add(GOLDEN)),
            lens: (mix64(pixel) >> 32) as u32,
        }
    }
}

/// A pseudo-random permutation of `0..len` chosen by `seed`, evaluated at `index`
/// without memory (Kensler, "Correlated Multi-Jittered Sampling", 2013, listing 3: a
/// hash restricted to the next power of two, cycle-walked back into `0..len`).
///
/// # Panics
/// Never for `index < len`; `len` must be at least 1.
#[inline]
pub(crate) fn permute(mut index: u32, len: u32, seed: u32) -> u32 {
    debug_assert!(index < len);
    let mut mask = len - 1;
    mask |= mask >> 1;
    mask |= mask >> 2;
    mask |= mask >> 4;
    mask |= mask >> 8;
    mask |= mask >> 16;
    loop {
        index = permute_hash(index, mask, seed);
        if index < len {
            // `(index + seed) % len`, reduced first: a seed within `len` of `u32::MAX`
            // neither overflows nor (wrapping) breaks the permutation.
            return (index + seed % len) % len;
        }
    }
}

/// One step of [`permute`]'s cycle walk: Kensler's hash of `index`, within `0..=mask`.
#[inline(always)]
fn permute_hash(mut index: u32, mask: u32, seed: u32) -> u32 {
    index ^= seed;
    index = index.wrapping_mul(0xe170_893d);
    index ^= seed >> 16;
    index ^= (index & mask) >> 4;
    index ^= seed >> 8;
    index = index.wrapping_mul(0x0929_eb3f);
    index ^= seed >> 23;
    index ^= (index & mask) >> 1;
    index = index.wrapping_mul(1 | seed >> 27);
    index = index.wrapping_mul(0x6935_fa69);
    index ^= (index & mask) >> 11;
    index = index.wrapping_mul(0x74dc_b303);
    index ^= (index & mask) >> 2;
    index = index.wrapping_mul(0x9e50_1cc3);
    index ^= (index & mask) >> 2;
    index = index.wrapping_mul(0xc860_a3df);
    index &= mask;
    index ^ index >> 5
}

/// How many seeds [`permute_lanes`] shuffles at once: eight `u32` lanes, one AVX2
/// register.
const PERMUTE_LANES: usize = 8;

/// [`permute`]`(index, len, seed)` of each of `seeds` where `len`, the number of
/// strata, is a power of two: then `mask` is `len - 1`, so the hash lands in `0..len`
/// at the first step (its last two steps keep it within the mask) and the walk never
/// loops, and `% len` is `& mask`. With no loop and no division, eight seeds go through
/// the same integer operations side by side.
#[inline(always)]
fn permute_lanes(index: u32, len: u32, seeds: [u32; PERMUTE_LANES]) -> [u32; PERMUTE_LANES] {
    debug_assert!(len.is_power_of_two() && index < len);
    let mask = len - 1;
    seeds.map(|seed| (permute_hash(index, mask, seed) + (seed & mask)) & mask)
}

/// The strata of one pixel: the unit square split into `count` cells of equal area,
/// `rows = round(sqrt(count))` rows, each holding `count / rows` or one more cells side
/// by side, each row as tall as its share of the cells.
///
/// Every `count` is stratified exactly, squares (4 -> 2 x 2, 16 -> 4 x 4) and others
/// alike (3 -> two cells 2/3 tall side by side over one cell 1/3 tall; 5 -> a row of 3
/// over a row of 2).
#[derive(Clone, Debug)]
pub(crate) struct Strata {
    /// Each cell's corner and size, worked out once (four divisions a sample otherwise):
    /// one cell per sample.
    cells: Vec<(DVec2, DVec2)>,
    /// Whether lens samples are drawn: cameras without a lens ignore `p_lens`, so
    /// they are left at the lens centre and their stratum is not looked up.
    lens: bool,
    /// Whether this processor runs AVX2 ([`IndexSamples::draw`]).
    avx2: bool,
}

impl Strata {
    /// The camera's rays of the block `rows x cols` through each pixel's sample, the
    /// block's samples `drawn` row by row:
    /// [`Camera::generate_sampled_block_rays`], or where lens samples are drawn and the
    /// processor runs AVX2, its AVX2 build
    /// ([`Camera::generate_sampled_block_rays_avx2`]), the same rays.
    #[inline]
    pub(crate) fn sampled_block_rays(
        &self,
        camera: &Camera,
        (rows, cols): (Range<u32>, Range<u32>),
        drawn: &[CameraSample],
        ray: impl FnMut(u32, u32, Option<DRay>),
    ) {
        #[cfg(target_arch = "x86_64")]
        if self.avx2 && self.lens {
            // SAFETY: `avx2` is true only where the processor runs AVX2 (`Strata::new`
            // asks it), which is all `generate_sampled_block_rays_avx2` needs.
            #[allow(unsafe_code)]
            unsafe {
                camera.generate_sampled_block_rays_avx2(rows, cols, drawn, ray);
            }
            return;
        }
        let (top, left, width) = (rows.start, cols.start, cols.len() as u32);
        let sample = |row: u32, col: u32| drawn[((row - top) * width + (col - left)) as usize];
        camera.generate_sampled_block_rays(rows, cols, sample, ray);
    }

    /// The strata of `count` samples (at least 1).
    pub(crate) fn new(count: u32) -> Self {
        let count = count.max(1);
        // round(sqrt(count)) is between 1 and count.
        let rows = f64::from(count).sqrt().round().max(1.0) as u32;
        Self {
            cells: (0..count)
                .map(|cell| cell_of(cell, count, count / rows, count % rows))
                .collect(),
            lens: true,
            avx2: avx2_detected(),
        }
    }

    /// The same strata, drawing lens samples only if `lens` (a camera without a lens
    /// ignores them). The film samples do not change: they are drawn first.
    pub(crate) fn with_lens(self, lens: bool) -> Self {
        Self { lens, ..self }
    }

    /// The corner and size of cell `cell` (`cell < count`).
    #[inline]
    pub(crate) fn cell(&self, cell: u32) -> (DVec2, DVec2) {
        self.cells[cell as usize]
    }

    /// The camera sample every pixel shares, if there is one: with one sample per
    /// pixel, the pixel centre through the lens centre (see
    /// [`IndexSamples::camera_sample`]).
    #[inline]
    pub(crate) fn shared_sample(&self) -> Option<CameraSample> {
        (self.cells.len() == 1).then_some(CameraSample::CENTER)
    }

    /// The camera sample of sample `index` in pixel `(row, col)`, one at a time (see
    /// [`IndexSamples::camera_sample`]).
    #[cfg(test)]
    fn camera_sample(&self, row: u32, col: u32, index: u32) -> CameraSample {
        self.index(index).camera_sample(PixelSeed::new(row, col))
    }

    /// Sample `index` of every pixel (`index < count`): what its camera samples ask of
    /// the strata, looked up once for a block of pixels.
    #[inline]
    pub(crate) fn index(&self, index: u32) -> IndexSamples<'_> {
        let (corner, size) = self.cell(index);
        IndexSamples {
            strata: self,
            index,
            salt: u64::from(index).wrapping_mul(GOLDEN),
            corner,
            size,
        }
    }
}

/// Sample `index` of every pixel: its film stratum and its part of the hash, worked out
/// once for a block of pixels ([`Strata::index`]).
#[derive(Clone, Copy, Debug)]
pub(crate) struct IndexSamples<'a> {
    strata: &'a Strata,
    index: u32,
    /// `index` times [`GOLDEN`]: the sample's part of each pixel's [`SampleRng`] state.
    salt: u64,
    /// The corner of the film stratum.
    corner: DVec2,
    /// The size of the film stratum.
    size: DVec2,
}

impl IndexSamples<'_> {
    /// The camera sample of this index in the pixel of `seed`.
    ///
    /// One sample is the pixel centre through the lens centre: the lecture's viewing
    /// ray, so a one-sample render is exactly the homework's image. More samples are
    /// jittered in their strata; lens samples (used only by cameras with a lens) are
    /// stratified the same way, their strata shuffled per pixel against the film's so
    /// film and lens positions are not correlated.
    #[inline]
    pub(crate) fn camera_sample(&self, seed: PixelSeed) -> CameraSample {
        let count = self.strata.cells.len() as u32;
        // `shared_sample`'s rule, checked here directly: asked through it, the 16-sample
        // Lit render ran 4% slower (medians of 7, alternated).
        if count == 1 {
            return CameraSample::CENTER;
        }
        let mut rng = SampleRng::of_pixel(seed, self.salt);
        let p_film = self.corner + self.size * DVec2::new(rng.next_f64(), rng.next_f64());
        if !self.strata.lens {
            return CameraSample {
                p_film,
                p_lens: CameraSample::CENTER.p_lens,
            };
        }
        let lens_cell = permute(self.index, count, seed.lens);
        let (corner, size) = self.strata.cell(lens_cell);
        let p_lens = corner + size * DVec2::new(rng.next_f64(), rng.next_f64());
        CameraSample { p_film, p_lens }
    }

    /// The camera samples of this index in the pixels of `seeds`, into `samples` (as
    /// long): [`IndexSamples::camera_sample`] of each, bit for bit.
    ///
    /// Without a lens, on a processor with AVX2, four pixels at a time
    /// ([`IndexSamples::draw_films_avx2`]): the three SplitMix64 hashes of a sample were
    /// about half of its viewing ray's instructions, and SSE2 has no cheaper 64-bit
    /// multiply than the scalar one.
    #[inline]
    pub(crate) fn draw(&self, seeds: &[PixelSeed], samples: &mut [CameraSample]) {
        #[cfg(target_arch = "x86_64")]
        if self.strata.avx2 && self.strata.cells.len() > 1 {
            // SAFETY: `avx2` is true only where the processor runs AVX2 (`Strata::new`
            // asks it), which is all `draw_films_avx2` and `draw_lenses_avx2` need.
            #[allow(unsafe_code)]
            unsafe {
                if self.strata.lens {
                    self.draw_lenses_avx2(seeds, samples);
                } else {
                    self.draw_films_avx2(seeds, samples);
                }
            }
            return;
        }
        for (&seed, sample) in seeds.iter().zip(samples) {
            *sample = self.camera_sample(seed);
        }
    }

    /// [`IndexSamples::draw`] without a lens, compiled for AVX2 so that the hashes of
    /// four pixels go through 256-bit registers: the same integer operations, and the
    /// conversion to `f64` by [`exact_f64`] (AVX2 has no 64-bit integer conversion), so
    /// the same bits.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn draw_films_avx2(&self, seeds: &[PixelSeed], samples: &mut [CameraSample]) {
        for (&seed, sample) in seeds.iter().zip(samples) {
            let mut rng = SampleRng::of_pixel(seed, self.salt);
            let (x, y) = (rng.next_u64() >> 11, rng.next_u64() >> 11);
            let unit = DVec2::new(exact_f64(x), exact_f64(y)) * UNIT;
            *sample = CameraSample {
                p_film: self.corner + self.size * unit,
                p_lens: CameraSample::CENTER.p_lens,
            };
        }
    }

    /// [`IndexSamples::draw`] with a lens, compiled for AVX2: first each pixel's four
    /// random numbers (the film point's two, the lens point's two), four pixels at a
    /// time as in [`IndexSamples::draw_films_avx2`]; then pixel by pixel its lens stratum
    /// (whose shuffle may walk a cycle, which keeps that loop from running in lanes) and
    /// both points. The numbers are drawn in the same order from the same generator, so
    /// the samples are [`IndexSamples::camera_sample`]'s to the bit.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn draw_lenses_avx2(&self, seeds: &[PixelSeed], samples: &mut [CameraSample]) {
        let count = self.strata.cells.len() as u32;
        let mut drawn = [[0u64; 4]; DRAWN];
        let mut lens_cells = [0u32; DRAWN];
        for (seeds, samples) in seeds.chunks(DRAWN).zip(samples.chunks_mut(DRAWN)) {
            for (&seed, bits) in seeds.iter().zip(&mut drawn) {
                let mut rng = SampleRng::of_pixel(seed, self.salt);
                *bits = [0; 4].map(|_| rng.next_u64() >> 11);
            }
            if count.is_power_of_two() {
                let lanes = seeds.chunks(PERMUTE_LANES);
                for (seeds, cells) in lanes.zip(lens_cells.chunks_mut(PERMUTE_LANES)) {
                    // A short last group's missing lanes shuffle seed 0, unused.
                    let mut lens = [0; PERMUTE_LANES];
                    for (lane, seed) in lens.iter_mut().zip(seeds) {
                        *lane = seed.lens;
                    }
                    let shuffled = permute_lanes(self.index, count, lens);
                    cells.copy_from_slice(&shuffled[..cells.len()]);
                }
            } else {
                for (&seed, cell) in seeds.iter().zip(&mut lens_cells) {
                    *cell = permute(self.index, count, seed.lens);
                }
            }
            for ((bits, &lens_cell), sample) in drawn.iter().zip(&lens_cells).zip(samples) {
                let unit = bits.map(exact_f64);
                let (corner, size) = self.strata.cell(lens_cell);
                *sample = CameraSample {
                    p_film: self.corner + self.size * (DVec2::new(unit[0], unit[1]) * UNIT),
                    p_lens: corner + size * (DVec2::new(unit[2], unit[3]) * UNIT),
                };
            }
        }
    }
}

/// How many pixels' random numbers [`IndexSamples::draw_lenses_avx2`] draws before it
/// makes their samples (a block of 8 x 8 pixels in one pass).
const DRAWN: usize = 64;

/// `2^-53`: a number's top 53 bits as a fraction of 1.
const UNIT: f64 = 1.0 / (1u64 << 53) as f64;

/// `bits as f64` for `bits < 2^53`, by integer operations and one exact addition: the
/// low 52 bits as the mantissa of `2^52 + low`, less `2^52`, plus `2^52` if bit 52 is
/// set. Every step is exact, so the result is the conversion's to the bit; unlike the
/// conversion it runs four lanes at a time in AVX2.
#[inline(always)]
fn exact_f64(bits: u64) -> f64 {
    debug_assert!(bits < 1 << 53);
    const TWO_52: u64 = 0x4330_0000_0000_0000;
    let low = f64::from_bits(TWO_52 | (bits & ((1 << 52) - 1))) - f64::from_bits(TWO_52);
    let high = f64::from_bits((bits >> 52).wrapping_neg() & TWO_52);
    low + high
}

/// Whether this processor runs AVX2.
fn avx2_detected() -> bool {
    #[cfg(target_arch = "x86_64")]
    return std::arch::is_x86_feature_detected!("avx2");
    #[cfg(not(target_arch = "x86_64"))]
    false
}

/// The corner and size of cell `cell` of `count` strata whose short rows hold `short`
/// cells, the first `long_rows` rows one more.
fn cell_of(cell: u32, count: u32, short: u32, long_rows: u32) -> (DVec2, DVec2) {
    debug_assert!(cell < count);
    let long = short + 1;
    // Rows 0..long_rows hold `long` cells, the rest `short`.
    let (row_cells, first_in_row, col) = if cell < long_rows * long {
        let row = cell / long;
        (long, row * long, cell % long)
    } else {
        let rest = cell - long_rows * long;
        let col = rest % short;
        (short, cell - col, col)
    };
    let n = f64::from(count);
    let corner = DVec2::new(
        f64::from(col) / f64::from(row_cells),
        f64::from(first_in_row) / n,
    );
    let size = DVec2::new(1.0 / f64::from(row_cells), f64::from(row_cells) / n);
    (corner, size)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The strata of `count` cover the unit square exactly once, with equal areas.
    #[track_caller]
    fn check_strata(count: u32, expected_rows: usize) {
        let strata = Strata::new(count);
        let cells: Vec<_> = (0..count).map(|i| strata.cell(i)).collect();
        let area: f64 = cells.iter().map(|(_, s)| s.x * s.y).sum();
        assert!((area - 1.0).abs() < 1e-12, "{count}: area {area}");
        for (corner, size) in &cells {
            assert!((size.x * size.y - 1.0 / f64::from(count)).abs() < 1e-12);
            assert!(corner.min_element() >= 0.0);
            assert!((*corner + *size).max_element() <= 1.0 + 1e-12);
        }
        // A grid of test points each falls in exactly one cell.
        for i in 0..37 {
            for j in 0..37 {
                let p = DVec2::new((f64::from(i) + 0.5) / 37.0, (f64::from(j) + 0.5) / 37.0);
                let inside = cells
                    .iter()
                    .filter(|(c, s)| p.cmpge(*c).all() && p.cmplt(*c + *s).all())
                    .count();
                assert_eq!(inside, 1, "{count}: point {p} in {inside} cells");
            }
        }
        let mut rows: Vec<u64> = cells.iter().map(|(c, _)| c.y.to_bits()).collect();
        rows.dedup();
        assert_eq!(rows.len(), expected_rows, "{count}");
    }

    #[test]
    fn strata_tile_the_pixel_with_equal_areas() {
        for (count, rows) in [
            (1, 1),
            (2, 1),
            (3, 2),
            (4, 2),
            (5, 2),
            (7, 3),
            (16, 4),
            (17, 4),
        ] {
            check_strata(count, rows);
        }
        // Squares are square grids.
        assert_eq!(
            Strata::new(16).cell(5),
            (DVec2::new(0.25, 0.25), DVec2::splat(0.25))
        );
    }

    #[test]
    fn permute_is_a_permutation() {
        for len in [1, 2, 3, 7, 16, 100] {
            // The largest seeds: their offset once overflowed (and, wrapped, repeated an index).
            for seed in [0, 1, 0xdead_beef, u32::MAX - 2, u32::MAX] {
                let mut seen: Vec<u32> = (0..len).map(|i| permute(i, len, seed)).collect();
                seen.sort_unstable();
                assert_eq!(seen, (0..len).collect::<Vec<_>>(), "len {len} seed {seed}");
            }
        }
    }

    /// The shuffle in lanes is [`permute`]'s walk, lane by lane, for every power of two
    /// up to 64 strata (and a few far larger), every index, the edge seeds and many
    /// others, in every lane.
    #[test]
    fn permute_lanes_are_the_walk() {
        let mut numbers = crate::test_numbers::Numbers(0x5eed_1e25);
        let lens = (0..7)
            .map(|power| 1u32 << power)
            .chain([1 << 12, 1 << 20, 1 << 31]);
        for len in lens {
            for index in (0..len.min(64)).chain([len - 1]) {
                for round in 0..40 {
                    let seeds: [u32; PERMUTE_LANES] = if round == 0 {
                        [
                            0,
                            1,
                            len - 1,
                            len,
                            0xdead_beef,
                            u32::MAX - len,
                            u32::MAX - 1,
                            u32::MAX,
                        ]
                    } else {
                        std::array::from_fn(|_| numbers.bits())
                    };
                    let walked = seeds.map(|seed| permute(index, len, seed));
                    assert_eq!(
                        permute_lanes(index, len, seeds),
                        walked,
                        "{len} {index} {seeds:?}"
                    );
                }
            }
        }
    }

    #[test]
    fn samples_stay_in_their_strata_and_depend_only_on_the_pixel_and_index() {
        let strata = Strata::new(9);
        for index in 0..9 {
            let s = strata.camera_sample(3, 4, index);
            let (corner, size) = strata.cell(index);
            assert!(s.p_film.cmpge(corner).all() && s.p_film.cmplt(corner + size).all());
            assert!(s.p_lens.cmpge(DVec2::ZERO).all() && s.p_lens.cmplt(DVec2::ONE).all());
            assert_eq!(s, strata.camera_sample(3, 4, index));
        }
        assert_ne!(strata.camera_sample(3, 4, 0), strata.camera_sample(4, 3, 0));
        assert_eq!(Strata::new(1).camera_sample(7, 7, 0), CameraSample::CENTER);
        // Without a lens, the same film samples and the lens centre.
        let no_lens = strata.clone().with_lens(false);
        for index in 0..9 {
            let s = no_lens.camera_sample(3, 4, index);
            assert_eq!(s.p_film, strata.camera_sample(3, 4, index).p_film);
            assert_eq!(s.p_lens, DVec2::splat(0.5));
        }
    }

    #[test]
    fn exact_conversions_are_the_conversions() {
        let mut rng = SampleRng::new(5, 6, 7);
        let edges = [
            0,
            1,
            2,
            (1 << 52) - 1,
            1 << 52,
            (1 << 52) + 1,
            (1 << 53) - 1,
        ];
        let random = (0..10_000).map(|_| rng.next_u64() >> 11);
        for bits in edges.into_iter().chain(random) {
            assert_eq!(exact_f64(bits).to_bits(), (bits as f64).to_bits(), "{bits}");
        }
    }

    /// A block's samples drawn together (four at a time with AVX2, where the processor
    /// has it, with and without a lens, and one at a time) are each pixel's own, bit for
    /// bit.
    #[test]
    fn drawn_samples_are_each_pixels_own() {
        let bits = |s: &CameraSample| [s.p_film, s.p_lens].map(|p| p.to_array().map(f64::to_bits));
        // Every count a render's strata could take up to 64: powers of two shuffle their
        // lens strata in lanes, the others walk.
        for count in 1..=64 {
            for lens in [false, true] {
                for avx2 in [false, avx2_detected()] {
                    let mut strata = Strata::new(count).with_lens(lens);
                    strata.avx2 = avx2;
                    // A few pixels, a whole block's, and more than a block's.
                    for pixels in [7, DRAWN, DRAWN + 1] {
                        let seeds: Vec<_> = (0..pixels as u32)
                            .map(|col| PixelSeed::new(3 + count, 1000 * count + col))
                            .collect();
                        for index in 0..count {
                            let samples = strata.index(index);
                            let mut drawn = vec![CameraSample::CENTER; pixels];
                            samples.draw(&seeds, &mut drawn);
                            for (seed, sample) in seeds.iter().zip(&drawn) {
                                let own = samples.camera_sample(*seed);
                                assert_eq!(bits(sample), bits(&own), "{count} {lens} {avx2}");
                            }
                        }
                    }
                }
            }
        }
    }

    /// The samples are the hash of the pixel and the index the images were made with:
    /// a few of them to the bit.
    #[test]
    fn samples_keep_their_bits() {
        let strata = Strata::new(16);
        let s = strata.camera_sample(17, 42, 5);
        let expected = [
            0x3fd1_1cb7_97a8_936a,
            0x3fd8_ba44_0276_e644,
            0x3fe5_1bce_1cc7_6d34,
            0x3fd2_e8ae_502d_71fd,
        ];
        assert_eq!(
            [s.p_film.x, s.p_film.y, s.p_lens.x, s.p_lens.y].map(f64::to_bits),
            expected
        );
    }

    #[test]
    fn uniform_numbers_have_the_right_mean() {
        let mut rng = SampleRng::new(1, 2, 3);
        let n = 100_000;
        let mean = (0..n).map(|_| rng.next_f64()).sum::<f64>() / f64::from(n);
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
    }
}

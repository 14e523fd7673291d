//! Where in a pixel (and on the lens) each sample goes: stratified jitter from a hash of
//! (row, col, sample index), so an image never depends on thread scheduling.

use glam::DVec2;
use viewray_camera::CameraSample;

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
    #[inline]
    pub(crate) fn new(row: u32, col: u32, sample: u32) -> Self {
        let pixel = mix64((u64::from(row) << 32 | u64::from(col)).wrapping_add(GOLDEN));
        Self {
            state: mix64(pixel ^ u64::from(sample).wrapping_mul(GOLDEN)),
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
        // 2^-53: the top 53 bits as a fraction.
        (self.next_u64() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// A per-pixel seed for [`permute`], from the pixel alone.
#[inline]
fn pixel_seed(row: u32, col: u32) -> u32 {
    (mix64(u64::from(row) << 32 | u64::from(col)) >> 32) as u32
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
        index ^= index >> 5;
        if index < len {
            // `(index + seed) % len`, reduced first: a seed within `len` of `u32::MAX`
            // neither overflows nor (wrapping) breaks the permutation.
            return (index + seed % len) % len;
        }
    }
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
}

impl Strata {
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
    /// pixel, the pixel centre through the lens centre (see [`Strata::camera_sample`]).
    #[inline]
    pub(crate) fn shared_sample(&self) -> Option<CameraSample> {
        (self.cells.len() == 1).then_some(CameraSample::CENTER)
    }

    /// The camera sample of sample `index` in pixel `(row, col)`.
    ///
    /// One sample is the pixel centre through the lens centre: the lecture's viewing
    /// ray, so a one-sample render is exactly the homework's image. More samples are
    /// jittered in their strata; lens samples (used only by cameras with a lens) are
    /// stratified the same way, their strata shuffled per pixel against the film's so
    /// film and lens positions are not correlated.
    #[inline]
    pub(crate) fn camera_sample(&self, row: u32, col: u32, index: u32) -> CameraSample {
        let count = self.cells.len() as u32;
        // `shared_sample`'s rule, checked here directly: asked through it, the 16-sample
        // Lit render ran 4% slower (medians of 7, alternated).
        if count == 1 {
            return CameraSample::CENTER;
        }
        let mut rng = SampleRng::new(row, col, index);
        let (corner, size) = self.cell(index);
        let p_film = corner + size * DVec2::new(rng.next_f64(), rng.next_f64());
        if !self.lens {
            return CameraSample {
                p_film,
                p_lens: CameraSample::CENTER.p_lens,
            };
        }
        let lens_cell = permute(index, count, pixel_seed(row, col));
        let (corner, size) = self.cell(lens_cell);
        let p_lens = corner + size * DVec2::new(rng.next_f64(), rng.next_f64());
        CameraSample { p_film, p_lens }
    }
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
    fn uniform_numbers_have_the_right_mean() {
        let mut rng = SampleRng::new(1, 2, 3);
        let n = 100_000;
        let mean = (0..n).map(|_| rng.next_f64()).sum::<f64>() / f64::from(n);
        assert!((mean - 0.5).abs() < 0.01, "{mean}");
    }
}

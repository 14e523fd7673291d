//! The binned SAH builder: items with boxes in, a [`Bvh`] out.
//!
//! A node is opened by splitting its largest child until it has eight; each split is
//! chosen by sweeping 32 bins per axis (8 for small ranges), the three axes side by side.
//! Large ranges are binned and built in parallel.

use glam::{IVec4, Mat3A, Vec3A, Vec3Swizzles, Vec4};
use rayon::prelude::*;

use super::memory::advise_huge_pages;
use super::node::{Bvh, LEAF, MAX_ITEMS, MAX_LEAF, Node, WIDTH, leaf_ref};
use crate::Aabb;

/// Anything with a bounding box, so that a [`Bvh`] can be built over it.
pub trait Bounded {
    /// The axis-aligned box that holds the item.
    fn bounds(&self) -> Aabb;
}

impl Bounded for Aabb {
    fn bounds(&self) -> Aabb {
        *self
    }
}

/// Parameters of the binned SAH build.
///
/// The surface area heuristic estimates the cost of a subtree as the probability of a
/// ray entering a box (its surface area relative to the parent's) times the work done
/// there:
///
/// ```text
/// cost(split) = traversal_cost + (A_left blocks(N_left) + A_right blocks(N_right)) / A
/// cost(leaf)  = blocks(N),   blocks(n) = ceil(n / block_size)
/// ```
///
/// A leaf is made when it is no dearer than the best split and holds at most
/// `max_leaf_items` items. A range of at most one block (and at most `max_leaf_items`
/// items) is always a leaf: no split tests fewer blocks, and each side takes a block of
/// its own (a triangle packet, with lanes to spare).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct BuildParams {
    /// How many items one intersection test handles at once (4 for triangle packets).
    pub block_size: u32,
    /// The most items a leaf may hold (at most 16).
    pub max_leaf_items: u32,
    /// The cost of visiting a node, relative to intersecting one block.
    pub traversal_cost: f32,
}

impl Default for BuildParams {
    /// One item per test, leaves of up to 4 items: the settings for a list of objects.
    fn default() -> Self {
        Self {
            block_size: 1,
            max_leaf_items: 4,
            traversal_cost: 1.0,
        }
    }
}

/// Depth (in nodes) after which the build stops using SAH and halves ranges by count.
/// Each level then at least halves the largest range, so with fewer than 2^27 items
/// the depth stays below `FORCE_MEDIAN_DEPTH + 27 = 67`.
const FORCE_MEDIAN_DEPTH: u32 = 40;
/// Ranges at least this large are split with parallel binning and built in parallel.
const PARALLEL_ITEMS: usize = 16 * 1024;

/// Whether a range of `n` items is worked on in parallel: when it is large enough and
/// the current pool has more than one thread. (On one thread the parallel build only
/// adds work: each subtree built into its own array and copied into place.)
fn in_parallel(n: usize) -> bool {
    n >= PARALLEL_ITEMS && rayon::current_num_threads() > 1
}

impl Bvh {
    /// Builds the hierarchy over `items` with the binned SAH (see [`BuildParams`]).
    ///
    /// Large ranges are binned and built in parallel on the current rayon pool.
    /// `items` must hold fewer than 2^27 items with finite boxes; more are not indexed.
    pub fn build<T: Bounded + Sync>(items: &[T], params: BuildParams) -> Self {
        let count = items.len().min(MAX_ITEMS);
        let mut build_items: Vec<BuildItem> = items[..count]
            .par_iter()
            .enumerate()
            .map(|(index, item)| BuildItem::new(item.bounds(), index as u32))
            .collect();
        Self::build_from(&mut build_items, params)
    }

    /// Builds from prepared items (boxes with their indices); used by meshes, which
    /// compute the boxes of their triangles themselves.
    pub(crate) fn build_from(items: &mut [BuildItem], params: BuildParams) -> Self {
        if items.is_empty() {
            return Self::default();
        }
        let range = RangeInfo::of(items, 0);
        let bounds = range.bounds;
        let builder = Builder::new(params);
        let mut nodes = Vec::with_capacity(items.len() / 2 + 1);
        advise_huge_pages(&mut nodes);
        builder.build_node(items, range, 0, &mut nodes);
        let item_order = items.iter().map(BuildItem::index).collect();
        Self {
            nodes,
            item_order,
            bounds,
        }
    }
}

/// An item during the build: its box and its index in the input, as two SIMD registers,
/// `lo = (min, index)` and `hi = (max, 0)`, each loaded with one aligned load.
///
/// The index rides in `lo.w` with bit 30 set ([`INDEX_TAG`]), which makes it a normal
/// float (exponent 128 to 143 for indices below 2^27): the builder's arithmetic runs on
/// whole registers, and a denormal in the unused lane would slow every operation.
#[derive(Clone, Copy, Debug, bytemuck::Pod, bytemuck::Zeroable)]
#[repr(C)]
pub(crate) struct BuildItem {
    lo: Vec4,
    hi: Vec4,
}

/// Set in the bits of [`BuildItem::lo`]'s `w`; see [`BuildItem`].
const INDEX_TAG: u32 = 1 << 30;

impl BuildItem {
    pub(crate) fn new(bounds: Aabb, index: u32) -> Self {
        debug_assert!((index as usize) < MAX_ITEMS);
        Self {
            lo: bounds.min.extend(f32::from_bits(index | INDEX_TAG)),
            hi: bounds.max.extend(0.0),
        }
    }

    #[inline(always)]
    fn min(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo)
    }

    #[inline(always)]
    fn max(&self) -> Vec3A {
        Vec3A::from_vec4(self.hi)
    }

    fn index(&self) -> u32 {
        self.lo.w.to_bits() & !INDEX_TAG
    }

    /// Whether the box is empty (made from [`Aabb::EMPTY`]).
    pub(crate) fn is_empty(&self) -> bool {
        self.lo.x > self.hi.x
    }

    /// Twice the box center: the point binned (the factor 2 cancels out).
    #[inline(always)]
    fn centroid2(&self) -> Vec3A {
        Vec3A::from_vec4(self.lo + self.hi)
    }
}

/// A contiguous range of build items with its box and the box of its centroids.
#[derive(Clone, Copy, Debug)]
struct RangeInfo {
    start: usize,
    end: usize,
    bounds: Aabb,
    centroids: Aabb,
    /// Decided: this range becomes a leaf.
    leaf: bool,
}

impl RangeInfo {
    fn of(items: &[BuildItem], start: usize) -> Self {
        type Bounds = (Vec3A, Vec3A, Vec3A, Vec3A);
        const EMPTY: Bounds = (
            Vec3A::INFINITY,
            Vec3A::NEG_INFINITY,
            Vec3A::INFINITY,
            Vec3A::NEG_INFINITY,
        );
        let add = |(lo, hi, clo, chi): Bounds, item: &BuildItem| {
            let c = item.centroid2();
            (
                lo.min(item.min()),
                hi.max(item.max()),
                clo.min(c),
                chi.max(c),
            )
        };
        let merge = |a: Bounds, b: Bounds| (a.0.min(b.0), a.1.max(b.1), a.2.min(b.2), a.3.max(b.3));
        // The items at even and odd positions into two sets of bounds, merged at the
        // end: two chains of minima and maxima that run side by side.
        let fold = |items: &[BuildItem]| {
            let pairs = items.chunks_exact(2);
            let rest = pairs.remainder();
            let (even, odd) = pairs.fold((EMPTY, EMPTY), |(even, odd), pair| {
                (add(even, &pair[0]), add(odd, &pair[1]))
            });
            rest.iter().fold(merge(even, odd), add)
        };
        let (lo, hi, clo, chi) = if in_parallel(items.len()) {
            items
                .par_chunks(PARALLEL_ITEMS / 4)
                .map(fold)
                .reduce(|| EMPTY, merge)
        } else {
            fold(items)
        };
        Self {
            start,
            end: start + items.len(),
            bounds: Aabb::new(lo.into(), hi.into()),
            centroids: Aabb::new(clo.into(), chi.into()),
            leaf: false,
        }
    }

    fn len(&self) -> usize {
        self.end - self.start
    }
}

/// Number of bins per axis for large ranges.
const BINS: usize = 32;
/// From how many items on binning uses two sets of bins (see `Bins::add`).
const TWO_BIN_SETS_ITEMS: usize = 256;
/// Number of bins per axis for ranges of at most `FEW_ITEMS` items, where setting up
/// and sweeping 32 bins would cost more than binning the items.
const FEW_BINS: usize = 8;
/// See [`FEW_BINS`].
const FEW_ITEMS: usize = 32;

/// Per-axis bins: boxes and counts of the items whose centroids fall in each.
///
/// `count[b][axis]` is the count of bin `b` on `axis`: the three axes' counts of a bin
/// are one register for the sweep (below 2^27, [`MAX_ITEMS`], so they fit an `i32`).
#[derive(Clone, Copy)]
struct Bins<const B: usize> {
    min: [[Vec3A; B]; 3],
    max: [[Vec3A; B]; 3],
    count: [[i32; 4]; B],
}

impl<const B: usize> Bins<B> {
    fn new() -> Self {
        Self {
            min: [[Vec3A::INFINITY; B]; 3],
            max: [[Vec3A::NEG_INFINITY; B]; 3],
            count: [[0; 4]; B],
        }
    }

    /// The `origin` and `scale` that put a range's items in bins: an item's bin
    /// position on each axis is `(centroid2 - origin) * scale`, `B` bins across the
    /// centroids' extent; an axis without extent has scale 0.
    fn mapping(range: &RangeInfo) -> (Vec3A, Vec3A) {
        let origin = Vec3A::from(range.centroids.min);
        let extent = Vec3A::from(range.centroids.max) - origin;
        let scale = Vec3A::select(
            extent.cmpgt(Vec3A::ZERO),
            Vec3A::splat(B as f32 * (1.0 - 1e-6)) / extent,
            Vec3A::ZERO,
        );
        (origin, scale)
    }

    fn add(&mut self, items: &[BuildItem], origin: Vec3A, scale: Vec3A) {
        if items.len() < TWO_BIN_SETS_ITEMS {
            for item in items {
                self.add_one(item, origin, scale);
            }
            return;
        }
        // Neighbouring items are mostly neighbours in space too and fall in the same
        // bins, so each item's update would wait for the one before it to reach memory:
        // the items at even and odd positions go to two sets of bins, two chains that
        // run side by side, merged at the end (min, max and sums: the same bins).
        let mut odd = Self::new();
        let pairs = items.chunks_exact(2);
        let rest = pairs.remainder();
        for pair in pairs {
            self.add_one(&pair[0], origin, scale);
            odd.add_one(&pair[1], origin, scale);
        }
        for item in rest {
            self.add_one(item, origin, scale);
        }
        self.merge_from(&odd);
    }

    #[inline(always)]
    fn add_one(&mut self, item: &BuildItem, origin: Vec3A, scale: Vec3A) {
        const { assert!(B.is_power_of_two()) };
        let last = (B - 1) as f32;
        let (lo, hi) = (item.min(), item.max());
        let bin = ((item.centroid2() - origin) * scale)
            .min(Vec3A::splat(last))
            .max(Vec3A::ZERO);
        for (axis, b) in whole_bins(bin).into_iter().enumerate() {
            // The bin is at most B - 1 already; the mask (B is a power of two) tells the
            // compiler so, and saves three bounds checks per item.
            let b = b & (B - 1);
            self.min[axis][b] = self.min[axis][b].min(lo);
            self.max[axis][b] = self.max[axis][b].max(hi);
            self.count[b][axis] += 1;
        }
    }

    fn merge_from(&mut self, other: &Self) {
        for axis in 0..3 {
            for b in 0..B {
                self.min[axis][b] = self.min[axis][b].min(other.min[axis][b]);
                self.max[axis][b] = self.max[axis][b].max(other.max[axis][b]);
                self.count[b][axis] += other.count[b][axis];
            }
        }
    }
}

/// The whole parts of the three lanes of `x`, which are in `[0, 2^31)`: the bins of an
/// item on the three axes.
///
/// `as` converts lane by lane and saturates (8% of the build's instructions); one
/// SSE2 conversion does the three lanes at once, with the same results in that range.
#[inline(always)]
fn whole_bins(x: Vec3A) -> [usize; 3] {
    debug_assert!(x.cmpge(Vec3A::ZERO).all() && x.cmplt(Vec3A::splat(2.0f32.powi(31))).all());
    #[cfg(target_arch = "x86_64")]
    #[allow(unsafe_code)]
    // SAFETY: these SSE2 intrinsics only compute on registers (no memory access), and
    // SSE2 is part of the x86_64 baseline, so the instructions always exist.
    unsafe {
        use std::arch::x86_64::{_mm_cvtsi128_si32, _mm_cvttps_epi32, _mm_shuffle_epi32};
        let whole = _mm_cvttps_epi32(x.into());
        [
            _mm_cvtsi128_si32(whole) as usize,
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b01>(whole)) as usize,
            _mm_cvtsi128_si32(_mm_shuffle_epi32::<0b10>(whole)) as usize,
        ]
    }
    #[cfg(not(target_arch = "x86_64"))]
    {
        let whole = x.as_uvec3();
        [whole.x as usize, whole.y as usize, whole.z as usize]
    }
}

/// Half the surface area of the box `lo..hi` (zero when empty):
/// `dx dy + dy dz + dz dx`, summed left to right.
#[inline(always)]
fn half_area(lo: Vec3A, hi: Vec3A) -> f32 {
    let d = (hi - lo).max(Vec3A::ZERO);
    // One multiply for the three products; `element_sum` adds `(x + y) + z`, the
    // order of the written-out formula, so the SAH costs are the same to the bit.
    (d * d.yzx()).element_sum()
}

/// How to divide a range.
enum Split {
    /// Make it a leaf.
    Leaf,
    /// Items whose bin (of `bins`) on `axis` is below `bin` go left.
    Plane {
        axis: usize,
        bin: usize,
        bins: usize,
        origin: Vec3A,
        scale: Vec3A,
    },
    /// Halve by count (no usable SAH split, or the tree is too deep).
    Median,
}

/// One side of a candidate split on each of the three axes: the boxes and item counts
/// (one lane per axis) of the bins swept so far.
struct Side {
    lo: [Vec3A; 3],
    hi: [Vec3A; 3],
    count: IVec4,
}

impl Side {
    const EMPTY: Self = Self {
        lo: [Vec3A::INFINITY; 3],
        hi: [Vec3A::NEG_INFINITY; 3],
        count: IVec4::ZERO,
    };

    #[inline(always)]
    fn add<const B: usize>(&mut self, bins: &Bins<B>, b: usize) {
        for axis in 0..3 {
            self.lo[axis] = self.lo[axis].min(bins.min[axis][b]);
            self.hi[axis] = self.hi[axis].max(bins.max[axis][b]);
        }
        self.count += IVec4::from_array(bins.count[b]);
    }

    /// Per axis, the side's half area times its blocks; infinite for an empty side.
    #[inline(always)]
    fn cost(&self, blocks: impl Fn(IVec4) -> Vec3A) -> Vec3A {
        let extent = |axis: usize| (self.hi[axis] - self.lo[axis]).max(Vec3A::ZERO);
        // Rows: the x, y and z extents of the three boxes.
        let d = Mat3A::from_cols(extent(0), extent(1), extent(2)).transpose();
        let (dx, dy, dz) = (d.x_axis, d.y_axis, d.z_axis);
        // `half_area`'s `(x y + y z) + z x`, lane by lane.
        let area = (dx * dy + dy * dz) + dz * dx;
        let blocks = blocks(self.count);
        Vec3A::select(blocks.cmpeq(Vec3A::ZERO), Vec3A::INFINITY, area * blocks)
    }
}

struct Builder {
    params: BuildParams,
    /// `log2(block_size)` when the block size is a power of two (1 for objects, 4 for
    /// triangle packets): [`Builder::blocks`] then shifts rather than divides, in the
    /// innermost loop of the SAH sweep.
    block_shift: Option<u32>,
}

impl Builder {
    /// A builder for `params`, brought into range: leaves of 1 to [`MAX_LEAF`] items
    /// (a leaf's ref has room for no more), blocks of 1 to 2^27 items.
    fn new(params: BuildParams) -> Self {
        // No range holds more than `MAX_ITEMS` (2^27) items, so a larger block counts
        // as one block, as a block of that size does; `n + block_size - 1` then stays
        // below 2^28 and fits an `i32`.
        let size = params.block_size.clamp(1, MAX_ITEMS as u32);
        Self {
            params: BuildParams {
                block_size: size,
                max_leaf_items: params.max_leaf_items.clamp(1, MAX_LEAF),
                ..params
            },
            block_shift: size.is_power_of_two().then(|| size.trailing_zeros()),
        }
    }

    /// `ceil(n / block_size)`, as the SAH counts it.
    fn blocks(&self, n: u32) -> f32 {
        match self.block_shift {
            // n <= 2^27 and block_size <= 2^27: `n + block_size - 1` does not overflow.
            Some(shift) => ((n + (1 << shift) - 1) >> shift) as f32,
            None => n.div_ceil(self.params.block_size) as f32,
        }
    }

    /// Chooses how to split `items` (the items of `range`) with the binned SAH.
    ///
    /// `traversal_cost` is the cost of the extra node a split would create: zero while
    /// the node being opened still has a free slot for the second half.
    fn choose_split(
        &self,
        items: &[BuildItem],
        range: &RangeInfo,
        depth: u32,
        traversal_cost: f32,
    ) -> Split {
        let n = items.len();
        let small = n <= self.params.max_leaf_items as usize;
        // One block is a leaf: split, it would take two blocks (for a mesh, two triangle
        // packets with lanes to spare), and the SAH's areas can favour that while the
        // node has free slots, where a split costs no node. Otherwise a leaf costs
        // `blocks(n)` per unit of area, a split at least `traversal_cost`: when the leaf
        // is no dearer, it wins without binning.
        if n <= self.params.block_size.min(self.params.max_leaf_items) as usize
            || small && self.blocks(n as u32) <= traversal_cost
        {
            return Split::Leaf;
        }
        if depth >= FORCE_MEDIAN_DEPTH {
            return if small { Split::Leaf } else { Split::Median };
        }
        if n <= FEW_ITEMS {
            self.binned_sah::<FEW_BINS>(items, range, traversal_cost)
        } else {
            self.binned_sah::<BINS>(items, range, traversal_cost)
        }
    }

    /// [`Builder::choose_split`] with `B` bins per axis.
    fn binned_sah<const B: usize>(
        &self,
        items: &[BuildItem],
        range: &RangeInfo,
        traversal_cost: f32,
    ) -> Split {
        let n = items.len();
        let small = n <= self.params.max_leaf_items as usize;
        let (origin, scale) = Bins::<B>::mapping(range);
        if scale == Vec3A::ZERO {
            return if small { Split::Leaf } else { Split::Median };
        }
        // Filled in place: the bins are 0.9 KB (8) to 3.4 KB (32), and moving them out
        // of a block costs a copy on each of the many small ranges.
        let mut bins = Bins::<B>::new();
        if in_parallel(n) {
            bins = items
                .par_chunks(PARALLEL_ITEMS / 4)
                .map(|chunk| {
                    let mut bins = Bins::<B>::new();
                    bins.add(chunk, origin, scale);
                    bins
                })
                .reduce(Bins::new, |mut a, b| {
                    a.merge_from(&b);
                    a
                });
        } else {
            bins.add(items, origin, scale);
        }

        let Some((split_cost, axis, bin)) = self.sweep(&bins, scale) else {
            return if small { Split::Leaf } else { Split::Median };
        };
        let area = half_area(range.bounds.min.into(), range.bounds.max.into());
        let leaf_cost = area * self.blocks(n as u32);
        if small && leaf_cost <= area * traversal_cost + split_cost {
            return Split::Leaf;
        }
        Split::Plane {
            axis,
            bin,
            bins: B,
            origin,
            scale,
        }
    }

    /// The cheapest split of the binned items: its SAH cost (the children's areas times
    /// their blocks), axis and bin, the lowest axis and then the lowest bin among equal
    /// costs; `None` when no split has two nonempty sides.
    ///
    /// The three axes are swept side by side, one lane each: per bin, the three boxes'
    /// half areas come from one transposed set of extents, with the operations of
    /// [`half_area`] in its order, so each lane's cost is the one an axis-by-axis sweep
    /// would compute, to the bit. An empty bin changes neither side, so its costs are
    /// its neighbour's and, compared strictly, never win.
    #[inline(always)]
    fn sweep<const B: usize>(&self, bins: &Bins<B>, scale: Vec3A) -> Option<(f32, usize, usize)> {
        // [`Builder::blocks`] of the first three lanes (counts below 2^27), chosen once
        // per sweep: for a power-of-two block size one add, one shift and one conversion
        // for the three, with the same results (the sums are below 2^28, where `i32`
        // and `u32` agree).
        match self.block_shift {
            Some(shift) => self.sweep_with(bins, scale, |n: IVec4| {
                let whole = (n + IVec4::splat((1 << shift) - 1)) >> shift;
                Vec3A::from_vec4(whole.as_vec4())
            }),
            None => self.sweep_with(bins, scale, |n: IVec4| {
                Vec3A::from_array(n.truncate().to_array().map(|n| self.blocks(n as u32)))
            }),
        }
    }

    /// [`Builder::sweep`] with `blocks` counting the blocks of three counts.
    #[inline(always)]
    fn sweep_with<const B: usize>(
        &self,
        bins: &Bins<B>,
        scale: Vec3A,
        blocks: impl Fn(IVec4) -> Vec3A + Copy,
    ) -> Option<(f32, usize, usize)> {
        // `right_cost[b]`: the cost of the bins `b..B` on each axis.
        let mut right_cost = [Vec3A::ZERO; B];
        let mut side = Side::EMPTY;
        for b in (1..B).rev() {
            side.add(bins, b);
            right_cost[b] = side.cost(blocks);
        }
        let (mut best_cost, mut best_bin) = (Vec3A::INFINITY, Vec3A::ZERO);
        let mut side = Side::EMPTY;
        for (b, right) in right_cost.iter().enumerate().skip(1) {
            side.add(bins, b - 1);
            let cost = side.cost(blocks) + *right;
            let better = cost.cmplt(best_cost);
            best_cost = Vec3A::select(better, cost, best_cost);
            best_bin = Vec3A::select(better, Vec3A::splat(b as f32), best_bin);
        }
        // An axis without extent has all its items in bin 0 and no split.
        let best_cost = Vec3A::select(scale.cmpeq(Vec3A::ZERO), Vec3A::INFINITY, best_cost);
        let axis = (0..3).fold(0, |best, axis| {
            if best_cost[axis] < best_cost[best] {
                axis
            } else {
                best
            }
        });
        best_cost[axis]
            .is_finite()
            .then(|| (best_cost[axis], axis, best_bin[axis] as usize))
    }

    /// Splits `range` (whose items are `items`) into two, or decides it is a leaf.
    fn split(
        &self,
        items: &mut [BuildItem],
        range: RangeInfo,
        depth: u32,
    ) -> Result<(RangeInfo, RangeInfo), RangeInfo> {
        match self.choose_split(items, &range, depth, 0.0) {
            Split::Leaf => Err(RangeInfo {
                leaf: true,
                ..range
            }),
            Split::Plane {
                axis,
                bin,
                bins,
                origin,
                scale,
            } => {
                // The item's bin is its position `x` clamped to [0, bins - 1] and
                // truncated (see `Bins::add`); for a whole `bin` in 1..bins, that bin is
                // below `bin` exactly when `x < bin` (positions are finite).
                debug_assert!((1..bins).contains(&bin));
                // All three lanes at once and then the axis's bit of the mask: picking
                // the lane first would branch on `axis` for every item.
                let bin = Vec3A::splat(bin as f32);
                let goes_left = |item: &BuildItem| {
                    (((item.centroid2() - origin) * scale).cmplt(bin).bitmask() >> axis) & 1 != 0
                };
                let mid = partition(items, goes_left);
                let (left, right) = items.split_at(mid);
                Ok((
                    RangeInfo::of(left, range.start),
                    RangeInfo::of(right, range.start + mid),
                ))
            }
            Split::Median => {
                let axis = Vec3A::from(range.centroids.max - range.centroids.min).max_position();
                let mid = items.len() / 2;
                items.select_nth_unstable_by(mid, |a, b| {
                    a.centroid2()[axis].total_cmp(&b.centroid2()[axis])
                });
                let (left, right) = items.split_at(mid);
                Ok((
                    RangeInfo::of(left, range.start),
                    RangeInfo::of(right, range.start + mid),
                ))
            }
        }
    }

    /// Builds the node for `range` (whose items are `items`) and its subtree, appending
    /// the nodes to `out`; returns the node's index.
    fn build_node(
        &self,
        items: &mut [BuildItem],
        range: RangeInfo,
        depth: u32,
        out: &mut Vec<Node>,
    ) -> u32 {
        let index = out.len();
        out.push(Node::EMPTY);

        // Open the range into up to eight children, always splitting the largest one.
        // (In an array on the stack: a vector was two allocations per node.)
        let mut slots = [range; WIDTH];
        let mut len = 1;
        while len < WIDTH {
            let candidate = slots[..len]
                .iter()
                .enumerate()
                .filter(|(_, c)| !c.leaf)
                .max_by(|a, b| {
                    a.1.bounds
                        .surface_area()
                        .total_cmp(&b.1.bounds.surface_area())
                })
                .map(|(i, _)| i);
            let Some(i) = candidate else { break };
            let child = slots[i];
            let local = child.start - range.start..child.end - range.start;
            match self.split(&mut items[local], child, depth) {
                Ok((left, right)) => {
                    slots[i] = left;
                    slots[len] = right;
                    len += 1;
                }
                Err(leaf) => slots[i] = leaf,
            }
        }
        let children = &mut slots[..len];
        // The children left unsplit become nodes unless, small enough, the full SAH
        // (now counting the cost of a new node) prefers a leaf.
        for child in children.iter_mut() {
            if !child.leaf && child.len() <= self.params.max_leaf_items as usize {
                let local = &items[child.start - range.start..child.end - range.start];
                let split = self.choose_split(local, child, depth + 1, self.params.traversal_cost);
                child.leaf = matches!(split, Split::Leaf);
            }
        }
        children.sort_by_key(|c| c.start);
        let children = &*children;

        // The children's items: disjoint slices, in order.
        let mut rest = items;
        let slices = children.iter().map(move |child| {
            let (head, tail) = std::mem::take(&mut rest).split_at_mut(child.len());
            rest = tail;
            head
        });
        let mut node = Node::EMPTY;
        if in_parallel(range.len()) {
            let slices: Vec<&mut [BuildItem]> = slices.collect();
            // Build the inner children's subtrees in parallel, each into its own array,
            // then append them with their node indices shifted.
            let subtrees: Vec<Option<Vec<Node>>> = children
                .par_iter()
                .zip(slices.into_par_iter())
                .map(|(child, slice)| {
                    (!child.leaf).then(|| {
                        let mut nodes = Vec::new();
                        self.build_node(slice, *child, depth + 1, &mut nodes);
                        nodes
                    })
                })
                .collect();
            for (slot, (child, subtree)) in children.iter().zip(subtrees).enumerate() {
                let child_ref = match subtree {
                    None => leaf_ref(child.start, child.len()),
                    Some(subtree) => {
                        let base = out.len() as u32;
                        out.extend(subtree.into_iter().map(|mut n| {
                            for c in &mut n.children {
                                if *c & LEAF == 0 {
                                    *c += base;
                                }
                            }
                            n
                        }));
                        base
                    }
                };
                node.set_child(slot, &child.bounds, child_ref);
            }
        } else {
            for (slot, (child, slice)) in children.iter().zip(slices).enumerate() {
                let child_ref = if child.leaf {
                    leaf_ref(child.start, child.len())
                } else {
                    self.build_node(slice, *child, depth + 1, out)
                };
                node.set_child(slot, &child.bounds, child_ref);
            }
        }
        out[index] = node;
        index as u32
    }
}

/// Moves the items for which `goes_left` holds to the front; returns how many there
/// are. (Gathering both sides' extents in the same pass was slower: their eight
/// accumulators and the split plane do not fit the sixteen SSE registers, and each
/// item's update went through the stack.)
fn partition(items: &mut [BuildItem], goes_left: impl Fn(&BuildItem) -> bool) -> usize {
    let mut left = 0;
    for i in 0..items.len() {
        let item = items[i];
        let go = goes_left(&item);
        items[i] = items[left];
        items[left] = item;
        left += usize::from(go);
    }
    left
}

#[cfg(test)]
mod tests;

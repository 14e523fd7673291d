//! Tests of the builder's parts against their plain versions (the SSE2 conversion, the
//! three-axes sweep, the partition, two sets of bins) and of the trees it builds.

use glam::Vec3;
use proptest::prelude::*;

use super::*;
use crate::bvh::node::MAX_LEAF;

proptest! {
    /// The SSE2 conversion gives what `as` gives, lane by lane, over the bins' range
    /// and beyond it (fractions just below a whole number included).
    #[test]
    fn whole_bins_are_the_lanes_truncated(
        x in 0.0f32..64.0,
        y in 0.0f32..2_147_483_520.0,
        z in prop::sample::select(vec![0.0f32, 0.999_999_94, 1.0, 30.999_998, 31.0]),
    ) {
        let v = Vec3A::new(x, y, z);
        prop_assert_eq!(whole_bins(v), [x as usize, y as usize, z as usize]);
    }

    /// The three axes swept side by side choose what a sweep axis by axis chooses,
    /// with the same cost to the bit, for 8 and 32 bins and blocks of 1, 3, 4, 8 and
    /// 2^31 items (more than a range holds); the boxes lie on a coarse grid so that
    /// bins are often empty, costs often tie and an axis often has no extent.
    #[test]
    fn the_sweep_of_three_axes_is_the_sweep_axis_by_axis(
        boxes in prop::collection::vec(
            (prop::array::uniform3(0u8..6), prop::array::uniform3(0u8..4)),
            1..120,
        ),
        flat in prop::sample::select(vec![None, Some(0usize), Some(1), Some(2)]),
        block_size in prop::sample::select(vec![1u32, 3, 4, 8, 1 << 31]),
    ) {
        let items: Vec<BuildItem> = boxes
            .iter()
            .enumerate()
            .map(|(i, (lo, size))| {
                let mut lo = Vec3::from(lo.map(f32::from));
                if let Some(axis) = flat {
                    lo[axis] = 1.0;
                }
                let hi = lo + Vec3::from(size.map(f32::from));
                BuildItem::new(Aabb::new(lo, hi), i as u32)
            })
            .collect();
        let builder = Builder::new(BuildParams { block_size, ..BuildParams::default() });
        let range = RangeInfo::of(&items, 0);
        prop_assert_eq!(
            sweeps_agree::<FEW_BINS>(&builder, &items, &range),
            Ok(())
        );
        prop_assert_eq!(sweeps_agree::<BINS>(&builder, &items, &range), Ok(()));
    }
}

/// A block size beyond 2^27 items ([`MAX_ITEMS`], the most a range holds) counts
/// blocks as the size it is clamped to does: one for every nonempty range.
#[test]
fn a_block_larger_than_any_range_counts_one_block() {
    for size in [1 << 27, (1 << 27) + 1, 1 << 28, 1 << 31, u32::MAX] {
        let builder = Builder::new(BuildParams {
            block_size: size,
            ..BuildParams::default()
        });
        for n in [0, 1, 5, 1 << 20, 1 << 27] {
            assert_eq!(builder.blocks(n), n.div_ceil(size) as f32, "{size} {n}");
        }
    }
}

/// The partition puts exactly the items that go left in front, the others behind,
/// and loses none (all left, all right, alternating and random sides, from 0 to 300
/// items); the bounds and centroid bounds of each side are those of its items.
#[test]
fn partition_moves_the_left_items_to_the_front() {
    let mut random = xorshift(0x1234_5678);
    for n in [0usize, 1, 2, 3, 7, 64, 300] {
        for pattern in 0..4 {
            let mut items: Vec<BuildItem> = (0..n)
                .map(|i| {
                    let x = match pattern {
                        0 => -1.0,
                        1 => 1.0,
                        2 => {
                            if i % 2 == 0 {
                                -1.0
                            } else {
                                1.0
                            }
                        }
                        _ => (random() % 1000) as f32 - 500.0,
                    };
                    let min = Vec3::new(x, i as f32, 0.0);
                    BuildItem::new(Aabb::new(min, min + Vec3::ONE), i as u32)
                })
                .collect();
            let goes_left = |item: &BuildItem| item.centroid2().x < 0.5;
            let left_count = items.iter().filter(|item| goes_left(item)).count();
            let mid = partition(&mut items, goes_left);
            assert_eq!(mid, left_count, "{n} items, pattern {pattern}");
            assert!(items[..mid].iter().all(goes_left));
            assert!(!items[mid..].iter().any(goes_left));
            let mut indices: Vec<u32> = items.iter().map(BuildItem::index).collect();
            indices.sort_unstable();
            assert!(
                indices.iter().copied().eq(0..n as u32),
                "items lost or repeated"
            );
            for side in [&items[..mid], &items[mid..]] {
                if side.is_empty() {
                    continue;
                }
                let range = RangeInfo::of(side, 0);
                let lo = side
                    .iter()
                    .fold(Vec3A::INFINITY, |lo, item| lo.min(item.min()));
                let hi = side
                    .iter()
                    .fold(Vec3A::NEG_INFINITY, |hi, item| hi.max(item.max()));
                assert_eq!(Vec3A::from(range.bounds.min), lo);
                assert_eq!(Vec3A::from(range.bounds.max), hi);
                let c = side.iter().map(BuildItem::centroid2);
                let c_lo = c.clone().fold(Vec3A::INFINITY, Vec3A::min);
                let c_hi = c.fold(Vec3A::NEG_INFINITY, Vec3A::max);
                assert_eq!(Vec3A::from(range.centroids.min), c_lo);
                assert_eq!(Vec3A::from(range.centroids.max), c_hi);
            }
        }
    }
}

/// 40 boxes with one centre, which no plane separates: asked for leaves of up to
/// 100 items (clamped to 16) and of up to 0 (counted as 1), they still become
/// leaves of 1 to 16 items that hold every item once. (A leaf's ref has four bits
/// for its count: a leaf of 40 would name the wrong items.)
#[test]
fn leaves_hold_at_most_sixteen_items_whatever_is_asked() {
    let boxes = vec![Aabb::new(Vec3::ZERO, Vec3::ONE); 40];
    for max_leaf_items in [0, 100] {
        let bvh = Bvh::build(
            &boxes,
            BuildParams {
                max_leaf_items,
                ..BuildParams::default()
            },
        );
        let mut seen = [0; 40];
        for (start, count) in bvh.leaves() {
            assert!((1..=MAX_LEAF).contains(&count), "{max_leaf_items}: {count}");
            for position in start..start + count {
                seen[bvh.item_order()[position as usize] as usize] += 1;
            }
        }
        assert_eq!(seen, [1; 40], "{max_leaf_items}");
    }
}

#[test]
fn a_build_item_keeps_its_box_and_index_and_no_lane_is_denormal() {
    let bounds = Aabb::new(Vec3::new(-1.0, 2.0, -3.5), Vec3::new(4.0, 5.0, 6.25));
    for index in [0, 1, 7, (1 << 23) - 1, 1 << 23, MAX_ITEMS as u32 - 1] {
        let item = BuildItem::new(bounds, index);
        assert_eq!(item.index(), index);
        assert_eq!(Vec3::from(item.min()), bounds.min);
        assert_eq!(Vec3::from(item.max()), bounds.max);
        assert!(item.lo.w.is_normal(), "index {index}: {}", item.lo.w);
        assert_eq!(item.hi.w, 0.0);
        assert_eq!(Vec3::from(item.centroid2()), Vec3::new(3.0, 7.0, 2.75));
    }
}

/// Binning a large range into two sets of bins and merging them gives the bins of
/// one item at a time, for an even and an odd number of items, the last bin
/// included; so does binning an empty range.
#[test]
fn two_sets_of_bins_give_the_bins_of_one() {
    for n in [0, TWO_BIN_SETS_ITEMS - 1, TWO_BIN_SETS_ITEMS, 1001] {
        // Boxes of different sizes along a slanted line, in an order that puts
        // neighbours in different bins now and then.
        let items: Vec<BuildItem> = (0..n)
            .map(|i| {
                let k = (i * 37 % n.max(1)) as f32;
                let lo = Vec3::new(k, 0.5 * k, -0.25 * k);
                let size = 1.0 + (i % 5) as f32;
                BuildItem::new(Aabb::new(lo, lo + Vec3::splat(size)), i as u32)
            })
            .collect();
        let (origin, scale) = Bins::<BINS>::mapping(&RangeInfo::of(&items, 0));
        let mut both = Bins::<BINS>::new();
        both.add(&items, origin, scale);
        let mut one = Bins::<BINS>::new();
        for item in &items {
            one.add_one(item, origin, scale);
        }
        assert_eq!(both.count, one.count, "{n} items");
        assert_eq!(both.count.iter().map(|c| c[0]).sum::<i32>() as usize, n);
        assert_eq!(both.min, one.min, "{n} items");
        assert_eq!(both.max, one.max, "{n} items");
    }
}

/// Only a pool of two or more threads builds in parallel, and only ranges of
/// `PARALLEL_ITEMS` or more (the two paths give the same hierarchy, see below; on
/// one thread the parallel one is only slower).
#[test]
fn only_large_ranges_on_several_threads_are_built_in_parallel() {
    let in_pool = |threads: usize, n: usize| pool(threads).install(|| in_parallel(n));
    assert!(!in_pool(1, 100 * PARALLEL_ITEMS));
    assert!(in_pool(2, PARALLEL_ITEMS));
    assert!(!in_pool(2, PARALLEL_ITEMS - 1));
    assert!(in_pool(3, 100 * PARALLEL_ITEMS));
}

/// A range large enough to be built in parallel gives the same hierarchy, node for
/// node, on one thread (where it is built serially) and on three.
#[test]
fn the_hierarchy_is_the_same_on_one_thread_and_on_three() {
    let mut bits = xorshift(0x2545_f491);
    let mut random = move || (bits() % 10_000) as f32 / 100.0;
    let boxes: Vec<Aabb> = (0..3 * PARALLEL_ITEMS)
        .map(|_| {
            let lo = Vec3::new(random(), random(), random());
            Aabb::new(lo, lo + Vec3::new(random(), random(), random()) / 50.0)
        })
        .collect();
    let build =
        |threads: usize| pool(threads).install(|| Bvh::build(&boxes, BuildParams::default()));
    let (one, three) = (build(1), build(3));
    assert!(one.node_count() > 1000);
    assert_eq!(one.item_order, three.item_order);
    assert_eq!(one.nodes.len(), three.nodes.len());
    for (a, b) in one.nodes.iter().zip(&three.nodes) {
        assert_eq!(a.children, b.children);
        assert_eq!(
            a.planes.map(|row| row.map(f32::to_bits)),
            b.planes.map(|row| row.map(f32::to_bits))
        );
    }
}

/// A rayon pool of `threads` threads.
fn pool(threads: usize) -> rayon::ThreadPool {
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads)
        .build()
        .expect("a pool")
}

/// A xorshift generator of 32-bit numbers from `seed` (not zero), for test data.
fn xorshift(seed: u32) -> impl FnMut() -> u32 {
    let mut state = seed;
    move || {
        state ^= state << 13;
        state ^= state >> 17;
        state ^= state << 5;
        state
    }
}

/// Whether [`Builder::sweep`] agrees with [`sweep_axis_by_axis`] on `items` put in
/// `B` bins: `Err` with both answers when not.
fn sweeps_agree<const B: usize>(
    builder: &Builder,
    items: &[BuildItem],
    range: &RangeInfo,
) -> Result<(), String> {
    let (origin, scale) = Bins::<B>::mapping(range);
    let mut bins = Bins::<B>::new();
    bins.add(items, origin, scale);
    let side_by_side = builder
        .sweep(&bins, scale)
        .map(|(c, a, b)| (c.to_bits(), a, b));
    let by_axis = sweep_axis_by_axis(builder, &bins, scale).map(|(c, a, b)| (c.to_bits(), a, b));
    if side_by_side == by_axis {
        Ok(())
    } else {
        Err(format!("{B} bins: {side_by_side:?} against {by_axis:?}"))
    }
}

/// The SAH sweep one axis at a time, each bin's cost from [`half_area`] and
/// [`Builder::blocks`]: what [`Builder::sweep`] must match.
fn sweep_axis_by_axis<const B: usize>(
    builder: &Builder,
    bins: &Bins<B>,
    scale: Vec3A,
) -> Option<(f32, usize, usize)> {
    let mut best: Option<(f32, usize, usize)> = None;
    for axis in (0..3).filter(|&axis| scale[axis] != 0.0) {
        let mut right_cost = [f32::INFINITY; B];
        let (mut lo, mut hi, mut count) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
        for b in (1..B).rev() {
            lo = lo.min(bins.min[axis][b]);
            hi = hi.max(bins.max[axis][b]);
            count += bins.count[b][axis] as u32;
            if count > 0 {
                right_cost[b] = half_area(lo, hi) * builder.blocks(count);
            }
        }
        let (mut lo, mut hi, mut count) = (Vec3A::INFINITY, Vec3A::NEG_INFINITY, 0);
        for (b, right) in right_cost.iter().enumerate().skip(1) {
            lo = lo.min(bins.min[axis][b - 1]);
            hi = hi.max(bins.max[axis][b - 1]);
            count += bins.count[b - 1][axis] as u32;
            if count == 0 {
                continue;
            }
            let cost = half_area(lo, hi) * builder.blocks(count) + right;
            if best.is_none_or(|(c, _, _)| cost < c) {
                best = Some((cost, axis, b));
            }
        }
    }
    best.filter(|(c, _, _)| c.is_finite())
}

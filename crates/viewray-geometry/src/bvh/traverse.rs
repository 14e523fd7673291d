//! A single ray's walks through the hierarchy: its box test against a node's eight
//! children, the closest-hit walk (nearest child first, one step at a time, so that the
//! rays of an incoherent packet can take turns) and the any-hit walk, with the stacks
//! they reuse from a thread-local.

use std::cell::RefCell;
use std::thread::LocalKey;

use glam::{Vec3, Vec4};

use super::memory::prefetch;
use super::node::{Bvh, GROUPS, LEAF, Node, WIDTH, decode_leaf};
use crate::Ray;

/// The traversal stack: a node pushes at most `WIDTH - 1 = 7` entries more than it pops
/// (the closest-hit walk pushes the hit children but the nearest; the any-hit walk
/// pushes all `WIDTH` and pops one at once, hence the `+ 1`), and the tree is less than
/// 67 nodes deep (the builder's bound, see `FORCE_MEDIAN_DEPTH` in `build.rs`).
pub(crate) const STACK_SIZE: usize = (WIDTH - 1) * 67 + 1;
/// The stack's length: `STACK_SIZE` and a node's row of `WIDTH` more, so that a node's
/// sorted children are pushed as one fixed-size copy of the whole row (only the first
/// ones count; a copy of variable length is a call to `memcpy`).
pub(crate) const STACK_ROOM: usize = STACK_SIZE + WIDTH;

/// A traversal stack: subtrees still to visit and the distances at which the ray
/// enters them.
pub(crate) struct Stack {
    pub(crate) refs: [u32; STACK_ROOM],
    pub(crate) t: [f32; STACK_ROOM],
}

impl Stack {
    const EMPTY: Self = Self {
        refs: [0; STACK_ROOM],
        t: [0.0; STACK_ROOM],
    };
}

thread_local! {
    /// Four stacks per thread, enough for a world's packet traversal, the mesh packet
    /// traversal nested in it and the single rays that finish its subtrees: a stack is
    /// several kilobytes, and zeroing a fresh one for every ray cost a quarter of the
    /// time of a primary ray.
    static STACKS: [RefCell<Stack>; 4] = const {
        [
            RefCell::new(Stack::EMPTY),
            RefCell::new(Stack::EMPTY),
            RefCell::new(Stack::EMPTY),
            RefCell::new(Stack::EMPTY),
        ]
    };
}

/// Runs `f` with a value of this thread's `pool` that no caller up the stack holds, or
/// hands `f` back when callbacks nest deeper than the pool has values.
#[inline(always)]
fn with_free<T, const N: usize, R, F: FnOnce(&mut T) -> R>(
    pool: &'static LocalKey<[RefCell<T>; N]>,
    f: F,
) -> Result<R, F> {
    let mut f = Some(f);
    let done = pool.with(|cells| {
        for cell in cells {
            if let Ok(mut value) = cell.try_borrow_mut() {
                return f.take().map(|f| f(&mut value));
            }
        }
        None
    });
    match (done, f) {
        (Some(result), _) => Ok(result),
        (None, Some(f)) => Err(f),
        (None, None) => unreachable!("the closure runs at most once"),
    }
}

/// Runs `f` with a free traversal stack of this thread (a fresh one when callbacks
/// nest traversals more than four deep).
#[inline(always)]
pub(crate) fn with_stack<R>(f: impl FnOnce(&mut Stack) -> R) -> R {
    with_free(&STACKS, f).unwrap_or_else(|f| {
        let mut fresh = Stack::EMPTY;
        f(&mut fresh)
    })
}

/// How many rays walk the tree side by side in an incoherent packet.
pub(crate) const WALKS: usize = 8;
/// The fewest nodes for which an incoherent packet's rays walk side by side: 2 MiB of
/// nodes, twice a core's L2 cache on common processors. Below it most of a walk's loads
/// hit the caches, and taking turns only adds work. 1M incoherent rays on 1 thread, in
/// packets of 64, side by side against one after another: 0.30 s against 0.23 s on a
/// 20k-triangle icosphere (938 nodes), 0.29 s against 0.27 s on 82k (4,660 nodes);
/// 0.30-0.32 s against 0.39-0.43 s on 330k (24,936 nodes), 0.33-0.36 s against
/// 0.47-0.51 s on 1.3M (53,038 nodes).
const WALK_NODES: usize = 8192;

thread_local! {
    /// The stacks of walks side by side.
    static WALK_STACKS: [RefCell<[Stack; WALKS]>; 1] =
        const { [RefCell::new([Stack::EMPTY; WALKS])] };
}

#[cfg(test)]
thread_local! {
    /// Tests set this to walk incoherent packets side by side in trees of any size.
    pub(crate) static WALK_ALWAYS: std::cell::Cell<bool> = const { std::cell::Cell::new(false) };
}

/// Runs `f` with this thread's [`WALKS`] stacks for walks side by side (fresh ones if a
/// callback nests another such walk).
#[inline(always)]
pub(crate) fn with_walk_stacks<R>(f: impl FnOnce(&mut [Stack; WALKS]) -> R) -> R {
    with_free(&WALK_STACKS, f).unwrap_or_else(|f| f(&mut Box::new([Stack::EMPTY; WALKS])))
}

/// The robust enlargement of box exits: `1 + 2 gamma(3)` (Ize, "Robust BVH Ray
/// Traversal", JCGT 2013), so that rounding never culls a box a ray grazes.
pub(crate) const ROBUST: f32 = 1.0 + 2.0 * 3.0 * f32::EPSILON;

/// The slab numbers of four rays along one axis, from their origins `o` and directions
/// `d` on that axis: the origin moved for the near plane, the origin moved for the far
/// plane, and the reciprocal direction. Every box test, single ray or packet, starts
/// from these, so a packet's rays are tested with exactly the single-ray numbers.
///
/// A ray parallel to the slabs never leaves the slab it starts in. With 1 / 0 = inf, a
/// ray exactly on a box face would give 0 * inf = NaN; a direction component below
/// 1e-30 is replaced by +-1e-30, whose huge finite reciprocal avoids the NaN, and the
/// origin is moved a little into the slab for each plane (toward the far plane for the
/// near one, and back for the far one), which keeps a ray on the face inside the closed
/// slab: (max - o) * 1e30 would otherwise make it leave at t = 0.
#[inline(always)]
pub(crate) fn slab_numbers(o: Vec4, d: Vec4) -> (Vec4, Vec4, Vec4) {
    let small = d.abs().cmplt(Vec4::splat(1e-30));
    if !small.any() {
        return (o, o, Vec4::ONE / d);
    }
    let sign = Vec4::ONE.copysign(d);
    let shift = (o.abs() * 1e-6).max(Vec4::splat(1e-20));
    let near = Vec4::select(small, o + sign * shift, o);
    let far = Vec4::select(small, o - sign * shift, o);
    let d = Vec4::select(small, sign * 1e-30, d);
    (near, far, Vec4::ONE / d)
}

/// The slab test of four (ray, box) pairs, from the distances to each pair's near and
/// far plane on each axis: which pairs' slab intervals meet `[t_min, t_max]`, and the
/// entry distances. The exit distance is enlarged by [`ROBUST`].
#[inline(always)]
pub(crate) fn slab_test(near: [Vec4; 3], far: [Vec4; 3], t_min: Vec4, t_max: Vec4) -> (u32, Vec4) {
    let t_near = near[0].max(near[1]).max(near[2]).max(t_min);
    let t_far = (far[0].min(far[1]).min(far[2]) * ROBUST).min(t_max);
    (t_near.cmple(t_far).bitmask(), t_near)
}

/// The distances along four rays to four near and far slab planes on each axis:
/// `(plane - origin) * inverse`, with the origin moved for each plane (see
/// [`slab_numbers`]).
#[inline(always)]
pub(crate) fn plane_distances(
    near_plane: [Vec4; 3],
    far_plane: [Vec4; 3],
    origin_near: [Vec4; 3],
    origin_far: [Vec4; 3],
    inverse: [Vec4; 3],
) -> ([Vec4; 3], [Vec4; 3]) {
    (
        per_axis(|axis| (near_plane[axis] - origin_near[axis]) * inverse[axis]),
        per_axis(|axis| (far_plane[axis] - origin_far[axis]) * inverse[axis]),
    )
}

/// `[f(0), f(1), f(2)]`, written out: `array::map` is not always inlined in the hot
/// loops, and then costs a call per box test.
#[inline(always)]
pub(crate) fn per_axis<T>(f: impl Fn(usize) -> T) -> [T; 3] {
    [f(0), f(1), f(2)]
}

/// Where a ray's closest-hit walk stands (see [`Bvh::closest_step`]): the subtree it
/// visits next, how many entries of its stack are pending, and its closest hit so far.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Walk {
    pub(crate) current: u32,
    pub(crate) sp: usize,
    pub(crate) t_max: f32,
}

impl Walk {
    /// A walk that starts at `start` (a node index or a leaf ref) with nothing pending.
    pub(crate) const fn new(start: u32, t_max: f32) -> Self {
        Self {
            current: start,
            sp: 0,
            t_max,
        }
    }
}

/// A single ray's test against a node's eight boxes: [`BoxRay`] with SSE, the x86-64
/// baseline, and the same test in one AVX register where the processor has it
/// (`avx::AvxRay`), with the same bits.
pub(crate) trait ChildBoxes {
    /// The bit mask of the boxes whose slab interval meets `[t_min, t_max]`, and the
    /// entry distances (see [`slab_test`]).
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]);
}

impl ChildBoxes for BoxRay {
    #[inline(always)]
    fn hit_children<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: f32,
        t_max: f32,
    ) -> (u32, [f32; WIDTH]) {
        self.hit_children_sse::<OCTANT>(node, Vec4::splat(t_min), Vec4::splat(t_max))
    }
}

/// What a single ray's closest-hit traversal carries down the tree besides its closest
/// distance: the ray, where hits may start, and what happens at leaves.
pub(crate) struct RayTraversal<'a, R, L, P> {
    pub(crate) ray: &'a R,
    pub(crate) t_min: f32,
    /// `leaf(start, count, t_max)` intersects the items of a leaf and returns the new
    /// closest distance.
    pub(crate) leaf: L,
    /// Starts loading the items of a leaf the ray will visit.
    pub(crate) prefetch_leaf: P,
}

/// A ray prepared for box tests: origin and reciprocal direction splatted across lanes,
/// and the direction's sign pattern, which selects the monomorphized traversal.
#[derive(Clone, Copy, Debug)]
pub(crate) struct BoxRay {
    pub(crate) origin_near: [Vec4; 3],
    pub(crate) origin_far: [Vec4; 3],
    pub(crate) inverse: [Vec4; 3],
    /// Bit `axis` is set when the direction is negative on that axis.
    pub(crate) octant: u8,
    /// Whether origin and direction are finite and the direction is not zero; other
    /// rays hit nothing (and would make NaN of the box tests).
    pub(crate) valid: bool,
}

impl BoxRay {
    pub(crate) fn new(ray: &Ray) -> Self {
        let (o, d) = (ray.origin, ray.direction);
        let numbers = per_axis(|axis| slab_numbers(Vec4::splat(o[axis]), Vec4::splat(d[axis])));
        let octant = (0..3).fold(0, |bits, axis| {
            bits | (u8::from(d[axis].is_sign_negative()) << axis)
        });
        Self {
            origin_near: per_axis(|axis| numbers[axis].0),
            origin_far: per_axis(|axis| numbers[axis].1),
            inverse: per_axis(|axis| numbers[axis].2),
            octant,
            valid: o.is_finite() && d.is_finite() && d != Vec3::ZERO,
        }
    }

    /// The ray of lane `lane` of a packet.
    #[inline(always)]
    pub(crate) fn from_lanes(
        origin_near: [f32; 3],
        origin_far: [f32; 3],
        inverse: [f32; 3],
        octant: u8,
    ) -> Self {
        Self {
            origin_near: origin_near.map(Vec4::splat),
            origin_far: origin_far.map(Vec4::splat),
            inverse: inverse.map(Vec4::splat),
            octant,
            valid: true,
        }
    }

    /// Tests the ray against a node's eight boxes, two groups of four with SSE; returns
    /// the bit mask of boxes whose slab interval meets `[t_min, t_max]`, and the entry
    /// distances (see [`slab_test`]).
    #[inline(always)]
    pub(crate) fn hit_children_sse<const OCTANT: u8>(
        &self,
        node: &Node,
        t_min: Vec4,
        t_max: Vec4,
    ) -> (u32, [f32; WIDTH]) {
        let p = &node.planes;
        let mut mask = 0;
        let mut t_near_all = [0.0; WIDTH];
        for group in 0..GROUPS {
            let lanes = 4 * group..4 * group + 4;
            let (near_plane, far_plane) = node_planes::<OCTANT>(p, lanes.clone());
            let (near, far) = plane_distances(
                near_plane,
                far_plane,
                self.origin_near,
                self.origin_far,
                self.inverse,
            );
            let (hit, t_near) = slab_test(near, far, t_min, t_max);
            mask |= hit << (4 * group);
            t_near.write_to_slice(&mut t_near_all[lanes]);
        }
        (mask, t_near_all)
    }
}

/// Which of a node's `planes` is the near (or, with `far`, the far) plane along `axis`
/// for rays whose direction signs are `OCTANT`: the min plane for a positive direction.
#[inline(always)]
pub(crate) const fn plane_index<const OCTANT: u8>(axis: usize, far: bool) -> usize {
    let negative = (OCTANT >> axis) & 1 == 1;
    axis + if negative != far { 3 } else { 0 }
}

/// The near and far planes, per axis, of four of a node's boxes (`lanes`) for rays whose
/// direction signs are `OCTANT`.
///
/// Choosing the near and far plane by the direction's sign (rather than taking min and
/// max of the distances) keeps an empty box (min > max) empty, so unused slots never
/// hit. The sign pattern is a constant of the monomorphized traversal.
#[inline(always)]
pub(crate) fn node_planes<const OCTANT: u8>(
    planes: &[[f32; WIDTH]; 6],
    lanes: std::ops::Range<usize>,
) -> ([Vec4; 3], [Vec4; 3]) {
    let plane = |axis: usize, far: bool| {
        Vec4::from_slice(&planes[plane_index::<OCTANT>(axis, far)][lanes.clone()])
    };
    (
        per_axis(|axis| plane(axis, false)),
        per_axis(|axis| plane(axis, true)),
    )
}

impl Bvh {
    /// Whether an incoherent packet's rays walk this tree side by side (see
    /// [`WALK_NODES`]) rather than one after another.
    pub(crate) fn walks_pay(&self) -> bool {
        #[cfg(test)]
        if WALK_ALWAYS.get() {
            return true;
        }
        self.nodes.len() >= WALK_NODES
    }

    /// Finds the closest hit: visits the leaves the ray may reach, nearest box first,
    /// and calls `leaf(start, count, t_max)`, which intersects the items at positions
    /// `start..start + count` and returns the new `t_max` (the closest hit so far, or
    /// `t_max` unchanged). Boxes entered beyond the current `t_max` are skipped.
    /// Returns the final `t_max`.
    ///
    /// A ray with a non-finite origin or direction, or a zero direction, visits no
    /// leaf. No allocation: the stack is a fixed array.
    pub fn closest(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32, f32) -> f32,
    ) -> f32 {
        self.closest_prepared(&BoxRay::new(ray), t_min, t_max, leaf, |_, _| {})
    }

    pub(crate) fn closest_prepared(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32, f32) -> f32,
        prefetch_leaf: impl Fn(u32, u32),
    ) -> f32 {
        if !ray.valid {
            return t_max;
        }
        match ray.octant {
            0 => self.closest_in_octant::<0>(ray, t_min, t_max, leaf, prefetch_leaf),
            1 => self.closest_in_octant::<1>(ray, t_min, t_max, leaf, prefetch_leaf),
            2 => self.closest_in_octant::<2>(ray, t_min, t_max, leaf, prefetch_leaf),
            3 => self.closest_in_octant::<3>(ray, t_min, t_max, leaf, prefetch_leaf),
            4 => self.closest_in_octant::<4>(ray, t_min, t_max, leaf, prefetch_leaf),
            5 => self.closest_in_octant::<5>(ray, t_min, t_max, leaf, prefetch_leaf),
            6 => self.closest_in_octant::<6>(ray, t_min, t_max, leaf, prefetch_leaf),
            _ => self.closest_in_octant::<7>(ray, t_min, t_max, leaf, prefetch_leaf),
        }
    }

    /// [`Bvh::closest`] for rays whose direction signs are `OCTANT`.
    fn closest_in_octant<const OCTANT: u8>(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32, f32) -> f32,
        prefetch_leaf: impl Fn(u32, u32),
    ) -> f32 {
        if self.nodes.is_empty() {
            return t_max;
        }
        #[cfg(target_arch = "x86_64")]
        if crate::avx::detected() {
            #[allow(unsafe_code)]
            // SAFETY: the processor runs AVX and POPCNT.
            return unsafe {
                self.closest_in_octant_avx::<OCTANT>(ray, t_min, t_max, leaf, prefetch_leaf)
            };
        }
        with_stack(|stack| {
            let mut traversal = RayTraversal {
                ray,
                t_min,
                leaf,
                prefetch_leaf,
            };
            self.closest_with_stack::<OCTANT, _, _, _>(&mut traversal, 0, t_max, stack)
        })
    }

    /// [`Bvh::closest_in_octant`] compiled for AVX, with the AVX box test. Its body
    /// repeats the baseline's so that the closure is written (and compiled) here: a
    /// closure gets its enclosing function's instruction set.
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,popcnt")]
    fn closest_in_octant_avx<const OCTANT: u8>(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32, f32) -> f32,
        prefetch_leaf: impl Fn(u32, u32),
    ) -> f32 {
        let ray = crate::avx::AvxRay::new(ray);
        with_stack(|stack| {
            let mut traversal = RayTraversal {
                ray: &ray,
                t_min,
                leaf,
                prefetch_leaf,
            };
            self.closest_with_stack::<OCTANT, _, _, _>(&mut traversal, 0, t_max, stack)
        })
    }

    /// The closest-hit traversal of the subtree `start` (a node index or a leaf ref)
    /// for rays whose direction signs are `OCTANT`, from the closest distance so far,
    /// `t_max`, with a stack to use.
    #[inline(always)]
    pub(crate) fn closest_with_stack<const OCTANT: u8, R, L, P>(
        &self,
        traversal: &mut RayTraversal<'_, R, L, P>,
        start: u32,
        t_max: f32,
        stack: &mut Stack,
    ) -> f32
    where
        R: ChildBoxes,
        L: FnMut(u32, u32, f32) -> f32,
        P: Fn(u32, u32),
    {
        let RayTraversal {
            ray,
            t_min,
            leaf,
            prefetch_leaf,
        } = traversal;
        let mut walk = Walk::new(start, t_max);
        while self.closest_step::<OCTANT, _, _, _>(
            *ray,
            *t_min,
            &mut walk,
            stack,
            leaf,
            prefetch_leaf,
        ) {}
        walk.t_max
    }

    /// One step of [`Bvh::closest_with_stack`]: visits `walk.current`, then chooses
    /// what to visit next. Returns false once the walk is over.
    #[inline(always)]
    pub(crate) fn closest_step<const OCTANT: u8, R, L, P>(
        &self,
        ray: &R,
        t_min: f32,
        walk: &mut Walk,
        stack: &mut Stack,
        leaf: &mut L,
        prefetch_leaf: &P,
    ) -> bool
    where
        R: ChildBoxes,
        L: FnMut(u32, u32, f32) -> f32,
        P: Fn(u32, u32),
    {
        let Stack {
            refs: stack_refs,
            t: stack_t,
        } = stack;
        let current = walk.current;
        if current & LEAF != 0 {
            let (start, count) = decode_leaf(current);
            walk.t_max = leaf(start, count, walk.t_max);
        } else {
            let node = &self.nodes[current as usize];
            let (mask, t_near) = ray.hit_children::<OCTANT>(node, t_min, walk.t_max);
            if mask != 0 {
                let mut bits = mask;
                while bits != 0 {
                    let child = node.children[bits.trailing_zeros() as usize];
                    bits &= bits - 1;
                    if child & LEAF == 0 {
                        prefetch(&self.nodes, child as usize, [0, 64, 128, 192]);
                    } else {
                        let (start, count) = decode_leaf(child);
                        prefetch_leaf(start, count);
                    }
                }
                if mask.count_ones() == 1 {
                    walk.current = node.children[mask.trailing_zeros() as usize];
                    return true;
                }
                if mask.count_ones() == 2 {
                    // What the sort below does with two children (on a tie the later
                    // slot comes first), without its loops.
                    let (a, b) = (
                        mask.trailing_zeros() as usize,
                        (mask & (mask - 1)).trailing_zeros() as usize,
                    );
                    let (near, far) = if t_near[a] < t_near[b] {
                        (a, b)
                    } else {
                        (b, a)
                    };
                    stack_refs[walk.sp] = node.children[far];
                    stack_t[walk.sp] = t_near[far];
                    walk.sp += 1;
                    walk.current = node.children[near];
                    return true;
                }
                // Sort the hit children far to near, push all but the nearest and
                // descend into it.
                let mut refs = [0u32; WIDTH];
                let mut dists = [0f32; WIDTH];
                let mut k = 0;
                let mut bits = mask;
                while bits != 0 {
                    let slot = bits.trailing_zeros() as usize;
                    bits &= bits - 1;
                    let (child, dist) = (node.children[slot], t_near[slot]);
                    let mut j = k;
                    while j > 0 && dists[j - 1] < dist {
                        refs[j] = refs[j - 1];
                        dists[j] = dists[j - 1];
                        j -= 1;
                    }
                    refs[j] = child;
                    dists[j] = dist;
                    k += 1;
                }
                let sp = walk.sp;
                stack_refs[sp..sp + WIDTH].copy_from_slice(&refs);
                stack_t[sp..sp + WIDTH].copy_from_slice(&dists);
                walk.sp += k - 1;
                walk.current = refs[k - 1];
                return true;
            }
        }
        // Pop the nearest pending subtree that can still hold a closer hit.
        loop {
            if walk.sp == 0 {
                return false;
            }
            walk.sp -= 1;
            if stack_t[walk.sp] <= walk.t_max {
                walk.current = stack_refs[walk.sp];
                return true;
            }
        }
    }

    /// Whether any leaf reports a hit: calls `leaf(start, count)` for the leaves whose
    /// boxes the ray meets within `[t_min, t_max]` and stops at the first `true`.
    pub fn any(
        &self,
        ray: &Ray,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32) -> bool,
    ) -> bool {
        self.any_prepared(&BoxRay::new(ray), t_min, t_max, leaf)
    }

    pub(crate) fn any_prepared(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32) -> bool,
    ) -> bool {
        if !ray.valid {
            return false;
        }
        match ray.octant {
            0 => self.any_in_octant::<0>(ray, t_min, t_max, leaf),
            1 => self.any_in_octant::<1>(ray, t_min, t_max, leaf),
            2 => self.any_in_octant::<2>(ray, t_min, t_max, leaf),
            3 => self.any_in_octant::<3>(ray, t_min, t_max, leaf),
            4 => self.any_in_octant::<4>(ray, t_min, t_max, leaf),
            5 => self.any_in_octant::<5>(ray, t_min, t_max, leaf),
            6 => self.any_in_octant::<6>(ray, t_min, t_max, leaf),
            _ => self.any_in_octant::<7>(ray, t_min, t_max, leaf),
        }
    }

    /// [`Bvh::any`] for rays whose direction signs are `OCTANT`.
    fn any_in_octant<const OCTANT: u8>(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        #[cfg(target_arch = "x86_64")]
        if crate::avx::detected() {
            #[allow(unsafe_code)]
            // SAFETY: the processor runs AVX and POPCNT.
            return unsafe { self.any_in_octant_avx::<OCTANT>(ray, t_min, t_max, leaf) };
        }
        with_stack(|stack| {
            self.any_with_stack::<OCTANT, _>(ray, 0, t_min, t_max, leaf, &mut stack.refs)
        })
    }

    /// [`Bvh::any_in_octant`] compiled for AVX, with the AVX box test (its body
    /// repeated for the closure, as in [`Bvh::closest_in_octant_avx`]).
    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx,popcnt")]
    fn any_in_octant_avx<const OCTANT: u8>(
        &self,
        ray: &BoxRay,
        t_min: f32,
        t_max: f32,
        leaf: impl FnMut(u32, u32) -> bool,
    ) -> bool {
        let ray = crate::avx::AvxRay::new(ray);
        with_stack(|stack| {
            self.any_with_stack::<OCTANT, _>(&ray, 0, t_min, t_max, leaf, &mut stack.refs)
        })
    }

    /// The any-hit traversal of the subtree `root` (a child reference: a node, 0 for
    /// the whole tree, or a leaf) for rays whose direction signs are `OCTANT`, with a
    /// stack to use.
    #[inline(always)]
    pub(crate) fn any_with_stack<const OCTANT: u8, R: ChildBoxes>(
        &self,
        ray: &R,
        root: u32,
        t_min: f32,
        t_max: f32,
        mut leaf: impl FnMut(u32, u32) -> bool,
        stack: &mut [u32; STACK_ROOM],
    ) -> bool {
        let mut sp = 0usize;
        let mut current = root;
        loop {
            if current & LEAF != 0 {
                let (start, count) = decode_leaf(current);
                if leaf(start, count) {
                    return true;
                }
            } else {
                let node = &self.nodes[current as usize];
                let (mut mask, _) = ray.hit_children::<OCTANT>(node, t_min, t_max);
                while mask != 0 {
                    stack[sp] = node.children[mask.trailing_zeros() as usize];
                    sp += 1;
                    mask &= mask - 1;
                }
            }
            if sp == 0 {
                return false;
            }
            sp -= 1;
            current = stack[sp];
        }
    }
}

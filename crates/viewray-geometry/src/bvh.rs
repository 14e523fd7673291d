//! An eight-wide bounding volume hierarchy, built by binned SAH and traversed front to
//! back.
//!
//! One [`Bvh`] type serves every level: a [`Mesh`](crate::Mesh) indexes its triangles
//! (leaves point at packets of four), and a [`World`](crate::World) indexes its bounded
//! objects. The BVH only knows boxes: callers build it from a slice of anything
//! [`Bounded`] and intersect the items of a leaf themselves, in a closure.

use std::cell::RefCell;
use std::thread::LocalKey;

use glam::{IVec4, Mat3A, Vec3, Vec3A, Vec3Swizzles, Vec4};
use rayon::prelude::*;

use crate::{Aabb, Ray};

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
/// `max_leaf_items` items.
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

/// A node with up to eight children whose boxes are stored as structure of arrays, so
/// that one ray is tested against four boxes with one SIMD instruction per slab plane.
///
/// `planes[axis + 3 * is_max][child]` and the child refs: 224 bytes, 256 with the
/// cache-line alignment. Eight children rather than four make the tree a third
/// shallower, and each level costs an incoherent ray one round trip to memory.
#[derive(Clone, Copy, Debug)]
#[repr(C, align(64))]
pub(crate) struct Node {
    pub(crate) planes: [[f32; WIDTH]; 6],
    pub(crate) children: [u32; WIDTH],
}

/// Children per node.
pub(crate) const WIDTH: usize = 8;
/// SIMD groups of four children per node.
pub(crate) const GROUPS: usize = WIDTH / 4;

/// Child ref flag: the child is a leaf `(start, count)` rather than a node index.
pub(crate) const LEAF: u32 = 1 << 31;
/// Bits of a leaf ref that hold `count - 1`.
const COUNT_BITS: u32 = 4;
/// The most items a leaf can refer to.
const MAX_LEAF: u32 = 1 << COUNT_BITS;
/// The first item of a leaf must be below this (2^27 = 134 million).
pub(crate) const MAX_ITEMS: usize = 1 << (31 - COUNT_BITS);
/// The ref of an unused child slot (never a valid leaf: its items would end past
/// `MAX_ITEMS`); its box is empty, so no ray enters it.
const EMPTY_REF: u32 = u32::MAX;
/// Depth (in nodes) after which the build stops using SAH and halves ranges by count.
/// Each level then at least halves the largest range, so with fewer than 2^27 items
/// the depth stays below `FORCE_MEDIAN_DEPTH + 27 = 67`.
const FORCE_MEDIAN_DEPTH: u32 = 40;
/// The traversal stack: a node pushes at most `WIDTH - 1 = 7` entries more than it pops
/// (the closest-hit walk pushes the hit children but the nearest; the any-hit walk
/// pushes all `WIDTH` and pops one at once, hence the `+ 1`), and the tree is less than
/// 67 nodes deep.
pub(crate) const STACK_SIZE: usize = (WIDTH - 1) * 67 + 1;
/// The stack's length: `STACK_SIZE` and a node's row of `WIDTH` more, so that a node's
/// sorted children are pushed as one fixed-size copy of the whole row (only the first
/// ones count; a copy of variable length is a call to `memcpy`).
pub(crate) const STACK_ROOM: usize = STACK_SIZE + WIDTH;
/// Ranges at least this large are split with parallel binning and built in parallel.
const PARALLEL_ITEMS: usize = 16 * 1024;

/// Whether a range of `n` items is worked on in parallel: when it is large enough and
/// the current pool has more than one thread. (On one thread the parallel build only
/// adds work: each subtree built into its own array and copied into place.)
fn in_parallel(n: usize) -> bool {
    n >= PARALLEL_ITEMS && rayon::current_num_threads() > 1
}

impl Node {
    pub(crate) const EMPTY: Self = Self {
        planes: [
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
            [f32::NEG_INFINITY; WIDTH],
        ],
        children: [EMPTY_REF; WIDTH],
    };

    pub(crate) fn set_child(&mut self, slot: usize, bounds: &Aabb, child: u32) {
        for axis in 0..3 {
            self.planes[axis][slot] = bounds.min[axis];
            self.planes[axis + 3][slot] = bounds.max[axis];
        }
        self.children[slot] = child;
    }

    #[cfg(test)]
    fn child_bounds(&self, slot: usize) -> Aabb {
        let p = &self.planes;
        Aabb::new(
            Vec3::new(p[0][slot], p[1][slot], p[2][slot]),
            Vec3::new(p[3][slot], p[4][slot], p[5][slot]),
        )
    }
}

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

/// Asks the CPU to start loading the bytes at `offsets` from the start of
/// `items[index]` into the cache, so that the loads of the children a ray will visit
/// overlap. The offsets are constants, so this is straight-line code: a loop here cost
/// coherent rays, whose data is already cached, a tenth of their time.
#[inline(always)]
pub(crate) fn prefetch<T, const N: usize>(items: &[T], index: usize, offsets: [usize; N]) {
    #[cfg(target_arch = "x86_64")]
    if let Some(item) = items.get(index) {
        let start = std::ptr::from_ref(item).cast::<i8>();
        for offset in offsets {
            #[allow(unsafe_code)]
            // SAFETY: `_mm_prefetch` is only a hint: it reads nothing the program can
            // observe and never faults, whatever the address. It is an SSE instruction,
            // and SSE is part of the x86_64 baseline.
            unsafe {
                use std::arch::x86_64::{_MM_HINT_T0, _mm_prefetch};
                _mm_prefetch::<_MM_HINT_T0>(start.wrapping_add(offset));
            }
        }
    }
    #[cfg(not(target_arch = "x86_64"))]
    let _ = (items, index, offsets);
}

/// Asks the kernel to back `buffer`'s unused capacity with 2 MiB pages (Linux's
/// transparent huge pages, where the system leaves them to `madvise`), before the
/// buffer is filled: a mesh's build items, nodes and triangle packets are tens of
/// megabytes each. One fault then maps 2 MiB instead of 4 KiB (a seventh of a build had
/// gone to the kernel's page faults), and a ray's random walk through the hierarchy
/// misses the TLB far less often. Only a hint: nothing changes where the system
/// declines, or on other systems.
pub(crate) fn advise_huge_pages<T>(buffer: &mut Vec<T>) {
    #[cfg(target_os = "linux")]
    {
        const HUGE_PAGE: usize = 2 << 20;
        let spare = buffer.spare_capacity_mut();
        let start = spare.as_mut_ptr() as usize;
        let end = start + std::mem::size_of_val(spare);
        // The whole huge pages inside the unused capacity.
        let (first, last) = (
            start.next_multiple_of(HUGE_PAGE),
            end / HUGE_PAGE * HUGE_PAGE,
        );
        if last > first {
            #[allow(unsafe_code)]
            // SAFETY: the range lies inside `buffer`'s allocation, which this function
            // borrows mutably; `MADV_HUGEPAGE` only changes how the kernel backs those
            // pages, never their contents or whether they may be read and written. An
            // error (for example no huge page support) leaves everything as it was.
            unsafe {
                libc::madvise(
                    first as *mut libc::c_void,
                    last - first,
                    libc::MADV_HUGEPAGE,
                );
            }
        }
    }
    #[cfg(not(target_os = "linux"))]
    let _ = buffer;
}

fn leaf_ref(start: usize, count: usize) -> u32 {
    debug_assert!(start < MAX_ITEMS && (1..=MAX_LEAF as usize).contains(&count));
    LEAF | ((start as u32) << COUNT_BITS) | (count as u32 - 1)
}

pub(crate) fn decode_leaf(child: u32) -> (u32, u32) {
    ((child & !LEAF) >> COUNT_BITS, (child & (MAX_LEAF - 1)) + 1)
}

/// A bounding volume hierarchy over items with boxes, with up to eight children per node.
///
/// Leaves refer to runs of consecutive positions in [`Bvh::item_order`]: position `i`
/// holds the index (in the slice it was built from) of the `i`-th item in leaf order,
/// so callers can store their items reordered by leaf and read a leaf's items from one
/// contiguous run.
#[derive(Clone, Debug, Default)]
pub struct Bvh {
    nodes: Vec<Node>,
    item_order: Vec<u32>,
    bounds: Aabb,
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

    /// For each position in leaf order, the index of the item (in the slice the
    /// hierarchy was built from) stored there.
    pub fn item_order(&self) -> &[u32] {
        &self.item_order
    }

    /// The box around all items ([`Aabb::EMPTY`] when there are none).
    pub fn bounds(&self) -> Aabb {
        self.bounds
    }

    /// The number of nodes.
    pub fn node_count(&self) -> usize {
        self.nodes.len()
    }

    /// Whether an incoherent packet's rays walk this tree side by side (see
    /// [`WALK_NODES`]) rather than one after another.
    pub(crate) fn walks_pay(&self) -> bool {
        #[cfg(test)]
        if WALK_ALWAYS.get() {
            return true;
        }
        self.nodes.len() >= WALK_NODES
    }

    /// The memory held by the nodes and the item order, in bytes.
    pub fn memory_bytes(&self) -> usize {
        self.nodes.len() * std::mem::size_of::<Node>() + self.item_order.len() * 4
    }

    /// Every leaf as `(first position, item count)`, in node order.
    pub fn leaves(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        self.nodes
            .iter()
            .flat_map(|node| node.children)
            .filter(|&child| child & LEAF != 0 && child != EMPTY_REF)
            .map(decode_leaf)
    }

    /// Drops the item order, for callers that store their items in leaf order.
    pub(crate) fn clear_item_order(&mut self) {
        self.item_order = Vec::new();
    }

    /// Rewrites every leaf `(start, count)` to `f(start, count)`: a mesh re-points its
    /// leaves from triangle positions to packet positions.
    pub(crate) fn remap_leaves(&mut self, mut f: impl FnMut(u32, u32) -> (u32, u32)) {
        for node in &mut self.nodes {
            for child in &mut node.children {
                if *child & LEAF != 0 && *child != EMPTY_REF {
                    let (start, count) = decode_leaf(*child);
                    let (start, count) = f(start, count);
                    *child = leaf_ref(start as usize, count as usize);
                }
            }
        }
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

    /// The nodes, root first.
    pub(crate) fn nodes(&self) -> &[Node] {
        &self.nodes
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
            self.any_with_stack::<OCTANT, _>(ray, t_min, t_max, leaf, &mut stack.refs)
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
            self.any_with_stack::<OCTANT, _>(&ray, t_min, t_max, leaf, &mut stack.refs)
        })
    }

    /// The any-hit traversal from the root for rays whose direction signs are
    /// `OCTANT`, with a stack to use.
    #[inline(always)]
    pub(crate) fn any_with_stack<const OCTANT: u8, R: ChildBoxes>(
        &self,
        ray: &R,
        t_min: f32,
        t_max: f32,
        mut leaf: impl FnMut(u32, u32) -> bool,
        stack: &mut [u32; STACK_ROOM],
    ) -> bool {
        let mut sp = 0usize;
        let mut current = 0u32;
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

    /// Checks the structure: every child box holds its subtree, leaves tile the items.
    #[cfg(test)]
    pub(crate) fn validate(&self, item_bounds: &dyn Fn(u32) -> Aabb) {
        if self.nodes.is_empty() {
            // An empty BVH has no root to check.
            assert!(self.item_order.is_empty());
            return;
        }
        let mut seen = vec![false; self.item_order.len()];
        let mut stack = vec![(0u32, self.bounds)];
        while let Some((node_index, bounds)) = stack.pop() {
            let node = &self.nodes[node_index as usize];
            for slot in 0..WIDTH {
                let child = node.children[slot];
                let child_bounds = node.child_bounds(slot);
                if child == EMPTY_REF {
                    assert!(child_bounds.is_empty());
                    continue;
                }
                assert_eq!(
                    child_bounds.union(bounds),
                    bounds,
                    "child box outside its parent"
                );
                if child & LEAF != 0 {
                    let (start, count) = decode_leaf(child);
                    for position in start..start + count {
                        assert!(!seen[position as usize], "item in two leaves");
                        seen[position as usize] = true;
                        let item = item_bounds(self.item_order[position as usize]);
                        assert_eq!(
                            item.union(child_bounds),
                            child_bounds,
                            "item outside its leaf"
                        );
                    }
                } else {
                    stack.push((child, child_bounds));
                }
            }
        }
        assert!(seen.iter().all(|&s| s), "item in no leaf");
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
        // A leaf costs `blocks(n)` per unit of area, a split at least `traversal_cost`:
        // when the leaf is no dearer, it wins without binning (the second look at the
        // children of up to one block in `build_node`, where most small ranges end).
        if n <= 1 || small && self.blocks(n as u32) <= traversal_cost {
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
mod tests {
    use proptest::prelude::*;

    use super::*;

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

    /// 200 unit boxes in a row along x, a gap of 1 between neighbours, seen end on: the
    /// nearest box hides every other, so a front-to-back walk that skips boxes entered
    /// beyond the closest hit visits one leaf, whichever end the ray comes from (two
    /// octants) and however the boxes were ordered when the tree was built.
    #[test]
    fn closest_visits_only_the_nearest_leaf_of_a_row_of_boxes() {
        let mut boxes: Vec<Aabb> = (0..200)
            .map(|k| {
                let x = 2.0 * k as f32;
                Aabb::new(Vec3::new(x, -0.5, -0.5), Vec3::new(x + 1.0, 0.5, 0.5))
            })
            .collect();
        for shuffled in [false, true] {
            if shuffled {
                // A fixed permutation: 73 is coprime with 200.
                boxes = (0..200).map(|k| boxes[(k * 73) % 200]).collect();
            }
            let bvh = Bvh::build(&boxes, BuildParams::default());
            for (origin, direction, nearest_t) in [
                (Vec3::new(-10.0, 0.1, 0.2), Vec3::X, 10.0),
                (Vec3::new(410.0, -0.1, 0.2), Vec3::NEG_X, 11.0),
            ] {
                let ray = Ray::new(origin, direction);
                let mut visits = 0;
                let t = bvh.closest(&ray, 0.0, f32::INFINITY, |start, count, t_max| {
                    visits += 1;
                    let order = bvh.item_order();
                    (start..start + count)
                        .filter_map(|p| boxes[order[p as usize] as usize].slab_interval(&ray))
                        .map(|(t_enter, _)| t_enter)
                        .fold(t_max, f32::min)
                });
                assert_eq!(t, nearest_t, "from {origin}");
                assert_eq!(visits, 1, "from {origin}, shuffled: {shuffled}");
            }
        }
    }

    /// A node where the ray enters exactly two children: the nearer is visited first
    /// (from either side, whichever slot it has), and of two entered at the same
    /// distance the later slot first, as the sort of three or more children orders them.
    #[test]
    fn of_two_children_the_nearer_and_on_a_tie_the_later_slot_comes_first() {
        // Two unit boxes side by side along x, each its own leaf under the root.
        let boxes = [
            Aabb::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0)),
            Aabb::new(Vec3::new(5.0, 0.0, 0.0), Vec3::new(6.0, 1.0, 1.0)),
        ];
        let bvh = Bvh::build(&boxes, BuildParams::default());
        let root = &bvh.nodes()[0];
        let leaves: Vec<u32> = root
            .children
            .iter()
            .copied()
            .filter(|&c| c != EMPTY_REF)
            .collect();
        assert!(
            leaves.len() == 2 && leaves.iter().all(|&c| c & LEAF != 0),
            "two leaves"
        );
        let item_of = |start: u32| bvh.item_order()[start as usize] as usize;
        let visits = |ray: &Ray, hit_t: &dyn Fn(usize) -> Option<f32>| {
            let mut visited = Vec::new();
            bvh.closest(ray, 0.0, f32::INFINITY, |start, _, t_max| {
                visited.push(item_of(start));
                hit_t(item_of(start)).map_or(t_max, |t| t.min(t_max))
            });
            visited
        };
        let entry = |item: usize, ray: &Ray| boxes[item].slab_interval(ray).map(|(t, _)| t);
        for (origin, direction, nearest) in [
            (Vec3::new(-1.0, 0.5, 0.5), Vec3::X, 0),
            (Vec3::new(7.0, 0.5, 0.5), Vec3::NEG_X, 1),
        ] {
            let ray = Ray::new(origin, direction);
            let visited = visits(&ray, &|item| entry(item, &ray));
            assert_eq!(visited, [nearest], "from {origin}: only the nearer leaf");
        }
        // Two boxes stacked in y, and a ray along their shared face: both entered at
        // the same distance.
        let stacked = [
            Aabb::new(Vec3::new(0.0, 0.0, 0.0), Vec3::new(1.0, 1.0, 1.0)),
            Aabb::new(Vec3::new(0.0, 1.0, 0.0), Vec3::new(1.0, 6.0, 1.0)),
        ];
        let bvh = Bvh::build(&stacked, BuildParams::default());
        let root = &bvh.nodes()[0];
        let slots: Vec<(usize, u32)> = root
            .children
            .iter()
            .enumerate()
            .filter(|&(_, &c)| c != EMPTY_REF)
            .map(|(slot, &c)| (slot, bvh.item_order()[decode_leaf(c).0 as usize]))
            .collect();
        assert_eq!(slots.len(), 2);
        let later_item = slots[1].1 as usize;
        let ray = Ray::new(Vec3::new(-1.0, 1.0, 0.5), Vec3::X);
        let mut visited = Vec::new();
        bvh.closest(&ray, 0.0, f32::INFINITY, |start, _, t_max| {
            visited.push(bvh.item_order()[start as usize] as usize);
            t_max
        });
        assert_eq!(visited.len(), 2, "both entered");
        assert_eq!(visited[0], later_item, "the later slot first");
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

    /// Boxes along x at geometric distances (1.1^k) make the binned SAH peel a few off
    /// at each level, the deepest trees a build makes, and a ray down the row that hits
    /// nothing walks all of it, pushing up to seven children a level: the traversal
    /// stack must hold that (its size is the bound derived at `STACK_SIZE`).
    #[test]
    fn a_ray_down_the_deepest_tree_visits_every_leaf() {
        let boxes: Vec<Aabb> = (0..400)
            .map(|k| {
                let x = 1.1f32.powi(k);
                Aabb::new(Vec3::new(x, -0.5, -0.5), Vec3::new(x * 1.01, 0.5, 0.5))
            })
            .collect();
        let bvh = Bvh::build(&boxes, BuildParams::default());
        let ray = Ray::new(Vec3::new(0.0, 0.0, 0.0), Vec3::X);
        let mut seen = 0;
        let t = bvh.closest(&ray, 0.0, f32::INFINITY, |_, count, t_max| {
            seen += count;
            t_max
        });
        assert_eq!((t, seen), (f32::INFINITY, 400));
        let mut seen = 0;
        assert!(!bvh.any(&ray, 0.0, f32::INFINITY, |_, count| {
            seen += count;
            false
        }));
        assert_eq!(seen, 400);
    }

    /// A ray parallel to an axis that lies exactly in the plane of a box's face is inside
    /// the closed slab: the BVH's box test must enter that box (0 x inf would be NaN).
    #[test]
    fn a_ray_in_the_plane_of_a_face_enters_the_box() {
        let unit = Aabb::new(Vec3::ZERO, Vec3::ONE);
        let bvh = Bvh::build(&[unit], BuildParams::default());
        for (origin, direction) in [
            (Vec3::new(0.0, 0.5, 5.0), Vec3::NEG_Z), // in the plane x = 0 (a min face)
            (Vec3::new(1.0, 0.5, 5.0), Vec3::NEG_Z), // in the plane x = 1 (a max face)
            (Vec3::new(0.5, 1.0, -5.0), Vec3::Z),    // in y = 1, the other way
            (Vec3::new(0.0, 0.0, 5.0), Vec3::NEG_Z), // along an edge
        ] {
            let ray = Ray::new(origin, direction);
            let mut entered = false;
            bvh.closest(&ray, 0.0, f32::INFINITY, |_, _, t_max| {
                entered = true;
                t_max
            });
            assert!(entered, "{origin} + t {direction}");
            assert!(bvh.any(&ray, 0.0, f32::INFINITY, |_, _| true), "{origin}");
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

    /// Asking for huge pages is only a hint: a buffer of several huge pages, half
    /// filled before and half after, keeps its length, capacity and every value (the
    /// `madvise` call runs here, on whole 2 MiB pages of the unused half).
    #[test]
    fn advising_huge_pages_leaves_a_buffer_as_it_was() {
        let n = 3 << 20;
        let mut buffer: Vec<u64> = Vec::with_capacity(n);
        buffer.extend(0..n as u64 / 2);
        advise_huge_pages(&mut buffer);
        assert_eq!((buffer.len(), buffer.capacity()), (n / 2, n));
        buffer.extend(n as u64 / 2..n as u64);
        assert!(buffer.iter().enumerate().all(|(i, &v)| v == i as u64));
        let mut empty: Vec<u64> = Vec::new();
        advise_huge_pages(&mut empty);
        assert!(empty.is_empty());
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

    /// A walk side by side inside another (a callback's) gets stacks of its own.
    #[test]
    fn nested_walks_side_by_side_get_stacks_of_their_own() {
        let outer_inner = with_walk_stacks(|outer| {
            outer[0].refs[0] = 1;
            let inner = with_walk_stacks(|inner| {
                inner[0].refs[0] = 2;
                std::ptr::from_ref(&inner[0]) as usize
            });
            assert_eq!(outer[0].refs[0], 1);
            (std::ptr::from_ref(&outer[0]) as usize, inner)
        });
        assert_ne!(outer_inner.0, outer_inner.1);
        // Once the outer one is done, its stacks are free again.
        let again = with_walk_stacks(|stacks| std::ptr::from_ref(&stacks[0]) as usize);
        assert_eq!(again, outer_inner.0);
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
        let by_axis =
            sweep_axis_by_axis(builder, &bins, scale).map(|(c, a, b)| (c.to_bits(), a, b));
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
}

//! The hierarchy's layout: nodes of eight children whose boxes are stored as rows of
//! planes, the refs that name a child node or a leaf's run of items, and the [`Bvh`]
//! that holds the nodes and the order of the items.

use glam::Vec3;

use crate::Aabb;

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
pub(super) const MAX_LEAF: u32 = 1 << COUNT_BITS;
/// The first item of a leaf must be below this (2^27 = 134 million).
pub(crate) const MAX_ITEMS: usize = 1 << (31 - COUNT_BITS);
/// The ref of an unused child slot (never a valid leaf: its items would end past
/// `MAX_ITEMS`); its box is empty, so no ray enters it.
pub(super) const EMPTY_REF: u32 = u32::MAX;

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

    /// The box of child `slot`, as stored.
    pub(crate) fn child_bounds(&self, slot: usize) -> Aabb {
        let p = &self.planes;
        Aabb::new(
            Vec3::new(p[0][slot], p[1][slot], p[2][slot]),
            Vec3::new(p[3][slot], p[4][slot], p[5][slot]),
        )
    }
}

pub(super) fn leaf_ref(start: usize, count: usize) -> u32 {
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
    pub(super) nodes: Vec<Node>,
    pub(super) item_order: Vec<u32>,
    pub(super) bounds: Aabb,
}

impl Bvh {
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

    /// The nodes, root first.
    pub(crate) fn nodes(&self) -> &[Node] {
        &self.nodes
    }

    /// The box of the only leaf, as the root stores it, when the hierarchy is a root
    /// whose one child is a leaf of every item (a few items whose boxes no split
    /// separates, such as copies of one shape).
    pub(crate) fn one_leaf_box(&self) -> Option<Aabb> {
        let [root] = self.nodes.as_slice() else {
            return None;
        };
        let mut used = (0..WIDTH).filter(|&slot| root.children[slot] != EMPTY_REF);
        let (Some(slot), None) = (used.next(), used.next()) else {
            return None;
        };
        let child = root.children[slot];
        let every_item = decode_leaf(child) == (0, self.item_order.len() as u32);
        (child & LEAF != 0 && every_item).then(|| root.child_bounds(slot))
    }

    /// Whether `leaf(start, count)` is true for some leaf inside boxes that `enters`
    /// accepts all the way down from the root: a walk of the hierarchy for questions
    /// about a whole set of rays at once (see `world/region.rs`), which descends only
    /// into the children whose stored box `enters` says the set may enter.
    pub(crate) fn any_leaf_entered(
        &self,
        enters: impl Fn(&Aabb) -> bool,
        mut leaf: impl FnMut(u32, u32) -> bool,
    ) -> bool {
        if self.nodes.is_empty() {
            return false;
        }
        let mut stack = vec![0_u32];
        while let Some(node) = stack.pop() {
            let node = &self.nodes[node as usize];
            for (slot, &child) in node.children.iter().enumerate() {
                if child == EMPTY_REF || !enters(&node.child_bounds(slot)) {
                    continue;
                }
                if child & LEAF == 0 {
                    stack.push(child);
                } else {
                    let (start, count) = decode_leaf(child);
                    if leaf(start, count) {
                        return true;
                    }
                }
            }
        }
        false
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

//! Tests of the walks through a built hierarchy (front to back, rays along faces, the
//! deepest trees), of their stacks, and of the huge-pages hint.

use glam::Vec3;

use super::memory::advise_huge_pages;
use super::node::{EMPTY_REF, LEAF, decode_leaf};
use super::traverse::with_walk_stacks;
use super::{BuildParams, Bvh};
use crate::{Aabb, Ray};

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

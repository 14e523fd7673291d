//! Tests of the packets' parts against the single-ray numbers and tests, and of the
//! traversal's choices (front to back, which subtrees stay with the packet).

use glam::{Vec3, Vec4};

use super::boxes::PacketBoxes;
use super::closest::PacketVisitor;
use super::lanes::{
    Lanes, PACKET_GROUPS, PACKET_SIZE, lane, lane_mask, lanes_of, max_lane, set_lane,
};
use super::rays::{BoxPacket, ChunkNumbers, LaneNumbers};
use crate::bvh::{BoxRay, Bvh, LEAF, Node, WIDTH};
use crate::{Aabb, Ray};

#[test]
fn a_lane_mask_holds_the_lanes_of_its_bits() {
    for bits in 0..16 {
        assert_eq!(lane_mask(bits).bitmask(), bits);
        assert_eq!(
            lane_mask(bits | 0xf0).bitmask(),
            bits,
            "only the low four bits"
        );
    }
}

/// The largest number among the lanes a mask selects, and only those.
#[test]
fn max_lane_reads_only_the_masked_lanes() {
    let mut values: Lanes = [Vec4::ZERO; PACKET_GROUPS];
    // Lane i holds 100 - i: the lowest selected lane holds the largest number.
    for i in 0..PACKET_SIZE {
        set_lane(&mut values, i, 100.0 - i as f32);
    }
    assert_eq!(max_lane(&values, 0b10), 99.0);
    assert_eq!(max_lane(&values, 0b1000), 97.0);
    assert_eq!(max_lane(&values, 0b1100), 98.0);
    assert_eq!(max_lane(&values, (1 << 5) | (1 << 40)), 95.0);
    assert_eq!(max_lane(&values, 1 << 63), 37.0);
    assert_eq!(max_lane(&values, 0), f32::NEG_INFINITY);
    // Lane i holds i: now every unselected lane of a group holds more than the
    // selected one below it.
    for i in 0..PACKET_SIZE {
        set_lane(&mut values, i, i as f32);
    }
    for lane in [0, 1, 2, 4, 41, 62] {
        assert_eq!(max_lane(&values, 1 << lane), lane as f32);
    }
    assert_eq!(max_lane(&values, 0b101), 2.0);
}

proptest::proptest! {
    /// The packet's interval test bounds its rays' own tests: every child a ray
    /// enters, the packet enters, and no earlier than the ray; where the processor
    /// runs AVX, its AVX test gives the same bits (for rays of one
    /// octant whose directions differ in length and in angle, so that the extreme
    /// reciprocals differ, against boxes ahead, around and behind the origins). Each
    /// lane's test of one box is its single ray's, with SSE and AVX alike.
    #[test]
    fn the_packet_box_test_bounds_each_ray_box_test(
        rays in proptest::collection::vec(
            (0.0f32..1.0, 0.0f32..1.0, 0.0f32..1.0, 0.1f32..3.0, 0.1f32..3.0, 0.1f32..3.0),
            1..=PACKET_SIZE,
        ),
        boxes in proptest::collection::vec(
            (-4.0f32..8.0, -4.0f32..8.0, -4.0f32..8.0, 0.01f32..3.0, 0.01f32..3.0, 0.01f32..3.0),
            WIDTH,
        ),
        t_max in 0.5f32..20.0,
    ) {
        let rays: Vec<Ray> = rays
            .iter()
            .map(|&(ox, oy, oz, dx, dy, dz)| Ray::new(Vec3::new(ox, oy, oz), Vec3::new(dx, dy, dz)))
            .collect();
        let mut node = Node::EMPTY;
        for (slot, &(x, y, z, w, h, d)) in boxes.iter().enumerate() {
            let min = Vec3::new(x, y, z);
            node.set_child(slot, &Aabb::new(min, min + Vec3::new(w, h, d)), slot as u32);
        }
        let mut chunk = ChunkNumbers::EMPTY;
        chunk.fill(&rays);
        // Every direction is positive: octant 0.
        let mut gathered = LaneNumbers::EMPTY;
        let packet = BoxPacket::new(&chunk, &mut gathered, 0, chunk.octants[0]);
        let (t_min4, t_max4) = (Vec4::ZERO, Vec4::splat(t_max));
        let (packet_mask, packet_near) = packet.hit_children_sse::<0>(&node, t_min4, t_max4);
        #[cfg(target_arch = "x86_64")]
        if crate::avx::detected() {
            // The AVX test is the SSE test to the bit.
            #[allow(unsafe_code)]
            // SAFETY: the processor runs AVX and POPCNT.
            let avx = unsafe { crate::avx::AvxPacket::new(&packet) };
            let (mask, near) = avx.hit_children::<0>(&node, 0.0, t_max);
            proptest::prop_assert_eq!(
                (mask, near.map(f32::to_bits)),
                (packet_mask, packet_near.map(f32::to_bits))
            );
        }
        // Each lane's own test of one box, four lanes at a time (and eight with AVX), is
        // its single ray's test to the bit, with a `t_max` of its own, for all lanes
        // and for every third.
        let mut t_max_lanes: Lanes = [Vec4::ZERO; PACKET_GROUPS];
        for i in 0..PACKET_SIZE {
            set_lane(&mut t_max_lanes, i, t_max * (0.25 + i as f32 / 48.0));
        }
        for lanes in [packet.all_lanes(), packet.all_lanes() & 0x9249_2492_4924_9249] {
            for slot in 0..WIDTH {
                let hit = packet.rays_hitting::<0>(&node, slot, lanes, t_min4, &t_max_lanes);
                for (i, ray) in rays.iter().enumerate() {
                    let ray = BoxRay::new(ray);
                    let t_max4 = Vec4::splat(lane(&t_max_lanes, i));
                    let alone = ray.hit_children_sse::<0>(&node, t_min4, t_max4).0 >> slot & 1;
                    let expected = u64::from(alone) & (lanes >> i) & 1;
                    proptest::prop_assert_eq!(hit >> i & 1, expected, "lane {} slot {}", i, slot);
                }
                #[cfg(target_arch = "x86_64")]
                if crate::avx::detected() {
                    #[allow(unsafe_code)]
                    // SAFETY: the processor runs AVX and POPCNT.
                    let avx = unsafe { crate::avx::AvxPacket::new(&packet) };
                    let wide = avx.rays_hitting::<0>(&node, slot, lanes, 0.0, &t_max_lanes);
                    proptest::prop_assert_eq!(wide, hit, "slot {}", slot);
                }
            }
        }
        for ray in &rays {
            let (mask, near) = BoxRay::new(ray).hit_children_sse::<0>(&node, t_min4, t_max4);
            proptest::prop_assert_eq!(mask & !packet_mask, 0, "{:?}", ray);
            for slot in lanes_of(u64::from(mask)) {
                proptest::prop_assert!(packet_near[slot] <= near[slot], "{:?} slot {}", ray, slot);
            }
        }
    }
}

/// Directions `(1, 1, -2) L` and `(1 + s, 1, -2) L` spread by `s L` on x over a
/// shortest length of `sqrt(6) L`: traced as a packet while `s <= 0.2 sqrt(6) =
/// 0.4899`, whatever `L`, whether they are the whole chunk or are gathered from a
/// chunk that also holds a ray of another octant. The spread is measured across the
/// lanes, not lane by lane (in lanes 0 and 1, each ray spreads nothing on its own).
#[test]
fn a_packet_is_coherent_while_its_directions_spread_at_most_a_fifth() {
    let coherent = |s: f32, length: f32, gathered: bool| {
        let mut rays = vec![
            Ray::new(Vec3::ZERO, Vec3::new(1.0, 1.0, -2.0) * length),
            Ray::new(Vec3::ZERO, Vec3::new(1.0 + s, 1.0, -2.0) * length),
        ];
        if gathered {
            rays.push(Ray::new(Vec3::ZERO, Vec3::new(0.0, 0.0, 2.0)));
        }
        let mut chunk = ChunkNumbers::EMPTY;
        chunk.fill(&rays);
        // Octant 0b100: negative z only.
        assert_eq!(chunk.octants[4], 0b11);
        assert_eq!(chunk.octants[4] == chunk.all, !gathered);
        let mut gathered = LaneNumbers::EMPTY;
        let packet = BoxPacket::new(&chunk, &mut gathered, 4, chunk.octants[4]);
        packet.coherent
    };
    for (length, gathered) in [(1.0, false), (3.0, false), (1.0, true), (3.0, true)] {
        assert!(coherent(0.48, length, gathered), "L {length}, {gathered}");
        assert!(!coherent(0.5, length, gathered), "L {length}, {gathered}");
    }
}

/// Boxes traced by test visitors: each lane's ray, and the boxes in the BVH's item
/// order.
struct BoxScene<'a> {
    boxes: &'a [Aabb],
    order: &'a [u32],
    rays: &'a [Ray],
}

impl BoxScene<'_> {
    /// A leaf for lane `lane`: the nearest entry into the boxes at positions
    /// `start..start + count`, if nearer than `t_max`.
    fn nearest(&self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
        (start..start + count)
            .filter_map(|p| {
                self.boxes[self.order[p as usize] as usize].slab_interval(&self.rays[lane])
            })
            .map(|(t_enter, _)| t_enter)
            .fold(t_max, f32::min)
    }
}

/// The packet walk, like the single-ray one, goes front to back: 200 boxes in a row
/// along x seen end on by four parallel rays, the nearest box hides the others, so
/// each ray's leaf test runs once (`Bvh::closest`'s test, for packets). From inside
/// the row, the nearest child is in the middle of a node, not at one end.
#[test]
fn the_packet_walk_visits_only_the_nearest_leaf_of_a_row_of_boxes() {
    struct Nearest<'a> {
        scene: BoxScene<'a>,
        visits: [u32; PACKET_SIZE],
    }
    impl PacketVisitor for Nearest<'_> {
        fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
            self.visits[lane] += 1;
            self.scene.nearest(lane, start, count, t_max)
        }
    }
    let boxes: Vec<Aabb> = (0..200)
        .map(|k| {
            let x = 2.0 * k as f32;
            Aabb::new(Vec3::new(x, -0.5, -0.5), Vec3::new(x + 1.0, 0.5, 0.5))
        })
        .collect();
    let bvh = Bvh::build(&boxes, crate::BuildParams::default());
    // From either end, and from between boxes 99 and 100 (x = 199 to 200) either way.
    for (x, direction, nearest_t) in [
        (-10.0, Vec3::X, 10.0),
        (410.0, Vec3::NEG_X, 11.0),
        (199.25, Vec3::X, 0.75),
        (199.5, Vec3::NEG_X, 0.5),
    ] {
        let rays: Vec<Ray> = (0..4)
            .map(|k| Ray::new(Vec3::new(x, 0.1 * k as f32, 0.2), direction))
            .collect();
        let mut chunk = ChunkNumbers::EMPTY;
        chunk.fill(&rays);
        let octant = usize::from(direction.x < 0.0);
        let mut gathered = LaneNumbers::EMPTY;
        let packet = BoxPacket::new(&chunk, &mut gathered, octant as u8, chunk.octants[octant]);
        assert!(packet.coherent);
        let mut t_max = [Vec4::INFINITY; PACKET_GROUPS];
        let mut nearest = Nearest {
            scene: BoxScene {
                boxes: &boxes,
                order: bvh.item_order(),
                rays: &rays,
            },
            visits: [0; PACKET_SIZE],
        };
        bvh.closest_packet(&packet, chunk.all, 0.0, &mut t_max, &mut nearest, |_, _| {});
        for (i, ray) in rays.iter().enumerate() {
            let lane_ray = packet.rays[i] as usize;
            assert_eq!(lane_ray, i, "whole chunk: lane i holds ray i");
            assert_eq!(lane(&t_max, i), nearest_t, "{ray:?}");
            assert_eq!(nearest.visits[i], 1, "{ray:?}");
        }
    }
}

/// A subtree that a quarter of the packet enters stays with the packet even where
/// the packet enters many children of a node: eight plates stacked along the view,
/// each of sixteen tiles, seen by an 8 x 8 packet of parallel rays. The root's
/// children are the plates, all entered by every ray; the nearest plate is walked by
/// the packet, so its leaves are tested through `leaf_lanes` and never by a ray
/// finishing the plate alone.
#[test]
fn a_subtree_most_rays_enter_is_walked_as_a_packet() {
    struct Counting<'a> {
        scene: BoxScene<'a>,
        in_lanes: bool,
        alone: u32,
        together: u32,
    }
    impl PacketVisitor for Counting<'_> {
        fn leaf(&mut self, lane: usize, start: u32, count: u32, t_max: f32) -> f32 {
            if !self.in_lanes {
                self.alone += 1;
            }
            self.scene.nearest(lane, start, count, t_max)
        }
        fn leaf_lanes(&mut self, lanes: u64, start: u32, count: u32, t_max: &mut Lanes) {
            self.in_lanes = true;
            for i in lanes_of(lanes) {
                self.together += 1;
                let t = self.leaf(i, start, count, lane(t_max, i));
                set_lane(t_max, i, t);
            }
            self.in_lanes = false;
        }
    }
    // Plates at z = 0, -1, ..., -7, each 4 x 4 tiles of 2 x 2 over [0, 8]^2.
    let boxes: Vec<Aabb> = (0..8)
        .flat_map(|plate| (0..16).map(move |tile| (plate, tile)))
        .map(|(plate, tile)| {
            let (x, y, z) = (
                2.0 * (tile % 4) as f32,
                2.0 * (tile / 4) as f32,
                -(plate as f32),
            );
            Aabb::new(Vec3::new(x, y, z - 0.1), Vec3::new(x + 2.0, y + 2.0, z))
        })
        .collect();
    let bvh = Bvh::build(&boxes, crate::BuildParams::default());
    let root = &bvh.nodes()[0];
    assert!(
        root.children.iter().all(|&c| c & LEAF == 0),
        "the root's children are the plates' nodes"
    );
    let rays: Vec<Ray> = (0..64)
        .map(|k| {
            let (x, y) = ((k % 8) as f32 + 0.5, (k / 8) as f32 + 0.5);
            Ray::new(Vec3::new(x, y, 10.0), Vec3::NEG_Z)
        })
        .collect();
    let mut chunk = ChunkNumbers::EMPTY;
    chunk.fill(&rays);
    let octant = 0b100;
    let mut gathered = LaneNumbers::EMPTY;
    let packet = BoxPacket::new(
        &chunk,
        &mut gathered,
        octant,
        chunk.octants[octant as usize],
    );
    assert!(packet.coherent);
    let mut t_max = [Vec4::INFINITY; PACKET_GROUPS];
    let mut counting = Counting {
        scene: BoxScene {
            boxes: &boxes,
            order: bvh.item_order(),
            rays: &rays,
        },
        in_lanes: false,
        alone: 0,
        together: 0,
    };
    bvh.closest_packet(
        &packet,
        chunk.all,
        0.0,
        &mut t_max,
        &mut counting,
        |_, _| {},
    );
    for i in 0..64 {
        assert_eq!(lane(&t_max, i), 10.0, "ray {i} stops at the nearest plate");
    }
    assert_eq!(counting.alone, 0, "no ray finished a plate alone");
    assert!(counting.together >= 64, "{} lane tests", counting.together);
}

/// The four-at-a-time slab numbers are bit for bit those of single rays, octants
/// and validity included, for directions with zero, negative-zero, tiny and
/// non-finite components.
#[test]
fn chunk_numbers_are_the_single_ray_numbers() {
    let components = [
        0.0,
        -0.0,
        1e-31,
        -1e-31,
        1e-30,
        0.5,
        -2.0,
        3e-7,
        f32::INFINITY,
        f32::NAN,
    ];
    let origins = [
        Vec3::ZERO,
        Vec3::new(1.0, -2.0, 1e-25),
        Vec3::new(-0.0, 3e5, 0.25),
    ];
    let mut rays = Vec::new();
    for &x in &components {
        for &y in &components {
            for (i, &z) in components.iter().enumerate() {
                rays.push(Ray::new(origins[i % 3], Vec3::new(x, y, z)));
            }
        }
    }
    for chunk_rays in rays.chunks(37) {
        let mut chunk = ChunkNumbers::EMPTY;
        chunk.fill(chunk_rays);
        // Each lane in at most one octant, and no lane past the last ray.
        let mut seen = 0;
        for &mask in &chunk.octants {
            assert_eq!(mask & seen, 0, "octants overlap");
            assert_eq!(mask & !chunk.all, 0, "a lane past the last ray");
            seen |= mask;
        }
        for (i, ray) in chunk_rays.iter().enumerate() {
            let single_ray = BoxRay::new(ray);
            let in_octant = chunk.octants.iter().position(|mask| mask & (1 << i) != 0);
            assert_eq!(in_octant.is_some(), single_ray.valid, "{ray:?}");
            if !single_ray.valid {
                continue;
            }
            assert_eq!(in_octant, Some(usize::from(single_ray.octant)), "{ray:?}");
            for axis in 0..3 {
                let lane = |lanes: &[Lanes; 3]| lane(&lanes[axis], i).to_bits();
                let single = |lanes: &[Vec4; 3]| lanes[axis].x.to_bits();
                assert_eq!(
                    lane(&chunk.numbers.origin_near),
                    single(&single_ray.origin_near)
                );
                assert_eq!(
                    lane(&chunk.numbers.origin_far),
                    single(&single_ray.origin_far)
                );
                assert_eq!(lane(&chunk.numbers.inverse), single(&single_ray.inverse));
            }
        }
    }
}

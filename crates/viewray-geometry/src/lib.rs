//! viewray's ray-casting core: rays, shapes, triangle meshes and the BVH.
//!
//! This crate owns the geometry a viewing ray meets. It knows nothing about cameras,
//! scene files or images, and it does no I/O.
//!
//! Rays keep the lecture's *unnormalized* directions: a ray is `origin + t * direction`
//! and every `t` this crate reports is in units of the ray's own direction, whatever
//! its length. Queries take a range `t_range` and accept `t_range.start <= t <
//! t_range.end`; a shadow ray toward a light at `p = origin + direction` is
//! `any_hit(&ray, 1e-4..1.0)`.
//!
//! # Map
//!
//! - [`Ray`], [`DRay`]: rays in `f32` (tracing) and `f64` (camera arithmetic).
//! - [`Sphere`], [`Plane`], [`Triangle`], [`Aabb`] (the `Box` primitive and the BVH's
//!   bound): analytic shapes, each with `closest_hit`.
//! - [`MeshData`] (vertex data, from vectors or tobj's flat arrays, plus the
//!   [`MeshData::icosphere`] and [`MeshData::cuboid`] generators) and [`Mesh`] (validated,
//!   with its BVH); [`Instance`]: a shared mesh placed by an affine transform.
//! - [`World`]: a list of [`Object`]s with a top-level BVH; hits name the object's index.
//! - [`Hit`]: what a closest-hit query reports; [`TriangleHit`] and [`ObjectHit`]: the
//!   closest triangle or object before its surface details are computed;
//!   [`GeometryError`]: why data was refused.
//! - [`Bvh`]: the hierarchy itself, generic over anything [`Bounded`].
//!
//! # Design
//!
//! Robustness first, then speed; every choice below is covered by the tests in
//! `src/tests.rs` (brute-force agreement, watertightness, edge cases).
//!
//! - **Watertight triangles.** Ray/triangle tests follow Woop, Benthin and Wald,
//!   "Watertight Ray/Triangle Intersection" (JCGT 2013): the ray is sheared onto +z,
//!   edge functions of a shared edge are bit-identical in both triangles, and exact
//!   zeros are recomputed in `f64`. A ray through an edge or vertex of a closed mesh
//!   never slips through; zero-area faces are dropped when a mesh is built.
//! - **Robust boxes.** Box exits are widened by `1 + 2 gamma(3)` (Ize, "Robust BVH Ray
//!   Traversal", JCGT 2013), and a direction component of zero is handled without NaN,
//!   so that axis-parallel rays along box faces (common with orthographic cameras and
//!   axis-aligned meshes) still enter the boxes they graze.
//! - **Binned SAH, eight children per node.** 32 bins per axis; a node is opened by
//!   repeatedly splitting its largest child until it has eight, splits that fill a free
//!   slot cost no extra node, leaves hold at most 8 triangles. Large ranges are binned
//!   and built in parallel with rayon (on a one-thread pool the build stays serial:
//!   building each subtree into its own array and copying it into place only adds
//!   work). After a depth of 40 the build halves ranges by
//!   count, which bounds the depth and so the traversal stack. The build is shaped by
//!   its small ranges, of which there are as many as leaves: a range no bigger than one
//!   block becomes a leaf without binning (no split can be cheaper), the SAH sweep runs
//!   the three axes side by side, one per SIMD lane (each bin's three boxes transposed,
//!   their half areas computed with the scalar formula's operations in its order, so
//!   every cost is the axis-by-axis cost to the bit), build items are two
//!   aligned SIMD registers with the index in a spare lane, and the three bins of an item
//!   are one SSE2 conversion. Large ranges bin their even and odd items into two sets of
//!   bins merged after (neighbouring items fall in the same bins, and one set would make
//!   each update wait for the last). A split moves the items first and then folds each
//!   side's bounds, even and odd items in two chains (gathered while moving, both sides'
//!   eight accumulators spilled out of the SSE registers). The move is one pass without
//!   a branch on the side: each item is swapped with the first item not yet known to go
//!   left, and the count of left items grows by 0 or 1 (the two-ended partition it
//!   replaced branched on every item's side, which a processor cannot predict). Each of these
//!   leaves the nodes the same; the last one changes the order of a leaf's triangles,
//!   which matters only where a ray meets two of them at exactly the same distance (no
//!   image or hit checksum changed). Around the tree, a mesh writes its build items in
//!   place in parallel and fills its triangle packets in parallel too (on 2 threads
//!   these serial steps had been a fifth of the build), each packet's corners as four
//!   points transposed into rows of x, y and z rather than 36 scalar stores.
//! - **Structure-of-arrays nodes and triangle packets.** A node stores its children's
//!   boxes as rows of eight floats, tested four at a time with SSE (glam's `Vec4`, the
//!   x86_64 baseline: no `target-cpu=native`). Leaves point at packets of four triangles
//!   in structure-of-arrays layout, stored in leaf order, tested at once. Most of a
//!   leaf's triangles lie beside a ray that reaches it: a packet whose four edge tests
//!   all fail is rejected before the division for `t`.
//! - **Ordered, allocation-free traversal.** Children hit are visited nearest first, and
//!   subtrees entered beyond the closest hit so far are skipped. The traversal is
//!   compiled once per sign pattern of the direction, so the near and far plane of each
//!   slab are constants. Its stack is a fixed array reused from a thread-local (zeroing
//!   a fresh one per ray cost a quarter of a primary ray), with a node's row to spare so
//!   that a node's sorted children are pushed by one fixed-size copy (a copy of the
//!   exact length was a call to `memcpy` per node). On large meshes rays are
//!   bound by memory latency, so the children a ray will visit are prefetched as soon
//!   as their boxes are hit (one of the crate's three `unsafe` blocks: the x86_64
//!   prefetch hint; the others are the builder's SSE2 float-to-integer conversion and
//!   the `madvise` that asks for huge pages, see the speed notes).
//! - **Packets for coherent rays.** [`Mesh::closest_triangles`] and
//!   [`World::closest_objects`] trace up to 64 rays of one octant (a renderer's 8 x 8
//!   pixel block) together. One interval-arithmetic test per node bounds every ray of
//!   the packet at once; rounded subtraction and multiplication are monotonic, so it
//!   never culls a box that a ray's own test would enter. Leaves, and the children of a
//!   node where the packet enters six or more (geometry fine next to the packet), are
//!   tested against each ray, four rays per SSE instruction with exactly the single-ray
//!   arithmetic, and the rays that hit finish them alone; such a child that 16 or more
//!   of the packet's rays enter stays with the packet (walking it once for a quarter of
//!   the packet is cheaper than walking it sixteen times). A packet therefore finds the
//!   hits its rays find alone (of two surfaces at exactly the same `t`, either may be
//!   reported), for a fraction of the node visits: the upper levels, which every ray of
//!   a block repeats, are walked once. Packets whose unit directions spread more than
//!   0.05 (random rays) are traced ray by ray. A packet's slab numbers are set up four
//!   rays at a time, bit for bit as for single rays.
//! - **Packets for shadow rays.** [`World::any_hits`] traces up to 64 rays of one octant
//!   (a block's shadow rays toward one light) together: the packet's interval test walks
//!   the top-level BVH once, each leaf goes to the rays whose own box test enters it,
//!   and a ray that hits stops searching; every ray gets the answer [`World::any_hit`]
//!   gives it. The numbers a packet is set up from (seven kilobytes) are reused from a
//!   thread-local: zeroing them for each batch of shadow rays cost more than tracing it.
//! - **Short cuts for simple worlds.** A world with one bounded object skips its
//!   top-level BVH (whose one box only repeats the object's own first test), and an
//!   instance with the identity transform does not carry rays into object space.
//! - **Deferred surfaces.** Traversal keeps only `t`, face and barycentrics; normals and
//!   texture coordinates are computed once, for the winner ([`Mesh::closest_triangle`],
//!   [`World::closest_object`] and the packet queries skip them altogether).
//!
//! # Speed
//!
//! `cargo bench -p viewray-geometry --features bench` measures build time, memory and
//! throughput on a 1,310,720-triangle icosphere side by side with the obvhs crate
//! (CWBVH); `--features bench,embree` adds Embree 3 (the system's libembree3) in the
//! same run: its packet kernels `rtcIntersect16` (tiles of 4 x 4 pixels) and
//! `rtcIntersect8` (4 x 2) on the coherent primary rays, `rtcIntersect1` ray by ray, and
//! its build. It prints one table with the ratio of viewray's speed to each peer's
//! (above 1.00x: viewray is faster). A case's contenders take turns, one run each per
//! round after a warm-up run of each: on the development machine, a virtual machine
//! shared with others, slow spells last seconds (the same process traced the coherent
//! rays at 0.068 s a pass for a while and at 0.052 s after), and with each contender's
//! runs back to back a spell fell on whichever ran then (viewray's packets came out at
//! 0.82x of `rtcIntersect16` in one run and 1.02x in the next). Three full runs after
//! the latest round of changes (`VIEWRAY_BENCH_RUNS=3`, so each figure a median of 3),
//! and the ratios of the three runs of the round before; read the ratios within a run,
//! as Embree's own figures move by a tenth to a third between runs. Embree's one-thread
//! builds before the latest round ran on two threads (see *Embree's one-thread build*
//! below), so that column's build ratios understate viewray:
//!
//! | 1 thread unless stated | run 1 | run 2 | run 3 | round before (three runs) |
//! |---|---|---|---|---|
//! | build | 0.396 s (Embree 0.431: 1.09x) | 0.296 s (0.517: 1.75x) | 0.333 s (0.461: 1.38x) | 0.74x, 0.95x, 0.68x |
//! | build, 2 threads | 0.160 s (0.226: 1.41x) | 0.226 s (0.276: 1.22x) | 0.214 s (0.280: 1.31x) | 1.13x, 1.43x, 1.34x |
//! | coherent, packets of 64 vs `rtcIntersect16` | 19.74 Mrays/s (1.06x) | 20.45 (1.10x) | 19.22 (1.14x) | 1.11x, 1.12x, 1.10x |
//! | coherent, packets of 64 vs `rtcIntersect8` | 1.32x | 1.33x | 1.36x | 1.34x, 1.35x, 1.36x |
//! | primary, ray by ray vs `rtcIntersect1` | 8.10 Mrays/s (0.88x) | 7.92 (0.86x) | 8.09 (0.89x) | 0.87x, 0.87x, 0.83x |
//! | incoherent vs `rtcIntersect1` | 1.98 Mrays/s (1.02x) | 1.88 (1.00x) | 1.91 (0.98x) | 1.01x, 0.92x, 0.94x |
//! | coherent, 2 threads, vs `rtcIntersect16` | 41.32 Mrays/s (1.12x) | 36.71 (1.03x) | 34.77 (0.97x) | 0.96x, 0.90x, 0.90x |
//! | incoherent, 2 threads, vs `rtcIntersect1` | 4.26 Mrays/s (1.05x) | 3.92 (0.96x) | 4.31 (1.01x) | 0.97x, 0.95x, 0.91x |
//!
//! Memory: 53.9 bytes per triangle (BVH + triangle packets; obvhs 60.3). viewray is
//! 1.94x to 4.71x faster than obvhs everywhere. Embree finds the same closest hit
//! (within 1e-4 of `t`) for all but 2 of the 1,048,576 primary rays and of the million
//! incoherent ones. The latest round kept the hierarchy, the hits and the images bit
//! for bit:
//!
//! - **Embree's one-thread build.** Embree runs a build on as many threads as the most
//!   any live device asked for (`getMaxNumThreads` in its `device.cpp`), not on the
//!   count of the device that builds. The bench kept the tracing scene's device, made
//!   with all threads, alive through the build cases, so the "1 thread" Embree builds
//!   of the rounds before ran on both cores (0.22 to 0.30 s, its two-thread figure).
//!   That device now asks for one thread: a scratch program timing one-thread devices
//!   with `getrusage` saw 0.42 to 0.46 s a build with user time equal to wall time, and
//!   0.22 s with twice the wall time in user time while a device of all threads lived.
//! - **The sweep's block counts.** A bin's three counts are one register, a side's
//!   counts an integer vector, and the blocks of the three lanes one add, one shift and
//!   one conversion, the choice between shifting and dividing made once per sweep (a
//!   fifth of each bin's step had gone to three scalar conversions and a branch). The
//!   same trees (counts are below 2^27, where `i32` and `u32` agree; the block size is
//!   clamped to 2^27, which counts as any larger block does): the profile example's
//!   `build` 4,409 M to 4,113 M instructions, its wall time within the noise.
//! - **A ray's watertight set-up and the packets' sign test.** Each ray reaching a
//!   leaf picks its axes once; the lookups went through glam's `Index` on `Vec3`, a
//!   `match` on the axis (branches that depend on the ray's direction), now arrays and
//!   a constant table of successors. A packet is rejected when the least edge function
//!   is below zero and the greatest above (two minima, two maxima, two comparisons,
//!   for six comparisons and four ORs; a NaN lane may go either way, and its `t` is
//!   NaN, never a hit). 100,000 incoherent rays 130.5 M to 126.8 M instructions, the
//!   profile example's coherent packets 37.6 M to 36.3 M. The three runs before these
//!   two changes had the incoherent rays at 0.93x, 0.94x and 0.95x of
//!   `rtcIntersect1`; the three after, above, at 0.98x to 1.02x.
//!
//! The round before changed the traversals and kept the hierarchy, the hits and the
//! images bit for bit:
//!
//! - **AVX box tests.** Callgrind, which models the caches, put 100,000 of the
//!   incoherent rays at the same first-level cache misses as `rtcIntersect1` (22.3
//!   against 22.6 per ray) but twice its instructions (1,649 against 836 per ray; Embree
//!   runs its AVX2 kernels under valgrind): the gap was instructions, and most of them
//!   went to testing a node's eight boxes as two groups of four in SSE. Where the
//!   processor has AVX (and POPCNT, which comes with it), detected at run time, the
//!   single-ray and packet traversals now run compiled for it and test the eight boxes
//!   in one 256-bit register per plane (module `avx`, the only home of those
//!   intrinsics). The operations are the SSE test's, lane for lane and operand for
//!   operand, with no fused multiply-add, so the bits are the same on every x86-64
//!   processor: proptests compare the masks and entry distances bit for bit (with boxes
//!   whose corner lies on the ray, where the exit's enlargement decides), and a test
//!   traces single rays and packets both ways. A node where a single ray enters exactly
//!   two children pushes the farther one without sorting. Instructions per incoherent
//!   ray: 1,649 to 1,305; for the million coherent primary rays, 645.6 M to 568.3 M.
//! - **Lane masks from a table.** 7% of the packet tracing's instructions went to
//!   building four-lane masks from bits, four loads and shuffles each; a table of the
//!   sixteen masks is one load (bare packet tracing 5% faster). The largest closest
//!   distance among a packet's lanes, worked out after every hand-over to single rays,
//!   goes through the table for every group instead of a branch per group (565.8 M to
//!   544.6 M instructions for the million coherent rays; after the table runs above).
//! - **Packets in the items' memory.** A build fills about 120 MB of fresh memory, and
//!   the kernel zeroes every page it faults in: with the system allocator, the profile
//!   example's four builds spent 0.28 to 0.58 s in the kernel against 1.5 s of user
//!   time. The triangle packets are now written into the build items' buffer, made
//!   large enough for both and cast from empty to empty (bytemuck; no unsafe code):
//!   0.19 to 0.21 s in the kernel, one-thread builds 2% to 3% faster by the fastest
//!   runs. (`viewray render` uses mimalloc, which already reused the items' pages.)
//!
//! Targets and where they stand, 1 thread: coherent packets at 1.06x to 1.14x of
//! `rtcIntersect16` (met); the build at 1.09x to 1.75x of Embree's speed (met; 1.22x
//! to 1.41x on 2 threads); memory 53.9 bytes per triangle (met); incoherent rays at
//! 0.98x to 1.02x of `rtcIntersect1` (even: met in two runs of three, 2% short in the
//! third). Three more runs a round later, with the tracing unchanged: build 1.92x,
//! 1.76x, 1.58x (2 threads 1.35x, 1.37x, 1.45x); coherent packets 0.97x, 1.10x, 1.13x
//! (the 0.97x in a slow spell over viewray's runs: 16.1 to 19.3 Mrays/s against 20.4
//! to 20.6 in the other two); incoherent 1.01x, 0.94x, 1.00x (the 0.94x with viewray's
//! runs at 1.56 to 1.80 Mrays/s). Over the six runs the incoherent rays stand at even,
//! 0.94x to 1.02x, median 1.00x.
//!
//! **Incoherent rays side by side (the latest round).** A ray's walk through a tree
//! larger than the caches waits on memory at every level, one load at a time: the next
//! node is known only once the current one is tested. [`Mesh::closest_triangles`]
//! (and [`World::closest_objects`] for a world whose one bounded object is a large
//! mesh, or whose own tree is that large) now walks an incoherent packet's rays
//! (directions too spread for the shared box test) eight at a time, taking turns one node or leaf
//! each: the node a walk goes to next was prefetched by its step, and arrives while the
//! other seven take theirs, so up to eight loads are in flight instead of one. Each walk
//! is exactly a single ray's (the traversal loop is one step function, which the
//! single-ray walk calls in a loop), so the hits are the same to the bit; tests compare
//! them with single rays, on the AVX and SSE paths, with a switch that makes every tree
//! walk side by side and on a 330k-triangle mesh that does so by itself. Taking turns
//! costs instructions (a fifth more per ray) and the branch predictor's grip on each
//! walk, so only trees of 8,192 nodes or more do it (see `WALK_NODES` in `bvh.rs`: 1M
//! incoherent rays side by side against one after another, 1 thread: 0.30 s against
//! 0.23 s at 20k triangles, 0.29 against 0.27 s at 82k, 0.30 to 0.32 s against 0.39 to
//! 0.43 s at 330k, 0.33 to 0.36 s against 0.47 to 0.51 s at 1.3M). Four walks side by
//! side took 0.42 s at 1.3M, sixteen the same as eight. Coherent packets keep handing
//! their subtrees to single rays one after another: walking those side by side too
//! gained nothing (the million primary rays 0.0505 to 0.0516 s against 0.0504 to
//! 0.0507 s, three alternated runs), since a packet's rays in one subtree share its
//! nodes and the first ray's loads serve the others.
//! The bench's new case, the million incoherent rays handed over 64 at a time, four
//! runs:
//!
//! | 1 thread unless stated | run 1 | run 2 | run 3 | run 4 |
//! |---|---|---|---|---|
//! | incoherent, 64 at a time, vs `rtcIntersect1` | 2.30 Mrays/s (1.30x) | 2.38 (1.27x) | 2.84 (1.41x) | 2.46 (1.31x) |
//! | the same vs `rtcIntersect16` (incoherent context) | 1.26x | 1.25x | 1.38x | 1.26x |
//! | the same, 2 threads, vs `rtcIntersect1` | 4.98 Mrays/s (1.26x) | 4.69 (1.31x) | 5.06 (1.23x) | 4.93 (1.29x) |
//! | incoherent, ray by ray, vs `rtcIntersect1` | 1.78 Mrays/s (1.01x) | 1.76 (0.97x) | 1.97 (0.99x) | 2.02 (1.03x) |
//! | coherent, packets of 64, vs `rtcIntersect16` | 20.58 Mrays/s (1.11x) | 17.30 (0.96x) | 17.13 (0.95x) | 20.34 (1.14x) |
//! | build vs Embree | 0.422 s (1.42x) | 0.277 s (1.77x) | 0.390 s (1.29x) | 0.398 s (1.35x) |
//! | build, 2 threads | 1.26x | 1.33x | 1.35x | 1.79x |
//!
//! Runs 2 and 3 ran back to back in a slow spell that took viewray's coherent packets
//! to 17.1 to 17.3 Mrays/s and Embree's to 17.9 (scratch timings of the packets just
//! after swung between 0.050 and 0.061 s a pass every minute or so, for the round's
//! binary and the one before alike, whose callgrind instruction counts agree within
//! 0.01%). Embree's 16-wide kernel, handed the same rays in an incoherent context,
//! traces them at its single-ray speed (1.82 to 2.06 Mrays/s). Ray by ray, the
//! incoherent rays stay even with `rtcIntersect1` (0.97x to 1.03x): one ray alone has
//! nothing to take turns with.
//!
//! Measured and left out in the same round: nodes of 128 bytes instead of 256, each
//! child's box quantized to 8 bits per plane within its node's box (rounded outward,
//! widened by a margin, decoded to `f32` at each visit), which halves the nodes' share
//! of the caches. The same hits, but 1M incoherent rays one by one took 0.58 to 0.70 s
//! against 0.51 to 0.58 s (medians of five, six alternated pairs: 4% to 30% slower):
//! decoding sits between a node's load and its box test, on the path every level
//! waits on. Node bytes do matter: nodes padded to 512 bytes (so that
//! they use half of the cache's sets) made the same rays about a tenth slower.
//!
//! These standings hold for the benchmark's 1.3M triangles, whose 70 MB are twice the
//! development machine's 32 MB L3: there both libraries wait on memory. On meshes that
//! fit in the caches the instructions show, and Embree's kernels (AVX-512 on this
//! machine, fused multiply-adds) lead: at 6 subdivisions (81,920 triangles) coherent
//! packets 0.83x of `rtcIntersect16` and incoherent rays 0.83x of `rtcIntersect1`; at
//! 5 (20,480) 0.69x and 0.84x (one run each of `VIEWRAY_BENCH_SUBDIVISIONS=6` and
//! `=5`). The leaf tests are most of the difference for packets (232 of the 420
//! instructions a coherent ray costs at 5 subdivisions): each lane's ray meets four
//! triangles per instruction, where Embree's 16-wide kernel meets one triangle with
//! sixteen rays. viewray's box and triangle tests stay without fused multiply-adds, so
//! that the baseline and AVX paths give the same bits and a scene renders the same on
//! every machine. Prefetching still pays at that size (1M incoherent rays at 5
//! subdivisions 0.19 s against 0.20 s without it, at 6 0.25 s against 0.27 to 0.33 s).
//! At 5 subdivisions a packet reaches a leaf with 12.6 of its rays on average (at 8,
//! with 1.2: there the leaves are tested ray by ray whatever the kernel). Measured and
//! left out: a ray-parallel leaf test for packets, one triangle against eight rays
//! sharing their watertight axes per AVX instruction, the same operations and the same
//! choice within a packet as the four-triangle test (the same checksums): about 108
//! instructions a triangle for eight rays against about 24 a ray and triangle, but
//! gathering the rays' numbers into eight lanes and the call's set-up ate the gain.
//! Compacting the lanes that share their axes, the 65,536 coherent rays of the
//! profile example at 5 subdivisions took 26.7 M instructions against 27.5 M (-3%);
//! testing fixed groups of eight lanes in place, whose numbers lie side by side,
//! 28.5 M, and 52.4 M against 50.6 M at 7. A kernel of its own for packets would have
//! to keep their rays in that layout from the start, as Embree's 16-wide one does. What is left of the incoherent gap is instructions (about 1,270 against
//! Embree's 836 per ray, which on this machine runs AVX-512 kernels) around waiting on
//! memory: about 100 per node visit (the box test is 30 of them; the rest the hit
//! children's prefetches, sorting and stack) and about 260 per leaf (a call with its
//! saved registers, the ray's set-up once, the watertight test of four triangles
//! at a time). perf of a million of them puts two thirds of the leaf tests' time on the
//! first load of a leaf's triangles and a third of the traversal's on the first load
//! of a node: prefetched as the ray reaches the parent, too late for the child it
//! enters next. Measured and left out: the leaves' triangle tests compiled for AVX too
//! (1.1% fewer instructions); prefetching fewer lines of a child node (no change beyond
//! the noise); prefetching the children nearest first, after sorting them (1M rays
//! 0.537 s against 0.528 s, medians of five alternated runs); the leaf test inlined
//! into the traversal (tried with a nightly compiler's `#[inline(always)]` on the
//! closure: 4.8% fewer instructions, but 0.559 s against 0.537 s, medians of six
//! alternated runs, with sixteen copies of the leaf test in the traversals); a hit
//! child's prefetch without a branch on its kind (the address chosen between node and
//! leaf, six lines either way: five alternated runs within 3% both ways); the SAH's
//! node cost raised from 1 to 2 blocks, with leaves of up to 8 or 12 triangles (the
//! same hits; 51.0 and 50.0 bytes a triangle instead of 53.9, but 1M incoherent rays
//! at 0.515 and 0.513 s against 0.516 s and coherent packets at 0.0501 and 0.0502 s
//! against 0.0506 s, medians of six alternated runs: no speed to show for a different
//! hierarchy). Nor do the eight copies of the traversal (one per direction octant) cost
//! the incoherent rays anything: one AVX traversal for every octant, with the near and
//! far planes' rows chosen per ray as Embree does, traced the million rays in the same
//! time (medians of five 0.502 to 0.581 s against 0.496 to 0.565 s, five alternated
//! runs), and with the leaf test inlined into that single copy (nightly
//! `#[inline(always)]` on the closure, so no sixteen copies this time) no faster
//! either (0.512 to 0.607 s). The same rays sorted by octant run 8% to 10% faster
//! (medians 0.442 to 0.518 s against 0.494 to 0.533 s): rays of one octant from
//! random origins reach the same side of the sphere, and the leaves they share stay
//! in the cache. That is the lever left for incoherent rays, reordering them, which a
//! caller tracing one ray at a time (as `rtcIntersect1` is called) cannot use.
//!
//! **Huge pages.** A mesh's build items (32 bytes a triangle), nodes and triangle
//! packets (40 bytes a triangle) are tens of megabytes each; filled page by page at 4
//! KiB, a seventh of a 1-thread build went to the kernel's page faults, and an
//! incoherent ray's walk through 70 MB touches a new page at nearly every node and
//! leaf, each a miss in the TLB. `madvise(MADV_HUGEPAGE)` on each buffer before it is
//! filled (Linux, through the libc crate; Embree's allocator does the same) gives 2 MiB
//! pages where the system leaves them to `madvise`: the 1-thread build 13% faster
//! (medians of five alternated runs of nine builds, 0.329 s to 0.286 s), 1M incoherent
//! rays 3% to 9% faster, coherent rays unchanged; `viewray render` of the icosphere
//! (one build per process, mimalloc) builds 5% faster in one batch of six alternated
//! runs and no faster in another of five. Where the system keeps huge pages off,
//! nothing changes. On the development machine, a virtual machine that backs its memory
//! lazily, huge pages not touched for a while are slow to touch again: the first build
//! of the bench's cases, and the first build of a process after a pause, took 0.37 to
//! 0.54 s (0.27 to 0.30 s for the builds after it, and for a process started right
//! after another). The kernel never had to compact memory for them (`compact_stall`
//! stayed 0 in `/proc/vmstat`). Keeping the build items on 4 KiB pages, to touch fewer
//! huge pages, made the steady builds slower (0.29 to 0.31 s) and the bench's no
//! steadier, so every large buffer asks.
//!
//! Where the build stands: ahead of Embree on 1 thread (1.09x to 1.75x) and on 2 (1.22x
//! to 1.41x). The rounds before measured 0.68x to 0.95x on 1 thread against an Embree
//! that, unknown to the bench, built on two (above). perf of the 1-thread build puts about a
//! quarter of its time on binning (three bins' boxes and counts updated per item and
//! axis), a quarter on choosing splits (the small ranges' binning and the sweeps: a
//! build sees half a million ranges of at most 32 items) and a sixth on the partition
//! and each side's bounds, and, in a process that builds several meshes with the system
//! allocator, up to a third of the whole on the kernel zeroing fresh pages (before the
//! packets reused the items' memory). The tree is the same as Embree's kind
//! (binned SAH, 32 bins, eight children), and every item is visited about twenty times
//! over the levels; the time goes to that per-visit work (Embree's kernels are compiled
//! once per instruction set and chosen at run time; viewray's builder is SSE2, and
//! faster on one thread all the same). Measured and left out: a branch-free
//! block partition (swapping only misplaced items, BlockQuicksort-style: no faster);
//! reusing the split a small child's second look chose when the child is opened (the
//! same split; only 0.3% of the instructions, and a larger range record cost more);
//! transposing all the bins before the sweep instead of each side's extents in it (15%
//! more instructions: the stores of the transposed bins); the builder compiled for AVX2
//! (10% fewer instructions but 15% to 25% slower: a 32-byte load of an item just
//! written as two 16-byte halves cannot be forwarded, and the partition waits on it).
//!
//! The packets trace a leaf's triangles one ray at a time against four triangles per
//! SSE instruction, where Embree's 16-wide kernel tests sixteen rays at once; they came
//! out ahead (1.10x to 1.12x) once the box tests went to AVX. The incoherent rays wait
//! on memory as much as Embree's do (the same cache misses, above): perf of 1M of them
//! puts 62% of the leaf tests' time on the first load of a leaf's triangles and a
//! quarter of the traversal's on the first load of the next node, both prefetched only
//! as the ray reaches the parent (the prefetch still pays: without it for child nodes the same
//! rays took 0.60 to 0.66 s against 0.51 to 0.55 s, medians of 5 in three alternated
//! runs, and skipping it for a lone hit child, loaded at once anyway, cost 3% to 13%).
//! Tracing two rays of one octant side by side, a step of each in turn so that one's
//! wait overlaps the other's work (the same hits), was 20% slower (0.65 to 0.67 s
//! against 0.52 to 0.54 s for the 1M rays, three runs): each step's mispredicted
//! branches flush the other ray's work with its own. Eight side by side, each step
//! prefetching the next node of its walk, pay on trees beyond the caches (the latest
//! round, above): enough loads in flight to outweigh the lost predictions. The rule for handing subtrees to
//! single rays trades the benchmark against finer meshes: handing them over only where
//! the packet enters all eight children would trace the 1.3M-triangle icosphere 6% to
//! 7% faster but 5.2M and 21M triangles 6% to 40% slower (bare packet tracing at 1024 x
//! 1024, medians of 11); the 16-ray rule gains 4% to 6% at 82k and 1.3M triangles and
//! is within noise (up to 3% slower) at 5.2M and 21M.
//!
//! Because wall-clock time on a shared machine is this noisy, changes are decided on
//! instruction counts: `examples/profile.rs` is a fixed workload for callgrind (see its
//! doc). On its 81,920-triangle icosphere (6 subdivisions) the tracing of the 65,536
//! primary rays in packets of 64 (`--toggle-collect='*closest_triangles*'`) executes
//! 36.3 M instructions where the processor has AVX (callgrind's does; 37.6 M before the
//! latest round's watertight set-up and sign test, 48.8 M with the SSE box tests
//! before the AVX ones, 49.6 M before that round). Its `build` workload (the
//! icosphere generated once, then built five times) executes 926 M instructions for the
//! whole program on one thread (990 M before the latest round's sweep; 1,187 M before
//! the build changes of the round before that;
//! 1,151 M before the partition lost its branches: more instructions, less time;
//! 1,179 M before a split's bounds were folded after the partition, 1,849 M before
//! the builder's rewrite); at 8 subdivisions (1.3 M triangles) it runs in 2.29 s on 1
//! thread against 2.46 s with the branching partition (medians of seven alternated runs),
//! and in 1.50 s against 1.57 s on 2 (nine, on a busy machine). Instruction counts are no
//! substitute for the table (Embree uses AVX-512, and rays wait on memory), but two
//! builds of viewray compare reliably.
//!
//! Wider instruction sets, measured and left out:
//!
//! - A build of the whole crate for `x86-64-v4` (AVX-512) traces 10% to 20% faster
//!   (packets at 0.92x to 0.93x of `rtcIntersect16` against 0.77x to 0.81x), but glam
//!   then fuses multiplies and adds at compile time, which changes the bits of a hit.
//!   Compiling only the traversal loops for `x86-64-v3` and `x86-64-v4` beside the
//!   baseline, chosen at run time (the same bits), gained -1% to 5% (packets 15.62, 15.29
//!   and 14.38 Mrays/s against 15.19, 14.53 and 14.54 with the baseline, alternated
//!   runs): not worth three copies of every traversal. What paid was the explicit
//!   test of eight boxes in one AVX register (above): compiled for AVX, the SSE
//!   test stays two groups of four.
//! - Two rays against a leaf's four triangles per 256-bit AVX instruction (each half
//!   exactly one ray's 128-bit test) cut the icosphere render's instructions by 4.4%
//!   (880 M to 841 M) and its time not at all (`render_s` 0.080 to 0.098 s against
//!   0.080 to 0.090 s, six alternated runs): the leaf tests wait on something other
//!   than their arithmetic, most likely the loads of their triangles.
//!   Tried again after the early rejection above (with AVX detected at run time, rays
//!   paired where they share their shear axes, six rays a leaf on average): bare packet
//!   tracing 0.0573 to 0.0595 s against 0.0568 to 0.0618 s (medians of 11, three
//!   alternated runs), no gain.
//! - Taking the one lane hit without the horizontal minimum (one lane is the common
//!   case): no measurable change.
//! - The whole crate built with AVX2 (without fused multiply-adds) for the build: the
//!   1-thread build of the 1.3M-triangle icosphere got slower, fastest of nine 0.329 to
//!   0.342 s against 0.285 to 0.288 s (four alternated runs).
//!
//!
//! Where the time goes (callgrind, one thread):
//!
//! - **A render of the icosphere** (`viewray render target/icosphere/icosphere.ron
//!   --stats --threads 1`, Flat shading, 1024 x 1024 primary rays) executes 887 M
//!   instructions, of which packet tracing ([`World::closest_objects`], which hands the
//!   packets straight to the mesh) is 735 M: the render costs 1.21x its tracing in
//!   instructions (1.39x before a perspective camera shared its eye and `-d w` across
//!   rays and the block loop stopped building film points it does not use). In wall-clock
//!   time, `viewray-render`'s `examples/icosphere.rs` times the render against the same
//!   rays traced as the same packets: the fastest of 11 runs gives 1.07x to 1.14x on 1
//!   thread (before: 1.34x to 1.39x), the medians 1.16x to 1.18x (before: 1.31x to 1.40x),
//!   three runs each, the two versions alternated; the aim is 1.10x. The session before:
//!   1.15x by the fastest runs on 1 and 2 threads, 1.15x to 1.28x by the medians (two
//!   runs). The round after (868.5 M instructions, 711.6 M of them tracing: 1.22x), two
//!   runs: 1.13x and 1.15x by the medians on 1 thread, 1.11x and 1.15x on 2, 1.14x by
//!   the fastest runs; the latest round (which did not touch this path), three runs:
//!   1.15x to 1.23x by the medians on 1 thread, 1.14x to 1.16x on 2, 1.14x to 1.16x
//!   by the fastest runs. The latest round: a one-sample render asks the camera for
//!   a block's rays at once (each column's `u U` and each row's `v V` worked out once,
//!   the same bits), and the leaf and packet changes above made the bare tracing about
//!   a tenth faster. `viewray render --stats` on the icosphere went from 0.0733 s to
//!   0.0635 s on 1 thread (medians of 11 alternated runs: 1.15x faster); against its
//!   own faster tracing the render stays at 1.11x to 1.15x by the fastest runs (1.10x
//!   to 1.22x by the medians, three runs on a quiet machine). Splitting the block loop
//!   in two (camera samples, then rays) so that its iterations overlap gained nothing
//!   measurable. The latest round shaded each sample straight into its pixel's sum
//!   (no buffer of colours in between: no measurable change) and gave the mesh huge
//!   pages; in six runs after, the render took 1.09x to 1.12x the bare tracing's time
//!   by the fastest runs, on 1 and 2 threads (1.03x to 1.16x by the medians), and
//!   `render --stats` 0.060 to 0.067 s on 1 thread. What is left
//!   is the camera's `f64` arithmetic (two divisions a ray), the block's bookkeeping
//!   (clearing the tile's sums alone writes as many bytes as the image) and Flat
//!   shading, about 140 instructions a ray together. The latest round put a block's rays,
//!   pixel indices and hits in fixed slots written by index (each push had stored the
//!   vector's length back to memory and loaded it again, the ray's stores being possible
//!   aliases of it) and kept only each ray's pixel index (the row and column follow from
//!   the tile where a film point asks): the render's own instructions outside the
//!   tracing 95.9 M to 83.6 M for the million rays (the whole tile loop 649.7 M to
//!   637.4 M). In five alternated runs of the example against a binary from the round's
//!   start, the render took 1.086x to 1.107x the bare tracing's time by the fastest runs
//!   on 1 thread (middle run 1.097x) against 1.104x to 1.126x (1.116x); by the medians
//!   1.07x to 1.14x (one run at 1.46x) against 1.11x to 1.13x. With the round's faster
//!   leaf set-up, which speeds the bare tracing as much as the render, four more
//!   alternated runs: 1.098x to 1.127x on 1 thread and 1.111x to 1.129x on 2 (the
//!   round's start: 1.104x to 1.113x and 1.100x to 1.139x). The render stands at the 10%
//!   line, not clearly inside it.
//!
//!   The latest round made the example's figure steadier (the render on the bare
//!   loop's pool, as `viewray render` uses rayon's global one, timed up to the finished
//!   image as `--stats` times it, 21 runs, and the median of each render's ratio to the
//!   bare run just before it: the middle half of those ratios now spans about 2%), put
//!   a block's rays, pixel indices and hits in arrays of 64 (the render's own
//!   instructions 70.9 M to 62.4 M per million rays at 6 subdivisions; each ray's
//!   write compares against a constant instead of a slice's length) and takes the
//!   image from a zeroed allocation (its pages arrive zeroed and are first touched by
//!   the tiles' copies on every thread, not filled by one thread first). Paired ratios
//!   before: 1.101x, 1.098x, 1.101x on 1 thread, 1.128x, 1.111x, 1.105x on 2; after:
//!   1.095x, 1.091x, 1.066x and 1.116x, 1.108x, 1.107x; three more runs on the final
//!   code: 1.101x, 1.116x, 1.076x and 1.106x, 1.120x, 1.104x. Taking each part out in
//!   turn (wrong images, timing only; 1.091x to 1.120x with every part, in the same
//!   runs) shows where the tenth goes on 1 thread: Flat shading and the sums 3% to 5%
//!   (1.057x and 1.068x without them), generating the rays 2% to 5% (generating them
//!   twice: 1.138x), and writing the 12 MB image, whose fresh pages the kernel zeroes
//!   as they are first touched, 1% to 5% (1.040x to 1.086x without the tiles' copies). Generation is about 20 instructions a ray (two `f64`
//!   sums and the rounding to `f32` for a ray stored whole); the image is the render's
//!   output. The render stays at the 10% line: 1.07x to 1.12x on 1 thread, 1.10x to
//!   1.12x on 2.
//! - **The default scene, Lit** (`viewray render --size 320x180 --samples 4 --threads
//!   1`, 16 objects on a ground plane) executed about 1,760 instructions per sample
//!   (405.8 M, the render loop alone) at the start of the latest round of work on it and
//!   about 1,430 (330.4 M) after: shadow-ray packets ([`World::any_hits`]), primary
//!   and mirror packets ([`World::closest_objects`]), and shading and bookkeeping,
//!   which is more than half (grid lines filtered over each sample's footprint, surface
//!   details, Blinn-Phong with `powf`, each sample's view, offset origin and shadow
//!   rays). With so few objects a packet's setup (its slab numbers and bounds) costs as
//!   much as its traversal.
//!
//! Instruction counts misled on the Lit render: the latest round removed 8% of its
//! instructions (the shading buffers reused from batch to batch) for 2% of its time,
//! and the largest gain of the round removed almost none. The render waited on
//! memory it had just written: four samples' vectors copied into small arrays lane by
//! lane and read back sixteen bytes at a time, which the processor cannot forward
//! from its pending stores (`perf` put 7.7% of the time on glam's `Vec4::new`); a
//! `Hit` returned and copied into place straight after its fields were written (7%,
//! hence [`World::shading_surface_into`]); a group of lanes built on the stack and
//! copied with `memcpy`. Reading each vector where it lies took the Lit render from
//! 1.649 s to 1.504 s on 1 thread (medians of 5). The other gains of that round: the
//! ground plane tested four rays at a time in every packet (about 8% of the time had
//! gone to the per-ray plane tests; 1.449 s to 1.379 s, medians of 9), single lanes
//! of a packet read through arrays instead of glam's `match` on the lane (a jump
//! table, mispredicted whenever the lane changes: 1.692 s to 1.652 s), the two
//! footprint divisions in one, and no spherical uv for shading (the renderer never
//! reads it; `atan2f` and `asinf` were 1.6% of the time).
//!
//! At 1280 x 720, 16 samples, 2 threads (`viewray render --size 1280x720 --samples 16
//! --threads 2 --stats`, 38,387,820 rays), nine runs alternated with the renderer this
//! work started from (401e71b, before shadow and mirror rays went as packets): 0.664 to
//! 0.787 s, median 0.680 s, against 1.411 to 1.593 s, median 1.437 s: 2.11x by the
//! medians, 2.12x by the fastest runs (the round before ended at 1.60x; against that
//! round's last renderer, 0.665 s against 0.871 s, medians of 7). Images identical
//! byte for byte.
//!
//! Measured and set aside on the Lit render:
//!
//! - `line_coverage` inlined into its caller (0.882 s against 0.884 s, medians of 7),
//!   `World::surface` inlined across crates (0.962 s against 0.911 s), and its
//!   division by the grid spacing replaced with a multiplication (for a unit grid the
//!   same bits; no faster, so the division is not what it waits on).
//! - `line_coverage` without branches (all three windows worked out, one picked by
//!   masks): a third fewer simulated mispredictions, 1.69 s to 1.85 s.
//! - The ray prepared for triangles once per leaf rather than once per triangle:
//!   414.2 M to 417.1 M instructions, because the world's leaves hold one or two
//!   objects and there is nothing to share.
//! - The grid footprints four samples at a time, like the lights: 410.0 M to 422.4 M
//!   instructions and no faster (measured before the gathering was fixed).
//! - The whole program built for `x86-64-v3` without fused multiply-adds (the same
//!   bits): 4% faster (medians of 5), not worth a second build of the renderer.

mod aabb;
#[cfg(target_arch = "x86_64")]
mod avx;
mod bvh;
mod error;
mod hit;
mod instance;
mod mesh;
mod packet;
mod ray;
mod shapes;
#[cfg(test)]
mod tests;
mod world;

pub use aabb::Aabb;
pub use bvh::{Bounded, BuildParams, Bvh};
pub use error::GeometryError;
pub use hit::Hit;
pub use instance::Instance;
pub use mesh::{Mesh, MeshData, TriangleHit};
pub use ray::{DRay, Ray};
pub use shapes::{Plane, Sphere, Triangle};
pub use world::{Object, ObjectHit, World};

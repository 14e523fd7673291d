//! Apertures with blades: the polygon, its sampling (uniform, exact on the edges, the
//! square's centre at the lens centre), the rotation's wrapping and the bad values.

use std::f64::consts::{FRAC_1_SQRT_2, PI};

use glam::{DVec2, DVec3};
use viewray_camera::{
    Camera, CameraError, CameraSample, Frame, Iris, Perspective, Projection, ThinLens,
    sample_regular_polygon,
};

#[track_caller]
fn near(got: DVec2, expected: DVec2) {
    assert!(
        got.abs_diff_eq(expected, 1e-12),
        "{got} != {expected} (expected)"
    );
}

fn degrees(angle: f64) -> DVec2 {
    let (sin, cos) = angle.to_radians().sin_cos();
    DVec2::new(cos, sin)
}

#[test]
fn the_square_maps_to_the_polygon_by_hand_worked_points() {
    let h = FRAC_1_SQRT_2;
    // The centre of the square is the centre of the lens, whatever the polygon.
    for blades in [3, 4, 5, 6, 9] {
        assert_eq!(
            sample_regular_polygon(DVec2::splat(0.5), blades, 0.3),
            DVec2::ZERO
        );
    }
    // Four blades, no rotation: corners at 45, 135, 225 and 315 degrees, an edge's
    // middle on +u at cos 45 = 0.7071.
    // (1, 0.5) is the disk's (1, 0): angle 0, the middle of the right edge.
    near(
        sample_regular_polygon(DVec2::new(1.0, 0.5), 4, 0.0),
        DVec2::new(h, 0.0),
    );
    // (0.5, 1) is (0, 1): the middle of the top edge.
    near(
        sample_regular_polygon(DVec2::new(0.5, 1.0), 4, 0.0),
        DVec2::new(0.0, h),
    );
    // (1, 1) is (h, h) at 45 degrees: a corner.
    near(sample_regular_polygon(DVec2::ONE, 4, 0.0), DVec2::new(h, h));
    // (0, 0.5) is (-1, 0) (the concentric mapping's negative radius): the left edge.
    near(
        sample_regular_polygon(DVec2::new(0.0, 0.5), 4, 0.0),
        DVec2::new(-h, 0.0),
    );
    // (0.75, 0.5) is (0.5, 0): halfway out to the right edge's middle.
    near(
        sample_regular_polygon(DVec2::new(0.75, 0.5), 4, 0.0),
        DVec2::new(0.5 * h, 0.0),
    );
    // Six blades turned by 30 degrees: corners at 0, 60, ... 300 degrees, so angle 0
    // is a corner, (1, 0).
    near(
        sample_regular_polygon(DVec2::new(1.0, 0.5), 6, 30f64.to_radians()),
        DVec2::new(1.0, 0.0),
    );
    // Five blades, no rotation: corners at 36, 108, 180, 252, 324 degrees. The disk's
    // (0, 1), angle 90, is a quarter of the way (x = 90 / 72 + 1/2 = 1.75, t = 0.75)
    // along the edge from the corner at 36 degrees to the one at 108.
    near(
        sample_regular_polygon(DVec2::new(0.5, 1.0), 5, 0.0),
        0.25 * degrees(36.0) + 0.75 * degrees(108.0),
    );
    // The same turned by 90 degrees: a corner at 126, the edge's middle at 90, so the
    // disk's (0, 1) lands there, cos 36 from the centre.
    near(
        sample_regular_polygon(DVec2::new(0.5, 1.0), 5, PI / 2.0),
        DVec2::new(0.0, (PI / 5.0).cos()),
    );
    // The disk's (0, -1), angle -90 = 270: x = 270 / 72 + 1/2 = 4.25 (mod 5), the edge
    // from 252 to 324 degrees, a quarter of the way.
    near(
        sample_regular_polygon(DVec2::new(0.5, 0.0), 5, 0.0),
        0.75 * degrees(252.0) + 0.25 * degrees(324.0),
    );
}

/// The largest of `point . n_k` over the polygon's edge normals `n_k` (at the angles
/// `rotation + 2 pi k / N`): `cos(pi / N)` on an edge, less inside.
fn edge_reach(point: DVec2, blades: u32, rotation: f64) -> f64 {
    reach(point, &edge_normals(blades, rotation))
}

/// The polygon's outward edge normals.
fn edge_normals(blades: u32, rotation: f64) -> Vec<DVec2> {
    (0..blades)
        .map(|k| {
            let (sin, cos) = (rotation + 2.0 * PI * f64::from(k) / f64::from(blades)).sin_cos();
            DVec2::new(cos, sin)
        })
        .collect()
}

fn reach(point: DVec2, normals: &[DVec2]) -> f64 {
    normals
        .iter()
        .map(|n| point.dot(*n))
        .fold(f64::NEG_INFINITY, f64::max)
}

#[test]
fn the_squares_edges_land_exactly_on_the_polygons_edges() {
    for (blades, rotation) in [(3, 0.0), (5, 0.7), (6, -2.0), (8, PI), (64, 0.1)] {
        let apothem = (PI / f64::from(blades)).cos();
        for i in 0..=400 {
            let s = f64::from(i) / 400.0;
            for p in [
                DVec2::new(s, 0.0),
                DVec2::new(s, 1.0),
                DVec2::new(0.0, s),
                DVec2::new(1.0, s),
            ] {
                let q = sample_regular_polygon(p, blades, rotation);
                let reach = edge_reach(q, blades, rotation);
                assert!(
                    (reach - apothem).abs() < 1e-15,
                    "{p} -> {q}: {reach} from the edge at {apothem}"
                );
            }
            // Inside the square: strictly inside the polygon.
            let inner = DVec2::new(0.01 + 0.98 * s, 0.3);
            let q = sample_regular_polygon(inner, blades, rotation);
            assert!(edge_reach(q, blades, rotation) < apothem, "{inner} -> {q}");
        }
    }
}

/// SplitMix64: a fixed sequence of numbers in `[0, 1)`, so the statistical test below
/// gives the same verdict on every run.
struct SplitMix(u64);

impl SplitMix {
    fn next(&mut self) -> f64 {
        self.0 = self.0.wrapping_add(0x9E37_79B9_7F4A_7C15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
        z ^= z >> 31;
        // The top 53 bits as a fraction.
        #[allow(clippy::cast_precision_loss)]
        let x = (z >> 11) as f64 / (1u64 << 53) as f64;
        x
    }
}

#[test]
fn the_density_is_uniform_over_the_polygon() {
    // A 48 x 48 grid over [-1, 1]^2; the cells wholly inside the polygon (all four
    // corners inside: it is convex) must each receive the same share of the samples
    // that land in them, and those cells their share of the polygon's area.
    const GRID: usize = 48;
    const SAMPLES: usize = 400_000;
    for (blades, rotation, seed) in [(5, 0.3, 1), (6, 0.0, 2), (3, -1.0, 3), (9, 2.5, 4)] {
        let apothem = (PI / f64::from(blades)).cos();
        let normals = edge_normals(blades, rotation);
        let cell = 2.0 / GRID as f64;
        let corner = |i: usize| -1.0 + cell * i as f64;
        let inside = |x: usize, y: usize| {
            [(0, 0), (1, 0), (0, 1), (1, 1)].iter().all(|&(dx, dy)| {
                reach(DVec2::new(corner(x + dx), corner(y + dy)), &normals) <= apothem
            })
        };
        let mut counts = vec![0u32; GRID * GRID];
        let mut rng = SplitMix(seed);
        for _ in 0..SAMPLES {
            let p = DVec2::new(rng.next(), rng.next());
            let q = sample_regular_polygon(p, blades, rotation);
            assert!(reach(q, &normals) <= apothem + 1e-15, "{q} outside");
            #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
            let (x, y) = (
                (((q.x + 1.0) / cell) as usize).min(GRID - 1),
                (((q.y + 1.0) / cell) as usize).min(GRID - 1),
            );
            counts[y * GRID + x] += 1;
        }
        let cells: Vec<f64> = (0..GRID * GRID)
            .filter(|&i| inside(i % GRID, i / GRID))
            .map(|i| f64::from(counts[i]))
            .collect();
        let total: f64 = cells.iter().sum();
        let k = cells.len() as f64;
        let expected = total / k;
        let chi_square: f64 = cells
            .iter()
            .map(|o| (o - expected).powi(2) / expected)
            .sum();
        // chi^2 with k - 1 degrees of freedom: mean k - 1, deviation sqrt(2 (k - 1)).
        let dof = k - 1.0;
        assert!(
            chi_square < dof + 6.0 * (2.0 * dof).sqrt(),
            "{blades} blades: chi^2 = {chi_square} over {dof} degrees of freedom"
        );
        // The share of the samples in those cells is their share of the area,
        // (N / 2) sin(2 pi / N) for the polygon.
        let area = f64::from(blades) / 2.0 * (2.0 * PI / f64::from(blades)).sin();
        let share = k * cell * cell / area;
        let seen = total / SAMPLES as f64;
        assert!(
            (seen - share).abs() < 0.005,
            "{blades} blades: {seen} of the samples in {share} of the area"
        );
    }
}

#[test]
fn an_iris_wraps_its_rotation_and_rejects_bad_blades() {
    let rotation = |degrees: f64| {
        Iris::from_degrees(6, degrees)
            .unwrap()
            .rotation
            .to_degrees()
    };
    let close = |a: f64, b: f64| assert!((a - b).abs() < 1e-12, "{a} != {b}");
    close(rotation(-30.0), -30.0);
    close(rotation(330.0), -30.0);
    close(rotation(400.0), 40.0);
    close(rotation(-400.0), -40.0);
    close(rotation(180.0), -180.0);
    close(rotation(-180.0), -180.0);
    // Whole turns in degrees are exact: 390 is the same number as 30.
    assert_eq!(
        Iris::from_degrees(6, 390.0).unwrap(),
        Iris::from_degrees(6, 30.0).unwrap()
    );
    close(Iris::new(5, 3.5 * PI).unwrap().rotation, -0.5 * PI);
    close(Iris::new(5, -PI).unwrap().rotation, -PI);
    close(Iris::new(5, PI).unwrap().rotation, -PI);
    assert_eq!(Iris::new(0, 1.0).unwrap().blades, 0);
    assert!(Iris::new(0, 0.0).unwrap().is_round());
    assert!(!Iris::new(3, 0.0).unwrap().is_round());
    assert_eq!(Iris::default(), Iris::ROUND);

    let out_of_range = |blades: u32| {
        assert_eq!(
            Iris::new(blades, 0.0),
            Err(CameraError::OutOfRange {
                name: "blades",
                expected: "0 (a round lens) or 3 to 64 (a polygon)",
                value: f64::from(blades),
            })
        );
    };
    out_of_range(1);
    out_of_range(2);
    out_of_range(65);
    assert!(Iris::new(3, 0.0).is_ok());
    assert!(Iris::new(64, 0.0).is_ok());
    assert_eq!(
        Iris::new(1, 0.0).unwrap_err().to_string(),
        "blades must be 0 (a round lens) or 3 to 64 (a polygon), found 1"
    );
    assert!(matches!(
        Iris::from_degrees(5, f64::NAN),
        Err(CameraError::NotFinite {
            name: "blade_rotation",
            ..
        })
    ));
    assert!(matches!(
        Iris::new(5, f64::INFINITY),
        Err(CameraError::NotFinite {
            name: "blade_rotation",
            ..
        })
    ));
    // A rotation outside [-pi, pi] written into the struct is refused where the camera
    // is built, so an exporter can hand it on as it is.
    for rotation in [PI + 1e-9, -PI - 1e-9] {
        assert!(matches!(
            Iris {
                blades: 5,
                rotation
            }
            .validate(),
            Err(CameraError::OutOfRange {
                name: "blade_rotation",
                ..
            })
        ));
    }
    for rotation in [PI, -PI, 0.0] {
        assert_eq!(
            Iris {
                blades: 5,
                rotation
            }
            .validate(),
            Ok(())
        );
    }
    assert!(matches!(
        Iris {
            blades: 5,
            rotation: f64::NAN
        }
        .validate(),
        Err(CameraError::NotFinite { .. })
    ));
}

#[test]
fn an_iris_knows_its_corners_and_what_lies_on_it() {
    let hexagon = Iris::new(6, 0.0).unwrap();
    let corners = hexagon.corners();
    assert_eq!(corners.len(), 6);
    for (k, corner) in corners.iter().enumerate() {
        near(*corner, degrees(30.0 + 60.0 * k as f64));
    }
    assert!(Iris::ROUND.corners().is_empty());
    let apothem = (PI / 6.0).cos();
    // Corners and edges are on it, beyond them is not.
    assert!(hexagon.contains(corners[0]));
    assert!(hexagon.contains(DVec2::new(apothem, 0.0)));
    assert!(!hexagon.contains(DVec2::new(apothem + 1e-9, 0.0)));
    assert!(!hexagon.contains(DVec2::new(1.0, 0.0)));
    assert!(hexagon.contains(DVec2::ZERO));
    // Turned by 30 degrees, (1, 0) is a corner.
    let turned = Iris::from_degrees(6, 30.0).unwrap();
    assert!(turned.contains(DVec2::new(1.0, 0.0)));
    assert!(!turned.contains(DVec2::new(0.0, 1.0)));
    // A turned pentagon: just beyond the middle of the edge facing 0.4 rad is outside,
    // just inside it is in; the corners beside it are on it.
    let pentagon = Iris::new(5, 0.4).unwrap();
    let apothem = (PI / 5.0).cos();
    let facing = DVec2::new(0.4f64.cos(), 0.4f64.sin());
    assert!(!pentagon.contains((apothem + 1e-6) * facing));
    assert!(pentagon.contains((apothem - 1e-6) * facing));
    for corner in pentagon.corners() {
        assert!(pentagon.contains(corner));
        assert!(!pentagon.contains(1.001 * corner));
    }
    // The unit disk, its edge included.
    assert!(Iris::ROUND.contains(DVec2::new(0.6, 0.8)));
    assert!(Iris::ROUND.contains(DVec2::new(-1.0, 0.0)));
    assert!(!Iris::ROUND.contains(DVec2::new(0.6, 0.81)));
    // The sampler's points are all on the aperture; a round one samples the disk.
    let pentagon = Iris::new(5, 0.4).unwrap();
    for i in 0..=20 {
        for j in 0..=20 {
            let p = DVec2::new(f64::from(i) / 20.0, f64::from(j) / 20.0);
            assert!(pentagon.contains(pentagon.sample(p)));
            assert_eq!(
                Iris::ROUND.sample(p),
                viewray_camera::sample_unit_disk_concentric(p)
            );
            assert_eq!(
                pentagon.sample(p),
                sample_regular_polygon(p, 5, pentagon.rotation)
            );
        }
    }
}

fn thin_lens(iris: Iris) -> Camera {
    let pinhole = Perspective {
        distance: 1.0,
        viewport: DVec2::new(2.0, 2.0),
        shift: DVec2::ZERO,
    };
    let projection = Projection::ThinLens(ThinLens {
        iris,
        ..ThinLens::new(pinhole, 0.5, 4.0)
    });
    Camera::new(Frame::CANONICAL, projection, 2, 2).unwrap()
}

#[test]
fn a_thin_lens_with_blades_starts_its_rays_on_the_polygon() {
    let h = FRAC_1_SQRT_2;
    let square = thin_lens(Iris::new(4, 0.0).unwrap());
    assert_eq!(square.projection().iris(), Some(Iris::new(4, 0.0).unwrap()));
    let sample = |p_lens: DVec2| CameraSample {
        p_film: DVec2::splat(0.5),
        p_lens,
    };
    // The lens sample (1, 0.5) is the middle of the square's right edge, r cos 45 to
    // the right of e; the ray still reaches the focus point at t = 1.
    let ray = square
        .generate_ray(0, 1, sample(DVec2::new(1.0, 0.5)))
        .unwrap();
    assert!(ray.origin.abs_diff_eq(DVec3::new(0.5 * h, 0.0, 0.0), 1e-12));
    // Pixel (0, 1)'s centre is (u, v) = (0.5, 0.5): its focus point is 4 (0.5, 0.5, -1).
    assert!(ray.at(1.0).abs_diff_eq(DVec3::new(2.0, 2.0, -4.0), 1e-12));
    // One sample per pixel, the square's centre: the lens centre, whatever the blades.
    let centre = square.generate_ray(0, 1, CameraSample::CENTER).unwrap();
    assert_eq!(centre.origin, DVec3::ZERO);
    // A round lens's rays are those of today: the concentric mapping, bit for bit.
    let round = thin_lens(Iris::ROUND);
    let p = DVec2::new(0.9, 0.2);
    let disk = viewray_camera::sample_unit_disk_concentric(p);
    assert_eq!(
        round.generate_ray(1, 0, sample(p)).unwrap().origin,
        (0.5 * disk).extend(0.0)
    );
    // Bad blades are refused where the camera is built.
    let pinhole = Perspective::CANONICAL;
    let bad = Projection::ThinLens(ThinLens {
        iris: Iris {
            blades: 2,
            rotation: 0.0,
        },
        ..ThinLens::new(pinhole, 0.5, 4.0)
    });
    assert!(matches!(
        Camera::new(Frame::CANONICAL, bad, 2, 2),
        Err(CameraError::OutOfRange { name: "blades", .. })
    ));
    // An orthographic lens is round.
    let ortho = Projection::Orthographic(viewray_camera::Orthographic {
        viewport: DVec2::ONE,
        lens: Some(viewray_camera::Lens {
            aperture: 0.1,
            focus: 2.0,
        }),
    });
    assert_eq!(ortho.iris(), Some(Iris::ROUND));
    assert_eq!(Projection::Perspective(pinhole).iris(), None);
}

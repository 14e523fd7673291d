//! The golden checker's own tests: what must pass (the same pixels, last-bit noise) and
//! what must fail (a visible change, a moved edge, another size, a blank golden).

use crate::scene;

use image::RgbaImage;
use scene::{Mistake, Pattern, Scene};
use viewray_compare::{Failure, LoadError, Thresholds, compare, load_png};

const W: u32 = 128;
const H: u32 = 96;

fn golden() -> RgbaImage {
    Scene::default().render(W, H, Mistake::NONE, Pattern::Grid(4))
}

/// Compares `actual` with the golden and checks the verdict; returns the failures.
#[track_caller]
fn check(name: &str, actual: &RgbaImage, should_pass: bool) -> Vec<Failure> {
    let comparison = compare(&golden(), actual, &Thresholds::GOLDEN);
    assert_eq!(
        comparison.passed(),
        should_pass,
        "{name}: {} {:?}",
        comparison.reasons(),
        comparison.metrics
    );
    comparison.failures
}

/// `image` with `change` applied to channel `c` of every `every`-th pixel.
fn perturbed(image: &RgbaImage, every: usize, change: impl Fn(usize, u8) -> u8) -> RgbaImage {
    let mut out = image.clone();
    for (i, pixel) in out.pixels_mut().enumerate() {
        if i % every == 0 {
            let c = i % 3;
            pixel[c] = change(i, pixel[c]);
        }
    }
    out
}

#[test]
fn the_same_pixels_and_last_bit_noise_pass() {
    let golden = golden();
    check("identical", &golden, true);
    check(
        "+1 in one channel of every 7th pixel",
        &perturbed(&golden, 7, |_, v| v.saturating_add(1)),
        true,
    );
    check(
        "+-1 in one channel of every pixel",
        &perturbed(&golden, 1, |i, v| {
            if i % 2 == 0 {
                v.saturating_add(1)
            } else {
                v.saturating_sub(1)
            }
        }),
        true,
    );
    // The triangle moved by a hundredth of a pixel: a few of the 16 samples land on the
    // other side of its edges, as when another machine's last bits differ.
    let grazed = Scene {
        triangle_offset: (0.01 * 4.0 / f64::from(W), 0.0),
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Grid(4));
    let comparison = compare(&golden, &grazed, &Thresholds::GOLDEN);
    let metrics = comparison.metrics.unwrap();
    assert!(metrics.max_channel_difference > 2, "{metrics:?}");
    assert!(comparison.passed(), "{}", comparison.reasons());
}

#[test]
fn a_lossless_re_encoding_passes_because_pixels_are_compared_not_bytes() {
    use image::ImageEncoder as _;
    use image::codecs::png::{CompressionType, FilterType, PngEncoder};
    let golden = golden();
    let dir = tempfile::tempdir().unwrap();
    let mut paths = Vec::new();
    for (name, compression, filter) in [
        ("fast.png", CompressionType::Fast, FilterType::NoFilter),
        ("best.png", CompressionType::Best, FilterType::Paeth),
    ] {
        let mut bytes = Vec::new();
        PngEncoder::new_with_quality(&mut bytes, compression, filter)
            .write_image(golden.as_raw(), W, H, image::ExtendedColorType::Rgba8)
            .unwrap();
        let path = dir.path().join(name);
        std::fs::write(&path, bytes).unwrap();
        paths.push(path);
    }
    let fast = std::fs::read(&paths[0]).unwrap();
    let best = std::fs::read(&paths[1]).unwrap();
    assert_ne!(fast, best, "the two files should differ byte for byte");
    let comparison = compare(
        &load_png(&paths[0]).unwrap(),
        &load_png(&paths[1]).unwrap(),
        &Thresholds::GOLDEN,
    );
    assert!(comparison.passed(), "{}", comparison.reasons());
    assert_eq!(comparison.metrics.unwrap().max_channel_difference, 0);
}

#[test]
fn a_visible_colour_change_fails() {
    let recoloured = Scene {
        red: [0.7, 0.12, 0.1],
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Grid(4));
    let failures = check("the disc's red 12% darker", &recoloured, false);
    assert!(
        failures
            .iter()
            .any(|f| matches!(f, Failure::PeakFlip { .. })),
        "{failures:?}"
    );
}

#[test]
fn an_edge_moved_by_one_pixel_fails_both_gates() {
    let moved = Scene {
        triangle_offset: (4.0 / f64::from(W), 0.0),
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Grid(4));
    let failures = check("triangle moved 1 px right", &moved, false);
    assert!(
        failures
            .iter()
            .any(|f| matches!(f, Failure::TooManyBadPixels { .. })),
        "{failures:?}"
    );
    assert!(
        failures
            .iter()
            .any(|f| matches!(f, Failure::PeakFlip { .. })),
        "{failures:?}"
    );
}

#[test]
fn a_different_size_fails_without_metrics() {
    let larger = Scene::default().render(W + 2, H, Mistake::NONE, Pattern::Grid(4));
    let comparison = compare(&golden(), &larger, &Thresholds::GOLDEN);
    assert_eq!(
        comparison.failures,
        [Failure::SizeMismatch {
            expected: (W, H),
            actual: (W + 2, H)
        }]
    );
    assert!(comparison.metrics.is_none() && comparison.heatmap().is_none());
    assert_eq!(
        comparison.reasons(),
        "sizes differ: expected 128x96, actual 130x96"
    );
}

#[test]
fn a_uniform_golden_fails_even_against_itself() {
    let blank = RgbaImage::from_pixel(W, H, image::Rgba([20, 20, 30, 255]));
    let comparison = compare(&blank, &blank, &Thresholds::GOLDEN);
    assert_eq!(comparison.failures, [Failure::UniformExpected]);
    // One odd pixel does not make a golden meaningful either.
    let mut almost = blank.clone();
    almost.put_pixel(3, 3, image::Rgba([200, 0, 0, 255]));
    assert_eq!(
        compare(&almost, &almost, &Thresholds::GOLDEN).failures,
        [Failure::UniformExpected]
    );
}

#[test]
fn the_heatmap_is_black_where_nothing_differs_and_bright_where_the_edge_moved() {
    let moved = Scene {
        triangle_offset: (4.0 / f64::from(W), 0.0),
        ..Scene::default()
    }
    .render(W, H, Mistake::NONE, Pattern::Grid(4));
    let heatmap = compare(&golden(), &moved, &Thresholds::GOLDEN)
        .heatmap()
        .unwrap();
    assert_eq!(heatmap.dimensions(), (W, H));
    let brightness = |x: u32, y: u32| {
        heatmap
            .get_pixel(x, y)
            .0
            .iter()
            .map(|&c| u32::from(c))
            .sum::<u32>()
    };
    // Top-left corner: background in both. The triangle's left edge at v = 0.4 runs near
    // column 64 + 0.55 * 32 = 81.6 at row 0.5 * 96 - 0.4 * 32 = 35.2.
    assert!(brightness(2, 2) < 30, "{}", brightness(2, 2));
    let edge = (75..90).map(|x| brightness(x, 35)).max().unwrap();
    assert!(edge > 300, "{edge}");
}

#[test]
fn unreadable_files_are_errors_that_name_the_file() {
    let dir = tempfile::tempdir().unwrap();
    let text = dir.path().join("notes.png");
    std::fs::write(&text, "not an image").unwrap();
    let truncated = dir.path().join("truncated.png");
    let mut bytes = Vec::new();
    golden()
        .write_to(
            &mut std::io::Cursor::new(&mut bytes),
            image::ImageFormat::Png,
        )
        .unwrap();
    std::fs::write(&truncated, &bytes[..bytes.len() / 2]).unwrap();
    let missing = dir.path().join("missing.png");

    let error = load_png(&text).unwrap_err();
    assert!(matches!(error, LoadError::NotPng { .. }), "{error:?}");
    assert!(
        error.to_string().contains("notes.png: not a PNG file"),
        "{error}"
    );
    let error = load_png(&truncated).unwrap_err();
    assert!(matches!(error, LoadError::Decode { .. }), "{error:?}");
    assert!(
        error
            .to_string()
            .contains("truncated.png: the PNG does not decode"),
        "{error}"
    );
    let error = load_png(&missing).unwrap_err();
    assert!(matches!(error, LoadError::Unreadable { .. }), "{error:?}");
    assert!(
        error
            .to_string()
            .contains("missing.png: cannot read the file"),
        "{error}"
    );
    assert!(load_png(dir.path()).is_err());
}

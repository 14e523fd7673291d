//! The image limits: each bound exactly at its edge, which check wins when several fail,
//! and the sentence each error says (the command line, scene files and the live
//! playground all print these).

use viewray_camera::ImageLimitError::{Empty, Samples, SamplesText, SideTooLarge, TooManyPixels};
use viewray_camera::{
    Camera, CameraError, ImageLimitError, ImageLimits, MAX_IMAGE_PIXELS, MAX_IMAGE_SIDE,
    MAX_SAMPLES,
};

/// Tight limits to test the edges with small numbers: 10 a side, 50 pixels, 8 samples.
const SMALL: ImageLimits = ImageLimits {
    max_side: 10,
    max_pixels: 50,
    max_samples: 8,
};

#[track_caller]
fn check_size(
    limits: ImageLimits,
    (width, height): (u64, u64),
    expected: Result<(u32, u32), ImageLimitError>,
) {
    assert_eq!(
        limits.check_size(width, height),
        expected,
        "{width} x {height}"
    );
}

#[test]
fn viewray_limits_are_16384_a_side_2_to_the_28_pixels_and_65536_samples() {
    assert_eq!(MAX_IMAGE_SIDE, 1 << 14);
    assert_eq!(
        MAX_IMAGE_PIXELS,
        u64::from(MAX_IMAGE_SIDE) * u64::from(MAX_IMAGE_SIDE)
    );
    assert_eq!(MAX_SAMPLES, 1 << 16);
    assert_eq!(
        ImageLimits::default(),
        ImageLimits {
            max_side: MAX_IMAGE_SIDE,
            max_pixels: MAX_IMAGE_PIXELS,
            max_samples: MAX_SAMPLES,
        }
    );
    assert_eq!(ImageLimits::VIEWRAY, ImageLimits::default());
}

#[test]
fn sizes_are_checked_at_each_edge() {
    check_size(SMALL, (1, 1), Ok((1, 1)));
    check_size(SMALL, (10, 5), Ok((10, 5)));
    check_size(SMALL, (5, 10), Ok((5, 10)));
    // A zero side, either one: empty, before any other check.
    check_size(
        SMALL,
        (0, 5),
        Err(Empty {
            width: 0,
            height: 5,
        }),
    );
    check_size(
        SMALL,
        (5, 0),
        Err(Empty {
            width: 5,
            height: 0,
        }),
    );
    check_size(
        SMALL,
        (0, 99),
        Err(Empty {
            width: 0,
            height: 99,
        }),
    );
    // One side over, either one: the side, before the pixels.
    let side = |width, height| {
        Err(SideTooLarge {
            width,
            height,
            max_side: 10,
        })
    };
    check_size(SMALL, (11, 1), side(11, 1));
    check_size(SMALL, (1, 11), side(1, 11));
    check_size(SMALL, (11, 11), side(11, 11));
    check_size(SMALL, (u64::MAX, u64::MAX), side(u64::MAX, u64::MAX));
    // Both sides within, too many pixels: 51 is one over, 50 is exactly the limit.
    check_size(
        SMALL,
        (10, 6),
        Err(TooManyPixels {
            width: 10,
            height: 6,
            max_pixels: 50,
        }),
    );
    check_size(
        SMALL,
        (6, 9),
        Err(TooManyPixels {
            width: 6,
            height: 9,
            max_pixels: 50,
        }),
    );
    check_size(SMALL, (10, 5), Ok((10, 5)));
    // viewray's own: the largest image is exactly 16384 x 16384.
    let viewray = ImageLimits::VIEWRAY;
    check_size(viewray, (16_384, 16_384), Ok((16_384, 16_384)));
    check_size(
        viewray,
        (16_385, 1),
        Err(SideTooLarge {
            width: 16_385,
            height: 1,
            max_side: MAX_IMAGE_SIDE,
        }),
    );
}

#[test]
fn samples_are_checked_as_numbers_and_as_text() {
    assert_eq!(SMALL.check_samples(1), Ok(1));
    assert_eq!(SMALL.check_samples(8), Ok(8));
    for samples in [0, 9, u64::from(u32::MAX) + 1, u64::MAX] {
        assert_eq!(
            SMALL.check_samples(samples),
            Err(Samples {
                samples,
                max_samples: 8
            }),
            "{samples}"
        );
    }
    assert_eq!(SMALL.parse_samples("1"), Ok(1));
    assert_eq!(SMALL.parse_samples(" 8 "), Ok(8));
    for text in [
        "0",
        "9",
        "-1",
        "2.5",
        "x",
        "",
        "4294967297",
        "99999999999999999999999",
    ] {
        assert_eq!(
            SMALL.parse_samples(text),
            Err(SamplesText { max_samples: 8 }),
            "{text:?}"
        );
    }
    assert_eq!(ImageLimits::VIEWRAY.parse_samples("65536"), Ok(65_536));
    assert!(ImageLimits::VIEWRAY.parse_samples("65537").is_err());
}

#[test]
fn tighter_limits_stay_within_viewrays() {
    let tight = ImageLimits {
        max_side: 4096,
        max_pixels: 1 << 22,
        max_samples: 1024,
    };
    assert_eq!(tight.within_viewray(), tight);
    let loose = ImageLimits {
        max_side: u32::MAX,
        max_pixels: u64::MAX,
        max_samples: u32::MAX,
    };
    assert_eq!(loose.within_viewray(), ImageLimits::VIEWRAY);
    // Each bound on its own.
    let mixed = ImageLimits {
        max_side: 100,
        max_pixels: u64::MAX,
        max_samples: 7,
    };
    assert_eq!(
        mixed.within_viewray(),
        ImageLimits {
            max_side: 100,
            max_pixels: MAX_IMAGE_PIXELS,
            max_samples: 7
        }
    );
    let mixed = ImageLimits {
        max_side: u32::MAX,
        max_pixels: 9,
        max_samples: u32::MAX,
    };
    assert_eq!(
        mixed.within_viewray(),
        ImageLimits {
            max_side: MAX_IMAGE_SIDE,
            max_pixels: 9,
            max_samples: MAX_SAMPLES
        }
    );
}

#[test]
fn each_error_says_what_was_found_and_the_limit() {
    let said = |error: ImageLimitError| error.to_string();
    assert_eq!(
        said(Empty {
            width: 0,
            height: 48
        }),
        "the image must be at least 1 x 1 pixels, found 0 x 48"
    );
    assert_eq!(
        said(SideTooLarge {
            width: 100_000,
            height: 10,
            max_side: 16_384
        }),
        "100000 x 10 is too large: each side can be at most 16384 pixels"
    );
    // viewray's own pixel limit is named with its power of two; a tighter one is not.
    assert_eq!(
        said(TooManyPixels {
            width: 16_384,
            height: 16_385,
            max_pixels: MAX_IMAGE_PIXELS
        }),
        "16384 x 16385 is too large: at most 268435456 pixels (2^28)"
    );
    assert_eq!(
        said(TooManyPixels {
            width: 4096,
            height: 4096,
            max_pixels: 1 << 22
        }),
        "4096 x 4096 is too large: at most 4194304 pixels"
    );
    assert_eq!(
        said(Samples {
            samples: 0,
            max_samples: 65_536
        }),
        "samples must be between 1 and 65536, found 0"
    );
    assert_eq!(
        said(SamplesText { max_samples: 1024 }),
        "expected a whole number of samples from 1 to 1024"
    );
}

#[test]
fn a_camera_needs_a_pixel_and_says_so_in_the_same_words() {
    let error = Camera::canonical(0, 3).unwrap_err();
    assert_eq!(
        error,
        CameraError::Image(Empty {
            width: 0,
            height: 3
        })
    );
    assert_eq!(
        error.to_string(),
        "the image must be at least 1 x 1 pixels, found 0 x 3"
    );
    // A camera is not bound by the render limits: figures and tests build any size.
    assert!(Camera::canonical(MAX_IMAGE_SIDE + 1, 1).is_ok());
}

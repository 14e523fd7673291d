//! The values the command line takes, parsed and checked: numbers joined by commas
//! (points, vectors, pixels, offsets), image sizes and counts within viewray's limits,
//! and `-` for a standard stream. Each parser's error is the sentence clap prints after
//! `invalid value '..' for '--option'`.

use std::path::Path;

use glam::{DVec2, DVec3};
use viewray_camera::ImageLimits;
use viewray_scene::{MAX_FPS, MAX_FRAMES};

/// The SCENE argument that means standard input.
pub(crate) const STDIN: &str = "-";

/// Whether a SCENE or OUT argument is `-`, standard input or output.
pub(crate) fn is_standard_stream(path: &Path) -> bool {
    path.as_os_str() == STDIN
}

/// Parses `text` as comma-separated finite numbers, exactly `N` of them.
fn parse_numbers<const N: usize>(text: &str, example: &str) -> Result<[f64; N], String> {
    let parts: Vec<&str> = text.split(',').map(str::trim).collect();
    let wrong = || format!("expected {N} numbers separated by commas, like {example}");
    if parts.len() != N {
        return Err(wrong());
    }
    let mut numbers = [0.0; N];
    for (number, part) in numbers.iter_mut().zip(parts) {
        *number = part.parse::<f64>().map_err(|_| wrong())?;
        if !number.is_finite() {
            return Err(format!("`{part}` is not a finite number"));
        }
    }
    Ok(numbers)
}

/// Parses a point or vector `X,Y,Z`.
pub(crate) fn parse_vec3(text: &str) -> Result<DVec3, String> {
    parse_numbers::<3>(text, "0,1.5,-2").map(DVec3::from)
}

/// Parses an offset inside a pixel: two numbers in `[0, 1)`.
pub(crate) fn parse_offset(text: &str) -> Result<DVec2, String> {
    let offset = DVec2::from(parse_numbers::<2>(text, "0.5,0.5")?);
    if !(0.0..1.0).contains(&offset.x) || !(0.0..1.0).contains(&offset.y) {
        return Err(format!(
            "{},{} lies outside the pixel: each offset must be in [0, 1)",
            offset.x, offset.y
        ));
    }
    Ok(offset)
}

/// Parses a lens point: two numbers (whether it lies on the aperture depends on the
/// scene's camera, checked once it is loaded).
pub(crate) fn parse_lens_point(text: &str) -> Result<DVec2, String> {
    parse_numbers::<2>(text, "0.5,-0.5").map(DVec2::from)
}

/// Parses a pixel `ROW,COL` (or `I,J`): any two whole numbers; the command checks them
/// against the image.
pub(crate) fn parse_pixel(text: &str) -> Result<(i64, i64), String> {
    let wrong = || "expected a pixel as two whole numbers ROW,COL, like 2,3".to_owned();
    let (row, col) = text.split_once(',').ok_or_else(wrong)?;
    let row = row.trim().parse().map_err(|_| wrong())?;
    let col = col.trim().parse().map_err(|_| wrong())?;
    Ok((row, col))
}

/// Parses an image size `WIDTHxHEIGHT` within viewray's image limits.
pub(crate) fn parse_size(text: &str) -> Result<(u32, u32), String> {
    let wrong = || "expected the size as WIDTHxHEIGHT in pixels, like 640x480".to_owned();
    let (width, height) = text.split_once(['x', 'X']).ok_or_else(wrong)?;
    let width: u64 = width.trim().parse().map_err(|_| wrong())?;
    let height: u64 = height.trim().parse().map_err(|_| wrong())?;
    ImageLimits::VIEWRAY
        .check_size(width, height)
        .map_err(|error| error.to_string())
}

/// Parses a number of samples per pixel, 1 to [`viewray_camera::MAX_SAMPLES`].
pub(crate) fn parse_samples(text: &str) -> Result<u32, String> {
    ImageLimits::VIEWRAY
        .parse_samples(text)
        .map_err(|error| error.to_string())
}

/// Parses a number of frames, 1 to [`MAX_FRAMES`].
pub(crate) fn parse_frames(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of frames from 1 to {MAX_FRAMES}");
    let frames: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(frames) {
        Ok(frames) if (1..=MAX_FRAMES).contains(&frames) => Ok(frames),
        _ => Err(wrong()),
    }
}

/// Parses a number of frames per second, 1 to [`MAX_FPS`].
pub(crate) fn parse_fps(text: &str) -> Result<u32, String> {
    let wrong = || format!("expected a whole number of frames per second from 1 to {MAX_FPS}");
    let fps: u64 = text.trim().parse().map_err(|_| wrong())?;
    match u32::try_from(fps) {
        Ok(fps) if (1..=MAX_FPS).contains(&fps) => Ok(fps),
        _ => Err(wrong()),
    }
}

/// The most render threads `--threads` accepts.
const MAX_THREADS: usize = 1024;

/// Parses a number of threads, 1 to [`MAX_THREADS`].
pub(crate) fn parse_threads(text: &str) -> Result<usize, String> {
    let wrong = || format!("expected a whole number of threads from 1 to {MAX_THREADS}");
    let threads: usize = text.trim().parse().map_err(|_| wrong())?;
    if (1..=MAX_THREADS).contains(&threads) {
        Ok(threads)
    } else {
        Err(wrong())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn sizes_samples_threads_and_offsets_are_checked() {
        assert_eq!(parse_size("640x480"), Ok((640, 480)));
        assert_eq!(parse_size("16384X16384"), Ok((16384, 16384)));
        for bad in [
            "0x10",
            "10x0",
            "100000x10",
            "16384x16385",
            "640",
            "640x",
            "axb",
            "-1x5",
            "99999999999999999999x1",
        ] {
            assert!(parse_size(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_samples("16"), Ok(16));
        for bad in ["0", "-1", "65537", "99999999999", "x"] {
            assert!(parse_samples(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_frames("48"), Ok(48));
        for bad in ["0", "10001", "-3", "2.5", "x"] {
            assert!(parse_frames(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_fps("24"), Ok(24));
        for bad in ["0", "101", "24.0"] {
            assert!(parse_fps(bad).is_err(), "{bad}");
        }
        assert_eq!(parse_threads("2"), Ok(2));
        assert!(parse_threads("0").is_err());
        assert_eq!(parse_offset("0,0.999"), Ok(DVec2::new(0.0, 0.999)));
        for bad in ["1,0", "0,-0.1", "0.5", "nan,0"] {
            assert!(parse_offset(bad).is_err(), "{bad}");
        }
    }

    #[test]
    fn vectors_parse_with_negative_numbers_and_spaces() {
        assert_eq!(parse_vec3("-1, 0,5.5"), Ok(DVec3::new(-1.0, 0.0, 5.5)));
        assert!(parse_vec3("1,2").is_err());
        assert!(parse_vec3("1,2,x").is_err());
        assert!(parse_vec3("1,2,inf").is_err());
        assert_eq!(parse_pixel("2, 3"), Ok((2, 3)));
        assert_eq!(
            parse_pixel("-9223372036854775808,0"),
            Ok((i64::MIN, 0)),
            "any whole number parses; the command checks it against the image"
        );
        assert!(parse_pixel("2.5,3").is_err());
        assert!(parse_pixel("9223372036854775808,0").is_err());
    }
}

//! The student's pictures: a lit scene where the camera says, its shading options, its
//! mistakes, and its files, which read back at the right size.

use super::v;
use crate::support::student::{
    Aim, CameraSpec, Format, Gamma, LightChange, Mistake, Picture, Projection, RenderOptions,
    Scene, Vec3, project, render,
};

const SIZE: (u32, u32) = (64, 48);

/// Looking at the example scene's sphere and box from the front, a little above.
fn camera() -> CameraSpec {
    CameraSpec {
        eye: v(0.3, 2.0, 6.0),
        aim: Aim::LookAt(v(0.3, 0.5, 0.0)),
        up: Vec3::Y,
        projection: Projection::Perspective {
            d: 1.0,
            viewport: (0.8, 0.6),
            shift: (0.0, 0.0),
        },
    }
}

/// The 8-bit colour where `point` appears.
fn colour_at(picture: &Picture, point: Vec3) -> [u8; 3] {
    let (x, y) = project(&camera(), SIZE, point).expect("the point is in view");
    picture.pixel8(y as u32, x as u32)
}

#[test]
fn the_picture_shows_a_lit_sphere_and_box_on_the_ground() {
    let picture = render(
        &Scene::example(),
        &camera(),
        &[],
        SIZE,
        &RenderOptions::default(),
    );
    assert_eq!((picture.width, picture.height), SIZE);
    // The sky at the top: the background, sRGB-encoded.
    let [r, g, b] = picture.pixel8(0, 0);
    assert!(b > g && g > r && r > 150, "sky {:?}", [r, g, b]);
    // The sphere's front is red, the box's blue, the ground grey.
    let [r, g, b] = colour_at(&picture, v(-0.9, 0.7, 0.7));
    assert!(r > 2 * g && r > 2 * b, "sphere {:?}", [r, g, b]);
    let [r, g, b] = colour_at(&picture, v(0.9, 0.6, 0.6));
    assert!(b > 2 * r && b > g, "box {:?}", [r, g, b]);
    let [r, g, b] = colour_at(&picture, v(0.0, 0.0, 2.5));
    assert!(
        r.abs_diff(g) < 12 && g.abs_diff(b) < 12 && r > 60,
        "ground {:?}",
        [r, g, b]
    );
}

#[test]
fn shading_options_change_the_shading_and_not_the_picture_size() {
    let scene = Scene::example();
    let base = RenderOptions::default();
    let brightness = |options: RenderOptions| -> u64 {
        let picture = render(&scene, &camera(), &[], SIZE, &options);
        assert_eq!(picture.values.len(), 64 * 48);
        picture.rgb8().iter().map(|&x| u64::from(x)).sum()
    };
    let normal = brightness(base);
    assert!(
        brightness(RenderOptions {
            gamma: Gamma::Linear,
            ..base
        }) < normal
    );
    assert!(
        brightness(RenderOptions {
            gamma: Gamma::Twice,
            ..base
        }) > normal
    );
    assert!(
        brightness(RenderOptions {
            light_scale: 2.0,
            ..base
        }) > normal
    );
    assert!(
        brightness(RenderOptions {
            light_scale: 0.5,
            ..base
        }) < normal
    );
    assert!(
        brightness(RenderOptions {
            ambient: 0.4,
            ..base
        }) > normal
    );
    assert!(
        brightness(RenderOptions {
            shadows: false,
            ..base
        }) > normal
    );
    assert!(
        brightness(RenderOptions {
            phong: false,
            ..base
        }) < normal
    );
    let red = LightChange::Recoloured(v(1.0, 0.3, 0.3));
    assert!(
        brightness(RenderOptions {
            light_change: Some(red),
            ..base
        }) < normal
    );
    let moved = LightChange::Moved(v(8.0, 0.0, 0.0));
    assert_ne!(
        brightness(RenderOptions {
            light_change: Some(moved),
            ..base
        }),
        normal
    );
}

#[test]
fn jittered_samples_are_the_same_every_time() {
    let options = RenderOptions {
        samples: 16,
        ..RenderOptions::default()
    };
    let once = render(&Scene::example(), &camera(), &[], SIZE, &options);
    let twice = render(&Scene::example(), &camera(), &[], SIZE, &options);
    assert_eq!(once, twice);
    // Antialiasing changes the edges, not the picture: most pixels stay within a few
    // levels of the one-sample render.
    let single = render(
        &Scene::example(),
        &camera(),
        &[],
        SIZE,
        &RenderOptions::default(),
    );
    let (a, b) = (once.rgb8(), single.rgb8());
    let near = a
        .iter()
        .zip(&b)
        .filter(|(x, y)| x.abs_diff(**y) <= 8)
        .count();
    assert!(a != b && near * 10 > a.len() * 8, "{near} of {}", a.len());
}

/// u-sign mirrors the picture left-right, v-sign turns it upside down (the camera has no
/// shift, so the image plane is symmetric about its centre).
#[test]
fn a_mistaken_camera_makes_the_mistaken_picture() {
    let scene = Scene::example();
    let options = RenderOptions::default();
    let right = render(&scene, &camera(), &[], SIZE, &options);
    let (w, h) = SIZE;
    let agree = |picture: &Picture, at: &dyn Fn(u32, u32) -> (u32, u32)| {
        let mut same = 0;
        for row in 0..h {
            for col in 0..w {
                let (r, c) = at(row, col);
                let (a, b) = (picture.pixel8(row, col), right.pixel8(r, c));
                same += usize::from(a.iter().zip(b).all(|(x, y)| x.abs_diff(y) <= 1));
            }
        }
        same
    };
    let mirrored = render(&scene, &camera(), &[Mistake::USign], SIZE, &options);
    assert_ne!(mirrored, right);
    // Rounding may move a pixel on an edge; all but a handful agree.
    let n = (w * h) as usize;
    assert!(agree(&mirrored, &|r, c| (r, w - 1 - c)) >= n - 4);
    let flipped = render(&scene, &camera(), &[Mistake::VSign], SIZE, &options);
    assert!(agree(&flipped, &|r, c| (h - 1 - r, c)) >= n - 4);
}

/// The header of a Netpbm file: magic number, width, height, maxval, and where the
/// samples start (comments skipped).
fn netpbm_header(bytes: &[u8]) -> (String, u32, u32, u32, usize) {
    let mut words = Vec::new();
    let mut i = 0;
    while words.len() < 4 {
        match bytes[i] {
            b'#' => {
                while bytes[i] != b'\n' {
                    i += 1;
                }
            }
            c if c.is_ascii_whitespace() => {}
            _ => {
                let start = i;
                while !bytes[i].is_ascii_whitespace() {
                    i += 1;
                }
                words.push(String::from_utf8(bytes[start..i].to_vec()).unwrap());
                continue;
            }
        }
        i += 1;
    }
    let number = |k: usize| words[k].parse::<u32>().unwrap();
    // One whitespace byte ends the header.
    (words[0].clone(), number(1), number(2), number(3), i + 1)
}

#[test]
fn every_format_writes_a_file_of_the_right_size() {
    let dir = tempfile::tempdir().unwrap();
    let picture = render(
        &Scene::example(),
        &camera(),
        &[],
        SIZE,
        &RenderOptions::default(),
    );
    let (w, h) = SIZE;
    let pixels = (w * h) as usize;
    for format in Format::ALL {
        let path = dir
            .path()
            .join(format!("{format:?}.{}", format.extension()));
        picture.write(&path, format);
        let bytes = std::fs::read(&path).unwrap();
        let what = format!("{format:?}");
        match format {
            Format::Png | Format::Png16 | Format::PngGrey => {
                let image = image::open(&path).unwrap();
                assert_eq!((image.width(), image.height()), SIZE, "{what}");
                let expected = match format {
                    Format::Png => image::ColorType::Rgb8,
                    Format::Png16 => image::ColorType::Rgb16,
                    _ => image::ColorType::L8,
                };
                assert_eq!(image.color(), expected, "{what}");
                if format == Format::Png {
                    assert_eq!(image.to_rgb8().into_raw(), picture.rgb8());
                }
            }
            _ => {
                let (magic, width, height, maxval, start) = netpbm_header(&bytes);
                assert_eq!((width, height), SIZE, "{what}");
                let body = &bytes[start..];
                match format {
                    Format::PpmP6 => {
                        assert_eq!((magic.as_str(), maxval), ("P6", 255));
                        assert_eq!(body, picture.rgb8());
                    }
                    Format::Ppm16 => {
                        assert_eq!((magic.as_str(), maxval), ("P6", 65535));
                        assert_eq!(body.len(), pixels * 6);
                        // Big-endian: the first red sample.
                        let first = u16::from_be_bytes([body[0], body[1]]);
                        assert_eq!(first, picture.rgb16()[0]);
                    }
                    Format::PgmP5 => {
                        assert_eq!((magic.as_str(), maxval), ("P5", 255));
                        assert_eq!(body.len(), pixels);
                    }
                    Format::PpmP3 | Format::PgmP2 => {
                        let channels = if format == Format::PpmP3 { 3 } else { 1 };
                        assert_eq!(magic, if channels == 3 { "P3" } else { "P2" });
                        let text = std::str::from_utf8(body).unwrap();
                        assert!(text.lines().all(|line| line.len() <= 70), "{what}");
                        let samples: Vec<u8> = text
                            .split_whitespace()
                            .map(|s| s.parse().unwrap())
                            .collect();
                        let expected = if channels == 3 {
                            picture.rgb8()
                        } else {
                            picture.grey8()
                        };
                        assert_eq!(samples, expected, "{what}");
                        assert!(bytes.windows(2).any(|w| w == b"\n#"), "{what}: no comment");
                    }
                    _ => unreachable!(),
                }
            }
        }
    }
}

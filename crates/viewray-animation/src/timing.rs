//! Time: from a frame number to a time in `[0, 1]`, and from a time to the camera of a
//! scene file's animation.

use viewray_camera::Camera;
use viewray_scene::{Animation, Ease, SceneError};

/// `ease` applied to `x` in `[0, 1]`:
///
/// ```text
/// Linear:  x
/// InOut:   3 x^2 - 2 x^3      (smoothstep: 0 -> 0, 1/2 -> 1/2, 1 -> 1, flat at both ends)
/// ```
pub fn eased(ease: Ease, x: f64) -> f64 {
    match ease {
        Ease::Linear => x,
        Ease::InOut => x * x * (3.0 - 2.0 * x),
    }
}

/// The time of frame `frame` (0-based) of `frames`, eased:
///
/// ```text
/// t = ease(k / (n - 1))       (t = 0 for a single frame)
/// ```
///
/// With [`Ease::Linear`], frame `k` of `n` is exactly time `k / (n - 1)`: the first frame
/// is time 0 and the last time 1.
pub fn frame_time(ease: Ease, frame: u32, frames: u32) -> f64 {
    if frames <= 1 {
        return 0.0;
    }
    eased(ease, f64::from(frame) / f64::from(frames - 1))
}

/// The camera of `animation` at time `t`, for a `width x height` image: before the first
/// key the first key's camera, after the last the last's, and between keys `a` and `b`
/// the two mixed field by field with `s = (t - t_a) / (t_b - t_a)`
/// ([`CameraSpec::mix`](viewray_scene::CameraSpec::mix)); at a key's time, that key's
/// camera exactly.
///
/// # Errors
/// A [`SceneError`] placed at the later key when the mixed camera is not valid (the view
/// direction passing through zero, say).
pub fn camera_at(
    animation: &Animation,
    t: f64,
    width: u32,
    height: u32,
) -> Result<Camera, SceneError> {
    let keys = &animation.keys;
    let build = |index: usize, spec: &viewray_scene::CameraSpec| {
        spec.camera(width, height).map_err(|message| {
            animation.key_error(
                index,
                format!("animation: the camera at t = {t}: {message}"),
            )
        })
    };
    if keys.is_empty() {
        return Err(animation.error("animation: no keys"));
    }
    // The last key at or before t; before the first key, the first.
    let at_or_before = keys.iter().rposition(|key| key.t <= t).unwrap_or(0);
    let a = &keys[at_or_before];
    match keys.get(at_or_before + 1) {
        Some(b) if t > a.t => {
            let s = (t - a.t) / (b.t - a.t);
            let mixed = a.camera.mix(&b.camera, s).map_err(|message| {
                animation.key_error(at_or_before + 1, format!("animation: {message}"))
            })?;
            build(at_or_before + 1, &mixed)
        }
        _ => build(at_or_before, &a.camera),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn linear_frames_are_evenly_spaced_from_0_to_1() {
        let times: Vec<f64> = (0..5).map(|k| frame_time(Ease::Linear, k, 5)).collect();
        assert_eq!(times, [0.0, 0.25, 0.5, 0.75, 1.0]);
        assert_eq!(frame_time(Ease::Linear, 0, 1), 0.0);
        assert_eq!(frame_time(Ease::InOut, 0, 1), 0.0);
    }

    #[test]
    fn in_out_starts_and_ends_slowly_and_is_symmetric() {
        assert_eq!(eased(Ease::InOut, 0.0), 0.0);
        assert_eq!(eased(Ease::InOut, 0.5), 0.5);
        assert_eq!(eased(Ease::InOut, 1.0), 1.0);
        // 3 (1/10)^2 - 2 (1/10)^3 = 0.028.
        assert!((eased(Ease::InOut, 0.1) - 0.028).abs() < 1e-15);
        for k in 0..=20 {
            let x = f64::from(k) / 20.0;
            let sum = eased(Ease::InOut, x) + eased(Ease::InOut, 1.0 - x);
            assert!((sum - 1.0).abs() < 1e-12, "{x}");
        }
    }
}

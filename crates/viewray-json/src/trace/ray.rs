//! The viewing ray's numbers: the pixel's image-plane point (or a panoramic camera's
//! angles) with their formulas, the camera's frame, and the family's rule for the ray.

use glam::{DVec2, DVec3};
use viewray_camera::{
    Camera, CameraSample, Projection, equirectangular_angles, pixel_to_image_plane,
};

use super::text::{Text, d3, m};

impl Text {
    /// The pixel's image point, the camera's numbers for it, and its ray.
    pub(super) fn viewing_ray(
        &mut self,
        camera: &Camera,
        (row, col): (u32, u32),
        ray: Option<(DVec3, DVec3)>,
    ) {
        let (i, j) = (row + 1, col + 1);
        let (w, h) = (camera.width(), camera.height());
        let image = DVec2::new(f64::from(col), f64::from(row)) + CameraSample::CENTER.p_film;
        let size = DVec2::new(f64::from(w), f64::from(h));
        let frame = camera.frame();
        let projection = camera.projection();
        if let Some(viewport) = projection.viewport() {
            let uv = pixel_to_image_plane(row, col, CameraSample::CENTER.p_film, (w, h), viewport);
            self.line(
                1,
                format!(
                    "u =  ((j - 1/2)/W - 1/2) vw = (({j} - 0.5)/{w} - 0.5) x {} = {}",
                    m(viewport.x),
                    m(uv.x)
                ),
            );
            self.line(
                1,
                format!(
                    "v = -((i - 1/2)/H - 1/2) vh = -(({i} - 0.5)/{h} - 0.5) x {} = {}",
                    m(viewport.y),
                    m(uv.y)
                ),
            );
        } else {
            self.line(
                1,
                format!(
                    "x = j - 1/2 = {}, y = i - 1/2 = {}   (the pixel's centre, from the top-left)",
                    m(image.x),
                    m(image.y)
                ),
            );
        }
        match projection {
            Projection::Equirectangular => {
                let (longitude, latitude) = equirectangular_angles(image, size);
                self.line(
                    1,
                    format!(
                        "longitude = 2 pi (x/W - 1/2) = 2 pi ({}/{w} - 0.5) = {}",
                        m(image.x),
                        m(longitude)
                    ),
                );
                self.line(
                    1,
                    format!(
                        "latitude  = pi (1/2 - y/H) = pi (0.5 - {}/{h}) = {}",
                        m(image.y),
                        m(latitude)
                    ),
                );
            }
            Projection::Fisheye(fisheye) => {
                let p = fisheye.image_point(image, size);
                self.line(
                    1,
                    format!("a = 2x/W - 1 = 2 x {}/{w} - 1 = {}", m(image.x), m(p.a)),
                );
                self.line(
                    1,
                    format!(
                        "b = (1 - 2y/H) H/W = (1 - 2 x {}/{h}) x {h}/{w} = {}",
                        m(image.y),
                        m(p.b)
                    ),
                );
                self.line(1, format!("r = sqrt(a^2 + b^2) = {}", m(p.r)));
                self.line(
                    1,
                    format!(
                        "theta = r F/2 = {} x {}/2 = {}   (F = {} degrees)",
                        m(p.r),
                        m(fisheye.fov),
                        m(p.theta),
                        m(fisheye.fov.to_degrees())
                    ),
                );
            }
            _ => {}
        }
        self.line(
            1,
            format!(
                "frame e = {}, U = {}, V = {}, W = {}   (the lecture's e, u, v, w)",
                d3(frame.e()),
                d3(frame.u()),
                d3(frame.v()),
                d3(frame.w())
            ),
        );
        let Some((origin, direction)) = ray else {
            self.line(
                1,
                "r > 1: outside the image circle, the camera has no ray for this pixel",
            );
            return;
        };
        let (origin_rule, direction_rule, parameters) = ray_rule(projection);
        if let Some(parameters) = parameters {
            self.line(1, parameters);
        }
        let direction_rule = match projection {
            Projection::ThinLens(p) if p.is_tilted() => {
                self.line(1, tilted_lens_numbers(p));
                TILTED_DIRECTION
            }
            _ => direction_rule,
        };
        self.line(1, format!("origin    = {origin_rule} = {}", d3(origin)));
        self.line(
            1,
            format!("direction = {direction_rule} = {}", d3(direction)),
        );
    }
}

/// The centre ray of a tilted thin lens: through the point where the pinhole ray `c`
/// meets the plane of focus `m . P = F`, reached at `t = 1` (the camera crate's module
/// `scheimpflug`); where that point is not ahead of the lens, the ray runs along `c`.
const TILTED_DIRECTION: &str =
    "(F / m.c) c where m.c > 0, else c;  c = (u + sx) U + (v + sy) V - d W";

/// A tilted lens's numbers for [`TILTED_DIRECTION`]: its tilt and swing, `F = d`, and
/// `m = n + (1 - F/f) W` in camera coordinates (`n` the lens's axis).
fn tilted_lens_numbers(lens: &viewray_camera::ThinLens) -> String {
    let focal_length = lens.distance;
    let m_vector = lens.lens_normal() + DVec3::Z * (1.0 - focal_length / lens.focus);
    format!(
        "tilt {} degrees, swing {} degrees: plane of focus m.P = F, F = d = {}, \
         m = n + (1 - F/f) W = {} (camera coordinates)",
        m(lens.tilt.to_degrees()),
        m(lens.swing.to_degrees()),
        m(focal_length),
        d3(m_vector)
    )
}

/// The rule of a family's viewing ray: origin and direction in the lecture's notation
/// (the lens at its centre), and the family's parameters in them.
fn ray_rule(projection: &Projection) -> (&'static str, &'static str, Option<String>) {
    match projection {
        Projection::Perspective(p) => (
            "e",
            "(u + sx) U + (v + sy) V - d W",
            Some(format!(
                "d = {}, shift (sx, sy) = ({}, {})",
                m(p.distance),
                m(p.shift.x),
                m(p.shift.y)
            )),
        ),
        Projection::ThinLens(p) => (
            "e   (the lens centre)",
            "(f/d)((u + sx) U + (v + sy) V - d W)",
            Some(format!(
                "d = {}, shift (sx, sy) = ({}, {}), focus f = {}",
                m(p.distance),
                m(p.shift.x),
                m(p.shift.y),
                m(p.focus)
            )),
        ),
        Projection::Orthographic(_) => ("e + u U + v V", "-W", None),
        Projection::Oblique(p) => (
            "e + u U + v V",
            "-W - L (cos(phi) U + sin(phi) V)",
            Some(format!(
                "L = {}, phi = {} degrees",
                m(p.ratio),
                m(p.angle.to_degrees())
            )),
        ),
        Projection::Equirectangular => (
            "e",
            "sin(longitude) cos(latitude) U + sin(latitude) V - cos(longitude) cos(latitude) W",
            None,
        ),
        Projection::Fisheye(_) => ("e", "sin(theta) (a/r U + b/r V) - cos(theta) W", None),
    }
}

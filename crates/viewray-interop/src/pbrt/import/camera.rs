//! The directives of the camera and the image (`Camera`, `Film`, `Sampler`), and the
//! camera they make once the file is read.

use glam::{DMat4, DVec2, DVec3};
use viewray_scene::{Aperture, CameraDocument, PerspectiveSize, ProjectionDocument};

use super::{At, CameraDirective, DEFAULT_FILM, Importer};
use crate::ImportError;
use crate::common::camera_document;
use crate::pbrt::parse::Params;

impl Importer<'_> {
    /// `Camera "type" params`: kept until the end, when the film size is known.
    pub(super) fn camera(&mut self, at: At) -> Result<(), ImportError> {
        let kind = self.parser.kind("Camera", at)?;
        let params = self.parser.params()?;
        if !self.state.ctm.is_finite() || self.state.ctm.determinant() == 0.0 {
            return Err(self.error(at, "the camera transform is singular"));
        }
        self.named_coordinate_systems
            .insert("camera".to_owned(), self.state.ctm.inverse());
        self.camera = Some(CameraDirective {
            kind,
            params,
            camera_from_world: self.state.ctm,
            at,
        });
        Ok(())
    }

    /// `Film "type" params`: the image size.
    pub(super) fn film(&mut self, at: At) -> Result<(), ImportError> {
        self.parser.kind("Film", at)?;
        let params = self.parser.params()?;
        let integer = |name: &str, default: u32| -> Result<u32, ImportError> {
            match params.numbers(name) {
                None => Ok(default),
                Some(([x], _)) if x.fract() == 0.0 && *x >= 1.0 && *x <= f64::from(u32::MAX) => {
                    Ok(*x as u32)
                }
                Some((_, at)) => {
                    Err(self.error(at, format!("\"{name}\" must be one positive whole number")))
                }
            }
        };
        let width = integer("xresolution", DEFAULT_FILM.0)?;
        let height = integer("yresolution", DEFAULT_FILM.1)?;
        (self.width, self.height) = (width, height);
        Ok(())
    }

    /// `Sampler "type" params`: the samples per pixel.
    pub(super) fn sampler(&mut self, at: At) -> Result<(), ImportError> {
        self.parser.kind("Sampler", at)?;
        let params = self.parser.params()?;
        match params.numbers("pixelsamples") {
            None => {}
            Some(([x], _)) if x.fract() == 0.0 && *x >= 1.0 && *x <= 1e9 => {
                self.samples = *x as u32;
            }
            Some((_, at)) => {
                return Err(self.error(at, "\"pixelsamples\" must be one positive whole number"));
            }
        }
        Ok(())
    }

    /// The camera of the `Camera` directive, and the mirror (identity or a scale by -1 in
    /// `x`) that makes the scene's picture pbrt's.
    pub(super) fn camera_document(
        &mut self,
        directive: &CameraDirective,
    ) -> Result<(CameraDocument, DMat4), ImportError> {
        let CameraDirective {
            kind,
            params,
            camera_from_world,
            at,
        } = directive;
        let world_from_camera = camera_from_world.inverse();
        let (x, y, z) = (
            world_from_camera.x_axis.truncate(),
            world_from_camera.y_axis.truncate(),
            world_from_camera.z_axis.truncate(),
        );
        let handedness = x.cross(y).dot(z);
        let screen = self.screen_window(params)?;
        let (projection, mirror, columns) = match kind.as_str() {
            "perspective" | "orthographic" => {
                let (projection, centre) = self.projection(kind, params, screen, *at)?;
                // U = x, V = y, W = -z; an off-centre orthographic window moves the eye.
                let eye = if kind == "orthographic" {
                    world_from_camera.transform_point3(centre.extend(0.0))
                } else {
                    world_from_camera.w_axis.truncate()
                };
                (projection, handedness > 0.0, [x, y, -z, eye])
            }
            "spherical" => {
                let mapping = params.string("mapping").unwrap_or("equalarea");
                if mapping != "equirectangular" {
                    return Err(self.error(
                        *at,
                        format!(
                            "the spherical camera's mapping \"{mapping}\" has no viewray \
                             counterpart (viewray has equirectangular)"
                        ),
                    ));
                }
                // x = W, y = V, z = -U.
                (
                    ProjectionDocument::Equirectangular,
                    handedness < 0.0,
                    [-z, y, x, world_from_camera.w_axis.truncate()],
                )
            }
            other => {
                return Err(self.error(
                    *at,
                    format!(
                        "unsupported camera \"{other}\", expected perspective, orthographic \
                         or spherical"
                    ),
                ));
            }
        };
        let mirror = if mirror {
            self.comments.push(
                "pbrt's camera is left-handed and this one was set up with a plain LookAt: \
                 the scene is mirrored in x so that the picture is pbrt's."
                    .to_owned(),
            );
            DMat4::from_scale(DVec3::new(-1.0, 1.0, 1.0))
        } else {
            DMat4::IDENTITY
        };
        let m = mirror
            * DMat4::from_cols(
                columns[0].extend(0.0),
                columns[1].extend(0.0),
                columns[2].extend(0.0),
                columns[3].extend(1.0),
            );
        let camera = camera_document(m, projection).map_err(|message| self.error(*at, message))?;
        Ok((camera, mirror))
    }

    /// The camera's `screenwindow` `[x0, x1, y0, y1]`, by default `[-a, a] x [-1, 1]` for
    /// a frame aspect ratio `a > 1`, else `[-1, 1] x [-1/a, 1/a]`.
    pub(super) fn screen_window(&self, params: &Params) -> Result<[f64; 4], ImportError> {
        let aspect = f64::from(self.width) / f64::from(self.height);
        let frame_aspect = params.number("frameaspectratio").unwrap_or(aspect);
        Ok(match params.numbers("screenwindow") {
            Some(([x0, x1, y0, y1], _)) => [*x0, *x1, *y0, *y1],
            Some((_, at)) => return Err(self.error(at, "\"screenwindow\" needs four numbers")),
            None if frame_aspect > 1.0 => [-frame_aspect, frame_aspect, -1.0, 1.0],
            None => [-1.0, 1.0, -1.0 / frame_aspect, 1.0 / frame_aspect],
        })
    }

    /// The projection of a perspective or orthographic camera from its screen window,
    /// field of view and lens, and the window's centre (in units of `t` for a perspective
    /// camera, of the scene for an orthographic one).
    pub(super) fn projection(
        &mut self,
        kind: &str,
        params: &Params,
        screen: [f64; 4],
        at: At,
    ) -> Result<(ProjectionDocument, DVec2), ImportError> {
        let lens = params.number("lensradius").unwrap_or(0.0);
        let focus = params.number("focaldistance").unwrap_or(1e6);
        let viewport = DVec2::new(screen[1] - screen[0], screen[3] - screen[2]);
        let centre = DVec2::new(screen[1] + screen[0], screen[3] + screen[2]) / 2.0;
        let projection = if kind == "perspective" {
            let fov = params.number("fov").unwrap_or(90.0);
            if !(fov > 0.0 && fov < 180.0) {
                return Err(self.error(
                    at,
                    format!("\"fov\" must be between 0 and 180 degrees, found {fov}"),
                ));
            }
            let t = (fov.to_radians() / 2.0).tan();
            let size = PerspectiveSize::Viewport {
                distance: 1.0,
                viewport: viewport * t,
            };
            if lens > 0.0 {
                ProjectionDocument::ThinLens {
                    size,
                    shift: centre * t,
                    aperture: Aperture::Radius(lens),
                    focus,
                }
            } else {
                ProjectionDocument::Perspective {
                    size,
                    shift: centre * t,
                }
            }
        } else {
            if centre != DVec2::ZERO {
                self.comments.push(
                    "pbrt's orthographic screen window is off-centre: the eye is moved to its \
                     centre."
                        .to_owned(),
                );
            }
            ProjectionDocument::Orthographic {
                viewport,
                lens: (lens > 0.0).then_some(viewray_camera::Lens {
                    aperture: lens,
                    focus,
                }),
            }
        };
        Ok((projection, centre))
    }
}

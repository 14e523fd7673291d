//! How a figure places 3D points: through a viewray camera, or as a side view.

use glam::{DVec2, DVec3, Vec2};
use viewray_camera::{Camera, Frame, Orthographic, Projection};

use viewray_draw::{Mapping, Rect};

/// A map from world points to figure pixels.
///
/// Every 3D element of a figure is placed through one of these, so a figure can be
/// checked against the camera that it shows: a [`CameraView`] is a viewray [`Camera`]
/// (its [`Camera::project`]), a [`SideView`] draws the y-z plane in world units.
// A camera is a few hundred bytes; a figure builds a handful of views and copies them
// into the record of the rays it draws, so boxing the camera would only add allocations.
#[allow(clippy::large_enum_variant)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) enum FigureView {
    /// Through a camera onto a rectangle of the figure.
    Camera(CameraView),
    /// The y-z plane seen from `+x`.
    Side(SideView),
}

impl FigureView {
    /// The figure point (pixels, y down) where the world point `p` is drawn, or `None`
    /// where a camera does not see it.
    pub(crate) fn to_figure(self, p: DVec3) -> Option<Vec2> {
        match self {
            FigureView::Camera(view) => view.to_figure(p),
            FigureView::Side(view) => Some(view.to_figure(p)),
        }
    }
}

/// A viewray [`Camera`] whose image is drawn over a rectangle of the figure: a world
/// point goes where [`Camera::project`] puts it.
///
/// ```text
/// figure = rect.min + project(p) * (rect.width / W, rect.height / H)
/// ```
///
/// The 3D figures look at their scene through an orthographic "figure camera"
/// ([`CameraView::fit_orthographic`]); the taxonomy's thumbnails through a
/// [`Preset`](viewray_camera::Preset)'s camera.
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct CameraView {
    /// The camera.
    pub(crate) camera: Camera,
    /// Where its image lies on the figure.
    pub(crate) rect: Rect,
}

impl CameraView {
    /// The view of `camera`'s whole image stretched over `rect`.
    pub(crate) fn new(camera: Camera, rect: Rect) -> CameraView {
        CameraView { camera, rect }
    }

    /// An orthographic figure camera looking along `-towards_eye` with `up` up, framed
    /// so that every point of `points` lies inside `rect` at least `margin` pixels from
    /// its edges, centred, at one scale for both axes.
    ///
    /// # Panics
    /// If `towards_eye` is zero or parallel to `up`, or `points` is empty or not finite:
    /// figure code passes constants.
    pub(crate) fn fit_orthographic(
        towards_eye: DVec3,
        up: DVec3,
        points: &[DVec3],
        rect: Rect,
        margin: f32,
    ) -> CameraView {
        let frame = Frame::from_eye_view_up(DVec3::ZERO, -towards_eye, up)
            .expect("a figure camera's view and up are valid");
        let camera_points: Vec<DVec3> = points
            .iter()
            .map(|&p| frame.camera_from_world_point(p))
            .collect();
        let min = camera_points.iter().fold(DVec3::INFINITY, |a, &b| a.min(b));
        let max = camera_points
            .iter()
            .fold(DVec3::NEG_INFINITY, |a, &b| a.max(b));
        assert!(min.is_finite() && max.is_finite(), "points to fit");
        // The image size in whole pixels; the rectangle shrinks to match.
        let width = rect.width().round().max(1.0);
        let height = rect.height().round().max(1.0);
        let usable = DVec2::new(
            f64::from(width - 2.0 * margin).max(1.0),
            f64::from(height - 2.0 * margin).max(1.0),
        );
        let extent = (max - min).truncate().max(DVec2::splat(1e-9));
        let scale = (usable.x / extent.x).min(usable.y / extent.y);
        let viewport = DVec2::new(f64::from(width), f64::from(height)) / scale;
        // Move the eye within the image plane to the points' centre, and back along w
        // past the nearest point so that everything lies in front of the image plane.
        let centre = (min + max) / 2.0;
        let eye = frame.world_from_camera_point(DVec3::new(centre.x, centre.y, max.z + 1.0));
        let frame = frame
            .with_eye(eye)
            .expect("finite points make a finite eye");
        let projection = Projection::Orthographic(Orthographic {
            viewport,
            lens: None,
        });
        // Whole-pixel sizes of at most a canvas: the casts cannot truncate.
        #[allow(clippy::cast_possible_truncation, clippy::cast_sign_loss)]
        let camera = Camera::new(frame, projection, width as u32, height as u32)
            .expect("a figure camera is valid");
        let rect = Rect::from_xywh(rect.min.x, rect.min.y, width, height);
        CameraView { camera, rect }
    }

    /// Figure pixels per image pixel, `(rect.width / W, rect.height / H)`.
    fn pixel_scale(&self) -> Vec2 {
        Vec2::new(
            self.rect.width() / self.camera.width() as f32,
            self.rect.height() / self.camera.height() as f32,
        )
    }

    /// The figure point of the continuous image point `image` of the camera.
    pub(crate) fn image_to_figure(&self, image: DVec2) -> Vec2 {
        self.rect.min + image.as_vec2() * self.pixel_scale()
    }

    /// The figure point where the camera sees `p`, or `None` where it does not (behind a
    /// perspective eye or a parallel camera's image plane).
    pub(crate) fn to_figure(self, p: DVec3) -> Option<Vec2> {
        self.camera
            .project(p)
            .map(|image| self.image_to_figure(image))
    }
}

/// A side view: a vertical plane of the world seen face-on, `right` pointing right and
/// `up` up on the figure. The lecture's figures look at the y-z plane from `+x`, so `-z`
/// points right and `y` up (a camera looking down `-z` looks right); a camera's own side
/// view ([`SideWindow::fit`](crate::SideWindow::fit)) uses the plane through its **v** and **w**. The third
/// coordinate, along `right x up` (towards the viewer), is dropped: a point is drawn
/// where its orthographic projection onto the plane falls.
///
/// ```text
/// figure = mapping.to_canvas((p . right, p . up))
/// ```
#[derive(Clone, Copy, Debug, PartialEq)]
pub(crate) struct SideView {
    /// From `(p . right, p . up)` in world units to figure pixels.
    pub(crate) mapping: Mapping,
    /// The region of the plane the view was fitted to, as `(p . right, p . up)`: what it
    /// is sure to show.
    pub(crate) bounds: Rect,
    /// The world direction drawn to the right, a unit vector.
    pub(crate) right: DVec3,
    /// The world direction drawn up, a unit vector perpendicular to `right`.
    pub(crate) up: DVec3,
}

impl SideView {
    /// The side view of the y-z plane from `+x` showing at least `-z` in `depth` and `y`
    /// in `height` (world units) inside `canvas`, centred, at one scale.
    ///
    /// # Panics
    /// If either range or the canvas is empty: figure code passes constants.
    pub(crate) fn fit(depth: (f64, f64), height: (f64, f64), canvas: Rect) -> SideView {
        SideView::fit_plane(DVec3::NEG_Z, DVec3::Y, depth, height, canvas)
    }

    /// The side view with `right` and `up` (unit vectors, perpendicular) showing at least
    /// `p . right` in `across` and `p . up` in `height` inside `canvas`, centred, at one
    /// scale.
    ///
    /// # Panics
    /// If either range or the canvas is empty.
    pub(crate) fn fit_plane(
        right: DVec3,
        up: DVec3,
        across: (f64, f64),
        height: (f64, f64),
        canvas: Rect,
    ) -> SideView {
        let world = Rect::from_corners(
            Vec2::new(across.0 as f32, height.0 as f32),
            Vec2::new(across.1 as f32, height.1 as f32),
        );
        SideView {
            mapping: Mapping::fit(world, canvas).expect("a side view of a non-empty region"),
            bounds: world,
            right,
            up,
        }
    }

    /// The plane coordinates `(p . right, p . up)` of the world point `p`.
    pub(crate) fn plane_point(&self, p: DVec3) -> DVec2 {
        DVec2::new(p.dot(self.right), p.dot(self.up))
    }

    /// The direction out of the figure, towards its viewer: `right x up`.
    pub(crate) fn towards_viewer(&self) -> DVec3 {
        self.right.cross(self.up)
    }

    /// The figure point of world point `p`.
    pub(crate) fn to_figure(self, p: DVec3) -> Vec2 {
        self.mapping.to_canvas(self.plane_point(p).as_vec2())
    }

    /// A world length in figure pixels.
    pub(crate) fn length(&self, length: f64) -> f32 {
        self.mapping.length_to_canvas(length as f32)
    }

    /// The part `(t0, t1)` of the parameter range `t` of the ray `origin + t direction`
    /// whose side-view image lies inside [`SideView::bounds`], or `None`.
    pub(crate) fn clip_ray(
        &self,
        ray: &viewray_geometry::DRay,
        t: (f64, f64),
    ) -> Option<(f64, f64)> {
        // In plane coordinates: x(t) = o . right + t d . right, y(t) = o . up + t d . up.
        let axes = [
            (
                ray.origin.dot(self.right),
                ray.direction.dot(self.right),
                f64::from(self.bounds.min.x),
                f64::from(self.bounds.max.x),
            ),
            (
                ray.origin.dot(self.up),
                ray.direction.dot(self.up),
                f64::from(self.bounds.min.y),
                f64::from(self.bounds.max.y),
            ),
        ];
        let (mut t0, mut t1) = t;
        for (start, slope, low, high) in axes {
            if slope == 0.0 {
                if start < low || start > high {
                    return None;
                }
                continue;
            }
            let (a, b) = ((low - start) / slope, (high - start) / slope);
            t0 = t0.max(a.min(b));
            t1 = t1.min(a.max(b));
        }
        (t0 < t1).then_some((t0, t1))
    }
}

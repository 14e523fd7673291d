//! A movie: a scene, the cameras of every frame, and how a frame is rendered and laid out.

use glam::Vec2;
use image::{RgbImage, RgbaImage};
use viewray_camera::Camera;
use viewray_diagram::{SideViewCanvas, SideWindow, side_view};
use viewray_draw::{Anchor, Baseline, Color, Figure, Item, Label, Rect, Sampling, raster};
use viewray_render::{RenderError, RenderSettings, render};
use viewray_scene::{Animation, LoadOptions, MAX_FPS, MAX_FRAMES, Scene, SceneError};

use crate::demos::{Demo, Shot};
use crate::timing::{camera_at, frame_time};

/// The most pixels a frame may have, pictures and diagrams together: 2^24 (4096 x 4096).
/// A frame is held as floats while it renders and as bytes while it is encoded, and the
/// GIF palette learns from three frames at once: beyond this a frame would take gigabytes.
pub const MAX_FRAME_PIXELS: u64 = 1 << 24;

/// Overrides of an animation's own settings.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct MovieSettings {
    /// How many frames, instead of the animation's (1 to [`MAX_FRAMES`]).
    pub frames: Option<u32>,
    /// Frames per second, instead of the animation's (1 to [`MAX_FPS`]).
    pub fps: Option<u32>,
    /// Whether each picture gets the side view of its camera beside it.
    pub with_diagram: bool,
}

/// Why a movie cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum MovieError {
    /// The scene or its animation is not valid (placed in the file).
    #[error(transparent)]
    Scene(#[from] SceneError),
    /// A frame would be too large to hold.
    #[error(
        "a frame of {width} x {height} pixels is too large to animate: at most {MAX_FRAME_PIXELS} \
         pixels (4096 x 4096){}",
        if *.with_diagram { ", side views included" } else { "" }
    )]
    FrameTooLarge {
        /// The frame's width (pictures and diagrams side by side).
        width: u64,
        /// Its height.
        height: u64,
        /// Whether side views are part of it.
        with_diagram: bool,
    },
    /// A frame count or rate outside the limits.
    #[error("{0}")]
    Setting(String),
}

/// What an animation renders: a scene and, for every frame, the cameras of its pictures
/// (one, or two side by side), with the side view of each when asked.
///
/// A frame's pixels depend only on the scene and the frame's number: its cameras are
/// fixed when the movie is made, each render is deterministic (see `viewray-render`),
/// and the side views are drawn in one window fixed for the whole movie.
#[derive(Clone, Debug)]
pub struct Movie {
    scene: Scene,
    shots: Vec<Vec<Shot>>,
    fps: u32,
    /// The size of each picture.
    picture: (u32, u32),
    /// The side views' window and width, when they are drawn.
    diagram: Option<(SideWindow, u32)>,
}

impl Movie {
    /// The movie of a scene file's animation: frame `k` of `n` looks through the camera
    /// at time `ease(k / (n - 1))` ([`camera_at`]), at the scene's image size.
    ///
    /// # Errors
    /// [`MovieError::Scene`], placed at a key, when a frame's camera is not valid;
    /// [`MovieError::Setting`] or [`MovieError::FrameTooLarge`] for settings beyond the
    /// limits.
    pub fn from_animation(
        scene: Scene,
        animation: &Animation,
        settings: MovieSettings,
    ) -> Result<Movie, MovieError> {
        let frames = check_frames(settings.frames.unwrap_or(animation.frames))?;
        let fps = check_fps(settings.fps.unwrap_or(animation.fps))?;
        let (width, height) = (scene.camera().width(), scene.camera().height());
        let shots = (0..frames)
            .map(|k| {
                let t = frame_time(animation.ease, k, frames);
                camera_at(animation, t, width, height).map(|camera| {
                    vec![Shot {
                        camera,
                        caption: None,
                    }]
                })
            })
            .collect::<Result<Vec<_>, SceneError>>()?;
        Movie::new(scene, shots, fps, settings.with_diagram)
    }

    /// The movie of a built-in demo, its scene loaded with `options` (a picture size and
    /// samples per pixel instead of the demo's).
    ///
    /// # Errors
    /// [`MovieError::Scene`] for an invalid size or sample count;
    /// [`MovieError::Setting`] or [`MovieError::FrameTooLarge`] for settings beyond the
    /// limits.
    pub fn from_demo(
        demo: &Demo,
        options: LoadOptions,
        settings: MovieSettings,
    ) -> Result<Movie, MovieError> {
        let frames = check_frames(settings.frames.unwrap_or(demo.frames))?;
        let fps = check_fps(settings.fps.unwrap_or(demo.fps))?;
        let scene = demo.scene(options)?;
        let (width, height) = (scene.camera().width(), scene.camera().height());
        // Check the frame's size before computing thousands of cameras for it.
        let panels = demo.shots(0, frames, width, height).len();
        check_frame_size(width, height, panels, settings.with_diagram)?;
        let shots = (0..frames)
            .map(|k| demo.shots(k, frames, width, height))
            .collect();
        Movie::new(scene, shots, fps, settings.with_diagram)
    }

    fn new(
        scene: Scene,
        shots: Vec<Vec<Shot>>,
        fps: u32,
        with_diagram: bool,
    ) -> Result<Movie, MovieError> {
        let picture = (scene.camera().width(), scene.camera().height());
        let panels = shots.first().map_or(1, Vec::len);
        check_frame_size(picture.0, picture.1, panels, with_diagram)?;
        let diagram = with_diagram.then(|| {
            let cameras: Vec<Camera> = shots.iter().flatten().map(|shot| shot.camera).collect();
            (SideWindow::fit(&scene, &cameras), diagram_width(picture.1))
        });
        Ok(Movie {
            scene,
            shots,
            fps,
            picture,
            diagram,
        })
    }

    /// The number of frames.
    pub fn frames(&self) -> u32 {
        u32::try_from(self.shots.len()).expect("at most MAX_FRAMES frames")
    }

    /// Frames per second.
    pub fn fps(&self) -> u32 {
        self.fps
    }

    /// The scene (its own camera is the one it was loaded with; the frames' are
    /// [`Movie::shots`]).
    pub fn scene(&self) -> &Scene {
        &self.scene
    }

    /// The cameras of frame `frame`, left to right.
    ///
    /// # Panics
    /// If `frame` is not below [`Movie::frames`].
    pub fn shots(&self, frame: u32) -> &[Shot] {
        &self.shots[frame as usize]
    }

    /// The size of each picture: the render's size.
    pub fn picture_size(&self) -> (u32, u32) {
        self.picture
    }

    /// The size of a frame: the pictures side by side, each followed by its side view
    /// when there are side views.
    pub fn frame_size(&self) -> (u32, u32) {
        let panels = self.shots.first().map_or(1, Vec::len) as u32;
        let diagram = self.diagram.as_ref().map_or(0, |(_, width)| *width);
        (panels * (self.picture.0 + diagram), self.picture.1)
    }

    /// Renders frame `frame`: each picture rendered by `viewray-render` (its tiles in
    /// parallel, as `settings` says), its caption written over its top-left corner, its
    /// side view beside it. The pixels depend on the scene and `frame` alone.
    ///
    /// # Errors
    /// [`RenderError`] if the render's thread pool cannot start.
    ///
    /// # Panics
    /// If `frame` is not below [`Movie::frames`].
    pub fn render_frame(
        &self,
        frame: u32,
        settings: &RenderSettings,
    ) -> Result<RgbImage, RenderError> {
        let (frame_width, frame_height) = self.frame_size();
        let mut figure = Figure::new(frame_width, frame_height);
        let (width, height) = self.picture;
        let mut x = 0;
        for shot in self.shots(frame) {
            let scene = scene_with_camera(&self.scene, shot.camera);
            let rendered = render(&scene, settings, |_, _| {})?;
            let rgb = rendered.image.to_rgb_image();
            let rect = Rect::from_xywh(x as f32, 0.0, width as f32, height as f32);
            figure.push(Item::Image {
                pixels: rgba(&rgb),
                rect,
                sampling: Sampling::Nearest,
            });
            if let Some(caption) = &shot.caption {
                push_caption(&mut figure, caption, rect);
            }
            x += width;
            if let Some((window, diagram_width)) = &self.diagram {
                let diagram = side_view(
                    &self.scene,
                    &shot.camera,
                    window,
                    SideViewCanvas::Beside,
                    None,
                );
                figure.push(Item::Image {
                    pixels: raster::render_scaled(&diagram, diagram_scale(height)),
                    rect: Rect::from_xywh(x as f32, 0.0, *diagram_width as f32, height as f32),
                    sampling: Sampling::Nearest,
                });
                x += diagram_width;
            }
        }
        let pixels = raster::render(&figure);
        Ok(image::DynamicImage::ImageRgba8(pixels).to_rgb8())
    }
}

/// `scene` looking through `camera` instead of its own camera.
fn scene_with_camera(scene: &Scene, camera: Camera) -> Scene {
    scene.clone().with_camera(camera)
}

fn rgba(rgb: &RgbImage) -> RgbaImage {
    image::DynamicImage::ImageRgb8(rgb.clone()).to_rgba8()
}

/// How much a side view's canvas ([`SideViewCanvas::Beside`]) is scaled to stand beside
/// a picture `height` pixels tall.
fn diagram_scale(height: u32) -> f32 {
    height as f32 / SideViewCanvas::Beside.size().1 as f32
}

/// A side view's width beside a picture `height` pixels tall: its canvas's (16:9) at
/// [`diagram_scale`], rounded as `render_scaled` rounds it.
fn diagram_width(height: u32) -> u32 {
    (SideViewCanvas::Beside.size().0 as f32 * diagram_scale(height)).round() as u32
}

/// Writes `caption` over the top-left corner of `rect`, on a translucent white band so
/// that it reads over any picture; the text is 1/16 of the picture's height.
fn push_caption(figure: &mut Figure, caption: &str, rect: Rect) {
    let size = (rect.height() / 16.0).max(9.0);
    let margin = size * 0.4;
    let label = Label::new(caption, rect.min + Vec2::new(margin, margin))
        .with_size(size)
        .with_color(Color::from_hex(0x1A1A1A))
        .with_anchor(Anchor::Start, Baseline::Top);
    let band = label.bounds().expand(margin * 0.6);
    figure.push(Item::Polygon {
        points: vec![
            band.min,
            Vec2::new(band.max.x, band.min.y),
            band.max,
            Vec2::new(band.min.x, band.max.y),
        ],
        fill: Color::rgba(255, 255, 255, 190),
        stroke: None,
    });
    figure.push(label);
}

fn check_frames(frames: u32) -> Result<u32, MovieError> {
    if (1..=MAX_FRAMES).contains(&frames) {
        Ok(frames)
    } else {
        Err(MovieError::Setting(format!(
            "frames must be between 1 and {MAX_FRAMES}, found {frames}"
        )))
    }
}

fn check_fps(fps: u32) -> Result<u32, MovieError> {
    if (1..=MAX_FPS).contains(&fps) {
        Ok(fps)
    } else {
        Err(MovieError::Setting(format!(
            "fps must be between 1 and {MAX_FPS}, found {fps}"
        )))
    }
}

/// Refuses a frame of `panels` pictures of `width x height` (each with a side view when
/// `with_diagram`) of more than [`MAX_FRAME_PIXELS`].
fn check_frame_size(
    width: u32,
    height: u32,
    panels: usize,
    with_diagram: bool,
) -> Result<(), MovieError> {
    let diagram = if with_diagram {
        u64::from(diagram_width(height))
    } else {
        0
    };
    let frame_width = panels as u64 * (u64::from(width) + diagram);
    let frame_height = u64::from(height);
    if frame_width * frame_height > MAX_FRAME_PIXELS {
        return Err(MovieError::FrameTooLarge {
            width: frame_width,
            height: frame_height,
            with_diagram,
        });
    }
    Ok(())
}

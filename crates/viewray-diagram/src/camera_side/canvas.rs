//! The canvases a side view is drawn on, and where each puts the drawing and caption.

use glam::Vec2;
use viewray_draw::Rect;

use crate::style;

/// The canvases a side view is drawn on.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum SideViewCanvas {
    /// A slide, 1600 x 900, with a title: for `viewray diagram`.
    #[default]
    Slide,
    /// A panel beside a render, 1000 x 600, without a title: the same labels read
    /// larger when the panel is shown at half a screen's width (the live playground).
    Panel,
    /// A 16:9 panel beside an animation's picture, 1280 x 720, without a title, the
    /// drawing filling it: painted at the picture's height
    /// ([`render_scaled`](viewray_draw::raster::render_scaled)), every line and label
    /// shrinks with it.
    Beside,
}

/// Where a canvas puts things.
pub(super) struct Layout {
    /// Where the drawing goes (all of the canvas but the title and caption, if apart).
    pub(super) drawing: Rect,
    /// Where the caption's first baseline starts.
    pub(super) caption_at: Vec2,
    /// Whether there is a title.
    pub(super) title: bool,
}

impl SideViewCanvas {
    /// The canvas size in pixels.
    pub fn size(self) -> (u32, u32) {
        match self {
            SideViewCanvas::Slide => style::SLIDE,
            SideViewCanvas::Panel => (1000, 600),
            SideViewCanvas::Beside => (1280, 720),
        }
    }

    /// Where this canvas puts the drawing and the caption.
    pub(super) fn layout(self) -> Layout {
        match self {
            SideViewCanvas::Slide => Layout {
                drawing: Rect::from_corners(Vec2::new(40.0, 100.0), Vec2::new(1560.0, 800.0)),
                caption_at: Vec2::new(56.0, 858.0),
                title: true,
            },
            SideViewCanvas::Panel => Layout {
                drawing: Rect::from_corners(Vec2::new(50.0, 50.0), Vec2::new(950.0, 490.0)),
                caption_at: Vec2::new(24.0, 540.0),
                title: false,
            },
            SideViewCanvas::Beside => Layout {
                drawing: Rect::from_xywh(0.0, 0.0, 1280.0, 720.0),
                caption_at: Vec2::new(20.0, 700.0),
                title: false,
            },
        }
    }
}

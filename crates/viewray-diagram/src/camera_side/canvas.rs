//! The canvases a side view is drawn on, and where each puts the drawing and caption.

use glam::Vec2;
use viewray_draw::Rect;

use crate::sketch::LINE_SPACING;
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
    /// A square panel, 800 x 800, without a title: for a top view, whose window is as
    /// deep as it is wide, beside the side view (the live playground).
    Square,
    /// A panel of the given size in pixels, without a title, for a box on a screen whose
    /// shape is known (the live playground's views): the drawing fills it above a caption
    /// as on [`SideViewCanvas::Panel`], whose margins and label sizes it keeps, so that a
    /// box shown at a given height reads the same whatever its width. Ask for about 600
    /// pixels tall, at least 300 by 300.
    Fitted {
        /// The width in pixels.
        width: u32,
        /// The height in pixels.
        height: u32,
    },
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
    /// Where the caption's first baseline starts (beside a picture: its last, the
    /// caption growing upwards over the drawing).
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
            SideViewCanvas::Square => (800, 800),
            SideViewCanvas::Fitted { width, height } => (width, height),
            SideViewCanvas::Beside => (1280, 720),
        }
    }

    /// The caption's left edge, which is also its margin on the right.
    pub(super) fn caption_left(self) -> f32 {
        match self {
            SideViewCanvas::Slide => 56.0,
            SideViewCanvas::Panel | SideViewCanvas::Square | SideViewCanvas::Fitted { .. } => 24.0,
            SideViewCanvas::Beside => 20.0,
        }
    }

    /// Where this canvas puts the drawing and a caption of `lines` lines: a caption
    /// longer than the canvas's usual one (one line on a slide, two on a panel or a
    /// square) takes
    /// its room from the drawing's bottom.
    pub(super) fn layout(self, lines: usize) -> Layout {
        let extra = |usual: usize| {
            lines.saturating_sub(usual) as f32 * LINE_SPACING * style::SMALL_LABEL_SIZE
        };
        let left = self.caption_left();
        match self {
            SideViewCanvas::Slide => Layout {
                drawing: Rect::from_corners(
                    Vec2::new(40.0, 100.0),
                    Vec2::new(1560.0, 800.0 - extra(1)),
                ),
                caption_at: Vec2::new(left, 858.0 - extra(1)),
                title: true,
            },
            SideViewCanvas::Panel => Layout {
                drawing: Rect::from_corners(
                    Vec2::new(50.0, 50.0),
                    Vec2::new(950.0, 490.0 - extra(2)),
                ),
                caption_at: Vec2::new(left, 540.0 - extra(2)),
                title: false,
            },
            SideViewCanvas::Fitted { width, height } => {
                let (width, height) = (width as f32, height as f32);
                Layout {
                    drawing: Rect::from_corners(
                        Vec2::new(50.0, 50.0),
                        // A long caption on a narrow panel leaves the drawing 100 tall.
                        Vec2::new(width - 50.0, (height - 110.0 - extra(2)).max(150.0)),
                    ),
                    caption_at: Vec2::new(left, height - 60.0 - extra(2)),
                    title: false,
                }
            }
            SideViewCanvas::Square => Layout {
                drawing: Rect::from_corners(
                    Vec2::new(40.0, 40.0),
                    Vec2::new(760.0, 640.0 - extra(2)),
                ),
                caption_at: Vec2::new(left, 690.0 - extra(2)),
                title: false,
            },
            SideViewCanvas::Beside => Layout {
                drawing: Rect::from_xywh(0.0, 0.0, 1280.0, 720.0),
                caption_at: Vec2::new(left, 700.0),
                title: false,
            },
        }
    }
}

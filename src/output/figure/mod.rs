//! Figures, SVG or PNG: what a figure is, and what every figure shares.
//!
//! A [`Figure`] knows its size before it is drawn — its legends and keys are
//! laid out first ([`legend`], [`layout`]) and the image grows to hold them —
//! and draws itself on any plotters backend; [`save`] picks the backend by
//! the file's extension ([`backend`]). Categories are coloured by
//! [`palette`]. One file per figure:
//!
//! * [`orbit`] — a motion's time history in six panels (the paper's Figs. 12–16);
//! * [`sweep`] — a sweep's bifurcation diagram (Figs. 9–10) or frequency
//!   response ([`sweep_panels`]), its branches drawn by [`branch`], its
//!   bifurcations marked by [`symbol`];
//! * [`map`] — a parameter map (Fig. 11), optionally with exact curves over it;
//! * [`regime`] — a regime map from curves alone: regions filled and
//!   numbered, curves by kind, codimension-two points marked;
//! * [`basins`] — basins of attraction over the starts `(x, v)`;
//! * [`diagram`] — an orbit diagram: stroboscopic samples swept up and down, exponents, branches;
//! * [`trade`] — error against computing time.

pub mod backend;
pub mod basins;
pub mod branch;
pub mod diagram;
pub mod law;
pub mod layout;
pub mod legend;
pub mod map;
pub mod orbit;
pub mod palette;
pub mod regime;
pub mod sweep;
pub mod sweep_panels;
pub mod symbol;
pub mod trade;

use plotters::coord::Shift;
use plotters::prelude::*;

pub use backend::{register, save, DrawError, Format, FAMILY};

use layout::Rect;
use legend::Legend;

/// A figure: its size in pixels, known before drawing, and its drawing.
pub trait Figure {
    /// Width and height in pixels.
    fn size(&self) -> (u32, u32);
    /// Draw on `root`, an area of [`Figure::size`].
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError>;
}

/// Text size of a figure's title.
const TITLE_SIZE: u32 = 22;
/// Text size of a panel's caption.
const CAPTION_SIZE: u32 = 18;
/// Text size of tick labels.
const TICK_SIZE: u32 = 13;
/// Text size of axis names.
const AXIS_SIZE: u32 = 15;
/// Light grey of the fine grid.
const LIGHT_GRID: RGBColor = RGBColor(238, 238, 238);
/// Grey of dashed reference lines and their labels.
const REFERENCE_GREY: RGBColor = RGBColor(110, 110, 110);

/// The pixels of `area` (for a chart: its plotting area).
fn pixels<DB: DrawingBackend, CT: CoordTranslate>(area: &DrawingArea<DB, CT>) -> Rect {
    let (x, y) = area.get_pixel_range();
    Rect {
        x0: x.start,
        y0: y.start,
        x1: x.end,
        y1: y.end,
    }
}

/// Where a legend sits over a chart.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum Corner {
    UpperLeft,
    UpperRight,
    Middle,
}

/// Draw `legend` over the plotting area `plot` (pixels of `root`) at
/// `corner`, wrapped to fit the area's width.
fn overlay<DB: DrawingBackend>(
    legend: &Legend,
    root: &DrawingArea<DB, Shift>,
    plot: Rect,
    corner: Corner,
) -> Result<(), DrawError> {
    const INSET: i32 = 10;
    let layout = legend.layout(plot.x1 - plot.x0 - 2 * INSET);
    let (w, h) = (layout.bounds.x1, layout.bounds.y1);
    let origin = match corner {
        Corner::UpperLeft => (plot.x0 + INSET, plot.y0 + INSET),
        Corner::UpperRight => (plot.x1 - INSET - w, plot.y0 + INSET),
        Corner::Middle => ((plot.x0 + plot.x1 - w) / 2, (plot.y0 + plot.y1 - h) / 2),
    };
    legend.draw(&layout, root, origin)
}

//! Figures of a time history (SPEC §8, the paper's Figs. 12–16), drawn with
//! `plotters`: six panels — the phase plane `(x, v)`, the friction force
//! along displacement and along velocity, `x(t)`, `v(t)` and `x''(t)`. Each
//! piece is coloured by its domain (stick in black), switching points are
//! marked with circles, the start point filled; the boundaries are dashed
//! lines, labelled, in the panels with a velocity axis.
//!
//! SVG or PNG, by the file's extension. Text is set in DejaVu Sans, shipped
//! in `assets/fonts` and compiled in, so neither backend needs system font
//! libraries.

use std::path::Path;
use std::sync::OnceLock;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use plotters::style::{register_font, FontStyle};

use crate::output::report::{History, Sample};

/// DejaVu Sans (Bitstream Vera licence, see `assets/fonts/LICENSE-DejaVu`).
static FONT: &[u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
/// The font family the figures use (registered by [`register`]).
pub const FAMILY: &str = "sans-serif";

/// Register the built-in font as `sans-serif` for plotters (once; later
/// calls return the first result). Every figure of this crate draws its text
/// with it, so call this before drawing.
pub fn register() -> Result<(), String> {
    static DONE: OnceLock<Result<(), String>> = OnceLock::new();
    DONE.get_or_init(|| {
        register_font(FAMILY, FontStyle::Normal, FONT)
            .map_err(|_| "the built-in font could not be loaded".to_string())
    })
    .clone()
}

/// The figure formats, by extension.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// `.svg`
    Svg,
    /// `.png`
    Png,
}

impl Format {
    /// The format of `path`, from its extension.
    pub fn of(path: &Path) -> Result<Self, String> {
        match path
            .extension()
            .and_then(|e| e.to_str())
            .map(|e| e.to_ascii_lowercase())
            .as_deref()
        {
            Some("svg") => Ok(Format::Svg),
            Some("png") => Ok(Format::Png),
            _ => Err(format!(
                "`{}`: unknown figure format; use a file name ending in .svg or .png",
                path.display()
            )),
        }
    }
}

/// The six panels' titles, in drawing order (left to right, top to bottom).
pub const PANEL_TITLES: [&str; 6] = [
    "phase plane (x, v)",
    "friction force along displacement",
    "friction force along velocity",
    "displacement x(t)",
    "velocity v(t)",
    "acceleration x''(t)",
];

const WIDTH: u32 = 1200;
const HEIGHT: u32 = 1320;

/// Where a panel's velocity axis is, for the boundary lines.
#[derive(Clone, Copy, PartialEq)]
enum VelocityAxis {
    None,
    Vertical,
    Horizontal,
}

struct Panel {
    title: &'static str,
    x_desc: &'static str,
    y_desc: &'static str,
    fx: fn(&Sample) -> f64,
    fy: fn(&Sample) -> f64,
    velocity: VelocityAxis,
    legend: bool,
}

fn panels() -> [Panel; 6] {
    [
        Panel {
            title: PANEL_TITLES[0],
            x_desc: "x",
            y_desc: "v",
            fx: |s| s.x,
            fy: |s| s.v,
            velocity: VelocityAxis::Vertical,
            legend: true,
        },
        Panel {
            title: PANEL_TITLES[1],
            x_desc: "x",
            y_desc: "F (per unit mass)",
            fx: |s| s.x,
            fy: |s| s.friction,
            velocity: VelocityAxis::None,
            legend: false,
        },
        Panel {
            title: PANEL_TITLES[2],
            x_desc: "v",
            y_desc: "F (per unit mass)",
            fx: |s| s.v,
            fy: |s| s.friction,
            velocity: VelocityAxis::Horizontal,
            legend: false,
        },
        Panel {
            title: PANEL_TITLES[3],
            x_desc: "t",
            y_desc: "x",
            fx: |s| s.t,
            fy: |s| s.x,
            velocity: VelocityAxis::None,
            legend: false,
        },
        Panel {
            title: PANEL_TITLES[4],
            x_desc: "t",
            y_desc: "v",
            fx: |s| s.t,
            fy: |s| s.v,
            velocity: VelocityAxis::Vertical,
            legend: false,
        },
        Panel {
            title: PANEL_TITLES[5],
            x_desc: "t",
            y_desc: "x''",
            fx: |s| s.t,
            fy: |s| s.a,
            velocity: VelocityAxis::None,
            legend: false,
        },
    ]
}

/// Colour of a domain label (0: stick).
fn colour(label: u32) -> RGBColor {
    const PALETTE: [RGBColor; 9] = [
        RGBColor(31, 119, 180),
        RGBColor(214, 39, 40),
        RGBColor(44, 160, 44),
        RGBColor(255, 127, 14),
        RGBColor(148, 103, 189),
        RGBColor(140, 86, 75),
        RGBColor(227, 119, 194),
        RGBColor(188, 189, 34),
        RGBColor(23, 190, 207),
    ];
    if label == 0 {
        BLACK
    } else {
        PALETTE[(label as usize - 1) % PALETTE.len()]
    }
}

fn legend_name(label: u32) -> String {
    if label == 0 {
        "stick".to_string()
    } else {
        format!("Ω{label}")
    }
}

/// `[lo, hi]` with a margin, widened to include `extra`, never empty.
fn range(values: impl Iterator<Item = f64>, extra: &[f64]) -> (f64, f64) {
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for v in values.chain(extra.iter().copied()) {
        if v.is_finite() {
            lo = lo.min(v);
            hi = hi.max(v);
        }
    }
    if !(lo.is_finite() && hi.is_finite()) {
        return (-1.0, 1.0);
    }
    let span = hi - lo;
    let pad = if span > 0.0 {
        0.06 * span
    } else {
        0.5 * lo.abs().max(1.0)
    };
    (lo - pad, hi + pad)
}

/// Draw `history` into `path` (SVG or PNG by extension), with `title` on top.
pub fn plot(history: &History, title: &str, path: &Path) -> Result<(), String> {
    let format = Format::of(path)?;
    register()?;
    let fail = |e: String| format!("cannot draw `{}`: {e}", path.display());
    match format {
        Format::Svg => {
            let root = SVGBackend::new(path, (WIDTH, HEIGHT)).into_drawing_area();
            draw(&root, history, title).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, (WIDTH, HEIGHT)).into_drawing_area();
            draw(&root, history, title).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    history: &History,
    title: &str,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let body = root.titled(title, (FAMILY, 22).into_font()).map_err(err)?;
    let areas = body.split_evenly((3, 2));
    let boundary_vs: Vec<f64> = history.boundaries.iter().map(|b| b.1).collect();
    let grey = RGBColor(110, 110, 110);
    for (panel, area) in panels().iter().zip(areas.iter()) {
        let xs = history.samples().map(panel.fx);
        let ys = history.samples().map(panel.fy);
        let (x_extra, y_extra): (&[f64], &[f64]) = match panel.velocity {
            VelocityAxis::Vertical => (&[], &boundary_vs),
            VelocityAxis::Horizontal => (&boundary_vs, &[]),
            VelocityAxis::None => (&[], &[]),
        };
        let (x0, x1) = range(xs, x_extra);
        let (y0, y1) = range(ys, y_extra);
        let mut chart = ChartBuilder::on(area)
            .caption(panel.title, (FAMILY, 18).into_font())
            .margin(12)
            .x_label_area_size(42)
            .y_label_area_size(62)
            .build_cartesian_2d(x0..x1, y0..y1)
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(238, 238, 238))
            .bold_line_style(RGBColor(215, 215, 215))
            .x_desc(panel.x_desc)
            .y_desc(panel.y_desc)
            .label_style((FAMILY, 13).into_font())
            .axis_desc_style((FAMILY, 15).into_font())
            .draw()
            .map_err(err)?;
        // Boundaries, dashed and labelled (a label too close to the previous
        // one, which would overprint it, is left out).
        let mut last_label: Option<f64> = None;
        for &(label, v) in &history.boundaries {
            let (line, at, pos) = match panel.velocity {
                VelocityAxis::None => continue,
                VelocityAxis::Vertical => (
                    vec![(x0, v), (x1, v)],
                    (x1 - 0.01 * (x1 - x0), v),
                    Pos::new(HPos::Right, VPos::Bottom),
                ),
                VelocityAxis::Horizontal => (
                    vec![(v, y0), (v, y1)],
                    (v, y1 - 0.01 * (y1 - y0)),
                    Pos::new(HPos::Left, VPos::Top),
                ),
            };
            chart
                .draw_series(DashedLineSeries::new(line, 7, 5, grey.stroke_width(1)))
                .map_err(err)?;
            let (span, gap) = match panel.velocity {
                VelocityAxis::Horizontal => (x1 - x0, 0.05),
                _ => (y1 - y0, 0.035),
            };
            if last_label.is_some_and(|w| (v - w).abs() < gap * span) {
                continue;
            }
            last_label = Some(v);
            let name = label
                .strip_prefix("Sigma")
                .map_or_else(|| label.to_string(), |n| format!("Σ{n}"));
            // Boundaries across the velocity axis lie close together: name only.
            let text = if panel.velocity == VelocityAxis::Horizontal {
                format!(" {name}")
            } else {
                format!(" {name} (v = {v}) ")
            };
            chart
                .draw_series(std::iter::once(Text::new(
                    text,
                    at,
                    (FAMILY, 13).into_font().color(&grey).pos(pos),
                )))
                .map_err(err)?;
        }
        // The motion, piece by piece, coloured by domain.
        let mut labelled: Vec<u32> = Vec::new();
        for piece in &history.pieces {
            let c = colour(piece.label);
            let series = chart
                .draw_series(LineSeries::new(
                    piece.samples.iter().map(|s| ((panel.fx)(s), (panel.fy)(s))),
                    c.stroke_width(2),
                ))
                .map_err(err)?;
            if panel.legend && !labelled.contains(&piece.label) {
                labelled.push(piece.label);
                series
                    .label(legend_name(piece.label))
                    .legend(move |(x, y)| {
                        PathElement::new(vec![(x, y), (x + 22, y)], c.stroke_width(3))
                    });
            }
        }
        // Switching points (hollow) and the start point (filled).
        let marks = history
            .pieces
            .iter()
            .skip(1)
            .filter(|p| p.switching)
            .filter_map(|p| p.samples.first())
            .map(|s| Circle::new(((panel.fx)(s), (panel.fy)(s)), 4, BLACK.stroke_width(1)));
        chart.draw_series(marks).map_err(err)?;
        if let Some(s) = history.pieces.first().and_then(|p| p.samples.first()) {
            chart
                .draw_series(std::iter::once(Circle::new(
                    ((panel.fx)(s), (panel.fy)(s)),
                    5,
                    BLACK.filled(),
                )))
                .map_err(err)?;
        }
        if panel.legend {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::MiddleMiddle)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .label_font((FAMILY, 13).into_font())
                .draw()
                .map_err(err)?;
        }
    }
    Ok(())
}

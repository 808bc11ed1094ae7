//! Figures of a time history (SPEC §8, the paper's Figs. 12–16): six panels
//! — the phase plane `(x, v)`, the friction force along displacement and
//! along velocity, `x(t)`, `v(t)` and `x''(t)`. Each piece is coloured by its
//! domain (stick in black), switching points are marked with circles, the
//! start point filled; the boundaries are dashed lines, labelled, in the
//! panels with a velocity axis.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::legend::{Entry, Legend, Mark};
use super::palette::category;
use super::{
    overlay, pixels, save, Corner, DrawError, Figure, AXIS_SIZE, CAPTION_SIZE, FAMILY, LIGHT_GRID,
    REFERENCE_GREY, TICK_SIZE, TITLE_SIZE,
};
use crate::output::history::{History, Sample};

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

/// A quantity of a sample, and its axis name.
#[derive(Clone, Copy)]
enum Quantity {
    T,
    X,
    V,
    A,
    F,
}

impl Quantity {
    fn of(self, s: &Sample) -> f64 {
        match self {
            Quantity::T => s.t,
            Quantity::X => s.x,
            Quantity::V => s.v,
            Quantity::A => s.a,
            Quantity::F => s.friction,
        }
    }

    fn name(self) -> &'static str {
        match self {
            Quantity::T => "t",
            Quantity::X => "x",
            Quantity::V => "v",
            Quantity::A => "x''",
            Quantity::F => "F (per unit mass)",
        }
    }
}

/// The panels' axes, in the order of [`PANEL_TITLES`].
const AXES: [(Quantity, Quantity); 6] = [
    (Quantity::X, Quantity::V),
    (Quantity::X, Quantity::F),
    (Quantity::V, Quantity::F),
    (Quantity::T, Quantity::X),
    (Quantity::T, Quantity::V),
    (Quantity::T, Quantity::A),
];

/// Where a panel's velocity axis is, for the boundary lines.
#[derive(Clone, Copy, PartialEq)]
enum VelocityAxis {
    None,
    Vertical,
    Horizontal,
}

impl VelocityAxis {
    fn of((x, y): (Quantity, Quantity)) -> Self {
        match (x, y) {
            (_, Quantity::V) => VelocityAxis::Vertical,
            (Quantity::V, _) => VelocityAxis::Horizontal,
            _ => VelocityAxis::None,
        }
    }
}

/// Colour of a domain label (0: stick).
fn colour(label: u32) -> RGBColor {
    match label {
        0 => BLACK,
        k => category(k as usize - 1),
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

/// The six panels of a time history.
pub struct OrbitFigure<'a> {
    history: &'a History,
    title: &'a str,
    legend: Legend,
}

impl<'a> OrbitFigure<'a> {
    /// The figure of `history`, with `title` on top.
    pub fn new(history: &'a History, title: &'a str) -> Self {
        // The domains in order of first visit.
        let mut labels: Vec<u32> = Vec::new();
        for piece in &history.pieces {
            if !labels.contains(&piece.label) {
                labels.push(piece.label);
            }
        }
        let entries = labels
            .into_iter()
            .map(|l| Entry::new(Mark::Line(colour(l)), legend_name(l)))
            .collect();
        Self {
            history,
            title,
            legend: Legend::new(None, entries, TICK_SIZE, true),
        }
    }
}

/// Draw `history` into `path` (SVG or PNG by extension), with `title` on top.
pub fn plot(history: &History, title: &str, path: &Path) -> Result<(), String> {
    save(&OrbitFigure::new(history, title), path)
}

impl Figure for OrbitFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (WIDTH, HEIGHT)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let history = self.history;
        root.fill(&WHITE)?;
        let body = root.titled(self.title, (FAMILY, TITLE_SIZE).into_font())?;
        let areas = body.split_evenly((3, 2));
        let boundary_vs: Vec<f64> = history.boundaries.iter().map(|b| b.1).collect();
        for (k, area) in areas.iter().enumerate() {
            let (qx, qy) = AXES[k];
            let velocity = VelocityAxis::of(AXES[k]);
            let (fx, fy) = (|s: &Sample| qx.of(s), |s: &Sample| qy.of(s));
            let (x_extra, y_extra): (&[f64], &[f64]) = match velocity {
                VelocityAxis::Vertical => (&[], &boundary_vs),
                VelocityAxis::Horizontal => (&boundary_vs, &[]),
                VelocityAxis::None => (&[], &[]),
            };
            let (x0, x1) = range(history.samples().map(fx), x_extra);
            let (y0, y1) = range(history.samples().map(fy), y_extra);
            let mut chart = ChartBuilder::on(area)
                .caption(PANEL_TITLES[k], (FAMILY, CAPTION_SIZE).into_font())
                .margin(12)
                .x_label_area_size(42)
                .y_label_area_size(62)
                .build_cartesian_2d(x0..x1, y0..y1)?;
            chart
                .configure_mesh()
                .light_line_style(LIGHT_GRID)
                .bold_line_style(RGBColor(215, 215, 215))
                .x_desc(qx.name())
                .y_desc(qy.name())
                .label_style((FAMILY, TICK_SIZE).into_font())
                .axis_desc_style((FAMILY, AXIS_SIZE).into_font())
                .draw()?;
            // Boundaries, dashed and labelled (a label too close to the
            // previous one, which would overprint it, is left out).
            let mut last_label: Option<f64> = None;
            for &(label, v) in &history.boundaries {
                let (line, at, pos) = match velocity {
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
                chart.draw_series(DashedLineSeries::new(
                    line,
                    7,
                    5,
                    REFERENCE_GREY.stroke_width(1),
                ))?;
                let (span, gap) = match velocity {
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
                let text = if velocity == VelocityAxis::Horizontal {
                    format!(" {name}")
                } else {
                    format!(" {name} (v = {v}) ")
                };
                chart.draw_series(std::iter::once(Text::new(
                    text,
                    at,
                    (FAMILY, TICK_SIZE)
                        .into_font()
                        .color(&REFERENCE_GREY)
                        .pos(pos),
                )))?;
            }
            // The motion, piece by piece, coloured by domain.
            for piece in &history.pieces {
                chart.draw_series(LineSeries::new(
                    piece.samples.iter().map(|s| (fx(s), fy(s))),
                    colour(piece.label).stroke_width(2),
                ))?;
            }
            // Switching points (hollow) and the start point (filled).
            let marks = history
                .pieces
                .iter()
                .skip(1)
                .filter(|p| p.switching)
                .filter_map(|p| p.samples.first())
                .map(|s| Circle::new((fx(s), fy(s)), 4, BLACK.stroke_width(1)));
            chart.draw_series(marks)?;
            if let Some(s) = history.pieces.first().and_then(|p| p.samples.first()) {
                chart.draw_series(std::iter::once(Circle::new(
                    (fx(s), fy(s)),
                    5,
                    BLACK.filled(),
                )))?;
            }
            if k == 0 {
                overlay(
                    &self.legend,
                    root,
                    pixels(chart.plotting_area()),
                    Corner::Middle,
                )?;
            }
        }
        Ok(())
    }
}

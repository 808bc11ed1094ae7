//! The trade's figure: error against computing time, one point per piece
//! count and per integrator tolerance (log–log).

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::legend::{Entry, Legend, Mark};
use super::palette::category;
use super::{overlay, pixels, save, Corner, DrawError, Figure, AXIS_SIZE, FAMILY, TICK_SIZE};
use crate::study::trade::Trade;

/// The trade's figure.
pub struct TradeFigure<'a> {
    trade: &'a Trade,
    legend: Legend,
}

/// The two series: the N-piece predictions, the integrator's ladder.
const SERIES: [(bool, &str); 2] = [
    (true, "N-piece analytical prediction"),
    (false, "integrator, tolerance ladder"),
];

impl<'a> TradeFigure<'a> {
    /// The figure of `trade`.
    pub fn new(trade: &'a Trade) -> Self {
        let entries = SERIES
            .iter()
            .enumerate()
            .map(|(k, &(_, name))| Entry::new(Mark::Dot(colour(k)), name))
            .collect();
        Self {
            trade,
            legend: Legend::new(None, entries, TICK_SIZE, true),
        }
    }
}

/// Series `k`'s colour (blue, red).
fn colour(k: usize) -> RGBColor {
    category(3 * k)
}

/// Error against time, log–log, into `path` (SVG or PNG).
pub fn plot_trade(t: &Trade, path: &Path) -> Result<(), String> {
    save(&TradeFigure::new(t), path)
}

impl Figure for TradeFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (900, 650)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let t = self.trade;
        root.fill(&WHITE)?;
        let pts: Vec<(f64, f64, String, bool)> = t
            .rows
            .iter()
            .filter(|r| {
                r.error.is_finite() && r.error > 0.0 && r.seconds.is_finite() && r.seconds > 0.0
            })
            .map(|r| {
                let label = match (r.pieces, r.tol) {
                    (Some(n), _) => format!("N = {n}"),
                    (_, Some(tol)) => format!("tol {tol:e}"),
                    _ => String::new(),
                };
                (r.seconds * 1e3, r.error, label, r.pieces.is_some())
            })
            .collect();
        let (mut x0, mut x1, mut y0, mut y1) = (
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::INFINITY,
            f64::NEG_INFINITY,
        );
        for p in &pts {
            x0 = x0.min(p.0);
            x1 = x1.max(p.0);
            y0 = y0.min(p.1);
            y1 = y1.max(p.1);
        }
        if pts.is_empty() {
            (x0, x1, y0, y1) = (1e-3, 1.0, 1e-12, 1.0);
        }
        let title = format!("{}: error against computing time", t.model);
        let mut chart = ChartBuilder::on(root)
            .caption(title, (FAMILY, 20).into_font())
            .margin(16)
            .x_label_area_size(45)
            .y_label_area_size(70)
            .build_cartesian_2d(
                (x0 / 2.0..x1 * 2.0).log_scale(),
                (y0 / 5.0..y1 * 5.0).log_scale(),
            )?;
        chart
            .configure_mesh()
            .x_desc("time [ms]")
            .y_label_formatter(&|v| format!("{v:.0e}"))
            .x_label_formatter(&|v| format!("{v}"))
            .y_desc("largest error (switching points, amplitude)")
            .label_style((FAMILY, TICK_SIZE).into_font())
            .axis_desc_style((FAMILY, AXIS_SIZE).into_font())
            .draw()?;
        for (k, &(pieces, _)) in SERIES.iter().enumerate() {
            let c = colour(k);
            let series: Vec<(f64, f64)> = pts
                .iter()
                .filter(|p| p.3 == pieces)
                .map(|p| (p.0, p.1))
                .collect();
            chart.draw_series(LineSeries::new(series.clone(), c.stroke_width(1)))?;
            chart.draw_series(series.into_iter().map(|p| Circle::new(p, 4, c.filled())))?;
        }
        for p in &pts {
            chart.draw_series(std::iter::once(Text::new(
                format!(" {}", p.2),
                (p.0, p.1),
                (FAMILY, 12).into_font(),
            )))?;
        }
        overlay(
            &self.legend,
            root,
            pixels(chart.plotting_area()),
            Corner::UpperRight,
        )
    }
}

//! The figure of a smooth law's sweep: steady sliding's rest position and
//! every cycle's point on the section `v = 0` against the parameter, stable
//! and unstable, with the Hopf points and the stick-slip cycle's ends.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use super::legend::{Entry, Legend, Mark};
use super::palette::category;
use super::{
    overlay, pixels, save, Corner, DrawError, Figure, AXIS_SIZE, FAMILY, REFERENCE_GREY, TICK_SIZE,
};
use crate::orbit::equilibrium::Verdict;
use crate::study::law::LawSweep;

/// The law's bifurcation diagram.
pub struct LawFigure<'a> {
    sweep: &'a LawSweep,
    legend: Legend,
}

/// Steady sliding's colour.
fn rest() -> RGBColor {
    category(0)
}

/// The stick-slip cycle's colour.
fn stick_slip() -> RGBColor {
    category(3)
}

/// A slip cycle's colour.
fn slip() -> RGBColor {
    category(6)
}

impl<'a> LawFigure<'a> {
    /// The figure of `sweep`.
    pub fn new(sweep: &'a LawSweep) -> Self {
        let entries = vec![
            Entry::new(Mark::Line(rest()), "steady sliding, stable"),
            Entry::new(Mark::Dashed(rest()), "steady sliding, unstable"),
            Entry::new(Mark::Dot(stick_slip()), "stick-slip cycle"),
            Entry::new(Mark::Dot(slip()), "slip cycle, stable"),
            Entry::new(Mark::Hollow(slip()), "slip cycle, unstable"),
            Entry::new(
                Mark::Dashed(REFERENCE_GREY),
                "Hopf point; stick-slip cycle's end",
            ),
        ];
        Self {
            sweep,
            legend: Legend::new(None, entries, TICK_SIZE, true),
        }
    }
}

/// The law's sweep drawn into `path` (SVG or PNG).
pub fn plot_law_sweep(sweep: &LawSweep, path: &Path) -> Result<(), String> {
    save(&LawFigure::new(sweep), path)
}

impl Figure for LawFigure<'_> {
    fn size(&self) -> (u32, u32) {
        (1000, 650)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let s = self.sweep;
        root.fill(&WHITE)?;
        let rests: Vec<(f64, f64, bool)> = s
            .points
            .iter()
            .filter_map(|p| {
                let e = p.rest.equilibrium?;
                Some((p.rest.value, e.x, e.verdict == Verdict::Stable))
            })
            .collect();
        let cycles: Vec<(f64, f64, bool, bool)> = s
            .points
            .iter()
            .flat_map(|p| {
                p.cycles.iter().map(move |c| {
                    (
                        p.rest.value,
                        c.x,
                        c.stick > 0.0,
                        c.verdict == Verdict::Stable,
                    )
                })
            })
            .collect();
        let xs = s.points.iter().map(|p| p.rest.value);
        let (x0, x1) = xs.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        let ys = rests.iter().map(|r| r.1).chain(cycles.iter().map(|c| c.1));
        let (y0, y1) = ys.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
        let (x0, x1) = if x1 > x0 {
            (x0, x1)
        } else {
            (x0 - 1.0, x0 + 1.0)
        };
        let (y0, y1) = if y1 > y0 {
            (y0, y1)
        } else if y0.is_finite() {
            (y0 - 1.0, y0 + 1.0)
        } else {
            (0.0, 1.0)
        };
        let pad = 0.08 * (y1 - y0);
        let title = format!(
            "{}: steady sliding and the cycles on v = 0 along {}",
            s.model, s.param
        );
        let mut chart = ChartBuilder::on(root)
            .caption(title, (FAMILY, 20).into_font())
            .margin(16)
            .x_label_area_size(45)
            .y_label_area_size(70)
            // Headroom above the data for the legend.
            .build_cartesian_2d(x0..x1, (y0 - pad)..(y1 + 4.0 * pad))?;
        chart
            .configure_mesh()
            .x_desc(s.param.as_str())
            .y_desc("x (rest position; cycle's largest displacement, on v = 0)")
            .label_style((FAMILY, TICK_SIZE).into_font())
            .axis_desc_style((FAMILY, AXIS_SIZE).into_font())
            .draw()?;
        // Steady sliding: solid where stable, dashed where not, split where
        // the stability changes.
        for w in rests.windows(2) {
            let segment = vec![(w[0].0, w[0].1), (w[1].0, w[1].1)];
            if w[0].2 && w[1].2 {
                chart.draw_series(LineSeries::new(segment, rest().stroke_width(2)))?;
            } else {
                chart.draw_series(DashedLineSeries::new(segment, 8, 5, rest().stroke_width(2)))?;
            }
        }
        for &(v, x, sticks, stable) in &cycles {
            let c = if sticks { stick_slip() } else { slip() };
            let style = if stable {
                c.filled()
            } else {
                c.stroke_width(2)
            };
            chart.draw_series(std::iter::once(Circle::new((v, x), 4, style)))?;
        }
        let at: Vec<(f64, &str)> = s
            .changes
            .iter()
            .map(|c| (c.change.at, "Hopf"))
            .chain(s.stick_slip.iter().map(|e| (e.at, "stick-slip end")))
            .collect();
        for (v, label) in at {
            chart.draw_series(DashedLineSeries::new(
                vec![(v, y0 - pad), (v, y1 + 4.0 * pad)],
                6,
                4,
                REFERENCE_GREY.stroke_width(1),
            ))?;
            chart.draw_series(std::iter::once(Text::new(
                format!(" {label} {v:.6}"),
                (v, y0 - 0.5 * pad),
                (FAMILY, 12).into_font(),
            )))?;
        }
        overlay(
            &self.legend,
            root,
            pixels(chart.plotting_area()),
            Corner::UpperLeft,
        )
    }
}

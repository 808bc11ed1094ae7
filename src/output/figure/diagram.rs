//! The figure of an orbit diagram: three panels over the parameter, one
//! above the other — the stroboscopic samples of `x`, those of `v`, and the
//! largest Lyapunov exponent — the up sweep and the down sweep in two
//! colours (where they differ, hysteresis), the periodic branches of the
//! sweep over them at the same section (stable solid, unstable dashed, one
//! colour per structure), and a legend with every name in full.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::palette::category;
use super::sweep::{STABLE_WIDTH, UNSTABLE_WIDTH};
use super::{save, DrawError, Figure, FAMILY, REFERENCE_GREY, TITLE_SIZE};
use crate::study::diagram::{BranchSection, Column, OrbitDiagram};

const WIDTH: u32 = 1500;
/// The height of the image unless the legend needs more.
const HEIGHT: u32 = 1150;
const LEGEND_WIDTH: u32 = 420;
const LEGEND_ORIGIN: (i32, i32) = ((WIDTH - LEGEND_WIDTH) as i32 + 10, 76);
/// The up sweep's colour, and the down sweep's.
const UP: RGBColor = RGBColor(31, 119, 180);
const DOWN: RGBColor = RGBColor(214, 39, 40);
/// Branch colours start after the two sweep colours in the palette.
const BRANCH_RANK: usize = 4;

/// Draw `diagram` into `path` (`.svg` or `.png`) under `title`.
pub fn plot_diagram(diagram: &OrbitDiagram, title: &str, path: &Path) -> Result<(), String> {
    save(&DiagramFigure::new(diagram, title), path)
}

/// The figure of an orbit diagram.
pub struct DiagramFigure<'a> {
    diagram: &'a OrbitDiagram,
    title: String,
    legend: (Legend, LegendLayout),
}

fn branch_colour(k: usize) -> RGBColor {
    // Skip the palette's blue and red: they are the sweeps'.
    category(if k < 2 { k + 1 } else { k + BRANCH_RANK - 2 })
}

fn branch_name(b: &BranchSection) -> String {
    stickslip_codegen::structure::with_periods(&b.structure, b.n)
}

/// The distinct branch names, in order of first appearance.
fn names(d: &OrbitDiagram) -> Vec<String> {
    let mut out: Vec<String> = Vec::new();
    for b in &d.branches {
        let n = branch_name(b);
        if !out.contains(&n) {
            out.push(n);
        }
    }
    out
}

impl<'a> DiagramFigure<'a> {
    /// The figure of `diagram`, titled `title`.
    pub fn new(diagram: &'a OrbitDiagram, title: &str) -> Self {
        let mut entries = vec![
            Entry::new(
                Mark::Dot(UP),
                format!("simulation, {} increasing", diagram.param),
            ),
            Entry::new(
                Mark::Dot(DOWN),
                format!("simulation, {} decreasing", diagram.param),
            ),
        ];
        // One colour and one entry per structure (a sweep may give one
        // structure in several branches).
        let names = names(diagram);
        for (k, name) in names.iter().enumerate() {
            let c = branch_colour(k);
            let of_name = || diagram.branches.iter().filter(|b| &branch_name(b) == name);
            entries.push(Entry::new(Mark::Line(c), format!("{name} (stable)")));
            if of_name().any(|b| b.points.iter().any(|p| !p.stable)) {
                entries.push(Entry::new(Mark::Dashed(c), format!("{name} (unstable)")));
            }
        }
        let legend = Legend::new(Some("orbit diagram".into()), entries, 14, false);
        let layout = legend.layout(LEGEND_WIDTH as i32 - 20);
        Self {
            diagram,
            title: title.to_string(),
            legend: (legend, layout),
        }
    }
}

/// `[lo, hi]` of `values`, widened a little (and made non-empty).
fn span(values: impl Iterator<Item = f64>) -> (f64, f64) {
    let (lo, hi) = values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        });
    if !lo.is_finite() {
        return (-1.0, 1.0);
    }
    let pad = 0.05 * (hi - lo).max(1e-9 * lo.abs().max(1.0));
    (lo - pad, hi + pad)
}

type Panel<'b, DB> = ChartContext<
    'b,
    DB,
    Cartesian2d<plotters::coord::types::RangedCoordf64, plotters::coord::types::RangedCoordf64>,
>;

impl Figure for DiagramFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let bottom = LEGEND_ORIGIN.1 + self.legend.1.bounds.y1 + 16;
        (WIDTH, HEIGHT.max(bottom as u32))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let d = self.diagram;
        root.fill(&WHITE)?;
        let (upper, _) = root.split_vertically(HEIGHT);
        let body = upper
            .margin(8, 0, 0, 0)
            .titled(&self.title, (FAMILY, TITLE_SIZE).into_font())?;
        let (plots, _) = body.split_horizontally(WIDTH - LEGEND_WIDTH);
        let panels = plots.split_evenly((3, 1));
        let columns = || d.up.iter().chain(&d.down);
        let p_span = span(columns().map(|c| c.value));
        let pick_x = |c: &Column| c.x.clone();
        let pick_v = |c: &Column| c.v.clone();
        type Pick<'p> = &'p dyn Fn(&Column) -> Vec<f64>;
        let state_panels: [(&str, Pick, bool); 2] = [
            ("x at W t = 0 mod 2π", &pick_x, true),
            ("v at W t = 0 mod 2π", &pick_v, false),
        ];
        for (area, (name, pick, is_x)) in panels.iter().zip(state_panels) {
            let branch_values = d.branches.iter().flat_map(|b| {
                b.points
                    .iter()
                    .flat_map(move |p| if is_x { p.x.clone() } else { p.v.clone() })
            });
            let y_span = span(columns().flat_map(pick).chain(branch_values));
            let mut chart = ChartBuilder::on(area)
                .margin(12)
                .x_label_area_size(36)
                .y_label_area_size(72)
                .build_cartesian_2d(p_span.0..p_span.1, y_span.0..y_span.1)?;
            axes(&mut chart, &d.param, name)?;
            for (cols, colour) in [(&d.up, UP), (&d.down, DOWN)] {
                chart.draw_series(cols.iter().flat_map(|c| {
                    pick(c)
                        .into_iter()
                        .map(move |y| Circle::new((c.value, y), 1, colour.mix(0.7).filled()))
                }))?;
            }
            let names = names(d);
            for b in &d.branches {
                let k = names.iter().position(|n| *n == branch_name(b)).unwrap_or(0);
                let c = branch_colour(k);
                for strand in 0..b.n as usize {
                    // Runs of equal stability, one polyline each.
                    let mut run: Vec<(f64, f64)> = Vec::new();
                    let mut stable = None;
                    let flush = |chart: &mut Panel<DB>,
                                 run: &mut Vec<(f64, f64)>,
                                 stable: Option<bool>|
                     -> Result<(), DrawError> {
                        if run.len() >= 2 {
                            if stable == Some(true) {
                                chart.draw_series(LineSeries::new(
                                    run.iter().copied(),
                                    c.stroke_width(STABLE_WIDTH),
                                ))?;
                            } else {
                                chart.draw_series(DashedLineSeries::new(
                                    run.iter().copied(),
                                    6,
                                    4,
                                    c.stroke_width(UNSTABLE_WIDTH),
                                ))?;
                            }
                        } else if let (Some(&p), Some(true)) = (run.first(), stable) {
                            chart.draw_series(std::iter::once(Circle::new(p, 2, c.filled())))?;
                        }
                        run.clear();
                        Ok(())
                    };
                    for p in &b.points {
                        let y = if is_x { p.x[strand] } else { p.v[strand] };
                        if stable.is_some_and(|s| s != p.stable) {
                            let last = run.last().copied();
                            flush(&mut chart, &mut run, stable)?;
                            // The two stretches meet.
                            if let Some(l) = last {
                                run.push(l);
                            }
                        }
                        stable = Some(p.stable);
                        run.push((p.value, y));
                    }
                    flush(&mut chart, &mut run, stable)?;
                }
            }
        }
        // The exponents.
        let finite = |c: &Column| c.exponent.filter(|e| e.is_finite());
        let e_span = span(columns().filter_map(finite).chain([0.0]));
        let mut chart = ChartBuilder::on(&panels[2])
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(72)
            .build_cartesian_2d(p_span.0..p_span.1, e_span.0..e_span.1)?;
        axes(&mut chart, &d.param, "largest Lyapunov exponent (1/time)")?;
        chart.draw_series(std::iter::once(PathElement::new(
            vec![(p_span.0, 0.0), (p_span.1, 0.0)],
            REFERENCE_GREY.stroke_width(1),
        )))?;
        for (cols, colour) in [(&d.up, UP), (&d.down, DOWN)] {
            let pts: Vec<(f64, f64)> = cols
                .iter()
                .filter_map(|c| finite(c).map(|e| (c.value, e)))
                .collect();
            chart.draw_series(LineSeries::new(pts.iter().copied(), colour.stroke_width(1)))?;
            chart.draw_series(pts.iter().map(|&p| Circle::new(p, 2, colour.filled())))?;
        }
        let (legend, layout) = &self.legend;
        legend.draw(layout, root, LEGEND_ORIGIN)
    }
}

fn axes<DB: DrawingBackend>(chart: &mut Panel<'_, DB>, x: &str, y: &str) -> Result<(), DrawError> {
    chart
        .configure_mesh()
        .light_line_style(super::LIGHT_GRID)
        .x_desc(x)
        .y_desc(y)
        .label_style((FAMILY, super::TICK_SIZE).into_font())
        .axis_desc_style((FAMILY, super::AXIS_SIZE).into_font())
        .draw()?;
    Ok(())
}

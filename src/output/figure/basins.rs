//! The figure of basins of attraction: one coloured cell per grid start by
//! the attractor it reaches, black borders between basins, and a legend of
//! the attractors with their grid fraction and basin stability, every name
//! in full (wrapped to the legend's column; the image grows downwards when
//! the legend needs it). Starts not (yet) computed are left white.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::collections::HashMap;
use std::path::Path;

use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::palette::category;
use super::{save, DrawError, Figure, FAMILY, TITLE_SIZE};
use crate::study::basins::{summarize, AttractorBasin, BasinFile, BasinsError};

const WIDTH: u32 = 1400;
/// The height of the image unless the legend needs more.
const HEIGHT: u32 = 900;
const LEGEND_WIDTH: u32 = 480;
/// The legend's upper-left corner, in pixels of the image.
const LEGEND_ORIGIN: (i32, i32) = ((WIDTH - LEGEND_WIDTH) as i32 + 10, 76);

/// The fixed colour of what is no attractor of the palette: no motion, a
/// permanent stick, a start that reached nothing. Periodic motions and
/// irregular attractors take the palette's colours in legend order.
fn fixed_colour(name: &str) -> Option<RGBColor> {
    match name {
        "NM" => Some(RGBColor(236, 236, 228)),
        "stick" => Some(RGBColor(90, 90, 90)),
        "chaotic" | "quasi-periodic" => None,
        _ if name.starts_with("P_")
            || name.starts_with("cycle longer")
            || name.starts_with("stick-slip cycle")
            || name.starts_with("slip cycle")
            || name.starts_with("autonomous") =>
        {
            None
        }
        _ => Some(RGBColor(160, 160, 160)),
    }
}

/// Draw the basins in `file` (complete or partial) into `out` (`.svg` or `.png`).
pub fn plot_basins(file: &Path, out: &Path) -> Result<(), BasinsError> {
    plot_basin_file(&BasinFile::read(file)?, out)
}

/// Draw the starts of `basins` (a file read, or a run kept in memory,
/// [`Basins::to_file`](crate::study::basins::Basins::to_file)) into `out`.
pub fn plot_basin_file(basins: &BasinFile, out: &Path) -> Result<(), BasinsError> {
    save(&BasinsFigure::new(basins), out).map_err(BasinsError::Plot)
}

/// The figure of a basin file.
pub struct BasinsFigure<'a> {
    file: &'a BasinFile,
    /// Each grid cell's attractor, if computed.
    cells: Vec<Option<&'a str>>,
    colours: HashMap<String, RGBColor>,
    legend: (Legend, LegendLayout),
}

fn entry_text(a: &AttractorBasin, samples: usize) -> String {
    let mut t = format!("{}: {:.1} % of the grid", a.name, 100.0 * a.fraction);
    if samples > 0 {
        t.push_str(&format!(
            ", stability {:.3} [{:.3}, {:.3}]",
            a.stability, a.interval[0], a.interval[1]
        ));
    }
    if let Some(e) = a.exponent {
        t.push_str(&format!(", λ1 = {e:.4}"));
    }
    t
}

impl<'a> BasinsFigure<'a> {
    /// The figure of `file` (complete or partial).
    pub fn new(file: &'a BasinFile) -> Self {
        let h = &file.header;
        let grid = h.grid_len();
        let mut cells: Vec<Option<&str>> = vec![None; grid];
        for s in &file.starts {
            if let Some(c) = cells.get_mut(s.index) {
                *c = Some(s.attractor.as_str());
            }
        }
        let attractors = summarize(h, &file.starts);
        let samples = file.starts.iter().filter(|s| s.index >= grid).count();
        let mut colours = HashMap::new();
        let mut rank = 0;
        let mut entries = Vec::new();
        for a in &attractors {
            let c = fixed_colour(&a.name).unwrap_or_else(|| {
                rank += 1;
                category(rank - 1)
            });
            colours.insert(a.name.clone(), c);
            entries.push(Entry::new(Mark::Swatch(c), entry_text(a, samples)));
        }
        let title = if samples > 0 {
            format!("attractors: grid share, basin stability of {samples} random starts [95 % CI]")
        } else {
            "attractors: share of the grid".to_string()
        };
        let legend = Legend::new(Some(title), entries, 14, false);
        let layout = legend.layout(LEGEND_WIDTH as i32 - 20);
        Self {
            file,
            cells,
            colours,
            legend: (legend, layout),
        }
    }
}

/// Edges of the cells around the values of an axis.
fn edges(values: &[f64]) -> Vec<f64> {
    let n = values.len();
    if n == 1 {
        let half = 0.05 * values[0].abs().max(1.0);
        return vec![values[0] - half, values[0] + half];
    }
    let mut e = Vec::with_capacity(n + 1);
    e.push(values[0] - 0.5 * (values[1] - values[0]));
    for w in values.windows(2) {
        e.push(0.5 * (w[0] + w[1]));
    }
    e.push(values[n - 1] + 0.5 * (values[n - 1] - values[n - 2]));
    e
}

impl Figure for BasinsFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let bottom = LEGEND_ORIGIN.1 + self.legend.1.bounds.y1 + 16;
        (WIDTH, HEIGHT.max(bottom as u32))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let h = &self.file.header;
        let (nx, nv) = (h.x.count, h.v.count);
        root.fill(&WHITE)?;
        let params: Vec<String> = h
            .params
            .iter()
            .filter(|(n, _)| n == "W" || n == "Q0")
            .map(|(n, v)| format!("{n} = {v}"))
            .collect();
        let title = format!(
            "{}: basins of attraction at W t = {}{}{}, {nx} × {nv} starts",
            h.model,
            h.phase,
            if params.is_empty() { "" } else { ", " },
            params.join(", ")
        );
        let (upper, _) = root.split_vertically(HEIGHT);
        let body = upper
            .margin(8, 0, 0, 0)
            .titled(&title, (FAMILY, TITLE_SIZE).into_font())?;
        let (plot_area, _) = body.split_horizontally(WIDTH - LEGEND_WIDTH);
        let xe = edges(&h.x.values());
        let ve = edges(&h.v.values());
        let range = |e: &[f64]| {
            let (a, b) = (e[0], e[e.len() - 1]);
            if a <= b {
                a..b
            } else {
                b..a
            }
        };
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(range(&xe), range(&ve))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc("x (start)")
            .y_desc("v (start)")
            .label_style((FAMILY, 14).into_font())
            .axis_desc_style((FAMILY, 17).into_font())
            .draw()?;
        let cell = |i: usize| {
            let (ix, iv) = (i % nx, i / nx);
            [(xe[ix], ve[iv]), (xe[ix + 1], ve[iv + 1])]
        };
        chart.draw_series((0..nx * nv).filter_map(|i| {
            let name = self.cells[i]?;
            let c = self.colours.get(name).copied().unwrap_or(WHITE);
            Some(Rectangle::new(cell(i), c.filled()))
        }))?;
        let mut borders = Vec::new();
        let differ = |i: usize, j: usize| match (self.cells[i], self.cells[j]) {
            (Some(a), Some(b)) => a != b,
            _ => false,
        };
        for iv in 0..nv {
            for ix in 0..nx {
                let i = iv * nx + ix;
                if ix + 1 < nx && differ(i, i + 1) {
                    borders.push(vec![(xe[ix + 1], ve[iv]), (xe[ix + 1], ve[iv + 1])]);
                }
                if iv + 1 < nv && differ(i, i + nx) {
                    borders.push(vec![(xe[ix], ve[iv + 1]), (xe[ix + 1], ve[iv + 1])]);
                }
            }
        }
        chart.draw_series(
            borders
                .into_iter()
                .map(|line| PathElement::new(line, BLACK.stroke_width(1))),
        )?;
        let (legend, layout) = &self.legend;
        legend.draw(layout, root, LEGEND_ORIGIN)
    }
}

//! The figure of a parameter map (the paper's Fig. 11): one coloured cell
//! per grid point by its set of motions ([`PointResult::label`]), black
//! borders between neighbouring cells with different sets, and a legend of
//! the sets with their number of points, every name in full (wrapped to the
//! legend's column; the image grows downwards when the legend needs it).
//! Points not (yet) computed are hatched grey. The exact transition curves
//! of a curves run may be drawn over the cells ([`draw_map_with_curves`]).

use plotters::coord::Shift;
use plotters::prelude::*;
use std::collections::HashMap;
use std::path::Path;

use super::layout::Rect;
use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::palette::category;
use super::regime::{curve_legend, draw_curves};
use super::{save, DrawError, Figure, FAMILY, TITLE_SIZE};
use crate::study::curves::CurveSet;
use crate::study::map::{MapError, MapFile, PointResult};

const WIDTH: u32 = 1500;
/// The height of the image unless the legend needs more.
const HEIGHT: u32 = 900;
const LEGEND_WIDTH: u32 = 520;
/// The legend's upper-left corner, in pixels of the image.
const LEGEND_ORIGIN: (i32, i32) = ((WIDTH - LEGEND_WIDTH) as i32 + 10, 76);
/// Sets listed one by one; the rest are summed on one line.
const MAX_ENTRIES: usize = 60;
const NOT_COMPUTED: &str = "not computed";
/// Pixels between the legend of the sets and that of the curves.
const KEY_GAP: i32 = 16;

/// Labels with a fixed colour: no motion, and points without a motion found
/// (a set of motions, an unforced model's cycles among them, takes the
/// palette's).
fn is_special(label: &str) -> bool {
    !label.starts_with("P_")
        && !label.starts_with("NM +")
        && !label.contains("stick-slip cycle")
        && !label.contains("slip cycle")
}

fn colour_of(label: &str, rank: usize) -> RGBColor {
    match label {
        "NM" => RGBColor(236, 236, 228),
        "invalid" => RGBColor(70, 70, 70),
        NOT_COMPUTED => RGBColor(200, 200, 200),
        _ if is_special(label) => RGBColor(120, 120, 120),
        _ => category(rank),
    }
}

/// Edges of the cells around the values of an axis: midpoints between
/// neighbours, half a step beyond the ends.
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

/// Draw the map in `file` (complete or partial) into `out` (`.svg` or `.png`).
pub fn plot_map(file: &Path, out: &Path) -> Result<(), MapError> {
    let map = MapFile::read(file)?;
    draw_map(&map, out)
}

/// Draw `map` into `out` (`.svg` or `.png`).
pub fn draw_map(map: &MapFile, out: &Path) -> Result<(), MapError> {
    draw_map_with_curves(map, None, out)
}

/// Draw `map` into `out` (`.svg` or `.png`) with the exact transition
/// curves of `curves`, if given, over its cells: solid or dashed by kind as
/// on the regime map ([`super::regime::curve_style`]), codimension-two
/// points marked, the kinds listed under the legend.
pub fn draw_map_with_curves(
    map: &MapFile,
    curves: Option<&CurveSet>,
    out: &Path,
) -> Result<(), MapError> {
    let figure = match curves {
        Some(set) => MapFigure::with_curves(map, set).map_err(MapError::Plot)?,
        None => MapFigure::new(map),
    };
    save(&figure, out).map_err(MapError::Plot)
}

/// The figure of a map.
pub struct MapFigure<'a> {
    map: &'a MapFile,
    /// Each cell's point, if computed.
    cells: Vec<Option<&'a PointResult>>,
    /// Each cell's label.
    labels: Vec<String>,
    colours: HashMap<String, RGBColor>,
    legend: (Legend, LegendLayout),
    /// Curves drawn over the cells, if any.
    curves: Option<Curves<'a>>,
}

/// Curves over a map: the set, whether its `x` is the map's `y`, and the
/// legend of their kinds.
struct Curves<'a> {
    set: &'a CurveSet,
    swap: bool,
    key: Option<(Legend, LegendLayout)>,
}

impl<'a> MapFigure<'a> {
    /// The figure of `map` (complete or partial).
    pub fn new(map: &'a MapFile) -> Self {
        let h = &map.header;
        let (nx, ny) = (h.x.count, h.y.count);
        let mut cells: Vec<Option<&PointResult>> = vec![None; nx * ny];
        for p in &map.points {
            if let Some(c) = cells.get_mut(p.index) {
                *c = Some(p);
            }
        }
        let labels: Vec<String> = cells
            .iter()
            .map(|c| c.map_or_else(|| NOT_COMPUTED.to_string(), |p| p.label()))
            .collect();
        // Legend order: most frequent first, then by name.
        let mut counts: HashMap<&str, usize> = HashMap::new();
        for l in &labels {
            *counts.entry(l.as_str()).or_default() += 1;
        }
        let mut order: Vec<(&str, usize)> = counts.into_iter().collect();
        order.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
        let names: Vec<&str> = order.iter().map(|(l, _)| *l).collect();
        let colours = set_colours(&names);
        let legend = legend(&order, &colours);
        let layout = legend.layout(LEGEND_WIDTH as i32 - 20);
        Self {
            map,
            cells,
            labels,
            colours,
            legend: (legend, layout),
            curves: None,
        }
    }

    /// The figure of `map` with the curves of `curves` drawn over the cells
    /// (and their kinds listed under the legend). An error when the curves
    /// are not over the map's two parameters (in either order).
    pub fn with_curves(map: &'a MapFile, curves: &'a CurveSet) -> Result<Self, String> {
        let h = &map.header;
        let (mx, my) = (h.x.name.as_str(), h.y.name.as_str());
        let (cx, cy) = (curves.x.0.as_str(), curves.y.0.as_str());
        let swap = if (cx, cy) == (mx, my) {
            false
        } else if (cx, cy) == (my, mx) {
            true
        } else {
            return Err(format!(
                "the curves are over ({cx}, {cy}), the map over ({mx}, {my})"
            ));
        };
        let mut figure = Self::new(map);
        let key = curve_legend(curves).map(|l| {
            let layout = l.layout(LEGEND_WIDTH as i32 - 20);
            (l, layout)
        });
        figure.curves = Some(Curves {
            set: curves,
            swap,
            key,
        });
        Ok(figure)
    }

    /// Where the curves' legend goes (under the sets'), pixels of the image.
    fn key_origin(&self) -> (i32, i32) {
        (
            LEGEND_ORIGIN.0,
            LEGEND_ORIGIN.1 + self.legend.1.bounds.y1 + KEY_GAP,
        )
    }
}

/// The colours of the sets of motions `labels`, in their order: the
/// palette by rank among the motion sets (the fixed colours of `NM`,
/// `invalid`, … take no rank). The map's figure ranks its sets by points,
/// the regime figure by area.
pub fn set_colours(labels: &[&str]) -> HashMap<String, RGBColor> {
    let mut rank = 0;
    labels
        .iter()
        .map(|l| {
            let c = colour_of(l, rank);
            if !is_special(l) {
                rank += 1;
            }
            (l.to_string(), c)
        })
        .collect()
}

/// The legend of the sets `order` (label, points): the first
/// [`MAX_ENTRIES`] one by one, the rest summed.
fn legend(order: &[(&str, usize)], colours: &HashMap<String, RGBColor>) -> Legend {
    let shown = if order.len() > MAX_ENTRIES {
        MAX_ENTRIES - 1
    } else {
        order.len()
    };
    let mut entries: Vec<Entry> = order[..shown]
        .iter()
        .map(|(label, count)| {
            let c = colours.get(*label).copied().unwrap_or(WHITE);
            Entry::new(Mark::Swatch(c), format!("{label} ({count})"))
        })
        .collect();
    if shown < order.len() {
        let rest: usize = order[shown..].iter().map(|(_, c)| c).sum();
        entries.push(Entry::new(
            Mark::None,
            format!("… {} more sets ({rest} points)", order.len() - shown),
        ));
    }
    Legend::new(
        Some("motions found (points)".to_string()),
        entries,
        14,
        false,
    )
}

impl Figure for MapFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let mut bottom = LEGEND_ORIGIN.1 + self.legend.1.bounds.y1 + 16;
        if let Some((_, layout)) = self.curves.as_ref().and_then(|c| c.key.as_ref()) {
            bottom = self.key_origin().1 + layout.bounds.y1 + 16;
        }
        (WIDTH, HEIGHT.max(bottom as u32))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let h = &self.map.header;
        let (nx, ny) = (h.x.count, h.y.count);
        let (cells, labels) = (&self.cells, &self.labels);
        root.fill(&WHITE)?;
        let mut title = format!(
            "{}: motions over ({}, {}), {} × {} points",
            h.model, h.x.name, h.y.name, nx, ny
        );
        if let Some(s) = h.shard {
            title.push_str(&format!(" (shard {s})"));
        }
        let (upper, _) = root.split_vertically(HEIGHT);
        let body = upper
            .margin(8, 0, 0, 0)
            .titled(&title, (FAMILY, TITLE_SIZE).into_font())?;
        let (plot_area, _) = body.split_horizontally(WIDTH - LEGEND_WIDTH);

        let xe = edges(&h.x.values());
        let ye = edges(&h.y.values());
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
            .build_cartesian_2d(range(&xe), range(&ye))?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(h.x.name.as_str())
            .y_desc(h.y.name.as_str())
            .label_style((FAMILY, 14).into_font())
            .axis_desc_style((FAMILY, 17).into_font())
            .draw()?;
        let cell = |i: usize| {
            let (ix, iy) = (i % nx, i / nx);
            [(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])]
        };
        // Cells.
        chart.draw_series((0..nx * ny).map(|i| {
            let c = self.colours.get(&labels[i]).copied().unwrap_or(WHITE);
            Rectangle::new(cell(i), c.filled())
        }))?;
        // Not computed: a diagonal across the cell.
        let hatch = RGBColor(150, 150, 150);
        chart.draw_series(
            (0..nx * ny)
                .filter(|&i| cells[i].is_none())
                .map(|i| PathElement::new(cell(i).to_vec(), hatch.stroke_width(1))),
        )?;
        // Region borders between neighbours with different labels.
        let mut borders = Vec::new();
        for iy in 0..ny {
            for ix in 0..nx {
                let i = iy * nx + ix;
                // Not between computed and missing points: that is no region border.
                let differ =
                    |j: usize| labels[i] != labels[j] && cells[i].is_some() && cells[j].is_some();
                if ix + 1 < nx && differ(i + 1) {
                    borders.push(vec![(xe[ix + 1], ye[iy]), (xe[ix + 1], ye[iy + 1])]);
                }
                if iy + 1 < ny && differ(i + nx) {
                    borders.push(vec![(xe[ix], ye[iy + 1]), (xe[ix + 1], ye[iy + 1])]);
                }
            }
        }
        chart.draw_series(
            borders
                .into_iter()
                .map(|line| PathElement::new(line, BLACK.stroke_width(2))),
        )?;
        if let Some(c) = &self.curves {
            let (xs, ys) = (range(&xe), range(&ye));
            let bounds = ([xs.start, ys.start], [xs.end, ys.end]);
            draw_curves(&mut chart, root, c.set, bounds, c.swap)?;
            if let Some((legend, layout)) = &c.key {
                legend.draw(layout, root, self.key_origin())?;
            }
        }
        let (legend, layout) = &self.legend;
        legend.draw(layout, root, LEGEND_ORIGIN)
    }
}

impl MapFigure<'_> {
    /// The legend's boxes in pixels of the image, and the image's box.
    pub fn legend_boxes(&self) -> (Vec<Rect>, Rect) {
        let (w, h) = self.size();
        let (x, y) = LEGEND_ORIGIN;
        let mut boxes: Vec<Rect> = self.legend.1.boxes().map(|r| r.shifted(x, y)).collect();
        if let Some((_, layout)) = self.curves.as_ref().and_then(|c| c.key.as_ref()) {
            let (x, y) = self.key_origin();
            boxes.extend(layout.boxes().map(|r| r.shifted(x, y)));
        }
        (boxes, Rect::at(0, 0, (w as i32, h as i32)))
    }
}

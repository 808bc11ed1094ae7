//! The figure of a parameter map (the paper's Fig. 11): one coloured cell
//! per grid point by its set of motions ([`PointResult::label`]), black
//! borders between neighbouring cells with different sets, and a legend of
//! the sets with their number of points. Points not (yet) computed are
//! hatched grey. SVG or PNG by the file's extension; text in DejaVu Sans,
//! compiled in like [`crate::output::plot`]'s.

use plotters::coord::Shift;
use plotters::prelude::*;
use std::collections::HashMap;
use std::path::Path;

use crate::output::plot::{register, Format, FAMILY};
use crate::study::map::{MapError, MapFile, PointResult};

const WIDTH: u32 = 1500;
const HEIGHT: u32 = 900;
const LEGEND_WIDTH: u32 = 520;
const NOT_COMPUTED: &str = "not computed";

/// Colours of the labels, most frequent first.
const PALETTE: [RGBColor; 20] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
    RGBColor(174, 199, 232),
    RGBColor(255, 187, 120),
    RGBColor(152, 223, 138),
    RGBColor(255, 152, 150),
    RGBColor(197, 176, 213),
    RGBColor(196, 156, 148),
    RGBColor(247, 182, 210),
    RGBColor(219, 219, 141),
    RGBColor(158, 218, 229),
    RGBColor(57, 59, 121),
    RGBColor(132, 60, 57),
];

/// Labels with a fixed colour: no motion, and points without a motion found.
fn is_special(label: &str) -> bool {
    !label.starts_with("P_") && !label.starts_with("NM +")
}

fn colour_of(label: &str, rank: usize) -> RGBColor {
    match label {
        "NM" => RGBColor(236, 236, 228),
        "invalid" => RGBColor(70, 70, 70),
        NOT_COMPUTED => RGBColor(200, 200, 200),
        _ if is_special(label) => RGBColor(120, 120, 120),
        _ if rank < PALETTE.len() => PALETTE[rank],
        _ => {
            // Beyond the palette: spread hues by the golden angle.
            let h = (rank as f64 * 137.508) % 360.0;
            let (s, l) = (0.55, 0.55);
            let c = (1.0 - (2.0f64 * l - 1.0).abs()) * s;
            let x = c * (1.0 - ((h / 60.0) % 2.0 - 1.0).abs());
            let (r, g, b) = match (h / 60.0) as u32 {
                0 => (c, x, 0.0),
                1 => (x, c, 0.0),
                2 => (0.0, c, x),
                3 => (0.0, x, c),
                4 => (x, 0.0, c),
                _ => (c, 0.0, x),
            };
            let m = l - c / 2.0;
            let u = |v: f64| ((v + m) * 255.0).round() as u8;
            RGBColor(u(r), u(g), u(b))
        }
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
    let format = Format::of(out).map_err(MapError::Plot)?;
    register().map_err(MapError::Plot)?;
    let fail = |e: String| MapError::Plot(format!("cannot draw `{}`: {e}", out.display()));
    match format {
        Format::Svg => {
            let root = SVGBackend::new(out, (WIDTH, HEIGHT)).into_drawing_area();
            draw(&root, map).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(out, (WIDTH, HEIGHT)).into_drawing_area();
            draw(&root, map).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}

fn draw<DB: DrawingBackend>(root: &DrawingArea<DB, Shift>, map: &MapFile) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
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
    // Palette colours by rank among the motion sets (the fixed colours of
    // NM, invalid, … take no rank).
    let mut rank = 0;
    let colours: HashMap<&str, RGBColor> = order
        .iter()
        .map(|(l, _)| {
            let c = colour_of(l, rank);
            if !is_special(l) {
                rank += 1;
            }
            (*l, c)
        })
        .collect();

    root.fill(&WHITE).map_err(err)?;
    let mut title = format!(
        "{}: motions over ({}, {}), {} × {} points",
        h.model, h.x.name, h.y.name, nx, ny
    );
    if let Some(s) = h.shard {
        title.push_str(&format!(" (shard {s})"));
    }
    let body = root
        .margin(8, 0, 0, 0)
        .titled(&title, (FAMILY, 22).into_font())
        .map_err(err)?;
    let (plot_area, legend_area) = body.split_horizontally(WIDTH - LEGEND_WIDTH);

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
        .build_cartesian_2d(range(&xe), range(&ye))
        .map_err(err)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_desc(h.x.name.as_str())
        .y_desc(h.y.name.as_str())
        .label_style((FAMILY, 14).into_font())
        .axis_desc_style((FAMILY, 17).into_font())
        .draw()
        .map_err(err)?;
    // Cells.
    let hatch = RGBColor(150, 150, 150);
    chart
        .draw_series((0..nx * ny).map(|i| {
            let (ix, iy) = (i % nx, i / nx);
            let c = colours[labels[i].as_str()];
            Rectangle::new([(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])], c.filled())
        }))
        .map_err(err)?;
    // Not computed: a diagonal across the cell.
    chart
        .draw_series((0..nx * ny).filter(|&i| cells[i].is_none()).map(|i| {
            let (ix, iy) = (i % nx, i / nx);
            PathElement::new(
                vec![(xe[ix], ye[iy]), (xe[ix + 1], ye[iy + 1])],
                hatch.stroke_width(1),
            )
        }))
        .map_err(err)?;
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
    chart
        .draw_series(
            borders
                .into_iter()
                .map(|line| PathElement::new(line, BLACK.stroke_width(2))),
        )
        .map_err(err)?;

    // Legend.
    let legend = legend_area.margin(40, 10, 10, 10);
    legend
        .draw(&Text::new(
            "motions found (points)",
            (0, 0),
            (FAMILY, 17).into_font(),
        ))
        .map_err(err)?;
    let row = 24i32;
    let (_, legend_h) = legend.dim_in_pixel();
    let rows = ((legend_h as i32 - 40) / row).max(1) as usize;
    let shown = if order.len() > rows {
        rows - 1
    } else {
        order.len()
    };
    for (k, (label, count)) in order.iter().take(shown).enumerate() {
        let y = 30 + k as i32 * row;
        legend
            .draw(&Rectangle::new(
                [(0, y), (26, y + 16)],
                colours[label].filled(),
            ))
            .map_err(err)?;
        legend
            .draw(&Rectangle::new(
                [(0, y), (26, y + 16)],
                BLACK.stroke_width(1),
            ))
            .map_err(err)?;
        legend
            .draw(&Text::new(
                format!("{label} ({count})"),
                (34, y),
                (FAMILY, 14).into_font(),
            ))
            .map_err(err)?;
    }
    if shown < order.len() {
        let y = 30 + shown as i32 * row;
        let rest: usize = order[shown..].iter().map(|(_, c)| c).sum();
        legend
            .draw(&Text::new(
                format!("… {} more sets ({rest} points)", order.len() - shown),
                (34, y),
                (FAMILY, 14).into_font(),
            ))
            .map_err(err)?;
    }
    Ok(())
}

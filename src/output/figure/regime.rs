//! The regime map drawn from curves alone: regions filled and labelled with
//! their motions, the curves over them, codimension-two points marked.
//!
//! Each region is filled at the raster's resolution in the colour of its
//! label — one colour per distinct set of motions, ranked by area as the
//! map's figure ranks its sets by points ([`super::map::set_colours`]) — and
//! numbered at its sample point, the point where it was classified. The
//! curves are drawn over the regions in the style of their kind
//! ([`curve_style`]): non-smooth transitions solid, eigenvalue
//! bifurcations dashed, each kind in its own dark ink; codimension-two
//! points are marked with a diamond. On the right, the legend: every
//! region's number and colour with its motions in full (wrapped, never
//! cut), then the kinds of curve and the codimension-two points. The image
//! grows downwards when the legend needs the room.

use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::collections::HashMap;
use std::path::Path;

use super::layout::{line_height, text_width, Rect};
use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::map::set_colours;
use super::symbol::{Symbol, INK};
use super::{pixels, save, DrawError, Figure, AXIS_SIZE, FAMILY, TICK_SIZE, TITLE_SIZE};
use crate::bifurcation::TransitionKind;
use crate::study::curves::regions::raster::clip;
use crate::study::curves::{CurveSet, Regions};

const WIDTH: u32 = 1500;
/// The height of the image unless the legend needs more.
const HEIGHT: u32 = 900;
const LEGEND_WIDTH: u32 = 520;
/// The legend's upper-left corner, in pixels of the image.
const LEGEND_ORIGIN: (i32, i32) = ((WIDTH - LEGEND_WIDTH) as i32 + 10, 76);
/// Pixels between the legend of the regions and that of the curves.
const LEGEND_GAP: i32 = 16;
/// Text size of the legends and of the regions' numbers.
const KEY_SIZE: u32 = 14;
/// The symbol of a codimension-two point.
pub const CODIM2: Symbol = Symbol::Diamond;

/// How a curve of a kind is drawn: its ink and whether it is dashed
/// (eigenvalue bifurcations) or solid (non-smooth transitions).
pub fn curve_style(kind: TransitionKind) -> (RGBColor, bool) {
    match kind {
        TransitionKind::Grazing => (RGBColor(0, 0, 0), false),
        TransitionKind::StickOnset => (RGBColor(25, 45, 140), false),
        TransitionKind::StickVanishing => (RGBColor(150, 20, 20), false),
        TransitionKind::PassableOnset => (RGBColor(0, 105, 40), false),
        TransitionKind::Fold => (RGBColor(0, 0, 0), true),
        TransitionKind::BranchPoint => (RGBColor(90, 90, 90), true),
        TransitionKind::PeriodDoubling => (RGBColor(110, 20, 130), true),
        TransitionKind::NeimarkSacker => (RGBColor(130, 75, 0), true),
        TransitionKind::SteadySliding => (RGBColor(0, 110, 130), true),
    }
}

/// A kind's name in a legend (`stick onset`, `period doubling`, …).
pub fn kind_text(kind: TransitionKind) -> String {
    kind.name().replace('_', " ")
}

/// The legend of the curves of `set`: one entry per kind present, in the
/// order of [`TransitionKind`], then one per combination of kinds meeting
/// at codimension-two points with their number. `None` for no curves.
pub fn curve_legend(set: &CurveSet) -> Option<Legend> {
    let mut kinds: Vec<TransitionKind> = set.curves.iter().map(|c| c.kind).collect();
    kinds.sort_by_key(|&k| k as u8);
    kinds.dedup();
    let mut entries: Vec<Entry> = kinds
        .into_iter()
        .map(|k| {
            let (ink, dashed) = curve_style(k);
            let mark = if dashed {
                Mark::Dashed(ink)
            } else {
                Mark::Line(ink)
            };
            Entry::new(mark, kind_text(k))
        })
        .collect();
    let mut meetings: Vec<(String, usize)> = Vec::new();
    for p in &set.codim2 {
        let mut ks = p.kinds.clone();
        ks.sort_by_key(|&k| k as u8);
        let text = ks
            .into_iter()
            .map(kind_text)
            .collect::<Vec<_>>()
            .join(" × ");
        match meetings.iter_mut().find(|(t, _)| *t == text) {
            Some((_, n)) => *n += 1,
            None => meetings.push((text, 1)),
        }
    }
    for (text, n) in meetings {
        let what = if text.is_empty() {
            "codimension-two point".to_string()
        } else {
            format!("codimension two: {text}")
        };
        entries.push(Entry::new(Mark::Symbol(CODIM2), format!("{what} ({n})")));
    }
    (!entries.is_empty()).then(|| Legend::new(Some("curves".to_string()), entries, KEY_SIZE, false))
}

/// The box `[x0, x1] × [y0, y1]` ordered low to high.
fn ordered(x: [f64; 2], y: [f64; 2]) -> ([f64; 2], [f64; 2]) {
    (
        [x[0].min(x[1]), y[0].min(y[1])],
        [x[0].max(x[1]), y[0].max(y[1])],
    )
}

/// The pieces of the polyline `points` inside the box from `lo` to `hi`
/// (non-finite points break the line).
pub fn clip_polyline(points: &[[f64; 2]], lo: [f64; 2], hi: [f64; 2]) -> Vec<Vec<(f64, f64)>> {
    let mut pieces: Vec<Vec<(f64, f64)>> = Vec::new();
    let mut open = false;
    let finite = |p: &[f64; 2]| p[0].is_finite() && p[1].is_finite();
    let inside = |p: &[f64; 2]| (lo[0]..=hi[0]).contains(&p[0]) && (lo[1]..=hi[1]).contains(&p[1]);
    if let [p] = points {
        if finite(p) && inside(p) {
            pieces.push(vec![(p[0], p[1])]);
        }
    }
    for w in points.windows(2) {
        let clipped = if finite(&w[0]) && finite(&w[1]) {
            clip(w[0], w[1], lo, hi)
        } else {
            None
        };
        match clipped {
            Some((a, b)) => {
                let continues = open && a == w[0];
                if !continues {
                    pieces.push(vec![(a[0], a[1])]);
                }
                if let Some(piece) = pieces.last_mut() {
                    piece.push((b[0], b[1]));
                }
                open = b == w[1];
            }
            None => open = false,
        }
    }
    pieces
}

/// The chart a map or regime figure draws on.
pub type Chart<'a, DB> = ChartContext<'a, DB, Cartesian2d<RangedCoordf64, RangedCoordf64>>;

/// Draw the curves of `set` on `chart`, clipped to the box `lo`–`hi`, then
/// its codimension-two points on `root` (the image). `swap`: the set's `x`
/// is the chart's vertical axis.
pub fn draw_curves<DB: DrawingBackend>(
    chart: &mut Chart<'_, DB>,
    root: &DrawingArea<DB, Shift>,
    set: &CurveSet,
    (lo, hi): ([f64; 2], [f64; 2]),
    swap: bool,
) -> Result<(), DrawError> {
    let oriented = |p: [f64; 2]| if swap { [p[1], p[0]] } else { p };
    for curve in &set.curves {
        let (ink, dashed) = curve_style(curve.kind);
        let points: Vec<[f64; 2]> = curve.points.iter().map(|&p| oriented(p)).collect();
        for piece in clip_polyline(&points, lo, hi) {
            if dashed {
                chart.draw_series(DashedLineSeries::new(piece, 8, 5, ink.stroke_width(2)))?;
            } else {
                chart.draw_series(LineSeries::new(piece, ink.stroke_width(2)))?;
            }
        }
    }
    for p in &set.codim2 {
        let [x, y] = oriented([p.x, p.y]);
        let inside = (lo[0]..=hi[0]).contains(&x) && (lo[1]..=hi[1]).contains(&y);
        if inside {
            CODIM2.draw(root, chart.backend_coord(&(x, y)))?;
        }
    }
    Ok(())
}

/// Draw the regime map of `set` cut into `regions` to `path` (SVG or PNG by extension).
pub fn plot_regimes(
    set: &CurveSet,
    regions: &Regions,
    title: &str,
    path: &Path,
) -> Result<(), String> {
    save(&RegimeFigure::new(set, regions, title)?, path)
}

/// The figure of a regime map.
pub struct RegimeFigure<'a> {
    set: &'a CurveSet,
    regions: &'a Regions,
    title: String,
    /// Each region's colour.
    colours: Vec<RGBColor>,
    /// The regions' legend, then the curves'.
    legends: Vec<(Legend, LegendLayout)>,
}

impl<'a> RegimeFigure<'a> {
    /// The figure of `set` cut into `regions`. An error when the regions
    /// are not a raster of their size or a cell names no region.
    pub fn new(set: &'a CurveSet, regions: &'a Regions, title: &str) -> Result<Self, String> {
        let (nx, ny) = (regions.nx, regions.ny);
        if nx == 0 || ny == 0 || regions.cells.len() != nx * ny {
            return Err(format!(
                "the regions are no raster: {} cells for {nx} × {ny}",
                regions.cells.len()
            ));
        }
        for (name, [a, b]) in [&set.x, &set.y] {
            if !(a.is_finite() && b.is_finite() && a != b) {
                return Err(format!(
                    "the range of {name} is empty or not finite: {a} to {b}"
                ));
            }
        }
        if let Some(c) = regions.cells.iter().find(|&&c| c >= regions.regions.len()) {
            return Err(format!(
                "a cell of the regions names region {c} of {}",
                regions.regions.len()
            ));
        }
        // Labels by area, largest first, then by name: the map's order.
        let mut area: HashMap<&str, usize> = HashMap::new();
        for &c in &regions.cells {
            *area.entry(regions.regions[c].label.as_str()).or_default() += 1;
        }
        for r in &regions.regions {
            area.entry(r.label.as_str()).or_default();
        }
        let mut order: Vec<(&str, usize)> = area.into_iter().collect();
        order.sort_by(|a, b| b.1.cmp(&a.1).then_with(|| a.0.cmp(b.0)));
        let labels: Vec<&str> = order.iter().map(|(l, _)| *l).collect();
        let by_label = set_colours(&labels);
        let colours = regions
            .regions
            .iter()
            .map(|r| by_label.get(&r.label).copied().unwrap_or(WHITE))
            .collect();
        let entries = labels
            .iter()
            .map(|&l| {
                let numbers: Vec<String> = (0..regions.regions.len())
                    .filter(|&k| regions.regions[k].label == l)
                    .map(|k| (k + 1).to_string())
                    .collect();
                let c = by_label.get(l).copied().unwrap_or(WHITE);
                Entry::new(Mark::Swatch(c), format!("{}: {l}", numbers.join(", ")))
            })
            .collect();
        let mut legends = vec![Legend::new(
            Some("regions: motions found".to_string()),
            entries,
            KEY_SIZE,
            false,
        )];
        legends.extend(curve_legend(set));
        let width = LEGEND_WIDTH as i32 - 20;
        let legends = legends
            .into_iter()
            .map(|l| {
                let layout = l.layout(width);
                (l, layout)
            })
            .collect();
        Ok(Self {
            set,
            regions,
            title: title.to_string(),
            colours,
            legends,
        })
    }

    /// Where each legend's upper-left corner goes, in pixels of the image.
    fn legend_origins(&self) -> Vec<(i32, i32)> {
        let (x, mut y) = LEGEND_ORIGIN;
        self.legends
            .iter()
            .map(|(_, layout)| {
                let at = (x, y);
                y += layout.bounds.y1 + LEGEND_GAP;
                at
            })
            .collect()
    }

    /// The legends' boxes in pixels of the image, and the image's box.
    pub fn legend_boxes(&self) -> (Vec<Rect>, Rect) {
        let (w, h) = self.size();
        let boxes = self
            .legends
            .iter()
            .zip(self.legend_origins())
            .flat_map(|((_, layout), (x, y))| layout.boxes().map(move |r| r.shifted(x, y)))
            .collect();
        (boxes, Rect::at(0, 0, (w as i32, h as i32)))
    }
}

impl Figure for RegimeFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let bottom = match (self.legends.last(), self.legend_origins().last()) {
            (Some((_, layout)), Some(&(_, y))) => y + layout.bounds.y1 + 16,
            _ => 0,
        };
        (WIDTH, HEIGHT.max(bottom.max(0) as u32))
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        let (set, regions) = (self.set, self.regions);
        let (nx, ny) = (regions.nx, regions.ny);
        root.fill(&WHITE)?;
        let (upper, _) = root.split_vertically(HEIGHT);
        let body = upper
            .margin(8, 0, 0, 0)
            .titled(&self.title, (FAMILY, TITLE_SIZE).into_font())?;
        let (plot_area, _) = body.split_horizontally(WIDTH - LEGEND_WIDTH);
        let (xr, yr) = (set.x.1, set.y.1);
        let (lo, hi) = ordered(xr, yr);
        let mut chart = ChartBuilder::on(&plot_area)
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(64)
            .build_cartesian_2d(lo[0]..hi[0], lo[1]..hi[1])?;
        chart
            .configure_mesh()
            .disable_mesh()
            .x_desc(set.x.0.as_str())
            .y_desc(set.y.0.as_str())
            .label_style((FAMILY, TICK_SIZE + 1).into_font())
            .axis_desc_style((FAMILY, AXIS_SIZE + 2).into_font())
            .draw()?;
        // The regions, one rectangle per run of equal cells along a row.
        let edge = |r: [f64; 2], k: usize, n: usize| r[0] + (r[1] - r[0]) * k as f64 / n as f64;
        let mut runs = Vec::new();
        for iy in 0..ny {
            let row = &regions.cells[iy * nx..(iy + 1) * nx];
            let mut start = 0;
            for ix in 1..=nx {
                if ix == nx || row[ix] != row[start] {
                    let corners = [
                        (edge(xr, start, nx), edge(yr, iy, ny)),
                        (edge(xr, ix, nx), edge(yr, iy + 1, ny)),
                    ];
                    runs.push(Rectangle::new(corners, self.colours[row[start]].filled()));
                    start = ix;
                }
            }
        }
        chart.draw_series(runs)?;
        draw_curves(&mut chart, root, set, (lo, hi), false)?;
        // Each region's number at its sample, on a light box.
        let h = line_height(KEY_SIZE);
        let plot = pixels(chart.plotting_area());
        for (k, r) in regions.regions.iter().enumerate() {
            let (x, y) = (r.sample[0], r.sample[1]);
            if !(x.is_finite() && y.is_finite()) {
                continue;
            }
            let text = (k + 1).to_string();
            let w = text_width(&text, KEY_SIZE) + 6;
            // Kept inside the plot, also for a region whose sample lies on the box's edge.
            let c = chart.backend_coord(&(x, y));
            let c = (
                c.0.clamp(
                    plot.x0 + w / 2 + 1,
                    (plot.x1 - w / 2 - 1).max(plot.x0 + w / 2 + 1),
                ),
                c.1.clamp(
                    plot.y0 + h / 2 + 1,
                    (plot.y1 - h / 2 - 1).max(plot.y0 + h / 2 + 1),
                ),
            );
            let b = Rect::at(c.0 - w / 2, c.1 - h / 2, (w, h));
            root.draw(&Rectangle::new(
                [(b.x0, b.y0), (b.x1, b.y1)],
                WHITE.mix(0.8).filled(),
            ))?;
            root.draw(&Text::new(
                text,
                c,
                (FAMILY, KEY_SIZE)
                    .into_font()
                    .color(&INK)
                    .pos(Pos::new(HPos::Center, VPos::Center)),
            ))?;
        }
        for ((legend, layout), origin) in self.legends.iter().zip(self.legend_origins()) {
            legend.draw(layout, root, origin)?;
        }
        Ok(())
    }
}

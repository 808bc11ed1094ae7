//! The bifurcation diagram of a sweep, in the style of the paper's Figs. 9–10:
//! switching phase `W t mod 2π` and switching displacement against the
//! parameter, the eigenvalues' moduli and real parts; one colour per
//! structure (named in the legend), transitions as dashed vertical lines.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;

use crate::output::plot::{register, Format, FAMILY};
use crate::study::sweep::{Sweep, TransitionKind};

const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(214, 39, 40),
    RGBColor(44, 160, 44),
    RGBColor(148, 103, 189),
    RGBColor(255, 127, 14),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(23, 190, 207),
    RGBColor(188, 189, 34),
    RGBColor(127, 127, 127),
];

/// Panel titles, in drawing order.
pub const SWEEP_TITLES: [&str; 4] = [
    "switching phase W t mod 2π",
    "switching displacement x",
    "eigenvalue moduli |λ|",
    "eigenvalue real parts Re λ",
];

fn kind_name(k: TransitionKind) -> &'static str {
    match k {
        TransitionKind::Grazing => "GB",
        TransitionKind::StickOnset => "stick onset",
        TransitionKind::StickVanishing => "stick vanishing",
        TransitionKind::PassableOnset => "passable onset",
        TransitionKind::Eigenvalue => "|λ| = 1",
    }
}

/// Draw `sweep` into `path` (SVG or PNG by extension).
pub fn plot_sweep(sweep: &Sweep, title: &str, path: &Path) -> Result<(), String> {
    let format = Format::of(path)?;
    register()?;
    let fail = |e: String| format!("cannot draw `{}`: {e}", path.display());
    let size = (1200, 1000);
    match format {
        Format::Svg => {
            let root = SVGBackend::new(path, size).into_drawing_area();
            draw(&root, sweep, title).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, size).into_drawing_area();
            draw(&root, sweep, title).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    sweep: &Sweep,
    title: &str,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
    let body = root.titled(title, (FAMILY, 22).into_font()).map_err(err)?;
    let areas = body.split_evenly((2, 2));
    // Structures in order of first appearance get the colours.
    let mut names: Vec<String> = Vec::new();
    for p in &sweep.points {
        for m in &p.motions {
            if m.structure != "NM" && !names.contains(&m.structure) {
                names.push(m.structure.clone());
            }
        }
    }
    let colour = |s: &str| PALETTE[names.iter().position(|n| n == s).unwrap_or(0) % PALETTE.len()];
    let lo = sweep.points.first().map_or(0.0, |p| p.value);
    let hi = sweep.points.last().map_or(1.0, |p| p.value);
    type Getter = fn(&crate::study::sweep::MotionSummary) -> Vec<f64>;
    let getters: [Getter; 4] = [
        |m| m.points.iter().map(|p| p.phase).collect(),
        |m| m.points.iter().map(|p| p.x).collect(),
        |m| m.eigenvalues.iter().map(|e| e[0].hypot(e[1])).collect(),
        |m| m.eigenvalues.iter().map(|e| e[0]).collect(),
    ];
    for (panel, area) in areas.iter().enumerate() {
        let get = getters[panel];
        let mut ys: Vec<f64> = Vec::new();
        for p in &sweep.points {
            for m in &p.motions {
                ys.extend(get(m).into_iter().filter(|v| v.is_finite()));
            }
        }
        let (mut y0, mut y1) = ys
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                (a.min(v), b.max(v))
            });
        if panel == 0 {
            (y0, y1) = (0.0, std::f64::consts::TAU);
        }
        if !(y0.is_finite() && y1.is_finite()) || y0 >= y1 {
            (y0, y1) = (y0.min(0.0) - 1.0, y1.max(0.0) + 1.0);
        }
        let pad = 0.05 * (y1 - y0);
        let mut chart = ChartBuilder::on(area)
            .caption(SWEEP_TITLES[panel], (FAMILY, 18).into_font())
            .margin(12)
            .x_label_area_size(40)
            .y_label_area_size(60)
            .build_cartesian_2d(lo..hi, (y0 - pad)..(y1 + pad))
            .map_err(err)?;
        chart
            .configure_mesh()
            .light_line_style(RGBColor(238, 238, 238))
            .x_desc(sweep.param.as_str())
            .label_style((FAMILY, 13).into_font())
            .axis_desc_style((FAMILY, 15).into_font())
            .draw()
            .map_err(err)?;
        if panel >= 2 {
            let level = if panel == 2 { 1.0 } else { 0.0 };
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(lo, level), (hi, level)],
                    5,
                    4,
                    BLACK.stroke_width(1),
                ))
                .map_err(err)?;
        }
        for t in &sweep.transitions {
            chart
                .draw_series(DashedLineSeries::new(
                    vec![(t.value, y0 - pad), (t.value, y1 + pad)],
                    6,
                    4,
                    RGBColor(120, 120, 120).stroke_width(1),
                ))
                .map_err(err)?;
            if panel == 0 {
                chart
                    .draw_series(std::iter::once(Text::new(
                        kind_name(t.kind).to_string(),
                        (t.value, y1 + 0.5 * pad),
                        (FAMILY, 11).into_font().color(&RGBColor(90, 90, 90)),
                    )))
                    .map_err(err)?;
            }
        }
        for name in &names {
            let c = colour(name);
            let pts: Vec<(f64, f64)> = sweep
                .points
                .iter()
                .flat_map(|p| {
                    p.motions
                        .iter()
                        .filter(|m| &m.structure == name)
                        .flat_map(move |m| get(m).into_iter().map(move |y| (p.value, y)))
                })
                .filter(|(_, y)| y.is_finite())
                .collect();
            let series = chart
                .draw_series(
                    pts.into_iter()
                        .map(|(x, y)| Circle::new((x, y), 2, c.filled())),
                )
                .map_err(err)?;
            if panel == 1 {
                series
                    .label(name.clone())
                    .legend(move |(x, y)| Circle::new((x + 8, y), 4, c.filled()));
            }
        }
        if panel == 1 && !names.is_empty() {
            chart
                .configure_series_labels()
                .position(SeriesLabelPosition::UpperRight)
                .background_style(WHITE.mix(0.85))
                .border_style(RGBColor(180, 180, 180))
                .label_font((FAMILY, 12).into_font())
                .draw()
                .map_err(err)?;
        }
    }
    Ok(())
}

//! The trade as a table and a figure: error against computing time, one
//! point per piece count and per integrator tolerance (log–log).

use std::path::Path;

use plotters::prelude::*;

use crate::output::plot::{register, Format, FAMILY};
use crate::study::trade::Trade;

/// A text table of the trade.
pub fn table(t: &Trade) -> String {
    let mut out = format!(
        "speed/accuracy trade of `{}` (reference: the law integrated at rtol {:e}, {} belt events per cycle, amplitude {:.9})\n\n",
        t.model,
        t.reference_tol,
        t.reference.belt_events.len(),
        t.reference.amplitude
    );
    out.push_str(&format!(
        "{:<11} {:>7} {:>8} {:>12} {:>12} {:>12} {:>12} {:>12}  structure / note\n",
        "method", "pieces", "tol", "time [ms]", "err W t", "err x", "err ampl.", "error"
    ));
    for r in &t.rows {
        let pieces = r.pieces.map_or("-".into(), |n| n.to_string());
        let tol = r.tol.map_or("-".into(), |t| format!("{t:e}"));
        let what = r.note.clone().unwrap_or_else(|| {
            if r.structure.len() > 60 {
                format!("{}… ({} chars)", &r.structure[..57], r.structure.len())
            } else {
                r.structure.clone()
            }
        });
        out.push_str(&format!(
            "{:<11} {:>7} {:>8} {:>12.4} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e}  {}\n",
            r.method,
            pieces,
            tol,
            r.seconds * 1e3,
            r.error_phase,
            r.error_x,
            r.error_amplitude,
            r.error,
            what
        ));
    }
    match t.order {
        Some(o) => out.push_str(&format!(
            "\nobserved convergence order in N (N >= 8): {o:.3} (interpolating a smooth law: 2)\n"
        )),
        None => {
            out.push_str("\nobserved convergence order in N: not enough comparable piece counts\n")
        }
    }
    out
}

/// Error against time, log–log, into `path` (SVG or PNG).
pub fn plot_trade(t: &Trade, path: &Path) -> Result<(), String> {
    let format = Format::of(path)?;
    register()?;
    let fail = |e: String| format!("cannot draw `{}`: {e}", path.display());
    match format {
        Format::Svg => {
            let root = SVGBackend::new(path, (900, 650)).into_drawing_area();
            draw(&root, t).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
        Format::Png => {
            let root = BitMapBackend::new(path, (900, 650)).into_drawing_area();
            draw(&root, t).map_err(fail)?;
            root.present().map_err(|e| fail(e.to_string()))
        }
    }
}

fn draw<DB: DrawingBackend>(
    root: &DrawingArea<DB, plotters::coord::Shift>,
    t: &Trade,
) -> Result<(), String> {
    let err = |e: DrawingAreaErrorKind<DB::ErrorType>| e.to_string();
    root.fill(&WHITE).map_err(err)?;
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
        )
        .map_err(err)?;
    chart
        .configure_mesh()
        .x_desc("time [ms]")
        .y_label_formatter(&|v| format!("{v:.0e}"))
        .x_label_formatter(&|v| format!("{v}"))
        .y_desc("largest error (switching points, amplitude)")
        .label_style((FAMILY, 13).into_font())
        .axis_desc_style((FAMILY, 15).into_font())
        .draw()
        .map_err(err)?;
    let blue = RGBColor(31, 119, 180);
    let red = RGBColor(214, 39, 40);
    for (pieces, colour, name) in [
        (true, blue, "N-piece analytical prediction"),
        (false, red, "integrator, tolerance ladder"),
    ] {
        let series: Vec<(f64, f64)> = pts
            .iter()
            .filter(|p| p.3 == pieces)
            .map(|p| (p.0, p.1))
            .collect();
        chart
            .draw_series(LineSeries::new(series.clone(), colour.stroke_width(1)))
            .map_err(err)?
            .label(name)
            .legend(move |(x, y)| Circle::new((x + 8, y), 4, colour.filled()));
        chart
            .draw_series(
                series
                    .into_iter()
                    .map(|p| Circle::new(p, 4, colour.filled())),
            )
            .map_err(err)?;
    }
    for p in &pts {
        chart
            .draw_series(std::iter::once(Text::new(
                format!(" {}", p.2),
                (p.0, p.1),
                (FAMILY, 12).into_font(),
            )))
            .map_err(err)?;
    }
    chart
        .configure_series_labels()
        .position(SeriesLabelPosition::UpperRight)
        .background_style(WHITE.mix(0.85))
        .border_style(RGBColor(180, 180, 180))
        .label_font((FAMILY, 13).into_font())
        .draw()
        .map_err(err)?;
    Ok(())
}

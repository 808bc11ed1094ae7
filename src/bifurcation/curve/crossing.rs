//! Where a curve crosses a line of the plane: each crossing solved on the
//! extended system with the line's parameter fixed (not interpolated).

use crate::bifurcation::bordered::Correction;
use crate::model::Model;

use super::start::{system, to_point, unknowns};
use super::{Curve, CurveOptions, CurvePoint, Line, Plane};

/// Where `curve` crosses `line`, each crossing solved exactly (the curve's
/// equations with the line's parameter fixed), in curve order. A crossing
/// whose corrector fails is left out.
pub fn crossings<M: Model>(
    base: &M::Params,
    plane: &Plane,
    curve: &Curve,
    line: Line,
    opts: &CurveOptions,
) -> Vec<CurvePoint> {
    let mut out = Vec::new();
    let Some(first) = curve.points.first() else {
        return out;
    };
    let Ok(mut sys) = system::<M>(
        base,
        plane,
        curve.structure.as_ref(),
        first,
        curve.condition,
    ) else {
        return out;
    };
    sys.pin_tangent_arrivals(&unknowns(first));
    let (axis, value) = match line {
        Line::X(v) => (0, v),
        Line::Y(v) => (1, v),
    };
    let coord = |q: &CurvePoint| if axis == 0 { q.x } else { q.y };
    let n = sys.len();
    let mut border = vec![0.0; n];
    sys.axis(axis, &mut border);
    let np = curve.points.len();
    // A closed curve's last point joins its first.
    let pairs = if curve.ends.is_empty() && np > 2 {
        np
    } else {
        np - 1
    };
    for i in 0..pairs {
        let (a, b) = (&curve.points[i], &curve.points[(i + 1) % np]);
        let (da, db) = (coord(a) - value, coord(b) - value);
        if da == 0.0 {
            out.push(a.clone());
            continue;
        }
        if !(da < 0.0 && db > 0.0 || da > 0.0 && db < 0.0) {
            continue;
        }
        let theta = da / (da - db);
        let (xa, mut xb) = (unknowns(a), unknowns(b));
        if i + 1 == np && n > 2 {
            // Across the closing pair, the phases continue by whole turns.
            let turns = ((xa[1] - xb[1]) / std::f64::consts::TAU).round();
            for k in 0..(n - 2) / 2 {
                xb[2 * k + 1] += turns * std::f64::consts::TAU;
            }
        }
        let mut x: Vec<f64> = xa
            .iter()
            .zip(&xb)
            .map(|(p, q)| p + theta * (q - p))
            .collect();
        x[n - 2 + axis] = value;
        let anchor = x.clone();
        if let Correction::Converged { .. } =
            sys.correct(&mut x, &border, &anchor, opts.tolerance, 40)
        {
            x[n - 2 + axis] = value;
            out.push(to_point(&x));
        }
    }
    // The last point of an open curve on the line.
    if !(curve.ends.is_empty() && np > 2) && np > 0 && coord(&curve.points[np - 1]) == value {
        out.push(curve.points[np - 1].clone());
    }
    out
}

//! A curves run's box checked into a [`Plane`]: both parameters free
//! parameters of the model and distinct, both ranges finite and non-empty,
//! the model valid at the box's corners, every seed and `--at` line inside
//! the box.

use crate::bifurcation::curve::{Line, Plane};
use crate::model::param::ParamSet;
use crate::model::Model;

use super::{CurvesError, CurvesOptions};

impl CurvesOptions {
    /// The line `name = value` of this box: vertical (`x = value`) when
    /// `name` is the horizontal parameter, horizontal when it is the
    /// vertical one. `what` names the option (`--seed`, `--at`) in errors.
    pub fn line(&self, what: &str, name: &str, value: f64) -> Result<Line, CurvesError> {
        let line = if name == self.x.0 {
            Line::X(value)
        } else if name == self.y.0 {
            Line::Y(value)
        } else {
            return Err(CurvesError::LineParam {
                what: what.to_string(),
                name: name.to_string(),
                x: self.x.0.clone(),
                y: self.y.0.clone(),
            });
        };
        self.check_line(what, line)?;
        Ok(line)
    }

    /// `line` lies in the box (a finite value within its parameter's range).
    fn check_line(&self, what: &str, line: Line) -> Result<(), CurvesError> {
        let ((name, [lo, hi]), value) = match line {
            Line::X(v) => (&self.x, v),
            Line::Y(v) => (&self.y, v),
        };
        if !value.is_finite() || value < *lo || value > *hi {
            return Err(CurvesError::LineOutside {
                what: what.to_string(),
                name: name.clone(),
                value,
                lo: *lo,
                hi: *hi,
            });
        }
        Ok(())
    }

    /// The checked plane of model `M` at `base`.
    pub fn plane<M: Model>(&self, base: &M::Params) -> Result<Plane, CurvesError> {
        // The parameter set holds the free parameters alone (a scene's
        // fixed ones are constants), indexed by their place among them.
        let info = M::info(base);
        let index = |name: &str| {
            base.index_of(name)
                .ok_or_else(|| CurvesError::UnknownParam {
                    name: name.to_string(),
                    model: info.name.to_string(),
                    free: info
                        .free
                        .iter()
                        .map(|&i| info.params[i].name)
                        .collect::<Vec<_>>()
                        .join(", "),
                })
        };
        let (x, y) = (index(&self.x.0)?, index(&self.y.0)?);
        if x == y {
            return Err(CurvesError::SameParam(self.x.0.clone()));
        }
        for (name, [lo, hi]) in [&self.x, &self.y] {
            if !lo.is_finite() || !hi.is_finite() || lo >= hi {
                return Err(CurvesError::Range {
                    name: name.clone(),
                    lo: *lo,
                    hi: *hi,
                });
            }
        }
        for &vx in &self.x.1 {
            for &vy in &self.y.1 {
                let mut p = *base;
                p.set(x, vx);
                p.set(y, vy);
                p.check().map_err(|source| CurvesError::Corner {
                    at: format!("{} = {vx}, {} = {vy}", self.x.0, self.y.0),
                    source,
                })?;
            }
        }
        for &l in &self.seeds {
            self.check_line("--seed", l)?;
        }
        for &l in &self.at {
            self.check_line("--at", l)?;
        }
        Ok(Plane {
            x,
            y,
            x_range: self.x.1,
            y_range: self.y.1,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::paper::{Paper, Params};

    fn opts() -> CurvesOptions {
        CurvesOptions {
            x: ("W".into(), [0.2, 8.0]),
            y: ("Q0".into(), [0.0, 180.0]),
            seeds: Vec::new(),
            at: Vec::new(),
        }
    }

    #[test]
    fn lines_by_name_and_inside_the_box() {
        let o = opts();
        assert_eq!(o.line("--seed", "Q0", 70.0), Ok(Line::Y(70.0)));
        assert_eq!(o.line("--at", "W", 8.0), Ok(Line::X(8.0)));
        assert!(matches!(
            o.line("--seed", "d", 0.1),
            Err(CurvesError::LineParam { .. })
        ));
        for v in [-1.0, 180.5, f64::NAN, f64::INFINITY] {
            assert!(matches!(
                o.line("--at", "Q0", v),
                Err(CurvesError::LineOutside { .. })
            ));
        }
    }

    #[test]
    fn the_plane_is_checked() {
        let base = Params::default();
        let p = opts().plane::<Paper>(&base).expect("valid");
        assert_eq!(p.x_range, [0.2, 8.0]);
        assert_ne!(p.x, p.y);
        let mut o = opts();
        o.y.0 = "W".into();
        assert_eq!(
            o.plane::<Paper>(&base),
            Err(CurvesError::SameParam("W".into()))
        );
        let mut o = opts();
        o.x.0 = "nope".into();
        assert!(matches!(
            o.plane::<Paper>(&base),
            Err(CurvesError::UnknownParam { .. })
        ));
        let mut o = opts();
        o.x.1 = [3.0, 3.0];
        assert!(matches!(
            o.plane::<Paper>(&base),
            Err(CurvesError::Range { .. })
        ));
        let mut o = opts();
        o.seeds.push(Line::X(9.0));
        assert!(matches!(
            o.plane::<Paper>(&base),
            Err(CurvesError::LineOutside { .. })
        ));
    }
}

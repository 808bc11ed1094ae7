//! The speed/accuracy trade, measured: the periodic motion of a
//! smooth-law model predicted analytically by its N-piece models and
//! computed by numerical integration at several tolerances, each compared
//! with the law integrated at a tight tolerance (switching points at the belt
//! speed, amplitude) and timed; and, for self-excited oscillators, where
//! each N-piece model's steady sliding changes stability along a parameter
//! against the law's own threshold ([`Thresholds`]).

use std::time::Instant;

use serde::Serialize;

use crate::dynamics::integrate::{Integrator, Side, State};
use crate::dynamics::simulate::{Location, Segment, SimOptions, Simulator};
use crate::model::param::ParamSet;
use crate::model::smooth::SmoothModel;
use crate::model::{MappingKind, Model, ModelVisitor};
use crate::models::ModelRef;
use crate::orbit::attractor::{self, Attractor, AttractorOptions};
use crate::study::equilibria::{self, Scan};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// The motion's fingerprint used for comparisons.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Fingerprint {
    /// Events at the belt speed over one cycle: `(W t mod 2π, x)`, by phase.
    pub belt_events: Vec<(f64, f64)>,
    /// `max x − min x` over one cycle.
    pub amplitude: f64,
    /// Forcing periods per cycle.
    pub periods: u32,
}

/// One computation and its error against the reference.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct TradeRow {
    /// `"pieces"` or `"integrator"`.
    pub method: String,
    /// Number of pieces (analytical prediction).
    pub pieces: Option<u32>,
    /// Integrator tolerance.
    pub tol: Option<f64>,
    /// The structure found (piecewise models) or `-`.
    pub structure: String,
    /// Wall time of the computation, seconds.
    pub seconds: f64,
    /// Largest error of a switching phase (W t) at the belt speed.
    pub error_phase: f64,
    /// Largest error of a switching displacement at the belt speed.
    pub error_x: f64,
    /// Error of the amplitude.
    pub error_amplitude: f64,
    /// The largest of the three (NaN when the motions differ in kind).
    pub error: f64,
    /// Why there is no error, if any.
    pub note: Option<String>,
}

impl TradeRow {
    /// The row of one method: its errors against `reference`, or the error
    /// that stopped it (`note`, every number NaN).
    fn measured(
        method: &str,
        pieces: Option<u32>,
        tol: Option<f64>,
        result: Result<(Fingerprint, String, f64), String>,
        reference: &Fingerprint,
    ) -> Self {
        let row = |structure: String, seconds: f64, errors: [f64; 4], note: Option<String>| Self {
            method: method.into(),
            pieces,
            tol,
            structure,
            seconds,
            error_phase: errors[0],
            error_x: errors[1],
            error_amplitude: errors[2],
            error: errors[3],
            note,
        };
        match result {
            Ok((fp, structure, seconds)) => {
                let (ep, ex, ea, note) = compare(&fp, reference);
                let error = if note.is_some() {
                    f64::NAN
                } else {
                    ep.max(ex).max(ea)
                };
                row(structure, seconds, [ep, ex, ea, error], note)
            }
            Err(e) => row("-".into(), f64::NAN, [f64::NAN; 4], Some(e)),
        }
    }
}

/// The whole measurement.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Trade {
    /// The smooth model.
    pub model: String,
    /// The reference: the law integrated at this tolerance, then shot to a periodic motion.
    pub reference_tol: f64,
    /// The reference motion.
    pub reference: Fingerprint,
    /// One row per piece count and per tolerance.
    pub rows: Vec<TradeRow>,
    /// Least-squares slope of `log error` against `log N` (N ≥ 8): the observed convergence order.
    pub order: Option<f64>,
}

/// Why a trade could not be measured.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum TradeError {
    /// Bad input (parameters, piece counts).
    #[error("{0}")]
    Input(String),
    /// The reference could not be computed.
    #[error("the reference integration failed: {0}")]
    Reference(String),
}

fn compare(a: &Fingerprint, reference: &Fingerprint) -> (f64, f64, f64, Option<String>) {
    let da = (a.amplitude - reference.amplitude).abs();
    if a.periods != reference.periods || a.belt_events.len() != reference.belt_events.len() {
        return (
            f64::NAN,
            f64::NAN,
            da,
            Some(format!(
                "{} belt events in {} period(s) against the reference's {} in {}",
                a.belt_events.len(),
                a.periods,
                reference.belt_events.len(),
                reference.periods
            )),
        );
    }
    let (mut dp, mut dx) = (0.0f64, 0.0f64);
    for (p, q) in a.belt_events.iter().zip(&reference.belt_events) {
        let d = (p.0 - q.0).rem_euclid(TAU);
        dp = dp.max(d.min(TAU - d));
        dx = dx.max((p.1 - q.1).abs());
    }
    (dp, dx, da, None)
}

/// The reference fingerprint (and how long it took) of the smooth model `S`
/// at `p`: integrate from rest past the transient, shoot to the periodic
/// state, follow one cycle.
fn integrated<S: SmoothModel>(
    p: S::Params,
    rtol: f64,
    periods: u32,
) -> Result<(Fingerprint, f64), String> {
    let start = Instant::now();
    let integ = Integrator::<S>::new(p, rtol).map_err(|e| e.to_string())?;
    let rest = State {
        phase: 0.0,
        x: 0.0,
        v: 0.0,
        side: if integ.belt() > 0.0 {
            Side::Below
        } else {
            Side::Above
        },
    };
    let mut after = integ
        .run(rest, 100.0 * TAU, |_| {})
        .map_err(|e| e.to_string())?;
    // Let the transient decay until one cycle moves the state by about the
    // tolerance, then refine by shooting (which may fail where the period map
    // is only as smooth as the integration: then the settled state is kept).
    let tol = (rtol * 10.0).max(1e-12);
    let mut moved = f64::INFINITY;
    for _ in 0..2000 {
        let next = integ
            .period_map(after, periods)
            .map_err(|e| e.to_string())?;
        moved = (next.x - after.x).abs().max((next.v - after.v).abs());
        after = next;
        if moved <= tol * (1.0 + after.x.abs()) {
            break;
        }
    }
    let periodic = match integ.shoot(after, periods, tol) {
        Ok(p) => p,
        Err(_) if moved <= 1e3 * tol * (1.0 + after.x.abs()) => after,
        Err(e) => return Err(e.to_string()),
    };
    let mut events = Vec::new();
    let (mut lo, mut hi) = (periodic.x, periodic.x);
    let mut state = periodic;
    let n = 400 * periods as usize;
    for i in 1..=n {
        let to = periodic.phase + TAU * periods as f64 * i as f64 / n as f64;
        state = integ
            .run(state, to, |e| events.push((e.phase.rem_euclid(TAU), e.x)))
            .map_err(|e| e.to_string())?;
        lo = lo.min(state.x);
        hi = hi.max(state.x);
    }
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok((
        Fingerprint {
            belt_events: events,
            amplitude: hi - lo,
            periods,
        },
        start.elapsed().as_secs_f64(),
    ))
}

/// The fingerprint of the piecewise model `M` at `p`: its attractor from rest.
fn piecewise<M: Model>(p: M::Params) -> Result<(Fingerprint, String, f64), String> {
    let start = Instant::now();
    let sim = Simulator::<M>::new(p, SimOptions::default()).map_err(|e| e.to_string())?;
    let rest = sim.start(0.0, 0.0, 0.0).map_err(|e| e.to_string())?;
    let motion = match attractor::find(&sim, rest, AttractorOptions::default())
        .map_err(|e| e.to_string())?
    {
        Attractor::Periodic(m) => m,
        Attractor::NoMotion(_) => return Err("no motion reaches the belt speed".into()),
        Attractor::Stick(_) => return Err("the mass sticks forever".into()),
        Attractor::Autonomous(_) => {
            return Err("no forcing: the stick-slip cycle is autonomous".into())
        }
    };
    let seconds = start.elapsed().as_secs_f64();
    let info = sim.info();
    let stick = info.stick_boundary();
    let m = motion.points.len();
    let shift = TAU * motion.structure.periods() as f64;
    let mut events: Vec<(f64, f64)> = Vec::new();
    let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
    for k in 0..m {
        let mi = info.mappings[motion.structure.steps()[k]];
        let a = motion.points[k];
        if Some(mi.from) == stick {
            events.push((a.phase.rem_euclid(TAU), a.x));
        }
        let b_phase = if k + 1 < m {
            motion.points[k + 1].phase
        } else {
            motion.points[0].phase + shift
        };
        let location = if mi.kind == MappingKind::Stick {
            Location::Stick
        } else {
            Location::Domain(mi.domain.expect("flow mapping"))
        };
        let seg = Segment {
            x: a.x,
            v: sim.velocity(mi.from),
            phase: a.phase,
            location,
            search_from: a.phase,
        };
        for i in 0..=40 {
            let phase = a.phase + (b_phase - a.phase) * i as f64 / 40.0;
            let (x, _) = sim.state_at(&seg, phase);
            lo = lo.min(x);
            hi = hi.max(x);
        }
    }
    // A stick onset and the stick's end are two belt events, as in the integration;
    // a point that is both the end of one stick mapping's arrival and a start is counted once.
    events.sort_by(|a, b| a.0.total_cmp(&b.0));
    events.dedup_by(|a, b| (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12);
    Ok((
        Fingerprint {
            belt_events: events,
            amplitude: hi - lo,
            periods: motion.structure.periods(),
        },
        motion.structure.notation(info),
        seconds,
    ))
}

struct Piecewise<'a> {
    set: &'a [(String, f64)],
}

impl ModelVisitor for Piecewise<'_> {
    type Output = Result<(Fingerprint, String, f64), String>;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        let pairs: Vec<(&str, f64)> = self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        Some(
            base.with_pairs(M::identity(&base), &pairs)
                .map_err(|e| e.to_string())
                .and_then(piecewise::<M>),
        )
    }
}

/// The trade for the smooth model `model` names (its piecewise scenes are
/// its scenes `plN`, compiled in as `NAME::plN` or in the same file).
pub struct Measure<'a> {
    /// The model.
    pub model: &'a ModelRef,
    /// Parameter values.
    pub set: &'a [(String, f64)],
    /// Piece counts.
    pub pieces: &'a [u32],
    /// Integrator tolerances.
    pub tols: &'a [f64],
    /// The reference tolerance.
    pub reference_tol: f64,
}

impl ModelVisitor for Measure<'_> {
    type Output = Result<Trade, TradeError>;
    fn smooth<S: SmoothModel>(self, base: S::Params) -> Option<Self::Output> {
        Some(self.measure::<S>(base))
    }
}

impl Measure<'_> {
    fn measure<S: SmoothModel>(self, base: S::Params) -> Result<Trade, TradeError> {
        let name = S::info(&base).name;
        let pairs: Vec<(&str, f64)> = self.set.iter().map(|(n, v)| (n.as_str(), *v)).collect();
        let p = base
            .with_pairs(S::identity(&base), &pairs)
            .map_err(|e| TradeError::Input(e.to_string()))?;
        if S::oscillator(&p).amplitude == 0.0 {
            return Err(TradeError::Input(format!(
                "`{name}` is unforced at these parameter values (forcing amplitude 0): it has no \
                 forced periodic motion to measure. Measure where steady sliding changes \
                 stability with `--threshold PARAM=FROM:TO:COUNT` (for example the belt speed), \
                 or switch the forcing on with `--set`"
            )));
        }
        // Piecewise predictions first: the finest one gives the period N of the motion.
        let mut pw = Vec::new();
        for &n in self.pieces {
            let scene = self.model.scene(&format!("pl{n}"));
            let missing = || {
                TradeError::Input(format!(
                    "no model `{scene}`: the model file needs `scene pl{n} {{ pieces: {n}; }}`"
                ))
            };
            let result = scene
                .visit(Piecewise { set: self.set })
                .map_err(|_| missing())?
                .ok_or_else(missing)?;
            pw.push((n, result));
        }
        let periods = pw
            .iter()
            .rev()
            .find_map(|(_, r)| r.as_ref().ok().map(|f| f.0.periods))
            .unwrap_or(1);
        let (reference, _) =
            integrated::<S>(p, self.reference_tol, periods).map_err(TradeError::Reference)?;
        let mut rows = Vec::new();
        for (n, result) in pw {
            rows.push(TradeRow::measured(
                "pieces",
                Some(n),
                None,
                result,
                &reference,
            ));
        }
        for &tol in self.tols {
            let result = integrated::<S>(p, tol, periods)
                .map(|(fp, seconds)| (fp, "-".to_string(), seconds));
            rows.push(TradeRow::measured(
                "integrator",
                None,
                Some(tol),
                result,
                &reference,
            ));
        }
        let order = convergence_order(&rows);
        Ok(Trade {
            model: name.to_string(),
            reference_tol: self.reference_tol,
            reference,
            rows,
            order,
        })
    }
}

/// Least-squares slope of `-log(error)` against `log N` over the piece
/// counts N ≥ 8 with a finite, positive error.
pub fn convergence_order(rows: &[TradeRow]) -> Option<f64> {
    let pts: Vec<(u32, f64)> = rows
        .iter()
        .filter_map(|r| Some((r.pieces?, r.error)))
        .collect();
    order_in_pieces(&pts)
}

/// Least-squares slope of `-log(error)` against `log N` over the pairs
/// `(N, error)` with N ≥ 8 and a finite, positive error.
fn order_in_pieces(errors: &[(u32, f64)]) -> Option<f64> {
    let pts: Vec<(f64, f64)> = errors
        .iter()
        .filter(|&&(n, e)| n >= 8 && e.is_finite() && e > 0.0)
        .map(|&(n, e)| ((n as f64).ln(), e.ln()))
        .collect();
    if pts.len() < 2 {
        return None;
    }
    let n = pts.len() as f64;
    let mx = pts.iter().map(|p| p.0).sum::<f64>() / n;
    let my = pts.iter().map(|p| p.1).sum::<f64>() / n;
    let sxy: f64 = pts.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    let sxx: f64 = pts.iter().map(|p| (p.0 - mx).powi(2)).sum();
    (sxx > 0.0).then(|| -sxy / sxx)
}

/// Where steady sliding changes stability along a parameter: one N-piece
/// model's thresholds against the law's.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct ThresholdRow {
    /// Number of pieces.
    pub pieces: u32,
    /// The located changes of stability, in the order of the grid.
    pub at: Vec<f64>,
    /// Largest relative error of a threshold against the law's (NaN when
    /// the number of changes differs).
    pub error: f64,
    /// Wall time of the scan, seconds.
    pub seconds: f64,
    /// Why there is no error, if any.
    pub note: Option<String>,
}

/// The thresholds of steady sliding measured for every piece count.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Thresholds {
    /// The smooth model.
    pub model: String,
    /// The parameter scanned.
    pub param: String,
    /// Its first and last value.
    pub range: [f64; 2],
    /// Number of grid values (each change is located between two of them).
    pub count: usize,
    /// The law's thresholds (its Hopf points), from its exact slope.
    pub law: Vec<f64>,
    /// Wall time of the law's scan, seconds.
    pub law_seconds: f64,
    /// One row per piece count.
    pub rows: Vec<ThresholdRow>,
    /// Least-squares slope of `-log(error)` against `log N` (N ≥ 8, errors
    /// above rounding): the observed order. `None` when fewer than two
    /// errors are above rounding.
    pub order: Option<f64>,
    /// Every piece count's thresholds are the law's to rounding (64 ulps).
    pub exact: bool,
}

/// The threshold measurement of the smooth model `model` along `range =
/// (name, from, to, count)`, its scenes `plN` for each N in `pieces`.
pub struct MeasureThresholds<'a> {
    /// The model.
    pub model: &'a ModelRef,
    /// Parameter values.
    pub set: &'a [(String, f64)],
    /// The parameter and its grid.
    pub range: (String, f64, f64, usize),
    /// Piece counts.
    pub pieces: &'a [u32],
}

impl ModelVisitor for MeasureThresholds<'_> {
    type Output = Result<Thresholds, TradeError>;
    fn smooth<S: SmoothModel>(self, base: S::Params) -> Option<Self::Output> {
        Some(self.measure::<S>(base))
    }
}

impl MeasureThresholds<'_> {
    fn request(&self) -> equilibria::Request {
        equilibria::Request {
            set: self.set.to_vec(),
            range: Some(self.range.clone()),
        }
    }

    fn measure<S: SmoothModel>(self, base: S::Params) -> Result<Thresholds, TradeError> {
        let input = |e: &dyn std::fmt::Display| TradeError::Input(e.to_string());
        let (name, from, to, count) = self.range.clone();
        let start = Instant::now();
        let law = self
            .request()
            .smooth::<S>(base)
            .expect("a smooth model")
            .map_err(|e| input(&e))?;
        let law_seconds = start.elapsed().as_secs_f64();
        let law: Vec<f64> = law.changes.iter().map(|c| c.change.at).collect();
        if law.is_empty() {
            return Err(TradeError::Input(format!(
                "the law's steady sliding does not change stability for {name} in [{from}, {to}]: \
                 widen the range (`stickslip equilibria --param {name}=…` shows its stability)"
            )));
        }
        let mut rows = Vec::new();
        for &n in self.pieces {
            let scene = self.model.scene(&format!("pl{n}"));
            let missing = || {
                TradeError::Input(format!(
                    "no model `{scene}`: the model file needs `scene pl{n} {{ pieces: {n}; }}`"
                ))
            };
            let start = Instant::now();
            let scan: Scan = scene
                .visit(self.request())
                .map_err(|_| missing())?
                .ok_or_else(missing)?
                .map_err(|e| input(&e))?;
            let seconds = start.elapsed().as_secs_f64();
            let at: Vec<f64> = scan.changes.iter().map(|c| c.change.at).collect();
            let (error, note) = if at.len() == law.len() {
                let e = at
                    .iter()
                    .zip(&law)
                    .map(|(a, b)| (a - b).abs() / b.abs())
                    .fold(0.0, f64::max);
                (e, None)
            } else {
                (
                    f64::NAN,
                    Some(format!(
                        "{} changes against the law's {}",
                        at.len(),
                        law.len()
                    )),
                )
            };
            rows.push(ThresholdRow {
                pieces: n,
                at,
                error,
                seconds,
                note,
            });
        }
        let rounding = 64.0 * f64::EPSILON;
        let above: Vec<(u32, f64)> = rows
            .iter()
            .filter(|r| r.error > rounding)
            .map(|r| (r.pieces, r.error))
            .collect();
        let exact = rows.iter().all(|r| r.error <= rounding);
        Ok(Thresholds {
            model: S::info(&base).name.to_string(),
            param: name,
            range: [from, to],
            count,
            law,
            law_seconds,
            rows,
            order: order_in_pieces(&above),
            exact,
        })
    }
}

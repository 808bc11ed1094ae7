//! Two-parameter transition curves and exact regime maps (`stickslip
//! curves`): every transition a sweep locates along the seed lines,
//! continued in both parameters to the box's edge, back to itself, or to a
//! codimension-two point ([`crate::bifurcation::curve`]).

use serde::Serialize;

mod codim2;
mod cover;
mod plane;
pub mod regions;
mod seeds;

pub use regions::{regions, Regions};

use crate::bifurcation::curve::{Curve, CurveOptions, Line};
use crate::bifurcation::TransitionKind;
use crate::model::param::ParamError;
use crate::model::Model;
use crate::study::sweep::{SweepError, SweepOptions};

use cover::Cover;

/// The box and the seeds of a curves run.
#[derive(Clone, Debug, PartialEq)]
pub struct CurvesOptions {
    /// The horizontal parameter and its range `[lo, hi]`.
    pub x: (String, [f64; 2]),
    /// The vertical parameter and its range.
    pub y: (String, [f64; 2]),
    /// Seed lines (`--seed Q0=70`: the sweep along `x` at `y = 70`;
    /// `--seed W=5`: along `y` at `x = 5`). The middle horizontal line when
    /// empty. More are added automatically.
    pub seeds: Vec<Line>,
    /// Report where each curve crosses these lines (`--at Q0=v1,v2`: the
    /// horizontal lines `y = v`; `--at W=...`: vertical ones).
    pub at: Vec<Line>,
}

/// One end of a curve, as reported.
#[derive(Clone, Debug, PartialEq)]
pub struct EndSummary {
    /// `box_edge`, `codim2`, `newton_failure` or `max_points`.
    pub reason: String,
    /// Where: `[x, y]`.
    pub point: [f64; 2],
    /// For `codim2`: its index in [`CurveSet::codim2`].
    pub codim2: Option<usize>,
    /// For `newton_failure`: why.
    pub detail: Option<String>,
    /// For `codim2`: how well the second condition holds there, relative
    /// to its scale ([`crate::bifurcation::curve::codim2_residual`]):
    /// rounding where the point was solved with both conditions.
    pub residual: Option<f64>,
}

/// One traced curve, as reported.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSummary {
    /// The transition it marks.
    pub kind: TransitionKind,
    /// The boundary involved (its name), if any.
    pub boundary: Option<String>,
    /// The motion whose condition vanishes: `P_{...}` (with `^N`) or `NM`.
    pub structure: String,
    /// Its first end (`None`: a closed curve).
    pub from: Option<EndSummary>,
    /// Its second end (`None`: a closed curve).
    pub to: Option<EndSummary>,
    /// Its points `[x, y]` in arclength order.
    pub points: Vec<[f64; 2]>,
    /// Its exact crossings of the `--at` lines, `[x, y]`.
    pub at: Vec<[f64; 2]>,
}

/// A codimension-two point: two conditions vanish at once.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Codim2Point {
    /// Horizontal parameter.
    pub x: f64,
    /// Vertical parameter.
    pub y: f64,
    /// The transitions that meet there.
    pub kinds: Vec<TransitionKind>,
    /// The curves that end or pass there (indices in [`CurveSet::curves`]).
    pub curves: Vec<usize>,
}

/// A transition a sweep located whose curve could not be traced from it,
/// and that no traced curve passes: a curve the run is missing.
#[derive(Clone, Debug, PartialEq)]
pub struct FailedStart {
    /// The transition.
    pub kind: TransitionKind,
    /// The boundary involved (its name), if any.
    pub boundary: Option<String>,
    /// The motion: `P_{...}` (with `^N`) or `NM`.
    pub structure: String,
    /// Where it was located: `[x, y]`.
    pub point: [f64; 2],
    /// Why the trace failed.
    pub why: String,
}

/// Everything a curves run found.
#[derive(Clone, Debug, PartialEq)]
pub struct CurveSet {
    /// The horizontal parameter's name and range.
    pub x: (String, [f64; 2]),
    /// The vertical parameter's name and range.
    pub y: (String, [f64; 2]),
    /// The curves.
    pub curves: Vec<CurveSummary>,
    /// The codimension-two points.
    pub codim2: Vec<Codim2Point>,
    /// The located transitions whose curve is missing (its trace failed).
    pub failed_starts: Vec<FailedStart>,
}

/// Why a curves run could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurvesError {
    /// A bad parameter or range.
    #[error("{0}")]
    Options(String),
    /// `--x` or `--y` names no free parameter of the model.
    #[error("`{name}` is not a free parameter of {model}; free: {free}")]
    UnknownParam {
        /// The name given.
        name: String,
        /// The model.
        model: String,
        /// Its free parameters.
        free: String,
    },
    /// `--x` and `--y` name one parameter.
    #[error("--x and --y both name `{0}`: give two different parameters")]
    SameParam(String),
    /// An empty, reversed or non-finite range.
    #[error("bad range of `{name}`: {lo}:{hi} (need finite from < to)")]
    Range {
        /// The parameter.
        name: String,
        /// From.
        lo: f64,
        /// To.
        hi: f64,
    },
    /// The model rejects its parameters at a corner of the box.
    #[error("the box reaches invalid parameters at {at}: {source}")]
    Corner {
        /// The corner.
        at: String,
        /// Why.
        source: ParamError,
    },
    /// A `--seed` or `--at` line on neither parameter of the box.
    #[error("{what} {name}=...: `{name}` is neither --x ({x}) nor --y ({y})")]
    LineParam {
        /// `--seed` or `--at`.
        what: String,
        /// The parameter given.
        name: String,
        /// The horizontal parameter.
        x: String,
        /// The vertical one.
        y: String,
    },
    /// A `--seed` or `--at` line outside the box.
    #[error("{what} {name}={value}: outside the box's range {lo}:{hi} of `{name}`")]
    LineOutside {
        /// `--seed` or `--at`.
        what: String,
        /// The parameter.
        name: String,
        /// The value given.
        value: f64,
        /// The range's from.
        lo: f64,
        /// Its to.
        hi: f64,
    },
    /// The sweep along a seed line failed.
    #[error("the sweep along the seed line failed: {0}")]
    Sweep(#[from] SweepError),
}

/// How thoroughly a curves run covers the box.
#[derive(Clone, Copy, Debug)]
pub struct CurvesSettings {
    /// Grid values of each seed line's sweep.
    pub count: usize,
    /// Extra seed lines spread over the box, this many each way (`n`
    /// horizontal lines at `y = lo + k (hi − lo) / (n + 1)`, and vertical
    /// ones).
    pub spread: usize,
    /// Sweep the box's four edges too: every curve that leaves the box
    /// crosses one. On by default: measured with
    /// `bash benches/curves-runs.sh` and `EXTRA=--no-edges` (the guide,
    /// "Regime maps"), it finds 29 curves on Shaw's box where 20 are found
    /// without, and 70 on Fig. 11's where 39 are, at three times the run
    /// time there.
    pub edges: bool,
    /// At most this many lines added near transitions no traced curve passes.
    pub max_missing: usize,
    /// At most this many lines added between neighbouring lines whose
    /// motions differ in a way no curve between them explains.
    pub max_refine: usize,
    /// Short sweeps across each curve the lines traced, at this many
    /// places along it (what lies across a border no line crosses).
    pub probes: usize,
    /// Transitions of motions of more mappings than this are not traced
    /// (the long cycles of period-adding cascades: thin bands whose curves
    /// cost a continuation of that many switching points each). The
    /// default, 24, traces the paper model's cascades to period 7 (Fig. 11:
    /// 39 curves where 12 gives 31, 6.6 s where 12 takes 3.8 s).
    pub max_mappings: usize,
    /// At most this many curves traced by branch switching at the
    /// codimension-two points of the curves found (the second condition's
    /// curve of the same motion through each).
    pub max_partners: usize,
    /// The sweeps' settings.
    pub sweep: SweepOptions,
    /// The curves' continuation.
    pub curve: CurveOptions,
}

impl Default for CurvesSettings {
    fn default() -> Self {
        Self {
            count: 100,
            spread: 3,
            edges: true,
            max_missing: 6,
            max_refine: 4,
            probes: 0,
            max_mappings: 24,
            max_partners: 200,
            sweep: SweepOptions::default(),
            curve: CurveOptions {
                max_points: 2000,
                ..CurveOptions::default()
            },
        }
    }
}

/// Trace every transition curve of `M` at `base` in the box of `opts`.
pub fn curves<M: Model>(base: &M::Params, opts: &CurvesOptions) -> Result<CurveSet, CurvesError> {
    curves_with::<M>(base, opts, &CurvesSettings::default())
}

/// [`curves`] with the given settings.
pub fn curves_with<M: Model>(
    base: &M::Params,
    opts: &CurvesOptions,
    settings: &CurvesSettings,
) -> Result<CurveSet, CurvesError> {
    traced::<M>(base, opts, settings).map(|(set, _)| set)
}

/// [`curves_with`], with the traced curves themselves (conditions,
/// structures, switching points), in the order of [`CurveSet::curves`].
pub fn traced<M: Model>(
    base: &M::Params,
    opts: &CurvesOptions,
    settings: &CurvesSettings,
) -> Result<(CurveSet, Vec<Curve>), CurvesError> {
    let plane = opts.plane::<M>(base)?;
    if settings.count < 2 {
        return Err(CurvesError::Options(format!(
            "each line's sweep needs at least 2 grid values, not {}",
            settings.count
        )));
    }
    if settings.max_mappings == 0 {
        return Err(CurvesError::Options(
            "the longest motion traced (--max-mappings, max_mappings) must have at least 1 mapping, not 0".into(),
        ));
    }
    let mut cover = Cover::<M>::new(base, plane, settings);
    let seeds = if opts.seeds.is_empty() {
        vec![Line::Y(0.5 * (opts.y.1[0] + opts.y.1[1]))]
    } else {
        opts.seeds.clone()
    };
    for line in seeds {
        cover.line(line)?;
    }
    // The lines whose crossings are asked for are swept too, so that every
    // transition a sweep locates on them starts a curve.
    for &line in &opts.at {
        if !opts.seeds.contains(&line) {
            cover.line(line)?;
        }
    }
    cover.spread();
    cover.missing();
    cover.refine();
    cover.probe();
    cover.carry();
    cover.partners();
    Ok(cover.finish(opts))
}

//! Two-parameter transition curves and exact regime maps (`stickslip
//! curves`): every transition a sweep locates along the seed lines,
//! continued in both parameters to the box's edge, back to itself, or to a
//! codimension-two point ([`crate::bifurcation::curve`]).

use serde::Serialize;

pub mod regions;

pub use regions::{regions, Regions};

use crate::bifurcation::curve::Line;
use crate::bifurcation::TransitionKind;
use crate::model::Model;

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
}

/// Why a curves run could not run.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum CurvesError {
    /// A bad parameter or range.
    #[error("{0}")]
    Options(String),
}

/// Trace every transition curve of `M` at `base` in the box of `opts`.
pub fn curves<M: Model>(base: &M::Params, opts: &CurvesOptions) -> Result<CurveSet, CurvesError> {
    let _ = (base, opts);
    Err(CurvesError::Options("not built yet".into()))
}

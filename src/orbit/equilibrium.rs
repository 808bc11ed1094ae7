//! Steady sliding: the equilibrium of an unforced friction oscillator
//! (SPEC §14), its exact linearisation, and where along a parameter it loses
//! stability.
//!
//! With no forcing (`A0 = 0`) the mass can rest in the lab frame while the
//! belt slides under it: `v = 0`, `x* = −f(0)/c`, with the relative velocity
//! `u = −V`. Its linearisation is `x'' + (2 d + f'(0)) x' + c x = 0`: the
//! law's slope at the equilibrium enters the damping, so a falling law
//! (`f' < 0`) destabilises it once `−f'(0) > 2 d` (the textbook condition
//! `2 ζ ω_n > −(1/m) df/dv_rel` for stability).
//!
//! * A piecewise-linear model rests in the domain whose velocity band holds
//!   `v = 0`; its coefficients are the domain's own (`2 d_j` already holds
//!   the piece's slope), so the linearisation is exact.
//! * Where `v = 0` is a continuous boundary, the equilibrium sits on the
//!   kink of the law, between two domains. If both sides turn (foci,
//!   `λ = −σ ± i ω`), a small orbit crosses the kink twice per turn and
//!   contracts by `exp(−π (σ_below/ω_below + σ_above/ω_above))`: stable iff
//!   that sum is positive. Otherwise it is stable iff both sides are.
//! * Where `v = 0` is the stick boundary (a belt at rest), the mass sticks:
//!   that is a permanent stick, not steady sliding.
//! * A smooth law uses its own slope `f'(0)`, from the law's expression
//!   graph, not from any pieces.
//!
//! [`locate`] finds where the stability changes between two parameter
//! values, by bisection down to adjacent floating-point numbers: a Hopf
//! point of a smooth law (the margin `2 d + f'(0)` crosses zero), or, for a
//! piecewise law, the value where the equilibrium leaves its band (a
//! boundary velocity crosses 0).

use serde::Serialize;

use crate::model::{FrictionOscillator, Model, ModelInfo, Regime, SmoothModel};

/// Where the equilibrium rests.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Seat {
    /// Inside a domain's velocity band (its index).
    Domain(usize),
    /// On a continuous boundary (its index), between the domain below and
    /// the domain above it.
    Boundary {
        /// The boundary.
        boundary: usize,
        /// The domain whose band ends at the boundary.
        below: usize,
        /// The domain whose band starts there.
        above: usize,
    },
    /// On a smooth law.
    Law,
}

impl Seat {
    /// Its name in `info`: `domain 15`, `Sigma5`, `law`.
    pub fn label(&self, info: &ModelInfo) -> String {
        match *self {
            Seat::Domain(j) => format!("domain {}", info.domains[j].label),
            Seat::Boundary { boundary, .. } => info.boundaries[boundary].label.to_string(),
            Seat::Law => "law".to_string(),
        }
    }
}

/// Stability of the equilibrium.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// Every small perturbation decays.
    Stable,
    /// Some small perturbation grows.
    Unstable,
    /// Neither: a centre, exactly at a change of stability.
    Neutral,
}

/// Steady sliding: the mass at rest, `x = x*`, `v = 0`.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Equilibrium {
    /// The rest position `x*`.
    pub x: f64,
    /// Where it rests.
    pub seat: Seat,
    /// The linearisation's damping `2 d + f'(0)` (on a boundary: the side
    /// below's).
    pub two_d: f64,
    /// The linearisation's stiffness `c`.
    pub c: f64,
    /// The eigenvalues of `[[0, 1], [−c, −2 d − f'(0)]]` as `[re, im]`, the
    /// larger real part first (on a boundary: the side below's; the side
    /// above's are in [`Equilibrium::above`]).
    pub eigenvalues: [[f64; 2]; 2],
    /// On a boundary, the eigenvalues of the domain above.
    pub above: Option<[[f64; 2]; 2]>,
    /// Focus, node or critically damped (of the side below on a boundary).
    pub regime: Regime,
    /// Stable, unstable or neutral.
    pub verdict: Verdict,
    /// The signed stability margin: positive when stable, zero at the
    /// change of stability. Inside a domain or on a law, `2 d + f'(0)`
    /// (with `c > 0`); on a boundary between two foci,
    /// `σ_below/ω_below + σ_above/ω_above`.
    pub margin: f64,
}

/// Why a model has no steady sliding here.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum EquilibriumError {
    /// The forcing is on: the oscillator is not autonomous.
    #[error("the forcing is on (A0 = {amplitude}): steady sliding is an equilibrium of the unforced oscillator only; set the forcing amplitude to 0 (e.g. --set Q0=0)")]
    Forced {
        /// `A0`.
        amplitude: f64,
    },
    /// `v = 0` is the stick velocity: the belt is at rest.
    #[error("the belt is at rest (v = 0 is the stick boundary {boundary}): the mass sticks rather than slides; give the belt a speed")]
    OnStick {
        /// The stick boundary's label.
        boundary: String,
    },
    /// No domain's band holds `v = 0`.
    #[error("no domain's velocity band holds v = 0, so the model has no steady sliding")]
    NoBand,
    /// `c = 0`: every position is an equilibrium, or none is.
    #[error("the stiffness is {c}: steady sliding needs a spring (c ≠ 0) to fix a rest position")]
    NoSpring {
        /// `c`.
        c: f64,
    },
}

/// The eigenvalues of `[[0, 1], [−c, −two_d]]`, computed without
/// cancellation: the larger real root from the quadratic formula, the other
/// from the product `c`.
pub fn eigenvalues(two_d: f64, c: f64) -> [[f64; 2]; 2] {
    let disc = two_d * two_d - 4.0 * c;
    if disc < 0.0 {
        let im = 0.5 * (-disc).sqrt();
        let re = -0.5 * two_d;
        [[re, im], [re, -im]]
    } else {
        let q = -0.5 * (two_d + two_d.signum() * disc.sqrt());
        if q == 0.0 {
            return [[0.0, 0.0]; 2];
        }
        let (a, b) = (q, c / q);
        let (hi, lo) = if a >= b { (a, b) } else { (b, a) };
        [[hi, 0.0], [lo, 0.0]]
    }
}

fn verdict_of(margin: f64) -> Verdict {
    if margin > 0.0 {
        Verdict::Stable
    } else if margin < 0.0 {
        Verdict::Unstable
    } else {
        Verdict::Neutral
    }
}

/// The margin of one side: `2 d_j` where `c > 0`, a saddle (`c < 0`) is
/// unstable whatever its damping.
fn side_margin(two_d: f64, c: f64) -> f64 {
    if c > 0.0 {
        two_d
    } else {
        -1.0
    }
}

fn in_domain(x: f64, two_d: f64, c: f64, seat: Seat) -> Equilibrium {
    let margin = side_margin(two_d, c);
    Equilibrium {
        x,
        seat,
        two_d,
        c,
        eigenvalues: eigenvalues(two_d, c),
        above: None,
        regime: Regime::classify(two_d, c),
        verdict: verdict_of(margin),
        margin,
    }
}

/// Steady sliding of a piecewise-linear model at `p` (see the module).
pub fn steady_sliding<M: Model>(p: &M::Params) -> Result<Equilibrium, EquilibriumError> {
    let osc = M::oscillator(p);
    if osc.amplitude != 0.0 {
        return Err(EquilibriumError::Forced {
            amplitude: osc.amplitude,
        });
    }
    let info: &ModelInfo = M::info(p);
    for (b, boundary) in info.boundaries.iter().enumerate() {
        if M::boundary_velocity(p, b) == 0.0 {
            if boundary.stick {
                return Err(EquilibriumError::OnStick {
                    boundary: boundary.label.to_string(),
                });
            }
            let below = info.domains.iter().position(|d| d.upper == Some(b));
            let above = info.domains.iter().position(|d| d.lower == Some(b));
            let (Some(below), Some(above)) = (below, above) else {
                return Err(EquilibriumError::NoBand);
            };
            return on_boundary::<M>(p, b, below, above);
        }
    }
    let velocity =
        |b: Option<usize>, unbounded: f64| b.map_or(unbounded, |b| M::boundary_velocity(p, b));
    let j = info
        .domains
        .iter()
        .position(|d| {
            velocity(d.lower, f64::NEG_INFINITY) < 0.0 && 0.0 < velocity(d.upper, f64::INFINITY)
        })
        .ok_or(EquilibriumError::NoBand)?;
    let co = M::coefficients(p, j);
    if co.c == 0.0 || !co.c.is_finite() {
        return Err(EquilibriumError::NoSpring { c: co.c });
    }
    Ok(in_domain(-co.b / co.c, co.two_d, co.c, Seat::Domain(j)))
}

/// The equilibrium on the kink between `below` and `above`.
fn on_boundary<M: Model>(
    p: &M::Params,
    boundary: usize,
    below: usize,
    above: usize,
) -> Result<Equilibrium, EquilibriumError> {
    let lo = M::coefficients(p, below);
    let hi = M::coefficients(p, above);
    if lo.c == 0.0 || !lo.c.is_finite() {
        return Err(EquilibriumError::NoSpring { c: lo.c });
    }
    let turns = |two_d: f64, c: f64| c > 0.0 && two_d * two_d < 4.0 * c;
    let margin = if turns(lo.two_d, lo.c) && turns(hi.two_d, hi.c) {
        // σ/ω of each half-turn: σ = 2d/2, ω = √(c − d²).
        let ratio = |two_d: f64, c: f64| 0.5 * two_d / (c - 0.25 * two_d * two_d).sqrt();
        ratio(lo.two_d, lo.c) + ratio(hi.two_d, hi.c)
    } else {
        side_margin(lo.two_d, lo.c).min(side_margin(hi.two_d, hi.c))
    };
    Ok(Equilibrium {
        x: -lo.b / lo.c,
        seat: Seat::Boundary {
            boundary,
            below,
            above,
        },
        two_d: lo.two_d,
        c: lo.c,
        eigenvalues: eigenvalues(lo.two_d, lo.c),
        above: Some(eigenvalues(hi.two_d, hi.c)),
        regime: Regime::classify(lo.two_d, lo.c),
        verdict: verdict_of(margin),
        margin,
    })
}

/// Steady sliding of a smooth-law model at `p`: the law's own value and
/// slope at `v = 0`.
pub fn steady_sliding_smooth<M: SmoothModel>(
    p: &M::Params,
) -> Result<Equilibrium, EquilibriumError> {
    let osc = <M as FrictionOscillator>::oscillator(p);
    if osc.amplitude != 0.0 {
        return Err(EquilibriumError::Forced {
            amplitude: osc.amplitude,
        });
    }
    if M::belt(p) == 0.0 {
        return Err(EquilibriumError::OnStick {
            boundary: "the belt speed".to_string(),
        });
    }
    let c = osc.stiffness;
    if c == 0.0 || !c.is_finite() {
        return Err(EquilibriumError::NoSpring { c });
    }
    let [f, slope] = M::kinetic(p, 0.0);
    Ok(in_domain(-f / c, 2.0 * osc.damping + slope, c, Seat::Law))
}

/// What changes at a located change of stability.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
#[serde(rename_all = "lowercase", tag = "kind")]
pub enum Loss {
    /// The margin `2 d + f'(0)` crosses zero inside one band or on a smooth
    /// law: a Hopf point (a pair of eigenvalues crosses the imaginary axis).
    Hopf,
    /// The equilibrium leaves its band through the boundary (index): the
    /// nonsmooth change of a piecewise law, where the law's slope jumps.
    Band {
        /// The boundary crossed.
        boundary: usize,
    },
    /// The equilibrium moves from one domain's band into another's (the
    /// boundary between them is not adjacent, or not known here; see
    /// [`locate_in`], which names it as a [`Loss::Band`]).
    Domains {
        /// The domain on the side of smaller parameter values.
        from: usize,
        /// The domain on the other side.
        to: usize,
    },
    /// The equilibrium ceases to exist (a band without a spring, the belt
    /// stopping).
    End,
}

/// A change of stability located between two parameter values.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Change {
    /// The parameter value: the two bracketing values are adjacent
    /// floating-point numbers, or within `tol` relative.
    pub at: f64,
    /// Stable on the side of smaller parameter values.
    pub before: Option<Verdict>,
    /// Stable on the side of larger values.
    pub after: Option<Verdict>,
    /// What happens there.
    pub loss: Loss,
    /// The equilibrium at the located value.
    pub equilibrium: Option<Equilibrium>,
}

fn class(e: &Result<Equilibrium, EquilibriumError>) -> Option<Verdict> {
    e.as_ref().ok().map(|e| match e.verdict {
        Verdict::Neutral => Verdict::Stable,
        v => v,
    })
}

/// The change of stability between `a < b` of the equilibria `at(·)`, whose
/// classes (stable, unstable, absent) differ at `a` and `b`: bisection until
/// the bracket is two adjacent floating-point numbers (or `tol` relative).
/// The located value is the bracket's end where the margin is closest to
/// zero; on a band change, the value where the equilibrium sits on the
/// boundary.
pub fn locate<F>(at: F, mut a: f64, mut b: f64, tol: f64) -> Option<Change>
where
    F: Fn(f64) -> Result<Equilibrium, EquilibriumError>,
{
    let (ea, eb) = (at(a), at(b));
    let (ca, cb) = (class(&ea), class(&eb));
    if ca == cb {
        return None;
    }
    let (before, after) = (ca, cb);
    let (mut seat_a, mut seat_b) = (
        ea.as_ref().ok().map(|e| e.seat),
        eb.as_ref().ok().map(|e| e.seat),
    );
    let mut boundary_hit: Option<(f64, Equilibrium)> = None;
    for _ in 0..2100 {
        let m = 0.5 * (a + b);
        if m <= a || m >= b || (b - a) <= tol * a.abs().max(b.abs()) {
            break;
        }
        let em = at(m);
        if let Ok(e) = &em {
            if let Seat::Boundary { .. } = e.seat {
                boundary_hit = Some((m, *e));
            }
        }
        if class(&em) == ca {
            a = m;
            seat_a = em.as_ref().ok().map(|e| e.seat);
        } else {
            b = m;
            seat_b = em.as_ref().ok().map(|e| e.seat);
        }
    }
    let (ea, eb) = (at(a), at(b));
    let loss = match (seat_a, seat_b) {
        (None, _) | (_, None) => Loss::End,
        (Some(sa), Some(sb)) if sa == sb => Loss::Hopf,
        (Some(Seat::Boundary { boundary, .. }), _) | (_, Some(Seat::Boundary { boundary, .. })) => {
            Loss::Band { boundary }
        }
        (Some(Seat::Domain(from)), Some(Seat::Domain(to))) => Loss::Domains { from, to },
        _ => Loss::Hopf,
    };
    let (value, equilibrium) = match (loss, boundary_hit) {
        (Loss::Band { .. }, Some((m, e))) => (m, Some(e)),
        _ => match (&ea, &eb) {
            (Ok(x), Ok(y)) if x.margin.abs() <= y.margin.abs() => (a, Some(*x)),
            (Ok(_), Ok(y)) => (b, Some(*y)),
            (Ok(x), Err(_)) => (a, Some(*x)),
            (Err(_), Ok(y)) => (b, Some(*y)),
            _ => (0.5 * (a + b), None),
        },
    };
    Some(Change {
        at: value,
        before,
        after,
        loss,
        equilibrium,
    })
}

/// [`locate`] for a piecewise-linear model: a band change is named by the
/// boundary the two domains share.
pub fn locate_in<M: Model, F>(p: &M::Params, at: F, a: f64, b: f64, tol: f64) -> Option<Change>
where
    F: Fn(f64) -> Result<Equilibrium, EquilibriumError>,
{
    let mut change = locate(at, a, b, tol)?;
    if let Loss::Domains { from, to } = change.loss {
        let domains = &M::info(p).domains;
        let (f, t) = (&domains[from], &domains[to]);
        let shared = [f.lower, f.upper]
            .into_iter()
            .flatten()
            .find(|&x| t.lower == Some(x) || t.upper == Some(x));
        if let Some(boundary) = shared {
            change.loss = Loss::Band { boundary };
        }
    }
    Some(change)
}

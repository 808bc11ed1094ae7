//! The exact tangent map of the stroboscopic (Poincaré) map along the
//! event-driven simulation.
//!
//! The stroboscopic map `P` takes `(x, v)` at `W t = φ0 + 2πk` to `(x, v)` at
//! `φ0 + 2π(k+1)`. Its derivative is the product, in time order, of
//!
//! * **the flow of a domain** `j` over an elapsed time `τ`: the flow is linear
//!   (SPEC §4), so its state-transition matrix is the homogeneous fundamental
//!   matrix `Φ(τ) = [[Ec + d Es, Es], [−c Es, Ec − d Es]]` with
//!   `(Ec, Es)` of [`crate::model::homogeneous::general`] at `d = d_j`,
//!   `c = c_j` (the forcing does not enter the tangent);
//! * **a pass** through a boundary `v = V_b`: the crossing time depends on the
//!   state, and the saltation matrix `S = I + (f⁺ − f⁻) nᵀ / (nᵀ f⁻)` with
//!   `n = (0, 1)`, `f = (v, a)` is `diag(1, a⁺ / a⁻)` (`a∓` the accelerations
//!   of the domains before and after, at the crossing);
//! * **a stick onset**: the arrival time shifts by `δt = −δv / a⁻`, and the
//!   stuck mass moves as `x = x_i + V (t − t_i)` whatever its arrival, so
//!   `δx` is kept and `δv` collapses: `S = [[1, 0], [0, 0]]`; while stuck the
//!   tangent is the same projection (`δx` constant, `δv = 0`);
//! * **a stick end** where `Fnf = A0 cos(W t) − 2 d V − c x = ±as`: the end time
//!   moves by `δt = c δx / Ḟ` with `Ḟ = −A0 W sin(W t) − c V` the rate of `Fnf`
//!   along the stick, and the flow that follows starts later by `δt`, so at
//!   the nominal end time `δv = −a⁺ δt`: `S = [[1, 0], [−c a⁺ / Ḟ, 0]]`.
//!
//! **Grazing** (a tangent touch, `a⁻ = 0` at the boundary) is where `P` is not
//! differentiable: perturbations to one side cross the boundary, with a
//! square-root dependence, those to the other do not. A `Graze` event applies
//! the identity (the one-sided derivative of the perturbations that stay in
//! the domain); a pass or a stick end found with `a⁻ = 0` or `Ḟ = 0` (which the
//! event search does not produce except by exact coincidence, a set of
//! measure zero) likewise applies the identity on the affected component,
//! and is counted in [`Tangent::singular`] so that a caller can tell.
//!
//! A stick makes the tangent map singular (rank one): a run that contains a
//! stick has a second exponent of `−∞`. [`Tangent::collapsed`] records it,
//! so that the exponent is reported as `−∞` rather than as the logarithm of
//! a rounding residue.
//!
//! Propagating the tangent allocates nothing.

use nalgebra::Matrix2;

use crate::dynamics::simulate::{Event, EventKind, Location, Segment, SimError, Simulator};
use crate::model::homogeneous;
use crate::model::Model;

/// A tangent matrix carried along a trajectory, with what happened to it.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Tangent {
    /// `∂(x, v)(now) / ∂(x, v)(start)` (or the product with a start basis).
    pub matrix: Matrix2<f64>,
    /// A stick collapsed the velocity direction since the start.
    pub collapsed: bool,
    /// Events where the derivative does not exist (pass or stick end at a
    /// tangency) met since the start: the identity was applied there.
    pub singular: u32,
}

impl Tangent {
    /// The tangent `m` at the start.
    pub fn new(m: Matrix2<f64>) -> Self {
        Self {
            matrix: m,
            collapsed: false,
            singular: 0,
        }
    }
}

/// The state-transition matrix of the flow of segment location `location`
/// over the elapsed phase `dphi` (time `dphi / W`).
pub fn flow_matrix<M: Model>(sim: &Simulator<M>, location: Location, dphi: f64) -> Matrix2<f64> {
    match location {
        Location::Domain(j) => {
            let co = sim.coefficients(j);
            let d = 0.5 * co.two_d;
            let tau = dphi / sim.oscillator().frequency;
            let (ec, es) = homogeneous::general(d, co.c, tau);
            Matrix2::new(ec + d * es, es, -co.c * es, ec - d * es)
        }
        Location::Stick => Matrix2::new(1.0, 0.0, 0.0, 0.0),
    }
}

/// The jump matrix of the tangent at `event`, and whether the derivative
/// exists there (`false`: a tangency, the identity was used on that part).
pub fn event_matrix<M: Model>(sim: &Simulator<M>, event: &Event) -> (Matrix2<f64>, bool) {
    match event.kind {
        EventKind::Graze => (Matrix2::identity(), true),
        EventKind::Pass => {
            let before = sim.acceleration(event.before, event.x, event.v, event.phase);
            let after = sim.acceleration(event.after, event.x, event.v, event.phase);
            let ratio = after / before;
            if ratio.is_finite() {
                (Matrix2::new(1.0, 0.0, 0.0, ratio), true)
            } else {
                (Matrix2::identity(), false)
            }
        }
        EventKind::StickOnset => (Matrix2::new(1.0, 0.0, 0.0, 0.0), true),
        EventKind::StickEnd => {
            let osc = sim.oscillator();
            let w = osc.frequency;
            let c = osc.stiffness;
            let rate = -osc.amplitude * w * event.phase.sin() - c * event.v;
            let after = sim.acceleration(event.after, event.x, event.v, event.phase);
            let slope = -c * after / rate;
            if slope.is_finite() {
                (Matrix2::new(1.0, 0.0, slope, 0.0), true)
            } else {
                (Matrix2::new(1.0, 0.0, 0.0, 0.0), false)
            }
        }
    }
}

/// Carry `tangent` along the flow of `seg` over the phase `dphi`.
#[inline]
fn carry<M: Model>(sim: &Simulator<M>, seg: &Segment, dphi: f64, tangent: &mut Tangent) {
    tangent.matrix = flow_matrix(sim, seg.location, dphi) * tangent.matrix;
    if seg.location == Location::Stick {
        tangent.collapsed = true;
    }
}

/// Simulate from `seg` to `phase_end`, multiplying `tangent` by the tangent
/// map of the motion on the way (the tangent is taken to be at `seg.phase`); `on_event` sees every event. Returns the
/// segment in force at `phase_end`, re-anchored there (its start moved to
/// `phase_end`) so that the next call starts a fresh segment.
/// Allocates nothing.
pub fn advance<M: Model>(
    sim: &Simulator<M>,
    mut seg: Segment,
    phase_end: f64,
    tangent: &mut Tangent,
    mut on_event: impl FnMut(&Event),
) -> Result<Segment, SimError> {
    // The tangent has been carried up to phase `at` (a graze keeps the
    // segment, with its start, but the tangent has moved on).
    let mut at = seg.phase;
    let limit = sim.options().max_events;
    for _ in 0..limit {
        match sim.next_event(&seg, phase_end)? {
            None => {
                carry(sim, &seg, phase_end - at, tangent);
                let (x, v) = sim.state_at(&seg, phase_end);
                return Ok(Segment {
                    x,
                    v,
                    phase: phase_end,
                    search_from: seg.search_from.max(phase_end),
                    ..seg
                });
            }
            Some((event, next)) => {
                carry(sim, &seg, event.phase - at, tangent);
                let (jump, exists) = event_matrix(sim, &event);
                tangent.matrix = jump * tangent.matrix;
                if event.kind == EventKind::StickOnset {
                    tangent.collapsed = true;
                }
                if !exists {
                    tangent.singular += 1;
                }
                at = event.phase;
                on_event(&event);
                seg = next;
            }
        }
    }
    Err(SimError::TooManyEvents {
        limit,
        phase: seg.search_from,
    })
}

//! The smooth margin of a stick that must not end early (SPEC §3, §6), for
//! a two-parameter curve of that transition.
//!
//! While the mass sticks on a boundary of velocity `v_s` it moves with it,
//! `x(φ) = x_a + v_s (φ − φ_a) / W`, so the non-friction force
//! `Fnf(φ) = A0 cos φ − 2 d v_s − c x(φ)` has the rate
//! `dFnf/dφ = −A0 sin φ − c v_s / W` and its extrema are in closed form:
//! `sin φ* = −c v_s / (A0 W)` (none when `|c v_s| ≥ |A0| W`: then `Fnf` is
//! monotone and the stick cannot end early). The stick holds while
//! `|Fnf| < as`; it ends before the structure's exit where an interior
//! local maximum of `Fnf` reaches `+as` or an interior local minimum
//! reaches `−as`. The margin is the smallest of `as − Fnf(φ*)` over the
//! interior maxima and `as + Fnf(φ*)` over the interior minima: a smooth
//! function of the stick's start and the parameters while that extremum
//! stays inside the stick, zero where `|Fnf|` touches `as` tangentially.
//!
//! The event search's margin of the same condition (a phase difference:
//! where the stick ends against where the structure says) jumps there, so
//! a sweep locates the transition by bisection; this margin crosses zero
//! with it, and a curve can be traced on it.
//!
//! The stick also ends early where its exit turns tangential: at the exit
//! `|Fnf| = as` by the structure's own equation, and the stick ends there
//! only if `|Fnf|` reaches `as` from inside, `d|Fnf|/dφ > 0`. Where that
//! rate is negative `|Fnf|` was above `as` just before the exit (an extremum
//! of `Fnf` has entered the stick through its exit). The interior
//! extremum's margin vanishes quadratically there (its distance to the
//! exit squared, and only on the side where it is inside), the rate
//! linearly: the margin is the smaller of the two, so that the transition
//! has a simple zero a curve can be traced on (the paper model's
//! `P_{3_31 0_11 1_11 0_11 1_11 3_13 4_33 3_31 0_11 1_11 3_13 4_33}` near
//! W = 2.6977, Q0 = 204.18: `DP` has a pole there, `1 / (dFnf/dφ)` from the
//! exit's phase, and the motion's period-doubling curve runs into it).

use crate::dynamics::simulate::Simulator;
use crate::model::{MappingKind, Model, ModelInfo, Oscillator};
use crate::orbit::periodic::{arrival, SwitchingPoint};
use crate::orbit::structure::Structure;
use std::cmp::Ordering;

/// The margin of the stick on boundary `k` from `(x_a, φ_a)` to phase
/// `phi_b` against an early end (see the module): the smallest over its
/// interior extrema of `Fnf` and its exit's rate ([`exit_rate`]), in force
/// per unit mass (the rate per radian of forcing phase); `None` when the
/// model has no static bound there. `as − |Fnf|` at an extremum is its
/// value at the extremum's own side (a maximum against `+as`, a minimum
/// against `−as`). NaN where either is.
pub(super) fn early_end_margin<M: Model>(
    sim: &Simulator<M>,
    k: usize,
    x_a: f64,
    phi_a: f64,
    phi_b: f64,
) -> Option<f64> {
    let interior = early_end(sim, k, x_a, phi_a, phi_b).map(|(m, _, _)| m);
    let exit = stick_exit_rate::<M>(sim.params(), k, x_a, phi_a, phi_b);
    match (interior, exit) {
        (Some(a), Some(b)) if a.is_nan() || b.is_nan() => Some(f64::NAN),
        (Some(a), Some(b)) => Some(a.min(b)),
        (a, b) => a.or(b),
    }
}

/// `d|Fnf|/dφ` at the exit `phi_b` of the stick on boundary `k` from
/// `(x_a, φ_a)` at `p` (`|Fnf| = as` there): positive where `|Fnf|`
/// reaches `as` from inside and the stick ends as claimed, zero where the
/// exit turns tangential, negative where `|Fnf|` was beyond `as` just before
/// (the stick ended earlier). From the model's closed forms alone (no
/// simulator): also what the monodromy's pole at a tangential exit is
/// cleared with (`bifurcation::curve::condition::exit_rates`). `None` if
/// `k` is not the model's stick boundary, the model has no static bound,
/// or the stick takes no time.
pub(crate) fn stick_exit_rate<M: Model>(
    p: &M::Params,
    k: usize,
    x_a: f64,
    phi_a: f64,
    phi_b: f64,
) -> Option<f64> {
    if M::info(p).stick_boundary() != Some(k)
        || M::static_bound(p).is_none()
        || phi_a.partial_cmp(&phi_b) != Some(Ordering::Less)
    {
        return None;
    }
    let osc = M::oscillator(p);
    let vs = M::boundary_velocity(p, k);
    let f = fnf_along::<M>(p, vs, osc.frequency, x_a, phi_a, phi_b)?;
    Some(f.signum() * fnf_rate(&osc, vs, phi_b))
}

/// The interior extremum of [`early_end`] of the stick `segment` of
/// `structure` at `points` with the smallest margin: that margin and the
/// phase from the stick's start to it. An extremum at the start makes the
/// margin vanish quadratically, no curve to trace; one at the exit is the
/// exit turning tangential, whose rate [`early_end_margin`] takes. `None`
/// if `segment` is no stick or has no interior extremum.
pub(crate) fn early_end_extremum<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    segment: usize,
) -> Option<(f64, f64)> {
    let (k, a, b) = stick_ends(sim.info(), structure, points, segment)?;
    early_end(sim, k, a.x, a.phase, b.phase).map(|(m, _, phi)| (m, phi - a.phase))
}

/// The boundary the stick `segment` of `structure` sticks on, its start and
/// its exit at `points`; `None` if `segment` is no stick (or `points` do not
/// fit the structure).
fn stick_ends(
    info: &ModelInfo,
    structure: &Structure,
    points: &[SwitchingPoint],
    segment: usize,
) -> Option<(usize, SwitchingPoint, SwitchingPoint)> {
    let step = *structure.steps().get(segment)?;
    let mi = info.mappings[step];
    if mi.kind != MappingKind::Stick || points.len() != structure.len() {
        return None;
    }
    let shift = crate::orbit::periodic::cycle_shift(structure, points);
    Some((mi.from, points[segment], arrival(points, segment, shift)))
}

/// How nearly `Fnf` touches `±as` tangentially at an end of the stick
/// `segment` of `structure` at `points` (its start or its exit): at each
/// end the larger of `||Fnf| − as|` and `|dFnf/dφ|` (a force per unit mass,
/// and its rate per radian: the force's change over one radian of forcing
/// phase, so both are read on the force's scale), the smaller over the two
/// ends. Zero where an extremum of `Fnf` at the static bound sits at an
/// end of the stick: the
/// stick's vanishing met on a curve that holds `|Fnf| = as` at the stick's
/// start (a passable onset: on one side the extremum enters the stick at
/// `±as` and the stick ends at once, a margin born at zero that the interior
/// extrema of [`early_end`] do not yet hold), or a stick's exit turning
/// tangential. `None` if `segment` is no stick or the model has no static
/// bound there.
pub(crate) fn end_touch<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    segment: usize,
) -> Option<f64> {
    let (k, a, b) = stick_ends(sim.info(), structure, points, segment)?;
    let (stick, bound) = sim.stick()?;
    if stick != k {
        return None;
    }
    let touch = |phi: f64| {
        let f = force_along(sim, k, a.x, a.phase, phi)?;
        Some((f.abs() - bound).abs().max(force_rate(sim, k, phi).abs()))
    };
    Some(touch(a.phase)?.min(touch(b.phase)?))
}

/// The smallest margin over the interior extrema ([`early_end_margin`]),
/// that extremum's distance (in phase) to the nearer end of the stick, and
/// its phase (where the stick touches `±as` when the margin is zero).
pub(crate) fn early_end<M: Model>(
    sim: &Simulator<M>,
    k: usize,
    x_a: f64,
    phi_a: f64,
    phi_b: f64,
) -> Option<(f64, f64, f64)> {
    let (stick, bound) = sim.stick()?;
    // (NaN phases fail `phi_a < phi_b`.)
    if stick != k || phi_a.partial_cmp(&phi_b) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let osc = sim.oscillator();
    let (a0, c, w) = (osc.amplitude, osc.stiffness, osc.frequency);
    let vs = sim.velocity(k);
    // sin φ* = s, with s = −c v_s / (A0 W).
    let s = -c * vs / (a0 * w);
    if s.abs().partial_cmp(&1.0) != Some(std::cmp::Ordering::Less) {
        return None;
    }
    let base = s.asin();
    let tau = std::f64::consts::TAU;
    let mut best: Option<(f64, f64, f64)> = None;
    for root in [base, std::f64::consts::PI - base] {
        // The first root above φ_a, then every turn up to φ_b.
        let mut n = ((phi_a - root) / tau).ceil();
        loop {
            let phi = root + n * tau;
            n += 1.0;
            if phi <= phi_a {
                continue;
            }
            if phi >= phi_b {
                break;
            }
            let f = force_along(sim, k, x_a, phi_a, phi)?;
            // d²Fnf/dφ² = −A0 cos φ*: negative at a maximum.
            let curvature = -a0 * phi.cos();
            let margin = if curvature < 0.0 {
                bound - f
            } else {
                bound + f
            };
            if best.is_none_or(|(b, _, _)| margin.is_nan() || margin < b) {
                best = Some((margin, (phi - phi_a).min(phi_b - phi), phi));
            }
        }
    }
    best
}

/// Where the event search of a segment that starts on the stick boundary
/// `k` at `(x_a, φ_a)` and ends at `phi_b` starts: `φ_a`, unless `|Fnf|`
/// starts beyond `as` and moving back inside (`Fnf` above `+as` and
/// falling, or below `−as` and rising), and is inside again before
/// `phi_b`; then the first phase inside (found stepping from
/// `φ_a + 2 e / |dFnf/dφ|`, `e` the excess, doubling the step, then
/// bisected to rounding).
///
/// For a stick: the simulator ends such a stick at once, and the walk
/// would report that as the stick ending early; but its start beyond `as`
/// is the stick onset's own condition (`F_in above < 0 < F_in below`,
/// which with `as = ak` is `|Fnf| < as` at the same point), measured by
/// that condition's margin. On a passable-onset curve of an `as = ak` law
/// the start is at `as` to rounding all along the curve, and the immediate
/// end flipped the walk's smallest margin from the stick's phase tolerance
/// to minus its length from one point to the next (`stribeck8`, W = 1.18,
/// Q0 = 6.45: +3.9e-7 to −0.42), taken for a codimension-two point. For a
/// flow leaving `k` (a pass) the same start keeps the search from reading
/// the flow's own start, where `|Fnf|` turns inside, as an arrival that
/// sticks: the pass's criterion there is the pass's margin.
pub(super) fn search_start<M: Model>(
    sim: &Simulator<M>,
    k: usize,
    x_a: f64,
    phi_a: f64,
    phi_b: f64,
) -> f64 {
    let Some((stick, bound)) = sim.stick() else {
        return phi_a;
    };
    let Some(f0) = force_along(sim, k, x_a, phi_a, phi_a) else {
        return phi_a;
    };
    if stick != k || f0.abs().partial_cmp(&bound) != Some(Ordering::Greater) {
        return phi_a;
    }
    let rate = force_rate(sim, k, phi_a);
    if (rate * f0.signum()).partial_cmp(&0.0) != Some(Ordering::Less) {
        return phi_a;
    }
    let inside = |phi: f64| force_along(sim, k, x_a, phi_a, phi).map(|f| f.abs() < bound);
    let excess = f0.abs() - bound;
    let mut step = 2.0 * excess / rate.abs();
    // The last phase known outside, and the first found inside.
    let mut outside = phi_a;
    let mut found = None;
    for _ in 0..60 {
        let phi = phi_a + step;
        if phi.partial_cmp(&phi_b) != Some(Ordering::Less) {
            break;
        }
        if phi > phi_a {
            match inside(phi) {
                Some(true) => {
                    found = Some(phi);
                    break;
                }
                Some(false) => outside = phi,
                None => break,
            }
        }
        step = 2.0 * step.max(f64::EPSILON * phi_a.abs().max(1.0));
    }
    let Some(mut first) = found else {
        return phi_a;
    };
    // Bisected to rounding: the doubling may overshoot the re-entry by
    // up to its last step, and the search must not skip what lies there.
    loop {
        let mid = 0.5 * (outside + first);
        if !(mid > outside && mid < first) {
            return first;
        }
        match inside(mid) {
            Some(true) => first = mid,
            Some(false) => outside = mid,
            None => return first,
        }
    }
}

/// `Fnf` at phase `phi` of the stick on boundary `k` that starts at
/// `(x_a, φ_a)`: the mass moves with the belt, `x = x_a + v_k (φ − φ_a) / W`.
fn force_along<M: Model>(
    sim: &Simulator<M>,
    k: usize,
    x_a: f64,
    phi_a: f64,
    phi: f64,
) -> Option<f64> {
    let w = sim.oscillator().frequency;
    fnf_along::<M>(sim.params(), sim.velocity(k), w, x_a, phi_a, phi)
}

/// `dFnf/dφ = −A0 sin φ − c v_k / W` at phase `phi` of a stick on boundary
/// `k` (the rate of [`force_along`]).
fn force_rate<M: Model>(sim: &Simulator<M>, k: usize, phi: f64) -> f64 {
    fnf_rate(&sim.oscillator(), sim.velocity(k), phi)
}

/// [`force_along`] at `p` for a stick moving at `vs` under forcing
/// frequency `w`.
fn fnf_along<M: Model>(
    p: &M::Params,
    vs: f64,
    w: f64,
    x_a: f64,
    phi_a: f64,
    phi: f64,
) -> Option<f64> {
    let x = x_a + vs * (phi - phi_a) / w;
    M::stick_forces(p, x, phi).map(|f| f.non_friction)
}

/// [`force_rate`] for the oscillator `osc` and a stick moving at `vs`.
fn fnf_rate(osc: &Oscillator, vs: f64, phi: f64) -> f64 {
    -osc.amplitude * phi.sin() - osc.stiffness * vs / osc.frequency
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::dynamics::simulate::SimOptions;
    use crate::models::paper::{Paper, Params};

    /// The exit's rate is `d|Fnf|/dφ` of the force along the stick, by
    /// central differences of `force_along` at the exit (which move the
    /// mass with the belt), at phases where it is positive, negative and
    /// near zero; and the stick's smooth margin is the smaller of it and
    /// the interior extrema's.
    #[test]
    fn the_exit_rate_is_the_force_rate_along_the_stick() {
        // Each with `Q0 W > c V m` (SPEC §3): `Fnf` has extrema on a stick.
        for (w, q) in [(2.6977, 204.18), (3.7, 150.0), (8.0, 70.0)] {
            let p = Params {
                W: w,
                Q0: q,
                ..Params::default()
            };
            let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("params");
            let (k, _) = sim.stick().expect("a stick boundary");
            let (x_a, phi_a) = (0.3, 1.0);
            let mut signs = [false; 2];
            for i in 1..200 {
                let phi_b = phi_a + 0.031 * i as f64;
                let rate = stick_exit_rate::<Paper>(&p, k, x_a, phi_a, phi_b).expect("a rate");
                let h = 1e-6;
                let f = |phi: f64| force_along(&sim, k, x_a, phi_a, phi).expect("Fnf").abs();
                let fd = (f(phi_b + h) - f(phi_b - h)) / (2.0 * h);
                let scale = 1.0 + rate.abs();
                assert!(
                    (rate - fd).abs() <= 1e-6 * scale,
                    "W = {w}, Q0 = {q}, φ_b = {phi_b}: {rate} against {fd}"
                );
                signs[usize::from(rate > 0.0)] = true;
                let margin = early_end_margin(&sim, k, x_a, phi_a, phi_b).expect("a margin");
                let interior = early_end(&sim, k, x_a, phi_a, phi_b).map(|(m, _, _)| m);
                assert_eq!(margin, interior.map_or(rate, |m| m.min(rate)));
            }
            assert!(signs[0] && signs[1], "W = {w}, Q0 = {q}: one sign only");
        }
    }

    /// A stick that takes no time has no exit rate.
    #[test]
    fn a_stick_of_no_time_has_no_exit_rate() {
        let sim =
            Simulator::<Paper>::new(Params::default(), SimOptions::default()).expect("params");
        let (k, _) = sim.stick().expect("a stick boundary");
        let p = Params::default();
        assert_eq!(stick_exit_rate::<Paper>(&p, k, 0.0, 1.0, 1.0), None);
        assert_eq!(stick_exit_rate::<Paper>(&p, k + 1, 0.0, 1.0, 2.0), None);
    }
}

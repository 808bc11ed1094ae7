//! Steady states found by simulation: the attractor's mapping structure and
//! period, refined by Newton; or "no motion" (NM) certified by a bound.

use serde::Serialize;

use crate::dynamics::simulate::{Event, EventKind, Location, Segment, Simulator};
use crate::model::{MappingKind, Model, ModelInfo, Side};
use crate::orbit::motion::{solve, Motion, OrbitError};
use crate::orbit::periodic::{NewtonOptions, SwitchingPoint};
use crate::orbit::steady::{steady_response, SteadyResponse};
use crate::orbit::structure::Structure;

mod autonomous;
mod cycle;

pub use autonomous::{autonomous_cycle, autonomous_multiplier, AutonomousCycle};
use cycle::{detect_cycle, detect_long_cycle};

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// Limits of the search for a steady state.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct AttractorOptions {
    /// Forcing periods simulated at most.
    pub max_periods: u32,
    /// Longest cycle, in mappings, looked for. `None` (the default): scaled
    /// with the model ([`AttractorOptions::cycle_cap`]), and longer cycles
    /// (up to 32 forcing periods and 16 times that cap) are still found by
    /// their period. `Some(n)`: a motion settled on a longer cycle ends in
    /// [`OrbitError::CycleTooLong`], "the cycle is longer than n mappings",
    /// never in "no periodic motion".
    pub max_cycle: Option<usize>,
    /// Newton's options for the refinement.
    pub newton: NewtonOptions,
}

impl Default for AttractorOptions {
    fn default() -> Self {
        Self {
            max_periods: 3000,
            max_cycle: None,
            newton: NewtonOptions::default(),
        }
    }
}

/// The cycle cap when none is given: 160 mappings, or 4 per mapping
/// function of the model if that is more (a model with hundreds of pieces
/// crosses hundreds of boundaries per forcing period).
pub const DEFAULT_MAX_CYCLE: usize = 160;

/// Cycles longer than the cap are still recognised, by their period, up to
/// this many forcing periods (and up to 16 times the cap in mappings): with
/// the model's own cap they are refined, with a cap given they are reported
/// as too long.
const LONG_CYCLE_PERIODS: u32 = 32;

impl AttractorOptions {
    /// The longest cycle looked for, in mappings, for a model with `info`.
    pub fn cycle_cap(&self, info: &ModelInfo) -> usize {
        self.max_cycle
            .unwrap_or_else(|| DEFAULT_MAX_CYCLE.max(4 * info.mappings.len()))
    }
}

/// No boundary contact, proved: the motion stays in one domain forever.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct NoMotion {
    /// The domain (index).
    pub domain: usize,
    /// Largest velocity of the steady (forced) response.
    pub max_v: f64,
    /// Smallest velocity of the steady response.
    pub min_v: f64,
    /// Phase at which the certificate was established.
    pub certified_at: f64,
}

/// A stick that lasts forever, proved: the mass rests on the belt and the
/// non-friction force never reaches the static bound.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct PermanentStick {
    /// Where the mass rests.
    pub x: f64,
    /// Its velocity (the belt's).
    pub v: f64,
    /// Phase `W t` at which the stick began.
    pub since: f64,
    /// The largest `|Fnf|` over a forcing period, `|A0| + |2 d V + c x|`.
    pub max_force: f64,
    /// The static friction bound `as` it stays within.
    pub static_bound: f64,
}

/// What a simulation settles to.
#[derive(Clone, Debug, PartialEq)]
pub enum Attractor {
    /// A periodic motion, refined and checked.
    Periodic(Motion),
    /// No boundary contact.
    NoMotion(NoMotion),
    /// A stick that never ends.
    Stick(PermanentStick),
    /// The stick-slip cycle of an unforced (autonomous) system.
    Autonomous(AutonomousCycle),
}

/// Whether the stick segment `seg` lasts forever. On the stick boundary
/// `Fnf = A0 cos(W t) − 2 d V − c x` with `x = x_i + V (t − t_i)`: if the mass
/// moves (`V ≠ 0`) and the spring pulls (`c ≠ 0`), `|c x|` grows without
/// bound and every stick ends; otherwise `Fnf` is periodic, its largest
/// modulus is exactly `|A0| + |2 d V + c x|`, and the stick is permanent iff
/// that is at most `as` (a touch of the bound does not end a stick).
pub fn permanent_stick<M: Model>(sim: &Simulator<M>, seg: &Segment) -> Option<PermanentStick> {
    if seg.location != Location::Stick {
        return None;
    }
    let (_, bound) = sim.stick()?;
    let osc = sim.oscillator();
    if seg.v != 0.0 && osc.stiffness != 0.0 {
        return None;
    }
    let offset = 2.0 * osc.damping * seg.v + osc.stiffness * seg.x;
    let max_force = osc.amplitude.abs() + offset.abs();
    (max_force <= bound).then_some(PermanentStick {
        x: seg.x,
        v: seg.v,
        since: seg.phase,
        max_force,
        static_bound: bound,
    })
}

/// The mapping that the segment between two events follows.
pub fn mapping_between(info: &ModelInfo, before: &Event, after: &Event) -> Option<usize> {
    match before.after {
        Location::Domain(j) => info.mappings.iter().position(|m| {
            m.domain == Some(j) && m.from == before.boundary && m.to == after.boundary
        }),
        Location::Stick => {
            let side = match after.after {
                Location::Domain(j) if info.domains[j].lower == Some(after.boundary) => Side::Above,
                _ => Side::Below,
            };
            info.mappings
                .iter()
                .position(|m| m.kind == MappingKind::Stick && m.exit == Some(side))
        }
    }
}

/// Certificate that the motion in domain `j` from `(x, v, phase)` never
/// reaches the domain's boundaries: the forced response plus a bound on the
/// decaying homogeneous part stays strictly inside the band.
pub fn no_motion_certificate<M: Model>(
    sim: &Simulator<M>,
    j: usize,
    x: f64,
    v: f64,
    phase: f64,
) -> Option<NoMotion> {
    let p = sim.params();
    let co = M::coefficients(p, j);
    let osc = sim.oscillator();
    let SteadyResponse { a, b, offset, .. } = steady_response::<M>(p, j)?;
    let (d, c) = (0.5 * co.two_d, co.c);
    let w = osc.frequency;
    let xp = a * phase.cos() + b * phase.sin() + offset;
    let vp = w * (-a * phase.sin() + b * phase.cos());
    let (x0, y0) = (x - xp, v - vp);
    let w2 = d * d - c;
    let s = if w2 < 0.0 {
        (1.0 / (-w2).sqrt()).min(1.0 / (std::f64::consts::E * d))
    } else if w2 > 0.0 {
        1.0 / (std::f64::consts::E * (d - w2.sqrt()))
    } else {
        1.0 / (std::f64::consts::E * d)
    };
    let h = y0.abs() + (c * x0 + d * y0).abs() * s;
    let amplitude = w * a.hypot(b);
    let dom = sim.info().domains[j];
    let hi_ok = dom.upper.is_none_or(|k| amplitude + h < sim.velocity(k));
    let lo_ok = dom.lower.is_none_or(|k| -amplitude - h > sim.velocity(k));
    (hi_ok && lo_ok && h.is_finite()).then_some(NoMotion {
        domain: j,
        max_v: amplitude,
        min_v: -amplitude,
        certified_at: phase,
    })
}

/// The cycle of the last `m` events, as a structure of period `periods`
/// started at its canonical mapping, solved by Newton from the events.
fn candidate<M: Model>(
    sim: &Simulator<M>,
    events: &[Event],
    m: usize,
    periods: u32,
    newton: NewtonOptions,
) -> Result<Motion, OrbitError> {
    let info = sim.info();
    let n = events.len();
    let window = &events[n - 1 - m..];
    let mut steps = Vec::with_capacity(m);
    let mut points = Vec::with_capacity(m);
    for i in 0..m {
        let idx = mapping_between(sim.info(), &window[i], &window[i + 1]).ok_or_else(|| {
            OrbitError::Guess(format!(
                "the simulated motion uses a mapping that `{}` does not generate (after the event at W t = {})",
                info.name, window[i].phase
            ))
        })?;
        steps.push(idx);
        points.push(SwitchingPoint {
            phase: window[i].phase,
            x: window[i].x,
        });
    }
    let structure = Structure::from_indices(info, &steps, periods)?;
    let (canonical, offset) = structure.canonical(info);
    // Points past the window's end are the window's first ones, one cycle later.
    let cycle = TAU * periods as f64;
    let rotated: Vec<SwitchingPoint> = (0..m)
        .map(|k| {
            let pt = points[(offset + k) % m];
            let later = if offset + k >= m { cycle } else { 0.0 };
            SwitchingPoint {
                phase: pt.phase + later,
                x: pt.x,
            }
        })
        .collect();
    Ok(solve(sim, canonical, rotated, newton))
}

/// Simulate from `start` until the motion settles; name and refine it.
pub fn find<M: Model>(
    sim: &Simulator<M>,
    start: Segment,
    opts: AttractorOptions,
) -> Result<Attractor, OrbitError> {
    match find_or_stop::<M, std::convert::Infallible>(sim, start, opts, None)? {
        Settle::Attractor(a) => Ok(*a),
        Settle::Stopped(never) => match never {},
    }
}

/// How [`find_or_stop`] ends: the attractor found, or the caller's stop.
#[derive(Clone, Debug, PartialEq)]
pub enum Settle<T> {
    /// What the simulation settled to (as [`find`] returns it).
    Attractor(Box<Attractor>),
    /// The hook stopped the search with this value.
    Stopped(T),
}

fn settled<T>(a: Attractor) -> Result<Settle<T>, OrbitError> {
    Ok(Settle::Attractor(Box::new(a)))
}

/// A hook called at every stroboscopic phase `start.phase + 2πn`
/// (`n = 0, 1, …`) with the segment in force there and the events met since
/// the previous one (grazes included; none at `n = 0`); `Some` stops the
/// search.
pub type StroboscopicHook<'a, T> = &'a mut dyn FnMut(&Segment, f64, &[Event]) -> Option<T>;

/// [`find`], with a hook that can stop the search at any stroboscopic phase:
/// the simulation then runs period by period, and a segment that outlasts a
/// period is re-anchored there (so that the event search never re-scans a
/// long event-free stretch). Without a hook it is exactly [`find`].
pub fn find_or_stop<M: Model, T>(
    sim: &Simulator<M>,
    start: Segment,
    opts: AttractorOptions,
    mut hook: Option<StroboscopicHook<'_, T>>,
) -> Result<Settle<T>, OrbitError> {
    let mut strobe = start.phase;
    if let Some(t) = hook.as_mut().and_then(|stop| stop(&start, strobe, &[])) {
        return Ok(Settle::Stopped(t));
    }
    strobe += TAU;
    let cap = opts.cycle_cap(sim.info());
    let mut seg = start;
    let mut events: Vec<Event> = Vec::new();
    // Enough events for cycles of up to 2 cap mappings, and of longer ones
    // (up to 16 cap mappings) to be recognised as too long.
    let keep = 32 * cap + 4;
    // The events of the current period, for the hook.
    let mut met: Vec<Event> = Vec::new();
    let mut tried_loose: Vec<(usize, u32)> = Vec::new();
    let mut tried_long: Vec<(usize, u32)> = Vec::new();
    let mut chunk = 4.0 * TAU;
    let mut phase = start.phase;
    let end = start.phase + opts.max_periods as f64 * TAU;
    while phase < end {
        phase += chunk;
        // Short chunks first (most motions settle fast), longer ones later.
        chunk = (chunk * 1.5).min(20.0 * TAU);
        let mut count = 0usize;
        if let Some(stop) = hook.as_mut() {
            while strobe <= phase {
                let before = seg;
                met.clear();
                seg = sim.run(seg, strobe, |e| {
                    met.push(*e);
                    record(&mut events, &mut count, e);
                })?;
                if seg == before {
                    let (x, v) = sim.state_at(&seg, strobe);
                    seg = Segment {
                        x,
                        v,
                        phase: strobe,
                        search_from: seg.search_from.max(strobe),
                        ..seg
                    };
                }
                if let Some(t) = stop(&seg, strobe, &met) {
                    return Ok(Settle::Stopped(t));
                }
                // The certificate is a proof at any state: checked every
                // period here, where the search runs period by period anyway,
                // instead of only after a whole chunk without events.
                if let Location::Domain(j) = seg.location {
                    let (x, v) = sim.state_at(&seg, strobe);
                    if let Some(nm) = no_motion_certificate(sim, j, x, v, strobe) {
                        return settled(Attractor::NoMotion(nm));
                    }
                }
                strobe += TAU;
            }
        }
        seg = sim.run(seg, phase, |e| record(&mut events, &mut count, e))?;
        if events.len() > keep {
            events.drain(..events.len() - keep);
        }
        if let Some(stick) = permanent_stick(sim, &seg) {
            return settled(Attractor::Stick(stick));
        }
        if let Some(cycle) = autonomous_cycle(sim, &events) {
            return settled(Attractor::Autonomous(cycle));
        }
        if count == 0 {
            if let Location::Domain(j) = seg.location {
                let (x, v) = sim.state_at(&seg, phase);
                if let Some(nm) = no_motion_certificate(sim, j, x, v, phase) {
                    return settled(Attractor::NoMotion(nm));
                }
            }
            continue;
        }
        // A loose match after a short transient is refined by Newton and
        // accepted if it is an admissible, stable motion; a strict match
        // (the transient has decayed to 1e-7) is accepted if admissible.
        let mut last = None;
        let mut strict = false;
        for (tol, need_stable) in [(1e-4, true), (1e-7, false)] {
            let Some((m, periods)) = detect_cycle(&events, cap, tol) else {
                continue;
            };
            strict |= !need_stable;
            // A loose candidate that failed is not tried again.
            if need_stable {
                if tried_loose.contains(&(m, periods)) {
                    continue;
                }
                tried_loose.push((m, periods));
            }
            let motion = candidate(sim, &events, m, periods, opts.newton)?;
            let stable = motion.stability.is_some_and(|s| s.is_stable());
            if motion.is_admissible() && (stable || !need_stable) {
                return settled(Attractor::Periodic(primitive(sim, motion, opts.newton)));
            }
            last = Some(motion);
        }
        // Settled (to 1e-7) on a cycle longer than the cap; or, at the end of
        // the search, on one that repeats to 1e-4. With a cap given, that is
        // the outcome; with the model's own cap the cycle is refined (once)
        // like any other.
        let last_chunk = phase + chunk >= end;
        if !strict {
            let long = detect_long_cycle(&events, cap, 1e-7).or_else(|| {
                last_chunk
                    .then(|| detect_long_cycle(&events, cap, 1e-4))
                    .flatten()
            });
            if let Some((m, periods)) = long {
                if opts.max_cycle.is_some() {
                    return Err(OrbitError::CycleTooLong {
                        cap,
                        mappings: m,
                        periods,
                    });
                }
                if !tried_long.contains(&(m, periods)) {
                    tried_long.push((m, periods));
                    let motion = candidate(sim, &events, m, periods, opts.newton)?;
                    if motion.is_admissible() {
                        return settled(Attractor::Periodic(primitive(sim, motion, opts.newton)));
                    }
                    last = Some(motion);
                }
            }
        }
        if last_chunk {
            if let Some(motion) = last {
                let motion = motion.into_result()?;
                return settled(Attractor::Periodic(motion));
            }
        }
    }
    let undamped =
        (0..sim.info().domains.len()).all(|j| M::coefficients(sim.params(), j).two_d == 0.0);
    if undamped {
        if let Some(motion) = neutral_edge(sim, &events, cap, opts.newton) {
            return settled(Attractor::Periodic(motion));
        }
    }
    Err(OrbitError::Unsettled {
        periods: opts.max_periods,
        undamped,
        instead: None,
    })
}

/// Keep `e` for cycle detection (a graze is no switching point), counting it.
fn record(events: &mut Vec<Event>, count: &mut usize, e: &Event) {
    if e.kind != EventKind::Graze {
        events.push(*e);
        *count += 1;
    }
}

/// Relative tolerance on a touched admissibility condition: the edge member of
/// a neutral family touches `|Fnf| = as` at a turning point.
const EDGE_TOL: f64 = 1e-9;

/// An undamped search that did not settle may be creeping towards the edge of
/// a neutral family (the undamped Coulomb oscillator at `W = sqrt(c) / (2 n)`
/// from rest: a stick whose length shrinks like `N^(-1/2)`, the onset
/// approaching the non-stop member whose turning point has `|Fnf| = as`).
/// The latest loose cycle with its stick mappings dropped is solved by the
/// family solver; it is returned if it is admissible up to a touch
/// (`margin >= -EDGE_TOL` relative) and `DP` has the eigenvalue 1.
fn neutral_edge<M: Model>(
    sim: &Simulator<M>,
    events: &[Event],
    cap: usize,
    newton: NewtonOptions,
) -> Option<Motion> {
    let info = sim.info();
    for tol in [1e-4, 1e-3, 1e-2] {
        let Some((m, periods)) = detect_cycle(events, cap, tol) else {
            continue;
        };
        let n = events.len();
        let window = &events[n - 1 - m..];
        let mut steps = Vec::with_capacity(m);
        let mut points: Vec<SwitchingPoint> = Vec::with_capacity(m);
        // The point that starts the next kept mapping: a stick's onset.
        let mut pending: Option<SwitchingPoint> = None;
        for i in 0..m {
            let idx = mapping_between(sim.info(), &window[i], &window[i + 1])?;
            let here = SwitchingPoint {
                phase: window[i].phase,
                x: window[i].x,
            };
            if info.mappings[idx].kind == MappingKind::Stick {
                pending.get_or_insert(here);
                continue;
            }
            steps.push(idx);
            points.push(pending.take().unwrap_or(here));
        }
        if steps.is_empty() || steps.len() == m {
            return None;
        }
        // A stick dropped at the window's end belongs to the first kept mapping.
        if let Some(onset) = pending {
            points[0] = SwitchingPoint {
                phase: onset.phase - TAU * periods as f64,
                x: onset.x,
            };
        }
        let structure = Structure::from_indices(info, &steps, periods).ok()?;
        let (canonical, offset) = structure.canonical(info);
        let k = steps.len();
        let cycle = TAU * periods as f64;
        let rotated: Vec<SwitchingPoint> = (0..k)
            .map(|j| {
                let pt = points[(offset + j) % k];
                let later = if offset + j >= k { cycle } else { 0.0 };
                SwitchingPoint {
                    phase: pt.phase + later,
                    x: pt.x,
                }
            })
            .collect();
        let motion = solve(sim, canonical, rotated, newton);
        if let Some(edge) = to_edge(sim, motion, newton) {
            return Some(edge);
        }
    }
    None
}

/// Whether `motion` is a neutral-family member that is admissible up to a
/// touch; `Ok` with the touched conditions cleared, or `Err` with the most
/// negative relative margin (`None` if it is not a neutral member at all).
fn edge_check(mut motion: Motion) -> Result<Motion, Option<f64>> {
    if !motion.termination.converged() || !motion.stability.is_some_and(|s| s.has_unit_eigenvalue())
    {
        return Err(None);
    }
    let worst = motion
        .violations
        .iter()
        .map(|v| v.margin / (1.0 + v.margin.abs()))
        .fold(0.0_f64, f64::min);
    if worst >= -EDGE_TOL {
        motion.violations.clear();
        Ok(motion)
    } else {
        Err(Some(worst))
    }
}

/// From a member of a neutral family that violates an admissibility condition
/// (the family's continuation past its edge), walk along the family to where
/// the worst margin is zero: secant steps along the null direction of
/// `I − DP` at the first point, each re-solved by the family solver.
fn to_edge<M: Model>(sim: &Simulator<M>, motion: Motion, newton: NewtonOptions) -> Option<Motion> {
    let current = motion;
    let (s0, f0) = match edge_check(current.clone()) {
        Ok(m) => return Some(m),
        Err(None) => return None,
        Err(Some(f)) => (0.0, f),
    };
    // `DP` is ordered `(W t, x)`.
    let dp = current.dp?;
    let svd = (nalgebra::Matrix2::identity() - dp).svd(false, true);
    let v_t = svd.v_t?;
    let i = svd.singular_values.imin();
    let dir = v_t.row(i).transpose();
    let base = current.points.clone();
    let scale = 1.0 + base[0].x.abs();
    let solve_at = |s: f64| {
        let mut guess = base.clone();
        guess[0] = SwitchingPoint {
            phase: base[0].phase + s * dir[0],
            x: base[0].x + s * dir[1],
        };
        solve(sim, current.structure.clone(), guess, newton)
    };
    let mut s1 = 1e-3 * scale;
    let (mut sp, mut fp) = (s0, f0);
    for _ in 0..30 {
        match edge_check(solve_at(s1)) {
            Ok(mut inside) => {
                // Past the edge: bisect between the last violating member
                // and this admissible one, keeping the admissible side.
                let (mut out, mut ins) = (sp, s1);
                for _ in 0..60 {
                    if (ins - out).abs() <= 1e-13 * scale {
                        break;
                    }
                    let mid = 0.5 * (out + ins);
                    match edge_check(solve_at(mid)) {
                        Ok(m) => {
                            inside = m;
                            ins = mid;
                        }
                        Err(Some(_)) => out = mid,
                        Err(None) => break,
                    }
                }
                return Some(inside);
            }
            Err(None) => return None,
            Err(Some(f1)) => {
                if f1 == fp {
                    return None;
                }
                let next = s1 - f1 * (s1 - sp) / (f1 - fp);
                (sp, fp) = (s1, f1);
                s1 = next;
            }
        }
    }
    None
}

/// A cycle found as `r` repetitions of a shorter one (a slowly alternating
/// transient can make the doubled cycle match first) is reported as the
/// shorter cycle: same mappings repeated, points repeating after `m / r`
/// mappings shifted by a whole number of forcing periods.
pub fn primitive<M: Model>(sim: &Simulator<M>, motion: Motion, newton: NewtonOptions) -> Motion {
    let m = motion.structure.len();
    let n = motion.structure.periods() as usize;
    let steps = motion.structure.steps();
    for q in 1..m {
        if m % q != 0 || (n * q) % m != 0 {
            continue;
        }
        let shift = TAU * (n * q / m) as f64;
        let repeats = (0..m).all(|k| {
            let (a, b) = (motion.points[k], motion.points[(k + q) % m]);
            let wrap = if k + q >= m { TAU * n as f64 } else { 0.0 };
            steps[k] == steps[(k + q) % m]
                && (b.phase + wrap - a.phase - shift).abs() < 1e-8 * (1.0 + a.phase.abs())
                && (b.x - a.x).abs() < 1e-8 * (1.0 + a.x.abs())
        });
        if repeats && n * q / m >= 1 {
            let Ok(short) = Structure::from_indices(sim.info(), &steps[..q], (n * q / m) as u32)
            else {
                continue;
            };
            let reduced = solve(sim, short, motion.points[..q].to_vec(), newton);
            if reduced.is_admissible() {
                return reduced;
            }
        }
    }
    motion
}

/// Seed `structure` by simulation: from rest and from a few other starts,
/// look for a stretch of the simulated event sequence that follows the
/// structure, and return its switching points.
pub fn seed<M: Model>(sim: &Simulator<M>, structure: &Structure) -> Option<Vec<SwitchingPoint>> {
    let m = structure.len();
    let starts = [
        (0.0, 0.0),
        (0.5, 1.0),
        (-0.5, 2.0),
        (1.0, -1.0),
        (-1.0, 4.0),
        (2.0, 0.0),
    ];
    for &(x0, v0) in &starts {
        for k in 0..4 {
            let phase0 = k as f64 * 0.25 * TAU;
            let Ok(seg) = sim.start(x0, v0, phase0) else {
                continue;
            };
            let mut events = Vec::new();
            if sim
                .run(seg, phase0 + 200.0 * TAU, |e| {
                    if e.kind != EventKind::Graze {
                        events.push(*e)
                    }
                })
                .is_err()
            {
                continue;
            }
            let maps: Vec<Option<usize>> = events
                .windows(2)
                .map(|w| mapping_between(sim.info(), &w[0], &w[1]))
                .collect();
            // Latest window matching the structure (the transient has decayed most there).
            for s in (0..maps.len().saturating_sub(m - 1)).rev() {
                for r in 0..m {
                    let ok = (0..m).all(|i| maps[s + i] == Some(structure.steps()[(r + i) % m]));
                    if ok && structure.is_autonomous() {
                        if r != 0 {
                            continue;
                        }
                        // Held with the return (event s + m) at W t = 0.
                        let back = events[s + m].phase;
                        return Some(
                            events[s..s + m]
                                .iter()
                                .map(|e| SwitchingPoint {
                                    phase: e.phase - back,
                                    x: e.x,
                                })
                                .collect(),
                        );
                    }
                    if ok {
                        // Event s + i starts mapping (r + i) mod m; mappings before r
                        // are taken one cycle earlier so that the phases increase.
                        let shift = TAU * structure.periods() as f64;
                        return Some(
                            (0..m)
                                .map(|k| {
                                    let e = &events[s + (k + m - r) % m];
                                    let back = if k < r { shift } else { 0.0 };
                                    SwitchingPoint {
                                        phase: e.phase - back,
                                        x: e.x,
                                    }
                                })
                                .collect(),
                        );
                    }
                }
            }
        }
    }
    None
}

//! The admissibility margins of `admissible::conditions` (velocity extrema
//! from the closed form, the event search only near a zero margin, text
//! only for violated conditions) against two independent computations, on
//! many motions: the reference orbits, attractors of the paper model over
//! W and Q0, the Coulomb oscillator, a 16-piece Stribeck law, the paper
//! model with negative damping (stribeck8), each also perturbed at random
//! so that conditions are violated.
//!
//! 1. `sampled`: the algorithm the fast one replaced, kept here verbatim
//!    (24 samples of the acceleration per segment, every sign change refined
//!    by Newton, the event search on every segment, every text written).
//!    Every margin of a converged motion must equal it to rounding (1e-13
//!    of the velocities involved: the closed form's zero of the acceleration
//!    and the sampled search's Newton land within a few ulps of each
//!    other), and every condition's kind, segment, boundary and violated
//!    text must match.
//! 2. `dense`: the same with 2000 samples per segment and the ends of the
//!    segment for the boundaries it does not touch (the infimum over the
//!    open segment): every margin must match it to 1e-12 (relative to the
//!    velocities involved), perturbed points included.
//!
//! And `worst_margin` is the smallest margin of `conditions`, with its kind,
//! segment and boundary; `violations` (a motion's admissibility) is the
//! violated subset of `conditions`, with the same texts and margins.

mod common;

use stickslip::dynamics::simulate::{EventKind, Location, Segment, SimOptions, Simulator};
use stickslip::model::{MappingKind, Model, Side};
use stickslip::models::coulomb::{self, Coulomb};
use stickslip::models::paper::{self, Paper};
use stickslip::models::stribeck::pl16::{self, Pl16};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::admissible::{
    conditions, violations, worst_margin, Violation, ViolationKind, SAME_EVENT,
};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;

fn phase_tol(phase: f64) -> f64 {
    1e-7 * phase.abs().max(1.0)
}

/// The interior margin by sampling (`n` samples; `ends`: the segment's ends
/// count for the boundaries it does not touch; `flat`: the departure has no
/// acceleration, so a zero of it within the phase tolerance of the start is
/// the departure itself, not an extremum).
#[allow(clippy::too_many_arguments)]
fn sampled_interior_margin<M: Model>(
    sim: &Simulator<M>,
    seg: &Segment,
    end: f64,
    touched: [usize; 2],
    j: usize,
    n: usize,
    ends: bool,
    flat: bool,
) -> [Option<(f64, usize)>; 2] {
    let dom = sim.info().domains[j];
    let p = sim.params();
    let h = (end - seg.phase) / n as f64;
    // The smallest margin to the lower and to the upper boundary, each a
    // condition of its own.
    let mut best: [Option<(f64, usize)>; 2] = [None; 2];
    let mut consider = |v: f64, extremum: bool| {
        for (side, k) in [dom.lower, dom.upper].into_iter().enumerate() {
            let Some(k) = k else { continue };
            if !extremum && touched.contains(&k) {
                continue;
            }
            let margin = if side == 0 {
                v - sim.velocity(k)
            } else {
                sim.velocity(k) - v
            };
            if best[side].is_none_or(|(m, _)| margin < m) {
                best[side] = Some((margin, k));
            }
        }
    };
    let accel = |phi: f64| {
        let (x, v) = sim.state_at(seg, phi);
        M::normal_field(p, j, x, v, phi)
    };
    let w = sim.oscillator().frequency;
    let mut prev = accel(seg.phase)[0];
    for i in 1..=n {
        let phi = seg.phase + h * i as f64;
        let a = accel(phi)[0];
        if (a > 0.0) != (prev > 0.0) {
            let (mut lo, mut hi) = (phi - h, phi);
            let mut t = 0.5 * (lo + hi);
            for _ in 0..50 {
                let [at, rate] = accel(t);
                if (at > 0.0) == (prev > 0.0) {
                    lo = t;
                } else {
                    hi = t;
                }
                let newton = t - at * w / rate;
                let next = if rate != 0.0 && newton > lo && newton < hi {
                    newton
                } else {
                    0.5 * (lo + hi)
                };
                if (next - t).abs() <= 4.0 * f64::EPSILON * t.abs().max(1.0) {
                    t = next;
                    break;
                }
                t = next;
            }
            if !(flat && t - seg.phase <= phase_tol(end)) {
                consider(sim.state_at(seg, t).1, true);
            }
        }
        if i < n {
            consider(sim.state_at(seg, phi).1, false);
        }
        prev = a;
    }
    if ends {
        consider(seg.v, false);
        consider(sim.state_at(seg, end).1, false);
    }
    best
}

/// The conditions as computed before the closed-form extrema (verbatim but
/// for the interior margin's `n` and `ends`, and its one margin per
/// boundary of the domain).
fn sampled_conditions<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    n: usize,
    ends: bool,
) -> Vec<Violation> {
    let info = sim.info();
    let p = sim.params();
    let m = points.len();
    let shift = 2.0 * std::f64::consts::PI * structure.periods() as f64;
    let mut out = Vec::new();
    let label = |k: usize| info.boundaries[k].label;
    for k in 0..m {
        let mi = info.mappings[structure.steps()[k]];
        let next_mi = info.mappings[structure.steps()[(k + 1) % m]];
        let a = points[k];
        let b = if k + 1 < m {
            points[k + 1]
        } else {
            SwitchingPoint {
                phase: points[0].phase + shift,
                x: points[0].x,
            }
        };
        let mut add =
            |kind: ViolationKind, boundary: Option<usize>, condition: String, margin: f64| {
                out.push(Violation {
                    segment: k,
                    condition,
                    margin,
                    kind,
                    boundary,
                })
            };
        let duration = b.phase - a.phase;
        add(
            ViolationKind::Duration,
            None,
            format!(
                "mapping {} must take positive time (W t from {} to {})",
                mi.name, a.phase, b.phase
            ),
            duration,
        );
        if duration.is_nan() || duration <= 0.0 {
            continue;
        }
        if duration > shift + phase_tol(b.phase) {
            add(
                ViolationKind::Duration,
                None,
                format!(
                    "mapping {} must take less than the whole cycle (W t from {} to {})",
                    mi.name, a.phase, b.phase
                ),
                shift - duration,
            );
            continue;
        }
        match (mi.kind, mi.domain) {
            (MappingKind::Stick, _) => {
                // A stick that starts with |Fnf| beyond as and moving back
                // inside fails its onset (that condition's margin), not its
                // end: its end is searched from the first phase inside,
                // found here by stepping 1e-12 of the stick's length at a
                // time, doubling.
                let vs = sim.velocity(mi.from);
                let fnf = |phi: f64| {
                    M::stick_forces(
                        p,
                        a.x + vs * (phi - a.phase) / M::oscillator(p).frequency,
                        phi,
                    )
                    .map(|f| f.non_friction)
                };
                let bound = sim.stick().map_or(f64::INFINITY, |(_, s)| s);
                let mut search_from = a.phase;
                if let Some(f0) = fnf(a.phase).filter(|f| f.abs() > bound) {
                    let mut h = 1e-12 * (b.phase - a.phase);
                    while a.phase + h < b.phase {
                        let f = fnf(a.phase + h).unwrap_or(f0);
                        if f.abs() < bound {
                            search_from = a.phase + h;
                            break;
                        }
                        if f.abs() > f0.abs() {
                            break;
                        }
                        h *= 2.0;
                    }
                }
                let seg = Segment {
                    x: a.x,
                    v: vs,
                    phase: a.phase,
                    location: Location::Stick,
                    search_from,
                };
                let (margin, what) = match sim.next_event(&seg, b.phase + phase_tol(b.phase)) {
                    Ok(Some((e, _))) if e.kind == EventKind::StickEnd => {
                        let exit_ok = match (e.after, mi.exit) {
                            (Location::Domain(j), Some(Side::Above)) => j == mi.from + 1,
                            (Location::Domain(j), Some(Side::Below)) => j == mi.from,
                            _ => false,
                        };
                        if !exit_ok {
                            (
                                -(b.phase - e.phase).abs().max(f64::MIN_POSITIVE),
                                format!(
                                    "the stick on {} ends to the other side at W t = {}",
                                    label(mi.from),
                                    e.phase
                                ),
                            )
                        } else {
                            (
                                e.phase - b.phase + phase_tol(b.phase),
                                format!(
                                    "the stick on {} must last until W t = {} (|Fnf| < as)",
                                    label(mi.from),
                                    b.phase
                                ),
                            )
                        }
                    }
                    Ok(Some((e, _))) => (
                        0.0,
                        format!(
                            "unexpected {:?} during the stick at W t = {}",
                            e.kind, e.phase
                        ),
                    ),
                    Ok(None) => (
                        0.0,
                        format!(
                            "|Fnf| < as until W t = {}: the stick does not end there",
                            b.phase
                        ),
                    ),
                    Err(e) => (f64::NAN, format!("simulation failed: {e}")),
                };
                add(ViolationKind::StickEnd, Some(mi.from), what, margin);
            }
            (_, Some(j)) => {
                let dom = info.domains[j];
                let (va, vb) = (sim.velocity(mi.from), sim.velocity(mi.to));
                let [acc0, rate0] = M::normal_field(p, j, a.x, va, a.phase);
                let into = if dom.lower == Some(mi.from) {
                    1.0
                } else {
                    -1.0
                };
                // Zero up to rounding (1e-12 of the acceleration's terms)
                // is zero: the rate decides (a departure after a stick with
                // as = ak).
                let (osc, co) = (sim.oscillator(), sim.coefficients(j));
                let scale =
                    osc.amplitude.abs() + co.b.abs() + (co.c * a.x).abs() + (co.two_d * va).abs();
                let flat = (into * acc0).abs() <= 1e-12 * scale;
                let dep = if flat { into * rate0 } else { into * acc0 };
                add(
                    ViolationKind::Departure,
                    Some(mi.from),
                    format!(
                        "the flow must leave {} into domain {}",
                        label(mi.from),
                        dom.label
                    ),
                    dep,
                );
                let seg = Segment {
                    x: a.x,
                    v: va,
                    phase: a.phase,
                    location: Location::Domain(j),
                    search_from: a.phase,
                };
                let interior = || {
                    sampled_interior_margin(sim, &seg, b.phase, [mi.from, mi.to], j, n, ends, flat)
                };
                // The margin to each boundary where the flow arrives or
                // contacts one early (but the early contact's own).
                let sides = match sim.next_event(&seg, b.phase + phase_tol(b.phase)) {
                    Ok(Some((e, _)))
                        if e.phase < b.phase - phase_tol(b.phase) || e.boundary != mi.to =>
                    {
                        let what = if e.kind == EventKind::Graze {
                            "grazes"
                        } else {
                            "crosses"
                        };
                        let depth = interior()
                            .into_iter()
                            .flatten()
                            .map(|(m, _)| m)
                            .reduce(f64::min)
                            .map_or(0.0, |m| m.min(0.0));
                        add(
                            ViolationKind::Interior,
                            Some(e.boundary),
                            format!(
                                "the flow of {} {what} {} at W t = {} before reaching {}",
                                mi.name,
                                label(e.boundary),
                                e.phase,
                                label(mi.to)
                            ),
                            depth,
                        );
                        // Each other boundary's margin too, as on arrival
                        // (since stop 31).
                        Some(Some(e.boundary))
                    }
                    Ok(Some(_)) => Some(None),
                    Ok(None) => {
                        let (_, v) = sim.state_at(&seg, b.phase);
                        add(
                            ViolationKind::Arrival,
                            Some(mi.to),
                            format!(
                                "the flow of {} does not reach {} by W t = {}",
                                mi.name,
                                label(mi.to),
                                b.phase
                            ),
                            -(v - vb).abs(),
                        );
                        None
                    }
                    Err(e) => {
                        add(
                            ViolationKind::Other,
                            None,
                            format!("simulation failed: {e}"),
                            f64::NAN,
                        );
                        None
                    }
                };
                if let Some(skip) = sides {
                    for (margin, kb) in interior().into_iter().flatten() {
                        if Some(kb) != skip {
                            add(
                                ViolationKind::Interior,
                                Some(kb),
                                format!(
                                    "the flow of {} must stay off {} before its arrival",
                                    mi.name,
                                    label(kb)
                                ),
                                margin,
                            );
                        }
                    }
                }
                let acc1 = M::normal_field(p, j, b.x, vb, b.phase)[0];
                let out_sign = if dom.upper == Some(mi.to) { 1.0 } else { -1.0 };
                add(
                    ViolationKind::Arrival,
                    Some(mi.to),
                    format!("the arrival on {} must be transversal", label(mi.to)),
                    out_sign * acc1,
                );
                if next_mi.kind != MappingKind::Stick && next_mi.domain == Some(j) {
                    add(
                        ViolationKind::Other,
                        Some(mi.to),
                        format!(
                            "{} arrives on {} from domain {} and {} leaves into the same domain",
                            mi.name,
                            label(mi.to),
                            dom.label,
                            next_mi.name
                        ),
                        -(acc1.abs()),
                    );
                }
                if let (Some(f), true) = (
                    M::stick_forces(p, b.x, b.phase),
                    info.boundaries[mi.to].stick,
                ) {
                    let from_above = dom.lower == Some(mi.to);
                    let (fa, fb) = (f.input_above, f.input_below);
                    if next_mi.kind == MappingKind::Stick {
                        add(
                            ViolationKind::StickOnset,
                            Some(mi.to),
                            format!("stick onset on {} needs F_in above < 0 < F_in below (F_in above = {fa}, F_in below = {fb})", label(mi.to)),
                            (-fa).min(fb),
                        );
                    } else if next_mi.domain != Some(j) {
                        let margin = if from_above {
                            (-fa).min(-fb)
                        } else {
                            fa.min(fb)
                        };
                        let need = if from_above {
                            "both input forces < 0"
                        } else {
                            "both input forces > 0"
                        };
                        add(
                            ViolationKind::Pass,
                            Some(mi.to),
                            format!(
                                "passing {} needs {need} (F_in above = {fa}, F_in below = {fb})",
                                label(mi.to)
                            ),
                            margin,
                        );
                    }
                }
            }
            (_, None) => add(
                ViolationKind::Other,
                None,
                "a flow mapping without a domain".into(),
                f64::NAN,
            ),
        }
    }
    out
}

/// What the comparison saw.
#[derive(Default, Debug)]
struct Tally {
    point_sets: usize,
    conditions: usize,
    violated: usize,
    interior: usize,
    as_sampled: usize,
    /// Violated interior conditions compared with `violations`.
    violated_interior: usize,
    /// Their largest difference, relative to the velocities.
    largest_difference: f64,
    differs_from_sampled: Vec<String>,
}

/// The same text, but numbers equal to 1e-12 of their size: the walk and
/// the dense reference find an event's phase by different arithmetic
/// (since stop 29 their random point sets reach a flow crossing found at
/// 7.610495939149074 and ...073).
fn same_text(a: &str, b: &str) -> bool {
    let (ta, tb): (Vec<&str>, Vec<&str>) = (a.split(' ').collect(), b.split(' ').collect());
    ta.len() == tb.len()
        && ta.iter().zip(&tb).all(|(x, y)| {
            x == y
                || matches!((x.parse::<f64>(), y.parse::<f64>()), (Ok(u), Ok(v))
                    if (u - v).abs() <= 1e-12 * u.abs().max(1.0))
        })
}

fn same(a: f64, b: f64, tol: f64) -> bool {
    (a.is_nan() && b.is_nan()) || a == b || (a - b).abs() <= tol
}

/// Compare the conditions at `points`; `solution`: the points solve the
/// mapping equations (a converged motion), so the margins must equal the
/// sampled ones to rounding.
fn compare<M: Model>(
    what: &str,
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    solution: bool,
    tally: &mut Tally,
) {
    let fast = conditions(sim, structure, points);
    let dense = sampled_conditions(sim, structure, points, 2000, true);
    let sampled = sampled_conditions(sim, structure, points, 24, false);
    tally.point_sets += 1;
    assert_eq!(fast.len(), dense.len(), "{what}: {fast:#?}\n{dense:#?}");
    let vscale = (0..sim.info().boundaries.len())
        .map(|k| sim.velocity(k).abs())
        .fold(1.0f64, f64::max);
    for (i, (f, d)) in fast.iter().zip(&dense).enumerate() {
        let at = format!("{what}: condition {i}: {f:?} vs dense {d:?}");
        assert_eq!(
            (f.segment, f.kind, f.boundary),
            (d.segment, d.kind, d.boundary),
            "{at}"
        );
        let tol = 1e-12 * vscale.max(d.margin.abs());
        assert!(same(f.margin, d.margin, tol), "{at}");
        let violated = f.margin.is_nan() || f.margin <= 0.0;
        if violated {
            assert!(same_text(&f.condition, &d.condition), "{at}");
            tally.violated += 1;
        } else {
            assert!(f.condition.is_empty(), "{at}");
        }
        tally.conditions += 1;
        if f.kind == ViolationKind::Interior {
            tally.interior += 1;
        }
    }
    // The sampled search with 24 samples: the same to the bit, unless it
    // misses an extremum (two in one sample interval) or the segment's
    // ends are the infimum (points off a motion).
    let aligned = sampled.len() == fast.len()
        && sampled
            .iter()
            .zip(&fast)
            .all(|(s, f)| (s.segment, s.kind, s.boundary) == (f.segment, f.kind, f.boundary));
    let near =
        |s: &Violation, f: &Violation| same(s.margin, f.margin, 1e-13 * vscale.max(s.margin.abs()));
    let as_sampled = aligned && sampled.iter().zip(&fast).all(|(s, f)| near(s, f));
    if as_sampled {
        tally.as_sampled += 1;
    } else {
        let diff = format!(
            "{what}: {:?}",
            sampled
                .iter()
                .zip(&fast)
                .filter(|(s, f)| !near(s, f))
                .map(|(s, f)| (s.segment, s.kind, s.margin, f.margin))
                .collect::<Vec<_>>()
        );
        assert!(
            !solution,
            "a converged motion must keep its margins: {diff}"
        );
        tally.differs_from_sampled.push(diff);
    }
    // violations: the violated ones, each extremum from the closed form.
    let violated = violations(sim, structure, points);
    let expected: Vec<&Violation> = fast
        .iter()
        .filter(|c| c.margin.is_nan() || c.margin <= 0.0)
        .collect();
    assert_eq!(
        violated.len(),
        expected.len(),
        "{what}: {violated:#?}\n{expected:#?}"
    );
    for (v, e) in violated.iter().zip(&expected) {
        let at = format!("{what}: violation {v:?} vs condition {e:?}");
        assert_eq!(
            (v.segment, v.kind, v.boundary, &v.condition),
            (e.segment, e.kind, e.boundary, &e.condition),
            "{at}"
        );
        // The same walk with the same closed form: the same bits.
        let scale = vscale.max(e.margin.abs());
        assert!(same(v.margin, e.margin, 0.0), "{at}");
        if e.kind == ViolationKind::Interior && e.margin.is_finite() {
            tally.violated_interior += 1;
            let d = (v.margin - e.margin).abs() / scale;
            tally.largest_difference = tally.largest_difference.max(d);
        }
    }
    // worst_margin: the smallest of them, NaN first.
    let worst = worst_margin(sim, structure, points).expect("points");
    let key = |m: f64| if m.is_nan() { f64::NEG_INFINITY } else { m };
    let smallest = fast
        .iter()
        .min_by(|a, b| key(a.margin).total_cmp(&key(b.margin)))
        .expect("conditions");
    assert!(
        key(worst.margin) == key(smallest.margin),
        "{what}: {worst:?} vs {smallest:?}"
    );
    let first = fast
        .iter()
        .find(|c| key(c.margin) == key(smallest.margin))
        .expect("the smallest");
    // Named by the smallest force criterion on the same boundary when the
    // two vanish together (a tangential contact on a stick boundary).
    let force = fast
        .iter()
        .filter(|c| matches!(c.kind, ViolationKind::Pass | ViolationKind::StickOnset))
        .min_by(|a, b| key(a.margin).total_cmp(&key(b.margin)));
    let named = match (first.kind, force) {
        (ViolationKind::Arrival | ViolationKind::Interior | ViolationKind::Departure, Some(f))
            if f.boundary == first.boundary
                && (f.margin - first.margin).abs() <= SAME_EVENT * first.margin.abs().max(1.0) =>
        {
            f
        }
        _ => first,
    };
    assert_eq!(
        (worst.kind, worst.segment, worst.boundary),
        (named.kind, named.segment, named.boundary),
        "{what}"
    );
}

/// A small deterministic generator (xorshift64*), uniform in [-1, 1).
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        let r = self.0.wrapping_mul(0x2545_f491_4f6c_dd1d);
        (r >> 11) as f64 / (1u64 << 52) as f64 - 1.0
    }
}

/// The motion, then perturbations of it at three sizes.
fn motion_and_perturbations<M: Model>(
    what: &str,
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    rng: &mut Rng,
    tally: &mut Tally,
) {
    compare(what, sim, structure, points, true, tally);
    let scale = points.iter().map(|p| p.x.abs()).fold(1e-3f64, f64::max);
    for size in [1e-6, 1e-3, 3e-2, 3e-1] {
        let moved: Vec<SwitchingPoint> = points
            .iter()
            .map(|p| SwitchingPoint {
                phase: p.phase + size * rng.next(),
                x: p.x + size * scale * rng.next(),
            })
            .collect();
        compare(
            &format!("{what} perturbed by {size:e}"),
            sim,
            structure,
            &moved,
            false,
            tally,
        );
    }
}

/// The attractor from rest, if it is a periodic motion.
fn attractor<M: Model>(what: &str, sim: &Simulator<M>, rng: &mut Rng, tally: &mut Tally) -> bool {
    let start = sim.start(0.0, 0.0, 0.0).expect("start");
    match attractor::find(sim, start, AttractorOptions::default()) {
        Ok(Attractor::Periodic(m)) if m.structure.len() <= 40 => {
            let what = format!("{what}: {}", m.structure.notation(sim.info()));
            motion_and_perturbations(&what, sim, &m.structure, &m.points, rng, tally);
            true
        }
        _ => false,
    }
}

#[test]
fn fast_margins_match_the_sampled_and_dense_references() {
    let mut tally = Tally::default();
    let mut rng = Rng(0x9e37_79b9_7f4a_7c15);
    // The reference orbits, and Newton's motions from them.
    for r in common::reference::references() {
        let sim = r.simulator();
        let structure = r.structure();
        let what = format!("reference {} at W = {}", r.structure, r.w);
        motion_and_perturbations(&what, &sim, &structure, &r.points, &mut rng, &mut tally);
        let m = solve(
            &sim,
            structure.clone(),
            r.points.clone(),
            NewtonOptions::default(),
        );
        assert!(m.is_admissible(), "{what}: {:?}", m.violations);
        compare(&what, &sim, &structure, &m.points, true, &mut tally);
    }
    // The paper model over W and Q0 (sticks, passes, grazing neighbourhoods).
    let mut found = 0;
    for q0 in [40.0, 70.0, 120.0] {
        for i in 0..24 {
            let w = 0.4 + 8.4 * i as f64 / 23.0;
            let p = paper::Params {
                W: w,
                Q0: q0,
                ..paper::Params::default()
            };
            let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("params");
            let what = format!("paper at W = {w}, Q0 = {q0}");
            found += attractor(&what, &sim, &mut rng, &mut tally) as usize;
        }
    }
    assert!(found >= 50, "{found} paper motions");
    // Coulomb friction (a stick boundary only).
    for (w, q0) in [(0.8, 0.5), (0.5, 1.0), (1.3, 2.0), (0.3, 0.8)] {
        let p = coulomb::Params {
            W: w,
            Q0: q0,
            ..coulomb::Params::default()
        };
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("params");
        attractor(
            &format!("coulomb at W = {w}, Q0 = {q0}"),
            &sim,
            &mut rng,
            &mut tally,
        );
    }
    // A 16-piece Stribeck law (many narrow bands).
    for (w, q0) in [(1.5, 6.0), (1.0, 8.0), (2.5, 10.0)] {
        let sim = Simulator::<Pl16>::new(pl16::Params { W: w, Q0: q0 }, SimOptions::default())
            .expect("params");
        attractor(
            &format!("stribeck pl16 at W = {w}, Q0 = {q0}"),
            &sim,
            &mut rng,
            &mut tally,
        );
    }
    // Negative effective damping in some domains.
    for w in [1.0, 1.5, 2.5] {
        let p = stribeck8::Params {
            W: w,
            ..stribeck8::Params::default()
        };
        let sim = Simulator::<Stribeck8>::new(p, SimOptions::default()).expect("params");
        attractor(&format!("stribeck8 at W = {w}"), &sim, &mut rng, &mut tally);
    }
    eprintln!(
        "{} point sets, {} conditions ({} interior, {} violated); {} as the sampled search to rounding; \
         violations: {} interior ones within {:.1e} (relative) of the conditions",
        tally.point_sets,
        tally.conditions,
        tally.interior,
        tally.violated,
        tally.as_sampled,
        tally.violated_interior,
        tally.largest_difference
    );
    for d in tally.differs_from_sampled.iter().take(20) {
        eprintln!("differs from the sampled search (off a motion): {d}");
    }
    assert!(tally.violated_interior > 0, "{tally:?}");
    assert!(
        tally.violated > 200,
        "too few violated conditions: {tally:?}"
    );
}

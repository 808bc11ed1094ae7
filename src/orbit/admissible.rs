//! Admissibility of a solution of the mapping equations (SPEC §6): is it a
//! real motion? Every condition is evaluated with a signed margin (positive:
//! satisfied), and every violated one is reported with its segment, so that
//! a sweep knows why a motion stops existing and can locate where the margin
//! crosses zero.

use serde::Serialize;

use crate::dynamics::simulate::{EventKind, Location, Segment, Simulator};
use crate::model::{MappingKind, Model, Side};
use crate::orbit::periodic::SwitchingPoint;
use crate::orbit::structure::Structure;

/// Which condition of SPEC §6 a violation breaks; it names the transition a
/// parameter sweep meets where the condition starts to fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ViolationKind {
    /// A mapping with no positive duration.
    Duration,
    /// The flow does not leave its start boundary into its domain.
    Departure,
    /// The flow reaches another boundary before its arrival (grazing from inside).
    Interior,
    /// The arrival is not transversal (grazing at the arrival).
    Arrival,
    /// A stick onset whose force criterion fails: the flow passes instead.
    StickOnset,
    /// A pass whose force criterion fails: the flow sticks instead.
    Pass,
    /// A stick that ends elsewhere than the structure says (`|Fnf|` reaches `as` early).
    StickEnd,
    /// Anything else (an inconsistent structure, a failed simulation).
    Other,
}

/// One condition, satisfied or not.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Violation {
    /// Index of the mapping (in application order) where it happens.
    pub segment: usize,
    /// What is violated, in the model's terms.
    pub condition: String,
    /// By how much (negative or zero: violated; units of the quantity compared).
    pub margin: f64,
    /// Which kind of condition.
    #[serde(skip)]
    pub kind: ViolationKind,
    /// The boundary involved, if any (index).
    #[serde(skip)]
    pub boundary: Option<usize>,
}

/// Tolerance on phases when comparing a simulated event with a switching point.
fn phase_tol(phase: f64) -> f64 {
    1e-7 * phase.abs().max(1.0)
}

/// The smallest signed distance, over the open segment, from the velocity of
/// the flow in domain `j` to the domain's boundaries (positive: strictly
/// inside): for a boundary the segment starts or ends on, only interior
/// extrema of `v` count (where the acceleration changes sign, refined by
/// bisection); for any other boundary, every sample and extremum.
fn interior_margin<M: Model>(
    sim: &Simulator<M>,
    seg: &Segment,
    end: f64,
    touched: [usize; 2],
    j: usize,
) -> Option<(f64, usize)> {
    let dom = M::INFO.domains[j];
    let p = sim.params();
    let n = 24;
    let h = (end - seg.phase) / n as f64;
    let mut best: Option<(f64, usize)> = None;
    let mut consider = |v: f64, extremum: bool| {
        for k in [dom.lower, dom.upper].into_iter().flatten() {
            if !extremum && touched.contains(&k) {
                continue;
            }
            let margin = if Some(k) == dom.lower {
                v - sim.velocity(k)
            } else {
                sim.velocity(k) - v
            };
            if best.is_none_or(|(m, _)| margin < m) {
                best = Some((margin, k));
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
            // An extremum of v: safeguarded Newton on the acceleration
            // (its rate in phase is DF / W).
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
            consider(sim.state_at(seg, t).1, true);
        }
        if i < n {
            consider(sim.state_at(seg, phi).1, false);
        }
        prev = a;
    }
    best
}

/// Every condition of SPEC §6 for `points` of `structure`, with its margin;
/// the violated ones are those with margin `<= 0` (see [`violations`]).
pub fn conditions<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Vec<Violation> {
    let info = M::INFO;
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
        // The durations add up to the cycle's 2πN, so a longer one means that
        // another mapping takes negative time; the event search over the
        // whole span (Newton may put it anywhere) would be unbounded work.
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
                // |Fnf| < as during the stick: the first stick end is the one claimed.
                let seg = Segment {
                    x: a.x,
                    v: sim.velocity(mi.from),
                    phase: a.phase,
                    location: Location::Stick,
                    search_from: a.phase,
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
                // Departure into the domain (on the stick boundary after a stick
                // with as = ak the acceleration is 0 and its rate decides).
                let [acc0, rate0] = M::normal_field(p, j, a.x, va, a.phase);
                let into = if dom.lower == Some(mi.from) {
                    1.0
                } else {
                    -1.0
                };
                let dep = if into * acc0 == 0.0 {
                    into * rate0
                } else {
                    into * acc0
                };
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
                // The arrival on β is the first boundary contact.
                let seg = Segment {
                    x: a.x,
                    v: va,
                    phase: a.phase,
                    location: Location::Domain(j),
                    search_from: a.phase,
                };
                match sim.next_event(&seg, b.phase + phase_tol(b.phase)) {
                    Ok(Some((e, _)))
                        if e.phase < b.phase - phase_tol(b.phase) || e.boundary != mi.to =>
                    {
                        let what = if e.kind == EventKind::Graze {
                            "grazes"
                        } else {
                            "crosses"
                        };
                        let depth = interior_margin(sim, &seg, b.phase, [mi.from, mi.to], j)
                            .map_or(0.0, |(m, _)| m.min(0.0));
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
                    }
                    Ok(Some(_)) => {
                        if let Some((margin, kb)) =
                            interior_margin(sim, &seg, b.phase, [mi.from, mi.to], j)
                        {
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
                    }
                    Err(e) => add(
                        ViolationKind::Other,
                        None,
                        format!("simulation failed: {e}"),
                        f64::NAN,
                    ),
                }
                // Transversal arrival.
                let acc1 = M::normal_field(p, j, b.x, vb, b.phase)[0];
                let out_sign = if dom.upper == Some(mi.to) { 1.0 } else { -1.0 };
                add(
                    ViolationKind::Arrival,
                    Some(mi.to),
                    format!("the arrival on {} must be transversal", label(mi.to)),
                    out_sign * acc1,
                );
                // What happens at β.
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

/// The violated conditions of SPEC §6 for `points` of `structure` (empty for a real motion).
pub fn violations<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Vec<Violation> {
    let mut all = conditions(sim, structure, points);
    all.retain(|c| c.margin.is_nan() || c.margin <= 0.0);
    all
}

//! Admissibility of a solution of the mapping equations (SPEC §6): is it a
//! real motion? Every condition is evaluated with a signed margin (positive:
//! satisfied), and every violated one is reported with its segment, so that
//! a sweep knows why a motion stops existing and can locate where the margin
//! crosses zero.
//!
//! Along a flow segment the velocity's extrema come from the closed form
//! ([`crate::orbit::extrema`]): a segment whose acceleration provably keeps
//! its sign costs one evaluation, and the event search of the simulation is
//! run only where a margin is too small for the closed form to decide alone.
//! There the event search decides which boundary the flow meets first, the
//! closed form how far from it the flow stays: a graze it reports (a touch
//! within its graze tolerance) of an extremum the closed form keeps off the
//! boundary is no contact (`contact::first_contact`), so that each margin
//! is the closed form's on both sides of its zero and a sweep locates the
//! zero of the same smooth function as a two-parameter curve.
//! The text of a condition is written only when it is violated.
//!
//! Every extremum's value is the closed form's at its zero of the
//! acceleration: the margins are smooth functions of the points, equal to
//! rounding to an independent dense search (`tests/margins.rs`).

use crate::dynamics::simulate::{
    Event, EventKind, Location, Segment, Simulator, MAX_STEPS_PER_PERIOD,
};
use crate::model::{MappingKind, Model, Side};
use crate::orbit::extrema::{SegmentFlow, Zero};
use crate::orbit::periodic::{arrival, SwitchingPoint};
use crate::orbit::structure::Structure;

mod contact;
mod sink;
mod stick;

use contact::first_contact;
pub(crate) use stick::{early_end, early_end_extremum, end_touch, stick_exit_rate};

pub use sink::{ConditionId, Margin, Violation, ViolationKind, SAME_EVENT};
use sink::{Except, Several, Sink, Violated, Worst};

/// A departure's acceleration into its domain within this fraction of the
/// acceleration's terms (forcing, the domain's constant, spring and damper)
/// is zero: the departure is tangential and the rate of the acceleration
/// decides. After a stick whose static bound is the kinetic limit
/// (`as = ak`, the smooth laws' N-piece models) the force balance cancels to
/// a few ulps at every departure.
const FLAT_DEPARTURE: f64 = 1e-12;

/// Tolerance on phases when comparing a simulated event with a switching point.
fn phase_tol(phase: f64) -> f64 {
    1e-7 * phase.abs().max(1.0)
}

/// The smallest signed distance, over the open segment `(seg.phase, end)`,
/// from the velocity of the flow in domain `j` to the domain's boundaries
/// (positive: strictly inside), with the boundary where it is smallest: for
/// a boundary the segment starts or ends on (`touched`), over the interior
/// extrema of `v`; for any other boundary, over the whole segment (its
/// infimum: the extrema and the ends). `None` when no extremum and no other
/// boundary count.
///
/// The extrema are the zeros of the acceleration, all of them, passed to
/// [`InteriorMargin::extremum`] with the closed form's velocity there.
struct InteriorMargin<'a, M: Model> {
    sim: &'a Simulator<M>,
    /// Only the signs of the margins count ([`Sink::signs_only`]).
    signs_only: bool,
    j: usize,
    touched: [usize; 2],
    best: Option<(f64, usize)>,
    /// The smallest margin on the domain's lower and upper boundary alone
    /// (infinite where none counts): which boundary the closed form puts
    /// the flow near, for [`FlowCheck::keeps_off`].
    sides: [f64; 2],
}

impl<'a, M: Model> InteriorMargin<'a, M> {
    fn new(sim: &'a Simulator<M>, touched: [usize; 2], j: usize, signs_only: bool) -> Self {
        Self {
            sim,
            signs_only,
            j,
            touched,
            best: None,
            sides: [f64::INFINITY; 2],
        }
    }

    fn consider(&mut self, v: f64, extremum: bool) {
        let dom = self.sim.info().domains[self.j];
        for (side, k) in [dom.lower, dom.upper].into_iter().enumerate() {
            let Some(k) = k else { continue };
            if !extremum && self.touched.contains(&k) {
                continue;
            }
            let margin = if side == 0 {
                v - self.sim.velocity(k)
            } else {
                self.sim.velocity(k) - v
            };
            if self.best.is_none_or(|(m, _)| margin < m) {
                self.best = Some((margin, k));
            }
            // NaN stays (it proves nothing: see `FlowCheck::keeps_off`).
            if margin < self.sides[side] || margin.is_nan() {
                self.sides[side] = margin;
            }
        }
    }

    /// The next extremum of `v` (a zero of the acceleration), where the
    /// closed form gives the velocity `v`.
    fn extremum(&mut self, v: f64) {
        self.consider(v, true);
    }

    /// The margin, given the velocities at the segment's start and end,
    /// and the smallest margins on the lower and upper boundary alone.
    fn finish(mut self, start_v: f64, end_v: f64) -> (Option<(f64, usize)>, [f64; 2]) {
        // The ends, for the boundaries not touched.
        self.consider(start_v, false);
        self.consider(end_v, false);
        (self.best, self.sides)
    }
}

/// How the first boundary contact of a flow segment compares with its arrival.
enum Outcome {
    /// On the mapping's target, at its end (within the phase tolerance).
    Arrives,
    /// Elsewhere or earlier.
    Early(crate::dynamics::simulate::Event),
    /// Not before the end.
    Missing,
    /// The event search failed.
    Failed(crate::dynamics::simulate::SimError),
}

/// What the closed form says about one flow segment.
struct FlowCheck {
    /// The interior margin ([`InteriorMargin`]).
    interior: Option<(f64, usize)>,
    /// Whether the first boundary contact is, for certain, the arrival on
    /// the mapping's target within the phase tolerance (where the event
    /// search would find it): every margin is clear of zero.
    arrives: bool,
    /// The domain's lower and upper boundary (indices), each with the
    /// smallest margin of the closed form on it alone (infinite: none
    /// counts).
    sides: [(Option<usize>, f64); 2],
}

impl FlowCheck {
    /// The interior margin to each of the domain's boundaries that counts
    /// (lower, then upper): a margin of its own per boundary, so that the
    /// margin to one is defined (and smooth) whatever the other's.
    fn per_boundary(&self) -> [Option<(f64, usize)>; 2] {
        self.sides
            .map(|(b, m)| b.filter(|_| m != f64::INFINITY).map(|k| (m, k)))
    }

    /// Whether the closed form keeps the flow strictly inside, off boundary
    /// `k` (see `contact::first_contact`): any positive margin. Within the
    /// band where the event search decides (`near` of [`check_flow`]) a
    /// graze it reports there is a touch within its graze tolerance; beyond
    /// it, the flow's slow departure from `k` read as a graze. On `coulomb`
    /// with `V = 0, d = 0` a flow leaving the stick boundary on a
    /// stick-onset curve (accelerating at 6.3e-3 from it) was read as
    /// grazing it 1e-6 after the start at some points of the curve, where
    /// the closed form keeps it off by 0.77: its margin flipped from 0.77
    /// to 0 from one point to the next, and the curve ended there at a
    /// codimension-two point that held its second condition only to
    /// 2.5e-3 of its scale (`bash benches/curves-runs.sh shaw`).
    fn keeps_off(&self, k: usize) -> bool {
        self.sides.iter().any(|&(b, m)| b == Some(k) && m > 0.0)
    }
}

/// The interior margin of the flow of `seg` to phase `b` on boundary `to`
/// (collected by `margin`, which knows the domain and the boundaries the
/// segment touches), and whether its arrival is certain (`dep`: the
/// departure's acceleration into the domain, exactly 0 where it is zero to
/// rounding, [`FLAT_DEPARTURE`]).
fn check_flow<M: Model>(
    sim: &Simulator<M>,
    flow: &SegmentFlow,
    seg: &Segment,
    to: usize,
    b: f64,
    dep: f64,
    mut margin: InteriorMargin<'_, M>,
) -> FlowCheck {
    let j = margin.j;
    let dom = sim.info().domains[j];
    let co = sim.coefficients(j);
    let osc = sim.oscillator();
    let w = osc.frequency;
    let tol = phase_tol(b);
    let lo = dom.lower.map(|k| sim.velocity(k));
    let hi = dom.upper.map(|k| sim.velocity(k));
    let vscale = lo
        .unwrap_or(0.0)
        .abs()
        .max(hi.unwrap_or(0.0).abs())
        .max(seg.v.abs());
    // Closer than this to a boundary, the event search decides.
    let near = (100.0 * sim.options().graze_tol).max(1e-9 * vscale);
    let mut clear = true;
    let off = |v: f64, err: f64| {
        lo.is_none_or(|l| v - err - l > near) && hi.is_none_or(|h| h - v - err > near)
    };
    // Where only the signs of the margins count, an extremum proven clear
    // of both boundaries before the arrival needs no further refinement
    // (its margin, inexact, is positive and not the one reported).
    let signs_only = margin.signs_only;
    let enough = |z: &Zero| signs_only && z.phase + z.phase_err < b && off(z.state.v, z.v_err);
    // A departure with no acceleration (from a stick whose static bound is
    // the kinetic limit, `as = ak`: the flow leaves on the rate of its
    // acceleration) has a zero of the acceleration at its start: the
    // departure itself, on the boundary it leaves, not an interior contact.
    // Counted, its margin is zero up to rounding wherever the motion lives,
    // and its sign flickers from point to point.
    flow.acceleration_zeros(seg.phase, b + tol, enough, |z| {
        if z.phase > b {
            clear = false;
            return;
        }
        if dep == 0.0 && z.phase - seg.phase <= tol {
            return;
        }
        margin.extremum(z.state.v);
        clear &= off(z.state.v, z.v_err);
    });
    let e = flow.at(b);
    let (interior, sides) = margin.finish(seg.v, e.v);
    let vb = sim.velocity(to);
    let out = if dom.upper == Some(to) { 1.0 } else { -1.0 };
    let ascale = osc.amplitude.abs()
        + co.b.abs()
        + (co.c * e.x).abs()
        + (co.two_d * e.v).abs()
        + (co.c * seg.x).abs();
    // The event search's own limit on stiff domains.
    let step =
        std::f64::consts::FRAC_PI_4.min(w * 0.5 / (co.c.abs().sqrt() + 0.5 * co.two_d.abs()));
    let steps = std::f64::consts::TAU / step;
    let arrives = clear
        && steps <= MAX_STEPS_PER_PERIOD
        && dep > 1e-9 * ascale
        && out * e.a > 1e-9 * ascale
        && (e.v - vb).abs() * w <= 1e-3 * tol * e.a.abs()
        && [e.x, e.v, e.a].iter().all(|v| v.is_finite());
    FlowCheck {
        interior,
        arrives,
        sides: [(dom.lower, sides[0]), (dom.upper, sides[1])],
    }
}

/// Every condition of SPEC §6 for `points` of `structure`, with its margin;
/// the violated ones are those with margin `<= 0` (see [`violations`]).
/// Only the violated ones carry their text ([`Violation::condition`]).
pub fn conditions<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Vec<Violation> {
    let mut out = Vec::with_capacity(6 * points.len());
    walk(sim, structure, points, &mut out);
    out
}

/// The smallest margin of every condition of [`conditions`] (NaN counts as
/// the smallest), with its kind, segment and boundary; `None` for no points.
/// Where the smallest is a departure, arrival or interior contact on a stick
/// boundary and the smallest force criterion (pass, stick onset) on that
/// boundary is within [`SAME_EVENT`] of it, the two vanish together and the
/// margin is named by the force criterion (its kind and segment; the value
/// stays the smallest). Writes no text and allocates nothing: for a
/// continuation that watches the margins point by point.
pub fn worst_margin<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Option<Margin> {
    let mut worst = Worst::default();
    walk(sim, structure, points, &mut worst);
    worst.result()
}

/// The margin of the one condition `(kind, segment, boundary)` of
/// [`conditions`] (the smallest if several match; NaN: not evaluable),
/// `None` if the walk does not evaluate it at these points. No text, no
/// allocation: the condition of a two-parameter curve. Each margin is a
/// smooth function of the points here: the interior margin from the closed
/// form with no event search, and a stick's end (`StickEnd`) by the
/// interior extrema of `Fnf` against `±as` and the exit's rate
/// `d|Fnf|/dφ`, the smaller (a force; `stick::early_end_margin`) instead of
/// the event search's phase difference, which jumps where the stick starts
/// to end early.
pub(crate) fn margin_of<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    id: ConditionId,
) -> Option<f64> {
    let mut margin = [None];
    margins_of(sim, structure, points, &[id], &mut margin);
    margin[0]
}

/// [`margin_of`] for several conditions in one walk: the margin of `ids[i]`
/// in `margins[i]` (`None` if the walk does not evaluate it). No text, no
/// allocation.
pub(crate) fn margins_of<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    ids: &[ConditionId],
    margins: &mut [Option<f64>],
) {
    margins.fill(None);
    let mut several = Several { ids, margins };
    walk(sim, structure, points, &mut several);
}

/// [`worst_margin`] over every condition but the `excluded` ones (a
/// two-parameter curve's own condition and those that vanish with it):
/// what ends that curve. No text, no allocation.
pub(crate) fn worst_margin_except<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    excluded: &[ConditionId],
) -> Option<Margin> {
    let mut except = Except {
        excluded,
        worst: Worst::default(),
    };
    walk(sim, structure, points, &mut except);
    except.worst.result()
}

fn walk<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
    out: &mut impl Sink,
) {
    let info = sim.info();
    let p = sim.params();
    let m = points.len();
    let shift = crate::orbit::periodic::cycle_shift(structure, points);
    let label = |k: usize| info.boundaries[k].label;
    // Each margin as a smooth function of the points: no event search.
    let smooth = out.smooth();
    let signs_only = out.signs_only();
    for k in 0..m {
        let mi = info.mappings[structure.steps()[k]];
        let next_mi = info.mappings[structure.steps()[(k + 1) % m]];
        let (a, b) = (points[k], arrival(points, k, shift));
        let mut add =
            |kind: ViolationKind,
             boundary: Option<usize>,
             margin: f64,
             text: &dyn Fn() -> String| { out.add(k, kind, boundary, margin, text) };
        let duration = b.phase - a.phase;
        add(ViolationKind::Duration, None, duration, &|| {
            format!(
                "mapping {} must take positive time (W t from {} to {})",
                mi.name, a.phase, b.phase
            )
        });
        if duration.is_nan() || duration <= 0.0 {
            continue;
        }
        // The durations add up to the cycle's 2πN, so a longer one means that
        // another mapping takes negative time; the event search over the
        // whole span (Newton may put it anywhere) would be unbounded work.
        if duration > shift + phase_tol(b.phase) {
            add(ViolationKind::Duration, None, shift - duration, &|| {
                format!(
                    "mapping {} must take less than the whole cycle (W t from {} to {})",
                    mi.name, a.phase, b.phase
                )
            });
            continue;
        }
        match (mi.kind, mi.domain) {
            (MappingKind::Stick, _) if smooth => {
                // As a smooth function of the points: the interior extrema
                // of Fnf against ±as and the exit's rate, the smaller.
                if let Some(m) = stick::early_end_margin(sim, mi.from, a.x, a.phase, b.phase) {
                    add(ViolationKind::StickEnd, Some(mi.from), m, &|| {
                        format!(
                            "the stick on {} must keep |Fnf| < as until W t = {}",
                            label(mi.from),
                            b.phase
                        )
                    });
                }
            }
            (MappingKind::Stick, _) => {
                // |Fnf| < as during the stick: the first stick end is the one claimed.
                // A start beyond `as` moving back inside is the stick
                // onset's condition, not an early end (`stick::search_start`).
                let seg = Segment {
                    x: a.x,
                    v: sim.velocity(mi.from),
                    phase: a.phase,
                    location: Location::Stick,
                    search_from: stick::search_start(sim, mi.from, a.x, a.phase, b.phase),
                };
                let event = sim.next_event(&seg, b.phase + phase_tol(b.phase));
                let (margin, exit_ok) = match &event {
                    Ok(Some((e, _))) if e.kind == EventKind::StickEnd => {
                        let exit_ok = match (e.after, mi.exit) {
                            (Location::Domain(j), Some(Side::Above)) => j == mi.from + 1,
                            (Location::Domain(j), Some(Side::Below)) => j == mi.from,
                            _ => false,
                        };
                        if exit_ok {
                            (e.phase - b.phase + phase_tol(b.phase), true)
                        } else {
                            (-(b.phase - e.phase).abs().max(f64::MIN_POSITIVE), false)
                        }
                    }
                    Ok(_) => (0.0, true),
                    Err(_) => (f64::NAN, true),
                };
                add(
                    ViolationKind::StickEnd,
                    Some(mi.from),
                    margin,
                    &|| match &event {
                        Ok(Some((e, _))) if e.kind == EventKind::StickEnd => {
                            if !exit_ok {
                                format!(
                                    "the stick on {} ends to the other side at W t = {}",
                                    label(mi.from),
                                    e.phase
                                )
                            } else {
                                format!(
                                    "the stick on {} must last until W t = {} (|Fnf| < as)",
                                    label(mi.from),
                                    b.phase
                                )
                            }
                        }
                        Ok(Some((e, _))) => format!(
                            "unexpected {:?} during the stick at W t = {}",
                            e.kind, e.phase
                        ),
                        Ok(None) => format!(
                            "|Fnf| < as until W t = {}: the stick does not end there",
                            b.phase
                        ),
                        Err(e) => format!("simulation failed: {e}"),
                    },
                );
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
                // Zero up to rounding counts as zero: with as = ak the
                // force balance at the stick's end cancels to a few ulps of
                // its terms, whose sign is noise (stribeck8: ±3e-13 at
                // every departure from the stick, flickering along a sweep).
                let coef = sim.coefficients(j);
                let acc_scale = M::oscillator(p).amplitude.abs()
                    + coef.b.abs()
                    + (coef.c * a.x).abs()
                    + (coef.two_d * va).abs();
                let flat_departure = (into * acc0).abs() <= FLAT_DEPARTURE * acc_scale;
                let acc_into = if flat_departure { 0.0 } else { into * acc0 };
                let dep = if flat_departure {
                    into * rate0
                } else {
                    into * acc0
                };
                add(ViolationKind::Departure, Some(mi.from), dep, &|| {
                    format!(
                        "the flow must leave {} into domain {}",
                        label(mi.from),
                        dom.label
                    )
                });
                let seg = Segment {
                    x: a.x,
                    v: va,
                    phase: a.phase,
                    location: Location::Domain(j),
                    search_from: stick::search_start(sim, mi.from, a.x, a.phase, b.phase),
                };
                let check =
                    SegmentFlow::new(sim.oscillator(), sim.coefficients(j), a.x, va, a.phase).map(
                        |f| {
                            let ends = [mi.from, mi.to];
                            let margin = InteriorMargin::new(sim, ends, j, signs_only);
                            check_flow(sim, &f, &seg, mi.to, b.phase, acc_into, margin)
                        },
                    );
                // A flow the closed form cannot follow has no margin.
                let interior = || match &check {
                    Some(c) => c.interior,
                    None => Some((f64::NAN, mi.to)),
                };
                // Each boundary of the domain on its own: where the flow
                // nears both, the margin to one is a condition of its own
                // however small the other's (a curve traces it across).
                let per_boundary = || match &check {
                    Some(c) => c.per_boundary(),
                    None => [Some((f64::NAN, mi.to)), None],
                };
                // The arrival on β is the first boundary contact: certain from
                // the closed form when every margin is clear of zero, else
                // the event search decides.
                let tol = phase_tol(b.phase);
                let early = |e: &Event| e.phase < b.phase - tol || e.boundary != mi.to;
                let event = match &check {
                    Some(c) if c.arrives || smooth => None,
                    c => Some(first_contact(sim, &seg, b.phase + tol, early, |k| {
                        c.as_ref().is_some_and(|c| c.keeps_off(k))
                    })),
                };
                let outcome = match event {
                    None => Outcome::Arrives,
                    Some(Ok(Some((e, _)))) if early(&e) => Outcome::Early(e),
                    Some(Ok(Some(_))) => Outcome::Arrives,
                    Some(Ok(None)) => Outcome::Missing,
                    Some(Err(e)) => Outcome::Failed(e),
                };
                // Where the flow arrives, or contacts a boundary early: its
                // margin to each boundary (but the early contact's own).
                let sides = match outcome {
                    Outcome::Arrives => Some(None),
                    Outcome::Early(e) => {
                        let what = if e.kind == EventKind::Graze {
                            "grazes"
                        } else {
                            "crosses"
                        };
                        let depth = interior().map_or(0.0, |(m, _)| m.min(0.0));
                        add(ViolationKind::Interior, Some(e.boundary), depth, &|| {
                            format!(
                                "the flow of {} {what} {} at W t = {} before reaching {}",
                                mi.name,
                                label(e.boundary),
                                e.phase,
                                label(mi.to)
                            )
                        });
                        // Each other boundary's margin as on arrival: the
                        // early contact (often the curve's own grazing, a
                        // few ulps inside) must not hide it. On `stribeck8`
                        // (W=2.3:2.6 × Q0=1:3) a grazing curve ran on past
                        // where its flow's margin to the domain's other
                        // boundary vanished, to -0.072 (`codim2_residual`
                        // 1.8e-2 at its end).
                        Some(Some(e.boundary))
                    }
                    Outcome::Missing => {
                        let (_, v) = sim.state_at(&seg, b.phase);
                        add(
                            ViolationKind::Arrival,
                            Some(mi.to),
                            -(v - vb).abs(),
                            &|| {
                                format!(
                                    "the flow of {} does not reach {} by W t = {}",
                                    mi.name,
                                    label(mi.to),
                                    b.phase
                                )
                            },
                        );
                        None
                    }
                    Outcome::Failed(e) => {
                        add(ViolationKind::Other, None, f64::NAN, &|| {
                            format!("simulation failed: {e}")
                        });
                        None
                    }
                };
                if let Some(skip) = sides {
                    for (margin, kb) in per_boundary().into_iter().flatten() {
                        if Some(kb) != skip {
                            add(ViolationKind::Interior, Some(kb), margin, &|| {
                                format!(
                                    "the flow of {} must stay off {} before its arrival",
                                    mi.name,
                                    label(kb)
                                )
                            });
                        }
                    }
                }
                // Transversal arrival.
                let acc1 = M::normal_field(p, j, b.x, vb, b.phase)[0];
                let out_sign = if dom.upper == Some(mi.to) { 1.0 } else { -1.0 };
                add(
                    ViolationKind::Arrival,
                    Some(mi.to),
                    out_sign * acc1,
                    &|| format!("the arrival on {} must be transversal", label(mi.to)),
                );
                // What happens at β.
                if next_mi.kind != MappingKind::Stick && next_mi.domain == Some(j) {
                    add(ViolationKind::Other, Some(mi.to), -(acc1.abs()), &|| {
                        format!(
                            "{} arrives on {} from domain {} and {} leaves into the same domain",
                            mi.name,
                            label(mi.to),
                            dom.label,
                            next_mi.name
                        )
                    });
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
                            (-fa).min(fb),
                            &|| {
                                format!("stick onset on {} needs F_in above < 0 < F_in below (F_in above = {fa}, F_in below = {fb})", label(mi.to))
                            },
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
                        add(ViolationKind::Pass, Some(mi.to), margin, &|| {
                            format!(
                                "passing {} needs {need} (F_in above = {fa}, F_in below = {fb})",
                                label(mi.to)
                            )
                        });
                    }
                }
            }
            (_, None) => add(ViolationKind::Other, None, f64::NAN, &|| {
                "a flow mapping without a domain".into()
            }),
        }
    }
}

/// The violated conditions of SPEC §6 for `points` of `structure` (empty for a real motion).
pub fn violations<M: Model>(
    sim: &Simulator<M>,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Vec<Violation> {
    let mut violated = Violated(Vec::new());
    walk(sim, structure, points, &mut violated);
    violated.0
}

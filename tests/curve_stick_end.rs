//! The curve of a stick that ends early (`StickEnd`, named
//! `stick_vanishing`), paper model, plane (W, Q0):
//!
//! At Q0 = 200 a sweep along W ends the branch of `P_{3_31 0_11 1_11 3_13 4_33}`
//! at W ≈ 2.7324753: during its stick the non-friction force `Fnf` has an
//! interior maximum that reaches the static bound `as`, so beyond it the
//! stick ends early (into Ω1: a short slip and a second stick,
//! `P_{3_31 0_11 1_11 0_11 1_11 3_13 4_33}`).
//!
//! 1. The curve started from that transition: at every point the motion is
//!    re-solved by `PeriodicSolver` at that (W, Q0), and the largest `Fnf`
//!    over the stick is found by this test's own scan and bisection on
//!    `dFnf/dφ` (the closed form of SPEC §3 with `x = x_a + V (φ − φ_a)/W`):
//!    `as − max Fnf` is zero to 1e-10 of the condition's scale.
//! 2. Sweeps along W at other Q0 locate the transition within 1e-8 of the
//!    curve's exact crossing of that line.

mod common;

use common::sweep_ends::branch_ends;

use stickslip::bifurcation::curve::{
    condition_at_transition, condition_scale, crossings, trace, Condition, Curve, CurveOptions,
    CurvePoint, Line, Plane,
};
use stickslip::bifurcation::TransitionKind;
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::admissible::ViolationKind;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::study::sweep::{sweep, SweepOptions};
use stickslip::Model;

const STRUCTURE: &str = "P_{3_31 0_11 1_11 3_13 4_33}";

fn plane() -> Plane {
    Plane {
        x: Params::index_of("W").unwrap(),
        y: Params::index_of("Q0").unwrap(),
        x_range: [2.6, 2.9],
        y_range: [185.0, 215.0],
    }
}

fn at(w: f64, q: f64) -> Params {
    Params {
        W: w,
        Q0: q,
        ..Params::default()
    }
}

/// The sweep along W at `q` over the box's W range.
fn sweep_at(q: f64) -> stickslip::study::sweep::Sweep {
    let [lo, hi] = plane().x_range;
    sweep::<Paper>(at(2.75, q), "W", lo, hi, 60, SweepOptions::default()).expect("sweep")
}

/// The ends of the branches of [`STRUCTURE`] that the sweep at `q` names
/// `stick_vanishing`, with the switching points there.
fn stick_ends(q: f64) -> Vec<(f64, Vec<SwitchingPoint>)> {
    branch_ends(&sweep_at(q), STRUCTURE, "stick_vanishing")
}

/// The start and the arrival of mapping `k` of `structure` at `points`
/// (the last one's arrival is the first point a cycle on).
fn span(structure: &Structure, points: &[SwitchingPoint], k: usize) -> [SwitchingPoint; 2] {
    let m = points.len();
    let mut b = points[(k + 1) % m];
    if k + 1 == m {
        b.phase += std::f64::consts::TAU * structure.periods() as f64;
    }
    [points[k], b]
}

/// The curve traced from the stick's vanishing at `(w, q)` with switching
/// points `points`, whose condition must be the smooth margin of the stick
/// `segment` (`why` names it).
fn stick_end_curve(
    structure: &Structure,
    w: f64,
    q: f64,
    points: Vec<SwitchingPoint>,
    segment: usize,
    why: &str,
) -> Curve {
    let cond = condition_at_transition::<Paper>(
        &at(w, q),
        structure,
        &points,
        TransitionKind::StickVanishing,
    )
    .expect("a condition at the stick's vanishing");
    let Condition::Margin {
        kind,
        segment: found,
        ..
    } = cond
    else {
        panic!("{cond:?}");
    };
    assert_eq!(kind, ViolationKind::StickEnd);
    assert_eq!(found, segment, "{why}");
    let start = CurvePoint { x: w, y: q, points };
    trace::<Paper>(
        &Params::default(),
        &plane(),
        Some(structure),
        &start,
        cond,
        &CurveOptions::default(),
    )
    .expect("the stick-end curve")
}

/// `as − max Fnf` over the interior of the stick `segment` of the motion
/// of `structure` at `(w, q)` (the stick from `points[segment]` to the next
/// point), by this test's own scan of `dFnf/dφ` and bisection; the motion is
/// re-solved first from `points`. `None` if `Fnf` has no interior maximum.
fn stick_margin(
    structure: &Structure,
    w: f64,
    q: f64,
    points: &[SwitchingPoint],
    segment: usize,
) -> Option<f64> {
    let p = at(w, q);
    let mut pts = points.to_vec();
    let t = PeriodicSolver::<Paper>::new(structure.clone()).solve(
        &p,
        &mut pts,
        NewtonOptions::default(),
    );
    assert!(t.converged(), "re-solving at ({w}, {q}): {t:?}");
    let [a, b] = span(structure, &pts, segment);
    // SPEC §3: Fnf = A0 cos(W t) − 2 d V − c x, stuck at v = V, per unit mass.
    let a0 = p.Q0 / p.m;
    let bound = p.mus * p.g;
    let x = |phi: f64| a.x + p.V * (phi - a.phase) / p.W;
    let fnf = |phi: f64| a0 * phi.cos() - 2.0 * p.d * p.V - p.c * x(phi);
    let rate = |phi: f64| -a0 * phi.sin() - p.c * p.V / p.W;
    let n = 4000;
    let h = (b.phase - a.phase) / n as f64;
    let mut best: Option<f64> = None;
    for i in 0..n {
        let (lo, hi) = (a.phase + h * i as f64, a.phase + h * (i + 1) as f64);
        // A maximum: the rate turns from positive to negative.
        if rate(lo) > 0.0 && rate(hi) <= 0.0 {
            let phi = common::roots::bisect(lo, hi, |s| rate(s) <= 0.0, 0.0);
            let f = fnf(phi);
            best = Some(best.map_or(bound - f, |v: f64| v.min(bound - f)));
        }
    }
    best
}

/// The curve from the sweep's stick end at Q0 = 200.
fn the_curve() -> (Structure, Curve) {
    let structure = Structure::parse(Paper::INFO, STRUCTURE, 1).expect("structure");
    let ends = stick_ends(200.0);
    eprintln!(
        "Q0 = 200: stick ends at W = {:?}",
        ends.iter().map(|e| e.0).collect::<Vec<_>>()
    );
    let (w, points) = ends
        .iter()
        .find(|e| (e.0 - 2.7324753).abs() < 1e-6)
        .cloned()
        .expect("the stick end near W = 2.7324753");
    let t0 = std::time::Instant::now();
    let c = stick_end_curve(
        &structure,
        w,
        200.0,
        points,
        3,
        "the stick 0_11 is the fourth mapping applied",
    );
    eprintln!(
        "{:?}: {} points in {:?}, ends {:?}",
        c.kind,
        c.points.len(),
        t0.elapsed(),
        c.ends
            .iter()
            .map(|e| (e.reason.clone(), e.at.x, e.at.y))
            .collect::<Vec<_>>()
    );
    (structure, c)
}

#[test]
fn a_stick_end_curve_satisfies_its_condition_and_the_sweeps_locate_it() {
    let base = Params::default();
    let (structure, c) = the_curve();
    assert_eq!(c.kind, TransitionKind::StickVanishing);
    assert!(c.points.len() >= 5, "{} points", c.points.len());
    let (lo, hi) = c
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), q| {
            (a.min(q.y), b.max(q.y))
        });
    eprintln!("Q0 from {lo} to {hi}");
    assert!(hi - lo > 10.0, "Q0 from {lo} to {hi}");
    // 1. Every point (and end): as − max Fnf = 0, independently.
    let mut worst = 0.0f64;
    for q in c.points.iter().chain(c.ends.iter().map(|e| &e.at)) {
        let g = stick_margin(&structure, q.x, q.y, &q.points, 3).expect("an interior maximum");
        let scale =
            condition_scale::<Paper>(&at(q.x, q.y), c.condition, Some(&structure), &q.points);
        worst = worst.max(g.abs() / scale);
    }
    eprintln!("largest |as − max Fnf| / scale over the curve: {worst:e}");
    assert!(worst <= 1e-10, "|g| / scale = {worst:e}");
    // 2. Sweeps along W at other Q0 locate the crossings.
    let mut matched = 0;
    for q in [200.0, 205.0, 210.0] {
        let xs = crossings::<Paper>(&base, &plane(), &c, Line::Y(q), &CurveOptions::default());
        assert!(!xs.is_empty(), "no crossing of Q0 = {q}");
        let located = stick_ends(q);
        for x in &xs {
            assert_eq!(x.y, q);
            let near = located
                .iter()
                .map(|(v, _)| (v - x.x).abs())
                .fold(f64::INFINITY, f64::min);
            eprintln!(
                "Q0 = {q}: the curve crosses at W = {} ({near:e} from the sweep's)",
                x.x
            );
            assert!(near <= 1e-8, "Q0 = {q}: W = {}: {near:e}", x.x);
            matched += 1;
        }
    }
    // Two crossings of each line: the curve is a U whose arms both cross.
    assert!(matched >= 6, "{matched} crossings");
}

/// The `curves` run over the window, seeded along Q0 = 200, starts this
/// curve from the sweep's transition, and every curve ends on the box's
/// edge or at a codimension-two point (none crawls to the point limit: a
/// stick whose extremum of Fnf sits at its exit is not traced, its margin
/// vanishing quadratically there).
#[test]
fn the_curves_run_starts_the_stick_end_curve() {
    use stickslip::bifurcation::curve::CurveEndReason;
    use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
    let base = Params::default();
    let opts = CurvesOptions {
        x: ("W".into(), plane().x_range),
        y: ("Q0".into(), plane().y_range),
        seeds: vec![Line::Y(200.0)],
        at: Vec::new(),
    };
    let t0 = std::time::Instant::now();
    // With the box's edges (the default): their sweeps add the curves of
    // the 12- and 17-mapping motions near W = 2.697, Q0 = 204.2 whose
    // sticks' exits turn tangential (the test below). Until stop 39 their
    // period-doubling curves crawled to `newton_failure` ends there, which
    // the last check counts, and nine of their stick-vanishing curves
    // failed to start.
    let (set, curves) = traced::<Paper>(&base, &opts, &CurvesSettings::default()).expect("the run");
    eprintln!("{} curves in {:?}", curves.len(), t0.elapsed());
    assert!(set.failed_starts.is_empty(), "{:#?}", set.failed_starts);
    let stick_ends: Vec<&Curve> = curves
        .iter()
        .filter(|c| {
            matches!(
                c.condition,
                Condition::Margin {
                    kind: ViolationKind::StickEnd,
                    ..
                }
            )
        })
        .collect();
    let ours = stick_ends
        .iter()
        .find(|c| {
            c.structure
                .as_ref()
                .map(|s| s.notation(Paper::INFO))
                .as_deref()
                == Some(STRUCTURE)
        })
        .expect("the stick-end curve of P_{3_31 0_11 1_11 3_13 4_33}");
    let xs = crossings::<Paper>(
        &base,
        &plane(),
        ours,
        Line::Y(200.0),
        &CurveOptions::default(),
    );
    assert!(
        xs.iter().any(|x| (x.x - 2.7324753081).abs() < 1e-8),
        "{:?}",
        xs.iter().map(|x| x.x).collect::<Vec<_>>()
    );
    // The grazing of Σ1 (the belt's velocity) by `P_{3_31 0_11 3_13 4_33}`
    // ends where the velocity maximum before the arrival on Σ1 leaves the
    // segment through that arrival as the arrival turns tangential, with
    // the stick-onset force there (beyond, the maximum and the minimum
    // after it are gone, and with them the grazing margin). That is a
    // codimension-two end, a passable onset on Σ1, whichever side of it the
    // last bits put the corrector's last point. Independently of the
    // tracer: at that end the motion's own conditions (`conditions`, with
    // the event search) give a stick-onset margin of zero to 1e-6.
    let grazing = curves
        .iter()
        .find(|c| {
            c.kind == TransitionKind::Grazing
                && c.structure
                    .as_ref()
                    .map(|s| s.notation(Paper::INFO))
                    .as_deref()
                    == Some("P_{3_31 0_11 3_13 4_33}")
                && c.ends
                    .iter()
                    .any(|e| (e.at.x - 2.66697).abs() < 1e-4 && (e.at.y - 192.125).abs() < 1e-2)
        })
        .expect("the grazing curve of P_{3_31 0_11 3_13 4_33} ending near (2.66697, 192.125)");
    let end = grazing
        .ends
        .iter()
        .find(|e| (e.at.x - 2.66697).abs() < 1e-4)
        .expect("that end");
    assert!(
        matches!(
            end.reason,
            CurveEndReason::Codim2 {
                kind: TransitionKind::PassableOnset,
                boundary: Some(1),
            }
        ),
        "{:?}",
        end.reason
    );
    let sim = stickslip::dynamics::simulate::Simulator::<Paper>::new(
        at(end.at.x, end.at.y),
        Default::default(),
    )
    .expect("params");
    let s = grazing.structure.as_ref().expect("a motion's curve");
    let margins = stickslip::orbit::admissible::conditions(&sim, s, &end.at.points);
    let onset = margins
        .iter()
        .filter(|m| m.kind == ViolationKind::StickOnset)
        .map(|m| m.margin.abs())
        .fold(f64::INFINITY, f64::min);
    assert!(onset < 1e-6, "stick-onset margin {onset:e} at the end");
    let other = common::cycle::other_ends(Paper::INFO, &curves);
    assert!(other.is_empty(), "{other:#?}");
}

/// The period-2 motion of the stick-end box whose stick `0_11` (the ninth
/// mapping applied) ends where `Fnf` reaches `as` ever more slowly.
const DOUBLE: &str = "P_{3_31 0_11 1_11 0_11 1_11 3_13 4_33 3_31 0_11 1_11 3_13 4_33}";

/// `d|Fnf|/dφ` at the exit of the stick `segment` of the motion of
/// `structure` at `(w, q)` with switching points `points` (this test's own
/// closed form of SPEC §3), with the largest residual of the motion's
/// mapping equations there. Not re-solved: where the exit is tangential
/// the stick's equation has no derivative in its exit's phase, and Newton
/// on the motion alone is singular (the curve's system, with both
/// parameters and the condition, is not).
fn exit_rate(
    structure: &Structure,
    w: f64,
    q: f64,
    points: &[SwitchingPoint],
    segment: usize,
) -> (f64, f64) {
    let p = at(w, q);
    let mut residual = 0.0f64;
    for (k, &step) in structure.steps().iter().enumerate() {
        let [a, b] = span(structure, points, k);
        for r in Paper::residual(&p, step, a.x, a.phase, b.x, b.phase).iter() {
            residual = residual.max(r.abs());
        }
    }
    let [a, b] = span(structure, points, segment);
    let a0 = p.Q0 / p.m;
    let x = a.x + p.V * (b.phase - a.phase) / p.W;
    let fnf = a0 * b.phase.cos() - 2.0 * p.d * p.V - p.c * x;
    let rate = -a0 * b.phase.sin() - p.c * p.V / p.W;
    (fnf.signum() * rate, residual)
}

/// Where a stick's exit turns tangential (`Fnf` reaches `as` with zero
/// rate; beyond, `|Fnf|` exceeds `as` just before the exit and the stick
/// ends early) the stick vanishes: the lower end in W of the branch of
/// [`DOUBLE`] along every line Q0 = const of the box's top. The margin of
/// an interior extremum vanishes there quadratically, the exit's rate
/// linearly: the curve is traced on the rate (until stop 39 its starts
/// failed, "the start is not on the curve"). Independently: at every point
/// of the curve the motion's mapping equations hold and the exit's rate is
/// zero to 1e-10 of the force's scale, by this test's own closed form
/// (with `|Fnf| = as` at the exit: the stick's own equation), and sweeps
/// along W at three Q0
/// end the branch within 1e-8 of the curve's crossing of that line.
///
/// `DP` has a simple pole there (the exit's phase moves with the stick's
/// start as `1 / (dFnf/dφ)`), and the motion's period-doubling curve runs
/// close along the curve into it: it ends at a codimension-two point with
/// a stick's vanishing (before stop 39 it crawled to a corrector failure
/// at W = 2.69765, Q0 = 204.183, the raw `det(I + DP)` held to 1e-7 of
/// its scale). Its points re-solved have an eigenvalue −1 of `DP`.
#[test]
fn a_stick_whose_exit_turns_tangential_vanishes_on_a_traced_curve() {
    let base = Params::default();
    let structure = Structure::parse(Paper::INFO, DOUBLE, 2).expect("structure");
    let branch_ends = |q: f64, around: f64| {
        let s = sweep::<Paper>(
            at(around, q),
            "W",
            around - 2e-3,
            around + 2e-3,
            40,
            SweepOptions::default(),
        )
        .expect("sweep");
        branch_ends(&s, DOUBLE, "stick_vanishing")
    };
    // The branch's lower end at Q0 = 205.
    let ends = branch_ends(205.0, 2.6919);
    let (w, points) = ends
        .iter()
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .cloned()
        .expect("the branch's ends at Q0 = 205");
    eprintln!(
        "Q0 = 205: the branch ends at {:?}",
        ends.iter().map(|e| e.0).collect::<Vec<_>>()
    );
    let segment = 8;
    let c = stick_end_curve(
        &structure,
        w,
        205.0,
        points,
        segment,
        "the stick 0_11 before the excursion 1_11",
    );
    eprintln!(
        "{} points, ends {:?}",
        c.points.len(),
        c.ends
            .iter()
            .map(|e| (e.reason.clone(), e.at.x, e.at.y))
            .collect::<Vec<_>>()
    );
    assert!(c.points.len() >= 5, "{} points", c.points.len());
    let mut worst = 0.0f64;
    for q in c.points.iter().chain(c.ends.iter().map(|e| &e.at)) {
        let (rate, residual) = exit_rate(&structure, q.x, q.y, &q.points, segment);
        let scale =
            condition_scale::<Paper>(&at(q.x, q.y), c.condition, Some(&structure), &q.points);
        assert!(residual <= 1e-9, "mapping residual {residual:e}");
        worst = worst.max(rate.abs() / scale);
    }
    eprintln!("largest |d|Fnf|/dφ| / scale at the exit over the curve: {worst:e}");
    assert!(worst <= 1e-10, "{worst:e}");
    for q in [210.0, 205.0, 204.4] {
        let xs = crossings::<Paper>(&base, &plane(), &c, Line::Y(q), &CurveOptions::default());
        assert_eq!(
            xs.len(),
            1,
            "Q0 = {q}: {:?}",
            xs.iter().map(|x| x.x).collect::<Vec<_>>()
        );
        let located = branch_ends(q, xs[0].x);
        let near = located
            .iter()
            .map(|(v, _)| (v - xs[0].x).abs())
            .fold(f64::INFINITY, f64::min);
        eprintln!(
            "Q0 = {q}: the curve crosses at W = {} ({near:e} from the sweep's)",
            xs[0].x
        );
        assert!(near <= 1e-8, "Q0 = {q}: W = {}: {near:e}", xs[0].x);
    }
    // The motion's period-doubling curve, from the top edge's sweep (the
    // run's own start), ends at a codimension-two point with a stick's
    // vanishing; its points have an eigenvalue −1, re-solved.
    use stickslip::bifurcation::curve::CurveEndReason;
    use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
    let opts = CurvesOptions {
        x: ("W".into(), plane().x_range),
        y: ("Q0".into(), plane().y_range),
        seeds: vec![Line::Y(200.0)],
        at: Vec::new(),
    };
    let (_, curves) = traced::<Paper>(&base, &opts, &CurvesSettings::default()).expect("the run");
    let pd = curves
        .iter()
        .find(|c| {
            c.kind == TransitionKind::PeriodDoubling
                && c.structure.as_ref().is_some_and(|s| {
                    s.periods() == 2 && s.notation(Paper::INFO).starts_with(DOUBLE)
                })
        })
        .expect("the period-doubling curve of the period-2 motion");
    eprintln!(
        "period doubling: {} points, ends {:?}",
        pd.points.len(),
        pd.ends
            .iter()
            .map(|e| (e.reason.clone(), e.at.x, e.at.y))
            .collect::<Vec<_>>()
    );
    assert!(
        pd.ends.iter().any(|e| matches!(
            e.reason,
            CurveEndReason::Codim2 {
                kind: TransitionKind::StickVanishing,
                ..
            }
        )),
        "{:?}",
        pd.ends
    );
    let mut checked = 0;
    for q in pd.points.iter().filter(|q| q.y >= 205.0) {
        let p = at(q.x, q.y);
        let mut pts = q.points.clone();
        let t = PeriodicSolver::<Paper>::new(structure.clone()).solve(
            &p,
            &mut pts,
            NewtonOptions::default(),
        );
        assert!(t.converged(), "re-solving at ({}, {}): {t:?}", q.x, q.y);
        let dp = stickslip::orbit::periodic::monodromy::<Paper>(
            &p,
            structure.steps(),
            std::f64::consts::TAU * 2.0,
            &pts,
        )
        .expect("DP");
        let (tr, det) = (dp.trace(), dp.determinant());
        let root = (tr * tr - 4.0 * det).max(0.0).sqrt();
        let lambda = [0.5 * (tr - root), 0.5 * (tr + root)]
            .into_iter()
            .min_by(|a, b| (a + 1.0).abs().total_cmp(&(b + 1.0).abs()))
            .expect("two roots");
        eprintln!("({}, {}): λ = {lambda}", q.x, q.y);
        assert!(
            (lambda + 1.0).abs() <= 1e-7,
            "λ = {lambda} at ({}, {})",
            q.x,
            q.y
        );
        checked += 1;
    }
    assert!(checked >= 3, "{checked} points checked");
}

//! Two-parameter curves of transitions (`bifurcation::curve`), each claim
//! checked by an independent computation:
//!
//! 1. at every point of curves of several kinds (paper model, plane
//!    (W, Q0)), the motion re-solved by `PeriodicSolver` at that (W, Q0)
//!    from the curve's switching points, and the condition evaluated by the
//!    public API (`admissible::conditions`' margin of that condition, or
//!    `det(I ∓ DP)` from `PeriodicSolver::poincare_jacobian`): zero to
//!    1e-10 relative to the quantity's scale (`condition_scale`);
//! 2. branches followed along W at other Q0 end at transitions (and have
//!    bifurcations) that the curves' exact crossings of `Q0 = q` match to 1e-8;
//! 3. the extended system's Jacobian against central differences of its residuals;
//! 4. a corrector step and a tangent allocate nothing;
//! 5. a fold curve of the Coulomb oscillator: `det(I − DP)` independently;
//! 6. the no-motion regime's grazing curve against bisection on the closed form.

mod common;

use common::counting::{allocations, Counting};
use stickslip::bifurcation::bordered::Correction;
use stickslip::bifurcation::curve::{
    condition_at_transition, condition_scale, crossings, system, trace, unknowns, Condition, Curve,
    CurveEndReason, CurveOptions, CurvePoint, Line, Plane,
};
use stickslip::bifurcation::{
    follow, Branch, ContinuationOptions, EndReason, Start, TransitionKind,
};
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::orbit::admissible::conditions;
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::motion::Motion;
use stickslip::orbit::periodic::{NewtonOptions, PeriodicSolver};
use stickslip::orbit::structure::Structure;
use stickslip::{Model, ParamSet};

#[global_allocator]
static GLOBAL: Counting = Counting;

fn with<P: ParamSet>(base: &P, plane: &Plane, x: f64, y: f64) -> P {
    let mut p = *base;
    p.set(plane.x, x);
    p.set(plane.y, y);
    p
}

/// The motion a simulation from rest settles on.
fn settle<M: Model>(p: M::Params) -> Option<Motion> {
    let sim = Simulator::<M>::new(p, SimOptions::default()).ok()?;
    let start = sim.start(0.0, 0.0, 0.0).ok()?;
    let opts = AttractorOptions {
        max_periods: 2000,
        ..AttractorOptions::default()
    };
    match attractor::find(&sim, start, opts) {
        Ok(Attractor::Periodic(m)) => Some(m),
        _ => None,
    }
}

fn paper_plane() -> Plane {
    use stickslip::models::paper::Params;
    Plane {
        x: Params::index_of("W").unwrap(),
        y: Params::index_of("Q0").unwrap(),
        x_range: [0.2, 8.0],
        y_range: [0.0, 180.0],
    }
}

/// The branch through the motion from rest at `(w, q)`, followed along W.
fn branch_at<M: Model>(base: &M::Params, plane: &Plane, w: f64, q: f64) -> Option<Branch> {
    let p = with(base, plane, w, q);
    let m = settle::<M>(p)?;
    let mut b = *base;
    b.set(plane.y, q);
    let o = ContinuationOptions {
        bounds: (plane.x_range[0], plane.x_range[1]),
        ..ContinuationOptions::default()
    };
    let start = Start {
        structure: m.structure.clone(),
        value: w,
        points: m.points.clone(),
        direction: None,
    };
    follow::<M>(&b, plane.x, &start, &o).ok()
}

/// The curves of every transition that ends `branch` (at `Q0 = q`) and of
/// its eigenvalue bifurcations.
fn curves_of<M: Model>(base: &M::Params, plane: &Plane, branch: &Branch, q: f64) -> Vec<Curve> {
    let mut starts = Vec::new();
    for e in &branch.ends {
        if let EndReason::Transition { kind, .. } = e.reason {
            starts.push((kind, e.at.clone()));
        }
    }
    for b in &branch.bifurcations {
        starts.push((b.kind, b.at.clone()));
    }
    let opts = CurveOptions::default();
    let mut out = Vec::new();
    for (kind, at) in starts {
        let p = with(base, plane, at.value, q);
        let Some(cond) = condition_at_transition::<M>(&p, &branch.structure, &at.points, kind)
        else {
            eprintln!(
                "no condition for {kind:?} at W = {} (a vanishing segment)",
                at.value
            );
            continue;
        };
        let start = CurvePoint {
            x: at.value,
            y: q,
            points: at.points.clone(),
        };
        match trace::<M>(base, plane, Some(&branch.structure), &start, cond, &opts) {
            Ok(c) => out.push(c),
            Err(e) => eprintln!("{kind:?} {cond:?} at W = {}: {e}", at.value),
        }
    }
    out
}

/// The largest `|g| / scale` over the curve's points, each motion re-solved
/// at its (x, y) and each condition evaluated by the public API.
fn worst_on_curve<M: Model>(base: &M::Params, plane: &Plane, c: &Curve) -> f64 {
    let mut worst = 0.0f64;
    let structure: Option<&Structure> = c.structure.as_ref();
    for q in c.points.iter().chain(c.ends.iter().map(|e| &e.at)) {
        let p = with(base, plane, q.x, q.y);
        let mut pts = q.points.clone();
        let s = structure.expect("a structure");
        let mut solver = PeriodicSolver::<M>::new(s.clone());
        // Newton at fixed (x, y); at a tangential arrival its elimination is
        // singular, and the point's own residual is checked instead.
        let t = solver.solve(&p, &mut pts, NewtonOptions::default());
        let l = PeriodicSolver::<M>::length_scale(&p, &q.points);
        let w = M::oscillator(&p).frequency.abs();
        if !t.converged() {
            pts = q.points.clone();
            let r = solver.residual(&p, &pts);
            assert!(
                r <= 1e-10 * l * w.max(1.0),
                "residual {r:e} at {q:?}: {t:?}"
            );
        }
        let scale = condition_scale::<M>(&p, c.condition, structure, &pts);
        let g = match c.condition {
            Condition::Margin {
                kind,
                segment,
                boundary,
            } => {
                let sim = Simulator::<M>::new(p, SimOptions::default()).unwrap();
                conditions(&sim, s, &pts)
                    .iter()
                    .filter(|v| v.kind == kind && v.segment == segment && v.boundary == boundary)
                    .map(|v| v.margin)
                    .fold(f64::INFINITY, f64::min)
            }
            Condition::Eigen(kind) => {
                let dp = solver.poincare_jacobian(&p, &pts).expect("DP");
                let e = nalgebra::Matrix2::identity();
                match kind {
                    TransitionKind::PeriodDoubling => (e + dp).determinant(),
                    TransitionKind::NeimarkSacker => dp.determinant() - 1.0,
                    _ => (e - dp).determinant(),
                }
            }
            Condition::RestGrazing { .. } | Condition::NormalField { .. } => {
                unreachable!("no curve of the paper model is traced on {:?}", c.condition)
            }
        };
        worst = worst.max(g.abs() / scale);
    }
    worst
}

fn describe(c: &Curve) -> String {
    format!(
        "{:?} {:?}: {} points, ends {:?}",
        c.kind,
        c.condition,
        c.points.len(),
        c.ends
            .iter()
            .map(|e| (e.reason.clone(), e.at.x, e.at.y))
            .collect::<Vec<_>>()
    )
}

/// The curves of every transition of the branches through the motions
/// from rest along W at Q0 = 70 (paper model).
fn paper_curves() -> Vec<Curve> {
    use stickslip::models::paper::{Paper, Params};
    let base = Params::default();
    let plane = paper_plane();
    let mut curves: Vec<Curve> = Vec::new();
    let mut seen: Vec<Structure> = Vec::new();
    for w in [
        0.5, 1.0, 1.5, 2.0, 2.5, 3.0, 3.5, 3.9, 4.5, 5.0, 5.5, 6.5, 7.5,
    ] {
        let Some(b) = branch_at::<Paper>(&base, &plane, w, 70.0) else {
            continue;
        };
        if seen.contains(&b.structure) {
            continue;
        }
        seen.push(b.structure.clone());
        let t0 = std::time::Instant::now();
        let cs = curves_of::<Paper>(&base, &plane, &b, 70.0);
        eprintln!(
            "{}: {} curves in {:?}",
            b.structure.notation(Paper::INFO),
            cs.len(),
            t0.elapsed()
        );
        curves.extend(cs);
    }
    for c in &curves {
        eprintln!("{}", describe(c));
    }
    curves
}

#[test]
fn paper_curves_satisfy_their_conditions_and_match_branches_at_other_q0() {
    use stickslip::models::paper::{Paper, Params};
    let base = Params::default();
    let plane = paper_plane();
    let curves = paper_curves();
    let kinds: Vec<TransitionKind> = curves.iter().map(|c| c.kind).collect();
    assert!(curves.len() >= 3, "{kinds:?}");
    assert!(kinds.iter().any(|k| !k.is_eigenvalue()));
    let mut specials = 0;
    for c in &curves {
        let worst = worst_on_curve::<Paper>(&base, &plane, c);
        assert!(worst <= 1e-10, "{}: |g| / scale = {worst:e}", describe(c));
        // A fold or period-doubling curve met on the way: its test function
        // vanishes there too (DP by the public solver).
        for sp in &c.special {
            let p = with(&base, &plane, sp.at.x, sp.at.y);
            let s = c.structure.clone().unwrap();
            let dp = PeriodicSolver::<Paper>::new(s)
                .poincare_jacobian(&p, &sp.at.points)
                .expect("DP");
            let e = nalgebra::Matrix2::identity();
            let psi = match sp.kind {
                TransitionKind::PeriodDoubling => (e + dp).determinant(),
                _ => (e - dp).determinant(),
            };
            let scale = 1.0 + dp.trace().abs() + dp.determinant().abs();
            assert!(
                psi.abs() <= 1e-8 * scale,
                "{:?} at {:?}: {psi:e}",
                sp.kind,
                sp.at
            );
            assert!(sp.index + 1 < c.points.len());
            specials += 1;
        }
    }
    eprintln!("{specials} special points");
    // Other Q0: the branches' ends and bifurcations lie on the curves.
    let mut total_matched = 0;
    for q in [40.0, 100.0, 150.0] {
        let mut found = Vec::new();
        for (i, c) in curves.iter().enumerate() {
            for x in crossings::<Paper>(&base, &plane, c, Line::Y(q), &CurveOptions::default()) {
                assert_eq!(x.y, q);
                found.push((i, x));
            }
        }
        let mut matched = 0;
        for (i, x) in &found {
            // The branch of this motion at Q0 = q, from the crossing.
            let c = &curves[*i];
            let kind = c.kind;
            let structure = c.structure.clone().unwrap();
            let mut b = base;
            b.Q0 = q;
            let o = ContinuationOptions {
                bounds: (plane.x_range[0], plane.x_range[1]),
                ..ContinuationOptions::default()
            };
            // Start a little inside the branch (the condition's positive
            // side, whichever it is) and let the continuation locate the end.
            let branch = [1e-3, -1e-3].iter().find_map(|dw| {
                let start = Start {
                    structure: structure.clone(),
                    value: x.x + dw,
                    points: x.points.clone(),
                    direction: None,
                };
                follow::<Paper>(&b, plane.x, &start, &o).ok()
            });
            let Some(branch) = branch else {
                continue;
            };
            let mut values: Vec<f64> = branch
                .ends
                .iter()
                .filter(|e| matches!(e.reason, EndReason::Transition { .. }))
                .map(|e| e.at.value)
                .collect();
            values.extend(branch.bifurcations.iter().map(|f| f.at.value));
            let near = values
                .iter()
                .map(|v| (v - x.x).abs())
                .fold(f64::INFINITY, f64::min);
            eprintln!("Q0 = {q}: {kind:?} at W = {} (branch: {near:e})", x.x);
            if near.is_finite() {
                assert!(
                    near <= 1e-8,
                    "{kind:?} at Q0 = {q}: W = {} is {near:e} from the branch's",
                    x.x
                );
                matched += 1;
            }
        }
        eprintln!("Q0 = {q}: {} crossings, {matched} matched", found.len());
        total_matched += matched;
    }
    // A crossing with no branch is skipped above, so the check must not be
    // empty: every one of the 17 crossings has a branch that locates it.
    assert!(
        total_matched >= 17,
        "only {total_matched} crossings checked against branches"
    );
}

/// The Coulomb oscillator of issue 11's fold (V = 0, static 1.5× kinetic).
fn coulomb_base() -> stickslip::models::coulomb::Params {
    stickslip::models::coulomb::Params {
        V: 0.0,
        d: 0.02,
        mus: 0.45,
        muk: 0.3,
        Q0: 1.0,
        ..Default::default()
    }
}

fn coulomb_plane() -> Plane {
    use stickslip::models::coulomb::Params;
    Plane {
        x: Params::index_of("W").unwrap(),
        y: Params::index_of("Q0").unwrap(),
        x_range: [0.05, 0.5],
        y_range: [0.8, 1.2],
    }
}

/// The fold of the Coulomb oscillator's branch from rest at W = 0.2, Q0 = 1.
fn coulomb_fold() -> (Structure, CurvePoint) {
    let (s, p, _) = coulomb_fold_branch();
    (s, p)
}

/// The fold and its branch.
fn coulomb_fold_branch() -> (Structure, CurvePoint, Branch) {
    use stickslip::models::coulomb::Coulomb;
    let (base, plane) = (coulomb_base(), coulomb_plane());
    let b = branch_at::<Coulomb>(&base, &plane, 0.2, 1.0).expect("the branch");
    let f = b
        .bifurcations
        .iter()
        .find(|f| f.kind == TransitionKind::Fold)
        .expect("a fold");
    (
        b.structure.clone(),
        CurvePoint {
            x: f.at.value,
            y: 1.0,
            points: f.at.points.clone(),
        },
        b.clone(),
    )
}

#[test]
fn a_fold_curve_of_the_coulomb_oscillator() {
    use stickslip::models::coulomb::Coulomb;
    let (base, plane) = (coulomb_base(), coulomb_plane());
    let (structure, start, one) = coulomb_fold_branch();
    assert!((start.x - 0.219892416).abs() < 1e-8, "{}", start.x);
    let t0 = std::time::Instant::now();
    let c = trace::<Coulomb>(
        &base,
        &plane,
        Some(&structure),
        &start,
        Condition::Eigen(TransitionKind::Fold),
        &CurveOptions::default(),
    )
    .expect("the fold curve");
    eprintln!("{} in {:?}", describe(&c), t0.elapsed());
    assert!(c.points.len() >= 5);
    let worst = worst_on_curve::<Coulomb>(&base, &plane, &c);
    assert!(worst <= 1e-10, "|det(I − DP)| / scale = {worst:e}");
    // The curve spans Q0 (not a point), and crosses Q0 = 1 at the branch's fold.
    let (lo, hi) = c
        .points
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), q| {
            (a.min(q.y), b.max(q.y))
        });
    assert!(hi - lo > 0.1, "Q0 from {lo} to {hi}");
    let at = crossings::<Coulomb>(&base, &plane, &c, Line::Y(1.0), &CurveOptions::default());
    assert!(
        at.iter().any(|q| (q.x - start.x).abs() < 1e-9),
        "{:?} vs {}",
        at.iter().map(|q| q.x).collect::<Vec<_>>(),
        start.x
    );
    // At another Q0, the branch's own fold lies on the curve.
    for q in [0.9, 1.1] {
        let at = crossings::<Coulomb>(&base, &plane, &c, Line::Y(q), &CurveOptions::default());
        let guess = at.first().expect("a crossing");
        // The branch at Q0 = q, followed along W from the Q0 = 1 branch's
        // points a little away from its fold (Newton at that W).
        let mut b = base;
        b.Q0 = q;
        let o = ContinuationOptions {
            bounds: (plane.x_range[0], plane.x_range[1]),
            ..ContinuationOptions::default()
        };
        let branch = one
            .points
            .iter()
            .filter(|p| (p.value - start.x).abs() > 0.01 && (p.value - start.x).abs() < 0.05)
            .find_map(|p| {
                let s = Start {
                    structure: structure.clone(),
                    value: p.value,
                    points: p.points.clone(),
                    direction: None,
                };
                follow::<Coulomb>(&b, plane.x, &s, &o).ok().filter(|br| {
                    br.bifurcations
                        .iter()
                        .any(|f| f.kind == TransitionKind::Fold)
                })
            })
            .expect("the branch at Q0 = q, with a fold");
        let near = branch
            .bifurcations
            .iter()
            .filter(|f| f.kind == TransitionKind::Fold)
            .map(|f| (f.at.value - guess.x).abs())
            .fold(f64::INFINITY, f64::min);
        assert!(near <= 1e-8, "Q0 = {q}: fold {near:e} from the curve");
    }
}

#[test]
fn the_extended_jacobian_matches_central_differences() {
    use stickslip::models::coulomb::Coulomb;
    let (base, plane) = (coulomb_base(), coulomb_plane());
    let (structure, start) = coulomb_fold();
    let cond = Condition::Eigen(TransitionKind::Fold);
    let mut sys = system::<Coulomb>(&base, &plane, Some(&structure), &start, cond).unwrap();
    // A point off the curve, so that nothing vanishes by accident.
    let mut x = unknowns(&start);
    for (i, v) in x.iter_mut().enumerate() {
        *v += 1e-3 * ((i % 3) as f64 - 1.0);
    }
    let n = x.len();
    let jac = sys.jacobian(&x).expect("a Jacobian").to_vec();
    let rows = n - 1;
    assert_eq!(jac.len(), rows * n);
    let (mut rp, mut rm) = (vec![0.0; rows], vec![0.0; rows]);
    for i in 0..n {
        let h = 1e-5 * x[i].abs().max(0.1);
        let mut y = x.clone();
        y[i] = x[i] + h;
        sys.residuals(&y, &mut rp);
        y[i] = x[i] - h;
        sys.residuals(&y, &mut rm);
        for r in 0..rows {
            let fd = (rp[r] - rm[r]) / (2.0 * h);
            let scale = jac[r * n..(r + 1) * n]
                .iter()
                .fold(0.0f64, |a, v| a.max(v.abs()));
            let err = (fd - jac[r * n + i]).abs();
            assert!(
                err <= 1e-6 * scale,
                "row {r} column {i}: {} vs central difference {fd} (row scale {scale})",
                jac[r * n + i]
            );
        }
    }
}

#[test]
fn corrector_step_and_tangent_allocate_nothing() {
    use stickslip::models::coulomb::Coulomb;
    use stickslip::models::paper::{Paper, Params};
    let (base, plane) = (coulomb_base(), coulomb_plane());
    let (structure, start) = coulomb_fold();
    let cond = Condition::Eigen(TransitionKind::Fold);
    let sys = system::<Coulomb>(&base, &plane, Some(&structure), &start, cond).unwrap();
    check_allocations(sys, &start, "fold");
    // A margin: its condition walks the motion's segments (a grazing of
    // the paper model at Q0 = 70).
    let (pb, pp) = (Params::default(), paper_plane());
    let (structure, start, cond) = [3.0, 3.5, 4.5, 5.0]
        .iter()
        .filter_map(|&w| branch_at::<Paper>(&pb, &pp, w, 70.0))
        .find_map(|b| {
            b.ends.iter().find_map(|e| match e.reason {
                EndReason::Transition { kind, .. } => {
                    let p = with(&pb, &pp, e.at.value, 70.0);
                    let c = condition_at_transition::<Paper>(&p, &b.structure, &e.at.points, kind)?;
                    let start = CurvePoint {
                        x: e.at.value,
                        y: 70.0,
                        points: e.at.points.clone(),
                    };
                    Some((b.structure.clone(), start, c))
                }
                _ => None,
            })
        })
        .expect("a transition with a condition");
    let sys = system::<Paper>(&pb, &pp, Some(&structure), &start, cond).unwrap();
    check_allocations(sys, &start, "margin");
}

/// A tangent and a corrector step from the curve point `start` (a
/// transition, on the curve to about 1e-12) allocate nothing.
fn check_allocations<M: Model>(
    mut sys: stickslip::bifurcation::curve::Extended<M>,
    start: &CurvePoint,
    what: &str,
) {
    let x0 = unknowns(start);
    let n = x0.len();
    let mut border = vec![0.0; n];
    sys.axis(1, &mut border);
    let mut t = vec![0.0; n];
    let (count, r) = allocations(|| sys.tangent(&x0, &border, &mut t));
    assert!(r.is_ok(), "{what}: {r:?}");
    assert_eq!(count, 0, "{what}: the tangent allocated {count} times");
    let mut x: Vec<f64> = x0.iter().zip(&t).map(|(a, d)| a + 1e-4 * d).collect();
    let anchor = x.clone();
    let (count, c) = allocations(|| sys.correct(&mut x, &t, &anchor, 1e-12, 12));
    assert!(matches!(c, Correction::Converged { .. }), "{what}: {c:?}");
    assert_eq!(count, 0, "{what}: the corrector allocated {count} times");
    assert!(sys.mapping_residual(&x) < 1e-10 * sys.length.max(1.0));
    assert!(sys.distance(&x, &x0) > 1e-5, "{what}: the step moved");
}

/// The no-motion regime's largest velocity in domain `j` (closed form,
/// written out here from the domain's coefficients).
fn rest_max_v<M: Model>(p: &M::Params, j: usize) -> f64 {
    let co = M::coefficients(p, j);
    let osc = M::oscillator(p);
    let w = osc.frequency;
    w * osc.amplitude.abs() / ((co.c - w * w).powi(2) + (co.two_d * w).powi(2)).sqrt()
}

#[test]
fn the_rest_grazing_curve_is_the_closed_form() {
    use stickslip::models::paper::{Paper, Params};
    let base = Params::default();
    let plane = paper_plane();
    // The domain of the rest (unbounded below), grazing its upper boundary.
    let j = Paper::INFO
        .domains
        .iter()
        .position(|d| d.lower.is_none())
        .unwrap();
    let k = Paper::INFO.domains[j].upper.unwrap();
    // Bisection in W on the left of the resonance.
    let graze_at = |q: f64| {
        let g = |w: f64| {
            let p = with(&base, &plane, w, q);
            Paper::boundary_velocity(&p, k) - rest_max_v::<Paper>(&p, j)
        };
        let (mut lo, mut hi) = (0.2, 5.0);
        assert!(g(lo) > 0.0 && g(hi) < 0.0, "Q0 = {q}");
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(mid) > 0.0 {
                lo = mid
            } else {
                hi = mid
            }
        }
        lo
    };
    let w70 = graze_at(70.0);
    let start = CurvePoint {
        x: w70 + 1e-6,
        y: 70.0,
        points: Vec::new(),
    };
    let cond = Condition::RestGrazing { boundary: k };
    let c = trace::<Paper>(&base, &plane, None, &start, cond, &CurveOptions::default())
        .expect("the curve");
    eprintln!("{}", describe(&c));
    assert_eq!(c.kind, TransitionKind::Grazing);
    assert_eq!(c.ends.len(), 2);
    for q in [20.0, 40.0, 100.0, 150.0] {
        let at = crossings::<Paper>(&base, &plane, &c, Line::Y(q), &CurveOptions::default());
        let w = graze_at(q);
        assert!(
            at.iter().any(|x| (x.x - w).abs() <= 1e-9 * w),
            "Q0 = {q}: {:?} vs {w}",
            at.iter().map(|x| x.x).collect::<Vec<_>>()
        );
    }
    for q in &c.points {
        let p = with(&base, &plane, q.x, q.y);
        let g = Paper::boundary_velocity(&p, k) - rest_max_v::<Paper>(&p, j);
        assert!(
            g.abs() <= 1e-10 * Paper::boundary_velocity(&p, k).abs(),
            "{g:e} at {q:?}"
        );
    }
}

#[test]
fn a_period_doubling_curve_of_the_paper_model() {
    use stickslip::models::paper::{Paper, Params};
    // Issue 11's period doubling of P_{3_33 4_33} (Q0 = 100, mu3 = 3, W ≈ 10.8).
    let base = Params {
        mu3: 3.0,
        ..Params::default()
    };
    let plane = Plane {
        x_range: [10.0, 12.0],
        y_range: [80.0, 120.0],
        ..paper_plane()
    };
    let b = branch_at::<Paper>(&base, &plane, 10.75, 100.0).expect("the branch");
    let pd = b
        .bifurcations
        .iter()
        .find(|f| f.kind == TransitionKind::PeriodDoubling)
        .expect("a period doubling");
    let start = CurvePoint {
        x: pd.at.value,
        y: 100.0,
        points: pd.at.points.clone(),
    };
    let p = with(&base, &plane, start.x, start.y);
    let cond = condition_at_transition::<Paper>(&p, &b.structure, &start.points, pd.kind)
        .expect("a condition");
    assert_eq!(cond, Condition::Eigen(TransitionKind::PeriodDoubling));
    let t0 = std::time::Instant::now();
    let c = trace::<Paper>(
        &base,
        &plane,
        Some(&b.structure),
        &start,
        cond,
        &CurveOptions::default(),
    )
    .expect("the curve");
    eprintln!("{} in {:?}", describe(&c), t0.elapsed());
    assert!(c.points.len() >= 5);
    let worst = worst_on_curve::<Paper>(&base, &plane, &c);
    assert!(worst <= 1e-10, "|det(I + DP)| / scale = {worst:e}");
    for q in [90.0, 110.0] {
        let at = crossings::<Paper>(&base, &plane, &c, Line::Y(q), &CurveOptions::default());
        let mut bq = base;
        bq.Q0 = q;
        let o = ContinuationOptions {
            bounds: (plane.x_range[0], plane.x_range[1]),
            ..ContinuationOptions::default()
        };
        let Some(x) = at.first() else {
            continue;
        };
        let branch = [1e-2, -1e-2]
            .iter()
            .find_map(|dw| {
                let s = Start {
                    structure: b.structure.clone(),
                    value: x.x + dw,
                    points: x.points.clone(),
                    direction: None,
                };
                follow::<Paper>(&bq, plane.x, &s, &o).ok()
            })
            .expect("the branch at Q0 = q");
        let near = branch
            .bifurcations
            .iter()
            .filter(|f| f.kind == TransitionKind::PeriodDoubling)
            .map(|f| (f.at.value - x.x).abs())
            .fold(f64::INFINITY, f64::min);
        eprintln!("Q0 = {q}: PD at W = {} ({near:e} from the branch's)", x.x);
        assert!(near <= 1e-8, "Q0 = {q}: {near:e}");
    }
}

#[test]
fn sweeps_at_other_q0_locate_the_curves_crossings() {
    use stickslip::models::paper::{Paper, Params};
    use stickslip::study::sweep::{sweep, SweepOptions};
    let base = Params::default();
    let plane = paper_plane();
    let curves = paper_curves();
    let mut matched = 0;
    for q in [40.0, 100.0] {
        let mut b = base;
        b.Q0 = q;
        let s = sweep::<Paper>(b, "W", 0.2, 8.0, 40, SweepOptions::default()).expect("sweep");
        let mut located: Vec<(TransitionKind, f64)> =
            s.transitions.iter().map(|t| (t.kind, t.value)).collect();
        located.extend(s.bifurcations.iter().map(|f| (f.kind, f.value)));
        for c in &curves {
            for x in crossings::<Paper>(&base, &plane, c, Line::Y(q), &CurveOptions::default()) {
                let near = located
                    .iter()
                    .filter(|(k, _)| *k == c.kind)
                    .map(|(_, v)| (v - x.x).abs())
                    .fold(f64::INFINITY, f64::min);
                eprintln!(
                    "Q0 = {q}: {:?} at W = {} ({near:e} from the sweep's)",
                    c.kind, x.x
                );
                // The same event if within 1e-6: then to 1e-8.
                if near <= 1e-6 {
                    assert!(
                        near <= 1e-8,
                        "Q0 = {q}: {:?} at W = {}: {near:e}",
                        c.kind,
                        x.x
                    );
                    matched += 1;
                }
            }
        }
    }
    assert!(
        matched >= 3,
        "only {matched} crossings located by the sweeps"
    );
}

/// A passable-onset curve along which `DP` is singular (the arrival on Σ1
/// is tangential all along it, so its eigenvalues are noise): it used to
/// crawl in steps of 1e-8 until `max_points` (the curves run's seed line
/// Q0 = 135 starts it at W = 2.57386); it must cross the box.
#[test]
fn a_passable_onset_curve_with_singular_dp_crosses_the_box() {
    use stickslip::models::paper::{Paper, Params};
    use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
    let base = Params::default();
    let opts = CurvesOptions {
        x: ("W".into(), [2.4, 2.8]),
        y: ("Q0".into(), [130.0, 140.0]),
        seeds: vec![Line::Y(135.0)],
        at: Vec::new(),
    };
    // The seed line alone: the edges' sweeps trace other passable-onset
    // curves of the box first (one ends at a codimension-two point).
    let settings = CurvesSettings {
        spread: 0,
        edges: false,
        ..CurvesSettings::default()
    };
    let plane = opts.plane::<Paper>(&base).expect("a valid box");
    let (_, curves) = traced::<Paper>(&base, &opts, &settings).expect("the run runs");
    let c = curves
        .iter()
        .find(|c| c.kind == TransitionKind::PassableOnset)
        .expect("the passable-onset curve");
    eprintln!("{}", describe(c));
    assert!(
        c.ends.iter().all(|e| e.reason == CurveEndReason::BoxEdge),
        "{}",
        describe(c)
    );
    assert!(c.points.len() < 500, "{}", describe(c));
    let worst = worst_on_curve::<Paper>(&base, &plane, c);
    assert!(worst <= 1e-10, "worst condition {worst:e}");
}

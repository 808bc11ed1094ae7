//! Self-excited (unforced) oscillators, against independent computations:
//! steady sliding's eigenvalues against the characteristic polynomial and
//! nalgebra's eigenvalues, the Hopf point of a smooth Stribeck law against
//! the textbook condition `2 ζ ω_n = −(1/m) df/dv_rel` in closed form, the
//! nonsmooth loss of stability of its piecewise scenes where the
//! equilibrium sits on a breakpoint, and the Coulomb belt oscillator's
//! stick-slip cycle against its closed form.

mod common;

use std::ffi::OsStr;
use std::path::PathBuf;
use std::process::{Command, Output};

use nalgebra::Matrix2;
use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::coulomb::{self, Coulomb};
use stickslip::models::stribeck::{self, Stribeck};
use stickslip::models::ModelRef;
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::orbit::equilibrium::{
    eigenvalues, steady_sliding, steady_sliding_smooth, EquilibriumError, Loss, Seat, Verdict,
};
use stickslip::study::equilibria::{scan, scan_smooth, Scan};
use stickslip::study::trade::MeasureThresholds;
use stickslip::{Model, ModelVisitor, ParamSet, SmoothModel};

fn belt() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/belt.ssm")
}

/// `stickslip ARGS…`, run to its end.
fn stickslip<S: AsRef<OsStr>>(args: impl IntoIterator<Item = S>) -> Output {
    Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(args)
        .output()
        .expect("runs")
}

/// `stickslip COMMAND --model-file examples/belt.ssm ARGS…`.
fn on_belt(command: &str, args: &[&str]) -> Output {
    let file = belt();
    let head = [
        OsStr::new(command),
        OsStr::new("--model-file"),
        file.as_os_str(),
    ];
    stickslip(head.into_iter().chain(args.iter().map(OsStr::new)))
}

/// The eigenvalues solve `λ² + 2d λ + c = 0` and agree with nalgebra's
/// eigenvalues of the companion matrix, for foci, nodes and saddles.
#[test]
fn eigenvalues_are_the_companion_matrix_roots() {
    for &(two_d, c) in &[
        (0.1, 1.0),
        (-0.3, 4.0),
        (3.0, 1.0),
        (-3.0, 1.0),
        (0.5, -2.0),
        (1e-9, 1e6),
        (1e4, 1e-4),
    ] {
        let e = eigenvalues(two_d, c);
        let m = Matrix2::new(0.0, 1.0, -c, -two_d);
        let reference = m.complex_eigenvalues();
        let scale = two_d.abs().max(c.abs().sqrt());
        for ev in e {
            let (re, im) = (ev[0], ev[1]);
            // λ² + 2d λ + c, real and imaginary parts.
            let p_re = re * re - im * im + two_d * re + c;
            let p_im = 2.0 * re * im + two_d * im;
            assert!(
                p_re.abs() <= 1e-12 * scale * scale && p_im.abs() <= 1e-12 * scale * scale,
                "{two_d} {c}: {ev:?}"
            );
            let nearest = reference
                .iter()
                .map(|r| (r.re - re).hypot(r.im - im))
                .fold(f64::INFINITY, f64::min);
            assert!(
                nearest <= 1e-9 * scale,
                "{two_d} {c}: {ev:?} vs {reference:?}"
            );
        }
        // Product and sum of the roots.
        let (a, b) = (e[0], e[1]);
        let prod = a[0] * b[0] - a[1] * b[1];
        assert!(
            (prod - c).abs() <= 1e-12 * c.abs().max(scale * scale),
            "{two_d} {c}"
        );
        assert!((a[0] + b[0] + two_d).abs() <= 1e-12 * scale, "{two_d} {c}");
    }
}

/// Coulomb friction on a moving belt, unforced: the mass rests where the
/// spring holds the kinetic friction, `x* = μk g / c`, with the viscous
/// damping alone (the law is flat).
#[test]
fn coulomb_steady_sliding_is_where_the_spring_holds_the_friction() {
    let p = coulomb::Params {
        Q0: 0.0,
        V: 0.5,
        d: 0.05,
        ..coulomb::Params::default()
    };
    let e = steady_sliding::<Coulomb>(&p).expect("steady sliding");
    assert!((e.x - p.muk * p.g / p.c).abs() <= 1e-15);
    assert_eq!(e.verdict, Verdict::Stable);
    let w = (p.c - p.d * p.d).sqrt();
    assert!((e.eigenvalues[0][0] + p.d).abs() <= 1e-15 && (e.eigenvalues[0][1] - w).abs() <= 1e-15);
    // Forced, or with the belt at rest, there is none, and the error says why.
    let forced = coulomb::Params { Q0: 0.5, ..p };
    assert!(matches!(
        steady_sliding::<Coulomb>(&forced),
        Err(EquilibriumError::Forced { .. })
    ));
    let at_rest = coulomb::Params { V: 0.0, ..p };
    let err = steady_sliding::<Coulomb>(&at_rest).unwrap_err();
    assert!(matches!(err, EquilibriumError::OnStick { .. }), "{err}");
    assert!(err.to_string().contains("Sigma1"), "{err}");
}

/// The Stribeck law: `f'(0) = −(μs − μk) g / vs · e^{−V/vs} + σ` at the rest
/// state (relative velocity `−V`), so steady sliding is stable iff
/// `2 d + f'(0) > 0`, and the Hopf point is `V* = vs ln((μs − μk) g /
/// (vs (2 d + σ)))`. The located point agrees to 1e-9 (relative), for
/// several dampings.
#[test]
fn the_hopf_point_of_a_smooth_law_is_the_textbook_condition() {
    for &d in &[0.02, 0.1, 0.4, 1.0] {
        let base = stribeck::Params {
            Q0: 0.0,
            d,
            ..stribeck::Params::default()
        };
        let closed =
            base.vs * ((base.mus - base.muk) * base.g / (base.vs * (2.0 * d + base.sigma))).ln();
        let s = scan_smooth::<Stribeck>(base, "V", 0.05, 6.0, 13).expect("scan");
        let hopf: Vec<_> = s
            .changes
            .iter()
            .filter(|c| c.change.loss == Loss::Hopf)
            .collect();
        assert_eq!(hopf.len(), 1, "d = {d}: {:?}", s.changes);
        let at = hopf[0].change.at;
        assert!(
            (at - closed).abs() <= 1e-9 * closed,
            "d = {d}: {at} vs {closed}"
        );
        assert_eq!(hopf[0].change.before, Some(Verdict::Unstable));
        assert_eq!(hopf[0].change.after, Some(Verdict::Stable));
        // Below and above by 1e-6: unstable, stable; the eigenvalues'
        // real part is −(2 d + f'(0)) / 2 from the law's exact slope.
        for (v, stable) in [
            (closed * (1.0 - 1e-6), false),
            (closed * (1.0 + 1e-6), true),
        ] {
            let p = stribeck::Params { V: v, ..base };
            let e = steady_sliding_smooth::<Stribeck>(&p).expect("steady sliding");
            assert_eq!(e.verdict == Verdict::Stable, stable, "d = {d}, V = {v}");
            let slope = -(p.mus - p.muk) * p.g / p.vs * (-v / p.vs).exp() + p.sigma;
            assert!(
                (e.two_d - (2.0 * d + slope)).abs() <= 1e-13,
                "{} vs {}",
                e.two_d,
                2.0 * d + slope
            );
            let [f, _] = Stribeck::kinetic(&p, 0.0);
            assert!((e.x + f / p.c).abs() <= 1e-15);
        }
    }
}

struct Scanned(&'static str, f64, f64, usize);

impl ModelVisitor for Scanned {
    type Output = (Scan, Vec<f64>);
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        let s = scan::<M>(base, self.0, self.1, self.2, self.3).expect("scan");
        // At each located change, the crossed boundary's velocity.
        let at_boundary = s
            .changes
            .iter()
            .filter_map(|c| match c.change.loss {
                Loss::Band { boundary } => {
                    let p = base
                        .with_pairs(M::identity(&base), &[(self.0, c.change.at)])
                        .ok()?;
                    Some(M::boundary_velocity(&p, boundary))
                }
                _ => None,
            })
            .collect();
        Some((s, at_boundary))
    }
    fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
        Some((
            scan_smooth::<M>(base, self.0, self.1, self.2, self.3).expect("scan"),
            Vec::new(),
        ))
    }
}

/// A piecewise law loses stability where the equilibrium crosses a
/// breakpoint: located there to the rounding of the boundary's velocity,
/// stable on one side and not on the other. The scenes free the belt speed
/// and the damping, so a breakpoint sits where steady sliding changes
/// stability at the defaults: every scene has the law's own threshold.
#[test]
fn a_piecewise_law_loses_stability_on_a_breakpoint() {
    let exact = -0.5 * (0.1f64).ln(); // belt.ssm: 2ζ√c v0 m / ((μs − μd) FN) = 0.1
    let (law, _) = ModelRef::File {
        path: belt(),
        scene: None,
    }
    .visit(Scanned("vd", 0.2, 3.0, 15))
    .expect("loads")
    .expect("smooth");
    assert_eq!(law.changes.len(), 1);
    assert!(
        (law.changes[0].change.at - exact).abs() <= 1e-9 * exact,
        "{:?}",
        law.changes
    );
    let mut errors = Vec::new();
    for scene in ["pl8", "pl16", "pl32", "pl64"] {
        let (s, at_boundary) = ModelRef::File {
            path: belt(),
            scene: Some(scene.to_string()),
        }
        .visit(Scanned("vd", 0.2, 3.0, 15))
        .expect("loads")
        .expect("piecewise");
        let bands: Vec<_> = s
            .changes
            .iter()
            .filter(|c| matches!(c.change.loss, Loss::Band { .. }))
            .collect();
        assert_eq!(bands.len(), 1, "{scene}: {:?}", s.changes);
        let c = &bands[0].change;
        assert_ne!(c.before, c.after, "{scene}");
        // On the boundary: its velocity is 0 to a few ulps of the belt speed.
        assert!(
            at_boundary[0].abs() <= 8.0 * f64::EPSILON * c.at,
            "{scene}: {at_boundary:?}"
        );
        assert!(matches!(
            c.equilibrium.map(|e| e.seat),
            Some(Seat::Domain(_)) | Some(Seat::Boundary { .. })
        ));
        errors.push((c.at - exact).abs() / exact);
    }
    assert!(
        errors.iter().all(|&e| e <= 64.0 * f64::EPSILON),
        "{errors:?}"
    );
}

/// `trade` of an unforced model says there is no forced motion to trade and
/// what to run instead; `trade --threshold` gives each scene's threshold
/// against the law's, in text and JSON, and refuses a grid of no values.
#[test]
fn trade_measures_the_threshold_of_an_unforced_model() {
    let out = on_belt("trade", &[]);
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success());
    assert!(
        err.contains("unforced") && err.contains("--threshold"),
        "{err}"
    );
    let out = on_belt(
        "trade",
        &["--threshold", "vd=0.2:3:15", "--pieces", "8,16", "--json"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let exact = -0.5 * (0.1f64).ln();
    let law = json["law"][0].as_f64().expect("the law's threshold");
    assert!((law - exact).abs() <= 1e-12 * exact, "{json}");
    for row in json["rows"].as_array().expect("rows") {
        let at = row["at"][0].as_f64().expect("a threshold");
        assert!((at - exact).abs() <= 64.0 * f64::EPSILON * exact, "{row}");
    }
    assert_eq!(json["exact"], true);
    let text = String::from_utf8_lossy(
        &on_belt("trade", &["--threshold", "vd=0.2:3:15", "--pieces", "8"]).stdout,
    )
    .to_string();
    assert!(text.contains("the law's threshold to rounding"), "{text}");
    let out = on_belt("trade", &["--threshold", "vd=0.2:3:0"]);
    assert!(!out.status.success());
    assert!(String::from_utf8_lossy(&out.stderr).contains("count"));
}

/// Away from the defaults (a damping whose threshold is no breakpoint), a
/// scene's threshold lies on a breakpoint within a piece of the law's: the
/// error falls with the pieces, at first order, as `trade --threshold`
/// measures it. The law's threshold is the closed form `-v0/2 ln(2 zeta)`
/// (belt.ssm: `(mus - mud) FN / (m v0) = 1`, `c = 1`).
#[test]
fn a_piecewise_threshold_converges_at_first_order_away_from_the_defaults() {
    let model = ModelRef::File {
        path: belt(),
        scene: None,
    };
    for zeta in [0.03, 0.08] {
        let set = [("zeta".to_string(), zeta)];
        let measure = MeasureThresholds {
            model: &model,
            set: &set,
            range: ("vd".to_string(), 0.2, 3.0, 15),
            pieces: &[8, 16, 32, 64],
        };
        let t = model
            .visit(measure)
            .expect("loads")
            .expect("a smooth law")
            .expect("measured");
        let exact = -0.5 * (2.0 * zeta).ln();
        assert_eq!(t.law.len(), 1);
        assert!((t.law[0] - exact).abs() <= 1e-12 * exact, "{:?}", t.law);
        assert!(!t.exact);
        let errors: Vec<f64> = t.rows.iter().map(|r| r.error).collect();
        assert!(errors[3] < errors[0] / 5.0, "zeta {zeta}: {errors:?}");
        let order = t.order.expect("an order");
        assert!((0.8..1.5).contains(&order), "zeta {zeta}: order {order}");
    }
}

/// The Coulomb belt oscillator without damping or forcing: the stick ends at
/// `x_r = μs g / c`; the slip is a half-ellipse about `x_k = μk g / c` of
/// amplitude `A = √((x_r − x_k)² + V²/c)`, back to the belt speed at `2 x_k −
/// x_r`. Stick `2 (x_r − x_k) / V`, slip `(π + 2 atan(V / (ω (x_r − x_k)))) / ω`,
/// largest `|x|` = `x_k + A`; the cycle is superstable (multiplier 0). The
/// slip ends in a stick where the kinetic friction holds the spring there,
/// `|c (2 x_k − x_r)| < μk g`, i.e. `μs < 3 μk` (SPEC §3: otherwise the mass
/// passes the belt speed), which every case here meets.
#[test]
fn the_coulomb_stick_slip_cycle_is_its_closed_form() {
    for &(v, mus, muk, c) in &[
        (0.5, 0.4, 0.3, 1.0),
        (0.2, 0.6, 0.25, 4.0),
        (1.5, 0.5, 0.2, 0.5),
    ] {
        let p = coulomb::Params {
            Q0: 0.0,
            d: 0.0,
            V: v,
            mus,
            muk,
            c,
            ..coulomb::Params::default()
        };
        assert!(mus < 3.0 * muk, "a cycle of one stick and one slip");
        let w = c.sqrt();
        let (xr, xk) = (mus * p.g / c, muk * p.g / c);
        let y0 = xr - xk;
        let amp = y0.hypot(v / w);
        let stick = 2.0 * y0 / v;
        let slip = (std::f64::consts::PI + 2.0 * (v / (w * y0)).atan()) / w;
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("params");
        let start = sim.start(0.0, v, 0.0).expect("start");
        let Attractor::Autonomous(cycle) =
            attractor::find(&sim, start, AttractorOptions::default()).expect("settles")
        else {
            panic!("an autonomous cycle")
        };
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-10 * b.abs().max(1.0);
        assert!(close(cycle.stick, stick), "{} vs {stick}", cycle.stick);
        assert!(close(cycle.slip, slip), "{} vs {slip}", cycle.slip);
        assert!(close(cycle.period, stick + slip));
        assert!(
            close(cycle.x, 2.0 * xk - xr),
            "{} vs {}",
            cycle.x,
            2.0 * xk - xr
        );
        let a = cycle.amplitude.expect("closed form");
        assert!(
            close(a.x, (xk + amp).max((xk - amp).abs())),
            "{} vs {}",
            a.x,
            xk + amp
        );
        assert!(close(a.v, v.max(amp * w)), "{} vs {}", a.v, amp * w);
        assert_eq!(cycle.is_stable(), Some(true));
        assert!(cycle.multiplier.expect("multiplier").abs() <= 1e-12);
    }
}

/// A damped unforced simulation that comes to rest reports the steady
/// sliding it rests at; the command line names it.
#[test]
fn simulate_names_steady_sliding() {
    let out = on_belt(
        "simulate",
        &["--scene", "pl16", "--set", "vd=1.5", "--json"],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let e = &json["steady_sliding"];
    assert_eq!(e["verdict"], "stable", "{json}");
    // x* = −b_j / c_j of its domain, and the same as `equilibria` finds.
    let (s, _) = ModelRef::File {
        path: belt(),
        scene: Some("pl16".to_string()),
    }
    .visit(Scanned("vd", 1.5, 1.5, 1))
    .expect("loads")
    .expect("piecewise");
    let x = s.points[0].equilibrium.expect("steady sliding").x;
    assert_eq!(e["x"].as_f64(), Some(x));
    let text = on_belt("simulate", &["--scene", "pl16", "--set", "vd=1.5"]);
    let text = String::from_utf8_lossy(&text.stdout);
    assert!(
        text.contains("steady sliding at x = ") && text.contains("stable"),
        "{text}"
    );
}

struct Swept;

impl ModelVisitor for Swept {
    type Output = (stickslip::study::sweep::Sweep, Scan);
    fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
        let s = stickslip::study::sweep::sweep::<M>(base, "vd", 0.2, 3.0, 15, Default::default())
            .expect("sweep");
        Some((s, scan::<M>(base, "vd", 0.2, 3.0, 15).expect("scan")))
    }
}

/// Whether the structure `P_{…}` has the stick mapping `0_11`.
fn sticks(structure: &str) -> bool {
    structure.split([' ', '{', '}']).any(|name| name == "0_11")
}

fn swept(scene: &str) -> (stickslip::study::sweep::Sweep, Scan) {
    ModelRef::File {
        path: belt(),
        scene: Some(scene.to_string()),
    }
    .visit(Swept)
    .expect("loads")
    .expect("piecewise")
}

/// `sweep` on an unforced model: the equilibrium moving from band to band
/// is no grazing; its one loss of stability is a steady-sliding transition
/// at the value `equilibria` locates, into the stick-slip cycle; the
/// unstable cycle that shrinks onto the equilibrium there is that same
/// transition, not a second one. Every other transition is a cycle's.
#[test]
fn a_sweep_of_an_unforced_model_has_no_false_grazing() {
    use stickslip::bifurcation::TransitionKind;
    for scene in ["pl16", "pl64"] {
        let (sweep, s) = swept(scene);
        let rest: Vec<_> = sweep
            .transitions
            .iter()
            .filter(|t| t.kind == TransitionKind::SteadySliding)
            .collect();
        assert_eq!(rest.len(), 1, "{scene}: {:?}", sweep.transitions);
        let t = rest[0];
        assert_eq!(t.value, s.changes[0].change.at, "{scene}");
        assert!(t.to.starts_with("P_{") && sticks(&t.to), "{scene}: {t:?}");
        for u in &sweep.transitions {
            assert!(u.from.starts_with("P_{") || u == t, "{scene}: {u:?}");
            assert!(
                u == t || (u.value - t.value).abs() > 1e-8,
                "{scene}: {u:?} at the steady-sliding change"
            );
        }
    }
}

/// What the reference integrator (`tests/common/events.rs`, Dormand–Prince
/// with its own event location, nothing of the closed forms) does from
/// `(x0, v0)` in `domain` over `time`: the events and the final state.
fn integrate<M: Model>(
    p: &M::Params,
    x0: f64,
    v0: f64,
    domain: Option<usize>,
    time: f64,
) -> (Vec<common::events::RefEvent>, [f64; 2]) {
    let ode = common::events::PiecewiseOde::of::<M>(p);
    let (events, y, _) = ode.integrate_to(0.0, x0, v0, domain, time, 1e-12);
    (events, y)
}

/// The belt's sweep follows its cycles, stable and unstable, and the fold
/// between them, against the reference integrator:
/// * the stable stick-slip cycle dies where its stick vanishes, on the
///   unstable slip cycle (a non-smooth fold of cycles): on one side of it a
///   simulation from the cycle keeps sticking, on the other it comes to
///   rest;
/// * the unstable slip cycle at a grid value separates the two: from a
///   hair inside it the motion decays to steady sliding, from a hair
///   outside it sticks;
/// * its Floquet multiplier is the derivative of the integrator's return
///   map on the boundary its first point lies on (central differences),
///   and its period the integrator's return time.
#[test]
fn a_sweep_follows_the_cycles_and_the_fold_between_them() {
    use stickslip::bifurcation::TransitionKind;
    use stickslip::dynamics::simulate::EventKind;
    use stickslip::orbit::structure::Structure;
    let (sweep, _) = swept("pl16");
    let vanishing: Vec<_> = sweep
        .transitions
        .iter()
        .filter(|t| t.kind == TransitionKind::StickVanishing)
        .collect();
    assert_eq!(vanishing.len(), 1, "{:?}", sweep.transitions);
    let fold = vanishing[0].value;
    // The slip cycle (no stick) ends there too, and is unstable.
    let slip = sweep
        .branches
        .iter()
        .find(|b| {
            !sticks(&b.structure) && b.ends.iter().any(|e| (e.value - fold).abs() <= 1e-9 * fold)
        })
        .unwrap_or_else(|| {
            let ends: Vec<_> = sweep
                .branches
                .iter()
                .map(|b| (&b.structure, &b.ends))
                .collect();
            panic!("no slip cycle ends at the fold {fold}: {ends:?}")
        });
    assert!(slip.points.iter().all(|q| !q.stable), "{slip:?}");
    assert!(slip.points.iter().all(|q| q.value <= fold + 1e-9));
    // That unstable slip cycle at a grid value of the bistable window.
    let at = sweep
        .points
        .iter()
        .find_map(|g| {
            let m = g
                .motions
                .iter()
                .find(|m| !m.stable && m.structure == slip.structure)?;
            Some((g.value, m.clone()))
        })
        .expect("the unstable slip cycle at a grid value");

    struct Check {
        fold: f64,
        value: f64,
        motion: stickslip::study::sweep::MotionSummary,
        stick_x: f64,
    }
    impl ModelVisitor for Check {
        type Output = ();
        fn piecewise<M: Model>(self, base: M::Params) -> Option<()> {
            let id = M::identity(&base);
            let at = |vd: f64| base.with_pairs(id, &[("vd", vd)]).expect("params");
            let info = M::info(&base);
            // Both sides of the fold, from the stick onset of the cycle there.
            for (side, sticks) in [(-1e-3, true), (1e-3, false)] {
                let vd = self.fold + side;
                let p = at(vd);
                let rest = steady_sliding::<M>(&p).expect("steady sliding").x;
                let (events, y) = integrate::<M>(&p, self.stick_x, vd, None, 400.0);
                let late = events
                    .iter()
                    .filter(|e| e.phase > 300.0 * M::oscillator(&p).frequency)
                    .any(|e| e.kind == EventKind::StickOnset);
                assert_eq!(late, sticks, "vd = {vd}: {} events", events.len());
                if !sticks {
                    assert!((y[0] - rest).abs() < 1e-3 && y[1].abs() < 1e-3, "{y:?}");
                }
            }
            // The unstable slip cycle: its first point on the boundary of its
            // first mapping, entering that mapping's domain.
            let p = at(self.value);
            let w = M::oscillator(&p).frequency;
            let structure = Structure::parse(info, &self.motion.structure, 1).expect("structure");
            let first = info.mappings[structure.steps()[0]];
            let (b, domain) = (first.from, first.domain);
            let vb = M::boundary_velocity(&p, b);
            let rest = steady_sliding::<M>(&p).expect("steady sliding").x;
            let x0 = self.motion.start_x;
            for (scale, sticks) in [(0.99, false), (1.01, true)] {
                let x = rest + scale * (x0 - rest);
                let (events, _) = integrate::<M>(&p, x, vb, domain, 600.0);
                let stuck = events.iter().any(|e| e.kind == EventKind::StickOnset);
                assert_eq!(stuck, sticks, "from {scale} of the cycle");
            }
            // Return map on boundary b: the second crossing of b after the start.
            let period = self.motion.period.expect("a period");
            let back = |x: f64| {
                let (events, _) = integrate::<M>(&p, x, vb, domain, 1.5 * period);
                let e = events
                    .iter()
                    .filter(|e| e.boundary == b && e.kind == EventKind::Pass)
                    .nth(1)
                    .copied()
                    .expect("returns");
                (e.x, e.phase / w)
            };
            let (x1, t1) = back(x0);
            assert!((x1 - x0).abs() <= 1e-9 * x0.abs().max(1.0), "{x1} vs {x0}");
            assert!((t1 - period).abs() <= 1e-9 * period, "{t1} vs {period}");
            let h = 1e-5 * (x0 - rest).abs();
            let mu = (back(x0 + h).0 - back(x0 - h).0) / (2.0 * h);
            let reported = self.motion.eigenvalues[0][0];
            assert!(mu > 1.0, "unstable: {mu}");
            assert!((reported - mu).abs() <= 1e-6 * mu, "{reported} vs {mu}");
            Some(())
        }
    }
    // The stick onset of the stick-slip cycle at the grid value below the fold.
    let stick_x = sweep
        .points
        .iter()
        .rev()
        .find(|g| g.value < fold)
        .and_then(|g| g.motions.iter().find(|m| sticks(&m.structure)))
        .expect("the stick-slip cycle below the fold")
        .start_x;
    ModelRef::File {
        path: belt(),
        scene: Some("pl16".to_string()),
    }
    .visit(Check {
        fold,
        value: at.0,
        motion: at.1,
        stick_x,
    })
    .expect("loads")
    .expect("piecewise");
}

/// Forced and self-excited together: a weak forcing on the belt oscillator's
/// stick-slip cycle gives a motion on a torus. `simulate` does not settle,
/// and says what the motion does instead, from the Lyapunov exponents, and
/// what to run next.
#[test]
fn an_unsettled_simulation_says_what_it_found() {
    let out = on_belt(
        "simulate",
        &["--scene", "pl16", "--set", "vd=0.5,Q0=0.05,W=1.618"],
    );
    assert!(!out.status.success());
    let err = String::from_utf8_lossy(&out.stderr);
    assert!(err.contains("no periodic motion"), "{err}");
    assert!(
        err.contains("what it does instead") && err.contains("quasi-periodic"),
        "{err}"
    );
    assert!(err.contains("stickslip lyapunov"), "{err}");
}

/// Newton with the period unknown (`orbit::autonomous`): from a guess
/// perturbed by 1 % in every point and the period, the Coulomb cycle comes
/// back to its closed form, and the belt's 12-mapping cycle to the one the
/// simulation found. The first point's phase is held.
#[test]
fn newton_with_the_period_unknown_finds_the_cycle() {
    use stickslip::orbit::autonomous::{solve, AutonomousError};
    use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};

    struct Refined;
    impl ModelVisitor for Refined {
        type Output = Vec<(f64, f64)>;
        fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
            let mut out = Vec::new();
            let p = base
                .with_pairs(M::identity(&base), &[("vd", 0.5)])
                .or_else(|_| base.with_pairs(M::identity(&base), &[]))
                .expect("params");
            let sim = Simulator::<M>::new(p, SimOptions::default()).expect("params");
            let v = M::boundary_velocity(&p, 0);
            let start = sim.start(0.0, v, 0.0).expect("start");
            let Attractor::Autonomous(cycle) =
                attractor::find(&sim, start, AttractorOptions::default()).expect("settles")
            else {
                panic!("a cycle")
            };
            // The simulated cycle's points, from its events: re-simulate one
            // cycle from its onset and record every switching point.
            let w = M::oscillator(&p).frequency;
            let shift = cycle.period * w;
            let mut points = vec![SwitchingPoint {
                phase: cycle.onset,
                x: cycle.x,
            }];
            let seg = sim.start(cycle.x, cycle.v, cycle.onset).expect("onset");
            sim.run(seg, cycle.onset + 1.5 * shift, |e| {
                if points.len() < cycle.steps.len() {
                    points.push(SwitchingPoint {
                        phase: e.phase,
                        x: e.x,
                    });
                }
            })
            .expect("one cycle");
            assert_eq!(points.len(), cycle.steps.len());
            let guess: Vec<SwitchingPoint> = points
                .iter()
                .enumerate()
                .map(|(k, q)| SwitchingPoint {
                    phase: if k == 0 { q.phase } else { q.phase + 0.01 },
                    x: q.x * 1.01,
                })
                .collect();
            let c = solve::<M>(
                &p,
                &cycle.steps,
                &guess,
                shift * 1.01,
                NewtonOptions::default(),
            )
            .expect("converges");
            assert_eq!(c.points[0].phase, points[0].phase, "the phase condition");
            out.push((c.period(w), cycle.period));
            for (a, b) in c.points.iter().zip(&points) {
                out.push((a.x, b.x));
                out.push((a.phase, b.phase));
            }
            // Forced: refused.
            if let Ok(q) = p.with_pairs(M::identity(&p), &[("Q0", 0.5)]) {
                assert!(matches!(
                    solve::<M>(&q, &cycle.steps, &guess, shift, NewtonOptions::default()),
                    Err(AutonomousError::Forced(_))
                ));
            }
            Some(out)
        }
    }
    for model in [
        ModelRef::Name("coulomb".to_string()),
        ModelRef::File {
            path: belt(),
            scene: Some("pl16".to_string()),
        },
    ] {
        let pairs = if let ModelRef::Name(_) = model {
            // Q0 = 0, d = 0, V = 0.5: the closed form of the test above.
            struct Unforced;
            impl ModelVisitor for Unforced {
                type Output = Vec<(f64, f64)>;
                fn piecewise<M: Model>(self, base: M::Params) -> Option<Self::Output> {
                    let p = base
                        .with_pairs(M::identity(&base), &[("Q0", 0.0), ("d", 0.0), ("V", 0.5)])
                        .expect("params");
                    Refined.piecewise::<M>(p)
                }
            }
            model.visit(Unforced).expect("model").expect("piecewise")
        } else {
            model.visit(Refined).expect("loads").expect("piecewise")
        };
        for (a, b) in pairs {
            assert!((a - b).abs() <= 1e-10 * b.abs().max(1.0), "{a} vs {b}");
        }
    }
    // The Coulomb cycle's period is the closed form's.
    let closed = 0.4 + std::f64::consts::PI + 2.0 * (0.5f64 / 0.1).atan();
    let p = coulomb::Params {
        Q0: 0.0,
        d: 0.0,
        V: 0.5,
        ..coulomb::Params::default()
    };
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("params");
    let Attractor::Autonomous(c) = attractor::find(
        &sim,
        sim.start(0.0, 0.5, 0.0).expect("start"),
        AttractorOptions::default(),
    )
    .expect("settles") else {
        panic!("a cycle")
    };
    assert!((c.period - closed).abs() <= 1e-10);
}

/// `equilibria`'s bad input: an empty grid, a fixed parameter, the forcing
/// on; each a message that says what to do, never a panic.
#[test]
fn equilibria_refuses_bad_input_with_a_message() {
    let run = |args: &[&str]| {
        let out = stickslip(["equilibria"].iter().chain(args));
        (
            out.status.code(),
            String::from_utf8_lossy(&out.stdout).to_string()
                + &String::from_utf8_lossy(&out.stderr),
        )
    };
    let belt = belt().display().to_string();
    let (code, text) = run(&["--model-file", &belt, "--param", "vd=0.2:3:0"]);
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("between 1 and"), "{text}");
    let (code, text) = run(&["--model", "paper::sweep_w", "--set", "Q0=0"]);
    assert_eq!(code, Some(1), "{text}");
    assert!(text.contains("free:"), "{text}");
    let (code, text) = run(&["--model", "stribeck"]);
    assert_eq!(code, Some(0), "{text}");
    assert!(
        text.contains("no steady sliding") && text.contains("Q0=0"),
        "{text}"
    );
}

/// `orbit` on an unforced model solves the structure with its period
/// unknown: the unstable slip cycle at vd = 1.6 from a guess near it, its
/// return and period against the reference integrator, its multiplier
/// above 1, `N = 0` and the period in the JSON.
#[test]
fn orbit_solves_an_autonomous_cycle_with_its_period_unknown() {
    use stickslip::dynamics::simulate::EventKind;
    use stickslip::orbit::structure::Structure;
    const S: &str = "P_{10_10_10 11_10_11 12_11_12 13_12_13 14_13_14 15_14_15 16_15_15 \
                     15_15_14 14_14_13 13_13_12 12_12_11 11_11_10}";
    let out = on_belt(
        "orbit",
        &[
            "--scene",
            "pl16",
            "--set",
            "vd=1.6",
            "--guess",
            "0,1.3",
            "--json",
            "--structure",
            S,
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    assert_eq!(json["N"], 0, "{json}");
    let period = json["period"].as_f64().expect("a period");
    let mu = json["eigenvalues"][0][0].as_f64().expect("a multiplier");
    assert!(mu > 1.0, "{json}");
    let x0 = json["points"][0]["x"].as_f64().expect("x");

    struct Check(f64, f64);
    impl ModelVisitor for Check {
        type Output = (f64, f64);
        fn piecewise<M: Model>(self, base: M::Params) -> Option<(f64, f64)> {
            let p = base
                .with_pairs(M::identity(&base), &[("vd", 1.6)])
                .expect("params");
            let info = M::info(&p);
            let first = info.mappings[Structure::parse(info, S, 1).expect("parses").steps()[0]];
            let vb = M::boundary_velocity(&p, first.from);
            let (events, _) = integrate::<M>(&p, self.0, vb, first.domain, 1.5 * self.1);
            let e = events
                .iter()
                .filter(|e| e.boundary == first.from && e.kind == EventKind::Pass)
                .nth(1)
                .copied()
                .expect("returns");
            Some((e.x, e.phase / M::oscillator(&p).frequency))
        }
    }
    let (x1, t1) = ModelRef::File {
        path: belt(),
        scene: Some("pl16".to_string()),
    }
    .visit(Check(x0, period))
    .expect("loads")
    .expect("piecewise");
    assert!((x1 - x0).abs() <= 1e-9 * x0.abs(), "{x1} vs {x0}");
    assert!((t1 - period).abs() <= 1e-9 * period, "{t1} vs {period}");
}

/// `map` of an unforced model shows its regimes over two parameters:
/// steady sliding only, bistable, the cycle only; its two methods agree
/// cell by cell (continuation of the cycles and the equilibrium's closed
/// form, against simulations from several starts with the equilibrium's
/// stability), and a cell is bistable exactly where `equilibria` calls
/// steady sliding stable and a simulation from rest sticks.
#[test]
fn a_map_of_an_unforced_model_shows_its_regimes() {
    let dir = std::env::temp_dir().join(format!("stickslip-belt-map-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let mut cells: Vec<Vec<(String, String)>> = Vec::new();
    for method in ["continuation", "simulation"] {
        let out = dir.join(format!("{method}.csv"));
        let _ = std::fs::remove_file(&out);
        let run = on_belt(
            "map",
            &[
                "--scene",
                "pl16",
                "--x",
                "vd=0.2:3:8",
                "--y",
                "zeta=0.02:0.1:4",
                "--method",
                method,
                "--out",
                out.to_str().expect("utf-8 path"),
            ],
        );
        assert!(
            run.status.success(),
            "{}",
            String::from_utf8_lossy(&run.stderr)
        );
        let text = std::fs::read_to_string(&out).expect("csv");
        cells.push(
            text.lines()
                .skip(2)
                .map(|l| {
                    let f: Vec<&str> = l.split(',').collect();
                    (
                        format!("{},{}", f[1], f[2]),
                        f[4].trim_matches('"').to_string(),
                    )
                })
                .collect(),
        );
    }
    assert_eq!(cells[0], cells[1]);
    let kinds: std::collections::BTreeSet<&str> = cells[0].iter().map(|c| c.1.as_str()).collect();
    for regime in ["NM", "NM;stick-slip cycle", "stick-slip cycle"] {
        assert!(kinds.contains(regime), "{kinds:?}");
    }
    // Bistable exactly where steady sliding is stable and the cycle lives.
    struct Stable(f64, f64);
    impl ModelVisitor for Stable {
        type Output = bool;
        fn piecewise<M: Model>(self, base: M::Params) -> Option<bool> {
            let p = base
                .with_pairs(M::identity(&base), &[("vd", self.0), ("zeta", self.1)])
                .expect("params");
            Some(steady_sliding::<M>(&p).is_ok_and(|e| e.verdict == Verdict::Stable))
        }
    }
    for (at, motions) in &cells[0] {
        let (vd, zeta) = at.split_once(',').expect("two coordinates");
        let stable = ModelRef::File {
            path: belt(),
            scene: Some("pl16".to_string()),
        }
        .visit(Stable(vd.parse().expect("vd"), zeta.parse().expect("zeta")))
        .expect("loads")
        .expect("piecewise");
        assert_eq!(
            motions.split(';').any(|m| m == "NM"),
            stable,
            "{at}: {motions}"
        );
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// `describe` of an unforced model names its steady sliding, in text and
/// JSON, as `equilibria` gives it; a forced model has none.
#[test]
fn describe_names_steady_sliding() {
    let run = |args: &[&str]| {
        let out = stickslip(["describe"].iter().chain(args));
        assert!(
            out.status.success(),
            "{}",
            String::from_utf8_lossy(&out.stderr)
        );
        String::from_utf8_lossy(&out.stdout).to_string()
    };
    let file = belt();
    let file = file.to_str().expect("utf-8 path");
    let json: serde_json::Value = serde_json::from_str(&run(&[
        "--model-file",
        file,
        "--scene",
        "pl16",
        "--set",
        "vd=1.5",
        "--json",
    ]))
    .expect("json");
    let (s, _) = ModelRef::File {
        path: belt(),
        scene: Some("pl16".to_string()),
    }
    .visit(Scanned("vd", 1.5, 1.5, 1))
    .expect("loads")
    .expect("piecewise");
    let x = s.points[0].equilibrium.expect("steady sliding").x;
    assert_eq!(json["steady_sliding"]["x"].as_f64(), Some(x), "{json}");
    assert_eq!(json["steady_sliding"]["verdict"], "stable");
    let text = run(&["--model-file", file, "--scene", "pl16", "--set", "vd=1.5"]);
    assert!(
        text.contains(&format!("steady sliding at x = {x:.12}")),
        "{text}"
    );
    let forced = run(&["--model", "paper", "--json"]);
    assert!(!forced.contains("steady_sliding"), "{forced}");
}

/// `sweep` of the belt law itself writes its CSV (one row per motion, the
/// numbers of its JSON to the last bit) and its figure; `--no-unstable`
/// leaves out the unstable slip cycles and keeps steady sliding.
#[test]
fn a_law_sweep_writes_its_csv_and_figure() {
    let dir = std::env::temp_dir().join(format!("stickslip-law-sweep-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let (csv, svg) = (dir.join("law.csv"), dir.join("law.svg"));
    let range = ["--param", "vd=0.2:3:8"];
    let out = on_belt(
        "sweep",
        &[
            range[0],
            range[1],
            "--csv",
            csv.to_str().expect("path"),
            "--plot",
            svg.to_str().expect("path"),
            "--json",
        ],
    );
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    let text = std::fs::read_to_string(&csv).expect("csv written");
    let mut rows = text.lines();
    assert_eq!(
        rows.next(),
        Some("vd,kind,x,stable,period,stick,multiplier")
    );
    let rows: Vec<Vec<&str>> = rows.map(|r| r.split(',').collect()).collect();
    let mut expected = Vec::new();
    for p in json["points"].as_array().expect("points") {
        let value = p["value"].as_f64().expect("value");
        if let Some(x) = p["equilibrium"]["x"].as_f64() {
            expected.push((value, "steady_sliding".to_string(), x));
        }
        for c in p["cycles"].as_array().expect("cycles") {
            let kind = if c["stick"].as_f64() > Some(0.0) {
                "stick_slip"
            } else {
                "slip"
            };
            expected.push((value, kind.to_string(), c["x"].as_f64().expect("x")));
        }
    }
    assert_eq!(rows.len(), expected.len());
    for (row, (value, kind, x)) in rows.iter().zip(&expected) {
        assert_eq!(row[0].parse::<f64>().ok(), Some(*value));
        assert_eq!(row[1], kind);
        assert_eq!(row[2].parse::<f64>().ok(), Some(*x));
    }
    assert!(expected.iter().any(|e| e.1 == "slip"));
    let svg_text = std::fs::read_to_string(&svg).expect("figure written");
    assert!(svg_text.contains("<svg") && svg_text.contains("Hopf"));
    let out = on_belt("sweep", &[range[0], range[1], "--no-unstable", "--json"]);
    let json: serde_json::Value = serde_json::from_slice(&out.stdout).expect("json");
    for p in json["points"].as_array().expect("points") {
        assert!(p["equilibrium"]["x"].is_f64());
        for c in p["cycles"].as_array().expect("cycles") {
            assert_eq!(c["verdict"], "stable", "{c}");
        }
    }
    std::fs::remove_dir_all(&dir).ok();
}

/// `curves` of an unforced model says why it traces no curve of a cycle
/// (its period is an unknown) and where to look instead, not a NaN.
#[test]
fn curves_of_an_unforced_model_say_why_no_cycle_curve_is_traced() {
    let out = on_belt(
        "curves",
        &[
            "--scene",
            "pl16",
            "--x",
            "vd=1.0:1.5",
            "--y",
            "zeta=0.04:0.06",
        ],
    );
    let text = String::from_utf8_lossy(&out.stdout);
    assert!(text.contains("Missing curves"), "{text}");
    assert!(
        text.contains("an autonomous cycle") && text.contains("stickslip map"),
        "{text}"
    );
    assert!(!text.contains("NaN"), "{text}");
}

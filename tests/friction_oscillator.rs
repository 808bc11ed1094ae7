//! The textbook friction oscillator (`coulomb`), beyond Den Hartog's
//! non-stop motion (`den_hartog.rs`): the permanent stick, the neutral family
//! of the undamped oscillator at `W = sqrt(c) / (2 n)`, the tie `mus = muk` at
//! velocity reversals, and the unforced belt stick-slip cycle, each against
//! an independent computation.

use std::process::Command;

use stickslip::dynamics::simulate::{EventKind, Location, SimOptions, Simulator};
use stickslip::models::coulomb::{Coulomb, Params};
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::output::report::Report;

const TAU: f64 = 2.0 * std::f64::consts::PI;
const PI: f64 = std::f64::consts::PI;

/// `coulomb` at `[m, d, c, V, mus, muk, Q0, W]`, `g = 9.8`.
fn coulomb([m, d, c, v, mus, muk, q0, w]: [f64; 8]) -> Params {
    Params {
        m,
        d,
        c,
        V: v,
        mus,
        muk,
        g: 9.8,
        Q0: q0,
        W: w,
    }
}

fn find(p: Params, x: f64, v: f64, phase: f64) -> Result<Attractor, String> {
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).expect("valid parameters");
    let start = sim.start(x, v, phase).expect("start");
    attractor::find(&sim, start, AttractorOptions::default()).map_err(|e| e.to_string())
}

#[test]
fn a_forcing_below_the_static_bound_sticks_forever_and_is_reported_so() {
    // From rest at x = 0 with V = 0, Fnf = A0 cos(W t): the stick is permanent
    // iff A0 <= as. Either side of the threshold, several stiffnesses,
    // frequencies and friction ratios (mus = muk included).
    for (c, w) in [(1.0, 0.5), (30.0, 4.4), (30.0, 11.0), (0.2, 3.0)] {
        for ratio in [1.0, 1.3] {
            for (factor, sticks) in [(0.5, true), (0.999, true), (1.001, false), (1.5, false)] {
                let (m, muk) = (2.0, 0.4);
                let a_s = ratio * muk * 9.8;
                let p = coulomb([m, 0.1, c, 0.0, ratio * muk, muk, factor * a_s * m, w]);
                let how = format!("c = {c}, W = {w}, mus/muk = {ratio}, A0 = {factor} as");
                match find(p, 0.0, 0.0, 0.0) {
                    Ok(Attractor::Stick(s)) => {
                        assert!(sticks, "{how}: {s:?}");
                        assert_eq!((s.x, s.v), (0.0, 0.0), "{how}");
                        assert!((s.max_force - factor * a_s).abs() < 1e-12 * a_s, "{how}");
                    }
                    other => assert!(!sticks, "{how}: {other:?}"),
                }
            }
        }
    }
}

#[test]
fn a_stick_reached_after_a_transient_is_permanent_exactly_when_the_bound_says() {
    // Moving starts that come to rest: where the search reports a permanent
    // stick, |A0| + c |x| <= as holds, and the simulation from that state
    // really has no further event over many periods.
    let mut seen = 0;
    for x0 in [0.5, 0.9, 2.0, -1.5] {
        for v0 in [0.0, 1.0, -2.0] {
            let p = coulomb([1.0, 0.05, 1.0, 0.0, 2.0 / 9.8, 2.0 / 9.8, 1.0, 0.5]);
            match find(p, x0, v0, 0.3) {
                Ok(Attractor::Stick(s)) => {
                    seen += 1;
                    assert!(1.0 + s.x.abs() <= 2.0, "{s:?}");
                    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
                    let seg = sim.start(s.x, 0.0, s.since).unwrap();
                    assert_eq!(seg.location, Location::Stick);
                    let mut events = 0;
                    sim.run(seg, s.since + 200.0 * TAU, |e| {
                        if e.kind != EventKind::Graze {
                            events += 1
                        }
                    })
                    .unwrap();
                    assert_eq!(events, 0, "{s:?}");
                }
                Ok(Attractor::Periodic(m)) => panic!("({x0}, {v0}): {:?}", m.structure),
                other => panic!("({x0}, {v0}): {other:?}"),
            }
        }
    }
    assert_eq!(seen, 12);
}

/// `stickslip simulate --model coulomb --set SET` with `extra` arguments:
/// its standard output, after asserting success.
fn simulate_coulomb(set: &str, extra: &[&str]) -> Vec<u8> {
    let out = Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .args(["simulate", "--model", "coulomb", "--set", set])
        .args(extra)
        .output()
        .expect("run the CLI");
    assert!(out.status.success(), "{out:?}");
    out.stdout
}

/// The same with `--json`, parsed.
fn simulate_coulomb_json(set: &str, extra: &[&str]) -> serde_json::Value {
    let mut args = vec!["--json"];
    args.extend_from_slice(extra);
    serde_json::from_slice(&simulate_coulomb(set, &args)).expect("JSON")
}

#[test]
fn simulate_json_reports_the_stick_with_its_position() {
    let set = "V=0,mus=2,muk=2,Q0=1,m=1,c=1,g=1,W=0.5";
    let json = simulate_coulomb_json(set, &[]);
    assert_eq!(json["kind"], "stick");
    assert_eq!(json["x"], 0.0);
    assert_eq!(json["static_bound"], 2.0);
    let text = simulate_coulomb(set, &[]);
    assert!(String::from_utf8_lossy(&text).contains("permanent stick"));
}

#[test]
fn with_a_moving_belt_no_stick_is_permanent() {
    // x = x_i + V (t − t_i) stretches the spring without bound: every stick
    // ends, even with a forcing far below the static bound.
    for v in [0.3, -0.5] {
        let p = coulomb([1.0, 0.05, 1.0, v, 0.6, 0.4, 0.1, 0.7]);
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
        let seg = sim.start(0.0, v, 0.0).unwrap();
        assert_eq!(seg.location, Location::Stick);
        let mut ends = 0;
        sim.run(seg, 100.0 * TAU, |e| {
            if e.kind == EventKind::StickEnd {
                ends += 1
            }
        })
        .unwrap();
        assert!(ends >= 3, "V = {v}: {ends} stick ends");
        assert!(!matches!(find(p, 0.0, v, 0.0), Ok(Attractor::Stick(_))));
    }
}

/// Den Hartog's symmetric motion at `W = sqrt(c) / (2 n)`, `d = 0`: the
/// half-period transfer matrix is the identity, so `(s, q) = 0` and
/// `X0 = A0 / (c − W²)` at the phase `π` of the minimum; any free oscillation
/// `h` with `h(π/W) = h(0)` rides along as long as the velocity keeps its sign
/// (Csernák, Stépán & Shaw 2007): the family is `x(φ_min) = −X0 + δ`.
#[test]
fn the_undamped_oscillator_at_half_integer_ratios_has_a_neutral_family() {
    let (m, c, q0): (f64, f64, f64) = (2.5, 30.0, 70.0);
    let a0 = q0 / m;
    for n in [1.0, 2.0] {
        let w = c.sqrt() / (2.0 * n);
        let x0 = a0 / (c - w * w);
        let muk = 0.005 * a0 / 9.8;
        let p = coulomb([m, 0.0, c, 0.0, muk, muk, q0, w]);
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
        let mut members = Vec::new();
        for delta in [0.0, 0.02 * x0, -0.02 * x0] {
            let how = format!("n = {n}, δ = {delta}");
            let motion = match find(p, -x0 + delta, 0.0, PI) {
                Ok(Attractor::Periodic(m)) => m,
                other => panic!("{how}: {other:?}"),
            };
            let st = motion.stability.expect("stability");
            assert!(st.has_unit_eigenvalue(), "{how}: {:?}", st.eigenvalues);
            assert!(
                matches!(Report::of_motion(&sim, &motion), Report::NeutralFamily(_)),
                "{how}"
            );
            // The member is the one the start lies on: the minimum is where it started.
            let lowest = motion
                .points
                .iter()
                .map(|p| p.x)
                .fold(f64::INFINITY, f64::min);
            assert!((lowest - (-x0 + delta)).abs() < 1e-9, "{how}: {lowest}");
            members.push(lowest);
        }
        assert!(members.windows(2).all(|w| (w[0] - w[1]).abs() > 1e-3));
        // Viscous damping or a detuned frequency makes the motion isolated.
        for (d, wf) in [(0.05, 1.0), (0.0, 1.01)] {
            let q = Params { d, W: w * wf, ..p };
            let sim = Simulator::<Coulomb>::new(q, SimOptions::default()).unwrap();
            if let Ok(Attractor::Periodic(m)) = find(q, -x0, 0.0, PI) {
                let st = m.stability.expect("stability");
                assert!(!st.has_unit_eigenvalue(), "d = {d}, W = {wf} W: {st:?}");
                assert!(matches!(Report::of_motion(&sim, &m), Report::Periodic(_)));
            }
        }
    }
}

/// Unforced belt stick-slip (Q0 = 0, V > 0, mus > muk, d = 0): a stick ends
/// where `c x_e = as` (`Fnf = −c x = −as`), the slip obeys
/// `x'' + c x = ak` from `(x_e, V)`: with `u = x − ak/c`, `u0 = (as − ak)/c`,
/// `ω = sqrt(c)`, the velocity `V cos ωt − u0 ω sin ωt` returns to `V` after
/// `T_slip = (2π − 2 atan2(u0 ω, V)) / ω` at `u = −u0`, where it arrives
/// from below with `Fnf = as − 2 ak`: it sticks again if `Fnf − ak ≤ 0`
/// (SPEC §3's pass test uses the kinetic input forces), i.e. `as ≤ 3 ak`;
/// the stick then lasts `T_stick = 2 u0 / V`.
#[test]
fn the_unforced_belt_stick_slip_cycle_has_den_hartogs_closed_form_durations() {
    for (c, v, mus, muk, m) in [
        (1.0, 0.5, 0.4, 0.3, 1.0),
        (30.0, 3.0, 0.5, 0.4, 5.0),
        (4.0, 0.1, 0.5, 0.2, 0.7),
    ] {
        let (a_s, ak) = (mus * 9.8, muk * 9.8);
        let omega = f64::sqrt(c);
        let u0 = (a_s - ak) / c;
        let t_slip = (TAU - 2.0 * (u0 * omega).atan2(v)) / omega;
        let t_stick = 2.0 * u0 / v;
        let x_end = a_s / c;
        let w = 1.3; // only sets the phase unit: phase = W t
        let p = coulomb([m, 0.0, c, v, mus, muk, 0.0, w]);
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
        let seg = sim.start(0.0, v, 0.0).unwrap();
        let mut events = Vec::new();
        sim.run(seg, w * 6.0 * (t_slip + t_stick), |e| events.push(*e))
            .unwrap();
        let ends: Vec<_> = events
            .iter()
            .filter(|e| e.kind == EventKind::StickEnd)
            .collect();
        let onsets: Vec<_> = events
            .iter()
            .filter(|e| e.kind == EventKind::StickOnset)
            .collect();
        assert!(ends.len() >= 4 && onsets.len() >= 3, "{events:?}");
        assert_eq!(
            events.len(),
            ends.len() + onsets.len(),
            "only sticks and slips"
        );
        let how = format!("c = {c}, V = {v}, as = {a_s}, ak = {ak}");
        for e in &ends {
            assert!((e.x - x_end).abs() < 1e-12 * x_end.max(1.0), "{how}: {e:?}");
            assert_eq!(e.after, Location::Domain(0), "{how}");
        }
        // Every slip (from the first stick end on) and every stick.
        for pair in events.windows(2) {
            let dt = (pair[1].phase - pair[0].phase) / w;
            let want = match pair[0].kind {
                EventKind::StickEnd => t_slip,
                _ => t_stick,
            };
            assert!((dt - want).abs() < 1e-10 * want, "{how}: {dt} vs {want}");
        }
        for e in &onsets {
            assert!((e.x - (ak / c - u0)).abs() < 1e-10, "{how}: {e:?}");
        }
    }
}

/// The example: with `mus = muk` a stick that ends where `|Fnf| = as`
/// leaves with zero acceleration, and the velocity's rounding near that
/// tangent departure looked like a return to the belt speed: a stick with
/// `|Fnf| > as` followed, "ended" when `Fnf` came back to the bound, and the
/// search never settled. The stable non-stop motion is the same as at
/// `mus = 1.41` (the static bound does not enter a motion without stops).
#[test]
fn static_equal_to_kinetic_friction_finds_the_non_stop_motion() {
    let muk = 1.401_268_089_790_084_7;
    let w = 4.381_780_460_041_329_5;
    let mut found = Vec::new();
    for mus in [muk, 1.41] {
        let p = Params {
            g: 9.8,
            ..coulomb([2.5, 0.0, 30.0, 0.0, mus, muk, 70.0, w])
        };
        match find(p, 0.0, 0.0, 0.0) {
            Ok(Attractor::Periodic(m)) => {
                assert_eq!(m.structure.notation(Coulomb::INFO), "P_{1_11 2_11}");
                assert!(m.is_admissible());
                let lam = m.stability.expect("stability").largest_modulus;
                assert!((lam - 0.508).abs() < 1e-3, "{lam}");
                found.push(m.points);
            }
            other => panic!("mus = {mus}: {other:?}"),
        }
    }
    for (a, b) in found[0].iter().zip(&found[1]) {
        assert!((a.phase - b.phase).abs() < 1e-10 && (a.x - b.x).abs() < 1e-10);
    }
}

/// `orbit` near a member of the neutral family: `I − DP` is singular, so
/// Newton's plain step is useless ("the line search found no decrease"); the
/// minimum-norm step converges to a nearby member, which is reported as a
/// neutral family. A member is `x_max = X0 + δ` at `W t = 0`,
/// `x_min = −X0 + δ` at `W t = π`; off-family guesses converge onto it, and
/// the same fallback does not turn a damped motion into a family.
#[test]
fn orbit_near_a_family_member_reports_the_neutral_family() {
    use stickslip::orbit::motion;
    use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
    use stickslip::orbit::structure::Structure;
    let (m, c, q0): (f64, f64, f64) = (2.5, 30.0, 70.0);
    let a0 = q0 / m;
    let w = c.sqrt() / 2.0;
    let x0 = a0 / (c - w * w);
    let muk = 0.005 * a0 / 9.8;
    let p = coulomb([m, 0.0, c, 0.0, muk, muk, q0, w]);
    let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
    let structure = Structure::parse(Coulomb::INFO, "P_{1_11 2_11}", 1).unwrap();
    // A member shifted by `dx` with its phases off by up to `dphase`.
    for (dphase, dx) in [(1e-3, 0.0), (1e-3, 1e-3), (-2e-3, 5e-3)] {
        let guess = vec![
            SwitchingPoint {
                phase: dphase,
                x: x0 + dx,
            },
            SwitchingPoint {
                phase: PI + 0.5 * dphase,
                x: -x0 + dx,
            },
        ];
        let motion = motion::solve(&sim, structure.clone(), guess, NewtonOptions::default());
        let how = format!("guess offsets ({dphase}, {dx})");
        assert!(motion.is_admissible(), "{how}: {motion:?}");
        assert!(
            matches!(Report::of_motion(&sim, &motion), Report::NeutralFamily(_)),
            "{how}"
        );
        // On the family: turning points half a period apart, amplitudes X0 ± δ.
        let (a, b) = (motion.points[0], motion.points[1]);
        let delta = a.x - x0;
        assert!((b.x - (-x0 + delta)).abs() < 1e-9, "{how}: {a:?} {b:?}");
        assert!(
            ((b.phase - a.phase).rem_euclid(TAU) - PI).abs() < 1e-9,
            "{how}"
        );
        assert!(
            (delta - dx).abs() < 1e-2,
            "{how}: the member is near the guess ({delta})"
        );
    }
    // With damping the motion is isolated: Newton's own step converges and
    // the eigenvalue 1 is gone.
    let q = Params { d: 0.05, ..p };
    let sim = Simulator::<Coulomb>::new(q, SimOptions::default()).unwrap();
    let guess = vec![
        SwitchingPoint { phase: 0.0, x: x0 },
        SwitchingPoint { phase: PI, x: -x0 },
    ];
    let motion = motion::solve(&sim, structure, guess, NewtonOptions::default());
    if motion.termination.converged() {
        assert!(!motion.stability.unwrap().has_unit_eigenvalue());
    }
}

/// Without forcing the system is autonomous: `simulate` reports the belt
/// stick-slip cycle by the return of the stick-onset state, with its period
/// and the stick and slip durations of the closed form above (library and
/// CLI JSON).
#[test]
fn simulate_reports_the_unforced_belt_cycle_as_autonomous() {
    for (c, v, mus, muk, m) in [(1.0, 0.5, 0.4, 0.3, 1.0), (30.0, 3.0, 0.5, 0.4, 5.0)] {
        let (a_s, ak) = (mus * 9.8, muk * 9.8);
        let omega = f64::sqrt(c);
        let u0 = (a_s - ak) / c;
        let t_slip = (TAU - 2.0 * (u0 * omega).atan2(v)) / omega;
        let t_stick = 2.0 * u0 / v;
        let how = format!("c = {c}, V = {v}");
        let p = coulomb([m, 0.0, c, v, mus, muk, 0.0, 1.3]);
        // Started on the belt (from rest at c = 30 the undamped slip never
        // reaches the belt speed).
        let cycle = match find(p, 0.0, v, 0.0) {
            Ok(Attractor::Autonomous(a)) => a,
            other => panic!("{how}: {other:?}"),
        };
        assert!(
            (cycle.stick - t_stick).abs() < 1e-10 * t_stick,
            "{how}: {cycle:?}"
        );
        assert!(
            (cycle.slip - t_slip).abs() < 1e-10 * t_slip,
            "{how}: {cycle:?}"
        );
        assert!((cycle.period - t_stick - t_slip).abs() < 1e-10 * cycle.period);
        assert!((cycle.x - (ak / c - u0)).abs() < 1e-10, "{how}: {cycle:?}");
        assert_eq!(cycle.steps.len(), 2, "{how}: one stick, one slip");
        let set = format!("m={m},c={c},V={v},mus={mus},muk={muk},Q0=0,d=0,g=9.8,W=1.3");
        let json = simulate_coulomb_json(&set, &["--from", &format!("0,{v},0")]);
        assert_eq!(json["kind"], "autonomous_cycle", "{json}");
        let get = |k: &str| json[k].as_f64().expect(k);
        assert!((get("stick") - t_stick).abs() < 1e-10 * t_stick, "{json}");
        assert!((get("slip") - t_slip).abs() < 1e-10 * t_slip, "{json}");
        assert!((get("period") - t_stick - t_slip).abs() < 1e-10 * (t_stick + t_slip));
    }
    // With forcing the cycle is not autonomous (the onset test does not apply).
    let p = coulomb([1.0, 0.0, 1.0, 0.5, 0.4, 0.3, 0.5, 1.3]);
    assert!(!matches!(
        find(p, 0.0, 0.0, 0.0),
        Ok(Attractor::Autonomous(_))
    ));
}

/// An unsettled search says when the model is undamped (no transient decay:
/// the motion may drift for ever), and only then.
#[test]
fn an_unsettled_undamped_motion_says_so() {
    use stickslip::orbit::motion::OrbitError;
    let opts = AttractorOptions {
        max_periods: 40,
        ..AttractorOptions::default()
    };
    for (d, undamped) in [(0.0, true), (1e-3, false)] {
        let p = Params {
            g: 1.0,
            ..coulomb([1.0, d, 1.0, 0.0, 0.15, 0.1, 1.0, 0.3])
        };
        let sim = Simulator::<Coulomb>::new(p, SimOptions::default()).unwrap();
        let start = sim.start(0.0, 0.0, 0.0).unwrap();
        match attractor::find(&sim, start, opts) {
            Err(e @ OrbitError::Unsettled { .. }) => {
                assert_eq!(
                    e,
                    OrbitError::Unsettled {
                        periods: 40,
                        undamped,
                        instead: None,
                    }
                );
                assert_eq!(e.to_string().contains("undamped"), undamped, "{e}");
            }
            other => panic!("d = {d}: {other:?}"),
        }
    }
}

/// Undamped at W = sqrt(c) / 2 (n = 1) from rest, the motion keeps a stick
/// whose length shrinks like N^(-1/2): it creeps towards the edge member of
/// the neutral family (the non-stop motion whose turning point has
/// |Fnf| = as exactly). `simulate` names the family, with the eigenvalue 1;
/// with a little damping the family is gone and so is the claim.
#[test]
fn simulate_from_rest_finds_the_edge_of_the_neutral_family() {
    let run = |d: f64| {
        simulate_coulomb_json(
            &format!("m=1,c=1,g=1,d={d},V=0,mus=0.1,muk=0.1,Q0=1,W=0.5"),
            &[],
        )
    };
    let json = run(0.0);
    assert_eq!(json["kind"], "neutral_family", "{json}");
    let eig = json["eigenvalues"].as_array().expect("eigenvalues");
    let unit = eig.iter().any(|e| {
        let (re, im) = (e[0].as_f64().unwrap(), e[1].as_f64().unwrap());
        (re - 1.0).abs() < 1e-9 && im.abs() < 1e-9
    });
    assert!(unit, "{eig:?}");
    // The edge: at one turning point |Fnf| = |Q0 cos(W t) − c x| = mus g.
    let points = json["points"].as_array().expect("points");
    let edge = points
        .iter()
        .map(|p| {
            let (wt, x) = (p["Wt"].as_f64().unwrap(), p["x"].as_f64().unwrap());
            ((wt.cos() - x).abs() - 0.1).abs()
        })
        .fold(f64::INFINITY, f64::min);
    assert!(edge < 1e-8, "distance from the edge {edge:e}");
    let damped = run(1e-3);
    assert_ne!(damped["kind"], "neutral_family", "{damped}");
}

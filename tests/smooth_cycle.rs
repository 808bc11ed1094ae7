//! A smooth law's self-excited cycles (`orbit::smooth`) against an
//! integrator written here: the belt oscillator of `examples/belt.ssm`,
//! its law written out below by hand (not taken from the model file), and
//! Dormand–Prince steps from `tests/common/dopri.rs` with events located
//! by bisection on one-step solutions.
//!
//! * The unstable slip cycle of the bistable window: its section point and
//!   period, and its Floquet multiplier against `exp ∮ (trace of the
//!   Jacobian) dt = exp ∮ −(2 d + f'(v)) dt`, the multiplier of a planar
//!   cycle that never reaches the discontinuity.
//! * The stable stick-slip cycle: its stick duration and period against
//!   the cycle built from the stick's end, where the static bound fixes
//!   the state.
//! * What `settle` reaches from two starts in the bistable window.

mod common;

use std::path::PathBuf;

use common::dopri;
use stickslip::models::ModelRef;
use stickslip::orbit::equilibrium::Verdict;
use stickslip::orbit::smooth::{settle, ReturnMap, SmoothCycle, SmoothOptions, SmoothSettled};
use stickslip::{ModelVisitor, ParamSet, SmoothModel};

/// `examples/belt.ssm`'s defaults, with the belt speed `vd`.
#[derive(Clone, Copy)]
struct Belt {
    vd: f64,
}

impl Belt {
    const ZETA: f64 = 0.05;
    const C: f64 = 1.0;
    const MUS: f64 = 1.0;
    const MUD: f64 = 0.5;
    const V0: f64 = 0.5;

    fn two_d(&self) -> f64 {
        2.0 * Self::ZETA * Self::C.sqrt()
    }

    /// The law below the belt speed (`v < vd`), continued smoothly beyond
    /// it, and its slope.
    fn below(&self, v: f64) -> (f64, f64) {
        let e = (-(self.vd - v) / Self::V0).exp();
        (
            -(Self::MUD + (Self::MUS - Self::MUD) * e),
            -(Self::MUS - Self::MUD) / Self::V0 * e,
        )
    }

    /// `[x, v, ∫ trace]'` while slipping below the belt speed.
    fn field(&self, y: &[f64; 3]) -> [f64; 3] {
        let (f, df) = self.below(y[1]);
        [
            y[1],
            -self.two_d() * y[1] - Self::C * y[0] - f,
            -self.two_d() - df,
        ]
    }

    /// Slip from `y` until `event(y)` turns from positive to non-positive
    /// (after `skip` of time, so that a start on the event does not count):
    /// the time taken and the state there. Fixed steps of `h`; the event is
    /// located by bisection on one-step solutions from the step's start.
    /// Also the largest velocity at the steps' ends.
    fn slip_until(&self, y: [f64; 3], event: impl Fn(&[f64; 3]) -> f64) -> (f64, [f64; 3], f64) {
        let h = 2e-3;
        let f = |_: f64, y: &[f64; 3]| self.field(y);
        let (mut t, mut y) = (0.0, y);
        let mut armed = event(&y) > 0.0;
        let mut top = y[1];
        for _ in 0..10_000_000 {
            let next = dopri::step(f, t, y, h).y;
            top = top.max(next[1]);
            if armed && event(&next) <= 0.0 {
                let (mut a, mut b) = (0.0, h);
                for _ in 0..200 {
                    let m = 0.5 * (a + b);
                    if event(&dopri::step(f, t, y, m).y) > 0.0 {
                        a = m;
                    } else {
                        b = m;
                    }
                    if b - a <= 1e-17 {
                        break;
                    }
                }
                let s = 0.5 * (a + b);
                return (t + s, dopri::step(f, t, y, s).y, top);
            }
            armed |= event(&next) > 0.0;
            t += h;
            y = next;
        }
        panic!("no event from {y:?}");
    }

    /// The return to `v = 0` downwards from `(x, 0)` without reaching the
    /// belt speed: the new `x`, the time, `∮ trace`, and the largest
    /// velocity on the way.
    fn slip_return(&self, x: f64) -> (f64, f64, f64, f64) {
        let (t, y, top) = self.slip_until([x, 0.0, 0.0], |y| y[1]);
        (y[0], t, y[2], top)
    }
}

/// The model file, as its smooth model.
fn belt_file() -> ModelRef {
    ModelRef::File {
        path: PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("examples/belt.ssm"),
        scene: None,
    }
}

/// The cycle through the section near a point, by shooting.
type CycleNear<'a> = &'a dyn Fn(f64) -> Option<SmoothCycle>;
/// What `settle` reaches from `(x, v)`.
type SettleFrom<'a> = &'a dyn Fn(f64, f64) -> SmoothSettled;

/// Run `f` with the smooth model of `examples/belt.ssm` at `vd`.
fn with_belt<T>(vd: f64, f: impl Fn(CycleNear, SettleFrom) -> T) -> T {
    struct Visit<F>(f64, F);
    impl<T, F: Fn(CycleNear, SettleFrom) -> T> ModelVisitor for Visit<F> {
        type Output = T;
        fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<T> {
            let p = base
                .with_pairs(M::identity(&base), &[("vd", self.0)])
                .unwrap();
            let map = ReturnMap::<M>::new(p, 1e-12).unwrap();
            let cycle = |x: f64| map.cycle(x).unwrap();
            let from =
                move |x: f64, v: f64| settle::<M>(p, (x, v), SmoothOptions::default()).unwrap();
            Some((self.1)(&cycle, &from))
        }
    }
    belt_file().visit(Visit(vd, f)).unwrap().unwrap()
}

#[test]
fn the_unstable_slip_cycle_matches_an_independent_integrator() {
    let vd = 1.4;
    let belt = Belt { vd };
    let rest = -belt.below(0.0).0 / Belt::C;
    // The independent return map's fixed point: bracket by a scan, then
    // bisection on P(x) − x.
    let g = |x: f64| belt.slip_return(x).0 - x;
    let xs: Vec<f64> = (1..40).map(|i| rest + 0.04 * i as f64).collect();
    let k = (1..xs.len())
        .find(|&i| g(xs[i - 1]) < 0.0 && g(xs[i]) > 0.0)
        .expect("a sign change of P(x) − x: the unstable cycle");
    let (mut a, mut b) = (xs[k - 1], xs[k]);
    for _ in 0..80 {
        let m = 0.5 * (a + b);
        if g(m) < 0.0 {
            a = m;
        } else {
            b = m;
        }
    }
    let x_ref = 0.5 * (a + b);
    let (_, period_ref, trace, top) = belt.slip_return(x_ref);
    let multiplier_ref = trace.exp();
    assert!(multiplier_ref > 1.0, "unstable: {multiplier_ref}");
    // It never reaches the belt speed (else the formula would not hold).
    assert!(top < 0.99 * vd, "{top}");

    let cycle = with_belt(vd, |cycle, _| cycle(x_ref + 1e-3).expect("the cycle"));
    assert_eq!(cycle.stick, 0.0);
    assert!(cycle.events.is_empty(), "{:?}", cycle.events);
    assert_eq!(cycle.verdict, Verdict::Unstable);
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(rel(cycle.x, x_ref) < 1e-10, "{} vs {x_ref}", cycle.x);
    assert!(
        rel(cycle.period, period_ref) < 1e-10,
        "{} vs {period_ref}",
        cycle.period
    );
    assert!(
        rel(cycle.multiplier, multiplier_ref) < 1e-8,
        "{} vs {multiplier_ref}",
        cycle.multiplier
    );
}

#[test]
fn the_stick_slip_cycle_matches_the_cycle_built_from_the_stick_end() {
    for vd in [0.5, 1.0, 1.4] {
        let belt = Belt { vd };
        // The stick ends where the spring and damper overcome the static
        // bound: −2 d vd − c x = −μs (the mass has been carried forward).
        let x_end = (Belt::MUS - belt.two_d() * vd) / Belt::C;
        // Slip (below the belt speed) until the velocity returns to vd.
        let (slip, arrival, _) = belt.slip_until([x_end, vd, 0.0], |y| vd - y[1]);
        // The force that must hold the mass there is within the bound: it sticks.
        let fnf = -belt.two_d() * vd - Belt::C * arrival[0];
        assert!(fnf.abs() < Belt::MUS, "{vd}: {fnf}");
        let stick = (x_end - arrival[0]) / vd;
        // The largest x: v = 0 downwards on the way.
        let (_, top, _) = belt.slip_until([x_end, vd, 0.0], |y| y[1]);

        let cycle = with_belt(vd, |cycle, _| cycle(top[0]).expect("the cycle"));
        let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
        assert!(
            rel(cycle.stick, stick) < 1e-10,
            "{vd}: {} vs {stick}",
            cycle.stick
        );
        assert!(
            rel(cycle.period, slip + stick) < 1e-10,
            "{vd}: {} vs {}",
            cycle.period,
            slip + stick
        );
        assert!(
            rel(cycle.x, top[0]) < 1e-10,
            "{vd}: {} vs {}",
            cycle.x,
            top[0]
        );
        assert_eq!(cycle.multiplier, 0.0);
        assert_eq!(cycle.verdict, Verdict::Stable);
        // One stick per period: its onset and its end.
        assert_eq!(cycle.events.len(), 2, "{:?}", cycle.events);
    }
}

#[test]
fn settle_reaches_either_attractor_of_the_bistable_window() {
    with_belt(1.4, |_, from| {
        match from(0.0, 0.0) {
            SmoothSettled::SteadySliding { equilibrium, .. } => {
                assert_eq!(equilibrium.verdict, Verdict::Stable);
                assert!((equilibrium.x - 0.5 * (1.0 + (-2.8f64).exp())).abs() < 1e-12);
            }
            other => panic!("{other:?}"),
        }
        match from(3.0, 0.0) {
            SmoothSettled::Cycle { cycle, .. } => assert!(cycle.stick > 0.0, "{cycle:?}"),
            other => panic!("{other:?}"),
        }
    });
    // Below the Hopf point only the cycle is left; above the fold, only rest.
    with_belt(1.0, |_, from| {
        assert!(matches!(from(0.5, 0.0), SmoothSettled::Cycle { .. }));
    });
    with_belt(2.5, |_, from| {
        assert!(matches!(
            from(3.0, 0.0),
            SmoothSettled::SteadySliding { .. }
        ));
    });
}

/// `stickslip simulate ARGS…`: status, stdout, stderr.
fn simulate(args: &[&str]) -> (bool, String, String) {
    let out = std::process::Command::new(env!("CARGO_BIN_EXE_stickslip"))
        .arg("simulate")
        .args(args)
        .output()
        .expect("runs");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
        String::from_utf8_lossy(&out.stderr).into_owned(),
    )
}

#[test]
fn simulate_takes_the_smooth_law_itself() {
    let file = belt_file().to_string();
    // From rest in the bistable window: steady sliding, named, with its
    // eigenvalues; from far out: the stick-slip cycle, as the library has it.
    let (ok, text, err) = simulate(&["--model-file", &file, "--set", "vd=1.4"]);
    assert!(ok, "{err}");
    assert!(
        text.contains("steady sliding at x = 0.530405031313") && text.contains("stable"),
        "{text}"
    );
    let (ok, json, err) = simulate(&[
        "--model-file",
        &file,
        "--set",
        "vd=1.4",
        "--from",
        "3,0,0",
        "--json",
    ]);
    assert!(ok, "{err}");
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(v["kind"], "cycle");
    let lib = with_belt(1.4, |cycle, _| cycle(2.1).expect("the cycle"));
    // The same cycle, reached from another section point (rounding only).
    let near = |k: &str, want: f64| (v["cycle"][k].as_f64().unwrap() - want).abs() <= 1e-12 * want;
    assert!(
        near("period", lib.period) && near("stick", lib.stick),
        "{json} {lib:?}"
    );
    assert_eq!(v["cycle"]["multiplier"].as_f64().unwrap(), 0.0);
    // Overdamped: no turning point at all, yet steady sliding is reached.
    let (ok, text, err) = simulate(&["--model-file", &file, "--set", "zeta=3"]);
    assert!(
        ok && text.contains("steady sliding") && text.contains("stable"),
        "{text}{err}"
    );
    // A figure needs a piecewise scene: a clear error, naming what to do.
    let svg = std::env::temp_dir().join("smooth_cycle_refused.svg");
    let (ok, _, err) = simulate(&["--model-file", &file, "--plot", svg.to_str().unwrap()]);
    assert!(
        !ok && err.contains("--plot") && err.contains("--scene"),
        "{err}"
    );
}

#[test]
fn simulate_settles_the_forced_smooth_law_on_a_fixed_point_of_its_period_map() {
    use stickslip::dynamics::integrate::{Integrator, Side, State};
    use stickslip::models::stribeck::{Params, Stribeck};
    let (ok, json, err) = simulate(&["--model", "stribeck", "--json"]);
    assert!(ok, "{err}");
    let m: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert_eq!(m["periods"], 1);
    assert_eq!(m["sticks"], true);
    assert_eq!(m["verdict"], "stable");
    // The trade reference's motion: three events at the belt speed a cycle.
    assert_eq!(m["events"].as_array().unwrap().len(), 3, "{json}");
    // A stick collapses a direction: one multiplier is 0.
    assert_eq!(m["multipliers"][1][0].as_f64().unwrap(), 0.0);
    // The state returns after one period under the integrator at another
    // tolerance.
    let f = |k: &str| m[k].as_f64().unwrap();
    let p = Params::default();
    let integ = Integrator::<Stribeck>::new(p, 1e-10).unwrap();
    let side = if f("v") > integ.belt() {
        Side::Above
    } else {
        Side::Below
    };
    let start = State {
        phase: f("phase"),
        x: f("x"),
        v: f("v"),
        side,
    };
    let end = integ.period_map(start, 1).unwrap();
    assert!(
        (end.x - start.x).abs() < 1e-8 && (end.v - start.v).abs() < 1e-8,
        "{start:?} -> {end:?}"
    );
}

/// `sweep_law` of `examples/belt.ssm` along `vd`.
fn law_sweep(from: f64, to: f64, count: usize) -> stickslip::study::law::LawSweep {
    struct Visit(f64, f64, usize);
    impl ModelVisitor for Visit {
        type Output = stickslip::study::law::LawSweep;
        fn smooth<M: SmoothModel>(self, base: M::Params) -> Option<Self::Output> {
            Some(stickslip::study::law::sweep_law::<M>(base, "vd", self.0, self.1, self.2).unwrap())
        }
    }
    belt_file().visit(Visit(from, to, count)).unwrap().unwrap()
}

#[test]
fn the_law_swept_has_the_hopf_point_the_bistable_window_and_the_fold() {
    let s = law_sweep(0.2, 3.0, 15);
    let hopf = -0.5 * (0.1f64).ln();
    assert_eq!(s.changes.len(), 1);
    assert!((s.changes[0].change.at - hopf).abs() <= 1e-9 * hopf);
    assert_eq!(s.stick_slip.len(), 1, "{:?}", s.stick_slip);
    let fold = s.stick_slip[0].at;
    assert!(s.stick_slip[0].below && fold > hopf);
    for p in &s.points {
        let e = p.rest.equilibrium.as_ref().expect("steady sliding");
        let kinds: Vec<(bool, Verdict)> = p
            .cycles
            .iter()
            .map(|c| (c.stick > 0.0, c.verdict))
            .collect();
        let v = p.rest.value;
        if v < hopf {
            // Unstable steady sliding inside the stable stick-slip cycle.
            assert_eq!(e.verdict, Verdict::Unstable);
            assert_eq!(kinds, [(true, Verdict::Stable)], "{v}");
        } else if v < fold {
            // The bistable window: the unstable slip cycle separates them.
            assert_eq!(e.verdict, Verdict::Stable);
            assert_eq!(
                kinds,
                [(false, Verdict::Unstable), (true, Verdict::Stable)],
                "{v}"
            );
            assert!(p.cycles[0].x > e.x && p.cycles[0].multiplier > 1.0);
        } else {
            assert_eq!(e.verdict, Verdict::Stable);
            assert!(kinds.is_empty(), "{v}: {kinds:?}");
        }
    }
}

#[test]
fn the_slip_cycle_is_born_at_the_hopf_point_with_square_root_amplitude() {
    // Subcritical: x − x* on the section grows as sqrt(vd − vd*).
    let hopf = -0.5 * (0.1f64).ln();
    let s = law_sweep(hopf + 0.0025, hopf + 0.01, 2);
    let amplitude = |i: usize| {
        let p = &s.points[i];
        let slip = p
            .cycles
            .iter()
            .find(|c| c.stick == 0.0)
            .expect("the slip cycle");
        slip.x - p.rest.equilibrium.as_ref().unwrap().x
    };
    let ratio = amplitude(1) / amplitude(0);
    assert!((ratio - 2.0).abs() < 0.05, "{ratio}");
}

#[test]
fn the_located_fold_of_the_law_is_confirmed_by_the_independent_integrator() {
    let fold = law_sweep(1.7, 1.9, 3).stick_slip[0].at;
    // From the stick's end the motion slips, turns on v = 0, and on its
    // next swing reaches the belt speed again (sticks) below the fold and
    // falls short above it.
    for (vd, sticks) in [(fold * (1.0 - 1e-3), true), (fold * (1.0 + 1e-3), false)] {
        let belt = Belt { vd };
        let x_end = (Belt::MUS - belt.two_d() * vd) / Belt::C;
        let (_, turn, _) = belt.slip_until([x_end, vd, 0.0], |y| y[1]);
        let (_, _, _, top) = belt.slip_return(turn[0]);
        assert_eq!(top >= vd, sticks, "{vd}: top {top}");
    }
    // And by the library's own simulation from far out.
    with_belt(fold * (1.0 - 1e-3), |_, from| {
        assert!(matches!(from(3.0, 0.0), SmoothSettled::Cycle { .. }));
    });
    with_belt(fold * (1.0 + 1e-3), |_, from| {
        assert!(matches!(
            from(3.0, 0.0),
            SmoothSettled::SteadySliding { .. }
        ));
    });
}

//! What the fuzz targets do with their bytes, shared by the cargo-fuzz
//! targets (`fuzz/fuzz_targets/`) and by the main workspace's bounded smoke
//! test (`tests/fuzz_smoke.rs`), which replays `fuzz/seeds/` and random
//! inputs under `cargo test`. Depends on `stickslip` and `stickslip-codegen`
//! only.
//!
//! Besides "no panic, no hang", each entry point is held to what it promises:
//! a rejected model's report locates every error in `fuzz.ssm`;
//! `Simulator::new` fails exactly when `ParamSet::check` does; `start` fails
//! exactly on a non-finite state; simulated events come in order at finite
//! phases; a Newton solution reported admissible has finite points; the
//! run-time back end accepts exactly what the checks accept, and its
//! machine code returns at any point.

#![allow(dead_code)]

use stickslip::dynamics::simulate::{SimOptions, Simulator, MAX_STEPS_PER_PERIOD};
use stickslip::model::Model;
use stickslip::models::{coulomb, paper, stribeck8};
use stickslip::orbit::attractor::{self, AttractorOptions};
use stickslip::orbit::motion;
use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
use stickslip::orbit::structure::Structure;
use stickslip::ParamSet;

const TAU: f64 = std::f64::consts::TAU;

/// The bytes as a model file (invalid UTF-8 replaced): see [`model_text`].
pub fn model_source(data: &[u8]) {
    model_text(&String::from_utf8_lossy(data));
}

/// A model file's text through `check_source`, the entry point of
/// `stickslip check`, `build.rs` and `model!(file = ...)`. The generator must
/// return code that parses as a Rust file, or a report whose every error is
/// located in `fuzz.ssm` (a line of the file, a column within it or just
/// past its end) and rendered as rustc renders (`error: MESSAGE`,
/// `--> fuzz.ssm:LINE:COL`, the source line, a caret).
pub fn model_text(source: &str) {
    match stickslip_codegen::check_source(source, "fuzz.ssm") {
        Ok(generated) => {
            assert!(!generated.code.is_empty());
            if let Err(e) = syn::parse_file(&generated.code) {
                panic!(
                    "generated code does not parse ({e}):\n{}\nfrom:\n{source}",
                    generated.code
                );
            }
        }
        Err(report) => {
            let rendered = report.render();
            assert!(
                rendered.ends_with(" in fuzz.ssm\n"),
                "no count line:\n{rendered}"
            );
            assert!(!report.errors.is_empty(), "a report without an error");
            let lines: Vec<&str> = source.lines().collect();
            for e in &report.errors {
                assert!(
                    !e.message.starts_with("internal error"),
                    "the generator panicked: {}\non:\n{source}",
                    e.message
                );
                let at = e
                    .position
                    .unwrap_or_else(|| panic!("unlocated error `{}` in:\n{rendered}", e.message));
                assert!(
                    at.line >= 1 && at.line <= lines.len() + 1,
                    "error on line {} of a {}-line file: `{}`",
                    at.line,
                    lines.len(),
                    e.message
                );
                let width = lines.get(at.line - 1).map_or(0, |l| l.chars().count());
                assert!(
                    at.column >= 1 && at.column <= width + 1,
                    "column {} on a line of {width} characters: `{}`",
                    at.column,
                    e.message
                );
                let arrow = format!(
                    "{:w$}--> fuzz.ssm:{}:{}\n",
                    "",
                    at.line,
                    at.column,
                    w = at.line.to_string().len()
                );
                let head = format!("error: {}\n{arrow}", e.message);
                assert!(
                    e.rendered.starts_with(&head),
                    "not rendered as rustc does:\n{}",
                    e.rendered
                );
                assert!(rendered.contains(&e.rendered));
            }
        }
    }
}

/// A model file's text through the run-time back end, as `--model-file` and
/// `Model.from_source` load it (`jit::compile_text`; compiled, called,
/// freed, so that memory stays bounded over a long run). It must accept
/// exactly what `check_source` accepts, fail with the same report where
/// that rejects, and compile the model and each of its scenes to functions
/// that return (whatever the numbers) when called at points from `r`, NaN
/// and infinities included.
pub fn model_loaded(source: &str, r: &mut Bytes<'_>) {
    use stickslip::model::loaded::routines::ROUTINES;
    use stickslip_codegen::jit::{compile_text, Compiled};
    let checked = stickslip_codegen::check_source(source, "fuzz.ssm");
    let mut scenes: Vec<Option<String>> = vec![None];
    if let Ok(generated) = &checked {
        scenes.extend(
            generated
                .instances
                .iter()
                .filter_map(|i| i.name.split_once("::").map(|(_, s)| Some(s.to_string()))),
        );
    }
    for scene in scenes {
        let compiled = compile_text(source, "fuzz.ssm", None, scene.as_deref(), &ROUTINES);
        match (&checked, compiled) {
            (Err(report), Err(loaded)) => assert_eq!(
                report, &loaded,
                "the run-time back end reports otherwise than check:\n{source}"
            ),
            (Err(report), Ok(_)) => panic!(
                "the run-time back end compiled a model check rejects ({}):\n{source}",
                report.render()
            ),
            (Ok(_), Err(loaded)) => panic!(
                "the run-time back end rejects a model check accepts ({}):\n{source}",
                loaded.render()
            ),
            (Ok(_), Ok(Compiled::Piecewise { instance, code, .. })) => {
                let defaults: Vec<f64> = instance
                    .free
                    .iter()
                    .map(|&i| instance.params[i].default)
                    .collect();
                let p: Vec<f64> = defaults.iter().map(|&d| r.f64(d)).collect();
                let m = &code.machine;
                for _ in 0..4 {
                    let a: [f64; 8] = std::array::from_fn(|_| r.f64(1.0));
                    let mut out2 = [0.0; 2];
                    let mut out10 = [0.0; 10];
                    for &f in &code.flows {
                        m.call(f, &p, &[a[0], a[1], a[2], a[3]], &mut out2);
                    }
                    for &f in &code.fields {
                        m.call(f, &p, &[a[0], a[1], a[2]], &mut out2);
                    }
                    for (&res, &map) in code.residuals.iter().zip(&code.mappings) {
                        m.call(res, &p, &a, &mut out2);
                        m.call(map, &p, &a, &mut out10);
                    }
                    if let Some(s) = code.stick {
                        let mut out5 = [0.0; 5];
                        m.call(s.forces, &p, &[a[0], a[1]], &mut out5);
                    }
                }
                let (mut out1, mut out3, mut out5) = ([0.0; 1], [0.0; 3], [0.0; 5]);
                for &f in &code.coefficients {
                    m.call(f, &p, &[], &mut out3);
                }
                for &f in &code.velocities {
                    m.call(f, &p, &[], &mut out1);
                }
                m.call(code.oscillator, &p, &[], &mut out5);
                m.call(code.conditions, &p, &[], &mut out3);
                // Too few parameter values: NaN, nothing read.
                m.call(
                    code.oscillator,
                    &p[..p.len().saturating_sub(1)],
                    &[],
                    &mut out5,
                );
                assert!(p.is_empty() || out5.iter().all(|v| v.is_nan()));
            }
            (Ok(_), Ok(Compiled::Smooth { smooth, code })) => {
                let p: Vec<f64> = smooth.params.iter().map(|d| r.f64(d.default)).collect();
                let m = &code.machine;
                let (mut out1, mut out2) = ([0.0; 1], [0.0; 2]);
                for _ in 0..4 {
                    m.call(code.kinetic, &p, &[r.f64(1.0)], &mut out2);
                }
                m.call(code.belt, &p, &[], &mut out1);
                m.call(code.bound, &p, &[], &mut out1);
            }
        }
    }
}

/// Reads the fuzz input; past its end every read is 0, which selects the
/// default of each choice (so the empty input runs the paper model at its
/// defaults, from rest).
pub struct Bytes<'a> {
    data: &'a [u8],
    pos: usize,
}

impl<'a> Bytes<'a> {
    pub fn new(data: &'a [u8]) -> Self {
        Self { data, pos: 0 }
    }

    pub fn byte(&mut self) -> u8 {
        let b = self.data.get(self.pos).copied().unwrap_or(0);
        self.pos += 1;
        b
    }

    fn bits(&mut self) -> u64 {
        let mut out = 0u64;
        for _ in 0..8 {
            out = (out << 8) | self.byte() as u64;
        }
        out
    }

    /// A value near `default` or anywhere: the default, a relative
    /// perturbation, a power-of-two rescaling (either sign, 2^-128..2^127),
    /// a special value (0, -0, NaN, ±inf, tiny, huge), raw bits, or a small
    /// multiple of 1/16.
    pub fn f64(&mut self, default: f64) -> f64 {
        const SPECIAL: [f64; 14] = [
            0.0,
            -0.0,
            f64::NAN,
            f64::INFINITY,
            f64::NEG_INFINITY,
            f64::MIN_POSITIVE,
            5e-324,
            f64::MAX,
            f64::MIN,
            f64::EPSILON,
            1e-12,
            1e12,
            1.0,
            -1.0,
        ];
        let sel = self.byte();
        match sel % 6 {
            0 => default,
            1 => default * (1.0 + (self.byte() as i8) as f64 / 256.0),
            2 => {
                let sign = if sel & 0x80 != 0 { -1.0 } else { 1.0 };
                sign * default * 2f64.powi((self.byte() as i8) as i32)
            }
            3 => SPECIAL[self.byte() as usize % SPECIAL.len()],
            4 => f64::from_bits(self.bits()),
            _ => (self.byte() as i8) as f64 / 16.0,
        }
    }
}

/// The largest number of event-search steps per forcing period over the
/// domains (the step rule of `Simulator::next_event`).
fn steps_per_period<M: Model>(p: &M::Params) -> f64 {
    let w = M::oscillator(p).frequency;
    (0..M::info(p).domains.len())
        .map(|j| {
            let co = M::coefficients(p, j);
            let step = std::f64::consts::FRAC_PI_4
                .min(w * 0.5 / (co.c.abs().sqrt() + 0.5 * co.two_d.abs()));
            TAU / step
        })
        .fold(0.0, f64::max)
}

/// The bytes as parameters, states, structures and guesses for one of the
/// built-in models (the paper model, Coulomb, the 8-piece Stribeck model, and
/// the paper's `reference` scene, whose constants are folded at build time).
pub fn runtime(data: &[u8]) {
    let mut r = Bytes::new(data);
    match r.byte() % 4 {
        0 => exercise::<paper::Paper>(&mut r),
        1 => exercise::<coulomb::Coulomb>(&mut r),
        2 => exercise::<stribeck8::Stribeck8>(&mut r),
        _ => exercise::<paper::reference::Reference>(&mut r),
    }
}

/// Work per input is bounded: at most 400 events per simulated run, 4
/// forcing periods for `run`, 12 for `attractor::find`, 30 Newton iterations.
fn exercise<M: Model>(r: &mut Bytes)
where
    M::Params: Default,
{
    let mut p = M::Params::default();
    for i in 0..p.names().len() {
        let value = r.f64(p.get(i));
        p.set(i, value);
    }
    let checked = p.check();
    let opts = SimOptions {
        graze_tol: 1e-10,
        max_events: 400,
    };
    let sim = match Simulator::<M>::new(p, opts) {
        Ok(sim) => {
            assert!(
                checked.is_ok(),
                "Simulator::new accepted {p:?}: {checked:?}"
            );
            sim
        }
        Err(e) => {
            assert!(
                checked.is_err(),
                "Simulator::new rejected checked {p:?}: {e}"
            );
            return;
        }
    };

    // The event search walks about `steps_per_period` steps per forcing
    // period (refused above `MAX_STEPS_PER_PERIOD`, a typed error). Between a
    // few hundred thousand and that limit a run is slow but finite: such
    // inputs stop here, to keep the work per input bounded.
    let steps = steps_per_period::<M>(&p);
    if steps > 2e5 && steps <= MAX_STEPS_PER_PERIOD {
        return;
    }

    // A bounded simulation from an arbitrary state.
    let (x, v, phase) = (r.f64(0.0), r.f64(0.0), r.f64(0.0));
    let finite = x.is_finite() && v.is_finite() && phase.is_finite();
    match sim.start(x, v, phase) {
        Ok(seg) => {
            assert!(finite);
            let end = phase + (1 + r.byte() % 4) as f64 * TAU;
            let mut last = phase;
            let _ = sim.run(seg, end, |e| {
                assert!(
                    e.phase.is_finite() && e.x.is_finite() && e.v.is_finite(),
                    "{e:?}"
                );
                assert!(
                    e.phase >= last,
                    "events out of order: {e:?} after phase {last}"
                );
                last = e.phase;
            });
        }
        Err(_) => assert!(!finite, "start rejected a finite state ({x}, {v}, {phase})"),
    }

    // A structure (mostly well-formed, sometimes arbitrary text) solved by
    // Newton from an arbitrary guess.
    let info = M::info(&p);
    let names = info.mapping_names();
    let text = if r.byte() % 8 == 7 {
        let n = r.byte() % 24;
        let raw: Vec<u8> = (0..n).map(|_| r.byte()).collect();
        String::from_utf8_lossy(&raw).into_owned()
    } else {
        let n = 1 + r.byte() as usize % 6;
        (0..n)
            .map(|_| names[r.byte() as usize % names.len()])
            .collect::<Vec<_>>()
            .join(" ")
    };
    let periods = (r.byte() % 4) as u32;
    if let Ok(structure) = Structure::parse(info, &text, periods) {
        let m = structure.len();
        let guess: Vec<SwitchingPoint> = (0..m)
            .map(|k| SwitchingPoint {
                phase: r.f64(TAU * periods as f64 * k as f64 / m as f64),
                x: r.f64(0.0),
            })
            .collect();
        let newton = NewtonOptions {
            tolerance: 1e-12,
            max_iterations: 1 + r.byte() as usize % 30,
        };
        let motion = motion::solve(&sim, structure.clone(), guess, newton);
        if motion.is_admissible() {
            assert!(
                motion
                    .points
                    .iter()
                    .all(|q| q.phase.is_finite() && q.x.is_finite()),
                "an admissible motion with non-finite points: {motion:?}"
            );
        }
        // Seeding simulates 200 forcing periods from each of 24 starts.
        if r.byte() % 8 == 1 && steps <= 2e3 {
            let _ = attractor::seed(&sim, &structure);
        }
    }

    // The steady state from another arbitrary start, briefly.
    let (x, v, phase) = (r.f64(0.0), r.f64(0.0), r.f64(0.0));
    if let Ok(seg) = sim.start(x, v, phase) {
        let opts = AttractorOptions {
            max_periods: 1 + (r.byte() % 12) as u32,
            max_cycle: Some(1 + r.byte() as usize % 12),
            newton: NewtonOptions {
                tolerance: 1e-12,
                max_iterations: 30,
            },
        };
        let _ = attractor::find(&sim, seg, opts);
    }
}

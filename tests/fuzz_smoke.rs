//! The fuzz targets under `cargo test`, bounded (a few seconds): the same
//! harness as `fuzz/fuzz_targets/` (`fuzz/harness.rs`), fed
//!
//! * every file of `fuzz/seeds/` (the seed corpora, and any input a fuzzing
//!   run found to crash, kept there as a regression);
//! * random inputs from proptest (fixed seed, fixed case counts): byte
//!   strings, soups of the model language's tokens, and mutations of the
//!   shipped models for the generator; byte strings for the runtime entry
//!   points (parameters, states, structures and guesses decoded from them).
//!
//! The harness asserts that nothing panics, that a rejected model's report
//! locates every error, and that the runtime entry points agree with each
//! other (see `fuzz/harness.rs`). Real fuzzing: README, "Bad input".

use std::path::Path;

use proptest::prelude::*;
use proptest::test_runner::RngSeed;

#[path = "../fuzz/harness.rs"]
mod harness;

#[path = "../fuzz/grammar.rs"]
mod grammar;

fn config(cases: u32) -> ProptestConfig {
    ProptestConfig {
        cases,
        failure_persistence: None,
        rng_seed: RngSeed::Fixed(0xf022_5eed),
        max_shrink_iters: 400,
        ..ProptestConfig::default()
    }
}

/// Every file of `fuzz/seeds/NAME/`, with its name.
fn seeds(name: &str) -> Vec<(String, Vec<u8>)> {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("fuzz/seeds")
        .join(name);
    let mut out: Vec<(String, Vec<u8>)> = std::fs::read_dir(&dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|entry| {
            let path = entry.expect("directory entry").path();
            let bytes = std::fs::read(&path).expect("read a seed");
            (path.display().to_string(), bytes)
        })
        .collect();
    out.sort();
    out
}

#[test]
fn model_source_seeds() {
    let seeds = seeds("model_source");
    assert!(seeds.len() >= 30, "the seed corpus is missing");
    for (name, bytes) in seeds {
        eprintln!("{name}");
        harness::model_source(&bytes);
    }
}

#[test]
fn model_grammar_seeds() {
    let seeds = seeds("model_grammar");
    assert!(seeds.len() >= 4, "the seed corpus is missing");
    for (name, bytes) in seeds {
        eprintln!("{name}");
        grammar::model_grammar(&bytes);
    }
}

/// The grammar target reaches the generator's back end: of 60 random
/// inputs, some build (code that parses as Rust) and some are rejected.
#[test]
fn model_grammar_builds_some_models_and_rejects_others() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(0x5eed);
    let (mut built, mut rejected) = (0, 0);
    for _ in 0..60 {
        let n = rng.gen_range(0..600);
        let bytes: Vec<u8> = (0..n).map(|_| rng.gen()).collect();
        let text = grammar::model_from_bytes(&bytes);
        match stickslip_codegen::check_source(&text, "fuzz.ssm") {
            Ok(_) => built += 1,
            Err(_) => rejected += 1,
        }
        grammar::model_grammar(&bytes);
    }
    eprintln!("built {built}, rejected {rejected}");
    assert!(
        built >= 20 && rejected >= 20,
        "built {built}, rejected {rejected}"
    );
}

#[test]
fn model_jit_seeds() {
    let seeds = seeds("model_jit");
    assert!(seeds.len() >= 4, "the seed corpus is missing");
    for (name, bytes) in seeds {
        eprintln!("{name}");
        grammar::model_jit(&bytes);
    }
}

/// The run-time back end on random grammar inputs: it compiles some (and
/// calls their code) and rejects others, always as `check_source` does.
#[test]
fn model_jit_compiles_some_models_and_rejects_others() {
    use rand::{Rng, SeedableRng};
    let mut rng = rand::rngs::StdRng::seed_from_u64(0x0046);
    let (mut compiled, mut rejected) = (0, 0);
    for _ in 0..40 {
        let n = rng.gen_range(0..600);
        let bytes: Vec<u8> = (0..n).map(|_| rng.gen()).collect();
        let text = grammar::model_from_bytes(&bytes);
        match stickslip_codegen::check_source(&text, "fuzz.ssm") {
            Ok(_) => compiled += 1,
            Err(_) => rejected += 1,
        }
        grammar::model_jit(&bytes);
    }
    eprintln!("compiled {compiled}, rejected {rejected}");
    assert!(
        compiled >= 10 && rejected >= 10,
        "compiled {compiled}, rejected {rejected}"
    );
}

#[test]
fn runtime_params_seeds() {
    let seeds = seeds("runtime_params");
    assert!(!seeds.is_empty(), "the seed corpus is missing");
    for (name, bytes) in seeds {
        eprintln!("{name}");
        harness::runtime(&bytes);
    }
}

/// Pieces of the model language, for token soups.
const TOKENS: &[&str] = &[
    "model",
    "bad",
    "param",
    "let",
    "oscillator",
    "law",
    "boundary",
    "domain",
    "scene",
    "stick",
    "free",
    "structures",
    "pieces",
    "mass",
    "damping",
    "stiffness",
    "forcing",
    "frequency",
    "belt",
    "range",
    "kinetic",
    "v",
    "m",
    "W",
    "mu",
    "Sigma1",
    "Sigma2",
    "Sigma10",
    "Tau",
    "0",
    "1",
    "2",
    "-1",
    "0.5",
    "1e400",
    "1e-300",
    "2147483647",
    "\"1_11 0_11\"",
    "\"\"",
    "exp",
    "ln",
    "sqrt",
    "sin",
    "cos",
    "abs",
    "sign",
    "powi",
    "=",
    "=>",
    ">",
    ">=",
    "<",
    "<=",
    "+",
    "-",
    "*",
    "/",
    "%",
    ",",
    ";",
    ":",
    "::",
    "(",
    ")",
    "{",
    "}",
    "[",
    "]",
    "#",
    "!",
    "///",
    "//!",
    "\n",
    "'",
    "\"",
];

fn token_soup() -> impl Strategy<Value = String> {
    prop::collection::vec(prop::sample::select(TOKENS), 0..120).prop_map(|t| t.join(" "))
}

/// One edit of a model's text: delete, insert a byte, insert a token, or
/// duplicate a stretch.
#[derive(Clone, Debug)]
enum Edit {
    Delete(prop::sample::Index, u8),
    Byte(prop::sample::Index, u8),
    Token(prop::sample::Index, &'static str),
    Duplicate(prop::sample::Index, u8),
}

fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<prop::sample::Index>(), 1..16u8).prop_map(|(i, n)| Edit::Delete(i, n)),
        (any::<prop::sample::Index>(), any::<u8>()).prop_map(|(i, b)| Edit::Byte(i, b)),
        (any::<prop::sample::Index>(), prop::sample::select(TOKENS))
            .prop_map(|(i, t)| Edit::Token(i, t)),
        (any::<prop::sample::Index>(), 1..64u8).prop_map(|(i, n)| Edit::Duplicate(i, n)),
    ]
}

fn mutate(source: &str, edits: &[Edit]) -> Vec<u8> {
    let mut s = source.as_bytes().to_vec();
    for e in edits {
        let len = s.len().max(1);
        match e {
            Edit::Delete(i, n) => {
                let at = i.index(len).min(s.len());
                let end = (at + *n as usize).min(s.len());
                s.drain(at..end);
            }
            Edit::Byte(i, b) => s.insert(i.index(len).min(s.len()), *b),
            Edit::Token(i, t) => {
                let at = i.index(len).min(s.len());
                s.splice(at..at, t.bytes());
            }
            Edit::Duplicate(i, n) => {
                let at = i.index(len).min(s.len());
                let end = (at + *n as usize).min(s.len());
                let copy = s[at..end].to_vec();
                s.splice(at..at, copy);
            }
        }
    }
    s
}

const MODELS: [&str; 3] = [
    include_str!("../models/paper.ssm"),
    include_str!("../models/coulomb.ssm"),
    include_str!("../models/stribeck8.ssm"),
];

proptest! {
    #![proptest_config(config(1000))]

    #[test]
    fn model_source_random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..400)) {
        harness::model_source(&bytes);
    }

    #[test]
    fn model_source_token_soup(soup in token_soup()) {
        harness::model_source(soup.as_bytes());
    }

    #[test]
    fn model_source_token_soup_in_a_model(soup in token_soup()) {
        harness::model_source(format!("model m {{ {soup} }}").as_bytes());
    }
}

proptest! {
    #![proptest_config(config(40))]

    /// Each input is a whole model (a build's worth of work): fewer cases.
    #[test]
    fn model_grammar_random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..800)) {
        grammar::model_grammar(&bytes);
    }
}

proptest! {
    #![proptest_config(config(300))]

    #[test]
    fn model_source_mutated_models(
        which in 0..MODELS.len(),
        edits in prop::collection::vec(edit(), 1..6),
    ) {
        harness::model_source(&mutate(MODELS[which], &edits));
    }

    #[test]
    fn runtime_params_random_bytes(bytes in prop::collection::vec(any::<u8>(), 0..200)) {
        harness::runtime(&bytes);
    }
}

// ------------------------------------------------ regressions found by fuzzing

/// `runtime_params` input `[44, 44, 211]`: the paper model with `m = 5 · 2^-45`.
/// The laws divide by `m`, so `2 d_j` is about 1e12 and the event search's
/// step about 1e-12 in phase: one forcing period took ~5e12 steps (a hang).
/// Now a typed error at once.
#[test]
fn a_too_stiff_domain_is_a_typed_error_not_a_hang() {
    use stickslip::dynamics::simulate::{SimError, SimOptions, Simulator};
    use stickslip::models::paper::{Paper, Params};
    let p = Params {
        m: 5.0 * 2f64.powi(-45),
        ..Params::default()
    };
    let sim = Simulator::<Paper>::new(p, SimOptions::default()).expect("valid parameters");
    let seg = sim.start(0.0, 0.0, 0.0).expect("finite start");
    let started = std::time::Instant::now();
    let r = sim.run(seg, std::f64::consts::TAU, |_| {});
    assert!(
        matches!(&r, Err(SimError::Unresolvable { reason, .. }) if reason.contains("too stiff")),
        "{r:?}"
    );
    assert!(started.elapsed().as_secs_f64() < 1.0);
}

/// At a phase of 1e17 the phase's rounding (16) exceeds the event search's
/// step (at most π/4): the search could not advance and looped forever.
#[test]
fn a_phase_beyond_resolution_is_a_typed_error_not_a_hang() {
    use stickslip::dynamics::simulate::{SimError, SimOptions, Simulator};
    use stickslip::models::paper::{Paper, Params};
    let sim = Simulator::<Paper>::new(Params::default(), SimOptions::default()).expect("defaults");
    let seg = sim.start(0.0, 0.0, 1e17).expect("finite start");
    let r = sim.run(seg, 1e17 + 64.0, |_| {});
    assert!(
        matches!(&r, Err(SimError::Unresolvable { reason, .. }) if reason.contains("too large")),
        "{r:?}"
    );
}

/// `runtime_params` input `fuzz/seeds/runtime_params/regression-slow-admissibility`:
/// the paper's `reference` scene at `W = 3 · 2^49`, `Q0 = -5.8125`, where
/// Newton on `P_{3_33 3_33}` from a guess with a point at `W t = π · 2^50`
/// converges to points 3.5e15 apart. The admissibility check then searched
/// that whole span for events, π/4 at a time (a hang). A mapping longer than
/// the whole cycle is now a violation at once (another one takes negative time).
#[test]
fn a_solution_spanning_more_than_its_cycle_is_rejected_at_once() {
    use stickslip::dynamics::simulate::{SimOptions, Simulator};
    use stickslip::models::paper::reference::{Params, Reference};
    use stickslip::orbit::admissible::ViolationKind;
    use stickslip::orbit::periodic::{NewtonOptions, SwitchingPoint};
    use stickslip::orbit::structure::Structure;

    let p = Params {
        Q0: -5.8125,
        W: 3.0 * 2f64.powi(49),
    };
    let sim = Simulator::<Reference>::new(p, SimOptions::default()).expect("valid parameters");
    let structure = Structure::parse(Reference::INFO, "3_33 3_33", 1).expect("a structure");
    let guess = vec![
        SwitchingPoint { phase: 0.0, x: 0.0 },
        SwitchingPoint {
            phase: std::f64::consts::PI * 2f64.powi(50),
            x: 0.0,
        },
    ];
    let newton = NewtonOptions {
        tolerance: 1e-12,
        max_iterations: 21,
    };
    let started = std::time::Instant::now();
    let motion = stickslip::orbit::motion::solve(&sim, structure, guess, newton);
    assert!(started.elapsed().as_secs_f64() < 1.0);
    assert!(!motion.is_admissible());
    // Newton's step test is in natural units (phases in radians): here the
    // phases (~3.5e15) round to 0.5 rad, so Newton may stop as not converged
    // (rejected at once, the admissibility never reached); if it converges,
    // the mapping longer than the whole cycle is the violation.
    assert!(
        !motion.termination.converged()
            || motion.violations.iter().any(|v| {
                v.kind == ViolationKind::Duration && v.condition.contains("whole cycle")
            }),
        "{:?} {:#?}",
        motion.termination,
        motion.violations
    );
}

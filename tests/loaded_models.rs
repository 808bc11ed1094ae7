//! Loading a model at run time (`model::loaded`): a file the checks reject
//! fails with `stickslip check`'s report, word for word (that it never
//! reaches the run-time back end: `tests/loaded_rejected.rs`); the same text
//! is one model; scenes, the file's name, the parameter capacity and a
//! smooth law's scenes; a new friction law written now runs through the
//! analyses.

use std::path::{Path, PathBuf};

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::model::loaded::{
    content_hash, load_file, load_source, Loaded, LoadedModel, CAPACITY,
};
use stickslip::models::ModelRef;
use stickslip::orbit::attractor::{self, Attractor, AttractorOptions};
use stickslip::{Model, ModelVisitor, ParamSet};

fn models_dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("models")
}

fn tmp(name: &str, text: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("loaded_models");
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, text).expect("write");
    path
}

/// The paper model with its name, a bound and a domain's law broken.
fn broken_paper() -> String {
    std::fs::read_to_string(models_dir().join("paper.ssm"))
        .expect("paper.ssm")
        .replace("param mus = 0.5, >= 0;", "param mus = 0.5, >= zero;")
        .replace(
            "(-mu2 * (v - V) + FN * muk) / m",
            "(-mu2 * (v - V) + FN * muk) / mm",
        )
}

#[test]
fn a_rejected_file_fails_as_check_reports_it() {
    let path = tmp("paper.ssm", &broken_paper());
    let origin = path.display().to_string();
    let e = load_file(&path, None).unwrap_err();
    let check = stickslip_codegen::check_file(&path, &origin).unwrap_err();
    assert_eq!(e.report, check, "the same report as `stickslip check`");
    assert!(e.report.errors.len() >= 2, "{e}");
    let text = e.to_string();
    assert!(text.contains(&format!("--> {origin}:")), "{text}");
    assert!(text.contains("mm"), "{text}");
    // From source too: the same errors, at `<source>`.
    let e = load_source(&broken_paper(), "<source>", None).unwrap_err();
    let check = stickslip_codegen::check_source(&broken_paper(), "<source>").unwrap_err();
    assert_eq!(e.report, check);
}

#[test]
fn the_same_text_is_the_same_model() {
    let text = format!(
        "{}\n// the same model {}\n",
        std::fs::read_to_string(models_dir().join("coulomb.ssm")).expect("coulomb.ssm"),
        line!()
    );
    let first = load_source(&text, "<once>", None).expect("loads");
    for _ in 0..5 {
        assert_eq!(load_source(&text, "<once>", None).expect("loads"), first);
    }
    let LoadedModel::Piecewise(p) = first else {
        panic!("piecewise")
    };
    let LoadedModel::Piecewise(q) = load_source(&text, "<again>", None).expect("loads") else {
        panic!("piecewise")
    };
    // One description (and one piece of machine code) for both.
    assert!(std::ptr::eq(Loaded::info(&p), Loaded::info(&q)));
    assert_eq!(Loaded::info(&p).source_hash, Some(content_hash(&text)));
}

#[test]
fn a_scene_is_chosen_by_name_and_an_unknown_one_is_refused() {
    let path = models_dir().join("paper.ssm");
    let LoadedModel::Piecewise(p) = load_file(&path, Some("reference")).expect("loads") else {
        panic!("a scene is piecewise")
    };
    assert_eq!(Loaded::info(&p).name, "paper::reference");
    assert_eq!(p.names(), ["Q0", "W"]);
    let e = load_file(&path, Some("nope")).unwrap_err().to_string();
    assert!(
        e.contains("model `paper` has no scene `nope` (its scenes: sweep_w, reference)"),
        "{e}"
    );
    // A smooth law's `pieces` scene is a piecewise-linear model.
    let stribeck = models_dir().join("stribeck.ssm");
    assert!(matches!(
        load_file(&stribeck, None),
        Ok(LoadedModel::Smooth(_))
    ));
    assert!(matches!(
        load_file(&stribeck, Some("pl8")),
        Ok(LoadedModel::Piecewise(_))
    ));
}

#[test]
fn a_model_file_must_be_named_after_its_model() {
    let text = std::fs::read_to_string(models_dir().join("coulomb.ssm")).expect("coulomb.ssm");
    let path = tmp("not_coulomb.ssm", &text);
    let e = load_file(&path, None).unwrap_err().to_string();
    assert!(e.contains("name the file `coulomb.ssm`"), "{e}");
}

#[test]
fn more_free_parameters_than_the_capacity_are_refused_at_the_first_past_it() {
    let extra: String = (0..=CAPACITY)
        .map(|i| format!("    param p{i} = 1.0;\n"))
        .collect();
    let text = std::fs::read_to_string(models_dir().join("coulomb.ssm"))
        .expect("coulomb.ssm")
        .replace("    oscillator {", &format!("{extra}\n    oscillator {{"));
    let e = load_source(&text, "<big>", None).unwrap_err();
    let first = &e.report.errors[0];
    assert!(
        first
            .message
            .contains(&format!("at most {CAPACITY} free parameters")),
        "{e}"
    );
    // Coulomb has 9 parameters: the 33rd is `p23`.
    let name = format!("p{}", CAPACITY - 9);
    assert!(first.message.contains(&format!("`{name}`")), "{e}");
    assert!(first.position.is_some(), "located: {e}");
}

/// A friction law of our own, written here: Coulomb friction plus a cubic
/// viscous term, as three affine pieces (the language's piecewise form).
const OWN_LAW: &str = r#"
//! A mass on a belt with a friction law of its own: a static jump, a
//! falling branch just above the belt speed, a rising one beyond.
model own_law {
    /// Mass.
    param m = 1.0, > 0;
    /// Damping per unit mass.
    param d = 0.08, >= 0;
    /// Stiffness per unit mass.
    param c = 1.0, > 0;
    /// Belt speed.
    param V = 0.6;
    /// Where the friction starts to rise again.
    param V1 = 1.2;
    /// Static and kinetic levels.
    param fs = 0.5, >= 0;
    param fk = 0.3, >= 0;
    /// Slopes.
    param s1 = 0.4;
    param s2 = 0.2;
    /// Forcing.
    param Q0 = 0.6;
    param W = 0.9, > 0;

    oscillator { mass: m, damping: d, stiffness: c, forcing: Q0 / m, frequency: W }

    /// Belt speed.
    boundary Sigma1: v = V, stick fs;
    /// Slope change.
    boundary Sigma2: v = V1;

    /// Above V1: rising.
    domain 2: v > Sigma2 => fk - s1 * (V1 - V) + s2 * (v - V1);
    /// Between V and V1: falling.
    domain 1: Sigma1 < v < Sigma2 => fk - s1 * (v - V);
    /// Below the belt speed.
    domain 3: v < Sigma1 => -fk;
}
"#;

struct Settles;

impl ModelVisitor for Settles {
    type Output = String;
    fn piecewise<M: Model>(self, base: M::Params) -> Option<String> {
        let sim = Simulator::<M>::new(base, SimOptions::default()).expect("valid defaults");
        let start = sim.start(0.0, 0.0, 0.0).expect("start");
        Some(
            match attractor::find(&sim, start, AttractorOptions::default()) {
                Ok(Attractor::Periodic(m)) => m.structure.notation(sim.info()),
                other => format!("{other:?}"),
            },
        )
    }
}

#[test]
fn a_new_friction_law_written_now_is_simulated_without_a_build() {
    let path = tmp("own_law.ssm", OWN_LAW);
    let model = ModelRef::File {
        path: path.clone(),
        scene: None,
    };
    let found = model.visit(Settles).expect("loads").expect("piecewise");
    assert!(found.starts_with("P_{"), "{found}");
    // The same text from source gives the same motion.
    let source = ModelRef::Source {
        text: OWN_LAW.to_string(),
        origin: "<own>".into(),
        scene: None,
    };
    assert_eq!(
        source.visit(Settles).expect("loads").expect("piecewise"),
        found
    );
}

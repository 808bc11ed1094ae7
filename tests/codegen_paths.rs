//! The proc-macro path and the build.rs path generate identical code for the
//! same model file, and the macro-generated model computes the same numbers.

mod from_macro {
    stickslip::model!(file = "models/paper.ssm");
}

use stickslip::models::paper::{Paper, Params};
use stickslip::Model;

#[test]
fn macro_and_build_script_emit_the_same_source() {
    for name in ["paper", "coulomb", "stribeck8"] {
        let built = stickslip::models::generated_source(name).expect("compiled-in model");
        let via_macro = match name {
            "paper" => stickslip::model_source!(file = "models/paper.ssm"),
            "coulomb" => stickslip::model_source!(file = "models/coulomb.ssm"),
            _ => stickslip::model_source!(file = "models/stribeck8.ssm"),
        };
        assert_eq!(
            built, via_macro,
            "model {name}: build.rs and model! generated different code"
        );
        assert!(built.starts_with("// @generated"));
    }
}

#[test]
fn macro_model_computes_bitwise_the_same() {
    let p = Params {
        W: 4.4,
        ..Params::default()
    };
    let q = from_macro::paper::Params {
        W: 4.4,
        ..Default::default()
    };
    for idx in 0..Paper::INFO.mappings.len() {
        let a = Paper::mapping(&p, idx, 0.5, 1.0, -0.5, 2.0);
        let b = from_macro::paper::Paper::mapping(&q, idx, 0.5, 1.0, -0.5, 2.0);
        assert_eq!(a, b);
    }
}

//! A model file the checks reject never reaches the run-time back end: the
//! process's count of compilations to machine code does not move when a
//! rejected text is loaded, and moves by one for a text that passes (the
//! only test of this binary, so that no other load runs meanwhile).

use stickslip::model::loaded::load_source;
use stickslip_codegen::jit::compilations;

#[test]
fn a_rejected_model_is_never_compiled_and_a_checked_one_once() {
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models");
    let coulomb = std::fs::read_to_string(dir.join("coulomb.ssm")).expect("coulomb.ssm");
    let rejected = [
        // A syntax error.
        coulomb.replace("param m = 1.0, > 0;", "param m = 1.0, > ;"),
        // A check error: a parameter declared twice.
        coulomb.replace("param V = 0.5;", "param V = 0.5;\n    param V = 0.7;"),
        // An unknown name in a law.
        coulomb.replace("muk * FN / m;", "muk * FNN / m;"),
        // Not a model at all.
        "fn main() {}".to_string(),
    ];
    assert_eq!(compilations(), 0);
    for (k, text) in rejected.iter().enumerate() {
        assert_ne!(text, &coulomb, "case {k} changes the file");
        let e = load_source(text, "<rejected>", None).expect_err("rejected");
        assert!(e.to_string().contains("<rejected>"), "case {k}: {e}");
        assert_eq!(compilations(), 0, "case {k} reached the back end: {e}");
    }
    load_source(&coulomb, "<coulomb>", None).expect("coulomb loads");
    assert_eq!(compilations(), 1);
    load_source(&coulomb, "<coulomb>", None).expect("coulomb loads");
    assert_eq!(compilations(), 1, "loaded again, compiled once");
}

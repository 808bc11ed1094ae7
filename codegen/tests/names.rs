//! Names the language accepts but Rust could not use as written, or that
//! would collide in the generated code: each rejected at the name, with its
//! `test.ssm:LINE:COL`, through `generate_source` (the `build.rs` path; the
//! same cases through `model!` are in `tests/ui/names/`). And the names that
//! look hostile but are accepted: they generate code that parses.
//!
//! `model(extra, scenes)` puts `extra` on line 8 (and on), after the six
//! parameters of lines 2..=7; scenes follow the six body lines.

use stickslip_codegen::generate_source;

fn model(name: &str, extra: &str, scenes: &str) -> String {
    format!(
        "model {name} {{
    param m = 1.0, > 0;
    param d = 0.05, >= 0;
    param c = 1.0, > 0;
    param W = 1.0, > 0;
    param mu = 0.3;
    param k = 0.1;
{extra}    oscillator {{ mass: m, damping: d, stiffness: c, forcing: 0.5, frequency: W }}
    boundary Sigma1: v = 1.0, stick 0.4;
    boundary Sigma2: v = 2.0;
    domain 1: Sigma1 < v < Sigma2 => mu + k * (v - 1.0);
    domain 2: v > Sigma2 => mu + k;
    domain 3: v < Sigma1 => -mu;
{scenes}}}
"
    )
}

/// The report must hold exactly one error: `message` at `test.ssm:at`.
fn rejects(source: &str, message: &str, at: &str) {
    let report = match generate_source(source, "test.ssm") {
        Ok(_) => panic!("accepted:\n{source}"),
        Err(r) => r,
    };
    assert_eq!(
        report.matches("error:").count(),
        1,
        "one error expected:\n{report}"
    );
    assert!(
        report.contains(&format!("error: {message}\n")),
        "message {message:?} missing:\n{report}"
    );
    assert!(
        report.contains(&format!("--> test.ssm:{at}\n")),
        "location {at} missing:\n{report}"
    );
}

fn accepts(source: &str) -> String {
    let g = generate_source(source, "test.ssm").unwrap_or_else(|r| panic!("{r}\n{source}"));
    syn::parse_file(&g.code).expect("generated code parses");
    g.code
}

#[test]
fn a_scene_defined_twice() {
    let src = model(
        "bad",
        "",
        "    scene sweep { free: W; }\n    scene sweep { free: W, mu; }\n",
    );
    rejects(
        &src,
        "scene `sweep` is defined twice (first at line 14, column 11)",
        "15:11",
    );
}

#[test]
fn scenes_equal_after_nfc() {
    let src = model(
        "bad",
        "",
        "    scene ét { free: W; }\n    scene ét { free: mu; }\n",
    );
    rejects(
        &src,
        "scene `ét` is defined twice (first at line 14, column 11)",
        "15:11",
    );
}

#[test]
fn scenes_equal_after_raw_removal() {
    let src = model(
        "bad",
        "",
        "    scene r#sweep { free: W; }\n    scene sweep { free: mu; }\n",
    );
    rejects(
        &src,
        "scene `sweep` is defined twice (first at line 14, column 11)",
        "15:11",
    );
}

#[test]
fn a_scene_named_like_the_parameter_struct() {
    let src = model("bad", "", "    scene Params { free: W; }\n");
    rejects(
        &src,
        "scene `Params` would generate a module `Params` that clashes with the parameter struct `Params` in the generated code; rename the scene",
        "14:11",
    );
}

#[test]
fn a_scene_named_like_the_model_type() {
    let src = model("my_model", "", "    scene MyModel { free: W; }\n");
    rejects(
        &src,
        "scene `MyModel` would generate a module `MyModel` that clashes with the type `MyModel` of model `my_model` in the generated code; rename the scene",
        "14:11",
    );
}

#[test]
fn scenes_named_like_primitive_types() {
    for (written, name) in [("f64", "f64"), ("usize", "usize"), ("r#str", "str")] {
        let src = model("bad", "", &format!("    scene {written} {{ free: W; }}\n"));
        rejects(
            &src,
            &format!("scene `{name}` would generate a module `{name}` that clashes with the primitive type `{name}` in the generated code; rename the scene"),
            "14:11",
        );
    }
}

#[test]
fn parameters_equal_after_nfc() {
    let src = model("bad", "    param é = 0.1;\n    param é = 0.2;\n", "");
    rejects(
        &src,
        "`é` is defined twice (first at line 8, column 11)",
        "9:11",
    );
}

#[test]
fn a_let_equal_to_a_parameter_after_nfc() {
    let src = model("bad", "    param é1 = 0.1;\n    let é1 = 2.0 * mu;\n", "");
    rejects(
        &src,
        "`é1` is defined twice (first at line 8, column 11)",
        "9:9",
    );
}

#[test]
fn parameters_equal_after_raw_removal() {
    let src = model("bad", "    param r#mu = 0.1;\n", "");
    rejects(
        &src,
        "`mu` is defined twice (first at line 6, column 11)",
        "8:11",
    );
}

#[test]
fn a_raw_v_is_the_velocity() {
    let src = model("bad", "    param r#v = 0.1;\n", "");
    rejects(&src, "`v` is the velocity and cannot be redefined", "8:11");
}

#[test]
fn keywords_that_cannot_be_names() {
    for kw in ["self", "Self", "super", "crate", "_"] {
        let src = model("bad", &format!("    param {kw} = 0.1;\n"), "");
        rejects(
            &src,
            &format!("expected identifier, found keyword `{kw}`"),
            "8:11",
        );
        let src = model("bad", "", &format!("    scene {kw} {{ free: W; }}\n"));
        rejects(
            &src,
            &format!("expected identifier, found keyword `{kw}`"),
            "14:11",
        );
        let src = model(kw, "", "");
        rejects(
            &src,
            &format!("expected identifier, found keyword `{kw}`"),
            "1:7",
        );
    }
}

#[test]
fn keywords_that_cannot_be_raw() {
    for kw in ["self", "Self", "super", "crate"] {
        let src = model("bad", &format!("    param r#{kw} = 0.1;\n"), "");
        rejects(
            &src,
            &format!("`r#{kw}` is not an identifier: `self`, `Self`, `super`, `crate` and `_` cannot be written raw, nor name anything in a model"),
            "8:11",
        );
    }
}

#[test]
fn hostile_names_that_are_accepted() {
    // Keywords written raw, 2024's `gen`, the generator's own names, names
    // without a camel case, prelude names: all compile (see tests/hygiene.rs
    // at the workspace root for the numbers).
    let extra = "    param r#fn = 0.1;\n    param gen = 0.1;\n    param p = 0.1;\n    param x0 = 0.1;\n    param t3 = 0.1;\n    param INFO = 0.1;\n    param Params = 0.1;\n    param Some = 0.1;\n    param μs = 0.1;\n";
    let scenes = "    scene _1 { free: W; }\n    scene __ { free: W; }\n    scene self_ { free: W; }\n    scene params { free: W; }\n    scene INFO { free: W; }\n    scene r#fn { free: W; }\n    scene sweep_w { free: W; }\n    scene sweepW { free: W; }\n    scene SweepW { free: W; }\n";
    let code = accepts(&model("r#match", extra, scenes));
    for item in [
        "pub r#fn: f64",
        "pub r#gen: f64",
        "pub p: f64",
        "pub mod _1",
        "pub struct Scene1;",
        "pub mod __",
        "pub struct Scene;",
        "pub struct SceneSelf;",
        "pub struct SceneParams;",
        "pub struct SceneINFO;",
        "pub mod r#fn",
        "pub struct Fn;",
        "pub struct Match;",
        "name: \"match::fn\"",
    ] {
        assert!(code.contains(item), "{item} missing");
    }
    // A name used in another normal form than it was declared in is the same name.
    let src = model("nfc", "    param é = 0.1;\n", "    scene s { free: é; }\n")
        .replace("frequency: W", "frequency: W + 0.0 * é");
    accepts(&src);
}

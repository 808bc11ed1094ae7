//! One grammar of mapping structures for the model checker and the runtime
//! (`stickslip_codegen::structure`): a scene's `structures: "TEXT";` passes
//! the checker (`check_source`, the path of `build.rs`, `model!` and
//! `stickslip check`) exactly when `Structure::parse` accepts TEXT for the
//! same model at run time, and a rejected one is rejected with the same message.

use stickslip::models::paper::Paper;
use stickslip::orbit::structure::Structure;

/// Structure texts of every shape: the paper's notation, its variants, and
/// each way of getting it wrong.
const CASES: &[&str] = &[
    // Accepted shapes of one closed structure.
    "P_{3_31 0_11 3_13 4_33}",
    "P{3_31 0_11 3_13 4_33}",
    "3_31 0_11 3_13 4_33",
    "  P_{ 3_31   0_11\t3_13 4_33 }  ",
    "P_{3_33 4_33}",
    "3_33 4_33",
    "P_{3_31 1_12 2_22 1_21 3_13 4_33}",
    "P_{1_11 3_13 3_31}",
    // Unbalanced or malformed delimiters.
    "P_{3_31 0_11 3_13 4_33",
    "P{3_33 4_33",
    "3_33 4_33}",
    "P_{{3_33 4_33}}",
    "P_[3_33 4_33]",
    "p_{3_33 4_33}",
    "P_ {3_33 4_33}",
    "P_{3_33 4_33}^2",
    // Empty.
    "",
    "   ",
    "P_{}",
    "P{ }",
    // Unknown mappings.
    "P_{3_31 9_99}",
    "3_33 4_34",
    "Sigma1",
    // Not closed, disconnected, stuck.
    "P_{1_22 3_13 4_33}",
    "P_{3_13 4_33}",
    "3_31",
    "0_11",
    "0_11 0_11",
    "P_{0_11 3_13 4_33}",
];

/// The paper model with one more scene studying `text`.
fn with_scene(text: &str) -> String {
    let path = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("models/paper.ssm");
    let source = std::fs::read_to_string(path).expect("models/paper.ssm");
    let end = source.rfind('}').expect("the model's closing brace");
    // `{:?}` writes a string literal the model language reads back as `text`.
    format!(
        "{}    scene probe {{\n        free: W;\n        structures: {text:?};\n    }}\n}}\n",
        &source[..end]
    )
}

#[test]
fn checker_and_runtime_accept_and_reject_the_same_structures() {
    let (mut accepted, mut rejected) = (0, 0);
    for &text in CASES {
        let runtime = Structure::parse(Paper::INFO, text, 1);
        let checker = stickslip_codegen::check_source(&with_scene(text), "paper.ssm");
        match (&runtime, &checker) {
            (Ok(_), Ok(_)) => accepted += 1,
            (Err(e), Err(report)) => {
                rejected += 1;
                let rendered = report.render();
                assert!(
                    rendered.contains(&e.to_string()),
                    "{text:?}: the runtime says `{e}`, the checker\n{rendered}"
                );
                assert!(
                    rendered.contains("paper.ssm:"),
                    "{text:?}: the error is located\n{rendered}"
                );
            }
            (Ok(_), Err(report)) => panic!(
                "{text:?}: the runtime accepts it, the checker rejects it:\n{}",
                report.render()
            ),
            (Err(e), Ok(_)) => {
                panic!("{text:?}: the checker accepts it, the runtime rejects it: {e}")
            }
        }
    }
    // The list exercises both answers, so agreeing is not trivial.
    assert!(
        accepted >= 8 && rejected >= 15,
        "{accepted} accepted, {rejected} rejected"
    );
}

#[test]
fn an_accepted_structure_means_the_same_mappings_on_both_paths() {
    // The checker keeps a scene's structures as written; the scene then
    // generates exactly the mappings they use, which must be those the
    // runtime resolves the same text to.
    for &text in CASES {
        let Ok(structure) = Structure::parse(Paper::INFO, text, 1) else {
            continue;
        };
        let generated = stickslip_codegen::check_source(&with_scene(text), "paper.ssm")
            .unwrap_or_else(|r| panic!("{text:?}: {}", r.render()));
        let mut want: Vec<&str> = structure
            .steps()
            .iter()
            .map(|&i| Paper::INFO.mappings[i].name)
            .collect();
        want.sort_unstable();
        want.dedup();
        let scene = generated
            .code
            .split("pub mod probe")
            .nth(1)
            .unwrap_or_else(|| panic!("{text:?}: no scene `probe`"));
        for m in Paper::INFO.mapping_names() {
            let declared = scene.contains(&format!("name: \"{m}\""));
            assert_eq!(
                declared,
                want.contains(&m),
                "{text:?}: mapping {m} in the scene's INFO"
            );
        }
    }
}

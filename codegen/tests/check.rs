//! The checker, through `generate_source`: each test starts from a valid
//! model (`BASE`, the paper's model without docs and scenes), makes one
//! mistake, and asserts both the message and its `test.ssm:LINE:COL`.
//!
//! Edits replace text within a line, so the line numbers of `BASE` below
//! hold in every test unless the test says otherwise.

mod common;

use common::{accepted, edit, errors, generate};

/// Line numbers: 1 `model`, 2..=16 params, 17 `let`, 18..=24 oscillator,
/// 25..=27 boundaries, 28..=31 domains (2, 1, 3, 4), 32 `}`.
const BASE: &str = r#"model paper {
    param m = 5.0, > 0;
    param d = 0.1, >= 0;
    param c = 30.0, > 0;
    param V = 3.0;
    param V1 = 4.5;
    param V2 = 1.5;
    param mus = 0.5, >= 0;
    param muk = 0.4, >= 0;
    param mu1 = 0.1;
    param mu2 = 0.5;
    param mu3 = 0.1;
    param mu4 = 0.5;
    param g = 9.8, > 0;
    param Q0 = 70.0;
    param W = 3.0, > 0;
    let FN = m * g;
    oscillator {
        mass: m,
        damping: d,
        stiffness: c,
        forcing: Q0 / m,
        frequency: W,
    }
    boundary Sigma1: v = V, stick mus * FN / m;
    boundary Sigma2: v = V1;
    boundary Sigma3: v = V2;
    domain 2: v > Sigma2 => (mu1 * (v - V1) - mu2 * (V1 - V) + FN * muk) / m;
    domain 1: Sigma1 < v < Sigma2 => (-mu2 * (v - V) + FN * muk) / m;
    domain 3: Sigma3 < v < Sigma1 => (-mu3 * (v - V) - FN * muk) / m;
    domain 4: v < Sigma3 => (mu4 * (v - V2) - mu3 * (V2 - V) - FN * muk) / m;
}
"#;

/// A two-piece Coulomb-like law with a slope, continuous at the only
/// boundary, which carries no stick.
const COULOMB: &str = r#"model coulomb {
    param m = 1.0, > 0;
    param d = 0.05, >= 0;
    param c = 1.0, > 0;
    param A = 0.5;
    param W = 1.0, > 0;
    param mu = 0.3;
    param k = 0.1;
    param V = 1.0;
    oscillator { mass: m, damping: d, stiffness: c, forcing: A, frequency: W }
    boundary Sigma1: v = V;
    domain 1: v > Sigma1 => mu + k * (v - V);
    domain 2: v < Sigma1 => mu - k * (V - v);
}
"#;

/// `BASE` with edits.
fn with(edits: &[(&str, &str)]) -> String {
    edit(BASE, edits)
}

/// `BASE` with `scene` inserted before the closing brace: its first line is line 32.
fn with_scene(scene: &str) -> String {
    let end = BASE.rfind('}').expect("closing brace");
    format!("{}{}{}", &BASE[..end], scene, &BASE[end..])
}

/// Assert that the model is rejected with exactly one error, at `location`,
/// whose message contains every fragment.
#[track_caller]
fn assert_error(source: &str, location: &str, fragments: &[&str]) {
    let errs = errors(source);
    assert_eq!(errs.len(), 1, "expected one error, got {errs:#?}");
    assert_has(&errs, location, fragments);
}

/// Assert that one of `errs` is at `location` and contains every fragment.
#[track_caller]
fn assert_has(errs: &[(String, String)], location: &str, fragments: &[&str]) {
    let found = errs.iter().any(|(m, l)| {
        l == &format!("test.ssm:{location}") && fragments.iter().all(|f| m.contains(f))
    });
    assert!(
        found,
        "no error at test.ssm:{location} containing {fragments:?} in {errs:#?}"
    );
}

// ---------------------------------------------------------------- accepted

#[test]
fn base_model_is_accepted_with_all_its_mappings() {
    let g = accepted(BASE);
    assert_eq!(g.name, "paper");
    for m in [
        "1_11", "1_22", "1_21", "1_12", "2_22", "3_33", "3_11", "3_13", "3_31", "4_33",
    ] {
        assert!(
            g.code.contains(&format!("pub fn mapping_{m}(")),
            "mapping {m} missing"
        );
    }
    // The stick mapping, in its two variants.
    assert!(g.code.contains("pub fn mapping_0_11_above("));
    assert!(g.code.contains("pub fn mapping_0_11_below("));
    // Domain 2 is unbounded above, domain 4 below: no global mappings there.
    assert!(!g.code.contains("pub fn mapping_2_32("));
    assert!(!g.code.contains("pub fn mapping_4_31("));
    assert!(g
        .code
        .contains("4 domains, 3 boundaries, 11 mappings, 0 scenes"));
}

#[test]
fn continuous_two_piece_law_without_stick_is_accepted() {
    let g = accepted(COULOMB);
    assert_eq!(g.name, "coulomb");
    assert!(g.code.contains("pub fn mapping_1_11("));
    assert!(g.code.contains("pub fn mapping_2_11("));
    assert_eq!(g.code.matches("pub fn mapping_").count(), 2, "{}", g.code);
    assert!(!g.code.contains("mapping_0_11"), "no stick boundary");
    assert!(g
        .code
        .contains("2 domains, 1 boundaries, 2 mappings, 0 scenes"));
}

#[test]
fn coulomb_jump_without_stick_is_rejected() {
    // Constant levels `mu` and `-mu`: a jump at the only boundary.
    let src = edit(
        COULOMB,
        &[
            ("=> mu + k * (v - V);", "=> mu;"),
            ("=> mu - k * (V - v);", "=> -mu;"),
        ],
    );
    assert_error(
        &src,
        "11:14",
        &[
            "kinetic friction jumps at `Sigma1` (domain 2 gives -0.3, domain 1 gives 0.3)",
            "but `Sigma1` is not a stick boundary",
            "declare `stick BOUND`",
        ],
    );
}

#[test]
fn scene_with_valid_structures_is_accepted() {
    let src = with_scene(
        "    scene s {\n        free: W, Q0;\n        structures: \"3_31 0_11 3_13 4_33\", \"P_{3_33 4_33}\";\n    }\n",
    );
    let g = accepted(&src);
    let names: Vec<&str> = g.instances.iter().map(|i| i.name.as_str()).collect();
    assert_eq!(names, ["paper", "paper::s"]);
    assert_eq!(g.instances[1].type_name, "S");
}

#[test]
fn full_report_shows_the_line_and_a_caret_under_the_token() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu5 * (v - V) + FN * muk)")]);
    let report = generate(&src).unwrap_err();
    assert_eq!(
        report,
        "error: unknown name `mu5` in the friction law of domain 1\n  \
         --> test.ssm:29:40\n   \
         |\n29 |     domain 1: Sigma1 < v < Sigma2 => (-mu5 * (v - V) + FN * muk) / m;\n   \
         |                                        ^^^\n\
         1 error in test.ssm\n"
    );
}

// ------------------------------------------------------------------ syntax

#[test]
fn missing_semicolon() {
    // syn reports at the token where `;` was expected: the next item.
    let src = with(&[("param V = 3.0;", "param V = 3.0")]);
    assert_error(&src, "6:5", &["expected `;`"]);
}

#[test]
fn malformed_band() {
    let src = with(&[("domain 1: Sigma1 < v", "domain 1: Sigma1 < w")]);
    assert_error(
        &src,
        "29:24",
        &["expected a velocity band: `v > SigmaA`, `SigmaA < v < SigmaB` or `v < SigmaA`"],
    );
}

#[test]
fn syntax_errors_in_several_items_are_all_reported() {
    let src = with(&[
        ("param V = 3.0;", "param V = 3.0 3.0;"),
        ("let FN = m * g;", "let = m * g;"),
    ]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    assert_has(&errs, "5:19", &["expected `;`"]);
    assert_has(&errs, "17:9", &["expected identifier"]);
}

#[test]
fn syntax_error_inside_the_oscillator_is_reported_once() {
    let src = with(&[("damping: d,", "damping d,")]);
    assert_error(&src, "20:17", &["expected `:`"]);
}

#[test]
fn syntax_error_inside_braces_does_not_hide_the_next_item() {
    // The scene ends at its closing brace: the next item is parsed, and its
    // missing `;` (seen at the model's closing brace) is reported too.
    let src = with_scene("    scene s {\n        free W;\n    }\n    param zz = 1.0\n");
    let errs = errors(&src);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    assert_has(&errs, "33:14", &["expected `:`"]);
    assert_has(&errs, "36:1", &["expected `;`"]);
}

#[test]
fn unknown_item_keyword() {
    let src = with(&[("param V = 3.0;", "parm V = 3.0;")]);
    assert_error(&src, "5:5", &["expected one of"]);
}

#[test]
fn attribute_other_than_doc_comment() {
    let src = with(&[("param V = 3.0;", "#[foo] param V = 3.0;")]);
    assert_error(
        &src,
        "5:5",
        &["only doc comments (`///`) may annotate a model item"],
    );
}

#[test]
fn unbalanced_delimiter() {
    // Located by scanning the delimiters: where it was noticed, naming the opener.
    let src = with(&[("- FN * muk) / m;\n}", "- FN * muk / m;\n}")]);
    assert_error(
        &src,
        "32:1",
        &["mismatched closing `}`: the `(` at 31:29 is still open"],
    );
}

// ------------------------------------------------------------------- names

#[test]
fn unknown_name_in_a_law() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu5 * (v - V) + FN * muk)")]);
    assert_error(
        &src,
        "29:40",
        &["unknown name `mu5` in the friction law of domain 1"],
    );
}

#[test]
fn unknown_name_in_a_let() {
    let src = with(&[("let FN = m * g;", "let FN = m * gg;")]);
    assert_error(
        &src,
        "17:18",
        &["unknown name `gg` in derived quantity `FN`"],
    );
}

#[test]
fn unknown_name_in_the_oscillator() {
    let src = with(&[("damping: d,", "damping: dd,")]);
    assert_error(&src, "20:18", &["unknown name `dd` in the damping"]);
}

#[test]
fn unknown_boundary_in_a_band() {
    let src = with(&[("domain 4: v < Sigma3", "domain 4: v < Sigma9")]);
    assert_error(&src, "31:19", &["unknown boundary `Sigma9`"]);
}

#[test]
fn unknown_function() {
    let src = with(&[("forcing: Q0 / m,", "forcing: Q0 * tan(m),")]);
    assert_error(
        &src,
        "22:23",
        &["unknown function `tan`; available: exp, ln, sqrt, sin, cos, abs, sign, powi"],
    );
}

#[test]
fn duplicate_param() {
    let src = with(&[("param mu4 = 0.5;", "param mu4 = 0.5; param mu3 = 0.7;")]);
    assert_error(
        &src,
        "13:28",
        &["`mu3` is defined twice (first at line 12, column 11)"],
    );
}

#[test]
fn let_reusing_a_param_name() {
    let src = with(&[("let FN = m * g;", "let FN = m * g; let g = 1.0;")]);
    assert_error(
        &src,
        "17:25",
        &["`g` is defined twice (first at line 14, column 11)"],
    );
}

#[test]
fn param_named_v() {
    let src = with(&[("param V = 3.0;", "param V = 3.0; param v = 1.0;")]);
    assert_error(
        &src,
        "5:26",
        &["`v` is the velocity and cannot be redefined"],
    );
}

#[test]
fn duplicate_domain_label() {
    let src = with(&[("domain 4:", "domain 3:")]);
    assert_error(&src, "31:12", &["domain 3 is declared twice"]);
}

#[test]
fn domain_label_zero() {
    let src = with(&[("domain 4:", "domain 0:")]);
    assert_error(
        &src,
        "31:12",
        &["a domain label is a positive integer (0 is the stick mapping's)"],
    );
}

#[test]
fn duplicate_boundary_number() {
    // Only the duplicate is reported, not the domains that name `Tau1`.
    let src = with(&[
        ("boundary Sigma2: v = V1;", "boundary Tau1: v = V1;"),
        ("domain 2: v > Sigma2", "domain 2: v > Tau1"),
        ("Sigma1 < v < Sigma2", "Sigma1 < v < Tau1"),
    ]);
    assert_error(
        &src,
        "26:14",
        &["boundary number 1 is used twice (`Sigma1` and `Tau1`)"],
    );
}

#[test]
fn duplicate_boundary_label() {
    let src = with(&[(
        "boundary Sigma3: v = V2;",
        "boundary Sigma3: v = V2; boundary Sigma3: v = 6.0;",
    )]);
    assert_error(
        &src,
        "27:39",
        &["boundary number 3 is used twice (`Sigma3` and `Sigma3`)"],
    );
}

#[test]
fn boundary_label_without_number() {
    let src = with(&[(
        "boundary Sigma3: v = V2;",
        "boundary Sigma3: v = V2; boundary Sigma: v = 6.0;",
    )]);
    assert_error(
        &src,
        "27:39",
        &["boundary label `Sigma` must end in its number, e.g. `Sigma1`"],
    );
}

#[test]
fn boundaries_with_the_same_velocity() {
    let src = with(&[("boundary Sigma3: v = V2;", "boundary Sigma3: v = V1;")]);
    assert_error(
        &src,
        "27:14",
        &["`Sigma2` and `Sigma3` have the same velocity 4.5 at the defaults"],
    );
}

// ------------------------------------------------------------------- bands

#[test]
fn overlapping_bands() {
    let src = with(&[("domain 4: v < Sigma3", "domain 4: Sigma3 < v < Sigma1")]);
    assert_error(
        &src,
        "31:15",
        &["domain 4 overlaps domain 3: both cover the same velocity band"],
    );
}

#[test]
fn gap_between_two_boundaries() {
    let src = with(&[(
        "    domain 1: Sigma1 < v < Sigma2 => (-mu2 * (v - V) + FN * muk) / m;\n",
        "",
    )]);
    assert_error(
        &src,
        "26:14",
        &["gap: no domain covers the band Sigma1 < v < Sigma2"],
    );
}

#[test]
fn gap_above_the_highest_boundary() {
    // No boundary lies above the gap: the error points at the model's name.
    let src = with(&[(
        "    domain 2: v > Sigma2 => (mu1 * (v - V1) - mu2 * (V1 - V) + FN * muk) / m;\n",
        "",
    )]);
    assert_error(&src, "1:7", &["gap: no domain covers the band v > Sigma2"]);
}

#[test]
fn band_spanning_a_boundary() {
    let src = with(&[
        ("domain 1: Sigma1 < v", "domain 1: Sigma3 < v"),
        (
            "    domain 3: Sigma3 < v < Sigma1 => (-mu3 * (v - V) - FN * muk) / m;\n",
            "",
        ),
    ]);
    assert_error(
        &src,
        "29:15",
        &["domain 1's band contains the boundary Sigma1: a domain lies between two adjacent boundaries"],
    );
}

#[test]
fn empty_band() {
    let src = with(&[(
        "domain 1: Sigma1 < v < Sigma2",
        "domain 1: Sigma2 < v < Sigma1",
    )]);
    assert_error(
        &src,
        "29:15",
        &["empty band in domain 1: `Sigma2` is not below `Sigma1`"],
    );
}

// ------------------------------------------------------------ friction laws

#[test]
fn non_affine_law_names_the_product() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu2 * (v * v) + FN * muk)")]);
    assert_error(
        &src,
        "29:47",
        &[
            "the friction law of domain 1 is not affine in `v`",
            "the term `v * v` is nonlinear in `v`",
            "split the band into affine pieces",
        ],
    );
}

#[test]
fn non_affine_law_names_the_function() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu2 * exp(v) + FN * muk)")]);
    // The term is printed from its tokens, hence the space before `(`.
    assert_error(
        &src,
        "29:46",
        &[
            "the friction law of domain 1 is not affine in `v`",
            "the term `exp (v)` is nonlinear",
        ],
    );
}

#[test]
fn non_affine_law_names_the_smallest_term() {
    // `sqrt(v * v)` is not affine because `v * v` is not.
    let src = with(&[(
        "- FN * muk) / m;\n}",
        "- FN * muk + sqrt(v * v) - V2) / m;\n}",
    )]);
    assert_error(
        &src,
        "31:80",
        &["domain 4 is not affine in `v`: the term `v * v`"],
    );
}

#[test]
fn abs_of_v_is_not_affine() {
    // The second derivative of `abs(v)` folds to 0 (that of `sign` is 0),
    // but the law has a kink at v = 0, inside domain 4's band.
    let src = with(&[("- FN * muk) / m;\n}", "- FN * muk + abs(v) - V2) / m;\n}")]);
    assert_error(
        &src,
        "31:75",
        &["domain 4 is not affine in `v`: the term `abs (v)`"],
    );
}

#[test]
fn abs_of_v_is_rejected_even_where_its_sign_is_constant() {
    // On v > V, `abs(v - V)` equals `v - V`, but the flows use the law's value
    // and slope at v = 0, where it is `V - v`: the model would be wrong.
    let src = edit(
        COULOMB,
        &[("=> mu + k * (v - V);", "=> mu + k * abs(v - V);")],
    );
    assert_error(&src, "12:38", &["the term `abs (v - V)` is nonlinear"]);
}

#[test]
fn powi_of_v_is_not_affine_but_first_power_is() {
    let src = with(&[(
        "(-mu2 * (v - V) + FN * muk)",
        "(-mu2 * powi(v, 2) + FN * muk)",
    )]);
    assert_error(&src, "29:46", &["the term `powi (v , 2)` is nonlinear"]);
    accepted(&with(&[(
        "(-mu2 * (v - V) + FN * muk)",
        "(-mu2 * powi(v - V, 1) + FN * muk)",
    )]));
}

#[test]
fn division_by_v_is_not_affine() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu2 / (v - V) + FN * muk)")]);
    assert_error(&src, "29:39", &["the term `- mu2 / (v - V)` is nonlinear"]);
}

#[test]
fn jump_at_a_non_stick_boundary() {
    // Domain 2 uses `mus` where domain 1 uses `muk`: 4.75 vs 3.77 at V1.
    let src = with(&[(
        "- mu2 * (V1 - V) + FN * muk)",
        "- mu2 * (V1 - V) + FN * mus)",
    )]);
    assert_error(
        &src,
        "26:14",
        &[
            "kinetic friction jumps at `Sigma2` (domain 1 gives 3.77",
            "domain 2 gives 4.75), but `Sigma2` is not a stick boundary",
            "make the laws meet there or declare `stick BOUND`",
        ],
    );
}

#[test]
fn continuity_only_at_the_default_parameters() {
    // Domain 2 uses `mu5`, domain 1 `mu2`: equal defaults, different parameters.
    let src = with(&[
        ("param mu4 = 0.5;", "param mu4 = 0.5; param mu5 = 0.5;"),
        (
            "- mu2 * (V1 - V) + FN * muk)",
            "- mu5 * (V1 - V) + FN * muk)",
        ),
    ]);
    assert_error(
        &src,
        "26:14",
        &[
            "kinetic friction is continuous at `Sigma2` only for the default parameter values",
            "domains 1 and 2 do not meet there for other values",
        ],
    );
}

#[test]
fn static_bound_below_kinetic_level() {
    // 0.1 * 9.8 = 0.98 < 3.92 = muk * g on both sides of Sigma1.
    let src = with(&[("stick mus * FN / m", "stick 0.1 * FN / m")]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    assert_has(
        &errs,
        "25:35",
        &[
            "the static bound `0.1 * FN / m` = 0.98",
            "is below the kinetic friction level 3.92",
            "above `Sigma1` (domain 1): static friction must be at least kinetic",
        ],
    );
    assert_has(
        &errs,
        "25:35",
        &[
            "is below the kinetic friction level 3.92",
            "below `Sigma1` (domain 3)",
        ],
    );
}

#[test]
fn static_bound_equal_to_kinetic_level_is_accepted() {
    accepted(&with(&[("stick mus * FN / m", "stick muk * FN / m")]));
}

// --------------------------------------------------------------- oscillator

#[test]
fn zero_mass_at_the_defaults() {
    let src = with(&[("mass: m,", "mass: m - 5.0,")]);
    assert_error(
        &src,
        "19:15",
        &["the mass `m - 5.0` is 0 at the defaults; it must be positive"],
    );
}

#[test]
fn negative_mass_default() {
    let src = with(&[("param m = 5.0, > 0;", "param m = -5.0;")]);
    assert_error(
        &src,
        "19:15",
        &["the mass `m` is -5 at the defaults; it must be positive"],
    );
}

#[test]
fn zero_stiffness_at_the_defaults() {
    let src = with(&[("stiffness: c,", "stiffness: c - 30.0,")]);
    assert_error(
        &src,
        "21:20",
        &["the stiffness `c - 30.0` is 0 at the defaults; it must be positive"],
    );
}

#[test]
fn negative_stiffness_default() {
    let src = with(&[("param c = 30.0, > 0;", "param c = -30.0;")]);
    assert_error(
        &src,
        "21:20",
        &["the stiffness `c` is -30 at the defaults; it must be positive"],
    );
}

#[test]
fn zero_frequency_at_the_defaults() {
    let src = with(&[("frequency: W,", "frequency: W - W,")]);
    assert_error(
        &src,
        "23:20",
        &["the forcing frequency `W - W` is 0 at the defaults; it must be positive"],
    );
}

#[test]
fn unknown_oscillator_field() {
    let src = with(&[("damping: d,", "damping: d, spring: c,")]);
    assert_error(
        &src,
        "20:21",
        &["unknown oscillator field `spring`; expected mass, damping, stiffness, forcing, frequency"],
    );
}

#[test]
fn missing_oscillator_field() {
    let src = with(&[("frequency: W,", "")]);
    assert_error(&src, "18:5", &["the oscillator lacks frequency"]);
}

#[test]
fn oscillator_field_given_twice() {
    let src = with(&[("damping: d,", "damping: d, damping: d,")]);
    assert_error(&src, "20:21", &["`damping` is given twice"]);
}

#[test]
fn oscillator_declared_twice() {
    let src = with_scene(
        "    oscillator { mass: m, damping: d, stiffness: c, forcing: Q0, frequency: W }\n",
    );
    assert_error(&src, "32:5", &["the oscillator is declared twice"]);
}

// ------------------------------------------------------- division by zero

#[test]
fn division_by_literal_zero() {
    let src = with(&[("forcing: Q0 / m,", "forcing: Q0 / 0.0,")]);
    assert_error(
        &src,
        "22:23",
        &["division by zero: `0.0` is the constant 0 in the forcing amplitude"],
    );
}

#[test]
fn division_by_an_expression_that_folds_to_zero() {
    let src = with(&[("forcing: Q0 / m,", "forcing: Q0 / (m - m),")]);
    assert_error(
        &src,
        "22:23",
        &["division by zero: `(m - m)` is the constant 0 in the forcing amplitude"],
    );
}

#[test]
fn division_by_zero_in_a_law() {
    let src = with(&[("(-mu2 * (v - V) + FN * muk)", "(-mu2 / (v - v) + FN * muk)")]);
    assert_error(
        &src,
        "29:46",
        &["division by zero: `(v - v)` is the constant 0 in the friction law of domain 1"],
    );
}

#[test]
fn negative_power_of_zero() {
    let src = with(&[("forcing: Q0 / m,", "forcing: Q0 * powi(m - m, -1),")]);
    assert_error(
        &src,
        "22:28",
        &["division by zero: negative power of 0 in the forcing amplitude"],
    );
}

#[test]
fn division_by_zero_at_the_defaults_of_a_free_parameter() {
    // `z` is free in the model, but 0 at its default: the forcing is inf
    // there, in the model and in every scene fixing `z` alike.
    let src = with(&[
        ("param Q0 = 70.0;", "param Q0 = 70.0; param z = 0.0;"),
        ("forcing: Q0 / m,", "forcing: Q0 / z,"),
    ]);
    assert_error(
        &src,
        "22:18",
        &["the forcing amplitude: `Q0 / z` evaluates to inf at the defaults, with Q0 = 70, z = 0"],
    );
}

// ------------------------------------------------------------ `v` misplaced

#[test]
fn v_in_a_let() {
    let src = with(&[("let FN = m * g;", "let FN = m * g * v;")]);
    assert_error(
        &src,
        "17:22",
        &["`v` (the velocity) is only defined inside a friction law, not in derived quantity `FN`"],
    );
}

#[test]
fn v_in_the_oscillator() {
    let src = with(&[("damping: d,", "damping: d * v,")]);
    assert_error(
        &src,
        "20:22",
        &["`v` (the velocity) is only defined inside a friction law, not in the damping"],
    );
}

#[test]
fn v_in_a_boundary_velocity() {
    let src = with(&[("boundary Sigma2: v = V1;", "boundary Sigma2: v = V1 + v;")]);
    assert_error(
        &src,
        "26:31",
        &["`v` (the velocity) is only defined inside a friction law, not in the velocity of Sigma2"],
    );
}

#[test]
fn v_in_a_static_bound() {
    let src = with(&[("stick mus * FN / m", "stick mus * FN / m + v")]);
    assert_error(
        &src,
        "25:50",
        &["`v` (the velocity) is only defined inside a friction law, not in the static bound of Sigma1"],
    );
}

// ------------------------------------------------------ parameter defaults

#[test]
fn default_referring_to_a_name() {
    let src = with(&[("param V1 = 4.5;", "param V1 = V + 1.5;")]);
    assert_error(
        &src,
        "6:16",
        &["the default of `V1` must be a number; it cannot refer to `V`"],
    );
}

#[test]
fn bound_referring_to_a_name() {
    let src = with(&[("param m = 5.0, > 0;", "param m = 5.0, > c;")]);
    assert_error(
        &src,
        "2:22",
        &["a bound of `m` must be a number; it cannot refer to `c`"],
    );
}

#[test]
fn default_that_is_a_string() {
    let src = with(&[("param V = 3.0;", "param V = \"3\";")]);
    assert_error(&src, "5:15", &["expected a number in the default of `V`"]);
}

#[test]
fn default_that_is_not_finite() {
    let src = with(&[("param V = 3.0;", "param V = 1e400;")]);
    assert_error(
        &src,
        "5:15",
        &["the number `1e400` in the default of `V` is out of range: it would be inf as an f64"],
    );
}

#[test]
fn default_violating_its_lower_bound() {
    let src = with(&[("param d = 0.1, >= 0;", "param d = -0.1, >= 0;")]);
    assert_error(
        &src,
        "3:21",
        &["the default -0.1 of `d` violates its bound >= 0"],
    );
}

#[test]
fn mass_default_violating_its_bound_is_also_a_non_positive_mass() {
    // The default is a number, so the checks at the defaults still run.
    let src = with(&[("param m = 5.0, > 0;", "param m = -1.0, > 0;")]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    assert_has(
        &errs,
        "2:21",
        &["the default -1 of `m` violates its bound > 0"],
    );
    assert_has(
        &errs,
        "19:15",
        &["the mass `m` is -1 at the defaults; it must be positive"],
    );
}

#[test]
fn default_violating_its_second_bound() {
    let src = with(&[("param d = 0.1, >= 0;", "param d = 0.1, >= 0, <= 0.05;")]);
    assert_error(
        &src,
        "3:26",
        &["the default 0.1 of `d` violates its bound <= 0.05"],
    );
}

// ------------------------------------------------------------------- stick

#[test]
fn two_stick_boundaries() {
    // Only the second stick is reported, not the domains that name `Sigma2`.
    let src = with(&[(
        "boundary Sigma2: v = V1;",
        "boundary Sigma2: v = V1, stick mus;",
    )]);
    assert_error(
        &src,
        "26:14",
        &["only one boundary can carry static friction; `Sigma1` already does"],
    );
}

// ------------------------------------------------------------------ scenes

fn scene(body: &str) -> String {
    with_scene(&format!("    scene s {{\n{body}    }}\n"))
}

#[test]
fn scene_freeing_an_unknown_parameter() {
    let src = scene("        free: W, Q9;\n");
    assert_error(&src, "33:18", &["unknown parameter `Q9`"]);
}

#[test]
fn scene_freeing_a_let_quantity() {
    let src = scene("        free: FN;\n");
    assert_error(
        &src,
        "33:15",
        &["`FN` is a derived quantity; free the parameters it is computed from"],
    );
}

#[test]
fn scene_freeing_a_parameter_twice() {
    let src = scene("        free: W, Q0, W;\n");
    assert_error(&src, "33:22", &["`W` is freed twice"]);
}

#[test]
fn scene_structure_with_an_unknown_mapping() {
    let src = scene("        free: W;\n        structures: \"3_31 5_11\";\n");
    assert_error(
        &src,
        "34:21",
        &["`5_11` is not a mapping of model `paper` (it has 1_11, 1_22, 1_21, 1_12, 2_22, 3_33, 3_11, 3_13, 3_31, 4_33, 0_11)"],
    );
}

#[test]
fn scene_structure_that_does_not_chain() {
    // Applied right to left: 3_13 ends on Sigma1, then 1_22 starts on Sigma2.
    let src =
        scene("        free: W;\n        structures: \"3_31 0_11 3_13 4_33\", \"1_22 3_13\";\n");
    assert_error(
        &src,
        "34:44",
        &["3_13 ends on Sigma1, but 1_22 starts on Sigma2"],
    );
}

#[test]
fn scene_structure_that_does_not_close() {
    // Applied right to left: 3_13 (Sigma3 to Sigma1), then 0_11 (sticks on
    // Sigma1); the cycle does not close, since 3_13 starts on Sigma3.
    let src = scene("        free: W;\n        structures: \"0_11 3_13\";\n");
    assert_error(
        &src,
        "34:21",
        &["0_11 ends on Sigma1, but 3_13 starts on Sigma3"],
    );
}

#[test]
fn scene_structure_that_is_empty() {
    let src = scene("        free: W;\n        structures: \"P_{}\";\n");
    assert_error(&src, "34:21", &["an empty mapping structure"]);
}

#[test]
fn scene_with_an_unknown_entry() {
    let src = scene("        fixed: W;\n");
    assert_error(
        &src,
        "33:9",
        &["expected `free: NAMES;`, `structures: \"..\", ..;` or `pieces: N;` in a scene"],
    );
}

// ---------------------------------------------------------- several errors

#[test]
fn several_errors_are_reported_at_once() {
    let src = with(&[
        ("param d = 0.1, >= 0;", "param d = -0.1, >= 0;"),
        ("param mu4 = 0.5;", "param mu4 = 0.5; param mu3 = 0.7;"),
        ("damping: d,", "damping: d, spring: c,"),
        ("(-mu2 * (v - V) + FN * muk)", "(-mu5 * (v - V) + FN * muk)"),
        ("(-mu3 * (v - V) - FN * muk)", "(-mu3 * (v * v) - FN * muk)"),
    ]);
    let report = generate(&src).unwrap_err();
    assert!(report.ends_with("\n5 errors in test.ssm\n"), "{report}");
    let errs = errors(&src);
    let mut locations: Vec<&str> = errs.iter().map(|(_, l)| l.as_str()).collect();
    locations.sort_by_key(|l| {
        let mut it = l.rsplit(':').map(|n| n.parse::<u32>().unwrap_or(0));
        let col = it.next().unwrap_or(0);
        (it.next().unwrap_or(0), col)
    });
    assert_eq!(
        locations,
        [
            "test.ssm:3:21",
            "test.ssm:13:28",
            "test.ssm:20:21",
            "test.ssm:29:40",
            "test.ssm:30:47",
        ]
    );
    assert_has(
        &errs,
        "3:21",
        &["the default -0.1 of `d` violates its bound >= 0"],
    );
    assert_has(&errs, "13:28", &["`mu3` is defined twice"]);
    assert_has(&errs, "20:21", &["unknown oscillator field `spring`"]);
    assert_has(
        &errs,
        "29:40",
        &["unknown name `mu5` in the friction law of domain 1"],
    );
    assert_has(
        &errs,
        "30:47",
        &["domain 3 is not affine in `v`: the term `v * v`"],
    );
}

#[test]
fn non_affine_law_and_gap_are_reported_together() {
    let src = with(&[
        ("(-mu2 * (v - V) + FN * muk)", "(-mu2 * (v * v) + FN * muk)"),
        (
            "    domain 4: v < Sigma3 => (mu4 * (v - V2) - mu3 * (V2 - V) - FN * muk) / m;\n",
            "",
        ),
    ]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 2, "{errs:#?}");
    assert_has(&errs, "29:47", &["the term `v * v` is nonlinear"]);
    assert_has(
        &errs,
        "27:14",
        &["gap: no domain covers the band v < Sigma3"],
    );
}

#[test]
fn first_phase_errors_are_all_reported() {
    let src = with(&[
        ("param mu4 = 0.5;", "param mu4 = 0.5; param mu3 = 0.7;"),
        (
            "boundary Sigma2: v = V1;",
            "boundary Sigma2: v = V1, stick mus;",
        ),
        ("domain 4:", "domain 3:"),
    ]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 3, "{errs:#?}");
    assert_has(&errs, "13:28", &["`mu3` is defined twice"]);
    assert_has(
        &errs,
        "26:14",
        &["only one boundary can carry static friction"],
    );
    assert_has(&errs, "31:12", &["domain 3 is declared twice"]);
}

// An error that leaves a placeholder (a default, a name, a boundary) must not
// be followed by errors computed from that placeholder.

#[test]
fn unknown_name_in_the_mass_is_not_also_a_zero_mass() {
    let src = with(&[("mass: m,", "mass: mm,")]);
    assert_error(&src, "19:15", &["unknown name `mm` in the mass"]);
}

#[test]
fn unknown_name_in_a_boundary_velocity_does_not_reorder_the_bands() {
    let src = with(&[("boundary Sigma2: v = V1;", "boundary Sigma2: v = V9;")]);
    assert_error(
        &src,
        "26:26",
        &["unknown name `V9` in the velocity of Sigma2"],
    );
}

#[test]
fn division_by_zero_in_a_boundary_velocity_does_not_reorder_the_bands() {
    let src = with(&[(
        "boundary Sigma2: v = V1;",
        "boundary Sigma2: v = V1 / (m - m);",
    )]);
    assert_error(
        &src,
        "26:31",
        &["division by zero: `(m - m)` is the constant 0 in the velocity of Sigma2"],
    );
}

#[test]
fn several_errors_in_expressions_are_reported_at_once() {
    let src = with(&[
        ("let FN = m * g;", "let FN = m * gg;"),
        ("forcing: Q0 / m,", "forcing: Q0 / 0.0,"),
        ("(-mu2 * (v - V) + FN * muk)", "(-mu5 * (v - V) + FN * muk)"),
    ]);
    let errs = errors(&src);
    assert_eq!(errs.len(), 3, "{errs:#?}");
    assert_has(&errs, "17:18", &["unknown name `gg`"]);
    assert_has(&errs, "22:23", &["division by zero: `0.0`"]);
    assert_has(&errs, "29:40", &["unknown name `mu5`"]);
}

// --------------------------------------------------------------- robustness

#[test]
fn no_panic_on_damaged_models() {
    // Every line removed, and every line cut in half: the front end must
    // answer (accept or report located errors), never panic.
    let lines: Vec<&str> = BASE.lines().collect();
    for i in 0..lines.len() {
        for variant in 0..2 {
            let mut l = lines.clone();
            let cut;
            if variant == 0 {
                l.remove(i);
            } else {
                let n = l[i].chars().count() / 2;
                cut = l[i].chars().take(n).collect::<String>();
                l[i] = &cut;
            }
            let src = l.join("\n");
            if let Err(report) = generate(&src) {
                assert!(
                    report.contains("--> test.ssm:") && report.ends_with(" in test.ssm\n"),
                    "malformed report for line {} variant {variant}:\n{report}",
                    i + 1
                );
            }
        }
    }
}

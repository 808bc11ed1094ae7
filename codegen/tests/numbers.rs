//! Bad input, classes 3–5 of issue 9: numbers that are not finite, depth,
//! tokens and files, and no false rejections. Each test makes one change to
//! a valid model and asserts the message and its `test.ssm:LINE:COL`, through
//! `generate_source` (or `generate_file` for file-level cases), on a thread
//! with the default 2 MiB stack where depth is concerned.

mod common;

use common::{accepted, edit, errors, parse_report};
use stickslip_codegen::{generate_file, generate_source};

/// A valid two-piece model. Lines: 1 `model`, 2..=10 params, 11 oscillator,
/// 12 boundary, 13..=14 domains, 15 `}`.
const COULOMB: &str = r#"model coulomb {
    param m = 1.0, > 0;
    param d = 0.05, >= 0;
    param c = 1.0, > 0;
    param A = 0.5;
    param W = 1.0, > 0;
    param mu = 0.3;
    param k = 0.1;
    param V = 1.0;
    param tiny = 1e-310;
    oscillator { mass: m, damping: d, stiffness: c, forcing: A, frequency: W }
    boundary Sigma1: v = V, stick 0.5;
    domain 1: v > Sigma1 => mu + k * (v - V);
    domain 2: v < Sigma1 => -mu - k * (V - v);
}
"#;

/// A smooth-law model. Lines: 1 `model`, 2..=10 params, 11 oscillator,
/// 12 `law {`, 13 belt, 14 stick, 15 range, 16 kinetic, 17 `}`, 18 scene, 19 `}`.
const SMOOTH: &str = r#"model smooth {
    param m = 1.0, > 0;
    param d = 0.1, >= 0;
    param c = 4.0, > 0;
    param V = 1.0, > 0;
    param mus = 0.6, >= 0;
    param muk = 0.3, >= 0;
    param vs = 0.4, > 0;
    param g = 9.8, > 0;
    param W = 1.5, > 0;
    oscillator { mass: m, damping: d, stiffness: c, forcing: 6.0 / m, frequency: W }
    law {
        belt: V,
        stick: mus * g * 2.0,
        range: 8.0,
        kinetic: sign(v - V) * (muk + (mus - muk) * exp(-abs(v - V) / vs)) * g,
    }
    scene pl4 { free: W; pieces: 4; }
}
"#;

#[track_caller]
fn assert_error(source: &str, location: &str, message: &str) {
    let errs = errors(source);
    assert_eq!(
        errs,
        vec![(message.to_string(), format!("test.ssm:{location}"))],
        "for:\n{source}"
    );
}

/// Run `f` on a thread with the default stack of a spawned thread (2 MiB):
/// what a build script or a test thread gets.
fn on_default_stack<T: Send + 'static>(f: impl FnOnce() -> T + Send + 'static) -> T {
    std::thread::Builder::new()
        .stack_size(2 << 20)
        .spawn(f)
        .expect("spawn")
        .join()
        .expect("no panic, no stack overflow")
}

// ------------------------------------------------------- numbers: literals

#[test]
fn base_models_are_accepted() {
    accepted(COULOMB);
    accepted(SMOOTH);
}

#[test]
fn literal_that_overflows_is_rejected_at_the_literal() {
    let src = edit(COULOMB, &[("param A = 0.5;", "param A = 1e999;")]);
    assert_error(
        &src,
        "5:15",
        "the number `1e999` in the default of `A` is out of range: it would be inf as an f64",
    );
    let src = edit(COULOMB, &[("param mu = 0.3;", "param mu = 0.3, < 1e999;")]);
    assert_error(
        &src,
        "7:23",
        "the number `1e999` in a bound of `mu` is out of range: it would be inf as an f64",
    );
    let src = edit(COULOMB, &[("stick 0.5", "stick 2e308")]);
    assert_error(
        &src,
        "12:35",
        "the number `2e308` in the static bound of Sigma1 is out of range: it would be inf as an f64",
    );
}

#[test]
fn folded_constant_that_overflows_is_rejected_at_the_operation() {
    let src = edit(COULOMB, &[("param A = 0.5;", "param A = exp(1000.0);")]);
    assert_error(
        &src,
        "5:15",
        "the default of `A`: `exp (1000.0)` evaluates to inf",
    );
    let src = edit(
        COULOMB,
        &[("param A = 0.5;", "param A = 1.0 + 1e308 * 10.0;")],
    );
    assert_error(
        &src,
        "5:21",
        "the default of `A`: `1e308 * 10.0` evaluates to inf",
    );
    // 0 * inf is NaN, reported at the inf, not again at the product.
    let src = edit(
        COULOMB,
        &[("param A = 0.5;", "param A = 0.0 * exp(800.0);")],
    );
    assert_error(
        &src,
        "5:21",
        "the default of `A`: `exp (800.0)` evaluates to inf",
    );
}

#[test]
fn value_at_the_defaults_that_is_not_finite_is_rejected_with_the_names() {
    // The forcing of the issue: `0.5 / m` with a subnormal `m`.
    let src = edit(
        COULOMB,
        &[
            ("param m = 1.0, > 0;", "param m = 1e-310, > 0;"),
            ("forcing: A,", "forcing: 0.5 / m,"),
        ],
    );
    assert_error(
        &src,
        "11:62",
        "the forcing amplitude: `0.5 / m` evaluates to inf at the defaults, with m = 1e-310",
    );
    // A let, a boundary velocity, a static level, a friction law, the frequency.
    let cases = [
        ("stick 0.5", "stick 0.5 * exp(V * 800.0)", "12:41", "the static bound of Sigma1: `exp (V * 800.0)` evaluates to inf at the defaults, with V = 1"),
        ("v = V,", "v = V / (m - 1.0),", "12:26", "the velocity of Sigma1: `V / (m - 1.0)` evaluates to inf at the defaults, with V = 1, m = 1"),
        ("=> mu + k * (v - V);", "=> mu / (k - 0.1) + k * (v - V);", "13:29", "the friction law of domain 1: `mu / (k - 0.1)` evaluates to inf at the defaults, with mu = 0.3, k = 0.1"),
        ("frequency: W }", "frequency: W * powi(10.0 * W, 400) }", "11:80", "the forcing frequency: `powi (10.0 * W , 400)` evaluates to inf at the defaults, with W = 1"),
        ("forcing: A,", "forcing: ln(A - 0.5),", "11:62", "the forcing amplitude: `ln (A - 0.5)` evaluates to -inf at the defaults, with A = 0.5"),
        ("forcing: A,", "forcing: sqrt(A - 1.0),", "11:62", "the forcing amplitude: `sqrt (A - 1.0)` evaluates to NaN at the defaults, with A = 0.5"),
    ];
    for (from, to, at, message) in cases {
        assert_error(&edit(COULOMB, &[(from, to)]), at, message);
    }
    let src = edit(
        COULOMB,
        &[("param V = 1.0;", "param V = 1.0; let q = 1.0 / (V - 1.0);")],
    );
    assert_error(
        &src,
        "9:28",
        "derived quantity `q`: `1.0 / (V - 1.0)` evaluates to inf at the defaults, with V = 1",
    );
}

#[test]
fn subnormal_values_that_lead_to_finite_numbers_are_accepted() {
    // `tiny` = 1e-310 is subnormal: as a term, a factor or a bound it is fine.
    accepted(&edit(
        COULOMB,
        &[
            ("forcing: A,", "forcing: A + tiny * 1e300,"),
            ("param k = 0.1;", "param k = 0.1, > 1e-320;"),
        ],
    ));
}

#[test]
fn powi_exponent_beyond_i32_is_rejected_at_the_exponent() {
    let src = edit(COULOMB, &[("forcing: A,", "forcing: powi(A, 2147483648),")]);
    assert_error(
        &src,
        "11:70",
        "the exponent 2147483648 of `powi` is out of range: it must fit in an i32 (|n| <= 2147483647)",
    );
    let src = edit(
        COULOMB,
        &[("forcing: A,", "forcing: powi(A, -99999999999999999999),")],
    );
    assert_error(
        &src,
        "11:71",
        "the exponent of `powi` is out of range: it must fit in an i32",
    );
    // Nested powers whose product overflows i32 are kept apart, not wrapped.
    accepted(&edit(
        COULOMB,
        &[("forcing: A,", "forcing: A * powi(powi(m, 65536), 65536),")],
    ));
}

// ---------------------------------------------------------- smooth laws

#[test]
fn smooth_law_with_a_pole_in_its_range_is_rejected_at_the_law() {
    // 1 / (v - 2) has its pole at v = 2, inside V ± 8 = [-7, 9]: between
    // grid points, found exactly.
    let src = edit(
        SMOOTH,
        &[(
            "exp(-abs(v - V) / vs)) * g,\n",
            "exp(-abs(v - V) / vs)) * g + 0.01 / (v - 2.0001),\n",
        )],
    );
    assert_error(
        &src,
        "16:18",
        "the kinetic law has a pole at v = 2.0001 (the belt speed 1 + 1.0001), inside the law's range: \
         a smooth law must be finite on V ± range",
    );
    // ln(v + 3) is -inf at v = -3 (a grid point) and NaN below.
    let src = edit(
        SMOOTH,
        &[(
            "exp(-abs(v - V) / vs)) * g,\n",
            "exp(-abs(v - V) / vs)) * g + 0.01 * ln(v + 3.0),\n",
        )],
    );
    assert_error(
        &src,
        "16:18",
        "the kinetic law is -inf at v = -3 (the belt speed 1 - 4), inside the law's range: \
         a smooth law must be finite on V ± range",
    );
}

#[test]
fn smooth_law_whose_second_derivative_is_infinite_at_the_range_end_is_rejected() {
    // sqrt(v + 7) is finite on [-7, 9], but its derivatives are infinite at
    // v = -7, the lower end of the range.
    let src = edit(
        SMOOTH,
        &[(
            "exp(-abs(v - V) / vs)) * g,\n",
            "exp(-abs(v - V) / vs)) * g + 0.01 * sqrt(v + 7.0),\n",
        )],
    );
    assert_error(
        &src,
        "16:18",
        "the kinetic law's first derivative is inf at v = -7 (the belt speed 1 - 8), inside the law's range: \
         a smooth law must be finite on V ± range",
    );
    // Outside the range it is fine.
    accepted(&edit(
        SMOOTH,
        &[(
            "exp(-abs(v - V) / vs)) * g,\n",
            "exp(-abs(v - V) / vs)) * g + 0.01 * sqrt(v + 7.5),\n",
        )],
    ));
}

#[test]
fn stribeck_with_a_small_stribeck_velocity_builds_and_its_pieces_are_continuous() {
    // The shipped model with vs = 0.1 (issue 9, part 5). Its continuity
    // check used to try vs < 0 and call the pieces discontinuous.
    let src = include_str!("../../models/stribeck.ssm");
    for vs in ["0.1", "0.05", "0.4"] {
        let s = src.replace("param vs = 0.4, > 0;", &format!("param vs = {vs}, > 0;"));
        assert!(s.contains(&format!("vs = {vs},")));
        on_default_stack(move || generate_source(&s, "stribeck.ssm").map(|_| ()))
            .unwrap_or_else(|r| panic!("vs = {vs}: {r}"));
    }
}

#[test]
fn continuity_check_tries_only_valid_parameter_values() {
    // Continuous for every vs > 0, but not for vs < 0 (where exp(-1/vs)
    // overflows and the pieces no longer meet numerically).
    let src = edit(SMOOTH, &[("param vs = 0.4, > 0;", "param vs = 0.02, > 0;")]);
    accepted(&src);
}

// ----------------------------------------------------------------- depth

#[test]
fn five_thousand_nested_parentheses_get_a_located_error() {
    let deep = format!("{}A{}", "(".repeat(5000), ")".repeat(5000));
    let src = edit(COULOMB, &[("forcing: A,", &format!("forcing: {deep},"))]);
    let errs = on_default_stack(move || errors(&src));
    assert_eq!(
        errs,
        vec![(
            "expression nested deeper than 64 levels (parentheses, calls and unary operators); split it with `let`".to_string(),
            "test.ssm:11:126".to_string()
        )]
    );
    // 64 levels are fine.
    let ok = format!("{}A{}", "(".repeat(63), ")".repeat(63));
    let src = edit(COULOMB, &[("forcing: A,", &format!("forcing: {ok},"))]);
    on_default_stack(move || accepted(&src).code.len());
}

#[test]
fn five_thousand_unary_minus_signs_get_a_located_error() {
    let deep = format!("{}A", "- ".repeat(5000));
    let src = edit(COULOMB, &[("forcing: A,", &format!("forcing: {deep},"))]);
    let errs = on_default_stack(move || errors(&src));
    assert_eq!(
        errs,
        vec![(
            "expression nested deeper than 64 levels (unary operators and parentheses); split it with `let`".to_string(),
            "test.ssm:11:190".to_string()
        )]
    );
    // Mixed: -(-(-(... counts both.
    let deep = format!("{}A{}", "-(".repeat(40), ")".repeat(40));
    let src = edit(COULOMB, &[("forcing: A,", &format!("forcing: {deep},"))]);
    let errs = on_default_stack(move || errors(&src));
    assert_eq!(errs.len(), 1, "{errs:?}");
    assert!(errs[0].0.starts_with("expression nested deeper than 64"));
}

#[test]
fn sum_of_fifty_thousand_terms_compiles_on_a_default_stack() {
    let n = 50_000;
    let terms: String = (1..=n).map(|i| format!(" + {i}.0 * k")).collect();
    let src = edit(COULOMB, &[("forcing: A,", &format!("forcing: A{terms},"))]);
    let code = on_default_stack(move || accepted(&src).code);
    // Every term reaches the generated code (the last ones too).
    for i in [1, 2, 25_000, 49_999, 50_000] {
        assert!(
            code.contains(&format!("{i}.0")),
            "term {i} in the generated code"
        );
    }
}

// ----------------------------------------------------------------- tokens

#[test]
fn attribute_inside_an_expression_is_rejected() {
    let src = edit(
        COULOMB,
        &[("param A = 0.5;", "param A = #[cfg(any())] 0.5;")],
    );
    assert_error(
        &src,
        "5:15",
        "attributes are not allowed inside an expression (in the default of `A`); only doc comments, and only on items",
    );
    let src = edit(
        COULOMB,
        &[("forcing: A,", "forcing: A + #[cfg(any())] 0.5,")],
    );
    assert_error(
        &src,
        "11:66",
        "attributes are not allowed inside an expression (in the forcing amplitude); only doc comments, and only on items",
    );
}

#[test]
fn doc_comments_with_backslashes_and_quotes_compile() {
    let docs = r##"/// a \ b, "quoted", \n, "#, \\, \u{0}, }"##;
    let src = edit(
        COULOMB,
        &[
            ("model coulomb {", &format!("{docs}\nmodel coulomb {{")),
            ("    param A", &format!("    {docs}\n    param A")),
        ],
    );
    let g = accepted(&src);
    assert!(
        g.doc.contains(r##"a \ b, "quoted", \n, "#, \\"##),
        "{}",
        g.doc
    );
    // The generated module parses as Rust.
    syn::parse_file(&g.code).expect("generated code parses");
}

#[test]
fn byte_order_mark_does_not_shift_columns() {
    let src = format!(
        "\u{feff}{}",
        edit(COULOMB, &[("param A = 0.5;", "param A = q;")])
    );
    assert_error(
        &src,
        "5:15",
        "the default of `A` must be a number; it cannot refer to `q`",
    );
}

#[test]
fn crlf_line_ends_and_tabs_keep_lines_and_columns() {
    let src = edit(COULOMB, &[("param A = 0.5;", "param A = q;")]).replace('\n', "\r\n");
    assert_error(
        &src,
        "5:15",
        "the default of `A` must be a number; it cannot refer to `q`",
    );
    // A tab counts as one column; the caret line repeats it so it lines up.
    let src = edit(COULOMB, &[("    param A = 0.5;", "\tparam A =\tq;")]);
    assert_error(
        &src,
        "5:12",
        "the default of `A` must be a number; it cannot refer to `q`",
    );
    let report = generate_source(&src, "test.ssm").unwrap_err();
    assert!(
        report.contains("5 | \tparam A =\tq;\n  | \t         \t^\n"),
        "{report}"
    );
}

fn temp_file(name: &str, bytes: &[u8]) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("stickslip-numbers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).expect("temp dir");
    let path = dir.join(name);
    std::fs::write(&path, bytes).expect("write");
    path
}

#[test]
fn non_utf8_byte_is_located_at_its_line_and_column() {
    let mut bytes = COULOMB
        .replace("param mu = 0.3;", "param mu = 0.3; // \u{e9}")
        .into_bytes();
    // Replace the two UTF-8 bytes of é by a lone Latin-1 byte.
    let at = bytes.windows(2).position(|w| w == [0xc3, 0xa9]).expect("é");
    bytes.splice(at..at + 2, [0xe9]);
    let path = temp_file("coulomb.ssm", &bytes);
    let report = generate_file(&path, "coulomb.ssm").unwrap_err();
    assert_eq!(
        parse_report(&report),
        vec![(
            "the file is not valid UTF-8 at byte 0xE9 (save it as UTF-8)".to_string(),
            "coulomb.ssm:7:24".to_string()
        )],
        "{report}"
    );
}

#[test]
fn file_named_unlike_its_model_is_located_at_the_name() {
    let path = temp_file("other.ssm", COULOMB.as_bytes());
    let report = generate_file(&path, "models/other.ssm").unwrap_err();
    let errs = parse_report(&report);
    assert_eq!(
        errs,
        vec![(
            "the model is named `coulomb`, but its file is `other.ssm`: name the file `coulomb.ssm` (or the model `other`)".to_string(),
            "models/other.ssm:1:7".to_string()
        )],
        "{report}"
    );
    let path = temp_file("coulomb.ssm", COULOMB.as_bytes());
    generate_file(&path, "models/coulomb.ssm").expect("named after its model");
    // The name does not hide the model's other errors: a law that is not
    // affine in `v` is reported with it.
    let src = edit(COULOMB, &[("mu + k * (v - V);", "mu + k * v * v;")]);
    let path = temp_file("b2.ssm", src.as_bytes());
    let errs = parse_report(&generate_file(&path, "b2.ssm").unwrap_err());
    assert_eq!(errs.len(), 2, "{errs:?}");
    assert!(errs[0].0.contains("but its file is `b2.ssm`"), "{errs:?}");
    assert!(errs[1].0.contains("is not affine in `v`"), "{errs:?}");
}

// -------------------------------------------------------------- messages

#[test]
fn numbers_in_messages_are_rounded() {
    use stickslip_codegen::diagnostic::num;
    assert_eq!(0.1 + 0.2, 0.30000000000000004);
    assert_eq!(num(0.1 + 0.2), "0.3");
    assert_eq!(num(3.7700000000000005), "3.77");
    assert_eq!(num(1e-310), "1e-310");
    assert_eq!(num(-2.5e20), "-2.5e20");
    assert_eq!(num(123456.7), "123456.7");
    assert_eq!(num(f64::INFINITY), "inf");
    // Through the checker: the static bound below the kinetic level.
    let src = edit(
        COULOMB,
        &[
            ("stick 0.5", "stick 0.1 + 0.2"),
            ("param mu = 0.3;", "param mu = 0.37 + 0.1 * 34.0;"),
        ],
    );
    let errs = errors(&src);
    assert!(
        errs.iter()
            .any(|(m, _)| m.contains("= 0.3 is below the kinetic friction level 3.77 above")),
        "{errs:?}"
    );
}

#[test]
fn unbalanced_brace_is_located_at_the_unclosed_delimiter() {
    let src = edit(COULOMB, &[("frequency: W }", "frequency: W")]);
    assert_error(
        &src,
        "11:16",
        "this `{` is never closed (the `}` on line 15 seems to belong to the `{` on line 1)",
    );
    let src = edit(COULOMB, &[("(v - V);", "(v - V));")]);
    assert_error(
        &src,
        "13:45",
        "mismatched closing `)`: the `{` at 1:15 is still open",
    );
    let src = format!("{COULOMB})");
    assert_error(&src, "16:1", "unexpected closing `)`: nothing is open here");
    let src = edit(COULOMB, &[("(v - V);", "(v - V];")]);
    assert_error(
        &src,
        "13:44",
        "mismatched closing `]`: the `(` at 13:38 is still open",
    );
}

#[test]
fn an_unterminated_comment_or_string_is_named_where_it_starts() {
    // A block comment opened on line 7 and never closed swallows the
    // model's closing brace: the comment is the error, not the brace.
    let src = edit(
        COULOMB,
        &[("param V = 1.0;", "param V = 1.0; /* belt /* speed */")],
    );
    assert_error(
        &src,
        "9:20",
        "unterminated block comment: this `/*` is never closed by a `*/` \
         (block comments nest: every `/*` inside needs its own `*/`)",
    );
    let src = edit(
        COULOMB,
        &[(
            "\n}\n",
            "\n    scene s { free: W; structures: \"P_{0_11 1_11}; }\n}\n",
        )],
    );
    assert_error(
        &src,
        "15:36",
        "unterminated string: this `\"` is never closed by another `\"`",
    );
}

#[test]
fn scene_structure_the_runtime_would_reject_is_rejected_at_the_string() {
    // Two stick mappings in a row: the runtime cannot choose an exit side.
    let src = edit(
        COULOMB,
        &[(
            "\n}\n",
            "\n    scene s { free: W; structures: \"P_{0_11 0_11}\", \"P{1_11 0_11}\"; }\n}\n",
        )],
    );
    assert_error(
        &src,
        "15:36",
        "the stick mapping 0_11 must be followed by a mapping that leaves the stick boundary into a domain",
    );
    let src = edit(
        COULOMB,
        &[(
            "\n}\n",
            "\n    scene s { free: W; structures: \"P_{1_11 0_11\"; }\n}\n",
        )],
    );
    assert_error(
        &src,
        "15:36",
        "`P_{1_11 0_11` is not a structure: write `P_{3_31 0_11 3_13 4_33}` or the names alone",
    );
}

/// Known gap (issue 9 part 3 covers syntax depth only): depth through
/// names. 5000 chained `let`s did not finish within 15 minutes in a debug
/// build; run with `N=500 cargo test -- --ignored long_chain` to measure.
#[test]
#[ignore = "depth through chained lets is not bounded yet: slow"]
fn long_chain_of_lets_gets_a_located_error_or_compiles() {
    // Depth through names, not syntax: each `let` adds to the previous one.
    let n: usize = std::env::var("N")
        .ok()
        .and_then(|n| n.parse().ok())
        .unwrap_or(5000);
    let mut lets = String::from("param V = 1.0;\n");
    for i in 1..=n {
        let prev = if i == 1 {
            "k".to_string()
        } else {
            format!("a{}", i - 1)
        };
        lets.push_str(&format!("    let a{i} = {prev} + {i}.0 * k;\n"));
    }
    let src = edit(
        COULOMB,
        &[
            ("param V = 1.0;\n", &lets),
            ("forcing: A,", &format!("forcing: a{n},")),
        ],
    );
    let result = on_default_stack(move || generate_source(&src, "test.ssm").map(|g| g.code.len()));
    eprintln!("{:?}", result.as_ref().map_err(|e| &e[..e.len().min(400)]));
}

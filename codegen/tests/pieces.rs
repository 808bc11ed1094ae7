//! The N-piece models of a smooth law, built on the expression graph by
//! `expand`: each piece is affine and meets the smooth law at its
//! breakpoints, at any values of the law's parameters (the pieces are
//! symbolic in them), compared with the smooth law lowered on its own.

use stickslip_codegen::expand::{expand, Main};
use stickslip_codegen::lowered::LAW_V;
use stickslip_codegen::{model_from_tokens, tokenize};

/// `models/stribeck.ssm` with a scene that frees the law's parameters.
fn model() -> stickslip_codegen::Model {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/stribeck.ssm");
    let text = std::fs::read_to_string(path).expect("models/stribeck.ssm");
    let end = text.rfind('}').expect("a model");
    let source = format!(
        "{}    scene sym {{ free: V, muk, mus, vs, sigma, W; pieces: 8; }}\n}}\n",
        &text[..end]
    );
    model_from_tokens(tokenize(&source).expect("tokens")).expect("a valid model")
}

fn at(v: f64) -> Vec<f64> {
    let mut vars = vec![0.0; LAW_V as usize + 1];
    vars[LAW_V as usize] = v;
    vars
}

#[test]
fn pieces_interpolate_the_law_at_any_parameter_values() {
    let model = model();
    let expanded = expand(&model)
        .map_err(|d| format!("{d:?}"))
        .expect("expands");
    let Main::Smooth(smooth) = &expanded.main else {
        panic!("stribeck has a smooth law")
    };
    let names: Vec<&str> = model.params.iter().map(|p| p.name.as_str()).collect();
    let scene = expanded
        .scenes
        .iter()
        .find(|s| s.module == "sym")
        .expect("scene sym");
    let inst = &scene.instance;
    let (g, sg) = (&inst.lowered.graph, &smooth.lowered.graph);
    assert_eq!(inst.domains.len(), 8);
    let mut checked = 0;
    for scale in [1.0, 0.8, 1.25] {
        // Every parameter at its default, the law's free ones scaled.
        let full: Vec<f64> = model
            .params
            .iter()
            .map(|p| match p.name.as_str() {
                "V" | "muk" | "vs" | "sigma" => p.default * scale,
                _ => p.default,
            })
            .collect();
        let free: Vec<f64> = inst.free.iter().map(|&i| full[i]).collect();
        let belt = full[names.iter().position(|&n| n == "V").expect("V")];
        let law = |v: f64| sg.eval(smooth.law.kinetic, &full, &at(v));
        let velocity = |k: usize| g.eval(inst.lowered.boundary_velocity[k], &free, &[]);
        for (j, d) in inst.domains.iter().enumerate() {
            let piece = |v: f64| g.eval(inst.lowered.domains[j].law, &free, &at(v));
            for edge in [d.lower, d.upper].into_iter().flatten() {
                let v = velocity(edge);
                if inst.boundaries[edge].stick {
                    // The law jumps at the belt speed: the piece takes its
                    // one-sided limit there.
                    assert!((v - belt).abs() < 1e-12 * (1.0 + belt.abs()));
                    // That limit is `±mus g` (the exponential is 1 and the
                    // viscous term 0 there): the static bound, `as = ak`.
                    let side = if d.lower == Some(edge) { 1.0 } else { -1.0 };
                    let param = |n: &str| full[names.iter().position(|&m| m == n).expect(n)];
                    let limit = side * param("mus") * param("g");
                    assert!(
                        (piece(v) - limit).abs() < 1e-13 * (1.0 + limit.abs()),
                        "domain {}: {} at the belt speed, the law's limit is {limit}",
                        d.label,
                        piece(v)
                    );
                } else {
                    let (p, f) = (piece(v), law(v));
                    assert!(
                        (p - f).abs() < 1e-11 * (1.0 + f.abs()),
                        "domain {} at v = {v}: piece {p}, law {f} (scale {scale})",
                        d.label
                    );
                }
                checked += 1;
            }
            // Affine: the midpoint of two points of the band is the mean.
            let (a, b) = match (d.lower, d.upper) {
                (Some(l), Some(u)) => (velocity(l), velocity(u)),
                (Some(l), None) => (velocity(l), velocity(l) + 1.0),
                (None, Some(u)) => (velocity(u) - 1.0, velocity(u)),
                (None, None) => unreachable!("eight pieces have edges"),
            };
            let mid = piece(0.5 * (a + b));
            let mean = 0.5 * (piece(a) + piece(b));
            assert!((mid - mean).abs() < 1e-12 * (1.0 + mean.abs()));
        }
    }
    assert_eq!(checked, 3 * (2 * 7));
}

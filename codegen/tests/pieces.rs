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

/// `models/stribeck.ssm` with the scenes `extra` added.
fn with_scenes(extra: &str) -> stickslip_codegen::Model {
    let path = concat!(env!("CARGO_MANIFEST_DIR"), "/../models/stribeck.ssm");
    let text = std::fs::read_to_string(path).expect("models/stribeck.ssm");
    let end = text.rfind('}').expect("a model");
    let source = format!("{}    {extra}\n}}\n", &text[..end]);
    model_from_tokens(tokenize(&source).expect("tokens")).expect("a valid model")
}

/// The offsets `|v - V|` of the breakpoints below the belt speed of scene
/// `name`, at the defaults, ascending.
fn offsets_below(model: &stickslip_codegen::Model, name: &str) -> Vec<f64> {
    let expanded = expand(model)
        .map_err(|d| format!("{d:?}"))
        .expect("expands");
    let scene = expanded
        .scenes
        .iter()
        .find(|s| s.module == name)
        .expect("the scene");
    let inst = &scene.instance;
    let free: Vec<f64> = inst.free.iter().map(|&i| model.params[i].default).collect();
    let g = &inst.lowered.graph;
    let belt = model
        .params
        .iter()
        .find(|p| p.name == "V")
        .expect("V")
        .default;
    let mut u: Vec<f64> = inst
        .lowered
        .boundary_velocity
        .iter()
        .map(|&b| belt - g.eval(b, &free, &[]))
        .filter(|&u| u > 0.0)
        .collect();
    u.sort_by(f64::total_cmp);
    u
}

/// The law of `stribeck.ssm` below the belt speed, at `u = V - v`, in closed
/// form: `f'(v) = -(mus - muk) g / vs exp(-u / vs) + sigma`, and the
/// cumulative density of de Boor's rule, `∫ sqrt|f''|` from 0 to `u`, up to
/// a factor: `1 - exp(-u / (2 vs))`.
struct Below {
    d: f64,
    fall: f64,
    vs: f64,
    sigma: f64,
}

impl Below {
    fn new(model: &stickslip_codegen::Model) -> Self {
        let p = |n: &str| model.params.iter().find(|p| p.name == n).expect(n).default;
        Below {
            d: p("d"),
            fall: (p("mus") - p("muk")) * p("g") / p("vs"),
            vs: p("vs"),
            sigma: p("sigma"),
        }
    }
    /// Where `2 d + f'` vanishes.
    fn hopf(&self) -> f64 {
        self.vs * (self.fall / (2.0 * self.d + self.sigma)).ln()
    }
    fn level(&self, u: f64) -> f64 {
        1.0 - (-u / (2.0 * self.vs)).exp()
    }
    fn offset(&self, level: f64) -> f64 {
        -2.0 * self.vs * (1.0 - level).ln()
    }
}

/// Breakpoints equidistribute `∫ sqrt|f''|` (de Boor's rule, against its
/// closed form); a scene that frees the damping can move steady sliding's
/// stability, and gets a breakpoint exactly where `2 d + f'` vanishes at the
/// defaults, the rest equidistributed on either side of it (three of the
/// four pieces below it, where the density is). A scene that frees only the
/// forcing keeps the plain rule.
#[test]
fn a_breakpoint_sits_where_steady_sliding_changes_stability() {
    let model = with_scenes(
        "scene damped { free: d, W; pieces: 8; }\n    scene forced { free: W, Q0; pieces: 8; }",
    );
    let law = Below::new(&model);
    let total = law.level(8.0);
    // Free only the forcing: u_j at levels j/4 of the total.
    let plain = offsets_below(&model, "forced");
    assert_eq!(plain.len(), 3);
    for (j, &u) in plain.iter().enumerate() {
        let expected = law.offset(total * (j + 1) as f64 / 4.0);
        assert!((u - expected).abs() <= 2e-3 * expected, "{plain:?}");
    }
    // Free the damping: a breakpoint at the stability change.
    let pinned = offsets_below(&model, "damped");
    let hopf = law.hopf();
    assert_eq!(pinned.len(), 3);
    assert!(
        (pinned[2] - hopf).abs() <= 4.0 * f64::EPSILON * hopf,
        "{pinned:?} against {hopf}"
    );
    for (j, &u) in pinned[..2].iter().enumerate() {
        let expected = law.offset(law.level(hopf) * (j + 1) as f64 / 3.0);
        assert!((u - expected).abs() <= 2e-3 * expected, "{pinned:?}");
    }
    // No piece straddles the change: steady sliding on the piece just
    // inside it (the secant slope in `v`) is unstable, just outside stable.
    let f = |u: f64| -law.fall * law.vs * (-u / law.vs).exp() - law.sigma * u;
    let secant = |a: f64, b: f64| -(f(b) - f(a)) / (b - a);
    let inside = 2.0 * law.d + secant(pinned[1], hopf);
    let outside = 2.0 * law.d + secant(hopf, 8.0);
    assert!(inside < 0.0 && outside > 0.0, "{inside} {outside}");
}

//! What `sweep` shows of branches and bifurcations — the JSON, the text
//! report, the figure and `--no-unstable` — on a synthetic sweep built here
//! from closed forms: a branch turning back at a fold (stable half, unstable
//! half), a branch losing stability at a period doubling with the doubled
//! branch born there, and a branch losing it at a Neimark–Sacker point.
//! Every number checked is computed again from those forms.

use std::f64::consts::TAU;
use std::path::PathBuf;
use std::process::Command;

use serde_json::Value;
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::output::figure::layout::Rect;
use stickslip::output::figure::palette::category;
use stickslip::output::figure::register;
use stickslip::output::figure::sweep::{
    plot_sweep, SweepFigure, View, STABLE_WIDTH, UNSTABLE_WIDTH,
};
use stickslip::output::sweep_table;
use stickslip::study::sweep::{
    BifurcationSummary, BranchEndSummary, BranchSample, BranchSummary, Cut, MotionSummary, Sweep,
    SweepPoint, Transition, TransitionKind,
};

const A: &str = "P_{3_31 0_11 3_13 4_33}";
const B: &str = "P_{3_33 4_33}";
const BB: &str = "P_{3_33 4_33 3_33 4_33}";
const C: &str = "P_{3_31 1_11 3_13 4_33}";

/// Branch A, by arclength `s ∈ [0, 1]`: `W = 2 − 4 (s − ½)²` turns back at
/// W = 2; `λ = 0.6 + 0.8 s` reaches +1 there.
fn fold_at(s: f64) -> (f64, f64, f64, f64) {
    (2.0 - 4.0 * (s - 0.5).powi(2), 1.0 + s, s, 0.6 + 0.8 * s)
}

/// Branch B: phase `(5.5 + W/2) mod 2π` (it wraps), `x = W/2`,
/// `λ = −(W/2 − ¼)`, −1 at W = 2.5.
fn pd_at(w: f64) -> (f64, f64, f64) {
    ((5.5 + 0.5 * w).rem_euclid(TAU), 0.5 * w, -(0.5 * w - 0.25))
}

/// Branch C: a complex pair of modulus `0.5 + 0.625 (W − 1)` at angle 0.9,
/// on the unit circle at W = 1.8.
fn ns_at(w: f64) -> [[f64; 2]; 2] {
    let r = 0.5 + 0.625 * (w - 1.0);
    [
        [r * 0.9f64.cos(), r * 0.9f64.sin()],
        [r * 0.9f64.cos(), -r * 0.9f64.sin()],
    ]
}

fn modulus(e: &[[f64; 2]]) -> f64 {
    e.iter().map(|z| z[0].hypot(z[1])).fold(0.0, f64::max)
}

fn sample(value: f64, points: Vec<(f64, f64)>, eigenvalues: Vec<[f64; 2]>) -> BranchSample {
    BranchSample {
        value,
        start_wt: points[0].0,
        start_x: points[0].1,
        stable: modulus(&eigenvalues) < 1.0,
        max_abs_x: points.iter().map(|p| p.1.abs()).fold(0.0, f64::max),
        max_abs_v: 1.0 + value,
        period: None,
        eigenvalues,
        points: points
            .into_iter()
            .map(|(phase, x)| SwitchingPoint { phase, x })
            .collect(),
    }
}

fn end(value: f64, reason: &str, boundary: Option<&str>, detail: Option<&str>) -> BranchEndSummary {
    BranchEndSummary {
        value,
        reason: reason.into(),
        boundary: boundary.map(String::from),
        detail: detail.map(String::from),
    }
}

fn motion(structure: &str, w: f64) -> MotionSummary {
    let (phase, x, l) = pd_at(w);
    MotionSummary {
        structure: structure.into(),
        n: 1,
        start_wt: phase,
        start_x: x,
        eigenvalues: vec![[l, 0.0], [0.1, 0.0]],
        stable: l.abs() < 1.0,
        max_abs_x: x.abs(),
        max_abs_v: 1.0 + w,
        max_v: None,
        period: None,
        points: vec![SwitchingPoint { phase, x }],
    }
}

fn branches() -> Vec<BranchSummary> {
    let fold: Vec<BranchSample> = (0..20)
        .map(|k| {
            let (w, phase, x, l) = fold_at((k as f64 + 0.5) / 20.0);
            sample(
                w,
                vec![(phase, x), (phase + 2.0, -x)],
                vec![[l, 0.0], [0.2, 0.0]],
            )
        })
        .collect();
    let (first, last) = (fold[0].value, fold[19].value);
    let pd: Vec<BranchSample> = (0..20)
        .map(|k| {
            let w = 1.05 + 0.1 * k as f64;
            let (phase, x, l) = pd_at(w);
            sample(w, vec![(phase, x)], vec![[l, 0.0], [0.1, 0.0]])
        })
        .collect();
    let doubled: Vec<BranchSample> = (1..=10)
        .map(|k| {
            let w = 2.5 + 0.05 * k as f64;
            let d = (w - 2.5).sqrt();
            let (phase, x, _) = pd_at(w);
            sample(
                w,
                vec![(phase, x + d), (phase, x - d)],
                vec![[0.5, 0.0], [0.1, 0.0]],
            )
        })
        .collect();
    let ns: Vec<BranchSample> = (0..12)
        .map(|k| {
            let w = 1.05 + 0.1 * k as f64;
            sample(w, vec![(0.5 * w, 1.0 - w)], ns_at(w).to_vec())
        })
        .collect();
    vec![
        BranchSummary {
            id: 0,
            structure: A.into(),
            n: 1,
            points: fold,
            ends: vec![
                end(first, "parameter_bound", None, None),
                end(last, "grazing", Some("Sigma1"), None),
            ],
        },
        BranchSummary {
            id: 1,
            structure: B.into(),
            n: 1,
            points: pd,
            ends: vec![
                end(1.0, "parameter_bound", None, None),
                end(3.0, "parameter_bound", None, None),
            ],
        },
        BranchSummary {
            id: 2,
            structure: BB.into(),
            n: 2,
            points: doubled,
            ends: vec![end(3.0, "parameter_bound", None, None)],
        },
        BranchSummary {
            id: 3,
            structure: C.into(),
            n: 1,
            points: ns,
            ends: vec![
                end(1.0, "parameter_bound", None, None),
                end(
                    2.2,
                    "newton_failure",
                    None,
                    Some("no convergence in 40 steps"),
                ),
            ],
        },
    ]
}

fn bifurcations() -> Vec<BifurcationSummary> {
    let (_, fold_phase, fold_x, _) = fold_at(0.5);
    let (pd_phase, pd_x, _) = pd_at(2.5);
    let ns = ns_at(1.8)[0];
    let b = |value, kind, structure: &str, eigenvalue, branch, born: Vec<usize>, at: (f64, f64)| {
        BifurcationSummary {
            value,
            kind,
            structure: structure.into(),
            n: 1,
            eigenvalue,
            branch,
            born,
            start_wt: at.0,
            start_x: at.1,
            max_abs_x: at.1.abs(),
            max_abs_v: 1.0 + value,
        }
    };
    vec![
        b(
            1.8,
            TransitionKind::NeimarkSacker,
            C,
            ns,
            3,
            vec![],
            (0.9, -0.8),
        ),
        b(
            2.0,
            TransitionKind::Fold,
            A,
            [1.0, 0.0],
            0,
            vec![],
            (fold_phase, fold_x),
        ),
        b(
            2.5,
            TransitionKind::PeriodDoubling,
            B,
            [-1.0, 0.0],
            1,
            vec![2],
            (pd_phase, pd_x),
        ),
    ]
}

fn synthetic(param: &str) -> Sweep {
    let grid = [1.0, 1.5, 2.0, 2.5, 3.0];
    let points = grid
        .iter()
        .map(|&w| {
            let mut motions = vec![motion(B, w)];
            if w == 1.0 {
                motions.push(MotionSummary {
                    structure: "NM".into(),
                    n: 1,
                    start_wt: f64::NAN,
                    start_x: f64::NAN,
                    eigenvalues: vec![],
                    stable: true,
                    max_abs_x: 0.2,
                    max_abs_v: 0.3,
                    max_v: Some(0.3),
                    period: None,
                    points: vec![],
                });
            }
            SweepPoint { value: w, motions }
        })
        .collect();
    Sweep {
        param: param.into(),
        points,
        transitions: vec![
            Transition {
                value: 2.2,
                from: C.into(),
                to: B.into(),
                kind: TransitionKind::Grazing,
                boundary: Some("Sigma1".into()),
            },
            Transition {
                value: 2.5,
                from: B.into(),
                to: format!("{BB}^2"),
                kind: TransitionKind::PeriodDoubling,
                boundary: None,
            },
        ],
        branches: branches(),
        bifurcations: bifurcations(),
        cuts: vec![Cut {
            value: 2.5,
            structure: format!("({BB})^{{×2}}"),
            n: 2,
            max_period: 1,
        }],
        cascades: Vec::new(),
    }
}

fn close(v: &Value, x: f64) -> bool {
    v.as_f64()
        .is_some_and(|y| (y - x).abs() <= 1e-12 * (1.0 + x.abs()))
}

#[test]
fn json_lists_branches_and_bifurcations_keyed_by_the_parameter() {
    let s = synthetic("W");
    let v: Value = serde_json::from_str(&sweep_table::json(&s).unwrap()).unwrap();
    let keys: Vec<&str> = v.as_object().unwrap().keys().map(String::as_str).collect();
    assert_eq!(
        keys,
        [
            "param",
            "points",
            "transitions",
            "branches",
            "bifurcations",
            "cuts",
            "cascades"
        ]
    );
    // A branch born by period doubling and not followed, keyed by `W`.
    assert!(close(&v["cuts"][0]["W"], 2.5));
    assert_eq!(v["cuts"][0]["N"], 2);
    assert_eq!(v["cuts"][0]["max_period"], 1);
    // The old keys keep their meaning.
    assert_eq!(v["points"].as_array().unwrap().len(), 5);
    assert!(close(&v["points"][3]["W"], 2.5));
    assert_eq!(v["points"][3]["motions"][0]["structure"], B);
    assert_eq!(v["transitions"][1]["kind"], "period_doubling");
    assert_eq!(v["transitions"][0]["boundary"], "Sigma1");
    // Branches: every point with its value under `W`, in arclength order.
    let bs = v["branches"].as_array().unwrap();
    assert_eq!(bs.len(), 4);
    for (j, b) in bs.iter().enumerate() {
        let mut keys: Vec<&str> = b.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(keys, ["N", "ends", "id", "points", "structure"]);
        assert_eq!(b["id"], j);
    }
    let fold = &bs[0];
    assert_eq!(
        (fold["structure"].as_str(), fold["N"].as_u64()),
        (Some(A), Some(1))
    );
    let pts = fold["points"].as_array().unwrap();
    assert_eq!(pts.len(), 20);
    for (k, p) in pts.iter().enumerate() {
        let mut keys: Vec<&str> = p.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "W",
                "eigenvalues",
                "max_abs_v",
                "max_abs_x",
                "stable",
                "start_Wt",
                "start_x"
            ]
        );
        let (w, phase, x, l) = fold_at((k as f64 + 0.5) / 20.0);
        assert!(close(&p["W"], w), "{p}");
        assert!(
            close(&p["start_Wt"], phase) && close(&p["start_x"], x),
            "{p}"
        );
        assert!(close(&p["eigenvalues"][0][0], l) && close(&p["eigenvalues"][1][0], 0.2));
        // Stable on the way up to the fold, unstable on the way back.
        assert_eq!(p["stable"], k < 10, "point {k}");
    }
    assert_eq!(bs[2]["N"], 2);
    assert_eq!(
        bs[2]["points"][0]["eigenvalues"][0],
        serde_json::json!([0.5, 0.0])
    );
    // Ends: `boundary` and `detail` only where they apply.
    let ends = fold["ends"].as_array().unwrap();
    assert_eq!(ends[0]["reason"], "parameter_bound");
    assert!(ends[0].get("boundary").is_none() && ends[0].get("detail").is_none());
    assert_eq!(
        (ends[1]["reason"].as_str(), ends[1]["boundary"].as_str()),
        (Some("grazing"), Some("Sigma1"))
    );
    assert!(close(&ends[1]["W"], fold_at(19.5 / 20.0).0));
    assert_eq!(bs[2]["ends"].as_array().unwrap().len(), 1);
    let failed = &bs[3]["ends"][1];
    assert_eq!(failed["reason"], "newton_failure");
    assert_eq!(failed["detail"], "no convergence in 40 steps");
    assert!(close(&failed["W"], 2.2));
    // Bifurcations.
    let fs = v["bifurcations"].as_array().unwrap();
    let kinds: Vec<&str> = fs.iter().map(|f| f["kind"].as_str().unwrap()).collect();
    assert_eq!(kinds, ["neimark_sacker", "fold", "period_doubling"]);
    for f in fs {
        let mut keys: Vec<&str> = f.as_object().unwrap().keys().map(String::as_str).collect();
        keys.sort_unstable();
        assert_eq!(
            keys,
            [
                "N",
                "W",
                "born",
                "branch",
                "eigenvalue",
                "kind",
                "max_abs_v",
                "max_abs_x",
                "start_Wt",
                "start_x",
                "structure"
            ]
        );
    }
    let ns = &fs[0];
    assert!(close(&ns["W"], 1.8));
    let z = ns["eigenvalue"].as_array().unwrap();
    let (re, im) = (z[0].as_f64().unwrap(), z[1].as_f64().unwrap());
    assert!((re.hypot(im) - 1.0).abs() < 1e-12 && (im.atan2(re) - 0.9).abs() < 1e-12);
    assert_eq!(
        (ns["structure"].as_str(), ns["branch"].as_u64()),
        (Some(C), Some(3))
    );
    let pd = &fs[2];
    assert_eq!(pd["eigenvalue"], serde_json::json!([-1.0, 0.0]));
    assert_eq!(pd["born"], serde_json::json!([2]));
    assert!(close(&pd["start_Wt"], pd_at(2.5).0) && close(&pd["start_x"], 1.25));
    assert_eq!(fs[1]["born"], serde_json::json!([]));
}

#[test]
fn json_of_the_stable_only_view_has_no_unstable_point_and_all_bifurcations() {
    let s = synthetic("W").stable_only();
    let v: Value = serde_json::from_str(&sweep_table::json(&s).unwrap()).unwrap();
    let stable = |p: &Value| p["stable"].as_bool().unwrap();
    let bs = v["branches"].as_array().unwrap();
    assert_eq!(bs.len(), 4, "every branch has a stable stretch");
    for b in bs {
        assert!(
            b["points"].as_array().unwrap().iter().all(stable),
            "{}",
            b["id"]
        );
    }
    assert_eq!(bs[0]["points"].as_array().unwrap().len(), 10);
    for p in v["points"].as_array().unwrap() {
        assert!(p["motions"].as_array().unwrap().iter().all(stable));
    }
    assert_eq!(v["bifurcations"].as_array().unwrap().len(), 3);
}

#[test]
fn a_parameter_named_like_a_key_is_refused() {
    for name in ["N", "stable", "kind", "motions"] {
        let e = sweep_table::json(&synthetic(name)).expect_err(name);
        assert!(e.to_string().contains(&format!("`{name}`")), "{e}");
    }
    // Any other name is fine.
    assert!(sweep_table::json(&synthetic("Q0")).is_ok());
}

fn lines_between<'a>(text: &'a str, start: &str, stop: &str) -> Vec<&'a str> {
    text.lines()
        .skip_while(|l| *l != start)
        .skip(1)
        .take_while(|l| *l != stop && !l.is_empty())
        .collect()
}

#[test]
fn text_report_lists_bifurcations_branches_and_their_stable_stretches() {
    let s = synthetic("W");
    let text = sweep_table::text(&s, 1.0, 3.0, 5, "Q0=70", true);
    let bif = lines_between(&text, "bifurcations:", "");
    assert_eq!(bif.len(), 3, "{text}");
    assert!(bif[0].starts_with("  W = 1.800000000000 "), "{}", bif[0]);
    assert!(bif[0].contains("neimark_sacker") && bif[0].contains(C));
    let (c, d) = (0.9f64.cos(), 0.9f64.sin());
    assert!(
        bif[0].contains(&format!("λ = {c:+.6}{d:+.6}i")),
        "{}",
        bif[0]
    );
    assert!(bif[0].ends_with("on branch #3"), "{}", bif[0]);
    assert!(bif[1].contains(" fold ") && bif[1].contains("λ = +1.000000+0.000000i"));
    assert!(bif[2].contains("period_doubling") && bif[2].contains("λ = -1.000000+0.000000i"));
    assert!(bif[2].ends_with("on branch #1, born #2"), "{}", bif[2]);

    let br = lines_between(&text, "branches:", "");
    // The fold branch: its range, the stable way up to the fold, the
    // unstable way back, how it ends.
    let (lo, hi) = (fold_at(0.5 / 20.0).0, fold_at(9.5 / 20.0).0);
    assert_eq!(
        br[0],
        format!("  #0 {A}: W from {lo:.6} to {hi:.6}, 20 points")
    );
    assert_eq!(
        br[1],
        format!("      stable    W = {lo:.6} -> 2.000000 (fold)")
    );
    let back = fold_at(19.5 / 20.0).0;
    assert_eq!(
        br[2],
        format!("      unstable  W = 2.000000 (fold) -> {back:.6}")
    );
    assert_eq!(
        br[3],
        format!("      ends: parameter_bound at W = {lo:.6}; grazing at W = {back:.6} (on Sigma1)")
    );
    // The period doubling and the branch born there.
    let at = |id: &str| br.iter().position(|l| l.starts_with(id)).unwrap();
    let b1 = at("  #1 ");
    assert_eq!(
        br[b1 + 1],
        "      stable    W = 1.050000 -> 2.500000 (period_doubling)"
    );
    assert_eq!(
        br[b1 + 2],
        "      unstable  W = 2.500000 (period_doubling) -> 2.950000"
    );
    let b2 = at("  #2 ");
    assert_eq!(
        br[b2],
        format!("  #2 {BB}^2: W from 2.550000 to 3.000000, 10 points")
    );
    assert_eq!(br[b2 + 1], "      stable    W = 2.550000 -> 3.000000");
    assert_eq!(br[b2 + 2], "      ends: parameter_bound at W = 3.000000");
    let b3 = at("  #3 ");
    assert_eq!(
        br[b3 + 1],
        "      stable    W = 1.050000 -> 1.800000 (neimark_sacker)"
    );
    assert!(br[b3 + 3].ends_with("newton_failure at W = 2.200000 (no convergence in 40 steps)"));
    // The motions as before: the unstable one marked.
    let motions = lines_between(&text, "motions:", "");
    assert_eq!(motions.len(), 5);
    assert_eq!(motions[4], format!("  W = 3.000000   {B} (unstable)"));
    assert_eq!(motions[0], format!("  W = 1.000000   {B}  +  NM"));

    // Today's view: nothing unstable, the rest unchanged.
    let stable = sweep_table::text(&s, 1.0, 3.0, 5, "Q0=70", false);
    assert!(!stable.contains("unstable"), "{stable}");
    let br = lines_between(&stable, "branches:", "");
    assert_eq!(
        br[1],
        format!("      stable    W = {lo:.6} -> 2.000000 (fold)")
    );
    assert!(br[2].starts_with("      ends: "), "{}", br[2]);
    assert_eq!(lines_between(&stable, "bifurcations:", "").len(), 3);
    assert_eq!(
        lines_between(&stable, "motions:", "")[4],
        "  W = 3.000000   "
    );
}

/// SVG elements `<tag …/>` as their attribute text.
fn elements<'a>(svg: &'a str, tag: &str) -> Vec<&'a str> {
    svg.split(&format!("<{tag} "))
        .skip(1)
        .filter_map(|e| e.split_once("/>").map(|(a, _)| a))
        .collect()
}

/// The texts of the SVG, trimmed.
fn texts(svg: &str) -> Vec<String> {
    svg.split("<text")
        .skip(1)
        .filter_map(|t| t.split_once('>').and_then(|(_, r)| r.split_once("</text>")))
        .map(|(t, _)| t.trim().to_string())
        .collect()
}

fn hex(c: plotters::style::RGBColor) -> String {
    format!("#{:02X}{:02X}{:02X}", c.0, c.1, c.2)
}

fn tmp(name: &str) -> PathBuf {
    let dir = PathBuf::from(env!("CARGO_TARGET_TMPDIR")).join("sweep_output");
    std::fs::create_dir_all(&dir).unwrap();
    dir.join(name)
}

/// The polylines of colour `c` and width `w`.
fn lines(svg: &str, c: &str, w: u32) -> usize {
    elements(svg, "polyline")
        .iter()
        .filter(|e| {
            e.contains(&format!("stroke=\"{c}\"")) && e.contains(&format!("stroke-width=\"{w}\""))
        })
        .count()
}

#[test]
fn figure_draws_stable_solid_unstable_dashed_and_one_mark_per_bifurcation() {
    register().unwrap();
    let s = synthetic("W");
    // Colours by first appearance: the grid's motions, then the branches.
    let colour = |rank: usize| hex(category(rank));
    let (cb, ca, cbb, cc) = (colour(0), colour(1), colour(2), colour(3));
    let all = tmp("all.svg");
    plot_sweep(&s, "synthetic", &all, true, View::Diagram).unwrap();
    // The PNG backend draws it too.
    let png = tmp("all.png");
    plot_sweep(
        &s,
        "a synthetic sweep: fold, period doubling, Neimark–Sacker",
        &png,
        true,
        View::Diagram,
    )
    .unwrap();
    assert!(std::fs::metadata(&png).unwrap().len() > 10_000);
    let svg = std::fs::read_to_string(&all).unwrap();
    for c in [&ca, &cb, &cbb, &cc] {
        assert!(lines(&svg, c, STABLE_WIDTH) >= 1, "no solid line in {c}");
    }
    // Dashed: many short pieces, for the three branches with an unstable part.
    for c in [&ca, &cb, &cc] {
        assert!(lines(&svg, c, UNSTABLE_WIDTH) >= 8, "no dashes in {c}");
    }
    assert_eq!(
        lines(&svg, &cbb, UNSTABLE_WIDTH),
        0,
        "the doubled branch is stable"
    );
    // One mark per bifurcation in each of the four panels, plus one per kind
    // in the key: squares and triangles filled, rings stroked.
    let ink = hex(stickslip::output::figure::symbol::INK);
    let filled = elements(&svg, "polygon")
        .iter()
        .filter(|e| e.contains(&format!("fill=\"{ink}\"")))
        .count();
    assert_eq!(filled, 2 * 4 + 2);
    let rings = elements(&svg, "circle")
        .iter()
        .filter(|e| e.contains(&format!("stroke=\"{ink}\"")))
        .count();
    assert_eq!(rings, 4 + 1);
    let texts = texts(&svg);
    for label in ["NS1", "F2", "PD3"] {
        let n = texts.iter().filter(|t| *t == label).count();
        assert_eq!(n, 5, "{label}: 4 panels + key");
    }

    // Without the unstable parts: the same solid lines, no dash, the marks.
    let stable = tmp("stable.svg");
    plot_sweep(&s, "synthetic", &stable, false, View::Diagram).unwrap();
    let svg2 = std::fs::read_to_string(&stable).unwrap();
    for c in [&ca, &cb, &cbb, &cc] {
        assert!(lines(&svg2, c, STABLE_WIDTH) >= 1, "no solid line in {c}");
        assert_eq!(lines(&svg2, c, UNSTABLE_WIDTH), 0, "dashes left in {c}");
    }
    let filled2 = elements(&svg2, "polygon")
        .iter()
        .filter(|e| e.contains(&format!("fill=\"{ink}\"")))
        .count();
    assert_eq!(filled2, filled);
    // The unstable grid motion (a ring) is gone too.
    let hollow = |svg: &str| {
        elements(svg, "circle")
            .iter()
            .filter(|e| e.contains(&format!("stroke=\"{cb}\"")) && e.contains("fill=\"none\""))
            .count()
    };
    assert!(hollow(&svg) >= 1 && hollow(&svg2) == 0);
}

fn check_labels(s: &Sweep, per_panel: usize) -> Vec<stickslip::output::figure::sweep::Label> {
    let figure = SweepFigure::new(s, "labels");
    let labels = figure.labels().unwrap();
    let (tags, key) = figure.placed().unwrap();
    assert_eq!(
        labels.len(),
        4 * per_panel,
        "every bifurcation labelled in every panel"
    );
    let marks: Vec<Rect> = labels.iter().map(|l| l.mark).collect();
    for (i, a) in labels.iter().enumerate() {
        assert!(a.rect.inside(&a.plot), "{a:?} leaves its panel");
        for b in &labels[i + 1..] {
            assert!(!a.rect.overlaps(&b.rect), "{a:?} overlaps {b:?}");
        }
        for m in &marks {
            assert!(!a.rect.overlaps(m), "{a:?} covers a mark {m:?}");
        }
        for t in tags.iter().flatten() {
            assert!(!a.rect.overlaps(&t.rect), "{a:?} overlaps tag {t:?}");
        }
        for k in &key {
            assert!(!a.rect.overlaps(k), "{a:?} overlaps the key {k:?}");
        }
    }
    labels
}

#[test]
fn bifurcation_labels_sit_by_their_marks_apart_from_each_other_and_the_tags() {
    register().unwrap();
    let s = synthetic("W");
    let labels = check_labels(&s, 3);
    for l in &labels {
        let (cx, cy) = ((l.mark.x0 + l.mark.x1) / 2, (l.mark.y0 + l.mark.y1) / 2);
        assert!(
            l.rect.distance2((cx, cy)) <= 12 * 12,
            "{l:?} far from its mark"
        );
    }
    let texts: Vec<&str> = labels.iter().take(3).map(|l| l.text.as_str()).collect();
    assert_eq!(texts, ["NS1", "F2", "PD3"]);

    // Crowded: thirty folds within a few pixels, all on |λ| = 1.
    let mut crowded = synthetic("W");
    crowded.bifurcations = (0..30)
        .map(|k| BifurcationSummary {
            value: 2.0 + 1e-4 * k as f64,
            kind: [TransitionKind::Fold, TransitionKind::BranchPoint][k % 2],
            ..bifurcations()[1].clone()
        })
        .collect();
    check_labels(&crowded, 30);
}

const BIN: &str = env!("CARGO_BIN_EXE_stickslip");

fn sweep_cli(extra: &[&str]) -> String {
    let mut args = vec![
        "sweep",
        "--param",
        "W=10.7:10.95:6",
        "--set",
        "Q0=100,mu3=3",
    ];
    args.extend_from_slice(extra);
    let o = Command::new(BIN).args(&args).output().unwrap();
    assert!(
        o.status.success(),
        "{args:?}: {}",
        String::from_utf8_lossy(&o.stderr)
    );
    String::from_utf8(o.stdout).unwrap()
}

/// JSON with and without `--no-unstable`: what is left out is unstable.
fn with_and_without() -> (Value, Value) {
    let all: Value = serde_json::from_str(&sweep_cli(&["--json"])).unwrap();
    let stable: Value = serde_json::from_str(&sweep_cli(&["--json", "--no-unstable"])).unwrap();
    (all, stable)
}

#[test]
fn no_unstable_through_the_cli_keeps_transitions_bifurcations_and_stable_motions() {
    let (all, stable) = with_and_without();
    assert_eq!(stable["param"], "W");
    assert_eq!(stable["transitions"], all["transitions"]);
    assert_eq!(stable["bifurcations"], all["bifurcations"]);
    let motions = |v: &Value, want: bool| -> Vec<Value> {
        v["points"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p["motions"].as_array().unwrap().clone())
            .filter(|m| m["stable"] == want)
            .collect()
    };
    assert!(!motions(&all, true).is_empty());
    assert_eq!(motions(&stable, true), motions(&all, true));
    assert!(motions(&stable, false).is_empty());
    assert!(!sweep_cli(&["--no-unstable"]).contains("unstable"));
}

/// Needs a sweep that keeps unstable motions (the arclength continuation
/// of issue 11): past the period doubling near W = 10.8 the period-1
/// motion goes on unstable. Today's sweep reports none there.
#[test]

fn no_unstable_through_the_cli_drops_every_unstable_motion() {
    let (all, stable) = with_and_without();
    let unstable = |v: &Value| {
        let motions = v["points"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|p| p["motions"].as_array().unwrap().clone());
        let samples = v["branches"]
            .as_array()
            .unwrap()
            .iter()
            .flat_map(|b| b["points"].as_array().unwrap().clone());
        motions
            .chain(samples)
            .filter(|m| m["stable"] == false)
            .count()
    };
    assert!(unstable(&all) > 0, "the case has unstable motions");
    assert_eq!(unstable(&stable), 0);
    assert_eq!(stable["transitions"], all["transitions"]);
    assert_eq!(stable["bifurcations"], all["bifurcations"]);
    assert!(sweep_cli(&[]).contains("(unstable)"));
    assert!(!sweep_cli(&["--no-unstable"]).contains("unstable"));
    // The figure too: dashed (thin) lines of a structure's colour only
    // without the flag.
    let thin = |flags: &[&str], name: &str| {
        let plot = tmp(name);
        let mut args = flags.to_vec();
        args.extend(["--plot", plot.to_str().unwrap()]);
        sweep_cli(&args);
        let svg = std::fs::read_to_string(&plot).unwrap();
        elements(&svg, "polyline")
            .iter()
            .filter(|e| (0..20).any(|k| e.contains(&format!("stroke=\"{}\"", hex(category(k))))))
            .filter(|e| e.contains(&format!("stroke-width=\"{UNSTABLE_WIDTH}\"")))
            .count()
    };
    assert!(thin(&[], "cli_all.svg") > 0);
    assert_eq!(thin(&["--no-unstable"], "cli_stable.svg"), 0);
}

/// A branch whose end point, located at a grazing, is the only point with
/// |λ| ≥ 1 (at a grazing arrival `DP` diverges): no zero-length unstable
/// stretch, the stable one reaches the end. At a parameter bound the same
/// point is a stretch of its own, and a longer unstable stretch before a
/// grazing end stays one.
#[test]
fn a_grazing_end_is_no_unstable_stretch_of_its_own() {
    let eig = |m: f64| vec![[m, 0.0], [0.1, 0.0]];
    let branch = |moduli: &[f64], ends: Vec<BranchEndSummary>| BranchSummary {
        id: 0,
        structure: B.into(),
        n: 1,
        points: moduli
            .iter()
            .enumerate()
            .map(|(i, &m)| sample(1.0 + 0.1 * i as f64, vec![(0.1 * i as f64, 0.2)], eig(m)))
            .collect(),
        ends,
    };
    let brief = |b: &BranchSummary| -> Vec<(bool, usize, usize, f64, f64)> {
        sweep_table::runs(b, &[])
            .iter()
            .map(|r| (r.stable, r.first, r.last, r.from, r.to))
            .collect()
    };
    let last = 1.0 + 0.1 * 4.0;
    // Grazing at both ends, the end points alone unstable.
    let both = branch(
        &[1.0, 0.5, 0.6, 0.7, 1.0],
        vec![
            end(1.0, "grazing", Some("Sigma3"), None),
            end(last, "stick_onset", Some("Sigma1"), None),
        ],
    );
    assert_eq!(brief(&both), vec![(true, 0, 4, 1.0, last)]);
    // A parameter bound: the unstable end point is its own stretch.
    let bound = branch(
        &[0.5, 0.6, 0.7, 0.8, 1.0],
        vec![
            end(1.0, "grazing", Some("Sigma3"), None),
            end(last, "parameter_bound", None, None),
        ],
    );
    assert_eq!(
        brief(&bound),
        vec![
            (true, 0, 3, 1.0, 1.0 + 0.1 * 3.0),
            (false, 4, 4, last, last)
        ]
    );
    // Two unstable points before a grazing end: an unstable stretch.
    let longer = branch(
        &[0.5, 0.6, 0.7, 1.2, 1.3],
        vec![
            end(1.0, "parameter_bound", None, None),
            end(last, "grazing", Some("Sigma1"), None),
        ],
    );
    assert_eq!(
        brief(&longer),
        vec![(true, 0, 2, 1.0, 1.2), (false, 3, 4, 1.0 + 0.1 * 3.0, last)]
    );
}

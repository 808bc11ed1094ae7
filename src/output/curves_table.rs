//! A curves run as text (one block per curve, then the codimension-two
//! points) or as JSON (the schema in the guide, "Regime maps"): the
//! parameters' names are keys of the ends and the codim-2 points.

use std::fmt::Write;

use serde_json::{json, Map, Value};

use crate::study::curves::{CurveSet, CurveSummary, EndSummary};

/// The keys of the ends and codim-2 points, which a parameter's name must not be.
const KEYS: [&str; 10] = [
    "end",
    "codim2",
    "detail",
    "residual",
    "kinds",
    "curves",
    "kind",
    "boundary",
    "structure",
    "why",
];

fn clash(name: &str) -> serde_json::Error {
    serde::ser::Error::custom(format!(
        "the parameter `{name}` has the name of a key of the curves' JSON \
         (the guide, \"Regime maps\"), so its value could not be told apart; \
         rename the parameter in the model"
    ))
}

fn end_json(set: &CurveSet, end: &Option<EndSummary>) -> Value {
    let Some(e) = end else {
        return Value::Null;
    };
    let mut o = Map::new();
    o.insert("end".into(), json!(e.reason));
    o.insert(set.x.0.clone(), json!(e.point[0]));
    o.insert(set.y.0.clone(), json!(e.point[1]));
    if let Some(k) = e.codim2 {
        o.insert("codim2".into(), json!(k));
    }
    if let Some(d) = &e.detail {
        o.insert("detail".into(), json!(d));
    }
    if let Some(r) = e.residual {
        o.insert("residual".into(), json!(r));
    }
    Value::Object(o)
}

/// The curve set as JSON: `{"x", "y", "curves": [{"kind", "boundary",
/// "structure", "from", "to", "points", "at"}], "codim2": [{<x>, <y>,
/// "kinds", "curves"}], "failed_starts": [{"kind", "boundary",
/// "structure", <x>, <y>, "why"}]}`.
pub fn json(set: &CurveSet) -> Result<String, serde_json::Error> {
    for name in [&set.x.0, &set.y.0] {
        if KEYS.contains(&name.as_str()) {
            return Err(clash(name));
        }
    }
    let curves: Vec<Value> = set
        .curves
        .iter()
        .map(|c| {
            json!({
                "kind": c.kind,
                "boundary": c.boundary,
                "structure": c.structure,
                "from": end_json(set, &c.from),
                "to": end_json(set, &c.to),
                "points": c.points,
                "at": c.at,
            })
        })
        .collect();
    let codim2: Vec<Value> = set
        .codim2
        .iter()
        .map(|q| {
            let mut o = Map::new();
            o.insert(set.x.0.clone(), json!(q.x));
            o.insert(set.y.0.clone(), json!(q.y));
            o.insert("kinds".into(), json!(q.kinds));
            o.insert("curves".into(), json!(q.curves));
            Value::Object(o)
        })
        .collect();
    let failed: Vec<Value> = set
        .failed_starts
        .iter()
        .map(|f| {
            let mut o = Map::new();
            o.insert("kind".into(), json!(f.kind));
            o.insert("boundary".into(), json!(f.boundary));
            o.insert("structure".into(), json!(f.structure));
            o.insert(set.x.0.clone(), json!(f.point[0]));
            o.insert(set.y.0.clone(), json!(f.point[1]));
            o.insert("why".into(), json!(f.why));
            Value::Object(o)
        })
        .collect();
    serde_json::to_string_pretty(&json!({
        "x": set.x.0,
        "y": set.y.0,
        "curves": curves,
        "codim2": codim2,
        "failed_starts": failed,
    }))
}

/// A codimension-two end whose second condition holds to more than this
/// (relative to its scale) is said, in the text, to be located only
/// approximately.
const APPROXIMATE: f64 = 1e-8;

fn end_text(set: &CurveSet, end: &Option<EndSummary>) -> String {
    let Some(e) = end else {
        return "closed".into();
    };
    let mut s = format!(
        "{} at {} = {:.10}, {} = {:.10}",
        e.reason, set.x.0, e.point[0], set.y.0, e.point[1]
    );
    if let Some(k) = e.codim2 {
        let _ = write!(s, " (codim-2 point {k})");
    }
    if let Some(r) = e.residual.filter(|&r| r > APPROXIMATE) {
        let _ = write!(
            s,
            " (located only approximately: the second condition holds there to {r:.1e} of its scale)"
        );
    }
    if let Some(d) = &e.detail {
        let _ = write!(s, " ({d})");
    }
    s
}

/// `" on NAME"` for a curve on a boundary, empty otherwise.
fn on_boundary(boundary: &Option<String>) -> String {
    boundary
        .as_deref()
        .map_or(String::new(), |b| format!(" on {b}"))
}

fn curve_text(out: &mut String, set: &CurveSet, i: usize, c: &CurveSummary) {
    let boundary = on_boundary(&c.boundary);
    let _ = writeln!(
        out,
        "curve {i}: {}{boundary} of {}",
        c.kind.name(),
        c.structure
    );
    let _ = writeln!(out, "  from: {}", end_text(set, &c.from));
    let _ = writeln!(out, "  to:   {}", end_text(set, &c.to));
    let _ = writeln!(out, "  points: {}", c.points.len());
    for a in &c.at {
        let _ = writeln!(
            out,
            "  crosses {} = {:.10}, {} = {:.10}",
            set.x.0, a[0], set.y.0, a[1]
        );
    }
}

/// The curve set as text: one block per curve (kind, boundary, structure,
/// ends, number of points, `--at` crossings), then the codim-2 table.
pub fn text(set: &CurveSet, settings: &str) -> String {
    let mut out = String::new();
    let [xl, xh] = set.x.1;
    let [yl, yh] = set.y.1;
    let _ = writeln!(
        out,
        "Transition curves in {} = {xl}..{xh}, {} = {yl}..{yh} ({settings}): {} curve(s), {} codimension-two point(s)",
        set.x.0,
        set.y.0,
        set.curves.len(),
        set.codim2.len()
    );
    for (i, c) in set.curves.iter().enumerate() {
        out.push('\n');
        curve_text(&mut out, set, i, c);
    }
    if !set.codim2.is_empty() {
        let _ = writeln!(
            out,
            "\nCodimension-two points\n  #  {:>16}  {:>16}  kinds; curves",
            set.x.0, set.y.0
        );
        for (i, q) in set.codim2.iter().enumerate() {
            let kinds: Vec<&str> = q.kinds.iter().map(|k| k.name()).collect();
            let curves: Vec<String> = q.curves.iter().map(|c| c.to_string()).collect();
            let _ = writeln!(
                out,
                "  {i:<2} {:>16.10}  {:>16.10}  {}; {}",
                q.x,
                q.y,
                kinds.join(" + "),
                curves.join(", ")
            );
        }
    }
    if !set.failed_starts.is_empty() {
        let _ = writeln!(
            out,
            "\nMissing curves: {} located transition(s) whose curve could not be traced",
            set.failed_starts.len()
        );
        for f in &set.failed_starts {
            let boundary = on_boundary(&f.boundary);
            let _ = writeln!(
                out,
                "  {}{boundary} of {} at {} = {:.10}, {} = {:.10}: {}",
                f.kind.name(),
                f.structure,
                set.x.0,
                f.point[0],
                set.y.0,
                f.point[1],
                f.why
            );
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::bifurcation::TransitionKind;
    use crate::study::curves::Codim2Point;

    fn set() -> CurveSet {
        let end = |reason: &str, codim2| EndSummary {
            reason: reason.into(),
            point: [1.5, 40.0],
            codim2,
            detail: None,
            residual: None,
        };
        CurveSet {
            x: ("W".into(), [0.2, 8.0]),
            y: ("Q0".into(), [0.0, 180.0]),
            curves: vec![CurveSummary {
                kind: TransitionKind::Grazing,
                boundary: Some("Sigma1".into()),
                structure: "P_{4_33}".into(),
                from: Some(end("box_edge", None)),
                to: Some(end("codim2", Some(0))),
                points: vec![[1.0, 2.0], [1.5, 40.0]],
                at: vec![[1.25, 20.0]],
            }],
            codim2: vec![Codim2Point {
                x: 1.5,
                y: 40.0,
                kinds: vec![TransitionKind::Grazing, TransitionKind::StickOnset],
                curves: vec![0],
            }],
            failed_starts: Vec::new(),
        }
    }

    #[test]
    fn json_keys_ends_by_parameter_name() {
        let v: Value = serde_json::from_str(&json(&set()).unwrap()).unwrap();
        assert_eq!(v["x"], "W");
        let c = &v["curves"][0];
        assert_eq!(c["kind"], "grazing");
        assert_eq!(c["to"]["end"], "codim2");
        assert_eq!(c["to"]["W"], 1.5);
        assert_eq!(c["to"]["codim2"], 0);
        assert!(c["from"].get("codim2").is_none());
        assert_eq!(v["codim2"][0]["Q0"], 40.0);
        assert_eq!(v["codim2"][0]["kinds"][1], "stick_onset");
    }

    #[test]
    fn a_failed_start_is_listed_in_json_and_text() {
        let mut s = set();
        let v: Value = serde_json::from_str(&json(&s).unwrap()).unwrap();
        assert_eq!(v["failed_starts"].as_array().map(Vec::len), Some(0));
        assert!(!text(&s, "").contains("Missing curves"));
        s.failed_starts.push(crate::study::curves::FailedStart {
            kind: TransitionKind::PassableOnset,
            boundary: Some("Sigma1".into()),
            structure: "P_{0_11 1_11 2_11}".into(),
            point: [0.41, 1.8],
            why: "the corrector does not converge".into(),
        });
        let v: Value = serde_json::from_str(&json(&s).unwrap()).unwrap();
        let f = &v["failed_starts"][0];
        assert_eq!(f["kind"], "passable_onset");
        assert_eq!(f["boundary"], "Sigma1");
        assert_eq!(f["structure"], "P_{0_11 1_11 2_11}");
        assert_eq!((f["W"].as_f64(), f["Q0"].as_f64()), (Some(0.41), Some(1.8)));
        assert_eq!(f["why"], "the corrector does not converge");
        let t = text(&s, "");
        assert!(
            t.contains("Missing curves: 1 located transition(s)")
                && t.contains("passable_onset on Sigma1 of P_{0_11 1_11 2_11} at W = 0.4100000000, Q0 = 1.8000000000: the corrector does not converge"),
            "{t}"
        );
    }

    #[test]
    fn a_parameter_named_like_a_key_is_an_error() {
        let mut s = set();
        s.x.0 = "kinds".into();
        assert!(json(&s).is_err());
    }

    #[test]
    fn text_names_the_curve_and_the_codim2_point() {
        let t = text(&set(), "default parameters");
        assert!(t.contains("curve 0: grazing on Sigma1 of P_{4_33}"), "{t}");
        assert!(t.contains("grazing + stick_onset; 0"), "{t}");
    }

    #[test]
    fn an_end_located_only_approximately_says_so() {
        let mut s = set();
        let at = |s: &CurveSet| {
            let v: Value = serde_json::from_str(&json(s).unwrap()).unwrap();
            v["curves"][0]["to"]["residual"].clone()
        };
        assert!(at(&s).is_null());
        s.curves[0].to.as_mut().unwrap().residual = Some(3e-14);
        assert_eq!(at(&s), 3e-14);
        assert!(!text(&s, "").contains("approximately"));
        s.curves[0].to.as_mut().unwrap().residual = Some(1.4e-6);
        let t = text(&s, "");
        assert!(
            t.contains("located only approximately: the second condition holds there to 1.4e-6"),
            "{t}"
        );
    }
}

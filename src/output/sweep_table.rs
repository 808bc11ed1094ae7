//! A sweep as text (transitions, then the motions at each grid point) or as
//! JSON (the schema in the README, "Bifurcations and maps").

use crate::study::sweep::Sweep;

/// The sweep of `sweep.param` as asked (`from`, `to`, `count`; `set` says
/// the other parameters): its transitions, then the motions at each point.
pub fn text(sweep: &Sweep, from: f64, to: f64, count: usize, set: &str) -> String {
    let name = &sweep.param;
    let mut out = format!("sweep of {name} over [{from}, {to}] ({count} points), {set}\n\n");
    out.push_str("transitions:\n");
    for t in &sweep.transitions {
        out.push_str(&format!(
            "  {name} = {:<18.12} {:<16} {} -> {}{}\n",
            t.value,
            serde_json::to_value(t.kind)
                .ok()
                .and_then(|v| v.as_str().map(String::from))
                .unwrap_or_default(),
            t.from,
            t.to,
            t.boundary
                .as_ref()
                .map_or(String::new(), |b| format!(" (on {b})"))
        ));
    }
    out.push_str("\nmotions:\n");
    for p in &sweep.points {
        let names: Vec<String> = p
            .motions
            .iter()
            .map(|m| {
                let n = if m.n > 1 {
                    format!("^{}", m.n)
                } else {
                    String::new()
                };
                let st = if m.stable { "" } else { " (unstable)" };
                format!("{}{n}{st}", m.structure)
            })
            .collect();
        out.push_str(&format!(
            "  {name} = {:<10.6} {}\n",
            p.value,
            names.join("  +  ")
        ));
    }
    out
}

/// The sweep as JSON: `param`, `points` (the parameter's value and the
/// motions there), `transitions` (the value, `from`, `to`, `kind`,
/// `boundary`), the value keyed by the parameter's name.
pub fn json(sweep: &Sweep) -> Result<String, serde_json::Error> {
    let name = &sweep.param;
    let points: Vec<serde_json::Value> = sweep
        .points
        .iter()
        .map(|p| {
            let mut o = serde_json::Map::new();
            o.insert(name.clone(), serde_json::json!(p.value));
            o.insert("motions".into(), serde_json::json!(p.motions));
            serde_json::Value::Object(o)
        })
        .collect();
    let transitions: Vec<serde_json::Value> = sweep
        .transitions
        .iter()
        .map(|t| {
            let mut o = serde_json::Map::new();
            o.insert(name.clone(), serde_json::json!(t.value));
            o.insert("from".into(), serde_json::json!(t.from));
            o.insert("to".into(), serde_json::json!(t.to));
            o.insert("kind".into(), serde_json::json!(t.kind));
            o.insert("boundary".into(), serde_json::json!(t.boundary));
            serde_json::Value::Object(o)
        })
        .collect();
    let doc = serde_json::json!({ "param": name, "points": points, "transitions": transitions });
    serde_json::to_string_pretty(&doc)
}

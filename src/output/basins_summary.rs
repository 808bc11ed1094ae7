//! What a basin run found, as the JSON of `stickslip basins --json` (the
//! Python package's `Basins.to_dict()` is the same document).

use serde_json::json;

use crate::study::basins::Basins;

/// `{"model", "params", "phase", "x", "v", "samples", "seed", "file",
/// "complete", "attractors"}`: the run's settings, the basin file `out`, and
/// each attractor with its grid share and basin stability.
pub fn json(b: &Basins) -> Result<String, serde_json::Error> {
    let h = &b.header;
    let params: serde_json::Map<String, serde_json::Value> = h
        .params
        .iter()
        .map(|(n, v)| (n.clone(), json!(v)))
        .collect();
    let value = json!({
        "model": h.model,
        "params": params,
        "phase": h.phase,
        "x": {"from": h.x.from, "to": h.x.to, "count": h.x.count},
        "v": {"from": h.v.from, "to": h.v.to, "count": h.v.count},
        "samples": h.samples,
        "seed": h.seed,
        "file": b.file.as_ref().map(|f| f.display().to_string()),
        "complete": b.complete,
        "attractors": b.attractors,
    });
    serde_json::to_string_pretty(&value)
}

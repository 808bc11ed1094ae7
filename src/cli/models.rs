//! `stickslip models`: the compiled-in models and their scenes.

use stickslip::models::{Entry, ALL};

use super::outcome::Outcome;

/// One line per model or scene (its size and free parameters), and under a
/// model the first line of its documentation.
pub fn run() -> Outcome {
    let mut out = String::new();
    for info in ALL.iter().filter_map(Entry::piecewise) {
        let free: Vec<&str> = info.free.iter().map(|&i| info.params[i].name).collect();
        let first_doc = info.doc.lines().next().unwrap_or("");
        out.push_str(&format!(
            "{:<20} {} domains, {} boundaries, {} mappings; free: {}\n",
            info.name,
            info.domains.len(),
            info.boundaries.len(),
            info.mapping_names().len(),
            free.join(", ")
        ));
        if info.scene.is_none() && !first_doc.is_empty() {
            out.push_str(&format!("{:<20} {}\n", "", first_doc));
        }
    }
    Outcome::ok(out)
}

//! The reference periodic motions of `../shared/reference/orbits.json`.

use serde_json::Value;
use stickslip::orbit::periodic::SwitchingPoint;

/// One reference motion.
pub struct Reference {
    pub structure: String,
    pub w: f64,
    pub q0: f64,
    pub periods: u32,
    /// Mapping names in application order.
    pub mappings: Vec<String>,
    /// Switching points; point k starts the k-th mapping applied.
    pub points: Vec<SwitchingPoint>,
    /// Eigenvalues `[re, im]` of the Poincaré-map Jacobian.
    pub eigenvalues: Vec<[f64; 2]>,
}

/// Every reference motion.
pub fn references() -> Vec<Reference> {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference/orbits.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v: Value = serde_json::from_str(&text).expect("valid JSON");
    let f = |v: &Value| v.as_f64().expect("number");
    v["orbits"]
        .as_array()
        .expect("orbits")
        .iter()
        .map(|o| Reference {
            structure: o["structure"].as_str().expect("structure").to_string(),
            w: f(&o["W"]),
            q0: f(&o["Q0"]),
            periods: f(&o["N_periods"]) as u32,
            mappings: o["mappings_in_application_order"]
                .as_array()
                .expect("mappings")
                .iter()
                .map(|m| m.as_str().expect("name").to_string())
                .collect(),
            points: o["switching_points"]
                .as_array()
                .expect("points")
                .iter()
                .map(|p| SwitchingPoint {
                    phase: f(&p["Wt"]),
                    x: f(&p["x"]),
                })
                .collect(),
            eigenvalues: o["eigenvalues"]
                .as_array()
                .expect("eigenvalues")
                .iter()
                .map(|e| [f(&e[0]), f(&e[1])])
                .collect(),
        })
        .collect()
}

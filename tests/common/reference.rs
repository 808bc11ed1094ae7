//! The reference periodic motions of `../shared/reference/orbits.json`.

use serde_json::Value;
use stickslip::dynamics::simulate::Segment;
use stickslip::dynamics::simulate::{Location, SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::periodic::SwitchingPoint;
use stickslip::orbit::structure::Structure;
use stickslip::Model;

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
    /// The Poincaré-map Jacobian, ordered `(W t, x)`, by rows.
    pub dp: [[f64; 2]; 2],
}

impl Reference {
    /// The paper model's simulator at this motion's `W` and `Q0`.
    pub fn simulator(&self) -> Simulator<Paper> {
        let p = Params {
            W: self.w,
            Q0: self.q0,
            ..Params::default()
        };
        Simulator::new(p, SimOptions::default()).expect("valid parameters")
    }

    /// The motion's mapping structure.
    pub fn structure(&self) -> Structure {
        Structure::parse(Paper::INFO, &self.structure, self.periods).expect("structure")
    }
}

/// The segment that starts mapping `idx` at `pt` (built directly: on a
/// boundary, `Simulator::start` would pick the side from the vector field).
pub fn segment_for<M: Model>(sim: &Simulator<M>, idx: usize, pt: SwitchingPoint) -> Segment {
    let mi = sim.info().mappings[idx];
    Segment {
        x: pt.x,
        v: sim.velocity(mi.from),
        phase: pt.phase,
        location: mi.domain.map_or(Location::Stick, Location::Domain),
        search_from: pt.phase,
    }
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
            dp: [0, 1].map(|i| [0, 1].map(|j| f(&o["DP_Wtx"][i][j]))),
        })
        .collect()
}

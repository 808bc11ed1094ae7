//! The generated mappings on the reference periodic motions of
//! `../shared/reference/orbits.json` (computed independently from the model
//! of SPEC §1): every mapping's residual vanishes between consecutive
//! switching points, and the product of the local Jacobians `DP_σ` (Eq. B.2)
//! is the reference Poincaré-map Jacobian `DP` with its eigenvalues.

use serde_json::Value;
use stickslip::models::paper::{Paper, Params};
use stickslip::nalgebra::Matrix2;
use stickslip::{Model, Side};

fn orbits() -> Vec<Value> {
    let path =
        std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../shared/reference/orbits.json");
    let text = std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
    let v: Value = serde_json::from_str(&text).expect("valid JSON");
    v["orbits"].as_array().expect("orbits").clone()
}

fn f(v: &Value) -> f64 {
    v.as_f64().expect("number")
}

#[test]
fn reference_orbits_satisfy_the_generated_mappings_and_their_jacobians() {
    let info = Paper::INFO;
    let all = orbits();
    assert!(all.len() >= 3);
    for orbit in &all {
        let p = Params {
            W: f(&orbit["W"]),
            Q0: f(&orbit["Q0"]),
            ..Params::default()
        };
        let n_periods = f(&orbit["N_periods"]);
        let pts = orbit["switching_points"].as_array().expect("points");
        let names: Vec<&str> = orbit["mappings_in_application_order"]
            .as_array()
            .expect("mappings")
            .iter()
            .map(|m| m.as_str().expect("name"))
            .collect();
        let m = names.len();
        let mut dp = Matrix2::identity();
        for k in 0..m {
            let (a, b) = (&pts[k], &pts[(k + 1) % m]);
            let (x0, phi0) = (f(&a["x"]), f(&a["Wt"]));
            let x1 = f(&b["x"]);
            let mut phi1 = f(&b["Wt"]);
            if k + 1 == m {
                phi1 += 2.0 * std::f64::consts::PI * n_periods;
            }
            // The stick mapping leaves towards the domain of the next mapping.
            let next = info.mappings[info
                .mapping_index(names[(k + 1) % m], None)
                .expect("next mapping")];
            let exit = next.domain.map(|j| {
                if info.domains[j].lower == Some(next.from) {
                    Side::Above
                } else {
                    Side::Below
                }
            });
            let idx = info.mapping_index(names[k], exit).expect("mapping exists");
            let e = Paper::mapping(&p, idx, x0, phi0, x1, phi1);
            assert!(
                e.residual.amax() < 1e-10,
                "{} at W = {}: mapping {} residual {:?}",
                orbit["structure"],
                p.W,
                names[k],
                e.residual
            );
            dp = e.local_jacobian().expect("transversal") * dp;
        }
        let reference = &orbit["DP_Wtx"];
        for r in 0..2 {
            for c in 0..2 {
                let want = f(&reference[r][c]);
                assert!(
                    (dp[(r, c)] - want).abs() < 1e-8 * want.abs().max(1.0),
                    "{}: DP[{r}][{c}] = {} vs reference {want}",
                    orbit["structure"],
                    dp[(r, c)]
                );
            }
        }
        let ev = dp.complex_eigenvalues();
        let want: Vec<(f64, f64)> = orbit["eigenvalues"]
            .as_array()
            .expect("eigenvalues")
            .iter()
            .map(|e| (f(&e[0]), f(&e[1])))
            .collect();
        for (re, im) in want {
            let close = ev
                .iter()
                .any(|z| (z.re - re).abs() < 1e-8 && (z.im - im).abs() < 1e-8);
            assert!(
                close,
                "{}: eigenvalue {re}+{im}i not among {ev:?}",
                orbit["structure"]
            );
        }
    }
}

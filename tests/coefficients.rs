//! The paper model's effective coefficients (SPEC §1, §10):
//! `2 d_j = 0.10, 0.22, 0.18, 0.30` and `b_j = 4.22, 3.68, -3.86, -4.04`
//! for domains 1..4, `c_j = 30`.

use stickslip::models::paper::{Paper, Params};
use stickslip::{Model, Regime};

#[test]
fn paper_effective_coefficients() {
    let p = Params::default();
    let expected = [
        (1, 0.10, 4.22),
        (2, 0.22, 3.68),
        (3, 0.18, -3.86),
        (4, 0.30, -4.04),
    ];
    for (label, two_d, b) in expected {
        let j = Paper::INFO
            .domains
            .iter()
            .position(|d| d.label == label)
            .expect("domain exists");
        let co = Paper::coefficients(&p, j);
        assert!(
            (co.two_d - two_d).abs() < 1e-13,
            "domain {label}: 2d = {}",
            co.two_d
        );
        assert!((co.b - b).abs() < 1e-13, "domain {label}: b = {}", co.b);
        assert_eq!(co.c, 30.0);
        assert_eq!(co.regime(), Regime::Underdamped);
    }
    // Boundaries, lowest first: Sigma3 (V2), Sigma1 (V), Sigma2 (V1).
    let labels: Vec<&str> = Paper::INFO.boundaries.iter().map(|b| b.label).collect();
    assert_eq!(labels, ["Sigma3", "Sigma1", "Sigma2"]);
    let v: Vec<f64> = (0..3).map(|k| Paper::boundary_velocity(&p, k)).collect();
    assert_eq!(v, [1.5, 3.0, 4.5]);
    assert_eq!(Paper::INFO.stick_boundary(), Some(1));
}

#[test]
fn paper_mappings_are_the_topology_of_spec_section_5() {
    let mut names = Paper::INFO.mapping_names();
    names.sort_unstable();
    let mut expected = [
        "1_11", "3_11", "2_22", "1_22", "4_33", "3_33", "1_21", "1_12", "3_31", "3_13", "0_11",
    ];
    expected.sort_unstable();
    assert_eq!(names, expected);
}

#[test]
fn scene_folds_fixed_parameters_and_keeps_the_numbers() {
    use stickslip::models::paper::sweep_w::{Params as SceneParams, SweepW};
    let full = Params {
        W: 4.2,
        ..Params::default()
    };
    let scene = SceneParams { W: 4.2 };
    for idx in 0..Paper::INFO.mappings.len() {
        let name = Paper::INFO.mappings[idx].name;
        let exit = Paper::INFO.mappings[idx].exit;
        let sidx = SweepW::INFO
            .mapping_index(name, exit)
            .expect("sweep_w generates every mapping");
        let a = Paper::mapping(&full, idx, 0.3, 1.0, -0.2, 2.5);
        let b = SweepW::mapping(&scene, sidx, 0.3, 1.0, -0.2, 2.5);
        let diff = (a.residual - b.residual)
            .amax()
            .max((a.d_prev - b.d_prev).amax())
            .max((a.d_next - b.d_next).amax());
        assert!(
            diff < 1e-12,
            "{name}: scene and full model differ by {diff:e}"
        );
    }
    // The reference scene generates only the mappings its structures use.
    use stickslip::models::paper::reference::Reference;
    let mut used = Reference::INFO.mapping_names();
    used.sort_unstable();
    assert_eq!(
        used,
        ["0_11", "1_11", "1_12", "1_21", "2_22", "3_13", "3_31", "3_33", "4_33"]
    );
}

#[test]
fn params_reject_bad_values_with_typed_errors() {
    use stickslip::ParamError;
    let info = Paper::INFO;
    assert!(matches!(
        Params::from_pairs(info, &[("W", f64::NAN)]),
        Err(ParamError::NotFinite { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("m", -1.0)]),
        Err(ParamError::OutOfRange { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("Omega", 1.0)]),
        Err(ParamError::Unknown { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("V1", 2.0)]),
        Err(ParamError::BoundaryOrder { .. })
    ));
    assert!(matches!(
        Params::from_pairs(info, &[("mus", 0.3)]),
        Err(ParamError::StaticBelowKinetic { .. })
    ));
    let scene = stickslip::models::paper::sweep_w::SweepW::INFO;
    let e =
        stickslip::models::paper::sweep_w::Params::from_pairs(scene, &[("Q0", 10.0)]).unwrap_err();
    assert!(matches!(e, ParamError::Fixed { .. }), "{e}");
    assert!(e.to_string().contains("fixed to 70"), "{e}");
    let ok = Params::from_pairs(info, &[("W", 3.7)]).expect("valid");
    assert_eq!(ok.W, 3.7);
}

/// A static bound equal to the kinetic level up to rounding is allowed
/// (a smooth law's N-piece model has `as = ak` at the belt speed, its
/// kinetic level a few ulps either side); one below it by more than 1e-12
/// of `1 + level` is `StaticBelowKinetic`. And `stribeck::pl4`, whose
/// pieces take the law's limit `mus g` exactly, is valid at its defaults.
#[test]
fn a_static_bound_equal_to_the_kinetic_level_up_to_rounding_is_allowed() {
    use stickslip::models::coulomb::{Coulomb, Params as CoulombParams};
    use stickslip::{ParamError, ParamSet};
    let info = Coulomb::INFO;
    let muk = 0.3;
    for (mus, ok) in [
        (muk, true),
        (muk * (1.0 - 4.0 * f64::EPSILON), true),
        (muk - 1e-13, true),
        (muk - 1e-11, false),
        (muk * (1.0 - 1e-9), false),
    ] {
        let r = CoulombParams::from_pairs(info, &[("muk", muk), ("mus", mus)]);
        assert_eq!(r.is_ok(), ok, "mus = {mus:e}: {r:?}");
        if !ok {
            assert!(
                matches!(r, Err(ParamError::StaticBelowKinetic { .. })),
                "{r:?}"
            );
        }
    }
    let pl4 = stickslip::models::stribeck::pl4::Params::default();
    assert!(pl4.check().is_ok());
}

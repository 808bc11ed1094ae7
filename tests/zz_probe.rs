mod common;
use nalgebra::DMatrix;
use stickslip::bifurcation::curve::{system, CurveOptions};
use stickslip::models::coulomb::Coulomb;
use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};
use stickslip::Model;

#[test]
fn probe() {
    let opts = CurvesOptions {
        x: ("W".into(), [0.3, 1.2]),
        y: ("Q0".into(), [0.5, 2.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    };
    let _ = CurveOptions::default();
    let (_, curves) =
        traced::<Coulomb>(&common::shaw::params(), &opts, &CurvesSettings::default()).unwrap();
    for c in &curves {
        let s = c.structure.as_ref().unwrap();
        if s.notation(Coulomb::INFO) != "P_{1_11 2_11}" {
            continue;
        }
        let n = c.points.len();
        for q in c.points.iter().step_by(6).chain(c.points[n - 3..].iter()) {
            let mut sys = system::<Coulomb>(
                &common::shaw::params(),
                &common::shaw::plane(),
                Some(s),
                q,
                c.condition,
            )
            .unwrap();
            let x = stickslip::bifurcation::curve::unknowns(q);
            let k = sys.len();
            let j = sys.jacobian(&x).unwrap().to_vec();
            let m = 2 * s.len();
            let fu = DMatrix::from_fn(m, m, |r, cc| j[r * k + cc]);
            let full = DMatrix::from_fn(m, k, |r, cc| j[r * k + cc]);
            let sv = fu.svd(false, false).singular_values;
            let sf = full.svd(false, false).singular_values;
            eprintln!(
                "{:?} W {:.8} Q0 {:.8}: F_u sv {:?}  [F_u F_l] min {:e}",
                c.kind,
                q.x,
                q.y,
                sv.as_slice(),
                sf.min()
            );
        }
    }
}

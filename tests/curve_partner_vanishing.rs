//! Branch switching does not start a curve on a motion one of whose
//! segments has no length.
//!
//! A segment of zero length solves its mapping equation exactly, so a
//! structure with one more mapping than the motion has (a stick of no
//! length between two flows of one domain, a flow of no length between
//! two sticks) still has solutions there: the reduced motion, written
//! with a segment that takes no time. Its equations are singular (the
//! segment's departure and arrival are free along it), its companions'
//! margins sit at rounding, and a curve traced on it is the reduced
//! motion's border under another motion's name, or not a border at all.
//! A line's start refuses such a structure (`condition_at_transition`: a
//! segment below 1e-3 rad); until stop 43 the branch switch's start did
//! not. On `stribeck8` W = 1…1.2 × Q0 = 4.6…5 two switched grazing curves
//! of period-2 motions ran with a stick `0_11` of 1e-10…2e-8 rad along
//! their whole length (one of them into a corrector failure, "the motion's
//! mapping equations … have a smallest singular value 8.4e-10"); over
//! W = 0.5…3 × Q0 = 1…12, 11 such curves, and 3 more switched from them.
//!
//! 1. every start `partner_start` returns from the codimension-two points
//!    of the curves the lines trace has every segment longer than 1e-3 rad
//!    (the line start's threshold);
//! 2. in the run with branch switching, every curve's middle point has
//!    every segment longer than 1e-6 rad.

use stickslip::bifurcation::curve::{codim2_places, partner_start, CurvePoint, PARTNER_STEP};
use stickslip::models::stribeck8::{self, Stribeck8};
use stickslip::orbit::structure::Structure;
use stickslip::study::curves::{traced, CurvesOptions, CurvesSettings};

fn opts() -> CurvesOptions {
    CurvesOptions {
        x: ("W".into(), [1.0, 1.2]),
        y: ("Q0".into(), [4.6, 5.0]),
        seeds: Vec::new(),
        at: Vec::new(),
    }
}

/// The shortest segment of the motion at `at` (in `W t`; the last one up
/// to the first switching point a cycle on).
fn shortest(structure: &Structure, at: &CurvePoint) -> f64 {
    let shift = std::f64::consts::TAU * structure.periods() as f64;
    let p = &at.points;
    let n = p.len();
    (0..n)
        .map(|k| {
            let next = if k + 1 < n {
                p[k + 1].phase
            } else {
                p[0].phase + shift
            };
            next - p[k].phase
        })
        .fold(f64::INFINITY, f64::min)
}

#[test]
fn switched_starts_and_curves_keep_every_segment() {
    let base = stribeck8::Params::default();
    let opts = opts();
    let plane = opts.plane::<Stribeck8>(&base).unwrap();

    // 1. The starts from the lines' curves.
    let lines_only = CurvesSettings {
        max_partners: 0,
        ..CurvesSettings::default()
    };
    let (_, lined) = traced::<Stribeck8>(&base, &opts, &lines_only).unwrap();
    let mut starts = 0;
    for c in &lined {
        for place in codim2_places(c) {
            let Some(s) = partner_start::<Stribeck8>(&base, &plane, c, &place, PARTNER_STEP, 1e-12)
            else {
                continue;
            };
            starts += 1;
            let short = shortest(&s.structure, &s.point);
            assert!(
                short > 1e-3,
                "a switched start of {:?} at ({}, {}) has a segment of {short:e} rad",
                s.kind,
                s.point.x,
                s.point.y
            );
        }
    }
    assert!(starts >= 10, "only {starts} switched starts");

    // 2. The whole run, switched curves of switched curves included.
    let (_, curves) = traced::<Stribeck8>(&base, &opts, &CurvesSettings::default()).unwrap();
    assert!(
        curves.len() > lined.len() && curves.len() >= 20,
        "{} curves ({} from the lines)",
        curves.len(),
        lined.len()
    );
    for c in &curves {
        let Some(s) = &c.structure else { continue };
        let mid = &c.points[c.points.len() / 2];
        let short = shortest(s, mid);
        assert!(
            short > 1e-6,
            "{:?} curve of {} has a segment of {short:e} rad at ({}, {})",
            c.kind,
            s.notation(Stribeck8::INFO),
            mid.x,
            mid.y
        );
    }
}

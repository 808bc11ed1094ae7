//! The continuation method of `map` against the simulation method (issue
//! 12, item 3), on a check grid of the paper model over the README's
//! Fig. 11 range (W ∈ [0.2, 8], Q0 ∈ [0, 180]): at every point the
//! continuation map lists every motion the simulation map lists, with the
//! same status; where it lists more, each extra motion is proven to exist
//! there independently of the map code — a periodic motion seeded by
//! simulation and solved by Newton (`orbit::motion::solve`: converged,
//! admissible, stable, with the same label), NM by the closed-form
//! certificate of `orbit::attractor` at the forced response written out
//! here. A point where the continuation map misses a motion fails.
//!
//! The grid is `STICKSLIP_CHECK_GRID` points a side (default 100: ~20 s in
//! the test profile on a busy 2-core machine; `CHECK=1 benches/map-speed.sh`
//! runs it in release mode). Other sizes are a harder check, not a
//! guaranteed pass: at 40 × 40 one point (W = 2.2, Q0 = 170.8) misses the
//! period-2 motion that rest reaches there, in a sliver of coexistence
//! with `P_{3_33 4_33}` narrower than the seed spacing whose neighbours
//! all agree (see the report of issue 12).

use std::collections::BTreeSet;
use std::fs;
use std::path::Path;

use stickslip::dynamics::simulate::{SimOptions, Simulator};
use stickslip::models::paper::{Paper, Params};
use stickslip::orbit::attractor::{no_motion_certificate, seed};
use stickslip::orbit::motion::solve;
use stickslip::orbit::periodic::NewtonOptions;
use stickslip::orbit::structure::Structure;
use stickslip::study::map::{run_map, GridAxis, MapFile, MapMethod, MapOptions};

fn grid() -> usize {
    std::env::var("STICKSLIP_CHECK_GRID")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(100)
}

fn map(dir: &Path, n: usize, method: MapMethod) -> MapFile {
    let x = GridAxis::parse_for::<Paper>(&Default::default(), &format!("W=0.2:8:{n}")).unwrap();
    let y = GridAxis::parse_for::<Paper>(&Default::default(), &format!("Q0=0:180:{n}")).unwrap();
    let out = dir.join(format!("{method:?}.csv"));
    let _ = fs::remove_file(&out);
    let opts = MapOptions {
        method,
        ..MapOptions::default()
    };
    let t = std::time::Instant::now();
    let s = run_map::<Paper>(&Params::default(), &x, &y, &out, &opts).unwrap();
    eprintln!("{method:?}: {} points in {:?}", s.computed, t.elapsed());
    assert!(s.complete);
    MapFile::read(&out).unwrap()
}

/// NM at `sim`'s parameters, proven: some domain's forced response
/// `x_p = a cos φ + b sin φ − b_j / c` stays inside its band for ever
/// (the certificate of `orbit::attractor` at the response, where the
/// decaying part is zero).
fn no_motion_proven(sim: &Simulator<Paper>) -> bool {
    let osc = sim.oscillator();
    (0..Paper::INFO.domains.len()).any(|j| {
        let co = sim.coefficients(j);
        let (d, c, w) = (co.two_d / 2.0, co.c, osc.frequency);
        let den = (c - w * w).powi(2) + 4.0 * d * d * w * w;
        let (a, b) = (
            osc.amplitude * (c - w * w) / den,
            2.0 * d * w * osc.amplitude / den,
        );
        no_motion_certificate(sim, j, a - co.b / c, w * b, 0.0).is_some()
    })
}

/// A periodic motion named `label` at `sim`'s parameters, proven: seeded by
/// simulation (here, or at a neighbouring grid point `steps` away, then
/// Newton here from there), solved by Newton, admissible and stable.
fn periodic_proven(sim: &Simulator<Paper>, label: &str, steps: [f64; 2]) -> Result<(), String> {
    let (text, periods) = match label.split_once('^') {
        Some((s, n)) => (s, n.parse::<u32>().map_err(|e| e.to_string())?),
        None => (label, 1),
    };
    let structure = Structure::parse(Paper::INFO, text, periods).map_err(|e| e.to_string())?;
    let p = *sim.params();
    let mut why = Vec::new();
    for (dw, dq) in [(0.0, 0.0), (-1.0, 0.0), (1.0, 0.0), (0.0, -1.0), (0.0, 1.0)] {
        let at = Params {
            W: p.W + dw * steps[0],
            Q0: p.Q0 + dq * steps[1],
            ..p
        };
        let Ok(there) = Simulator::<Paper>::new(at, SimOptions::default()) else {
            continue;
        };
        let Some(guess) = seed(&there, &structure) else {
            why.push(format!("({dw}, {dq}): no simulation follows it"));
            continue;
        };
        let m = solve(sim, structure.clone(), guess, NewtonOptions::default());
        if !m.is_admissible() {
            why.push(format!("({dw}, {dq}): not admissible"));
            continue;
        }
        match m.stability {
            Some(s) if s.is_stable() => return Ok(()),
            other => why.push(format!("({dw}, {dq}): not stable: {other:?}")),
        }
    }
    Err(why.join("; "))
}

#[test]
fn continuation_map_lists_every_simulated_motion_and_proves_the_extra_ones() {
    let n = grid();
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("map-continuation-check");
    fs::create_dir_all(&dir).unwrap();
    let old = map(&dir, n, MapMethod::Simulation);
    let new = map(&dir, n, MapMethod::Continuation);
    assert_eq!(old.points.len(), new.points.len());
    let mut failures = Vec::new();
    let mut extra_points = 0;
    for (a, b) in old.points.iter().zip(&new.points) {
        assert_eq!((a.index, a.x, a.y), (b.index, b.x, b.y));
        if a.status != b.status {
            failures.push(format!(
                "point {} (W={}, Q0={}): status `{}` by simulation, `{}` by continuation",
                a.index, a.x, a.y, a.status, b.status
            ));
        }
        let (sa, sb): (BTreeSet<&String>, BTreeSet<&String>) =
            (a.motions.iter().collect(), b.motions.iter().collect());
        for missing in sa.difference(&sb) {
            failures.push(format!(
                "point {} (W={}, Q0={}): {missing} found by simulation, missing by continuation ({:?})",
                a.index, a.x, a.y, b.motions
            ));
        }
        let extra: Vec<&&String> = sb.difference(&sa).collect();
        if extra.is_empty() {
            continue;
        }
        extra_points += 1;
        let p = Params {
            W: a.x,
            Q0: a.y,
            ..Params::default()
        };
        let sim = Simulator::<Paper>::new(p, SimOptions::default()).unwrap();
        for label in extra {
            let proof = if label.as_str() == "NM" {
                no_motion_proven(&sim)
                    .then_some(())
                    .ok_or_else(|| "no certificate".to_string())
            } else {
                periodic_proven(&sim, label, [7.8 / (n - 1) as f64, 180.0 / (n - 1) as f64])
            };
            match proof {
                Ok(()) => eprintln!(
                    "point {} (W={}, Q0={}): {label} coexists with {:?} (proven)",
                    a.index, a.x, a.y, a.motions
                ),
                Err(why) => failures.push(format!(
                    "point {} (W={}, Q0={}): extra {label} not proven: {why}",
                    a.index, a.x, a.y
                )),
            }
        }
    }
    eprintln!(
        "{n} x {n}: {extra_points} points list more motions than the simulation, {} failures",
        failures.len()
    );
    assert!(failures.is_empty(), "{}", failures.join("\n"));
}

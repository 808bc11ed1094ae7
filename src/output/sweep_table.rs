//! A sweep as text (transitions, bifurcations, branches, then the motions at
//! each grid point) or as JSON (the schema in the guide, "One-parameter
//! studies").

use serde::Serialize;
use serde_json::{Map, Value};

use crate::bifurcation::TransitionKind;
use crate::study::sweep::{
    BifurcationSummary, BranchSample, BranchSummary, Cascade, Sweep, FEIGENBAUM_DELTA,
};
use stickslip_codegen::structure::with_periods;

/// The stretches of a branch along which its motion is stable or unstable.
///
/// A branch's points are in arclength order; a run is a maximal stretch of
/// consecutive points of one stability. Where a bifurcation of the branch
/// lies between two runs' adjoining points (in the parameter and the
/// motion's first switching point: at a fold the parameter turns back),
/// both runs end and start at it.
#[derive(Clone, Debug, PartialEq)]
pub struct Run {
    /// Whether the motion is stable along it.
    pub stable: bool,
    /// Indices of its first and last point in the branch's `points`.
    pub first: usize,
    /// See `first`.
    pub last: usize,
    /// The parameter where it starts and ends, in arclength order.
    pub from: f64,
    /// See `from`.
    pub to: f64,
    /// The bifurcation where it starts, if one separates it from the run before.
    pub from_kind: Option<&'static str>,
    /// The bifurcation where it ends, if one separates it from the run after.
    pub to_kind: Option<&'static str>,
}

/// The runs of `branch` in arclength order; `bifurcations` of the whole
/// sweep (those on other branches are ignored).
pub fn runs(branch: &BranchSummary, bifurcations: &[BifurcationSummary]) -> Vec<Run> {
    let pts = &branch.points;
    let mut out: Vec<Run> = Vec::new();
    for (i, p) in pts.iter().enumerate() {
        match out.last_mut() {
            Some(r) if r.stable == p.stable => {
                r.last = i;
                r.to = p.value;
            }
            _ => out.push(Run {
                stable: p.stable,
                first: i,
                last: i,
                from: p.value,
                to: p.value,
                from_kind: None,
                to_kind: None,
            }),
        }
    }
    absorb_transition_ends(branch, &mut out);
    for k in 1..out.len() {
        let (a, b) = (&pts[out[k - 1].last], &pts[out[k].first]);
        let step = apart(a.value, a.start_x, a.start_wt, b);
        // The bifurcation of the branch between the two points: at a fold
        // the parameter turns back, so it is found by the motion as well.
        let between = bifurcations
            .iter()
            .filter(|f| f.branch == branch.id)
            .map(|f| {
                let d = apart(f.value, f.start_x, f.start_wt, a)
                    + apart(f.value, f.start_x, f.start_wt, b);
                (d, f)
            })
            .filter(|(d, _)| *d <= 1.5 * step + 1e-9)
            .min_by(|x, y| x.0.total_cmp(&y.0));
        if let Some((_, f)) = between {
            out[k - 1].to = f.value;
            out[k - 1].to_kind = Some(f.kind.name());
            out[k].from = f.value;
            out[k].from_kind = Some(f.kind.name());
        }
    }
    out
}

/// Whether a branch's end `reason` is a non-smooth transition (by
/// [`TransitionKind::name`]).
fn is_transition_end(reason: &str) -> bool {
    [
        TransitionKind::Grazing,
        TransitionKind::StickOnset,
        TransitionKind::StickVanishing,
        TransitionKind::PassableOnset,
    ]
    .iter()
    .any(|k| k.name() == reason)
}

/// A run made of the branch's end point alone, located at a non-smooth
/// transition, joins the run next to it. At a grazing arrival `DP`
/// diverges, so its eigenvalues leave the unit disc at the end point itself
/// (`P_{3_33 4_33}` at its grazing of Σ3, Q0 = 100: |λ| = 0.63 at 1e-12
/// before the end, 1 at it): a stretch of zero length that is the
/// transition's, not an unstable stretch of the motion. The branch's
/// points keep their own eigenvalues.
fn absorb_transition_ends(branch: &BranchSummary, out: &mut Vec<Run>) {
    let pts = &branch.points;
    let at_transition = |i: usize| {
        branch
            .ends
            .iter()
            .any(|e| is_transition_end(&e.reason) && e.value == pts[i].value)
    };
    if out.len() >= 2 {
        let last = out.len() - 1;
        if out[last].first == out[last].last && at_transition(out[last].last) {
            let r = out.pop().expect("two runs");
            let before = out.last_mut().expect("two runs");
            before.last = r.last;
            before.to = r.to;
        }
    }
    if out.len() >= 2 && out[0].first == out[0].last && at_transition(0) {
        let r = out.remove(0);
        out[0].first = r.first;
        out[0].from = r.from;
    }
}

/// How far the motion at (`value`, `x`, `phase`) is from the point `p`: the
/// sum of the differences in the parameter, the first switching point's
/// displacement and its phase (round the circle).
fn apart(value: f64, x: f64, phase: f64, p: &BranchSample) -> f64 {
    let dphase = (phase - p.start_wt).rem_euclid(TAU);
    (value - p.value).abs() + (x - p.start_x).abs() + dphase.min(TAU - dphase)
}

const TAU: f64 = 2.0 * std::f64::consts::PI;

/// `+0.600000+0.800000i`.
fn complex([re, im]: [f64; 2]) -> String {
    format!("{re:+.6}{im:+.6}i")
}

/// The sweep of `sweep.param` as asked (`from`, `to`, `count`; `set` says
/// the other parameters): its transitions, bifurcations, branches, then the
/// motions at each point. With `unstable` false, the unstable stretches of
/// the branches and the unstable motions are left out (today's view).
pub fn text(sweep: &Sweep, from: f64, to: f64, count: usize, set: &str, unstable: bool) -> String {
    let name = &sweep.param;
    let mut out = format!("sweep of {name} over [{from}, {to}] ({count} points), {set}\n\n");
    out.push_str("transitions (numbered as in the figure):\n");
    for (k, t) in sweep.transitions.iter().enumerate() {
        out.push_str(&format!(
            "  {:>3}  {name} = {:<18.12} {:<16} {} -> {}{}\n",
            k + 1,
            t.value,
            t.kind.name(),
            t.from,
            t.to,
            t.boundary
                .as_ref()
                .map_or(String::new(), |b| format!(" (on {b})"))
        ));
    }
    if !sweep.bifurcations.is_empty() {
        out.push_str("\nbifurcations:\n");
        for b in &sweep.bifurcations {
            let born = if b.born.is_empty() {
                String::new()
            } else {
                let ids: Vec<String> = b.born.iter().map(|i| format!("#{i}")).collect();
                format!(", born {}", ids.join(" "))
            };
            out.push_str(&format!(
                "  {name} = {:<18.12} {:<16} {}  λ = {}  on branch #{}{born}\n",
                b.value,
                b.kind.name(),
                with_periods(&b.structure, b.n),
                complex(b.eigenvalue),
                b.branch,
            ));
        }
    }
    if !sweep.cuts.is_empty() {
        out.push_str("\ncut (born by period doubling, longer than --max-period):\n");
        for c in &sweep.cuts {
            out.push_str(&format!(
                "  {name} = {:<18.12} {} not followed: period {} > {}\n",
                c.value,
                with_periods(&c.structure, c.n),
                c.n,
                c.max_period
            ));
        }
    }
    for c in &sweep.cascades {
        out.push_str(&cascade_block(name, c));
    }
    let shown: Vec<(&BranchSummary, Vec<Run>)> = sweep
        .branches
        .iter()
        .map(|b| {
            let mut r = runs(b, &sweep.bifurcations);
            r.retain(|r| unstable || r.stable);
            (b, r)
        })
        .filter(|(_, r)| !r.is_empty())
        .collect();
    if !shown.is_empty() {
        out.push_str("\nbranches:\n");
        for (b, runs) in &shown {
            out.push_str(&branch_block(name, b, runs));
        }
    }
    out.push_str("\nmotions:\n");
    for p in &sweep.points {
        let names: Vec<String> = p
            .motions
            .iter()
            .filter(|m| unstable || m.stable)
            .map(|m| {
                let st = if m.stable { "" } else { " (unstable)" };
                format!("{}{st}", with_periods(&m.structure, m.n))
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

/// A period-doubling cascade: its doublings, their spacing ratios, and
/// the accumulation point they extrapolate to.
fn cascade_block(name: &str, c: &Cascade) -> String {
    let mut out = String::from("\nperiod-doubling cascade:\n");
    for d in &c.doublings {
        out.push_str(&format!(
            "  {name} = {:<18.12} period {} -> {}\n",
            d.value,
            d.n,
            2 * d.n
        ));
    }
    if !c.ratios.is_empty() {
        let ratios: Vec<String> = c.ratios.iter().map(|r| format!("{r:.4}")).collect();
        out.push_str(&format!(
            "  spacing ratios {} (Feigenbaum's δ = {FEIGENBAUM_DELTA:.4})\n",
            ratios.join(", ")
        ));
    }
    if let Some(a) = c.accumulation {
        out.push_str(&format!(
            "  accumulation {name} ≈ {a:.10} (from the last ratio)\n"
        ));
    }
    if let Some(a) = c.accumulation_feigenbaum {
        out.push_str(&format!(
            "  accumulation {name} ≈ {a:.10} (with Feigenbaum's δ)\n"
        ));
    }
    out
}

/// One branch: its number, structure and range, its runs, its ends.
fn branch_block(name: &str, b: &BranchSummary, runs: &[Run]) -> String {
    let values = runs
        .iter()
        .flat_map(|r| b.points[r.first..=r.last].iter().map(|p| p.value));
    let (lo, hi) = values.fold((f64::INFINITY, f64::NEG_INFINITY), |(a, c), v| {
        (a.min(v), c.max(v))
    });
    let count: usize = runs.iter().map(|r| r.last + 1 - r.first).sum();
    let mut out = format!(
        "  #{} {}: {name} from {lo:.6} to {hi:.6}, {count} points\n",
        b.id,
        with_periods(&b.structure, b.n)
    );
    let at = |v: f64, kind: Option<&str>| match kind {
        Some(k) => format!("{v:.6} ({k})"),
        None => format!("{v:.6}"),
    };
    for r in runs {
        out.push_str(&format!(
            "      {:<9} {name} = {} -> {}\n",
            if r.stable { "stable" } else { "unstable" },
            at(r.from, r.from_kind),
            at(r.to, r.to_kind)
        ));
    }
    let ends: Vec<String> = b
        .ends
        .iter()
        .map(|e| {
            let mut s = format!("{} at {name} = {:.6}", e.reason, e.value);
            if let Some(on) = &e.boundary {
                s.push_str(&format!(" (on {on})"));
            }
            if let Some(d) = &e.detail {
                s.push_str(&format!(" ({d})"));
            }
            s
        })
        .collect();
    out.push_str(&format!(
        "      ends: {}\n",
        if ends.is_empty() {
            "none (a closed loop)".to_string()
        } else {
            ends.join("; ")
        }
    ));
    out
}

/// The motions at the grid values as CSV, one row per motion: the
/// parameter (the column named after it), `structure`, `N`, `start_Wt`,
/// `start_x`, `stable`, `lambda_max` (the largest `|λ|`, empty without
/// eigenvalues), `max_abs_x`, `max_abs_v` (empty where not finite).
pub fn csv(sweep: &Sweep) -> String {
    let num = |v: f64| {
        if v.is_finite() {
            format!("{v:?}")
        } else {
            String::new()
        }
    };
    let mut out = format!(
        "{},structure,N,start_Wt,start_x,stable,lambda_max,max_abs_x,max_abs_v\n",
        sweep.param
    );
    for p in &sweep.points {
        for m in &p.motions {
            let lambda = m
                .eigenvalues
                .iter()
                .map(|e| e[0].hypot(e[1]))
                .fold(f64::NAN, f64::max);
            out.push_str(&format!(
                "{},\"{}\",{},{},{},{},{},{},{}\n",
                num(p.value),
                m.structure,
                m.n,
                num(m.start_wt),
                num(m.start_x),
                m.stable,
                num(lambda),
                num(m.max_abs_x),
                num(m.max_abs_v),
            ));
        }
    }
    out
}

/// The keys of the objects that also carry the parameter's value.
const KEYS: [&str; 19] = [
    "motions",
    "from",
    "to",
    "kind",
    "boundary",
    "start_Wt",
    "start_x",
    "eigenvalues",
    "stable",
    "reason",
    "detail",
    "structure",
    "N",
    "eigenvalue",
    "branch",
    "born",
    "max_period",
    "max_abs_x",
    "max_abs_v",
];

fn clash(name: &str) -> serde_json::Error {
    serde::ser::Error::custom(format!(
        "the swept parameter `{name}` has the name of a key of the sweep's JSON \
         (the guide, \"One-parameter studies\"), so its value could not be told apart; \
         rename the parameter in the model"
    ))
}

/// `item` as a JSON object with the parameter's value first, keyed by the
/// parameter's name. The name must not be one of the item's own keys.
fn keyed(name: &str, value: f64, item: &impl Serialize) -> Result<Value, serde_json::Error> {
    let mut o = Map::new();
    o.insert(name.to_string(), serde_json::json!(value));
    let Value::Object(fields) = serde_json::to_value(item)? else {
        return Err(serde::ser::Error::custom(
            "a sweep item is not a JSON object",
        ));
    };
    for (k, v) in fields {
        if k == name {
            return Err(clash(name));
        }
        o.insert(k, v);
    }
    Ok(Value::Object(o))
}

#[derive(Serialize)]
struct PointFields<'a> {
    motions: &'a [crate::study::sweep::MotionSummary],
}

#[derive(Serialize)]
struct TransitionFields<'a> {
    from: &'a str,
    to: &'a str,
    kind: &'static str,
    boundary: &'a Option<String>,
}

/// The sweep as JSON, every parameter value keyed by the parameter's name:
/// `param`; `points` (each grid value and the motions there);
/// `transitions` (the value, `from`, `to`, `kind`, `boundary`); `branches`
/// (`id`, `structure`, `N`, `points` in arclength order with `start_Wt`,
/// `start_x`, `eigenvalues`, `stable`, `max_abs_x`, `max_abs_v`, and `ends` with `reason` and, where
/// they apply, `boundary` and `detail`); `bifurcations` (the value, `kind`,
/// `structure`, `N`, `eigenvalue`, `branch`, `born`, `start_Wt`,
/// `start_x`); `cuts` (the value, `structure`, `N`, `max_period`: branches
/// born by period doubling and not followed); `cascades` (`doublings` with
/// `value` and `N`, `ratios`, `accumulation`, `accumulation_feigenbaum`).
/// A parameter named like one of these keys is an error.
pub fn json(sweep: &Sweep) -> Result<String, serde_json::Error> {
    let name = &sweep.param;
    if KEYS.contains(&name.as_str()) {
        return Err(clash(name));
    }
    let points = sweep
        .points
        .iter()
        .map(|p| {
            keyed(
                name,
                p.value,
                &PointFields {
                    motions: &p.motions,
                },
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let transitions = sweep
        .transitions
        .iter()
        .map(|t| {
            keyed(
                name,
                t.value,
                &TransitionFields {
                    from: &t.from,
                    to: &t.to,
                    kind: t.kind.name(),
                    boundary: &t.boundary,
                },
            )
        })
        .collect::<Result<Vec<_>, _>>()?;
    let branches = sweep
        .branches
        .iter()
        .map(|b| {
            let samples = b
                .points
                .iter()
                .map(|q| keyed(name, q.value, q))
                .collect::<Result<Vec<_>, _>>()?;
            let ends = b
                .ends
                .iter()
                .map(|e| keyed(name, e.value, e))
                .collect::<Result<Vec<_>, _>>()?;
            Ok(serde_json::json!({
                "id": b.id,
                "structure": b.structure,
                "N": b.n,
                "points": samples,
                "ends": ends,
            }))
        })
        .collect::<Result<Vec<_>, serde_json::Error>>()?;
    let bifurcations = sweep
        .bifurcations
        .iter()
        .map(|f| keyed(name, f.value, f))
        .collect::<Result<Vec<_>, _>>()?;
    let cuts = sweep
        .cuts
        .iter()
        .map(|c| keyed(name, c.value, c))
        .collect::<Result<Vec<_>, _>>()?;
    let doc = serde_json::json!({
        "param": name,
        "points": points,
        "transitions": transitions,
        "branches": branches,
        "bifurcations": bifurcations,
        "cuts": cuts,
        "cascades": sweep.cascades,
    });
    serde_json::to_string_pretty(&doc)
}

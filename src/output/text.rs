//! The text forms of what the commands find: a report (what `orbit` and
//! `simulate` print without `--json`) and the trade's table.

use std::fmt;

use crate::orbit::equilibrium::{Equilibrium, Verdict};
use crate::orbit::stability::{Classification, Stability};
use crate::output::report::{MotionReport, ParamValues, Report};
use crate::study::equilibria::Scan;
use crate::study::trade::{Thresholds, Trade};

impl fmt::Display for ParamValues {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        for (i, (name, value)) in self.0.iter().enumerate() {
            if i > 0 {
                f.write_str(", ")?;
            }
            write!(f, "{name} = {value}")?;
        }
        Ok(())
    }
}

fn classification_text(s: &Stability) -> &'static str {
    match s.classification {
        Classification::Stable => "stable",
        Classification::Unstable => "unstable",
        Classification::NearSaddleNode => "near a saddle-node bifurcation (an eigenvalue near +1)",
        Classification::NearPeriodDoubling => {
            "near a period-doubling bifurcation (an eigenvalue near -1)"
        }
        Classification::NearNeimark => "near a Neimark bifurcation (a complex pair near |λ| = 1)",
    }
}

/// 12 decimals, or scientific notation for tiny nonzero values (round-off).
fn number(x: f64) -> String {
    if x == 0.0 || x.abs() >= 1e-6 {
        format!("{x:.12}")
    } else {
        format!("{x:.3e}")
    }
}

fn write_motion(f: &mut fmt::Formatter<'_>, r: &MotionReport) -> fmt::Result {
    let what = if !r.admissible {
        "NOT A MOTION (inadmissible Newton solution)"
    } else if r.period.is_some() {
        "autonomous cycle"
    } else {
        "periodic motion"
    };
    match r.period {
        Some(t) => writeln!(
            f,
            "{what}: {}, period T = {t:.12} (no forcing: W only sets the phase unit; model {})",
            r.structure, r.model
        )?,
        None => writeln!(
            f,
            "{what}: {}, period N = {} (model {})",
            r.structure, r.periods, r.model
        )?,
    }
    writeln!(f, "parameters: {}", r.params)?;
    writeln!(
        f,
        "Newton: converged in {} iteration{}, residual {}",
        r.newton.iterations,
        if r.newton.iterations == 1 { "" } else { "s" },
        r.newton
            .residual
            .map_or_else(|| "unknown".to_string(), |x| format!("{x:.1e}"))
    )?;
    writeln!(f)?;
    writeln!(
        f,
        "{:>3}  {:<8} {:<9} {:>17} {:>17} {:>18} {:>8}",
        "k", "mapping", "boundary", "W t", "W t mod 2π", "x", "v"
    )?;
    for p in &r.points {
        writeln!(
            f,
            "{:>3}  {:<8} {:<9} {:>17.12} {:>17.12} {:>18.12} {:>8}",
            p.k, p.mapping, p.boundary, p.phase, p.phase_mod_2pi, p.x, p.v
        )?;
    }
    writeln!(f, "(point k is the start of the k-th mapping applied)")?;
    writeln!(f)?;
    match &r.stability {
        Some(s) => {
            if r.period.is_some() {
                writeln!(
                    f,
                    "Floquet multipliers (the trivial 1 along the flow replaced by 0):"
                )?;
            } else {
                writeln!(f, "eigenvalues of DP (in (W t, x)):")?;
            }
            for (i, e) in s.eigenvalues.iter().enumerate() {
                let value = if e[1] == 0.0 {
                    number(e[0])
                } else {
                    let sign = if e[1] < 0.0 { '-' } else { '+' };
                    format!("{} {sign} {}i", number(e[0]), number(e[1].abs()))
                };
                writeln!(
                    f,
                    "  λ{} = {value:<36} |λ{}| = {}",
                    i + 1,
                    i + 1,
                    number(e[0].hypot(e[1]))
                )?;
            }
            write!(
                f,
                "stability: {} (largest |λ| = {:.6})",
                classification_text(s),
                s.largest_modulus
            )?;
            if s.has_zero_eigenvalue && r.period.is_none() {
                write!(f, "; one eigenvalue is 0 to round-off (stick)")?;
            }
            writeln!(f)?;
        }
        None => writeln!(
            f,
            "eigenvalues: none (DP does not exist: an arrival is tangent to its boundary)"
        )?,
    }
    if r.violations.is_empty() {
        writeln!(
            f,
            "admissible: yes (every segment, crossing and force criterion checked)"
        )
    } else {
        writeln!(f, "admissible: NO, violated conditions:")?;
        for v in &r.violations {
            let mapping = r.points.get(v.segment).map_or("?", |p| p.mapping);
            writeln!(
                f,
                "  mapping {} ({mapping}): {} (margin {:.3e})",
                v.segment, v.condition, v.margin
            )?;
        }
        Ok(())
    }
}

impl fmt::Display for Report {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Report::Periodic(r) | Report::Inadmissible(r) => write_motion(f, r),
            Report::NeutralFamily(r) => {
                write_motion(f, r)?;
                writeln!(
                    f,
                    "neutral family: DP has the eigenvalue 1 (to round-off): this motion is one \
                     of a continuum of neutrally stable periodic motions; other starts settle on \
                     other members (Csernák, Stépán & Shaw 2007: the undamped Coulomb oscillator \
                     at W = sqrt(c) / (2 n))"
                )
            }
            Report::NoMotion(r) if r.steady_sliding.is_some() => writeln!(
                f,
                "{} (model {}; no motion touches a boundary, certified at W t = {:.6})",
                steady_sliding_line(r.steady_sliding.as_ref().expect("checked"), &r.seat),
                r.model,
                r.certified_at
            ),
            Report::NoMotion(r) => writeln!(
                f,
                "NM (no motion touches a boundary; model {}): the steady motion stays in domain {} \
                 with {:.6} <= v <= {:.6} (certified by a bound on the transient at W t = {:.6})",
                r.model, r.domain, r.min_v, r.max_v, r.certified_at
            ),
            Report::Stick(r) => writeln!(
                f,
                "permanent stick (model {}): the mass sticks from W t = {:.6} on at x = {:.12}, \
                 v = {}; the non-friction force never exceeds {:.6} <= as = {:.6}",
                r.model, r.since, r.x, r.v, r.max_force, r.static_bound
            ),
            Report::Autonomous(r) => writeln!(
                f,
                "autonomous {} cycle (no forcing; model {}): {}, period T = {:.12} \
                 (stick {:.12}, slip {:.12}); the {} at x = {:.12}, v = {} \
                 (W t = {:.6}; W only sets the phase unit); {}",
                if r.stick > 0.0 { "stick-slip" } else { "slip" },
                r.model,
                r.structure,
                r.period,
                r.stick,
                r.slip,
                if r.stick > 0.0 {
                    "stick begins"
                } else {
                    "cycle passes its first boundary"
                },
                r.x,
                r.v,
                r.onset,
                match r.multiplier {
                    Some(m) if m.abs() <= 1e-12 => "stable, Floquet multiplier 0 to round-off \
                        (the trivial 1 removed; the stick resets every perturbation)"
                        .to_string(),
                    Some(m) if m.abs() < 1.0 =>
                        format!("stable, Floquet multiplier {m:.6e} (the trivial 1 removed)"),
                    Some(m) =>
                        format!("unstable, Floquet multiplier {m:.6e} (the trivial 1 removed)"),
                    None => "stability unknown: an arrival grazes its boundary".to_string(),
                }
            ),
            Report::NotConverged(r) => {
                writeln!(f, "{}", r.headline())?;
                writeln!(
                    f,
                    "iterations: {}, residual: {}",
                    r.newton.iterations,
                    r.newton
                        .residual
                        .map_or_else(|| "unknown".to_string(), |x| format!("{x:.3e}"))
                )
            }
        }
    }
}

/// A text table of the trade.
pub fn trade_table(t: &Trade) -> String {
    let mut out = format!(
        "speed/accuracy trade of `{}` (reference: the law integrated at rtol {:e}, {} belt events per cycle, amplitude {:.9})\n\n",
        t.model,
        t.reference_tol,
        t.reference.belt_events.len(),
        t.reference.amplitude
    );
    out.push_str(&format!(
        "{:<11} {:>7} {:>8} {:>12} {:>12} {:>12} {:>12} {:>12}  structure / note\n",
        "method", "pieces", "tol", "time [ms]", "err W t", "err x", "err ampl.", "error"
    ));
    for r in &t.rows {
        let pieces = r.pieces.map_or("-".into(), |n| n.to_string());
        let tol = r.tol.map_or("-".into(), |t| format!("{t:e}"));
        let what = r.note.clone().unwrap_or_else(|| {
            if r.structure.len() > 60 {
                format!("{}… ({} chars)", &r.structure[..57], r.structure.len())
            } else {
                r.structure.clone()
            }
        });
        out.push_str(&format!(
            "{:<11} {:>7} {:>8} {:>12.4} {:>12.3e} {:>12.3e} {:>12.3e} {:>12.3e}  {}\n",
            r.method,
            pieces,
            tol,
            r.seconds * 1e3,
            r.error_phase,
            r.error_x,
            r.error_amplitude,
            r.error,
            what
        ));
    }
    match t.order {
        Some(o) => out.push_str(&format!(
            "\nobserved convergence order in N (N >= 8): {o:.3} (interpolating a smooth law: 2)\n"
        )),
        None => {
            out.push_str("\nobserved convergence order in N: not enough comparable piece counts\n")
        }
    }
    out
}

/// A text table of the thresholds of steady sliding, N pieces against the law.
pub fn threshold_table(t: &Thresholds) -> String {
    let list = |at: &[f64]| {
        at.iter()
            .map(|a| format!("{a:.15}"))
            .collect::<Vec<_>>()
            .join(", ")
    };
    let mut out = format!(
        "where steady sliding of `{}` changes stability along {} in [{}, {}] ({} values, each change located between two): the law's own at {} = {} ({:.4} ms)\n\n",
        t.model,
        t.param,
        t.range[0],
        t.range[1],
        t.count,
        t.param,
        list(&t.law),
        t.law_seconds * 1e3
    );
    out.push_str(&format!(
        "{:>7} {:>12} {:>12}  {}\n",
        "pieces", "time [ms]", "rel. error", "threshold / note"
    ));
    for r in &t.rows {
        let what = r.note.clone().unwrap_or_else(|| list(&r.at));
        out.push_str(&format!(
            "{:>7} {:>12.4} {:>12.3e}  {}\n",
            r.pieces,
            r.seconds * 1e3,
            r.error,
            what
        ));
    }
    if t.exact {
        out.push_str(
            "\nevery piece count has the law's threshold to rounding: a breakpoint sits where steady sliding changes stability at the defaults\n",
        );
    } else {
        match t.order {
            Some(o) => out.push_str(&format!(
                "\nobserved convergence order in N (N >= 8): {o:.3} (a threshold lies on a breakpoint within a piece of the law's: 1)\n"
            )),
            None => out.push_str(
                "\nobserved convergence order in N: not enough piece counts with an error above rounding\n",
            ),
        }
    }
    out
}

/// A pair of eigenvalues `[re, im]`: `-0.03 ± 0.99i`, or `-0.5, -2`.
pub fn eigenvalue_pair(e: &[[f64; 2]; 2]) -> String {
    if e[0][1] != 0.0 {
        format!("{:.9} ± {:.9}i", e[0][0], e[0][1].abs())
    } else {
        format!("{:.9}, {:.9}", e[0][0], e[1][0])
    }
}

/// One sentence on steady sliding: where, how stable, the eigenvalues.
pub fn steady_sliding_line(e: &Equilibrium, seat: &str) -> String {
    let verdict = match e.verdict {
        Verdict::Stable => "stable",
        Verdict::Unstable => "unstable",
        Verdict::Neutral => "neutral (at a change of stability)",
    };
    let mut line = format!(
        "steady sliding at x = {:.12}, v = 0 ({seat}): {verdict}, eigenvalues {}",
        e.x,
        eigenvalue_pair(&e.eigenvalues)
    );
    if let Some(above) = &e.above {
        line.push_str(&format!(
            " below the kink, {} above",
            eigenvalue_pair(above)
        ));
    }
    line.push_str(&format!(", margin {:.6e}", e.margin));
    line
}

/// What a smooth law's simulation settled to, in words: steady sliding,
/// or the cycle with its period, stick, multiplier and events.
pub fn smooth_settled(s: &crate::orbit::smooth::SmoothSettled) -> String {
    use crate::orbit::smooth::SmoothSettled;
    match s {
        SmoothSettled::Periodic(m) => smooth_periodic(m),
        SmoothSettled::SteadySliding {
            equilibrium,
            returns,
        } => format!(
            "{} (after {returns} returns to the section v = 0)\n",
            steady_sliding_line(equilibrium, "law")
        ),
        SmoothSettled::Cycle { cycle, returns } => {
            let verdict = verdict_word(cycle.verdict);
            let kind = if cycle.stick > 0.0 {
                "stick-slip cycle"
            } else {
                "slip cycle"
            };
            let mut out = format!(
                "{kind}: period T = {:.12}, stick {:.12} per period, largest x = {:.12} (on v = 0), \
                 {verdict}, Floquet multiplier {:.9} (the trivial 1 removed)\n\
                 found after {returns} returns to the section v = 0; shooting on it\n",
                cycle.period, cycle.stick, cycle.x, cycle.multiplier
            );
            out.push_str(&event_lines(&cycle.events));
            out
        }
    }
}

/// A stability verdict in one word.
fn verdict_word(v: Verdict) -> &'static str {
    match v {
        Verdict::Stable => "stable",
        Verdict::Unstable => "unstable",
        Verdict::Neutral => "neutral",
    }
}

/// An integrated motion's events at the belt speed, a line each.
fn event_lines(events: &[crate::dynamics::integrate::BeltEvent]) -> String {
    events
        .iter()
        .map(|e| {
            format!(
                "  W t = {:>16.12}  x = {:>16.12}  {:?} -> {:?}\n",
                e.phase, e.x, e.before, e.after
            )
        })
        .collect()
}

/// A forced smooth-law periodic motion, in words.
pub fn smooth_periodic(m: &crate::orbit::smooth::SmoothPeriodic) -> String {
    let verdict = verdict_word(m.verdict);
    let kind = if m.sticks { "with stick" } else { "slip only" };
    let mut out = format!(
        "periodic motion of {} forcing period(s), {kind}: at W t = {:.12}, x = {:.12}, v = {:.12}; \
         {verdict}, Floquet multipliers {}\nfound after {} forcing periods; shooting on the stroboscopic map\n",
        m.periods,
        m.phase,
        m.x,
        m.v,
        eigenvalue_pair(&m.multipliers),
        m.transient
    );
    out.push_str(&event_lines(&m.events));
    out
}

/// A smooth law along a parameter as CSV: one row per motion at each grid
/// value, steady sliding (`kind` `steady_sliding`, its rest position `x`)
/// and each cycle (`stick_slip` or `slip`, its point `x` on `v = 0`, period,
/// stick time, multiplier).
pub fn law_sweep_csv(s: &crate::study::law::LawSweep) -> String {
    let mut out = format!("{},kind,x,stable,period,stick,multiplier\n", s.param);
    for p in &s.points {
        let value = p.rest.value;
        if let Some(e) = &p.rest.equilibrium {
            out.push_str(&format!(
                "{value:?},steady_sliding,{:?},{},,,\n",
                e.x,
                e.verdict == Verdict::Stable
            ));
        }
        for c in &p.cycles {
            let kind = if c.stick > 0.0 { "stick_slip" } else { "slip" };
            out.push_str(&format!(
                "{value:?},{kind},{:?},{},{:?},{:?},{:?}\n",
                c.x,
                c.verdict == Verdict::Stable,
                c.period,
                c.stick,
                c.multiplier
            ));
        }
    }
    out
}

/// A smooth law along a parameter: one line per grid value (steady
/// sliding, then every cycle), then the located changes.
pub fn law_sweep_table(s: &crate::study::law::LawSweep) -> String {
    let mut out = format!(
        "{} (the law itself) along {}: steady sliding and every cycle on the section v = 0\n",
        s.model, s.param
    );
    out.push_str(&format!(
        "{:>14}  {:<10}  {:>16}  cycles (x on v = 0, period T, stick, multiplier, stability)\n",
        s.param, "rest", "x*"
    ));
    for p in &s.points {
        let (verdict, x) = match &p.rest.equilibrium {
            Some(e) => (verdict_word(e.verdict), format!("{:.12}", e.x)),
            None => ("none", "-".to_string()),
        };
        let cycles: Vec<String> = p
            .cycles
            .iter()
            .map(|c| {
                let kind = if c.stick > 0.0 { "stick-slip" } else { "slip" };
                let v = verdict_word(c.verdict);
                format!(
                    "{kind} x={:.9} T={:.9} stick={:.9} mu={:.6} {v}",
                    c.x, c.period, c.stick, c.multiplier
                )
            })
            .collect();
        let cycles = if cycles.is_empty() {
            "none".to_string()
        } else {
            cycles.join("; ")
        };
        out.push_str(&format!(
            "{:>14.9}  {verdict:<10}  {x:>16}  {cycles}\n",
            p.rest.value
        ));
    }
    for c in &s.changes {
        out.push_str(&format!(
            "change of stability at {} = {}: {}\n",
            s.param, c.change.at, c.what
        ));
    }
    for e in &s.stick_slip {
        out.push_str(&format!("at {} = {}: {}\n", s.param, e.at, e.what));
    }
    out
}

/// A text table of steady sliding along a parameter, then its changes of
/// stability.
pub fn equilibria_table(s: &Scan) -> String {
    let mut out = String::new();
    if s.param.is_empty() {
        let point = &s.points[0];
        return match (&point.equilibrium, &point.seat) {
            (Some(e), Some(seat)) => {
                format!("model {}\n{}\n", s.model, steady_sliding_line(e, seat))
            }
            _ => format!(
                "model {}\nno steady sliding: {}\n",
                s.model,
                point.none.as_deref().unwrap_or("")
            ),
        };
    }
    out.push_str(&format!(
        "steady sliding of {} along {}\n",
        s.model, s.param
    ));
    out.push_str(&format!(
        "{:>14}  {:>16}  {:<12}  {:<10}  {:>13}  eigenvalues\n",
        s.param, "x*", "at", "stability", "margin"
    ));
    for p in &s.points {
        match (&p.equilibrium, &p.seat) {
            (Some(e), Some(seat)) => out.push_str(&format!(
                "{:>14.9}  {:>16.12}  {:<12}  {:<10}  {:>13.6e}  {}\n",
                p.value,
                e.x,
                seat,
                format!("{:?}", e.verdict).to_lowercase(),
                e.margin,
                eigenvalue_pair(&e.eigenvalues)
            )),
            _ => out.push_str(&format!(
                "{:>14.9}  none: {}\n",
                p.value,
                p.none.as_deref().unwrap_or("")
            )),
        }
    }
    if s.changes.is_empty() {
        out.push_str("no change of stability on this grid\n");
    }
    for c in &s.changes {
        let side = |v: Option<Verdict>| match v {
            Some(Verdict::Stable) | Some(Verdict::Neutral) => "stable",
            Some(Verdict::Unstable) => "unstable",
            None => "none",
        };
        out.push_str(&format!(
            "change of stability at {} = {:.15}: {} below, {} above; {}\n",
            s.param,
            c.change.at,
            side(c.change.before),
            side(c.change.after),
            c.what
        ));
    }
    out
}

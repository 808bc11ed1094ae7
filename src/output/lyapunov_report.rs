//! `stickslip lyapunov`: the spectrum as text or JSON.
//!
//! JSON has no infinity: an exponent of `−∞` (a stick collapses a direction)
//! is written as the string `"-inf"`; every finite exponent is a number.

use serde::Serialize;
use serde_json::Value;

use crate::orbit::lyapunov::{LyapunovOptions, Spectrum, Verdict};

/// The JSON document of `lyapunov --json`.
#[derive(Clone, Debug, Serialize)]
pub struct LyapunovReport {
    /// Exponents per unit time, largest first (`"-inf"` for `−∞`).
    pub exponents: [Value; 2],
    /// Exponents per forcing period.
    pub per_period: [Value; 2],
    /// Standard error of the block means (per unit time).
    pub error: Value,
    /// `periodic`, `chaotic`, `quasi_periodic`, `NM`, `stick` or `long_cycle`.
    pub attractor: &'static str,
    /// The periodic motion's structure `P_{…}`, else `null`.
    pub structure: Option<String>,
    /// Forcing periods of the periodic motion's cycle, else `null`.
    pub periods_per_cycle: Option<u32>,
    /// Forcing periods discarded, then accumulated.
    pub transient: u32,
    /// Forcing periods accumulated.
    pub periods: u32,
    /// The state `[x, v, W t]` at the end of the run.
    pub end: [f64; 3],
}

/// A number, or `"-inf"`/`"inf"`/`"nan"` where JSON has none.
pub fn number(x: f64) -> Value {
    if x.is_finite() {
        Value::from(x)
    } else if x.is_nan() {
        Value::from("nan")
    } else if x > 0.0 {
        Value::from("inf")
    } else {
        Value::from("-inf")
    }
}

impl LyapunovReport {
    /// The report of `s`, computed with `opts`.
    pub fn of(s: &Spectrum, opts: LyapunovOptions) -> Self {
        let (structure, n) = match &s.verdict {
            Verdict::Periodic { structure, n } => (Some(structure.clone()), Some(*n)),
            _ => (None, None),
        };
        Self {
            exponents: s.exponents.map(number),
            per_period: s.per_period.map(number),
            error: number(s.error),
            attractor: s.verdict.label(),
            structure,
            periods_per_cycle: n,
            transient: opts.transient,
            periods: opts.periods,
            end: [s.end.0, s.end.1, s.end.2],
        }
    }

    /// The text form.
    pub fn text(&self, s: &Spectrum) -> String {
        let show = |x: f64| {
            if x == f64::NEG_INFINITY {
                "-inf".to_string()
            } else {
                format!("{x:+.9e}")
            }
        };
        let verdict = verdict_text(&s.verdict);
        let mut out = format!(
            "Lyapunov exponents of the stroboscopic map ({} forcing periods after {} of transient)\n",
            self.periods, self.transient
        );
        out += &format!(
            "  per unit time:       {}  {}\n",
            show(s.exponents[0]),
            show(s.exponents[1])
        );
        out += &format!(
            "  per forcing period:  {}  {}\n",
            show(s.per_period[0]),
            show(s.per_period[1])
        );
        out += &format!(
            "  error (block standard error, per unit time): {:.2e}\n",
            s.error
        );
        if s.exponents[1] == f64::NEG_INFINITY {
            out += "  (-inf: a stick collapses the velocity direction)\n";
        }
        out += &format!("  attractor: {verdict}\n");
        out += &format!(
            "  end state: x = {:.9}, v = {:.9}, W t = {:.9}\n",
            s.end.0, s.end.1, s.end.2
        );
        out
    }
}

/// A verdict in words: `chaotic`, `quasi-periodic`, `periodic P_{…}, N = 2`.
pub fn verdict_text(v: &Verdict) -> String {
    match v {
        Verdict::Periodic { structure, n } => format!("periodic {structure}, N = {n}"),
        Verdict::Chaotic => "chaotic".to_string(),
        Verdict::QuasiPeriodic => "quasi-periodic".to_string(),
        Verdict::NoMotion => "NM (no boundary contact)".to_string(),
        Verdict::Stick => "stick (a stick that never ends)".to_string(),
        Verdict::LongCycle { longer_than } => {
            format!("cycle longer than {longer_than} forcing periods (no repeat, exponent < 0)")
        }
    }
}

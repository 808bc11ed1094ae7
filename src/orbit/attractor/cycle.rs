//! Recognising a cycle at the end of a simulation's events: the same
//! events (boundary, kind, sides, x) repeat, shifted by a whole number of
//! forcing periods; by length up to a cap, and longer cycles by period.

use crate::dynamics::simulate::Event;

use super::{LONG_CYCLE_PERIODS, TAU};

/// The smallest cycle at the end of `events`: `(m events, N periods)`.
pub(super) fn detect_cycle(events: &[Event], max_cycle: usize, tol: f64) -> Option<(usize, u32)> {
    let n = events.len();
    for m in 1..=max_cycle {
        if n < 2 * m + 1 {
            return None;
        }
        if let Some(periods) = repeats(events, m, tol) {
            return Some((m, periods));
        }
    }
    None
}

/// Whether the last `m + 1` events repeat the `m + 1` before them, shifted by
/// a whole number of forcing periods: that number, if so.
fn repeats(events: &[Event], m: usize, tol: f64) -> Option<u32> {
    let n = events.len();
    if m == 0 || n < 2 * m + 1 {
        return None;
    }
    let mut shift = None;
    for i in 0..=m {
        let (a, b) = (&events[n - 1 - i], &events[n - 1 - i - m]);
        if a.boundary != b.boundary
            || a.kind != b.kind
            || a.before != b.before
            || a.after != b.after
        {
            return None;
        }
        let ds = a.phase - b.phase;
        let scale = 1.0 + a.x.abs().max(b.x.abs());
        if (a.x - b.x).abs() > tol * scale {
            return None;
        }
        match shift {
            None => shift = Some(ds),
            Some(s) if (ds - s).abs() > tol * s.abs().max(1.0) => return None,
            _ => {}
        }
    }
    let s = shift?;
    let periods = (s / TAU).round();
    (periods >= 1.0 && (s - periods * TAU).abs() < 10.0 * tol * s.max(1.0))
        .then_some(periods as u32)
}

/// A cycle longer than `cap` mappings at the end of `events`, found by its
/// period instead of its length: for `N = 1, 2, …` forcing periods, the
/// events of the last `N` periods repeat the ones before them.
/// `(m events, N periods)`, the shortest period first.
pub(super) fn detect_long_cycle(events: &[Event], cap: usize, tol: f64) -> Option<(usize, u32)> {
    let last = events.last()?;
    for periods in 1..=LONG_CYCLE_PERIODS {
        let target = last.phase - TAU * periods as f64;
        // The event one cycle before the last one sits near `target`.
        let i = events.partition_point(|e| e.phase < target);
        for idx in [i.wrapping_sub(1), i] {
            let Some(m) = (events.len() - 1).checked_sub(idx) else {
                continue;
            };
            if m > cap && repeats(events, m, tol) == Some(periods) {
                return Some((m, periods));
            }
        }
    }
    None
}

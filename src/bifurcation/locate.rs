//! Locating where a quantity changes sign along a continuation step:
//! regula falsi (Illinois) in arclength, shared by the one-parameter
//! continuation and the two-parameter curves.

/// Regula falsi (Illinois) in arclength on `g` over `[0, s_bad]`, from a
/// sample where `g = g_from > 0` to one where `g = g_bad <= 0` (or NaN:
/// undefined), until the bracket is below `s_tol`. `trial(s)` corrects the
/// point at arclength `s` (`None`: the corrector failed there, counted as
/// undefined). Returns the last good trial (`None` if there was none) and
/// the last bad one.
pub(crate) fn regula_falsi<S>(
    g_from: f64,
    s_bad: f64,
    g_bad: f64,
    s_tol: f64,
    mut trial: impl FnMut(f64) -> Option<S>,
    g: impl Fn(&S) -> f64,
) -> (Option<S>, Option<S>) {
    let (mut lo, mut glo) = (0.0, g_from);
    let (mut hi, mut ghi) = (s_bad, g_bad);
    let mut good: Option<S> = None;
    let mut bad: Option<S> = None;
    // Which end moved last, twice in a row as ±2 (Illinois halves the other).
    let mut side = 0i8;
    for _ in 0..200 {
        if (hi - lo).abs() <= s_tol {
            break;
        }
        let mut s = if glo.is_finite() && ghi.is_finite() && glo != ghi {
            let (wl, wh) = match side {
                1 => (0.5, 1.0),
                -1 => (1.0, 0.5),
                _ => (1.0, 1.0),
            };
            lo + (hi - lo) * (wl * glo) / (wl * glo - wh * ghi)
        } else {
            0.5 * (lo + hi)
        };
        let span = hi - lo;
        if !(s > lo + 1e-3 * span && s < hi - 1e-3 * span) || side.abs() == 2 {
            s = 0.5 * (lo + hi);
            side = 0;
        }
        match trial(s) {
            Some(smp) => {
                let v = g(&smp);
                if v > 0.0 {
                    lo = s;
                    glo = v;
                    good = Some(smp);
                    side = if side == 1 { 2 } else { 1 };
                } else {
                    hi = s;
                    ghi = if v.is_nan() { f64::NAN } else { v };
                    bad = Some(smp);
                    side = if side == -1 { -2 } else { -1 };
                }
                // A trial on the zero itself (to rounding) ends the bracket
                // like any bad one, but not the search: the good end is
                // still wherever the last good trial was (a whole step away
                // if the first trial hits the zero), and what the callers
                // report is that end. Bisection closes in on it (the secant
                // through a zero lands on the bad end itself).
            }
            None => {
                hi = s;
                ghi = f64::NAN;
                side = 0;
            }
        }
    }
    (good, bad)
}

#[cfg(test)]
mod tests {
    use super::regula_falsi;

    /// The root of a smooth function, from a bracket, to the tolerance;
    /// the good side stays positive and the bad side non-positive.
    #[test]
    fn brackets_the_root_of_a_smooth_function() {
        let f = |s: f64| 0.3 - s * s;
        let (good, bad) = regula_falsi(f(0.0), 1.0, f(1.0), 1e-12, Some, |&s| f(s));
        let (good, bad) = (good.unwrap(), bad.unwrap());
        assert!(f(good) > 0.0 && f(bad) <= 0.0);
        assert!((good - 0.3f64.sqrt()).abs() < 1e-11, "{good}");
        assert!((bad - good).abs() <= 1e-11);
    }

    /// A trial that hits the zero exactly is a bad end, and the good end
    /// still closes in on it to the tolerance (it was left a whole step
    /// away when the search stopped there).
    #[test]
    fn a_trial_on_the_zero_still_brackets_it() {
        // Linear: the first secant lands on the root, where `g` is exactly 0.
        let f = |s: f64| 0.5 - s;
        let (good, bad) = regula_falsi(f(0.0), 1.0, f(1.0), 1e-12, Some, |&s| f(s));
        let (good, bad) = (good.unwrap(), bad.unwrap());
        assert_eq!(f(bad), 0.0);
        assert!(f(good) > 0.0 && 0.5 - good <= 1e-12, "{good}");
    }

    /// Where the quantity is undefined past the root (NaN, or a failed
    /// trial), bisection still closes in on its edge.
    #[test]
    fn closes_in_on_an_undefined_side() {
        let f = |s: f64| if s < 0.4 { 0.4 - s } else { f64::NAN };
        let (good, _) = regula_falsi(f(0.0), 1.0, f64::NAN, 1e-10, Some, |&s| f(s));
        assert!((good.unwrap() - 0.4).abs() < 1e-9);
        let trial = |s: f64| (s < 0.25).then_some(s);
        let (good, bad) = regula_falsi(1.0, 1.0, f64::NAN, 1e-10, trial, |_| 1.0);
        assert!((good.unwrap() - 0.25).abs() < 1e-9);
        assert!(bad.is_none());
    }
}

//! Locating the first event of a segment, without missing one.
//!
//! An event is the first root in phase of one of two *event functions*
//! `h_k(φ)` (for a flow in a domain: `v − V_lower`, `v − V_upper`; for a
//! stick: `Fnf ∓ as`). The caller provides, at any phase, the values `h_k`,
//! their common derivative `h'` and a bound `B(Δ)` on `|h''|` over the next
//! `Δ` in phase (for linear flows it follows from Grönwall's inequality on the
//! ODE that the acceleration and its rate satisfy; see `simulate`).
//!
//! **Step rule.** On an interval `(φ0, φ0 + Δ]` Taylor's theorem gives
//! `h(φ0 + s) = h0 + h0' s + R`, `|R| ≤ B s² / 2`. Then `h` has no root there if
//!
//! * `h0` and `h0'` have the same sign, or `h0 = 0` (moving away):
//!   `|h0| + |h0'| Δ − B Δ²/2 > 0`;
//! * otherwise (moving towards the root): `|h0| − |h0'| Δ − B Δ²/2 > 0`.
//!
//! An interval that passes this test for both functions is skipped: it cannot
//! contain a root, transversal or tangent. An interval that does not pass is
//! split in two and the halves are searched left first, so the root found is
//! the *first* one. Splitting stops at a width of about 1e-12 of the step, where
//! either `h` changes sign across the interval (a crossing, then polished by
//! safeguarded Newton to about 1e-15 in phase) or it does not (the function
//! touches zero without crossing: a graze, reported as such, never dropped).
//! Near a non-grazing extremum (`|h| = ε > 0` at `h' = 0`) the test passes once
//! `Δ < sqrt(2 ε / B)`, so the recursion always ends.

/// What the caller knows about the event functions at one phase.
#[derive(Clone, Copy, Debug)]
pub struct Probe {
    /// Values of the two event functions (`f64::INFINITY` for an absent one).
    pub h: [f64; 2],
    /// Their common derivative in phase.
    pub dh: f64,
    /// Their common second derivative in phase (an input to the bound).
    pub ddh: f64,
}

/// How a root was found.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum RootKind {
    /// `h` changes sign.
    Crossing,
    /// `h` touches zero without changing sign (tangency).
    Graze,
    /// The event functions are not finite here (the motion has blown up):
    /// the search stops at this phase.
    NotFinite,
    /// The phase cannot advance by the step here (the step is below the
    /// rounding of the phase, which is too large, or is 0): the search stops.
    Unresolved,
}

/// The first root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Root {
    /// Phase of the root.
    pub phase: f64,
    /// Which event function (0 or 1).
    pub which: usize,
    /// Crossing or graze.
    pub kind: RootKind,
}

/// Whether `h` certainly has no root in `(φ0, φ0 + Δ]`.
#[inline]
pub fn excluded(h0: f64, dh0: f64, bound: f64, delta: f64) -> bool {
    if h0.is_infinite() {
        return true;
    }
    let quad = 0.5 * bound * delta * delta;
    // A margin of a few ulps of h0, so that rounding in h0 cannot hide a root.
    let slack = 1e-14 * h0.abs();
    let away = h0 == 0.0 || (h0 > 0.0) == (dh0 > 0.0);
    if away {
        h0.abs() + dh0.abs() * delta - quad > slack && (h0 != 0.0 || dh0 != 0.0)
    } else {
        h0.abs() - dh0.abs() * delta - quad > slack
    }
}

/// Find the first root in `(φ0, φ_end]` of the two event functions.
///
/// * `probe(φ)` evaluates the functions at `φ`;
/// * `bound(φ, Δ)` bounds `|h''|` on `[φ, φ + Δ]`;
/// * `step` is the largest interval tested at once;
/// * `graze_tol` is how close to zero a non-crossing touch must come to be a graze.
pub fn first_root(
    probe: &impl Fn(f64) -> Probe,
    bound: &impl Fn(f64, f64, &Probe) -> f64,
    phi0: f64,
    phi_end: f64,
    step: f64,
    graze_tol: f64,
) -> Option<Root> {
    let mut phi = phi0;
    let mut p = probe(phi);
    while phi < phi_end {
        let delta = step.min(phi_end - phi);
        // Leaves are a few hundred ulps wide, well above the rounding of h.
        let min_width = (step * 1e-12).max(256.0 * f64::EPSILON * phi.abs());
        if let Some(r) = search(probe, bound, phi, delta, &p, graze_tol, min_width) {
            return Some(r);
        }
        let next = phi + delta;
        if next <= phi || next.is_nan() {
            return Some(Root {
                phase: phi,
                which: 0,
                kind: RootKind::Unresolved,
            });
        }
        let pn = probe(next);
        if let Some(r) = hidden_crossing(probe, phi, &p, next, &pn) {
            return Some(r);
        }
        phi = next;
        p = pn;
    }
    None
}

fn search(
    probe: &impl Fn(f64) -> Probe,
    bound: &impl Fn(f64, f64, &Probe) -> f64,
    a: f64,
    delta: f64,
    pa: &Probe,
    graze_tol: f64,
    min_width: f64,
) -> Option<Root> {
    if pa.h.iter().any(|h| h.is_nan()) || !pa.dh.is_finite() {
        return Some(Root {
            phase: a,
            which: 0,
            kind: RootKind::NotFinite,
        });
    }
    let b = bound(a, delta, pa);
    if !b.is_finite() {
        return Some(Root {
            phase: a,
            which: 0,
            kind: RootKind::NotFinite,
        });
    }
    // Near a tangency (value and slope both small) locate the extremum
    // directly: the exclusion test would need ever smaller intervals there.
    let slope_tol = 2.0 * (2.0 * b * graze_tol).sqrt();
    for k in 0..2 {
        if pa.h[k].abs() <= graze_tol && pa.dh.abs() <= slope_tol {
            if let Some(r) = tangency(probe, k, a, delta, pa, graze_tol, slope_tol) {
                return Some(r);
            }
        }
    }
    let open = [0, 1].map(|k| !excluded(pa.h[k], pa.dh, b, delta));
    if !open[0] && !open[1] {
        return None;
    }
    // Where the slope cannot vanish (|h'| > B Δ on the whole interval), each
    // open function is monotone there: one sign test decides, and a sign
    // change brackets its only root, polished directly.
    if (0..2).all(|k| !open[k] || pa.dh.abs() > b * delta) {
        let pb = probe(a + delta);
        let mut best: Option<Root> = None;
        for (k, _) in open.iter().enumerate().filter(|(_, o)| **o) {
            if pb.h[k] == 0.0 || (pa.h[k] > 0.0) != (pb.h[k] > 0.0) {
                let r = Root {
                    phase: polish(probe, k, a, a + delta, pa.h[k]),
                    which: k,
                    kind: RootKind::Crossing,
                };
                if best.is_none_or(|b| r.phase < b.phase) {
                    best = Some(r);
                }
            }
        }
        return best;
    }
    if delta <= min_width || a + delta <= a {
        let pb = probe(a + delta);
        // Among the open functions, the one that changes sign, else the one closest to zero.
        let mut best: Option<Root> = None;
        for (k, _) in open.iter().enumerate().filter(|(_, o)| **o) {
            let crosses = pb.h[k] == 0.0 || (pa.h[k] > 0.0) != (pb.h[k] > 0.0);
            // Rounding in h can hide a root that lies within a few ulps of
            // a + delta (the next interval, starting just past it, would then
            // look like it moves away from it): look one width further.
            let late = !crosses && pb.h[k].abs() < pa.h[k].abs() && {
                let pc = probe(a + 2.0 * delta);
                (pa.h[k] > 0.0) != (pc.h[k] > 0.0)
            };
            let root = if crosses {
                Some(Root {
                    phase: polish(probe, k, a, a + delta, pa.h[k]),
                    which: k,
                    kind: RootKind::Crossing,
                })
            } else if late {
                Some(Root {
                    phase: polish(probe, k, a, a + 2.0 * delta, pa.h[k]),
                    which: k,
                    kind: RootKind::Crossing,
                })
            } else if pa.h[k].abs().min(pb.h[k].abs()) <= graze_tol
                && pa.dh.abs().min(pb.dh.abs()) <= slope_tol
            {
                // Small and flat: a touch. (Small but steep is just next to a
                // crossing, which the next interval holds.)
                Some(Root {
                    phase: a,
                    which: k,
                    kind: RootKind::Graze,
                })
            } else {
                None
            };
            if let Some(r) = root {
                if best.is_none_or(|b| r.phase < b.phase) {
                    best = Some(r);
                }
            }
        }
        return best;
    }
    let half = 0.5 * delta;
    if let Some(r) = search(probe, bound, a, half, pa, graze_tol, min_width) {
        return Some(r);
    }
    let mid = a + half;
    let pm = probe(mid);
    if let Some(r) = hidden_crossing(probe, a, pa, mid, &pm) {
        return Some(r);
    }
    search(probe, bound, mid, delta - half, &pm, graze_tol, min_width)
}

/// A sign change of `h_k` between `a` and `b` after the search found no root
/// in `(a, b]`: the exclusion test reasons about the exact interval
/// `(a, a + Δ]`, but the next interval starts at the *rounded* `a + Δ`, and
/// `h` carries absolute rounding errors that the test's relative slack does
/// not cover. A root in that sub-ulp gap is a crossing all the same.
fn hidden_crossing(
    probe: &impl Fn(f64) -> Probe,
    a: f64,
    pa: &Probe,
    b: f64,
    pb: &Probe,
) -> Option<Root> {
    let mut best: Option<Root> = None;
    for k in 0..2 {
        let (ha, hb) = (pa.h[k], pb.h[k]);
        if ha.is_finite() && ha != 0.0 && (hb == 0.0 || (ha > 0.0) != (hb > 0.0)) {
            let r = Root {
                phase: polish(probe, k, a, b, ha),
                which: k,
                kind: RootKind::Crossing,
            };
            if best.is_none_or(|x| r.phase < x.phase) {
                best = Some(r);
            }
        }
    }
    best
}

/// The extremum of `h_k` in `[a, a + delta]` near a tangency: a graze if
/// `|h|` there is within `graze_tol`.
fn tangency(
    probe: &impl Fn(f64) -> Probe,
    k: usize,
    a: f64,
    delta: f64,
    pa: &Probe,
    graze_tol: f64,
    slope_tol: f64,
) -> Option<Root> {
    let pb = probe(a + delta);
    let at = if (pa.dh > 0.0) != (pb.dh > 0.0) {
        // The sign change of the slope, by safeguarded Newton on `h'`.
        bracketed_newton(
            |phi| {
                let p = probe(phi);
                (p.dh, p.ddh)
            },
            a,
            a + delta,
            pa.dh > 0.0,
        )
    } else if pa.dh.abs() <= slope_tol * 1e-3 {
        a
    } else {
        return None;
    };
    let h = probe(at).h[k];
    (h.abs() <= graze_tol && (h == 0.0 || (h > 0.0) == (pa.h[k] > 0.0) || pa.h[k] == 0.0))
        .then_some(Root {
            phase: at,
            which: k,
            kind: RootKind::Graze,
        })
}

/// The extremum of a touch reported at `phase`: the first phase, at or after
/// `phase`, where the slope `h'` no longer approaches the boundary (it is 0
/// or points to the `inside` sign), to the rounding of the phase; `phase`
/// itself if it does not approach there, or does not turn within `horizon`.
/// A search resumed just past it does not find the same touch again.
pub fn touch_extremum(probe: &impl Fn(f64) -> Probe, phase: f64, inside: f64, horizon: f64) -> f64 {
    let turned = |phi: f64| {
        let d = probe(phi).dh;
        d == 0.0 || (d > 0.0) == (inside > 0.0) || d.is_nan()
    };
    if turned(phase) {
        return phase;
    }
    let mut lo = phase;
    let mut w = (horizon * 1e-12).max(4.0 * f64::EPSILON * phase.abs());
    let mut hi = loop {
        let b = phase + w;
        if turned(b) {
            break b;
        }
        if w >= horizon {
            return phase;
        }
        lo = b;
        w *= 2.0;
    };
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo || mid >= hi {
            break;
        }
        if turned(mid) {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    hi
}

/// Safeguarded Newton between `a` and `b`, where function `k` changes sign.
fn polish(probe: &impl Fn(f64) -> Probe, k: usize, a: f64, b: f64, ha: f64) -> f64 {
    bracketed_newton(
        |phi| {
            let p = probe(phi);
            (p.h[k], p.dh)
        },
        a,
        b,
        ha > 0.0,
    )
}

/// The root of `f` between `a` and `b`, where it changes sign (`sign_a`: `f(a) > 0`),
/// to the rounding of the phase: Newton's step where it stays inside the
/// bracket, bisection where it does not. `eval` gives `(f, f')`.
fn bracketed_newton(eval: impl Fn(f64) -> (f64, f64), mut a: f64, mut b: f64, sign_a: bool) -> f64 {
    let mut x = 0.5 * (a + b);
    for _ in 0..100 {
        let (f, df) = eval(x);
        if f == 0.0 {
            return x;
        }
        if (f > 0.0) == sign_a {
            a = x;
        } else {
            b = x;
        }
        let newton = x - f / df;
        let resolution = 4.0 * f64::EPSILON * x.abs().max(1.0);
        // A Newton correction below the rounding of the phase: `x` is the
        // root to the phase's resolution. (Without this test such a step,
        // which rounds to `x` and so lands on the bracket's end, was taken
        // for a failed one, and bisection then halved the bracket some forty
        // times more: most of the simulation's time went there.)
        if df != 0.0 && (newton - x).abs() <= resolution {
            return x;
        }
        let next = if df != 0.0 && newton > a && newton < b {
            newton
        } else {
            0.5 * (a + b)
        };
        if (next - x).abs() <= resolution || b - a <= resolution {
            return next;
        }
        x = next;
    }
    x
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sine_probe(level: f64) -> impl Fn(f64) -> Probe {
        move |phi: f64| Probe {
            h: [phi.sin() - level, f64::INFINITY],
            dh: phi.cos(),
            ddh: -phi.sin(),
        }
    }

    #[test]
    fn finds_the_first_of_several_roots() {
        let p = sine_probe(0.5);
        let r = first_root(&p, &|_, _, _| 1.0, 0.0, 20.0, 10.0, 1e-12).unwrap();
        assert_eq!(r.kind, RootKind::Crossing);
        assert!((r.phase - (0.5f64).asin()).abs() < 1e-15, "{}", r.phase);
    }

    #[test]
    fn a_huge_step_cannot_skip_a_narrow_excursion() {
        // sin reaches 0.999999 only near pi/2: a sampling method with a coarse
        // step would miss both roots; the exclusion test cannot.
        let p = sine_probe(0.999_999);
        let r = first_root(&p, &|_, _, _| 1.0, 0.0, 20.0, 20.0, 1e-12).unwrap();
        assert_eq!(r.kind, RootKind::Crossing);
        assert!((r.phase.sin() - 0.999_999).abs() < 1e-15);
        assert!(r.phase < std::f64::consts::FRAC_PI_2);
    }

    #[test]
    fn tangency_is_a_graze_not_a_miss() {
        let p = sine_probe(1.0);
        let r = first_root(&p, &|_, _, _| 1.0, 0.0, 5.0, 5.0, 1e-9).unwrap();
        assert_eq!(r.kind, RootKind::Graze);
        assert!((r.phase - std::f64::consts::FRAC_PI_2).abs() < 1e-4);
        // Just below tangency: no root at all.
        let p = sine_probe(1.0 + 1e-6);
        assert!(first_root(&p, &|_, _, _| 1.0, 0.0, 5.0, 5.0, 1e-9).is_none());
    }

    #[test]
    fn a_phase_beyond_the_resolution_of_the_step_stops_the_search() {
        // At 1e17 the phase's rounding (16) exceeds the step: the walk could
        // not advance (it looped forever before); nor can a zero step.
        let p = sine_probe(2.0);
        for (phi0, step) in [(1e17, 0.5), (0.0, 0.0)] {
            let r = first_root(&p, &|_, _, _| 1.0, phi0, phi0 + 64.0, step, 1e-12).unwrap();
            assert_eq!(r.kind, RootKind::Unresolved);
            assert_eq!(r.phase, phi0);
        }
    }

    #[test]
    fn touch_extremum_is_the_turn_of_the_slope() {
        // h = sin φ − 1 touches 0 from below (the inside) at π/2 and 5π/2;
        // reported anywhere on the approach, the touch is at the turn.
        let p = sine_probe(1.0);
        let r = first_root(&p, &|_, _, _| 1.0, 0.0, 5.0, 1.0, 1e-9).unwrap();
        assert_eq!(r.kind, RootKind::Graze);
        for from in [r.phase, 1.5, 1.0] {
            let at = touch_extremum(&p, from, -1.0, 1.0);
            assert!((at - std::f64::consts::FRAC_PI_2).abs() < 1e-12, "{at}");
            assert!(p(at).dh <= 0.0);
        }
        // Past the turn, or beyond the horizon: where it is asked.
        assert_eq!(touch_extremum(&p, 2.0, -1.0, 1.0), 2.0);
        assert_eq!(touch_extremum(&p, 0.0, -1.0, 1.0), 0.0);
    }

    #[test]
    fn a_root_at_a_large_phase_is_polished_in_a_few_probes() {
        // At phase ~500 Newton's last correction is below half an ulp of the
        // phase: it rounds to the iterate, which is the bracket's end. It
        // used to be taken for a step outside the bracket, and some forty
        // bisections followed. The root of 3 (φ − 500) − 1 is not a float.
        let count = std::cell::Cell::new(0u32);
        let p = |phi: f64| {
            count.set(count.get() + 1);
            Probe {
                h: [3.0 * (phi - 500.0) - 1.0, f64::INFINITY],
                dh: 3.0,
                ddh: 0.0,
            }
        };
        let root = 1501.0 / 3.0;
        let at = polish(&p, 0, 499.9, 500.9, p(499.9).h[0]);
        assert!((at - root).abs() < 1e-12, "{at}");
        assert!(count.get() <= 5, "{} probes", count.get());
        // And the whole search.
        count.set(0);
        let r = first_root(&p, &|_, _, _| 1.0, 499.0, 502.0, 0.4, 1e-12).unwrap();
        assert_eq!(r.kind, RootKind::Crossing);
        assert!((r.phase - root).abs() < 1e-12, "{}", r.phase);
        assert!(count.get() <= 12, "{} probes", count.get());
    }

    #[test]
    fn leaving_a_root_is_not_a_root() {
        let p = sine_probe(0.0);
        let r = first_root(&p, &|_, _, _| 1.0, 0.0, 5.0, 1.0, 1e-12).unwrap();
        assert!(
            (r.phase - std::f64::consts::PI).abs() < 1e-14,
            "{}",
            r.phase
        );
    }
}

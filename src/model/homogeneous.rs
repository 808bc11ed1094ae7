//! The homogeneous solution of `x'' + 2 d x' + c x = 0` in every damping regime.
//!
//! With `w2 = d^2 - c` and the elapsed time `tau`, the solution from
//! `(X0, Y0)` is `x = Ec X0 + Es (Y0 + d X0)`, `v = Ec Y0 - Es (c X0 + d Y0)`
//! where
//!
//! * `Ec = exp(-d tau) cosh(sqrt(w2) tau)` and
//! * `Es = exp(-d tau) sinh(sqrt(w2) tau) / sqrt(w2)`
//!
//! (`cos`, `sin` for `w2 < 0`; `1`, `tau` at `w2 = 0`). Both are entire
//! functions of `z = w2 tau^2`, so near critical damping (`omega -> 0`) they
//! are computed from their power series in `z` and lose no digits (SPEC §4);
//! elsewhere from the closed forms. The generated code calls [`general`] when
//! the regime depends on a run-time parameter and one of the specialized
//! functions when the regime was fixed at build time. The functions take the
//! damping `d` and the stiffness `c` (not `d^2 - c`), so that an over-damped
//! pair of widely separated exponents keeps the digits of the slow one.

/// Below this `|z| = |w2| tau^2` the series is used (11 terms reach 1e-19).
const SERIES_LIMIT: f64 = 1.0;

/// The series' coefficients `1 / (2k)!` and `1 / (2k + 1)!`, k = 0 … 10
/// (`z^11 / 22!` < 1e-21 for `|z| <= 1`).
const TERMS: ([f64; 11], [f64; 11]) = {
    let mut c = [1.0; 11];
    let mut s = [1.0; 11];
    let mut k = 1;
    while k < 11 {
        let kf = k as f64;
        c[k] = c[k - 1] / ((2.0 * kf) * (2.0 * kf - 1.0));
        s[k] = s[k - 1] / ((2.0 * kf + 1.0) * (2.0 * kf));
        k += 1;
    }
    (c, s)
};

/// `sum a_k z^k`, k = 0 … 10, by Estrin's scheme: the pairs, quadruples and
/// the last octet are independent, so their multiplications overlap where
/// Horner's rule would chain ten of them (the series is on the hot path of
/// every short segment).
#[inline]
fn estrin(a: &[f64; 11], z: f64, z2: f64, z4: f64, z8: f64) -> f64 {
    let p01 = a[0] + a[1] * z;
    let p23 = a[2] + a[3] * z;
    let p45 = a[4] + a[5] * z;
    let p67 = a[6] + a[7] * z;
    let p89 = a[8] + a[9] * z;
    let q0 = p01 + p23 * z2;
    let q1 = p45 + p67 * z2;
    let q2 = p89 + a[10] * z2;
    (q0 + q1 * z4) + q2 * z8
}

/// `(sum z^k / (2k)!, sum z^k / (2k+1)!)`, i.e. `(cosh sqrt z, sinh sqrt z / sqrt z)`, for `|z| <= 1`.
#[inline]
fn series(z: f64) -> (f64, f64) {
    let z2 = z * z;
    let z4 = z2 * z2;
    let z8 = z4 * z4;
    (
        estrin(&TERMS.0, z, z2, z4, z8),
        estrin(&TERMS.1, z, z2, z4, z8),
    )
}

/// `(Ec, Es)` of `x'' + 2 d x' + c x = 0` for any sign of `w2 = d^2 - c`.
#[inline]
pub fn general(d: f64, c: f64, tau: f64) -> (f64, f64) {
    let w2 = d * d - c;
    let z = w2 * tau * tau;
    if z.abs() <= SERIES_LIMIT {
        let e = (-d * tau).exp();
        let (cs, s) = series(z);
        (e * cs, e * tau * s)
    } else if w2 < 0.0 {
        underdamped(d, (-w2).sqrt(), tau)
    } else {
        overdamped(d, c, tau)
    }
}

/// `(Ec, Es)` when `d^2 < c`, with `omega = sqrt(c - d^2)`: damped cosine and `sin(omega tau) / omega`.
#[inline]
pub fn underdamped(d: f64, omega: f64, tau: f64) -> (f64, f64) {
    let e = (-d * tau).exp();
    let (s, c) = libm::sincos(omega * tau);
    (e * c, e * s / omega)
}

/// `(Ec, Es)` when `d^2 > c`, `omega = sqrt(d^2 - c)`. Written with the two
/// exponents `lambda± = -d ± omega` so that `exp(-d tau) cosh(omega tau)`
/// never overflows while the motion decays; the exponent nearer zero is
/// formed as `-c / (d + omega)` (or `c / (omega - d)` for negative damping),
/// which keeps its digits when the two are widely separated (`d^2 >> c`).
/// The series covers `omega tau <= 1`, where the difference of the
/// exponentials would cancel.
#[inline]
pub fn overdamped(d: f64, c: f64, tau: f64) -> (f64, f64) {
    let w2 = d * d - c;
    let z = w2 * tau * tau;
    if z <= SERIES_LIMIT {
        let e = (-d * tau).exp();
        let (cs, s) = series(z);
        return (e * cs, e * tau * s);
    }
    let omega = w2.sqrt();
    let (up, down) = if d >= 0.0 {
        (-c / (d + omega), -(d + omega))
    } else {
        (omega - d, c / (omega - d))
    };
    let (eu, ed) = ((up * tau).exp(), (down * tau).exp());
    (0.5 * (eu + ed), 0.5 * (eu - ed) / omega)
}

/// `(Ec, Es)` at critical damping `d^2 = c`: `(exp(-d tau), tau exp(-d tau))`.
#[inline]
pub fn critical(d: f64, tau: f64) -> (f64, f64) {
    let e = (-d * tau).exp();
    (e, tau * e)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn series_matches_closed_forms_where_both_are_accurate() {
        for &z in &[-1.0, -0.5, -1e-3, 1e-3, 0.5, 1.0] {
            let (c, s) = series(z);
            let (cc, ss) = if z > 0.0 {
                let r: f64 = z.sqrt();
                (r.cosh(), r.sinh() / r)
            } else {
                let r: f64 = (-z).sqrt();
                (r.cos(), r.sin() / r)
            };
            assert!((c - cc).abs() < 4e-16 * cc.abs().max(1.0), "{z}: {c} {cc}");
            assert!((s - ss).abs() < 4e-16 * ss.abs().max(1.0), "{z}: {s} {ss}");
        }
    }

    #[test]
    fn regimes_join_continuously() {
        // Across z = +-1 (series <-> closed form) and across w2 = 0.
        let (d, tau) = (0.7, 1.3);
        for &w2 in &[-1.0 / (tau * tau), 1.0 / (tau * tau)] {
            let a = general(d, d * d - w2 * (1.0 - 1e-12), tau);
            let b = general(d, d * d - w2 * (1.0 + 1e-12), tau);
            assert!(
                (a.0 - b.0).abs() < 1e-12 && (a.1 - b.1).abs() < 1e-12,
                "{a:?} {b:?}"
            );
        }
        let a = general(d, d * d + 1e-300, tau);
        let b = general(d, d * d - 1e-300, tau);
        let c = critical(d, tau);
        assert_eq!(a, c);
        assert_eq!(b, c);
    }
}

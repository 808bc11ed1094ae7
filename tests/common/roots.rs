//! Root finders written for the tests (plain scanning and bisection, the
//! textbook method with a guaranteed bracket), independent of the crossing
//! search in `src/` (which brackets by step rules and refines by regula
//! falsi). Slow and simple on purpose: every result is the first point of a
//! scan where a predicate holds, narrowed to the last representable bit.

/// The first point of `(a, b]` where `outside` holds, given that it does
/// not hold at `a` and does at `b`: bisection until the bracket is at most
/// `tol` wide or cannot be split. Returns the outside end of the bracket.
pub fn bisect(a: f64, b: f64, outside: impl Fn(f64) -> bool, tol: f64) -> f64 {
    bracket(a, b, outside, tol).1
}

/// [`bisect`]'s final bracket `(inside, outside)`.
pub fn bracket(mut a: f64, mut b: f64, outside: impl Fn(f64) -> bool, tol: f64) -> (f64, f64) {
    loop {
        let mid = 0.5 * (a + b);
        if b - a <= tol || mid <= a || mid >= b {
            return (a, b);
        }
        if outside(mid) {
            b = mid;
        } else {
            a = mid;
        }
    }
}

/// Scan `from, from + ds, …` while below `until` for the first step whose
/// end satisfies `outside`, then bisect that step to `tol`. `None` when the
/// scan reaches `until` first.
pub fn first_point(
    from: f64,
    ds: f64,
    until: f64,
    outside: impl Fn(f64) -> bool,
    tol: f64,
) -> Option<f64> {
    let mut s = from;
    while s < until {
        if outside(s + ds) {
            return Some(bisect(s, s + ds, &outside, tol));
        }
        s += ds;
    }
    None
}

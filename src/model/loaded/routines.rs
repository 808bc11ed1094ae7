//! The routines machine code calls: those the compiled-in models' generated
//! code calls (`f64::sin`, `f64::cos`, `f64::exp`, `f64::ln` and the
//! homogeneous solutions of [`crate::model::homogeneous`]), each behind an
//! `extern "C"` wrapper whose address the run-time back end binds to an
//! imported symbol. Both back ends compute with the same routines, so their
//! numbers agree to rounding.

use stickslip_codegen::jit::{HomPair, Routines};

use crate::model::homogeneous;

extern "C" fn sin(x: f64) -> f64 {
    x.sin()
}

extern "C" fn cos(x: f64) -> f64 {
    x.cos()
}

extern "C" fn exp(x: f64) -> f64 {
    x.exp()
}

extern "C" fn ln(x: f64) -> f64 {
    x.ln()
}

fn pair((ec, es): (f64, f64)) -> HomPair {
    HomPair { ec, es }
}

extern "C" fn general(d: f64, c: f64, tau: f64) -> HomPair {
    pair(homogeneous::general(d, c, tau))
}

extern "C" fn underdamped(d: f64, omega: f64, tau: f64) -> HomPair {
    pair(homogeneous::underdamped(d, omega, tau))
}

extern "C" fn overdamped(d: f64, c: f64, tau: f64) -> HomPair {
    pair(homogeneous::overdamped(d, c, tau))
}

extern "C" fn critical(d: f64, tau: f64) -> HomPair {
    pair(homogeneous::critical(d, tau))
}

/// The table handed to the run-time back end.
pub const ROUTINES: Routines = Routines {
    sin,
    cos,
    exp,
    ln,
    general,
    underdamped,
    overdamped,
    critical,
};

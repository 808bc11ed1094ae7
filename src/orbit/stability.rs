//! Stability of a periodic motion from its Poincaré-map Jacobian (SPEC §7).

use nalgebra::Matrix2;
use serde::Serialize;

/// How a periodic motion behaves under perturbation.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Classification {
    /// Both eigenvalues inside the unit circle.
    Stable,
    /// An eigenvalue outside the unit circle.
    Unstable,
    /// A real eigenvalue near +1 (`det DP + 1 = tr DP`, Eq. B.4).
    NearSaddleNode,
    /// A real eigenvalue near −1 (`det DP + tr DP + 1 = 0`, Eq. B.3).
    NearPeriodDoubling,
    /// A complex pair near the unit circle.
    NearNeimark,
}

/// Eigenvalues and classification.
#[derive(Clone, Copy, Debug, PartialEq, Serialize)]
pub struct Stability {
    /// The eigenvalues as `[re, im]`, largest modulus first.
    pub eigenvalues: [[f64; 2]; 2],
    /// The largest modulus.
    pub largest_modulus: f64,
    /// Stable, unstable, or close to which bifurcation.
    pub classification: Classification,
    /// Whether one eigenvalue is zero to round-off (motions with stick, SPEC §7).
    pub has_zero_eigenvalue: bool,
}

/// How close to `+1` an eigenvalue must be to count as exactly `+1` (DP is
/// computed from closed forms, to about 1e-12).
pub const UNIT_TOL: f64 = 1e-9;

/// How close to the unit circle counts as "near a bifurcation".
pub const NEAR: f64 = 1e-3;

impl Stability {
    /// Classify a 2×2 Poincaré-map Jacobian.
    pub fn of(dp: &Matrix2<f64>) -> Self {
        let tr = dp.trace();
        let det = dp.determinant();
        let half = 0.5 * tr;
        let disc = half * half - det;
        let (e1, e2) = if disc >= 0.0 {
            // Stable formula for the smaller root.
            let s = disc.sqrt();
            let big = if half >= 0.0 { half + s } else { half - s };
            let small = if big != 0.0 { det / big } else { 0.0 };
            ([big, 0.0], [small, 0.0])
        } else {
            let s = (-disc).sqrt();
            ([half, s], [half, -s])
        };
        let modulus = |e: [f64; 2]| e[0].hypot(e[1]);
        let (e1, e2) = if modulus(e1) >= modulus(e2) {
            (e1, e2)
        } else {
            (e2, e1)
        };
        let largest = modulus(e1);
        let scale = dp.amax().max(1.0);
        let has_zero = modulus(e2) <= 1e-9 * scale;
        let classification = if (largest - 1.0).abs() <= NEAR {
            if e1[1] != 0.0 {
                Classification::NearNeimark
            } else if e1[0] > 0.0 {
                Classification::NearSaddleNode
            } else {
                Classification::NearPeriodDoubling
            }
        } else if largest < 1.0 {
            Classification::Stable
        } else {
            Classification::Unstable
        };
        Self {
            eigenvalues: [e1, e2],
            largest_modulus: largest,
            classification,
            has_zero_eigenvalue: has_zero,
        }
    }

    /// Whether both eigenvalues lie inside the unit circle.
    pub fn is_stable(&self) -> bool {
        self.largest_modulus < 1.0
    }

    /// Whether an eigenvalue is `+1` to round-off (within [`UNIT_TOL`]): the
    /// motion is one of a continuum of neutrally stable periodic motions
    /// (e.g. the undamped Coulomb oscillator at `W = sqrt(c) / (2 n)`,
    /// Csernák, Stépán & Shaw, Nonlinear Dyn. 2007), not an isolated one.
    pub fn has_unit_eigenvalue(&self) -> bool {
        self.eigenvalues
            .iter()
            .any(|e| (e[0] - 1.0).abs() <= UNIT_TOL && e[1].abs() <= UNIT_TOL)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigenvalues_match_nalgebra() {
        for dp in [
            Matrix2::new(
                -0.9943015113435921,
                2.702598577851798,
                -0.8265666634108872,
                1.6782300585664842,
            ),
            Matrix2::new(
                -0.01413562634194214,
                -1.2921521368599544,
                -0.005543046543256772,
                -0.5066955833666555,
            ),
            Matrix2::new(2.0, 1.0, 0.5, -3.0),
        ] {
            let s = Stability::of(&dp);
            let ev = dp.complex_eigenvalues();
            for e in s.eigenvalues {
                assert!(
                    ev.iter()
                        .any(|z| (z.re - e[0]).abs() < 1e-12 && (z.im - e[1]).abs() < 1e-12),
                    "{e:?} {ev:?}"
                );
            }
        }
    }

    #[test]
    fn classifies() {
        assert_eq!(
            Stability::of(&Matrix2::new(0.5, 0.0, 0.0, 0.2)).classification,
            Classification::Stable
        );
        assert_eq!(
            Stability::of(&Matrix2::new(1.5, 0.0, 0.0, 0.2)).classification,
            Classification::Unstable
        );
        assert_eq!(
            Stability::of(&Matrix2::new(1.0005, 0.0, 0.0, 0.2)).classification,
            Classification::NearSaddleNode
        );
        assert_eq!(
            Stability::of(&Matrix2::new(-0.9999, 0.0, 0.0, 0.2)).classification,
            Classification::NearPeriodDoubling
        );
        let (c, s) = (0.3f64.cos(), 0.3f64.sin());
        assert_eq!(
            Stability::of(&Matrix2::new(c, -s, s, c)).classification,
            Classification::NearNeimark
        );
        let stick = Stability::of(&Matrix2::new(
            -0.01413562634194214,
            -1.2921521368599544,
            -0.005543046543256772,
            -0.5066955833666555,
        ));
        assert!(stick.has_zero_eigenvalue);
        assert!((stick.eigenvalues[0][0] + 0.5208312097085976).abs() < 1e-12);
    }
}

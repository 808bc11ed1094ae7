//! What each panel of a sweep's figure shows, for each view: the
//! bifurcation diagram (switching phases and displacements, eigenvalues)
//! and the frequency response (the amplitudes `max |x|`, `max |v|`).

use super::branch::Quantity;
use crate::study::sweep::{BifurcationSummary, MotionSummary};

/// Which figure `sweep --plot` draws.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Default)]
pub enum View {
    /// The bifurcation diagram: switching phase and displacement against
    /// the parameter, the eigenvalues' moduli and real parts (2 × 2 panels).
    #[default]
    Diagram,
    /// The frequency response: `max |x|` and `max |v|` over each motion's
    /// cycle against the parameter (two panels side by side).
    Frc,
}

/// How a panel's vertical range is chosen.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Range {
    /// A phase: `[0, 2π)`, curves broken where they wrap round.
    Phase,
    /// The data's extent.
    Data,
    /// An eigenvalue quantity with its critical level (drawn dashed) and the
    /// band it is clipped to: at a grazing end `DP` diverges, and its
    /// eigenvalues with it.
    Eigenvalue {
        /// `|λ| = 1` or `Re λ = 0`.
        level: f64,
        /// The panel never reaches beyond this band.
        clip: (f64, f64),
    },
    /// An amplitude: from 0 to the data's largest value.
    Amplitude,
}

/// One panel.
#[derive(Clone, Copy)]
pub struct Panel {
    /// Its title.
    pub title: &'static str,
    /// The values of a motion at a grid point.
    pub motion: fn(&MotionSummary) -> Vec<f64>,
    /// The values of a branch's point.
    pub sample: Quantity,
    /// Where a bifurcation stands.
    pub marked: fn(&BifurcationSummary) -> f64,
    /// Its vertical range.
    pub range: Range,
}

/// Eigenvalue panels never extend past `|λ| = 4`.
const EIGEN_CLIP: f64 = 4.0;

const DIAGRAM: [Panel; 4] = [
    Panel {
        title: "switching phase W t mod 2π",
        motion: |m| m.points.iter().map(|p| p.phase).collect(),
        sample: |q| q.points.iter().map(|p| p.phase).collect(),
        marked: |b| b.start_wt,
        range: Range::Phase,
    },
    Panel {
        title: "switching displacement x",
        motion: |m| m.points.iter().map(|p| p.x).collect(),
        sample: |q| q.points.iter().map(|p| p.x).collect(),
        marked: |b| b.start_x,
        range: Range::Data,
    },
    Panel {
        title: "eigenvalue moduli |λ|",
        motion: |m| m.eigenvalues.iter().map(|e| e[0].hypot(e[1])).collect(),
        sample: |q| q.eigenvalues.iter().map(|e| e[0].hypot(e[1])).collect(),
        marked: |b| b.eigenvalue[0].hypot(b.eigenvalue[1]),
        range: Range::Eigenvalue {
            level: 1.0,
            clip: (0.0, EIGEN_CLIP),
        },
    },
    Panel {
        title: "eigenvalue real parts Re λ",
        motion: |m| m.eigenvalues.iter().map(|e| e[0]).collect(),
        sample: |q| q.eigenvalues.iter().map(|e| e[0]).collect(),
        marked: |b| b.eigenvalue[0],
        range: Range::Eigenvalue {
            level: 0.0,
            clip: (-EIGEN_CLIP, EIGEN_CLIP),
        },
    },
];

const FRC: [Panel; 2] = [
    Panel {
        title: "amplitude max |x| over the cycle",
        motion: |m| vec![m.max_abs_x],
        sample: |q| vec![q.max_abs_x],
        marked: |b| b.max_abs_x,
        range: Range::Amplitude,
    },
    Panel {
        title: "velocity amplitude max |v| over the cycle",
        motion: |m| vec![m.max_abs_v],
        sample: |q| vec![q.max_abs_v],
        marked: |b| b.max_abs_v,
        range: Range::Amplitude,
    },
];

impl View {
    /// Its panels, row by row.
    pub fn panels(self) -> &'static [Panel] {
        match self {
            View::Diagram => &DIAGRAM,
            View::Frc => &FRC,
        }
    }

    /// Rows and columns of panels.
    pub fn grid(self) -> (usize, usize) {
        match self {
            View::Diagram => (2, 2),
            View::Frc => (1, 2),
        }
    }

    /// Height of the title and the panels (pixels).
    pub fn panels_height(self) -> u32 {
        match self {
            View::Diagram => 1000,
            View::Frc => 560,
        }
    }
}

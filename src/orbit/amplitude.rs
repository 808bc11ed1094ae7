//! The amplitude of a periodic motion: the largest `|x|` and `|v|` over its
//! cycle, from the closed form (the frequency-response view of a sweep).
//!
//! Along a flow segment the velocity's extrema are the zeros of the
//! acceleration, found and proven by `SegmentFlow::acceleration_zeros`
//! (the search admissibility uses); between two of them the velocity is
//! monotone, so it vanishes there at most once, where a sign change says
//! so, and that zero (an extremum of `x`) is refined by Newton safeguarded
//! with bisection. A stick moves with the belt: its extrema are at its
//! ends, which are switching points. So the amplitude is the largest of
//! the switching points, the velocity extrema and the displacement extrema.

use crate::model::Model;
use crate::orbit::extrema::SegmentFlow;
use crate::orbit::periodic::{arrival, SwitchingPoint};
use crate::orbit::steady::SteadyResponse;
use crate::orbit::structure::Structure;
use crate::MappingKind;

/// The largest `|x|` and `|v|` over a motion's cycle.
#[derive(Clone, Copy, Debug, PartialEq, serde::Serialize)]
pub struct Amplitude {
    /// `max |x|`.
    pub x: f64,
    /// `max |v|`.
    pub v: f64,
}

impl Amplitude {
    /// The amplitude of a domain's steady forced response (the no-motion
    /// regime): `|offset| + √(a² + b²)` and `W √(a² + b²)`.
    pub fn of_steady(s: &SteadyResponse) -> Self {
        Self {
            x: s.offset.abs() + s.a.hypot(s.b),
            v: s.max_v.abs(),
        }
    }

    fn include(&mut self, x: f64, v: f64) {
        self.x = self.x.max(x.abs());
        self.v = self.v.max(v.abs());
    }
}

/// The amplitude of the periodic motion of `structure` through `points`
/// (point `k` the start of the `k`-th mapping) at parameters `p`; `None`
/// where a segment's closed form does not exist (`c_j = 0`, undamped
/// resonance) or a number is not finite.
pub fn of_motion<M: Model>(
    p: &M::Params,
    structure: &Structure,
    points: &[SwitchingPoint],
) -> Option<Amplitude> {
    let shift = crate::orbit::periodic::cycle_shift(structure, points);
    of_cycle::<M>(p, structure.steps(), shift, points)
}

/// [`of_motion`] of the cycle of mappings `steps` through `points`, the last
/// mapping arriving at the first point `shift` later in phase (an
/// autonomous cycle's phase length is its period times `W`).
pub fn of_cycle<M: Model>(
    p: &M::Params,
    steps: &[usize],
    shift: f64,
    points: &[SwitchingPoint],
) -> Option<Amplitude> {
    let info = M::info(p);
    let osc = M::oscillator(p);
    let mut amp = Amplitude { x: 0.0, v: 0.0 };
    for (k, &step) in steps.iter().enumerate() {
        let mi = info.mappings[step];
        let (a, b) = (points[k], arrival(points, k, shift));
        let va = M::boundary_velocity(p, mi.from);
        amp.include(a.x, va);
        let (MappingKind::Global | MappingKind::Local, Some(j)) = (mi.kind, mi.domain) else {
            // A stick: the belt's velocity all along, x linear between its ends.
            continue;
        };
        let flow = SegmentFlow::new(osc, M::coefficients(p, j), a.x, va, a.phase)?;
        // The velocity's extrema, and between them (monotone stretches) the
        // velocity's zeros, where x has its extrema.
        let mut knot = (a.phase, va);
        let mut stretch = |to: f64, v_to: f64, amp: &mut Amplitude| {
            if (knot.1 > 0.0) != (v_to > 0.0) && knot.1 != 0.0 && v_to != 0.0 {
                let x = flow.at(velocity_zero(&flow, knot.0, to, knot.1 > 0.0)).x;
                amp.include(x, 0.0);
            }
            knot = (to, v_to);
        };
        flow.acceleration_zeros(
            a.phase,
            b.phase,
            |_| false,
            |z| {
                amp.include(z.state.x, z.state.v);
                stretch(z.phase, z.state.v, &mut amp);
            },
        );
        stretch(b.phase, M::boundary_velocity(p, mi.to), &mut amp);
    }
    (amp.x.is_finite() && amp.v.is_finite()).then_some(amp)
}

/// The zero of the velocity on `[lo, hi]` (phases), where it is monotone and
/// changes sign (`v(lo) > 0` is `lo_positive`): Newton on `dv/dφ = a / W`,
/// safeguarded by bisection, to the phase's rounding.
fn velocity_zero(flow: &SegmentFlow, mut lo: f64, mut hi: f64, lo_positive: bool) -> f64 {
    let w = flow.frequency();
    let mut t = 0.5 * (lo + hi);
    for _ in 0..200 {
        let s = flow.at(t);
        if s.v == 0.0 {
            return t;
        }
        if (s.v > 0.0) == lo_positive {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - s.v * w / s.a;
        let next = if s.a != 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - t).abs() <= 4.0 * f64::EPSILON * t.abs().max(1.0) {
            return next;
        }
        t = next;
    }
    t
}

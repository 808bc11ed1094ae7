//! A reference simulation of a piecewise model with events, by numerical
//! integration: in domain `j` it integrates
//! `x'' = A0 cos(W t) − b_j − 2 d_j x' − c_j x` (coefficients from
//! `Model::coefficients`) with the Dormand–Prince 5(4) of [`super::dopri`];
//! a boundary crossing is found on the step's dense output and located by
//! bisection ([`super::roots`]) on re-taken steps of shorter length; on the
//! stick boundary it applies the force criteria of SPEC §3 to the input
//! forces `F_j(x, V, t)` of the domains above and below, and a stick
//! (`x = x_i + V (t − t_i)`) ends at the first root of `|Fnf| = as`, found by
//! scanning and bisection.
//!
//! It knows nothing of the closed forms or of the event search in `src/`.

use super::dopri;
use super::roots::{bisect, first_point};
use stickslip::dynamics::simulate::EventKind;
use stickslip::Model;

/// An event of the reference integration.
#[derive(Clone, Copy, Debug)]
pub struct RefEvent {
    pub phase: f64,
    pub x: f64,
    pub boundary: usize,
    pub kind: EventKind,
}

/// The model's ODE as data: read once from the model, then integrated numerically.
pub struct PiecewiseOde {
    pub a0: f64,
    pub w: f64,
    two_d: f64,
    c: f64,
    /// `(two_d_j, c_j, b_j)` per domain.
    coeff: Vec<(f64, f64, f64)>,
    /// `(lower, upper)` boundary index per domain.
    bands: Vec<(Option<usize>, Option<usize>)>,
    velocities: Vec<f64>,
    /// `(boundary, as)`.
    stick: Option<(usize, f64)>,
}

/// Sub-steps at which the dense output is checked for a crossing.
const SAMPLES: usize = 16;

impl PiecewiseOde {
    pub fn of<M: Model>(p: &M::Params) -> Self {
        let info = M::info(p);
        let osc = M::oscillator(p);
        Self {
            a0: osc.amplitude,
            w: osc.frequency,
            two_d: 2.0 * osc.damping,
            c: osc.stiffness,
            coeff: (0..info.domains.len())
                .map(|j| {
                    let co = M::coefficients(p, j);
                    (co.two_d, co.c, co.b)
                })
                .collect(),
            bands: info.domains.iter().map(|d| (d.lower, d.upper)).collect(),
            velocities: (0..info.boundaries.len())
                .map(|k| M::boundary_velocity(p, k))
                .collect(),
            stick: info
                .stick_boundary()
                .map(|k| (k, M::static_bound(p).expect("stick boundary has a bound"))),
        }
    }

    /// Acceleration in domain `j`.
    fn accel(&self, j: usize, t: f64, x: f64, v: f64) -> f64 {
        let (two_d, c, b) = self.coeff[j];
        self.a0 * (self.w * t).cos() - b - two_d * v - c * x
    }

    /// The domain whose band holds `v` strictly.
    pub fn domain_of(&self, v: f64) -> usize {
        self.bands
            .iter()
            .position(|&(lo, hi)| {
                lo.is_none_or(|k| self.velocities[k] < v)
                    && hi.is_none_or(|k| v < self.velocities[k])
            })
            .expect("v inside a band")
    }

    /// One step in domain `j`.
    fn step(&self, j: usize, t: f64, y: [f64; 2], h: f64) -> dopri::Step<2> {
        dopri::step(|t, y| [y[1], self.accel(j, t, y[0], y[1])], t, y, h)
    }

    /// `Fnf` on the stick boundary (SPEC Eq. 2).
    fn fnf(&self, vs: f64, t: f64, x: f64) -> f64 {
        self.a0 * (self.w * t).cos() - self.two_d * vs - self.c * x
    }

    /// Integrate from `(x0, v0)` at `t0` in `domain` (`None`: stuck on the
    /// stick boundary) to `t_end` at the relative tolerance `rtol`,
    /// recording events.
    pub fn integrate(
        &self,
        t0: f64,
        x0: f64,
        v0: f64,
        domain: Option<usize>,
        t_end: f64,
        rtol: f64,
    ) -> Vec<RefEvent> {
        self.run(t0, x0, v0, domain, t_end, rtol, false).0
    }

    /// [`Self::integrate`], stopping exactly at `t_end`: the events, and the
    /// state `(x, v)` and the domain (`None`: stuck) there.
    pub fn integrate_to(
        &self,
        t0: f64,
        x0: f64,
        v0: f64,
        domain: Option<usize>,
        t_end: f64,
        rtol: f64,
    ) -> (Vec<RefEvent>, [f64; 2], Option<usize>) {
        self.run(t0, x0, v0, domain, t_end, rtol, true)
    }

    #[allow(clippy::too_many_arguments)]
    fn run(
        &self,
        t0: f64,
        x0: f64,
        v0: f64,
        domain: Option<usize>,
        t_end: f64,
        rtol: f64,
        exact_end: bool,
    ) -> (Vec<RefEvent>, [f64; 2], Option<usize>) {
        let mut events = Vec::new();
        let (mut t, mut y) = (t0, [x0, v0]);
        let mut domain = domain;
        let mut h = 1e-3f64;
        let w = self.w;
        while t < t_end {
            match domain {
                None => {
                    // Stick: x = x_i + V (t − t_i) until |Fnf| = as.
                    let (k, bound) = self.stick.expect("stuck on the stick boundary");
                    let vs = self.velocities[k];
                    let (ts, xs) = (t, y[0]);
                    let fnf = |s: f64| self.fnf(vs, ts + s, xs + vs * s);
                    let out = |s: f64| fnf(s).abs() >= bound;
                    let Some(s) = first_point(0.0, 1e-3 / w, t_end - ts, out, 1e-16 * t_end) else {
                        return (events, [xs + vs * (t_end - ts), vs], None);
                    };
                    t = ts + s;
                    y = [xs + vs * s, vs];
                    events.push(RefEvent {
                        phase: w * t,
                        x: y[0],
                        boundary: k,
                        kind: EventKind::StickEnd,
                    });
                    // Fnf = +as: into the domain above; −as: below.
                    domain = Some(if fnf(s) > 0.0 { k + 1 } else { k });
                }
                Some(j) => {
                    let (lo, hi) = self.bands[j];
                    let lo_v = lo.map(|k| self.velocities[k]);
                    let hi_v = hi.map(|k| self.velocities[k]);
                    // Which boundary `v` lies beyond, if any (`true`: the lower).
                    let beyond = |v: f64| {
                        if lo_v.is_some_and(|l| v < l) {
                            Some(true)
                        } else if hi_v.is_some_and(|u| v > u) {
                            Some(false)
                        } else {
                            None
                        }
                    };
                    // One adaptive step (5th-order error control).
                    let hs = if exact_end {
                        h.min(t_end - t)
                    } else {
                        h.min(t_end + 1.0 - t)
                    };
                    let st = self.step(j, t, y, hs);
                    let en = st.error_norm(rtol);
                    if en > 1.0 {
                        h = hs * (0.9 * en.powf(-0.2)).max(0.2);
                        continue;
                    }
                    // Crossing: beyond a boundary at the step's end, or at a
                    // sample of the dense output confirmed by a real step.
                    let mut cross = beyond(st.y[1]).map(|lower| (hs, lower));
                    if cross.is_none() {
                        cross = (1..SAMPLES).find_map(|i| {
                            let s = hs * i as f64 / SAMPLES as f64;
                            beyond(st.dense(s / hs)[1])?;
                            beyond(self.step(j, t, y, s).y[1]).map(|lower| (s, lower))
                        });
                    }
                    let Some((s_hi, lower)) = cross else {
                        t += hs;
                        y = st.y;
                        h = hs * (0.9 * en.max(1e-10).powf(-0.2)).min(5.0);
                        continue;
                    };
                    // The crossing time: bisection on re-taken steps.
                    let past = |s: f64| beyond(self.step(j, t, y, s).y[1]) == Some(lower);
                    let s = bisect(0.0, s_hi, past, 4.0 * f64::EPSILON * (t + s_hi));
                    let ys = self.step(j, t, y, s).y;
                    t += s;
                    let k = if lower { lo } else { hi }.expect("crossed a present boundary");
                    let vb = self.velocities[k];
                    y = [ys[0], vb];
                    let into = if lower { j - 1 } else { j + 1 };
                    let (kind, next) = match self.stick {
                        Some((ks, _)) if ks == k => {
                            // Input forces: each side's field at (x, V, t) (SPEC §3).
                            let f_above = self.accel(k + 1, t, y[0], vb);
                            let f_below = self.accel(k, t, y[0], vb);
                            let pass = if lower {
                                f_above < 0.0 && f_below < 0.0
                            } else {
                                f_above > 0.0 && f_below > 0.0
                            };
                            if pass {
                                (EventKind::Pass, Some(into))
                            } else {
                                (EventKind::StickOnset, None)
                            }
                        }
                        _ => (EventKind::Pass, Some(into)),
                    };
                    if t <= t_end {
                        events.push(RefEvent {
                            phase: w * t,
                            x: y[0],
                            boundary: k,
                            kind,
                        });
                    }
                    domain = next;
                    h = h.min(1e-3);
                }
            }
        }
        (events, y, domain)
    }
}

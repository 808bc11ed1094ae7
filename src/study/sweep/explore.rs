//! The exploration behind a sweep: every branch of periodic motions reached
//! from the seeds (simulations from rest at both ends of the range), from
//! the global searches (every k-th grid value and just past every
//! transition), from what lives past each transition, and from the
//! bifurcations (the branches born there), each followed by
//! pseudo-arclength continuation ([`crate::bifurcation`]) through folds,
//! unstable parts kept.

use std::collections::VecDeque;

use crate::bifurcation::branch::{Branch, BranchPoint, EndReason};
use crate::bifurcation::{born, follow, ContinuationOptions, Start};
use crate::dynamics::simulate::Simulator;
use crate::model::Model;
use crate::orbit::attractor::Attractor;
use crate::orbit::autonomous::{shrinking, without};
use crate::orbit::motion::{Motion, OrbitError};
use crate::orbit::periodic::Termination;
use crate::orbit::structure::Structure;
use crate::study::search::{coexisting, same_motion, SearchOptions};

use super::grid::{at_value, SAME};
use super::settle;
use super::{stick_summary, with, Cut, MotionSummary, SweepOptions, Transition, TransitionKind};

/// The motion at a point of a branch (solved and checked by the continuation).
fn motion_of(structure: &Structure, at: &BranchPoint) -> Motion {
    Motion {
        structure: structure.clone(),
        points: at.points.clone(),
        termination: Termination::Converged {
            iterations: 0,
            residual: 0.0,
        },
        dp: Some(at.dp),
        stability: Some(at.stability),
        violations: Vec::new(),
    }
}

/// A branch born at a bifurcation, still to be followed.
struct Pending {
    start: Start,
    /// The bifurcation it is born at (index into `Explorer::bifurcations`).
    parent: Option<usize>,
}

/// An eigenvalue bifurcation on a found branch, with the branches born there.
pub(super) struct Located {
    /// The branch it lies on (index into `Explorer::branches`).
    pub branch: usize,
    /// Its index in that branch's `bifurcations`.
    pub which: usize,
    /// The branches born there.
    pub born: Vec<usize>,
}

/// Everything found, and what is still to follow.
pub(super) struct Explorer<'a, M: Model> {
    base: &'a M::Params,
    index: usize,
    opts: &'a SweepOptions,
    continuation: ContinuationOptions,
    queue: VecDeque<Pending>,
    /// Parameter values where the global search is still to run.
    searches: Vec<f64>,
    /// The branches, in the order found; their index is their id.
    pub branches: Vec<Branch>,
    /// The eigenvalue bifurcations on them.
    pub bifurcations: Vec<Located>,
    /// Non-smooth transitions and eigenvalue bifurcations, with what lies past.
    pub transitions: Vec<Transition>,
    /// Permanent sticks met by the simulations, at their parameter values.
    pub sticks: Vec<(f64, MotionSummary)>,
    /// Branches born by period doubling beyond the longest period followed.
    pub cuts: Vec<Cut>,
}

impl<'a, M: Model> Explorer<'a, M> {
    pub fn new(
        base: &'a M::Params,
        index: usize,
        bounds: (f64, f64),
        opts: &'a SweepOptions,
    ) -> Self {
        let mut continuation = opts.continuation;
        continuation.bounds = bounds;
        continuation.transition_tolerance = opts.tolerance;
        Self {
            base,
            index,
            opts,
            continuation,
            queue: VecDeque::new(),
            searches: Vec::new(),
            branches: Vec::new(),
            bifurcations: Vec::new(),
            transitions: Vec::new(),
            sticks: Vec::new(),
            cuts: Vec::new(),
        }
    }

    fn simulator(&self, value: f64) -> Option<Simulator<M>> {
        settle::simulator::<M>(with(self.base, self.index, value).ok()?)
    }

    /// Which found branch holds `motion` at `value`, if any.
    fn holding(&self, motion: &Motion, value: f64) -> Option<usize> {
        let sim = self.simulator(value)?;
        self.branches.iter().position(|b| {
            at_value(&sim, b, value)
                .iter()
                .any(|m| same_motion(m, motion, SAME))
        })
    }

    /// What a simulation found at `value`: a new periodic motion becomes a
    /// branch to follow; a permanent stick is kept for the grid.
    fn found(&mut self, value: f64, found: &Result<Attractor, OrbitError>) {
        match found {
            Ok(Attractor::Periodic(m)) => self.motion(value, m.clone()),
            Ok(Attractor::Stick(s)) => self.sticks.push((value, stick_summary(s))),
            Ok(Attractor::Autonomous(c)) => {
                if let Some(m) = self.simulator(value).and_then(|sim| c.motion(sim.info())) {
                    self.motion(value, m)
                }
            }
            _ => {}
        }
    }

    /// A motion at `value`: followed unless a found branch holds it.
    fn motion(&mut self, value: f64, m: Motion) {
        if !m.is_admissible() || self.holding(&m, value).is_some() {
            return;
        }
        self.queue.push_back(Pending {
            start: Start {
                structure: m.structure.clone(),
                value,
                points: m.points,
                direction: None,
            },
            parent: None,
        });
    }

    /// The simulations from rest at both ends of the range.
    pub fn seed(&mut self, values: &[f64]) {
        for &value in [values[0], values[values.len() - 1]].iter() {
            if let Some(sim) = self.simulator(value) {
                let found = settle::from_rest(&sim, self.opts);
                self.found(value, &found);
            }
            self.run();
        }
        if self.opts.every > 0 {
            // Every k-th value, but at least five spread over a short grid,
            // and the last.
            let step = self.opts.every.min(((values.len() - 1) / 4).max(1));
            self.searches.extend(values.iter().step_by(step).copied());
            self.searches.push(values[values.len() - 1]);
        }
    }

    /// Run every pending search and follow everything it finds.
    pub fn search_all(&mut self) {
        let mut searched: Vec<f64> = Vec::new();
        while let Some(value) = self.searches.pop() {
            // Both sides of one transition land within a hair of each other.
            let near = |v: &f64| (v - value).abs() <= 1e-6 * value.abs().max(1.0);
            if searched.iter().any(near) {
                continue;
            }
            searched.push(value);
            self.search(value);
            self.run();
        }
    }

    /// The global search at `value`: simulations from many starts, each
    /// stopped as soon as it nears a known stable motion.
    fn search(&mut self, value: f64) {
        if self.opts.starts == 0 {
            return;
        }
        let Some(sim) = self.simulator(value) else {
            return;
        };
        let mut known = Vec::new();
        for (id, b) in self.branches.iter().enumerate() {
            for m in at_value(&sim, b, value) {
                if m.stability.is_some_and(|s| s.is_stable()) {
                    known.push((id, m));
                }
            }
        }
        let opts = SearchOptions {
            starts: self.opts.starts,
            attractor: self.opts.attractor,
            ..SearchOptions::default()
        };
        for m in coexisting(&sim, &known, &opts) {
            self.motion(value, m);
        }
    }

    /// Follow every pending start.
    fn run(&mut self) {
        while let Some(p) = self.queue.pop_front() {
            if self.branches.len() >= self.opts.max_branches {
                self.queue.clear();
                return;
            }
            self.follow(p);
        }
    }

    fn follow(&mut self, p: Pending) {
        if self
            .opts
            .max_mappings
            .is_some_and(|max| p.start.structure.len() > max)
        {
            return;
        }
        let Ok(branch) = follow::<M>(self.base, self.index, &p.start, &self.continuation) else {
            return;
        };
        if branch.points.is_empty() {
            return;
        }
        // A branch found again (from another seed, or born where a found
        // branch already passes) is not followed twice.
        let mid = &branch.points[branch.points.len() / 2];
        let probe = motion_of(&branch.structure, mid);
        if let Some(id) = self.holding(&probe, mid.value) {
            if let Some(parent) = p.parent {
                if !self.bifurcations[parent].born.contains(&id) {
                    self.bifurcations[parent].born.push(id);
                }
            }
            return;
        }
        let id = self.branches.len();
        if let Some(parent) = p.parent {
            self.bifurcations[parent].born.push(id);
        }
        self.branches.push(branch);
        self.after_ends(id);
        self.after_bifurcations(id);
    }

    /// Past each non-smooth end of branch `id`: what the simulation finds
    /// there (and a global search).
    fn after_ends(&mut self, id: usize) {
        let b = &self.branches[id];
        let n = b.points.len();
        let mut todo = Vec::new();
        for (k, end) in b.ends.iter().enumerate() {
            let EndReason::Transition { kind, boundary } = end.reason else {
                if matches!(end.reason, EndReason::NewtonFailure(_)) {
                    todo.push((k, None, None));
                }
                continue;
            };
            todo.push((k, Some(kind), boundary));
        }
        for (k, kind, boundary) in todo {
            let b = &self.branches[id];
            let end = &b.ends[k];
            // The side beyond the end: away from the branch's neighbouring point.
            // Two ends: the first at `points[0]`; one end: at the last point.
            let neighbour = if k == 0 && b.ends.len() == 2 {
                b.points.get(1)
            } else {
                n.checked_sub(2).and_then(|i| b.points.get(i))
            };
            let dir = neighbour.map_or(0.0, |q| (end.at.value - q.value).signum());
            if dir == 0.0 {
                continue;
            }
            let structure = b.structure.clone();
            let old = motion_of(&structure, &end.at);
            let edge = end.at.value;
            let (past, found) = self.past(edge, dir, &old);
            // An unstable autonomous cycle that loses an excursion goes on
            // as the cycle without it (no simulation finds it).
            let reduced = if structure.is_autonomous() {
                self.reduced_cycle(id, k, kind, boundary, dir)
            } else {
                None
            };
            let to = match (kind, reduced) {
                (Some(TransitionKind::Grazing), Some(name)) => name,
                _ => settle::name(M::info(self.base), &found),
            };
            if let Some(kind) = kind {
                self.transitions.push(Transition {
                    value: edge,
                    from: structure.notation(M::info(self.base)),
                    to,
                    kind,
                    boundary: boundary.map(|i| M::info(self.base).boundaries[i].label.to_string()),
                });
            }
            self.found(past, &found);
            self.searches.push(past);
        }
    }

    /// Where an autonomous cycle ends because a stick or an excursion
    /// beyond a boundary shrinks to nothing (end `k` of branch `id`, the
    /// branch coming from `−dir`), the cycle without it
    /// ([`crate::orbit::autonomous::without`]): followed from just beside
    /// the end, on whichever side it exists. A stick-slip cycle whose stick
    /// vanishes becomes a slip cycle, on the side the branch came from when
    /// the two meet in a non-smooth fold of cycles (as where an unstable
    /// slip cycle born at a Hopf point dies on the stable stick-slip
    /// cycle); an unstable cycle, which no simulation finds, goes on so
    /// past each excursion it loses.
    fn reduced_cycle(
        &mut self,
        id: usize,
        k: usize,
        kind: Option<TransitionKind>,
        boundary: Option<usize>,
        dir: f64,
    ) -> Option<String> {
        let b = &self.branches[id];
        let end = &b.ends[k];
        let info = M::info(self.base);
        let which = match kind {
            Some(TransitionKind::StickVanishing) => {
                shrinking(info, &b.structure, &end.at.points, None, true)
            }
            Some(TransitionKind::Grazing) if !end.at.stability.is_stable() => {
                shrinking(info, &b.structure, &end.at.points, boundary, false)
            }
            _ => None,
        };
        let (structure, points) =
            which.and_then(|i| without(info, &b.structure, &end.at.points, i))?;
        let edge = end.at.value;
        let (lo, hi) = self.continuation.bounds;
        for side in [-dir, dir] {
            let value = edge + side * (1e-7 * edge.abs().max(1.0)).max(4.0 * self.opts.tolerance);
            if value < lo || value > hi {
                continue;
            }
            self.queue.push_back(Pending {
                start: Start {
                    structure: structure.clone(),
                    value,
                    points: points.clone(),
                    direction: None,
                },
                parent: None,
            });
        }
        Some(settle::structure_name(info, &structure))
    }

    /// Just past `edge` in direction `dir`: simulate from `old`; a little
    /// further if the motion there is too close to the edge to settle.
    fn past(&self, edge: f64, dir: f64, old: &Motion) -> (f64, Result<Attractor, OrbitError>) {
        let (lo, hi) = self.continuation.bounds;
        let mut last = (edge, Err(OrbitError::Guess("outside the range".into())));
        for rel in [1e-7, 1e-5, 1e-3] {
            let step = (rel * edge.abs().max(1.0)).max(4.0 * self.opts.tolerance);
            let past = edge + dir * step;
            if past < lo || past > hi {
                break;
            }
            let Some(sim) = self.simulator(past) else {
                break;
            };
            let found = settle::from_motion(&sim, old, self.opts);
            let settled = !matches!(found, Err(OrbitError::Unsettled { .. }));
            last = (past, found);
            if settled {
                break;
            }
        }
        last
    }

    /// The branches born at each bifurcation of branch `id`, and the
    /// transitions the bifurcations are.
    fn after_bifurcations(&mut self, id: usize) {
        let count = self.branches[id].bifurcations.len();
        for which in 0..count {
            let located = self.bifurcations.len();
            self.bifurcations.push(Located {
                branch: id,
                which,
                born: Vec::new(),
            });
            let b = &self.branches[id];
            let bif = &b.bifurcations[which];
            let starts = born::<M>(self.base, self.index, b, bif, &self.continuation);
            let from = b.structure.notation(M::info(self.base));
            let at = bif.at.clone();
            let kind = bif.kind;
            let structure = b.structure.clone();
            let names: Vec<String> = starts
                .iter()
                .map(|s| settle::structure_name(M::info(self.base), &s.structure))
                .collect();
            let to = if !names.is_empty() {
                let mut names = names;
                names.dedup();
                names.join(" / ")
            } else {
                // A fold or a Neimark–Sacker point: simulate just past, on the
                // side where the branch is gone or unstable.
                let dir = self.unstable_side(id, bif.index);
                let old = motion_of(&structure, &at);
                if dir == 0.0 {
                    from.clone()
                } else {
                    let (past, found) = self.past(at.value, dir, &old);
                    let name = settle::name(M::info(self.base), &found);
                    self.found(past, &found);
                    name
                }
            };
            self.transitions.push(Transition {
                value: at.value,
                from,
                to,
                kind,
                boundary: None,
            });
            for start in starts {
                let periods = start.structure.periods();
                if kind == TransitionKind::PeriodDoubling
                    && self.opts.max_period.is_some_and(|max| periods > max)
                {
                    self.cuts.push(Cut {
                        value: at.value,
                        structure: start.structure.notation(M::info(self.base)),
                        n: periods,
                        max_period: self.opts.max_period.unwrap_or(periods),
                    });
                    continue;
                }
                self.queue.push_back(Pending {
                    start,
                    parent: Some(located),
                });
            }
        }
    }

    /// At point `k` of branch `id` (a fold or a Neimark–Sacker point), the
    /// direction of the parameter beyond which no stable motion of the branch
    /// continues: beyond a fold's turning point, or towards the unstable
    /// neighbour.
    fn unstable_side(&self, id: usize, k: usize) -> f64 {
        let b = &self.branches[id];
        let at = b.points[k].value;
        let before = k.checked_sub(1).and_then(|i| b.points.get(i));
        let after = b.points.get(k + 1);
        match (before, after) {
            (Some(p), Some(q)) => {
                let (dp, dq) = (p.value - at, q.value - at);
                if dp.signum() == dq.signum() {
                    // A turning point: both neighbours on one side.
                    -dp.signum()
                } else if !p.stability.is_stable() {
                    dp.signum()
                } else {
                    dq.signum()
                }
            }
            (Some(p), None) => -(p.value - at).signum(),
            (None, Some(q)) => -(q.value - at).signum(),
            (None, None) => 0.0,
        }
    }

    /// Every motion of the found branches at `value`, with the branch's id.
    pub fn motions_at(&self, value: f64) -> Vec<(usize, Motion)> {
        let Some(sim) = self.simulator(value) else {
            return Vec::new();
        };
        let mut out = Vec::new();
        for (id, b) in self.branches.iter().enumerate() {
            for m in at_value(&sim, b, value) {
                out.push((id, m));
            }
        }
        out
    }

    /// A simulation result at `value` from elsewhere (the no-motion edges).
    pub fn take(&mut self, value: f64, found: &Result<Attractor, OrbitError>) {
        self.found(value, found);
        self.searches.push(value);
        self.run();
    }

    /// Note a transition found elsewhere (the no-motion edges).
    pub fn transition(&mut self, t: Transition) {
        self.transitions.push(t);
    }
}

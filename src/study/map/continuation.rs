//! The continuation classifier ([`MapMethod::Continuation`](super::MapMethod)):
//! a tile of the grid ([`TILE`](super::TILE) × `TILE` points) is classified
//! as a unit, each point's motions continued from its neighbours' by Newton
//! instead of simulated for hundreds of forcing periods.
//!
//! First sweep, row by row:
//!
//! 1. every motion of the left and lower neighbours is continued: Newton
//!    from its switching points at the point's parameters, kept if it
//!    converges, is admissible (every margin of SPEC §6 positive,
//!    [`worst_margin`]) and stable ([`Continuer`], allocation-free);
//! 2. "no motion" is decided in closed form: some domain's forced response
//!    stays strictly inside its band ([`no_motion_exists`]);
//! 3. the two starts of the simulation method (rest, and above the stick
//!    boundary half a period later) are simulated where something may be
//!    new: at seed points (every [`SEED_SPACING`]-th point both ways), where
//!    a neighbour's motion is lost (Newton fails, or the solution is
//!    inadmissible or unstable; the lost motion's first switching point is
//!    simulated too, to find what it becomes), where a motion is within
//!    [`MARGIN_GUARD`] of a transition, and where the point's set differs
//!    from a neighbour's. A start is simulated only until it enters the
//!    neighbourhood of a motion known there ([`known::settle`]): a few
//!    periods where nothing new happens, the full settle (cycle detection,
//!    Newton) where it goes somewhere new.
//!
//! Then, until nothing changes: the tile is swept back and forth,
//! continuing every neighbour's motion (all four neighbours) into the points
//! that lack it — a motion continued into a region where another also lives
//! is listed with it (coexistence) — and the starts are simulated at every
//! point not yet simulated whose set differs from a neighbour's. Sets only
//! grow: a motion is never dropped because a simulation went elsewhere.
//!
//! A tile's result depends only on the tile (its points, in a fixed order),
//! never on the shards, the threads or which tiles were computed before, so
//! a resumed or sharded run writes the same bytes as a single run. What is
//! written are labels (structure names, [`structure_label`]): a continued
//! motion keeps the canonical structure it was found with, and a motion
//! that continues into a repetition of a shorter cycle is reduced to it
//! ([`attractor::primitive`]), as the simulation names it. A point whose
//! starts were not simulated has the status `ok`.

use std::collections::BTreeSet;

use crate::dynamics::simulate::{SimOptions, Simulator};
use crate::model::{Model, ModelInfo};
use crate::orbit::admissible::worst_margin;
use crate::orbit::attractor::{self, no_motion_certificate, Attractor, AttractorOptions};
use crate::orbit::known::{self, guard_margin, KnownMotions, Settled};
use crate::orbit::motion::{segment_at, Motion, OrbitError};
use crate::orbit::periodic::{NewtonOptions, PeriodicSolver, SwitchingPoint, Termination};
use crate::orbit::stability::Stability;
use crate::orbit::steady::steady_response;
use crate::orbit::structure::Structure;

use super::classify::{failure, panic_text, point_params, starts, structure_label, unsettled};
use super::file::PointResult;
use super::grid::{tile_points, GridAxis};
use super::{MAX_PERIODS, NO_MOTION, STICK};

/// Newton's options when continuing a neighbour's motion: the neighbour is
/// a close guess, so a solve that needs more iterations than this is lost.
pub const CONTINUATION_NEWTON: NewtonOptions = NewtonOptions {
    tolerance: 1e-12,
    max_iterations: 16,
};

/// A known motion whose smallest admissibility margin (SPEC §6) is below
/// this fraction of the model's velocity scale (the largest boundary
/// velocity, at least 1) does not stop a start's simulation: it is close to
/// a grazing or a stick onset, where a state near it can leave it through
/// the transition (on the 100 × 100 check grid, starts that passed within
/// the neighbourhood of such motions, margins 1e-6 to 2e-3, went on to
/// motions of period 2 to 13; the paper model's guard is 2e-3 · 4.5 = 9e-3).
/// Such a start is simulated until it settles, and a point with such a
/// motion always simulates its starts.
pub const MARGIN_GUARD: f64 = 2e-3;

/// The starts are simulated at least at every `SEED_SPACING`-th point of a
/// tile in both directions, so that a region this wide is entered even where
/// no neighbour's motion is lost at its border.
pub const SEED_SPACING: usize = 8;

/// Sweeps over a tile after the first (alternately backwards and forwards),
/// at most; they stop as soon as one adds nothing.
const MAX_SWEEPS: usize = 8;

/// Newton solvers for the structures met so far, and a buffer for the
/// switching points: after a structure's first continuation, continuing a
/// motion of it allocates nothing (tests/allocation_hot_paths.rs).
#[derive(Debug)]
pub struct Continuer<M: Model> {
    solvers: Vec<PeriodicSolver<M>>,
    points: Vec<SwitchingPoint>,
}

impl<M: Model> Default for Continuer<M> {
    fn default() -> Self {
        Self::new()
    }
}

impl<M: Model> Continuer<M> {
    /// An empty workspace.
    pub fn new() -> Self {
        Self {
            solvers: Vec::new(),
            points: Vec::with_capacity(64),
        }
    }

    /// Prepare the workspace for `structure` (allocates the first time only).
    pub fn prepare(&mut self, structure: &Structure) -> usize {
        match self.solvers.iter().position(|s| s.structure() == structure) {
            Some(i) => i,
            None => {
                self.solvers.push(PeriodicSolver::new(structure.clone()));
                self.solvers.len() - 1
            }
        }
    }

    /// Continue the motion of `structure` with switching points `from` to
    /// the simulator's parameters: the new switching points (in the
    /// workspace) if Newton converges from them and the solution is
    /// admissible and stable, with its stability; `None` otherwise.
    /// Allocates nothing once [`prepare`](Self::prepare) has seen the
    /// structure, except the text of a failed Newton's reason.
    pub fn continue_motion(
        &mut self,
        sim: &Simulator<M>,
        structure: &Structure,
        from: &[SwitchingPoint],
    ) -> Option<(&[SwitchingPoint], Stability)> {
        let i = self.prepare(structure);
        let solver = &mut self.solvers[i];
        self.points.clear();
        self.points.extend_from_slice(from);
        let termination = solver.solve(sim.params(), &mut self.points, CONTINUATION_NEWTON);
        if !matches!(termination, Termination::Converged { .. }) {
            return None;
        }
        let margin = worst_margin(sim, structure, &self.points)?;
        if margin.margin.is_nan() || margin.margin <= 0.0 {
            return None;
        }
        let dp = solver.poincare_jacobian_at_solution(sim.params()).ok()?;
        let stability = Stability::of(&dp);
        stability
            .is_stable()
            .then_some((&self.points[..], stability))
    }
}

/// Whether "no motion" lives at the simulator's parameters: the forced
/// response of some domain stays strictly inside the domain's band
/// (certified by [`no_motion_certificate`] at the response itself, where the
/// decaying part is zero). Every start near it stays: a damped linear flow.
pub fn no_motion_exists<M: Model>(sim: &Simulator<M>) -> bool {
    let w = sim.oscillator().frequency;
    (0..sim.info().domains.len()).any(|j| {
        // The forced response at phase 0 (`c = 0`: no finite response).
        steady_response::<M>(sim.params(), j).is_some_and(|r| {
            let (x, v) = (r.a + r.offset, w * r.b);
            x.is_finite() && no_motion_certificate(sim, j, x, v, 0.0).is_some()
        })
    })
}

/// One point of a tile while it is classified.
struct Cell<M: Model> {
    index: usize,
    x: f64,
    y: f64,
    sim: Option<Simulator<M>>,
    status: String,
    motions: Vec<Found>,
    others: BTreeSet<&'static str>,
    /// Whether the starts were simulated here.
    checked: bool,
}

/// A motion of a cell: its label, the motion, and whether its smallest
/// admissibility margin is clear of [`MARGIN_GUARD`].
#[derive(Clone)]
struct Found {
    label: String,
    motion: Motion,
    clear: bool,
}

impl<M: Model> Cell<M> {
    fn has(&self, label: &str) -> bool {
        self.motions.iter().any(|f| f.label == label)
    }

    /// Add `motion` under `label` (not there yet).
    fn add(&mut self, label: String, motion: Motion) {
        let Some(sim) = self.sim.as_ref() else {
            return;
        };
        let scale = (0..sim.info().boundaries.len())
            .map(|k| sim.velocity(k).abs())
            .fold(1.0_f64, f64::max);
        let wm = guard_margin(sim, &motion);
        let clear = wm.is_some_and(|m| m >= MARGIN_GUARD * scale);
        self.motions.push(Found {
            label,
            motion,
            clear,
        });
    }

    /// The labels on the map (motions and the others), sorted.
    fn key(&self) -> Vec<String> {
        let mut motions: Vec<String> = self.motions.iter().map(|f| f.label.clone()).collect();
        motions.extend(self.others.iter().map(|s| s.to_string()));
        motions.sort();
        motions
    }

    fn result(&self) -> PointResult {
        let mut motions: Vec<String> = self.motions.iter().map(|f| f.label.clone()).collect();
        motions.extend(self.others.iter().map(|s| s.to_string()));
        motions.sort();
        PointResult {
            index: self.index,
            x: self.x,
            y: self.y,
            status: self.status.clone(),
            motions,
        }
    }
}

/// A converged motion from the continuer's points (admissible and stable).
fn motion_from(structure: &Structure, points: &[SwitchingPoint], stability: Stability) -> Motion {
    Motion {
        structure: structure.clone(),
        points: points.to_vec(),
        termination: Termination::Converged {
            iterations: 0,
            residual: 0.0,
        },
        dp: None,
        stability: Some(stability),
        violations: Vec::new(),
    }
}

/// Whether `structure` is some shorter cycle repeated.
fn is_repetition(structure: &Structure) -> bool {
    let s = structure.steps();
    let m = s.len();
    (1..m).any(|q| m % q == 0 && (0..m).all(|k| s[k] == s[(k + q) % m]))
}

/// Continue `motion` (a neighbour's) into `cell`: whether it was added.
fn continue_into<M: Model>(
    cell: &mut Cell<M>,
    continuer: &mut Continuer<M>,
    label: &str,
    motion: &Motion,
) -> Option<bool> {
    let sim = cell.sim.as_ref()?;
    if cell.has(label) {
        return Some(false);
    }
    let (points, stability) = continuer.continue_motion(sim, &motion.structure, &motion.points)?;
    let mut found = motion_from(&motion.structure, points, stability);
    let mut label = label.to_string();
    if is_repetition(&found.structure) {
        found = attractor::primitive(sim, found, NewtonOptions::default());
        label = structure_label(sim.info(), &found.structure);
        if cell.has(&label) {
            return Some(false);
        }
    }
    cell.add(label, found);
    Some(true)
}

/// Add what a simulation settled to; `Err` for a start that did not settle.
fn take<M: Model>(
    info: &ModelInfo,
    cell: &mut Cell<M>,
    found: Result<Settled, OrbitError>,
) -> Result<(), String> {
    match found {
        Ok(Settled::Known(_)) => Ok(()),
        Ok(Settled::Attractor(a)) => {
            match *a {
                Attractor::Periodic(m) => {
                    let label = structure_label(info, &m.structure);
                    if !cell.has(&label) {
                        cell.add(label, m);
                    }
                }
                Attractor::NoMotion(_) => {
                    cell.others.insert(NO_MOTION);
                }
                Attractor::Stick(_) => {
                    cell.others.insert(STICK);
                }
                Attractor::Autonomous(c) => {
                    cell.others.insert(super::cycle_label(&c));
                }
            }
            Ok(())
        }
        Err(e) => Err(failure(info, &e)),
    }
}

/// The known motions of `cell`, seen at `phase0` (each certifies starts
/// only within its reach, [`known::reach`]).
fn known_at<M: Model>(sim: &Simulator<M>, cell: &Cell<M>, phase0: f64) -> KnownMotions {
    let mut known = KnownMotions::new(sim, phase0);
    for (id, f) in cell.motions.iter().enumerate() {
        known.insert(sim, id, &f.motion);
    }
    known
}

/// Steps 2–4 of the module doc at one cell: closed-form NM, the two starts
/// simulated until they near a known motion, and the lost motions' starts.
fn settle_cell<M: Model>(cell: &mut Cell<M>, lost: &[&Motion]) {
    let Some(sim) = cell.sim.clone() else {
        return;
    };
    cell.checked = true;
    let opts = AttractorOptions {
        max_periods: MAX_PERIODS,
        ..AttractorOptions::default()
    };
    let mut problems = Vec::new();
    for (k, (x0, v0, phase0)) in starts(&sim).into_iter().enumerate() {
        let known = known_at(&sim, cell, phase0);
        let found = sim
            .start(x0, v0, phase0)
            .map_err(OrbitError::from)
            .and_then(|seg| known::settle(&sim, &known, seg, opts).outcome);
        if let Err(e @ OrbitError::Unsettled { .. }) = &found {
            let what = unsettled::<M>(&sim, (x0, v0, phase0), e);
            problems.push(format!("start {}: {what}", k + 1));
            continue;
        }
        if let Err(e) = take(sim.info(), cell, found) {
            problems.push(format!("start {}: {e}", k + 1));
        }
    }
    for motion in lost {
        let label = structure_label(sim.info(), &motion.structure);
        if cell.has(&label) || motion.points.is_empty() {
            continue;
        }
        let seg = segment_at(&sim, &motion.structure, &motion.points, 0);
        let known = known_at(&sim, cell, seg.phase);
        // What the lost motion becomes; a start that does not settle is no
        // start of the simulation method, so it does not change the status.
        let _ = take(
            sim.info(),
            cell,
            known::settle(&sim, &known, seg, opts).outcome,
        );
    }
    cell.status = if problems.is_empty() {
        "ok".to_string()
    } else {
        problems.join("; ")
    };
}

/// Classify every point of tile `tile` (see the module doc), row by row.
/// Never panics on bad parameters (status `invalid: …`); a panic inside
/// the numerics is caught and reported in the status of the tile's points
/// that were not finished.
pub fn classify_tile<M: Model>(
    base: &M::Params,
    x_axis: &GridAxis,
    y_axis: &GridAxis,
    tile: usize,
) -> Vec<PointResult> {
    let indices = tile_points(tile, x_axis.count, y_axis.count);
    let mut cells: Vec<Cell<M>> = indices
        .iter()
        .map(
            |&index| match point_params::<M>(base, x_axis, y_axis, index) {
                Ok((x, y, p)) => match Simulator::<M>::new(p, SimOptions::default()) {
                    Ok(sim) => Cell {
                        index,
                        x,
                        y,
                        sim: Some(sim),
                        status: String::new(),
                        motions: Vec::new(),
                        others: BTreeSet::new(),
                        checked: false,
                    },
                    Err(e) => Cell {
                        index,
                        x,
                        y,
                        sim: None,
                        status: format!("invalid: {e}"),
                        motions: Vec::new(),
                        others: BTreeSet::new(),
                        checked: false,
                    },
                },
                Err((x, y, status)) => Cell {
                    index,
                    x,
                    y,
                    sim: None,
                    status,
                    motions: Vec::new(),
                    others: BTreeSet::new(),
                    checked: false,
                },
            },
        )
        .collect();
    let outcome = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        classify_cells(&mut cells, x_axis.count)
    }));
    if let Err(panic) = outcome {
        let what = format!("panic: {}", panic_text(&*panic));
        for c in cells.iter_mut().filter(|c| c.status.is_empty()) {
            c.status = what.clone();
        }
    }
    cells.iter().map(Cell::result).collect()
}

/// The neighbours of cell `i` in a tile `w` cells wide with `n` cells.
fn neighbours(i: usize, w: usize, n: usize) -> impl Iterator<Item = usize> {
    let (cx, cy) = (i % w, i / w);
    let left = (cx > 0).then(|| i - 1);
    let below = (cy > 0).then(|| i - w);
    let right = (cx + 1 < w && i + 1 < n).then(|| i + 1);
    let above = (i + w < n).then(|| i + w);
    [left, below, right, above].into_iter().flatten()
}

/// Whether cell `i` must simulate its starts: nothing known there, a seed,
/// a motion close to a transition, or a set that differs from a neighbour's.
fn needs_check<M: Model>(cells: &[Cell<M>], i: usize, w: usize, only_done: bool) -> bool {
    let c = &cells[i];
    if c.checked || c.sim.is_none() {
        return false;
    }
    // Nothing continued into the cell: nothing is known there (a chaotic
    // or unsettled neighbour has no motion to continue), and only its
    // starts can say what lives there.
    if c.motions.is_empty() && c.others.is_empty() {
        return true;
    }
    let (cx, cy) = (i % w, i / w);
    if (cx % SEED_SPACING == 0 && cy % SEED_SPACING == 0) || c.motions.iter().any(|f| !f.clear) {
        return true;
    }
    let key = c.key();
    neighbours(i, w, cells.len())
        .filter(|&j| !only_done || j < i)
        .any(|j| cells[j].sim.is_some() && cells[j].key() != key)
}

/// The motions of the neighbours of cell `i` that it lacks (its lost motions).
fn lost_at<M: Model>(cells: &[Cell<M>], i: usize, w: usize) -> Vec<Motion> {
    let mut lost: Vec<Motion> = Vec::new();
    for j in neighbours(i, w, cells.len()) {
        for f in &cells[j].motions {
            if !cells[i].has(&f.label) && !lost.iter().any(|m| m.structure == f.motion.structure) {
                lost.push(f.motion.clone());
            }
        }
    }
    lost
}

/// Continue every neighbour's motion into the cells that lack it, sweeping
/// back and forth until nothing changes.
fn sweep<M: Model>(cells: &mut [Cell<M>], w: usize, continuer: &mut Continuer<M>) {
    let n = cells.len();
    for pass in 0..MAX_SWEEPS {
        let mut changed = false;
        let order: Vec<usize> = if pass % 2 == 0 {
            (0..n).rev().collect()
        } else {
            (0..n).collect()
        };
        for &i in &order {
            for j in neighbours(i, w, n) {
                let from: Vec<Found> = cells[j]
                    .motions
                    .iter()
                    .filter(|f| !cells[i].has(&f.label))
                    .cloned()
                    .collect();
                for Found { label, motion, .. } in &from {
                    if continue_into(&mut cells[i], continuer, label, motion) == Some(true) {
                        changed = true;
                    }
                }
            }
        }
        if !changed {
            break;
        }
    }
}

fn classify_cells<M: Model>(cells: &mut [Cell<M>], nx: usize) {
    let n = cells.len();
    let Some(first) = cells.first() else {
        return;
    };
    // The tile's width: its cells are consecutive in x within a row.
    let w = cells
        .iter()
        .take_while(|c| c.index / nx.max(1) == first.index / nx.max(1))
        .count()
        .max(1);
    let mut continuer = Continuer::<M>::new();
    // First sweep: continue from the cells already done (left, below), then
    // simulate the starts where needed.
    for i in 0..n {
        let mut lost: Vec<Motion> = Vec::new();
        for j in neighbours(i, w, n).filter(|&j| j < i) {
            let (done, rest) = cells.split_at_mut(i);
            let cell = &mut rest[0];
            for Found { label, motion, .. } in &done[j].motions {
                if continue_into(cell, &mut continuer, label, motion).is_some() {
                    continue;
                }
                if cell.sim.is_some() && !lost.iter().any(|m| m.structure == motion.structure) {
                    lost.push(motion.clone());
                }
            }
        }
        if let Some(sim) = &cells[i].sim {
            if no_motion_exists(sim) {
                cells[i].others.insert(NO_MOTION);
            }
        }
        if !lost.is_empty() || needs_check(cells, i, w, true) {
            let lost: Vec<&Motion> = lost.iter().collect();
            settle_cell(&mut cells[i], &lost);
        }
    }
    // Then: coexisting motions continued everywhere they live, and the
    // starts simulated wherever a set still differs from a neighbour's,
    // until neither adds anything.
    loop {
        sweep(cells, w, &mut continuer);
        let todo: Vec<usize> = (0..n)
            .filter(|&i| needs_check(cells, i, w, false))
            .collect();
        if todo.is_empty() {
            break;
        }
        for i in todo {
            let lost = lost_at(cells, i, w);
            let lost: Vec<&Motion> = lost.iter().collect();
            settle_cell(&mut cells[i], &lost);
        }
    }
    for c in cells.iter_mut().filter(|c| c.sim.is_some() && !c.checked) {
        c.status = "ok".to_string();
    }
}

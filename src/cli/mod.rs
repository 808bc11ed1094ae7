//! The command line: the parser, one module per subcommand (its arguments
//! and what it does), the arguments they share, their errors and output.

mod args;
mod basins;
mod check;
mod curves;
mod describe;
mod diagram;
mod equilibria;
mod error;
mod lyapunov;
mod map;
mod merge;
mod models;
mod orbit;
mod outcome;
mod reference;
mod simulate;
mod sweep;
mod trade;

use std::process::ExitCode;

use clap::{Parser, Subcommand};

use error::CliError;

/// Exact periodic motions of friction oscillators, from model files.
#[derive(Parser)]
#[command(name = "stickslip", version, about)]
pub struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Check model files as the build does (parse, check, generate), without
    /// compiling anything: each error as `error:`, `--> FILE:LINE:COL`, the
    /// source line and a caret, on stderr. Exit status 1 on any error.
    Check(check::CheckArgs),
    /// List the compiled-in models and their scenes.
    Models,
    /// Print a model's domains, boundaries and generated mappings.
    Describe(describe::DescribeArgs),
    /// Solve a given mapping structure for its periodic motion (Newton),
    /// check it (admissibility) and give its stability.
    Orbit(orbit::OrbitArgs),
    /// Simulate from a start state until the motion settles; name and refine
    /// the periodic motion, or certify that none touches a boundary (NM). A
    /// smooth law (a model without `--scene`) is integrated: steady sliding
    /// or a self-excited cycle when unforced, a periodic motion when forced.
    Simulate(simulate::SimulateArgs),
    /// Follow periodic motions along one parameter; locate every transition
    /// (grazing, stick onset and vanishing, passable onset, |λ| = 1) and what
    /// lives beyond it; report coexisting motions. A smooth law (a model
    /// without `--scene`): steady sliding and every cycle at each value,
    /// the Hopf point and the stick-slip cycle's fold located.
    Sweep(sweep::SweepArgs),
    /// Measure the speed/accuracy trade of a smooth-law model: its N-piece
    /// predictions and the integrator at several tolerances against the law
    /// integrated tightly (switching points, amplitude, time).
    Trade(trade::TradeArgs),
    /// Steady sliding of an unforced model (Q0 = 0): the rest position, its
    /// exact eigenvalues and stability, along a parameter with every change
    /// of stability located (a smooth law's Hopf point, the point where a
    /// piecewise law's equilibrium crosses a boundary).
    Equilibria(equilibria::EquilibriaArgs),
    /// Which motions exist at each point of a grid over two parameters (the
    /// paper's Fig. 11); all cores, resumable, shardable for a cluster.
    Map(map::MapArgs),
    /// Trace every transition curve over two parameters (grazing, stick
    /// onset and vanishing, passable onset, fold, period doubling,
    /// Neimark–Sacker) by continuation from the transitions sweeps locate;
    /// their codimension-two points; the regime map drawn from them.
    Curves(curves::CurvesArgs),
    /// The Lyapunov exponents of the stroboscopic map from the exact tangent
    /// map (stick and every switching included), with an error estimate and
    /// a verdict: periodic, chaotic, quasi-periodic, NM or stick.
    Lyapunov(lyapunov::LyapunovArgs),
    /// Join the outputs of `map --shard k/n` into one map (and figure),
    /// identical to a single run.
    Merge(merge::MergeArgs),
    /// Which attractor each start (x, v) at a forcing phase reaches: basin
    /// fractions of a grid and basin stability from random starts, with
    /// confidence intervals; all cores, resumable.
    Basins(basins::BasinsArgs),
    /// The brute-force bifurcation diagram: stroboscopic samples after a
    /// transient at each parameter value, swept up and down (hysteresis),
    /// with the largest Lyapunov exponent and the sweep's branches.
    OrbitDiagram(diagram::DiagramArgs),
    /// Print the command-line reference in Markdown (the guide's page).
    #[command(hide = true)]
    Reference,
}

impl Cli {
    /// Run the subcommand and print what it says; the exit status. An
    /// error is returned unprinted.
    pub fn run(self) -> Result<ExitCode, CliError> {
        let outcome = match self.command {
            // Streams its diagnostics, has its own exit status.
            Command::Check(args) => return check::run(&args),
            Command::Models => models::run(),
            Command::Describe(args) => describe::run(args)?,
            Command::Orbit(args) => orbit::run(args)?,
            Command::Simulate(args) => simulate::run(args)?,
            Command::Sweep(args) => sweep::run(args)?,
            Command::Trade(args) => trade::run(args)?,
            Command::Equilibria(args) => equilibria::run(args)?,
            Command::Map(args) => map::run(args)?,
            Command::Curves(args) => curves::run(args)?,
            Command::Merge(args) => merge::run(args)?,
            Command::Lyapunov(args) => lyapunov::run(args)?,
            Command::Basins(args) => basins::run(args)?,
            Command::OrbitDiagram(args) => diagram::run(args)?,
            Command::Reference => reference::run(),
        };
        Ok(outcome.print())
    }
}

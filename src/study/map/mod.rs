//! Parameter maps (SPEC §9, the paper's Fig. 11): which motions exist at
//! each point of a grid over two parameters.
//!
//! Two methods ([`MapMethod`]):
//!
//! - **continuation** (the default, [`classify_tile`]): the grid is cut into
//!   tiles of [`TILE`] × `TILE` points, each classified as a unit. A point's
//!   motions are its neighbours' motions continued by Newton to its
//!   parameters (kept when admissible and stable; allocation-free,
//!   [`Continuer`]), "no motion" is decided in closed form
//!   ([`no_motion_exists`]), and the simulation method's two starts are
//!   simulated only where something may be new — at seed points, where a
//!   motion is lost, where a motion is close to a transition, where a
//!   point's set differs from a neighbour's — and then only until they
//!   near a motion already known there. Coexisting motions are continued
//!   into every point where they live.
//! - **simulation** ([`classify_point`]): every point is simulated from two
//!   starts (rest, and a state above the stick boundary half a forcing
//!   period later) until it settles
//!   ([`attractor::find`](crate::orbit::attractor::find)); the distinct
//!   results are the point's motions.
//!
//! Either way the motions are named by structure and period, or `NM`, and
//! coexisting motions (the flow barrier of SPEC §10) show up as a set. On
//! the paper model's Fig. 11 range the continuation map lists every motion
//! the simulation map lists, and sometimes more (coexistence, each extra
//! proven: tests/map_continuation.rs).
//!
//! [`run_map`] computes a grid (or one shard of it, for a cluster job
//! array: the tiles whose number is `k` mod `n`) on all cores and appends
//! each point's line to the output file as soon as its tile is known, so
//! that a run killed at any moment resumes without losing or repeating a
//! point (the unfinished tiles are recomputed, only their missing points
//! written: a tile's result depends on the tile alone); at the end the
//! file is rewritten sorted by index. [`merge`] joins shard files into the
//! file a single run would have written, byte for byte.
//!
//! # File format
//!
//! ```text
//! # stickslip map model=paper x=W=3:5:6 y=Q0=50:80:3 base=m=5,d=0.1,... method=continuation [shard=0/3]
//! index,W,Q0,status,motions
//! 0,3.0,50.0,"ok","P_{3_31 0_11 3_13 4_33}"
//! 1,3.4,50.0,"ok","NM;P_{3_33 4_33}^2"
//! ```
//!
//! Grid point `index = iy * nx + ix` lies at `x = x.value(ix)`,
//! `y = y.value(iy)`. `status` is `ok` when every start settled, `invalid: …`
//! for parameters the model rejects, and otherwise names the starts that did
//! not settle (`start 2: unsettled`). `motions` are sorted and joined by `;`:
//! a structure in the paper's notation with `^N` when its period is `N > 1`
//! forcing periods, or `NM`. Numbers are printed in Rust's shortest
//! round-trip form, so a parsed line prints back byte for byte. The shard
//! appears in the header of a shard's file only: a complete map does not
//! depend on how it was split. The method does change what a point lists,
//! so the header records it (`method=`), and a resume or merge refuses a
//! file of the other method (or of none: a file written before the header
//! recorded it), as it refuses another grid.

mod classify;
mod continuation;
mod error;
mod file;
mod grid;
mod run;

pub use classify::{classify_point, motion_label};
pub use continuation::{classify_tile, no_motion_exists, Continuer, CONTINUATION_NEWTON};
pub use error::{AxisError, MapError};
pub use file::{MapFile, MapHeader, PointResult};
pub use grid::{grid_len, tile_count, tile_of, tile_points, GridAxis, Shard, TILE};
pub use run::{merge, run_map, run_map_counting, MapMethod, MapOptions, Summary};

/// Forcing periods simulated at most from each start.
pub const MAX_PERIODS: u32 = 600;

/// The label of "no motion touches a boundary".
pub const NO_MOTION: &str = "NM";

/// The label of a permanent stick in a map.
pub const STICK: &str = "stick";

/// The label of an unforced model's cycle in a map: `stick-slip cycle` or
/// `slip cycle` (its structure changes along the axes as its slip crosses
/// more or fewer pieces of a law; the regime is what the map shows).
pub fn cycle_label(c: &crate::orbit::attractor::AutonomousCycle) -> &'static str {
    if c.stick > 0.0 {
        "stick-slip cycle"
    } else {
        "slip cycle"
    }
}

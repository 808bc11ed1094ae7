//! The regions of a regime map: the parameter plane cut by the curves, each
//! connected region named by the motions that live in it.

use crate::model::Model;

use super::CurveSet;

/// One region of the plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// What lives there, as a map names it (`P_{...}`, `NM`, joined by `;`
    /// when several coexist).
    pub label: String,
    /// The point `[x, y]` where it was classified, well inside the region.
    pub sample: [f64; 2],
}

/// The plane as a raster of `nx × ny` cells, each the index of its region.
#[derive(Clone, Debug, PartialEq)]
pub struct Regions {
    /// Cells across.
    pub nx: usize,
    /// Cells up.
    pub ny: usize,
    /// `cells[iy * nx + ix]`: the region of the cell (row 0 at the bottom, `y` low).
    pub cells: Vec<usize>,
    /// The regions.
    pub regions: Vec<Region>,
}

/// Cut the plane of `set` into regions by its curves on an `nx × ny` raster
/// and classify each region once.
pub fn regions<M: Model>(base: &M::Params, set: &CurveSet, nx: usize, ny: usize) -> Regions {
    let _ = (base, set);
    Regions {
        nx,
        ny,
        cells: Vec::new(),
        regions: Vec::new(),
    }
}

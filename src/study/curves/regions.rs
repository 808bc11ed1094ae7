//! The regions of a regime map: the parameter plane cut by the curves, each
//! connected region named by the motions that live in it.
//!
//! The box is rasterized ([`raster`]): the cells a curve passes through are
//! walls, the other cells fall into 4-connected components, and each
//! component large enough ([`min_cells`]) is classified once, at its cell
//! farthest from any wall, exactly as a map classifies a grid point
//! ([`classify_point`]: simulation from two starts), the components in
//! parallel. Wall cells and components too small to classify take the
//! region of the nearest classified cell. A curve that ends inside the box
//! (at a codimension-two point) separates nothing by itself: the region
//! around its end is one region, with one label.

pub mod raster;

use rayon::prelude::*;

use crate::model::Model;
use crate::study::map::{classify_point, GridAxis};

use super::CurveSet;

pub use raster::{crosses, partition, Component, Partition, Raster};

/// One region of the plane.
#[derive(Clone, Debug, PartialEq)]
pub struct Region {
    /// What lives there, as a map's figure names it
    /// ([`PointResult::label`](crate::study::map::PointResult::label):
    /// `P_{...}`, `NM`, joined by ` + ` when several coexist; `unsettled`,
    /// `invalid`, … when no motion was found).
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

impl Regions {
    /// The distinct labels, in the order of their first region.
    pub fn labels(&self) -> Vec<&str> {
        let mut seen: Vec<&str> = Vec::new();
        for r in &self.regions {
            if !seen.contains(&r.label.as_str()) {
                seen.push(&r.label);
            }
        }
        seen
    }
}

/// Components smaller than this are not classified (they take their
/// neighbours' region): `max(4, nx·ny / 10⁴)` cells.
pub fn min_cells(nx: usize, ny: usize) -> usize {
    (nx * ny / 10_000).max(4)
}

/// Cut the plane of `set` into regions by its curves on an `nx × ny` raster
/// and classify each region once.
pub fn regions<M: Model>(base: &M::Params, set: &CurveSet, nx: usize, ny: usize) -> Regions {
    let (xname, yname) = (set.x.0.clone(), set.y.0.clone());
    let classify = |[x, y]: [f64; 2]| {
        let axis = |name: &str, v: f64| GridAxis {
            name: name.to_string(),
            from: v,
            to: v,
            count: 1,
        };
        classify_point::<M>(base, &axis(&xname, x), &axis(&yname, y), 0).label()
    };
    classify_partition(&partition(set, nx, ny), classify)
}

/// Name the regions of `cut`: `classify` at the sample of every component
/// of at least [`min_cells`] cells (in parallel; the result does not depend
/// on the order), the largest component should none be that large, the
/// box's centre should there be no cell free of walls. Every other cell
/// takes the region of the nearest classified cell that it reaches without
/// crossing a curve (centre to centre, breadth first over 4 neighbours):
/// a wall cell the region on its centre's side. Cells that no region
/// reaches so (shut in between curves) take the nearest region across them
/// (8 neighbours). Ties go to the region of lower index.
pub fn classify_partition(
    cut: &Partition,
    classify: impl Fn([f64; 2]) -> String + Sync,
) -> Regions {
    let r = &cut.raster;
    let (nx, ny) = (r.nx, r.ny);
    let min = min_cells(nx, ny);
    let mut chosen: Vec<usize> = (0..cut.components.len())
        .filter(|&k| cut.components[k].cells >= min)
        .collect();
    if chosen.is_empty() {
        // The first of the largest.
        let largest = (0..cut.components.len())
            .rev()
            .max_by_key(|&k| cut.components[k].cells);
        chosen.extend(largest);
    }
    // The sample cell of each region, and the seed cells it grows from.
    let samples: Vec<usize> = if chosen.is_empty() {
        vec![(ny / 2) * nx + nx / 2]
    } else {
        chosen.iter().map(|&k| cut.components[k].sample).collect()
    };
    let labels: Vec<String> = samples.par_iter().map(|&i| classify(r.centre(i))).collect();
    let regions: Vec<Region> = labels
        .into_iter()
        .zip(&samples)
        .map(|(label, &i)| Region {
            label,
            sample: r.centre(i),
        })
        .collect();
    const NONE: usize = usize::MAX;
    let mut cells = vec![NONE; nx * ny];
    let mut region_of = vec![NONE; cut.components.len()];
    for (k, &c) in chosen.iter().enumerate() {
        region_of[c] = k;
    }
    let mut seeds = Vec::new();
    for (i, c) in cut.component.iter().enumerate() {
        if let Some(&k) = c.and_then(|c| region_of.get(c)).filter(|&&k| k != NONE) {
            cells[i] = k;
            seeds.push(i);
        }
    }
    if seeds.is_empty() {
        cells[samples[0]] = 0;
        seeds.push(samples[0]);
    }
    // First across cell edges that no curve crosses (centre to centre), so
    // that a wall cell takes the region on its centre's side of the curve;
    // then, for cells cut off between curves, across anything.
    let open = |i: usize, j: usize| {
        let line = [cell_units(nx, i), cell_units(nx, j)];
        !cut.segments[i]
            .iter()
            .chain(&cut.segments[j])
            .any(|&s| crosses(line, s))
    };
    let fours = [(-1, 0), (1, 0), (0, -1), (0, 1)];
    let reached = grow(&mut cells, seeds, nx, ny, &fours, open);
    let eights = [
        (-1, 0),
        (1, 0),
        (0, -1),
        (0, 1),
        (-1, -1),
        (1, -1),
        (-1, 1),
        (1, 1),
    ];
    grow(&mut cells, reached, nx, ny, &eights, |_, _| true);
    Regions {
        nx,
        ny,
        cells,
        regions,
    }
}

/// The centre of cell `i` in cell units.
fn cell_units(nx: usize, i: usize) -> [f64; 2] {
    [(i % nx) as f64 + 0.5, (i / nx) as f64 + 0.5]
}

/// Grow the regions of `cells` (`usize::MAX`: none yet) from `seeds`, nearest
/// first, to every neighbour (`steps`) reachable through `open` edges; of two
/// regions reaching a cell in the same step the lower index wins. Returns
/// every cell that has a region.
fn grow(
    cells: &mut [usize],
    seeds: Vec<usize>,
    nx: usize,
    ny: usize,
    steps: &[(i64, i64)],
    open: impl Fn(usize, usize) -> bool,
) -> Vec<usize> {
    let mut all = seeds.clone();
    let mut front = seeds;
    while !front.is_empty() {
        let mut next: Vec<(usize, usize)> = Vec::new();
        for &i in &front {
            let (ix, iy) = ((i % nx) as i64, (i / nx) as i64);
            for &(dx, dy) in steps {
                let (jx, jy) = (ix + dx, iy + dy);
                if jx < 0 || jy < 0 || jx >= nx as i64 || jy >= ny as i64 {
                    continue;
                }
                let j = jy as usize * nx + jx as usize;
                if cells[j] == usize::MAX && open(i, j) {
                    next.push((j, cells[i]));
                }
            }
        }
        next.sort_unstable();
        next.dedup_by_key(|(j, _)| *j);
        front.clear();
        for &(j, k) in &next {
            cells[j] = k;
            front.push(j);
        }
        all.extend_from_slice(&front);
    }
    all
}

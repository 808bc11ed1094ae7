//! The plane cut by the curves on a raster, before anything is classified
//! ([`Partition`]): every cell a curve passes through is a wall (the cells
//! of a grid traversal, so a wall is a 4-connected chain of cells and no
//! 4-connected component leaks through it diagonally), the other cells fall
//! into 4-connected components, and each component's sample is its cell
//! farthest from any wall and from the box's edge (an exact Euclidean
//! distance transform).

use crate::study::curves::CurveSet;

/// The box `[x0, x1] × [y0, y1]` on `nx × ny` cells, row 0 at `y0`.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Raster {
    /// Cells across.
    pub nx: usize,
    /// Cells up.
    pub ny: usize,
    /// The horizontal range `[from, to]`.
    pub x: [f64; 2],
    /// The vertical range `[from, to]`.
    pub y: [f64; 2],
}

impl Raster {
    /// The raster of `set`'s box (at least one cell each way).
    pub fn of(set: &CurveSet, nx: usize, ny: usize) -> Self {
        Self {
            nx: nx.max(1),
            ny: ny.max(1),
            x: set.x.1,
            y: set.y.1,
        }
    }

    /// The parameters `[x, y]` at the centre of cell `i`.
    pub fn centre(&self, i: usize) -> [f64; 2] {
        let (ix, iy) = (i % self.nx, i / self.nx);
        let at =
            |r: [f64; 2], k: usize, n: usize| r[0] + (r[1] - r[0]) * (k as f64 + 0.5) / n as f64;
        [at(self.x, ix, self.nx), at(self.y, iy, self.ny)]
    }

    /// `[x, y]` in cell units: `(0, 0)` the box's corner at `(x0, y0)`,
    /// `(nx, ny)` the opposite one. `None` for a degenerate box or a point
    /// that is not finite.
    fn cell_units(&self, [x, y]: [f64; 2]) -> Option<[f64; 2]> {
        let u = (x - self.x[0]) / (self.x[1] - self.x[0]) * self.nx as f64;
        let v = (y - self.y[0]) / (self.y[1] - self.y[0]) * self.ny as f64;
        (u.is_finite() && v.is_finite()).then_some([u, v])
    }
}

/// One 4-connected component of the cells no curve passes through.
#[derive(Clone, Debug, PartialEq)]
pub struct Component {
    /// Its number of cells.
    pub cells: usize,
    /// Its cell farthest from every wall and from the box's edge (the
    /// lowest index of equally far ones).
    pub sample: usize,
    /// That cell's distance to the nearest wall or to the outside of the
    /// box, in cells (centre to centre).
    pub depth: f64,
}

/// The raster cut by the curves: walls and components.
#[derive(Clone, Debug, PartialEq)]
pub struct Partition {
    /// The raster.
    pub raster: Raster,
    /// `wall[iy * nx + ix]`: a curve passes through the cell.
    pub wall: Vec<bool>,
    /// The pieces of curve segments through each cell, in cell units
    /// (empty for a cell that is no wall).
    pub segments: Vec<Vec<[[f64; 2]; 2]>>,
    /// The component of each cell that is not a wall.
    pub component: Vec<Option<usize>>,
    /// The components, in the order of their lowest cell index.
    pub components: Vec<Component>,
}

/// Cut `set`'s box, rasterized on `nx × ny` cells, by every curve of `set`.
pub fn partition(set: &CurveSet, nx: usize, ny: usize) -> Partition {
    let raster = Raster::of(set, nx, ny);
    let segments = walls(set, &raster);
    let wall: Vec<bool> = segments.iter().map(|s| !s.is_empty()).collect();
    let (component, mut components) = components(&wall, raster.nx, raster.ny);
    let depth2 = depth2(&wall, raster.nx, raster.ny);
    for (i, c) in component.iter().enumerate() {
        if let Some(k) = *c {
            let best = &mut components[k];
            if depth2[i] as f64 > best.depth {
                best.depth = depth2[i] as f64;
                best.sample = i;
            }
        }
    }
    for c in &mut components {
        c.depth = c.depth.sqrt();
    }
    Partition {
        raster,
        wall,
        segments,
        component,
        components,
    }
}

/// The wall cells: for every cell, the segments of curves (clipped to the
/// box, in cell units) that pass through it.
pub fn walls(set: &CurveSet, raster: &Raster) -> Vec<Vec<[[f64; 2]; 2]>> {
    let mut wall = vec![Vec::new(); raster.nx * raster.ny];
    for curve in &set.curves {
        // A point that is not finite breaks the line.
        let points: Vec<Option<[f64; 2]>> =
            curve.points.iter().map(|&p| raster.cell_units(p)).collect();
        if let [Some(p)] = points[..] {
            mark_segment(&mut wall, raster, p, p);
        }
        for w in points.windows(2) {
            if let [Some(a), Some(b)] = w {
                mark_segment(&mut wall, raster, *a, *b);
            }
        }
    }
    wall
}

/// The part of the segment `a`–`b` inside the box `lo`–`hi` (each
/// coordinate `lo ≤ hi`; Liang–Barsky), if any.
pub fn clip(a: [f64; 2], b: [f64; 2], lo: [f64; 2], hi: [f64; 2]) -> Option<([f64; 2], [f64; 2])> {
    let d = [b[0] - a[0], b[1] - a[1]];
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [
        (-d[0], a[0] - lo[0]),
        (d[0], hi[0] - a[0]),
        (-d[1], a[1] - lo[1]),
        (d[1], hi[1] - a[1]),
    ] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    (t0 <= t1).then(|| {
        let at = |t: f64| [a[0] + t * d[0], a[1] + t * d[1]];
        (at(t0), at(t1))
    })
}

/// Mark every cell that the segment `a`–`b` (cell units) passes through: a
/// grid traversal (Amanatides–Woo) that steps one axis at a time, so the
/// marked cells form a 4-connected chain from `a`'s cell to `b`'s.
fn mark_segment(wall: &mut [Vec<[[f64; 2]; 2]>], raster: &Raster, a: [f64; 2], b: [f64; 2]) {
    let (nx, ny) = (raster.nx, raster.ny);
    let Some((a, b)) = clip(a, b, [0.0; 2], [nx as f64, ny as f64]) else {
        return;
    };
    let cell = |u: f64, n: usize| (u.floor().max(0.0) as usize).min(n - 1);
    let (mut ix, mut iy) = (cell(a[0], nx), cell(a[1], ny));
    let (ex, ey) = (cell(b[0], nx), cell(b[1], ny));
    let d = [b[0] - a[0], b[1] - a[1]];
    // The parameter t along the segment at the next vertical (horizontal)
    // cell edge, and its growth per cell.
    let next = |u: f64, i: usize, du: f64| {
        if du > 0.0 {
            ((i + 1) as f64 - u) / du
        } else if du < 0.0 {
            (i as f64 - u) / du
        } else {
            f64::INFINITY
        }
    };
    let (mut tx, mut ty) = (next(a[0], ix, d[0]), next(a[1], iy, d[1]));
    let (sx, sy) = (1.0 / d[0].abs(), 1.0 / d[1].abs());
    // Exactly the steps that lead from the first cell to the last: rounding
    // can never make the chain miss its end.
    let (mut left_x, mut left_y) = (ix.abs_diff(ex), iy.abs_diff(ey));
    wall[iy * nx + ix].push([a, b]);
    while left_x + left_y > 0 {
        if left_y == 0 || (left_x > 0 && tx <= ty) {
            ix = if ex > ix { ix + 1 } else { ix - 1 };
            tx += sx;
            left_x -= 1;
        } else {
            iy = if ey > iy { iy + 1 } else { iy - 1 };
            ty += sy;
            left_y -= 1;
        }
        wall[iy * nx + ix].push([a, b]);
    }
}

/// The 4-connected components of the cells that are not walls: each cell's
/// component, and the components (sample and depth still to be found).
fn components(wall: &[bool], nx: usize, ny: usize) -> (Vec<Option<usize>>, Vec<Component>) {
    let mut component: Vec<Option<usize>> = vec![None; wall.len()];
    let mut found = Vec::new();
    let mut stack = Vec::new();
    for start in 0..wall.len() {
        if wall[start] || component[start].is_some() {
            continue;
        }
        let k = found.len();
        let mut cells = 0;
        component[start] = Some(k);
        stack.push(start);
        while let Some(i) = stack.pop() {
            cells += 1;
            let (ix, iy) = (i % nx, i / nx);
            let neighbours = [
                (ix > 0).then(|| i - 1),
                (ix + 1 < nx).then(|| i + 1),
                (iy > 0).then(|| i - nx),
                (iy + 1 < ny).then(|| i + nx),
            ];
            for j in neighbours.into_iter().flatten() {
                if !wall[j] && component[j].is_none() {
                    component[j] = Some(k);
                    stack.push(j);
                }
            }
        }
        found.push(Component {
            cells,
            sample: start,
            depth: -1.0,
        });
    }
    (component, found)
}

/// The squared Euclidean distance (in cells, centre to centre) from every
/// cell to the nearest wall cell or to the nearest cell outside the box
/// (Felzenszwalb–Huttenlocher: exact, two passes of lower envelopes of parabolas).
fn depth2(wall: &[bool], nx: usize, ny: usize) -> Vec<i64> {
    // The raster framed by a ring of walls: the outside of the box.
    let (w, h) = (nx + 2, ny + 2);
    let far = ((w * w + h * h) as i64).saturating_mul(4);
    let mut f = vec![far; w * h];
    for iy in 0..h {
        for ix in 0..w {
            let inside = (1..=nx).contains(&ix) && (1..=ny).contains(&iy);
            if !inside || wall[(iy - 1) * nx + (ix - 1)] {
                f[iy * w + ix] = 0;
            }
        }
    }
    let mut line = Vec::with_capacity(w.max(h));
    let mut out = Vec::with_capacity(w.max(h));
    for iy in 0..h {
        line.clear();
        line.extend_from_slice(&f[iy * w..(iy + 1) * w]);
        envelope(&line, &mut out);
        f[iy * w..(iy + 1) * w].copy_from_slice(&out);
    }
    for ix in 0..w {
        line.clear();
        line.extend((0..h).map(|iy| f[iy * w + ix]));
        envelope(&line, &mut out);
        for (iy, &d) in out.iter().enumerate() {
            f[iy * w + ix] = d;
        }
    }
    let mut inner = Vec::with_capacity(nx * ny);
    for iy in 1..=ny {
        inner.extend_from_slice(&f[iy * w + 1..iy * w + 1 + nx]);
    }
    inner
}

/// Whether the segments `p`–`q` and `a`–`b` meet (touching counts).
pub fn crosses([p, q]: [[f64; 2]; 2], [a, b]: [[f64; 2]; 2]) -> bool {
    let side = |o: [f64; 2], u: [f64; 2], v: [f64; 2]| {
        (u[0] - o[0]) * (v[1] - o[1]) - (u[1] - o[1]) * (v[0] - o[0])
    };
    let (d1, d2) = (side(a, b, p), side(a, b, q));
    let (d3, d4) = (side(p, q, a), side(p, q, b));
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    // Collinear or touching: an end of one on the other.
    let on = |o: [f64; 2], u: [f64; 2], r: [f64; 2], d: f64| {
        d == 0.0
            && r[0] >= o[0].min(u[0])
            && r[0] <= o[0].max(u[0])
            && r[1] >= o[1].min(u[1])
            && r[1] <= o[1].max(u[1])
    };
    on(a, b, p, d1) || on(a, b, q, d2) || on(p, q, a, d3) || on(p, q, b, d4)
}

/// One dimension of the distance transform: `out[q] = min_p (q - p)² + f[p]`.
fn envelope(f: &[i64], out: &mut Vec<i64>) {
    let n = f.len();
    out.clear();
    out.resize(n, 0);
    // Parabolas of the lower envelope (their apexes) and where each begins.
    let mut v = vec![0usize; n];
    let mut z = vec![0f64; n + 1];
    let mut k = 0;
    z[0] = f64::NEG_INFINITY;
    z[1] = f64::INFINITY;
    let meet = |p: usize, q: usize| {
        let (p2, q2) = ((p * p) as f64, (q * q) as f64);
        ((f[q] as f64 + q2) - (f[p] as f64 + p2)) / (2.0 * (q as f64 - p as f64))
    };
    for q in 1..n {
        let mut s = meet(v[k], q);
        while s <= z[k] {
            k -= 1;
            s = meet(v[k], q);
        }
        k += 1;
        v[k] = q;
        z[k] = s;
        z[k + 1] = f64::INFINITY;
    }
    k = 0;
    for (q, o) in out.iter_mut().enumerate() {
        while z[k + 1] < q as f64 {
            k += 1;
        }
        let d = q as i64 - v[k] as i64;
        *o = d * d + f[v[k]];
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Brute-force squared distances, to check the transform.
    fn brute(wall: &[bool], nx: usize, ny: usize) -> Vec<i64> {
        (0..nx * ny)
            .map(|i| {
                let (x, y) = ((i % nx) as i64, (i / nx) as i64);
                let edge = [x + 1, nx as i64 - x, y + 1, ny as i64 - y]
                    .into_iter()
                    .map(|d| d * d)
                    .min()
                    .unwrap_or(0);
                (0..nx * ny)
                    .filter(|&j| wall[j])
                    .map(|j| {
                        let (a, b) = ((j % nx) as i64 - x, (j / nx) as i64 - y);
                        a * a + b * b
                    })
                    .fold(edge, i64::min)
            })
            .collect()
    }

    #[test]
    fn distance_transform_is_exact() {
        let (nx, ny) = (23, 17);
        let wall: Vec<bool> = (0..nx * ny).map(|i| (i * 7919 + i / 5) % 37 == 0).collect();
        assert_eq!(depth2(&wall, nx, ny), brute(&wall, nx, ny));
        let none = vec![false; nx * ny];
        assert_eq!(depth2(&none, nx, ny), brute(&none, nx, ny));
    }

    #[test]
    fn clipped_segments_stay_inside() {
        let hi = [2.0, 2.0];
        assert_eq!(
            clip([-1.0, 0.5], [3.0, 0.5], [0.0; 2], hi),
            Some(([0.0, 0.5], [2.0, 0.5]))
        );
        assert_eq!(clip([-1.0, 3.0], [-0.5, 5.0], [0.0; 2], hi), None);
        // A diagonal through the corner region: both ends moved onto the box.
        let (a, b) = clip([-1.0, 1.0], [1.0, 3.0], [0.0; 2], hi).unwrap();
        assert!(
            (a[0] - 0.0).abs() < 1e-15 && (a[1] - 2.0).abs() < 1e-15,
            "{a:?}"
        );
        assert_eq!(a, b);
    }
}

//! The grid of a map: its two axes ([`GridAxis`]), its tiles ([`TILE`]) and
//! the shards a cluster job array splits it into ([`Shard`]).

use crate::model::param::{ParamError, ParamSet};
use crate::model::Model;

use super::error::{AxisError, MapError};

/// One axis of a map: `count` values of parameter `name` from `from` to `to`.
#[derive(Clone, Debug, PartialEq)]
pub struct GridAxis {
    /// The parameter.
    pub name: String,
    /// First value.
    pub from: f64,
    /// Last value (may be below `from`).
    pub to: f64,
    /// Number of values (at least 1).
    pub count: usize,
}

impl GridAxis {
    /// Parse `NAME=FROM:TO:COUNT` without knowing the model (see [`parse_for`](Self::parse_for)).
    pub fn parse(text: &str) -> Result<Self, AxisError> {
        let syntax = || AxisError::Syntax {
            text: text.to_string(),
        };
        let (name, range) = text.split_once('=').ok_or_else(syntax)?;
        let name = name.trim();
        let valid_name = !name.is_empty()
            && name.chars().all(|c| c.is_ascii_alphanumeric() || c == '_')
            && !name.starts_with(|c: char| c.is_ascii_digit());
        if !valid_name {
            return Err(syntax());
        }
        let parts: Vec<&str> = range.split(':').map(str::trim).collect();
        let [from, to, count] = parts[..] else {
            return Err(syntax());
        };
        let number = |s: &str| match s.parse::<f64>() {
            Ok(v) if v.is_finite() => Ok(v),
            _ => Err(AxisError::NotFinite {
                text: text.to_string(),
                value: s.to_string(),
            }),
        };
        let (from, to) = (number(from)?, number(to)?);
        let count = match count.parse::<usize>() {
            Ok(n) if n > 0 => n,
            _ => {
                return Err(AxisError::Count {
                    text: text.to_string(),
                    value: count.to_string(),
                })
            }
        };
        Ok(Self {
            name: name.to_string(),
            from,
            to,
            count,
        })
    }

    /// Parse `NAME=FROM:TO:COUNT` for model `M` at `base`: `NAME` must be
    /// one of its run-time parameters ([`ParamSet::names`]).
    pub fn parse_for<M: Model>(base: &M::Params, text: &str) -> Result<Self, AxisError> {
        let axis = Self::parse(text)?;
        axis.check_for::<M>(base)
            .map_err(|source| AxisError::Parameter {
                text: text.to_string(),
                source,
            })?;
        Ok(axis)
    }

    /// Whether the axis's parameter is a run-time parameter of `M` (at `base`).
    pub fn check_for<M: Model>(&self, base: &M::Params) -> Result<(), ParamError> {
        if base.index_of(&self.name).is_some() {
            return Ok(());
        }
        let info = M::info(base);
        let free = base.names().join(", ");
        Err(match info.params.iter().find(|p| p.name == self.name) {
            Some(p) => ParamError::Fixed {
                name: self.name.clone(),
                model: info.name.to_string(),
                value: p.default,
                free,
            },
            None => ParamError::Unknown {
                name: self.name.clone(),
                model: info.name.to_string(),
                known: free,
            },
        })
    }

    /// Value `i` (`0 ≤ i < count`): `from + (to - from) i / (count - 1)`, exactly `to` at the end.
    pub fn value(&self, i: usize) -> f64 {
        if self.count <= 1 || i == 0 {
            self.from
        } else if i + 1 == self.count {
            self.to
        } else {
            self.from + (self.to - self.from) * i as f64 / (self.count - 1) as f64
        }
    }

    /// All values, in order.
    pub fn values(&self) -> Vec<f64> {
        (0..self.count).map(|i| self.value(i)).collect()
    }

    /// `NAME=FROM:TO:COUNT`, which [`parse`](Self::parse) reads back exactly.
    pub fn spec(&self) -> String {
        format!("{}={}:{}:{}", self.name, self.from, self.to, self.count)
    }
}

impl std::fmt::Display for GridAxis {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(&self.spec())
    }
}

/// Number of points of the grid `x × y`.
pub fn grid_len(x: &GridAxis, y: &GridAxis) -> Result<usize, AxisError> {
    x.count
        .checked_mul(y.count)
        .ok_or(AxisError::TooLarge(x.count, y.count))
}

/// Side of a tile, in grid points: the grid is cut into `TILE × TILE`
/// squares (smaller at the top and right edges), numbered row by row. A
/// tile is computed as a unit (the continuation method continues motions
/// between its points), and the tiling does not depend on the shards.
pub const TILE: usize = 16;

/// Tiles per row of a grid `nx` points wide.
pub fn tiles_per_row(nx: usize) -> usize {
    nx.max(1).div_ceil(TILE)
}

/// Number of tiles of an `nx × ny` grid.
pub fn tile_count(nx: usize, ny: usize) -> usize {
    tiles_per_row(nx) * ny.div_ceil(TILE)
}

/// The tile of grid point `index` of a grid `nx` points wide.
pub fn tile_of(index: usize, nx: usize) -> usize {
    let nx = nx.max(1);
    let (ix, iy) = (index % nx, index / nx);
    (iy / TILE) * tiles_per_row(nx) + ix / TILE
}

/// The grid indices of tile `tile` of an `nx × ny` grid, row by row.
pub fn tile_points(tile: usize, nx: usize, ny: usize) -> Vec<usize> {
    let per_row = tiles_per_row(nx);
    let (tx, ty) = (tile % per_row, tile / per_row);
    let xs = tx * TILE..(tx * TILE + TILE).min(nx);
    let ys = ty * TILE..(ty * TILE + TILE).min(ny);
    ys.flat_map(|iy| xs.clone().map(move |ix| iy * nx + ix))
        .collect()
}

/// Part `index` of `count` disjoint parts of a grid: the points of the
/// tiles ([`TILE`]) whose number is `index` mod `count`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Shard {
    /// Which part (`0 ≤ index < count`).
    pub index: usize,
    /// How many parts.
    pub count: usize,
}

impl Shard {
    /// Parse `k/n` (`0 ≤ k < n`).
    pub fn parse(text: &str) -> Result<Self, MapError> {
        let bad = || MapError::BadShard(text.to_string());
        let (k, n) = text.split_once('/').ok_or_else(bad)?;
        let index: usize = k.trim().parse().map_err(|_| bad())?;
        let count: usize = n.trim().parse().map_err(|_| bad())?;
        if count == 0 || index >= count {
            return Err(bad());
        }
        Ok(Self { index, count })
    }

    /// Whether grid point `i` of a grid `nx` points wide belongs to this part.
    pub fn contains(&self, i: usize, nx: usize) -> bool {
        tile_of(i, nx) % self.count == self.index
    }
}

impl std::fmt::Display for Shard {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn axis_values_hit_both_ends() {
        let a = GridAxis::parse("W=0.2:9:45").unwrap();
        assert_eq!(a.value(0), 0.2);
        assert_eq!(a.value(44), 9.0);
        assert_eq!(GridAxis::parse(&a.spec()).unwrap(), a);
        let one = GridAxis::parse("Q0=70:80:1").unwrap();
        assert_eq!(one.values(), vec![70.0]);
    }

    #[test]
    fn tiles_cover_the_grid_once() {
        for (nx, ny) in [(1, 1), (16, 16), (17, 5), (40, 33)] {
            let mut seen = vec![0; nx * ny];
            for t in 0..tile_count(nx, ny) {
                for i in tile_points(t, nx, ny) {
                    assert_eq!(tile_of(i, nx), t);
                    seen[i] += 1;
                }
            }
            assert!(seen.iter().all(|&n| n == 1), "{nx}x{ny}");
        }
    }
}

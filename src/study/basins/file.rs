//! The basin file (see the [module doc](super)): its header
//! ([`BasinHeader`]), one CSV line per start ([`StartResult`]), and the
//! whole file ([`BasinFile`]); written in canonical order atomically (a
//! temporary file beside it, synced, renamed over it), as the map's files are.

use std::fs;
use std::path::Path;

use crate::model::param::ParamSet;
use crate::model::Model;
use crate::study::map::GridAxis;
use crate::study::record::{complete_lines, write_atomic};

use super::error::{io_err, BasinsError};
use super::sample::random_start;

const MAGIC: &str = "# stickslip basins";

/// Where one start (a grid point or a random sample) goes.
#[derive(Clone, Debug, PartialEq)]
pub struct StartResult {
    /// Grid index `iv * nx + ix`; samples follow the grid (`nx · nv + k`).
    pub index: usize,
    /// The start's displacement.
    pub x: f64,
    /// The start's velocity.
    pub v: f64,
    /// The attractor reached: `P_{…}` (with `^N`), `NM`, `stick`,
    /// `chaotic`, `quasi-periodic`, or why none was (`unsettled`, …).
    pub attractor: String,
    /// The largest Lyapunov exponent (per unit time) where the attractor is
    /// not periodic and it was computed.
    pub exponent: Option<f64>,
}

impl StartResult {
    /// The CSV line, with its newline: `index,x,v,"attractor",exponent`.
    pub fn to_line(&self) -> String {
        let exponent = self.exponent.map_or(String::new(), |e| format!("{e:?}"));
        format!(
            "{},{:?},{:?},\"{}\",{exponent}\n",
            self.index,
            self.x,
            self.v,
            self.attractor.replace('"', "'").replace(['\n', '\r'], " ")
        )
    }

    /// Parse a line written by [`to_line`](Self::to_line).
    pub fn parse_line(line: &str) -> Result<Self, String> {
        let line = line.trim_end_matches(['\n', '\r']);
        let (head, rest) = line
            .split_once(",\"")
            .ok_or_else(|| "expected index,x,v,\"attractor\",exponent".to_string())?;
        let (attractor, tail) = rest
            .rsplit_once("\",")
            .ok_or_else(|| "expected index,x,v,\"attractor\",exponent".to_string())?;
        let fields: Vec<&str> = head.split(',').collect();
        let [index, x, v] = fields[..] else {
            return Err(format!(
                "expected 3 fields before the attractor, found {}",
                fields.len()
            ));
        };
        let number = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        };
        Ok(Self {
            index: index
                .parse()
                .map_err(|_| format!("`{index}` is not an index"))?,
            x: number(x)?,
            v: number(v)?,
            attractor: attractor.to_string(),
            exponent: if tail.is_empty() {
                None
            } else {
                Some(number(tail)?)
            },
        })
    }
}

/// What a basin file computes: everything its points depend on.
#[derive(Clone, Debug, PartialEq)]
pub struct BasinHeader {
    /// Model (or scene) name.
    pub model: String,
    /// The grid's displacement axis (`x=FROM:TO:COUNT`).
    pub x: GridAxis,
    /// The grid's velocity axis (`v=FROM:TO:COUNT`).
    pub v: GridAxis,
    /// The stroboscopic phase `W t` of every start.
    pub phase: f64,
    /// Random starts for basin stability.
    pub samples: usize,
    /// Their seed.
    pub seed: u64,
    /// Forcing periods simulated at most from each start.
    pub periods: u32,
    /// Forcing periods of the Lyapunov exponent of an unsettled start (0: none).
    pub lyapunov: u32,
    /// Every run-time parameter, in declaration order.
    pub params: Vec<(String, f64)>,
}

impl BasinHeader {
    /// The header of a basin run of `M` at `params`.
    #[allow(clippy::too_many_arguments)]
    pub fn new<M: Model>(
        params: &M::Params,
        x: &GridAxis,
        v: &GridAxis,
        phase: f64,
        samples: usize,
        seed: u64,
        periods: u32,
        lyapunov: u32,
    ) -> Self {
        Self {
            model: M::info(params).name.to_string(),
            x: x.clone(),
            v: v.clone(),
            phase,
            samples,
            seed,
            periods,
            lyapunov,
            params: params
                .names()
                .iter()
                .enumerate()
                .map(|(i, n)| (n.to_string(), params.get(i)))
                .collect(),
        }
    }

    /// Grid points.
    pub fn grid_len(&self) -> usize {
        self.x.count.saturating_mul(self.v.count)
    }

    /// Grid points and samples.
    pub fn len(&self) -> usize {
        self.grid_len().saturating_add(self.samples)
    }

    /// Whether there is nothing to compute (never, for a checked header).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The start of index `i`: a grid point, or a random sample.
    pub fn start(&self, i: usize) -> (f64, f64) {
        let g = self.grid_len();
        let nx = self.x.count;
        if i < g {
            (self.x.value(i % nx), self.v.value(i / nx))
        } else {
            let span = |a: &GridAxis| (a.from.min(a.to), a.from.max(a.to));
            random_start(self.seed, (i - g) as u64, span(&self.x), span(&self.v))
        }
    }

    /// The two header lines (comment and column names), with newlines.
    pub fn to_lines(&self) -> String {
        let params = self
            .params
            .iter()
            .map(|(n, v)| format!("{n}={v:?}"))
            .collect::<Vec<_>>()
            .join(",");
        format!(
            "{MAGIC} model={} x={} y={} phase={:?} samples={} seed={} periods={} lyapunov={} params={params}\nindex,x,v,attractor,exponent\n",
            self.model, self.x, self.v, self.phase, self.samples, self.seed, self.periods, self.lyapunov
        )
    }

    /// Parse the first header line.
    pub fn parse(line: &str) -> Result<Self, String> {
        let rest = line
            .trim_end()
            .strip_prefix(MAGIC)
            .ok_or_else(|| format!("the first line does not start with `{MAGIC}`"))?;
        let mut model = None;
        let (mut x, mut v, mut phase, mut samples, mut seed) = (None, None, None, None, None);
        let (mut periods, mut lyapunov, mut params) = (None, None, None);
        for token in rest.split_whitespace() {
            let (key, value) = token
                .split_once('=')
                .ok_or_else(|| format!("`{token}` in the header is not KEY=VALUE"))?;
            let bad = || format!("`{token}` in the header is not a valid value");
            match key {
                "model" => model = Some(value.to_string()),
                "x" => x = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "y" => v = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "phase" => phase = Some(value.parse::<f64>().map_err(|_| bad())?),
                "samples" => samples = Some(value.parse::<usize>().map_err(|_| bad())?),
                "seed" => seed = Some(value.parse::<u64>().map_err(|_| bad())?),
                "periods" => periods = Some(value.parse::<u32>().map_err(|_| bad())?),
                "lyapunov" => lyapunov = Some(value.parse::<u32>().map_err(|_| bad())?),
                "params" => {
                    let mut pairs = Vec::new();
                    for pair in value.split(',').filter(|p| !p.is_empty()) {
                        let (n, v) = pair
                            .split_once('=')
                            .ok_or_else(|| format!("`{pair}` in params is not NAME=VALUE"))?;
                        let v: f64 = v
                            .parse()
                            .map_err(|_| format!("`{v}` in params is not a number"))?;
                        pairs.push((n.to_string(), v));
                    }
                    params = Some(pairs);
                }
                other => return Err(format!("unknown header key `{other}`")),
            }
        }
        let missing = |what: &str| format!("the header lacks `{what}=`");
        Ok(Self {
            model: model.ok_or_else(|| missing("model"))?,
            x: x.ok_or_else(|| missing("x"))?,
            v: v.ok_or_else(|| missing("y"))?,
            phase: phase.ok_or_else(|| missing("phase"))?,
            samples: samples.ok_or_else(|| missing("samples"))?,
            seed: seed.ok_or_else(|| missing("seed"))?,
            periods: periods.ok_or_else(|| missing("periods"))?,
            lyapunov: lyapunov.ok_or_else(|| missing("lyapunov"))?,
            params: params.ok_or_else(|| missing("params"))?,
        })
    }

    /// How `other` describes a different run, if it does: the first field that differs.
    pub fn difference(&self, other: &Self) -> Option<String> {
        let show = |h: &Self| h.to_lines().lines().next().unwrap_or_default().to_string();
        if self == other {
            return None;
        }
        let (a, b) = (show(self), show(other));
        let ours: Vec<&str> = a.split_whitespace().collect();
        let theirs: Vec<&str> = b.split_whitespace().collect();
        let differs = ours
            .iter()
            .zip(&theirs)
            .find(|(p, q)| p != q)
            .map(|(p, q)| format!("{q}, not {p}"));
        Some(differs.unwrap_or_else(|| format!("`{b}`, not `{a}`")))
    }

    /// Check that `record` is start `record.index` of this run.
    fn check_record(&self, record: &StartResult) -> Result<(), String> {
        if record.index >= self.len() {
            return Err(format!(
                "index {} is outside the run's {} starts",
                record.index,
                self.len()
            ));
        }
        let (x, v) = self.start(record.index);
        if record.x.to_bits() != x.to_bits() || record.v.to_bits() != v.to_bits() {
            return Err(format!(
                "start {} is at ({:?}, {:?}), but the run puts it at ({x:?}, {v:?})",
                record.index, record.x, record.v
            ));
        }
        Ok(())
    }
}

/// A basin file as read: header, starts in file order, and the length of
/// its complete lines (a trailing line cut short by a kill is not counted).
#[derive(Clone, Debug, PartialEq)]
pub struct BasinFile {
    /// The header.
    pub header: BasinHeader,
    /// The starts, in file order.
    pub starts: Vec<StartResult>,
    /// Bytes of complete lines.
    pub valid_len: u64,
}

impl BasinFile {
    /// Read and check a basin file.
    pub fn read(path: &Path) -> Result<Self, BasinsError> {
        let bytes = fs::read(path).map_err(io_err(path))?;
        Self::parse(path, &bytes)?.ok_or_else(|| BasinsError::Header {
            path: path.to_path_buf(),
            reason: "the file has no complete header line".to_string(),
        })
    }

    /// Parse `bytes` (the contents of `path`); `None` when not even the
    /// header line is complete.
    pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Option<Self>, BasinsError> {
        let complete = complete_lines(bytes).map_err(|line| BasinsError::Corrupt {
            path: path.to_path_buf(),
            line,
            reason: "not UTF-8 text".to_string(),
        })?;
        let mut lines = complete.lines.iter().copied().enumerate();
        let Some((_, first)) = lines.next() else {
            return Ok(None);
        };
        let header = BasinHeader::parse(first).map_err(|reason| BasinsError::Header {
            path: path.to_path_buf(),
            reason,
        })?;
        let mut starts = Vec::new();
        for (k, line) in lines {
            if k == 1 && line.trim_end() == "index,x,v,attractor,exponent" {
                continue;
            }
            let corrupt = |reason: String| BasinsError::Corrupt {
                path: path.to_path_buf(),
                line: k + 1,
                reason,
            };
            let record = StartResult::parse_line(line).map_err(corrupt)?;
            header.check_record(&record).map_err(corrupt)?;
            starts.push(record);
        }
        Ok(Some(Self {
            header,
            starts,
            valid_len: complete.valid_len,
        }))
    }
}

/// Write `header` and `starts` (sorted by index) to `out` atomically.
pub(super) fn write_canonical(
    out: &Path,
    header: &BasinHeader,
    starts: &[StartResult],
) -> Result<(), BasinsError> {
    let mut text = header.to_lines();
    let mut sorted: Vec<&StartResult> = starts.iter().collect();
    sorted.sort_by_key(|p| p.index);
    for p in sorted {
        text.push_str(&p.to_line());
    }
    write_atomic(out, "basins", &text).map_err(|(path, source)| BasinsError::Io { path, source })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_round_trip() {
        let r = StartResult {
            index: 7,
            x: -0.30000000000000004,
            v: 1e-7,
            attractor: "P_{3_33 4_33}^2".into(),
            exponent: None,
        };
        assert_eq!(StartResult::parse_line(&r.to_line()).unwrap(), r);
        let c = StartResult {
            attractor: "chaotic".into(),
            exponent: Some(0.0123),
            ..r
        };
        assert_eq!(StartResult::parse_line(&c.to_line()).unwrap(), c);
    }
}

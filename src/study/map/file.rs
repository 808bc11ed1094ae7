//! The map file format (see the [module doc](super)): the header line
//! ([`MapHeader`]), one CSV line per grid point ([`PointResult`]), and the
//! whole file ([`MapFile`]), written atomically in canonical order.

use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::fs;
use std::path::Path;

use crate::model::param::ParamSet;
use crate::model::Model;
use crate::study::record::{complete_lines, write_atomic};

use super::error::{io_err, MapError};
use super::grid::{GridAxis, Shard};
use super::run::MapMethod;

/// What is known at one grid point.
#[derive(Clone, Debug, PartialEq)]
pub struct PointResult {
    /// Grid index `iy * nx + ix`.
    pub index: usize,
    /// The x-axis parameter's value.
    pub x: f64,
    /// The y-axis parameter's value.
    pub y: f64,
    /// `ok`, `invalid: …`, or the starts that did not settle.
    pub status: String,
    /// The distinct motions found, sorted: `P_{…}` (with `^N` for `N > 1`) or `NM`.
    pub motions: Vec<String>,
}

impl PointResult {
    /// The point's class on the map: its motions joined by ` + `, or, when
    /// none was found, the status's first word (`invalid`, `unsettled`,
    /// `chaotic`, `quasi_periodic`, …; `cycle longer than N` whole).
    pub fn label(&self) -> String {
        if !self.motions.is_empty() {
            return self.motions.join(" + ");
        }
        let s = self.status.as_str();
        let s = s
            .strip_prefix("start ")
            .and_then(|r| r.split_once(": ").map(|(_, rest)| rest))
            .unwrap_or(s);
        if s.starts_with("cycle longer than ") {
            return s.split(" periods").next().unwrap_or(s).to_string();
        }
        s.split([':', ' ', ';'])
            .next()
            .filter(|w| !w.is_empty())
            .unwrap_or("unknown")
            .to_string()
    }

    /// The CSV line, with its newline: `index,x,y,"status","motions"`.
    pub fn to_line(&self) -> String {
        format!(
            "{},{:?},{:?},{},{}\n",
            self.index,
            self.x,
            self.y,
            quote(&self.status),
            quote(&self.motions.join(";"))
        )
    }

    /// Parse a line written by [`to_line`](Self::to_line) (with or without its newline).
    pub fn parse_line(line: &str) -> Result<Self, String> {
        let line = line.strip_suffix('\n').unwrap_or(line);
        let line = line.strip_suffix('\r').unwrap_or(line);
        let fields = split_csv(line)?;
        let [index, x, y, status, motions] = &fields[..] else {
            return Err(format!(
                "expected 5 fields (index,x,y,status,motions), found {}",
                fields.len()
            ));
        };
        let index = index
            .parse::<usize>()
            .map_err(|_| format!("`{index}` is not a grid index"))?;
        let number = |s: &str| {
            s.parse::<f64>()
                .map_err(|_| format!("`{s}` is not a number"))
        };
        Ok(Self {
            index,
            x: number(x)?,
            y: number(y)?,
            status: status.clone(),
            motions: if motions.is_empty() {
                Vec::new()
            } else {
                motions.split(';').map(str::to_string).collect()
            },
        })
    }
}

/// A CSV field in double quotes, inner quotes doubled; line breaks become spaces.
fn quote(s: &str) -> String {
    let mut out = String::with_capacity(s.len() + 2);
    out.push('"');
    for c in s.chars() {
        match c {
            '"' => out.push_str("\"\""),
            '\n' | '\r' => out.push(' '),
            c => out.push(c),
        }
    }
    out.push('"');
    out
}

/// Split one CSV line (RFC 4180 quoting).
fn split_csv(line: &str) -> Result<Vec<String>, String> {
    let mut fields = Vec::new();
    let mut chars = line.chars().peekable();
    loop {
        let mut field = String::new();
        if chars.peek() == Some(&'"') {
            chars.next();
            loop {
                match chars.next() {
                    None => return Err("an unterminated quoted field".to_string()),
                    Some('"') if chars.peek() == Some(&'"') => {
                        chars.next();
                        field.push('"');
                    }
                    Some('"') => break,
                    Some(c) => field.push(c),
                }
            }
            match chars.next() {
                None => {
                    fields.push(field);
                    return Ok(fields);
                }
                Some(',') => fields.push(field),
                Some(c) => return Err(format!("`{c}` after a quoted field")),
            }
        } else {
            loop {
                match chars.next() {
                    None => {
                        fields.push(field);
                        return Ok(fields);
                    }
                    Some(',') => break,
                    Some('"') => return Err("a quote inside an unquoted field".to_string()),
                    Some(c) => field.push(c),
                }
            }
            fields.push(field);
        }
    }
}

/// The first line of a map file: what was computed.
#[derive(Clone, Debug, PartialEq)]
pub struct MapHeader {
    /// Model (or scene) name.
    pub model: String,
    /// For a model loaded from a file at run time, the file's content hash
    /// (`model::loaded::content_hash`): a resume or merge with another
    /// file's model is refused. `None` for a compiled-in model.
    pub source: Option<u64>,
    /// The x axis.
    pub x: GridAxis,
    /// The y axis.
    pub y: GridAxis,
    /// The other run-time parameters, in declaration order.
    pub base: Vec<(String, f64)>,
    /// How the points were classified (`--method`); `None` for a file
    /// written before the header recorded it.
    pub method: Option<MapMethod>,
    /// The part computed, in a shard's file only.
    pub shard: Option<Shard>,
}

const MAGIC: &str = "# stickslip map";

impl MapHeader {
    /// The header of a map of `M` at `base` over `x × y`, its points
    /// classified by `method`.
    pub fn new<M: Model>(
        base: &M::Params,
        x: &GridAxis,
        y: &GridAxis,
        method: MapMethod,
        shard: Option<Shard>,
    ) -> Self {
        let names = base.names();
        let info = M::info(base);
        let model = info.name.to_string();
        let base = names
            .iter()
            .enumerate()
            .filter(|(_, n)| **n != x.name && **n != y.name)
            .map(|(i, n)| (n.to_string(), base.get(i)))
            .collect();
        Self {
            model,
            source: info.source_hash,
            x: x.clone(),
            y: y.clone(),
            base,
            method: Some(method),
            shard: shard.filter(|s| s.count > 1),
        }
    }

    /// Grid points.
    pub fn len(&self) -> usize {
        self.x.count.saturating_mul(self.y.count)
    }

    /// Whether the grid is empty (never, for a parsed header).
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The two header lines (comment and column names), with newlines.
    pub fn to_lines(&self) -> String {
        let base = self
            .base
            .iter()
            .map(|(n, v)| format!("{n}={v}"))
            .collect::<Vec<_>>()
            .join(",");
        let mut s = format!("{MAGIC} model={}", self.model);
        if let Some(hash) = self.source {
            let _ = write!(s, " source={hash:016x}");
        }
        let _ = write!(s, " x={} y={} base={base}", self.x, self.y);
        if let Some(method) = self.method {
            let _ = write!(s, " method={}", method.name());
        }
        if let Some(shard) = self.shard {
            let _ = write!(s, " shard={shard}");
        }
        let _ = write!(
            s,
            "\nindex,{},{},status,motions\n",
            self.x.name, self.y.name
        );
        s
    }

    /// Parse the first header line (the comment).
    pub fn parse(line: &str) -> Result<Self, String> {
        let rest = line
            .trim_end()
            .strip_prefix(MAGIC)
            .ok_or_else(|| format!("the first line does not start with `{MAGIC}`"))?;
        let (mut model, mut x, mut y, mut base, mut shard) = (None, None, None, None, None);
        let mut source = None;
        let mut method = None;
        for token in rest.split_whitespace() {
            let (key, value) = token
                .split_once('=')
                .ok_or_else(|| format!("`{token}` in the header is not KEY=VALUE"))?;
            match key {
                "model" => model = Some(value.to_string()),
                "source" => {
                    source =
                        Some(u64::from_str_radix(value, 16).map_err(|_| {
                            format!("`{value}` in the header is not a content hash")
                        })?)
                }
                "x" => x = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "y" => y = Some(GridAxis::parse(value).map_err(|e| e.to_string())?),
                "base" => {
                    let mut pairs = Vec::new();
                    for pair in value.split(',').filter(|p| !p.is_empty()) {
                        let (n, v) = pair
                            .split_once('=')
                            .ok_or_else(|| format!("`{pair}` in base is not NAME=VALUE"))?;
                        let v: f64 = v
                            .parse()
                            .map_err(|_| format!("`{v}` in base is not a number"))?;
                        pairs.push((n.to_string(), v));
                    }
                    base = Some(pairs);
                }
                "method" => {
                    method = Some(MapMethod::parse(value).ok_or_else(|| {
                        format!("unknown method `{value}` (continuation or simulation)")
                    })?)
                }
                "shard" => shard = Some(Shard::parse(value).map_err(|e| e.to_string())?),
                other => return Err(format!("unknown header key `{other}`")),
            }
        }
        let missing = |what: &str| format!("the header lacks `{what}=`");
        Ok(Self {
            model: model.ok_or_else(|| missing("model"))?,
            source,
            x: x.ok_or_else(|| missing("x"))?,
            y: y.ok_or_else(|| missing("y"))?,
            base: base.ok_or_else(|| missing("base"))?,
            method,
            shard,
        })
    }

    /// How `other` describes a different grid (shards aside), if it does.
    pub(super) fn grid_difference(&self, other: &Self) -> Option<String> {
        if self.model != other.model {
            return Some(format!("model `{}`, not `{}`", other.model, self.model));
        }
        if self.source != other.source {
            let show = |h: Option<u64>| match h {
                Some(h) => format!("the model file of content hash {h:016x}"),
                None => "the compiled-in model".to_string(),
            };
            return Some(format!(
                "{}, not {}: a different model file",
                show(other.source),
                show(self.source)
            ));
        }
        if self.x != other.x {
            return Some(format!("x axis {}, not {}", other.x, self.x));
        }
        if self.y != other.y {
            return Some(format!("y axis {}, not {}", other.y, self.y));
        }
        if self.base != other.base {
            let show = |b: &[(String, f64)]| {
                b.iter()
                    .map(|(n, v)| format!("{n}={v}"))
                    .collect::<Vec<_>>()
                    .join(",")
            };
            return Some(format!(
                "parameters {}, not {}",
                show(&other.base),
                show(&self.base)
            ));
        }
        // Two methods in one file would mix two classifications.
        if self.method != other.method {
            let show = |m: Option<MapMethod>| {
                m.map_or(
                    "unrecorded (a file from before the header recorded it)",
                    |m| m.name(),
                )
            };
            return Some(format!(
                "method {}, not {} (run it with the same --method)",
                show(other.method),
                show(self.method)
            ));
        }
        None
    }

    /// Check that `record` is grid point `record.index` of this map (and of its shard).
    fn check_record(&self, record: &PointResult) -> Result<(), String> {
        if record.index >= self.len() {
            return Err(format!(
                "index {} is outside the {}-point grid",
                record.index,
                self.len()
            ));
        }
        if let Some(shard) = self.shard {
            if !shard.contains(record.index, self.x.count) {
                return Err(format!(
                    "index {} does not belong to shard {shard}",
                    record.index
                ));
            }
        }
        let nx = self.x.count;
        let (x, y) = (
            self.x.value(record.index % nx),
            self.y.value(record.index / nx),
        );
        if record.x.to_bits() != x.to_bits() || record.y.to_bits() != y.to_bits() {
            return Err(format!(
                "point {} is at ({:?}, {:?}), but the grid puts it at ({x:?}, {y:?})",
                record.index, record.x, record.y
            ));
        }
        Ok(())
    }
}

/// A map file as read: its header and points (in file order).
#[derive(Clone, Debug, PartialEq)]
pub struct MapFile {
    /// The header.
    pub header: MapHeader,
    /// The points, in file order.
    pub points: Vec<PointResult>,
    /// Bytes of complete lines: a trailing line without newline (a write cut short) is not counted.
    pub valid_len: u64,
    /// Whether such a partial trailing line was dropped.
    pub dropped_partial: bool,
}

impl MapFile {
    /// Read and check a map file: its header, every complete line (a partial
    /// last line, left by a killed run, is dropped), each point on the grid.
    pub fn read(path: &Path) -> Result<Self, MapError> {
        let bytes = fs::read(path).map_err(io_err(path))?;
        Self::parse(path, &bytes)?.ok_or_else(|| MapError::Header {
            path: path.to_path_buf(),
            reason: "the file has no complete header line".to_string(),
        })
    }

    /// Parse `bytes` (the contents of `path`); `None` when not even the
    /// header line is complete. A partial last line may end inside a
    /// character: only complete lines must be UTF-8.
    pub(super) fn parse(path: &Path, bytes: &[u8]) -> Result<Option<Self>, MapError> {
        let complete = complete_lines(bytes).map_err(|line| MapError::Corrupt {
            path: path.to_path_buf(),
            line,
            reason: "not UTF-8 text".to_string(),
        })?;
        let mut lines = complete.lines.iter().copied().enumerate();
        let Some((_, first)) = lines.next() else {
            return Ok(None);
        };
        let header = MapHeader::parse(first).map_err(|reason| MapError::Header {
            path: path.to_path_buf(),
            reason,
        })?;
        let columns = format!("index,{},{},status,motions", header.x.name, header.y.name);
        let mut points = Vec::new();
        for (k, line) in lines {
            let corrupt = |reason: String| MapError::Corrupt {
                path: path.to_path_buf(),
                line: k + 1,
                reason,
            };
            if k == 1 && line.trim_end() == columns {
                continue;
            }
            let record = PointResult::parse_line(line).map_err(corrupt)?;
            header.check_record(&record).map_err(corrupt)?;
            points.push(record);
        }
        Ok(Some(Self {
            header,
            points,
            valid_len: complete.valid_len,
            dropped_partial: complete.dropped_partial,
        }))
    }
}

/// Write `header` and `points` (sorted by index) to `out` atomically: a
/// temporary file beside it, synced, renamed over it.
pub(super) fn write_canonical(
    out: &Path,
    header: &MapHeader,
    points: &[PointResult],
) -> Result<(), MapError> {
    let mut text = header.to_lines();
    let mut sorted: Vec<&PointResult> = points.iter().collect();
    sorted.sort_by_key(|p| p.index);
    for p in sorted {
        text.push_str(&p.to_line());
    }
    write_atomic(out, "map", &text).map_err(|(path, source)| MapError::Io { path, source })
}

/// Merge records into `by_index`; identical duplicates are kept once, different ones collected.
pub(super) fn insert_all(
    by_index: &mut BTreeMap<usize, PointResult>,
    points: Vec<PointResult>,
    conflicts: &mut Vec<usize>,
) {
    for p in points {
        match by_index.get(&p.index) {
            Some(q) if q.to_line() != p.to_line() => conflicts.push(p.index),
            Some(_) => {}
            None => {
                by_index.insert(p.index, p);
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn lines_round_trip() {
        let p = PointResult {
            index: 12,
            x: 3.4000000000000004,
            y: 1e-7,
            status: "start 2: error (say \"no\", twice)".to_string(),
            motions: vec!["NM".to_string(), "P_{3_33 4_33}^2".to_string()],
        };
        let line = p.to_line();
        let q = PointResult::parse_line(&line).unwrap();
        assert_eq!(p, q);
        assert_eq!(q.to_line(), line);
        let empty = PointResult {
            motions: Vec::new(),
            ..p
        };
        assert_eq!(PointResult::parse_line(&empty.to_line()).unwrap(), empty);
    }

    #[test]
    fn labels() {
        let mut p = PointResult {
            index: 0,
            x: 0.0,
            y: 0.0,
            status: "start 1: unsettled (600 periods); start 2: unsettled (600 periods)".into(),
            motions: Vec::new(),
        };
        assert_eq!(p.label(), "unsettled");
        p.status = "start 1: chaotic (lambda1 = 9.7e-2 +- 3.0e-3); start 2: chaotic (…)".into();
        assert_eq!(p.label(), "chaotic");
        p.status = "start 1: cycle longer than 32 periods (lambda1 = -1.0e-3 +- 1.0e-4)".into();
        assert_eq!(p.label(), "cycle longer than 32");
        p.status = "start 1: quasi_periodic (lambda1 = 1.0e-5 +- 1.0e-4)".into();
        assert_eq!(p.label(), "quasi_periodic");
        p.status = "invalid: the forcing frequency is 0; it must be positive".into();
        assert_eq!(p.label(), "invalid");
        p.motions = vec!["NM".into(), "P_{3_33 4_33}".into()];
        assert_eq!(p.label(), "NM + P_{3_33 4_33}");
    }
}

//! The bifurcation diagram of a sweep, in the style of the paper's Figs. 9–10:
//! switching phase `W t mod 2π` and switching displacement against the
//! parameter, the eigenvalues' moduli and real parts; one colour per
//! structure, transitions as dashed vertical lines.
//!
//! Transitions crowd (several within a pixel where a motion grazes and
//! sticks in turn), so they are numbered in the order of the parameter: the
//! numbers stand over the upper panels, stacked in rows so that no two
//! overlap ([`tags`]; transitions within a pixel share one tag, `3–6`), and
//! a key under the panels lists each one in full — value, kind, the motions
//! on either side, the boundary — after the legend of the structures.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::layout::{line_height, stack, text_width, Rect};
use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::palette::category;
use super::{
    pixels, save, DrawError, Figure, AXIS_SIZE, CAPTION_SIZE, FAMILY, LIGHT_GRID, REFERENCE_GREY,
    TICK_SIZE, TITLE_SIZE,
};
use crate::study::sweep::{MotionSummary, Sweep, Transition, TransitionKind};

/// Panel titles, in drawing order.
pub const SWEEP_TITLES: [&str; 4] = [
    "switching phase W t mod 2π",
    "switching displacement x",
    "eigenvalue moduli |λ|",
    "eigenvalue real parts Re λ",
];

const WIDTH: u32 = 1200;
/// Height of the title and the four panels.
const PANELS_HEIGHT: u32 = 1000;
/// Margin around the key under the panels.
const KEY_MARGIN: i32 = 24;
/// Text size of the tags and the key.
const KEY_SIZE: u32 = 12;
/// Transitions closer than this (pixels) share a tag.
const SAME_PIXEL: i32 = 2;
/// Room between tags in a row (pixels).
const TAG_GAP: i32 = 4;

fn kind_name(k: TransitionKind) -> &'static str {
    match k {
        TransitionKind::Grazing => "grazing (GB)",
        TransitionKind::StickOnset => "stick onset",
        TransitionKind::StickVanishing => "stick vanishing",
        TransitionKind::PassableOnset => "passable onset",
        TransitionKind::Fold => "fold (λ = 1)",
        TransitionKind::BranchPoint => "branch point (λ = 1)",
        TransitionKind::PeriodDoubling => "period doubling (λ = −1)",
        TransitionKind::NeimarkSacker => "Neimark–Sacker (|λ| = 1)",
    }
}

/// `Sigma3` as `Σ3`.
fn boundary_name(label: &str) -> String {
    label
        .strip_prefix("Sigma")
        .map_or_else(|| label.to_string(), |n| format!("Σ{n}"))
}

/// A transition's line in the key.
fn describe(param: &str, t: &Transition) -> String {
    let on = t
        .boundary
        .as_deref()
        .map_or_else(String::new, |b| format!(" on {}", boundary_name(b)));
    format!(
        "{param} = {:.6}  {}: {} → {}{on}",
        t.value,
        kind_name(t.kind),
        t.from,
        t.to
    )
}

/// A tag over a panel: the numbers of one or more transitions.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Tag {
    /// `7`, `7,8` or `7–12`.
    pub text: String,
    /// The first and last transition numbered (1-based).
    pub numbers: (usize, usize),
    /// The pixel column of the first one's line.
    pub line: i32,
    /// The tag's box. From [`tags`], `y` counts rows upwards from the
    /// panel's top edge (row `r` spans `-(r + 1) h .. -r h` for the row
    /// height `h`); from [`SweepFigure::placed`], pixels of the image.
    pub rect: Rect,
}

/// The tags of transitions whose lines stand at pixel columns `lines`
/// (numbered 1, 2, … in this order, which is increasing), over a panel
/// spanning `[left, right)`: runs within `SAME_PIXEL` of their first share
/// a tag, and tags are stacked in rows ([`stack`]) so none overlaps another.
pub fn tags(lines: &[i32], left: i32, right: i32) -> Vec<Tag> {
    let mut groups: Vec<(usize, usize, i32)> = Vec::new();
    for (i, &x) in lines.iter().enumerate() {
        match groups.last_mut() {
            Some((_, last, first_x)) if x - *first_x <= SAME_PIXEL => *last = i + 1,
            _ => groups.push((i + 1, i + 1, x)),
        }
    }
    let texts: Vec<String> = groups
        .iter()
        .map(|&(a, b, _)| match b - a {
            0 => format!("{a}"),
            1 => format!("{a},{b}"),
            _ => format!("{a}–{b}"),
        })
        .collect();
    let widths: Vec<i32> = texts.iter().map(|t| text_width(t, KEY_SIZE)).collect();
    let centres: Vec<i32> = groups.iter().map(|g| g.2).collect();
    let h = line_height(KEY_SIZE);
    stack(&centres, &widths, left, right, TAG_GAP)
        .into_iter()
        .zip(groups.iter().zip(texts).zip(&widths))
        .map(|((x0, row), ((&(a, b, x), text), &w))| Tag {
            text,
            numbers: (a, b),
            line: x,
            rect: Rect::at(x0, -(row as i32 + 1) * h, (w, h)),
        })
        .collect()
}

/// The bifurcation diagram of a sweep.
pub struct SweepFigure<'a> {
    sweep: &'a Sweep,
    title: &'a str,
    /// Structures in order of first appearance (their colours' order).
    names: Vec<String>,
    /// Indices of the transitions in the order of the parameter.
    order: Vec<usize>,
    structures: (Legend, LegendLayout),
    key: (Legend, LegendLayout),
}

impl<'a> SweepFigure<'a> {
    /// The figure of `sweep`, with `title` on top.
    pub fn new(sweep: &'a Sweep, title: &'a str) -> Self {
        let mut names: Vec<String> = Vec::new();
        for p in &sweep.points {
            for m in &p.motions {
                if m.structure != "NM" && !names.contains(&m.structure) {
                    names.push(m.structure.clone());
                }
            }
        }
        let mut order: Vec<usize> = (0..sweep.transitions.len()).collect();
        order.sort_by(|&a, &b| {
            sweep.transitions[a]
                .value
                .total_cmp(&sweep.transitions[b].value)
        });
        let width = WIDTH as i32 - 2 * KEY_MARGIN;
        let structures = Legend::new(
            Some("structures".to_string()),
            names
                .iter()
                .enumerate()
                .map(|(k, n)| Entry::new(Mark::Dot(category(k)), n.clone()))
                .collect(),
            KEY_SIZE,
            false,
        );
        let key = Legend::new(
            Some("transitions (numbered over the upper panels)".to_string()),
            order
                .iter()
                .enumerate()
                .map(|(k, &i)| {
                    let t = &sweep.transitions[i];
                    Entry::new(
                        Mark::Tag(format!("{}", k + 1)),
                        describe(sweep.param.as_str(), t),
                    )
                })
                .collect(),
            KEY_SIZE,
            false,
        );
        let structures_layout = structures.layout(width);
        let key_layout = key.layout(width);
        Self {
            sweep,
            title,
            names,
            order,
            structures: (structures, structures_layout),
            key: (key, key_layout),
        }
    }

    /// Where the two legends go under the panels (upper-left corners).
    fn key_origins(&self) -> [(i32, i32); 2] {
        let y = PANELS_HEIGHT as i32 + KEY_MARGIN / 2;
        let below = if self.names.is_empty() {
            y
        } else {
            y + self.structures.1.bounds.y1 + KEY_MARGIN / 2
        };
        [(KEY_MARGIN, y), (KEY_MARGIN, below)]
    }
}

/// Draw `sweep` into `path` (SVG or PNG by extension).
pub fn plot_sweep(sweep: &Sweep, title: &str, path: &Path) -> Result<(), String> {
    save(&SweepFigure::new(sweep, title), path)
}

type Getter = fn(&MotionSummary) -> Vec<f64>;
const GETTERS: [Getter; 4] = [
    |m| m.points.iter().map(|p| p.phase).collect(),
    |m| m.points.iter().map(|p| p.x).collect(),
    |m| m.eigenvalues.iter().map(|e| e[0].hypot(e[1])).collect(),
    |m| m.eigenvalues.iter().map(|e| e[0]).collect(),
];

impl Figure for SweepFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let bottom = if self.order.is_empty() {
            self.key_origins()[0].1 + self.structures.1.bounds.y1
        } else {
            self.key_origins()[1].1 + self.key.1.bounds.y1
        };
        (
            WIDTH,
            (bottom + KEY_MARGIN).max(PANELS_HEIGHT as i32) as u32,
        )
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        self.draw_all(root).map(|_| ())
    }
}

impl SweepFigure<'_> {
    /// The tags over the upper panels as drawn, in pixels of the image
    /// (one list per panel), and the boxes of the key's texts and marks.
    pub fn placed(&self) -> Result<(Vec<Vec<Tag>>, Vec<Rect>), DrawError> {
        let mut svg = String::new();
        let tags = {
            let root = SVGBackend::with_string(&mut svg, self.size()).into_drawing_area();
            self.draw_all(&root)?
        };
        let [s, k] = self.key_origins();
        let structures = self.structures.1.boxes().map(|r| r.shifted(s.0, s.1));
        let key = self.key.1.boxes().map(|r| r.shifted(k.0, k.1));
        Ok((tags, structures.chain(key).collect()))
    }

    /// Draw the figure; the tags over the upper panels, in pixels of `root`.
    fn draw_all<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<Vec<Vec<Tag>>, DrawError> {
        let sweep = self.sweep;
        let mut placed = Vec::new();
        root.fill(&WHITE)?;
        let (panels, _) = root.split_vertically(PANELS_HEIGHT);
        let body = panels.titled(self.title, (FAMILY, TITLE_SIZE).into_font())?;
        let areas = body.split_evenly((2, 2));
        let lo = sweep.points.first().map_or(0.0, |p| p.value);
        let hi = sweep.points.last().map_or(1.0, |p| p.value);
        let values: Vec<f64> = self
            .order
            .iter()
            .map(|&i| sweep.transitions[i].value)
            .collect();
        for (panel, area) in areas.iter().enumerate() {
            let get = GETTERS[panel];
            let mut ys: Vec<f64> = Vec::new();
            for p in &sweep.points {
                for m in &p.motions {
                    ys.extend(get(m).into_iter().filter(|v| v.is_finite()));
                }
            }
            let (mut y0, mut y1) = ys
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
                    (a.min(v), b.max(v))
                });
            if panel == 0 {
                (y0, y1) = (0.0, std::f64::consts::TAU);
            }
            if !(y0.is_finite() && y1.is_finite()) || y0 >= y1 {
                (y0, y1) = (y0.min(0.0) - 1.0, y1.max(0.0) + 1.0);
            }
            let pad = 0.05 * (y1 - y0);
            let below = area
                .margin(12, 12, 12, 12)
                .titled(SWEEP_TITLES[panel], (FAMILY, CAPTION_SIZE).into_font())?;
            let builder = |top: u32| {
                let mut b = ChartBuilder::on(&below);
                b.margin_top(top)
                    .x_label_area_size(40)
                    .y_label_area_size(60);
                b
            };
            // Over the upper panels, the transitions' tags: the columns of
            // their lines from a chart laid out alike (nothing drawn), the
            // room for their rows kept above the plot.
            let tags = if panel < 2 && !values.is_empty() {
                let probe = builder(0).build_cartesian_2d(lo..hi, 0.0..1.0)?;
                let columns: Vec<i32> = values
                    .iter()
                    .map(|&v| probe.backend_coord(&(v, 0.0)).0)
                    .collect();
                let (left, right) = (pixels(&below).x0, pixels(&below).x1);
                tags(&columns, left, right)
            } else {
                Vec::new()
            };
            let band = tags.iter().map(|t| -t.rect.y0).max().map_or(0, |h| h + 2);
            let mut chart =
                builder(band as u32).build_cartesian_2d(lo..hi, (y0 - pad)..(y1 + pad))?;
            chart
                .configure_mesh()
                .light_line_style(LIGHT_GRID)
                .x_desc(sweep.param.as_str())
                .label_style((FAMILY, TICK_SIZE).into_font())
                .axis_desc_style((FAMILY, AXIS_SIZE).into_font())
                .draw()?;
            if panel >= 2 {
                let level = if panel == 2 { 1.0 } else { 0.0 };
                chart.draw_series(DashedLineSeries::new(
                    vec![(lo, level), (hi, level)],
                    5,
                    4,
                    BLACK.stroke_width(1),
                ))?;
            }
            for &v in &values {
                chart.draw_series(DashedLineSeries::new(
                    vec![(v, y0 - pad), (v, y1 + pad)],
                    6,
                    4,
                    REFERENCE_GREY.stroke_width(1),
                ))?;
            }
            for (k, name) in self.names.iter().enumerate() {
                let c = category(k);
                let pts: Vec<(f64, f64)> = sweep
                    .points
                    .iter()
                    .flat_map(|p| {
                        p.motions
                            .iter()
                            .filter(|m| &m.structure == name)
                            .flat_map(move |m| get(m).into_iter().map(move |y| (p.value, y)))
                    })
                    .filter(|(_, y)| y.is_finite())
                    .collect();
                chart.draw_series(
                    pts.into_iter()
                        .map(|(x, y)| Circle::new((x, y), 2, c.filled())),
                )?;
            }
            let top = pixels(chart.plotting_area()).y0;
            // Leaders first: a tag's box, drawn over them, hides where one
            // passes behind a lower tag.
            for t in &tags {
                let r = t.rect.shifted(0, top);
                root.draw(&PathElement::new(
                    vec![(t.line, top), ((r.x0 + r.x1) / 2, r.y1 - 1)],
                    REFERENCE_GREY.stroke_width(1),
                ))?;
            }
            for t in &tags {
                let r = t.rect.shifted(0, top);
                root.draw(&Rectangle::new(
                    [(r.x0, r.y0), (r.x1, r.y1)],
                    WHITE.filled(),
                ))?;
                root.draw(&Text::new(
                    t.text.clone(),
                    ((r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2),
                    (FAMILY, KEY_SIZE)
                        .into_font()
                        .color(&BLACK)
                        .pos(Pos::new(HPos::Center, VPos::Center)),
                ))?;
            }
            if panel < 2 {
                placed.push(
                    tags.into_iter()
                        .map(|t| Tag {
                            rect: t.rect.shifted(0, top),
                            ..t
                        })
                        .collect(),
                );
            }
        }
        let [s, k] = self.key_origins();
        if !self.names.is_empty() {
            self.structures.0.draw(&self.structures.1, root, s)?;
        }
        if !self.order.is_empty() {
            self.key.0.draw(&self.key.1, root, k)?;
        }
        Ok(placed)
    }
}

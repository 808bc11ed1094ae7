//! The bifurcation diagram of a sweep, in the style of the paper's Figs. 9–10:
//! switching phase `W t mod 2π` and switching displacement against the
//! parameter, the eigenvalues' moduli and real parts; one colour per
//! structure, transitions as dashed vertical lines.
//!
//! Each branch is a curve through its points in arclength order
//! ([`super::branch`]): solid where the motion is stable, thin and dashed
//! where it is unstable; the motions found at the grid points are dots
//! (rings when unstable). Every bifurcation is marked in each panel by the
//! symbol of its kind ([`symbol_of`]) and labelled (`F1`, `PD2`, …, numbered
//! in the order of the parameter) next to its mark, clear of every other
//! label and mark ([`place_near`]); a key lists each one in full.
//!
//! Transitions crowd (several within a pixel where a motion grazes and
//! sticks in turn), so they are numbered in the order of the parameter: the
//! numbers stand over the upper panels, stacked in rows so that no two
//! overlap ([`tags`]; transitions within a pixel share one tag, `3–6`). The
//! text output of `sweep` lists them with the same numbers, in full.
//!
//! The same drawing serves two views ([`View`]): the bifurcation diagram
//! and the frequency response (each motion's amplitude against the
//! parameter), whose panels [`super::sweep_panels`] lists.

use std::path::Path;

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::branch::{curves, Stroke};
use super::layout::{line_height, place_near, stack, text_width, Rect};
use super::legend::{Entry, Legend, LegendLayout, Mark};
use super::palette::category;
pub use super::sweep_panels::View;
use super::sweep_panels::{Panel, Range};
use super::symbol::{Symbol, INK, RADIUS};
use super::{
    pixels, save, DrawError, Figure, AXIS_SIZE, CAPTION_SIZE, FAMILY, LIGHT_GRID, REFERENCE_GREY,
    TICK_SIZE, TITLE_SIZE,
};
use crate::study::sweep::{BifurcationSummary, Sweep, TransitionKind};
use stickslip_codegen::structure::with_periods;

const WIDTH: u32 = 1200;
/// Margin around the key under the panels.
const KEY_MARGIN: i32 = 24;
/// Text size of the tags and the key.
const KEY_SIZE: u32 = 12;
/// Transitions closer than this (pixels) share a tag.
const SAME_PIXEL: i32 = 2;
/// Room between tags in a row (pixels).
const TAG_GAP: i32 = 4;
/// Room kept between a bifurcation's label and other labels and marks.
const LABEL_GAP: i32 = 2;
/// Width of a branch's stable stretches (pixels).
pub const STABLE_WIDTH: u32 = 2;
/// Width of a branch's unstable, dashed stretches (pixels).
pub const UNSTABLE_WIDTH: u32 = 1;
/// Dark grey of the key's sample lines.
const SAMPLE_GREY: RGBColor = RGBColor(70, 70, 70);

/// The symbol marking a bifurcation of `kind`, and its label's prefix.
pub fn symbol_of(kind: TransitionKind) -> (Symbol, &'static str) {
    match kind {
        TransitionKind::Fold => (Symbol::Square, "F"),
        TransitionKind::BranchPoint => (Symbol::Diamond, "BP"),
        TransitionKind::PeriodDoubling => (Symbol::Triangle, "PD"),
        TransitionKind::NeimarkSacker => (Symbol::Ring, "NS"),
        TransitionKind::Grazing => (Symbol::Cross, "G"),
        TransitionKind::StickOnset => (Symbol::Cross, "SO"),
        TransitionKind::StickVanishing => (Symbol::Cross, "SV"),
        TransitionKind::PassableOnset => (Symbol::Cross, "PO"),
        TransitionKind::SteadySliding => (Symbol::Ring, "H"),
    }
}

/// What each kind of bifurcation is, for the key.
fn kind_meaning(kind: TransitionKind) -> &'static str {
    match kind {
        TransitionKind::Fold => "fold: eigenvalue +1 where the branch turns back",
        TransitionKind::BranchPoint => "branch point: eigenvalue +1, other branches cross",
        TransitionKind::PeriodDoubling => "period doubling: eigenvalue −1, twice the period born",
        TransitionKind::NeimarkSacker => "Neimark–Sacker: a complex pair on |λ| = 1",
        _ => kind_name(kind),
    }
}

/// A bifurcation's line in the key.
fn describe_bifurcation(param: &str, b: &BifurcationSummary) -> String {
    let born = if b.born.is_empty() {
        String::new()
    } else {
        let ids: Vec<String> = b.born.iter().map(|i| format!("#{i}")).collect();
        format!(", born {}", ids.join(" "))
    };
    format!(
        "{param} = {:.8}  {} on {} (branch #{}), λ = {:+.4}{:+.4}i{born}",
        b.value,
        kind_name(b.kind),
        with_periods(&b.structure, b.n),
        b.branch,
        b.eigenvalue[0],
        b.eigenvalue[1],
    )
}

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
        TransitionKind::SteadySliding => "steady sliding changes stability",
    }
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

/// A bifurcation's label in one panel, as drawn.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Label {
    /// `F1`, `PD2`, …
    pub text: String,
    /// The panel (in the order of [`View::panels`]).
    pub panel: usize,
    /// The box of the bifurcation's mark, pixels of the image.
    pub mark: Rect,
    /// The label's box, pixels of the image.
    pub rect: Rect,
    /// The panel's plotting area, pixels of the image.
    pub plot: Rect,
}

/// The bifurcation diagram of a sweep.
pub struct SweepFigure<'a> {
    sweep: &'a Sweep,
    title: &'a str,
    /// Whether unstable stretches and motions are drawn.
    unstable: bool,
    /// Which panels.
    view: View,
    /// Structures in order of first appearance (their colours' order).
    names: Vec<String>,
    /// Indices of the transitions in the order of the parameter.
    order: Vec<usize>,
    /// Indices of the bifurcations in the order of the parameter.
    marks: Vec<usize>,
    /// The legends under the panels, top to bottom (only those with entries).
    legends: Vec<(Legend, LegendLayout)>,
}

impl<'a> SweepFigure<'a> {
    /// The figure of `sweep`, with `title` on top, unstable parts included.
    pub fn new(sweep: &'a Sweep, title: &'a str) -> Self {
        Self::showing(sweep, title, true)
    }

    /// The figure of `sweep`; with `unstable` false, without the branches'
    /// unstable stretches and the unstable motions at the grid points.
    pub fn showing(sweep: &'a Sweep, title: &'a str, unstable: bool) -> Self {
        Self::view(sweep, title, unstable, View::Diagram)
    }

    /// The figure of `sweep` in `view`.
    pub fn view(sweep: &'a Sweep, title: &'a str, unstable: bool, view: View) -> Self {
        let mut names: Vec<String> = Vec::new();
        // NM has no switching points, but an amplitude.
        let mut note = |name: &str| {
            if (name != "NM" || view == View::Frc) && !names.iter().any(|n| n == name) {
                names.push(name.to_string());
            }
        };
        for p in &sweep.points {
            for m in p.motions.iter().filter(|m| unstable || m.stable) {
                note(&m.structure);
            }
        }
        for b in &sweep.branches {
            if b.points.iter().any(|q| unstable || q.stable) {
                note(&b.structure);
            }
        }
        let by_value = |values: Vec<f64>| {
            let mut order: Vec<usize> = (0..values.len()).collect();
            order.sort_by(|&a, &b| values[a].total_cmp(&values[b]));
            order
        };
        let order = by_value(sweep.transitions.iter().map(|t| t.value).collect());
        let marks = by_value(sweep.bifurcations.iter().map(|b| b.value).collect());
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
        let mut lines = Vec::new();
        let drawn = |stable: bool| {
            sweep
                .branches
                .iter()
                .any(|b| b.points.iter().any(|q| q.stable == stable))
        };
        let dots = |stable: bool| {
            sweep
                .points
                .iter()
                .any(|p| p.motions.iter().any(|m| m.stable == stable))
        };
        if drawn(true) {
            lines.push(Entry::new(
                Mark::Line(SAMPLE_GREY),
                "branch, stable (a dot: a motion at a grid point)",
            ));
        }
        if unstable && drawn(false) {
            lines.push(Entry::new(Mark::Dashed(SAMPLE_GREY), "branch, unstable"));
        }
        if unstable && dots(false) {
            lines.push(Entry::new(
                Mark::Hollow(SAMPLE_GREY),
                "an unstable motion at a grid point",
            ));
        }
        let mut kinds: Vec<TransitionKind> = Vec::new();
        for b in &sweep.bifurcations {
            if !kinds.contains(&b.kind) {
                kinds.push(b.kind);
            }
        }
        kinds.sort_by_key(|&k| symbol_of(k).1);
        for k in kinds {
            let (symbol, prefix) = symbol_of(k);
            lines.push(Entry::new(
                Mark::Symbol(symbol),
                format!("{prefix}  {}", kind_meaning(k)),
            ));
        }
        let lines = Legend::new(Some("lines and marks".to_string()), lines, KEY_SIZE, false);
        let bifurcations = Legend::new(
            Some("bifurcations (labelled in the panels)".to_string()),
            marks
                .iter()
                .enumerate()
                .map(|(k, &i)| {
                    let b = &sweep.bifurcations[i];
                    Entry::new(
                        Mark::Tag(format!("{}{}", symbol_of(b.kind).1, k + 1)),
                        describe_bifurcation(&sweep.param, b),
                    )
                })
                .collect(),
            KEY_SIZE,
            false,
        );
        let legends = [structures, lines, bifurcations]
            .into_iter()
            .filter(|l| !l.entries.is_empty())
            .map(|l| {
                let layout = l.layout(width);
                (l, layout)
            })
            .collect();
        Self {
            sweep,
            title,
            unstable,
            view,
            names,
            order,
            marks,
            legends,
        }
    }

    /// Where the legends go under the panels (upper-left corners).
    fn key_origins(&self) -> Vec<(i32, i32)> {
        let mut y = self.view.panels_height() as i32 + KEY_MARGIN / 2;
        self.legends
            .iter()
            .map(|(_, layout)| {
                let at = (KEY_MARGIN, y);
                y += layout.bounds.y1 + KEY_MARGIN / 2;
                at
            })
            .collect()
    }

    /// The label of the `k`-th bifurcation in the order of the parameter.
    fn label(&self, k: usize) -> String {
        let b = &self.sweep.bifurcations[self.marks[k]];
        format!("{}{}", symbol_of(b.kind).1, k + 1)
    }
}

/// Draw `sweep` in `view` into `path` (SVG or PNG by extension); with
/// `unstable` false, without its unstable parts.
pub fn plot_sweep(
    sweep: &Sweep,
    title: &str,
    path: &Path,
    unstable: bool,
    view: View,
) -> Result<(), String> {
    save(&SweepFigure::view(sweep, title, unstable, view), path)
}

impl Figure for SweepFigure<'_> {
    fn size(&self) -> (u32, u32) {
        let panels = self.view.panels_height() as i32;
        let bottom = self
            .key_origins()
            .last()
            .zip(self.legends.last())
            .map_or(panels, |(o, (_, l))| o.1 + l.bounds.y1);
        (WIDTH, (bottom + KEY_MARGIN).max(panels) as u32)
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> Result<(), DrawError> {
        self.draw_all(root).map(|_| ())
    }
}

/// The smallest and largest of `values`, ignoring non-finite ones.
fn extent(values: impl Iterator<Item = f64>) -> (f64, f64) {
    values
        .filter(|v| v.is_finite())
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), v| {
            (a.min(v), b.max(v))
        })
}

impl SweepFigure<'_> {
    /// The tags over the upper panels as drawn, in pixels of the image
    /// (one list per panel), and the boxes of the key's texts and marks.
    pub fn placed(&self) -> Result<(Vec<Vec<Tag>>, Vec<Rect>), DrawError> {
        let (tags, _) = self.draw_to_string()?;
        let key = self
            .legends
            .iter()
            .zip(self.key_origins())
            .flat_map(|((_, layout), o)| layout.boxes().map(move |r| r.shifted(o.0, o.1)))
            .collect();
        Ok((tags, key))
    }

    /// The bifurcations' labels as drawn, panel by panel, each in the order
    /// of the parameter.
    pub fn labels(&self) -> Result<Vec<Label>, DrawError> {
        Ok(self.draw_to_string()?.1)
    }

    fn draw_to_string(&self) -> Result<(Vec<Vec<Tag>>, Vec<Label>), DrawError> {
        let mut svg = String::new();
        let root = SVGBackend::with_string(&mut svg, self.size()).into_drawing_area();
        self.draw_all(&root)
    }

    /// Draw the figure; the tags over the upper panels and the
    /// bifurcations' labels, in pixels of `root`.
    fn draw_all<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> Result<(Vec<Vec<Tag>>, Vec<Label>), DrawError> {
        let sweep = self.sweep;
        let shown = |stable: bool| self.unstable || stable;
        let mut placed = Vec::new();
        let mut labels = Vec::new();
        root.fill(&WHITE)?;
        let (panels, _) = root.split_vertically(self.view.panels_height());
        let body = panels.titled(self.title, (FAMILY, TITLE_SIZE).into_font())?;
        let areas = body.split_evenly(self.view.grid());
        let top_row = self.view.grid().1;
        let (lo, hi) = extent(
            sweep
                .points
                .iter()
                .map(|p| p.value)
                .chain(
                    sweep
                        .branches
                        .iter()
                        .flat_map(|b| b.points.iter().map(|q| q.value)),
                )
                .chain(sweep.bifurcations.iter().map(|b| b.value)),
        );
        let (lo, hi) = if lo < hi {
            (lo, hi)
        } else if lo.is_finite() {
            (lo - 0.5, lo + 0.5)
        } else {
            (0.0, 1.0)
        };
        let values: Vec<f64> = self
            .order
            .iter()
            .map(|&i| sweep.transitions[i].value)
            .collect();
        for ((panel, area), spec) in areas.iter().enumerate().zip(self.view.panels()) {
            let Panel {
                title,
                motion: get,
                sample: quantity,
                marked,
                range,
            } = *spec;
            let period = (range == Range::Phase).then_some(std::f64::consts::TAU);
            let branch_curves: Vec<(usize, Vec<_>)> = sweep
                .branches
                .iter()
                .map(|b| {
                    let colour = self.names.iter().position(|n| *n == b.structure);
                    (
                        colour.unwrap_or(0),
                        curves(b, quantity, period, self.unstable),
                    )
                })
                .collect();
            let (mut y0, mut y1) =
                extent(
                    sweep
                        .points
                        .iter()
                        .flat_map(|p| p.motions.iter().filter(|m| shown(m.stable)))
                        .flat_map(get)
                        .chain(branch_curves.iter().flat_map(|(_, cs)| {
                            cs.iter().flat_map(|c| c.points.iter().map(|p| p.1))
                        }))
                        .chain(sweep.bifurcations.iter().map(marked)),
                );
            let mut caption = title.to_string();
            match range {
                Range::Phase => (y0, y1) = (0.0, std::f64::consts::TAU),
                Range::Amplitude => y0 = 0.0,
                Range::Eigenvalue { level, clip } => {
                    if y0 < clip.0 || y1 > clip.1 {
                        caption = format!("{title} (clipped to [{}, {}])", clip.0, clip.1);
                    }
                    (y0, y1) = (y0.max(clip.0).min(level), y1.min(clip.1).max(level));
                }
                Range::Data => {}
            }
            if !(y0.is_finite() && y1.is_finite()) || y0 >= y1 {
                (y0, y1) = (y0.min(0.0) - 1.0, y1.max(0.0) + 1.0);
            }
            let pad = 0.05 * (y1 - y0);
            // Values past a clipped range are drawn on its edge.
            let clamp = |y: f64| y.clamp(y0 - pad, y1 + pad);
            let below = area
                .margin(12, 12, 12, 12)
                .titled(caption.as_str(), (FAMILY, CAPTION_SIZE).into_font())?;
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
            let tags = if panel < top_row && !values.is_empty() {
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
            if let Range::Eigenvalue { level, .. } = range {
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
            for (k, cs) in &branch_curves {
                let c = category(*k);
                for curve in cs {
                    match curve.stroke {
                        Stroke::Solid => {
                            chart.draw_series(LineSeries::new(
                                curve.points.iter().map(|&(x, y)| (x, clamp(y))),
                                c.stroke_width(STABLE_WIDTH),
                            ))?;
                        }
                        Stroke::Dashed => {
                            chart.draw_series(DashedLineSeries::new(
                                curve.points.iter().map(|&(x, y)| (x, clamp(y))),
                                6,
                                4,
                                c.stroke_width(UNSTABLE_WIDTH),
                            ))?;
                        }
                    }
                }
            }
            for (k, name) in self.names.iter().enumerate() {
                let c = category(k);
                for p in &sweep.points {
                    for m in p.motions.iter().filter(|m| &m.structure == name) {
                        if !shown(m.stable) {
                            continue;
                        }
                        let style = if m.stable {
                            c.filled()
                        } else {
                            c.stroke_width(1)
                        };
                        chart.draw_series(
                            get(m)
                                .into_iter()
                                .filter(|y| y.is_finite())
                                .map(|y| Circle::new((p.value, clamp(y)), 2, style)),
                        )?;
                    }
                }
            }
            let plot = pixels(chart.plotting_area());
            let top = plot.y0;
            // The bifurcations: marks first, then each label next to its
            // mark, clear of every mark and label of the panel.
            let centres: Vec<(i32, i32)> = self
                .marks
                .iter()
                .map(|&i| {
                    let b = &sweep.bifurcations[i];
                    chart.backend_coord(&(b.value, clamp(marked(b))))
                })
                .collect();
            let mut taken: Vec<Rect> = centres.iter().map(|&c| Symbol::rect(c)).collect();
            for (&i, &c) in self.marks.iter().zip(&centres) {
                symbol_of(sweep.bifurcations[i].kind).0.draw(root, c)?;
            }
            let h = line_height(KEY_SIZE);
            for (k, &c) in centres.iter().enumerate() {
                let text = self.label(k);
                let size = (text_width(&text, KEY_SIZE) + 4, h);
                let Some(r) = place_near(c, size, plot.grown(-2), &taken, LABEL_GAP) else {
                    continue;
                };
                if r.distance2(c) > i64::from((RADIUS + 2 * LABEL_GAP + 2).pow(2)) {
                    let to = (c.0.clamp(r.x0, r.x1 - 1), c.1.clamp(r.y0, r.y1 - 1));
                    root.draw(&PathElement::new(vec![c, to], INK.mix(0.6).stroke_width(1)))?;
                }
                root.draw(&Rectangle::new(
                    [(r.x0, r.y0), (r.x1, r.y1)],
                    WHITE.mix(0.8).filled(),
                ))?;
                root.draw(&Text::new(
                    text.clone(),
                    ((r.x0 + r.x1) / 2, (r.y0 + r.y1) / 2),
                    (FAMILY, KEY_SIZE)
                        .into_font()
                        .color(&INK)
                        .pos(Pos::new(HPos::Center, VPos::Center)),
                ))?;
                taken.push(r);
                labels.push(Label {
                    text,
                    panel,
                    mark: Symbol::rect(c),
                    rect: r,
                    plot,
                });
            }
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
            if panel < top_row {
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
        for ((legend, layout), origin) in self.legends.iter().zip(self.key_origins()) {
            legend.draw(layout, root, origin)?;
        }
        Ok((placed, labels))
    }
}

//! The one legend of every figure: entries (a mark and a text) measured with
//! the figure's font and laid out in as many columns as fit the width it is
//! given, a text too long for its column wrapped onto more lines. The layout
//! is computed before drawing, so a figure knows the room its legend needs
//! and grows to hold it: a legend never runs off the image.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};

use super::backend::{DrawError, FAMILY};
use super::layout::{line_height, text_width, wrap, Rect};
use super::symbol::Symbol;

/// What stands before an entry's text.
#[derive(Clone, Debug, PartialEq)]
pub enum Mark {
    /// A short line (a curve's colour).
    Line(RGBColor),
    /// A dashed line (an unstable stretch of a curve).
    Dashed(RGBColor),
    /// A dot (a series of points).
    Dot(RGBColor),
    /// A ring (an unstable point of a series).
    Hollow(RGBColor),
    /// A marker symbol (a point of note).
    Symbol(Symbol),
    /// A filled, outlined square (a region's colour).
    Swatch(RGBColor),
    /// A number or short tag (a key to marks in the figure).
    Tag(String),
    /// Nothing (a remark such as "… 3 more").
    None,
}

/// One entry.
#[derive(Clone, Debug, PartialEq)]
pub struct Entry {
    /// Its mark.
    pub mark: Mark,
    /// Its text.
    pub text: String,
}

impl Entry {
    /// An entry of `mark` and `text`.
    pub fn new(mark: Mark, text: impl Into<String>) -> Self {
        Self {
            mark,
            text: text.into(),
        }
    }
}

/// A legend: an optional heading over its entries.
#[derive(Clone, Debug, PartialEq)]
pub struct Legend {
    /// The heading.
    pub title: Option<String>,
    /// The entries, in reading order (down each column, then across).
    pub entries: Vec<Entry>,
    /// Text size in pixels.
    pub size: u32,
    /// Drawn on a white box with a border (over a chart), or bare.
    pub framed: bool,
}

/// Where each piece of a legend goes, relative to its upper-left corner.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendLayout {
    /// The heading's lines.
    pub title: Vec<(String, Rect)>,
    /// Each entry: its mark's box and its text's lines.
    pub entries: Vec<(Rect, Vec<(String, Rect)>)>,
    /// The whole legend (frame included): `(0, 0)` to `(width, height)`.
    pub bounds: Rect,
}

impl LegendLayout {
    /// Every box of text and mark, heading first.
    pub fn boxes(&self) -> impl Iterator<Item = &Rect> {
        self.title.iter().map(|(_, r)| r).chain(
            self.entries
                .iter()
                .flat_map(|(m, lines)| std::iter::once(m).chain(lines.iter().map(|(_, r)| r))),
        )
    }
}

const PAD: i32 = 6;
const MARK_GAP: i32 = 8;
const COLUMN_GAP: i32 = 24;
const ENTRY_GAP: i32 = 3;

impl Legend {
    /// A legend of `entries` at text size `size`.
    pub fn new(title: Option<String>, entries: Vec<Entry>, size: u32, framed: bool) -> Self {
        Self {
            title,
            entries,
            size,
            framed,
        }
    }

    fn mark_width(&self) -> i32 {
        let tags = self.entries.iter().filter_map(|e| match &e.mark {
            Mark::Tag(t) => Some(text_width(t, self.size)),
            _ => None,
        });
        let graphic = if self
            .entries
            .iter()
            .any(|e| !matches!(e.mark, Mark::Tag(_) | Mark::None))
        {
            22
        } else {
            0
        };
        tags.fold(graphic, i32::max)
    }

    /// The layout in at most `max_width` pixels: the most columns in which
    /// every entry fits unbroken; in one column, texts wrapped to the width.
    pub fn layout(&self, max_width: i32) -> LegendLayout {
        let line = line_height(self.size);
        let pad = if self.framed { PAD } else { 0 };
        let inner = (max_width - 2 * pad).max(1);
        let mark_w = self.mark_width();
        let text_x = if mark_w > 0 { mark_w + MARK_GAP } else { 0 };
        let natural = self
            .entries
            .iter()
            .map(|e| text_x + text_width(&e.text, self.size))
            .max()
            .unwrap_or(0);
        let n = self.entries.len().max(1);
        let columns =
            (((inner + COLUMN_GAP) / (natural + COLUMN_GAP).max(1)).max(1) as usize).min(n);
        let column_w = if columns == 1 {
            natural.min(inner)
        } else {
            natural
        };
        let text_w = (column_w - text_x).max(1);
        // Heading.
        let mut y = pad;
        let mut title = Vec::new();
        let mut width = 0;
        if let Some(t) = &self.title {
            for l in wrap(t, self.size, inner) {
                let w = text_width(&l, self.size);
                width = width.max(w);
                title.push((l, Rect::at(pad, y, (w, line))));
                y += line;
            }
            y += ENTRY_GAP;
        }
        let top = y;
        let rows = self.entries.len().div_ceil(columns);
        let mut bottom = top;
        let mut entries = Vec::with_capacity(self.entries.len());
        for (i, e) in self.entries.iter().enumerate() {
            let (column, row) = (i / rows.max(1), i % rows.max(1));
            if row == 0 {
                y = top;
            }
            let x = pad + column as i32 * (column_w + COLUMN_GAP);
            let lines: Vec<(String, Rect)> = wrap(&e.text, self.size, text_w)
                .into_iter()
                .enumerate()
                .map(|(k, l)| {
                    let w = text_width(&l, self.size);
                    (l, Rect::at(x + text_x, y + k as i32 * line, (w, line)))
                })
                .collect();
            let mark = match &e.mark {
                Mark::Tag(t) => Rect::at(x, y, (text_width(t, self.size), line)),
                Mark::None => Rect::at(x, y, (0, line)),
                _ => Rect::at(x, y + 1, (mark_w, line - 2)),
            };
            for (_, r) in &lines {
                width = width.max(r.x1 - pad);
            }
            y += lines.len() as i32 * line + ENTRY_GAP;
            bottom = bottom.max(y - ENTRY_GAP);
            entries.push((mark, lines));
        }
        LegendLayout {
            title,
            entries,
            bounds: Rect::at(0, 0, (width + 2 * pad, bottom + pad)),
        }
    }

    /// Draw `layout` (from [`Legend::layout`]) with its upper-left corner at
    /// `origin`, in the pixels of `area`.
    pub fn draw<DB: DrawingBackend>(
        &self,
        layout: &LegendLayout,
        area: &DrawingArea<DB, Shift>,
        (ox, oy): (i32, i32),
    ) -> Result<(), DrawError> {
        let at = |r: &Rect| r.shifted(ox, oy);
        let corners = |r: Rect| [(r.x0, r.y0), (r.x1, r.y1)];
        if self.framed {
            let b = at(&layout.bounds);
            area.draw(&Rectangle::new(corners(b), WHITE.mix(0.85).filled()))?;
            area.draw(&Rectangle::new(corners(b), RGBColor(180, 180, 180)))?;
        }
        let font = (FAMILY, self.size).into_font();
        let write = |s: &str, r: Rect| -> Result<(), DrawError> {
            area.draw(&Text::new(
                s.to_string(),
                (r.x0, (r.y0 + r.y1) / 2),
                font.clone()
                    .color(&BLACK)
                    .pos(Pos::new(HPos::Left, VPos::Center)),
            ))?;
            Ok(())
        };
        for (l, r) in &layout.title {
            write(l, at(r))?;
        }
        for (e, (mark, lines)) in self.entries.iter().zip(&layout.entries) {
            let m = at(mark);
            let mid = (m.y0 + m.y1) / 2;
            match &e.mark {
                Mark::Line(c) => {
                    area.draw(&PathElement::new(
                        vec![(m.x0, mid), (m.x1, mid)],
                        c.stroke_width(3),
                    ))?;
                }
                Mark::Dashed(c) => {
                    let mut x = m.x0;
                    while x < m.x1 {
                        area.draw(&PathElement::new(
                            vec![(x, mid), ((x + 5).min(m.x1), mid)],
                            c.stroke_width(1),
                        ))?;
                        x += 8;
                    }
                }
                Mark::Dot(c) => {
                    area.draw(&Circle::new(((m.x0 + m.x1) / 2, mid), 4, c.filled()))?;
                }
                Mark::Hollow(c) => {
                    area.draw(&Circle::new(((m.x0 + m.x1) / 2, mid), 4, c.stroke_width(1)))?;
                }
                Mark::Symbol(s) => s.draw(area, ((m.x0 + m.x1) / 2, mid))?,
                Mark::Swatch(c) => {
                    area.draw(&Rectangle::new(corners(m), c.filled()))?;
                    area.draw(&Rectangle::new(corners(m), BLACK.stroke_width(1)))?;
                }
                Mark::Tag(t) => write(t, m)?,
                Mark::None => {}
            }
            for (l, r) in lines {
                write(l, at(r))?;
            }
        }
        Ok(())
    }
}

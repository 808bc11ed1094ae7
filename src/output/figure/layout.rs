//! Text on a figure, measured in pixels: boxes, wrapping to a width,
//! labels along a horizontal axis stacked in rows so that none overlaps
//! another, and labels placed next to points of a chart clear of what is
//! already there.
//!
//! Widths come from the compiled-in font ([`super::backend::register`]), the
//! one the PNG backend draws with; an SVG viewer substitutes its own
//! `sans-serif`, of about the same widths.

use plotters::prelude::IntoFont;

use super::backend::{register, FAMILY};

/// A box in pixels: `x0 <= x < x1`, `y0 <= y < y1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Rect {
    /// Left.
    pub x0: i32,
    /// Top.
    pub y0: i32,
    /// Right (exclusive).
    pub x1: i32,
    /// Bottom (exclusive).
    pub y1: i32,
}

impl Rect {
    /// The box of `size` with its upper-left corner at `(x, y)`.
    pub fn at(x: i32, y: i32, (w, h): (i32, i32)) -> Self {
        Self {
            x0: x,
            y0: y,
            x1: x + w,
            y1: y + h,
        }
    }

    /// Whether the two boxes share a pixel.
    pub fn overlaps(&self, other: &Rect) -> bool {
        self.x0 < other.x1 && other.x0 < self.x1 && self.y0 < other.y1 && other.y0 < self.y1
    }

    /// Whether every pixel of `self` lies in `outer`.
    pub fn inside(&self, outer: &Rect) -> bool {
        self.x0 >= outer.x0 && self.x1 <= outer.x1 && self.y0 >= outer.y0 && self.y1 <= outer.y1
    }

    /// Moved by `(dx, dy)`.
    pub fn shifted(&self, dx: i32, dy: i32) -> Self {
        Self {
            x0: self.x0 + dx,
            y0: self.y0 + dy,
            x1: self.x1 + dx,
            y1: self.y1 + dy,
        }
    }
}

/// The advance width of `text` at `size` pixels. Should the font be
/// unavailable, a generous estimate (0.7 em a character) keeps layouts
/// from overlapping.
pub fn text_width(text: &str, size: u32) -> i32 {
    let measured = register()
        .ok()
        .and_then(|()| (FAMILY, size).into_font().box_size(text).ok());
    match measured {
        Some((w, _)) => w as i32,
        None => (0.7 * f64::from(size) * text.chars().count() as f64).ceil() as i32,
    }
}

/// The height of one line of text at `size` pixels, with its leading.
pub fn line_height(size: u32) -> i32 {
    (1.3 * f64::from(size)).ceil() as i32
}

/// `text` broken into lines no wider than `width` pixels: at spaces where
/// possible, inside a word only when the word alone is wider. Never loses a
/// character (the lines joined by spaces or nothing give `text` back).
pub fn wrap(text: &str, size: u32, width: i32) -> Vec<String> {
    let fits = |s: &str| text_width(s, size) <= width;
    let mut lines: Vec<String> = Vec::new();
    let mut line = String::new();
    for word in text.split(' ') {
        let candidate = if line.is_empty() {
            word.to_string()
        } else {
            format!("{line} {word}")
        };
        if fits(&candidate) {
            line = candidate;
            continue;
        }
        if !line.is_empty() {
            lines.push(std::mem::take(&mut line));
        }
        // The word alone: break it where it must.
        let mut rest = word;
        while !fits(rest) {
            let mut cut = 0;
            for (i, _) in rest.char_indices().skip(1) {
                if !fits(&rest[..i]) {
                    break;
                }
                cut = i;
            }
            if cut == 0 {
                // Not even one character fits: one a line.
                cut = rest.chars().next().map_or(rest.len(), char::len_utf8);
            }
            lines.push(rest[..cut].to_string());
            rest = &rest[cut..];
            if rest.is_empty() {
                break;
            }
        }
        line = rest.to_string();
    }
    if !line.is_empty() || lines.is_empty() {
        lines.push(line);
    }
    lines
}

/// Labels of width `widths[i]` centred on `centres[i]` (pixels along a
/// horizontal axis, in increasing order), each kept within `[left, right)`
/// (a label wider than that starts at `left`):
/// the left edge and the row (0 nearest the axis) of each, the lowest row in
/// which it keeps `gap` pixels from every label already placed there.
pub fn stack(
    centres: &[i32],
    widths: &[i32],
    left: i32,
    right: i32,
    gap: i32,
) -> Vec<(i32, usize)> {
    // The right edge of the last label in each row.
    let mut ends: Vec<i32> = Vec::new();
    centres
        .iter()
        .zip(widths)
        .map(|(&c, &w)| {
            let x0 = (c - w / 2).min(right - w).max(left);
            let row = ends
                .iter()
                .position(|&end| x0 >= end + gap)
                .unwrap_or(ends.len());
            if row == ends.len() {
                ends.push(x0 + w);
            } else {
                ends[row] = x0 + w;
            }
            (x0, row)
        })
        .collect()
}

impl Rect {
    /// The squared distance from `(x, y)` to the nearest pixel of the box.
    pub fn distance2(&self, (x, y): (i32, i32)) -> i64 {
        let dx = i64::from((self.x0 - x).max(x - (self.x1 - 1)).max(0));
        let dy = i64::from((self.y0 - y).max(y - (self.y1 - 1)).max(0));
        dx * dx + dy * dy
    }

    /// Grown by `d` pixels on every side.
    pub fn grown(&self, d: i32) -> Self {
        Self {
            x0: self.x0 - d,
            y0: self.y0 - d,
            x1: self.x1 + d,
            y1: self.y1 + d,
        }
    }
}

/// A box of `(w, h)` pixels for the label of the point `at`: inside
/// `within`, keeping `gap` pixels from every box of `taken`, as near to the
/// point as may be (on a grid of a few pixels; of equally near places, to
/// the right of the point first, then above). `None` when no place is left.
pub fn place_near(
    at: (i32, i32),
    (w, h): (i32, i32),
    within: Rect,
    taken: &[Rect],
    gap: i32,
) -> Option<Rect> {
    const STEP: i32 = 3;
    let free = |r: &Rect| r.inside(&within) && taken.iter().all(|t| !t.grown(gap).overlaps(r));
    let mut best: Option<((i64, u8), Rect)> = None;
    let mut y = within.y0;
    while y + h <= within.y1 {
        let mut x = within.x0;
        while x + w <= within.x1 {
            let r = Rect::at(x, y, (w, h));
            let side = if r.x0 > at.0 {
                0
            } else if r.y1 <= at.1 {
                1
            } else {
                2
            };
            let key = (r.distance2(at), side);
            if best.as_ref().is_none_or(|(k, _)| key < *k) && free(&r) {
                best = Some((key, r));
            }
            x += STEP;
        }
        y += STEP;
    }
    best.map(|(_, r)| r)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn wider_text_measures_wider() {
        let narrow = text_width("iiii", 14);
        let wide = text_width("WWWW", 14);
        assert!(narrow > 0 && wide > 2 * narrow, "{narrow} {wide}");
        assert!(text_width("WWWW", 28) >= 2 * wide - 2);
    }

    #[test]
    fn wrapped_lines_fit_and_keep_every_character() {
        let text =
            "P_{3_31 0_11 3_13 4_33 3_31 0_11 3_13 4_33 3_33 4_33 3_33 4_33 3_33 4_33}^5 (1)";
        for width in [40, 120, 300, 2000] {
            let lines = wrap(text, 14, width);
            for l in &lines {
                assert!(text_width(l, 14) <= width, "`{l}` wider than {width}");
            }
            let joined: String = lines.concat();
            assert_eq!(joined.replace(' ', ""), text.replace(' ', ""));
        }
        assert_eq!(wrap(text, 14, 2000).len(), 1);
        // A word wider than the width is cut inside.
        let long = "x".repeat(50);
        let lines = wrap(&long, 14, 60);
        assert!(lines.len() > 1 && lines.concat() == long);
        assert_eq!(wrap("", 14, 60), vec![String::new()]);
    }

    #[test]
    fn stacked_labels_never_overlap_and_stay_inside() {
        // Crowded: twenty labels within a few pixels, some at the edges.
        let centres: Vec<i32> = (0..20)
            .map(|i| [3, 50, 51, 52, 200, 398][i % 6] + i as i32 / 6)
            .collect();
        let mut centres = centres;
        centres.sort_unstable();
        let widths: Vec<i32> = (0..20).map(|i| 8 + 3 * (i % 4)).collect();
        let placed = stack(&centres, &widths, 0, 400, 3);
        let boxes: Vec<Rect> = placed
            .iter()
            .zip(&widths)
            .map(|(&(x0, row), &w)| Rect::at(x0, row as i32 * 10, (w, 10)))
            .collect();
        for (i, a) in boxes.iter().enumerate() {
            assert!(a.x0 >= 0 && a.x1 <= 400, "{a:?}");
            for b in &boxes[i + 1..] {
                let grown = Rect {
                    x0: a.x0 - 3,
                    x1: a.x1 + 3,
                    ..*a
                };
                assert!(!grown.overlaps(b), "{a:?} {b:?}");
            }
        }
        // Alone, a label sits centred on its point, in the first row.
        assert_eq!(stack(&[100], &[20], 0, 400, 3), vec![(90, 0)]);
    }

    #[test]
    fn labels_placed_near_points_keep_apart_and_inside() {
        let within = Rect::at(0, 0, (300, 200));
        // Forty points crowded on one line, as bifurcations at |λ| = 1.
        let mut taken: Vec<Rect> = (0..40)
            .map(|i| Rect::at(100 + i, 100 - 5, (11, 11)))
            .collect();
        let markers = taken.len();
        for i in 0..40 {
            let at = (105 + i, 100);
            let r = place_near(at, (30, 16), within, &taken, 2).expect("room left");
            assert!(r.inside(&within), "{r:?}");
            for t in &taken {
                assert!(!t.grown(2).overlaps(&r), "{r:?} meets {t:?}");
            }
            taken.push(r);
        }
        // The first label sits right by its point; a lone point's label too.
        let first = taken[markers];
        assert!(first.distance2((105, 100)) <= 10 * 10, "{first:?}");
        let lone = place_near((50, 50), (30, 16), within, &[], 2).unwrap();
        assert!(lone.distance2((50, 50)) <= 2, "{lone:?}");
        // No room: none.
        assert_eq!(
            place_near((5, 5), (30, 16), Rect::at(0, 0, (20, 20)), &[], 2),
            None
        );
    }
}

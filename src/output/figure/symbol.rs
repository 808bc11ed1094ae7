//! Marker symbols for points of note (a sweep's bifurcations): square,
//! diamond, triangle, ring and cross, centred on a pixel, drawn in one dark ink so
//! that they stand out over the coloured curves.

use plotters::coord::Shift;
use plotters::prelude::*;

use super::backend::DrawError;
use super::layout::Rect;

/// The ink of every symbol (no category colour uses it).
pub const INK: RGBColor = RGBColor(20, 20, 20);
/// Half the side of a symbol's box, in pixels.
pub const RADIUS: i32 = 5;

/// A marker shape.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Symbol {
    /// A filled square.
    Square,
    /// A filled diamond.
    Diamond,
    /// A filled triangle, point up.
    Triangle,
    /// An open ring.
    Ring,
    /// A cross (any other point of note).
    Cross,
}

impl Symbol {
    /// The box a symbol centred on `(x, y)` covers.
    pub fn rect((x, y): (i32, i32)) -> Rect {
        Rect {
            x0: x - RADIUS - 1,
            y0: y - RADIUS - 1,
            x1: x + RADIUS + 2,
            y1: y + RADIUS + 2,
        }
    }

    /// Draw the symbol centred on `(x, y)`, pixels of `area`.
    pub fn draw<DB: DrawingBackend>(
        self,
        area: &DrawingArea<DB, Shift>,
        (x, y): (i32, i32),
    ) -> Result<(), DrawError> {
        let r = RADIUS;
        let polygon = match self {
            Symbol::Cross => {
                for (a, b) in [
                    ((x - r, y - r), (x + r, y + r)),
                    ((x - r, y + r), (x + r, y - r)),
                ] {
                    area.draw(&PathElement::new(vec![a, b], INK.stroke_width(2)))?;
                }
                return Ok(());
            }
            Symbol::Square => vec![
                (x - r + 1, y - r + 1),
                (x + r - 1, y - r + 1),
                (x + r - 1, y + r - 1),
                (x - r + 1, y + r - 1),
            ],
            Symbol::Diamond => vec![
                (x, y - r - 1),
                (x + r + 1, y),
                (x, y + r + 1),
                (x - r - 1, y),
            ],
            Symbol::Triangle => vec![(x, y - r - 1), (x + r + 1, y + r), (x - r - 1, y + r)],
            Symbol::Ring => {
                area.draw(&Circle::new((x, y), r as u32, INK.stroke_width(2)))?;
                return Ok(());
            }
        };
        area.draw(&Polygon::new(polygon, INK.filled()))?;
        Ok(())
    }
}

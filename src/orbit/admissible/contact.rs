//! The first boundary contact of a flow segment as the admissibility walk
//! takes it: the event search's, except for a graze that the closed form
//! keeps off the boundary.

use crate::dynamics::simulate::{Event, EventKind, Segment, SimError, Simulator};
use crate::model::Model;

/// The first boundary contact of the flow of `seg` before `limit` that is
/// not a graze the closed form puts strictly inside (`keeps_off`: by any
/// positive margin): such a graze is a touch within the event search's
/// graze tolerance (`|v − V_k|` at the extremum below `graze_tol`) of an
/// extremum that the closed form, exact to rounding, keeps off the
/// boundary by a positive margin, or a slow departure from the boundary
/// read as a graze. The margin is
/// then the closed form's, positive, like on either side of that tolerance
/// band: were the graze taken as an early contact (margin 0), the margin a
/// sweep locates its transition on would be 0 on a band of width
/// `graze_tol` above its zero, and the located root the edge of that band
/// where the event search's classification flips (grid-dependent, about
/// `graze_tol / |dm/dλ|` off the zero of the smooth margin, which is the
/// two-parameter curve's). The event search still decides which boundary is
/// crossed first: it goes on past such a graze.
pub(super) fn first_contact<M: Model>(
    sim: &Simulator<M>,
    seg: &Segment,
    limit: f64,
    early: impl Fn(&Event) -> bool,
    keeps_off: impl Fn(usize) -> bool,
) -> Result<Option<(Event, Segment)>, SimError> {
    let mut seg = *seg;
    // One graze per extremum (the search resumes past each): a segment has
    // few; the bound only keeps a pathological one finite.
    for _ in 0..16 {
        match sim.next_event(&seg, limit)? {
            Some((e, next)) if e.kind == EventKind::Graze && early(&e) && keeps_off(e.boundary) => {
                seg = next;
            }
            other => return Ok(other),
        }
    }
    sim.next_event(&seg, limit)
}

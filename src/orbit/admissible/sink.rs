//! What a condition of SPEC §6 is, and where the evaluated conditions go:
//! a list with text for the violated ones ([`Violation`]), or the smallest
//! margin alone ([`Margin`], the continuation's per-point check).

use serde::Serialize;

/// Which condition of SPEC §6 a violation breaks; it names the transition a
/// parameter sweep meets where the condition starts to fail.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum ViolationKind {
    /// A mapping with no positive duration.
    Duration,
    /// The flow does not leave its start boundary into its domain.
    Departure,
    /// The flow reaches another boundary before its arrival (grazing from inside).
    Interior,
    /// The arrival is not transversal (grazing at the arrival).
    Arrival,
    /// A stick onset whose force criterion fails: the flow passes instead.
    StickOnset,
    /// A pass whose force criterion fails: the flow sticks instead.
    Pass,
    /// A stick that ends elsewhere than the structure says (`|Fnf|` reaches `as` early).
    StickEnd,
    /// Anything else (an inconsistent structure, a failed simulation).
    Other,
}

/// One condition, satisfied or not.
#[derive(Clone, Debug, PartialEq, Serialize)]
pub struct Violation {
    /// Index of the mapping (in application order) where it happens.
    pub segment: usize,
    /// What is violated, in the model's terms. Written only for a violated
    /// condition (margin `<= 0` or NaN); empty for a satisfied one.
    pub condition: String,
    /// By how much (negative or zero: violated; units of the quantity compared).
    pub margin: f64,
    /// Which kind of condition.
    #[serde(skip)]
    pub kind: ViolationKind,
    /// The boundary involved, if any (index).
    #[serde(skip)]
    pub boundary: Option<usize>,
}

/// The smallest margin of a point's conditions (see [`super::worst_margin`]): no text.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Margin {
    /// The margin (NaN: the condition could not be evaluated, counted as violated).
    pub margin: f64,
    /// Which kind of condition.
    pub kind: ViolationKind,
    /// Index of the mapping (in application order).
    pub segment: usize,
    /// The boundary involved, if any (index).
    pub boundary: Option<usize>,
}

/// Where the conditions go: a list with text for the violated ones, or the
/// smallest margin alone.
pub(super) trait Sink {
    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        text: impl FnOnce() -> String,
    );

    /// Whether the margins are wanted as smooth functions of the points
    /// (a curve's condition): the arrival is taken as the first boundary
    /// contact without the event search, so that the interior margin is
    /// always the closed form's, never replaced by the depth of an early
    /// contact or by a missing arrival.
    fn smooth(&self) -> bool {
        false
    }

    /// Whether only the violated conditions are wanted, so that a margin
    /// proven positive may be inexact (a velocity extremum proven clear of
    /// the boundaries is not refined further): [`super::violations`].
    fn signs_only(&self) -> bool {
        false
    }
}

impl Sink for Vec<Violation> {
    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        text: impl FnOnce() -> String,
    ) {
        let violated = margin.is_nan() || margin <= 0.0;
        self.push(Violation {
            segment,
            condition: if violated { text() } else { String::new() },
            margin,
            kind,
            boundary,
        });
    }
}

/// The violated conditions only.
pub(super) struct Violated(pub(super) Vec<Violation>);

impl Sink for Violated {
    fn signs_only(&self) -> bool {
        true
    }

    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        text: impl FnOnce() -> String,
    ) {
        if margin.is_nan() || margin <= 0.0 {
            self.0.add(segment, kind, boundary, margin, text);
        }
    }
}

/// The smallest margin, and the smallest force criteria (pass, stick
/// onset) to name it by when it vanishes with one (see [`super::worst_margin`]).
#[derive(Default)]
pub(super) struct Worst {
    smallest: Option<Margin>,
    pass: Option<Margin>,
    stick_onset: Option<Margin>,
}

/// How close (relative, at least absolute 1e-6) a force criterion's margin
/// must be to the smallest margin for the two to count as one event.
pub const SAME_EVENT: f64 = 1e-6;

impl Worst {
    fn keep(slot: &mut Option<Margin>, m: Margin) {
        // NaN counts as the smallest (an unevaluable condition is violated).
        let key = |m: f64| if m.is_nan() { f64::NEG_INFINITY } else { m };
        if slot.is_none_or(|w| key(m.margin) < key(w.margin)) {
            *slot = Some(m);
        }
    }

    pub(super) fn result(self) -> Option<Margin> {
        let mut w = self.smallest?;
        // On a stick boundary, a departure, arrival or interior contact that
        // turns tangential is the same event as a force criterion changing
        // sign (the input force of that side vanishes with the
        // acceleration): it is named by the force criterion (stick onset,
        // passable onset), as SPEC §3 names it.
        //
        // Where a flow between two contacts with the boundary shrinks to
        // nothing, the pass into it and the stick onset after it vanish
        // together: the pass names it (the passage that fails turns into a
        // stick, which removes the excursion: a stick onset), so that the
        // name does not depend on which of the two rounding makes smaller.
        if matches!(
            w.kind,
            ViolationKind::Arrival | ViolationKind::Interior | ViolationKind::Departure
        ) {
            let with = |f: &Option<Margin>| {
                f.filter(|f| {
                    f.boundary == w.boundary
                        && (f.margin - w.margin).abs() <= SAME_EVENT * w.margin.abs().max(1.0)
                })
            };
            if let Some(f) = with(&self.pass).or(with(&self.stick_onset)) {
                w.kind = f.kind;
                w.segment = f.segment;
            }
        }
        Some(w)
    }
}

impl Sink for Worst {
    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        _text: impl FnOnce() -> String,
    ) {
        let m = Margin {
            margin,
            kind,
            segment,
            boundary,
        };
        match kind {
            ViolationKind::Pass => Self::keep(&mut self.pass, m),
            ViolationKind::StickOnset => Self::keep(&mut self.stick_onset, m),
            _ => {}
        }
        Self::keep(&mut self.smallest, m);
    }
}

/// Several conditions, each picked by its kind, segment and boundary: the
/// smallest margin among the entries matching `ids[i]` in `margins[i]`
/// (`None` where none matches; a two-parameter curve's condition and its
/// companions, `bifurcation::curve`).
pub(super) struct Several<'a> {
    pub(super) ids: &'a [ConditionId],
    pub(super) margins: &'a mut [Option<f64>],
}

impl Sink for Several<'_> {
    fn smooth(&self) -> bool {
        true
    }

    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        _text: impl FnOnce() -> String,
    ) {
        let key = |m: f64| if m.is_nan() { f64::NEG_INFINITY } else { m };
        for (id, slot) in self.ids.iter().zip(self.margins.iter_mut()) {
            if *id == (kind, segment, boundary) && slot.is_none_or(|w| key(margin) < key(w)) {
                *slot = Some(margin);
            }
        }
    }
}

/// A condition's identity: kind, segment, boundary.
pub type ConditionId = (ViolationKind, usize, Option<usize>);

/// The smallest margin (named as [`Worst`] names it) of every condition but
/// the excluded ones.
pub(super) struct Except<'a> {
    pub(super) excluded: &'a [ConditionId],
    pub(super) worst: Worst,
}

impl Sink for Except<'_> {
    fn add(
        &mut self,
        segment: usize,
        kind: ViolationKind,
        boundary: Option<usize>,
        margin: f64,
        text: impl FnOnce() -> String,
    ) {
        if !self.excluded.contains(&(kind, segment, boundary)) {
            self.worst.add(segment, kind, boundary, margin, text);
        }
    }
}

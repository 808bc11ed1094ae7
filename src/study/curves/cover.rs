//! Covering the box with curves: sweeps along seed lines, each transition
//! they locate continued in both parameters unless a traced curve already
//! passes there, and more lines where a curve must be missing.
//!
//! The lines, in order: the seed lines and the `--at` lines; `spread` horizontal and `spread`
//! vertical lines evenly spaced, and with `edges` the box's four edges; then, for every transition on any line
//! that no traced curve passes (its trace failed, or it began nowhere a
//! traced curve reaches), a line through it across its own line and one
//! beside it (at most `max_missing`); then, between two neighbouring
//! parallel lines, the line halfway when a motion lives on one and not the
//! other and no curve of that motion runs between them: an island or isola
//! seen by one line only (at most `max_refine`, never closer than 1/64 of
//! the span); then, with `probes` > 0, short sweeps across every curve
//! traced so far at that many places along it, reaching 1/64 of the span to
//! each side: a band that opens where two curves cross, away from every
//! line (a period-adding cascade between a grazing and a passable onset),
//! is found where it touches a probed curve. What neither a line nor a
//! probe crosses stays unseen: an isola smaller than the spacing of the
//! lines and away from every line and curve is not found. Then, no line:
//! each start that failed where an excursion of its motion shrinks to
//! nothing is traced on the reduced motion ([`Cover::carry`]); last,
//! branch switching: from every codimension-two point of a traced curve,
//! the second condition's curve of the same motion ([`Cover::partners`]).

use stickslip_codegen::structure as grammar;

use crate::bifurcation::curve::{
    codim2_places, codim2_residual, crossings, inadmissible_point, partner_start, reduced_start,
    trace_watching, Condition, Curve, CurveEnd, CurveEndReason, Line, Plane, PARTNER_STEP,
};
use crate::bifurcation::transition_kind;
use crate::model::{Model, ModelInfo};
use crate::orbit::structure::Structure;
use crate::study::sweep::SweepOptions;

use super::codim2::{codim2_points, same_place, SAME_PLACE};
use super::seeds::{structure_name, sweep_line, LineSweep, Start};
use super::{
    CurveSet, CurveSummary, CurvesError, CurvesOptions, CurvesSettings, EndSummary, FailedStart,
};

/// A transition and a curve cross a line at one place when this close
/// (relative to the value, at least absolute).
const ON_CURVE: f64 = 1e-7;

/// Refinement lines are never closer than this fraction of the span; a
/// probe reaches this far to each side of its curve.
const FINEST: f64 = 1.0 / 64.0;

/// Two parallel lines closer than this fraction of the span are one.
const SAME_LINE: f64 = 1e-12;

/// Grid values of a probe's sweep.
const PROBE_COUNT: usize = 16;

/// Everything found so far.
pub(super) struct Cover<'a, M: Model> {
    base: &'a M::Params,
    plane: Plane,
    settings: &'a CurvesSettings,
    /// The lines swept, in order, and what they found.
    sweeps: Vec<LineSweep>,
    /// The curves traced, in the order found.
    curves: Vec<Curve>,
    /// The starts whose trace failed, with why.
    failed: Vec<(Start, String)>,
    _model: std::marker::PhantomData<M>,
}

fn same_structure(info: &ModelInfo, a: Option<&Structure>, b: Option<&Structure>) -> bool {
    match (a, b) {
        (None, None) => true,
        (Some(a), Some(b)) => a.canonical(info).0 == b.canonical(info).0,
        _ => false,
    }
}

/// The value of a line, and the coordinate of a point along that line's parameter.
fn line_value(line: Line) -> f64 {
    match line {
        Line::X(v) | Line::Y(v) => v,
    }
}

/// A traced curve stays within this fraction of the box (each parameter
/// over its span) of its start when it is taken for a failed start.
const NO_EXTENT: f64 = 1e-4;

/// Why `curve` is a failed start, not a curve: it fails both ways
/// (a corrector failure or the point limit, neither end on the box's edge
/// or at a codimension-two point, nor closed) within [`NO_EXTENT`] of the
/// box of its start. Measured: a passable onset of `stribeck::pl4`
/// (W=0.92:0.96 × Q0=4.8:5.0, a period-3 motion of 14 mappings whose
/// equations are singular there, smallest singular value 5.6e-12) went
/// 7 points, 6e-7 of the box, before both ends failed; it carries nothing
/// its start does not.
fn stuck(plane: &Plane, curve: &Curve) -> Option<String> {
    let [a, b] = curve.ends.as_slice() else {
        return None;
    };
    failed(b)?;
    let why = failed(a)?;
    let extent = extent(plane, curve)?;
    (extent <= NO_EXTENT).then(|| {
        format!("the curve does not leave its start ({extent:.1e} of the box both ways): {why}")
    })
}

/// Why an end is a failure (a corrector failure or the point limit).
fn failed(e: &CurveEnd) -> Option<String> {
    match &e.reason {
        CurveEndReason::NewtonFailure(why) => Some(why.clone()),
        CurveEndReason::MaxPoints => Some("the point limit".into()),
        _ => None,
    }
}

/// How far `curve` reaches from its first point (each parameter over its
/// span).
fn extent(plane: &Plane, curve: &Curve) -> Option<f64> {
    let first = curve.points.first()?;
    let spans = [
        plane.x_range[1] - plane.x_range[0],
        plane.y_range[1] - plane.y_range[0],
    ];
    Some(curve.points.iter().fold(0.0f64, |m, q| {
        m.max(((q.x - first.x) / spans[0]).hypot((q.y - first.y) / spans[1]))
    }))
}

/// Whether a curve traced by branch switching carries nothing: it fails at
/// an end and stays within [`NO_EXTENT`] of the box of its start. On
/// `stribeck8` W = 0.95…1.02 × Q0 = 4.4…5.0 the passable-onset curve of a
/// motion whose split stick's excursion shrinks there, switched to from
/// its period doubling's end, went 4e-8 in W before its system turned
/// singular (smallest singular value 5.7e-12).
fn partial(plane: &Plane, curve: &Curve) -> bool {
    curve.ends.iter().any(|e| failed(e).is_some())
        && extent(plane, curve).is_some_and(|x| x <= NO_EXTENT)
}

/// Whether the start's motion has at most `max` mappings (is traced).
fn traceable(start: &Start, max: usize) -> bool {
    start.structure.as_ref().is_none_or(|s| s.len() <= max)
}

/// Whether two lines are one: parallel, and within [`SAME_LINE`] of the
/// box's span apart (the spread's middle line `lo + (hi − lo) / 2` and the
/// default seed `(lo + hi) / 2` differ by rounding).
fn same_line(plane: &Plane, a: Line, b: Line) -> bool {
    let close = |u: f64, v: f64, [lo, hi]: [f64; 2]| (u - v).abs() <= SAME_LINE * (hi - lo);
    match (a, b) {
        (Line::X(u), Line::X(v)) => close(u, v, plane.x_range),
        (Line::Y(u), Line::Y(v)) => close(u, v, plane.y_range),
        _ => false,
    }
}

impl<'a, M: Model> Cover<'a, M> {
    pub fn new(base: &'a M::Params, plane: Plane, settings: &'a CurvesSettings) -> Self {
        Self {
            base,
            plane,
            settings,
            sweeps: Vec::new(),
            curves: Vec::new(),
            failed: Vec::new(),
            _model: std::marker::PhantomData,
        }
    }

    /// The sweeps' settings: longer motions start no curve. Their branches
    /// are followed one period doubling further (a transition past a
    /// longer branch's end may lead to a traceable motion), and no further:
    /// a cascade into chaos would follow branches of hundreds of mappings.
    fn sweep_options(&self) -> SweepOptions {
        SweepOptions {
            max_mappings: self
                .settings
                .sweep
                .max_mappings
                .or(Some(self.settings.max_mappings.saturating_mul(2))),
            ..self.settings.sweep
        }
    }

    /// Trace every start no traced curve passes.
    fn trace_new(&mut self, starts: &[Start]) {
        let max = self.settings.max_mappings;
        for start in starts.iter().filter(|s| traceable(s, max)) {
            if self.on_curve(start) {
                continue;
            }
            match self.trace_start(start, None) {
                Ok(curve) => self.curves.push(curve),
                Err(why) => self.failed.push((start.clone(), why)),
            }
        }
    }

    /// The curve through `start`, or why none (with `watched` watched
    /// along it: [`trace_watching`]).
    fn trace_start(&self, start: &Start, watched: Option<Condition>) -> Result<Curve, String> {
        match trace_watching::<M>(
            self.base,
            &self.plane,
            start.structure.as_ref(),
            &start.point,
            start.condition,
            watched,
            &self.settings.curve,
        ) {
            Ok(curve) if !curve.points.is_empty() => match stuck(&self.plane, &curve) {
                Some(why) => Err(why),
                None => Ok(curve),
            },
            Ok(_) => Err("the curve has no point".into()),
            Err(e) => Err(e.to_string()),
        }
    }

    /// `start` carried to the reduced motion where an excursion of its
    /// motion shrinks to nothing ([`reduced_start`]), on its line.
    fn reduced(&self, start: &Start) -> Option<Start> {
        let fixed = match start.line {
            Line::Y(_) => 1,
            Line::X(_) => 0,
        };
        let r = reduced_start::<M>(
            self.base,
            &self.plane,
            start.structure.as_ref()?,
            &start.point,
            start.condition,
            fixed,
            self.settings.curve.tolerance,
        )?;
        let Condition::Margin { kind, boundary, .. } = r.condition else {
            return None;
        };
        Some(Start {
            kind: transition_kind(kind),
            boundary,
            structure: Some(r.structure),
            condition: r.condition,
            point: r.point,
            line: start.line,
        })
    }

    /// Sweep along `line` (once) and trace every transition found there
    /// that no traced curve passes. Whether the line was new.
    pub fn line(&mut self, line: Line) -> Result<bool, CurvesError> {
        if self
            .sweeps
            .iter()
            .any(|s| same_line(&self.plane, s.line, line))
        {
            return Ok(false);
        }
        let sw = sweep_line::<M>(
            self.base,
            &self.plane,
            line,
            None,
            self.settings.count,
            self.sweep_options(),
        )?;
        self.trace_new(&sw.starts);
        self.sweeps.push(sw);
        Ok(true)
    }

    /// A line added by the run itself: a failed sweep there is no error
    /// (the line is only skipped).
    fn extra(&mut self, line: Line) -> bool {
        let inside = match line {
            Line::X(v) => (self.plane.x_range[0]..=self.plane.x_range[1]).contains(&v),
            Line::Y(v) => (self.plane.y_range[0]..=self.plane.y_range[1]).contains(&v),
        };
        inside && self.line(line).unwrap_or(false)
    }

    /// Whether a traced curve of the start's transition crosses the start's
    /// line at the start.
    fn on_curve(&self, start: &Start) -> bool {
        let along = |x: f64, y: f64| match start.line {
            Line::Y(_) => x,
            Line::X(_) => y,
        };
        let at = along(start.point.x, start.point.y);
        let tol = ON_CURVE * at.abs().max(1.0);
        let v = line_value(start.line);
        self.curves.iter().any(|c| {
            if c.kind != start.kind
                || c.boundary != start.boundary
                || !same_structure(
                    M::info(self.base),
                    c.structure.as_ref(),
                    start.structure.as_ref(),
                )
            {
                return false;
            }
            // Only a curve reaching the line can cross it.
            let across = |x: f64, y: f64| match start.line {
                Line::Y(_) => y,
                Line::X(_) => x,
            };
            let (lo, hi) = c
                .points
                .iter()
                .fold((f64::INFINITY, -f64::INFINITY), |b, p| {
                    let a = across(p.x, p.y);
                    (b.0.min(a), b.1.max(a))
                });
            if v < lo - tol || v > hi + tol {
                return false;
            }
            crossings::<M>(self.base, &self.plane, c, start.line, &self.settings.curve)
                .iter()
                .any(|q| (along(q.x, q.y) - at).abs() <= tol)
        })
    }

    /// The evenly spread lines, then (with `edges`) the box's four edges.
    /// Every curve that leaves the box crosses an edge: a sweep along the
    /// edges finds those whose transition it resolves there, wherever the
    /// inner lines pass them by. On Shaw's box (`coulomb`, `V = 0`) the top
    /// edge crosses a second symmetric motion's pitchfork that no inner
    /// line meets.
    pub fn spread(&mut self) {
        let n = self.settings.spread;
        let [xl, xh] = self.plane.x_range;
        let [yl, yh] = self.plane.y_range;
        for k in 1..=n {
            let f = k as f64 / (n + 1) as f64;
            self.extra(Line::Y(yl + f * (yh - yl)));
            self.extra(Line::X(xl + f * (xh - xl)));
        }
        if self.settings.edges {
            for line in [Line::Y(yl), Line::Y(yh), Line::X(xl), Line::X(xh)] {
                self.extra(line);
            }
        }
    }

    /// Lines through, and beside, every transition no traced curve passes.
    pub fn missing(&mut self) {
        let mut budget = self.settings.max_missing;
        let mut next = 0;
        // Lines added here are swept too and may show more such transitions.
        while next < self.sweeps.len() && budget > 0 {
            let starts = self.sweeps[next].starts.clone();
            next += 1;
            for start in starts {
                if budget == 0 {
                    break;
                }
                if !traceable(&start, self.settings.max_mappings) || self.on_curve(&start) {
                    continue;
                }
                let [xl, xh] = self.plane.x_range;
                let [yl, yh] = self.plane.y_range;
                let beside = |v: f64, lo: f64, hi: f64| {
                    let d = FINEST * (hi - lo);
                    if v + d <= hi {
                        v + d
                    } else {
                        v - d
                    }
                };
                let (through, near) = match start.line {
                    Line::Y(_) => (
                        Line::X(start.point.x),
                        Line::X(beside(start.point.x, xl, xh)),
                    ),
                    Line::X(_) => (
                        Line::Y(start.point.y),
                        Line::Y(beside(start.point.y, yl, yh)),
                    ),
                };
                for l in [through, near] {
                    if budget > 0 && self.extra(l) {
                        budget -= 1;
                    }
                }
            }
        }
    }

    /// Halfway lines between neighbouring parallel lines whose motions
    /// differ unexplained.
    pub fn refine(&mut self) {
        let mut budget = self.settings.max_refine;
        loop {
            let Some(line) = self.unexplained() else {
                return;
            };
            if budget == 0 || !self.extra(line) {
                return;
            }
            budget -= 1;
        }
    }

    /// Last, each failed start where an excursion of its motion shrinks to
    /// nothing, carried to the reduced motion ([`reduced_start`]), traced
    /// there unless a traced curve passes it: that motion's curve, which no
    /// line located (a period-2 `T T` with unequal halves, born at `T`'s
    /// period doubling). Last, so that such a curve changes none of the
    /// lines the run sweeps: traced as soon as its start failed, on
    /// `stribeck8` W = 0.95…1.02 × Q0 = 4.4…5.0 it explained the band whose
    /// unexplained motion makes the run add four refinement lines, and the
    /// four curves those lines find went unfound. A failed start whose
    /// reduced motion's curve is traced (from there, or already) is no
    /// missing curve: it leaves the failed list.
    pub fn carry(&mut self) {
        let failed = std::mem::take(&mut self.failed);
        for (start, why) in failed {
            if !self.on_curve(&start) {
                if let Some(r) = self.reduced(&start) {
                    if self.on_curve(&r) {
                        continue;
                    }
                    if let Ok(curve) = self.trace_start(&r, None) {
                        self.curves.push(curve);
                        continue;
                    }
                }
            }
            self.failed.push((start, why));
        }
    }

    /// Last, branch switching: from every codimension-two point of a traced
    /// curve (its codim-2 ends, and the fold and period-doubling points
    /// along a margin curve), the second condition's curve of the same
    /// motion ([`partner_start`]), traced unless a traced curve passes its
    /// start; the curves so found are switched from in turn, at most
    /// `max_partners` traces in all. What a line finds only where it
    /// happens to cross the curve (the tips of a period-adding cascade's
    /// bands, where a grazing meets a passable onset) is found from the
    /// point where it meets a curve a line did find.
    pub fn partners(&mut self) {
        let mut budget = self.settings.max_partners;
        let mut next = 0;
        while next < self.curves.len() && budget > 0 {
            let curve = self.curves[next].clone();
            next += 1;
            for place in codim2_places(&curve) {
                // A smaller step where the first one's start fails another
                // condition: a third curve passing near the point.
                for step in [PARTNER_STEP, PARTNER_STEP / 16.0] {
                    if budget == 0 {
                        break;
                    }
                    let Some(s) = partner_start::<M>(
                        self.base,
                        &self.plane,
                        &curve,
                        &place,
                        step,
                        self.settings.curve.tolerance,
                    ) else {
                        continue;
                    };
                    let start = Start {
                        kind: s.kind,
                        boundary: s.boundary,
                        structure: Some(s.structure),
                        condition: s.condition,
                        line: if s.horizontal {
                            Line::X(s.point.x)
                        } else {
                            Line::Y(s.point.y)
                        },
                        point: s.point,
                    };
                    if !traceable(&start, self.settings.max_mappings) || self.on_curve(&start) {
                        break;
                    }
                    budget -= 1;
                    let Ok(traced) = self.trace_start(&start, Some(curve.condition)) else {
                        continue;
                    };
                    if partial(&self.plane, &traced)
                        || inadmissible_point::<M>(self.base, &self.plane, &traced).is_some()
                    {
                        break;
                    }
                    // Named by its trace (an arrival's margin may mark a
                    // passable onset): passed by a traced curve so named?
                    let renamed = traced.kind != start.kind;
                    let named = Start {
                        kind: traced.kind,
                        ..start
                    };
                    if !renamed || !self.on_curve(&named) {
                        self.curves.push(traced);
                    }
                    break;
                }
            }
        }
    }

    /// A short sweep across every curve the lines traced, at `probes`
    /// places spread along it, each transition found there traced unless a
    /// traced curve passes it: what lies across a border where no line
    /// crosses it (a band that opens between two curves where they cross,
    /// such as a period-adding cascade between a grazing and a passable
    /// onset). One round: the curves the probes trace are not probed in
    /// turn (the bands between a cascade's bands, each of longer motions,
    /// would follow in hundreds).
    pub fn probe(&mut self) {
        let lined = self.curves.len();
        for next in 0..lined {
            let places = probe_places(&self.plane, &self.curves[next], self.settings.probes);
            for (line, range) in places {
                let sw = sweep_line::<M>(
                    self.base,
                    &self.plane,
                    line,
                    Some(range),
                    PROBE_COUNT,
                    self.sweep_options(),
                );
                if let Ok(sw) = sw {
                    self.trace_new(&sw.starts);
                }
            }
        }
    }

    /// The first halfway line (horizontal lines first, lowest first) between
    /// neighbours that disagree unexplained.
    fn unexplained(&self) -> Option<Line> {
        let spans = [
            self.plane.y_range[1] - self.plane.y_range[0],
            self.plane.x_range[1] - self.plane.x_range[0],
        ];
        for (horizontal, span) in [(true, spans[0]), (false, spans[1])] {
            let mut lines: Vec<(f64, &LineSweep)> = self
                .sweeps
                .iter()
                .filter_map(|s| match (s.line, horizontal) {
                    (Line::Y(v), true) | (Line::X(v), false) => Some((v, s)),
                    _ => None,
                })
                .collect();
            lines.sort_by(|a, b| a.0.total_cmp(&b.0));
            for w in lines.windows(2) {
                let ((a, sa), (b, sb)) = (w[0], w[1]);
                if b - a < 2.0 * FINEST * span {
                    continue;
                }
                let (ma, mb) = (
                    motions(sa, self.settings.max_mappings),
                    motions(sb, self.settings.max_mappings),
                );
                let differ = ma
                    .iter()
                    .filter(|m| !mb.contains(m))
                    .chain(mb.iter().filter(|m| !ma.contains(m)));
                for m in differ {
                    if !self.runs_between(m, horizontal, a, b) {
                        let mid = 0.5 * (a + b);
                        return Some(if horizontal {
                            Line::Y(mid)
                        } else {
                            Line::X(mid)
                        });
                    }
                }
            }
        }
        None
    }

    /// Whether a curve of motion `name` (its notation, without `^N`) has a
    /// point strictly between the lines `a < b` (horizontal lines: in `y`).
    fn runs_between(&self, name: &str, horizontal: bool, a: f64, b: f64) -> bool {
        self.curves.iter().any(|c| {
            let own = match &c.structure {
                None => "NM".to_string(),
                Some(s) => s.notation(M::info(self.base)),
            };
            own == name
                && c.points.iter().any(|p| {
                    let v = if horizontal { p.y } else { p.x };
                    v > a && v < b
                })
        })
    }

    /// The curves in a stable order, their codim-2 points and `--at` crossings.
    pub fn finish(self, opts: &CurvesOptions) -> (CurveSet, Vec<Curve>) {
        // A failed start that a curve traced from elsewhere passes is no
        // missing curve (one carried to the reduced motion's curve is
        // dropped by `carry`).
        let failed_starts = self
            .failed
            .iter()
            .filter(|(start, _)| !self.on_curve(start))
            .map(|(start, why)| FailedStart {
                kind: start.kind,
                boundary: start
                    .boundary
                    .map(|k| M::info(self.base).boundaries[k].label.to_string()),
                structure: structure_name(M::info(self.base), start.structure.as_ref()),
                point: [start.point.x, start.point.y],
                why: why.clone(),
            })
            .collect();
        let mut curves = self.curves;
        let key = |c: &Curve| {
            let first = c
                .points
                .iter()
                .map(|p| (p.x, p.y))
                .min_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)))
                .unwrap_or((f64::NAN, f64::NAN));
            (
                c.kind.name(),
                c.boundary,
                structure_name(M::info(self.base), c.structure.as_ref()),
                first,
            )
        };
        curves.sort_by(|a, b| {
            let (ka, kb) = (key(a), key(b));
            (ka.0, ka.1, &ka.2)
                .cmp(&(kb.0, kb.1, &kb.2))
                .then(ka.3 .0.total_cmp(&kb.3 .0))
                .then(ka.3 .1.total_cmp(&kb.3 .1))
        });
        let codim2 = codim2_points(&self.plane, &curves);
        let summaries = curves
            .iter()
            .map(|c| {
                let end = |k: usize| {
                    let e = c.ends.get(k)?;
                    let (reason, detail) = match &e.reason {
                        CurveEndReason::BoxEdge => ("box_edge", None),
                        CurveEndReason::Codim2 { .. } => ("codim2", None),
                        CurveEndReason::NewtonFailure(why) => ("newton_failure", Some(why.clone())),
                        CurveEndReason::MaxPoints => ("max_points", None),
                    };
                    let codim2 = matches!(e.reason, CurveEndReason::Codim2 { .. })
                        .then(|| {
                            codim2.iter().position(|q| {
                                same_place(&self.plane, SAME_PLACE, (q.x, q.y), (e.at.x, e.at.y))
                            })
                        })
                        .flatten();
                    Some(EndSummary {
                        reason: reason.to_string(),
                        point: [e.at.x, e.at.y],
                        codim2,
                        detail,
                        residual: codim2_residual::<M>(self.base, &self.plane, c, e),
                    })
                };
                let at = opts
                    .at
                    .iter()
                    .flat_map(|&l| {
                        crossings::<M>(self.base, &self.plane, c, l, &self.settings.curve)
                    })
                    .map(|q| [q.x, q.y])
                    .collect();
                CurveSummary {
                    kind: c.kind,
                    boundary: c
                        .boundary
                        .map(|k| M::info(self.base).boundaries[k].label.to_string()),
                    structure: structure_name(M::info(self.base), c.structure.as_ref()),
                    from: end(0),
                    to: end(1),
                    points: c.points.iter().map(|p| [p.x, p.y]).collect(),
                    at,
                }
            })
            .collect();
        let set = CurveSet {
            x: opts.x.clone(),
            y: opts.y.clone(),
            curves: summaries,
            codim2,
            failed_starts,
        };
        (set, curves)
    }
}

/// Where to probe across `curve`: `n` places evenly spread along its
/// arclength (in units of the box's spans), each a line across the curve
/// (vertical where the curve runs more horizontally) reaching [`FINEST`] of
/// the span to each side, within the box.
fn probe_places(plane: &Plane, curve: &Curve, n: usize) -> Vec<(Line, [f64; 2])> {
    let [xl, xh] = plane.x_range;
    let [yl, yh] = plane.y_range;
    let (sx, sy) = (xh - xl, yh - yl);
    let scaled: Vec<(f64, f64)> = curve.points.iter().map(|p| (p.x / sx, p.y / sy)).collect();
    let mut along = vec![0.0];
    for w in scaled.windows(2) {
        let last = along[along.len() - 1];
        along.push(last + (w[1].0 - w[0].0).hypot(w[1].1 - w[0].1));
    }
    let total = along[along.len() - 1];
    if scaled.len() < 2 || total.is_nan() || total <= 0.0 {
        return Vec::new();
    }
    (0..n)
        .filter_map(|k| {
            let s = (k as f64 + 0.5) / n as f64 * total;
            let i = along
                .partition_point(|&a| a <= s)
                .clamp(1, scaled.len() - 1)
                - 1;
            let (a, b) = (scaled[i], scaled[i + 1]);
            let len = along[i + 1] - along[i];
            let f = if len > 0.0 {
                ((s - along[i]) / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            let (x, y) = ((a.0 + f * (b.0 - a.0)) * sx, (a.1 + f * (b.1 - a.1)) * sy);
            let (line, lo, hi) = if (b.0 - a.0).abs() >= (b.1 - a.1).abs() {
                let d = FINEST * sy;
                (Line::X(x), (y - d).max(yl), (y + d).min(yh))
            } else {
                let d = FINEST * sx;
                (Line::Y(y), (x - d).max(xl), (x + d).min(xh))
            };
            (lo < hi).then_some((line, [lo, hi]))
        })
        .collect()
}

/// The motions seen anywhere along a line (by notation, without `^N`), of
/// at most `max_mappings` mappings (a compact `(P_{…})^{×k}` counts its
/// block `k` times).
fn motions(s: &LineSweep, max_mappings: usize) -> Vec<&str> {
    let mut out: Vec<&str> = s
        .labels
        .iter()
        .flat_map(|l| l.split(';'))
        .filter(|m| !m.is_empty() && *m != "stick")
        .filter(|m| m.split_whitespace().count() * grammar::repeats(m) <= max_mappings)
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

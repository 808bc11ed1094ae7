//! Mapping structures `P_{σm … σ2 σ1}` (SPEC §6): parsed and printed in the
//! paper's notation, applied right to left, validated against the model's
//! topology.

use stickslip_codegen::structure as grammar;

use crate::model::{MappingKind, ModelInfo, Side};

/// Why a structure was rejected (the grammar and its errors are shared with
/// the model checker: `stickslip_codegen::structure`).
pub use stickslip_codegen::structure::StructureError;

/// A mapping structure with its period `N` (forcing periods per cycle), or
/// the structure of an autonomous cycle (an unforced model, SPEC §14), whose
/// period is an unknown (`N = 0`).
///
/// An autonomous cycle's switching points are held in one gauge: time has
/// no origin, so the cycle's return to its first point is put at `W t = 0`
/// and the first point's phase is `−W T` ([`Structure::shift`]). The
/// unknowns of the forced case, `(x_k, W t_k)`, then serve unchanged: the
/// first point's phase carries the period.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Structure {
    /// Indices into `ModelInfo::mappings`, in application order (`σ1` first);
    /// stick mappings resolved to the exit side the next mapping needs.
    steps: Vec<usize>,
    /// Forcing periods per cycle; 0 for an autonomous cycle.
    periods: u32,
}

impl Structure {
    /// Parse `P_{3_31 0_11 3_13 4_33}`, `P{..}` or `3_31 0_11 3_13 4_33`
    /// (applied right to left: `4_33` first) for model `info`, with period
    /// `periods`. The grammar is `stickslip_codegen::structure`, the one the
    /// model checker applies to a scene's structures.
    pub fn parse(info: &ModelInfo, text: &str, periods: u32) -> Result<Self, StructureError> {
        let mut names = grammar::written_names(text)?;
        names.reverse();
        Self::from_names(info, &names, periods)
    }

    /// Build from mapping names in application order.
    pub fn from_names(
        info: &ModelInfo,
        applied: &[&str],
        periods: u32,
    ) -> Result<Self, StructureError> {
        if applied.is_empty() {
            return Err(StructureError::Empty);
        }
        if periods == 0 {
            return Err(StructureError::ZeroPeriod);
        }
        let views: Vec<grammar::MappingView> = info
            .mappings
            .iter()
            .map(|m| grammar::MappingView {
                name: m.name,
                from: m.from,
                to: m.to,
                domain_above_from: m.domain.map(|j| info.domains[j].lower == Some(m.from)),
            })
            .collect();
        let labels: Vec<&str> = info.boundaries.iter().map(|b| b.label).collect();
        let resolved = grammar::resolve(info.name, &views, &labels, applied)?;
        let mut steps = Vec::with_capacity(resolved.len());
        for (i, exit) in resolved {
            let idx = match exit {
                None => i,
                Some(e) => {
                    let side = match e {
                        grammar::Exit::Above => Side::Above,
                        grammar::Exit::Below => Side::Below,
                    };
                    info.mapping_index(info.mappings[i].name, Some(side))
                        .ok_or_else(|| {
                            StructureError::StickExit(info.mappings[i].name.to_string())
                        })?
                }
            };
            steps.push(idx);
        }
        Ok(Self { steps, periods })
    }

    /// The structure of an autonomous cycle (period unknown) from mapping
    /// indices in application order.
    pub fn autonomous(info: &ModelInfo, applied: &[usize]) -> Result<Self, StructureError> {
        let mut s = Self::from_indices(info, applied, 1)?;
        s.periods = 0;
        Ok(s)
    }

    /// Whether this is an autonomous cycle's structure (period unknown).
    pub fn is_autonomous(&self) -> bool {
        self.periods == 0
    }

    /// The phase `W t` from the first switching point (at phase `first`)
    /// to the cycle's return to it: `2π N`, or for an autonomous cycle (held
    /// with its return at `W t = 0`) `−first`.
    pub fn shift(&self, first: f64) -> f64 {
        if self.is_autonomous() {
            -first
        } else {
            std::f64::consts::TAU * self.periods as f64
        }
    }

    /// Build from mapping indices in application order (as found by simulation).
    pub fn from_indices(
        info: &ModelInfo,
        applied: &[usize],
        periods: u32,
    ) -> Result<Self, StructureError> {
        let names: Vec<&str> = applied.iter().map(|&i| info.mappings[i].name).collect();
        Self::from_names(info, &names, periods)
    }

    /// The mapping indices in application order.
    pub fn steps(&self) -> &[usize] {
        &self.steps
    }

    /// Number of mappings `m`.
    pub fn len(&self) -> usize {
        self.steps.len()
    }

    /// Always false: a structure has at least one mapping.
    pub fn is_empty(&self) -> bool {
        self.steps.is_empty()
    }

    /// Forcing periods per cycle.
    pub fn periods(&self) -> u32 {
        self.periods
    }

    /// The structure applied `k` times in a row: `k·N` forcing periods
    /// (a motion of `structure` is also one of `structure.repeated(k)`).
    pub fn repeated(&self, k: u32) -> Self {
        let k = k.max(1);
        Self {
            steps: self
                .steps
                .iter()
                .copied()
                .cycle()
                .take(self.steps.len() * k as usize)
                .collect(),
            periods: self.periods * k,
        }
    }

    /// `T` where this structure is `T T`: two equal halves, each over half
    /// the forcing periods (a motion of `T` is also one of `T T`, see
    /// [`Self::repeated`]). `None` for any other structure.
    pub fn half(&self) -> Option<Self> {
        let h = self.steps.len() / 2;
        let halves = h > 0
            && self.steps.len() % 2 == 0
            && self.periods % 2 == 0
            && self.steps[..h] == self.steps[h..];
        halves.then(|| Self {
            steps: self.steps[..h].to_vec(),
            periods: self.periods / 2,
        })
    }

    /// Whether any mapping is the stick mapping.
    pub fn has_stick(&self, info: &ModelInfo) -> bool {
        self.steps
            .iter()
            .any(|&i| info.mappings[i].kind == MappingKind::Stick)
    }

    /// The same cycle started at its canonical mapping: the rotation whose
    /// sequence of (domain, from, to) is smallest, domains lowest band first
    /// and the stick mapping last. The reference motions start this way (at
    /// `4_33` for the paper model). Returns the rotation offset too.
    pub fn canonical(&self, info: &ModelInfo) -> (Self, usize) {
        let key = |i: usize| {
            let m = &info.mappings[i];
            (m.domain.unwrap_or(usize::MAX), m.from, m.to)
        };
        let m = self.steps.len();
        let best = (0..m)
            .min_by(|&r, &s| {
                let a = (0..m).map(|k| key(self.steps[(r + k) % m]));
                let b = (0..m).map(|k| key(self.steps[(s + k) % m]));
                a.cmp(b)
            })
            .unwrap_or(0);
        let steps = (0..m).map(|k| self.steps[(best + k) % m]).collect();
        (
            Self {
                steps,
                periods: self.periods,
            },
            best,
        )
    }

    /// The paper's notation, `P_{σm … σ1}`; a block repeated `k ≥ 2`
    /// times (a period-doubling cascade's motions) as `(P_{block})^{×k}`.
    pub fn notation(&self, info: &ModelInfo) -> String {
        let names: Vec<&str> = self
            .steps
            .iter()
            .rev()
            .map(|&i| info.mappings[i].name)
            .collect();
        grammar::notation(&names)
    }

    /// Its name with its period: [`Structure::notation`], with `^N` where
    /// the notation does not imply `N` (`P_{…}^2`; `(P_{…})^{×8}` is a
    /// motion of 8 forcing periods).
    pub fn label(&self, info: &ModelInfo) -> String {
        if self.is_autonomous() {
            return self.notation(info);
        }
        grammar::with_periods(&self.notation(info), self.periods)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::models::paper::Paper;

    #[test]
    fn parses_both_notations_and_applies_right_to_left() {
        let info = Paper::INFO;
        let a = Structure::parse(info, "P_{3_31 0_11 3_13 4_33}", 1).unwrap();
        let b = Structure::parse(info, "3_31 0_11 3_13 4_33", 1).unwrap();
        assert_eq!(a, b);
        let names: Vec<&str> = a.steps().iter().map(|&i| info.mappings[i].name).collect();
        assert_eq!(names, ["4_33", "3_13", "0_11", "3_31"]);
        assert_eq!(a.notation(info), "P_{3_31 0_11 3_13 4_33}");
        // 0_11 is followed by 3_31 (domain 3 lies below Sigma1): it leaves downwards.
        assert_eq!(info.mappings[a.steps()[2]].exit, Some(Side::Below));
    }

    #[test]
    fn rejects_disconnected_and_unknown_mappings() {
        let info = Paper::INFO;
        let e = Structure::parse(info, "P_{1_22 3_13 4_33}", 1).unwrap_err();
        assert_eq!(
            e.to_string(),
            "3_13 ends on Sigma1, but 1_22 starts on Sigma2"
        );
        let e = Structure::parse(info, "P_{3_31 9_99}", 1).unwrap_err();
        assert!(matches!(e, StructureError::UnknownMapping { .. }), "{e}");
        assert_eq!(
            Structure::parse(info, "P_{}", 1).unwrap_err(),
            StructureError::Empty
        );
        assert_eq!(
            Structure::parse(info, "3_33 4_33", 0).unwrap_err(),
            StructureError::ZeroPeriod
        );
    }

    #[test]
    fn a_structure_of_two_equal_halves_has_a_half() {
        let info = Paper::INFO;
        let t = Structure::parse(info, "P_{3_31 0_11 3_13 4_33}", 1).unwrap();
        assert_eq!(t.repeated(2).half(), Some(t.clone()));
        // Not two halves: an odd count, one period, unequal halves.
        assert_eq!(t.half(), None);
        let s = Structure::parse(info, "P_{3_33 4_33 3_33 4_33}", 2).unwrap();
        assert_eq!(s.half().map(|h| (h.len(), h.periods())), Some((2, 1)));
        assert_eq!(
            Structure::parse(info, "P_{3_33 4_33 3_33 4_33}", 1)
                .unwrap()
                .half(),
            None
        );
        let u = "P_{3_31 0_11 3_13 4_33 3_31 1_11 3_13 4_33}";
        assert_eq!(Structure::parse(info, u, 2).unwrap().half(), None);
    }

    #[test]
    fn canonical_rotation_starts_at_the_lowest_domain() {
        let info = Paper::INFO;
        let s = Structure::parse(info, "P_{3_13 4_33 3_31 1_12 2_22 1_21}", 1).unwrap();
        let (c, _) = s.canonical(info);
        assert_eq!(c.notation(info), "P_{3_31 1_12 2_22 1_21 3_13 4_33}");
    }
}

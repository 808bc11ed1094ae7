//! `stickslip describe`: what a model is, at given parameters.

use serde::Serialize;

use crate::model::param::ParamSet;
use crate::model::{Model, Regime};
use crate::orbit::equilibrium::{steady_sliding, Equilibrium};

/// A domain at given parameters.
#[derive(Clone, Debug, Serialize)]
pub struct DomainDescription {
    /// Label (`1`).
    pub label: u32,
    /// Lower band edge (`None`: unbounded).
    pub v_min: Option<f64>,
    /// Upper band edge (`None`: unbounded).
    pub v_max: Option<f64>,
    /// `2 d_j`.
    pub two_d: f64,
    /// `c_j`.
    pub c: f64,
    /// `b_j`.
    pub b: f64,
    /// Damping regime.
    pub regime: Regime,
}

/// A boundary at given parameters.
#[derive(Clone, Debug, Serialize)]
pub struct BoundaryDescription {
    /// Label (`Sigma1`).
    pub label: String,
    /// Velocity.
    pub v: f64,
    /// Whether static friction acts here.
    pub stick: bool,
    /// `as` on the stick boundary, else `None`.
    pub static_bound: Option<f64>,
}

/// What `describe` prints (the `--json` form is this, serialized).
#[derive(Clone, Debug, Serialize)]
pub struct Description {
    /// Model (or `model::scene`) name.
    pub model: String,
    /// Free parameters and their values, in declaration order.
    pub params: serde_json::Map<String, serde_json::Value>,
    /// Domains, by label.
    pub domains: Vec<DomainDescription>,
    /// Boundaries, by label.
    pub boundaries: Vec<BoundaryDescription>,
    /// The generated mappings.
    pub mappings: Vec<String>,
    /// With no forcing, steady sliding: its rest position, eigenvalues and
    /// stability (as `simulate --json` gives it).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub steady_sliding: Option<Equilibrium>,
    /// Where it rests (`domain 15`; text output only).
    #[serde(skip)]
    pub seat: String,
}

/// Describe model `M` at parameters `p`.
pub fn describe<M: Model>(p: &M::Params) -> Description {
    let info = M::info(p);
    let mut params = serde_json::Map::new();
    for (k, name) in p.names().iter().enumerate() {
        params.insert(name.to_string(), serde_json::json!(p.get(k)));
    }
    let vel = |k: Option<usize>| k.map(|k| M::boundary_velocity(p, k));
    let mut domains: Vec<DomainDescription> = info
        .domains
        .iter()
        .enumerate()
        .map(|(j, d)| {
            let c = M::coefficients(p, j);
            DomainDescription {
                label: d.label,
                v_min: vel(d.lower),
                v_max: vel(d.upper),
                two_d: c.two_d,
                c: c.c,
                b: c.b,
                regime: c.regime(),
            }
        })
        .collect();
    domains.sort_by_key(|d| d.label);
    let mut boundaries: Vec<BoundaryDescription> = info
        .boundaries
        .iter()
        .enumerate()
        .map(|(k, b)| BoundaryDescription {
            label: b.label.to_string(),
            v: M::boundary_velocity(p, k),
            stick: b.stick,
            static_bound: if b.stick { M::static_bound(p) } else { None },
        })
        .collect();
    boundaries.sort_by_key(|b| {
        info.boundaries
            .iter()
            .find(|x| x.label == b.label)
            .map(|x| x.number)
    });
    let steady = steady_sliding::<M>(p).ok();
    Description {
        model: info.name.to_string(),
        params,
        domains,
        boundaries,
        mappings: info.mapping_names().into_iter().map(String::from).collect(),
        seat: steady.map_or_else(String::new, |e| e.seat.label(info)),
        steady_sliding: steady,
    }
}

fn fmt_edge(v: Option<f64>, unbounded: &str) -> String {
    v.map_or_else(|| unbounded.to_string(), |v| format!("{v}"))
}

impl std::fmt::Display for Description {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        writeln!(f, "model {}", self.model)?;
        let params: Vec<String> = self
            .params
            .iter()
            .map(|(k, v)| format!("{k} = {v}"))
            .collect();
        writeln!(f, "parameters: {}", params.join(", "))?;
        writeln!(f, "\ndomains:")?;
        writeln!(
            f,
            "  {:>5}  {:>22}  {:>10}  {:>10}  {:>10}  regime",
            "label", "band", "2d_j", "c_j", "b_j"
        )?;
        for d in &self.domains {
            let band = format!(
                "({}, {})",
                fmt_edge(d.v_min, "-inf"),
                fmt_edge(d.v_max, "+inf")
            );
            writeln!(
                f,
                "  {:>5}  {:>22}  {:>10.6}  {:>10.6}  {:>10.6}  {}",
                d.label,
                band,
                d.two_d,
                d.c,
                d.b,
                d.regime.name()
            )?;
        }
        writeln!(f, "\nboundaries:")?;
        for b in &self.boundaries {
            match b.static_bound {
                Some(s) => writeln!(
                    f,
                    "  {:<8} v = {:<10} stick, static bound as = {s}",
                    b.label, b.v
                )?,
                None => writeln!(f, "  {:<8} v = {:<10} continuous", b.label, b.v)?,
            }
        }
        writeln!(
            f,
            "\nmappings ({}): {}",
            self.mappings.len(),
            self.mappings.join(" ")
        )?;
        if let Some(e) = &self.steady_sliding {
            writeln!(
                f,
                "\n{}",
                crate::output::text::steady_sliding_line(e, &self.seat)
            )?;
        }
        Ok(())
    }
}

//! The equations of SPEC §3–5 as expressions in an instance's graph: the
//! closed-form flow of a domain, the mapping residuals, the normal vector
//! field and its rate, and the force criteria on the stick boundary.
//!
//! Fourth pass: [`build`] forms, for every instance of [`crate::expand`],
//! each quantity its generated functions return, as graph nodes
//! ([`Equations`], [`SmoothEquations`]); exact derivatives by
//! [`Graph::diff`]. Nothing here knows about Rust syntax: [`crate::emit`]
//! turns the nodes into code.

use proc_macro2::{Ident, Span};

use crate::diagnostic::Diagnostics;
use crate::expand::{Expanded, Header, Instance, Main, Route, Smooth};
use crate::expr::{Graph, Hom, Id};
use crate::lowered::{Lowered, LAW_V};

/// `(x, v)` at phase `phi1` of the flow in domain `j` started at
/// `(x0, v0)` at phase `phi0` (SPEC §4, Appendix A).
///
/// With `A, B, C` the forced response (A.4–A.5), `X0, Y0` the initial offset
/// from it and `tau = (phi1 - phi0) / W` the elapsed time:
///
/// `x = Ec X0 + Es (Y0 + d_j X0) + x_p(phi1)`,
/// `v = Ec Y0 - Es (c_j X0 + d_j Y0) + v_p(phi1)`,
///
/// where `Ec, Es` are the fused `exp(-d tau) cosh/sinh` functions that stay
/// exact through critical damping (see [`Hom`]).
pub fn flow(inst: &mut Lowered, j: usize, x0: Id, v0: Id, phi0: Id, phi1: Id) -> (Id, Id) {
    let dn = inst.domains[j];
    let (w, a0) = (inst.frequency, inst.forcing);
    let g = &mut inst.graph;
    let (d, c, b) = (dn.d, dn.c, dn.b);
    let w_sq = g.powi(w, 2);
    let c_minus = g.sub(c, w_sq);
    let two = g.constant(2.0);
    let two_d = g.mul(two, d);
    let two_dw = g.mul(two_d, w);
    let cm2 = g.powi(c_minus, 2);
    let tdw2 = g.powi(two_dw, 2);
    let den = g.add(cm2, tdw2);
    let a_num = g.mul(a0, c_minus);
    let a = g.div(a_num, den);
    let b_num = g.mul(two_dw, a0);
    let bb = g.div(b_num, den);
    let nb = g.neg(b);
    let cc = g.div(nb, c);
    let (xp0, vp0) = particular(g, a, bb, cc, w, phi0);
    let (xp1, vp1) = particular(g, a, bb, cc, w, phi1);
    let x_off = g.sub(x0, xp0);
    let y_off = g.sub(v0, vp0);
    let dphi = g.sub(phi1, phi0);
    let tau = g.div(dphi, w);
    let ec = g.hom(Hom::Ec, d, c, tau);
    let es = g.hom(Hom::Es, d, c, tau);
    // x_h = Ec X0 + Es (Y0 + d X0)
    let dx = g.mul(d, x_off);
    let ydx = g.add(y_off, dx);
    let t1 = g.mul(ec, x_off);
    let t2 = g.mul(es, ydx);
    let xh = g.add(t1, t2);
    // v_h = Ec Y0 - Es (c X0 + d Y0)
    let cx = g.mul(c, x_off);
    let dy = g.mul(d, y_off);
    let cxdy = g.add(cx, dy);
    let t3 = g.mul(ec, y_off);
    let t4 = g.mul(es, cxdy);
    let vh = g.sub(t3, t4);
    (g.add(xh, xp1), g.add(vh, vp1))
}

/// The forced response `x_p = A cos(phi) + B sin(phi) + C` and its velocity.
fn particular(g: &mut Graph, a: Id, b: Id, c: Id, w: Id, phi: Id) -> (Id, Id) {
    let (cs, sn) = (g.cos(phi), g.sin(phi));
    let acos = g.mul(a, cs);
    let bsin = g.mul(b, sn);
    let s = g.add(acos, bsin);
    let x = g.add(s, c);
    let asin = g.mul(a, sn);
    let bcos = g.mul(b, cs);
    let dv = g.sub(bcos, asin);
    (x, g.mul(w, dv))
}

/// Residual of a flow mapping in domain `j` from boundary `from` to `to`
/// (Eq. 38): `f1 = x_j(t_{i+1}) - x_{i+1}`, `f2 = y_j(t_{i+1}) - V_β`.
pub fn flow_mapping(
    inst: &mut Lowered,
    j: usize,
    from: usize,
    to: usize,
    vars: [Id; 4],
) -> [Id; 2] {
    let [x0, phi0, x1, phi1] = vars;
    let (va, vb) = (inst.boundary_velocity[from], inst.boundary_velocity[to]);
    let (x, v) = flow(inst, j, x0, va, phi0, phi1);
    let g = &mut inst.graph;
    [g.sub(x, x1), g.sub(v, vb)]
}

/// Residual of the stick mapping on boundary `k` with static bound `bound` (Eq. 37), leaving to the
/// domain above (`sign = +1`) or below (`sign = -1`):
/// `f1 = x_i + V (t_{i+1} - t_i) - x_{i+1}`,
/// `f2 = A0 cos(W t_{i+1}) - 2 d V - c x_{i+1} - sign * as`.
pub fn stick_mapping(inst: &mut Lowered, k: usize, bound: Id, sign: f64, vars: [Id; 4]) -> [Id; 2] {
    let [x0, phi0, x1, phi1] = vars;
    let vs = inst.boundary_velocity[k];
    let (w, a0, d, c) = (inst.frequency, inst.forcing, inst.damping, inst.stiffness);
    let g = &mut inst.graph;
    let dphi = g.sub(phi1, phi0);
    let tau = g.div(dphi, w);
    let vt = g.mul(vs, tau);
    let s = g.add(x0, vt);
    let f1 = g.sub(s, x1);
    let fnf = non_friction_force(g, a0, d, c, vs, x1, phi1);
    let sg = g.constant(sign);
    let sb = g.mul(sg, bound);
    let f2 = g.sub(fnf, sb);
    [f1, f2]
}

/// `Fnf = A0 cos(phi) - 2 d V - c x` (Eq. 2).
fn non_friction_force(g: &mut Graph, a0: Id, d: Id, c: Id, vs: Id, x: Id, phi: Id) -> Id {
    let cs = g.cos(phi);
    let f = g.mul(a0, cs);
    let two = g.constant(2.0);
    let tdv = g.mul(two, d);
    let tdv = g.mul(tdv, vs);
    let cx = g.mul(c, x);
    let s = g.sub(f, tdv);
    g.sub(s, cx)
}

/// The normal component of the vector field in domain `j` (Eq. 10),
/// `F_j = A0 cos(phi) - f_j(y) - 2 d y - c x`, and its rate along the flow
/// (Eqs. 21–23), `DF_j = F_x y + F_y F_j + F_phi W`.
pub fn normal_field(inst: &mut Lowered, j: usize, vars: [Id; 3]) -> (Id, Id) {
    let [x, y, phi] = vars;
    let law = inst.domains[j].law;
    let (w, a0, d, c) = (inst.frequency, inst.forcing, inst.damping, inst.stiffness);
    let g = &mut inst.graph;
    let f = g.substitute(law, LAW_V, y);
    let cs = g.cos(phi);
    let forcing = g.mul(a0, cs);
    let two = g.constant(2.0);
    let tdy = g.mul(two, d);
    let tdy = g.mul(tdy, y);
    let cx = g.mul(c, x);
    let s = g.sub(forcing, f);
    let s = g.sub(s, tdy);
    let field = g.sub(s, cx);
    let rate = (|| -> Result<Id, crate::expr::DiffError> {
        let fx = g.diff(field, var_index(g, x))?;
        let fy = g.diff(field, var_index(g, y))?;
        let fp = g.diff(field, var_index(g, phi))?;
        let a = g.mul(fx, y);
        let b = g.mul(fy, field);
        let cc = g.mul(fp, w);
        let ab = g.add(a, b);
        Ok(g.add(ab, cc))
    })()
    .expect("the normal field depends on x, y, phi only through elementary functions");
    (field, rate)
}

fn var_index(g: &Graph, id: Id) -> u32 {
    match g.node(id) {
        crate::expr::Node::Var(k) => k,
        _ => unreachable!("normal_field takes variables"),
    }
}

/// Forces on the stick boundary `k` at `(x, phi)` (Eqs. 24–25):
/// `[Fnf, F_in above, F_in below, F_out above, F_out below]` with
/// `F_in = Fnf - f(V±)` (kinetic) and `F_out = Fnf ∓ as` (static).
pub fn stick_forces(inst: &mut Lowered, k: usize, bound: Id, vars: [Id; 2]) -> [Id; 5] {
    let [x, phi] = vars;
    let vs = inst.boundary_velocity[k];
    let (above, below) = (k + 1, k);
    let (la, lb) = (inst.domains[above].law, inst.domains[below].law);
    let (a0, d, c) = (inst.forcing, inst.damping, inst.stiffness);
    let g = &mut inst.graph;
    let fnf = non_friction_force(g, a0, d, c, vs, x, phi);
    let fa = g.substitute(la, LAW_V, vs);
    let fb = g.substitute(lb, LAW_V, vs);
    [
        fnf,
        g.sub(fnf, fa),
        g.sub(fnf, fb),
        g.sub(fnf, bound),
        g.add(fnf, bound),
    ]
}

/// Kinetic friction levels on both sides of the stick boundary `k`,
/// `(f_above(V), f_below(V))`.
pub fn kinetic_levels(inst: &mut Lowered, k: usize) -> (Id, Id) {
    let vs = inst.boundary_velocity[k];
    let (la, lb) = (inst.domains[k + 1].law, inst.domains[k].law);
    let g = &mut inst.graph;
    (g.substitute(la, LAW_V, vs), g.substitute(lb, LAW_V, vs))
}

/// The equations of every generated type of one model file.
pub struct Generation {
    /// What the `@generated` header says.
    pub header: Header,
    /// The model's own type.
    pub main: MainEquations,
    /// Each scene: its module, its doc line, its equations.
    pub scenes: Vec<(Ident, String, Equations)>,
}

/// The model's own type.
pub enum MainEquations {
    /// Affine domains.
    Piecewise(Box<Equations>),
    /// A smooth law.
    Smooth(Box<SmoothEquations>),
}

/// The damping regime of a domain when it is known at build time.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Regime {
    /// `d_j^2 < c_j`.
    Underdamped,
    /// `d_j^2 > c_j`.
    Overdamped,
    /// `d_j^2 = c_j`.
    Critical,
}

/// The parameter conditions `check` tests at run time.
pub struct Conditions {
    /// `m`, `c`, `W`.
    pub mass: Id,
    /// See `mass`.
    pub stiffness: Id,
    /// See `mass`.
    pub frequency: Id,
    /// The boundaries' velocities.
    pub velocities: Vec<Id>,
    /// Static bound and kinetic levels above and below the stick boundary.
    pub stick: Option<[Id; 3]>,
}

/// One domain's functions.
pub struct DomainEquations {
    /// `[2 d_j, c_j, b_j]`.
    pub coefficients: [Id; 3],
    /// The regime, when fixed at build time.
    pub regime: Option<Regime>,
    /// `[x, v]` of the flow, in the variables `x0, v0, phi0, phi1`.
    pub flow: [Id; 2],
    /// `[F, DF]`, in the variables `x, y, phi`.
    pub field: [Id; 2],
}

/// One generated mapping's residual and Jacobian blocks, in the variables
/// `x0, phi0, x1, phi1`.
pub struct MappingEquations {
    /// `[f1, f2]`.
    pub residual: [Id; 2],
    /// `∂f_i/∂(x0, phi0, x1, phi1)`, row by row.
    pub jacobian: [Id; 8],
}

/// The stick boundary's functions.
pub struct StickEquations {
    /// `[Fnf, F_in above, F_in below, F_out above, F_out below]` in `x, phi`.
    pub forces: [Id; 5],
    /// The static bound `as`.
    pub bound: Id,
}

/// Every quantity of one generated `Model` type.
pub struct Equations {
    /// The instance (its graph holds every node below).
    pub instance: Instance,
    /// Checked at run time.
    pub conditions: Conditions,
    /// Per domain.
    pub domains: Vec<DomainEquations>,
    /// Per generated mapping.
    pub mappings: Vec<MappingEquations>,
    /// `[m, d, c, A0, W]`.
    pub oscillator: [Id; 5],
    /// On the stick boundary.
    pub stick: Option<StickEquations>,
}

/// Every quantity of a smooth model's type.
pub struct SmoothEquations {
    /// The smooth model (its graph holds every node below).
    pub smooth: Smooth,
    /// `[f(v), f'(v)]`.
    pub kinetic: [Id; 2],
    /// `[m, d, c, A0, W]`.
    pub oscillator: [Id; 5],
    /// `[m, c, W, as, f(V + eps), f(V - eps)]` checked at run time.
    pub conditions: [Id; 6],
}

/// Form the equations of every instance.
pub fn build(expanded: Expanded) -> Result<Generation, Diagnostics> {
    let main = match expanded.main {
        Main::Piecewise(i) => MainEquations::Piecewise(Box::new(piecewise(*i)?)),
        Main::Smooth(s) => MainEquations::Smooth(Box::new(smooth(*s))),
    };
    let mut scenes = Vec::new();
    for s in expanded.scenes {
        scenes.push((s.module, s.doc, piecewise(s.instance)?));
    }
    Ok(Generation {
        header: expanded.header,
        main,
        scenes,
    })
}

fn smooth(mut s: Smooth) -> SmoothEquations {
    let nodes = s.law;
    let g = &mut s.lowered.graph;
    let slope = g
        .diff(nodes.kinetic, LAW_V)
        .unwrap_or_else(|_| g.constant(f64::NAN));
    let eps = g.constant(1e-12);
    let range_eps = g.mul(nodes.range, eps);
    let above = g.add(nodes.belt, range_eps);
    let below = g.sub(nodes.belt, range_eps);
    let f_above = g.substitute(nodes.kinetic, LAW_V, above);
    let f_below = g.substitute(nodes.kinetic, LAW_V, below);
    let l = &s.lowered;
    SmoothEquations {
        kinetic: [nodes.kinetic, slope],
        oscillator: [l.mass, l.damping, l.stiffness, l.forcing, l.frequency],
        conditions: [
            l.mass,
            l.stiffness,
            l.frequency,
            nodes.stick,
            f_above,
            f_below,
        ],
        smooth: s,
    }
}

/// The equations of one instance. Nodes are made in a fixed order (the
/// conditions, the regimes, each domain, each mapping, the stick boundary):
/// the generated code names its temporaries in that order.
fn piecewise(mut instance: Instance) -> Result<Equations, Diagnostics> {
    let stick = instance.stick();
    let inst = &mut instance.lowered;
    let levels = stick.map(|(k, _)| kinetic_levels(inst, k));
    let conditions = Conditions {
        mass: inst.mass,
        stiffness: inst.stiffness,
        frequency: inst.frequency,
        velocities: inst.boundary_velocity.clone(),
        stick: stick.zip(levels).map(|((_, sb), (la, lb))| [sb, la, lb]),
    };
    let regimes: Vec<Option<Regime>> = inst
        .domains
        .clone()
        .iter()
        .map(|dn| {
            let g = &mut inst.graph;
            let d2 = g.powi(dn.d, 2);
            let w2 = g.sub(d2, dn.c);
            match g.as_const(w2) {
                Some(w) if w < 0.0 => Some(Regime::Underdamped),
                Some(w) if w > 0.0 => Some(Regime::Overdamped),
                Some(_) => Some(Regime::Critical),
                None => None,
            }
        })
        .collect();
    let mut domains = Vec::new();
    for (j, regime) in regimes.into_iter().enumerate() {
        let dn = inst.domains[j];
        let g = &mut inst.graph;
        let two = g.constant(2.0);
        let two_d = g.mul(two, dn.d);
        let [x0, v0, phi0, phi1] = [0, 1, 2, 3].map(|k| inst.graph.var(k));
        let (x, v) = flow(inst, j, x0, v0, phi0, phi1);
        let vars = [0, 1, 2].map(|k| inst.graph.var(k));
        let (field, rate) = normal_field(inst, j, vars);
        domains.push(DomainEquations {
            coefficients: [two_d, dn.c, dn.b],
            regime,
            flow: [x, v],
            field: [field, rate],
        });
    }
    let mut mappings = Vec::new();
    for m in &instance.mappings {
        let inst = &mut instance.lowered;
        let vars = [0, 1, 2, 3].map(|k| inst.graph.var(k));
        let residual = match (m.route, stick) {
            (Route::Flow { domain }, _) => flow_mapping(inst, domain, m.from, m.to, vars),
            (Route::Stick { above }, Some((_, bound))) => {
                let sign = if above { 1.0 } else { -1.0 };
                stick_mapping(inst, m.from, bound, sign, vars)
            }
            (Route::Stick { .. }, None) => return Err(internal(&m.name, "no static bound")),
        };
        let mut jacobian = [residual[0]; 8];
        for (i, fi) in residual.into_iter().enumerate() {
            for k in 0..4u32 {
                jacobian[4 * i + k as usize] = inst
                    .graph
                    .diff(fi, k)
                    .map_err(|e| internal(&m.name, &format!("{e:?}")))?;
            }
        }
        mappings.push(MappingEquations { residual, jacobian });
    }
    let inst = &mut instance.lowered;
    let stick = stick.map(|(k, bound)| {
        let vars = [0, 1].map(|i| inst.graph.var(i));
        StickEquations {
            forces: stick_forces(inst, k, bound, vars),
            bound,
        }
    });
    let l = &instance.lowered;
    Ok(Equations {
        conditions,
        domains,
        mappings,
        oscillator: [l.mass, l.damping, l.stiffness, l.forcing, l.frequency],
        stick,
        instance,
    })
}

fn internal(mapping: &str, why: &str) -> Diagnostics {
    let mut d = Diagnostics::new();
    d.error(
        Span::call_site(),
        format!("internal: cannot differentiate mapping {mapping}: {why}"),
    );
    d
}

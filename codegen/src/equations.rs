//! The equations of SPEC §3–5 as expressions in an instance's graph: the
//! closed-form flow of a domain, the mapping residuals, the normal vector
//! field and its rate, and the force criteria on the stick boundary.
//!
//! Nothing here knows about Rust syntax: [`crate::emit`] turns the nodes into code.

use crate::expr::{Graph, Hom, Id};
use crate::instance::{Instance, LAW_V};

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
pub fn flow(inst: &mut Instance, j: usize, x0: Id, v0: Id, phi0: Id, phi1: Id) -> (Id, Id) {
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
    inst: &mut Instance,
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

/// Residual of the stick mapping on boundary `k` (Eq. 37), leaving to the
/// domain above (`sign = +1`) or below (`sign = -1`):
/// `f1 = x_i + V (t_{i+1} - t_i) - x_{i+1}`,
/// `f2 = A0 cos(W t_{i+1}) - 2 d V - c x_{i+1} - sign * as`.
pub fn stick_mapping(inst: &mut Instance, k: usize, sign: f64, vars: [Id; 4]) -> [Id; 2] {
    let [x0, phi0, x1, phi1] = vars;
    let vs = inst.boundary_velocity[k];
    let bound = inst
        .static_bound
        .expect("stick mapping on the stick boundary");
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
pub fn normal_field(inst: &mut Instance, j: usize, vars: [Id; 3]) -> (Id, Id) {
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
pub fn stick_forces(inst: &mut Instance, k: usize, vars: [Id; 2]) -> [Id; 5] {
    let [x, phi] = vars;
    let vs = inst.boundary_velocity[k];
    let bound = inst.static_bound.expect("stick boundary");
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
pub fn kinetic_levels(inst: &mut Instance, k: usize) -> (Id, Id) {
    let vs = inst.boundary_velocity[k];
    let (la, lb) = (inst.domains[k + 1].law, inst.domains[k].law);
    let g = &mut inst.graph;
    (g.substitute(la, LAW_V, vs), g.substitute(lb, LAW_V, vs))
}

//! The free functions of a generated type: per domain its coefficients,
//! closed-form flow and normal vector field; per mapping its residual and
//! exact Jacobian; the boundaries' velocities, the oscillator and the
//! forces on the stick boundary. The trait impl ([`super::model_impl`])
//! dispatches to them through the match arms collected here.

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use super::expression::{doc, doc1, straight_line, straight_line_with_phases};
use crate::equations::Equations;
use crate::expand::{Instance, MappingDecl, Route};
use crate::expr::Graph;
use crate::model::MappingKind;

/// The functions and the match arms that call them.
#[derive(Default)]
pub(super) struct Functions {
    /// The `pub fn` items.
    pub items: TokenStream,
    /// `j => coefficients_J(p),` …
    pub coefficients: TokenStream,
    /// `j => flow_J(…),` …
    pub flow: TokenStream,
    /// `j => normal_field_J(…),` …
    pub field: TokenStream,
    /// `i => residual_M(…),` …
    pub residual: TokenStream,
    /// `i => mapping_M(…),` …
    pub mapping: TokenStream,
    /// Body of `Model::stick_forces`.
    pub stick_forces: TokenStream,
    /// Body of `Model::static_bound`.
    pub static_bound: TokenStream,
}

/// Every function of one instance.
pub(super) fn functions(e: &Equations, pnames: &[Ident]) -> Functions {
    let mut out = Functions::default();
    domain_functions(e, pnames, &mut out);
    mapping_functions(e, pnames, &mut out);
    state_functions(e, pnames, &mut out);
    out
}

fn domain_functions(e: &Equations, pnames: &[Ident], out: &mut Functions) {
    let g = &e.instance.lowered.graph;
    let flow_vars: [(u32, &str); 4] = [(0, "x0"), (1, "v0"), (2, "phi0"), (3, "phi1")];
    for (j, (d, eq)) in e.instance.domains.iter().zip(&e.domains).enumerate() {
        let label = d.label;
        let (stmts, outs) = straight_line(g, pnames, &[], &eq.coefficients);
        let (a, b, c) = (&outs[0], &outs[1], &outs[2]);
        let f = format_ident!("coefficients_{}", label);
        let dc = doc1(&format!(
            "Effective coefficients of domain {label} (SPEC Eq. A.1): `x'' + 2 d_j x' + c_j x = A0 cos(W t) - b_j`."
        ));
        out.items.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params) -> ::stickslip::Coefficients {
                #stmts
                ::stickslip::Coefficients { two_d: #a, c: #b, b: #c }
            }
        });
        out.coefficients.extend(quote!(#j => #f(p),));

        let (stmts, outs) = straight_line(g, pnames, &flow_vars, &eq.flow);
        let (xo, vo) = (&outs[0], &outs[1]);
        let f = format_ident!("flow_{}", label);
        let dc = doc(&[
            format!("Closed-form flow in domain {label} (SPEC §4, Appendix A): the state `[x, v]` at phase"),
            "`phi1 = W t` of the motion that starts at `(x0, v0)` at phase `phi0`; exact in".into(),
            "every damping regime, written in the elapsed time `(phi1 - phi0) / W`.".into(),
        ]);
        out.items.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params, x0: f64, v0: f64, phi0: f64, phi1: f64) -> [f64; 2] {
                #stmts
                [#xo, #vo]
            }
        });
        out.flow.extend(quote!(#j => #f(p, x0, v0, phi0, phi1),));

        let (stmts, outs) = straight_line(g, pnames, &[(0, "x"), (1, "y"), (2, "phi")], &eq.field);
        let (fo, ro) = (&outs[0], &outs[1]);
        let f = format_ident!("normal_field_{}", label);
        let dc = doc(&[
            format!("Normal vector field of domain {label} (Eq. 10), `F = A0 cos(phi) - f(y) - 2 d y - c x`,"),
            "and its rate along the flow `DF = F_x y + F_y F + F_phi W` (Eqs. 21–23): `[F, DF]`.".into(),
        ]);
        out.items.extend(quote! {
            #dc
            #[inline]
            pub fn #f(p: &Params, x: f64, y: f64, phi: f64) -> [f64; 2] {
                #stmts
                [#fo, #ro]
            }
        });
        out.field.extend(quote!(#j => #f(p, x, y, phi),));
    }
}

/// What a mapping's functions say about it: the equation it solves.
fn mapping_doc(inst: &Instance, m: &MappingDecl) -> String {
    let b = |k: usize| &inst.boundaries[k].label;
    match m.route {
        Route::Stick { above } => format!(
            "Stick mapping `{}` on {} leaving {} (Eq. 37): `f1 = x_i + V (t_{{i+1}} - t_i) - x_{{i+1}}`, \
             `f2 = Fnf(x_{{i+1}}, t_{{i+1}}) {} as`.",
            m.name,
            b(m.from),
            if above { "upwards" } else { "downwards" },
            if above { "-" } else { "+" }
        ),
        Route::Flow { domain } => format!(
            "{} mapping `{}` in domain {} from {} to {} (Eq. 38): `f1 = x_j(t_{{i+1}}) - x_{{i+1}}`, `f2 = v_j(t_{{i+1}}) - V_β`.",
            if m.kind == MappingKind::Local { "Local" } else { "Global" },
            m.name,
            inst.domains[domain].label,
            b(m.from),
            b(m.to)
        ),
    }
}

fn mapping_functions(e: &Equations, pnames: &[Ident], out: &mut Functions) {
    let g: &Graph = &e.instance.lowered.graph;
    for (idx, (m, eq)) in e.instance.mappings.iter().zip(&e.mappings).enumerate() {
        let what = mapping_doc(&e.instance, m);
        let (stmts, outs) = straight_line_with_phases(
            g,
            pnames,
            &[(0, "x0"), (2, "x1")],
            &[(1, "a"), (3, "b")],
            &eq.residual,
        );
        let (f1, f2) = (&outs[0], &outs[1]);
        let rf = format_ident!("residual_{}", m.fn_name);
        let dc = doc(&[
            what.clone(),
            "Residual `f` only, from `(x0, a)` to `(x1, b)` (phases with their `cos`, `sin`)."
                .into(),
        ]);
        out.items.extend(quote! {
            #dc
            #[inline]
            pub fn #rf(p: &Params, x0: f64, a: ::stickslip::Phase, x1: f64, b: ::stickslip::Phase) -> ::stickslip::nalgebra::Vector2<f64> {
                #stmts
                ::stickslip::nalgebra::Vector2::new(#f1, #f2)
            }
        });
        out.residual.extend(quote!(#idx => #rf(p, x0, a, x1, b),));

        let mut outputs = eq.residual.to_vec();
        outputs.extend(&eq.jacobian);
        let (stmts, outs) = straight_line_with_phases(
            g,
            pnames,
            &[(0, "x0"), (2, "x1")],
            &[(1, "a"), (3, "b")],
            &outputs,
        );
        let (f1, f2) = (&outs[0], &outs[1]);
        let j = &outs[2..];
        let (a00, a01, b00, b01) = (&j[0], &j[1], &j[2], &j[3]);
        let (a10, a11, b10, b11) = (&j[4], &j[5], &j[6], &j[7]);
        let mf = format_ident!("mapping_{}", m.fn_name);
        let dc = doc(&[
            what,
            "Residual and its exact Jacobian blocks `∂f/∂(x_i, W t_i)` and `∂f/∂(x_{i+1}, W t_{i+1})`,".into(),
            "from `(x0, a)` to `(x1, b)`: the phases `a`, `b` carry their `cos` and `sin`.".into(),
        ]);
        out.items.extend(quote! {
            #dc
            #[inline]
            pub fn #mf(p: &Params, x0: f64, a: ::stickslip::Phase, x1: f64, b: ::stickslip::Phase) -> ::stickslip::MappingEval {
                #stmts
                ::stickslip::MappingEval {
                    residual: ::stickslip::nalgebra::Vector2::new(#f1, #f2),
                    d_prev: ::stickslip::nalgebra::Matrix2::new(#a00, #a01, #a10, #a11),
                    d_next: ::stickslip::nalgebra::Matrix2::new(#b00, #b01, #b10, #b11),
                }
            }
        });
        out.mapping.extend(quote!(#idx => #mf(p, x0, a, x1, b),));
    }
}

/// Boundaries, oscillator and stick forces.
fn state_functions(e: &Equations, pnames: &[Ident], out: &mut Functions) {
    let g = &e.instance.lowered.graph;
    let vel = &e.conditions.velocities;
    let (stmts, outs) = straight_line(g, pnames, &[], vel);
    let nb = vel.len();
    out.items.extend(quote! {
        /// Velocities of the boundaries, lowest first.
        #[inline]
        pub fn boundary_velocities(p: &Params) -> [f64; #nb] {
            #stmts
            [#(#outs),*]
        }
    });
    let (stmts, outs) = straight_line(g, pnames, &[], &e.oscillator);
    let (om, od, oc, oa, ow) = (&outs[0], &outs[1], &outs[2], &outs[3], &outs[4]);
    out.items.extend(quote! {
        /// The oscillator: `x'' + 2 d x' + c x = A0 cos(W t) - f(x')` (Eq. 5).
        #[inline]
        pub fn oscillator(p: &Params) -> ::stickslip::Oscillator {
            #stmts
            ::stickslip::Oscillator { mass: #om, damping: #od, stiffness: #oc, amplitude: #oa, frequency: #ow }
        }
    });
    let (Some(stick), Some(k)) = (&e.stick, e.instance.boundaries.iter().position(|b| b.stick))
    else {
        out.stick_forces = quote!({
            let _ = (p, x, phi);
            None
        });
        out.static_bound = quote!({
            let _ = p;
            None
        });
        return;
    };
    let (stmts, outs) = straight_line(g, pnames, &[(0, "x"), (1, "phi")], &stick.forces);
    let (a, b, c, d, e5) = (&outs[0], &outs[1], &outs[2], &outs[3], &outs[4]);
    let label = format!(
        "Forces on the stick boundary {} at `(x, W t)` (Eqs. 2, 24–25).",
        e.instance.boundaries[k].label
    );
    let dc = doc1(&label);
    out.items.extend(quote! {
        #dc
        #[inline]
        pub fn stick_forces(p: &Params, x: f64, phi: f64) -> ::stickslip::StickForces {
            #stmts
            ::stickslip::StickForces { non_friction: #a, input_above: #b, input_below: #c, output_above: #d, output_below: #e5 }
        }
    });
    let (stmts, outs) = straight_line(g, pnames, &[], &[stick.bound]);
    let o = &outs[0];
    out.items.extend(quote! {
        /// The static friction bound `as` per unit mass on the stick boundary.
        #[inline]
        pub fn static_bound(p: &Params) -> f64 {
            #stmts
            #o
        }
    });
    out.stick_forces = quote!(Some(stick_forces(p, x, phi)));
    out.static_bound = quote!(Some(static_bound(p)));
}

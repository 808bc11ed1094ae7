//! The piecewise-linear models of a smooth friction law, built at build
//! time for its `pieces: N` scenes (SPEC §12).
//!
//! **Breakpoint rule.** On each side of the belt speed the law is
//! interpolated linearly between breakpoints `|v − V| = 0 < u_1 < … < u_{k−1} < R`
//! (`k = N/2` pieces per side; the outermost piece interpolates on
//! `[u_{k−1}, R]` and continues beyond `R`). Linear interpolation on a piece
//! of width `h` errs by about `|f''| h² / 8`, so the breakpoints equidistribute
//! `∫ sqrt|f''(V ± u)| du` over `[0, R]` (de Boor's rule): every piece then
//! carries the same interpolation error, and the error falls as `N^-2`. The
//! second derivative is the law's exact symbolic derivative, evaluated at the
//! default parameters; the pieces' values are the law itself (symbolic in
//! the parameters), so a piecewise model interpolates the law at any
//! parameter values, at breakpoints placed for the defaults.
//!
//! **Where steady sliding changes stability.** A piecewise law's steady
//! sliding (the mass at rest, `v = 0`) is damped by `2 d + s`, with `s` the
//! slope of the piece it lies on: a secant of the law, the mean of `f'` over
//! the piece. Where a scene frees a parameter that enters the damping, the
//! belt speed or the law, its sweeps cross the offsets where `2 d + f'(V ± u)`
//! changes sign; each such offset at the defaults becomes a breakpoint, and
//! the breakpoints between them equidistribute the density within each span.
//! No piece then straddles a sign change, so at the defaults every piece's
//! steady sliding has the law's stability, and the threshold is the law's
//! own to the last bit, for every `N` with room for it (`N/2` pieces per side
//! more than such offsets). Away from the defaults the threshold lies on a
//! breakpoint within a piece's width of the law's, first order in `1/N`.
//!
//! **On the graph.** A piece's law is `f_a + (f_b - f_a) / (u_b - u_a) ·
//! (±(v - V) - u_a)` with `f_a`, `f_b` the law lowered with `v` standing for
//! the node `V ± u` ([`Velocity::Offset`]): the pieces are nodes of the
//! instance's graph, made from the checked law's expressions, with the
//! breakpoints as constants. Nodes are made in the order in which lowering
//! the written-out piece `f(V ± u_a) + …` would make them, so that the
//! generated code is the same as a hand-written N-piece model's.

use proc_macro2::Span;

use crate::check::{check_pieces, Edge, Piecewise};
use crate::diagnostic::Diagnostics;
use crate::expand::{assemble, BoundaryDecl, DomainDecl, Instance, ParamDecl, Parts};
use crate::expr::{Graph, Id};
use crate::law::{eval_law, lower_law, side_offset};
use crate::lower::Velocity;
use crate::lowered::{lower_instance, lower_oscillator, Lowered, LAW_V};
use crate::model::{Band, Law, Model, Scene};

/// The law on one side of the belt speed, at the defaults: `f(V ± u)`'s
/// derivatives in `v`, and the damping.
struct Side<'a> {
    g: &'a Graph,
    f1: Id,
    f2: Id,
    defaults: &'a [f64],
    belt: f64,
    damping: f64,
    range: f64,
    sign: f64,
}

impl Side<'_> {
    /// `2 d + f'(V ± u)`: the damping of steady sliding at `V ± u`.
    fn stability(&self, u: f64) -> f64 {
        2.0 * self.damping + eval_law(self.g, self.f1, self.defaults, self.belt + self.sign * u)
    }

    /// The offsets in `(0, R)` where steady sliding changes stability at the
    /// defaults (`2 d + f'(V ± u)` changes sign), each to the last bit.
    fn stability_changes(&self) -> Vec<f64> {
        const M: usize = 4000;
        let grid: Vec<(f64, f64)> = (0..=M)
            .map(|i| {
                let u = self.range * (i as f64 / M as f64).max(1e-9);
                (u, self.stability(u))
            })
            .collect();
        grid.windows(2)
            .filter(|w| w[0].1.is_finite() && w[1].1.is_finite())
            .filter(|w| (w[0].1 < 0.0) != (w[1].1 < 0.0) && w[0].1 != 0.0)
            .map(|w| {
                let (mut a, mut b) = (w[0].0, w[1].0);
                let below = w[0].1 < 0.0;
                loop {
                    let m = 0.5 * (a + b);
                    if m <= a || m >= b {
                        break b;
                    }
                    if (self.stability(m) < 0.0) == below {
                        a = m;
                    } else {
                        b = m;
                    }
                }
            })
            // Apart from the belt speed, the range's end and each other by
            // a millionth of the range: no sliver of a piece.
            .fold(Vec::new(), |mut pins: Vec<f64>, u| {
                let gap = 1e-6 * self.range;
                let last = pins.last().copied().unwrap_or(0.0);
                if u - last > gap && self.range - u > gap {
                    pins.push(u);
                }
                pins
            })
    }

    /// Breakpoint offsets `u_1 < … < u_{k−1}`: the `pins` and, between them,
    /// offsets that equidistribute `∫ sqrt|f''(V ± u)| du` within each span;
    /// each span gets at least one piece, the rest go where the density per
    /// piece is largest.
    fn breakpoints(&self, k: usize, pins: &[f64]) -> Vec<f64> {
        const M: usize = 4000;
        let range = self.range;
        let density: Vec<f64> = (0..=M)
            .map(|i| {
                let u = range * (i as f64 / M as f64).max(1e-9);
                eval_law(self.g, self.f2, self.defaults, self.belt + self.sign * u)
                    .abs()
                    .sqrt()
            })
            .collect();
        let finite: Vec<f64> = density
            .iter()
            .map(|d| if d.is_finite() { *d } else { 0.0 })
            .collect();
        let mean = finite.iter().sum::<f64>() / finite.len() as f64;
        // A floor keeps pieces finite where the law is locally straight.
        let floor = 1e-3 * mean.max(f64::MIN_POSITIVE);
        let mut cumulative = vec![0.0; M + 1];
        for i in 1..=M {
            let (a, b) = (finite[i - 1].max(floor), finite[i].max(floor));
            cumulative[i] = cumulative[i - 1] + 0.5 * (a + b) * range / M as f64;
        }
        // The offset where the cumulative density reaches `target`.
        let offset = |target: f64| {
            let i = cumulative.partition_point(|&c| c < target).clamp(1, M);
            let (c0, c1) = (cumulative[i - 1], cumulative[i]);
            let t = if c1 > c0 {
                (target - c0) / (c1 - c0)
            } else {
                0.0
            };
            range * ((i - 1) as f64 + t) / M as f64
        };
        // The cumulative density at offset `u`.
        let level = |u: f64| {
            let x = (u / range * M as f64).clamp(0.0, M as f64);
            let i = (x.floor() as usize).min(M - 1);
            cumulative[i] + (x - i as f64) * (cumulative[i + 1] - cumulative[i])
        };
        let pins: &[f64] = if pins.len() < k { pins } else { &[] };
        let mut ends = vec![0.0];
        ends.extend_from_slice(pins);
        ends.push(range);
        let spans: Vec<(f64, f64)> = ends
            .windows(2)
            .map(|w| (level(w[0]), level(w[1])))
            .collect();
        let mut count = vec![1usize; spans.len()];
        for _ in spans.len()..k {
            let widest = (0..spans.len())
                .max_by(|&a, &b| {
                    let per = |s: usize| (spans[s].1 - spans[s].0) / count[s] as f64;
                    per(a).total_cmp(&per(b))
                })
                .unwrap_or(0);
            count[widest] += 1;
        }
        let mut u = Vec::with_capacity(k.saturating_sub(1));
        for (s, &(c0, c1)) in spans.iter().enumerate() {
            if s > 0 {
                u.push(ends[s]);
            }
            for j in 1..count[s] {
                u.push(offset(c0 + (c1 - c0) * j as f64 / count[s] as f64));
            }
        }
        u
    }
}

/// Whether a scene freeing `free` can move steady sliding's stability
/// `2 d + f'(v)` at `v = 0`: a free parameter enters the damping, the belt
/// speed or the law.
fn stability_moves(model: &Model, law: &Law, free: &[usize]) -> bool {
    let mut inst = lower_instance(model, free, &mut Diagnostics::new());
    let nodes = lower_law(&mut inst, law, &mut Diagnostics::new());
    let g = &mut inst.graph;
    let f1 = g.diff(nodes.kinetic, LAW_V).unwrap_or(nodes.kinetic);
    [inst.damping, nodes.belt, f1]
        .iter()
        .any(|&id| g.depends_on_params(id))
}

/// Where the boundaries and pieces of an N-piece model go.
struct Plan {
    /// Boundaries, lowest velocity first.
    boundaries: Vec<Breakpoint>,
    /// Domains, lowest band first.
    pieces: Vec<Piece>,
    /// Where the law's one-sided limit at the belt speed is taken.
    delta: f64,
}

/// A boundary at `V + offset` (the belt speed itself: `offset` 0, stick).
struct Breakpoint {
    decl: BoundaryDecl,
    offset: f64,
}

/// A piece interpolating the law on `|v - V|` in `[ua, ub]`, on one side.
struct Piece {
    decl: DomainDecl,
    above: bool,
    ua: f64,
    ub: f64,
}

impl Plan {
    /// The boundaries and pieces of the `n`-piece model of a scene freeing
    /// `free`: breakpoints placed for the defaults by the law's second
    /// derivative, and, where the scene can move steady sliding's stability,
    /// one on each offset where it changes at the defaults.
    fn new(model: &Model, law: &Law, n: u32, free: &[usize]) -> Plan {
        let all: Vec<usize> = (0..model.params.len()).collect();
        let mut inst = lower_instance(model, &all, &mut Diagnostics::new());
        let nodes = lower_law(&mut inst, law, &mut Diagnostics::new());
        let defaults: Vec<f64> = model.params.iter().map(|p| p.default).collect();
        let g = &mut inst.graph;
        let f1 = g.diff(nodes.kinetic, LAW_V).unwrap_or(nodes.kinetic);
        let f2 = g.diff(f1, LAW_V).unwrap_or(f1);
        let belt = g.eval(nodes.belt, &defaults, &[]);
        let range = g.eval(nodes.range, &defaults, &[]);
        let damping = g.eval(inst.damping, &defaults, &[]);
        let pinned = stability_moves(model, law, free);
        let k = (n / 2) as usize;
        // Unsorted: the belt speed, then the breakpoints above, then below.
        let mut boundaries = vec![Breakpoint {
            decl: BoundaryDecl {
                label: "Sigma1".into(),
                number: 1,
                docs: vec!["The belt speed: the law jumps here and the mass can stick.".into()],
                stick: true,
            },
            offset: 0.0,
        }];
        let mut sides: Vec<(bool, Vec<f64>)> = Vec::new();
        for above in [true, false] {
            let side = Side {
                g: &inst.graph,
                f1,
                f2,
                defaults: &defaults,
                belt,
                damping,
                range,
                sign: if above { 1.0 } else { -1.0 },
            };
            let pins = if pinned {
                side.stability_changes()
            } else {
                Vec::new()
            };
            let mut u = side.breakpoints(k, &pins);
            for &uj in &u {
                let number = boundaries.len() as u32 + 1;
                let doc = if pins.contains(&uj) && pins.len() < k {
                    format!(
                        "Breakpoint |v - V| = {uj:.6}, where steady sliding changes stability at the defaults (2 d + f'(v) = 0)."
                    )
                } else {
                    format!("Breakpoint |v - V| = {uj:.6}.")
                };
                boundaries.push(Breakpoint {
                    decl: BoundaryDecl {
                        label: format!("Sigma{number}"),
                        number,
                        docs: vec![doc],
                        stick: false,
                    },
                    offset: side.sign * uj,
                });
            }
            u.insert(0, 0.0);
            u.push(range);
            sides.push((above, u));
        }
        let mut order: Vec<usize> = (0..boundaries.len()).collect();
        order.sort_by(|&a, &b| boundaries[a].offset.total_cmp(&boundaries[b].offset));
        let mut position = vec![0; order.len()];
        for (p, &b) in order.iter().enumerate() {
            position[b] = p;
        }
        let mut pieces = Vec::new();
        for (s, (above, u)) in sides.iter().enumerate() {
            for piece in 0..k {
                let (ua, ub) = (u[piece], u[piece + 1]);
                // Boundary indices (unsorted) of this piece's edges.
                let inner = if piece == 0 {
                    0
                } else if s == 0 {
                    piece
                } else {
                    k - 1 + piece
                };
                let outer = (piece + 1 < k).then(|| if s == 0 { piece + 1 } else { k + piece });
                let (lower, upper) = if *above {
                    (Some(inner), outer)
                } else {
                    (outer, Some(inner))
                };
                let span = if piece + 1 < k {
                    format!("[{ua:.6}, {ub:.6}]")
                } else {
                    format!("[{ua:.6}, ∞), interpolated up to {ub:.6}")
                };
                let side = if *above { "above" } else { "below" };
                pieces.push(Piece {
                    decl: DomainDecl {
                        label: (s * k + piece + 1) as u32,
                        docs: vec![format!(
                            "Piece {} {side} the belt speed: |v - V| in {span}.",
                            piece + 1
                        )],
                        lower: lower.map(|b| position[b]),
                        upper: upper.map(|b| position[b]),
                    },
                    above: *above,
                    ua,
                    ub,
                });
            }
        }
        pieces.sort_by_key(|p| p.decl.lower.map_or(-1, |l| l as i64));
        let mut slots: Vec<Option<Breakpoint>> = boundaries.into_iter().map(Some).collect();
        let boundaries = order.iter().filter_map(|&i| slots[i].take()).collect();
        Plan {
            boundaries,
            pieces,
            delta: side_offset(range),
        }
    }

    /// The model lowered with parameters `free` symbolic: the oscillator,
    /// the boundaries at `V + offset`, and each piece's law.
    fn lower(&self, model: &Model, law: &Law, free: &[usize], diags: &mut Diagnostics) -> Lowered {
        let mut inst = lower_oscillator(model, free, diags);
        let mut belt = None;
        for b in &self.boundaries {
            let ctx = format!("the velocity of {}", b.decl.label);
            let base = inst.lower(&law.belt, &ctx, None, diags);
            belt = Some(base);
            let velocity = if b.offset == 0.0 {
                base
            } else {
                Velocity::Offset {
                    base,
                    offset: b.offset,
                }
                .node(&mut inst.graph)
            };
            let stick = b.decl.stick.then(|| {
                let ctx = format!("the static bound of {}", b.decl.label);
                inst.lower(&law.stick, &ctx, None, diags)
            });
            inst.push_boundary(velocity, stick);
        }
        let v = inst.graph.var(LAW_V);
        let Some(belt) = belt else { return inst };
        for p in &self.pieces {
            let law_id = self.piece_law(&mut inst, law, p, belt, v, diags);
            inst.push_domain(law_id);
        }
        inst
    }

    /// `f_a + (f_b - f_a) / (u_b - u_a) * (±(v - V) - u_a)`, the law at the
    /// piece's ends `V ± u` (one-sided at the belt speed) interpolated.
    fn piece_law(
        &self,
        inst: &mut Lowered,
        law: &Law,
        p: &Piece,
        belt: Id,
        v: Id,
        diags: &mut Diagnostics,
    ) -> Id {
        let ctx = format!("the friction law of domain {}", p.decl.label);
        let sign = if p.above { 1.0 } else { -1.0 };
        let at = |u: f64| Velocity::Offset {
            base: belt,
            offset: sign * u,
        };
        // At the belt speed the law's one-sided limit, extrapolated from
        // `δ` and `2δ` off it (`2 f(V ± δ) − f(V ± 2δ)`, exact to `O(δ²)`):
        // the law itself at `V ± δ` is off the limit by `δ f'`, 5.8e-11 on
        // `stribeck` (`δ = 8e-12`, `f' = 7.3`), so the static bound
        // (the limit, `as = ak` there) exceeded the piece's level at the
        // belt speed and every departure from a stick set off with that
        // acceleration instead of none.
        let fa = if p.ua == 0.0 {
            let near = inst.lower(&law.kinetic, &ctx, Some(at(self.delta)), diags);
            let far = inst.lower(&law.kinetic, &ctx, Some(at(2.0 * self.delta)), diags);
            let g = &mut inst.graph;
            let two = g.constant(2.0);
            let twice = g.mul(two, near);
            g.sub(twice, far)
        } else {
            inst.lower(&law.kinetic, &ctx, Some(at(p.ua)), diags)
        };
        let fb = inst.lower(&law.kinetic, &ctx, Some(at(p.ub)), diags);
        let g = &mut inst.graph;
        let rise = g.sub(fb, fa);
        let du = g.constant(p.ub - p.ua);
        let slope = g.div(rise, du);
        let rel = if p.above {
            g.sub(v, belt)
        } else {
            g.sub(belt, v)
        };
        let ua = g.constant(p.ua);
        let from_a = g.sub(rel, ua);
        let run = g.mul(slope, from_a);
        g.add(fa, run)
    }

    /// The view of the continuity and static-bound checks.
    fn view<'a>(&'a self, model: &'a Model, law: &'a Law) -> Piecewise<'a> {
        Piecewise {
            params: &model.params,
            edges: self
                .boundaries
                .iter()
                .map(|b| Edge {
                    label: &b.decl.label,
                    span: Span::call_site(),
                    stick: b.decl.stick.then_some(&law.stick),
                })
                .collect(),
            domain_labels: self.pieces.iter().map(|p| p.decl.label).collect(),
        }
    }
}

/// The `n`-piece model of scene `scene` of a smooth model: boundaries at the
/// breakpoints (the belt speed carries the stick), one affine domain per piece
/// interpolating the law, and the scene's free parameters. Its checks run
/// here with every parameter free; their errors name the scene.
pub fn instance(
    model: &Model,
    law: &Law,
    scene: &Scene,
    n: u32,
    params: &[ParamDecl],
    diags: &mut Diagnostics,
) -> Instance {
    let plan = Plan::new(model, law, n, &scene.free);
    let mut check = Diagnostics::new();
    let all: Vec<usize> = (0..model.params.len()).collect();
    let symbolic = plan.lower(model, law, &all, &mut check);
    check_pieces(&plan.view(model, law), &symbolic, &mut check);
    for d in check.iter() {
        diags.error(
            d.span,
            format!(
                "in the {n}-piece model of scene `{}`: {}",
                scene.name, d.message
            ),
        );
    }
    let lowered = plan.lower(model, law, &scene.free, diags);
    let numbers: Vec<u32> = plan.boundaries.iter().map(|b| b.decl.number).collect();
    let bands: Vec<Band> = plan
        .pieces
        .iter()
        .map(|p| Band {
            label: p.decl.label,
            lower: p.decl.lower,
            upper: p.decl.upper,
        })
        .collect();
    let stick = plan.boundaries.iter().position(|b| b.decl.stick);
    let mappings = Model::topology_mappings(&numbers, stick, &bands);
    let boundaries = plan.boundaries.into_iter().map(|b| b.decl).collect();
    let domains = plan.pieces.into_iter().map(|p| p.decl).collect();
    let parts = Parts {
        boundaries,
        domains,
        mappings: &mappings,
        lowered,
    };
    assemble(model, Some(scene), params, parts)
}

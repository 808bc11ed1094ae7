//! The run-time back end: a model file's equations compiled to machine code
//! by Cranelift, for a model loaded while the program runs (no Rust build).
//!
//! It is the last pass of the same [`pipeline`](crate::pipeline) the
//! build-time route runs: `parse → check → expand → equations` are shared,
//! so a file gets the same report from `stickslip check`, the build and a
//! load, and only a model every check has passed reaches this pass. It
//! compiles one instance (the model, or the scene asked for), one function
//! per function the Rust back end writes (`walk`), into a [`Machine`]
//! (`memory`, the one module with `unsafe`). The runtime
//! (`stickslip::model::loaded`) puts the functions behind the model traits.
//!
//! [`compile_text`] is the entry point: source text in, [`Compiled`] or the
//! [`Report`] `stickslip check` gives.

mod memory;
mod walk;

use std::sync::atomic::{AtomicUsize, Ordering};

use cranelift_codegen::settings::{self, Configurable};
use cranelift_codegen::Context;
use cranelift_frontend::FunctionBuilderContext;
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::{FuncId, Module};
use proc_macro2::Span;

pub use memory::{FnId, Machine};

use crate::diagnostic::Diagnostics;
use crate::equations::{Equations, Generation, MainEquations, Regime, SmoothEquations};
use crate::expand::{Instance, Smooth};
use crate::expr::Id;
use crate::lowered::LAW_V;
use crate::report::{run_text, Report};
use crate::{names, pipeline, Backend, Model};
use walk::{symbol, Compiler, Function, Imports, Slot};

/// The most free parameters a loaded model may have: its parameter set is a
/// fixed-capacity array (`Copy`, no allocation on the hot paths).
pub const CAPACITY: usize = 32;

/// `(Ec, Es)`, as the runtime's homogeneous-solution routines return it.
#[repr(C)]
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct HomPair {
    /// `exp(-d tau) cosh(omega tau)`.
    pub ec: f64,
    /// `exp(-d tau) sinh(omega tau) / omega`.
    pub es: f64,
}

/// The runtime routines compiled code calls: those the Rust back end's code
/// calls (`f64::sin`, `f64::cos`, `f64::exp`, `f64::ln` and
/// `stickslip::model::homogeneous`), behind `extern "C"` wrappers, so that
/// both back ends compute the same numbers.
#[derive(Clone, Copy, Debug)]
pub struct Routines {
    /// `f64::sin`.
    pub sin: extern "C" fn(f64) -> f64,
    /// `f64::cos`.
    pub cos: extern "C" fn(f64) -> f64,
    /// `f64::exp`.
    pub exp: extern "C" fn(f64) -> f64,
    /// `f64::ln`.
    pub ln: extern "C" fn(f64) -> f64,
    /// `homogeneous::general(d, c, tau)`.
    pub general: extern "C" fn(f64, f64, f64) -> HomPair,
    /// `homogeneous::underdamped(d, omega, tau)`.
    pub underdamped: extern "C" fn(f64, f64, f64) -> HomPair,
    /// `homogeneous::overdamped(d, c, tau)`.
    pub overdamped: extern "C" fn(f64, f64, f64) -> HomPair,
    /// `homogeneous::critical(d, tau)`.
    pub critical: extern "C" fn(f64, f64) -> HomPair,
}

/// The machine code of a piecewise-linear model or scene, function by
/// function. Argument layouts: a flow `[x0, v0, phi0, phi1]`; a normal field
/// `[x, y, phi]`; a mapping `[x0, phi0, cos phi0, sin phi0, x1, phi1, cos
/// phi1, sin phi1]`; stick forces `[x, phi]`.
#[derive(Debug)]
pub struct PiecewiseCode {
    /// The code.
    pub machine: Machine,
    /// Per domain: `[2 d_j, c_j, b_j]`.
    pub coefficients: Vec<FnId<0, 3>>,
    /// Per domain: `[x, v]` of the flow.
    pub flows: Vec<FnId<4, 2>>,
    /// Per domain: `[F, DF]`.
    pub fields: Vec<FnId<3, 2>>,
    /// Per mapping: `[f1, f2]`.
    pub residuals: Vec<FnId<8, 2>>,
    /// Per mapping: `[f1, f2]`, then `∂f/∂(x0, phi0)` and `∂f/∂(x1, phi1)`
    /// row by row: `[f1, f2, a00, a01, a10, a11, b00, b01, b10, b11]`.
    pub mappings: Vec<FnId<8, 10>>,
    /// Per boundary: its velocity.
    pub velocities: Vec<FnId<0, 1>>,
    /// `[m, d, c, A0, W]`.
    pub oscillator: FnId<0, 5>,
    /// `[m, c, W]`, checked positive.
    pub conditions: FnId<0, 3>,
    /// On the stick boundary, if any.
    pub stick: Option<StickCode>,
}

/// The stick boundary's functions.
#[derive(Clone, Copy, Debug)]
pub struct StickCode {
    /// `[Fnf, F_in above, F_in below, F_out above, F_out below]` at `[x, phi]`.
    pub forces: FnId<2, 5>,
    /// `as`.
    pub bound: FnId<0, 1>,
    /// `[as, f_above(V), f_below(V)]`, checked.
    pub levels: FnId<0, 3>,
}

/// The machine code of a smooth-law model.
#[derive(Debug)]
pub struct SmoothCode {
    /// The code.
    pub machine: Machine,
    /// `[f(v), f'(v)]` at `[v]`.
    pub kinetic: FnId<1, 2>,
    /// `V`.
    pub belt: FnId<0, 1>,
    /// `as`.
    pub bound: FnId<0, 1>,
    /// `[m, d, c, A0, W]`.
    pub oscillator: FnId<0, 5>,
    /// `[m, c, W, as, f(V + eps), f(V - eps)]`, checked.
    pub conditions: FnId<0, 6>,
}

/// A compiled model with what the runtime describes it by.
pub enum Compiled {
    /// A piecewise-linear model or scene.
    Piecewise {
        /// Its declarations (names, parameters, boundaries, domains, mappings).
        instance: Box<Instance>,
        /// Each domain's damping regime when fixed by the file.
        regimes: Vec<Option<Regime>>,
        /// Its code.
        code: Box<PiecewiseCode>,
    },
    /// A model with a smooth law.
    Smooth {
        /// Its declarations.
        smooth: Box<Smooth>,
        /// Its code.
        code: Box<SmoothCode>,
    },
}

static COMPILED: AtomicUsize = AtomicUsize::new(0);

/// How many models this process has compiled to machine code: a model the
/// checks reject never adds one.
pub fn compilations() -> usize {
    COMPILED.load(Ordering::Relaxed)
}

/// Check `source` and compile its model (or its scene `scene`) to machine
/// code. `origin` names the file in messages; with `stem` (a file's name
/// without `.ssm`) the model must be named like it. The report of a file
/// the checks reject is `stickslip check`'s, word for word: the same passes
/// run, under the same guards.
pub fn compile_text(
    source: &str,
    origin: &str,
    stem: Option<&str>,
    scene: Option<&str>,
    routines: &Routines,
) -> Result<Compiled, Report> {
    run_text(source, origin, |tokens| {
        pipeline(tokens, stem, Jit { scene, routines })
    })
}

/// The run-time back end of [`pipeline`]: one instance to machine code.
struct Jit<'a> {
    scene: Option<&'a str>,
    routines: &'a Routines,
}

impl Backend for Jit<'_> {
    type Output = Compiled;
    fn emit(self, model: &Model, generation: Generation) -> Result<Compiled, Diagnostics> {
        let Generation { main, scenes, .. } = generation;
        let compiled = match (self.scene, main) {
            (None, MainEquations::Piecewise(e)) => self.piecewise(*e),
            (None, MainEquations::Smooth(s)) => self.smooth(*s),
            (Some(want), _) => {
                let names: Vec<String> = scenes
                    .iter()
                    .filter_map(|(_, _, e)| e.instance.scene_name.clone())
                    .collect();
                let Some((_, _, e)) = scenes
                    .into_iter()
                    .find(|(_, _, e)| e.instance.scene_name.as_deref() == Some(want))
                else {
                    return Err(no_scene(model, want, &names));
                };
                self.piecewise(e)
            }
        }?;
        COMPILED.fetch_add(1, Ordering::Relaxed);
        Ok(compiled)
    }
}

fn no_scene(model: &Model, want: &str, names: &[String]) -> Diagnostics {
    let model = names::bare(&model.name);
    let have = if names.is_empty() {
        "it has none".to_string()
    } else {
        format!("its scenes: {}", names.join(", "))
    };
    let mut d = Diagnostics::new();
    d.error(
        Span::call_site(),
        format!("model `{model}` has no scene `{want}` ({have})"),
    );
    d
}

fn internal(e: impl std::fmt::Display) -> Diagnostics {
    let mut d = Diagnostics::new();
    d.error(
        Span::call_site(),
        format!("internal: the model cannot be compiled to machine code: {e}"),
    );
    d
}

/// A model with more free parameters than [`CAPACITY`], refused at the
/// first one past it.
fn too_many(params: &[crate::expand::ParamDecl], free: &[usize]) -> Result<(), Diagnostics> {
    match free.get(CAPACITY) {
        None => Ok(()),
        Some(&i) => {
            let mut d = Diagnostics::new();
            d.error(
                params[i].ident.span(),
                format!(
                    "a model loaded at run time takes at most {CAPACITY} free parameters; \
                     `{}` is the {}th: fix some in a scene, or compile the model in \
                     (models/NAME.ssm)",
                    params[i].name,
                    CAPACITY + 1
                ),
            );
            Err(d)
        }
    }
}

/// A module for the host with the runtime's routines bound.
fn new_module(routines: &Routines) -> Result<JITModule, Diagnostics> {
    let mut flags = settings::builder();
    for (name, value) in [
        ("opt_level", "speed"),
        ("use_colocated_libcalls", "false"),
        ("is_pic", "false"),
    ] {
        flags.set(name, value).map_err(internal)?;
    }
    let isa = cranelift_native::builder()
        .map_err(internal)?
        .finish(settings::Flags::new(flags))
        .map_err(internal)?;
    let mut builder = JITBuilder::with_isa(isa, cranelift_module::default_libcall_names());
    let r = routines;
    builder.symbols([
        (symbol::SIN, r.sin as *const u8),
        (symbol::COS, r.cos as *const u8),
        (symbol::EXP, r.exp as *const u8),
        (symbol::LN, r.ln as *const u8),
        (symbol::GENERAL, r.general as *const u8),
        (symbol::UNDERDAMPED, r.underdamped as *const u8),
        (symbol::OVERDAMPED, r.overdamped as *const u8),
        (symbol::CRITICAL, r.critical as *const u8),
    ]);
    Ok(JITModule::new(builder))
}

/// Defines functions in one module, then finalizes it into a [`Machine`].
struct Build {
    module: JITModule,
    imports: Imports,
    ids: Vec<(FuncId, usize, usize)>,
    ctx: Option<(Context, FunctionBuilderContext)>,
}

impl Build {
    fn new(routines: &Routines) -> Result<Self, Diagnostics> {
        let mut module = new_module(routines)?;
        let imports = Imports::declare(&mut module).map_err(internal)?;
        let ctx = Some((module.make_context(), FunctionBuilderContext::new()));
        Ok(Self {
            module,
            imports,
            ids: Vec::new(),
            ctx,
        })
    }

    /// Define a function of `vars` computing `outputs`; its index.
    fn define(
        &mut self,
        graph: &crate::expr::Graph,
        vars: &[(u32, Slot)],
        args: usize,
        outputs: &[Id],
    ) -> Result<usize, Diagnostics> {
        let (ctx, fctx) = self
            .ctx
            .take()
            .unwrap_or_else(|| (self.module.make_context(), FunctionBuilderContext::new()));
        let mut compiler = Compiler {
            module: &mut self.module,
            imports: &self.imports,
            ctx,
            fctx,
            count: self.ids.len(),
        };
        let id = compiler.define(&Function {
            graph,
            vars,
            outputs,
        });
        self.ctx = Some((compiler.ctx, compiler.fctx));
        self.ids.push((id.map_err(internal)?, args, outputs.len()));
        Ok(self.ids.len() - 1)
    }

    fn finish(mut self, params: usize) -> Result<Machine, Diagnostics> {
        self.module.finalize_definitions().map_err(internal)?;
        Ok(Machine::new(self.module, &self.ids, params))
    }
}

const FLOW: [(u32, Slot); 4] = [
    (0, Slot::Plain(0)),
    (1, Slot::Plain(1)),
    (2, Slot::Plain(2)),
    (3, Slot::Plain(3)),
];
const FIELD: [(u32, Slot); 3] = [
    (0, Slot::Plain(0)),
    (1, Slot::Plain(1)),
    (2, Slot::Plain(2)),
];
const MAPPING: [(u32, Slot); 4] = [
    (0, Slot::Plain(0)),
    (1, Slot::Phase(1)),
    (2, Slot::Plain(4)),
    (3, Slot::Phase(5)),
];
const FORCES: [(u32, Slot); 2] = [(0, Slot::Plain(0)), (1, Slot::Plain(1))];

/// The typed handles of the functions defined in order `first..`.
fn ids<const A: usize, const O: usize>(
    machine: &Machine,
    indices: impl IntoIterator<Item = usize>,
) -> Result<Vec<FnId<A, O>>, Diagnostics> {
    indices
        .into_iter()
        .map(|i| machine.id(i).ok_or_else(|| internal("a function's arity")))
        .collect()
}

fn one<const A: usize, const O: usize>(
    machine: &Machine,
    i: usize,
) -> Result<FnId<A, O>, Diagnostics> {
    machine.id(i).ok_or_else(|| internal("a function's arity"))
}

impl Jit<'_> {
    fn piecewise(&self, e: Equations) -> Result<Compiled, Diagnostics> {
        let inst = &e.instance;
        too_many(&inst.params, &inst.free)?;
        let g = &inst.lowered.graph;
        let mut b = Build::new(self.routines)?;
        let defined =
            |b: &mut Build, vars: &[(u32, Slot)], args, outs: &[Id]| b.define(g, vars, args, outs);
        let mut coefficients = Vec::new();
        let mut flows = Vec::new();
        let mut fields = Vec::new();
        for d in &e.domains {
            coefficients.push(defined(&mut b, &[], 0, &d.coefficients)?);
            flows.push(defined(&mut b, &FLOW, 4, &d.flow)?);
            fields.push(defined(&mut b, &FIELD, 3, &d.field)?);
        }
        let mut residuals = Vec::new();
        let mut mappings = Vec::new();
        for m in &e.mappings {
            residuals.push(defined(&mut b, &MAPPING, 8, &m.residual)?);
            let mut all = m.residual.to_vec();
            all.extend(m.jacobian);
            mappings.push(defined(&mut b, &MAPPING, 8, &all)?);
        }
        let velocities: Vec<usize> = e
            .conditions
            .velocities
            .iter()
            .map(|&v| defined(&mut b, &[], 0, &[v]))
            .collect::<Result<_, _>>()?;
        let oscillator = defined(&mut b, &[], 0, &e.oscillator)?;
        let c = &e.conditions;
        let conditions = defined(&mut b, &[], 0, &[c.mass, c.stiffness, c.frequency])?;
        let stick = match (&e.stick, &c.stick) {
            (Some(s), Some(levels)) => Some((
                defined(&mut b, &FORCES, 2, &s.forces)?,
                defined(&mut b, &[], 0, &[s.bound])?,
                defined(&mut b, &[], 0, levels)?,
            )),
            _ => None,
        };
        let machine = b.finish(inst.free.len())?;
        let code = PiecewiseCode {
            coefficients: ids(&machine, coefficients)?,
            flows: ids(&machine, flows)?,
            fields: ids(&machine, fields)?,
            residuals: ids(&machine, residuals)?,
            mappings: ids(&machine, mappings)?,
            velocities: ids(&machine, velocities)?,
            oscillator: one(&machine, oscillator)?,
            conditions: one(&machine, conditions)?,
            stick: match stick {
                Some((f, s, l)) => Some(StickCode {
                    forces: one(&machine, f)?,
                    bound: one(&machine, s)?,
                    levels: one(&machine, l)?,
                }),
                None => None,
            },
            machine,
        };
        let regimes = e.domains.iter().map(|d| d.regime).collect();
        Ok(Compiled::Piecewise {
            instance: Box::new(e.instance),
            regimes,
            code: Box::new(code),
        })
    }

    fn smooth(&self, e: SmoothEquations) -> Result<Compiled, Diagnostics> {
        let s = &e.smooth;
        let free: Vec<usize> = (0..s.params.len()).collect();
        too_many(&s.params, &free)?;
        let g = &s.lowered.graph;
        let mut b = Build::new(self.routines)?;
        let law = [(LAW_V, Slot::Plain(0))];
        let kinetic = b.define(g, &law, 1, &e.kinetic)?;
        let belt = b.define(g, &[], 0, &[s.law.belt])?;
        let bound = b.define(g, &[], 0, &[s.law.stick])?;
        let oscillator = b.define(g, &[], 0, &e.oscillator)?;
        let conditions = b.define(g, &[], 0, &e.conditions)?;
        let machine = b.finish(free.len())?;
        let code = SmoothCode {
            kinetic: one(&machine, kinetic)?,
            belt: one(&machine, belt)?,
            bound: one(&machine, bound)?,
            oscillator: one(&machine, oscillator)?,
            conditions: one(&machine, conditions)?,
            machine,
        };
        Ok(Compiled::Smooth {
            smooth: Box::new(e.smooth),
            code: Box::new(code),
        })
    }
}

//! The run-time back end: a model file's equations compiled to machine code
//! by Cranelift, for a model loaded while the program runs (no Rust build).
//!
//! It is the last pass of the same pipeline the build-time route runs:
//! `parse → check → expand → equations` are shared,
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
use cranelift_frontend::FunctionBuilderContext;
use cranelift_jit::{JITBuilder, JITModule};
use cranelift_module::Module;
use proc_macro2::Span;

pub use memory::{FnId, Machine};

use crate::diagnostic::Diagnostics;
use crate::equations::{Equations, Generation, MainEquations, Regime, SmoothEquations};
use crate::expand::{Expanded, Instance, Main, Smooth};
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

    /// The one instance asked for, as the main one: the others are
    /// expanded (every check runs on every scene, as the build checks
    /// them) but get no equations.
    fn select(&self, model: &Model, mut expanded: Expanded) -> Result<Expanded, Diagnostics> {
        let Some(want) = self.scene else {
            expanded.scenes.clear();
            return Ok(expanded);
        };
        let names: Vec<String> = expanded
            .scenes
            .iter()
            .filter_map(|s| s.instance.scene_name.clone())
            .collect();
        let Some(at) = names.iter().position(|n| n == want) else {
            return Err(no_scene(model, want, &names));
        };
        let scene = expanded.scenes.swap_remove(at);
        expanded.main = Main::Piecewise(Box::new(scene.instance));
        expanded.scenes.clear();
        Ok(expanded)
    }

    fn emit(self, _: &Model, generation: Generation) -> Result<Compiled, Diagnostics> {
        let compiled = match generation.main {
            MainEquations::Piecewise(e) => self.piecewise(*e),
            MainEquations::Smooth(s) => self.smooth(*s),
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
fn new_module(routines: &Routines) -> Result<JITModule, String> {
    let mut flags = settings::builder();
    // The graph arrives optimized (hash-consed, folded): Cranelift's own
    // optimizer finds nothing to gain there and would cost compile time. Its
    // verifier checks the IR this back end writes where debug assertions
    // are on (tests, fuzzing); a release build trusts it.
    let verifier = if cfg!(debug_assertions) {
        "true"
    } else {
        "false"
    };
    for (name, value) in [
        ("opt_level", "none"),
        ("enable_verifier", verifier),
        ("use_colocated_libcalls", "false"),
        ("is_pic", "false"),
    ] {
        flags.set(name, value).map_err(|e| e.to_string())?;
    }
    let isa = cranelift_native::builder()
        .map_err(|e| e.to_string())?
        .finish(settings::Flags::new(flags))
        .map_err(|e| e.to_string())?;
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

/// One function to compile: its variables, argument count and outputs.
struct Spec<'a> {
    vars: &'a [(u32, Slot)],
    args: usize,
    outputs: Vec<Id>,
}

/// The functions of one model, collected, then compiled into a [`Machine`]:
/// on as many threads as the machine has cores (at most [`THREADS`]), each
/// a module of its own, the functions dealt out by size.
struct Build<'a> {
    graph: &'a crate::expr::Graph,
    specs: Vec<Spec<'a>>,
}

/// The most threads one model is compiled on.
const THREADS: usize = 4;

impl<'a> Build<'a> {
    fn new(graph: &'a crate::expr::Graph) -> Self {
        Self {
            graph,
            specs: Vec::new(),
        }
    }

    /// A function of `vars` (`args` of them) computing `outputs`; its index.
    fn define(&mut self, vars: &'a [(u32, Slot)], args: usize, outputs: &[Id]) -> usize {
        self.specs.push(Spec {
            vars,
            args,
            outputs: outputs.to_vec(),
        });
        self.specs.len() - 1
    }

    /// Compile every function; the machine reads `params` parameter values.
    fn finish(self, routines: &Routines, params: usize) -> Result<Machine, Diagnostics> {
        let threads = std::thread::available_parallelism()
            .map_or(1, |n| n.get())
            .clamp(1, THREADS)
            .min(self.specs.len().max(1));
        // Deal the functions out largest first, each to the lightest share.
        let size = |s: &Spec<'_>| {
            crate::expr::Schedule::new(self.graph, &s.outputs)
                .nodes()
                .count()
        };
        let mut order: Vec<(usize, usize)> = self.specs.iter().map(size).enumerate().collect();
        order.sort_by_key(|&(_, weight)| std::cmp::Reverse(weight));
        let mut shares: Vec<(usize, Vec<usize>)> = vec![(0, Vec::new()); threads];
        for (index, weight) in order {
            if let Some(share) = shares.iter_mut().min_by_key(|s| s.0) {
                share.0 += weight;
                share.1.push(index);
            }
        }
        let graph = self.graph;
        let specs = &self.specs;
        let parts = std::thread::scope(|scope| {
            let handles: Vec<_> = shares
                .into_iter()
                .map(|(_, share)| {
                    scope.spawn(move || compile_share(graph, specs, &share, routines))
                })
                .collect();
            handles
                .into_iter()
                .map(|h| h.join().unwrap_or_else(|p| std::panic::resume_unwind(p)))
                .collect::<Result<Vec<_>, _>>()
        })
        .map_err(internal)?;
        Ok(Machine::new(parts, self.specs.len(), params))
    }
}

/// The functions `share` of `specs` compiled into one module, finalized:
/// the module and, per function, its index among `specs`, id and arity.
fn compile_share(
    graph: &crate::expr::Graph,
    specs: &[Spec<'_>],
    share: &[usize],
    routines: &Routines,
) -> Result<memory::Part, String> {
    let mut module = new_module(routines)?;
    let imports = Imports::declare(&mut module)?;
    let mut compiler = Compiler {
        ctx: module.make_context(),
        module: &mut module,
        imports: &imports,
        fctx: FunctionBuilderContext::new(),
        count: 0,
    };
    let mut ids = Vec::with_capacity(share.len());
    for &i in share {
        let spec = &specs[i];
        let id = compiler.define(&Function {
            graph,
            vars: spec.vars,
            outputs: &spec.outputs,
        })?;
        ids.push((i, id, spec.args, spec.outputs.len()));
    }
    module.finalize_definitions().map_err(|e| e.to_string())?;
    Ok(memory::Part::new(module, ids))
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
        let mut b = Build::new(g);
        let mut coefficients = Vec::new();
        let mut flows = Vec::new();
        let mut fields = Vec::new();
        for d in &e.domains {
            coefficients.push(b.define(&[], 0, &d.coefficients));
            flows.push(b.define(&FLOW, 4, &d.flow));
            fields.push(b.define(&FIELD, 3, &d.field));
        }
        let mut residuals = Vec::new();
        let mut mappings = Vec::new();
        for m in &e.mappings {
            residuals.push(b.define(&MAPPING, 8, &m.residual));
            let mut all = m.residual.to_vec();
            all.extend(m.jacobian);
            mappings.push(b.define(&MAPPING, 8, &all));
        }
        let velocities: Vec<usize> = e
            .conditions
            .velocities
            .iter()
            .map(|&v| b.define(&[], 0, &[v]))
            .collect();
        let oscillator = b.define(&[], 0, &e.oscillator);
        let c = &e.conditions;
        let conditions = b.define(&[], 0, &[c.mass, c.stiffness, c.frequency]);
        let stick = match (&e.stick, &c.stick) {
            (Some(s), Some(levels)) => Some((
                b.define(&FORCES, 2, &s.forces),
                b.define(&[], 0, &[s.bound]),
                b.define(&[], 0, levels),
            )),
            _ => None,
        };
        let machine = b.finish(self.routines, inst.free.len())?;
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
        let mut b = Build::new(g);
        const LAW: [(u32, Slot); 1] = [(LAW_V, Slot::Plain(0))];
        let kinetic = b.define(&LAW, 1, &e.kinetic);
        let belt = b.define(&[], 0, &[s.law.belt]);
        let bound = b.define(&[], 0, &[s.law.stick]);
        let oscillator = b.define(&[], 0, &e.oscillator);
        let conditions = b.define(&[], 0, &e.conditions);
        let machine = b.finish(self.routines, free.len())?;
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

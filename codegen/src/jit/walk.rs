//! Graph nodes → Cranelift IR: one function per generated function of the
//! Rust back end, made by the same walk (`expr::Schedule`) that
//! `emit::expression` makes, one instruction per node.
//!
//! Every function has the signature `(params, args, out)`: it loads the
//! free parameters it reads from `params`, its variables from `args` (a
//! phase variable as three slots, the phase and its `cos`, `sin`, as a
//! `::stickslip::Phase` carries them), and stores its outputs to `out`.
//! The arithmetic is the Rust back end's, operation for operation, so the
//! results agree to rounding: `a * (1/b)` and `a + (-b)` are a division
//! and a subtraction exactly where the Rust source writes `/` and `-`,
//! `powi` is square-and-multiply as LLVM expands it, and `sin`, `cos`,
//! `exp`, `ln` and the homogeneous solutions are calls to the runtime's own
//! routines (`Routines`).

use cranelift_codegen::ir::condcodes::FloatCC;
use cranelift_codegen::ir::immediates::Ieee64;
use cranelift_codegen::ir::{types, AbiParam, FuncRef, InstBuilder, MemFlags, Signature, Value};
use cranelift_codegen::Context;
use cranelift_frontend::{FunctionBuilder, FunctionBuilderContext};
use cranelift_jit::JITModule;
use cranelift_module::{FuncId, Linkage, Module};

use crate::expr::{Graph, Hom, Id, Node, Schedule};

/// Where a function finds its variables in `args`.
#[derive(Clone, Copy, Debug)]
pub(super) enum Slot {
    /// A plain variable: one slot.
    Plain(usize),
    /// A phase: the phase, its `cos` and its `sin`, in three slots from here.
    Phase(usize),
}

/// The runtime routines a function may call, declared once per module.
pub(super) struct Imports {
    sin: FuncId,
    cos: FuncId,
    exp: FuncId,
    ln: FuncId,
    general: FuncId,
    underdamped: FuncId,
    overdamped: FuncId,
    critical: FuncId,
}

/// The imported symbols' names, each bound by `JITBuilder::symbol` to a
/// routine of [`super::Routines`].
pub(super) mod symbol {
    pub const SIN: &str = "stickslip_sin";
    pub const COS: &str = "stickslip_cos";
    pub const EXP: &str = "stickslip_exp";
    pub const LN: &str = "stickslip_ln";
    pub const GENERAL: &str = "stickslip_homogeneous_general";
    pub const UNDERDAMPED: &str = "stickslip_homogeneous_underdamped";
    pub const OVERDAMPED: &str = "stickslip_homogeneous_overdamped";
    pub const CRITICAL: &str = "stickslip_homogeneous_critical";
}

fn float_signature(module: &JITModule, args: usize, rets: usize) -> Signature {
    let mut sig = module.make_signature();
    sig.params
        .extend(std::iter::repeat_n(AbiParam::new(types::F64), args));
    sig.returns
        .extend(std::iter::repeat_n(AbiParam::new(types::F64), rets));
    sig
}

/// The signature of every compiled function: three pointers, no result.
pub(super) fn signature(module: &JITModule) -> Signature {
    let ptr = module.target_config().pointer_type();
    let mut sig = module.make_signature();
    sig.params.extend([AbiParam::new(ptr); 3]);
    sig
}

impl Imports {
    pub(super) fn declare(module: &mut JITModule) -> Result<Self, String> {
        let unary = float_signature(module, 1, 1);
        // `(Ec, Es)` comes back as a `#[repr(C)]` pair of `f64`, which the
        // C calling convention returns in two float registers: two results.
        let three = float_signature(module, 3, 2);
        let two = float_signature(module, 2, 2);
        let mut import = |name: &str, sig: &Signature| {
            module
                .declare_function(name, Linkage::Import, sig)
                .map_err(|e| e.to_string())
        };
        Ok(Self {
            sin: import(symbol::SIN, &unary)?,
            cos: import(symbol::COS, &unary)?,
            exp: import(symbol::EXP, &unary)?,
            ln: import(symbol::LN, &unary)?,
            general: import(symbol::GENERAL, &three)?,
            underdamped: import(symbol::UNDERDAMPED, &three)?,
            overdamped: import(symbol::OVERDAMPED, &three)?,
            critical: import(symbol::CRITICAL, &two)?,
        })
    }
}

/// One function to compile: what it computes and where its variables are.
pub(super) struct Function<'a> {
    /// The graph holding every node.
    pub graph: &'a Graph,
    /// Variable index → where it is in `args`.
    pub vars: &'a [(u32, Slot)],
    /// The values it stores to `out`, in order.
    pub outputs: &'a [Id],
}

/// The reusable contexts of one module's compilation.
pub(super) struct Compiler<'m> {
    pub module: &'m mut JITModule,
    pub imports: &'m Imports,
    pub ctx: Context,
    pub fctx: FunctionBuilderContext,
    pub count: usize,
}

impl Compiler<'_> {
    /// Define `f` in the module; its id.
    pub(super) fn define(&mut self, f: &Function<'_>) -> Result<FuncId, String> {
        let name = format!("f{}", self.count);
        self.count += 1;
        let sig = signature(self.module);
        let id = self
            .module
            .declare_function(&name, Linkage::Local, &sig)
            .map_err(|e| e.to_string())?;
        self.ctx.func.signature = sig;
        {
            let mut b = FunctionBuilder::new(&mut self.ctx.func, &mut self.fctx);
            let block = b.create_block();
            b.append_block_params_for_function_params(block);
            b.switch_to_block(block);
            b.seal_block(block);
            let p = b.block_params(block).to_vec();
            let mut walk = Walk {
                b,
                module: self.module,
                imports: self.imports,
                graph: f.graph,
                vars: f.vars,
                params: p[0],
                args: p[1],
                values: Vec::new(),
                homs: Vec::new(),
                refs: Vec::new(),
            };
            walk.body(f.outputs, p[2]);
            walk.b.ins().return_(&[]);
            walk.b.finalize();
        }
        self.module
            .define_function(id, &mut self.ctx)
            .map_err(|e| e.to_string())?;
        self.module.clear_context(&mut self.ctx);
        Ok(id)
    }
}

/// `(d, c, tau)` and the `(Ec, Es)` one call computed for them.
type HomCall = ((Id, Id, Id), (Value, Value));

struct Walk<'a, 'b> {
    b: FunctionBuilder<'b>,
    module: &'a mut JITModule,
    imports: &'a Imports,
    graph: &'a Graph,
    vars: &'a [(u32, Slot)],
    params: Value,
    args: Value,
    /// Each computed node's value, by node index.
    values: Vec<Option<Value>>,
    /// `(Ec, Es)` of each `(d, c, tau)` called for.
    homs: Vec<HomCall>,
    /// The routines declared in this function.
    refs: Vec<(FuncId, FuncRef)>,
}

/// Loads of values the function only reads, aligned, that cannot trap
/// (the caller passes arrays of the function's arity, `jit::memory`).
fn reads() -> MemFlags {
    MemFlags::trusted().with_readonly()
}

impl Walk<'_, '_> {
    /// Compute every reached node in index order (children first), then
    /// store the outputs.
    fn body(&mut self, outputs: &[Id], out: Value) {
        let schedule = Schedule::new(self.graph, outputs);
        let nodes: Vec<Id> = schedule.nodes().collect();
        // The calls first, each after what it needs, then the rest: few
        // values live across a call (which clobbers every float register),
        // so register allocation has little to spill. The order changes no
        // number: every node is the same operation on the same operands.
        let n = nodes.last().map_or(0, |l| l.0 as usize + 1);
        self.values = vec![None; n];
        // `1/b` in `a * (1/b)` and `-b` in `a + (-b)`, where used there only,
        // are never computed: the division and the subtraction take `b`.
        let g = self.graph;
        let mut fused = vec![false; n];
        for &id in &nodes {
            if let Node::Mul(_, b) | Node::Add(_, b) = g.node(id) {
                let fuses = matches!(
                    (g.node(id), g.node(b)),
                    (Node::Mul(..), Node::Recip(_)) | (Node::Add(..), Node::Neg(_))
                );
                if fuses && !schedule.is_bound(g, b) {
                    fused[b.0 as usize] = true;
                }
            }
        }
        let mut early = vec![false; n];
        for &id in nodes.iter().rev() {
            if early[id.0 as usize] || self.is_call(id) {
                early[id.0 as usize] = true;
                for c in crate::expr::children(self.graph.node(id)) {
                    early[c.0 as usize] = true;
                }
            }
        }
        for pass in [true, false] {
            for &id in nodes
                .iter()
                .filter(|id| early[id.0 as usize] == pass && !fused[id.0 as usize])
            {
                let v = self.node(&schedule, id);
                self.values[id.0 as usize] = Some(v);
            }
        }
        for (k, &o) in outputs.iter().enumerate() {
            let v = self.value(o);
            self.b
                .ins()
                .store(MemFlags::trusted(), v, out, (8 * k) as i32);
        }
    }

    /// Whether node `id` is a call to a runtime routine.
    fn is_call(&self, id: Id) -> bool {
        match self.graph.node(id) {
            Node::Exp(_) | Node::Ln(_) | Node::Hom(..) => true,
            Node::Sin(a) | Node::Cos(a) => !matches!(
                self.graph.node(a),
                Node::Var(k) if matches!(self.slot(k), Some(Slot::Phase(_)))
            ),
            _ => false,
        }
    }

    fn slot(&self, var: u32) -> Option<Slot> {
        self.vars.iter().find(|(v, _)| *v == var).map(|&(_, s)| s)
    }

    fn arg(&mut self, slot: usize) -> Value {
        self.b
            .ins()
            .load(types::F64, reads(), self.args, (8 * slot) as i32)
    }

    /// The value of a node computed before (children come first).
    fn value(&self, id: Id) -> Value {
        self.values[id.0 as usize].expect("children are computed before their parents")
    }

    fn call(&mut self, f: FuncId, args: &[Value]) -> Vec<Value> {
        let r = match self.refs.iter().find(|(id, _)| *id == f) {
            Some(&(_, r)) => r,
            None => {
                let r = self.module.declare_func_in_func(f, self.b.func);
                self.refs.push((f, r));
                r
            }
        };
        let call = self.b.ins().call(r, args);
        self.b.inst_results(call).to_vec()
    }

    fn unary(&mut self, f: FuncId, a: Id) -> Value {
        let a = self.value(a);
        self.call(f, &[a])[0]
    }

    /// `sin`/`cos` of `a`: the caller's value when `a` is a phase variable.
    fn trig(&mut self, a: Id, f: FuncId, offset: usize) -> Value {
        if let Node::Var(k) = self.graph.node(a) {
            if let Some(Slot::Phase(s)) = self.slot(k) {
                return self.arg(s + offset);
            }
        }
        self.unary(f, a)
    }

    fn node(&mut self, schedule: &Schedule, id: Id) -> Value {
        let g = self.graph;
        let v = |w: &Self, c: Id| w.value(c);
        match g.node(id) {
            Node::Const(bits) => self.b.ins().f64const(Ieee64::with_bits(bits)),
            Node::Param(k) => self
                .b
                .ins()
                .load(types::F64, reads(), self.params, (8 * k) as i32),
            Node::Var(k) => match self.slot(k) {
                Some(Slot::Plain(s) | Slot::Phase(s)) => self.arg(s),
                // A variable the function does not take (none is reached).
                None => self.b.ins().f64const(Ieee64::with_bits(f64::NAN.to_bits())),
            },
            Node::Add(a, b) => {
                // `a + (-x)` is written `a - x` where `-x` is not named.
                if let Node::Neg(x) = g.node(b) {
                    if !schedule.is_bound(g, b) {
                        let (l, r) = (v(self, a), v(self, x));
                        return self.b.ins().fsub(l, r);
                    }
                }
                let (l, r) = (v(self, a), v(self, b));
                self.b.ins().fadd(l, r)
            }
            Node::Mul(a, b) => {
                // `a * (1/x)` is written `a / x` where `1/x` is not named.
                if let Node::Recip(x) = g.node(b) {
                    if !schedule.is_bound(g, b) {
                        let (l, r) = (v(self, a), v(self, x));
                        return self.b.ins().fdiv(l, r);
                    }
                }
                let (l, r) = (v(self, a), v(self, b));
                self.b.ins().fmul(l, r)
            }
            Node::Neg(a) => {
                let a = v(self, a);
                self.b.ins().fneg(a)
            }
            Node::Recip(a) => {
                let a = v(self, a);
                let one = self.b.ins().f64const(1.0);
                self.b.ins().fdiv(one, a)
            }
            Node::Powi(a, n) => {
                let a = v(self, a);
                self.powi(a, n)
            }
            Node::Sqrt(a) => {
                let a = v(self, a);
                self.b.ins().sqrt(a)
            }
            Node::Abs(a) => {
                let a = v(self, a);
                self.b.ins().fabs(a)
            }
            Node::Sign(a) => {
                // `f64::signum`: NaN for NaN, else ±1 with the sign of `a`.
                let a = v(self, a);
                let one = self.b.ins().f64const(1.0);
                let signed = self.b.ins().fcopysign(one, a);
                let nan = self.b.ins().f64const(Ieee64::with_bits(f64::NAN.to_bits()));
                let is_nan = self.b.ins().fcmp(FloatCC::Unordered, a, a);
                self.b.ins().select(is_nan, nan, signed)
            }
            Node::Exp(a) => self.unary(self.imports.exp, a),
            Node::Ln(a) => self.unary(self.imports.ln, a),
            Node::Sin(a) => self.trig(a, self.imports.sin, 2),
            Node::Cos(a) => self.trig(a, self.imports.cos, 1),
            Node::Hom(kind, d, c, tau) => {
                let (ec, es) = self.hom(d, c, tau);
                match kind {
                    Hom::Ec => ec,
                    Hom::Es => es,
                }
            }
        }
    }

    /// `a^n` by square-and-multiply, low bits first, as LLVM expands
    /// `powi` with a constant exponent (and as `__powidf2` computes it).
    fn powi(&mut self, a: Value, n: i32) -> Value {
        let mut bits = n.unsigned_abs();
        let mut result: Option<Value> = None;
        let mut square = a;
        while bits != 0 {
            if bits & 1 == 1 {
                result = Some(match result {
                    Some(r) => self.b.ins().fmul(r, square),
                    None => square,
                });
            }
            bits >>= 1;
            if bits != 0 {
                square = self.b.ins().fmul(square, square);
            }
        }
        let r = match result {
            Some(r) => r,
            None => self.b.ins().f64const(1.0),
        };
        if n < 0 {
            let one = self.b.ins().f64const(1.0);
            self.b.ins().fdiv(one, r)
        } else {
            r
        }
    }

    /// `(Ec, Es)` of `(d, c, tau)`, one call per triple, to the routine the
    /// Rust back end calls: specialised when `d` and `c` are constants.
    fn hom(&mut self, d: Id, c: Id, tau: Id) -> (Value, Value) {
        if let Some(&(_, pair)) = self.homs.iter().find(|(k, _)| *k == (d, c, tau)) {
            return pair;
        }
        let g = self.graph;
        let (dv, tv) = (self.value(d), self.value(tau));
        let r = match (g.as_const(d), g.as_const(c)) {
            (Some(dc), Some(cc)) if dc * dc < cc => {
                let omega = self.b.ins().f64const((cc - dc * dc).sqrt());
                self.call(self.imports.underdamped, &[dv, omega, tv])
            }
            (Some(dc), Some(cc)) if dc * dc > cc => {
                let cv = self.value(c);
                self.call(self.imports.overdamped, &[dv, cv, tv])
            }
            (Some(_), Some(_)) => self.call(self.imports.critical, &[dv, tv]),
            _ => {
                let cv = self.value(c);
                self.call(self.imports.general, &[dv, cv, tv])
            }
        };
        let pair = (r[0], r[1]);
        self.homs.push(((d, c, tau), pair));
        pair
    }
}

//! A flat, hash-consed expression graph.
//!
//! Nodes live in a `Vec`; children are indices of earlier nodes, and a node
//! that already exists is never stored twice, so common subexpressions are
//! shared by construction (CSE). The constructors fold constants and apply a
//! few algebraic identities (`x + 0`, `x * 1`, `x * 0`, `x - x`, `--x`), which
//! is what makes symbolic checks such as "the second derivative of a friction
//! law is zero" decidable for affine laws.

use std::collections::HashMap;

/// Index of a node in an [`Graph`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Id(pub u32);

/// The two fused homogeneous-solution functions of a damped oscillator
/// `x'' + 2 d x' + c x = 0`, in the elapsed time `tau`, with `w2 = d^2 - c`
/// (the node holds `(d, c, tau)`, so that the run time can form the slow
/// exponent of an over-damped pair as `-c / (d + omega)` without cancellation):
///
/// * `Ec(d, w2, tau) = exp(-d tau) * cosh(sqrt(w2) tau)` (`cos` when `w2 < 0`),
/// * `Es(d, w2, tau) = exp(-d tau) * sinh(sqrt(w2) tau) / sqrt(w2)` (`sin/omega`
///   when `w2 < 0`, and `tau exp(-d tau)` at `w2 = 0`).
///
/// Both are entire in `w2`, so one formula holds in every damping regime
/// (SPEC §4); the runtime evaluates them with a series near `w2 tau^2 = 0`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Hom {
    /// `exp(-d tau) cosh(omega tau)`.
    Ec,
    /// `exp(-d tau) sinh(omega tau) / omega`.
    Es,
}

/// One node of the graph.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum Node {
    /// A literal, stored by its bits so that nodes can be hashed.
    Const(u64),
    /// A run-time parameter (index into the instance's free parameters).
    Param(u32),
    /// A variable (index into the function's arguments).
    Var(u32),
    /// `a + b`.
    Add(Id, Id),
    /// `a * b`.
    Mul(Id, Id),
    /// `-a`.
    Neg(Id),
    /// `1 / a`.
    Recip(Id),
    /// `a^n` for an integer `n`.
    Powi(Id, i32),
    /// `sqrt(a)`.
    Sqrt(Id),
    /// `exp(a)`.
    Exp(Id),
    /// `ln(a)`.
    Ln(Id),
    /// `sin(a)`.
    Sin(Id),
    /// `cos(a)`.
    Cos(Id),
    /// `|a|`.
    Abs(Id),
    /// `signum`, the derivative of `abs` away from zero.
    Sign(Id),
    /// A homogeneous-solution function `(d, c, tau)`.
    Hom(Hom, Id, Id, Id),
}

/// Why a derivative could not be formed.
#[derive(Clone, Debug, PartialEq)]
pub enum DiffError {
    /// A derivative of `Ec`/`Es` through `d` or `c`: coefficients never
    /// depend on the state or the phases, so it is not needed.
    DiscriminantDependsOnVariable,
}

/// The graph: nodes plus the interning table.
#[derive(Clone, Debug, Default)]
pub struct Graph {
    nodes: Vec<Node>,
    index: HashMap<Node, Id>,
    derivatives: HashMap<(Id, u32), Id>,
    /// The value of every node with the parameters at [`Graph::set_param_values`]
    /// (NaN for a parameter without a value and for every variable), kept
    /// as nodes are made: a non-finite number is located where it appears.
    values: Vec<f64>,
    param_values: Vec<f64>,
}

impl Graph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// The node behind an id.
    pub fn node(&self, id: Id) -> Node {
        self.nodes[id.0 as usize]
    }

    /// Number of distinct nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no nodes.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    fn intern(&mut self, node: Node) -> Id {
        if let Some(&id) = self.index.get(&node) {
            return id;
        }
        let id = Id(self.nodes.len() as u32);
        let value = eval_node(node, |c| self.values[c.0 as usize], &self.param_values, &[]);
        self.values.push(value);
        self.nodes.push(node);
        self.index.insert(node, id);
        id
    }

    /// Give the parameters values (usually their defaults): from now on
    /// [`Graph::value`] of every node is its value there.
    pub fn set_param_values(&mut self, values: Vec<f64>) {
        self.param_values = values;
        let mut all = Vec::with_capacity(self.nodes.len());
        for &node in &self.nodes {
            let value = eval_node(node, |c| all[c.0 as usize], &self.param_values, &[]);
            all.push(value);
        }
        self.values = all;
    }

    /// The node's value with the parameters at [`Graph::set_param_values`]
    /// and every variable unknown (NaN).
    pub fn value(&self, id: Id) -> f64 {
        self.values[id.0 as usize]
    }

    /// The value of a constant node, if it is one.
    pub fn as_const(&self, id: Id) -> Option<f64> {
        match self.node(id) {
            Node::Const(bits) => Some(f64::from_bits(bits)),
            _ => None,
        }
    }

    fn is_const(&self, id: Id, value: f64) -> bool {
        self.as_const(id) == Some(value)
    }

    /// A literal. `-0.0` is stored as `0.0` so that zero is one node.
    pub fn constant(&mut self, value: f64) -> Id {
        let value = if value == 0.0 { 0.0 } else { value };
        self.intern(Node::Const(value.to_bits()))
    }

    /// A free parameter.
    pub fn param(&mut self, index: u32) -> Id {
        self.intern(Node::Param(index))
    }

    /// A variable.
    pub fn var(&mut self, index: u32) -> Id {
        self.intern(Node::Var(index))
    }

    /// `a + b`.
    pub fn add(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x + y),
            (Some(0.0), _) => return b,
            (_, Some(0.0)) => return a,
            _ => {}
        }
        // x + (-x) = 0
        if self.node(b) == Node::Neg(a) || self.node(a) == Node::Neg(b) {
            return self.constant(0.0);
        }
        // (-x) + (-y) = -(x + y)
        if let (Node::Neg(x), Node::Neg(y)) = (self.node(a), self.node(b)) {
            let s = self.add(x, y);
            return self.neg(s);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Add(a, b))
    }

    /// `a - b`.
    pub fn sub(&mut self, a: Id, b: Id) -> Id {
        let nb = self.neg(b);
        self.add(a, nb)
    }

    /// `a * b`.
    pub fn mul(&mut self, a: Id, b: Id) -> Id {
        match (self.as_const(a), self.as_const(b)) {
            (Some(x), Some(y)) => return self.constant(x * y),
            (Some(z), _) | (_, Some(z)) if z == 0.0 => return self.constant(0.0),
            (Some(1.0), _) => return b,
            (_, Some(1.0)) => return a,
            (Some(-1.0), _) => return self.neg(b),
            (_, Some(-1.0)) => return self.neg(a),
            _ => {}
        }
        // Signs move outwards: (-x) * y = -(x * y).
        if let Node::Neg(x) = self.node(a) {
            let p = self.mul(x, b);
            return self.neg(p);
        }
        if let Node::Neg(y) = self.node(b) {
            let p = self.mul(a, y);
            return self.neg(p);
        }
        // x * (1/x) = 1
        if self.node(b) == Node::Recip(a) || self.node(a) == Node::Recip(b) {
            return self.constant(1.0);
        }
        if a == b {
            return self.powi(a, 2);
        }
        let (a, b) = if a <= b { (a, b) } else { (b, a) };
        self.intern(Node::Mul(a, b))
    }

    /// `-a`.
    pub fn neg(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(bits) => self.constant(-f64::from_bits(bits)),
            Node::Neg(x) => x,
            _ => self.intern(Node::Neg(a)),
        }
    }

    /// `1 / a`. The caller checks for a constant zero first (it is a model
    /// error with a location); here it folds to infinity like `f64` would.
    pub fn recip(&mut self, a: Id) -> Id {
        match self.node(a) {
            Node::Const(bits) => self.constant(1.0 / f64::from_bits(bits)),
            Node::Recip(x) => x,
            Node::Neg(x) => {
                let r = self.recip(x);
                self.neg(r)
            }
            _ => self.intern(Node::Recip(a)),
        }
    }

    /// `a / b`.
    pub fn div(&mut self, a: Id, b: Id) -> Id {
        let r = self.recip(b);
        self.mul(a, r)
    }

    /// `a^n` for an integer `n`.
    pub fn powi(&mut self, a: Id, n: i32) -> Id {
        if let Some(x) = self.as_const(a) {
            return self.constant(x.powi(n));
        }
        match n {
            0 => self.constant(1.0),
            1 => a,
            -1 => self.recip(a),
            _ => match self.node(a) {
                Node::Powi(x, m) => match m.checked_mul(n) {
                    Some(mn) => self.powi(x, mn),
                    None => self.intern(Node::Powi(a, n)),
                },
                _ => self.intern(Node::Powi(a, n)),
            },
        }
    }

    fn unary(&mut self, a: Id, make: fn(Id) -> Node, fold: fn(f64) -> f64) -> Id {
        match self.as_const(a) {
            Some(x) => self.constant(fold(x)),
            None => self.intern(make(a)),
        }
    }

    /// `sqrt(a)`.
    pub fn sqrt(&mut self, a: Id) -> Id {
        self.unary(a, Node::Sqrt, f64::sqrt)
    }
    /// `exp(a)`.
    pub fn exp(&mut self, a: Id) -> Id {
        self.unary(a, Node::Exp, f64::exp)
    }
    /// `ln(a)`.
    pub fn ln(&mut self, a: Id) -> Id {
        self.unary(a, Node::Ln, f64::ln)
    }
    /// `sin(a)`.
    pub fn sin(&mut self, a: Id) -> Id {
        self.unary(a, Node::Sin, f64::sin)
    }
    /// `cos(a)`.
    pub fn cos(&mut self, a: Id) -> Id {
        self.unary(a, Node::Cos, f64::cos)
    }
    /// `|a|`.
    pub fn abs(&mut self, a: Id) -> Id {
        self.unary(a, Node::Abs, f64::abs)
    }
    /// `signum(a)`.
    pub fn sign(&mut self, a: Id) -> Id {
        self.unary(a, Node::Sign, f64::signum)
    }

    /// A homogeneous-solution function (see [`Hom`]).
    pub fn hom(&mut self, kind: Hom, d: Id, w2: Id, tau: Id) -> Id {
        if self.is_const(tau, 0.0) {
            return match kind {
                Hom::Ec => self.constant(1.0),
                Hom::Es => self.constant(0.0),
            };
        }
        self.intern(Node::Hom(kind, d, w2, tau))
    }

    /// Whether `id` depends on variable `var`.
    pub fn depends_on(&self, id: Id, var: u32) -> bool {
        // Children always have smaller ids, so one forward pass suffices.
        let n = id.0 as usize + 1;
        let mut dep = vec![false; n];
        for i in 0..n {
            dep[i] = match self.nodes[i] {
                Node::Var(v) => v == var,
                Node::Const(_) | Node::Param(_) => false,
                node => children(node).iter().any(|c| dep[c.0 as usize]),
            };
        }
        dep[id.0 as usize]
    }

    /// Whether `id` depends on any run-time parameter.
    pub fn depends_on_params(&self, id: Id) -> bool {
        let n = id.0 as usize + 1;
        let mut dep = vec![false; n];
        for i in 0..n {
            dep[i] = match self.nodes[i] {
                Node::Param(_) => true,
                Node::Const(_) | Node::Var(_) => false,
                node => children(node).iter().any(|c| dep[c.0 as usize]),
            };
        }
        dep[id.0 as usize]
    }

    /// The exact derivative of `id` with respect to variable `var`,
    /// memoized, built in the same graph (so it shares subexpressions with
    /// the function itself).
    pub fn diff(&mut self, id: Id, var: u32) -> Result<Id, DiffError> {
        if let Some(&d) = self.derivatives.get(&(id, var)) {
            return Ok(d);
        }
        let result = match self.node(id) {
            Node::Const(_) | Node::Param(_) => self.constant(0.0),
            Node::Var(v) => self.constant(if v == var { 1.0 } else { 0.0 }),
            Node::Add(a, b) => {
                let (da, db) = (self.diff(a, var)?, self.diff(b, var)?);
                self.add(da, db)
            }
            Node::Mul(a, b) => {
                let (da, db) = (self.diff(a, var)?, self.diff(b, var)?);
                let l = self.mul(da, b);
                let r = self.mul(a, db);
                self.add(l, r)
            }
            Node::Neg(a) => {
                let da = self.diff(a, var)?;
                self.neg(da)
            }
            Node::Recip(a) => {
                // d(1/a) = -da / a^2
                let da = self.diff(a, var)?;
                let r2 = self.powi(id, 2);
                let p = self.mul(da, r2);
                self.neg(p)
            }
            Node::Powi(a, n) => {
                let da = self.diff(a, var)?;
                // n - 1 overflows only for n = i32::MIN: a^(n-1) = a^n / a.
                let pm = match n.checked_sub(1) {
                    Some(n1) => self.powi(a, n1),
                    None => self.div(id, a),
                };
                let k = self.constant(n as f64);
                let t = self.mul(k, pm);
                self.mul(t, da)
            }
            Node::Sqrt(a) => {
                // d sqrt(a) = da / (2 sqrt(a))
                let da = self.diff(a, var)?;
                let two = self.constant(2.0);
                let den = self.mul(two, id);
                self.div(da, den)
            }
            Node::Exp(a) => {
                let da = self.diff(a, var)?;
                self.mul(id, da)
            }
            Node::Ln(a) => {
                let da = self.diff(a, var)?;
                self.div(da, a)
            }
            Node::Sin(a) => {
                let da = self.diff(a, var)?;
                let c = self.cos(a);
                self.mul(c, da)
            }
            Node::Cos(a) => {
                let da = self.diff(a, var)?;
                let s = self.sin(a);
                let p = self.mul(s, da);
                self.neg(p)
            }
            Node::Abs(a) => {
                let da = self.diff(a, var)?;
                let s = self.sign(a);
                self.mul(s, da)
            }
            Node::Sign(_) => self.constant(0.0),
            Node::Hom(kind, d, w2, tau) => self.diff_hom(kind, d, w2, tau, var)?,
        };
        self.derivatives.insert((id, var), result);
        Ok(result)
    }

    /// Chain rule through `Ec`/`Es`:
    /// `dEc/dtau = -d Ec + w2 Es`, `dEs/dtau = Ec - d Es`,
    /// `dEc/dd = -tau Ec`, `dEs/dd = -tau Es`, `dEc/dw2 = tau Es / 2`.
    fn diff_hom(&mut self, kind: Hom, d: Id, c: Id, tau: Id, var: u32) -> Result<Id, DiffError> {
        let ec = self.hom(Hom::Ec, d, c, tau);
        let es = self.hom(Hom::Es, d, c, tau);
        let (dd, dc, dtau) = (self.diff(d, var)?, self.diff(c, var)?, self.diff(tau, var)?);
        let own = match kind {
            Hom::Ec => ec,
            Hom::Es => es,
        };
        // Partial derivative with respect to tau: dEc/dtau = -d Ec + w2 Es,
        // dEs/dtau = Ec - d Es, with w2 = d^2 - c.
        let d_own = self.mul(d, own);
        let p_tau = match kind {
            Hom::Ec => {
                let d2 = self.powi(d, 2);
                let w2 = self.sub(d2, c);
                let w = self.mul(w2, es);
                self.sub(w, d_own)
            }
            Hom::Es => self.sub(ec, d_own),
        };
        if self.as_const(dd) != Some(0.0) || self.as_const(dc) != Some(0.0) {
            // d/dd and d/dc are not needed: coefficients never depend on the
            // state or the phases.
            return Err(DiffError::DiscriminantDependsOnVariable);
        }
        Ok(self.mul(p_tau, dtau))
    }

    /// Replace variable `var` by the expression `by` everywhere below `id`.
    pub fn substitute(&mut self, id: Id, var: u32, by: Id) -> Id {
        let mut memo: HashMap<Id, Id> = HashMap::new();
        self.subst_rec(id, var, by, &mut memo)
    }

    fn subst_rec(&mut self, id: Id, var: u32, by: Id, memo: &mut HashMap<Id, Id>) -> Id {
        if let Some(&r) = memo.get(&id) {
            return r;
        }
        let r = match self.node(id) {
            Node::Var(v) if v == var => by,
            Node::Const(_) | Node::Param(_) | Node::Var(_) => id,
            Node::Add(a, b) => {
                let (a, b) = (
                    self.subst_rec(a, var, by, memo),
                    self.subst_rec(b, var, by, memo),
                );
                self.add(a, b)
            }
            Node::Mul(a, b) => {
                let (a, b) = (
                    self.subst_rec(a, var, by, memo),
                    self.subst_rec(b, var, by, memo),
                );
                self.mul(a, b)
            }
            Node::Neg(a) => {
                let a = self.subst_rec(a, var, by, memo);
                self.neg(a)
            }
            Node::Recip(a) => {
                let a = self.subst_rec(a, var, by, memo);
                self.recip(a)
            }
            Node::Powi(a, n) => {
                let a = self.subst_rec(a, var, by, memo);
                self.powi(a, n)
            }
            Node::Sqrt(a) => self.map_unary(a, var, by, memo, Graph::sqrt),
            Node::Exp(a) => self.map_unary(a, var, by, memo, Graph::exp),
            Node::Ln(a) => self.map_unary(a, var, by, memo, Graph::ln),
            Node::Sin(a) => self.map_unary(a, var, by, memo, Graph::sin),
            Node::Cos(a) => self.map_unary(a, var, by, memo, Graph::cos),
            Node::Abs(a) => self.map_unary(a, var, by, memo, Graph::abs),
            Node::Sign(a) => self.map_unary(a, var, by, memo, Graph::sign),
            Node::Hom(k, d, w2, tau) => {
                let d = self.subst_rec(d, var, by, memo);
                let w2 = self.subst_rec(w2, var, by, memo);
                let tau = self.subst_rec(tau, var, by, memo);
                self.hom(k, d, w2, tau)
            }
        };
        memo.insert(id, r);
        r
    }

    fn map_unary(
        &mut self,
        a: Id,
        var: u32,
        by: Id,
        memo: &mut HashMap<Id, Id>,
        f: fn(&mut Graph, Id) -> Id,
    ) -> Id {
        let a = self.subst_rec(a, var, by, memo);
        f(self, a)
    }

    /// Evaluate `id` with the given parameter and variable values.
    ///
    /// This is the reference the generated code is tested against; its
    /// `Ec`/`Es` use the textbook regime formulas (not the runtime's series),
    /// so that it is an independent computation away from critical damping.
    pub fn eval(&self, id: Id, params: &[f64], vars: &[f64]) -> f64 {
        let mut values: Vec<f64> = Vec::with_capacity(id.0 as usize + 1);
        for i in 0..=id.0 as usize {
            let value = eval_node(self.nodes[i], |c| values[c.0 as usize], params, vars);
            values.push(value);
        }
        values[id.0 as usize]
    }
}

/// One node's value from its children's (`v`), with the given parameter
/// and variable values (NaN where none is given).
fn eval_node(node: Node, v: impl Fn(Id) -> f64, params: &[f64], vars: &[f64]) -> f64 {
    match node {
        Node::Const(bits) => f64::from_bits(bits),
        Node::Param(k) => params.get(k as usize).copied().unwrap_or(f64::NAN),
        Node::Var(k) => vars.get(k as usize).copied().unwrap_or(f64::NAN),
        Node::Add(a, b) => v(a) + v(b),
        Node::Mul(a, b) => v(a) * v(b),
        Node::Neg(a) => -v(a),
        Node::Recip(a) => 1.0 / v(a),
        Node::Powi(a, n) => v(a).powi(n),
        Node::Sqrt(a) => v(a).sqrt(),
        Node::Exp(a) => v(a).exp(),
        Node::Ln(a) => v(a).ln(),
        Node::Sin(a) => v(a).sin(),
        Node::Cos(a) => v(a).cos(),
        Node::Abs(a) => v(a).abs(),
        Node::Sign(a) => v(a).signum(),
        Node::Hom(kind, d, c, tau) => {
            let (d, tau) = (v(d), v(tau));
            let w2 = d * d - v(c);
            let e = (-d * tau).exp();
            let (c, s) = if w2 > 0.0 {
                let w = w2.sqrt();
                ((w * tau).cosh(), (w * tau).sinh() / w)
            } else if w2 < 0.0 {
                let w = (-w2).sqrt();
                ((w * tau).cos(), (w * tau).sin() / w)
            } else {
                (1.0, tau)
            };
            match kind {
                Hom::Ec => e * c,
                Hom::Es => e * s,
            }
        }
    }
}

/// The walk both back ends make over the nodes a function's `outputs`
/// reach (`emit::expression` writing Rust, `jit` writing Cranelift IR):
/// which nodes are reached, in index order (children first), and how often
/// each is used. A node used twice or more, and every `Ec`/`Es`, is
/// computed once into a name; a node used once is written where it is used,
/// so that `a * (1 / b)` is a division and `a + (-b)` a subtraction there,
/// in both back ends alike.
#[derive(Clone, Debug)]
pub struct Schedule {
    reach: Vec<bool>,
    uses: Vec<u32>,
}

impl Schedule {
    /// The schedule of the function computing `outputs` in `g`.
    pub fn new(g: &Graph, outputs: &[Id]) -> Self {
        let n = outputs.iter().map(|o| o.0 as usize + 1).max().unwrap_or(0);
        let mut reach = vec![false; n];
        let mut uses = vec![0u32; n];
        let mut stack: Vec<Id> = outputs.to_vec();
        for o in outputs {
            uses[o.0 as usize] += 1;
        }
        while let Some(id) = stack.pop() {
            if reach[id.0 as usize] {
                continue;
            }
            reach[id.0 as usize] = true;
            for c in children(g.node(id)) {
                uses[c.0 as usize] += 1;
                stack.push(c);
            }
        }
        Self { reach, uses }
    }

    /// The reached nodes, children before their parents.
    pub fn nodes(&self) -> impl Iterator<Item = Id> + '_ {
        (0..self.reach.len())
            .filter(|&i| self.reach[i])
            .map(|i| Id(i as u32))
    }

    /// Whether node `id` is computed once into a name: used twice or more,
    /// or a homogeneous-solution function (its pair is one call). Leaves
    /// (constants, parameters, variables) never are.
    pub fn is_bound(&self, g: &Graph, id: Id) -> bool {
        match g.node(id) {
            Node::Const(_) | Node::Param(_) | Node::Var(_) => false,
            Node::Hom(..) => true,
            _ => self.uses.get(id.0 as usize).is_some_and(|&u| u >= 2),
        }
    }
}

/// The children of a node, in order.
pub fn children(node: Node) -> Vec<Id> {
    match node {
        Node::Const(_) | Node::Param(_) | Node::Var(_) => vec![],
        Node::Add(a, b) | Node::Mul(a, b) => vec![a, b],
        Node::Neg(a)
        | Node::Recip(a)
        | Node::Powi(a, _)
        | Node::Sqrt(a)
        | Node::Exp(a)
        | Node::Ln(a)
        | Node::Sin(a)
        | Node::Cos(a)
        | Node::Abs(a)
        | Node::Sign(a) => vec![a],
        Node::Hom(_, d, w2, tau) => vec![d, w2, tau],
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn identical_nodes_are_interned_once() {
        let mut g = Graph::new();
        let (x, y) = (g.var(0), g.var(1));
        let a = g.mul(x, y);
        let b = g.mul(y, x);
        assert_eq!(a, b);
        let n = g.len();
        let s = g.sin(a);
        let s2 = g.sin(b);
        assert_eq!(s, s2);
        assert_eq!(g.len(), n + 1);
    }

    #[test]
    fn folds_constants_and_identities() {
        let mut g = Graph::new();
        let x = g.var(0);
        let two = g.constant(2.0);
        let three = g.constant(3.0);
        let six = g.mul(two, three);
        assert_eq!(g.as_const(six), Some(6.0));
        let z = g.sub(x, x);
        assert_eq!(g.as_const(z), Some(0.0));
        let one = g.constant(1.0);
        assert_eq!(g.mul(x, one), x);
        let nx = g.neg(x);
        assert_eq!(g.neg(nx), x);
    }

    #[test]
    fn derivatives_match_finite_differences() {
        let mut g = Graph::new();
        let (x, p) = (g.var(0), g.param(0));
        // f = exp(-p x) * sin(x^3) / (1 + x^2) + sqrt(x) * ln(x)
        let px = g.mul(p, x);
        let npx = g.neg(px);
        let e = g.exp(npx);
        let x3 = g.powi(x, 3);
        let s = g.sin(x3);
        let one = g.constant(1.0);
        let x2 = g.powi(x, 2);
        let den = g.add(one, x2);
        let es = g.mul(e, s);
        let q = g.div(es, den);
        let sq = g.sqrt(x);
        let l = g.ln(x);
        let r = g.mul(sq, l);
        let f = g.add(q, r);
        let df = g.diff(f, 0).unwrap();
        for &xv in &[0.3, 0.9, 1.7] {
            let h = 1e-6;
            let fd = (g.eval(f, &[0.7], &[xv + h]) - g.eval(f, &[0.7], &[xv - h])) / (2.0 * h);
            let an = g.eval(df, &[0.7], &[xv]);
            assert!((fd - an).abs() < 1e-8 * (1.0 + an.abs()), "{fd} vs {an}");
        }
    }

    #[test]
    fn homogeneous_derivatives_match_finite_differences() {
        let mut g = Graph::new();
        let tau = g.var(0);
        for (d, w2) in [(0.3, -4.0), (0.2, 3.0), (-0.1, -1.0), (1.0, 0.0)] {
            let (dn, wn) = (g.constant(d), g.constant(d * d - w2));
            for kind in [Hom::Ec, Hom::Es] {
                let f = g.hom(kind, dn, wn, tau);
                let df = g.diff(f, 0).unwrap();
                for &t in &[0.1, 0.8, 2.0] {
                    let h = 1e-6;
                    let fd = (g.eval(f, &[], &[t + h]) - g.eval(f, &[], &[t - h])) / (2.0 * h);
                    let an = g.eval(df, &[], &[t]);
                    assert!(
                        (fd - an).abs() < 1e-7 * (1.0 + an.abs()),
                        "{kind:?} {d} {w2}: {fd} vs {an}"
                    );
                }
            }
        }
    }

    #[test]
    fn second_derivative_of_an_affine_law_is_exactly_zero() {
        let mut g = Graph::new();
        let (v, mu, vv, m) = (g.var(0), g.param(0), g.param(1), g.param(2));
        // (mu * (v - V) + 2) / m
        let dv = g.sub(v, vv);
        let t = g.mul(mu, dv);
        let two = g.constant(2.0);
        let s = g.add(t, two);
        let f = g.div(s, m);
        let d1 = g.diff(f, 0).unwrap();
        let d2 = g.diff(d1, 0).unwrap();
        assert_eq!(g.as_const(d2), Some(0.0));
        // v * v is not affine.
        let q = g.mul(v, v);
        let q1 = g.diff(q, 0).unwrap();
        let q2 = g.diff(q1, 0).unwrap();
        assert_eq!(g.as_const(q2), Some(2.0));
    }
}

//! Grammar-aware model files for the `model_grammar` fuzz target and its
//! replay in `tests/fuzz_smoke.rs`: the fuzz input's bytes choose a model
//! from the language's grammar (parameters with defaults and bounds, lets,
//! the oscillator block, boundaries with stick levels, domains over bands or
//! a smooth law, scenes with structures or pieces, nested expressions,
//! numbers up to the extremes, hostile identifiers), printed as text, then
//! slightly mutated (a token dropped, duplicated, swapped or renamed) for
//! near-well-formed inputs. The text goes through `check_source`, the entry
//! point of `stickslip check`, `build.rs` and `model!(file = ...)`, or
//! through the run-time back end (`model_jit`), which must accept exactly
//! what `check_source` accepts.
//!
//! Sizes are bounded (at most 8 parameters, 4 lets, 5 boundaries, 6 scenes,
//! expressions 5 deep, 4 mutations), so every input is checked in bounded
//! time. Needs the `harness` module at the crate root (`Bytes`,
//! `model_text`).

use crate::harness::{model_loaded, model_text, Bytes};

/// Build a model from `data`, check it: no panic, a located report or code
/// that parses as Rust (see `harness::model_text`).
pub fn model_grammar(data: &[u8]) {
    let source = model_from_bytes(data);
    model_text(&source);
}

/// Build a model from `data` and load it through the run-time back end
/// (see `harness::model_jit`); the bytes past the model's choose the points
/// its compiled functions are called at.
pub fn model_jit(data: &[u8]) {
    let source = model_from_bytes(data);
    let points = data.get(data.len() / 2..).unwrap_or_default();
    model_loaded(&source, &mut Bytes::new(points));
}

/// The model text `data` chooses (also used to write seeds).
pub fn model_from_bytes(data: &[u8]) -> String {
    let mut r = Bytes::new(data);
    // 3 in 8: a model that follows the rules; 3 in 8: the same, mutated;
    // 2 in 8: anything the grammar allows (and some it does not), mutated.
    let mode = r.byte() % 8;
    let mut g = Gen {
        r,
        out: Vec::new(),
        params: Vec::new(),
        lets: Vec::new(),
        positive: Vec::new(),
        strict: mode < 6,
    };
    g.model();
    let mutations = if mode < 3 { 0 } else { 1 + g.r.byte() % 4 };
    for _ in 0..mutations {
        g.mutate();
    }
    let mut text = String::new();
    for t in &g.out {
        text.push_str(t);
        if t.ends_with('\n') {
            continue;
        }
        text.push(' ');
    }
    text
}

/// Hostile identifiers beyond [`LEGAL_HOSTILE`]: Rust keywords and reserved
/// words, raw identifiers, the language's keywords and function names,
/// look-alikes of generated labels, letters that NFC changes (µ, Ω). Together the
/// two lists are every name a model author (or an attacker) might choose.
const RESERVED_HOSTILE: &[&str] = &[
    "self",
    "Self",
    "super",
    "crate",
    "fn",
    "mod",
    "type",
    "struct",
    "match",
    "loop",
    "async",
    "await",
    "dyn",
    "try",
    "yield",
    "abstract",
    "r#type",
    "r#match",
    "_",
    "v",
    "model",
    "param",
    "let",
    "oscillator",
    "law",
    "boundary",
    "domain",
    "scene",
    "stick",
    "free",
    "structures",
    "pieces",
    "ln",
    "sqrt",
    "cos",
    "sign",
    "powi",
    "Sigma0",
    "Sigma",
    "µ",
    "Ω",
];

/// Hostile names the language accepts as identifiers (not Rust keywords).
const LEGAL_HOSTILE: &[&str] = &[
    "x",
    "p",
    "t",
    "s",
    "q",
    "j",
    "k",
    "n",
    "w",
    "_x",
    "__",
    "Params",
    "ParamSet",
    "Model",
    "INFO",
    "SMOOTH_INFO",
    "Coefficients",
    "Oscillator",
    "std",
    "core",
    "f64",
    "usize",
    "Option",
    "Some",
    "None",
    "Ok",
    "Err",
    "Vec",
    "String",
    "TAU",
    "PI",
    "mass",
    "damping",
    "stiffness",
    "forcing",
    "frequency",
    "belt",
    "range",
    "kinetic",
    "exp",
    "sin",
    "abs",
    "Sigma1",
    "Tau1",
    "é",
    "naïve",
    "a_very_long_parameter_name_that_goes_on_and_on_and_on_for_a_while_0123456789",
];

/// Ordinary names.
const PLAIN: &[&str] = &[
    "m", "d", "c", "V", "V1", "V2", "mu", "mus", "muk", "mu1", "mu2", "g", "Q0", "W", "FN", "a",
    "b", "k", "vs", "sigma",
];

/// Numbers: ordinary, integer and float spellings, extremes, overflow,
/// subnormal, suffixed and underscored literals.
const NUMBERS: &[&str] = &[
    "0",
    "1",
    "2",
    "3",
    "0.0",
    "0.5",
    "1.0",
    "2.5",
    "30.0",
    "9.8",
    "1e3",
    "1e-3",
    "1e308",
    "1.7976931348623157e308",
    "1e309",
    "1e400",
    "2.2250738585072014e-308",
    "5e-324",
    "1e-400",
    "4.9e-324",
    "18446744073709551615",
    "18446744073709551616",
    "340282366920938463463374607431768211456",
    "1_000.5",
    "0.1f64",
    "1f32",
    "7u8",
    "0x10",
    "0b1",
    "0o7",
    "1.",
    "1e0",
    "0.000000000000000000001",
];

const FUNCTIONS: &[&str] = &[
    "exp", "ln", "sqrt", "sin", "cos", "abs", "sign", "powi", "tan", "max",
];

const BOUND_OPS: &[&str] = &[">", ">=", "<", "<="];

const FIELDS: [&str; 5] = ["mass", "damping", "stiffness", "forcing", "frequency"];

struct Gen<'a> {
    r: Bytes<'a>,
    out: Vec<String>,
    params: Vec<String>,
    lets: Vec<String>,
    /// Parameters declared `> 0` (for mass, stiffness, frequency).
    positive: Vec<String>,
    /// Follow the language's rules (a model that should build), or not.
    strict: bool,
}

impl Gen<'_> {
    fn tok(&mut self, t: &str) {
        self.out.push(t.to_string());
    }

    fn toks(&mut self, ts: &[&str]) {
        for t in ts {
            self.tok(t);
        }
    }

    fn newline(&mut self) {
        self.out.push("\n".into());
    }

    /// A choice in `0..n` (0 past the input's end).
    fn below(&mut self, n: usize) -> usize {
        self.r.byte() as usize % n.max(1)
    }

    /// True with probability about `k / 8`.
    fn chance(&mut self, k: u8) -> bool {
        self.r.byte() % 8 < k
    }

    fn pick<'s>(&mut self, from: &[&'s str]) -> &'s str {
        from[self.below(from.len())]
    }

    /// A new name: mostly plain, sometimes hostile, sometimes numbered
    /// (when strict: a legal identifier not used yet).
    fn name(&mut self) -> String {
        if self.strict {
            let base = if self.chance(2) {
                self.pick(LEGAL_HOSTILE)
            } else {
                self.pick(PLAIN)
            };
            let mut name = base.to_string();
            let mut k = 0;
            while self.params.contains(&name) || self.lets.contains(&name) {
                k += 1;
                name = format!("{base}_{k}");
            }
            return name;
        }
        match self.r.byte() % 8 {
            0..=4 => self.pick(PLAIN).to_string(),
            5 | 6 => {
                // Any hostile name: legal or reserved.
                let k = self.below(LEGAL_HOSTILE.len() + RESERVED_HOSTILE.len());
                match LEGAL_HOSTILE.get(k) {
                    Some(n) => n.to_string(),
                    None => RESERVED_HOSTILE[k - LEGAL_HOSTILE.len()].to_string(),
                }
            }
            _ => format!("{}{}", self.pick(PLAIN), self.r.byte()),
        }
    }

    /// A name in scope (a parameter or let), `v`, or (rarely) any name.
    fn reference(&mut self) -> String {
        let known = self.params.len() + self.lets.len();
        if self.strict {
            if known == 0 {
                return "1.5".into();
            }
            let i = self.below(known);
            return if i < self.params.len() {
                self.params[i].clone()
            } else {
                self.lets[i - self.params.len()].clone()
            };
        }
        match self.r.byte() % 8 {
            0..=5 if known > 0 => {
                let i = self.below(known);
                if i < self.params.len() {
                    self.params[i].clone()
                } else {
                    self.lets[i - self.params.len()].clone()
                }
            }
            6 => "v".into(),
            _ => self.name(),
        }
    }

    fn number(&mut self) -> String {
        if self.strict {
            return match self.r.byte() % 4 {
                0 => format!("{}.0", 1 + self.below(9)),
                1 => format!("{}.{}", self.below(4), 1 + self.below(99)),
                2 => format!("{}", 1 + self.below(20)),
                _ => format!("{}e-{}", 1 + self.below(9), self.below(4)),
            };
        }
        match self.r.byte() % 4 {
            0 | 1 => self.pick(NUMBERS).to_string(),
            2 => format!("{}.{}", self.r.byte(), self.r.byte()),
            _ => {
                let e = self.r.byte() as i8;
                format!("{}e{e}", 1 + self.r.byte() % 9)
            }
        }
    }

    /// An expression at most `depth` deep.
    fn expr(&mut self, depth: u32) {
        let kind = if depth == 0 {
            self.r.byte() % 3
        } else {
            self.r.byte() % 9
        };
        match kind {
            0 => {
                let n = self.number();
                self.tok(&n);
            }
            1 | 2 => {
                let n = self.reference();
                self.tok(&n);
            }
            3 => {
                self.tok("-");
                self.expr(depth - 1);
            }
            4 => {
                self.tok("(");
                self.expr(depth - 1);
                self.tok(")");
            }
            5 if self.strict => {
                // Functions defined everywhere, on small arguments.
                let f = self.pick(&["sin", "cos", "abs", "exp", "sqrt", "powi"]);
                self.toks(&[f, "("]);
                if f == "sqrt" || f == "exp" {
                    self.toks(&["abs", "(", "sin", "("]);
                    self.expr(depth - 1);
                    self.toks(&[")", ")"]);
                } else {
                    self.expr(depth - 1);
                }
                if f == "powi" {
                    let n = format!("{}", self.below(4));
                    self.toks(&[",", &n]);
                }
                self.tok(")");
            }
            5 => {
                let f = self.pick(FUNCTIONS);
                self.toks(&[f, "("]);
                self.expr(depth - 1);
                if f == "powi" || f == "max" || self.chance(1) {
                    self.tok(",");
                    if f == "powi" && self.chance(6) {
                        let n = format!("{}", (self.r.byte() as i8) / 8);
                        self.tok(&n);
                    } else {
                        self.expr(depth - 1);
                    }
                }
                self.tok(")");
            }
            _ => {
                self.expr(depth - 1);
                let ops = if self.strict { 3 } else { 6 + self.below(3) };
                let op = self.pick(&["+", "-", "*", "/", "*", "+", "%", "^"][..ops]);
                self.tok(op);
                self.expr(depth - 1);
            }
        }
    }

    fn depth(&mut self) -> u32 {
        self.r.byte() as u32 % 6
    }

    fn doc(&mut self) {
        if self.chance(2) {
            let kinds = if self.strict { 3 } else { 4 };
            let line = match self.r.byte() % kinds {
                0 => "/// A doc comment.",
                1 => "/// Doc with \"quotes\", `code` and a tab\there.",
                2 => "#[doc = \"attribute doc\"]",
                _ => "#[allow(unused)]",
            };
            self.tok(line);
            self.newline();
        }
    }

    fn model(&mut self) {
        if self.chance(1) {
            self.tok("//! A generated model.");
            self.newline();
        }
        let name = self.name();
        self.toks(&["model", &name, "{"]);
        self.newline();

        let smooth = self.chance(2);
        let n_params = self.below(9);
        for _ in 0..n_params {
            self.doc();
            let p = self.name();
            self.toks(&["param", &p, "="]);
            if self.strict {
                let n = self.number();
                self.tok(&n);
                if self.chance(5) {
                    self.toks(&[",", ">", "0"]);
                    self.positive.push(p.clone());
                }
                self.tok(";");
                self.newline();
                self.params.push(p);
                continue;
            }
            let d = self.depth().min(2);
            self.expr(d);
            for _ in 0..self.below(3) {
                self.tok(",");
                let op = self.pick(BOUND_OPS);
                self.tok(op);
                let d = self.depth().min(1);
                self.expr(d);
            }
            self.tok(";");
            self.newline();
            self.params.push(p);
        }
        for _ in 0..self.below(5) {
            self.doc();
            let l = self.name();
            self.toks(&["let", &l, "="]);
            let d = if self.strict {
                self.depth().min(3)
            } else {
                self.depth()
            };
            self.expr(d);
            self.tok(";");
            self.newline();
            self.lets.push(l);
        }
        if self.strict {
            self.strict_oscillator();
        } else if !self.chance(1) {
            self.oscillator();
        }
        let labels = match (smooth, self.strict) {
            (true, true) => {
                self.strict_law();
                Vec::new()
            }
            (true, false) => {
                self.law();
                Vec::new()
            }
            (false, true) => self.strict_pieces(),
            (false, false) => {
                self.pieces();
                Vec::new()
            }
        };
        for _ in 0..self.below(7) {
            if self.strict {
                self.strict_scene(smooth, &labels);
            } else {
                self.scene(smooth);
            }
        }
        self.tok("}");
        self.newline();
    }

    fn oscillator(&mut self) {
        self.doc();
        self.toks(&["oscillator", "{"]);
        self.newline();
        for (i, field) in FIELDS.iter().enumerate() {
            match self.r.byte() % 16 {
                0 => continue,
                1 => {
                    let f = self.pick(&FIELDS);
                    self.toks(&[f, ":"]);
                }
                2 => {
                    let f = self.name();
                    self.toks(&[&f, ":"]);
                }
                _ => self.toks(&[field, ":"]),
            }
            let d = self.depth().min(3);
            self.expr(d);
            if i + 1 < FIELDS.len() || self.chance(4) {
                self.tok(",");
            }
            self.newline();
        }
        self.tok("}");
        self.newline();
    }

    fn law(&mut self) {
        self.doc();
        self.toks(&["law", "{"]);
        for field in ["belt", "stick", "range", "kinetic"] {
            if self.r.byte() % 16 == 0 {
                continue;
            }
            self.toks(&[field, ":"]);
            let d = self.depth().min(4);
            self.expr(d);
            self.tok(",");
            self.newline();
        }
        self.tok("}");
        self.newline();
    }

    /// Boundaries at increasing velocities and the domains between them
    /// (mostly a well-formed partition of the velocity line).
    fn pieces(&mut self) {
        let n = 1 + self.below(5);
        let mut velocity = -2.0 + self.below(5) as f64;
        let mut labels = Vec::new();
        for k in 0..n {
            self.doc();
            let label = if self.r.byte() % 32 == 0 {
                self.name()
            } else {
                format!("Sigma{}", k + 1)
            };
            self.toks(&["boundary", &label, ":", "v", "="]);
            if self.chance(5) {
                let v = format!("{velocity:?}");
                self.tok(&v);
            } else {
                let d = self.depth().min(2);
                self.expr(d);
            }
            velocity += 0.25 + self.below(8) as f64 * 0.5;
            if self.chance(3) {
                self.toks(&[",", "stick"]);
                if self.chance(5) {
                    let s = self.number();
                    self.tok(&s);
                } else {
                    let d = self.depth().min(3);
                    self.expr(d);
                }
            }
            self.tok(";");
            self.newline();
            labels.push(label);
        }
        // Bands: below the first, between neighbours, above the last.
        let mut order: Vec<usize> = (0..=n).collect();
        if self.chance(2) {
            let (a, b) = (self.below(n + 1), self.below(n + 1));
            order.swap(a, b);
        }
        for (slot, &band) in order.iter().enumerate() {
            if self.r.byte() % 32 == 0 {
                continue;
            }
            self.doc();
            let label = if self.r.byte() % 32 == 0 {
                "0".to_string()
            } else {
                format!("{}", slot + 1)
            };
            self.toks(&["domain", &label, ":"]);
            let (lo, hi) = (
                band.checked_sub(1).map(|i| labels[i].clone()),
                labels.get(band).cloned(),
            );
            let less = if self.chance(1) { "<=" } else { "<" };
            match (lo, hi) {
                (None, Some(h)) => self.toks(&["v", less, &h]),
                (Some(l), None) => self.toks(&["v", if less == "<" { ">" } else { ">=" }, &l]),
                (Some(l), Some(h)) => self.toks(&[&l, "<", "v", less, &h]),
                (None, None) => self.toks(&["v", ">", "0"]),
            }
            self.tok("=>");
            let d = self.depth().min(4);
            self.expr(d);
            self.tok(";");
            self.newline();
        }
    }

    fn scene(&mut self, smooth: bool) {
        self.doc();
        let name = self.name();
        self.toks(&["scene", &name, "{"]);
        if self.chance(7) {
            self.tok("free");
            self.tok(":");
            let n = 1 + self.below(3);
            for i in 0..n {
                let p = self.reference();
                self.tok(&p);
                if i + 1 < n {
                    self.tok(",");
                }
            }
            self.tok(";");
        }
        if smooth || self.chance(1) {
            if self.chance(7) {
                let n = match self.r.byte() % 8 {
                    0 => format!("{}", self.r.byte()),
                    1 => "0".into(),
                    2 => "129".into(),
                    _ => format!("{}", 2 * (1 + self.below(8))),
                };
                self.toks(&["pieces", ":", &n, ";"]);
            }
        } else if self.chance(5) {
            self.tok("structures");
            self.tok(":");
            let n = 1 + self.below(3);
            for i in 0..n {
                let m = 1 + self.below(5);
                let s: Vec<String> = (0..m)
                    .map(|_| format!("{}_{}{}", self.below(5), self.below(5), self.below(5)))
                    .collect();
                self.tok(&format!("{:?}", s.join(" ")));
                if i + 1 < n {
                    self.tok(",");
                }
            }
            self.tok(";");
        }
        self.tok("}");
        self.newline();
    }

    /// A positive quantity: a parameter declared `> 0`, or a number.
    fn positive(&mut self) {
        if !self.positive.is_empty() && self.chance(5) {
            let i = self.below(self.positive.len());
            let p = self.positive[i].clone();
            self.tok(&p);
        } else {
            let n = self.number();
            self.tok(&n);
        }
    }

    fn strict_oscillator(&mut self) {
        self.doc();
        self.toks(&["oscillator", "{"]);
        self.newline();
        for field in FIELDS {
            self.toks(&[field, ":"]);
            match field {
                "damping" => {
                    let n = self.number();
                    self.toks(&["0.01", "*", &n]);
                }
                "forcing" => {
                    let d = self.depth().min(3);
                    self.expr(d);
                }
                _ => self.positive(),
            }
            self.tok(",");
            self.newline();
        }
        self.tok("}");
        self.newline();
    }

    /// A smooth law: Coulomb-like with a viscous term, static level above it.
    fn strict_law(&mut self) {
        self.doc();
        let belt = format!("{}.5", self.below(4));
        let level = format!("{}.25", 1 + self.below(8));
        let slope = format!("0.{}", self.below(10));
        self.toks(&[
            "law", "{", "belt", ":", &belt, ",", "stick", ":", "50.0", ",", "range", ":",
        ]);
        let range = format!("{}.0", 2 + self.below(8));
        self.toks(&[&range, ",", "kinetic", ":"]);
        self.toks(&["sign", "(", "v", "-", &belt, ")", "*", "("]);
        if self.chance(4) {
            self.toks(&[
                &level, "+", "exp", "(", "-", "abs", "(", "v", "-", &belt, ")", ")",
            ]);
        } else {
            self.tok(&level);
        }
        self.toks(&[")", "+", &slope, "*", "(", "v", "-", &belt, ")", ",", "}"]);
        self.newline();
    }

    /// Boundaries at increasing velocities, one of them a stick boundary,
    /// and one domain per band with an affine law, continuous at every
    /// other boundary (exact binary fractions, so exactly continuous).
    /// Returns the boundary labels' numbers.
    fn strict_pieces(&mut self) -> Vec<usize> {
        let n = 1 + self.below(4);
        let stick = self.below(n);
        let mut velocities = Vec::new();
        let mut u = -2.0 + self.below(5) as f64;
        for k in 0..n {
            self.doc();
            let label = format!("Sigma{}", k + 1);
            let v = format!("{u:?}");
            self.toks(&["boundary", &label, ":", "v", "=", &v]);
            if k == stick {
                self.toks(&[",", "stick", "100.0"]);
            }
            self.tok(";");
            self.newline();
            velocities.push(u);
            u += 0.5 * (1 + self.below(4)) as f64;
        }
        // Domain j covers band j: below Sigma1 (j = 0), between Sigma_j and
        // Sigma_{j+1}, above Sigma_n (j = n). Its law is y + s (v - u) with
        // u its lower boundary (the first one for the band below).
        let mut y = 0.25 * self.below(16) as f64 - 2.0;
        let mut laws = Vec::new();
        for j in 0..=n {
            let s = 0.25 * self.below(8) as f64 - 1.0;
            let u = velocities[j.saturating_sub(1)];
            if j > 0 && j - 1 == stick {
                // A jump at the stick boundary (up, as friction above the belt).
                y += 0.25 * (1 + self.below(8)) as f64;
            }
            laws.push(format!("{y:?} + {s:?} * (v - {u:?})"));
            // The value at the next boundary.
            if j > 0 && j < n {
                y += s * (velocities[j] - u);
            }
            if j == 0 {
                // Domain 0's law is anchored at Sigma1 itself.
                y += 0.0;
            }
        }
        let mut order: Vec<usize> = (0..=n).collect();
        // Domains in any order (the language does not care).
        for i in (1..order.len()).rev() {
            let k = self.below(i + 1);
            order.swap(i, k);
        }
        for &j in &order {
            self.doc();
            let label = format!("{}", j + 1);
            self.toks(&["domain", &label, ":"]);
            let band = if j == 0 {
                "v < Sigma1".to_string()
            } else if j == n {
                format!("v > Sigma{n}")
            } else {
                format!("Sigma{j} < v < Sigma{}", j + 1)
            };
            let law = laws[j].clone();
            self.toks(&[&band, "=>", &law, ";"]);
            self.newline();
        }
        // Boundary k (1-based) separates domains k (label) and k + 1.
        (1..=n)
            .map(|k| k + 100 * usize::from(k - 1 == stick))
            .collect()
    }

    /// A scene: one or two free parameters; a closed structure (a walk over
    /// the domains and back) or `pieces`.
    fn strict_scene(&mut self, smooth: bool, bounds: &[usize]) {
        if self.params.is_empty() {
            return;
        }
        let name = format!("scene{}", self.r.byte());
        if self.out.contains(&name) {
            return;
        }
        self.doc();
        self.toks(&["scene", &name, "{", "free", ":"]);
        let (i, k) = (self.below(self.params.len()), self.below(self.params.len()));
        let (a, b) = (self.params[i].clone(), self.params[k].clone());
        self.tok(&a);
        if b != a {
            self.toks(&[",", &b]);
        }
        self.tok(";");
        if smooth {
            let n = format!("{}", 2 * (1 + self.below(8)));
            self.toks(&["pieces", ":", &n, ";"]);
        } else if !bounds.is_empty() && self.chance(6) {
            let n = bounds.len();
            // A walk: from boundary b through an adjacent domain to one of
            // its boundaries (or, at the stick boundary, a stick mapping).
            let mut b = 1 + self.below(n);
            let mut walk = Vec::new();
            let steps = 1 + self.below(4);
            for step in 0..steps {
                // A stick mapping is followed by one that leaves the stick
                // boundary into a domain: never two in a row, counting the
                // turn back (last step) and the wrap to the start (first).
                let inner = step > 0 && step + 1 < steps;
                let after_stick = walk.last().is_some_and(|&(d, _, _)| d == 0);
                let stick = bounds[b - 1] > 100 && inner && !after_stick;
                let (domain, next) = if stick && self.chance(2) {
                    (0, b)
                } else if self.chance(4) {
                    // The domain below b: label b; its lower boundary b - 1.
                    (b, if b > 1 && self.chance(4) { b - 1 } else { b })
                } else {
                    // The domain above b: label b + 1; its upper boundary b + 1.
                    (b + 1, if b < n && self.chance(4) { b + 1 } else { b })
                };
                walk.push((domain, b, next));
                b = next;
            }
            // Back along the same domains.
            let back: Vec<(usize, usize, usize)> = walk
                .iter()
                .rev()
                .map(|&(d, from, to)| (d, to, from))
                .collect();
            walk.extend(back);
            // Applied right to left (the first mapping is the last written);
            // `i_jk` maps boundary k to boundary j through domain i.
            let text: Vec<String> = walk
                .iter()
                .rev()
                .map(|(d, from, to)| format!("{d}_{to}{from}"))
                .collect();
            self.toks(&["structures", ":"]);
            let lit = format!("{:?}", text.join(" "));
            self.toks(&[&lit, ";"]);
        }
        self.tok("}");
        self.newline();
    }

    /// One small mutation of the token list: drop, duplicate or swap a
    /// token, or replace a name by another.
    fn mutate(&mut self) {
        let len = self.out.len();
        if len == 0 {
            return;
        }
        let at = (self.r.byte() as usize * 256 + self.r.byte() as usize) % len;
        match self.r.byte() % 5 {
            0 => {
                self.out.remove(at);
            }
            1 => {
                let t = self.out[at].clone();
                self.out.insert(at, t);
            }
            2 => {
                let other = (self.r.byte() as usize * 256 + self.r.byte() as usize) % len;
                self.out.swap(at, other);
            }
            3 => {
                let n = self.name();
                self.out[at] = n;
            }
            _ => {
                let t = self.pick(&[
                    "{", "}", "(", ")", ";", ",", ":", "=", "=>", "-", "\"", "'", "#", "/*", "*/",
                ]);
                self.out.insert(at, t.to_string());
            }
        }
    }
}

//! Errors that point at the model: every error has a span; all of a file's
//! errors are collected, then shown either as one `syn::Error` (the macro
//! turns it into `compile_error!`s at the right tokens) or, for a model file
//! read by `build.rs`, as `file:line:col` lines with the offending source line.

use proc_macro2::Span;

/// One located error.
#[derive(Clone, Debug)]
pub struct Diagnostic {
    /// Where in the model.
    pub span: Span,
    /// What is wrong, in the model's terms.
    pub message: String,
}

/// All errors found so far.
#[derive(Clone, Debug, Default)]
pub struct Diagnostics {
    list: Vec<Diagnostic>,
}

impl Diagnostics {
    /// No errors yet.
    pub fn new() -> Self {
        Self::default()
    }

    /// Record an error at `span`.
    pub fn error(&mut self, span: Span, message: impl Into<String>) {
        self.list.push(Diagnostic {
            span,
            message: message.into(),
        });
    }

    /// Record every error carried by a `syn::Error`.
    pub fn push_syn(&mut self, error: syn::Error) {
        for e in error {
            self.error(e.span(), e.to_string());
        }
    }

    /// Whether nothing was recorded.
    pub fn is_empty(&self) -> bool {
        self.list.is_empty()
    }

    /// The errors, in the order found.
    pub fn iter(&self) -> impl Iterator<Item = &Diagnostic> {
        self.list.iter()
    }

    /// Number of errors.
    pub fn len(&self) -> usize {
        self.list.len()
    }

    /// All errors as one `syn::Error` (for `compile_error!`).
    pub fn to_syn_error(&self) -> syn::Error {
        let mut iter = self.list.iter();
        let first = iter.next().map(|d| syn::Error::new(d.span, &d.message));
        let mut err = first.unwrap_or_else(|| syn::Error::new(Span::call_site(), "invalid model"));
        for d in iter {
            err.combine(syn::Error::new(d.span, &d.message));
        }
        err
    }

    /// Human-readable report for a model read from `file`: each error as
    /// `error: message`, then `--> file:line:col`, the source line and a caret.
    /// Needs spans with locations (proc-macro2's fallback with `span-locations`).
    pub fn render(&self, file: &str, source: &str) -> String {
        let lines: Vec<&str> = source.lines().collect();
        let mut out = String::new();
        for d in &self.list {
            let start = d.span.start();
            let (line, col) = (start.line, start.column + 1);
            out.push_str(&format!(
                "error: {}\n  --> {}:{}:{}\n",
                d.message, file, line, col
            ));
            if let Some(text) = line.checked_sub(1).and_then(|i| lines.get(i)) {
                let width = line.to_string().len();
                let end = d.span.end();
                let len = if end.line == start.line && end.column > start.column {
                    end.column - start.column
                } else {
                    1
                };
                let pad: String = text
                    .chars()
                    .take(start.column)
                    .map(|c| if c == '\t' { '\t' } else { ' ' })
                    .collect();
                out.push_str(&format!(
                    "{:w$} |\n{} | {}\n{:w$} | {}{}\n",
                    "",
                    line,
                    text,
                    "",
                    pad,
                    "^".repeat(len),
                    w = width
                ));
            }
        }
        out.push_str(&format!(
            "{} error{} in {}\n",
            self.list.len(),
            if self.list.len() == 1 { "" } else { "s" },
            file
        ));
        out
    }

    /// Like [`render`](Self::render), but one line per error: `file:line:col: message`.
    pub fn locations(&self, file: &str) -> Vec<String> {
        self.list
            .iter()
            .map(|d| {
                let s = d.span.start();
                format!("{}:{}:{}: {}", file, s.line, s.column + 1, d.message)
            })
            .collect()
    }
}

/// A number for a message: shortest round-trip, but rounded to 12
/// significant digits first, so that the noise of arithmetic does not show
/// (`3.7700000000000005` prints as `3.77`); non-finite values print as
/// `inf`, `-inf`, `NaN`. Every checker message formats numbers with this.
pub fn num(x: f64) -> String {
    if !x.is_finite() || x == 0.0 {
        return format!("{x}");
    }
    let rounded: f64 = format!("{x:.11e}").parse().unwrap_or(x);
    let a = rounded.abs();
    if (1e-5..1e16).contains(&a) {
        format!("{rounded}")
    } else {
        format!("{rounded:e}")
    }
}

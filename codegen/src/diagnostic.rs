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
    /// Line and column (from 1) when there is no token to carry a span:
    /// errors found in the source text before it is tokenized.
    pub at: Option<(usize, usize)>,
}

impl Diagnostic {
    /// Line (from 1) and column (from 1).
    pub fn line_col(&self) -> (usize, usize) {
        match self.at {
            Some(at) => at,
            None => {
                let s = self.span.start();
                (s.line, s.column + 1)
            }
        }
    }
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
            at: None,
        });
    }

    /// Record an error at `line:col` (both from 1) of the source text.
    pub fn error_at(&mut self, line: usize, col: usize, message: impl Into<String>) {
        self.list.push(Diagnostic {
            span: Span::call_site(),
            message: message.into(),
            at: Some((line, col)),
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
    /// rustc shows its own (`error: message`, then `--> file:line:col`, the
    /// source line and a caret), then `N errors in FILE`. Needs spans with
    /// locations (proc-macro2's fallback with `span-locations`). The
    /// structured form is [`Report`](crate::report::Report).
    pub fn render(&self, file: &str, source: &str) -> String {
        crate::report::Report::from_diagnostics(self, file, source).render()
    }

    /// Like [`render`](Self::render), but one line per error: `file:line:col: message`.
    pub fn locations(&self, file: &str) -> Vec<String> {
        self.list
            .iter()
            .map(|d| {
                let (line, col) = d.line_col();
                format!("{}:{}:{}: {}", file, line, col, d.message)
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

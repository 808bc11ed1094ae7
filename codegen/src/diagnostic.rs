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
                let s = d.span.start();
                format!("{}:{}:{}: {}", file, s.line, s.column + 1, d.message)
            })
            .collect()
    }
}

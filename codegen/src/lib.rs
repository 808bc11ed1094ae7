//! The stickslip model language and its code generator.
//!
//! One pure library shared by the two drivers: stickslip's `build.rs` (model
//! files under `models/`) and the `stickslip::model!` proc-macro (inline models
//! or model files of your own crate). The generator is one pipeline,
//! `pipeline` (the first function below), whose passes each take the
//! previous one's typed output:
//!
//! 1. **parse** ([`parse`]) — tokens → syntax tree (`syn`), collecting every
//!    syntax error;
//! 2. **check** ([`check`], [`names`], [`law`]) — syntax tree → checked
//!    [`model::Model`], every error located at `file:line:col`;
//! 3. **expand** ([`expand`]) — checked model → one checked instance per
//!    generated type (the model, each scene, each `pieces: N` model of a
//!    smooth law, built and checked on the expression graph): its free
//!    parameters, mappings, names and lowered graph ([`lowered`]; [`lower`]
//!    turns each model expression into [`expr`] nodes);
//! 4. **equations** ([`equations`]) — the flows, mapping residuals and
//!    Jacobians, vector fields and force criteria of each instance as graph
//!    nodes; exact derivatives by [`expr::Graph::diff`];
//! 5. a back end ([`Backend`]): **emit** ([`emit`]) — equations → Rust
//!    tokens, pure, then formatted with `prettyplease` (the build-time
//!    route); or, with the `jit` feature, **jit** (`jit`) — one instance's
//!    equations → machine code by Cranelift (a model file loaded at run
//!    time).
//!
//! Errors of passes 1–4 are [`Diagnostics`]; [`report`] renders them. A
//! back end sees only a model every check has passed.
//!
//! Around the generated code, [`emit::registry`] writes the module wrapper both
//! drivers use and `build.rs`'s catalogue of the compiled-in models;
//! [`invocation`] is all of the proc-macro but its token conversion.
// `unsafe` lives in one module, `jit::memory`, which owns the machine
// code and calls it; everything else is safe code.
#![deny(unsafe_code)]
#![warn(missing_docs)]

#[cfg(feature = "generator")]
pub mod check;
#[cfg(feature = "generator")]
pub mod diagnostic;
#[cfg(feature = "generator")]
pub mod emit;
#[cfg(feature = "generator")]
pub mod equations;
#[cfg(feature = "generator")]
pub mod expand;
#[cfg(feature = "generator")]
pub mod expr;
#[cfg(feature = "generator")]
pub mod invocation;
#[cfg(feature = "jit")]
pub mod jit;
#[cfg(feature = "generator")]
pub mod law;
#[cfg(feature = "generator")]
pub mod lower;
#[cfg(feature = "generator")]
pub mod lowered;
#[cfg(feature = "generator")]
pub mod model;
#[cfg(feature = "generator")]
pub mod model_files;
#[cfg(feature = "generator")]
pub mod names;
#[cfg(feature = "generator")]
pub mod parse;
#[cfg(feature = "generator")]
pub mod report;
#[cfg(feature = "generator")]
pub mod source;
pub mod structure;

#[cfg(feature = "generator")]
use std::path::Path;
#[cfg(feature = "generator")]
use std::str::FromStr;

#[cfg(feature = "generator")]
use proc_macro2::TokenStream;

#[cfg(feature = "generator")]
pub use diagnostic::{Diagnostic, Diagnostics};
#[cfg(feature = "generator")]
pub use emit::Options;
#[cfg(feature = "generator")]
pub use report::{check_file, check_source, Located, Position, Report, Severity};

/// The generator, pass by pass: `parse → check → expand → equations`,
/// shared, then one back end (Rust source at build time, machine code at
/// run time). `file` is the stem of a model file, whose model must be named
/// like it.
#[cfg(feature = "generator")]
pub(crate) fn pipeline<B: Backend>(
    tokens: TokenStream,
    file: Option<&str>,
    backend: B,
) -> Result<B::Output, Diagnostics> {
    let ast = parse(tokens, file)?;
    let model = check(ast)?;
    let expanded = backend.select(&model, expand::expand(&model)?)?;
    let generation = equations::build(expanded)?;
    backend.emit(&model, generation)
}

/// The last pass of the generator's one pipeline: what is made of a
/// checked model's equations. A back end never sees a model a check rejected.
#[cfg(feature = "generator")]
pub trait Backend {
    /// What it makes.
    type Output;
    /// The instances it needs of those every check has passed (all, by
    /// default): only these get their equations.
    fn select(
        &self,
        model: &Model,
        expanded: expand::Expanded,
    ) -> Result<expand::Expanded, Diagnostics> {
        let _ = model;
        Ok(expanded)
    }
    /// Make it from the checked `model` and its equations.
    fn emit(
        self,
        model: &Model,
        generation: equations::Generation,
    ) -> Result<Self::Output, Diagnostics>;
}

/// The build-time back end: formatted Rust source ([`emit`]).
#[cfg(feature = "generator")]
pub(crate) struct RustSource<'a>(pub &'a Options);

#[cfg(feature = "generator")]
impl Backend for RustSource<'_> {
    type Output = GeneratedFile;
    fn emit(
        self,
        model: &Model,
        generation: equations::Generation,
    ) -> Result<GeneratedFile, Diagnostics> {
        let tokens = emit::emit(&generation);
        let code = emit::header(&generation.header, self.0) + &format(tokens)?;
        Ok(GeneratedFile {
            instances: instance_names(model),
            doc: model.docs.join("\n"),
            module: names::ident_text(&model.name).unwrap_or_else(|| model.name.clone()),
            name: names::bare(&model.name).to_string(),
            code,
        })
    }
}

/// Pass 1: the syntax tree; with `file`, the model must be named like it
/// (`models/NAME.ssm` holds `model NAME`), else an error at the name. That
/// error does not stop the checker: it is carried to pass 2 with the tree,
/// so that a misnamed file still gets every other error reported.
#[cfg(feature = "generator")]
fn parse(
    tokens: TokenStream,
    file: Option<&str>,
) -> Result<(parse::ModelAst, Diagnostics), Diagnostics> {
    let mut diags = Diagnostics::new();
    let ast = parse::parse_model(tokens, &mut diags);
    let mut misnamed = Diagnostics::new();
    if let (Some(ast), Some(stem)) = (&ast, file) {
        let name = names::bare(&ast.name.to_string()).to_string();
        if name != stem {
            misnamed.error(
                ast.name.span(),
                format!(
                    "the model is named `{name}`, but its file is `{stem}.ssm`: \
                     name the file `{name}.ssm` (or the model `{stem}`)"
                ),
            );
        }
    }
    match ast {
        Some(ast) if diags.is_empty() => Ok((ast, misnamed)),
        _ => Err(diags),
    }
}

/// Pass 2: the checked model; `diags` holds what pass 1 found that does not
/// stop the checker.
#[cfg(feature = "generator")]
fn check((ast, mut diags): (parse::ModelAst, Diagnostics)) -> Result<Model, Diagnostics> {
    names::check(&ast, &mut diags);
    match check::check(ast, &mut diags) {
        Some(m) if diags.is_empty() => Ok(m),
        _ => Err(diags),
    }
}

/// The emitted tokens, formatted. They always parse; should they not, the
/// error says so rather than panic.
#[cfg(feature = "generator")]
fn format(tokens: TokenStream) -> Result<String, Diagnostics> {
    match syn::parse2::<syn::File>(tokens) {
        Ok(mut file) => {
            emit::mark_unused(&mut file);
            Ok(prettyplease::unparse(&file))
        }
        Err(e) => {
            let mut d = Diagnostics::new();
            d.error(
                proc_macro2::Span::call_site(),
                format!("internal: generated code does not parse: {e}"),
            );
            Err(d)
        }
    }
}

#[cfg(feature = "generator")]
pub use model::Model;

/// Parse and check a model from tokens.
#[cfg(feature = "generator")]
pub fn model_from_tokens(tokens: TokenStream) -> Result<Model, Diagnostics> {
    model_named(tokens, None)
}

/// [`model_from_tokens`]; with `file`, the model must be named like it.
#[cfg(feature = "generator")]
fn model_named(tokens: TokenStream, file: Option<&str>) -> Result<Model, Diagnostics> {
    check(parse(tokens, file)?)
}

/// Generate the Rust module body for the model in `tokens`.
#[cfg(feature = "generator")]
pub fn generate(tokens: TokenStream, options: &Options) -> Result<GeneratedFile, Diagnostics> {
    generate_named(tokens, options, None)
}

#[cfg(feature = "generator")]
pub(crate) fn generate_named(
    tokens: TokenStream,
    options: &Options,
    file: Option<&str>,
) -> Result<GeneratedFile, Diagnostics> {
    pipeline(tokens, file, RustSource(options))
}

/// Tokenize model source text. Outside a proc-macro (build scripts, tests)
/// spans carry line and column; inside one, call
/// `proc_macro2::fallback::force()` first to get them.
#[cfg(feature = "generator")]
///
/// Delimiters that do not balance are located by [`source::unbalanced`]
/// (the tokenizer's own error does not say where).
pub fn tokenize(source: &str) -> Result<TokenStream, Diagnostics> {
    TokenStream::from_str(source).map_err(|e| {
        let mut d = Diagnostics::new();
        if !source::unbalanced(source, &mut d) {
            let message = names::tokenize_hint(source, e.span())
                .unwrap_or_else(|| format!("cannot tokenize the model: {e}"));
            d.error(e.span(), message);
        }
        d
    })
}

/// A generated model read from a file.
#[cfg(feature = "generator")]
#[derive(Clone, Debug)]
pub struct GeneratedFile {
    /// The model's name (`model NAME { .. }`), without `r#`.
    pub name: String,
    /// The model's module name in Rust (`paper`; `r#fn` for a model `r#fn`).
    pub module: String,
    /// The formatted module body.
    pub code: String,
    /// The model's doc comment.
    pub doc: String,
    /// The model and its scenes, each with its module path and type name.
    pub instances: Vec<InstanceName>,
}

/// Where a generated model or scene lives in the generated module.
#[cfg(feature = "generator")]
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct InstanceName {
    /// `paper` or `paper::sweep_w`.
    pub name: String,
    /// Rust path relative to the models module (`name` with keywords raw).
    pub path: String,
    /// The type implementing `Model` (`Paper`, `SweepW`), or `SmoothModel`
    /// for a model with a smooth law (`smooth`).
    pub type_name: String,
    /// Whether the type implements `SmoothModel` rather than `Model`.
    pub smooth: bool,
}

#[cfg(feature = "generator")]
fn instance_names(model: &Model) -> Vec<InstanceName> {
    // Display names are bare (`fn`); paths are Rust (`r#fn`).
    let rust = |n: &str| names::ident_text(n).unwrap_or_else(|| n.to_string());
    let mut out = vec![InstanceName {
        name: names::bare(&model.name).to_string(),
        path: rust(&model.name),
        type_name: names::type_name(&model.name, "Model"),
        smooth: model.law.is_some(),
    }];
    for s in &model.scenes {
        out.push(InstanceName {
            name: format!("{}::{}", names::bare(&model.name), names::bare(&s.name)),
            path: format!("{}::{}", rust(&model.name), rust(&s.name)),
            type_name: names::type_name(&s.name, "Scene"),
            smooth: false,
        });
    }
    out
}

/// Read, check and generate a model file. On failure the error is the
/// rendered report: `file:line:col`, the source line and a caret per error
/// ([`check_file`], rendered).
#[cfg(feature = "generator")]
pub fn generate_file(path: &Path, origin: &str) -> Result<GeneratedFile, String> {
    check_file(path, origin).map_err(|r| r.render())
}

/// Like [`generate_file`], from source text; `origin` names the file in messages.
#[cfg(feature = "generator")]
pub fn generate_source(source: &str, origin: &str) -> Result<GeneratedFile, String> {
    check_source(source, origin).map_err(|r| r.render())
}

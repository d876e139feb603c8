//! Symbolic engine of the wrinkle energy DSL (`energy_model!`).
//!
//! The pipeline turns a model declaration into Rust code implementing
//! `wrinkle_runtime::EnergyModel`:
//!
//! 1. **parse** ([`syntax`]): a typed AST with spans, by precedence climbing;
//! 2. **validate and lower** ([`semantic`]): name resolution, every error collected with the
//!    offending token's span, lowering into a hash-consed DAG ([`graph`]) with local
//!    constant folding and $`0`/$`1` identities;
//! 3. **differentiate** ([`kernel`]): residual $`r_i = \partial\psi_t/\partial j_i`$ and
//!    tangent $`k_{ij} = \partial r_i/\partial j_j`$, $`i \le j`$, by memoised recursion;
//! 4. **simplify** ([`simplify`]): all outputs of a term together in one `egg` e-graph bounded
//!    by size (never by time), extraction by weighted operation count, re-hash-consing for
//!    sharing;
//! 5. **generate** ([`codegen`]): straight-line kernels generic over the runtime `Scalar`
//!    (written by the private `kernel_writer`), and ([`taylor`]) Taylor-mode kernels that
//!    extend the residual's Taylor coefficients one order at a time from a per-point tape (the
//!    ANM's right-hand sides).
//!
//! Imports run one way: [`syntax`] and [`graph`] import no other module; [`semantic`] imports
//! both, [`simplify`] the graph, [`kernel`] these four, `kernel_writer` the graph and kernel,
//! [`taylor`] the graph and kernel_writer, [`codegen`] syntax, kernel, kernel_writer and
//! taylor. Field roles,
//! derivatives and jet entries come from the `wrinkle-contract` crate the runtime shares. On errors [`expand`] returns them with a stand-in for the model
//! ([`codegen::generate_stub`]). The output is a function of the input tokens alone
//! (`docs/dsl.md`, "Determinism").
//!
//! The crate is a plain library; the `wrinkle-macros` proc-macro crate only calls
//! [`expand`].

pub mod ansatz;
pub mod codegen;
pub mod graph;
pub mod kernel;
mod kernel_writer;
pub mod semantic;
pub mod simplify;
pub mod syntax;
pub mod taylor;

use proc_macro2::{Span, TokenStream};

pub use graph::{EvaluationError, ExpressionGraph, Function, Node, NodeId};
pub use kernel::{CompiledModel, ReferenceKernel, TermKernel, compile};
pub use semantic::{Derivative, FieldRole, JetEntry, LoweredModel, combine, lower_model};
pub use simplify::{SimplificationLimits, SimplificationStatistics, SimplifyError, StopKind};
pub use syntax::{ModelDeclaration, ModelOutline, ParsedModel, Quadrature, parse_model};

/// Parses and validates a model declaration, returning every error found.
pub fn parse_and_lower(input: TokenStream) -> Result<LoweredModel, syn::Error> {
    match parse_model(input) {
        ParsedModel::Complete(declaration) => derive_and_lower(&declaration),
        ParsedModel::Partial { errors, .. } | ParsedModel::Unnamed { errors } => {
            Err(combine(errors).expect("a parse that stopped has an error"))
        }
    }
}

/// Derives the terms of a declaration's ansatz, if it has one ([`ansatz::derive`]), and lowers
/// the result; a derived model carries its derivation report.
pub fn derive_and_lower(declaration: &ModelDeclaration) -> Result<LoweredModel, syn::Error> {
    match ansatz::derive(declaration)? {
        None => lower_model(declaration),
        Some(derived) => {
            let mut lowered = lower_model(&derived.declaration)?;
            lowered.derivation = Some(derived.report);
            Ok(lowered)
        }
    }
}

/// Runs the whole pipeline up to (not including) code generation.
pub fn analyze(
    input: TokenStream,
    limits: &SimplificationLimits,
) -> Result<CompiledModel, syn::Error> {
    let lowered = parse_and_lower(input)?;
    compile(lowered, limits).map_err(internal_error)
}

/// A simplifier error (an internal invariant broken, never the user's input) at the call site.
fn internal_error(error: SimplifyError) -> syn::Error {
    syn::Error::new(Span::call_site(), error.to_string())
}

/// Expands an `energy_model!` invocation with the default [`SimplificationLimits`]: the
/// generated code, or the errors and a stand-in for the model (see [`expand_with_limits`]).
pub fn expand(input: TokenStream) -> TokenStream {
    expand_with_limits(input, &SimplificationLimits::default())
}

/// [`expand`] with explicit simplification limits.
///
/// On errors: one `compile_error!` per error, at the offending token, and — when the model's
/// name parsed — a stand-in for the model ([`codegen::generate_stub`]: the same struct, `new`
/// and an `EnergyModel` implementation whose kernels are never reached), so that code using
/// the model reports nothing more and the user sees the declaration's own errors only.
pub fn expand_with_limits(input: TokenStream, limits: &SimplificationLimits) -> TokenStream {
    let (outline, errors) = match parse_model(input) {
        ParsedModel::Complete(declaration) => {
            let compiled = derive_and_lower(&declaration)
                .and_then(|lowered| compile(lowered, limits).map_err(internal_error));
            match compiled {
                Ok(compiled) => return codegen::generate(&compiled),
                Err(errors) => (Some(declaration.outline()), errors),
            }
        }
        ParsedModel::Partial { outline, errors } => (
            Some(outline),
            combine(errors).expect("a parse that stopped has an error"),
        ),
        ParsedModel::Unnamed { errors } => (
            None,
            combine(errors).expect("a parse that stopped has an error"),
        ),
    };
    let mut tokens = errors.to_compile_error();
    if let Some(outline) = outline {
        tokens.extend(codegen::generate_stub(&outline));
    }
    tokens
}

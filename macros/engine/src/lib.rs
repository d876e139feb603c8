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
//! 4. **simplify** ([`simplify`]): all outputs of a term together in one bounded `egg`
//!    e-graph, extraction by weighted operation count, re-hash-consing for sharing;
//! 5. **generate** ([`codegen`]): straight-line kernels generic over the runtime `Scalar`, and
//!    ([`taylor`]) Taylor-mode kernels that extend the residual's Taylor coefficients one order
//!    at a time from a per-point tape (the ANM's right-hand sides).
//!
//! The crate is a plain library; the `wrinkle-macros` proc-macro crate only calls
//! [`expand`].

pub mod codegen;
pub mod graph;
pub mod kernel;
mod kernel_writer;
pub mod semantic;
pub mod simplify;
pub mod syntax;
pub mod taylor;

use proc_macro2::TokenStream;

pub use graph::{EvaluationError, ExpressionGraph, Function, Node, NodeId};
pub use kernel::{CompiledModel, ReferenceKernel, TermKernel, compile};
pub use semantic::{Derivative, FieldRole, JetEntry, LoweredModel, lower_model};
pub use simplify::{SimplificationLimits, SimplificationStatistics, SimplifyError, StopKind};
pub use syntax::{ModelDeclaration, Quadrature};

/// Parses and validates a model declaration, returning every error found.
pub fn parse_and_lower(input: TokenStream) -> Result<LoweredModel, syn::Error> {
    let declaration: ModelDeclaration = syn::parse2(input)?;
    lower_model(&declaration)
}

/// Runs the whole pipeline up to (not including) code generation.
pub fn analyze(
    input: TokenStream,
    limits: &SimplificationLimits,
) -> Result<CompiledModel, syn::Error> {
    let lowered = parse_and_lower(input)?;
    compile(lowered, limits)
        .map_err(|error| syn::Error::new(proc_macro2::Span::call_site(), error.to_string()))
}

/// Expands an `energy_model!` invocation with the default [`SimplificationLimits`]: the
/// generated code, or `compile_error!` invocations pointing at the offending tokens.
pub fn expand(input: TokenStream) -> TokenStream {
    expand_with_limits(input, &SimplificationLimits::default())
}

/// [`expand`] with explicit simplification limits.
pub fn expand_with_limits(input: TokenStream, limits: &SimplificationLimits) -> TokenStream {
    match analyze(input, limits) {
        Ok(compiled) => codegen::generate(&compiled),
        Err(error) => error.to_compile_error(),
    }
}

//! From a lowered model to simplified per-term kernels: differentiation (residual and
//! tangent), one bounded e-graph run per term, structural-zero detection.

use std::collections::HashMap;
use std::fmt::Write;

use crate::graph::{ExpressionGraph, NodeId};
use crate::semantic::{LoweredModel, LoweredTerm};
use crate::simplify::{
    SimplificationLimits, SimplificationStatistics, SimplifyError, StopKind, simplify,
};
use crate::syntax::Quadrature;

/// The derivatives of one term before simplification (kept for verification).
#[derive(Clone, Debug)]
pub struct ReferenceKernel {
    /// Graph holding the unsimplified expressions (model jet indices).
    pub graph: ExpressionGraph,
    /// $`\psi_t`$.
    pub energy: NodeId,
    /// $`\partial\psi_t/\partial j_i`$ for every term-local `i`.
    pub residual: Vec<NodeId>,
    /// $`\partial^2\psi_t/\partial j_i\partial j_j`$ for every term-local `i <= j`, row by row.
    pub tangent: Vec<((usize, usize), NodeId)>,
}

/// The simplified kernels of one term.
#[derive(Clone, Debug)]
pub struct TermKernel {
    /// Term name.
    pub name: String,
    /// Quadrature rule.
    pub quadrature: Quadrature,
    /// Model jet indices this term reads, ascending (term-local index = position).
    pub jet: Vec<usize>,
    /// Simplified, hash-consed expressions of all outputs (model jet indices).
    pub graph: ExpressionGraph,
    /// The energy root.
    pub energy: NodeId,
    /// One residual root per term-local jet entry (the constant 0 when structurally zero).
    pub residual: Vec<NodeId>,
    /// Structurally non-zero upper-triangle tangent entries (term-local), row by row.
    pub tangent_pattern: Vec<(usize, usize)>,
    /// One tangent root per pattern entry.
    pub tangent: Vec<NodeId>,
    /// The unsimplified derivatives.
    pub reference: ReferenceKernel,
    /// E-graph statistics.
    pub statistics: SimplificationStatistics,
}

impl TermKernel {
    /// Whether residual entry `i` is structurally zero.
    pub fn residual_is_zero(&self, index: usize) -> bool {
        self.graph.constant_value(self.residual[index]) == Some(0.0)
    }
}

/// A fully compiled model: metadata plus one kernel per term.
#[derive(Clone, Debug)]
pub struct CompiledModel {
    /// The validated model (names, parameters, jet, unsimplified energies).
    pub model: LoweredModel,
    /// Per-term kernels, in declaration order.
    pub terms: Vec<TermKernel>,
    /// Human-readable simplification report (one line per term).
    pub report: String,
}

/// Differentiates and simplifies every term of `model`.
pub fn compile(
    model: LoweredModel,
    limits: &SimplificationLimits,
) -> Result<CompiledModel, SimplifyError> {
    let mut terms = Vec::with_capacity(model.terms.len());
    let mut report = String::new();
    for term in &model.terms {
        let kernel = compile_term(&model.graph, term, limits)?;
        report_term(&mut report, &kernel);
        terms.push(kernel);
    }
    Ok(CompiledModel {
        model,
        terms,
        report,
    })
}

/// Differentiates one term, simplifies all its outputs in one e-graph run and keeps the
/// structurally non-zero tangent entries.
fn compile_term(
    source: &ExpressionGraph,
    term: &LoweredTerm,
    limits: &SimplificationLimits,
) -> Result<TermKernel, SimplifyError> {
    let reference = differentiate_term(source, term.energy, &term.jet);
    let (mut graph, statistics, mut mapped) = simplify_outputs(&reference, limits)?;
    let zero = graph.constant(0.0);
    let mut root_of = |root: NodeId| *mapped.entry(root).or_insert(zero);
    let energy = root_of(reference.energy);
    let residual: Vec<NodeId> = reference.residual.iter().map(|&r| root_of(r)).collect();
    let mut tangent_pattern = Vec::new();
    let mut tangent = Vec::new();
    for &(entry, root) in &reference.tangent {
        let simplified = root_of(root);
        if graph.constant_value(simplified) != Some(0.0) {
            tangent_pattern.push(entry);
            tangent.push(simplified);
        }
    }
    Ok(TermKernel {
        name: term.name.clone(),
        quadrature: term.quadrature,
        jet: term.jet.clone(),
        graph,
        energy,
        residual,
        tangent_pattern,
        tangent,
        reference,
        statistics,
    })
}

/// Simplifies every output of `reference` that is not already the constant zero (those stay
/// out of the e-graph): the simplified graph, the run's statistics and the map from each
/// simplified output's root in `reference.graph` to its root in the new graph.
fn simplify_outputs(
    reference: &ReferenceKernel,
    limits: &SimplificationLimits,
) -> Result<
    (
        ExpressionGraph,
        SimplificationStatistics,
        HashMap<NodeId, NodeId>,
    ),
    SimplifyError,
> {
    let mut outputs = vec![reference.energy];
    outputs.extend(&reference.residual);
    outputs.extend(reference.tangent.iter().map(|(_, root)| *root));
    let live: Vec<NodeId> = outputs
        .iter()
        .copied()
        .filter(|&root| reference.graph.constant_value(root) != Some(0.0))
        .collect();
    if live.is_empty() {
        let statistics = SimplificationStatistics {
            nodes: 0,
            classes: 0,
            iterations: 0,
            stop: StopKind::NothingToDo,
            operations_before: 0,
            operations_after: 0,
            kept_input: false,
            operations_extracted: 0,
        };
        return Ok((ExpressionGraph::new(), statistics, HashMap::new()));
    }
    let result = simplify(&reference.graph, &live, limits)?;
    let map = live
        .iter()
        .copied()
        .zip(result.roots.iter().copied())
        .collect();
    Ok((result.graph, result.statistics, map))
}

/// Appends the term's line of the simplification report: sizes, structural zeros, why the
/// e-graph run stopped, operation counts.
fn report_term(report: &mut String, kernel: &TermKernel) {
    let statistics = &kernel.statistics;
    let zero_residuals = (0..kernel.residual.len())
        .filter(|&i| kernel.residual_is_zero(i))
        .count();
    let _ = writeln!(
        report,
        "term `{}`: {} jet entries, {} residual entries ({} structurally zero), {} of {} upper tangent entries non-zero; e-graph {} nodes in {} classes after {} iterations, stopped: {}; {} scalar operations before, {} after simplification{}",
        kernel.name,
        kernel.jet.len(),
        kernel.residual.len(),
        zero_residuals,
        kernel.tangent.len(),
        kernel.reference.tangent.len(),
        statistics.nodes,
        statistics.classes,
        statistics.iterations,
        statistics.stop,
        statistics.operations_before,
        statistics.operations_after,
        if statistics.kept_input {
            format!(
                " (the extracted form had {} operations: input kept)",
                statistics.operations_extracted
            )
        } else {
            String::new()
        },
    );
}

/// Residual and upper-triangle tangent of one term by memoised recursive differentiation.
fn differentiate_term(source: &ExpressionGraph, energy: NodeId, jet: &[usize]) -> ReferenceKernel {
    let mut graph = ExpressionGraph::new();
    let energy = graph.import(source, energy, &mut HashMap::new(), &|k| k);
    let residual: Vec<NodeId> = jet
        .iter()
        .map(|&entry| graph.differentiate(energy, entry, &mut HashMap::new()))
        .collect();
    // One memo per variable, shared by all residual entries differentiated w.r.t. it.
    let mut memos: Vec<HashMap<NodeId, NodeId>> = vec![HashMap::new(); jet.len()];
    let mut tangent = Vec::new();
    for (i, &row) in residual.iter().enumerate() {
        for j in i..jet.len() {
            let entry = graph.differentiate(row, jet[j], &mut memos[j]);
            tangent.push(((i, j), entry));
        }
    }
    ReferenceKernel {
        graph,
        energy,
        residual,
        tangent,
    }
}

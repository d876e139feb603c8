//! Straight-line Rust for the expressions of one term's graph, generic over
//! `S: ::wrinkle_runtime::Scalar`: the operations as emitted and the [`KernelWriter`] that
//! [`codegen`](crate::codegen) (energy, residual, tangent) and [`taylor`](crate::taylor)
//! (Taylor-mode kernels) both write with.
//!
//! Conventions (see `runtime/src/scalar.rs`): parameter-only sub-expressions are `f64`
//! locals; in a mixed operation the `f64` is always on the right (`x * c`, `x + c`,
//! `x - c`, `x / c`), `c - x` is emitted as `-x + c` and `c / x` as `x.recip() * c`.

use std::collections::HashSet;

use proc_macro2::{Ident, Literal, TokenStream};
use quote::{format_ident, quote};

use crate::graph::{ExpressionGraph, Node, NodeId};
use crate::kernel::TermKernel;

/// An operation as emitted, after peephole recognition of subtraction, negation, division
/// and reciprocal in the `+`/`*`/`pow` DAG.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Operation {
    Leaf,
    Add(NodeId, NodeId),
    Subtract(NodeId, NodeId),
    Multiply(NodeId, NodeId),
    Divide(NodeId, NodeId),
    Negate(NodeId),
    Power(NodeId, i32),
    Reciprocal(NodeId),
    Apply(crate::graph::Function, NodeId),
}

impl Operation {
    pub(crate) fn children(self) -> Vec<NodeId> {
        match self {
            Operation::Leaf => Vec::new(),
            Operation::Add(a, b)
            | Operation::Subtract(a, b)
            | Operation::Multiply(a, b)
            | Operation::Divide(a, b) => vec![a, b],
            Operation::Negate(a)
            | Operation::Power(a, _)
            | Operation::Reciprocal(a)
            | Operation::Apply(_, a) => vec![a],
        }
    }
}

/// `x` when `id` is $`(-1)\,x`$.
fn negated_operand(graph: &ExpressionGraph, id: NodeId) -> Option<NodeId> {
    if let Node::Multiply(a, b) = graph.node(id) {
        if graph.constant_value(a) == Some(-1.0) {
            return Some(b);
        }
        if graph.constant_value(b) == Some(-1.0) {
            return Some(a);
        }
    }
    None
}

/// `x` when `id` is $`x^{-1}`$.
fn reciprocal_operand(graph: &ExpressionGraph, id: NodeId) -> Option<NodeId> {
    match graph.node(id) {
        Node::Power(base, -1) => Some(base),
        _ => None,
    }
}

pub(crate) fn operation_of(graph: &ExpressionGraph, id: NodeId) -> Operation {
    match graph.node(id) {
        Node::Constant(_) | Node::Parameter(_) | Node::Jet(_) => Operation::Leaf,
        Node::Add(a, b) => {
            if let Some(x) = negated_operand(graph, b) {
                Operation::Subtract(a, x)
            } else if let Some(x) = negated_operand(graph, a) {
                Operation::Subtract(b, x)
            } else {
                Operation::Add(a, b)
            }
        }
        Node::Multiply(a, b) => {
            if graph.constant_value(a) == Some(-1.0) {
                Operation::Negate(b)
            } else if graph.constant_value(b) == Some(-1.0) {
                Operation::Negate(a)
            } else if let Some(x) = reciprocal_operand(graph, b) {
                Operation::Divide(a, x)
            } else if let Some(x) = reciprocal_operand(graph, a) {
                Operation::Divide(b, x)
            } else {
                Operation::Multiply(a, b)
            }
        }
        Node::Power(a, -1) => Operation::Reciprocal(a),
        Node::Power(a, n) => Operation::Power(a, n),
        Node::Apply(function, a) => Operation::Apply(function, a),
    }
}

/// Emits straight-line code for a set of outputs of one term.
pub(crate) struct KernelWriter<'a> {
    pub(crate) graph: &'a ExpressionGraph,
    pub(crate) term: &'a TermKernel,
    pub(crate) parameters: &'a [Ident],
}

impl KernelWriter<'_> {
    pub(crate) fn is_scalar(&self, id: NodeId) -> bool {
        self.graph.depends_on_jet(id)
    }

    /// An atomic expression naming the value of `id`.
    pub(crate) fn reference(&self, id: NodeId) -> TokenStream {
        match self.graph.node(id) {
            Node::Constant(value) => real_literal(value),
            Node::Parameter(k) => {
                let name = &self.parameters[k];
                quote!(self.#name)
            }
            Node::Jet(k) => {
                let local = self
                    .term
                    .jet
                    .iter()
                    .position(|&entry| entry == k)
                    .expect("a term only reads its own jet entries");
                quote!(jet[#local])
            }
            _ => {
                let name = local_name(id);
                quote!(#name)
            }
        }
    }

    /// `let` statements for every operation reachable from `roots`, children first.
    pub(crate) fn statements(&self, roots: &[NodeId]) -> TokenStream {
        let mut visited = HashSet::new();
        let mut order = Vec::new();
        for &root in roots {
            let mut stack = vec![(root, false)];
            while let Some((id, expanded)) = stack.pop() {
                if expanded {
                    order.push(id);
                    continue;
                }
                if !visited.insert(id) {
                    continue;
                }
                stack.push((id, true));
                for child in operation_of(self.graph, id).children().into_iter().rev() {
                    stack.push((child, false));
                }
            }
        }
        let mut tokens = TokenStream::new();
        for id in order {
            let operation = operation_of(self.graph, id);
            if matches!(operation, Operation::Leaf) {
                continue;
            }
            let name = local_name(id);
            let value = self.operation_tokens(operation);
            if self.is_scalar(id) {
                tokens.extend(quote!(let #name: S = #value;));
            } else {
                tokens.extend(quote!(let #name: f64 = #value;));
            }
        }
        tokens
    }

    fn operation_tokens(&self, operation: Operation) -> TokenStream {
        let scalar = |id| self.is_scalar(id);
        let r = |id| self.reference(id);
        match operation {
            Operation::Leaf => unreachable!("leaves are referenced inline"),
            Operation::Add(a, b) => {
                let (a, b) = if !scalar(a) && scalar(b) {
                    (b, a)
                } else {
                    (a, b)
                };
                let (a, b) = (r(a), r(b));
                quote!(#a + #b)
            }
            Operation::Multiply(a, b) => {
                let (a, b) = if !scalar(a) && scalar(b) {
                    (b, a)
                } else {
                    (a, b)
                };
                if a == b && scalar(a) {
                    let a = r(a);
                    return quote!(#a * #a);
                }
                let (a, b) = (r(a), r(b));
                quote!(#a * #b)
            }
            Operation::Subtract(a, b) => {
                let (sa, sb) = (scalar(a), scalar(b));
                let (a, b) = (r(a), r(b));
                if !sa && sb {
                    quote!(-#b + #a)
                } else {
                    quote!(#a - #b)
                }
            }
            Operation::Divide(a, b) => {
                let (sa, sb) = (scalar(a), scalar(b));
                let (a, b) = (r(a), r(b));
                if !sa && sb {
                    quote!(#b.recip() * #a)
                } else {
                    quote!(#a / #b)
                }
            }
            Operation::Negate(a) => {
                let a = r(a);
                quote!(-#a)
            }
            Operation::Reciprocal(a) => {
                let a = r(a);
                quote!(#a.recip())
            }
            Operation::Power(a, 2) => {
                let a = r(a);
                quote!(#a * #a)
            }
            Operation::Power(a, n) => {
                let a = r(a);
                let n = Literal::i32_unsuffixed(n);
                quote!(#a.powi(#n))
            }
            Operation::Apply(function, a) => {
                let a = r(a);
                let name = format_ident!("{}", function.name());
                match function {
                    // An instruction: nothing to remember.
                    crate::graph::Function::Sqrt => quote!(#a.#name()),
                    // The same argument at every point: remembered per thread.
                    _ => quote!(::wrinkle_runtime::memo::#name(#a)),
                }
            }
        }
    }

    /// `value` as an `S`: scalars as they are, `f64` via `S::from_f64`.
    fn as_scalar(&self, id: NodeId) -> TokenStream {
        let reference = self.reference(id);
        if self.is_scalar(id) {
            reference
        } else if self.graph.constant_value(id) == Some(0.0) {
            quote!(S::zero())
        } else {
            quote!(S::from_f64(#reference))
        }
    }

    pub(crate) fn energy(&self) -> TokenStream {
        let statements = self.statements(&[self.term.energy]);
        let value = self.as_scalar(self.term.energy);
        quote!({ #statements #value })
    }

    pub(crate) fn outputs(&self, roots: &[NodeId]) -> TokenStream {
        let statements = self.statements(roots);
        let assignments = roots.iter().enumerate().map(|(index, &root)| {
            let value = self.as_scalar(root);
            quote!(out[#index] = #value;)
        });
        quote!({ #statements #(#assignments)* })
    }
}

fn local_name(id: NodeId) -> Ident {
    format_ident!("t{}", id.0)
}

/// An `f64` literal token (negative values parenthesised so they stay atomic).
fn real_literal(value: f64) -> TokenStream {
    if value.is_nan() {
        return quote!(f64::NAN);
    }
    if value.is_infinite() {
        return if value > 0.0 {
            quote!(f64::INFINITY)
        } else {
            quote!((-f64::INFINITY))
        };
    }
    let literal = Literal::f64_suffixed(value.abs());
    if value < 0.0 {
        quote!((-#literal))
    } else {
        quote!(#literal)
    }
}

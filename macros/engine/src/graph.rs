//! Hash-consed expression DAG: construction with local simplification, symbolic
//! differentiation and an `f64` interpreter.

use std::collections::HashMap;

use thiserror::Error;

/// A function allowed on parameter-only expressions (evaluated in `f64`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Function {
    /// $`\sqrt{x}`$.
    Sqrt,
    /// $`\sin x`$.
    Sin,
    /// $`\cos x`$.
    Cos,
    /// $`e^x`$.
    Exp,
    /// $`\ln x`$.
    Ln,
}

impl Function {
    /// Looks a function up by its DSL name.
    pub fn from_name(name: &str) -> Option<Function> {
        Some(match name {
            "sqrt" => Function::Sqrt,
            "sin" => Function::Sin,
            "cos" => Function::Cos,
            "exp" => Function::Exp,
            "ln" => Function::Ln,
            _ => return None,
        })
    }
    /// The DSL name (also the `f64` method name, except `ln`).
    pub fn name(self) -> &'static str {
        match self {
            Function::Sqrt => "sqrt",
            Function::Sin => "sin",
            Function::Cos => "cos",
            Function::Exp => "exp",
            Function::Ln => "ln",
        }
    }
    /// Applies the function to an `f64`.
    pub fn apply(self, x: f64) -> f64 {
        match self {
            Function::Sqrt => x.sqrt(),
            Function::Sin => x.sin(),
            Function::Cos => x.cos(),
            Function::Exp => x.exp(),
            Function::Ln => x.ln(),
        }
    }
}

/// Index of a node in an [`ExpressionGraph`].
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct NodeId(pub usize);

/// One node of the DAG. Subtraction is $`a + (-1)\,b`$ and division $`a\,b^{-1}`$.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Node {
    /// A real constant.
    Constant(f64),
    /// Parameter number `k` (index into the model's parameters).
    Parameter(usize),
    /// Jet entry number `k` (index into the model jet).
    Jet(usize),
    /// $`a + b`$ (operands sorted).
    Add(NodeId, NodeId),
    /// $`a\,b`$ (operands sorted).
    Multiply(NodeId, NodeId),
    /// $`a^n`$.
    Power(NodeId, i32),
    /// $`f(a)`$, `a` depends on parameters only.
    Apply(Function, NodeId),
}

/// Hashable key of a node (constants by bit pattern, `-0.0` normalised to `0.0`).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
enum NodeKey {
    Constant(u64),
    Parameter(usize),
    Jet(usize),
    Add(NodeId, NodeId),
    Multiply(NodeId, NodeId),
    Power(NodeId, i32),
    Apply(Function, NodeId),
}

fn key_of(node: &Node) -> NodeKey {
    match *node {
        Node::Constant(value) => NodeKey::Constant(if value == 0.0 { 0 } else { value.to_bits() }),
        Node::Parameter(k) => NodeKey::Parameter(k),
        Node::Jet(k) => NodeKey::Jet(k),
        Node::Add(a, b) => NodeKey::Add(a, b),
        Node::Multiply(a, b) => NodeKey::Multiply(a, b),
        Node::Power(a, n) => NodeKey::Power(a, n),
        Node::Apply(f, a) => NodeKey::Apply(f, a),
    }
}

/// Errors of the `f64` interpreter.
#[derive(Debug, Error, PartialEq)]
pub enum EvaluationError {
    /// A parameter index beyond the supplied values.
    #[error("parameter #{index} requested but only {available} parameter values were given")]
    MissingParameter {
        /// Requested index.
        index: usize,
        /// Number of values given.
        available: usize,
    },
    /// A jet index beyond the supplied values.
    #[error("jet entry #{index} requested but only {available} jet values were given")]
    MissingJetEntry {
        /// Requested index.
        index: usize,
        /// Number of values given.
        available: usize,
    },
    /// A node id that does not belong to the graph.
    #[error("node #{0} does not exist in this expression graph")]
    UnknownNode(usize),
}

/// A hash-consed DAG of expressions: structurally equal nodes are stored once.
///
/// Construction applies constant folding and the identities $`x+0=x`$, $`1x=x`$,
/// $`0x=0`$, $`x^1=x`$, $`x^0=1`$, $`(x^m)^n=x^{mn}`$.
#[derive(Clone, Debug, Default)]
pub struct ExpressionGraph {
    nodes: Vec<Node>,
    lookup: HashMap<NodeKey, NodeId>,
    /// Per node: does it depend on a jet entry?
    depends_on_jet: Vec<bool>,
}

impl ExpressionGraph {
    /// An empty graph.
    pub fn new() -> Self {
        Self::default()
    }

    /// Number of distinct nodes.
    pub fn len(&self) -> usize {
        self.nodes.len()
    }

    /// Whether the graph has no nodes.
    pub fn is_empty(&self) -> bool {
        self.nodes.is_empty()
    }

    /// The node behind an id.
    pub fn node(&self, id: NodeId) -> Node {
        self.nodes[id.0]
    }

    /// Whether a node depends on some jet entry (otherwise it is a parameter-only `f64`).
    pub fn depends_on_jet(&self, id: NodeId) -> bool {
        self.depends_on_jet[id.0]
    }

    /// The constant value of a node, if it is a constant.
    pub fn constant_value(&self, id: NodeId) -> Option<f64> {
        match self.nodes[id.0] {
            Node::Constant(value) => Some(value),
            _ => None,
        }
    }

    fn intern(&mut self, node: Node) -> NodeId {
        let key = key_of(&node);
        if let Some(&id) = self.lookup.get(&key) {
            return id;
        }
        let depends = match node {
            Node::Constant(_) | Node::Parameter(_) => false,
            Node::Jet(_) => true,
            Node::Add(a, b) | Node::Multiply(a, b) => {
                self.depends_on_jet[a.0] || self.depends_on_jet[b.0]
            }
            Node::Power(a, _) | Node::Apply(_, a) => self.depends_on_jet[a.0],
        };
        let id = NodeId(self.nodes.len());
        self.nodes.push(node);
        self.depends_on_jet.push(depends);
        self.lookup.insert(key, id);
        id
    }

    /// A constant.
    pub fn constant(&mut self, value: f64) -> NodeId {
        self.intern(Node::Constant(if value == 0.0 { 0.0 } else { value }))
    }

    /// Parameter number `index`.
    pub fn parameter(&mut self, index: usize) -> NodeId {
        self.intern(Node::Parameter(index))
    }

    /// Jet entry number `index`.
    pub fn jet(&mut self, index: usize) -> NodeId {
        self.intern(Node::Jet(index))
    }

    /// $`a + b`$.
    pub fn add(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => self.constant(x + y),
            (Some(0.0), None) => b,
            (None, Some(0.0)) => a,
            _ => self.intern(Node::Add(a.min(b), a.max(b))),
        }
    }

    /// $`a\,b`$.
    pub fn multiply(&mut self, a: NodeId, b: NodeId) -> NodeId {
        match (self.constant_value(a), self.constant_value(b)) {
            (Some(x), Some(y)) => self.constant(x * y),
            (Some(x), _) | (_, Some(x)) if x == 0.0 => self.constant(0.0),
            (Some(1.0), None) => b,
            (None, Some(1.0)) => a,
            _ => self.intern(Node::Multiply(a.min(b), a.max(b))),
        }
    }

    /// $`-a`$, i.e. $`(-1)\,a`$.
    pub fn negate(&mut self, a: NodeId) -> NodeId {
        let minus_one = self.constant(-1.0);
        self.multiply(minus_one, a)
    }

    /// $`a - b`$.
    pub fn subtract(&mut self, a: NodeId, b: NodeId) -> NodeId {
        let negated = self.negate(b);
        self.add(a, negated)
    }

    /// $`a / b`$.
    pub fn divide(&mut self, a: NodeId, b: NodeId) -> NodeId {
        let reciprocal = self.power(b, -1);
        self.multiply(a, reciprocal)
    }

    /// $`a^n`$.
    pub fn power(&mut self, a: NodeId, exponent: i32) -> NodeId {
        if exponent == 0 {
            return self.constant(1.0);
        }
        if exponent == 1 {
            return a;
        }
        if let Some(x) = self.constant_value(a) {
            return self.constant(x.powi(exponent));
        }
        if let Node::Power(base, inner) = self.node(a)
            && let Some(product) = inner.checked_mul(exponent)
        {
            return self.power(base, product);
        }
        self.intern(Node::Power(a, exponent))
    }

    /// $`f(a)`$.
    pub fn apply(&mut self, function: Function, a: NodeId) -> NodeId {
        if let Some(x) = self.constant_value(a) {
            return self.constant(function.apply(x));
        }
        self.intern(Node::Apply(function, a))
    }

    /// Copies the sub-DAG rooted at `id` of `other` into `self`, returning the new root;
    /// jet entry `k` of `other` becomes jet entry `jet_map(k)`.
    pub fn import(
        &mut self,
        other: &ExpressionGraph,
        id: NodeId,
        memo: &mut HashMap<NodeId, NodeId>,
        jet_map: &dyn Fn(usize) -> usize,
    ) -> NodeId {
        if let Some(&done) = memo.get(&id) {
            return done;
        }
        let result = match other.node(id) {
            Node::Constant(value) => self.constant(value),
            Node::Parameter(k) => self.parameter(k),
            Node::Jet(k) => self.jet(jet_map(k)),
            Node::Add(a, b) => {
                let a = self.import(other, a, memo, jet_map);
                let b = self.import(other, b, memo, jet_map);
                self.add(a, b)
            }
            Node::Multiply(a, b) => {
                let a = self.import(other, a, memo, jet_map);
                let b = self.import(other, b, memo, jet_map);
                self.multiply(a, b)
            }
            Node::Power(a, n) => {
                let a = self.import(other, a, memo, jet_map);
                self.power(a, n)
            }
            Node::Apply(f, a) => {
                let a = self.import(other, a, memo, jet_map);
                self.apply(f, a)
            }
        };
        memo.insert(id, result);
        result
    }

    /// $`\partial\,\text{root}/\partial j_{\text{variable}}`$ by recursion over the DAG,
    /// memoised in `memo` (keyed by node, for this `variable` only).
    pub fn differentiate(
        &mut self,
        root: NodeId,
        variable: usize,
        memo: &mut HashMap<NodeId, NodeId>,
    ) -> NodeId {
        if let Some(&done) = memo.get(&root) {
            return done;
        }
        let result = if !self.depends_on_jet(root) {
            self.constant(0.0)
        } else {
            match self.node(root) {
                Node::Constant(_) | Node::Parameter(_) | Node::Apply(..) => self.constant(0.0),
                Node::Jet(k) => self.constant(if k == variable { 1.0 } else { 0.0 }),
                Node::Add(a, b) => {
                    let da = self.differentiate(a, variable, memo);
                    let db = self.differentiate(b, variable, memo);
                    self.add(da, db)
                }
                Node::Multiply(a, b) => {
                    let da = self.differentiate(a, variable, memo);
                    let db = self.differentiate(b, variable, memo);
                    let left = self.multiply(da, b);
                    let right = self.multiply(a, db);
                    self.add(left, right)
                }
                Node::Power(a, n) => {
                    let da = self.differentiate(a, variable, memo);
                    let lowered = self.power(a, n - 1);
                    let coefficient = self.constant(f64::from(n));
                    let scaled = self.multiply(coefficient, lowered);
                    self.multiply(scaled, da)
                }
            }
        };
        memo.insert(root, result);
        result
    }

    /// The jet entries (model jet indices, ascending) a node depends on.
    pub fn jet_dependencies(&self, roots: &[NodeId]) -> Vec<usize> {
        let mut seen = vec![false; self.nodes.len()];
        let mut stack: Vec<NodeId> = roots.to_vec();
        let mut entries = Vec::new();
        while let Some(id) = stack.pop() {
            if seen[id.0] || !self.depends_on_jet[id.0] {
                continue;
            }
            seen[id.0] = true;
            match self.nodes[id.0] {
                Node::Jet(k) => entries.push(k),
                Node::Add(a, b) | Node::Multiply(a, b) => stack.extend([a, b]),
                Node::Power(a, _) | Node::Apply(_, a) => stack.push(a),
                Node::Constant(_) | Node::Parameter(_) => {}
            }
        }
        entries.sort_unstable();
        entries.dedup();
        entries
    }

    /// Every node reachable from `roots`, children before parents (a topological order).
    pub fn topological_order(&self, roots: &[NodeId]) -> Vec<NodeId> {
        let mut visited = vec![false; self.nodes.len()];
        let mut order = Vec::new();
        // Iterative post-order.
        for &root in roots {
            let mut stack = vec![(root, false)];
            while let Some((id, expanded)) = stack.pop() {
                if expanded {
                    order.push(id);
                    continue;
                }
                if visited[id.0] {
                    continue;
                }
                visited[id.0] = true;
                stack.push((id, true));
                match self.nodes[id.0] {
                    Node::Add(a, b) | Node::Multiply(a, b) => {
                        stack.push((b, false));
                        stack.push((a, false));
                    }
                    Node::Power(a, _) | Node::Apply(_, a) => stack.push((a, false)),
                    _ => {}
                }
            }
        }
        order
    }

    /// Number of arithmetic operations (non-leaf nodes) reachable from `roots`.
    pub fn operation_count(&self, roots: &[NodeId]) -> usize {
        self.topological_order(roots)
            .into_iter()
            .filter(|id| {
                !matches!(
                    self.nodes[id.0],
                    Node::Constant(_) | Node::Parameter(_) | Node::Jet(_)
                )
            })
            .count()
    }

    /// Number of operations on the kernel scalar (non-leaf nodes that depend on the jet)
    /// reachable from `roots`; parameter-only `f64` work is not counted.
    pub fn scalar_operation_count(&self, roots: &[NodeId]) -> usize {
        self.topological_order(roots)
            .into_iter()
            .filter(|id| self.depends_on_jet[id.0] && !matches!(self.nodes[id.0], Node::Jet(_)))
            .count()
    }

    /// Evaluates `root` in `f64` at the given parameter values and (model) jet values.
    pub fn evaluate(
        &self,
        root: NodeId,
        parameters: &[f64],
        jet: &[f64],
    ) -> Result<f64, EvaluationError> {
        if root.0 >= self.nodes.len() {
            return Err(EvaluationError::UnknownNode(root.0));
        }
        let mut values: HashMap<NodeId, f64> = HashMap::new();
        for id in self.topological_order(&[root]) {
            let value_of = |x: NodeId| values[&x];
            let value = match self.nodes[id.0] {
                Node::Constant(value) => value,
                Node::Parameter(index) => {
                    *parameters
                        .get(index)
                        .ok_or(EvaluationError::MissingParameter {
                            index,
                            available: parameters.len(),
                        })?
                }
                Node::Jet(index) => *jet.get(index).ok_or(EvaluationError::MissingJetEntry {
                    index,
                    available: jet.len(),
                })?,
                Node::Add(a, b) => value_of(a) + value_of(b),
                Node::Multiply(a, b) => value_of(a) * value_of(b),
                Node::Power(a, n) => value_of(a).powi(n),
                Node::Apply(f, a) => f.apply(value_of(a)),
            };
            values.insert(id, value);
        }
        Ok(values[&root])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hash_consing_shares_commuted_operands_and_folds_identities() {
        let mut graph = ExpressionGraph::new();
        let x = graph.jet(0);
        let p = graph.parameter(0);
        let a = graph.multiply(x, p);
        let b = graph.multiply(p, x);
        assert_eq!(a, b);
        let zero = graph.constant(0.0);
        let one = graph.constant(1.0);
        assert_eq!(graph.add(a, zero), a);
        assert_eq!(graph.multiply(one, a), a);
        assert_eq!(graph.multiply(a, zero), zero);
        let two = graph.constant(2.0);
        let three = graph.constant(3.0);
        let six = graph.multiply(two, three);
        assert_eq!(graph.constant_value(six), Some(6.0));
        let squared = graph.power(x, 2);
        let fourth = graph.power(squared, 2);
        assert_eq!(graph.node(fourth), Node::Power(x, 4));
    }

    #[test]
    fn derivative_of_a_cubic_matches_closed_form() {
        // f = p x^3 y + x / y, df/dx = 3 p x^2 y + 1/y, df/dy = p x^3 - x/y^2.
        let mut graph = ExpressionGraph::new();
        let x = graph.jet(0);
        let y = graph.jet(1);
        let p = graph.parameter(0);
        let cube = graph.power(x, 3);
        let term = graph.multiply(p, cube);
        let term = graph.multiply(term, y);
        let ratio = graph.divide(x, y);
        let f = graph.add(term, ratio);
        let dx = graph.differentiate(f, 0, &mut HashMap::new());
        let dy = graph.differentiate(f, 1, &mut HashMap::new());
        let (pv, xv, yv) = (1.7, 0.3, -1.9);
        let dx_value = graph.evaluate(dx, &[pv], &[xv, yv]).unwrap();
        let dy_value = graph.evaluate(dy, &[pv], &[xv, yv]).unwrap();
        assert!((dx_value - (3.0 * pv * xv * xv * yv + 1.0 / yv)).abs() < 1e-14);
        assert!((dy_value - (pv * xv.powi(3) - xv / (yv * yv))).abs() < 1e-14);
    }

    #[test]
    fn evaluation_reports_missing_values() {
        let mut graph = ExpressionGraph::new();
        let x = graph.jet(3);
        assert_eq!(
            graph.evaluate(x, &[], &[1.0]),
            Err(EvaluationError::MissingJetEntry {
                index: 3,
                available: 1
            })
        );
        assert_eq!(
            graph.evaluate(NodeId(17), &[], &[]),
            Err(EvaluationError::UnknownNode(17))
        );
    }
}

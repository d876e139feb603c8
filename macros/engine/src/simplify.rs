//! Bounded equality saturation with [`egg`]: all outputs of a term (energy, residual
//! entries, tangent entries) are simplified together in one e-graph, extracted with a
//! weighted operation count and re-hash-consed so common sub-expressions are shared.

use std::collections::{BTreeMap, HashMap};
use std::fmt;
use std::str::FromStr;
use std::time::Duration;

use egg::{
    Analysis, CostFunction, DidMerge, EGraph, Extractor, Id, Language, Rewrite, Runner, StopReason,
    Subst, Symbol, define_language, rewrite,
};
use thiserror::Error;

use crate::graph::{ExpressionGraph, Function, Node, NodeId};

/// A totally ordered, hashable `f64` for e-graph leaves.
#[derive(Clone, Copy, Debug)]
pub struct Real(pub f64);

impl PartialEq for Real {
    fn eq(&self, other: &Self) -> bool {
        self.0.to_bits() == other.0.to_bits()
    }
}
impl Eq for Real {}
impl PartialOrd for Real {
    fn partial_cmp(&self, other: &Self) -> Option<std::cmp::Ordering> {
        Some(self.cmp(other))
    }
}
impl Ord for Real {
    fn cmp(&self, other: &Self) -> std::cmp::Ordering {
        self.0.total_cmp(&other.0)
    }
}
impl std::hash::Hash for Real {
    fn hash<H: std::hash::Hasher>(&self, state: &mut H) {
        self.0.to_bits().hash(state);
    }
}
impl fmt::Display for Real {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(formatter, "{:?}", self.0)
    }
}
impl FromStr for Real {
    type Err = std::num::ParseFloatError;
    fn from_str(text: &str) -> Result<Self, Self::Err> {
        // Only plain decimal numbers: `inf`/`nan` must stay symbols.
        if !text.starts_with(|c: char| c.is_ascii_digit() || c == '-') {
            return "not a number".parse::<f64>().map(Real);
        }
        text.parse().map(Real)
    }
}

define_language! {
    /// The e-graph language: `+`, `*`, integer `pow`, parameter-only functions, constants and
    /// symbols (`p<k>` for parameter `k`, `j<k>` for model jet entry `k`).
    pub enum Symbolic {
        "+" = Add([Id; 2]),
        "*" = Mul([Id; 2]),
        "pow" = Pow([Id; 2]),
        "sqrt" = Sqrt(Id),
        "sin" = Sin(Id),
        "cos" = Cos(Id),
        "exp" = Exp(Id),
        "ln" = Ln(Id),
        Constant(Real),
        Symbol(Symbol),
    }
}

/// Constant-folding analysis (after egg's `tests/math.rs`): an e-class with a known
/// constant value gets the constant leaf and loses its other nodes.
#[derive(Default)]
pub struct ConstantFolding;

fn finite(value: f64) -> Option<Real> {
    // `-0.0` is normalised so that it matches the `0.0` of the rules.
    value
        .is_finite()
        .then_some(Real(if value == 0.0 { 0.0 } else { value }))
}

/// What the analysis knows about an e-class.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClassData {
    /// Its constant value, if known.
    pub constant: Option<Real>,
    /// Whether it depends on a jet entry (otherwise it is a parameter-only `f64`).
    pub scalar: bool,
}

impl Analysis<Symbolic> for ConstantFolding {
    type Data = ClassData;

    fn make(egraph: &mut EGraph<Symbolic, Self>, enode: &Symbolic, _id: Id) -> Self::Data {
        let value = |id: &Id| egraph[*id].data.constant.map(|real| real.0);
        let scalar = match enode {
            Symbolic::Symbol(symbol) => symbol.as_str().starts_with('j'),
            _ => enode
                .children()
                .iter()
                .any(|child| egraph[*child].data.scalar),
        };
        let constant = (|| match enode {
            Symbolic::Constant(c) => Some(*c),
            Symbolic::Symbol(_) => None,
            Symbolic::Add([a, b]) => finite(value(a)? + value(b)?),
            Symbolic::Mul([a, b]) => finite(value(a)? * value(b)?),
            Symbolic::Pow([a, n]) => {
                let n = value(n)?;
                if n.fract() != 0.0 || n.abs() > 64.0 {
                    return None;
                }
                finite(value(a)?.powi(n as i32))
            }
            Symbolic::Sqrt(a) => finite(value(a)?.sqrt()),
            Symbolic::Sin(a) => finite(value(a)?.sin()),
            Symbolic::Cos(a) => finite(value(a)?.cos()),
            Symbolic::Exp(a) => finite(value(a)?.exp()),
            Symbolic::Ln(a) => finite(value(a)?.ln()),
        })();
        ClassData {
            constant,
            scalar: scalar && constant.is_none(),
        }
    }

    fn merge(&mut self, to: &mut Self::Data, from: Self::Data) -> DidMerge {
        // Floating-point folding along different association orders may differ in the
        // last bit; keep the value already there. A class proved equal to something
        // parameter-only is parameter-only.
        let mut changed_to = false;
        let mut changed_from = false;
        match (to.constant.is_some(), from.constant) {
            (false, Some(value)) => {
                to.constant = Some(value);
                changed_to = true;
            }
            (true, None) => changed_from = true,
            _ => {}
        }
        let scalar = to.scalar && from.scalar && to.constant.is_none();
        changed_to |= scalar != to.scalar;
        changed_from |= scalar != from.scalar;
        to.scalar = scalar;
        DidMerge(changed_to, changed_from)
    }

    fn modify(egraph: &mut EGraph<Symbolic, Self>, id: Id) {
        if let Some(value) = egraph[id].data.constant {
            let leaf = egraph.add(Symbolic::Constant(value));
            egraph.union(id, leaf);
            egraph[id].nodes.retain(|node| node.is_leaf());
        }
    }
}

type SymbolicRewrite = Rewrite<Symbolic, ConstantFolding>;

fn is_positive_integer(
    variable: &str,
) -> impl Fn(&mut EGraph<Symbolic, ConstantFolding>, Id, &Subst) -> bool {
    let variable = variable.parse().expect("valid pattern variable");
    move |egraph, _, subst| {
        egraph[subst[variable]]
            .data
            .constant
            .is_some_and(|real| real.0 > 0.0 && real.0.fract() == 0.0 && real.0 < 64.0)
    }
}

/// The rewrite rules: commutativity and associativity of `+` and `*`, identities,
/// factoring, and power collection.
pub fn rules() -> Vec<SymbolicRewrite> {
    vec![
        rewrite!("commute-add"; "(+ ?a ?b)" => "(+ ?b ?a)"),
        rewrite!("commute-multiply"; "(* ?a ?b)" => "(* ?b ?a)"),
        rewrite!("associate-add"; "(+ ?a (+ ?b ?c))" => "(+ (+ ?a ?b) ?c)"),
        rewrite!("associate-multiply"; "(* ?a (* ?b ?c))" => "(* (* ?a ?b) ?c)"),
        rewrite!("add-zero"; "(+ ?a 0.0)" => "?a"),
        rewrite!("multiply-one"; "(* ?a 1.0)" => "?a"),
        rewrite!("multiply-zero"; "(* ?a 0.0)" => "0.0"),
        rewrite!("cancel"; "(+ ?a (* -1.0 ?a))" => "0.0"),
        rewrite!("double"; "(+ ?a ?a)" => "(* 2.0 ?a)"),
        rewrite!("factor"; "(+ (* ?a ?b) (* ?a ?c))" => "(* ?a (+ ?b ?c))"),
        rewrite!("factor-one"; "(+ ?a (* ?a ?b))" => "(* ?a (+ 1.0 ?b))"),
        rewrite!("square"; "(* ?x ?x)" => "(pow ?x 2.0)"),
        rewrite!("power-one"; "(pow ?x 1.0)" => "?x"),
        rewrite!("collect-power"; "(* ?x (pow ?x ?n))" => "(pow ?x (+ ?n 1.0))"
            if is_positive_integer("?n")),
        rewrite!("collect-powers"; "(* (pow ?x ?m) (pow ?x ?n))" => "(pow ?x (+ ?m ?n))"
            if is_positive_integer("?m") if is_positive_integer("?n")),
    ]
}

/// Weighted operation count used for extraction: `+`, `*` cost 1, `pow` 1.5 (so $`x^3`$
/// beats $`x\,x\,x`$ while $`x\,x`$ beats $`x^2`$ for a leaf $`x`$), functions 4,
/// leaves 0 (a tree cost; sharing is recovered by re-hash-consing afterwards).
pub struct OperationCost;

impl CostFunction<Symbolic> for OperationCost {
    type Cost = f64;
    fn cost<C>(&mut self, enode: &Symbolic, mut costs: C) -> Self::Cost
    where
        C: FnMut(Id) -> Self::Cost,
    {
        let own = match enode {
            Symbolic::Add(_) | Symbolic::Mul(_) => 1.0,
            Symbolic::Pow(_) => 1.5,
            Symbolic::Constant(_) | Symbolic::Symbol(_) => 0.0,
            _ => 4.0,
        };
        enode.fold(own, |sum, id| sum + costs(id))
    }
}

/// Bounds of one equality-saturation run: sizes only, never time, so that the simplified
/// kernels are a function of the model alone — the same on a loaded machine, in a debug build
/// or at any optimisation level of the engine.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SimplificationLimits {
    /// Maximum number of e-nodes.
    pub node_limit: usize,
    /// Maximum number of rule-application iterations.
    pub iteration_limit: usize,
}

impl Default for SimplificationLimits {
    fn default() -> Self {
        Self {
            node_limit: 12_000,
            iteration_limit: 10,
        }
    }
}

/// Why equality saturation stopped.
#[derive(Clone, Debug, PartialEq)]
pub enum StopKind {
    /// No rule could add anything new.
    Saturated,
    /// The node limit was exceeded; holds the e-graph size that exceeded it.
    NodeLimit(usize),
    /// The iteration limit was reached; holds the number of iterations run.
    IterationLimit(usize),
    /// Any other reason given by egg.
    Other(String),
    /// Nothing to simplify (every output was already the constant zero).
    NothingToDo,
}

impl fmt::Display for StopKind {
    fn fmt(&self, formatter: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            StopKind::Saturated => write!(formatter, "saturated"),
            StopKind::NodeLimit(n) => write!(formatter, "node limit (e-graph reached {n} nodes)"),
            StopKind::IterationLimit(n) => write!(formatter, "iteration limit ({n} iterations)"),
            StopKind::Other(reason) => write!(formatter, "{reason}"),
            StopKind::NothingToDo => write!(formatter, "nothing to simplify"),
        }
    }
}

impl From<&StopReason> for StopKind {
    fn from(reason: &StopReason) -> Self {
        match reason {
            StopReason::Saturated => StopKind::Saturated,
            StopReason::NodeLimit(n) => StopKind::NodeLimit(*n),
            StopReason::IterationLimit(n) => StopKind::IterationLimit(*n),
            // `simplify` sets no time limit (egg's default is lifted), so egg never gives this.
            StopReason::TimeLimit(seconds) => StopKind::Other(format!("time limit ({seconds} s)")),
            StopReason::Other(reason) => StopKind::Other(reason.clone()),
        }
    }
}

/// Sizes and outcome of one simplification run.
#[derive(Clone, Debug, PartialEq)]
pub struct SimplificationStatistics {
    /// E-nodes at the end.
    pub nodes: usize,
    /// E-classes at the end.
    pub classes: usize,
    /// Iterations run.
    pub iterations: usize,
    /// Why it stopped.
    pub stop: StopKind,
    /// Scalar (jet-dependent) operations of the outputs before simplification (shared DAG).
    pub operations_before: usize,
    /// Scalar operations after extraction and re-hash-consing.
    pub operations_after: usize,
    /// Whether the extracted form had more operations than the input, so that the input
    /// (with the zeros the e-graph proved) was kept instead.
    pub kept_input: bool,
    /// Scalar operations of the extracted form (before the `kept_input` decision).
    pub operations_extracted: usize,
}

/// Errors of the simplifier (internal invariants; never caused by user input).
#[derive(Debug, Error, PartialEq)]
pub enum SimplifyError {
    /// An extracted `pow` whose exponent is not an integer constant.
    #[error("internal error: extracted a power with a non-integer exponent")]
    NonIntegerExponent,
    /// An extracted symbol that is neither a parameter nor a jet entry.
    #[error("internal error: unknown symbol `{0}` in the e-graph")]
    UnknownSymbol(String),
}

/// Result of [`simplify`].
#[derive(Clone, Debug)]
pub struct Simplified {
    /// The simplified, hash-consed outputs.
    pub graph: ExpressionGraph,
    /// One root per input root, in order.
    pub roots: Vec<NodeId>,
    /// What happened.
    pub statistics: SimplificationStatistics,
}

fn add_to_egraph(
    egraph: &mut EGraph<Symbolic, ConstantFolding>,
    graph: &ExpressionGraph,
    id: NodeId,
    memo: &mut HashMap<NodeId, Id>,
) -> Id {
    if let Some(&done) = memo.get(&id) {
        return done;
    }
    let node = match graph.node(id) {
        Node::Constant(value) => Symbolic::Constant(Real(value)),
        Node::Parameter(k) => Symbolic::Symbol(Symbol::from(format!("p{k}"))),
        Node::Jet(k) => Symbolic::Symbol(Symbol::from(format!("j{k}"))),
        Node::Add(a, b) => {
            let a = add_to_egraph(egraph, graph, a, memo);
            let b = add_to_egraph(egraph, graph, b, memo);
            Symbolic::Add([a, b])
        }
        Node::Multiply(a, b) => {
            let a = add_to_egraph(egraph, graph, a, memo);
            let b = add_to_egraph(egraph, graph, b, memo);
            Symbolic::Mul([a, b])
        }
        Node::Power(a, n) => {
            let a = add_to_egraph(egraph, graph, a, memo);
            let n = egraph.add(Symbolic::Constant(Real(f64::from(n))));
            Symbolic::Pow([a, n])
        }
        Node::Apply(function, a) => {
            let a = add_to_egraph(egraph, graph, a, memo);
            match function {
                Function::Sqrt => Symbolic::Sqrt(a),
                Function::Sin => Symbolic::Sin(a),
                Function::Cos => Symbolic::Cos(a),
                Function::Exp => Symbolic::Exp(a),
                Function::Ln => Symbolic::Ln(a),
            }
        }
    };
    let added = egraph.add(node);
    memo.insert(id, added);
    added
}

/// Own cost of a node in class `class`: parameter-only (`f64`) operations are nearly free
/// compared with operations on the kernel scalar (dual numbers, Taylor series).
fn own_cost(egraph: &EGraph<Symbolic, ConstantFolding>, class: Id, node: &Symbolic) -> f64 {
    let cost = OperationCost.cost(node, |_| 0.0);
    if egraph[class].data.scalar {
        cost
    } else {
        0.01 * cost
    }
}

/// Greedy DAG extraction: for every e-class, the node whose *set* of distinct e-classes
/// needed (with their chosen nodes' own costs) is cheapest, so shared sub-expressions are
/// counted once. Iterated to a fixed point (bounded number of passes); nodes whose
/// children need their own class (cycles) are skipped. Falls back to the tree-cost
/// [`Extractor`] for any class left without a choice.
fn dag_extract(egraph: &EGraph<Symbolic, ConstantFolding>) -> HashMap<Id, Symbolic> {
    // Ordered, so that a set's total is summed in the same order in every process (a
    // `HashMap`'s order is seeded at random).
    type CostSet = std::rc::Rc<BTreeMap<Id, f64>>;
    let mut classes: Vec<Id> = egraph.classes().map(|class| class.id).collect();
    classes.sort_unstable();
    let mut best: HashMap<Id, (f64, CostSet, Symbolic)> = HashMap::new();
    for _pass in 0..64 {
        let mut changed = false;
        for &class in &classes {
            for node in &egraph[class].nodes {
                let children: Option<Vec<&CostSet>> = node
                    .children()
                    .iter()
                    .map(|child| best.get(&egraph.find(*child)).map(|entry| &entry.1))
                    .collect();
                let Some(children) = children else { continue };
                if children.iter().any(|set| set.contains_key(&class)) {
                    continue;
                }
                let mut set: BTreeMap<Id, f64> = match children.first() {
                    Some(first) => (***first).clone(),
                    None => BTreeMap::new(),
                };
                for child in children.iter().skip(1) {
                    for (&id, &cost) in child.iter() {
                        set.insert(id, cost);
                    }
                }
                set.insert(class, own_cost(egraph, class, node));
                let total: f64 = set.values().sum();
                let improves = match best.get(&class) {
                    Some((current, ..)) => total < *current - 1e-9,
                    None => true,
                };
                if improves {
                    best.insert(class, (total, std::rc::Rc::new(set), node.clone()));
                    changed = true;
                }
            }
        }
        if !changed {
            break;
        }
    }
    let extractor = Extractor::new(egraph, OperationCost);
    classes
        .iter()
        .map(|&class| {
            let node = best
                .get(&class)
                .map(|entry| entry.2.clone())
                .unwrap_or_else(|| extractor.find_best_node(class).clone());
            (class, node)
        })
        .collect()
}

struct Rebuild<'a> {
    egraph: &'a EGraph<Symbolic, ConstantFolding>,
    choice: HashMap<Id, Symbolic>,
    graph: ExpressionGraph,
    memo: HashMap<Id, NodeId>,
}

impl Rebuild<'_> {
    fn build(&mut self, class: Id) -> Result<NodeId, SimplifyError> {
        let class = self.egraph.find(class);
        if let Some(&done) = self.memo.get(&class) {
            return Ok(done);
        }
        let node = self.choice[&class].clone();
        let result = match node {
            Symbolic::Constant(value) => self.graph.constant(value.0),
            Symbolic::Symbol(symbol) => {
                let text = symbol.as_str();
                let index = text[1..]
                    .parse::<usize>()
                    .map_err(|_| SimplifyError::UnknownSymbol(text.to_string()))?;
                match &text[..1] {
                    "p" => self.graph.parameter(index),
                    "j" => self.graph.jet(index),
                    _ => return Err(SimplifyError::UnknownSymbol(text.to_string())),
                }
            }
            Symbolic::Add([a, b]) => {
                let a = self.build(a)?;
                let b = self.build(b)?;
                self.graph.add(a, b)
            }
            Symbolic::Mul([a, b]) => {
                let a = self.build(a)?;
                let b = self.build(b)?;
                self.graph.multiply(a, b)
            }
            Symbolic::Pow([a, n]) => {
                // Written exponents are within ±64 (`syntax::MAX_EXPONENT`); differentiation
                // and power collection take them a little beyond, never near the `i32` bounds.
                let exponent = self.egraph[n]
                    .data
                    .constant
                    .filter(|real| real.0.fract() == 0.0 && real.0.abs() <= f64::from(i32::MAX))
                    .ok_or(SimplifyError::NonIntegerExponent)?;
                let a = self.build(a)?;
                self.graph.power(a, exponent.0 as i32)
            }
            Symbolic::Sqrt(a) => self.apply(Function::Sqrt, a)?,
            Symbolic::Sin(a) => self.apply(Function::Sin, a)?,
            Symbolic::Cos(a) => self.apply(Function::Cos, a)?,
            Symbolic::Exp(a) => self.apply(Function::Exp, a)?,
            Symbolic::Ln(a) => self.apply(Function::Ln, a)?,
        };
        self.memo.insert(class, result);
        Ok(result)
    }

    fn apply(&mut self, function: Function, argument: Id) -> Result<NodeId, SimplifyError> {
        let argument = self.build(argument)?;
        Ok(self.graph.apply(function, argument))
    }
}

/// Simplifies `roots` of `graph` together in one bounded e-graph and returns them
/// re-hash-consed in a fresh graph (jet and parameter indices unchanged).
pub fn simplify(
    graph: &ExpressionGraph,
    roots: &[NodeId],
    limits: &SimplificationLimits,
) -> Result<Simplified, SimplifyError> {
    let operations_before = graph.scalar_operation_count(roots);
    let mut egraph: EGraph<Symbolic, ConstantFolding> = EGraph::default();
    let mut memo = HashMap::new();
    let classes: Vec<Id> = roots
        .iter()
        .map(|&root| add_to_egraph(&mut egraph, graph, root, &mut memo))
        .collect();
    egraph.rebuild();
    let runner = Runner::default()
        .with_egraph(egraph)
        .with_node_limit(limits.node_limit)
        .with_iter_limit(limits.iteration_limit)
        // egg stops after 5 s unless told otherwise: lift that, the size limits decide.
        .with_time_limit(Duration::MAX)
        .run(&rules());
    let stop = runner
        .stop_reason
        .as_ref()
        .map(StopKind::from)
        .unwrap_or(StopKind::Other("unknown".to_string()));
    let egraph = &runner.egraph;
    let mut rebuild = Rebuild {
        egraph,
        choice: dag_extract(egraph),
        graph: ExpressionGraph::new(),
        memo: HashMap::new(),
    };
    let new_roots = classes
        .iter()
        .map(|&class| rebuild.build(class))
        .collect::<Result<Vec<_>, _>>()?;
    let mut new_graph = rebuild.graph;
    let mut new_roots = new_roots;
    let mut kept_input = false;
    let operations_extracted = new_graph.scalar_operation_count(&new_roots);
    if operations_extracted > operations_before {
        // Extraction minimises tree cost and may lose sharing: never return something more
        // expensive than the input, but keep the zeros the e-graph proved.
        kept_input = true;
        let mut fallback = ExpressionGraph::new();
        let mut memo = HashMap::new();
        new_roots = roots
            .iter()
            .zip(&new_roots)
            .map(|(&original, &simplified)| {
                if new_graph.constant_value(simplified) == Some(0.0) {
                    fallback.constant(0.0)
                } else {
                    fallback.import(graph, original, &mut memo, &|k| k)
                }
            })
            .collect();
        new_graph = fallback;
    }
    let statistics = SimplificationStatistics {
        nodes: egraph.total_number_of_nodes(),
        classes: egraph.number_of_classes(),
        iterations: runner.iterations.len(),
        stop,
        operations_before,
        operations_after: new_graph.scalar_operation_count(&new_roots),
        kept_input,
        operations_extracted,
    };
    Ok(Simplified {
        graph: new_graph,
        roots: new_roots,
        statistics,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cancellation_and_factoring_reach_the_expected_forms() {
        // (x*y + x*z) - x*(y + z) == 0 and x*x*x -> x^3.
        let mut graph = ExpressionGraph::new();
        let x = graph.jet(0);
        let y = graph.jet(1);
        let z = graph.jet(2);
        let xy = graph.multiply(x, y);
        let xz = graph.multiply(x, z);
        let sum = graph.add(xy, xz);
        let yz = graph.add(y, z);
        let factored = graph.multiply(x, yz);
        let difference = graph.subtract(sum, factored);
        let xx = graph.multiply(x, x);
        let cube = graph.multiply(xx, x);
        let mut result = simplify(
            &graph,
            &[difference, cube],
            &SimplificationLimits::default(),
        )
        .unwrap();
        assert_eq!(result.graph.constant_value(result.roots[0]), Some(0.0));
        let jet = result.graph.jet(0);
        assert_eq!(result.graph.node(result.roots[1]), Node::Power(jet, 3));
    }

    #[test]
    fn real_parsing_keeps_symbols_apart() {
        assert!("p0".parse::<Real>().is_err());
        assert!("inf".parse::<Real>().is_err());
        assert_eq!("-2.5".parse::<Real>().unwrap(), Real(-2.5));
    }
}

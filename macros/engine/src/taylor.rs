//! Taylor-mode kernels: the residual of a term along a jet series, one order at a time.
//!
//! For the Asymptotic Numerical Method the runtime needs, at every order $`k`$ of a step, the
//! order-$`k`$ coefficient of the residual $`r(\mathbf{j}(a))`$ with the order-$`k`$ jet
//! $`\mathbf{j}_k`$ still unknown (taken as zero), and, once the linear solve has given
//! $`\mathbf{j}_k`$, the true order-$`k`$ coefficients of every intermediate. Evaluating the
//! whole residual on truncated series recomputes every coefficient at every order
//! ($`O(N^3)`$ per step); here the residual's expression DAG is lowered once into a
//! [`TaylorProgram`] of elementary operations on series *registers*, and the generated code
//! keeps, per quadrature point, a *tape* with the coefficient history of the few registers a
//! recurrence reads: operands of series × series products, divisors, quotients and
//! reciprocals. Order $`k`$ then costs $`O(k)`$ per product and $`O(1)`$ per linear operation.
//!
//! Three kernels per term:
//! * `taylor_start` — order 0: a plain `f64` evaluation writing every slot's $`x_0`$;
//! * `taylor_predict` — order $`k \ge 1`$ with $`\mathbf{j}_k = 0`$: linear operations
//!   propagate order-$`k`$ values, products use [`product`](../../wrinkle_runtime) rules over the
//!   tape; returns the residual's order-$`k`$ coefficient and writes the slots' predicted
//!   $`x_k`$;
//! * `taylor_commit` — adds to each slot's $`x_k`$ its exact correction, the directional
//!   derivative at order 0 along $`\mathbf{j}_k`$ (the order-$`k`$ coefficient of any smooth
//!   function of the jet is affine in $`\mathbf{j}_k`$ with that slope): one forward-mode sweep.

use std::collections::HashMap;

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::graph::{ExpressionGraph, Node, NodeId};
use crate::kernel_writer::{KernelWriter, Operation, operation_of};

/// One elementary operation of a [`TaylorProgram`]; `usize` operands are registers,
/// [`NodeId`] operands are `f64` (parameter-only) nodes of the term graph.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Instruction {
    /// Term-local jet entry.
    Jet(usize),
    /// $`a + b`$.
    Add(usize, usize),
    /// $`a + c`$.
    AddReal(usize, NodeId),
    /// $`a - b`$.
    Subtract(usize, usize),
    /// $`a - c`$.
    SubtractReal(usize, NodeId),
    /// $`c - a`$.
    SubtractFromReal(usize, NodeId),
    /// $`-a`$.
    Negate(usize),
    /// $`a + a`$ (exact, so a product can read the history of $`a`$ instead).
    Double(usize),
    /// $`a\,c`$.
    Scale(usize, NodeId),
    /// $`a / c`$.
    DivideByReal(usize, NodeId),
    /// $`a\,b`$ (series × series).
    Multiply(usize, usize),
    /// $`a^2`$.
    Square(usize),
    /// $`a / b`$ (series ÷ series).
    Divide(usize, usize),
    /// $`1 / a`$.
    Reciprocal(usize),
}

impl Instruction {
    /// Registers whose coefficient history this instruction's recurrence reads (operands; the
    /// result itself for quotients and reciprocals is added by [`TaylorProgram::new`]).
    fn history_operands(self) -> Vec<usize> {
        match self {
            Instruction::Multiply(a, b) => vec![a, b],
            Instruction::Square(a) => vec![a],
            Instruction::Divide(_, b) => vec![b],
            Instruction::Reciprocal(a) => vec![a],
            _ => Vec::new(),
        }
    }
    fn needs_own_history(self) -> bool {
        matches!(self, Instruction::Divide(..) | Instruction::Reciprocal(_))
    }
    /// The series registers the instruction reads.
    fn operands(self) -> Vec<usize> {
        match self {
            Instruction::Jet(_) => Vec::new(),
            Instruction::Add(a, b)
            | Instruction::Subtract(a, b)
            | Instruction::Multiply(a, b)
            | Instruction::Divide(a, b) => vec![a, b],
            Instruction::AddReal(a, _)
            | Instruction::SubtractReal(a, _)
            | Instruction::SubtractFromReal(a, _)
            | Instruction::Negate(a)
            | Instruction::Double(a)
            | Instruction::Scale(a, _)
            | Instruction::DivideByReal(a, _)
            | Instruction::Square(a)
            | Instruction::Reciprocal(a) => vec![a],
        }
    }

    /// The instruction with every register operand `r` replaced by `map(r)`.
    fn with_registers(self, map: impl Fn(usize) -> usize) -> Self {
        match self {
            Instruction::Jet(local) => Instruction::Jet(local),
            Instruction::Add(a, b) => Instruction::Add(map(a), map(b)),
            Instruction::Subtract(a, b) => Instruction::Subtract(map(a), map(b)),
            Instruction::Multiply(a, b) => Instruction::Multiply(map(a), map(b)),
            Instruction::Divide(a, b) => Instruction::Divide(map(a), map(b)),
            Instruction::AddReal(a, c) => Instruction::AddReal(map(a), c),
            Instruction::SubtractReal(a, c) => Instruction::SubtractReal(map(a), c),
            Instruction::SubtractFromReal(a, c) => Instruction::SubtractFromReal(map(a), c),
            Instruction::Negate(a) => Instruction::Negate(map(a)),
            Instruction::Double(a) => Instruction::Double(map(a)),
            Instruction::Scale(a, c) => Instruction::Scale(map(a), c),
            Instruction::DivideByReal(a, c) => Instruction::DivideByReal(map(a), c),
            Instruction::Square(a) => Instruction::Square(map(a)),
            Instruction::Reciprocal(a) => Instruction::Reciprocal(map(a)),
        }
    }

    /// Whether the operation is nonlinear in its series operands.
    fn is_nonlinear(self) -> bool {
        matches!(
            self,
            Instruction::Multiply(..)
                | Instruction::Square(_)
                | Instruction::Divide(..)
                | Instruction::Reciprocal(_)
        )
    }
}

/// A residual output: a register, or a value that does not depend on the jet (its
/// coefficients of order ≥ 1 vanish).
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum TaylorOutput {
    /// The register holding the residual entry.
    Register(usize),
    /// Independent of the jet.
    Constant,
}

impl TaylorOutput {
    /// The output with its register `r` replaced by `map(r)`.
    fn renumbered(self, map: impl Fn(usize) -> usize) -> Self {
        match self {
            TaylorOutput::Register(r) => TaylorOutput::Register(map(r)),
            TaylorOutput::Constant => TaylorOutput::Constant,
        }
    }
}

/// The residual of one term as straight-line operations on series registers.
#[derive(Clone, Debug)]
pub struct TaylorProgram {
    /// Operations in evaluation order; register `i` is the result of instruction `i`.
    pub instructions: Vec<Instruction>,
    /// The tape slot of each register whose history is read, `None` otherwise.
    pub slot_of: Vec<Option<usize>>,
    /// Number of tape slots.
    pub slots: usize,
    /// One output per term-local residual entry.
    pub outputs: Vec<TaylorOutput>,
    /// Registers that are identically zero at every order ≥ 1 when the order-$`k`$ jet is zero
    /// (linear combinations of jet entries): `taylor_predict` skips them.
    pub zero_in_prediction: Vec<bool>,
}

impl TaylorProgram {
    /// Lowers the residual roots of a term (nodes of `graph`, whose `Jet(k)` leaves are model
    /// jet indices; `term_jet` maps term-local positions to them).
    pub fn new(graph: &ExpressionGraph, residual: &[NodeId], term_jet: &[usize]) -> Self {
        let mut builder = Builder {
            graph,
            term_jet,
            instructions: Vec::new(),
            register_of: HashMap::new(),
        };
        let outputs = residual
            .iter()
            .map(|&root| {
                if graph.depends_on_jet(root) {
                    TaylorOutput::Register(builder.register(root))
                } else {
                    TaylorOutput::Constant
                }
            })
            .collect();
        let (instructions, outputs) = factor_shared_operands(builder.instructions, outputs);
        let needs_history = history_needed(&instructions);
        let mut slots = 0;
        let slot_of = needs_history
            .iter()
            .map(|&needed| {
                needed.then(|| {
                    slots += 1;
                    slots - 1
                })
            })
            .collect();
        let mut zero_in_prediction = vec![false; instructions.len()];
        for (index, instruction) in instructions.iter().enumerate() {
            let zero = match *instruction {
                Instruction::Jet(_) => true,
                Instruction::Add(a, b) | Instruction::Subtract(a, b) => {
                    zero_in_prediction[a] && zero_in_prediction[b]
                }
                Instruction::AddReal(a, _)
                | Instruction::SubtractReal(a, _)
                | Instruction::SubtractFromReal(a, _)
                | Instruction::Negate(a)
                | Instruction::Double(a)
                | Instruction::Scale(a, _)
                | Instruction::DivideByReal(a, _) => zero_in_prediction[a],
                _ => false,
            };
            zero_in_prediction[index] = zero;
        }
        TaylorProgram {
            instructions,
            slot_of,
            slots,
            outputs,
            zero_in_prediction,
        }
    }

    /// The recurrences of the program, in instruction order: `(register, x, y)` with the tape
    /// slots whose history sum $`\sum_{j=1}^{k-1} x_j\,y_{k-j}`$ the register's order-$`k`$
    /// rule needs — the operands of a product (twice the operand of a square), the divisor and
    /// the quotient of a quotient or a reciprocal.
    pub fn history_pairs(&self) -> Vec<(usize, usize, usize)> {
        let slot = |register: usize| {
            self.slot_of[register].expect("operands of recurrences are on the tape")
        };
        self.instructions
            .iter()
            .enumerate()
            .filter_map(|(index, instruction)| match *instruction {
                Instruction::Multiply(a, b) => Some((index, slot(a), slot(b))),
                Instruction::Square(a) => Some((index, slot(a), slot(a))),
                Instruction::Divide(_, b) | Instruction::Reciprocal(b) => {
                    Some((index, slot(b), slot(index)))
                }
                _ => None,
            })
            .collect()
    }

    /// Whether the residual is affine in the jet (no nonlinear operation at all).
    pub fn is_linear(&self) -> bool {
        !self.instructions.iter().any(|i| i.is_nonlinear())
    }

    /// The `f64` nodes the program reads.
    fn real_operands(&self) -> Vec<NodeId> {
        self.instructions
            .iter()
            .filter_map(|instruction| match *instruction {
                Instruction::AddReal(_, c)
                | Instruction::SubtractReal(_, c)
                | Instruction::SubtractFromReal(_, c)
                | Instruction::Scale(_, c)
                | Instruction::DivideByReal(_, c) => Some(c),
                _ => None,
            })
            .collect()
    }
}

/// A constant factor of one term of a linear combination ([`factor_shared_operands`]).
#[derive(Clone, Copy, Debug, PartialEq)]
enum Factor {
    Scale(NodeId),
    DivideByReal(NodeId),
    Negate,
    Double,
}

/// One term of a linear combination: an *atom* register (anything but a sum, difference or
/// constant scaling) and the constant factors applied to it, innermost first.
type Term = (Vec<Factor>, usize);

/// Largest number of terms an output is expanded into before its factoring is given up.
const MAX_EXPANDED_TERMS: usize = 64;

/// Which registers of `instructions` a recurrence reads the history of (the tape slots).
fn history_needed(instructions: &[Instruction]) -> Vec<bool> {
    let mut history = vec![false; instructions.len()];
    for (index, instruction) in instructions.iter().enumerate() {
        for operand in instruction.history_operands() {
            history[operand] = true;
        }
        if instruction.needs_own_history() {
            history[index] = true;
        }
    }
    history
}

/// The tape slots and the recurrences (products, quotients, reciprocals) of `instructions`:
/// the memory a Taylor sweep streams per point and order, and its work.
fn tape_cost(instructions: &[Instruction]) -> (usize, usize) {
    let slots = history_needed(instructions).iter().filter(|&&h| h).count();
    let recurrences = instructions.iter().filter(|i| i.is_nonlinear()).count();
    (slots, recurrences)
}

/// `register` as a linear combination of atoms, or `None` past [`MAX_EXPANDED_TERMS`].
fn linear_terms(instructions: &[Instruction], register: usize) -> Option<Vec<Term>> {
    // (register, the factors applied to it, outermost first)
    let mut stack = vec![(register, Vec::new())];
    let mut terms = Vec::new();
    while let Some((r, outer)) = stack.pop() {
        let with = |factor: Factor| {
            let mut factors: Vec<Factor> = outer.clone();
            factors.push(factor);
            factors
        };
        match instructions[r] {
            Instruction::Add(a, b) => {
                stack.push((b, outer.clone()));
                stack.push((a, outer));
            }
            Instruction::Subtract(a, b) => {
                stack.push((b, with(Factor::Negate)));
                stack.push((a, outer));
            }
            Instruction::Scale(a, c) => stack.push((a, with(Factor::Scale(c)))),
            Instruction::DivideByReal(a, c) => stack.push((a, with(Factor::DivideByReal(c)))),
            Instruction::Negate(a) => stack.push((a, with(Factor::Negate))),
            Instruction::Double(a) => stack.push((a, with(Factor::Double))),
            _ => {
                let mut factors = outer;
                factors.reverse();
                terms.push((factors, r));
                if terms.len() > MAX_EXPANDED_TERMS {
                    return None;
                }
            }
        }
    }
    Some(terms)
}

/// Appends `term` (its atom with its factors applied); returns its register.
fn emit_term(instructions: &mut Vec<Instruction>, (factors, atom): &Term) -> usize {
    let mut register = *atom;
    for factor in factors {
        instructions.push(match *factor {
            Factor::Scale(c) => Instruction::Scale(register, c),
            Factor::DivideByReal(c) => Instruction::DivideByReal(register, c),
            Factor::Negate => Instruction::Negate(register),
            Factor::Double => Instruction::Double(register),
        });
        register = instructions.len() - 1;
    }
    register
}

/// Appends the sum of `terms` (at least one), left to right; returns its register.
fn emit_sum(instructions: &mut Vec<Instruction>, terms: &[Term]) -> usize {
    let mut sum = emit_term(instructions, &terms[0]);
    for term in &terms[1..] {
        let register = emit_term(instructions, term);
        instructions.push(Instruction::Add(sum, register));
        sum = instructions.len() - 1;
    }
    sum
}

/// Factors the series operand that products in one residual output share out of them:
/// $`\sum_i c_i\,(x\,y_i) = x\,ig(\sum_i c_i\,y_iig)`$, the output's products expanded
/// through its sums and constant scalings. One recurrence replaces several, and the $`y_i`$
/// need no tape slot of their own unless another recurrence reads them: on the reference
/// envelope, $`\partial\psi/\partial w = 2Q^2 w\,(c^2 N_x + s^2 N_y + 2cs N_{xy})`$ was three
/// products of $`w`$ with strain and stress combinations (9 slots, 11 products), and is one
/// (7 slots, 9 products) — the Taylor sweeps stream the tape, so its slots are their memory
/// traffic. Kept only when the tape gets smaller (fewer slots, or as many and fewer
/// recurrences); otherwise the program is returned as it was. The factored sums round
/// differently from the expanded ones.
fn factor_shared_operands(
    instructions: Vec<Instruction>,
    outputs: Vec<TaylorOutput>,
) -> (Vec<Instruction>, Vec<TaylorOutput>) {
    let mut factored = instructions.clone();
    let mut replaced: HashMap<usize, usize> = HashMap::new();
    for output in &outputs {
        let TaylorOutput::Register(root) = *output else {
            continue;
        };
        if replaced.contains_key(&root) {
            continue;
        }
        let Some(mut terms) = linear_terms(&instructions, root) else {
            continue;
        };
        let mut factored_here = false;
        loop {
            // The operand shared by the most products among the terms (ties: the lowest).
            let mut uses: HashMap<usize, Vec<usize>> = HashMap::new();
            for (t, (_, atom)) in terms.iter().enumerate() {
                if let Instruction::Multiply(a, b) = factored[*atom] {
                    uses.entry(a).or_default().push(t);
                    uses.entry(b).or_default().push(t);
                }
            }
            let Some((shared, group)) = uses
                .into_iter()
                .filter(|(_, group)| group.len() >= 2)
                .max_by_key(|(operand, group)| (group.len(), std::cmp::Reverse(*operand)))
            else {
                break;
            };
            let cofactors: Vec<Term> = group
                .iter()
                .map(|&t| {
                    let (factors, atom) = &terms[t];
                    let Instruction::Multiply(a, b) = factored[*atom] else {
                        unreachable!("grouped terms are products");
                    };
                    (factors.clone(), if a == shared { b } else { a })
                })
                .collect();
            let cofactor = emit_sum(&mut factored, &cofactors);
            factored.push(Instruction::Multiply(shared, cofactor));
            let product = factored.len() - 1;
            let mut kept: Vec<Term> = terms
                .iter()
                .enumerate()
                .filter(|(t, _)| !group.contains(t))
                .map(|(_, term)| term.clone())
                .collect();
            kept.push((Vec::new(), product));
            terms = kept;
            factored_here = true;
        }
        if factored_here {
            let sum = emit_sum(&mut factored, &terms);
            replaced.insert(root, sum);
        }
    }
    if replaced.is_empty() {
        return (instructions, outputs);
    }
    let outputs_factored: Vec<TaylorOutput> = outputs
        .iter()
        .map(|output| output.renumbered(|r| *replaced.get(&r).unwrap_or(&r)))
        .collect();
    let (factored, outputs_factored) = without_dead_registers(&factored, &outputs_factored);
    if tape_cost(&factored) < tape_cost(&instructions) {
        (factored, outputs_factored)
    } else {
        (instructions, outputs)
    }
}

/// The instructions the outputs read, in order and renumbered, with the outputs renumbered.
fn without_dead_registers(
    instructions: &[Instruction],
    outputs: &[TaylorOutput],
) -> (Vec<Instruction>, Vec<TaylorOutput>) {
    let mut live = vec![false; instructions.len()];
    for output in outputs {
        if let TaylorOutput::Register(r) = *output {
            live[r] = true;
        }
    }
    for index in (0..instructions.len()).rev() {
        if live[index] {
            for operand in instructions[index].operands() {
                live[operand] = true;
            }
        }
    }
    let mut number = vec![usize::MAX; instructions.len()];
    let mut kept = Vec::new();
    for (index, instruction) in instructions.iter().enumerate() {
        if live[index] {
            number[index] = kept.len();
            kept.push(instruction.with_registers(|r| number[r]));
        }
    }
    let outputs = outputs
        .iter()
        .map(|output| output.renumbered(|r| number[r]))
        .collect();
    (kept, outputs)
}

struct Builder<'a> {
    graph: &'a ExpressionGraph,
    term_jet: &'a [usize],
    instructions: Vec<Instruction>,
    register_of: HashMap<NodeId, usize>,
}

impl Builder<'_> {
    fn push(&mut self, instruction: Instruction) -> usize {
        self.instructions.push(instruction);
        self.instructions.len() - 1
    }

    fn is_series(&self, id: NodeId) -> bool {
        self.graph.depends_on_jet(id)
    }

    /// The register of a jet-dependent node, lowering its operands first (iteratively, so deep
    /// expressions cannot overflow the stack).
    fn register(&mut self, root: NodeId) -> usize {
        let mut stack = vec![(root, false)];
        while let Some((id, expanded)) = stack.pop() {
            if self.register_of.contains_key(&id) {
                continue;
            }
            let operation = operation_of(self.graph, id);
            if !expanded {
                stack.push((id, true));
                for child in operation.children() {
                    if self.is_series(child) && !self.register_of.contains_key(&child) {
                        stack.push((child, false));
                    }
                }
                continue;
            }
            let register = self.lower(id, operation);
            self.register_of.insert(id, register);
        }
        self.register_of[&root]
    }

    fn lower(&mut self, id: NodeId, operation: Operation) -> usize {
        let series = |builder: &Self, n: NodeId| builder.is_series(n);
        let r = |builder: &Self, n: NodeId| builder.register_of[&n];
        match operation {
            Operation::Leaf => match self.graph.node(id) {
                Node::Jet(k) => {
                    let local = self
                        .term_jet
                        .iter()
                        .position(|&entry| entry == k)
                        .expect("a term only reads its own jet entries");
                    self.push(Instruction::Jet(local))
                }
                other => unreachable!("a jet-dependent leaf is a jet entry, not {other:?}"),
            },
            Operation::Add(a, b) => match (series(self, a), series(self, b)) {
                (true, true) if r(self, a) == r(self, b) => {
                    self.push(Instruction::Double(r(self, a)))
                }
                (true, true) => self.push(Instruction::Add(r(self, a), r(self, b))),
                (true, false) => self.push(Instruction::AddReal(r(self, a), b)),
                _ => self.push(Instruction::AddReal(r(self, b), a)),
            },
            Operation::Subtract(a, b) => match (series(self, a), series(self, b)) {
                (true, true) => self.push(Instruction::Subtract(r(self, a), r(self, b))),
                (true, false) => self.push(Instruction::SubtractReal(r(self, a), b)),
                _ => self.push(Instruction::SubtractFromReal(r(self, b), a)),
            },
            Operation::Multiply(a, b) => match (series(self, a), series(self, b)) {
                (true, true) => {
                    let (a, b) = (r(self, a), r(self, b));
                    self.multiply(a, b)
                }
                (true, false) => self.push(Instruction::Scale(r(self, a), b)),
                _ => self.push(Instruction::Scale(r(self, b), a)),
            },
            Operation::Divide(a, b) => match (series(self, a), series(self, b)) {
                (true, true) => self.push(Instruction::Divide(r(self, a), r(self, b))),
                (true, false) => self.push(Instruction::DivideByReal(r(self, a), b)),
                _ => {
                    let reciprocal = self.push(Instruction::Reciprocal(r(self, b)));
                    self.push(Instruction::Scale(reciprocal, a))
                }
            },
            Operation::Negate(a) => self.push(Instruction::Negate(r(self, a))),
            Operation::Reciprocal(a) => self.push(Instruction::Reciprocal(r(self, a))),
            Operation::Power(a, n) => {
                let base = r(self, a);
                let magnitude = self.positive_power(base, n.unsigned_abs());
                if n < 0 {
                    self.push(Instruction::Reciprocal(magnitude))
                } else {
                    magnitude
                }
            }
            Operation::Apply(..) => {
                unreachable!("functions apply to parameter-only expressions")
            }
        }
    }

    /// $`x^n`$, $`n \ge 1`$, by binary exponentiation (squares and products).
    fn positive_power(&mut self, base: usize, n: u32) -> usize {
        if n == 1 {
            return base;
        }
        let half = self.positive_power(base, n / 2);
        let squared = self.multiply(half, half);
        if n % 2 == 1 {
            self.multiply(squared, base)
        } else {
            squared
        }
    }

    /// `register` without its constant scalings: the innermost register and the scalings
    /// (`Scale`, `DivideByReal`, `Negate`, `Double`) that give `register` from it, innermost
    /// first.
    fn peel(&self, mut register: usize) -> (usize, Vec<Instruction>) {
        let mut scalings = Vec::new();
        while let scaling @ (Instruction::Scale(inner, _)
        | Instruction::DivideByReal(inner, _)
        | Instruction::Negate(inner)
        | Instruction::Double(inner)) = self.instructions[register]
        {
            scalings.push(scaling);
            register = inner;
        }
        scalings.reverse();
        (register, scalings)
    }

    /// $`a\,b`$ of two series registers, with constant scalings taken out of the product:
    /// $`(c\,x)(d\,y) = c\,d\,(x\,y)`$. The recurrence then reads the histories of $`x`$ and
    /// $`y`$, so a scaled copy of a register (`2 w_x` beside `w_x`, common after
    /// differentiation) needs no tape slot of its own.
    fn multiply(&mut self, a: usize, b: usize) -> usize {
        let (a, a_scalings) = self.peel(a);
        let (b, b_scalings) = self.peel(b);
        let mut product = if a == b {
            self.push(Instruction::Square(a))
        } else {
            self.push(Instruction::Multiply(a, b))
        };
        for scaling in a_scalings.into_iter().chain(b_scalings) {
            product = self.push(match scaling {
                Instruction::Scale(_, c) => Instruction::Scale(product, c),
                Instruction::DivideByReal(_, c) => Instruction::DivideByReal(product, c),
                Instruction::Double(_) => Instruction::Double(product),
                _ => Instruction::Negate(product),
            });
        }
        product
    }
}

fn register_name(register: usize) -> Ident {
    format_ident!("x{}", register)
}

fn delta_name(register: usize) -> Ident {
    format_ident!("d{}", register)
}

/// The generated bodies of one term's three Taylor-mode kernels.
pub(crate) struct TaylorKernels {
    pub start: TokenStream,
    pub predict: TokenStream,
    pub commit: TokenStream,
}

/// Generates the three kernels of `program` (the term's `f64` locals come from `writer`).
pub(crate) fn generate(program: &TaylorProgram, writer: &KernelWriter<'_>) -> TaylorKernels {
    let reals = writer.statements(&program.real_operands());
    let start = start_body(program, writer);
    let predict = predict_body(program, writer);
    let commit = commit_body(program, writer);
    TaylorKernels {
        start: quote!({ #reals #start }),
        predict: quote!({ let k = order; #reals #predict }),
        commit: quote!({ let k = order; #reals #commit }),
    }
}

/// Order 0: plain evaluation, every slot's $`x_0`$ written to the tape.
fn start_body(program: &TaylorProgram, writer: &KernelWriter<'_>) -> TokenStream {
    let mut start = TokenStream::new();
    for (index, instruction) in program.instructions.iter().enumerate() {
        let x = register_name(index);
        let value = start_value(*instruction, writer);
        start.extend(quote!(let #x: f64 = #value;));
        if let Some(s) = program.slot_of[index] {
            start.extend(quote!(tape[#s] = #x;));
        }
    }
    start
}

/// The order-0 value of one instruction.
fn start_value(instruction: Instruction, writer: &KernelWriter<'_>) -> TokenStream {
    let real = |c: NodeId| writer.reference(c);
    match instruction {
        Instruction::Jet(local) => quote!(jet[#local]),
        Instruction::Add(a, b) => binary(a, quote!(+), b),
        Instruction::Subtract(a, b) => binary(a, quote!(-), b),
        Instruction::Multiply(a, b) => binary(a, quote!(*), b),
        Instruction::Divide(a, b) => binary(a, quote!(/), b),
        Instruction::Square(a) => binary(a, quote!(*), a),
        Instruction::AddReal(a, c) => real_binary(a, quote!(+), real(c)),
        Instruction::SubtractReal(a, c) => real_binary(a, quote!(-), real(c)),
        Instruction::Scale(a, c) => real_binary(a, quote!(*), real(c)),
        Instruction::DivideByReal(a, c) => real_binary(a, quote!(/), real(c)),
        Instruction::SubtractFromReal(a, c) => {
            let (a, c) = (register_name(a), real(c));
            quote!(#c - #a)
        }
        Instruction::Negate(a) => {
            let a = register_name(a);
            quote!(-#a)
        }
        Instruction::Double(a) => binary(a, quote!(+), a),
        Instruction::Reciprocal(a) => {
            let a = register_name(a);
            quote!(1.0 / #a)
        }
    }
}

/// Order $`k`$ with a zero order-$`k`$ jet: the residual's coefficient in `out`, the slots'
/// predicted $`x_k`$ on the tape.
///
/// The recurrences' sums over rows $`1..k-1`$ come first, all in one pass
/// ([`histories`](../../wrinkle_runtime) of the runtime, into `h`); each nonlinear instruction
/// then adds its terms with rows 0 and $`k`$.
fn predict_body(program: &TaylorProgram, writer: &KernelWriter<'_>) -> TokenStream {
    let mut predict = TokenStream::new();
    let pairs = program.history_pairs();
    // The position of each recurrence's sum in `h`, by instruction.
    let mut history = vec![None; program.instructions.len()];
    for (p, &(register, _, _)) in pairs.iter().enumerate() {
        history[register] = Some(p);
    }
    if !pairs.is_empty() {
        let count = pairs.len();
        let pairs = pairs.iter().map(|&(_, x, y)| quote!((#x, #y)));
        predict.extend(quote! {
            let h: [f64; #count] = ::wrinkle_runtime::series::recurrence::histories(
                tape, stride, k, &[#(#pairs),*],
            );
        });
    }
    for (index, instruction) in program.instructions.iter().enumerate() {
        let slot = program.slot_of[index];
        if program.zero_in_prediction[index] {
            if let Some(s) = slot {
                predict.extend(quote!(tape[k * stride + #s] = 0.0;));
            }
            continue;
        }
        let x = register_name(index);
        let value = predict_value(program, index, *instruction, &history, writer);
        predict.extend(quote!(let #x: f64 = #value;));
        if let Some(s) = slot {
            predict.extend(quote!(tape[k * stride + #s] = #x;));
        }
    }
    let outputs = program
        .outputs
        .iter()
        .enumerate()
        .map(|(i, output)| match *output {
            TaylorOutput::Register(r) if !program.zero_in_prediction[r] => {
                let x = register_name(r);
                quote!(out[#i] = #x;)
            }
            _ => quote!(out[#i] = 0.0;),
        });
    predict.extend(quote!(#(#outputs)*));
    predict
}

/// The predicted order-$`k`$ value of instruction `index` (not zero in the prediction):
/// linear operations propagate order-$`k`$ values, nonlinear ones run their recurrence over
/// the tape; `history[index]` is the position of a recurrence's history sum in `h`.
fn predict_value(
    program: &TaylorProgram,
    index: usize,
    instruction: Instruction,
    history: &[Option<usize>],
    writer: &KernelWriter<'_>,
) -> TokenStream {
    let real = |c: NodeId| writer.reference(c);
    let slot = |register: usize| program.slot_of[register];
    let value_of = |r: usize| {
        if program.zero_in_prediction[r] {
            quote!(0.0)
        } else {
            let name = register_name(r);
            quote!(#name)
        }
    };
    let history = |index: usize| {
        let p = history[index].expect("every recurrence has a history sum");
        quote!(h[#p])
    };
    match instruction {
        Instruction::Jet(_) => unreachable!("jet entries are zero in the prediction"),
        Instruction::Add(a, b) => {
            let (a, b) = (value_of(a), value_of(b));
            quote!(#a + #b)
        }
        Instruction::Subtract(a, b) => {
            let (a, b) = (value_of(a), value_of(b));
            quote!(#a - #b)
        }
        Instruction::AddReal(a, _) | Instruction::SubtractReal(a, _) => value_of(a),
        Instruction::SubtractFromReal(a, _) | Instruction::Negate(a) => {
            let a = value_of(a);
            quote!(-#a)
        }
        Instruction::Double(a) => {
            let a = value_of(a);
            quote!(#a + #a)
        }
        Instruction::Scale(a, c) => {
            let (a, c) = (value_of(a), real(c));
            quote!(#a * #c)
        }
        Instruction::DivideByReal(a, c) => {
            let (a, c) = (value_of(a), real(c));
            quote!(#a / #c)
        }
        Instruction::Multiply(a, b) => {
            // (a b)_k = h + a_0 b_k + a_k b_0.
            let h = history(index);
            let terms = [(slot(a).unwrap(), b), (slot(b).unwrap(), a)]
                .into_iter()
                .filter(|&(_, at_k)| !program.zero_in_prediction[at_k])
                .map(|(at_0, at_k)| {
                    let at_k = register_name(at_k);
                    quote!(+ tape[#at_0] * #at_k)
                });
            quote!(#h #(#terms)*)
        }
        Instruction::Square(a) => {
            // (a²)_k = h + 2 a_0 a_k.
            let h = history(index);
            if program.zero_in_prediction[a] {
                h
            } else {
                let (at_0, at_k) = (slot(a).unwrap(), register_name(a));
                quote!(#h + 2.0 * tape[#at_0] * #at_k)
            }
        }
        Instruction::Divide(a, b) => {
            // c = a / b: c_k = (a_k − h − b_k c_0) / b_0, h = Σ_{j=1}^{k−1} b_j c_{k−j}.
            let a = value_of(a);
            let h = history(index);
            let (b0, c0) = (slot(b).unwrap(), slot(index).unwrap());
            let b_k = value_of(b);
            quote!((#a - #h - #b_k * tape[#c0]) / tape[#b0])
        }
        Instruction::Reciprocal(a) => {
            // r = 1 / b: r_k = −(h + b_k r_0) / b_0.
            let h = history(index);
            let (b0, r0) = (slot(a).unwrap(), slot(index).unwrap());
            let b_k = value_of(a);
            quote!(-(#h + #b_k * tape[#r0]) / tape[#b0])
        }
    }
}

/// Commit: the forward-mode derivative at order 0 along the order-$`k`$ jet, added to every
/// slot's $`x_k`$.
fn commit_body(program: &TaylorProgram, writer: &KernelWriter<'_>) -> TokenStream {
    let mut commit = TokenStream::new();
    for (index, instruction) in program.instructions.iter().enumerate() {
        let d = delta_name(index);
        let value = commit_value(program, index, *instruction, writer);
        commit.extend(quote!(let #d: f64 = #value;));
        if let Some(s) = program.slot_of[index] {
            commit.extend(quote!(tape[k * stride + #s] += #d;));
        }
    }
    commit
}

/// The directional derivative at order 0 of instruction `index` along the order-$`k`$ jet.
fn commit_value(
    program: &TaylorProgram,
    index: usize,
    instruction: Instruction,
    writer: &KernelWriter<'_>,
) -> TokenStream {
    let real = |c: NodeId| writer.reference(c);
    let order0 = |register: usize| {
        let s =
            program.slot_of[register].expect("operands of nonlinear operations are on the tape");
        quote!(tape[#s])
    };
    let dn = delta_name;
    match instruction {
        Instruction::Jet(local) => quote!(jet[#local]),
        Instruction::Add(a, b) => {
            let (a, b) = (dn(a), dn(b));
            quote!(#a + #b)
        }
        Instruction::Subtract(a, b) => {
            let (a, b) = (dn(a), dn(b));
            quote!(#a - #b)
        }
        Instruction::AddReal(a, _) | Instruction::SubtractReal(a, _) => {
            let a = dn(a);
            quote!(#a)
        }
        Instruction::SubtractFromReal(a, _) | Instruction::Negate(a) => {
            let a = dn(a);
            quote!(-#a)
        }
        Instruction::Double(a) => {
            let a = dn(a);
            quote!(#a + #a)
        }
        Instruction::Scale(a, c) => {
            let (a, c) = (dn(a), real(c));
            quote!(#a * #c)
        }
        Instruction::DivideByReal(a, c) => {
            let (a, c) = (dn(a), real(c));
            quote!(#a / #c)
        }
        Instruction::Multiply(a, b) => {
            let (da, db, a0, b0) = (dn(a), dn(b), order0(a), order0(b));
            quote!(#a0 * #db + #da * #b0)
        }
        Instruction::Square(a) => {
            let (da, a0) = (dn(a), order0(a));
            quote!(2.0 * #a0 * #da)
        }
        Instruction::Divide(a, b) => {
            let (da, db, b0, c0) = (dn(a), dn(b), order0(b), order0(index));
            quote!((#da - #db * #c0) / #b0)
        }
        Instruction::Reciprocal(a) => {
            let (da, a0, r0) = (dn(a), order0(a), order0(index));
            quote!(-(#da * #r0) / #a0)
        }
    }
}

fn binary(a: usize, operator: TokenStream, b: usize) -> TokenStream {
    let (a, b) = (register_name(a), register_name(b));
    quote!(#a #operator #b)
}

fn real_binary(a: usize, operator: TokenStream, c: TokenStream) -> TokenStream {
    let a = register_name(a);
    quote!(#a #operator #c)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Order-0 values of `instructions` at `jet`, with the constant node `NodeId(n)` worth
    /// `1.25 + 0.5 n`.
    fn values(instructions: &[Instruction], jet: &[f64]) -> Vec<f64> {
        let real = |c: NodeId| 1.25 + 0.5 * c.0 as f64;
        let mut x: Vec<f64> = Vec::new();
        for instruction in instructions {
            let value = match *instruction {
                Instruction::Jet(local) => jet[local],
                Instruction::Add(a, b) => x[a] + x[b],
                Instruction::AddReal(a, c) => x[a] + real(c),
                Instruction::Subtract(a, b) => x[a] - x[b],
                Instruction::SubtractReal(a, c) => x[a] - real(c),
                Instruction::SubtractFromReal(a, c) => real(c) - x[a],
                Instruction::Negate(a) => -x[a],
                Instruction::Double(a) => x[a] + x[a],
                Instruction::Scale(a, c) => x[a] * real(c),
                Instruction::DivideByReal(a, c) => x[a] / real(c),
                Instruction::Multiply(a, b) => x[a] * x[b],
                Instruction::Square(a) => x[a] * x[a],
                Instruction::Divide(a, b) => x[a] / x[b],
                Instruction::Reciprocal(a) => 1.0 / x[a],
            };
            x.push(value);
        }
        x
    }

    fn output_values(program: (&[Instruction], &[TaylorOutput]), jet: &[f64]) -> Vec<f64> {
        let x = values(program.0, jet);
        program
            .1
            .iter()
            .map(|output| match *output {
                TaylorOutput::Register(r) => x[r],
                TaylorOutput::Constant => 0.0,
            })
            .collect()
    }

    const JETS: [[f64; 5]; 3] = [
        [0.3, -1.7, 2.2, 0.9, -0.4],
        [1.1, 0.25, -0.6, 3.0, 1.9],
        [-2.0, 0.8, 0.05, -1.3, 0.7],
    ];

    #[test]
    fn an_operand_shared_by_products_of_one_output_is_factored_out() {
        use Instruction::*;
        // r = 2 (x y) / c + (x z) c' − (w x) + u (x, y, z, w, u = jet entries 0..5).
        let instructions = vec![
            Jet(0),                     // 0 x
            Jet(1),                     // 1 y
            Jet(2),                     // 2 z
            Jet(3),                     // 3 w
            Jet(4),                     // 4 u
            Multiply(0, 1),             // 5 x y
            Double(5),                  // 6
            DivideByReal(6, NodeId(3)), // 7
            Multiply(0, 2),             // 8 x z
            Scale(8, NodeId(5)),        // 9
            Add(7, 9),                  // 10
            Multiply(3, 0),             // 11 w x
            Subtract(10, 11),           // 12
            Add(12, 4),                 // 13
        ];
        let outputs = vec![TaylorOutput::Register(13), TaylorOutput::Constant];
        assert_eq!(tape_cost(&instructions), (4, 3));
        let (factored, factored_outputs) =
            factor_shared_operands(instructions.clone(), outputs.clone());
        assert_eq!(
            tape_cost(&factored),
            (2, 1),
            "x and one cofactor: {factored:?}"
        );
        for jet in &JETS {
            let before = output_values((&instructions, &outputs), jet);
            let after = output_values((&factored, &factored_outputs), jet);
            for (b, a) in before.iter().zip(&after) {
                assert!((a - b).abs() <= 1e-14 * b.abs().max(1.0), "{a} against {b}");
            }
        }
    }

    #[test]
    fn a_factoring_that_would_grow_the_tape_is_not_kept() {
        use Instruction::*;
        // Outputs x y + x z and y z: factoring x needs a slot for y + z, and y and z keep
        // theirs for y z (3 slots → 4).
        let instructions = vec![
            Jet(0),
            Jet(1),
            Jet(2),
            Multiply(0, 1),
            Multiply(0, 2),
            Add(3, 4),
            Multiply(1, 2),
        ];
        let outputs = vec![TaylorOutput::Register(5), TaylorOutput::Register(6)];
        let (kept, kept_outputs) = factor_shared_operands(instructions.clone(), outputs.clone());
        assert_eq!(kept, instructions);
        assert_eq!(kept_outputs, outputs);
    }

    #[test]
    fn products_shared_pairwise_are_factored_one_operand_at_a_time() {
        use Instruction::*;
        // x y + x z + y z + y w: y is in three products, x in two; y first, then nothing is
        // shared: y (x + z + w) + x z.
        let instructions = vec![
            Jet(0),
            Jet(1),
            Jet(2),
            Jet(3),
            Multiply(0, 1),
            Multiply(0, 2),
            Multiply(1, 2),
            Multiply(1, 3),
            Add(4, 5),
            Add(8, 6),
            Add(9, 7),
        ];
        let outputs = vec![TaylorOutput::Register(10)];
        let (factored, factored_outputs) =
            factor_shared_operands(instructions.clone(), outputs.clone());
        assert_eq!(tape_cost(&instructions), (4, 4));
        assert_eq!(tape_cost(&factored), (4, 2), "{factored:?}");
        for jet in &JETS {
            let before = output_values((&instructions, &outputs), jet)[0];
            let after = output_values((&factored, &factored_outputs), jet)[0];
            assert!((after - before).abs() <= 1e-14 * before.abs().max(1.0));
        }
    }
}

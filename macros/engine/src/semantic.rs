//! Validation of a parsed model (collecting every error it can) and lowering to the
//! hash-consed [`ExpressionGraph`].

use std::collections::HashMap;

use syn::Ident;

use crate::graph::{ExpressionGraph, Function, Node, NodeId};
use crate::syntax::{
    BinaryOperator, Expression, Item, MAX_EXPONENT, ModelDeclaration, Quadrature, SpanRange,
    TermDeclaration, available_derivatives, exponent_out_of_range,
};

pub use wrinkle_contract::{Derivative, FieldRole, JetEntry};

/// A runtime parameter.
#[derive(Clone, Debug)]
pub struct Parameter {
    /// Its name (a Rust identifier, the struct field name).
    pub name: Ident,
    /// Its documentation, empty when none was given.
    pub documentation: String,
    /// Declared `[varying]`: the runtime may make it a function of position.
    pub varying: bool,
}

/// One energy term after lowering.
#[derive(Clone, Debug)]
pub struct LoweredTerm {
    /// Term name.
    pub name: String,
    /// Quadrature rule.
    pub quadrature: Quadrature,
    /// The energy density in [`LoweredModel::graph`].
    pub energy: NodeId,
    /// The model jet entries the term depends on, ascending.
    pub jet: Vec<usize>,
}

/// A validated model whose expressions live in one hash-consed graph.
#[derive(Clone, Debug)]
pub struct LoweredModel {
    /// Rust type name.
    pub name: Ident,
    /// Registry name.
    pub registry_name: String,
    /// Doc comment lines.
    pub documentation: Vec<String>,
    /// Non-doc attributes forwarded to the struct.
    pub attributes: Vec<syn::Attribute>,
    /// Field names.
    pub fields: Vec<String>,
    /// Field roles, one per field ([`FieldRole::Other`] when none was declared).
    pub field_roles: Vec<FieldRole>,
    /// Parameters.
    pub parameters: Vec<Parameter>,
    /// Model jet, sorted by field then derivative; `Node::Jet(k)` refers to `jet[k]`.
    pub jet: Vec<JetEntry>,
    /// All expressions.
    pub graph: ExpressionGraph,
    /// The terms in declaration order.
    pub terms: Vec<LoweredTerm>,
    /// The derivation report of a model derived from a microscopic energy
    /// ([`crate::ansatz::derive`]), `None` for a hand-written one.
    pub derivation: Option<String>,
}

impl LoweredModel {
    /// The one-line description: the first non-empty doc line.
    pub fn description(&self) -> String {
        crate::syntax::description(&self.documentation)
    }
}

#[derive(Clone, Copy, Debug)]
enum Binding {
    Field(usize),
    Parameter(usize),
    Let(Option<NodeId>),
    Term,
}

impl Binding {
    fn kind(&self) -> &'static str {
        match self {
            Binding::Field(_) => "a field",
            Binding::Parameter(_) => "a parameter",
            Binding::Let(_) => "a `let` binding",
            Binding::Term => "an energy term",
        }
    }
}

/// Number of derivatives a field has in the jet.
const DERIVATIVES: usize = Derivative::ALL.len();

/// Raw jet code used during lowering: `DERIVATIVES * field + derivative`, so that codes sort
/// by field, then derivative.
fn jet_code(field: usize, derivative: Derivative) -> usize {
    DERIVATIVES * field + derivative.index()
}

/// The field a raw jet code belongs to.
fn field_of_code(code: usize) -> usize {
    code / DERIVATIVES
}

fn jet_entry_of_code(code: usize) -> JetEntry {
    JetEntry {
        field: field_of_code(code),
        derivative: Derivative::ALL[code % DERIVATIVES],
    }
}

struct Lowering {
    graph: ExpressionGraph,
    scope: HashMap<String, Binding>,
    /// Names declared later in the model (for "used before its definition" hints).
    declared_later: HashMap<String, &'static str>,
    fields: Vec<Ident>,
    errors: Vec<syn::Error>,
}

impl Lowering {
    /// The node of `expression`, or `None` after recording why it has none.
    fn lower(&mut self, expression: &Expression) -> Option<NodeId> {
        match expression {
            Expression::Number { value, .. } => Some(self.graph.constant(*value)),
            Expression::Parenthesized { inner, .. } => self.lower(inner),
            Expression::Name(name) => self.lower_name(name),
            Expression::Derivative { base, axis } => self.lower_derivative(expression, base, axis),
            Expression::Negate { operand, .. } => {
                let operand = self.lower(operand)?;
                Some(self.graph.negate(operand))
            }
            Expression::Binary { operator, lhs, rhs } => self.lower_binary(*operator, lhs, rhs),
            Expression::Power {
                base,
                exponent,
                exponent_span,
            } => self.lower_power(expression, base, *exponent, exponent_span),
            Expression::Call {
                function, argument, ..
            } => self.lower_call(expression, function, argument),
        }
    }

    /// A field's value, a parameter or a `let`.
    fn lower_name(&mut self, name: &Ident) -> Option<NodeId> {
        match self.scope.get(&name.to_string()).copied() {
            Some(Binding::Field(field)) => Some(self.graph.jet(jet_code(field, Derivative::Value))),
            Some(Binding::Parameter(index)) => Some(self.graph.parameter(index)),
            Some(Binding::Let(value)) => value,
            Some(Binding::Term) => {
                self.errors.push(syn::Error::new(
                    name.span(),
                    format!(
                        "`{name}` is an energy term, not a value: terms cannot be referenced (use a `let`)"
                    ),
                ));
                None
            }
            None => {
                self.unknown(name);
                None
            }
        }
    }

    /// `base.axis`: a derivative of a field, with the contract's spelling of the derivative.
    fn lower_derivative(
        &mut self,
        expression: &Expression,
        base: &Ident,
        axis: &Ident,
    ) -> Option<NodeId> {
        match self.scope.get(&base.to_string()).copied() {
            Some(Binding::Field(field)) => {
                let derivative = Derivative::from_name(&axis.to_string())
                    .filter(|derivative| derivative.order() > 0);
                if let Some(derivative) = derivative {
                    return Some(self.graph.jet(jet_code(field, derivative)));
                }
                self.errors.push(syn::Error::new(
                    axis.span(),
                    format!(
                        "unsupported derivative `{base}.{axis}`: the derivatives available are {}",
                        available_derivatives(base)
                    ),
                ));
            }
            Some(binding) => {
                self.errors.push(expression.span_range().error(format!(
                    "unsupported derivative: `{base}` is {}, and only fields have derivatives",
                    binding.kind()
                )));
            }
            None => self.unknown(base),
        }
        None
    }

    /// `lhs op rhs`; both sides are lowered (and their errors recorded) before either is used.
    fn lower_binary(
        &mut self,
        operator: BinaryOperator,
        lhs: &Expression,
        rhs: &Expression,
    ) -> Option<NodeId> {
        let a = self.lower(lhs);
        let b = self.lower(rhs);
        let (a, b) = (a?, b?);
        Some(match operator {
            BinaryOperator::Add => self.graph.add(a, b),
            BinaryOperator::Subtract => self.graph.subtract(a, b),
            BinaryOperator::Multiply => self.graph.multiply(a, b),
            BinaryOperator::Divide => {
                if self.graph.constant_value(b) == Some(0.0) {
                    self.errors
                        .push(rhs.span_range().error("division by the constant zero"));
                    return None;
                }
                self.graph.divide(a, b)
            }
        })
    }

    /// `base^exponent`. A power of a power is one power whose exponent is the product of the
    /// two: it must stay in the supported range too (the error points at the outer exponent).
    fn lower_power(
        &mut self,
        expression: &Expression,
        base: &Expression,
        exponent: i32,
        exponent_span: &SpanRange,
    ) -> Option<NodeId> {
        let lowered = self.lower(base)?;
        if exponent < 0 && self.graph.constant_value(lowered) == Some(0.0) {
            self.errors.push(
                expression
                    .span_range()
                    .error("negative power of the constant zero"),
            );
            return None;
        }
        let power = self.graph.power(lowered, exponent);
        if let Node::Power(_, combined) = self.graph.node(power)
            && combined.unsigned_abs() > MAX_EXPONENT.unsigned_abs()
        {
            self.errors
                .push(exponent_span.error(exponent_out_of_range(format_args!(
                    "this power of a power has the exponent {combined} (exponents multiply), which"
                ))));
            return None;
        }
        Some(power)
    }

    /// `function(argument)`: a known function of a parameter-only argument.
    fn lower_call(
        &mut self,
        expression: &Expression,
        function: &Ident,
        argument: &Expression,
    ) -> Option<NodeId> {
        let lowered = self.lower(argument);
        let Some(known) = Function::from_name(&function.to_string()) else {
            self.errors.push(syn::Error::new(
                function.span(),
                format!(
                    "unknown function `{function}`: expected one of `sqrt`, `sin`, `cos`, `exp`, `ln`"
                ),
            ));
            return None;
        };
        let lowered = lowered?;
        if self.graph.depends_on_jet(lowered) {
            let field = field_of_code(self.graph.jet_dependencies(&[lowered])[0]);
            self.errors.push(expression.span_range().error(format!(
                "`{function}` can only be applied to parameters and constants, but its argument depends on the field `{}` (functions are evaluated in f64, outside the differentiated kernels)",
                self.fields[field]
            )));
            return None;
        }
        Some(self.graph.apply(known, lowered))
    }

    fn unknown(&mut self, name: &Ident) {
        let message = match self.declared_later.get(&name.to_string()) {
            Some(kind) => format!(
                "unknown identifier `{name}`: {kind} of that name is declared later; declare it before use"
            ),
            None => format!(
                "unknown identifier `{name}`: not a field, parameter or earlier `let` of this model"
            ),
        };
        self.errors.push(syn::Error::new(name.span(), message));
    }

    /// Lowers the `let`s and terms in order; the terms that lower, depend on the jet and have
    /// a fresh name, with their energy nodes.
    fn lower_items<'a>(&mut self, items: &'a [Item]) -> Vec<(&'a TermDeclaration, NodeId)> {
        let mut terms = Vec::new();
        for item in items {
            match item {
                Item::Let(binding) => {
                    let value = self.lower(&binding.value);
                    declare_in(self, &binding.name, Binding::Let(value));
                }
                Item::Term(term) => {
                    let value = self.lower(&term.value);
                    let fresh = declare_in(self, &term.name, Binding::Term);
                    let Some(value) = value else { continue };
                    if !self.graph.depends_on_jet(value) {
                        self.errors.push(syn::Error::new(
                            term.name.span(),
                            format!(
                                "energy term `{}` depends on no field: a constant energy has no residual or tangent",
                                term.name
                            ),
                        ));
                    } else if fresh {
                        terms.push((term, value));
                    }
                }
                Item::Average(average) => {
                    // The derivation replaces every derived term before lowering; one left here
                    // has no microscopic energy or no ansatz to come from.
                    declare_in(self, &average.name, Binding::Term);
                    self.errors.push(syn::Error::new(
                        average.keyword,
                        "`average(…)` derives a term from a `microscopic` energy with an `ansatz`, and this model declares no `microscopic` energy",
                    ));
                }
            }
        }
        terms
    }
}

/// Validates a parsed model and lowers it, returning every error found (combined).
pub fn lower_model(declaration: &ModelDeclaration) -> Result<LoweredModel, syn::Error> {
    let mut errors: Vec<syn::Error> = declaration.deferred_errors.clone();
    let mut scope: HashMap<String, Binding> = HashMap::new();
    if declaration.fields.is_empty() {
        errors.push(syn::Error::new(
            declaration.fields_keyword,
            "a model needs at least one field (`fields: w;`)",
        ));
    }
    for (index, field) in declaration.fields.iter().enumerate() {
        declare(&mut scope, &field.name, Binding::Field(index), &mut errors);
    }
    let field_roles = validate_roles(declaration, &mut errors);
    validate_parameter_attributes(declaration, &mut errors);
    for (index, parameter) in declaration.parameters.iter().enumerate() {
        let binding = Binding::Parameter(index);
        declare(&mut scope, &parameter.name, binding, &mut errors);
    }
    let mut lowering = Lowering {
        graph: ExpressionGraph::new(),
        scope,
        declared_later: declared_later(&declaration.items),
        fields: declaration.fields.iter().map(|f| f.name.clone()).collect(),
        errors,
    };
    let raw_terms = lowering.lower_items(&declaration.items);
    let mut errors = lowering.errors;
    check_model(declaration, &lowering.graph, &raw_terms, &mut errors);
    if let Some(combined) = combine(errors) {
        return Err(combined);
    }
    let (jet, graph, terms) = renumber_jet(&lowering.graph, &raw_terms);
    Ok(LoweredModel {
        name: declaration.name.clone(),
        registry_name: declaration.registry_name.value(),
        documentation: declaration.documentation.clone(),
        attributes: declaration.attributes.clone(),
        fields: declaration
            .fields
            .iter()
            .map(|field| field.name.to_string())
            .collect(),
        field_roles,
        parameters: declaration
            .parameters
            .iter()
            .map(|parameter| Parameter {
                name: parameter.name.clone(),
                documentation: parameter
                    .documentation
                    .as_ref()
                    .map(|text| text.value())
                    .unwrap_or_default(),
                varying: parameter.attribute.is_some(),
            })
            .collect(),
        jet,
        graph,
        terms,
        derivation: None,
    })
}

/// Every `let` and term name with its kind, for "declared later" hints.
fn declared_later(items: &[Item]) -> HashMap<String, &'static str> {
    items
        .iter()
        .map(|item| match item {
            Item::Let(binding) => (binding.name.to_string(), "a `let`"),
            Item::Term(term) => (term.name.to_string(), "an energy term"),
            Item::Average(average) => (average.name.to_string(), "an energy term"),
        })
        .collect()
}

/// Model-level checks: at least one `energy` term and, when nothing else is wrong, every field
/// used by some term.
fn check_model(
    declaration: &ModelDeclaration,
    graph: &ExpressionGraph,
    raw_terms: &[(&TermDeclaration, NodeId)],
    errors: &mut Vec<syn::Error>,
) {
    let has_terms = declaration
        .items
        .iter()
        .any(|item| matches!(item, Item::Term(_) | Item::Average(_)));
    if !has_terms {
        errors.push(syn::Error::new(
            declaration.name.span(),
            format!(
                "model `{}` declares no `energy` term (add e.g. `energy stretching = ...;`)",
                declaration.name
            ),
        ));
    }
    if !errors.is_empty() {
        return;
    }
    let roots: Vec<NodeId> = raw_terms.iter().map(|(_, value)| *value).collect();
    let used_codes = graph.jet_dependencies(&roots);
    for (index, field) in declaration.fields.iter().map(|f| &f.name).enumerate() {
        if !used_codes.iter().any(|&code| field_of_code(code) == index) {
            errors.push(syn::Error::new(
                field.span(),
                format!("field `{field}` is used by no energy term"),
            ));
        }
    }
}

/// Renumbers the jet densely (model jet index = rank of the raw code among those the terms
/// use) and copies the terms into a fresh graph over those indices.
fn renumber_jet(
    graph: &ExpressionGraph,
    raw_terms: &[(&TermDeclaration, NodeId)],
) -> (Vec<JetEntry>, ExpressionGraph, Vec<LoweredTerm>) {
    let roots: Vec<NodeId> = raw_terms.iter().map(|(_, value)| *value).collect();
    let used_codes = graph.jet_dependencies(&roots);
    let jet: Vec<JetEntry> = used_codes.iter().map(|&c| jet_entry_of_code(c)).collect();
    let rank = |code: usize| {
        used_codes
            .binary_search(&code)
            .expect("every jet code reachable from a term is in the model jet")
    };
    let mut final_graph = ExpressionGraph::new();
    let mut memo = HashMap::new();
    let terms = raw_terms
        .iter()
        .map(|(term, value)| {
            let energy = final_graph.import(graph, *value, &mut memo, &rank);
            LoweredTerm {
                name: term.name.to_string(),
                quadrature: term.quadrature,
                energy,
                jet: final_graph.jet_dependencies(&[energy]),
            }
        })
        .collect();
    (jet, final_graph, terms)
}

/// The declared role of every field; an unknown role name or a role declared twice (other than
/// `other`) is an error at the role's token.
fn validate_roles(declaration: &ModelDeclaration, errors: &mut Vec<syn::Error>) -> Vec<FieldRole> {
    let mut roles = Vec::with_capacity(declaration.fields.len());
    let mut seen: HashMap<FieldRole, String> = HashMap::new();
    for field in &declaration.fields {
        let Some(role_name) = &field.role else {
            roles.push(FieldRole::Other);
            continue;
        };
        let Some(role) = FieldRole::from_name(&role_name.to_string()) else {
            let expected: Vec<String> = FieldRole::ALL
                .iter()
                .map(|role| format!("`{}`", role.name()))
                .collect();
            errors.push(syn::Error::new(
                role_name.span(),
                format!(
                    "unknown field role `{role_name}`: expected one of {}",
                    expected.join(", ")
                ),
            ));
            roles.push(FieldRole::Other);
            continue;
        };
        if role != FieldRole::Other {
            if let Some(previous) = seen.get(&role) {
                errors.push(syn::Error::new(
                    role_name.span(),
                    format!(
                        "field role `{role_name}` is already the role of field `{previous}`: each role (except `other`) names one field"
                    ),
                ));
            } else {
                seen.insert(role, field.name.to_string());
            }
        }
        roles.push(role);
    }
    roles
}

/// The one parameter attribute is `varying`: anything else is an error at the attribute.
fn validate_parameter_attributes(declaration: &ModelDeclaration, errors: &mut Vec<syn::Error>) {
    for parameter in &declaration.parameters {
        if let Some(attribute) = &parameter.attribute
            && attribute != VARYING
        {
            errors.push(syn::Error::new(
                attribute.span(),
                format!(
                    "unknown parameter attribute `{attribute}`: the only one is `{VARYING}` (a parameter the runtime may make a function of position)"
                ),
            ));
        }
    }
}

/// The parameter attribute of a function of position.
pub const VARYING: &str = "varying";

fn declare_in(lowering: &mut Lowering, name: &Ident, binding: Binding) -> bool {
    declare(&mut lowering.scope, name, binding, &mut lowering.errors)
}

fn declare(
    scope: &mut HashMap<String, Binding>,
    name: &Ident,
    binding: Binding,
    errors: &mut Vec<syn::Error>,
) -> bool {
    let key = name.to_string();
    if let Some(previous) = scope.get(&key) {
        errors.push(syn::Error::new(
            name.span(),
            format!(
                "duplicate name `{name}`: already declared as {}; fields, parameters, lets and terms share one namespace",
                previous.kind()
            ),
        ));
        false
    } else {
        scope.insert(key, binding);
        true
    }
}

/// Combines errors into one `syn::Error` (reported as several diagnostics).
pub fn combine(errors: Vec<syn::Error>) -> Option<syn::Error> {
    let mut iterator = errors.into_iter();
    let mut first = iterator.next()?;
    for error in iterator {
        first.combine(error);
    }
    Some(first)
}

//! From the microscopic energy's expressions to the normal form: every field replaced by its
//! harmonic expansion (with the exact derivative rule), every product multiplied out and
//! truncated. Anything that is not a polynomial in the fields — a division by an expression of
//! the fields, a negative power of one, a function of one — is an error at its tokens.

use std::collections::BTreeMap;

use syn::Ident;

use super::coefficient::{Atom, Complex, ParameterPolynomial};
use super::polynomial::{
    Polynomial, Symbol, TooLarge, Truncation, Variable, Wave, harmonic_derivative,
};
use super::rational::Rational;
use super::resolve::{Ansatz, Microscopic, MicroscopicName};
use crate::graph::Function;
use crate::syntax::{BinaryOperator, Expression, SpanRange};

/// What an expression is: an expression of the parameters only, or a polynomial of the fields'
/// harmonic coefficients.
#[derive(Clone, Debug)]
pub enum Value {
    /// Parameters and constants only.
    Parameter(ParameterPolynomial),
    /// Depends on the fields.
    Series(Polynomial),
}

impl Value {
    fn into_series(self) -> Polynomial {
        match self {
            Value::Parameter(p) => Polynomial::constant(Complex::real(p)),
            Value::Series(series) => series,
        }
    }
}

/// The message of an expression that is not a polynomial of the fields.
fn not_polynomial(what: &str) -> String {
    format!(
        "{what}: an ansatz derivation needs an energy that is a polynomial in the fields and their derivatives"
    )
}

/// The derivatives a microscopic energy may use, by spelling: `(p, q)` derivatives along X, Y.
pub fn derivative_of_spelling(spelling: &str) -> Option<(u8, u8)> {
    Some(match spelling {
        "x" => (1, 0),
        "y" => (0, 1),
        "xx" => (2, 0),
        "xy" => (1, 1),
        "yy" => (0, 2),
        _ => return None,
    })
}

/// Expands the expressions of one microscopic energy for one derived term.
pub struct Expander<'a> {
    /// The microscopic namespace.
    pub microscopic: &'a Microscopic<'a>,
    /// The ansatz.
    pub ansatz: &'a Ansatz<'a>,
    /// The carrier wave.
    pub wave: &'a Wave,
    /// The truncation and size bound.
    pub truncation: Truncation,
    /// `let`s replaced by averaged quantities: name → their harmonic coefficients' symbols.
    pub averaged: BTreeMap<String, Polynomial>,
    /// Values of `let`s already expanded.
    memo: BTreeMap<String, Option<Value>>,
    /// Errors, at the offending tokens.
    pub errors: Vec<syn::Error>,
    /// A product exceeded the size bound.
    pub too_large: Option<TooLarge>,
}

impl<'a> Expander<'a> {
    /// An expander with no averaged `let`s.
    pub fn new(
        microscopic: &'a Microscopic<'a>,
        ansatz: &'a Ansatz<'a>,
        wave: &'a Wave,
        truncation: Truncation,
    ) -> Self {
        Self {
            microscopic,
            ansatz,
            wave,
            truncation,
            averaged: BTreeMap::new(),
            memo: BTreeMap::new(),
            errors: Vec::new(),
            too_large: None,
        }
    }

    /// The value of `expression`, written at item position `position` (the `let`s before it are
    /// visible); `None` after recording an error.
    pub fn expand(&mut self, expression: &Expression, position: usize) -> Option<Value> {
        match expression {
            Expression::Number { value, span } => {
                let exact = Rational::from_decimal(&format!("{value}"));
                if exact.is_none() {
                    self.errors.push(syn::Error::new(
                        *span,
                        "this number has no exact fraction of 128-bit integers: the derivation computes with exact fractions",
                    ));
                }
                Some(Value::Parameter(ParameterPolynomial::constant(exact?)))
            }
            Expression::Parenthesized { inner, .. } => self.expand(inner, position),
            Expression::Name(name) => self.expand_name(name, position),
            Expression::Derivative { base, axis } => self.expand_derivative(expression, base, axis),
            Expression::Negate { operand, .. } => Some(match self.expand(operand, position)? {
                Value::Parameter(p) => Value::Parameter(p.negated()),
                Value::Series(s) => Value::Series(s.scaled(&Complex::constant(-Rational::ONE))),
            }),
            Expression::Binary { operator, lhs, rhs } => {
                let left = self.expand(lhs, position);
                let right = self.expand(rhs, position);
                self.combine(*operator, left?, right?, rhs)
            }
            Expression::Power { base, exponent, .. } => {
                let base_value = self.expand(base, position)?;
                self.power(expression, base_value, *exponent)
            }
            Expression::Call {
                function, argument, ..
            } => {
                let argument_value = self.expand(argument, position)?;
                self.call(expression, function, argument_value)
            }
        }
    }

    fn expand_name(&mut self, name: &Ident, position: usize) -> Option<Value> {
        let key = name.to_string();
        if let Some(series) = self.averaged.get(&key) {
            return Some(Value::Series(series.clone()));
        }
        match self.microscopic.names.get(&key).copied() {
            Some(MicroscopicName::Field(field)) => Some(Value::Series(self.jet(field, (0, 0)))),
            Some(MicroscopicName::Parameter(k)) => {
                Some(Value::Parameter(ParameterPolynomial::parameter(k)))
            }
            Some(MicroscopicName::Let {
                position: declared,
                value,
            }) if declared < position => {
                if let Some(known) = self.memo.get(&key) {
                    return known.clone();
                }
                let expanded = self.expand(value, declared).map(|value| match value {
                    Value::Parameter(p) if p.as_constant().is_none() && !p.is_atom() => {
                        Value::Parameter(ParameterPolynomial::atom(Atom::Named {
                            name: key.clone(),
                            definition: p,
                        }))
                    }
                    other => other,
                });
                self.memo.insert(key, expanded.clone());
                expanded
            }
            Some(MicroscopicName::Let { .. }) => {
                self.error(name, format!("unknown identifier `{name}`: a `let` of that name is declared later; declare it before use"))
            }
            Some(MicroscopicName::Term { .. }) => self.error(
                name,
                format!("`{name}` is an energy term, not a value: terms cannot be referenced (use a `let`)"),
            ),
            None => self.error(
                name,
                format!(
                    "unknown identifier `{name}`: not a field, parameter or earlier `let` of the microscopic energy `{}`",
                    self.microscopic.declaration.name
                ),
            ),
        }
    }

    fn error(&mut self, at: &Ident, message: String) -> Option<Value> {
        self.errors.push(syn::Error::new(at.span(), message));
        None
    }

    fn expand_derivative(
        &mut self,
        expression: &Expression,
        base: &Ident,
        axis: &Ident,
    ) -> Option<Value> {
        match self.microscopic.names.get(&base.to_string()).copied() {
            Some(MicroscopicName::Field(field)) => match derivative_of_spelling(&axis.to_string()) {
                Some(derivative) => Some(Value::Series(self.jet(field, derivative))),
                None => self.error(
                    axis,
                    format!(
                        "unsupported derivative `{base}.{axis}`: a microscopic energy may use `{base}.x`, `{base}.y`, `{base}.xx`, `{base}.xy` and `{base}.yy`"
                    ),
                ),
            },
            Some(_) => {
                self.errors.push(expression.span_range().error(format!(
                    "unsupported derivative: `{base}` is not a field, and only fields have derivatives"
                )));
                None
            }
            None => self.expand_name(base, usize::MAX).and(None),
        }
    }

    /// $`\partial^\alpha f`$ of microscopic field `field`: the sum over its harmonics $`m`$ of
    /// $`(\partial^\alpha f)_m e^{imQ\,\mathbf e\cdot\mathbf X}`$, both signs of $`m \ne 0`$.
    fn jet(&self, field: usize, derivative: (u8, u8)) -> Polynomial {
        let variable = Variable::Envelope(field);
        let mut series = Polynomial::zero();
        for part in &self.ansatz.parts[field] {
            let m = part.harmonic;
            series = series.plus(&harmonic_derivative(variable, m, derivative, self.wave));
            if m != 0 {
                series = series.plus(&harmonic_derivative(variable, -m, derivative, self.wave));
            }
        }
        series
    }

    fn product(&mut self, left: &Polynomial, right: &Polynomial) -> Option<Polynomial> {
        match left.times(right, &self.truncation) {
            Ok(product) => Some(product),
            Err(too_large) => {
                self.too_large = Some(too_large);
                None
            }
        }
    }

    fn combine(
        &mut self,
        operator: BinaryOperator,
        left: Value,
        right: Value,
        rhs: &Expression,
    ) -> Option<Value> {
        use BinaryOperator::*;
        match (operator, left, right) {
            (Add, Value::Parameter(a), Value::Parameter(b)) => Some(Value::Parameter(a.plus(&b))),
            (Subtract, Value::Parameter(a), Value::Parameter(b)) => {
                Some(Value::Parameter(a.plus(&b.negated())))
            }
            (Multiply, Value::Parameter(a), Value::Parameter(b)) => {
                Some(Value::Parameter(a.times(&b)))
            }
            (Add, a, b) => Some(Value::Series(a.into_series().plus(&b.into_series()))),
            (Subtract, a, b) => Some(Value::Series(
                a.into_series()
                    .plus(&b.into_series().scaled(&Complex::constant(-Rational::ONE))),
            )),
            (Multiply, Value::Parameter(p), Value::Series(s))
            | (Multiply, Value::Series(s), Value::Parameter(p)) => {
                Some(Value::Series(s.scaled(&Complex::real(p))))
            }
            (Multiply, Value::Series(a), Value::Series(b)) => {
                self.product(&a, &b).map(Value::Series)
            }
            (Divide, numerator, Value::Parameter(divisor)) => {
                let reciprocal = match divisor.as_constant() {
                    Some(value) if value.is_zero() => {
                        self.errors
                            .push(rhs.span_range().error("division by the constant zero"));
                        return None;
                    }
                    Some(value) => ParameterPolynomial::constant(value.reciprocal()),
                    None => ParameterPolynomial::atom(Atom::Reciprocal(divisor)),
                };
                Some(match numerator {
                    Value::Parameter(p) => Value::Parameter(p.times(&reciprocal)),
                    Value::Series(s) => Value::Series(s.scaled(&Complex::real(reciprocal))),
                })
            }
            (Divide, _, Value::Series(_)) => {
                self.errors.push(
                    rhs.span_range()
                        .error(not_polynomial("division by an expression of the fields")),
                );
                None
            }
        }
    }

    fn power(&mut self, expression: &Expression, base: Value, exponent: i32) -> Option<Value> {
        match base {
            Value::Parameter(p) if exponent >= 0 => {
                Some(Value::Parameter(p.power(exponent.unsigned_abs())))
            }
            Value::Parameter(p) => {
                let reciprocal = match p.as_constant() {
                    Some(value) if !value.is_zero() => {
                        ParameterPolynomial::constant(value.reciprocal())
                    }
                    Some(_) => {
                        self.errors.push(
                            expression
                                .span_range()
                                .error("negative power of the constant zero"),
                        );
                        return None;
                    }
                    None => ParameterPolynomial::atom(Atom::Reciprocal(p)),
                };
                Some(Value::Parameter(reciprocal.power(exponent.unsigned_abs())))
            }
            Value::Series(s) if exponent >= 0 => {
                match s.power(exponent.unsigned_abs(), &self.truncation) {
                    Ok(power) => Some(Value::Series(power)),
                    Err(too_large) => {
                        self.too_large = Some(too_large);
                        None
                    }
                }
            }
            Value::Series(_) => {
                let range = match expression {
                    Expression::Power { exponent_span, .. } => *exponent_span,
                    _ => expression.span_range(),
                };
                self.errors.push(range.error(not_polynomial(
                    "negative power of an expression of the fields",
                )));
                None
            }
        }
    }

    fn call(
        &mut self,
        expression: &Expression,
        function: &Ident,
        argument: Value,
    ) -> Option<Value> {
        let Some(known) = Function::from_name(&function.to_string()) else {
            return self.error(
                function,
                format!("unknown function `{function}`: expected one of `sqrt`, `sin`, `cos`, `exp`, `ln`"),
            );
        };
        match argument {
            Value::Parameter(p) => Some(Value::Parameter(ParameterPolynomial::atom(Atom::Apply(
                known, p,
            )))),
            Value::Series(_) => {
                self.errors
                    .push(expression.span_range().error(not_polynomial(&format!(
                        "`{function}` of an expression of the fields"
                    ))));
                None
            }
        }
    }
}

/// A parameter expression of the derived model (the ansatz's wavenumber and direction): names
/// are the derived model's parameters (`parameter_names`, in order).
pub fn parameter_expression(
    expression: &Expression,
    parameter_names: &[String],
    errors: &mut Vec<syn::Error>,
) -> Option<ParameterPolynomial> {
    let recurse = |inner: &Expression, errors: &mut Vec<syn::Error>| {
        parameter_expression(inner, parameter_names, errors)
    };
    let range = |e: &Expression| -> SpanRange { e.span_range() };
    match expression {
        Expression::Number { value, span } => match Rational::from_decimal(&format!("{value}")) {
            Some(exact) => Some(ParameterPolynomial::constant(exact)),
            None => {
                errors.push(syn::Error::new(
                    *span,
                    "this number has no exact fraction of 128-bit integers",
                ));
                None
            }
        },
        Expression::Name(name) => match parameter_names.iter().position(|p| name == p) {
            Some(k) => Some(ParameterPolynomial::parameter(k)),
            None => {
                errors.push(syn::Error::new(
                    name.span(),
                    format!("`{name}` is not a parameter of the model: the ansatz's wavenumber and direction are expressions of parameters"),
                ));
                None
            }
        },
        Expression::Parenthesized { inner, .. } => recurse(inner, errors),
        Expression::Negate { operand, .. } => Some(recurse(operand, errors)?.negated()),
        Expression::Binary { operator, lhs, rhs } => {
            let (a, b) = (recurse(lhs, errors), recurse(rhs, errors));
            let (a, b) = (a?, b?);
            Some(match operator {
                BinaryOperator::Add => a.plus(&b),
                BinaryOperator::Subtract => a.plus(&b.negated()),
                BinaryOperator::Multiply => a.times(&b),
                BinaryOperator::Divide => match b.as_constant() {
                    Some(value) if !value.is_zero() => a.scaled(value.reciprocal()),
                    Some(_) => {
                        errors.push(range(rhs).error("division by the constant zero"));
                        return None;
                    }
                    None => a.times(&ParameterPolynomial::atom(Atom::Reciprocal(b))),
                },
            })
        }
        Expression::Power { base, exponent, .. } => {
            let base = recurse(base, errors)?;
            if *exponent >= 0 {
                Some(base.power(exponent.unsigned_abs()))
            } else {
                Some(
                    ParameterPolynomial::atom(Atom::Reciprocal(base))
                        .power(exponent.unsigned_abs()),
                )
            }
        }
        Expression::Call {
            function, argument, ..
        } => {
            let argument = recurse(argument, errors)?;
            match Function::from_name(&function.to_string()) {
                Some(known) => Some(ParameterPolynomial::atom(Atom::Apply(known, argument))),
                None => {
                    errors.push(syn::Error::new(
                        function.span(),
                        format!("unknown function `{function}`"),
                    ));
                    None
                }
            }
        }
        Expression::Derivative { .. } => {
            errors.push(range(expression).error("the ansatz's wavenumber and direction are expressions of parameters, not of fields"));
            None
        }
    }
}

/// The symbol of an averaged quantity's harmonic coefficient, undifferentiated.
pub fn averaged_symbol(index: usize, harmonic: i32) -> Polynomial {
    Polynomial::symbol(Symbol::new(Variable::Average(index), harmonic))
}

//! A derived term back in the DSL: its polynomial as an [`Expression`] the ordinary pipeline
//! lowers like a hand-written term (so nothing downstream can tell the difference), and as
//! text for the model's derivation report (`wrinkle models --show`).

use proc_macro2::Span;
use syn::Ident;

use super::coefficient::{Atom, ParameterMonomial, ParameterPolynomial};
use super::polynomial::{Monomial, Polynomial, Symbol, Variable};
use super::rational::Rational;
use super::term::AveragedPart;
use crate::syntax::{BinaryOperator, Expression, SpanRange};

/// The DSL spelling of a derivative multi-index (`x`, `xy`, …; empty for the value).
pub fn derivative_spelling(derivative: (u8, u8)) -> String {
    let (p, q) = derivative;
    format!(
        "{}{}",
        "x".repeat(usize::from(p)),
        "y".repeat(usize::from(q))
    )
}

/// The names a derived polynomial refers to.
pub struct Names<'a> {
    /// The derived model's fields.
    pub fields: &'a [String],
    /// The derived model's parameters.
    pub parameters: &'a [String],
    /// The averaged parts of the term.
    pub parts: &'a [AveragedPart],
}

/// Builds [`Expression`]s at one span.
pub struct Emitter<'a> {
    /// The names.
    pub names: Names<'a>,
    /// Where every emitted token points (the derived term's `average`).
    pub span: Span,
}

impl Emitter<'_> {
    fn number(&self, value: f64) -> Expression {
        Expression::Number {
            value,
            span: self.span,
        }
    }

    fn name(&self, name: &str) -> Expression {
        Expression::Name(Ident::new(name, self.span))
    }

    fn binary(&self, operator: BinaryOperator, lhs: Expression, rhs: Expression) -> Expression {
        Expression::Binary {
            operator,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        }
    }

    fn parenthesized(&self, inner: Expression) -> Expression {
        Expression::Parenthesized {
            inner: Box::new(inner),
            span: self.span,
        }
    }

    fn power(&self, base: Expression, exponent: i32) -> Expression {
        if exponent == 1 {
            return base;
        }
        Expression::Power {
            base: Box::new(base),
            exponent,
            exponent_span: SpanRange::single(self.span),
        }
    }

    fn product(&self, factors: Vec<Expression>) -> Expression {
        let mut factors = factors.into_iter();
        let first = factors.next().unwrap_or_else(|| self.number(1.0));
        factors.fold(first, |product, factor| {
            self.binary(BinaryOperator::Multiply, product, factor)
        })
    }

    fn sum(&self, terms: Vec<Expression>) -> Expression {
        let mut terms = terms.into_iter();
        let first = terms.next().unwrap_or_else(|| self.number(0.0));
        let sum = terms.fold(first, |sum, term| {
            self.binary(BinaryOperator::Add, sum, term)
        });
        self.parenthesized(sum)
    }

    fn atom(&self, atom: &Atom) -> Expression {
        match atom {
            Atom::Parameter(k) => self.name(&self.names.parameters[*k]),
            Atom::Named { definition, .. } => self.parameters(definition),
            Atom::Reciprocal(inner) => self.power(self.parameters(inner), -1),
            Atom::Apply(function, inner) => Expression::Call {
                function: Ident::new(function.name(), self.span),
                argument: Box::new(self.parameters(inner)),
                close: self.span,
            },
        }
    }

    fn parameter_monomial(&self, monomial: &ParameterMonomial, value: Rational) -> Expression {
        let mut factors = vec![self.number(value.to_f64())];
        for (atom, power) in &monomial.0 {
            factors.push(self.power(self.atom(atom), *power as i32));
        }
        self.product(factors)
    }

    /// A parameter polynomial, parenthesised.
    pub fn parameters(&self, polynomial: &ParameterPolynomial) -> Expression {
        let terms = polynomial
            .0
            .iter()
            .map(|(monomial, value)| self.parameter_monomial(monomial, *value))
            .collect();
        self.sum(terms)
    }

    fn symbol(&self, symbol: &Symbol) -> Expression {
        match symbol.variable {
            Variable::Field(k) => {
                let name = &self.names.fields[k];
                let spelling = derivative_spelling(symbol.derivative);
                if spelling.is_empty() {
                    self.name(name)
                } else {
                    Expression::Derivative {
                        base: Ident::new(name, self.span),
                        axis: Ident::new(&spelling, self.span),
                    }
                }
            }
            Variable::AveragePart(k) => self.polynomial(&self.names.parts[k].definition),
            Variable::Envelope(_) | Variable::Average(_) => {
                unreachable!("a derived polynomial holds real symbols only")
            }
        }
    }

    /// A real polynomial of the derived fields and averaged parts, parenthesised.
    pub fn polynomial(&self, polynomial: &Polynomial) -> Expression {
        let terms = polynomial
            .0
            .iter()
            .map(|(monomial, value)| {
                let mut factors = vec![self.parameters(&value.real)];
                for (symbol, power) in grouped(monomial) {
                    factors.push(self.power(self.symbol(&symbol), power));
                }
                self.product(factors)
            })
            .collect();
        self.sum(terms)
    }
}

/// The distinct symbols of a monomial with their powers, in order.
fn grouped(monomial: &Monomial) -> Vec<(Symbol, i32)> {
    let mut groups: Vec<(Symbol, i32)> = Vec::new();
    for symbol in &monomial.0 {
        match groups.last_mut() {
            Some((last, power)) if last == symbol => *power += 1,
            _ => groups.push((*symbol, 1)),
        }
    }
    groups
}

/// Text of derived polynomials and of the microscopic energy, in DSL syntax.
pub mod text {
    use super::*;

    fn atom(names: &Names<'_>, atom: &Atom) -> String {
        match atom {
            Atom::Parameter(k) => names.parameters[*k].clone(),
            Atom::Named { name, .. } => name.clone(),
            Atom::Reciprocal(inner) => format!("1/{}", factor(names, inner)),
            Atom::Apply(function, inner) => {
                format!("{}({})", function.name(), parameters(names, inner))
            }
        }
    }

    /// A parameter polynomial as a factor: parenthesised when it is a sum.
    fn factor(names: &Names<'_>, polynomial: &ParameterPolynomial) -> String {
        let text = parameters(names, polynomial);
        if polynomial.term_count() > 1 {
            format!("({text})")
        } else {
            text
        }
    }

    /// `value * factors` with the numerator first and reciprocals as divisions.
    fn product(value: Rational, factors: &[String], divisors: &[String]) -> String {
        let mut text = String::new();
        let mut pieces: Vec<String> = Vec::new();
        let magnitude = if value < Rational::ZERO {
            -value
        } else {
            value
        };
        if magnitude != Rational::ONE || factors.is_empty() {
            pieces.push(magnitude.to_string());
        }
        pieces.extend(factors.iter().cloned());
        if value < Rational::ZERO {
            text.push('-');
        }
        text.push_str(&pieces.join("*"));
        for divisor in divisors {
            text.push('/');
            text.push_str(divisor);
        }
        text
    }

    fn power(base: String, power: u32) -> String {
        if power == 1 {
            base
        } else {
            format!("{base}^{power}")
        }
    }

    fn monomial_text(names: &Names<'_>, monomial: &ParameterMonomial, value: Rational) -> String {
        let mut factors = Vec::new();
        let mut divisors = Vec::new();
        for (a, n) in &monomial.0 {
            match a {
                Atom::Reciprocal(inner) => divisors.push(power(factor(names, inner), *n)),
                other => factors.push(power(atom(names, other), *n)),
            }
        }
        product(value, &factors, &divisors)
    }

    /// Joins signed terms with ` + ` and ` - `.
    fn joined(terms: Vec<String>) -> String {
        let mut text = String::new();
        for (k, term) in terms.into_iter().enumerate() {
            match (k, term.strip_prefix('-')) {
                (0, _) => text.push_str(&term),
                (_, Some(positive)) => {
                    text.push_str(" - ");
                    text.push_str(positive);
                }
                (_, None) => {
                    text.push_str(" + ");
                    text.push_str(&term);
                }
            }
        }
        if text.is_empty() {
            "0".to_string()
        } else {
            text
        }
    }

    /// A parameter polynomial.
    pub fn parameters(names: &Names<'_>, polynomial: &ParameterPolynomial) -> String {
        joined(
            polynomial
                .0
                .iter()
                .map(|(monomial, value)| monomial_text(names, monomial, *value))
                .collect(),
        )
    }

    fn symbol(names: &Names<'_>, symbol: &Symbol) -> String {
        match symbol.variable {
            Variable::Field(k) => {
                let spelling = derivative_spelling(symbol.derivative);
                if spelling.is_empty() {
                    names.fields[k].clone()
                } else {
                    format!("{}.{spelling}", names.fields[k])
                }
            }
            Variable::AveragePart(k) => names.parts[k].label.clone(),
            Variable::Envelope(_) | Variable::Average(_) => "?".to_string(),
        }
    }

    /// The atoms every monomial of every coefficient has, with their least power.
    fn common_factor(polynomial: &Polynomial) -> ParameterMonomial {
        let mut common: Option<Vec<(Atom, u32)>> = None;
        for value in polynomial.0.values() {
            for monomial in value.real.0.keys() {
                common = Some(match common {
                    None => monomial.0.clone(),
                    Some(so_far) => so_far
                        .into_iter()
                        .filter_map(|(atom, power)| {
                            let other = monomial.0.iter().find(|(a, _)| *a == atom)?;
                            Some((atom, power.min(other.1)))
                        })
                        .collect(),
                });
            }
        }
        ParameterMonomial(common.unwrap_or_default())
    }

    /// `monomial` divided by `factor` (which divides it).
    fn divided(monomial: &ParameterMonomial, factor: &ParameterMonomial) -> ParameterMonomial {
        ParameterMonomial(
            monomial
                .0
                .iter()
                .filter_map(|(atom, power)| {
                    let removed = factor.0.iter().find(|(a, _)| a == atom).map_or(0, |f| f.1);
                    (*power > removed).then(|| (atom.clone(), power - removed))
                })
                .collect(),
        )
    }

    /// A real polynomial of the derived fields, with the parameter atoms common to every
    /// coefficient factored out: `bending_stiffness*(wavenumber^4*w^2 + …)`.
    pub fn polynomial(names: &Names<'_>, polynomial: &Polynomial) -> String {
        let common = common_factor(polynomial);
        let terms: Vec<String> = polynomial
            .0
            .iter()
            .map(|(monomial, value)| {
                let coefficient = ParameterPolynomial(
                    value
                        .real
                        .0
                        .iter()
                        .map(|(m, r)| (divided(m, &common), *r))
                        .collect(),
                );
                let symbols: Vec<String> = grouped(monomial)
                    .into_iter()
                    .map(|(s, n)| power(symbol(names, &s), n as u32))
                    .collect();
                match (coefficient.as_constant(), coefficient.term_count()) {
                    (Some(value), _) => product(value, &symbols, &[]),
                    (None, 1) => {
                        let (m, r) = coefficient.0.iter().next().expect("one monomial");
                        let text = monomial_text(names, m, *r);
                        let (sign, magnitude) = match text.strip_prefix('-') {
                            Some(rest) => ("-", rest.to_string()),
                            None => ("", text),
                        };
                        format!("{sign}{}", [vec![magnitude], symbols].concat().join("*"))
                    }
                    (None, _) => format!(
                        "({})*{}",
                        parameters(names, &coefficient),
                        symbols.join("*")
                    ),
                }
            })
            .collect();
        let sum = joined(terms);
        if common.0.is_empty() {
            sum
        } else {
            format!("{}*({sum})", monomial_text(names, &common, Rational::ONE))
        }
    }

    /// An expression of the DSL as written (parentheses where the source has them).
    pub fn expression(expression: &Expression) -> String {
        match expression {
            Expression::Number { value, .. } => format!("{value}"),
            Expression::Name(name) => name.to_string(),
            Expression::Derivative { base, axis } => format!("{base}.{axis}"),
            Expression::Negate { operand, .. } => format!("-{}", self::expression(operand)),
            Expression::Binary { operator, lhs, rhs } => {
                let symbol = match operator {
                    BinaryOperator::Add => "+",
                    BinaryOperator::Subtract => "-",
                    BinaryOperator::Multiply => "*",
                    BinaryOperator::Divide => "/",
                };
                format!(
                    "{} {symbol} {}",
                    self::expression(lhs),
                    self::expression(rhs)
                )
            }
            Expression::Power { base, exponent, .. } => {
                format!("{}^{exponent}", self::expression(base))
            }
            Expression::Call {
                function, argument, ..
            } => format!("{function}({})", self::expression(argument)),
            Expression::Parenthesized { inner, .. } => format!("({})", self::expression(inner)),
        }
    }
}

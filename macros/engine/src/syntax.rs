//! Surface syntax of the energy DSL: a typed AST that keeps every span, and its parser.
//!
//! The expression grammar is parsed by precedence climbing on top of
//! [`syn::parse::ParseStream`] (syn's own Rust `Expr` would give `^` the precedence of
//! bitwise xor):
//!
//! ```text
//! expression := product (('+' | '-') product)*
//! product    := unary (('*' | '/') unary)*
//! unary      := '-' unary | power
//! power      := primary ('^' exponent)?          (right associative)
//! exponent   := '-'? power                       (must fold to an integer in -64..=64)
//! primary    := number | name | name '.' axis | function '(' expression ')' | '(' expression ')'
//! ```

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;
use syn::parse::{Parse, ParseStream};
use syn::{Attribute, Ident, LitStr, Token, bracketed, parenthesized};
use wrinkle_contract::Derivative;

mod keyword {
    syn::custom_keyword!(model);
    syn::custom_keyword!(fields);
    syn::custom_keyword!(parameters);
    syn::custom_keyword!(energy);
}

/// A source range, from the first to the last token of a construct.
///
/// Stable Rust cannot join spans; [`syn::Error::new_spanned`] on a `SpanRange` nevertheless
/// underlines the whole range because it uses the first and the last token it is given.
#[derive(Clone, Copy, Debug)]
pub struct SpanRange {
    /// Span of the first token.
    pub start: Span,
    /// Span of the last token.
    pub end: Span,
}

impl SpanRange {
    /// A range made of a single token.
    pub fn single(span: Span) -> Self {
        Self {
            start: span,
            end: span,
        }
    }
    /// The range from the start of `self` to the end of `other`.
    pub fn to(self, other: SpanRange) -> Self {
        Self {
            start: self.start,
            end: other.end,
        }
    }
    /// A compile error underlining this range.
    pub fn error(&self, message: impl std::fmt::Display) -> syn::Error {
        syn::Error::new_spanned(self, message)
    }
}

impl ToTokens for SpanRange {
    fn to_tokens(&self, tokens: &mut TokenStream) {
        let mut first = proc_macro2::Punct::new('<', proc_macro2::Spacing::Alone);
        first.set_span(self.start);
        let mut last = proc_macro2::Punct::new('>', proc_macro2::Spacing::Alone);
        last.set_span(self.end);
        tokens.extend([
            proc_macro2::TokenTree::Punct(first),
            proc_macro2::TokenTree::Punct(last),
        ]);
    }
}

/// A binary arithmetic operator.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum BinaryOperator {
    /// `+`
    Add,
    /// `-`
    Subtract,
    /// `*`
    Multiply,
    /// `/`
    Divide,
}

/// An expression of the DSL, with spans.
#[derive(Clone, Debug)]
pub enum Expression {
    /// A float or integer literal.
    Number {
        /// Its value.
        value: f64,
        /// Where it is written.
        span: Span,
    },
    /// A field value, a parameter or a `let` name.
    Name(Ident),
    /// `base.axis`: a first derivative of a field (`axis` must be `x` or `y`).
    Derivative {
        /// The differentiated name.
        base: Ident,
        /// The axis identifier as written.
        axis: Ident,
    },
    /// `-operand`.
    Negate {
        /// Span of the `-` token.
        operator: Span,
        /// The negated expression.
        operand: Box<Expression>,
    },
    /// `lhs op rhs`.
    Binary {
        /// The operator.
        operator: BinaryOperator,
        /// Left operand.
        lhs: Box<Expression>,
        /// Right operand.
        rhs: Box<Expression>,
    },
    /// `base ^ exponent` with an integer exponent.
    Power {
        /// The base.
        base: Box<Expression>,
        /// The (validated) integer exponent.
        exponent: i32,
        /// Range of the exponent as written.
        exponent_span: SpanRange,
    },
    /// `function(argument)`.
    Call {
        /// The function name as written.
        function: Ident,
        /// The argument.
        argument: Box<Expression>,
        /// Span of the closing parenthesis.
        close: Span,
    },
    /// `(inner)`: kept so that spans cover the parentheses.
    Parenthesized {
        /// The inner expression.
        inner: Box<Expression>,
        /// Span of the parenthesis group.
        span: Span,
    },
}

impl Expression {
    /// The source range of the whole expression.
    pub fn span_range(&self) -> SpanRange {
        match self {
            Expression::Number { span, .. } | Expression::Parenthesized { span, .. } => {
                SpanRange::single(*span)
            }
            Expression::Name(ident) => SpanRange::single(ident.span()),
            Expression::Derivative { base, axis } => SpanRange {
                start: base.span(),
                end: axis.span(),
            },
            Expression::Negate { operator, operand } => {
                SpanRange::single(*operator).to(operand.span_range())
            }
            Expression::Binary { lhs, rhs, .. } => lhs.span_range().to(rhs.span_range()),
            Expression::Power {
                base,
                exponent_span,
                ..
            } => base.span_range().to(*exponent_span),
            Expression::Call {
                function, close, ..
            } => SpanRange {
                start: function.span(),
                end: *close,
            },
        }
    }
}

/// Quadrature rule requested for a term, as written.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Quadrature {
    /// `[full]` or nothing: 3×3 Gauss.
    Full,
    /// `[reduced]`: 2×2 Gauss.
    Reduced,
}

/// `w [deflection]`: a field and, optionally, its role.
#[derive(Clone, Debug)]
pub struct FieldDeclaration {
    /// Field name.
    pub name: Ident,
    /// The role identifier as written (`deflection`), validated during lowering.
    pub role: Option<Ident>,
}

/// `young "Young's modulus E (MPa)"`.
#[derive(Clone, Debug)]
pub struct ParameterDeclaration {
    /// Parameter name.
    pub name: Ident,
    /// Optional documentation (units).
    pub documentation: Option<LitStr>,
}

/// `let name = value;`.
#[derive(Clone, Debug)]
pub struct LetDeclaration {
    /// The bound name.
    pub name: Ident,
    /// Its value.
    pub value: Expression,
}

/// `energy name [rule] = value;`.
#[derive(Clone, Debug)]
pub struct TermDeclaration {
    /// Term name.
    pub name: Ident,
    /// Quadrature rule.
    pub quadrature: Quadrature,
    /// Energy density expression.
    pub value: Expression,
}

/// A `let` or an `energy` item, in declaration order.
#[derive(Clone, Debug)]
pub enum Item {
    /// A `let` binding.
    Let(LetDeclaration),
    /// An `energy` term.
    Term(TermDeclaration),
}

/// A whole `model` declaration.
#[derive(Clone, Debug)]
pub struct ModelDeclaration {
    /// Doc comment lines (`///`), without the leading space.
    pub documentation: Vec<String>,
    /// Non-doc attributes, forwarded to the generated struct.
    pub attributes: Vec<Attribute>,
    /// Rust type name of the model.
    pub name: Ident,
    /// Registry name (`as "reference-envelope"`).
    pub registry_name: LitStr,
    /// Span of the `fields` keyword (for "no fields" errors).
    pub fields_keyword: Span,
    /// Unknown fields, each with its optional role.
    pub fields: Vec<FieldDeclaration>,
    /// Runtime parameters.
    pub parameters: Vec<ParameterDeclaration>,
    /// Lets and energy terms in order.
    pub items: Vec<Item>,
    /// Span of the model body braces.
    pub body: Span,
    /// Errors detected while parsing that did not prevent parsing the rest.
    pub deferred_errors: Vec<syn::Error>,
}

impl Parse for ModelDeclaration {
    fn parse(input: ParseStream) -> syn::Result<Self> {
        let attributes = input.call(Attribute::parse_outer)?;
        let mut documentation = Vec::new();
        let mut other_attributes = Vec::new();
        for attribute in attributes {
            if attribute.path().is_ident("doc")
                && let syn::Meta::NameValue(syn::MetaNameValue {
                    value:
                        syn::Expr::Lit(syn::ExprLit {
                            lit: syn::Lit::Str(text),
                            ..
                        }),
                    ..
                }) = &attribute.meta
            {
                let line = text.value();
                documentation.push(line.strip_prefix(' ').unwrap_or(&line).to_string());
                continue;
            }
            other_attributes.push(attribute);
        }
        input.parse::<keyword::model>()?;
        let name: Ident = input.parse()?;
        if !input.peek(Token![as]) {
            return Err(input.error(format!(
                "expected `as \"registry-name\"` after the model name `{name}`"
            )));
        }
        input.parse::<Token![as]>()?;
        let registry_name: LitStr = input.parse().map_err(|error| {
            syn::Error::new(
                error.span(),
                "expected the registry name as a string literal, e.g. `as \"my-model\"`",
            )
        })?;
        let content;
        let brace = syn::braced!(content in input);
        let mut deferred_errors = Vec::new();

        let fields_keyword = content.span();
        content.parse::<keyword::fields>().map_err(|error| {
            syn::Error::new(
                error.span(),
                "expected `fields: a, b, ...;` as the first line of the model",
            )
        })?;
        let fields_keyword_span = fields_keyword;
        content.parse::<Token![:]>()?;
        let mut fields = Vec::new();
        while !content.peek(Token![;]) {
            let name = content.parse::<Ident>()?;
            let role = if content.peek(syn::token::Bracket) {
                let inner;
                bracketed!(inner in content);
                let role: Ident = inner.parse()?;
                if !inner.is_empty() {
                    return Err(inner.error("expected a single field role, e.g. `w [deflection]`"));
                }
                Some(role)
            } else {
                None
            };
            fields.push(FieldDeclaration { name, role });
            if content.peek(Token![,]) {
                content.parse::<Token![,]>()?;
            } else {
                break;
            }
        }
        content.parse::<Token![;]>()?;

        let mut parameters = Vec::new();
        if content.peek(keyword::parameters) {
            content.parse::<keyword::parameters>()?;
            content.parse::<Token![:]>()?;
            while !content.peek(Token![;]) {
                let name: Ident = content.parse()?;
                let documentation = if content.peek(LitStr) {
                    Some(content.parse::<LitStr>()?)
                } else {
                    None
                };
                parameters.push(ParameterDeclaration {
                    name,
                    documentation,
                });
                if content.peek(Token![,]) {
                    content.parse::<Token![,]>()?;
                } else {
                    break;
                }
            }
            content.parse::<Token![;]>()?;
        }

        let mut items = Vec::new();
        while !content.is_empty() {
            if content.peek(Token![let]) {
                content.parse::<Token![let]>()?;
                let name: Ident = content.parse()?;
                content.parse::<Token![=]>()?;
                let value = parse_expression(&content, &mut deferred_errors)?;
                content.parse::<Token![;]>()?;
                items.push(Item::Let(LetDeclaration { name, value }));
            } else if content.peek(keyword::energy) {
                content.parse::<keyword::energy>()?;
                let name: Ident = content.parse()?;
                let mut quadrature = Quadrature::Full;
                if content.peek(syn::token::Bracket) {
                    let rule;
                    bracketed!(rule in content);
                    let rule_name: Ident = rule.parse()?;
                    if !rule.is_empty() {
                        return Err(rule.error("expected a single quadrature rule name"));
                    }
                    match rule_name.to_string().as_str() {
                        "full" => quadrature = Quadrature::Full,
                        "reduced" => quadrature = Quadrature::Reduced,
                        other => deferred_errors.push(syn::Error::new(
                            rule_name.span(),
                            format!(
                                "unknown quadrature rule `{other}`: expected `full` (3x3 Gauss) or `reduced` (2x2 Gauss)"
                            ),
                        )),
                    }
                }
                content.parse::<Token![=]>()?;
                let value = parse_expression(&content, &mut deferred_errors)?;
                content.parse::<Token![;]>()?;
                items.push(Item::Term(TermDeclaration {
                    name,
                    quadrature,
                    value,
                }));
            } else if content.peek(keyword::parameters) {
                return Err(content.error("`parameters:` must come right after `fields:`"));
            } else {
                return Err(content.error("expected `let name = ...;` or `energy name = ...;`"));
            }
        }
        if !input.is_empty() {
            return Err(input.error("unexpected tokens after the model body"));
        }
        Ok(ModelDeclaration {
            documentation,
            attributes: other_attributes,
            name,
            registry_name,
            fields_keyword: fields_keyword_span,
            fields,
            parameters,
            items,
            body: brace.span.join(),
            deferred_errors,
        })
    }
}

/// The derivatives of `base` the DSL offers, as written: `` `w.x` and `w.y` ``.
pub fn available_derivatives(base: &Ident) -> String {
    let spellings: Vec<String> = Derivative::ALL
        .iter()
        .filter(|derivative| derivative.order() > 0)
        .map(|derivative| format!("`{base}.{}`", derivative.name()))
        .collect();
    match spellings.as_slice() {
        [] => String::new(),
        [only] => only.clone(),
        [init @ .., last] => format!("{} and {last}", init.join(", ")),
    }
}

/// Parses one expression (see the module grammar). Recoverable problems (bad exponents) are
/// pushed to `errors` and parsing continues.
pub fn parse_expression(
    input: ParseStream,
    errors: &mut Vec<syn::Error>,
) -> syn::Result<Expression> {
    let mut lhs = parse_product(input, errors)?;
    loop {
        let operator = if input.peek(Token![+]) {
            input.parse::<Token![+]>()?;
            BinaryOperator::Add
        } else if input.peek(Token![-]) {
            input.parse::<Token![-]>()?;
            BinaryOperator::Subtract
        } else {
            return Ok(lhs);
        };
        let rhs = parse_product(input, errors)?;
        lhs = Expression::Binary {
            operator,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        };
    }
}

fn parse_product(input: ParseStream, errors: &mut Vec<syn::Error>) -> syn::Result<Expression> {
    let mut lhs = parse_unary(input, errors)?;
    loop {
        let operator = if input.peek(Token![*]) {
            input.parse::<Token![*]>()?;
            BinaryOperator::Multiply
        } else if input.peek(Token![/]) {
            input.parse::<Token![/]>()?;
            BinaryOperator::Divide
        } else {
            return Ok(lhs);
        };
        let rhs = parse_unary(input, errors)?;
        lhs = Expression::Binary {
            operator,
            lhs: Box::new(lhs),
            rhs: Box::new(rhs),
        };
    }
}

fn parse_unary(input: ParseStream, errors: &mut Vec<syn::Error>) -> syn::Result<Expression> {
    if input.peek(Token![-]) {
        let minus: Token![-] = input.parse()?;
        let operand = parse_unary(input, errors)?;
        return Ok(Expression::Negate {
            operator: minus.span,
            operand: Box::new(operand),
        });
    }
    parse_power(input, errors)
}

fn parse_power(input: ParseStream, errors: &mut Vec<syn::Error>) -> syn::Result<Expression> {
    let base = parse_primary(input, errors)?;
    if !input.peek(Token![^]) {
        return Ok(base);
    }
    input.parse::<Token![^]>()?;
    let negative = if input.peek(Token![-]) {
        Some(input.parse::<Token![-]>()?.span)
    } else {
        None
    };
    let written = parse_power(input, errors)?;
    let mut exponent_span = written.span_range();
    if let Some(minus) = negative {
        exponent_span = SpanRange::single(minus).to(exponent_span);
    }
    let exponent = exponent_value(&written)
        .and_then(|value| checked_exponent(if negative.is_some() { -value } else { value }));
    let exponent = exponent.unwrap_or_else(|message| {
        errors.push(exponent_span.error(message));
        1
    });
    Ok(Expression::Power {
        base: Box::new(base),
        exponent,
        exponent_span,
    })
}

/// Largest exponent magnitude the DSL accepts: exponents are integers from `-MAX_EXPONENT` to
/// `MAX_EXPONENT`, written or made by a power of a power. Differentiation lowers an exponent
/// by at most two and the simplifier collects powers of one base only while their exponents
/// stay below this bound, so every exponent inside the engine stays far inside `i32`.
pub const MAX_EXPONENT: i32 = 64;

/// The message for an exponent outside the supported range; `what` names it.
pub fn exponent_out_of_range(what: impl std::fmt::Display) -> String {
    format!("{what} is out of range: exponents are integers from -{MAX_EXPONENT} to {MAX_EXPONENT}")
}

/// `value` as an exponent, if it is an integer in the supported range.
fn checked_exponent(value: f64) -> Result<i32, String> {
    if value.is_finite() && value.fract() != 0.0 {
        Err(format!(
            "exponent must be an integer literal, found the non-integer `{value}`"
        ))
    } else if value.abs() <= f64::from(MAX_EXPONENT) {
        Ok(value as i32)
    } else {
        Err(exponent_out_of_range(format_args!("exponent `{value}`")))
    }
}

/// The value of an exponent written as a number literal, a `^` chain of them, or either in
/// parentheses.
fn exponent_value(expression: &Expression) -> Result<f64, String> {
    match expression {
        Expression::Number { value, .. } => Ok(*value),
        Expression::Power { base, exponent, .. } => Ok(exponent_value(base)?.powi(*exponent)),
        Expression::Parenthesized { inner, .. } => exponent_value(inner),
        _ => Err(
            "exponent must be an integer literal (e.g. `x^2` or `x^-1`); names and expressions are not allowed as exponents"
                .to_string(),
        ),
    }
}

fn parse_primary(input: ParseStream, errors: &mut Vec<syn::Error>) -> syn::Result<Expression> {
    let lookahead = input.lookahead1();
    if lookahead.peek(syn::LitInt) {
        let literal: syn::LitInt = input.parse()?;
        let value = literal.base10_parse::<f64>()?;
        return Ok(Expression::Number {
            value,
            span: literal.span(),
        });
    }
    if lookahead.peek(syn::LitFloat) {
        let literal: syn::LitFloat = input.parse()?;
        let value = literal.base10_parse::<f64>()?;
        return Ok(Expression::Number {
            value,
            span: literal.span(),
        });
    }
    if lookahead.peek(syn::token::Paren) {
        let content;
        let parenthesis = parenthesized!(content in input);
        let inner = parse_expression(&content, errors)?;
        if !content.is_empty() {
            return Err(content.error("expected an operator or `)`"));
        }
        return Ok(Expression::Parenthesized {
            inner: Box::new(inner),
            span: parenthesis.span.join(),
        });
    }
    if lookahead.peek(Ident) {
        let name: Ident = input.parse()?;
        if input.peek(Token![.]) {
            input.parse::<Token![.]>()?;
            if input.peek(syn::LitInt) || input.peek(syn::LitFloat) {
                let literal: syn::Lit = input.parse()?;
                return Err(syn::Error::new(
                    literal.span(),
                    format!(
                        "unsupported derivative: the derivatives available are {}",
                        available_derivatives(&name)
                    ),
                ));
            }
            let axis: Ident = input.parse()?;
            return Ok(Expression::Derivative { base: name, axis });
        }
        if input.peek(syn::token::Paren) {
            let content;
            let parenthesis = parenthesized!(content in input);
            let argument = parse_expression(&content, errors)?;
            if !content.is_empty() {
                return Err(content.error("functions take a single argument"));
            }
            return Ok(Expression::Call {
                function: name,
                argument: Box::new(argument),
                close: parenthesis.span.close(),
            });
        }
        return Ok(Expression::Name(name));
    }
    Err(lookahead.error())
}

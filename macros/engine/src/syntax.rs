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
//!
//! **Errors.** A problem that leaves the rest readable (an exponent that is not an integer in
//! the supported range, an unknown quadrature rule) is collected with its span and parsing goes
//! on; the first one that does not (a missing `;`, a stray token) stops the parser. Either way
//! [`parse_model`] keeps every error collected and, once the model's name has parsed, the
//! [`ModelOutline`] the stand-in for the model is generated from.

use proc_macro2::{Span, TokenStream};
use quote::ToTokens;
use syn::parse::{ParseStream, Parser};
use syn::{Attribute, Ident, LitStr, Token, bracketed, parenthesized};
use wrinkle_contract::Derivative;

mod ansatz;

pub use ansatz::{
    AnsatzDeclaration, AverageDeclaration, AverageOptions, FieldExpansion, HarmonicPart,
    MicroscopicDeclaration,
};

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

/// `young "Young's modulus E (MPa)"`, or `foundation [varying] "…"`.
#[derive(Clone, Debug)]
pub struct ParameterDeclaration {
    /// Parameter name.
    pub name: Ident,
    /// The attribute as written (`varying`), validated during lowering.
    pub attribute: Option<Ident>,
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
    /// A derived term, `energy name = average(term, …);`: replaced by an ordinary term by the
    /// derivation (`crate::ansatz`) before lowering.
    Average(AverageDeclaration),
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
    /// The microscopic energy derived terms are averaged from, if any.
    pub microscopic: Option<Box<MicroscopicDeclaration>>,
    /// The ansatz of derived terms, if any.
    pub ansatz: Option<Box<AnsatzDeclaration>>,
    /// Span of the model body braces.
    pub body: Span,
    /// Errors detected while parsing that did not prevent parsing the rest.
    pub deferred_errors: Vec<syn::Error>,
}

/// The one-line description of a model: the first non-empty line of its documentation.
pub fn description(documentation: &[String]) -> String {
    documentation
        .iter()
        .map(|line| line.trim())
        .find(|line| !line.is_empty())
        .unwrap_or("")
        .to_string()
}

impl ModelDeclaration {
    /// The parts of the declaration the generated type's declaration is made of.
    pub fn outline(&self) -> ModelOutline {
        ModelOutline {
            documentation: self.documentation.clone(),
            attributes: self.attributes.clone(),
            name: self.name.clone(),
            registry_name: Some(self.registry_name.value()),
            parameters: with_microscopic(&self.microscopic, &self.parameters),
        }
    }
}

/// A derived model's parameters: its microscopic energy's, then its own.
fn with_microscopic(
    microscopic: &Option<Box<MicroscopicDeclaration>>,
    parameters: &[ParameterDeclaration],
) -> Vec<ParameterDeclaration> {
    let mut all = microscopic
        .as_ref()
        .map_or_else(Vec::new, |m| m.parameters.clone());
    all.extend(parameters.iter().cloned());
    all
}

/// The parts of a model that declare the generated type — documentation, attributes, name,
/// registry name and parameters — as far as they parsed: what a stand-in for the model needs
/// when its declaration has errors.
#[derive(Clone, Debug)]
pub struct ModelOutline {
    /// Doc comment lines (`///`), without the leading space.
    pub documentation: Vec<String>,
    /// Non-doc attributes, forwarded to the generated struct.
    pub attributes: Vec<Attribute>,
    /// Rust type name of the model.
    pub name: Ident,
    /// Registry name, if it parsed.
    pub registry_name: Option<String>,
    /// The runtime parameters that parsed.
    pub parameters: Vec<ParameterDeclaration>,
}

/// What the parser made of an `energy_model!` invocation.
#[derive(Debug)]
pub enum ParsedModel {
    /// The whole declaration parsed; the errors that did not stop the parser (bad exponents,
    /// unknown quadrature rules) are in its [`ModelDeclaration::deferred_errors`].
    Complete(ModelDeclaration),
    /// An error stopped the parser after the model's name: the outline parsed before it, and
    /// every error found (those collected before the one that stopped it, then that one).
    Partial {
        /// What parsed before the error.
        outline: ModelOutline,
        /// Every error, in source order.
        errors: Vec<syn::Error>,
    },
    /// An error came before the model's name.
    Unnamed {
        /// The errors (one).
        errors: Vec<syn::Error>,
    },
}

/// Parses an `energy_model!` invocation. Problems that leave the rest readable are collected
/// and parsing goes on; the first one that does not (a missing `;`, a stray token) stops it,
/// and everything parsed and collected before it is kept.
pub fn parse_model(tokens: TokenStream) -> ParsedModel {
    let mut model = PartialModel::default();
    let parser = |input: ParseStream| {
        model.parse(input);
        Ok(())
    };
    // syn reports tokens left in a group the parser abandoned after an error: that error is
    // already recorded, so syn's only matters when the parser finished without one.
    if let Err(error) = parser.parse2(tokens)
        && !model.stopped
    {
        model.stop(error);
    }
    model.finish()
}

/// A declaration as far as it parsed.
#[derive(Default)]
struct PartialModel {
    documentation: Vec<String>,
    attributes: Vec<Attribute>,
    name: Option<Ident>,
    registry_name: Option<LitStr>,
    fields_keyword: Option<Span>,
    fields: Vec<FieldDeclaration>,
    parameters: Vec<ParameterDeclaration>,
    items: Vec<Item>,
    microscopic: Option<Box<MicroscopicDeclaration>>,
    ansatz: Option<Box<AnsatzDeclaration>>,
    body: Option<Span>,
    /// Every error so far, in source order.
    errors: Vec<syn::Error>,
    /// Whether an error stopped the parser.
    stopped: bool,
}

impl PartialModel {
    fn parse(&mut self, input: ParseStream) {
        if let Err(error) = self.parse_declaration(input) {
            self.stop(error);
        }
    }

    fn stop(&mut self, error: syn::Error) {
        self.errors.push(error);
        self.stopped = true;
    }

    /// `attributes model Name as "name" { fields … ; parameters … ; items }`.
    fn parse_declaration(&mut self, input: ParseStream) -> syn::Result<()> {
        self.parse_attributes(input)?;
        input.parse::<keyword::model>()?;
        let name: Ident = input.parse()?;
        self.name = Some(name.clone());
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
        self.registry_name = Some(registry_name);
        let content;
        let brace = syn::braced!(content in input);
        self.body = Some(brace.span.join());
        self.parse_fields(&content)?;
        self.parse_parameters(&content)?;
        while !content.is_empty() {
            self.parse_item(&content)?;
        }
        if !input.is_empty() {
            return Err(input.error("unexpected tokens after the model body"));
        }
        Ok(())
    }

    /// Outer attributes: doc comments become documentation lines, the rest is forwarded.
    fn parse_attributes(&mut self, input: ParseStream) -> syn::Result<()> {
        for attribute in input.call(Attribute::parse_outer)? {
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
                let line = line.strip_prefix(' ').unwrap_or(&line).to_string();
                self.documentation.push(line);
                continue;
            }
            self.attributes.push(attribute);
        }
        Ok(())
    }

    /// `fields: u [displacement_x], w;`.
    fn parse_fields(&mut self, content: ParseStream) -> syn::Result<()> {
        self.fields_keyword = Some(content.span());
        content.parse::<keyword::fields>().map_err(|error| {
            syn::Error::new(
                error.span(),
                "expected `fields: a, b, ...;` as the first line of the model",
            )
        })?;
        content.parse::<Token![:]>()?;
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
            self.fields.push(FieldDeclaration { name, role });
            if !content.peek(Token![,]) {
                break;
            }
            content.parse::<Token![,]>()?;
        }
        content.parse::<Token![;]>()?;
        Ok(())
    }

    /// `parameters: young "Young's modulus", poisson, c [varying];` (optional).
    fn parse_parameters(&mut self, content: ParseStream) -> syn::Result<()> {
        if !content.peek(keyword::parameters) {
            return Ok(());
        }
        content.parse::<keyword::parameters>()?;
        content.parse::<Token![:]>()?;
        while !content.peek(Token![;]) {
            let name: Ident = content.parse()?;
            let attribute = if content.peek(syn::token::Bracket) {
                let inner;
                bracketed!(inner in content);
                let attribute: Ident = inner.parse()?;
                if !inner.is_empty() {
                    return Err(inner.error(
                        "expected a single parameter attribute, e.g. `foundation [varying]`",
                    ));
                }
                Some(attribute)
            } else {
                None
            };
            let documentation = if content.peek(LitStr) {
                Some(content.parse::<LitStr>()?)
            } else {
                None
            };
            self.parameters.push(ParameterDeclaration {
                name,
                attribute,
                documentation,
            });
            if !content.peek(Token![,]) {
                break;
            }
            content.parse::<Token![,]>()?;
        }
        content.parse::<Token![;]>()?;
        Ok(())
    }

    /// `let name = value;`, `energy name [rule] = value;`, `energy name [rule] = average(…);`,
    /// or a `microscopic` or `ansatz` block.
    fn parse_item(&mut self, content: ParseStream) -> syn::Result<()> {
        if content.peek(ansatz::keyword::microscopic) {
            return self.parse_microscopic(content);
        }
        if content.peek(ansatz::keyword::ansatz) && content.peek2(syn::token::Brace) {
            return self.parse_ansatz(content);
        }
        if content.peek(Token![let]) {
            content.parse::<Token![let]>()?;
            let name: Ident = content.parse()?;
            content.parse::<Token![=]>()?;
            let value = parse_expression(content, &mut self.errors)?;
            content.parse::<Token![;]>()?;
            self.items.push(Item::Let(LetDeclaration { name, value }));
        } else if content.peek(keyword::energy) {
            content.parse::<keyword::energy>()?;
            let name: Ident = content.parse()?;
            let quadrature = self.parse_quadrature(content)?;
            content.parse::<Token![=]>()?;
            if content.peek(ansatz::keyword::average) && content.peek2(syn::token::Paren) {
                let item = self.parse_average(content, name, quadrature)?;
                content.parse::<Token![;]>()?;
                self.items.push(item);
                return Ok(());
            }
            let value = parse_expression(content, &mut self.errors)?;
            content.parse::<Token![;]>()?;
            self.items.push(Item::Term(TermDeclaration {
                name,
                quadrature,
                value,
            }));
        } else if content.peek(keyword::parameters) {
            return Err(content.error("`parameters:` must come right after `fields:`"));
        } else {
            return Err(content.error("expected `let name = ...;` or `energy name = ...;`"));
        }
        Ok(())
    }

    /// `[full]`, `[reduced]` or nothing (full); an unknown rule name is collected.
    fn parse_quadrature(&mut self, content: ParseStream) -> syn::Result<Quadrature> {
        if !content.peek(syn::token::Bracket) {
            return Ok(Quadrature::Full);
        }
        let rule;
        bracketed!(rule in content);
        let rule_name: Ident = rule.parse()?;
        if !rule.is_empty() {
            return Err(rule.error("expected a single quadrature rule name"));
        }
        Ok(match rule_name.to_string().as_str() {
            "full" => Quadrature::Full,
            "reduced" => Quadrature::Reduced,
            other => {
                self.errors.push(syn::Error::new(
                    rule_name.span(),
                    format!(
                        "unknown quadrature rule `{other}`: expected `full` (3x3 Gauss) or `reduced` (2x2 Gauss)"
                    ),
                ));
                Quadrature::Full
            }
        })
    }

    /// The declaration, or what parsed of it.
    fn finish(self) -> ParsedModel {
        let Some(name) = self.name else {
            return ParsedModel::Unnamed {
                errors: self.errors,
            };
        };
        if self.stopped {
            let outline = ModelOutline {
                documentation: self.documentation,
                attributes: self.attributes,
                name,
                registry_name: self.registry_name.map(|name| name.value()),
                parameters: with_microscopic(&self.microscopic, &self.parameters),
            };
            return ParsedModel::Partial {
                outline,
                errors: self.errors,
            };
        }
        let parsed = "a declaration that parsed without stopping has every part";
        ParsedModel::Complete(ModelDeclaration {
            documentation: self.documentation,
            attributes: self.attributes,
            name,
            registry_name: self.registry_name.expect(parsed),
            fields_keyword: self.fields_keyword.expect(parsed),
            fields: self.fields,
            parameters: self.parameters,
            items: self.items,
            microscopic: self.microscopic,
            ansatz: self.ansatz,
            body: self.body.expect(parsed),
            deferred_errors: self.errors,
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

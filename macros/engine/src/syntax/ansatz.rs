//! Surface syntax of the ansatz form: a `microscopic` energy, an `ansatz` block and derived
//! terms `energy name = average(term, …);` (`docs/dsl.md`, "Envelope models derived from a
//! microscopic energy").
//!
//! ```text
//! microscopic := 'microscopic' name '{' fields parameters? item* '}'   (a model body)
//! ansatz      := 'ansatz' '{' (setting ';' | expansion ';')* '}'
//! setting     := 'wavenumber' ':' expression | 'direction' ':' expression
//!              | 'slow_derivatives' ':' integer
//! expansion   := field '=' part ('+' part)*
//! part        := field                                        (the zeroth harmonic, real)
//!              | '2' 'Re' '(' coefficient 'e' '^' '{' integer? 'i' 'Q' 'e' '.' 'X' '}' ')'
//! coefficient := field | '(' field '+' 'i' field ')'          (real, or complex a + i b)
//! average     := 'average' '(' term (',' option)* ')'
//! option      := ('mean' | 'truncated' | 'without') '(' name (',' name)* ')'
//! ```

use proc_macro2::Span;
use syn::parse::{Parse, ParseStream};
use syn::{Ident, Token, braced, parenthesized};

use super::{Expression, FieldDeclaration, Item, ParameterDeclaration, PartialModel, Quadrature};

pub(super) mod keyword {
    syn::custom_keyword!(microscopic);
    syn::custom_keyword!(ansatz);
    syn::custom_keyword!(average);
    syn::custom_keyword!(wavenumber);
    syn::custom_keyword!(direction);
    syn::custom_keyword!(slow_derivatives);
    syn::custom_keyword!(Re);
    syn::custom_keyword!(mean);
    syn::custom_keyword!(truncated);
    syn::custom_keyword!(without);
}

/// `microscopic name { fields: …; parameters: …; let …; energy …; }`: the energy the derived
/// terms are averaged from, with its own namespace.
#[derive(Clone, Debug)]
pub struct MicroscopicDeclaration {
    /// Its name (provenance, and errors).
    pub name: Ident,
    /// Its fields (roles are ignored).
    pub fields: Vec<FieldDeclaration>,
    /// Its parameters: they become the derived model's first parameters.
    pub parameters: Vec<ParameterDeclaration>,
    /// Its lets and terms in order.
    pub items: Vec<Item>,
    /// Span of the `fields` keyword.
    pub fields_keyword: Span,
}

/// One part of a field's expansion: $`f_0`$ or $`2\,\mathrm{Re}(f_m e^{imQ\,\mathbf e\cdot\mathbf X})`$.
#[derive(Clone, Debug)]
pub struct HarmonicPart {
    /// $`m \ge 0`$ (0 for a plain field).
    pub harmonic: u32,
    /// Where the harmonic index is written (the first token of the part when implicit).
    pub harmonic_span: Span,
    /// The derived field holding the coefficient, or its real part.
    pub real: Ident,
    /// The derived field holding the imaginary part of a complex coefficient.
    pub imaginary: Option<Ident>,
}

/// `w = w0 + 2 Re((a + i b) e^{i Q e.X});`.
#[derive(Clone, Debug)]
pub struct FieldExpansion {
    /// The microscopic field.
    pub field: Ident,
    /// Its parts, as written.
    pub parts: Vec<HarmonicPart>,
}

/// The `ansatz { … }` block.
#[derive(Clone, Debug)]
pub struct AnsatzDeclaration {
    /// Span of the `ansatz` keyword.
    pub keyword: Span,
    /// $`Q`$ (`wavenumber: …;`), a parameter expression.
    pub wavenumber: Option<Expression>,
    /// $`\theta`$ of $`\mathbf e = (\cos\theta, \sin\theta)`$ (`direction: …;`); along X if
    /// absent.
    pub direction: Option<Expression>,
    /// Highest order of slow derivatives kept (`slow_derivatives: 2;`), with its span.
    pub slow_derivatives: Option<(u32, Span)>,
    /// One expansion per microscopic field.
    pub expansions: Vec<FieldExpansion>,
}

/// Where the zeroth harmonic of a derived term is taken, and what it leaves out.
#[derive(Clone, Debug, Default)]
pub struct AverageOptions {
    /// `mean(g, …)`: microscopic `let`s replaced by their zeroth harmonic before the rest of
    /// the term is expanded (the paper's membrane strain averaged before squaring).
    pub mean: Vec<Ident>,
    /// `truncated(g, …)`: microscopic `let`s expanded with all their harmonics, truncated, before
    /// the rest of the term is (the slow order of the rest does not count theirs).
    pub truncated: Vec<Ident>,
    /// `without(f, …)`: derived fields set to zero in this term.
    pub without: Vec<Ident>,
}

/// `energy name [rule] = average(term, options…);`: a derived term.
#[derive(Clone, Debug)]
pub struct AverageDeclaration {
    /// Name of the derived term.
    pub name: Ident,
    /// Its quadrature rule.
    pub quadrature: Quadrature,
    /// Span of the `average` keyword.
    pub keyword: Span,
    /// The microscopic term averaged.
    pub term: Ident,
    /// Its options.
    pub options: AverageOptions,
}

impl PartialModel {
    /// `microscopic name { … }`, after the `microscopic` keyword was peeked.
    pub(super) fn parse_microscopic(&mut self, content: ParseStream) -> syn::Result<()> {
        let keyword: keyword::microscopic = content.parse()?;
        if self.microscopic.is_some() {
            return Err(syn::Error::new(
                keyword.span,
                "a model has at most one `microscopic` energy",
            ));
        }
        let name: Ident = content.parse()?;
        let body;
        braced!(body in content);
        let mut inner = PartialModel::default();
        let parsed = inner.parse_fields(&body).and_then(|()| {
            inner.parse_parameters(&body)?;
            while !body.is_empty() {
                if body.peek(keyword::microscopic) || body.peek(keyword::ansatz) {
                    return Err(body.error(
                        "a microscopic energy is an ordinary model body: it holds no `microscopic` or `ansatz` block",
                    ));
                }
                inner.parse_item(&body)?;
            }
            Ok(())
        });
        self.errors.append(&mut inner.errors);
        parsed?;
        self.microscopic = Some(Box::new(MicroscopicDeclaration {
            name,
            fields: inner.fields,
            parameters: inner.parameters,
            items: inner.items,
            fields_keyword: inner.fields_keyword.unwrap_or(keyword.span),
        }));
        Ok(())
    }

    /// `ansatz { … }`, after the `ansatz` keyword was peeked.
    pub(super) fn parse_ansatz(&mut self, content: ParseStream) -> syn::Result<()> {
        let keyword: keyword::ansatz = content.parse()?;
        if self.ansatz.is_some() {
            return Err(syn::Error::new(
                keyword.span,
                "a model has at most one `ansatz` block",
            ));
        }
        let body;
        braced!(body in content);
        let mut ansatz = AnsatzDeclaration {
            keyword: keyword.span,
            wavenumber: None,
            direction: None,
            slow_derivatives: None,
            expansions: Vec::new(),
        };
        while !body.is_empty() {
            self.parse_ansatz_statement(&body, &mut ansatz)?;
            body.parse::<Token![;]>()?;
        }
        self.ansatz = Some(Box::new(ansatz));
        Ok(())
    }

    fn parse_ansatz_statement(
        &mut self,
        body: ParseStream,
        ansatz: &mut AnsatzDeclaration,
    ) -> syn::Result<()> {
        let repeated = |span: Span, what: &str| {
            syn::Error::new(span, format!("`{what}` is set twice in the ansatz"))
        };
        if body.peek(keyword::wavenumber) && body.peek2(Token![:]) {
            let word: keyword::wavenumber = body.parse()?;
            body.parse::<Token![:]>()?;
            let value = super::parse_expression(body, &mut self.errors)?;
            if ansatz.wavenumber.replace(value).is_some() {
                self.errors.push(repeated(word.span, "wavenumber"));
            }
        } else if body.peek(keyword::direction) && body.peek2(Token![:]) {
            let word: keyword::direction = body.parse()?;
            body.parse::<Token![:]>()?;
            let value = super::parse_expression(body, &mut self.errors)?;
            if ansatz.direction.replace(value).is_some() {
                self.errors.push(repeated(word.span, "direction"));
            }
        } else if body.peek(keyword::slow_derivatives) {
            let word: keyword::slow_derivatives = body.parse()?;
            body.parse::<Token![:]>()?;
            let order = self.parse_integer(body, "the order of slow derivatives")?;
            if let Some(order) = order
                && ansatz.slow_derivatives.replace(order).is_some()
            {
                self.errors.push(repeated(word.span, "slow_derivatives"));
            }
        } else {
            let field: Ident = body.parse().map_err(|error| {
                syn::Error::new(
                    error.span(),
                    "expected `wavenumber: …`, `direction: …`, `slow_derivatives: …` or a field's expansion `w = …`",
                )
            })?;
            body.parse::<Token![=]>()?;
            // A part whose harmonic index is invalid is reported and left out (no cascade).
            let mut parts: Vec<HarmonicPart> =
                self.parse_harmonic_part(body)?.into_iter().collect();
            while body.peek(Token![+]) {
                body.parse::<Token![+]>()?;
                parts.extend(self.parse_harmonic_part(body)?);
            }
            ansatz.expansions.push(FieldExpansion { field, parts });
        }
        Ok(())
    }

    /// A non-negative integer literal; anything else is collected as an error about `what`
    /// (then `None`).
    fn parse_integer(
        &mut self,
        input: ParseStream,
        what: &str,
    ) -> syn::Result<Option<(u32, Span)>> {
        let literal: syn::Lit = input.parse().map_err(|error| {
            syn::Error::new(error.span(), format!("expected an integer: {what}"))
        })?;
        let span = literal.span();
        let value = match &literal {
            syn::Lit::Int(integer) => integer.base10_parse::<u32>().ok(),
            _ => None,
        };
        if value.is_none() {
            self.errors.push(syn::Error::new(
                span,
                format!("{what} must be a non-negative integer literal"),
            ));
        }
        Ok(value.map(|value| (value, span)))
    }

    /// `field` or `2 Re(coefficient e^{m i Q e.X})`; `None` when the harmonic index is invalid
    /// (reported).
    fn parse_harmonic_part(&mut self, body: ParseStream) -> syn::Result<Option<HarmonicPart>> {
        if body.peek(Ident) {
            let real: Ident = body.parse()?;
            return Ok(Some(HarmonicPart {
                harmonic: 0,
                harmonic_span: real.span(),
                real,
                imaginary: None,
            }));
        }
        let two: syn::LitInt = body.parse().map_err(|error| {
            syn::Error::new(
                error.span(),
                "expected a field (the zeroth harmonic) or `2 Re(coefficient e^{m i Q e.X})`",
            )
        })?;
        if two.base10_digits() != "2" {
            return Err(syn::Error::new(
                two.span(),
                "a harmonic is written `2 Re(coefficient e^{m i Q e.X})`, with the factor 2",
            ));
        }
        body.parse::<keyword::Re>()?;
        let inside;
        parenthesized!(inside in body);
        let (real, imaginary) = parse_coefficient(&inside)?;
        let e: Ident = inside.parse()?;
        if e != "e" {
            return Err(syn::Error::new(e.span(), "expected `e^{m i Q e.X}`"));
        }
        inside.parse::<Token![^]>()?;
        let phase;
        braced!(phase in inside);
        let index = self.parse_phase(&phase)?;
        if !inside.is_empty() {
            return Err(inside.error("expected `)` after the phase `e^{m i Q e.X}`"));
        }
        Ok(index.map(|(harmonic, harmonic_span)| HarmonicPart {
            harmonic,
            harmonic_span,
            real,
            imaginary,
        }))
    }

    /// `m i Q e.X` (or `i Q e.X`, `m = 1`): the harmonic index, `None` if it is not a positive
    /// integer (reported).
    fn parse_phase(&mut self, phase: ParseStream) -> syn::Result<Option<(u32, Span)>> {
        let index = if phase.peek(syn::LitInt) || phase.peek(syn::LitFloat) {
            let index = self.parse_integer(phase, "the harmonic index")?;
            if let Some((0, span)) = index {
                self.errors.push(syn::Error::new(
                    span,
                    "harmonic index 0: the zeroth harmonic is written as a plain field, `w = w0 + …`",
                ));
                None
            } else {
                index
            }
        } else {
            Some((1, phase.span()))
        };
        let unit: Ident = phase.parse()?;
        let wavenumber_follows = unit == "iQ";
        if !wavenumber_follows {
            if unit != "i" {
                return Err(syn::Error::new(
                    unit.span(),
                    "expected `i Q e.X` in the phase",
                ));
            }
            let q: Ident = phase.parse()?;
            if q != "Q" {
                return Err(syn::Error::new(q.span(), "expected `Q e.X` after `i`"));
            }
        }
        let e: Ident = phase.parse()?;
        phase.parse::<Token![.]>()?;
        let x: Ident = phase.parse()?;
        if e != "e" || x != "X" || !phase.is_empty() {
            return Err(syn::Error::new(
                e.span(),
                "expected `e.X` (the phase is m Q e·X)",
            ));
        }
        Ok(index)
    }

    /// After `energy name [rule] =`, with `average` peeked: the derived term.
    pub(super) fn parse_average(
        &mut self,
        content: ParseStream,
        name: Ident,
        quadrature: Quadrature,
    ) -> syn::Result<Item> {
        let keyword: keyword::average = content.parse()?;
        let arguments;
        parenthesized!(arguments in content);
        let term: Ident = arguments.parse()?;
        let mut options = AverageOptions::default();
        while !arguments.is_empty() {
            arguments.parse::<Token![,]>()?;
            let list = if arguments.peek(keyword::mean) {
                arguments.parse::<keyword::mean>()?;
                &mut options.mean
            } else if arguments.peek(keyword::truncated) {
                arguments.parse::<keyword::truncated>()?;
                &mut options.truncated
            } else if arguments.peek(keyword::without) {
                arguments.parse::<keyword::without>()?;
                &mut options.without
            } else {
                return Err(arguments.error(
                    "expected an option of `average`: `mean(g, …)`, `truncated(g, …)` or `without(f, …)`",
                ));
            };
            let names;
            parenthesized!(names in arguments);
            let parsed = names.parse_terminated(Ident::parse, Token![,])?;
            list.extend(parsed);
        }
        if !content.peek(Token![;]) {
            return Err(content.error(
                "a derived term is `average(…)` alone: write hand-written parts as terms of their own",
            ));
        }
        Ok(Item::Average(AverageDeclaration {
            name,
            quadrature,
            keyword: keyword.span,
            term,
            options,
        }))
    }
}

/// `a` or `(a + i b)`.
fn parse_coefficient(inside: ParseStream) -> syn::Result<(Ident, Option<Ident>)> {
    if inside.peek(syn::token::Paren) {
        let complex;
        parenthesized!(complex in inside);
        let real: Ident = complex.parse()?;
        complex.parse::<Token![+]>()?;
        let unit: Ident = complex.parse()?;
        if unit != "i" {
            return Err(syn::Error::new(
                unit.span(),
                "a complex coefficient is written `(a + i b)`",
            ));
        }
        let imaginary: Ident = complex.parse()?;
        if !complex.is_empty() {
            return Err(complex.error("a complex coefficient is written `(a + i b)`"));
        }
        return Ok((real, Some(imaginary)));
    }
    Ok((inside.parse()?, None))
}

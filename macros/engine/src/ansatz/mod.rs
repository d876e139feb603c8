//! Envelope models derived from a microscopic energy: the method of Fourier series with slowly
//! variable coefficients (THEORY.md §3, the paper's (6)–(8), (14), (20)–(27), (63)–(64)),
//! automated.
//!
//! A model that declares a `microscopic` energy, an `ansatz` and derived terms
//! `energy name = average(term, …);` (`docs/dsl.md`) is rewritten by [`derive()`] into an ordinary
//! declaration — the microscopic parameters first among its parameters, each derived term an
//! ordinary `energy` item — that the rest of the pipeline lowers, differentiates, simplifies and
//! generates like a hand-written one. For each derived term:
//!
//! 1. **expand** ([`expand`]): every microscopic field is replaced by its expansion
//!    $`f = f_0 + \sum_{m>0} 2\,\mathrm{Re}(f_m e^{imQ\,\mathbf e\cdot\mathbf X})`$, every
//!    derivative by the exact rule
//!    $`(\partial^\alpha f)_m = (\partial_X + imQe_X)^{\alpha_X}(\partial_Y + imQe_Y)^{\alpha_Y}f_m`$,
//!    and the term is multiplied out in the normal form of [`polynomial`] (monomials of
//!    slow-jet symbols, [`coefficient`]s exact in the parameters, $`i^2 = -1`$), truncated to
//!    the ansatz's order of slow derivatives — the derivatives of the envelopes, the non-zero
//!    harmonics; those of the zeroth harmonics are the macroscopic model's own. The `let`s a term
//!    names in `mean(…)` are replaced by their zeroth harmonic before the rest is expanded (the
//!    paper's membrane strain, averaged before it is squared), those in `truncated(…)` by all
//!    their harmonics; their own slow derivatives are truncated inside them, not in the rest;
//! 2. **average**: the zeroth harmonic of the term, its average over a period (Parseval,
//!    $`(fg)_0 = \sum_m f_m g_{-m}`$);
//! 3. **integrate by parts** the monomials with a second slow derivative whose other factors
//!    include an envelope, **assuming every envelope vanishes on the boundary** as the paper
//!    does (clamped edges): $`M\,\partial_k\partial_l s \to
//!    -\tfrac12(\partial_k M\,\partial_l s + \partial_l M\,\partial_k s)`$;
//! 4. **split** each complex coefficient into the real fields of the ansatz,
//!    $`f_m = a + ib`$, $`f_{-m} = a - ib`$ (a real coefficient has $`b = 0`$); the result is
//!    real (checked), and $`\cos^2\theta + \sin^2\theta`$ is folded to 1 where that shortens a
//!    coefficient.
//!
//! Only polynomial energies are derived: a division by an expression of the fields, a negative
//! power of one or a function of one is an error at its tokens. The work is bounded by size —
//! at most [`MAX_MONOMIALS`] monomials in any polynomial — never by time, so the generated code
//! is a function of the declaration alone; the model's derivation report
//! (`ModelSpec::derivation`) gives the sizes.

pub mod coefficient;
pub mod emit;
pub mod expand;
pub mod polynomial;
pub mod rational;
pub mod resolve;
pub mod term;

use std::fmt::Write;

use crate::semantic::combine;
use crate::syntax::{
    AverageDeclaration, Expression, Item, ModelDeclaration, ParameterDeclaration, TermDeclaration,
};
use coefficient::{Atom, ParameterPolynomial};
use emit::{Emitter, Names};
use polynomial::{TooLarge, Truncation, Wave};
use rational::Rational;
use resolve::{Ansatz, Microscopic, TermOptions};
use term::{DerivedTerm, TermContext, TermError, derive_term};

/// The most monomials a polynomial of a derivation may hold (module documentation).
pub const MAX_MONOMIALS: usize = 50_000;

/// A declaration after its derivation: ordinary items only, and the derivation's report.
pub struct Derived {
    /// The declaration with every derived term replaced by an ordinary one and the
    /// microscopic parameters first.
    pub declaration: ModelDeclaration,
    /// Provenance (the microscopic energy and the ansatz), the derived densities in DSL syntax
    /// and the derivation's sizes: `ModelSpec::derivation`.
    pub report: String,
}

/// Derives the `average(…)` terms of `declaration`; `None` for a model without a
/// `microscopic` energy or `ansatz` (hand-written).
pub fn derive(declaration: &ModelDeclaration) -> Result<Option<Derived>, syn::Error> {
    let (microscopic_declaration, ansatz_declaration) = match (
        &declaration.microscopic,
        &declaration.ansatz,
    ) {
        (None, None) => return Ok(None),
        (Some(microscopic), Some(ansatz)) => (microscopic, ansatz),
        (Some(microscopic), None) => {
            return Err(syn::Error::new(
                microscopic.name.span(),
                format!(
                    "the microscopic energy `{}` needs an `ansatz {{ … }}` that says how its fields are expanded",
                    microscopic.name
                ),
            ));
        }
        (None, Some(ansatz)) => {
            return Err(syn::Error::new(
                ansatz.keyword,
                "an `ansatz` expands the fields of a `microscopic` energy, and this model declares none",
            ));
        }
    };
    let mut errors = declaration.deferred_errors.clone();
    let microscopic = Microscopic::new(microscopic_declaration, &mut errors);
    let parameters = derived_parameters(declaration, microscopic_declaration, &mut errors);
    let parameter_names: Vec<String> = parameters.iter().map(|p| p.name.to_string()).collect();
    let ansatz = Ansatz::new(ansatz_declaration, &microscopic, declaration, &mut errors);
    let wave = wave(&ansatz, &parameter_names, &mut errors);
    check_constant_carrier(ansatz_declaration, &parameters, &mut errors);
    if !errors.is_empty() {
        return Err(combine(errors).expect("errors"));
    }
    let wave = wave.expect("a wave without errors");
    let context = TermContext {
        microscopic: &microscopic,
        ansatz: &ansatz,
        wave: &wave,
        truncation: Truncation {
            order: ansatz.order,
            max_monomials: MAX_MONOMIALS,
        },
    };
    let field_names: Vec<String> = declaration
        .fields
        .iter()
        .map(|f| f.name.to_string())
        .collect();
    let mut items = Vec::with_capacity(declaration.items.len());
    let mut report = provenance(declaration, &microscopic, &ansatz, &parameter_names);
    let mut work = Vec::new();
    for item in &declaration.items {
        let Item::Average(average) = item else {
            items.push(item.clone());
            continue;
        };
        let Some(options) =
            TermOptions::new(average, &microscopic, &ansatz, declaration, &mut errors)
        else {
            continue;
        };
        match derive_term(&context, &options) {
            Ok(derived) => {
                let names = Names {
                    fields: &field_names,
                    parameters: &parameter_names,
                    parts: &derived.parts,
                };
                describe_term(&mut report, average, &derived, &names);
                work.push(format!(
                    "term `{}`: {} monomials expanded, {} in its zeroth harmonic, {} integrated by parts, {} derived",
                    average.name,
                    derived.statistics.expanded,
                    derived.statistics.averaged,
                    derived.statistics.integrated,
                    derived.statistics.derived
                ));
                let emitter = Emitter {
                    names,
                    span: average.keyword,
                };
                items.push(Item::Term(TermDeclaration {
                    name: average.name.clone(),
                    quadrature: average.quadrature,
                    value: emitter.polynomial(&derived.energy),
                }));
            }
            Err(TermError::Source(mut found)) => errors.append(&mut found),
            Err(TermError::TooLarge(too_large)) => errors.push(too_large_error(average, too_large)),
        }
    }
    if let Some(combined) = combine(errors) {
        return Err(combined);
    }
    let _ = writeln!(
        report,
        "work (bounded by {MAX_MONOMIALS} monomials per polynomial): {}",
        work.join("; ")
    );
    let mut rewritten = declaration.clone();
    rewritten.parameters = parameters;
    rewritten.items = items;
    rewritten.microscopic = None;
    rewritten.ansatz = None;
    Ok(Some(Derived {
        declaration: rewritten,
        report,
    }))
}

fn too_large_error(average: &AverageDeclaration, too_large: TooLarge) -> syn::Error {
    syn::Error::new(
        average.keyword,
        format!(
            "the derivation of `{}` exceeds {} monomials in one polynomial, the bound that keeps the compile time bounded: keep fewer harmonics or slow derivatives, or average its `let`s first with `mean(…)`",
            average.name, too_large.max_monomials
        ),
    )
}

/// The microscopic energy's parameters followed by the model's own; a name in both is an error
/// at the model's.
fn derived_parameters(
    declaration: &ModelDeclaration,
    microscopic: &crate::syntax::MicroscopicDeclaration,
    errors: &mut Vec<syn::Error>,
) -> Vec<ParameterDeclaration> {
    let mut parameters = microscopic.parameters.clone();
    for parameter in &declaration.parameters {
        if microscopic
            .parameters
            .iter()
            .any(|p| p.name == parameter.name)
        {
            errors.push(syn::Error::new(
                parameter.name.span(),
                format!(
                    "duplicate name `{}`: already a parameter of the microscopic energy `{}`, which the model has first",
                    parameter.name, microscopic.name
                ),
            ));
        } else {
            parameters.push(parameter.clone());
        }
    }
    parameters
}

/// A parameter declared `[varying]` in the ansatz's `wavenumber:` or `direction:` is an error
/// at its name: the derivation averages over periods of a carrier $`e^{iQ\mathbf e\cdot\mathbf X}`$
/// with constant $`Q`$ and $`\mathbf e`$, so the derivatives of a varying one would be lost.
fn check_constant_carrier(
    ansatz: &crate::syntax::AnsatzDeclaration,
    parameters: &[ParameterDeclaration],
    errors: &mut Vec<syn::Error>,
) {
    let settings = [
        ("wavenumber", &ansatz.wavenumber),
        ("direction", &ansatz.direction),
    ];
    for (setting, expression) in settings {
        let Some(expression) = expression else {
            continue;
        };
        let mut names = Vec::new();
        names_in(expression, &mut names);
        for name in names {
            if parameters
                .iter()
                .any(|p| p.name == *name && p.attribute.is_some())
            {
                errors.push(syn::Error::new(
                    name.span(),
                    format!(
                        "the ansatz's `{setting}` must be constant, and `{name}` is declared `[varying]`: the derivation averages over periods of a fixed carrier"
                    ),
                ));
            }
        }
    }
}

/// Every name an expression reads (derivatives included), in writing order.
fn names_in<'a>(expression: &'a Expression, names: &mut Vec<&'a syn::Ident>) {
    match expression {
        Expression::Number { .. } => {}
        Expression::Name(name) | Expression::Derivative { base: name, .. } => names.push(name),
        Expression::Negate { operand: inner, .. }
        | Expression::Power { base: inner, .. }
        | Expression::Call {
            argument: inner, ..
        }
        | Expression::Parenthesized { inner, .. } => names_in(inner, names),
        Expression::Binary { lhs, rhs, .. } => {
            names_in(lhs, names);
            names_in(rhs, names);
        }
    }
}

/// $`Q`$ and $`\mathbf e = (\cos\theta, \sin\theta)`$ of the ansatz; along X ($`\mathbf e =
/// (1, 0)`$ exactly) without a `direction`, or when it is the constant 0.
fn wave(
    ansatz: &Ansatz<'_>,
    parameter_names: &[String],
    errors: &mut Vec<syn::Error>,
) -> Option<Wave> {
    let declaration = ansatz.declaration;
    let wavenumber = match &declaration.wavenumber {
        Some(expression) => expand::parameter_expression(expression, parameter_names, errors),
        None if ansatz.has_harmonics() => {
            errors.push(syn::Error::new(
                declaration.keyword,
                "the ansatz has harmonics but no wavenumber: add `wavenumber: <parameter>;`",
            ));
            None
        }
        None => Some(ParameterPolynomial::zero()),
    };
    let angle = match &declaration.direction {
        Some(expression) => expand::parameter_expression(expression, parameter_names, errors),
        None => Some(ParameterPolynomial::zero()),
    };
    let (wavenumber, angle) = (wavenumber?, angle?);
    let direction = if angle.is_zero() {
        [
            ParameterPolynomial::constant(Rational::ONE),
            ParameterPolynomial::zero(),
        ]
    } else {
        [
            ParameterPolynomial::atom(Atom::Apply(crate::graph::Function::Cos, angle.clone())),
            ParameterPolynomial::atom(Atom::Apply(crate::graph::Function::Sin, angle)),
        ]
    };
    Some(Wave {
        wavenumber,
        direction,
    })
}

/// The provenance part of the report: the microscopic energy as written and the ansatz.
fn provenance(
    declaration: &ModelDeclaration,
    microscopic: &Microscopic<'_>,
    ansatz: &Ansatz<'_>,
    parameter_names: &[String],
) -> String {
    let source = microscopic.declaration;
    let list = |names: Vec<String>| names.join(", ");
    let mut report = String::new();
    let _ = writeln!(
        report,
        "derived from the microscopic energy `{}` (fields {}; parameters {}):",
        source.name,
        list(source.fields.iter().map(|f| f.name.to_string()).collect()),
        list(
            source
                .parameters
                .iter()
                .map(|p| p.name.to_string())
                .collect()
        ),
    );
    for item in &source.items {
        match item {
            Item::Let(binding) => {
                let _ = writeln!(
                    report,
                    "    let {} = {};",
                    binding.name,
                    emit::text::expression(&binding.value)
                );
            }
            Item::Term(term) => {
                let _ = writeln!(
                    report,
                    "    energy {} = {};",
                    term.name,
                    emit::text::expression(&term.value)
                );
            }
            Item::Average(_) => {}
        }
    }
    let parameter = |expression: &Option<crate::syntax::Expression>, default: &str| {
        expression
            .as_ref()
            .map_or(default.to_string(), emit::text::expression)
    };
    let _ = writeln!(
        report,
        "with the ansatz (Q = {}, e = (cos θ, sin θ) with θ = {}, slow derivatives up to order {}):",
        parameter(&ansatz.declaration.wavenumber, "none"),
        parameter(&ansatz.declaration.direction, "0"),
        ansatz.order
    );
    for expansion in &ansatz.declaration.expansions {
        let parts: Vec<String> = expansion
            .parts
            .iter()
            .map(|part| {
                let coefficient = match &part.imaginary {
                    Some(b) => format!("({} + i {b})", part.real),
                    None => part.real.to_string(),
                };
                match part.harmonic {
                    0 => coefficient,
                    1 => format!("2 Re({coefficient} e^{{i Q e.X}})"),
                    m => format!("2 Re({coefficient} e^{{{m} i Q e.X}})"),
                }
            })
            .collect();
        let _ = writeln!(report, "    {} = {}", expansion.field, parts.join(" + "));
    }
    let _ = writeln!(
        report,
        "each derived term is the zeroth harmonic (the average over a period) of a microscopic term, truncated, with its second slow derivatives integrated by parts assuming every envelope (every coefficient of a non-zero harmonic) vanishes on the boundary; the model `{}` has the parameters {}:",
        declaration.registry_name.value(),
        list(parameter_names.to_vec())
    );
    report
}

/// Appends a derived term's densities to the report.
fn describe_term(
    report: &mut String,
    average: &AverageDeclaration,
    derived: &DerivedTerm,
    names: &Names<'_>,
) {
    let options = &average.options;
    let mut written = vec![average.term.to_string()];
    for (keyword, list) in [
        ("mean", &options.mean),
        ("truncated", &options.truncated),
        ("without", &options.without),
    ] {
        if !list.is_empty() {
            let names: Vec<String> = list.iter().map(ToString::to_string).collect();
            written.push(format!("{keyword}({})", names.join(", ")));
        }
    }
    let _ = writeln!(
        report,
        "    energy {} = average({}):",
        average.name,
        written.join(", ")
    );
    for part in &derived.parts {
        let _ = writeln!(
            report,
            "        {} = {}",
            part.label,
            emit::text::polynomial(names, &part.definition)
        );
    }
    let _ = writeln!(
        report,
        "        {} = {}",
        average.name,
        emit::text::polynomial(names, &derived.energy)
    );
}

//! Resolution and validation of an ansatz declaration: the microscopic energy's namespace, the
//! derived model's parameters, each microscopic field's expansion into derived fields, and each
//! derived term's options. Every error is collected with the offending token's span.

use std::collections::BTreeMap;

use syn::Ident;

use crate::syntax::{
    AnsatzDeclaration, AverageDeclaration, Expression, Item, MicroscopicDeclaration,
    ModelDeclaration,
};

/// One microscopic name and what it is.
#[derive(Clone, Copy, Debug)]
pub enum MicroscopicName<'a> {
    /// Field number `k`.
    Field(usize),
    /// Parameter number `k` (also the derived model's parameter number `k`).
    Parameter(usize),
    /// A `let`, declared at item position `position`.
    Let {
        /// Item position in the microscopic body.
        position: usize,
        /// Its value.
        value: &'a Expression,
    },
    /// An energy term, at item position `position`.
    Term {
        /// Item position in the microscopic body.
        position: usize,
        /// Its density.
        value: &'a Expression,
    },
}

/// The microscopic energy's namespace.
pub struct Microscopic<'a> {
    /// The declaration.
    pub declaration: &'a MicroscopicDeclaration,
    /// Every name, resolved.
    pub names: BTreeMap<String, MicroscopicName<'a>>,
}

impl<'a> Microscopic<'a> {
    /// Collects the names of `declaration`; a name declared twice is an error at the second.
    pub fn new(declaration: &'a MicroscopicDeclaration, errors: &mut Vec<syn::Error>) -> Self {
        let mut names = BTreeMap::new();
        let mut averages = Vec::new();
        let mut declare = |name: &Ident, meaning: MicroscopicName<'a>| {
            if names.insert(name.to_string(), meaning).is_some() {
                errors.push(syn::Error::new(
                    name.span(),
                    format!(
                        "duplicate name `{name}` in the microscopic energy `{}`: fields, parameters, lets and terms share one namespace",
                        declaration.name
                    ),
                ));
            }
        };
        for (k, field) in declaration.fields.iter().enumerate() {
            declare(&field.name, MicroscopicName::Field(k));
        }
        for (k, parameter) in declaration.parameters.iter().enumerate() {
            declare(&parameter.name, MicroscopicName::Parameter(k));
        }
        for (position, item) in declaration.items.iter().enumerate() {
            match item {
                Item::Let(binding) => declare(
                    &binding.name,
                    MicroscopicName::Let {
                        position,
                        value: &binding.value,
                    },
                ),
                Item::Term(term) => declare(
                    &term.name,
                    MicroscopicName::Term {
                        position,
                        value: &term.value,
                    },
                ),
                Item::Average(average) => averages.push(average.keyword),
            }
        }
        for keyword in averages {
            errors.push(syn::Error::new(
                keyword,
                "a microscopic energy is written out: it derives no `average(…)` term",
            ));
        }
        Self { declaration, names }
    }

    /// The field names, for messages.
    pub fn field_list(&self) -> String {
        let names: Vec<String> = self
            .declaration
            .fields
            .iter()
            .map(|field| format!("`{}`", field.name))
            .collect();
        names.join(", ")
    }
}

/// A harmonic of a microscopic field, resolved to derived fields.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Part {
    /// $`m \ge 0`$.
    pub harmonic: i32,
    /// Derived field of the coefficient (its real part when complex).
    pub real: usize,
    /// Derived field of the imaginary part, if complex.
    pub imaginary: Option<usize>,
}

/// The resolved ansatz.
pub struct Ansatz<'a> {
    /// The declaration.
    pub declaration: &'a AnsatzDeclaration,
    /// Per microscopic field, its parts (in the order written).
    pub parts: Vec<Vec<Part>>,
    /// Highest order of slow derivatives kept.
    pub order: u32,
}

impl<'a> Ansatz<'a> {
    /// Resolves the expansions against the microscopic fields and the derived model's fields.
    pub fn new(
        declaration: &'a AnsatzDeclaration,
        microscopic: &Microscopic<'_>,
        model: &ModelDeclaration,
        errors: &mut Vec<syn::Error>,
    ) -> Self {
        let model_fields: BTreeMap<String, usize> = model
            .fields
            .iter()
            .enumerate()
            .map(|(k, field)| (field.name.to_string(), k))
            .collect();
        let mut parts: Vec<Option<Vec<Part>>> = vec![None; microscopic.declaration.fields.len()];
        let mut used: BTreeMap<usize, String> = BTreeMap::new();
        for expansion in &declaration.expansions {
            let field = match microscopic.names.get(&expansion.field.to_string()) {
                Some(MicroscopicName::Field(k)) => *k,
                _ => {
                    errors.push(syn::Error::new(
                        expansion.field.span(),
                        format!(
                            "`{}` is not a field of the microscopic energy `{}` (its fields: {})",
                            expansion.field,
                            microscopic.declaration.name,
                            microscopic.field_list()
                        ),
                    ));
                    continue;
                }
            };
            if parts[field].is_some() {
                errors.push(syn::Error::new(
                    expansion.field.span(),
                    format!("the ansatz expands `{}` twice", expansion.field),
                ));
                continue;
            }
            let mut resolved: Vec<Part> = Vec::new();
            for part in &expansion.parts {
                let mut field_of = |name: &Ident| {
                    let Some(&index) = model_fields.get(&name.to_string()) else {
                        errors.push(syn::Error::new(
                            name.span(),
                            format!(
                                "`{name}` is not a field of the model: declare it in `fields:` (with its role)"
                            ),
                        ));
                        return None;
                    };
                    if let Some(previous) = used.insert(index, name.to_string()) {
                        errors.push(syn::Error::new(
                            name.span(),
                            format!(
                                "the field `{previous}` is already a coefficient of the ansatz"
                            ),
                        ));
                    }
                    Some(index)
                };
                let real = field_of(&part.real);
                let imaginary = part.imaginary.as_ref().map(&mut field_of);
                let harmonic = part.harmonic as i32;
                if resolved.iter().any(|other| other.harmonic == harmonic) {
                    errors.push(syn::Error::new(
                        part.harmonic_span,
                        format!(
                            "harmonic {harmonic} of `{}` is given twice",
                            expansion.field
                        ),
                    ));
                }
                match (real, imaginary) {
                    (Some(real), None) => resolved.push(Part {
                        harmonic,
                        real,
                        imaginary: None,
                    }),
                    (Some(real), Some(Some(imaginary))) => resolved.push(Part {
                        harmonic,
                        real,
                        imaginary: Some(imaginary),
                    }),
                    _ => {}
                }
            }
            parts[field] = Some(resolved);
        }
        for (k, field) in microscopic.declaration.fields.iter().enumerate() {
            if parts[k].is_none() {
                errors.push(syn::Error::new(
                    declaration.keyword,
                    format!(
                        "the ansatz does not expand the microscopic field `{}`: add `{} = …;`",
                        field.name, field.name
                    ),
                ));
            }
        }
        let order = declaration.slow_derivatives.map_or(2, |(order, _)| order);
        Self {
            declaration,
            parts: parts.into_iter().map(Option::unwrap_or_default).collect(),
            order,
        }
    }

    /// Whether some field has a non-zero harmonic (and so the ansatz needs a wavenumber).
    pub fn has_harmonics(&self) -> bool {
        self.parts.iter().flatten().any(|part| part.harmonic != 0)
    }

    /// The part of microscopic field `field` for harmonic `|m|`.
    pub fn part(&self, field: usize, harmonic: i32) -> Option<&Part> {
        self.parts[field]
            .iter()
            .find(|part| part.harmonic == harmonic.abs())
    }

    /// Whether derived field `field` is a coefficient of the ansatz.
    pub fn uses_field(&self, field: usize) -> bool {
        self.parts
            .iter()
            .flatten()
            .any(|part| part.real == field || part.imaginary == Some(field))
    }
}

/// A derived term's options, resolved.
pub struct TermOptions<'a> {
    /// The microscopic term's density.
    pub energy: &'a Expression,
    /// Its item position.
    pub position: usize,
    /// `mean(…)` and `truncated(…)` lets, in the order written, with whether all their
    /// harmonics are kept.
    pub averaged: Vec<(&'a Ident, bool)>,
    /// Derived fields set to zero.
    pub without: Vec<usize>,
}

impl<'a> TermOptions<'a> {
    /// Resolves `average`'s term and options; `None` after recording why.
    pub fn new(
        average: &'a AverageDeclaration,
        microscopic: &Microscopic<'a>,
        ansatz: &Ansatz<'_>,
        model: &ModelDeclaration,
        errors: &mut Vec<syn::Error>,
    ) -> Option<Self> {
        let term = match microscopic.names.get(&average.term.to_string()) {
            Some(MicroscopicName::Term { position, value }) => Some((*value, *position)),
            _ => {
                let terms: Vec<String> = microscopic
                    .declaration
                    .items
                    .iter()
                    .filter_map(|item| match item {
                        Item::Term(term) => Some(format!("`{}`", term.name)),
                        _ => None,
                    })
                    .collect();
                errors.push(syn::Error::new(
                    average.term.span(),
                    format!(
                        "`{}` is not an energy term of the microscopic energy `{}` (its terms: {})",
                        average.term,
                        microscopic.declaration.name,
                        terms.join(", ")
                    ),
                ));
                None
            }
        };
        let mut averaged = Vec::new();
        let lists = [
            (&average.options.mean, false),
            (&average.options.truncated, true),
        ];
        for (names, all_harmonics) in lists {
            for name in names {
                match microscopic.names.get(&name.to_string()) {
                    Some(MicroscopicName::Let { .. }) => averaged.push((name, all_harmonics)),
                    _ => errors.push(syn::Error::new(
                        name.span(),
                        format!(
                            "`{name}` is not a `let` of the microscopic energy `{}`: only its lets can be averaged first",
                            microscopic.declaration.name
                        ),
                    )),
                }
            }
        }
        let mut without = Vec::new();
        for name in &average.options.without {
            match model.fields.iter().position(|field| field.name == *name) {
                Some(k) if ansatz.uses_field(k) => without.push(k),
                _ => errors.push(syn::Error::new(
                    name.span(),
                    format!("`{name}` is not a coefficient field of the ansatz"),
                )),
            }
        }
        let (energy, position) = term?;
        Some(Self {
            energy,
            position,
            averaged,
            without,
        })
    }
}

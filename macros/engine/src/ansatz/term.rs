//! One derived term: the microscopic term expanded, its zeroth harmonic taken, truncated,
//! integrated by parts, and split into the derived model's real fields.

use std::collections::BTreeMap;

use super::coefficient::Complex;
use super::expand::{Expander, averaged_symbol};
use super::polynomial::{Polynomial, Symbol, TooLarge, Truncation, Variable, Wave};
use super::rational::Rational;
use super::resolve::{Ansatz, Microscopic, MicroscopicName, TermOptions};

/// A real quantity a derived term is written with: a real or imaginary part of one harmonic
/// coefficient of an averaged `let` (`mean(gx)`, `re(gx[2])`, `im(gx[2])`), as a polynomial of
/// the derived fields.
#[derive(Clone, Debug)]
pub struct AveragedPart {
    /// How it prints.
    pub label: String,
    /// Its value (real coefficients; [`Variable::Field`] symbols).
    pub definition: Polynomial,
}

/// Sizes of one term's derivation (the work it took, reported in the model's derivation).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub struct TermStatistics {
    /// Monomials of the expanded term, every harmonic (after truncation).
    pub expanded: usize,
    /// Monomials of its zeroth harmonic.
    pub averaged: usize,
    /// Monomials integrated by parts.
    pub integrated: usize,
    /// Monomials of the derived density in real fields.
    pub derived: usize,
}

/// A derived term.
#[derive(Clone, Debug)]
pub struct DerivedTerm {
    /// The density: real coefficients, [`Variable::Field`] and [`Variable::AveragePart`]
    /// symbols.
    pub energy: Polynomial,
    /// Definitions of the [`Variable::AveragePart`] symbols, by index.
    pub parts: Vec<AveragedPart>,
    /// Its sizes.
    pub statistics: TermStatistics,
}

/// Why a term could not be derived.
pub enum TermError {
    /// Errors in the microscopic energy's expressions, at their tokens.
    Source(Vec<syn::Error>),
    /// A polynomial exceeded the size bound.
    TooLarge(TooLarge),
}

/// What the derivation of one term reads.
pub struct TermContext<'a> {
    /// The microscopic namespace.
    pub microscopic: &'a Microscopic<'a>,
    /// The ansatz.
    pub ansatz: &'a Ansatz<'a>,
    /// The carrier wave.
    pub wave: &'a Wave,
    /// Truncation order and size bound.
    pub truncation: Truncation,
}

/// An averaged `let`: its series (every harmonic, truncated) and the harmonics kept, $`\ge 0`$.
struct Averaged {
    name: String,
    series: Polynomial,
    harmonics: Vec<i32>,
}

/// Derives one term (module documentation).
pub fn derive_term(
    context: &TermContext<'_>,
    options: &TermOptions<'_>,
) -> Result<DerivedTerm, TermError> {
    let (averaged, symbols) = expand_averaged(context, options)?;
    let mut outer = Expander::new(
        context.microscopic,
        context.ansatz,
        context.wave,
        context.truncation,
    );
    outer.averaged = symbols;
    let expanded = outer.expand(options.energy, options.position);
    finish(&outer)?;
    let expanded = expanded.map(|value| match value {
        super::expand::Value::Parameter(p) => Polynomial::constant(Complex::real(p)),
        super::expand::Value::Series(series) => series,
    });
    let expanded = expanded.expect("an expansion without errors has a value");
    let mut statistics = TermStatistics {
        expanded: expanded.len(),
        ..TermStatistics::default()
    };
    let zeroth = expanded.zeroth_harmonic();
    statistics.averaged = zeroth.len();
    let (integrated, count) = zeroth.integrate_by_parts(
        |symbol| matches!(symbol.variable, Variable::Envelope(_)) && symbol.harmonic != 0,
        |symbol| !matches!(symbol.variable, Variable::Average(_)),
    );
    statistics.integrated = count;
    let split = Split {
        ansatz: context.ansatz,
        without: &options.without,
    };
    let (parts, part_index) = split.averaged_parts(&averaged, &context.truncation)?;
    let energy = integrated
        .substitute(
            |symbol| split.symbol(symbol, &part_index),
            &context.truncation,
        )
        .map_err(TermError::TooLarge)?;
    let energy = real_part(&energy, "term");
    statistics.derived = energy.len();
    Ok(DerivedTerm {
        energy,
        parts,
        statistics,
    })
}

/// Expands each averaged `let` and the symbols that stand for it in the term.
fn expand_averaged(
    context: &TermContext<'_>,
    options: &TermOptions<'_>,
) -> Result<(Vec<Averaged>, BTreeMap<String, Polynomial>), TermError> {
    let mut inner = Expander::new(
        context.microscopic,
        context.ansatz,
        context.wave,
        context.truncation,
    );
    let mut averaged = Vec::new();
    let mut symbols = BTreeMap::new();
    for (name, all_harmonics) in &options.averaged {
        let Some(MicroscopicName::Let { position, value }) =
            context.microscopic.names.get(&name.to_string()).copied()
        else {
            continue;
        };
        let Some(super::expand::Value::Series(series)) = inner.expand(value, position) else {
            continue;
        };
        let harmonics: Vec<i32> = if *all_harmonics {
            series.harmonics().into_iter().filter(|&m| m >= 0).collect()
        } else {
            vec![0]
        };
        let index = averaged.len();
        let mut stand_in = Polynomial::zero();
        for &m in &harmonics {
            stand_in = stand_in.plus(&averaged_symbol(index, m));
            if m != 0 {
                stand_in = stand_in.plus(&averaged_symbol(index, -m));
            }
        }
        symbols.insert(name.to_string(), stand_in);
        averaged.push(Averaged {
            name: name.to_string(),
            series,
            harmonics,
        });
    }
    finish(&inner)?;
    Ok((averaged, symbols))
}

fn finish(expander: &Expander<'_>) -> Result<(), TermError> {
    if !expander.errors.is_empty() {
        return Err(TermError::Source(expander.errors.clone()));
    }
    if let Some(too_large) = expander.too_large {
        return Err(TermError::TooLarge(too_large));
    }
    Ok(())
}

/// The real polynomial of a polynomial whose imaginary parts must vanish (a period average of
/// a real quantity, a real part): an internal invariant of the derivation.
fn real_part(polynomial: &Polynomial, what: &str) -> Polynomial {
    let mut real = Polynomial::zero();
    for (monomial, value) in &polynomial.0 {
        assert!(
            value.imaginary.is_zero(),
            "internal error of the ansatz derivation: the {what} has an imaginary part"
        );
        real.add_term(
            monomial.clone(),
            Complex::real(value.real.with_unit_direction()),
        );
    }
    real
}

/// The split of complex harmonic coefficients into the derived model's real fields.
struct Split<'a> {
    ansatz: &'a Ansatz<'a>,
    without: &'a [usize],
}

/// (averaged let, harmonic, imaginary component) → index of its part (none when it is zero).
type PartIndex = BTreeMap<(usize, i32, bool), usize>;

impl Split<'_> {
    /// Derived field `field`'s symbol with `symbol`'s derivative; zero if left out.
    fn field(&self, field: usize, symbol: &Symbol) -> Polynomial {
        if self.without.contains(&field) {
            return Polynomial::zero();
        }
        Polynomial::symbol(Symbol {
            variable: Variable::Field(field),
            harmonic: 0,
            derivative: symbol.derivative,
        })
    }

    /// $`f_m = a + ib`$, $`f_{-m} = a - ib`$ (for $`m > 0`$), $`f_0 = a`$, in real symbols.
    fn complex(&self, real: Polynomial, imaginary: Polynomial, harmonic: i32) -> Polynomial {
        let unit = if harmonic > 0 {
            Rational::ONE
        } else {
            -Rational::ONE
        };
        let i = Complex::imaginary(super::coefficient::ParameterPolynomial::constant(unit));
        real.plus(&imaginary.scaled(&i))
    }

    /// A symbol of the averaged term in real symbols.
    fn symbol(&self, symbol: &Symbol, parts: &PartIndex) -> Polynomial {
        match symbol.variable {
            Variable::Envelope(field) => {
                let part = self
                    .ansatz
                    .part(field, symbol.harmonic)
                    .expect("a symbol comes from a part of the ansatz");
                let real = self.field(part.real, symbol);
                let imaginary = part
                    .imaginary
                    .map_or_else(Polynomial::zero, |b| self.field(b, symbol));
                self.complex(real, imaginary, symbol.harmonic)
            }
            Variable::Average(index) => {
                let m = symbol.harmonic.abs();
                let part = |imaginary: bool| {
                    parts
                        .get(&(index, m, imaginary))
                        .map_or_else(Polynomial::zero, |&j| {
                            Polynomial::symbol(Symbol::new(Variable::AveragePart(j), 0))
                        })
                };
                self.complex(part(false), part(true), symbol.harmonic)
            }
            Variable::Field(_) | Variable::AveragePart(_) => Polynomial::symbol(*symbol),
        }
    }

    /// The non-zero real and imaginary parts of every kept harmonic of every averaged `let`.
    fn averaged_parts(
        &self,
        averaged: &[Averaged],
        truncation: &Truncation,
    ) -> Result<(Vec<AveragedPart>, PartIndex), TermError> {
        let mut parts = Vec::new();
        let mut index = PartIndex::new();
        for (k, quantity) in averaged.iter().enumerate() {
            for &m in &quantity.harmonics {
                let coefficient = quantity
                    .series
                    .harmonic(m)
                    .substitute(|symbol| self.symbol(symbol, &PartIndex::new()), truncation)
                    .map_err(TermError::TooLarge)?;
                let components = if m == 0 {
                    let real = real_part(&coefficient, "zeroth harmonic of an averaged let");
                    vec![(false, real, format!("mean({})", quantity.name))]
                } else {
                    let (real, imaginary) = components(&coefficient);
                    vec![
                        (false, real, format!("re({}[{m}])", quantity.name)),
                        (true, imaginary, format!("im({}[{m}])", quantity.name)),
                    ]
                };
                for (imaginary, definition, label) in components {
                    if definition.is_zero() {
                        continue;
                    }
                    index.insert((k, m, imaginary), parts.len());
                    parts.push(AveragedPart { label, definition });
                }
            }
        }
        Ok((parts, index))
    }
}

/// The real and imaginary parts of a polynomial in real symbols.
fn components(polynomial: &Polynomial) -> (Polynomial, Polynomial) {
    let mut real = Polynomial::zero();
    let mut imaginary = Polynomial::zero();
    for (monomial, value) in &polynomial.0 {
        real.add_term(
            monomial.clone(),
            Complex::real(value.real.with_unit_direction()),
        );
        imaginary.add_term(
            monomial.clone(),
            Complex::real(value.imaginary.with_unit_direction()),
        );
    }
    (real, imaginary)
}

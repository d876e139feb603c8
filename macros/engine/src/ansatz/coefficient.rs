//! Coefficients of the derivation's polynomials: polynomials in the model's parameters with
//! exact rational numbers ([`ParameterPolynomial`]), and complex numbers of them ([`Complex`],
//! $`i^2 = -1`$).
//!
//! An [`Atom`] is what the algebra does not expand further: a parameter, a parameter-only `let`
//! of the microscopic energy (kept by name, so that `bending_stiffness` prints as such), the
//! reciprocal of a parameter polynomial ($`1/(1-\nu^2)`$) or a function of one
//! ($`\cos\theta`$). Sums and products of parameters are expanded, so equal coefficients compare
//! equal and cancel exactly.

use std::collections::BTreeMap;
use std::collections::btree_map::Entry;

use super::rational::Rational;
use crate::graph::Function;

/// A factor the algebra keeps whole (module documentation).
#[derive(Clone, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Atom {
    /// A parameter-only `let` of the microscopic energy, by name, with its value.
    Named {
        /// The `let`'s name.
        name: String,
        /// Its value.
        definition: ParameterPolynomial,
    },
    /// Parameter number `k` of the derived model.
    Parameter(usize),
    /// $`1/p`$ of a parameter polynomial that is not a constant.
    Reciprocal(ParameterPolynomial),
    /// $`f(p)`$ of a parameter polynomial that is not a constant.
    Apply(Function, ParameterPolynomial),
}

/// A product of atoms with positive exponents, sorted by atom.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ParameterMonomial(pub Vec<(Atom, u32)>);

impl ParameterMonomial {
    /// The product of two monomials.
    fn times(&self, other: &ParameterMonomial) -> ParameterMonomial {
        let mut factors: BTreeMap<Atom, u32> = BTreeMap::new();
        for (atom, power) in self.0.iter().chain(&other.0) {
            *factors.entry(atom.clone()).or_insert(0) += power;
        }
        ParameterMonomial(factors.into_iter().collect())
    }
}

/// $`\sum_k r_k \prod_a a^{n_{ka}}`$ with rational $`r_k \ne 0`$ (module documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct ParameterPolynomial(pub BTreeMap<ParameterMonomial, Rational>);

impl ParameterPolynomial {
    /// $`0`$.
    pub fn zero() -> Self {
        Self::default()
    }

    /// A rational constant.
    pub fn constant(value: Rational) -> Self {
        let mut polynomial = Self::zero();
        polynomial.add_term(ParameterMonomial::default(), value);
        polynomial
    }

    /// One atom.
    pub fn atom(atom: Atom) -> Self {
        let mut polynomial = Self::zero();
        polynomial.add_term(ParameterMonomial(vec![(atom, 1)]), Rational::ONE);
        polynomial
    }

    /// Parameter number `index`.
    pub fn parameter(index: usize) -> Self {
        Self::atom(Atom::Parameter(index))
    }

    fn add_term(&mut self, monomial: ParameterMonomial, value: Rational) {
        if value.is_zero() {
            return;
        }
        match self.0.entry(monomial) {
            Entry::Vacant(vacant) => {
                vacant.insert(value);
            }
            Entry::Occupied(mut occupied) => {
                let sum = *occupied.get() + value;
                if sum.is_zero() {
                    occupied.remove();
                } else {
                    *occupied.get_mut() = sum;
                }
            }
        }
    }

    /// Whether this is $`0`$.
    pub fn is_zero(&self) -> bool {
        self.0.is_empty()
    }

    /// The value if this is a constant.
    pub fn as_constant(&self) -> Option<Rational> {
        match self.0.len() {
            0 => Some(Rational::ZERO),
            1 => self
                .0
                .iter()
                .next()
                .filter(|(monomial, _)| monomial.0.is_empty())
                .map(|(_, value)| *value),
            _ => None,
        }
    }

    /// $`a + b`$.
    pub fn plus(&self, other: &Self) -> Self {
        let mut sum = self.clone();
        for (monomial, value) in &other.0 {
            sum.add_term(monomial.clone(), *value);
        }
        sum
    }

    /// $`r\,a`$.
    pub fn scaled(&self, factor: Rational) -> Self {
        if factor.is_zero() {
            return Self::zero();
        }
        Self(
            self.0
                .iter()
                .map(|(monomial, value)| (monomial.clone(), *value * factor))
                .collect(),
        )
    }

    /// $`-a`$.
    pub fn negated(&self) -> Self {
        self.scaled(-Rational::ONE)
    }

    /// $`a\,b`$.
    pub fn times(&self, other: &Self) -> Self {
        let mut product = Self::zero();
        for (left, a) in &self.0 {
            for (right, b) in &other.0 {
                product.add_term(left.times(right), *a * *b);
            }
        }
        product
    }

    /// $`a^n`$, $`n \ge 0`$.
    pub fn power(&self, exponent: u32) -> Self {
        (0..exponent).fold(Self::constant(Rational::ONE), |product, _| {
            product.times(self)
        })
    }

    /// Whether this is one atom (to the power 1, coefficient 1).
    pub fn is_atom(&self) -> bool {
        let mut monomials = self.0.iter();
        match (monomials.next(), monomials.next()) {
            (Some((monomial, value)), None) => {
                *value == Rational::ONE && matches!(monomial.0[..], [(_, 1)])
            }
            _ => false,
        }
    }

    /// Number of monomials.
    pub fn term_count(&self) -> usize {
        self.0.len()
    }

    /// A monomial with $`\sin^n x`$, $`n \ge 2`$: the monomial, $`\sin x`$ and $`\cos x`$.
    fn sine_squared(&self) -> Option<(ParameterMonomial, Atom, Atom)> {
        self.0.keys().find_map(|monomial| {
            monomial.0.iter().find_map(|(atom, power)| match atom {
                Atom::Apply(Function::Sin, argument) if *power >= 2 => Some((
                    monomial.clone(),
                    atom.clone(),
                    Atom::Apply(Function::Cos, argument.clone()),
                )),
                _ => None,
            })
        })
    }

    /// Rewrites $`\sin^2 x = 1 - \cos^2 x`$ for every pair of atoms $`\cos x`$, $`\sin x`$ when
    /// that leaves fewer monomials (the derivation's $`Q^4(\cos^2\theta + \sin^2\theta)^2`$ is
    /// $`Q^4`$); otherwise returns the polynomial unchanged.
    pub fn with_unit_direction(&self) -> Self {
        let mut reduced = self.clone();
        while let Some((monomial, sine, cosine)) = reduced.sine_squared() {
            let value = reduced.0.remove(&monomial).expect("the monomial was found");
            let lowered: Vec<(Atom, u32)> = monomial
                .0
                .iter()
                .filter_map(|(atom, power)| match atom == &sine {
                    true if *power == 2 => None,
                    true => Some((atom.clone(), power - 2)),
                    false => Some((atom.clone(), *power)),
                })
                .collect();
            let lowered = ParameterMonomial(lowered);
            let cosine_squared = ParameterMonomial(vec![(cosine, 2)]);
            reduced.add_term(lowered.times(&cosine_squared), -value);
            reduced.add_term(lowered, value);
        }
        if reduced.term_count() < self.term_count() {
            reduced
        } else {
            self.clone()
        }
    }
}

/// $`a + ib`$ with parameter-polynomial parts.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Complex {
    /// Real part.
    pub real: ParameterPolynomial,
    /// Imaginary part.
    pub imaginary: ParameterPolynomial,
}

impl Complex {
    /// A real coefficient.
    pub fn real(real: ParameterPolynomial) -> Self {
        Self {
            real,
            imaginary: ParameterPolynomial::zero(),
        }
    }

    /// A rational constant.
    pub fn constant(value: Rational) -> Self {
        Self::real(ParameterPolynomial::constant(value))
    }

    /// $`1`$.
    pub fn one() -> Self {
        Self::constant(Rational::ONE)
    }

    /// $`i\,p`$.
    pub fn imaginary(imaginary: ParameterPolynomial) -> Self {
        Self {
            real: ParameterPolynomial::zero(),
            imaginary,
        }
    }

    /// Whether this is $`0`$.
    pub fn is_zero(&self) -> bool {
        self.real.is_zero() && self.imaginary.is_zero()
    }

    /// $`a + b`$.
    pub fn plus(&self, other: &Self) -> Self {
        Self {
            real: self.real.plus(&other.real),
            imaginary: self.imaginary.plus(&other.imaginary),
        }
    }

    /// $`a\,b`$ with $`i^2 = -1`$.
    pub fn times(&self, other: &Self) -> Self {
        let real = self
            .real
            .times(&other.real)
            .plus(&self.imaginary.times(&other.imaginary).negated());
        let imaginary = self
            .real
            .times(&other.imaginary)
            .plus(&self.imaginary.times(&other.real));
        Self { real, imaginary }
    }

    /// $`r\,a`$ for a rational $`r`$.
    pub fn scaled(&self, factor: Rational) -> Self {
        Self {
            real: self.real.scaled(factor),
            imaginary: self.imaginary.scaled(factor),
        }
    }

    /// $`\bar a`$ (parameters are real).
    pub fn conjugate(&self) -> Self {
        Self {
            real: self.real.clone(),
            imaginary: self.imaginary.negated(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn cos_sin(argument: usize) -> (ParameterPolynomial, ParameterPolynomial) {
        let theta = ParameterPolynomial::parameter(argument);
        (
            ParameterPolynomial::atom(Atom::Apply(Function::Cos, theta.clone())),
            ParameterPolynomial::atom(Atom::Apply(Function::Sin, theta)),
        )
    }

    #[test]
    fn parameter_polynomials_expand_and_cancel() {
        let nu = ParameterPolynomial::parameter(1);
        let one = ParameterPolynomial::constant(Rational::ONE);
        // (1 + ν)(1 − ν) − 1 + ν² = 0.
        let product = one.plus(&nu).times(&one.plus(&nu.negated()));
        let zero = product.plus(&one.negated()).plus(&nu.power(2));
        assert!(zero.is_zero());
        assert_eq!(product.term_count(), 2);
        assert_eq!(
            one.scaled(Rational::new(1, 2)).as_constant(),
            Some(Rational::new(1, 2))
        );
        assert_eq!(nu.as_constant(), None);
    }

    #[test]
    fn complex_products_use_i_squared_minus_one() {
        let q = ParameterPolynomial::parameter(0);
        let i_q = Complex::imaginary(q.clone());
        let square = i_q.times(&i_q);
        assert_eq!(square, Complex::real(q.power(2).negated()));
        assert_eq!(i_q.conjugate().plus(&i_q), Complex::default());
    }

    #[test]
    fn unit_direction_reduces_only_when_shorter() {
        let (c, s) = cos_sin(4);
        let unit = c.power(2).plus(&s.power(2));
        let reduced = unit.power(2).with_unit_direction();
        assert_eq!(reduced.as_constant(), Some(Rational::ONE));
        // 6c² + 2s² has two monomials either way: unchanged.
        let mixed = c
            .power(2)
            .scaled(Rational::integer(6))
            .plus(&s.power(2).scaled(Rational::integer(2)));
        assert_eq!(mixed.with_unit_direction(), mixed);
    }
}

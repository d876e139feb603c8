//! The derivation's normal form: polynomials whose monomials are products of *slow-jet
//! symbols* — a quantity, one of its harmonic indices and a derivative multi-index — with
//! [`Complex`] coefficients in the parameters.
//!
//! A field expanded as a Fourier series with slowly variable coefficients (THEORY.md §3, the
//! paper's (6)–(8)), $`f(\mathbf X) = \sum_m f_m(\mathbf X)\,e^{imQ\,\mathbf e\cdot\mathbf X}`$,
//! is represented by its coefficients $`f_m`$: the symbol $`\partial_X^{p}\partial_Y^{q} f_m`$ is
//! `Symbol { variable: Envelope(f), harmonic: m, derivative: (p, q) }`, and
//! $`f_{-m} = \overline{f_m}`$ ([`Polynomial::conjugate`]). The operations of a derivation:
//! * [`harmonic_derivative`]: the exact rule
//!   $`(\partial^\alpha f)_m = (\partial_X + imQe_X)^{\alpha_X}(\partial_Y + imQe_Y)^{\alpha_Y} f_m`$;
//! * products ([`Polynomial::times`]), with $`i^2 = -1`$ in the coefficients;
//! * [`Polynomial::zeroth_harmonic`]: the monomials whose harmonic indices sum to 0 — the
//!   period average (Parseval, $`(fg)_0 = \sum_m f_m g_{-m}`$);
//! * truncation by the order of slow derivatives ([`Monomial::slow_order`]: derivatives of
//!   non-zero harmonics — the envelopes — count, those of the zeroth harmonics, the macroscopic
//!   fields, do not), applied during products so that nothing beyond the order is ever formed;
//! * [`Polynomial::integrate_by_parts`] of monomials with a second slow derivative;
//! * [`Polynomial::substitute`]: the split of each complex coefficient into real fields.
//!
//! Monomials and coefficients are ordered maps and sorted vectors: every result, and the
//! order in which it is printed or emitted, is a function of the input alone.

use std::collections::BTreeMap;
use std::collections::btree_map::Entry;

use super::coefficient::{Complex, ParameterPolynomial};
use super::rational::Rational;

/// What a symbol is a harmonic coefficient of.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub enum Variable {
    /// The harmonic coefficients $`f_m`$ of microscopic field number `k`.
    Envelope(usize),
    /// The harmonic coefficients of averaged quantity number `k` (a microscopic `let` whose
    /// harmonics are taken before the rest of its term): real, so
    /// $`g_{-m} = \overline{g_m}`$; never differentiated.
    Average(usize),
    /// Real field number `k` of the derived model (harmonic 0), after the split.
    Field(usize),
    /// Real part number `k` of an averaged quantity (harmonic 0), after the split.
    AveragePart(usize),
}

/// $`\partial_X^{p}\partial_Y^{q}`$ of the harmonic-$`m`$ coefficient of a variable.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Symbol {
    /// The quantity.
    pub variable: Variable,
    /// Harmonic index $`m`$.
    pub harmonic: i32,
    /// Derivative multi-index $`(p, q)`$: $`p`$ derivatives along X, $`q`$ along Y.
    pub derivative: (u8, u8),
}

impl Symbol {
    /// The symbol of a variable itself, undifferentiated.
    pub fn new(variable: Variable, harmonic: i32) -> Symbol {
        Symbol {
            variable,
            harmonic,
            derivative: (0, 0),
        }
    }

    /// Total number of derivatives.
    pub fn derivative_order(&self) -> u32 {
        u32::from(self.derivative.0) + u32::from(self.derivative.1)
    }

    /// Slow derivatives that count for truncation: those of a non-zero harmonic.
    pub fn slow_order(&self) -> u32 {
        if self.harmonic == 0 {
            0
        } else {
            self.derivative_order()
        }
    }

    /// $`\overline{s}`$: the harmonic index changes sign.
    pub fn conjugate(&self) -> Symbol {
        Symbol {
            harmonic: -self.harmonic,
            ..*self
        }
    }

    /// One derivative fewer along `axis` (0 = X, 1 = Y), which the symbol has.
    fn lowered(&self, axis: usize) -> Symbol {
        let mut derivative = self.derivative;
        if axis == 0 {
            derivative.0 -= 1;
        } else {
            derivative.1 -= 1;
        }
        Symbol {
            derivative,
            ..*self
        }
    }

    /// One more derivative along `axis` (0 = X, 1 = Y).
    fn differentiated(&self, axis: usize) -> Symbol {
        let mut derivative = self.derivative;
        if axis == 0 {
            derivative.0 += 1;
        } else {
            derivative.1 += 1;
        }
        Symbol {
            derivative,
            ..*self
        }
    }
}

/// A product of symbols (repeated for powers), sorted.
#[derive(Clone, Debug, Default, PartialEq, Eq, PartialOrd, Ord, Hash)]
pub struct Monomial(pub Vec<Symbol>);

impl Monomial {
    fn times(&self, other: &Monomial) -> Monomial {
        let mut symbols = Vec::with_capacity(self.0.len() + other.0.len());
        symbols.extend_from_slice(&self.0);
        symbols.extend_from_slice(&other.0);
        symbols.sort_unstable();
        Monomial(symbols)
    }

    /// Sum of the harmonic indices: the monomial's own harmonic.
    pub fn harmonic(&self) -> i32 {
        self.0.iter().map(|symbol| symbol.harmonic).sum()
    }

    /// Sum of the slow orders of its symbols.
    pub fn slow_order(&self) -> u32 {
        self.0.iter().map(Symbol::slow_order).sum()
    }

    /// $`\partial_{axis}`$ of the monomial by the product rule: one monomial per factor.
    fn derivative(&self, axis: usize) -> Vec<Monomial> {
        (0..self.0.len())
            .map(|at| {
                let mut symbols = self.0.clone();
                symbols[at] = symbols[at].differentiated(axis);
                symbols.sort_unstable();
                Monomial(symbols)
            })
            .collect()
    }
}

/// The bound on a derivation's work: the monomials kept by truncation, and at most how many
/// a product may hold (a size, never a time: the result depends on the input alone).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Truncation {
    /// Highest slow order kept ([`Symbol::slow_order`]).
    pub order: u32,
    /// Most monomials one polynomial may have.
    pub max_monomials: usize,
}

/// A product exceeded [`Truncation::max_monomials`].
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct TooLarge {
    /// The bound.
    pub max_monomials: usize,
}

/// $`\sum_k c_k\,M_k`$: complex parameter coefficients $`c_k \ne 0`$ on distinct monomials.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Polynomial(pub BTreeMap<Monomial, Complex>);

impl Polynomial {
    /// $`0`$.
    pub fn zero() -> Self {
        Self::default()
    }

    /// A constant.
    pub fn constant(value: Complex) -> Self {
        let mut polynomial = Self::zero();
        polynomial.add_term(Monomial::default(), value);
        polynomial
    }

    /// One symbol.
    pub fn symbol(symbol: Symbol) -> Self {
        let mut polynomial = Self::zero();
        polynomial.add_term(Monomial(vec![symbol]), Complex::one());
        polynomial
    }

    /// Adds $`c\,M`$.
    pub fn add_term(&mut self, monomial: Monomial, value: Complex) {
        if value.is_zero() {
            return;
        }
        match self.0.entry(monomial) {
            Entry::Vacant(vacant) => {
                vacant.insert(value);
            }
            Entry::Occupied(mut occupied) => {
                let sum = occupied.get().plus(&value);
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

    /// Number of monomials.
    pub fn len(&self) -> usize {
        self.0.len()
    }

    /// Whether there are no monomials.
    pub fn is_empty(&self) -> bool {
        self.0.is_empty()
    }

    /// $`a + b`$.
    pub fn plus(&self, other: &Self) -> Self {
        let mut sum = self.clone();
        for (monomial, value) in &other.0 {
            sum.add_term(monomial.clone(), value.clone());
        }
        sum
    }

    /// $`c\,a`$.
    pub fn scaled(&self, factor: &Complex) -> Self {
        let mut product = Self::zero();
        for (monomial, value) in &self.0 {
            product.add_term(monomial.clone(), value.times(factor));
        }
        product
    }

    /// $`a\,b`$ without the monomials beyond `truncation.order`.
    pub fn times(&self, other: &Self, truncation: &Truncation) -> Result<Self, TooLarge> {
        let mut product = Self::zero();
        for (left, a) in &self.0 {
            let left_order = left.slow_order();
            for (right, b) in &other.0 {
                if left_order + right.slow_order() > truncation.order {
                    continue;
                }
                product.add_term(left.times(right), a.times(b));
                if product.len() > truncation.max_monomials {
                    return Err(TooLarge {
                        max_monomials: truncation.max_monomials,
                    });
                }
            }
        }
        Ok(product)
    }

    /// $`a^n`$, $`n \ge 0`$, truncated.
    pub fn power(&self, exponent: u32, truncation: &Truncation) -> Result<Self, TooLarge> {
        let mut product = Self::constant(Complex::one());
        for _ in 0..exponent {
            product = product.times(self, truncation)?;
        }
        Ok(product)
    }

    /// $`\bar a`$: every harmonic index and every coefficient's imaginary part change sign.
    pub fn conjugate(&self) -> Self {
        let mut conjugate = Self::zero();
        for (monomial, value) in &self.0 {
            let mut symbols: Vec<Symbol> = monomial.0.iter().map(Symbol::conjugate).collect();
            symbols.sort_unstable();
            conjugate.add_term(Monomial(symbols), value.conjugate());
        }
        conjugate
    }

    /// The harmonic-0 part: the monomials whose harmonic indices sum to 0 — the average over a
    /// period of the quantity the polynomial expands (Parseval).
    pub fn zeroth_harmonic(&self) -> Self {
        self.filtered(|monomial| monomial.harmonic() == 0)
    }

    /// The monomials of harmonic `m` (the coefficient of $`e^{imQ\,\mathbf e\cdot\mathbf X}`$).
    pub fn harmonic(&self, m: i32) -> Self {
        self.filtered(|monomial| monomial.harmonic() == m)
    }

    /// The distinct harmonics of the monomials, ascending.
    pub fn harmonics(&self) -> Vec<i32> {
        let mut harmonics: Vec<i32> = self.0.keys().map(Monomial::harmonic).collect();
        harmonics.sort_unstable();
        harmonics.dedup();
        harmonics
    }

    fn filtered(&self, keep: impl Fn(&Monomial) -> bool) -> Self {
        Self(
            self.0
                .iter()
                .filter(|(monomial, _)| keep(monomial))
                .map(|(monomial, value)| (monomial.clone(), value.clone()))
                .collect(),
        )
    }

    /// Integration by parts of the monomials $`c\,M\,\partial_k\partial_l s`$ with exactly one
    /// second-derivative factor, when $`M`$ vanishes on the boundary (one of its factors does,
    /// by `vanishes_on_boundary`) and can be differentiated (`differentiable`):
    /// $`M\,\partial_k\partial_l s \to -\tfrac12(\partial_k M\,\partial_l s + \partial_l M\,\partial_k s)`$,
    /// which is $`-\partial_k M\,\partial_k s`$ for $`k = l`$. The symmetric form for
    /// $`k \ne l`$ is rotation-covariant: the averaged Gaussian curvature of the plate, a null
    /// Lagrangian, cancels to exactly 0 for any wave direction. Returns the polynomial and
    /// how many monomials were integrated by parts.
    pub fn integrate_by_parts(
        &self,
        vanishes_on_boundary: impl Fn(&Symbol) -> bool,
        differentiable: impl Fn(&Symbol) -> bool,
    ) -> (Self, usize) {
        let mut result = Self::zero();
        let mut integrated = 0;
        for (monomial, value) in &self.0 {
            let second: Vec<usize> = (0..monomial.0.len())
                .filter(|&k| monomial.0[k].derivative_order() == 2)
                .collect();
            let [at] = second[..] else {
                result.add_term(monomial.clone(), value.clone());
                continue;
            };
            let mut rest = monomial.0.clone();
            let s = rest.remove(at);
            let rest = Monomial(rest);
            if !rest.0.iter().any(&vanishes_on_boundary) || !rest.0.iter().all(&differentiable) {
                result.add_term(monomial.clone(), value.clone());
                continue;
            }
            integrated += 1;
            // M ∂_k∂_l s → −½ ∂_l M ∂_k s, once per axis l of the second derivative of s (so
            // −∂_k M ∂_k s for k = l, the symmetric form for k ≠ l).
            let half = value.scaled(Rational::new(-1, 2));
            let axes: [usize; 2] = match s.derivative {
                (2, 0) => [0, 0],
                (0, 2) => [1, 1],
                _ => [0, 1],
            };
            for axis in axes {
                let lowered = s.lowered(axis);
                for term in rest.derivative(axis) {
                    result.add_term(term.times(&Monomial(vec![lowered])), half.clone());
                }
            }
        }
        (result, integrated)
    }

    /// Replaces every symbol by a polynomial (`replacement`, called once per distinct symbol)
    /// and expands: the split of complex coefficients into real fields.
    pub fn substitute(
        &self,
        mut replacement: impl FnMut(&Symbol) -> Polynomial,
        truncation: &Truncation,
    ) -> Result<Self, TooLarge> {
        let mut cache: BTreeMap<Symbol, Polynomial> = BTreeMap::new();
        let mut result = Self::zero();
        for (monomial, value) in &self.0 {
            let mut product = Self::constant(value.clone());
            for symbol in &monomial.0 {
                let replaced = cache
                    .entry(*symbol)
                    .or_insert_with(|| replacement(symbol))
                    .clone();
                product = product.times(&replaced, truncation)?;
            }
            result = result.plus(&product);
        }
        Ok(result)
    }
}

/// The carrier wave $`e^{iQ\,\mathbf e\cdot\mathbf X}`$: wavenumber $`Q`$ and direction
/// $`\mathbf e = (e_X, e_Y)`$, as parameter polynomials.
#[derive(Clone, Debug)]
pub struct Wave {
    /// $`Q`$.
    pub wavenumber: ParameterPolynomial,
    /// $`(e_X, e_Y)`$.
    pub direction: [ParameterPolynomial; 2],
}

fn binomial(n: u8, k: u8) -> Rational {
    (0..k).fold(Rational::ONE, |product, j| {
        product * Rational::new(i128::from(n - j), i128::from(j + 1))
    })
}

/// $`i^n`$ times a real coefficient.
fn times_i_power(real: ParameterPolynomial, n: u32) -> Complex {
    match n % 4 {
        0 => Complex::real(real),
        1 => Complex::imaginary(real),
        2 => Complex::real(real.negated()),
        _ => Complex::imaginary(real.negated()),
    }
}

/// The harmonic-$`m`$ coefficient of a derivative of a field (THEORY.md §3, the paper's (7)):
/// $$`(\partial_X^{p}\partial_Y^{q} f)_m = (\partial_X + imQe_X)^{p}\,(\partial_Y + imQe_Y)^{q}\,f_m
/// = \sum_{k \le p,\ l \le q}\binom pk\binom ql (imQe_X)^{p-k}(imQe_Y)^{q-l}\,
/// \partial_X^k\partial_Y^l f_m .`$$
pub fn harmonic_derivative(
    variable: Variable,
    harmonic: i32,
    derivative: (u8, u8),
    wave: &Wave,
) -> Polynomial {
    let (p, q) = derivative;
    let m = ParameterPolynomial::constant(Rational::integer(i128::from(harmonic)));
    let along = [
        m.times(&wave.wavenumber).times(&wave.direction[0]),
        m.times(&wave.wavenumber).times(&wave.direction[1]),
    ];
    let mut result = Polynomial::zero();
    for k in 0..=p {
        for l in 0..=q {
            let (a, b) = (u32::from(p - k), u32::from(q - l));
            let real = along[0]
                .power(a)
                .times(&along[1].power(b))
                .scaled(binomial(p, k) * binomial(q, l));
            let symbol = Symbol {
                variable,
                harmonic,
                derivative: (k, l),
            };
            let mut term = Polynomial::zero();
            term.add_term(Monomial(vec![symbol]), times_i_power(real, a + b));
            result = result.plus(&term);
        }
    }
    result
}

#[cfg(test)]
mod tests {
    use super::*;

    const WIDE: Truncation = Truncation {
        order: 8,
        max_monomials: 10_000,
    };

    /// $`Q`$ = parameter 0, $`\mathbf e = (1, 0)`$.
    fn along_x() -> Wave {
        Wave {
            wavenumber: ParameterPolynomial::parameter(0),
            direction: [
                ParameterPolynomial::constant(Rational::ONE),
                ParameterPolynomial::zero(),
            ],
        }
    }

    fn coefficient(polynomial: &Polynomial, symbols: &[Symbol]) -> Complex {
        let mut key = symbols.to_vec();
        key.sort_unstable();
        polynomial
            .0
            .get(&Monomial(key))
            .cloned()
            .unwrap_or_default()
    }

    fn q_power(n: u32, factor: i128) -> Complex {
        Complex::real(
            ParameterPolynomial::parameter(0)
                .power(n)
                .scaled(Rational::integer(factor)),
        )
    }

    /// $`(\partial_X^2 f)_1 = f_{1,XX} + 2iQ f_{1,X} - Q^2 f_1`$ (THEORY.md §3).
    #[test]
    fn second_derivative_rule_of_the_first_harmonic() {
        let f = Variable::Envelope(0);
        let rule = harmonic_derivative(f, 1, (2, 0), &along_x());
        assert_eq!(rule.len(), 3);
        let with = |d| Symbol {
            variable: f,
            harmonic: 1,
            derivative: d,
        };
        assert_eq!(coefficient(&rule, &[with((2, 0))]), Complex::one());
        assert_eq!(
            coefficient(&rule, &[with((1, 0))]),
            Complex::imaginary(ParameterPolynomial::parameter(0).scaled(Rational::integer(2)))
        );
        assert_eq!(coefficient(&rule, &[with((0, 0))]), q_power(2, -1));
        // The zeroth harmonic is differentiated as it is.
        let mean = harmonic_derivative(f, 0, (1, 1), &along_x());
        assert_eq!(
            mean,
            Polynomial::symbol(Symbol {
                variable: f,
                harmonic: 0,
                derivative: (1, 1)
            })
        );
    }

    /// The beam's bending $`\tfrac12(v'')^2`$ with $`v = v_1e^{iQX} + \bar v_1e^{-iQX}`$: its
    /// zeroth harmonic to two slow derivatives, integrated by parts, is
    /// $`Q^4|v_1|^2 + 4Q^2|v_1'|^2 + Q^2(\ldots)`$ with the $`-Q^2(\bar v_1 v_1'' + v_1\bar v_1'')`$
    /// turned into $`+2Q^2|v_1'|^2`$, and the order-one terms $`\pm 2iQ^3`$ in
    /// $`\bar v_1 v_1' - v_1\bar v_1'`$: (14)'s $`EI(Q^4v_1^2 + 6Q^2v_1'^2)`$ for a real $`v_1`$.
    #[test]
    fn beam_bending_averages_to_equation_14() {
        let v = Variable::Envelope(0);
        let curvature = harmonic_derivative(v, 1, (2, 0), &along_x()).plus(&harmonic_derivative(
            v,
            -1,
            (2, 0),
            &along_x(),
        ));
        let two = Truncation { order: 2, ..WIDE };
        let square = curvature.times(&curvature, &two).unwrap();
        let averaged = square.zeroth_harmonic();
        assert!(averaged.0.keys().all(|m| m.slow_order() <= 2));
        let (integrated, count) = averaged.integrate_by_parts(
            |s| matches!(s.variable, Variable::Envelope(_)) && s.harmonic != 0,
            |_| true,
        );
        assert_eq!(count, 2);
        let at = |harmonic, derivative| Symbol {
            variable: v,
            harmonic,
            derivative,
        };
        let (v1, w1) = (at(1, (0, 0)), at(-1, (0, 0)));
        let (d1, e1) = (at(1, (1, 0)), at(-1, (1, 0)));
        // (v'')² averaged = 2|(v'')_1|²: 2Q⁴|v1|² + 8Q²|v1'|² + 4Q²|v1'|² (by parts) = 12Q².
        assert_eq!(coefficient(&integrated, &[v1, w1]), q_power(4, 2));
        assert_eq!(coefficient(&integrated, &[d1, e1]), q_power(2, 12));
        let order_one = coefficient(&integrated, &[w1, d1]);
        assert_eq!(
            order_one,
            Complex::imaginary(
                ParameterPolynomial::parameter(0)
                    .power(3)
                    .scaled(Rational::integer(-4))
            )
        );
        assert_eq!(coefficient(&integrated, &[v1, e1]), order_one.conjugate());
        assert_eq!(integrated.len(), 4);
        assert_eq!(integrated.conjugate(), integrated);
    }

    #[test]
    fn truncation_bounds_the_products() {
        let v = Variable::Envelope(0);
        let slope = harmonic_derivative(v, 1, (1, 0), &along_x());
        let zero_order = Truncation { order: 0, ..WIDE };
        let square = slope.times(&slope, &zero_order).unwrap();
        assert_eq!(square.len(), 1);
        let tiny = Truncation {
            order: 8,
            max_monomials: 2,
        };
        assert_eq!(
            slope.times(&slope, &tiny),
            Err(TooLarge { max_monomials: 2 })
        );
    }
}

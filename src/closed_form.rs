//! Closed-form results for the clamped rectangle (THEORY.md §8, the paper's eqs. 40–62 and 96):
//! the independent truths that numerical results are checked against.
//!
//! The rectangle $`[0, L_X]\times[0, L_Y]`$ carries a tension $`N_Y > 0`$ and a compression
//! $`N_X = -\lambda`$; the envelope is clamped ($`w = 0`$ on the boundary). With
//! $`w = \sin(\pi X/L_X)\sin(\pi Y/L_Y)`$ in the linearised envelope equation (32) the neutral
//! curve is (42)
//! $$`\lambda(Q) = \frac{6DQ^2\pi^2/L_X^2 + (2DQ^2 + N_Y)\pi^2/L_Y^2 + DQ^4}{Q^2 + \pi^2/L_X^2}.`$$
//!
//! The post-bifurcation coefficient $`C(\alpha)`$ of (62) is a one-term Galerkin approximation of
//! the stress-function problem (55); [`stress_function`] solves that problem with many terms.

pub mod stress_function;

use std::f64::consts::PI;

/// Bending stiffness $`D = E h^3 / (12 (1 - \nu^2))`$ (N·mm).
pub fn bending_stiffness(young_modulus: f64, thickness: f64, poisson_ratio: f64) -> f64 {
    young_modulus * thickness.powi(3) / (12.0 * (1.0 - poisson_ratio * poisson_ratio))
}

/// Wavelength $`\ell = 2\pi/Q`$ (mm) of wrinkles of wavenumber $`Q`$ (1/mm).
pub fn wavelength(wavenumber: f64) -> f64 {
    2.0 * PI / wavenumber
}

/// A clamped rectangle in tension–compression (THEORY.md §8).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ClampedRectangle {
    /// $`L_X`$ (mm).
    pub length_x: f64,
    /// $`L_Y`$ (mm).
    pub length_y: f64,
    /// $`h`$ (mm).
    pub thickness: f64,
    /// $`E`$ (MPa).
    pub young_modulus: f64,
    /// $`\nu`$.
    pub poisson_ratio: f64,
    /// $`N_Y`$ (N/mm), the tension along Y.
    pub tension_y: f64,
}

impl ClampedRectangle {
    /// The paper's example 1: $`L_X = 400`$, $`L_Y = 200`$, $`h = 0.05`$, $`E = 70000`$,
    /// $`\nu = 0.3`$, $`N_Y = 10`$.
    pub fn example_one() -> Self {
        ClampedRectangle {
            length_x: 400.0,
            length_y: 200.0,
            thickness: 0.05,
            young_modulus: 70000.0,
            poisson_ratio: 0.3,
            tension_y: 10.0,
        }
    }

    /// Bending stiffness $`D`$ of the sheet.
    pub fn bending_stiffness(&self) -> f64 {
        bending_stiffness(self.young_modulus, self.thickness, self.poisson_ratio)
    }

    /// Coefficients $`(a, b, c)`$ of (42) written in $`s = Q^2`$:
    /// $`\lambda(s) = (D s^2 + a s + b)/(s + c)`$ with $`a = 6D\pi^2/L_X^2 + 2D\pi^2/L_Y^2`$,
    /// $`b = N_Y\pi^2/L_Y^2`$, $`c = \pi^2/L_X^2`$.
    fn neutral_curve_coefficients(&self) -> (f64, f64, f64) {
        let stiffness = self.bending_stiffness();
        let inverse_x = PI * PI / (self.length_x * self.length_x);
        let inverse_y = PI * PI / (self.length_y * self.length_y);
        let linear = 6.0 * stiffness * inverse_x + 2.0 * stiffness * inverse_y;
        (linear, self.tension_y * inverse_y, inverse_x)
    }

    /// Neutral curve (42): the compression $`\lambda = -N_X`$ at which the mode
    /// $`\sin(\pi X/L_X)\sin(\pi Y/L_Y)`$ of wavenumber $`Q`$ is neutrally stable.
    pub fn neutral_curve(&self, wavenumber: f64) -> f64 {
        let (linear, constant, shift) = self.neutral_curve_coefficients();
        let square = wavenumber * wavenumber;
        (self.bending_stiffness() * square * square + linear * square + constant) / (square + shift)
    }

    /// Exact minimiser of (42): returns $`(\lambda_c, Q_c)`$.
    ///
    /// Written in $`s = Q^2`$, (42) is the rational function
    /// $`\lambda(s) = (D s^2 + a s + b)/(s + c)`$ (see `neutral_curve_coefficients`), so
    /// $$`\frac{d\lambda}{ds} = \frac{(2Ds + a)(s + c) - (Ds^2 + as + b)}{(s + c)^2}
    ///   = \frac{D s^2 + 2Dc\,s + (ac - b)}{(s + c)^2}.`$$
    /// Stationarity is the quadratic $`s^2 + 2c\,s - \delta = 0`$ with
    /// $`\delta = (b - ac)/D`$, whose only positive root is
    /// $`s^* = -c + \sqrt{c^2 + \delta} = \delta/(c + \sqrt{c^2 + \delta})`$ (the second form has
    /// no cancellation). It is a minimum: the numerator grows with $`s`$, so $`\lambda`$ falls
    /// on $`(0, s^*)`$ and rises after. The root is polished by Newton's method on the
    /// quadratic (at most 4 steps, stopping when the step is below $`10^{-16} s^*`$), so
    /// $`Q_c = \sqrt{s^*}`$ and $`\lambda_c = \lambda(s^*)`$ are accurate to rounding
    /// (~1e-15 relative; the brute-force scan of `tests/closed_form_table1.rs` agrees to 1e-9).
    ///
    /// Returns `None` when $`\delta \le 0`$, i.e. $`N_Y \le D\pi^2/L_X^2\,(6L_Y^2/L_X^2 + 2)`$
    /// (tension too small): then $`\lambda`$ increases with $`Q`$ and has no wrinkling minimum.
    pub fn critical_point(&self) -> Option<(f64, f64)> {
        let stiffness = self.bending_stiffness();
        let (linear, constant, shift) = self.neutral_curve_coefficients();
        let excess = (constant - linear * shift) / stiffness;
        if !(excess.is_finite() && excess > 0.0) {
            return None;
        }
        let mut square = excess / (shift + (shift * shift + excess).sqrt());
        for _ in 0..4 {
            let residual = (square + 2.0 * shift) * square - excess;
            let step = residual / (2.0 * (square + shift));
            square -= step;
            if step.abs() <= 1e-16 * square {
                break;
            }
        }
        let wavenumber = square.sqrt();
        Some((self.neutral_curve(wavenumber), wavenumber))
    }

    /// Approximate wrinkling wavenumber (44):
    /// $`Q_{wr} = (12\pi^2(1-\nu^2))^{1/4} (h L_Y)^{-1/2} (\sigma_Y/E)^{1/4}`$ with
    /// $`\sigma_Y = N_Y/h`$.
    pub fn approximate_wavenumber(&self) -> f64 {
        let stress_y = self.tension_y / self.thickness;
        let poisson_factor = 1.0 - self.poisson_ratio * self.poisson_ratio;
        (12.0 * PI * PI * poisson_factor).powf(0.25) / (self.thickness * self.length_y).sqrt()
            * (stress_y / self.young_modulus).powf(0.25)
    }

    /// Approximate wrinkling stress magnitude (44):
    /// $`|\sigma_X^{wr}| = \pi/\sqrt{3(1-\nu^2)}\,\sqrt{E\sigma_Y}\,h/L_Y`$ (MPa).
    pub fn approximate_wrinkling_stress(&self) -> f64 {
        let stress_y = self.tension_y / self.thickness;
        let poisson_factor = 1.0 - self.poisson_ratio * self.poisson_ratio;
        PI / (3.0 * poisson_factor).sqrt() * (self.young_modulus * stress_y).sqrt() * self.thickness
            / self.length_y
    }

    /// Approximate critical load $`\lambda_0 = 2 D Q_{wr}^2`$ (N/mm); equals
    /// $`h\,|\sigma_X^{wr}|`$ of (44).
    pub fn approximate_critical_load(&self) -> f64 {
        let wavenumber = self.approximate_wavenumber();
        2.0 * self.bending_stiffness() * wavenumber * wavenumber
    }

    /// Wrinkling stress magnitude with the asymptotic correction (96):
    /// $`|\sigma_X^{wr2}| = |\sigma_X^{wr1}| + E\,\pi^2/(6(1-\nu^2))\,(2h^2/L_X^2 + h^2/L_Y^2)`$ (MPa).
    pub fn corrected_wrinkling_stress(&self) -> f64 {
        let poisson_factor = 1.0 - self.poisson_ratio * self.poisson_ratio;
        let thickness_squared = self.thickness * self.thickness;
        let correction = PI * PI / (6.0 * poisson_factor)
            * (2.0 * thickness_squared / (self.length_x * self.length_x)
                + thickness_squared / (self.length_y * self.length_y));
        self.approximate_wrinkling_stress() + self.young_modulus * correction
    }

    /// Aspect ratio $`\alpha = L_Y/L_X`$ of the Galerkin analysis.
    pub fn aspect_ratio(&self) -> f64 {
        self.length_y / self.length_x
    }

    /// Amplitude coefficient $`C(\alpha, \nu)`$ of (62) for this rectangle.
    pub fn amplitude_coefficient(&self) -> f64 {
        amplitude_coefficient(self.aspect_ratio(), self.poisson_ratio)
    }
}

/// Gauss–Legendre rule with `points` nodes on $`[-1, 1]`$: `(nodes, weights)`, nodes ascending.
///
/// Nodes are the roots of $`P_n`$, found by Newton's method from the asymptotic guess
/// $`\cos(\pi(i - 1/4)/(n + 1/2))`$; weights are $`2/((1 - x^2) P_n'(x)^2)`$.
/// Exact for polynomials of degree $`\le 2n - 1`$. `points = 0` gives empty vectors.
pub fn gauss_legendre(points: usize) -> (Vec<f64>, Vec<f64>) {
    let mut nodes = vec![0.0; points];
    let mut weights = vec![0.0; points];
    let order = points as f64;
    for index in 0..points.div_ceil(2) {
        let mut node = (PI * (index as f64 + 0.75) / (order + 0.5)).cos();
        let mut derivative = 1.0;
        for _ in 0..100 {
            let (value, slope) = legendre_with_derivative(points, node);
            derivative = slope;
            let step = value / slope;
            node -= step;
            if step.abs() <= 1e-16 {
                break;
            }
        }
        let (_, slope) = legendre_with_derivative(points, node);
        if slope.is_finite() {
            derivative = slope;
        }
        let weight = 2.0 / ((1.0 - node * node) * derivative * derivative);
        nodes[index] = -node;
        nodes[points - 1 - index] = node;
        weights[index] = weight;
        weights[points - 1 - index] = weight;
    }
    if points % 2 == 1 {
        nodes[points / 2] = 0.0;
    }
    (nodes, weights)
}

/// $`(P_n(x), P_n'(x))`$ by the three-term recurrence.
fn legendre_with_derivative(degree: usize, x: f64) -> (f64, f64) {
    let mut previous = 1.0;
    let mut current = x;
    if degree == 0 {
        return (1.0, 0.0);
    }
    for k in 2..=degree {
        let k = k as f64;
        let next = ((2.0 * k - 1.0) * x * current - (k - 1.0) * previous) / k;
        previous = current;
        current = next;
    }
    let degree = degree as f64;
    let derivative = degree * (x * current - previous) / (x * x - 1.0);
    (current, derivative)
}

/// The four dimensionless integrals of the Galerkin post-bifurcation analysis (57), (60).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct GalerkinIntegrals {
    /// $`I_1(\alpha) = \iint (\alpha^2 W_{rr} + W_{ss})^2`$.
    pub i1: f64,
    /// $`I_2 = \iint [1 - \cos\pi(1+r)]\cos\pi(1+s)\,W`$.
    pub i2: f64,
    /// $`I_3 = \iint (w^{(1)})^2 = 1`$.
    pub i3: f64,
    /// $`I_4 = \iint W_{ss}\,(w^{(1)})^2`$.
    pub i4: f64,
}

/// Galerkin integrals on $`[-1, 1]^2`$ with $`W = f(r) f(s)`$, $`f(x) = (1-x^2)^2`$, and
/// $`w^{(1)} = \cos(\pi r/2)\cos(\pi s/2)`$, in closed form.
///
/// Every integrand is a product of a function of $`r`$ and one of $`s`$, and the one-dimensional
/// moments are (repeated integration by parts; $`f`$ and $`f'`$ vanish at $`\pm 1`$, so
/// $`\int f''\cos\pi x = -\pi^2\int f\cos\pi x`$)
/// $$`\int f = \tfrac{16}{15},\quad \int f^2 = \tfrac{256}{315},\quad
///   \int f''^2 = \tfrac{128}{5},\quad \int f f'' = -\tfrac{256}{105},\quad
///   \int f\cos\pi x = \tfrac{48}{\pi^4},\quad \int f''\cos\pi x = -\tfrac{48}{\pi^2}.`$$
/// With $`1 - \cos\pi(1+r) = 1 + \cos\pi r`$, $`\cos\pi(1+s) = -\cos\pi s`$ and
/// $`\cos^2(\pi x/2) = (1 + \cos\pi x)/2`$:
/// $$`I_1(\alpha) = (1 + \alpha^4)\,\tfrac{128}{5}\cdot\tfrac{256}{315} +
///   2\alpha^2\left(\tfrac{256}{105}\right)^2,\qquad
///   I_2 = -\left(\tfrac{16}{15} + \tfrac{48}{\pi^4}\right)\tfrac{48}{\pi^4},`$$
/// $$`I_3 = 1,\qquad I_4 = -\tfrac{12}{\pi^2}\left(\tfrac{16}{15} + \tfrac{48}{\pi^4}\right)
///   = \tfrac{\pi^2}{4} I_2.`$$
/// (`tests/closed_form_table1.rs` checks them against 64-point Gauss quadrature.)
pub fn galerkin_integrals(aspect_ratio: f64) -> GalerkinIntegrals {
    let alpha_squared = aspect_ratio * aspect_ratio;
    let cosine_moment = 48.0 / PI.powi(4);
    let shifted_mean = 16.0 / 15.0 + cosine_moment;
    GalerkinIntegrals {
        i1: (1.0 + alpha_squared * alpha_squared) * (128.0 / 5.0) * (256.0 / 315.0)
            + 2.0 * alpha_squared * (256.0f64 / 105.0).powi(2),
        i2: -shifted_mean * cosine_moment,
        i3: 1.0,
        i4: -12.0 / (PI * PI) * shifted_mean,
    }
}

/// Amplitude coefficient (62): $`C(\alpha,\nu) = \sqrt{2 I_1 I_3 / (3\pi^2(1-\nu^2) I_2 I_4)}`$,
/// so that $`a/h = C\sqrt{\lambda/\lambda_0 - 1}`$ ($`a`$ is the *envelope* amplitude; the peak
/// physical deflection is $`2a`$).
pub fn amplitude_coefficient(aspect_ratio: f64, poisson_ratio: f64) -> f64 {
    let integrals = galerkin_integrals(aspect_ratio);
    (2.0 * integrals.i1 * integrals.i3
        / (3.0 * PI * PI * (1.0 - poisson_ratio * poisson_ratio) * integrals.i2 * integrals.i4))
        .sqrt()
}

/// Load ratio (61): $`\lambda/\lambda_0 = 1 + (3/2)\pi^2(1-\nu^2)\,I_2 I_4/(I_1 I_3)\,(a/h)^2
/// = 1 + (a/h)^2/C^2`$.
pub fn load_ratio_from_amplitude(
    aspect_ratio: f64,
    poisson_ratio: f64,
    amplitude_over_thickness: f64,
) -> f64 {
    let integrals = galerkin_integrals(aspect_ratio);
    1.0 + 1.5 * PI * PI * (1.0 - poisson_ratio * poisson_ratio) * integrals.i2 * integrals.i4
        / (integrals.i1 * integrals.i3)
        * amplitude_over_thickness
        * amplitude_over_thickness
}

/// Inverse of [`load_ratio_from_amplitude`] (62): $`a/h = C\sqrt{\lambda/\lambda_0 - 1}`$;
/// zero below the bifurcation ($`\lambda/\lambda_0 \le 1`$).
pub fn amplitude_from_load_ratio(aspect_ratio: f64, poisson_ratio: f64, load_ratio: f64) -> f64 {
    if load_ratio <= 1.0 {
        return 0.0;
    }
    amplitude_coefficient(aspect_ratio, poisson_ratio) * (load_ratio - 1.0).sqrt()
}

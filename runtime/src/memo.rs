//! The functions the model DSL allows on parameter-only expressions ($`\sin`$, $`\cos`$,
//! $`e^x`$, $`\ln`$), each remembering its last argument on each thread.
//!
//! A generated kernel evaluates its parameter-only subexpressions at every call, i.e. at every
//! quadrature point of every sweep: the reference envelope's $`\cos\theta`$ and
//! $`\sin\theta`$ of the wave direction cost 2 % of a whole run (128 × 64) in `sincos`,
//! called with the same argument millions of times. Here each function keeps its last
//! argument's bits and value in a thread-local cell: the same argument returns the same value
//! without the call, any other argument is computed (a point-varying parameter simply misses).
//! The value is the function's own, bit for bit, on every thread and in every order.

use std::cell::Cell;

/// Defines `$name(x) = x.$method()` remembering the last argument; `$at_zero` is the value at
/// $`x = +0`$ (the cell's initial entry).
macro_rules! remembering {
    ($(#[$documentation:meta])* $name:ident, $method:ident, $at_zero:expr) => {
        $(#[$documentation])*
        #[inline]
        pub fn $name(x: f64) -> f64 {
            thread_local! {
                static LAST: Cell<(u64, f64)> = const { Cell::new((0, $at_zero)) };
            }
            LAST.with(|last| {
                let (bits, value) = last.get();
                if bits == x.to_bits() {
                    value
                } else {
                    let value = x.$method();
                    last.set((x.to_bits(), value));
                    value
                }
            })
        }
    };
}

remembering!(
    /// $`\sin x`$ ([`f64::sin`]).
    sin,
    sin,
    0.0
);
remembering!(
    /// $`\cos x`$ ([`f64::cos`]).
    cos,
    cos,
    1.0
);
remembering!(
    /// $`e^x`$ ([`f64::exp`]).
    exp,
    exp,
    1.0
);
remembering!(
    /// $`\ln x`$ ([`f64::ln`]).
    ln,
    ln,
    f64::NEG_INFINITY
);

#[cfg(test)]
mod tests {
    use super::*;

    /// Bit for bit the functions' own values, for a repeated argument, a new one, the
    /// initial entry's $`+0`$, and $`-0`$ (a different bit pattern with the same value).
    #[test]
    fn remembered_values_are_the_functions_own() {
        let arguments = [
            0.0,
            -0.0,
            0.3,
            0.3,
            -1.7,
            0.3,
            1e-300,
            2.5,
            2.5,
            f64::NAN,
            0.0,
        ];
        for x in arguments {
            assert_eq!(sin(x).to_bits(), x.sin().to_bits(), "sin {x}");
            assert_eq!(cos(x).to_bits(), x.cos().to_bits(), "cos {x}");
            assert_eq!(exp(x).to_bits(), x.exp().to_bits(), "exp {x}");
            assert_eq!(ln(x).to_bits(), x.ln().to_bits(), "ln {x}");
        }
        // Another thread starts from the initial entry.
        std::thread::spawn(|| {
            assert_eq!(cos(0.0).to_bits(), 1.0f64.to_bits());
            assert_eq!(ln(0.0), f64::NEG_INFINITY);
            assert_eq!(sin(0.7).to_bits(), 0.7f64.sin().to_bits());
        })
        .join()
        .unwrap();
    }
}

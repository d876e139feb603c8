//! Microscopic energies the envelope models are derived from, each written once and shared by
//! every ansatz that expands it (`docs/dsl.md`, "Envelope models derived from a microscopic
//! energy").
//!
//! A microscopic energy is never a model of its own here — the Kirchhoff plate needs second
//! derivatives of `w`, which Q8 elements do not have — but the `microscopic` block of a derived
//! model. Each macro below takes a model declaration (`model Name as "name" { … }`, with its
//! fields, parameters, `ansatz` and `average(…)` terms) and hands it to
//! `wrinkle_macros::energy_model!` with the microscopic energy appended to its body, so that
//! a derived model's file holds only what is its own:
//!
//! ```ignore
//! wrinkle_models::from_kirchhoff_plate! {
//!     /// Reference envelope model derived from the Kirchhoff plate.
//!     model DerivedReferenceEnvelope as "derived-reference-envelope" {
//!         fields: u [displacement_x], v [displacement_y], w [envelope];
//!         parameters: wavenumber, direction;
//!         ansatz { wavenumber: wavenumber; direction: direction;
//!                  u = u; v = v; w = 2 Re(w e^{i Q e.X}); }
//!         energy membrane = average(membrane, mean(gx, gy, gxy));
//!         energy bending = average(bending);
//!     }
//! }
//! ```

/// Declares a model derived from the **Föppl–von Kármán plate with Kirchhoff bending**
/// (THEORY.md §2, the paper's (16)–(17)), the microscopic energy `kirchhoff_plate`:
/// fields `u`, `v`, `w`; parameters `young` (E, MPa), `poisson` (ν), `thickness` (h, mm), which
/// become the derived model's first parameters; lets `membrane_stiffness` $`= Eh/(1-\nu^2)`$,
/// `bending_stiffness` $`D = Eh^3/(12(1-\nu^2))`$ and the membrane strain
/// $`\gamma = \varepsilon(u) + \tfrac12\nabla w\otimes\nabla w`$ as `gx`, `gy`, `gxy`
/// (Voigt, $`2\gamma_{XY}`$); terms
/// $$`\texttt{membrane} = \tfrac12\gamma\cdot L_m\gamma,\qquad
/// \texttt{bending} = \tfrac D2\left[(\Delta w)^2 - 2(1-\nu)(w_{,XX}w_{,YY} - w_{,XY}^2)\right].`$$
#[macro_export]
macro_rules! from_kirchhoff_plate {
    ($(#[$attribute:meta])* model $name:ident as $registry:literal { $($body:tt)* }) => {
        $crate::__macros::energy_model! {
            $(#[$attribute])*
            model $name as $registry {
                $($body)*
                microscopic kirchhoff_plate {
                    fields: u, v, w;
                    parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio",
                        thickness "thickness h (mm)";
                    let membrane_stiffness = young * thickness / (1 - poisson^2);
                    let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
                    let gx = u.x + 0.5 * w.x^2;
                    let gy = v.y + 0.5 * w.y^2;
                    let gxy = u.y + v.x + w.x * w.y;
                    energy membrane = 0.5 * membrane_stiffness
                        * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
                    energy bending = 0.5 * bending_stiffness
                        * ((w.xx + w.yy)^2 - 2 * (1 - poisson) * (w.xx * w.yy - w.xy^2));
                }
            }
        }
    };
}

/// Declares a model derived from the **beam on a nonlinear elastic foundation** (THEORY.md §7,
/// the paper's (1)–(3)), the microscopic energy `beam`: fields `u` (axial displacement) and
/// `v` (deflection) of $`X`$; parameters `axial_stiffness` (ES, N), `beam_bending_stiffness`
/// (EI, N mm²), `foundation` (c, N/mm²), `cubic_foundation` (c₃, N/mm⁴); terms
/// $$`\texttt{stretching} = \tfrac{ES}2\left(u' + \tfrac12 v'^2\right)^2,\quad
/// \texttt{bending} = \tfrac{EI}2 v''^2,\quad
/// \texttt{support} = \tfrac c2 v^2 + \tfrac{c_3}4 v^4,`$$
/// the axial strain being the let `strain`.
#[macro_export]
macro_rules! from_beam {
    ($(#[$attribute:meta])* model $name:ident as $registry:literal { $($body:tt)* }) => {
        $crate::__macros::energy_model! {
            $(#[$attribute])*
            model $name as $registry {
                $($body)*
                microscopic beam {
                    fields: u, v;
                    parameters: axial_stiffness "ES (N)", beam_bending_stiffness "EI (N mm^2)",
                        foundation "c (N/mm^2)", cubic_foundation "c3 (N/mm^4)";
                    let strain = u.x + 0.5 * v.x^2;
                    energy stretching = 0.5 * axial_stiffness * strain^2;
                    energy bending = 0.5 * beam_bending_stiffness * v.xx^2;
                    energy support = 0.5 * foundation * v^2 + 0.25 * cubic_foundation * v^4;
                }
            }
        }
    };
}

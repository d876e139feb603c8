//! Derivations from a microscopic energy through the engine, without the proc macro: the
//! derivation report of the reference ansatz, determinism, the size bound, and the errors of a
//! malformed ansatz or a non-polynomial energy (messages; their spans are checked by the
//! trybuild cases of `macros/proc/tests/ui/`).

use proc_macro2::TokenStream;
use quote::quote;
use wrinkle_energy::{expand, parse_and_lower};

/// The Kirchhoff FvK plate (THEORY.md §2) as a `microscopic` block, with `extra` appended to
/// its items.
fn kirchhoff_plate(extra: TokenStream) -> TokenStream {
    quote! {
        microscopic kirchhoff_plate {
            fields: u, v, w;
            parameters: young, poisson, thickness;
            let membrane_stiffness = young * thickness / (1 - poisson^2);
            let bending_stiffness = young * thickness^3 / (12 * (1 - poisson^2));
            let gx = u.x + 0.5 * w.x^2;
            let gy = v.y + 0.5 * w.y^2;
            let gxy = u.y + v.x + w.x * w.y;
            energy membrane = 0.5 * membrane_stiffness
                * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
            energy bending = 0.5 * bending_stiffness
                * ((w.xx + w.yy)^2 - 2 * (1 - poisson) * (w.xx * w.yy - w.xy^2));
            #extra
        }
    }
}

/// The reference ansatz with `terms` as the derived terms.
fn reference(terms: TokenStream, extra: TokenStream) -> TokenStream {
    let plate = kirchhoff_plate(extra);
    quote! {
        /// Derived reference envelope.
        model DerivedReferenceEnvelope as "derived-reference-envelope" {
            fields: u [displacement_x], v [displacement_y], w [envelope];
            parameters: wavenumber, direction;
            #plate
            ansatz {
                wavenumber: wavenumber;
                direction: direction;
                u = u;
                v = v;
                w = 2 Re(w e^{i Q e.X});
            }
            #terms
        }
    }
}

fn error_text(tokens: TokenStream) -> String {
    match parse_and_lower(tokens) {
        Ok(_) => panic!("the declaration should not compile"),
        Err(error) => error
            .into_iter()
            .map(|e| e.to_string())
            .collect::<Vec<_>>()
            .join("\n"),
    }
}

/// The report gives the paper's densities: (20)–(23) for the averaged strain, (64) for the
/// bending (with $`(\cos^2\theta + \sin^2\theta)^2`$ folded to 1), in DSL syntax.
#[test]
fn reference_derivation_reports_the_papers_densities() {
    let terms = quote! {
        energy membrane = average(membrane, mean(gx, gy, gxy));
        energy bending = average(bending);
    };
    let lowered = parse_and_lower(reference(terms, quote!())).unwrap();
    let report = lowered.derivation.expect("a derived model has a report");
    for line in [
        "mean(gx) = u.x + wavenumber^2*cos(direction)^2*w^2 + w.x^2",
        "mean(gy) = v.y + wavenumber^2*sin(direction)^2*w^2 + w.y^2",
        "membrane = membrane_stiffness*(1/2*mean(gx)^2 + poisson*mean(gx)*mean(gy) + 1/2*mean(gy)^2 + (1/4 - 1/4*poisson)*mean(gxy)^2)",
        "bending = bending_stiffness*wavenumber^2*(wavenumber^2*w^2 + (6*sin(direction)^2 + 2*cos(direction)^2)*w.y^2 + 8*sin(direction)*cos(direction)*w.y*w.x + (2*sin(direction)^2 + 6*cos(direction)^2)*w.x^2)",
        "w = 2 Re(w e^{i Q e.X})",
        "term `bending`: 33 monomials expanded, 15 in its zeroth harmonic, 6 integrated by parts, 4 derived",
    ] {
        assert!(report.contains(line), "missing `{line}` in\n{report}");
    }
    assert_eq!(
        lowered
            .parameters
            .iter()
            .map(|p| p.name.to_string())
            .collect::<Vec<_>>(),
        ["young", "poisson", "thickness", "wavenumber", "direction"]
    );
}

/// Two expansions of the same derived model are the same text (no hash-map order, no clock).
#[test]
fn derived_expansion_is_deterministic() {
    let terms = quote! {
        energy membrane = average(membrane, truncated(gx, gy, gxy));
        energy bending = average(bending);
    };
    let first = expand(reference(terms.clone(), quote!())).to_string();
    let second = expand(reference(terms, quote!())).to_string();
    assert_eq!(first, second);
    assert!(!first.contains("compile_error"), "{first}");
}

/// A derivation that would form more monomials than the bound stops with an error, at once.
#[test]
fn derivation_work_is_bounded_by_size() {
    let tokens = quote! {
        /// Many harmonics, high degree, no truncation.
        model Huge as "huge" {
            fields: w0 [mean_deflection], a [envelope_real], b [envelope_imaginary], c, d, f, g;
            parameters: wavenumber;
            microscopic big {
                fields: w;
                energy e = (w.x + w.y + w.xx)^10;
            }
            ansatz {
                wavenumber: wavenumber;
                slow_derivatives: 30;
                w = w0 + 2 Re((a + i b) e^{i Q e.X}) + 2 Re((c + i d) e^{2 i Q e.X}) + 2 Re((f + i g) e^{3 i Q e.X});
            }
            energy e = average(e);
        }
    };
    let message = error_text(tokens);
    assert!(message.contains("exceeds 50000 monomials"), "{message}");
}

#[test]
fn non_polynomial_energies_are_errors() {
    for (energy, expected) in [
        (quote!(sin(w)), "`sin` of an expression of the fields"),
        (quote!(1 / w.x), "division by an expression of the fields"),
        (
            quote!(w ^ -2),
            "negative power of an expression of the fields",
        ),
        (
            quote!(sqrt(young) * exp(w.y)),
            "`exp` of an expression of the fields",
        ),
    ] {
        let terms = quote!(energy bad = average(odd););
        let extra = quote!(energy odd = #energy;);
        let message = error_text(reference(terms, extra));
        assert!(message.contains(expected), "{energy}: {message}");
        assert!(message.contains("polynomial in the fields"), "{message}");
    }
}

#[test]
fn malformed_ansatz_is_an_error() {
    let model = |ansatz: TokenStream, terms: TokenStream| {
        let plate = kirchhoff_plate(quote!());
        quote! {
            model M as "m" {
                fields: u [displacement_x], v [displacement_y], w [envelope], q;
                parameters: wavenumber;
                #plate
                ansatz { wavenumber: wavenumber; #ansatz }
                #terms
            }
        }
    };
    let bending = quote!(energy bending = average(bending););
    for (ansatz, terms, expected) in [
        (
            quote!(u = u; v = v; z = 2 Re(w e^{i Q e.X});),
            bending.clone(),
            "`z` is not a field of the microscopic energy `kirchhoff_plate`",
        ),
        (
            quote!(u = u; v = v; w = 2 Re(w1 e^{i Q e.X});),
            bending.clone(),
            "`w1` is not a field of the model",
        ),
        (
            quote!(u = u; w = 2 Re(w e^{i Q e.X});),
            bending.clone(),
            "the ansatz does not expand the microscopic field `v`",
        ),
        (
            quote!(u = u; v = v; w = 2 Re(w e^{1.5 i Q e.X});),
            bending.clone(),
            "the harmonic index must be a non-negative integer literal",
        ),
        (
            quote!(u = u; v = v; w = 2 Re(w e^{i Q e.X}) + 2 Re(q e^{1 i Q e.X});),
            bending.clone(),
            "harmonic 1 of `w` is given twice",
        ),
        (
            quote!(u = u; v = v; w = 2 Re(w e^{i Q e.X});),
            quote!(energy bending = average(shear);),
            "`shear` is not an energy term of the microscopic energy",
        ),
        (
            quote!(u = u; v = v; w = 2 Re(w e^{i Q e.X});),
            quote!(energy bending = average(bending, mean(strain), without(q));),
            "`strain` is not a `let` of the microscopic energy",
        ),
    ] {
        let message = error_text(model(ansatz.clone(), terms));
        assert!(message.contains(expected), "{ansatz}: {message}");
    }
}

#[test]
fn average_without_a_microscopic_energy_is_an_error() {
    let tokens = quote! {
        model M as "m" {
            fields: w;
            energy e = average(bending);
        }
    };
    let message = error_text(tokens);
    assert!(
        message.contains("declares no `microscopic` energy"),
        "{message}"
    );
}

//! End-to-end checks of the symbolic pipeline without the proc macro: parse + lower models
//! from `quote!` token streams, then verify the simplified kernels with the interpreter
//! against the unsimplified derivatives and against finite differences of the energy.

use proc_macro2::TokenStream;
use quote::quote;
use wrinkle_energy::{
    CompiledModel, Derivative, FieldRole, SimplificationLimits, StopKind, TermKernel, analyze,
    parse_and_lower,
};

/// A tiny deterministic generator (64-bit LCG, top 53 bits) for reproducible points.
struct Lcg(u64);

impl Lcg {
    fn uniform(&mut self, low: f64, high: f64) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        let unit = (self.0 >> 11) as f64 / (1u64 << 53) as f64;
        low + (high - low) * unit
    }
}

fn reference_envelope() -> TokenStream {
    quote! {
        /// Reference envelope model of Damil, Potier-Ferry & Hu (2014), eqs 22, 23, 64.
        model ReferenceEnvelope as "reference-envelope" {
            fields: u, v, w;
            parameters: young "Young's modulus E (MPa)", poisson "Poisson ratio", thickness, wavenumber, direction;
            let c = cos(direction);
            let s = sin(direction);
            let stiffness = young * thickness / (1 - poisson^2);
            let d = young * thickness^3 / (12 * (1 - poisson^2));
            let gx = u.x + w.x^2 + (wavenumber * c)^2 * w^2;
            let gy = v.y + w.y^2 + (wavenumber * s)^2 * w^2;
            let gxy = u.y + v.x + 2 * w.x * w.y + 2 * wavenumber^2 * c * s * w^2;
            energy membrane = 0.5 * stiffness * (gx^2 + gy^2 + 2 * poisson * gx * gy + 0.5 * (1 - poisson) * gxy^2);
            energy bending = d * (wavenumber^4 * w^2 + 6 * wavenumber^2 * (c * w.x + s * w.y)^2
                                  + 2 * wavenumber^2 * (c * w.y - s * w.x)^2);
        }
    }
}

const ENVELOPE_PARAMETERS: [f64; 5] = [3.5, 0.3, 0.2, 1.7, 0.4];

fn compiled(tokens: TokenStream) -> CompiledModel {
    analyze(tokens, &SimplificationLimits::default()).expect("model compiles")
}

fn relative_error(value: f64, truth: f64, scale: f64) -> f64 {
    (value - truth).abs() / truth.abs().max(scale)
}

fn random_jet(random: &mut Lcg, length: usize) -> Vec<f64> {
    (0..length).map(|_| random.uniform(-0.8, 0.8)).collect()
}

fn evaluate(
    term: &TermKernel,
    root: wrinkle_energy::NodeId,
    parameters: &[f64],
    jet: &[f64],
) -> f64 {
    term.graph
        .evaluate(root, parameters, jet)
        .expect("evaluates")
}

fn evaluate_reference(
    term: &TermKernel,
    root: wrinkle_energy::NodeId,
    parameters: &[f64],
    jet: &[f64],
) -> f64 {
    term.reference
        .graph
        .evaluate(root, parameters, jet)
        .expect("evaluates")
}

#[test]
fn reference_envelope_metadata_is_sorted_and_term_local() {
    let model = compiled(reference_envelope());
    assert_eq!(model.model.fields, ["u", "v", "w"]);
    assert_eq!(
        model.model.description(),
        "Reference envelope model of Damil, Potier-Ferry & Hu (2014), eqs 22, 23, 64."
    );
    let jet: Vec<(usize, Derivative)> = model
        .model
        .jet
        .iter()
        .map(|entry| (entry.field, entry.derivative))
        .collect();
    assert_eq!(
        jet,
        [
            (0, Derivative::X),
            (0, Derivative::Y),
            (1, Derivative::X),
            (1, Derivative::Y),
            (2, Derivative::Value),
            (2, Derivative::X),
            (2, Derivative::Y),
        ]
    );
    assert_eq!(model.terms[0].jet, [0, 1, 2, 3, 4, 5, 6]);
    // Bending reads w, w.x, w.y only.
    assert_eq!(model.terms[1].jet, [4, 5, 6]);
    // Bending: w is decoupled from its gradient; w.x and w.y are coupled.
    assert_eq!(
        model.terms[1].tangent_pattern,
        [(0, 0), (1, 1), (1, 2), (2, 2)]
    );
    // The membrane Hessian: u.x, u.y, v.x, v.y enter linearly through the strains, so
    // u.x–u.y, u.x–v.x, u.y–v.y and v.x–v.y couplings are structurally zero
    // (gxy = u.y + v.x couples u.y with v.x).
    let membrane = &model.terms[0];
    for zero in [(0, 1), (0, 2), (1, 3), (2, 3)] {
        assert!(!membrane.tangent_pattern.contains(&zero), "{zero:?}");
    }
    assert!(membrane.tangent_pattern.contains(&(1, 2)));
    assert!(membrane.tangent_pattern.contains(&(0, 3)));
}

#[test]
fn simplification_preserves_values_and_zeros_are_structural() {
    let model = compiled(reference_envelope());
    let mut random = Lcg(7);
    for term in &model.terms {
        for _ in 0..20 {
            let jet = random_jet(&mut random, model.model.jet.len());
            let p = &ENVELOPE_PARAMETERS;
            let energy = evaluate(term, term.energy, p, &jet);
            let truth = evaluate_reference(term, term.reference.energy, p, &jet);
            assert!(
                relative_error(energy, truth, 1e-300) < 1e-12,
                "{energy} vs {truth}"
            );
            for (index, &root) in term.residual.iter().enumerate() {
                let value = evaluate(term, root, p, &jet);
                let truth = evaluate_reference(term, term.reference.residual[index], p, &jet);
                assert!(
                    relative_error(value, truth, 1e-12) < 1e-12,
                    "term {} residual {index}: {value} vs {truth}",
                    term.name
                );
            }
            for &((i, j), root) in &term.reference.tangent {
                let reference_value = evaluate_reference(term, root, p, &jet);
                match term
                    .tangent_pattern
                    .iter()
                    .position(|&entry| entry == (i, j))
                {
                    Some(position) => {
                        let value = evaluate(term, term.tangent[position], p, &jet);
                        assert!(
                            relative_error(value, reference_value, 1e-12) < 1e-12,
                            "term {} tangent ({i},{j}): {value} vs {reference_value}",
                            term.name
                        );
                    }
                    None => assert_eq!(
                        reference_value, 0.0,
                        "term {} entry ({i},{j}) left out of the pattern is not zero",
                        term.name
                    ),
                }
            }
        }
    }
}

/// Central finite difference of `function` in direction `index` of `jet`.
fn central_difference(jet: &[f64], index: usize, function: impl Fn(&[f64]) -> f64) -> f64 {
    let step = 1e-5;
    let mut plus = jet.to_vec();
    let mut minus = jet.to_vec();
    plus[index] += step;
    minus[index] -= step;
    (function(&plus) - function(&minus)) / (2.0 * step)
}

#[test]
fn residual_and_tangent_match_finite_differences() {
    let model = compiled(reference_envelope());
    let mut random = Lcg(11);
    let p = &ENVELOPE_PARAMETERS;
    for term in &model.terms {
        for _ in 0..10 {
            let jet = random_jet(&mut random, model.model.jet.len());
            for (local, &entry) in term.jet.iter().enumerate() {
                let exact = evaluate(term, term.residual[local], p, &jet);
                let difference =
                    central_difference(&jet, entry, |x| evaluate(term, term.energy, p, x));
                assert!(
                    relative_error(difference, exact, 1.0) < 1e-7,
                    "term {} residual {local}: FD {difference} vs {exact}",
                    term.name
                );
            }
            for i in 0..term.jet.len() {
                for j in i..term.jet.len() {
                    let exact = term
                        .tangent_pattern
                        .iter()
                        .position(|&entry| entry == (i, j))
                        .map_or(0.0, |position| {
                            evaluate(term, term.tangent[position], p, &jet)
                        });
                    let difference = central_difference(&jet, term.jet[j], |x| {
                        evaluate(term, term.residual[i], p, x)
                    });
                    assert!(
                        relative_error(difference, exact, 1.0) < 1e-7,
                        "term {} tangent ({i},{j}): FD {difference} vs {exact}",
                        term.name
                    );
                }
            }
        }
    }
}

#[test]
fn egg_finds_structural_zeros_hash_consing_misses() {
    // The two w.x*w.y products are built in different orders, so only the e-graph can see
    // that they cancel: the w.x and w.y residuals and every tangent entry touching them
    // must be structurally zero, while the jet still lists them.
    let model = compiled(quote! {
        /// Cancellation.
        model Cancel as "cancel" {
            fields: w;
            parameters: k;
            energy spurious = k * w.x * w.y - w.y * (k * w.x) + k * w^4;
        }
    });
    let term = &model.terms[0];
    assert_eq!(term.jet, [0, 1, 2]);
    assert!(!term.residual_is_zero(0));
    assert!(term.residual_is_zero(1));
    assert!(term.residual_is_zero(2));
    assert_eq!(term.tangent_pattern, [(0, 0)]);
    // And the dropped entries are really zero.
    let mut random = Lcg(3);
    for _ in 0..10 {
        let jet = random_jet(&mut random, 3);
        for &(_, root) in &term.reference.tangent[1..] {
            let value = term.reference.graph.evaluate(root, &[2.5], &jet).unwrap();
            assert!(value.abs() < 1e-14, "{value}");
        }
        // k * 12 w^2.
        let value = evaluate(term, term.tangent[0], &[2.5], &jet);
        assert!(relative_error(value, 2.5 * 12.0 * jet[0] * jet[0], 1e-300) < 1e-12);
    }
}

#[test]
fn decoupled_fields_give_a_diagonal_pattern() {
    let model = compiled(quote! {
        /// Two springs.
        model Springs as "springs" {
            fields: u, w;
            parameters: a, b;
            energy springs [reduced] = a * u.x^2 + b * w^2;
        }
    });
    let term = &model.terms[0];
    assert_eq!(term.quadrature, wrinkle_energy::Quadrature::Reduced);
    assert_eq!(term.tangent_pattern, [(0, 0), (1, 1)]);
    let jet = [0.3, -0.2];
    assert_eq!(evaluate(term, term.tangent[0], &[1.5, 4.0], &jet), 3.0);
    assert_eq!(evaluate(term, term.tangent[1], &[1.5, 4.0], &jet), 8.0);
}

#[test]
fn report_states_why_the_egraph_stopped() {
    let model = compiled(reference_envelope());
    assert_eq!(model.report.lines().count(), 2);
    for (line, term) in model.report.lines().zip(&model.terms) {
        assert!(line.starts_with(&format!("term `{}`", term.name)), "{line}");
        assert!(
            line.contains(&format!("stopped: {}", term.statistics.stop)),
            "{line}"
        );
        assert!(line.contains(&format!("e-graph {} nodes", term.statistics.nodes)));
    }
    let tight = SimplificationLimits {
        node_limit: 60,
        ..SimplificationLimits::default()
    };
    let limited = analyze(reference_envelope(), &tight).unwrap();
    assert!(
        matches!(limited.terms[0].statistics.stop, StopKind::NodeLimit(size) if size > 60),
        "{}",
        limited.report
    );
    assert!(
        limited
            .report
            .contains("stopped: node limit (e-graph reached")
    );
    let one_iteration = SimplificationLimits {
        iteration_limit: 1,
        ..SimplificationLimits::default()
    };
    let limited = analyze(reference_envelope(), &one_iteration).unwrap();
    assert!(
        limited
            .report
            .contains("stopped: iteration limit (1 iterations)")
    );
    let small = compiled(quote! {
        /// Linear spring.
        model Spring as "spring" { fields: w; energy spring = w^2; }
    });
    assert_eq!(small.terms[0].statistics.stop, StopKind::Saturated);
    assert!(small.report.contains("stopped: saturated"));
}

#[test]
fn large_polynomial_energies_stay_within_limits_and_generate_valid_rust() {
    let tokens = quote! {
        /// Several polynomial terms.
        model Polynomial as "polynomial" {
            fields: u, v, w;
            parameters: a "first", b, c;
            let g = u.x + 0.5 * w.x^2 - a * w;
            let h = v.y + 0.5 * w.y^2 + b * u;
            energy first = a * g^2 + b * h^2 + c * g * h + a * b * w^4 + c * (u.y + v.x + w.x * w.y)^2;
            energy second = (u + v + w)^3 + a * u * v * w + b * (u.x - v.y)^2 + c * w.x^3 * w.y + u^2 * v^2;
            energy third = a * w^2 + b * w.x^2 + c * w.y^2 + a * b * w * w.x + b * c * w.x * w.y;
        }
    };
    let limits = SimplificationLimits::default();
    let model = analyze(tokens.clone(), &limits).unwrap();
    let mut random = Lcg(5);
    let p = [0.7, -1.3, 2.1];
    for term in &model.terms {
        let statistics = &term.statistics;
        assert!(statistics.iterations <= limits.iteration_limit);
        // egg checks the node limit between rule applications, so allow one iteration of overshoot.
        assert!(statistics.nodes <= 4 * limits.node_limit, "{statistics:?}");
        assert!(
            matches!(
                statistics.stop,
                StopKind::Saturated | StopKind::NodeLimit(_) | StopKind::IterationLimit(_)
            ),
            "{statistics:?}"
        );
        assert!(
            statistics.operations_after <= statistics.operations_before,
            "{statistics:?}"
        );
        for _ in 0..5 {
            let jet = random_jet(&mut random, model.model.jet.len());
            for (local, &entry) in term.jet.iter().enumerate() {
                let exact = evaluate(term, term.residual[local], &p, &jet);
                let difference =
                    central_difference(&jet, entry, |x| evaluate(term, term.energy, &p, x));
                assert!(relative_error(difference, exact, 1.0) < 1e-7);
            }
        }
    }
    let generated = wrinkle_energy::expand_with_limits(tokens, &limits);
    let file: syn::File = syn::parse2(generated.clone()).expect("generated code parses");
    assert_eq!(file.items.len(), 3, "struct, inherent impl, trait impl");
    let text = generated.to_string();
    assert!(text.contains("impl :: wrinkle_runtime :: EnergyModel for Polynomial"));
    assert!(!text.contains("compile_error"));
}

fn error_messages(tokens: TokenStream) -> Vec<String> {
    match parse_and_lower(tokens) {
        Ok(_) => panic!("expected errors"),
        Err(error) => error.into_iter().map(|e| e.to_string()).collect(),
    }
}

#[test]
fn validation_collects_several_errors() {
    let messages = error_messages(quote! {
        /// Broken.
        model Broken as "broken" {
            fields: u, w, w;
            parameters: k;
            let a = k * q;
            energy one = sin(w) + w.xxx + k.x;
            energy two [gauss] = tan(k) * w;
        }
    });
    let expected = [
        "duplicate name `w`",
        "unknown identifier `q`",
        "`sin` can only be applied to parameters and constants",
        "unsupported derivative `w.xxx`",
        "unsupported derivative: `k` is a parameter",
        "unknown quadrature rule `gauss`",
        "unknown function `tan`",
    ];
    assert_eq!(messages.len(), expected.len(), "{messages:#?}");
    for fragment in expected {
        assert!(
            messages.iter().any(|message| message.contains(fragment)),
            "missing {fragment:?} in {messages:#?}"
        );
    }
}

#[test]
fn model_level_errors_are_reported() {
    let no_term = error_messages(quote! { model Empty as "empty" { fields: w; } });
    assert_eq!(no_term.len(), 1);
    assert!(no_term[0].contains("declares no `energy` term"));
    let unused =
        error_messages(quote! { model Unused as "unused" { fields: u, w; energy e = w^2; } });
    assert_eq!(unused, ["field `u` is used by no energy term"]);
    let constant = error_messages(quote! {
        model Constant as "constant" { fields: w; parameters: k; energy e = w^2; energy f = k * 2; }
    });
    assert!(constant[0].contains("energy term `f` depends on no field"));
    let missing_name = error_messages(quote! { model Nameless { fields: w; energy e = w^2; } });
    assert!(missing_name[0].contains("expected `as \"registry-name\"`"));
    let exponent = error_messages(quote! {
        model Exponent as "exponent" { fields: w; parameters: n; energy e = w^n + w^2.5; }
    });
    assert_eq!(exponent.len(), 2, "{exponent:?}");
    assert!(exponent[0].contains("exponent must be an integer literal"));
    assert!(exponent[1].contains("non-integer `2.5`"));
}

#[test]
fn exponents_outside_the_supported_range_are_errors_that_state_it() {
    let messages = error_messages(quote! {
        model Powers as "powers" {
            fields: w;
            energy e = w^65 + w.x^-2147483648 + (w.y^8)^9 + w^2^7 + w^-64;
        }
    });
    // Written exponents are checked by the parser, a power of a power when it is lowered.
    assert_eq!(messages.len(), 4, "{messages:#?}");
    for (message, found) in messages.iter().zip([
        "exponent `65`",
        "exponent `-2147483648`",
        "exponent `128`",
        "the exponent 72",
    ]) {
        assert!(message.contains(found), "{message}");
        assert!(
            message.contains("out of range: exponents are integers from -64 to 64"),
            "{message}"
        );
    }
}

#[test]
fn exponents_at_the_ends_of_the_range_differentiate_and_simplify() {
    // w^-64 differentiates to w^-65 and w^-66, and the e-graph collects w^63 w^63 into w^126:
    // exponents the engine makes beyond the written range.
    let model = compiled(quote! {
        model Extremes as "extremes" {
            fields: w;
            energy e = w^-64 + w^64 + w^63 * w^63 + w.x^2;
        }
    });
    let term = &model.terms[0];
    let jet = [1.01, 0.3];
    let residual = evaluate(term, term.residual[0], &[], &jet);
    let truth = -64.0 * 1.01f64.powi(-65) + 64.0 * 1.01f64.powi(63) + 126.0 * 1.01f64.powi(125);
    assert!(
        relative_error(residual, truth, 1e-300) < 1e-12,
        "{residual} vs {truth}"
    );
    let tangent = evaluate(term, term.tangent[0], &[], &jet);
    let truth = 64.0 * 65.0 * 1.01f64.powi(-66)
        + 64.0 * 63.0 * 1.01f64.powi(62)
        + 126.0 * 125.0 * 1.01f64.powi(124);
    assert!(
        relative_error(tangent, truth, 1e-300) < 1e-12,
        "{tangent} vs {truth}"
    );
}

#[test]
fn power_binds_tighter_than_unary_minus_and_is_right_associative() {
    let model = compiled(quote! {
        model Precedence as "precedence" {
            fields: w;
            energy e = -w^2 + 2 * w^2^2 - 3 / w.x^-1;
        }
    });
    let term = &model.terms[0];
    // Model jet: w (0), w.x (1).  e = -w^2 + 2 w^4 - 3 w.x
    let (w, wx) = (0.7, -0.4);
    let value = evaluate(term, term.energy, &[], &[w, wx]);
    let truth = -w * w + 2.0 * w.powi(4) - 3.0 * wx;
    assert!(
        relative_error(value, truth, 1e-300) < 1e-14,
        "{value} vs {truth}"
    );
}

#[test]
fn field_roles_are_parsed_validated_and_default_to_other() {
    let lowered = parse_and_lower(quote! {
        model Plate as "plate" {
            fields: u [displacement_x], w [deflection], c;
            energy e = u.x^2 + w.x^2 + c^2;
        }
    })
    .expect("valid model");
    assert_eq!(
        lowered.field_roles,
        vec![
            FieldRole::DisplacementX,
            FieldRole::Deflection,
            FieldRole::Other
        ]
    );
    let unknown = error_messages(quote! {
        model Bad as "bad" { fields: w [transverse]; energy e = w^2; }
    });
    assert!(
        unknown[0].contains("unknown field role `transverse`"),
        "{unknown:?}"
    );
    assert!(unknown[0].contains("`deflection`"), "{unknown:?}");
    let twice = error_messages(quote! {
        model Bad as "bad" { fields: w [envelope], z [envelope], o [other], p [other];
            energy e = w^2 + z^2 + o^2 + p^2; }
    });
    assert_eq!(twice.len(), 1, "{twice:?}");
    assert!(
        twice[0].contains("already the role of field `w`"),
        "{twice:?}"
    );
}

#[test]
fn taylor_programs_tape_only_what_recurrences_read() {
    use wrinkle_energy::taylor::{Instruction, TaylorProgram};
    let model = compiled(reference_envelope());
    let membrane = &model.terms[0];
    let bending = &model.terms[1];
    let program = TaylorProgram::new(&membrane.graph, &membrane.residual, &membrane.jet);
    assert!(!program.is_linear());
    // Every operand of a product is on the tape, and nothing else but quotient histories.
    // No operand is a constant scaling of another register (`2 w_x`, `−w`, `w + w`): the
    // scaling is applied to the product, and the scaled copy needs no slot (14 slots → 9 here),
    // and `w`, shared by three products of ∂ψ/∂w, is factored out of them (9 slots → 7).
    let scaled = |r: usize| {
        matches!(
            program.instructions[r],
            Instruction::Scale(..)
                | Instruction::DivideByReal(..)
                | Instruction::Negate(_)
                | Instruction::Double(_)
        )
    };
    assert!(
        !program
            .instructions
            .iter()
            .any(|i| matches!(*i, Instruction::Add(a, b) if a == b)),
        "a register added to itself is a doubling"
    );
    for instruction in &program.instructions {
        if let Instruction::Multiply(a, b) = *instruction {
            assert!(program.slot_of[a].is_some() && program.slot_of[b].is_some());
            assert!(!scaled(a) && !scaled(b), "{instruction:?}");
        }
        if let Instruction::Square(a) = *instruction {
            assert!(program.slot_of[a].is_some());
            assert!(!scaled(a), "{instruction:?}");
        }
    }
    assert_eq!(program.slots, 7, "slots");
    let recurrences = program
        .instructions
        .iter()
        .filter(|i| matches!(i, Instruction::Multiply(..) | Instruction::Square(_)))
        .count();
    assert_eq!(recurrences, 9, "products and squares");
    eprintln!(
        "membrane: {} instructions, {} tape slots",
        program.instructions.len(),
        program.slots
    );
    let program = TaylorProgram::new(&bending.graph, &bending.residual, &bending.jet);
    assert!(program.is_linear());
    assert_eq!(program.slots, 0);
    assert!(program.zero_in_prediction.iter().all(|&z| z));
}

#[test]
fn a_stopping_parse_error_keeps_the_errors_collected_before_it() {
    let parsed = wrinkle_energy::parse_model(quote! {
        /// Broken late.
        model Late as "late" {
            fields: w;
            parameters: k;
            energy a [gauss] = k * w^65;
            energy b = w.x^2
            energy c = w^2;
        }
    });
    let wrinkle_energy::ParsedModel::Partial { outline, errors } = parsed else {
        panic!("expected a partial parse, got {parsed:?}");
    };
    let messages: Vec<String> = errors.iter().map(ToString::to_string).collect();
    assert_eq!(messages.len(), 3, "{messages:#?}");
    assert!(messages[0].contains("unknown quadrature rule `gauss`"));
    assert!(messages[1].contains("exponent `65`"));
    assert_eq!(messages[2], "expected `;`");
    assert_eq!(outline.name, "Late");
    assert_eq!(outline.registry_name.as_deref(), Some("late"));
    assert_eq!(outline.parameters.len(), 1);
}

/// The items of an expansion that are not `compile_error!` invocations, and how many of those
/// there are.
fn expanded_items(tokens: TokenStream) -> (Vec<syn::Item>, usize) {
    let file: syn::File =
        syn::parse2(wrinkle_energy::expand(tokens)).expect("the expansion parses as Rust items");
    let (errors, items): (Vec<syn::Item>, Vec<syn::Item>) =
        file.items.into_iter().partition(|item| {
            matches!(item, syn::Item::Macro(m)
                if m.mac.path.segments.last().is_some_and(|s| s.ident == "compile_error"))
        });
    (items, errors.len())
}

#[test]
fn errors_come_with_a_stand_in_for_the_model_when_its_name_parsed() {
    // A validation error: the stand-in has the declared parameters.
    let (items, errors) = expanded_items(quote! {
        /// Misspelt.
        model Misspelt as "misspelt" { fields: w; parameters: k, k; energy e = k * wx^2; }
    });
    assert_eq!(errors, 2, "unknown `wx` and the duplicate `k`");
    assert_eq!(items.len(), 3, "struct, inherent impl, trait impl");
    let syn::Item::Struct(definition) = &items[0] else {
        panic!("expected the struct first");
    };
    assert_eq!(definition.ident, "Misspelt");
    assert_eq!(definition.fields.len(), 1, "each parameter name once");
    // A parse error after the name: still a stand-in.
    let (items, errors) = expanded_items(quote! { model Nameless { fields: w; } });
    assert_eq!((items.len(), errors), (3, 1));
    // Before the name: only the error.
    let (items, errors) = expanded_items(quote! { modl Typo as "typo" { fields: w; } });
    assert_eq!((items.len(), errors), (0, 1));
}

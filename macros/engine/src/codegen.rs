//! Rust code generation: the parameter struct, `ModelSpec`, and the kernels of every term
//! (written by the `kernel_writer` module's `KernelWriter` and, for the Taylor-mode kernels,
//! [`taylor`](crate::taylor)).
//!
//! [`generate`] writes a compiled model. [`generate_stub`] writes, for a model whose
//! declaration has errors, the same struct with an `EnergyModel` implementation whose kernels
//! are never reached: code that uses the model then compiles on, and the user sees the
//! declaration's own errors, not one more per use of the type.

use std::collections::HashSet;

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::kernel::{CompiledModel, TermKernel};
use crate::kernel_writer::KernelWriter;
use crate::syntax::{ModelOutline, Quadrature, description};
use crate::taylor::TaylorProgram;

/// The generated type: the parts known as soon as the model's header and parameters parse
/// (all that [`generate_stub`] needs).
struct ModelType<'a> {
    name: &'a Ident,
    attributes: &'a [syn::Attribute],
    documentation: &'a [String],
    registry_name: &'a str,
    description: String,
    parameters: Vec<Ident>,
    parameter_documentation: Vec<String>,
}

impl ModelType<'_> {
    /// `pub struct Name { pub parameter: f64, … }` and its `new`.
    fn definition(&self) -> TokenStream {
        let (name, attributes, documentation) = (self.name, self.attributes, self.documentation);
        let (parameters, parameter_documentation) =
            (&self.parameters, &self.parameter_documentation);
        quote! {
            #(#attributes)*
            #(#[doc = #documentation])*
            #[derive(Clone, Debug, PartialEq)]
            pub struct #name {
                #(
                    #[doc = #parameter_documentation]
                    pub #parameters: f64,
                )*
            }

            #[allow(clippy::all)]
            impl #name {
                /// Creates the model from its parameter values (in declaration order).
                #[allow(clippy::too_many_arguments)]
                pub fn new(#(#parameters: f64),*) -> Self {
                    Self { #(#parameters),* }
                }
            }
        }
    }

    /// `from_parameters` and `parameter_values` of the `EnergyModel` implementation.
    fn parameter_methods(&self) -> TokenStream {
        let parameters = &self.parameters;
        let count = parameters.len();
        let indices = 0..count;
        let names: Vec<String> = parameters.iter().map(ToString::to_string).collect();
        let wrong_count = format!(
            "model `{}` takes {count} parameters ({}), got {{}}",
            escape_braces(self.registry_name),
            names.join(", ")
        );
        quote! {
            fn from_parameters(values: &[f64]) -> Self {
                assert_eq!(values.len(), #count, #wrong_count, values.len());
                Self { #(#parameters: values[#indices]),* }
            }

            fn parameter_values(&self) -> ::std::vec::Vec<f64> {
                ::std::vec![#(self.#parameters),*]
            }
        }
    }
}

/// The doc line of a parameter's struct field.
fn parameter_documentation(name: &Ident, documentation: &str) -> String {
    if documentation.is_empty() {
        format!("Parameter `{name}`.")
    } else {
        documentation.to_string()
    }
}

/// `text` as a literal piece of a `format!` string.
fn escape_braces(text: &str) -> String {
    text.replace('{', "{{").replace('}', "}}")
}

/// Generates the whole implementation for a compiled model.
pub fn generate(compiled: &CompiledModel) -> TokenStream {
    let model = &compiled.model;
    let model_type = ModelType {
        name: &model.name,
        attributes: &model.attributes,
        documentation: &model.documentation,
        registry_name: &model.registry_name,
        description: model.description(),
        parameters: model.parameters.iter().map(|p| p.name.clone()).collect(),
        parameter_documentation: model
            .parameters
            .iter()
            .map(|p| parameter_documentation(&p.name, &p.documentation))
            .collect(),
    };
    let programs: Vec<TaylorProgram> = compiled
        .terms
        .iter()
        .map(|term| TaylorProgram::new(&term.graph, &term.residual, &term.jet))
        .collect();
    let name = model_type.name;
    let definition = model_type.definition();
    let spec = model_spec(compiled, &model_type, &programs);
    let parameter_methods = model_type.parameter_methods();
    let kernel_methods = kernel_methods(compiled, &model_type, &programs);
    quote! {
        #definition

        #[allow(clippy::all, unused_variables, unused_parens)]
        impl ::wrinkle_runtime::EnergyModel for #name {
            const SPEC: &'static ::wrinkle_runtime::ModelSpec = #spec;

            #parameter_methods

            #kernel_methods
        }
    }
}

/// The `&ModelSpec` constant: names, roles, jet, terms and the simplification report.
fn model_spec(
    compiled: &CompiledModel,
    model_type: &ModelType<'_>,
    programs: &[TaylorProgram],
) -> TokenStream {
    let model = &compiled.model;
    let (registry_name, description) = (model_type.registry_name, &model_type.description);
    let field_names = &model.fields;
    let field_roles = model.field_roles.iter().map(|role| {
        let variant = format_ident!("{}", role.variant_name());
        quote!(::wrinkle_runtime::FieldRole::#variant)
    });
    let parameter_names = model_type.parameters.iter().map(ToString::to_string);
    let varying_names = model
        .parameters
        .iter()
        .filter(|p| p.varying)
        .map(|p| p.name.to_string());
    let jet_entries = model.jet.iter().map(|entry| {
        let field = entry.field;
        let derivative = format_ident!("{}", entry.derivative.variant_name());
        quote!(::wrinkle_runtime::JetEntry {
            field: #field,
            derivative: ::wrinkle_runtime::Derivative::#derivative,
        })
    });
    let term_specs = compiled
        .terms
        .iter()
        .zip(programs)
        .map(|(term, program)| term_spec(term, program));
    let report = &compiled.report;
    let derivation = match &model.derivation {
        Some(text) => quote!(::core::option::Option::Some(#text)),
        None => quote!(::core::option::Option::None),
    };
    quote! {
        &::wrinkle_runtime::ModelSpec {
            name: #registry_name,
            description: #description,
            fields: &[#(#field_names),*],
            field_roles: &[#(#field_roles),*],
            parameters: &[#(#parameter_names),*],
            varying_parameters: &[#(#varying_names),*],
            jet: &[#(#jet_entries),*],
            terms: &[#(#term_specs),*],
            simplification_report: #report,
            derivation: #derivation,
        }
    }
}

/// One `TermSpec`: quadrature, jet subset, tangent pattern, Taylor tape size, linearity.
fn term_spec(term: &TermKernel, program: &TaylorProgram) -> TokenStream {
    let term_name = &term.name;
    let quadrature = match term.quadrature {
        Quadrature::Full => quote!(Full),
        Quadrature::Reduced => quote!(Reduced),
    };
    let jet = &term.jet;
    let pattern = term.tangent_pattern.iter().map(|(i, j)| quote!((#i, #j)));
    let slots = program.slots;
    let linear = program.is_linear();
    quote!(::wrinkle_runtime::TermSpec {
        name: #term_name,
        quadrature: ::wrinkle_runtime::QuadratureRule::#quadrature,
        jet: &[#(#jet),*],
        tangent_pattern: &[#(#pattern),*],
        taylor_slots: #slots,
        linear_residual: #linear,
    })
}

/// The kernels of every term, one `match term` arm each: energy, residual, tangent and the
/// three Taylor-mode kernels.
fn kernel_methods(
    compiled: &CompiledModel,
    model_type: &ModelType<'_>,
    programs: &[TaylorProgram],
) -> TokenStream {
    let mut arms: [Vec<TokenStream>; 6] = Default::default();
    for (index, (term, program)) in compiled.terms.iter().zip(programs).enumerate() {
        let writer = KernelWriter {
            graph: &term.graph,
            term,
            parameters: &model_type.parameters,
        };
        let taylor = crate::taylor::generate(program, &writer);
        let kernels = [
            writer.energy(),
            writer.outputs(&term.residual),
            writer.outputs(&term.tangent),
            taylor.start,
            taylor.predict,
            taylor.commit,
        ];
        for (arms, kernel) in arms.iter_mut().zip(kernels) {
            arms.push(quote!(#index => #kernel,));
        }
    }
    let missing_term = format!(
        "model `{}` has {} energy terms; term {{}} does not exist",
        escape_braces(model_type.registry_name),
        compiled.terms.len()
    );
    let [energy, residual, tangent, start, predict, commit] =
        arms.map(|arms| quote!(match term { #(#arms)* _ => panic!(#missing_term, term), }));
    quote! {
        fn energy<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S]) -> S {
            #energy
        }

        fn residual<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
            #residual
        }

        fn tangent<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
            #tangent
        }

        fn taylor_start(&self, term: usize, jet: &[f64], tape: &mut [f64], stride: usize) {
            #start
        }

        fn taylor_predict(&self, term: usize, order: usize, tape: &mut [f64], stride: usize, out: &mut [f64]) {
            #predict
        }

        fn taylor_commit(&self, term: usize, order: usize, jet: &[f64], tape: &mut [f64], stride: usize) {
            #commit
        }
    }
}

/// A stand-in for a model whose declaration has errors (the errors themselves are emitted
/// beside it): the struct and `new` as [`generate`] writes them, with the parameters that
/// parsed (each name once), and an `EnergyModel` implementation whose `SPEC` has no fields
/// and no terms and whose kernels are unreachable — a model that does not compile never runs.
pub fn generate_stub(outline: &ModelOutline) -> TokenStream {
    let mut seen = HashSet::new();
    let parameters: Vec<_> = outline
        .parameters
        .iter()
        .filter(|parameter| seen.insert(parameter.name.to_string()))
        .collect();
    let model_type = ModelType {
        name: &outline.name,
        attributes: &outline.attributes,
        documentation: &outline.documentation,
        registry_name: outline.registry_name.as_deref().unwrap_or_default(),
        description: description(&outline.documentation),
        parameters: parameters.iter().map(|p| p.name.clone()).collect(),
        parameter_documentation: parameters
            .iter()
            .map(|p| {
                let written = p.documentation.as_ref().map(|text| text.value());
                parameter_documentation(&p.name, &written.unwrap_or_default())
            })
            .collect(),
    };
    let name = model_type.name;
    let definition = model_type.definition();
    let parameter_methods = model_type.parameter_methods();
    let (registry_name, description) = (model_type.registry_name, &model_type.description);
    let parameter_names = model_type.parameters.iter().map(ToString::to_string);
    let unreachable = format!(
        "model `{}` has errors in its declaration and no kernels",
        escape_braces(&name.to_string())
    );
    quote! {
        #definition

        #[allow(clippy::all, unused_variables)]
        impl ::wrinkle_runtime::EnergyModel for #name {
            const SPEC: &'static ::wrinkle_runtime::ModelSpec = &::wrinkle_runtime::ModelSpec {
                name: #registry_name,
                description: #description,
                fields: &[],
                field_roles: &[],
                parameters: &[#(#parameter_names),*],
                varying_parameters: &[],
                jet: &[],
                terms: &[],
                simplification_report: "",
                derivation: ::core::option::Option::None,
            };

            #parameter_methods

            fn energy<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S]) -> S {
                ::core::unreachable!(#unreachable)
            }

            fn residual<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
                ::core::unreachable!(#unreachable)
            }

            fn tangent<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
                ::core::unreachable!(#unreachable)
            }
        }
    }
}

//! Rust code generation: the parameter struct, `ModelSpec`, and the kernels of every term
//! (written by the `kernel_writer` module's `KernelWriter` and, for the Taylor-mode kernels, [`taylor`](crate::taylor)).

use proc_macro2::{Ident, TokenStream};
use quote::{format_ident, quote};

use crate::kernel::CompiledModel;
use crate::kernel_writer::KernelWriter;
use crate::syntax::Quadrature;
use crate::taylor::TaylorProgram;

/// Generates the whole implementation for a compiled model.
pub fn generate(compiled: &CompiledModel) -> TokenStream {
    let model = &compiled.model;
    let name = &model.name;
    let attributes = &model.attributes;
    let documentation = &model.documentation;
    let registry_name = &model.registry_name;
    let description = model.description();
    let field_names = &model.fields;
    let field_roles = model.field_roles.iter().map(|role| {
        let variant = format_ident!("{}", role.variant_name());
        quote!(::wrinkle_runtime::FieldRole::#variant)
    });
    let parameter_idents: Vec<Ident> = model
        .parameters
        .iter()
        .map(|parameter| parameter.name.clone())
        .collect();
    let parameter_names: Vec<String> = parameter_idents.iter().map(ToString::to_string).collect();
    let parameter_documentation: Vec<String> = model
        .parameters
        .iter()
        .map(|parameter| {
            if parameter.documentation.is_empty() {
                format!("Parameter `{}`.", parameter.name)
            } else {
                parameter.documentation.clone()
            }
        })
        .collect();
    let parameter_count = parameter_idents.len();
    let parameter_indices = 0..parameter_count;
    let term_count = compiled.terms.len();

    let jet_entries = model.jet.iter().map(|entry| {
        let field = entry.field;
        let derivative = format_ident!("{}", entry.derivative.variant_name());
        quote!(::wrinkle_runtime::JetEntry {
            field: #field,
            derivative: ::wrinkle_runtime::Derivative::#derivative,
        })
    });
    let term_specs = compiled.terms.iter().map(|term| {
        let term_name = &term.name;
        let quadrature = match term.quadrature {
            Quadrature::Full => quote!(Full),
            Quadrature::Reduced => quote!(Reduced),
        };
        let jet = &term.jet;
        let pattern = term.tangent_pattern.iter().map(|(i, j)| quote!((#i, #j)));
        let program = TaylorProgram::new(&term.graph, &term.residual, &term.jet);
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
    });
    let report = &compiled.report;

    let mut energy_arms = Vec::new();
    let mut residual_arms = Vec::new();
    let mut tangent_arms = Vec::new();
    let mut taylor_start_arms = Vec::new();
    let mut taylor_predict_arms = Vec::new();
    let mut taylor_commit_arms = Vec::new();
    for (index, term) in compiled.terms.iter().enumerate() {
        let writer = KernelWriter {
            graph: &term.graph,
            term,
            parameters: &parameter_idents,
        };
        let energy = writer.energy();
        let residual = writer.outputs(&term.residual);
        let tangent = writer.outputs(&term.tangent);
        energy_arms.push(quote!(#index => #energy,));
        residual_arms.push(quote!(#index => #residual,));
        tangent_arms.push(quote!(#index => #tangent,));
        let program = TaylorProgram::new(&term.graph, &term.residual, &term.jet);
        let taylor = crate::taylor::generate(&program, &writer);
        let (start, predict, commit) = (taylor.start, taylor.predict, taylor.commit);
        taylor_start_arms.push(quote!(#index => #start,));
        taylor_predict_arms.push(quote!(#index => #predict,));
        taylor_commit_arms.push(quote!(#index => #commit,));
    }
    let escaped_name = registry_name.replace('{', "{{").replace('}', "}}");
    let missing_term =
        format!("model `{escaped_name}` has {term_count} energy terms; term {{}} does not exist");
    let wrong_parameter_count = format!(
        "model `{escaped_name}` takes {parameter_count} parameters ({}), got {{}}",
        parameter_names.join(", ")
    );

    quote! {
        #(#attributes)*
        #(#[doc = #documentation])*
        #[derive(Clone, Debug, PartialEq)]
        pub struct #name {
            #(
                #[doc = #parameter_documentation]
                pub #parameter_idents: f64,
            )*
        }

        #[allow(clippy::all)]
        impl #name {
            /// Creates the model from its parameter values (in declaration order).
            #[allow(clippy::too_many_arguments)]
            pub fn new(#(#parameter_idents: f64),*) -> Self {
                Self { #(#parameter_idents),* }
            }
        }

        #[allow(clippy::all, unused_variables, unused_parens)]
        impl ::wrinkle_runtime::EnergyModel for #name {
            const SPEC: &'static ::wrinkle_runtime::ModelSpec = &::wrinkle_runtime::ModelSpec {
                name: #registry_name,
                description: #description,
                fields: &[#(#field_names),*],
                field_roles: &[#(#field_roles),*],
                parameters: &[#(#parameter_names),*],
                jet: &[#(#jet_entries),*],
                terms: &[#(#term_specs),*],
                simplification_report: #report,
            };

            fn from_parameters(values: &[f64]) -> Self {
                assert_eq!(values.len(), #parameter_count, #wrong_parameter_count, values.len());
                Self { #(#parameter_idents: values[#parameter_indices]),* }
            }

            fn parameter_values(&self) -> ::std::vec::Vec<f64> {
                ::std::vec![#(self.#parameter_idents),*]
            }

            fn energy<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S]) -> S {
                match term {
                    #(#energy_arms)*
                    _ => panic!(#missing_term, term),
                }
            }

            fn residual<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
                match term {
                    #(#residual_arms)*
                    _ => panic!(#missing_term, term),
                }
            }

            fn tangent<S: ::wrinkle_runtime::Scalar>(&self, term: usize, jet: &[S], out: &mut [S]) {
                match term {
                    #(#tangent_arms)*
                    _ => panic!(#missing_term, term),
                }
            }

            fn taylor_start(&self, term: usize, jet: &[f64], tape: &mut [f64], stride: usize) {
                match term {
                    #(#taylor_start_arms)*
                    _ => panic!(#missing_term, term),
                }
            }

            fn taylor_predict(&self, term: usize, order: usize, tape: &mut [f64], stride: usize, out: &mut [f64]) {
                match term {
                    #(#taylor_predict_arms)*
                    _ => panic!(#missing_term, term),
                }
            }

            fn taylor_commit(&self, term: usize, order: usize, jet: &[f64], tape: &mut [f64], stride: usize) {
                match term {
                    #(#taylor_commit_arms)*
                    _ => panic!(#missing_term, term),
                }
            }
        }
    }
}

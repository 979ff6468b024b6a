//! Inputs in generated code (docs/inputs.md#the-generated-trait): the trait named after
//! the struct (`Hover` → `HoverInputs`) with one method per `input`, which the user
//! implements, and its partials with a default by central differences. The generated
//! methods call them through the alias [`ALIAS`], bound in the block of the impl, so that a
//! struct without the trait is a compile error naming it ("the trait bound `Hover:
//! HoverInputs` is not satisfied").

use proc_macro2::{Ident, Span, TokenStream};
use quote::{format_ident, quote};

use crate::mechanics::ModelInput;

/// The name calls use for the inputs' trait inside the generated block.
pub(crate) const ALIAS: &str = "__VarmassInputs";

/// `HoverInputs` for `Hover`.
pub(crate) fn trait_name(name: &Ident) -> Ident {
    format_ident!("{}Inputs", name)
}

/// The trait (nothing for a system without inputs).
pub(crate) fn inputs_trait(
    name: &Ident,
    inputs: &[ModelInput],
    runtime: &TokenStream,
) -> TokenStream {
    if inputs.is_empty() {
        return TokenStream::new();
    }
    let trait_name = trait_name(name);
    let methods = inputs.iter().map(|input| input_methods(input, runtime));
    let doc = format!(
        "The inputs of [`{name}`]: functions its equations call, written in Rust \
         (docs/inputs.md). `{name}` must implement this trait; each method receives the \
         declared arguments (`y_dot` for `y'`)."
    );
    quote! {
        #[doc = #doc]
        pub trait #trait_name {
            #(#methods)*
        }
    }
}

/// `fn u(&self, t: f64, y: f64, y_dot: f64) -> f64;` and `fn u_partials(..) -> [f64; K]`.
fn input_methods(input: &ModelInput, runtime: &TokenStream) -> TokenStream {
    let name = Ident::new(&input.name, Span::call_site());
    let partials = format_ident!("{}_partials", input.name);
    let arguments: Vec<Ident> = (0..input.arguments.len())
        .map(|j| Ident::new(&input.rust_argument(j), Span::call_site()))
        .collect();
    let k = proc_macro2::Literal::usize_unsuffixed(arguments.len());
    let indices = (0..arguments.len()).map(proc_macro2::Literal::usize_unsuffixed);
    let declared = format!("{}({})", input.name, input.arguments.join(", "));
    let sampled = input.every.map(|h| {
        format!(
            "Sampled every {h} s: called at the sample times k·{h} s and a run's start only, its value held between \
             them (zero-order hold; docs/inputs.md#sampled-inputs)."
        )
    });
    let value_doc = format!("`input {declared}`: the input's value.");
    let partials_doc = format!(
        "The partials of `{}` with respect to its arguments, in order. Used only by the \
         Jacobian (the Newton iterations of the implicit steppers), never by the equations. \
         The default takes central differences with steps ε^(1/3)·max(|x|, 1) (relative error \
         about ε^(2/3) ≈ 4e-11); override it with exact partials when they are known.",
        input.name
    );
    if let Some(sampled) = sampled {
        // Held between samples: the equations see a constant, never its partials.
        return quote! {
            #[doc = #value_doc]
            #[doc = ""]
            #[doc = #sampled]
            fn #name(&self, #(#arguments: f64),*) -> f64;
        };
    }
    quote! {
        #[doc = #value_doc]
        fn #name(&self, #(#arguments: f64),*) -> f64;
        #[doc = #partials_doc]
        fn #partials(&self, #(#arguments: f64),*) -> [f64; #k] {
            #runtime::input::central_partials(
                |x: [f64; #k]| self.#name(#(x[#indices]),*),
                [#(#arguments),*],
            )
        }
    }
}

/// `use HoverInputs as __VarmassInputs;` for the block of the impl.
pub(crate) fn alias(name: &Ident) -> TokenStream {
    let trait_name = trait_name(name);
    let alias = Ident::new(ALIAS, Span::call_site());
    quote!(#[allow(unused_imports)] use #trait_name as #alias;)
}

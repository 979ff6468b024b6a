//! The stub emitted when expansion fails: the struct's trait impl still exists, so the
//! user's crate shows the real error and not a cascade of "trait not implemented".

use proc_macro2::{Literal, TokenStream};
use quote::quote;

/// A stub impl of `VariableMassSystem<n, s>` for `item` (none for a generic struct).
pub fn stub(item: &syn::ItemStruct, coordinates: usize, state_masses: usize) -> TokenStream {
    if !item.generics.params.is_empty() {
        return TokenStream::new();
    }
    let name = &item.ident;
    let n = Literal::usize_unsuffixed(coordinates);
    let s = Literal::usize_unsuffixed(2 * coordinates + state_masses);
    let rt = quote!(::varmass::core);
    let unreachable = quote!(::core::unreachable!(
        "the variable-mass system failed to compile"
    ));
    quote! {
        impl #name {
            /// (The system failed to compile.)
            pub const SOURCE: &'static str = "";
            /// (The system failed to compile.)
            pub const DERIVATION: &'static str = "";
            /// (The system failed to compile.)
            pub const DERIVATION_LATEX: &'static str = "";
            /// (The system failed to compile.)
            pub const PARAMETERS: &'static [&'static str] = &[];
        }
        #[allow(unused_variables)]
        impl #rt::VariableMassSystem<#n, #s> for #name {
            const COORDINATES: [&'static str; #n] = [""; #n];
            const MASSES: &'static [&'static str] = &[];
            fn mass(&self, index: usize, t: f64, state: &#rt::nalgebra::SVector<f64, #s>) -> f64 { #unreachable }
            fn mass_rate(&self, index: usize, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> f64 { #unreachable }
            fn mass_matrix(&self, t: f64, state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SMatrix<f64, #n, #n> { #unreachable }
            fn momenta(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn lagrangian(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> f64 { #unreachable }
            fn lagrangian_gradient(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn active_force(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn reactive_thrust(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn impact_force(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn mass_flux_force(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>) -> #rt::nalgebra::SVector<f64, #n> { #unreachable }
            fn accelerations(&self, t: f64, velocity_state: &#rt::nalgebra::SVector<f64, #s>)
                -> ::core::result::Result<#rt::nalgebra::SVector<f64, #n>, #rt::SystemError> { #unreachable }
        }
    }
}

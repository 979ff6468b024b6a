//! The stub emitted when expansion fails: the struct's trait impl still exists, so the
//! user's crate shows the real error and not a cascade of "trait not implemented".

use proc_macro2::{Literal, TokenStream};
use quote::quote;
use varmass_symbolic::emit::REQUIRED;

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
    // The required methods, spelled by the same list the emitter uses.
    let methods = REQUIRED.iter().map(|m| {
        let signature = m.signature(&rt, coordinates, 2 * coordinates + state_masses);
        quote!(#signature { #unreachable })
    });
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
            #(#methods)*
        }
    }
}

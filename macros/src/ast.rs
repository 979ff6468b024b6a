//! The typed view of the macro's input: the DSL string literal and the struct it is on.

use proc_macro2::TokenStream;

/// The attribute's argument: the system in the DSL, as one string literal.
pub fn parse_source(attr: TokenStream) -> syn::Result<syn::LitStr> {
    syn::parse2::<syn::LitStr>(attr.clone()).map_err(|_| {
        let span = if attr.is_empty() {
            proc_macro2::Span::call_site()
        } else {
            syn::spanned::Spanned::span(&attr)
        };
        syn::Error::new(
            span,
            "expected the system as one string literal, e.g. \
             #[variable_mass_system(\"coordinates x\\nmass m = m0 + c*x\\n…\")]",
        )
    })
}

/// The item the attribute is on, which must be a struct.
pub fn parse_struct(item: TokenStream) -> syn::Result<syn::ItemStruct> {
    match syn::parse2::<syn::Item>(item)? {
        syn::Item::Struct(s) => Ok(s),
        syn::Item::Enum(e) => Err(syn::Error::new_spanned(
            e.enum_token,
            "#[variable_mass_system] goes on a struct whose named `f64` fields are the parameters, not on an enum",
        )),
        other => Err(syn::Error::new_spanned(
            other,
            "#[variable_mass_system] goes on a struct whose named `f64` fields are the parameters",
        )),
    }
}

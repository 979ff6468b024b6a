//! Checks on the struct, one rule a function (after serde_derive's `check_*`).

use crate::ctxt::Ctxt;

/// The names of the struct's fields, after checking every rule below.
pub fn parameter_fields(cx: &Ctxt, item: &syn::ItemStruct) -> Vec<syn::Ident> {
    check_no_generics(cx, item);
    let fields = check_named_fields(cx, item);
    for field in &fields {
        check_f64(cx, field);
    }
    fields.iter().filter_map(|f| f.ident.clone()).collect()
}

/// Generated code reads each parameter as `self.name: f64`; a type parameter would leave
/// the equations' types open.
fn check_no_generics(cx: &Ctxt, item: &syn::ItemStruct) {
    if !item.generics.params.is_empty() || item.generics.where_clause.is_some() {
        cx.error_spanned_by(
            &item.generics,
            "a variable-mass system cannot be generic: its parameters are plain `f64` fields",
        );
    }
}

/// Parameters are named in the DSL, so the fields must have names.
fn check_named_fields(cx: &Ctxt, item: &syn::ItemStruct) -> Vec<syn::Field> {
    match &item.fields {
        syn::Fields::Named(named) => named.named.iter().cloned().collect(),
        syn::Fields::Unnamed(unnamed) => {
            cx.error_spanned_by(
                unnamed,
                "a variable-mass system needs named fields (its parameters); a tuple struct has none",
            );
            Vec::new()
        }
        syn::Fields::Unit => Vec::new(),
    }
}

/// The equations are `f64` arithmetic.
fn check_f64(cx: &Ctxt, field: &syn::Field) {
    let is_f64 =
        matches!(&field.ty, syn::Type::Path(p) if p.qself.is_none() && p.path.is_ident("f64"));
    if !is_f64 {
        let name = field
            .ident
            .as_ref()
            .map(|i| i.to_string())
            .unwrap_or_default();
        cx.error_spanned_by(
            &field.ty,
            format!("parameter `{name}` must be an `f64`: every field of a variable-mass system is a parameter of its equations"),
        );
    }
}

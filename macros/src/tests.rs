//! The expansion seen from inside: a model file and the same text inline generate the same
//! code, apart from the item that makes cargo track the file.

use proc_macro2::Span;
use quote::quote;
use syn::LitStr;

use crate::expand::expand;

/// The sled's struct, the same for both forms.
fn sled_struct() -> proc_macro2::TokenStream {
    quote! {
        struct Sled { m0: f64, c: f64, g: f64, theta: f64, f_d: f64 }
    }
}

/// The sled's expansion with `arguments`, as token text.
fn sled_text(arguments: proc_macro2::TokenStream) -> String {
    expand(arguments, sled_struct()).to_string()
}

/// The items of an expansion, as token text, split into the file-tracking constants and the
/// rest.
fn items(tokens: proc_macro2::TokenStream) -> (Vec<String>, Vec<String>) {
    let file: syn::File = syn::parse2(tokens).expect("the expansion parses as Rust");
    let (tracking, rest): (Vec<_>, Vec<_>) = file
        .items
        .iter()
        .partition(|item| matches!(item, syn::Item::Const(c) if c.ident == "_"));
    let text = |items: Vec<&syn::Item>| {
        items
            .into_iter()
            .map(|item| quote!(#item).to_string())
            .collect()
    };
    (text(tracking), text(rest))
}

#[test]
fn the_sled_file_and_the_same_text_inline_generate_identical_code() {
    let text = std::fs::read_to_string("../models/sled.vms").expect("models/sled.vms");
    let inline = LitStr::new(&text, Span::call_site());
    let (file_tracking, file_items) = items(expand(
        quote!(file = "../models/sled.vms", with = ["impact"]),
        sled_struct(),
    ));
    let (inline_tracking, inline_items) =
        items(expand(quote!(#inline, with = ["impact"]), sled_struct()));
    assert_eq!(inline_tracking.len(), 0);
    assert_eq!(file_tracking.len(), 1);
    assert!(
        file_tracking[0].contains("include_bytes") && file_tracking[0].contains("sled.vms\""),
        "{}",
        file_tracking[0]
    );
    // The struct, the inherent constants and the trait impl.
    assert_eq!(file_items.len(), 3);
    assert!(file_items[2].contains("VariableMassSystem"));
    assert_eq!(file_items, inline_items);
}

#[test]
fn leaving_the_impact_out_changes_the_code() {
    let with_impact = expand(
        quote!(file = "../models/sled.vms", with = ["impact"]),
        sled_struct(),
    );
    let without = expand(quote!(file = "../models/sled.vms"), sled_struct());
    assert!(!without.to_string().contains("compile_error"));
    assert_ne!(items(with_impact).1, items(without).1);
}

#[test]
fn minimal_emission_leaves_the_optional_outputs_out() {
    let full = sled_text(quote!(file = "../models/sled.vms", with = ["impact"]));
    let minimal = sled_text(quote!(
        file = "../models/sled.vms",
        with = ["impact"],
        emit = []
    ));
    let power_only = sled_text(quote!(
        file = "../models/sled.vms",
        with = ["impact"],
        emit = ["power"]
    ));
    for optional in ["fn hamiltonian", "fn power", "fn jacobian", "DERIVATION"] {
        assert!(full.contains(optional), "{optional}");
        assert!(!minimal.contains(optional), "{optional}");
    }
    assert!(power_only.contains("fn power") && !power_only.contains("fn jacobian"));
    for required in [
        "fn state_rate",
        "fn accelerations",
        "fn velocities",
        "SOURCE",
    ] {
        assert!(minimal.contains(required), "{required}");
    }
    assert!(minimal.len() < power_only.len() && power_only.len() < full.len());
}

#[test]
fn an_unknown_output_is_an_error_naming_the_known_ones() {
    let expanded = sled_text(quote!(file = "../models/sled.vms", emit = ["jacobain"]));
    assert!(
        expanded.contains(
            "unknown output `jacobain`; expected one of `hamiltonian`, `power`, `jacobian`, `derivation`"
        ),
        "{expanded}"
    );
}
